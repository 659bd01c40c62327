//! Refitting a spline map in its own space after the T-mesh it was fitted to has moved
//! ([`Domain::update`](crate::domain::Domain::update)): the same basis functions, elements,
//! Bézier extraction and Greville points, new control points by the rule of the first fit, then
//! the certification and, where the map folds, the untangling of that fit.
//!
//! The rule is not chosen again: with a fixed space and rule the control points are a linear
//! function of the T-mesh's vertex positions, `P = A X` (the T-mesh's piecewise quadratic map
//! is linear in `X`, and each rule is a fixed linear operator on its values: the inverse of the
//! collocation matrix at the Greville points, the least-squares solve at the Greville points
//! and `4^d` points per element, or the dual functionals of the quasi-interpolant). So the
//! tangent `dP = A dX` of a motion `dX` of the vertices is [`SplineMap::fit_by_rule`] applied
//! to `dX` itself, and an adjoint product `Aᵀ w` needs the transposed operator. Only the
//! untangling, run where the map is not certified, is non-linear. Its correction `c` (the
//! control points it kept minus those of the rule) is recorded ([`FitRecord`]) and added to the
//! next refits, which untangle again only where `A X + c` still folds: between two
//! untanglings the map is `P = A X + c` with `c` fixed, so `dP = A dX` holds there too, and
//! [`FitReport::untangled`] (the control points a refit's untangling moved) says when it does
//! not. The sensitivities of the control points to the boundary then need, beyond this linear
//! map, the derivative of the optimized T-mesh vertices `X` with respect to the boundary
//! vertices (the implicit function theorem at the optimum of the T-mesh objective, in the frame
//! [`Domain::update`](crate::domain::Domain::update) keeps fixed) and the derivative of the
//! boundary vertices with respect to the boundary's own control points (their boundary map at
//! fixed parameters, linear for B-spline curves and surfaces, rational for NURBS).

use std::time::Instant;

use super::{
    FitReport, QuadraticMap, SplineMap, ThbSpace, UntangleOptions, ValidityOptions, ValidityReport,
};
use crate::error::{Error, Result};
use crate::tmesh::{TMesh, Tree};

/// How the control points of a fit come from the values of the map fitted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FitRule {
    /// Interpolation at the Greville points ([`SplineMap::fit_collocation`]).
    #[default]
    Interpolation,
    /// Least squares at the Greville points and `4^d` points per element
    /// ([`SplineMap::fit_least_squares`]).
    LeastSquares,
    /// The quasi-interpolant ([`SplineMap::fit_quasi_interpolation`]).
    QuasiInterpolation,
}

impl FitRule {
    /// The rule of the fit a report describes.
    pub fn of(report: &FitReport) -> Self {
        if report.quasi_interpolation {
            FitRule::QuasiInterpolation
        } else if report.least_squares {
            FitRule::LeastSquares
        } else {
            FitRule::Interpolation
        }
    }

    /// The rule's name, as the README and messages write it.
    pub fn name(self) -> &'static str {
        match self {
            FitRule::Interpolation => "interpolation",
            FitRule::LeastSquares => "least squares",
            FitRule::QuasiInterpolation => "quasi-interpolation",
        }
    }
}

/// How the tree of a spline's space relates to the tree of a T-mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Relation {
    /// The same leaves: the space is the T-mesh's.
    Same,
    /// Every leaf of the space lies in a leaf of the T-mesh, some deeper: the space refines the
    /// T-mesh's (`igaparam_spline_refine` after the fit).
    Refinement,
}

/// An error unless the leaves of `space` are those of `mesh`.
pub(super) fn relation_is_same<const D: usize>(space: &Tree<D>, mesh: &Tree<D>) -> Result<()> {
    match relation(space, mesh)? {
        Relation::Same => Ok(()),
        Relation::Refinement => Err(Error::invalid(
            "the spline was refined after its fit: its space is not the T-mesh's, and the \
             sensitivities are given in the T-mesh's space only",
        )),
    }
}

/// Whether the leaves of `space` are those of `mesh` or refine them; an error otherwise.
fn relation<const D: usize>(space: &Tree<D>, mesh: &Tree<D>) -> Result<Relation> {
    let mut same = true;
    for &leaf in &space.leaves() {
        let cell = space.cells()[leaf];
        let centre: [i64; D] =
            std::array::from_fn(|k| cell.lower[k] as i64 + (cell.side() / 2) as i64);
        let outer = mesh.leaf_at(&centre).map(|c| mesh.cells()[c]);
        match outer {
            Some(o) if o.level == cell.level && o.lower == cell.lower => {}
            Some(o) if o.level < cell.level => same = false,
            _ => {
                return Err(Error::invalid(format!(
                    "the spline's element of level {} at {:?} is not in one cell of the domain's \
                     T-mesh, which was refined after the fit (or is another domain's): refit a \
                     spline fitted to this T-mesh",
                    cell.level,
                    cell.lower
                        .map(|v| v as f64 / crate::tmesh::UNIT as f64)
                        .to_vec()
                )))
            }
        }
    }
    let leaves = mesh.leaves().len();
    Ok(if same && leaves == space.leaves().len() {
        Relation::Same
    } else {
        Relation::Refinement
    })
}

impl<const D: usize> SplineMap<D, ThbSpace<D>> {
    /// Fits `f` in `space` by `rule` alone: no other rule is tried, nothing is certified or
    /// untangled. The control points are a linear function of the values of `f` (see the
    /// module documentation). Errors: those of the rule's fit (`f` undefined or not finite at
    /// a fit point, a singular collocation matrix).
    pub fn fit_by_rule(
        space: ThbSpace<D>,
        rule: FitRule,
        f: impl Fn([f64; D]) -> Option<[f64; D]> + Sync,
    ) -> Result<(Self, FitReport)> {
        match rule {
            FitRule::Interpolation => Self::fit_collocation(space, f),
            FitRule::LeastSquares => Self::fit_least_squares(space, f),
            FitRule::QuasiInterpolation => Self::fit_quasi_interpolation(space, f),
        }
    }

    /// The record of a fit for later refits: `rule` and, when the fit untangled the map
    /// (`report.untangled > 0`), the correction the untangling made to the rule's control
    /// points, computed by fitting `mesh` (with `positions`, the T-mesh this map was fitted to)
    /// by the rule again. The map must be in the T-mesh's own space.
    pub fn fit_record(
        &self,
        mesh: &TMesh<D>,
        positions: &[[f64; D]],
        report: &FitReport,
    ) -> Result<FitRecord> {
        let rule = FitRule::of(report);
        let mut record = FitRecord {
            rule,
            correction: Vec::new(),
            boundary_offset: report.boundary_offset,
            differentiable: report.untangled == 0,
        };
        if report.untangled > 0 {
            let source = QuadraticMap::new(mesh, positions)?;
            let (raw, _) = Self::fit_by_rule(self.space.clone(), rule, |x| source.eval(x))?;
            if raw.basis_count() != self.basis_count() {
                return Err(Error::invalid(
                    "the map is not in the space of the T-mesh it was fitted to",
                ));
            }
            record.correction = difference(&self.control, &raw.control);
        }
        Ok(record)
    }

    /// Recomputes the control points from the T-mesh `mesh` with vertex positions `positions`,
    /// in this map's own space: by the rule of `record` plus its correction, certified with
    /// `options`, and untangled with `untangle` where it is not certified. The space must be
    /// the THB space of the T-mesh's tree, or a refinement of it: then the map is fitted,
    /// certified and untangled in the T-mesh's space and carried exactly into this space (the
    /// spaces are nested), as a fit followed by the same refinement would give. Without a
    /// record (a map read from a file) the first fit's choice is made
    /// ([`SplineMap::fit_checked`]). The basis and the elements never change.
    ///
    /// Returns the fit report (its `untangled` counts the control points this refit's
    /// untangling moved, 0 when the correction carried over kept the map certified), the
    /// validity of the new map and the record for the next refit. Errors: the space's
    /// elements are not those of the T-mesh nor a refinement of them (`InvalidArgument`), a
    /// record of another size, and the errors of the fit; the map is then unchanged.
    pub fn refit_tmesh(
        &mut self,
        mesh: &TMesh<D>,
        positions: &[[f64; D]],
        record: Option<&FitRecord>,
        options: &ValidityOptions,
        untangle: &UntangleOptions,
    ) -> Result<(FitReport, ValidityReport, FitRecord)> {
        let start = Instant::now();
        let relation = relation(self.space.tree(), mesh.tree())?;
        let source = QuadraticMap::new(mesh, positions)?;
        let space = match relation {
            Relation::Same => self.space.clone(),
            Relation::Refinement => ThbSpace::new(mesh.tree().clone())?,
        };
        let f = |x| source.eval(x);
        let (mut map, mut report, mut validity, record) = match record {
            Some(record) => Self::refit_recorded(space, record, &f, options, untangle)?,
            None => {
                let (map, report, validity) = Self::fit_checked(space, f, options, untangle)?;
                let record = map.fit_record(mesh, positions, &report)?;
                (map, report, validity, record)
            }
        };
        if relation == Relation::Refinement {
            let (fine, carried) =
                Self::fit_quasi_interpolation(self.space.clone(), |x| map.eval(x))?;
            report.basis_count = carried.basis_count;
            report.element_count = carried.element_count;
            map = fine;
            validity = map.validity(options);
        }
        if map.basis_count() != self.basis_count() {
            return Err(Error::invalid(format!(
                "the refit has {} basis functions, the spline {}",
                map.basis_count(),
                self.basis_count()
            )));
        }
        self.control = map.control;
        report.seconds = start.elapsed().as_secs_f64();
        Ok((report, validity, record))
    }

    /// The fit of `f` in `space` by the record's rule plus its correction, certified, and
    /// untangled where it folds; with the record for the next refit.
    fn refit_recorded(
        space: ThbSpace<D>,
        record: &FitRecord,
        f: &(impl Fn([f64; D]) -> Option<[f64; D]> + Sync),
        options: &ValidityOptions,
        untangle: &UntangleOptions,
    ) -> Result<(Self, FitReport, ValidityReport, FitRecord)> {
        let (mut map, mut report) = Self::fit_by_rule(space, record.rule, f)?;
        let raw = map.control.clone();
        let mut next = record.clone();
        if !record.correction.is_empty() {
            if record.correction.len() != D * raw.len() {
                return Err(Error::invalid(format!(
                    "the fit record holds {} correction values for {} control points",
                    record.correction.len(),
                    raw.len()
                )));
            }
            for (p, c) in map
                .control
                .iter_mut()
                .zip(record.correction.chunks_exact(D))
            {
                for k in 0..D {
                    p[k] += c[k];
                }
            }
        }
        report.boundary_offset = record.boundary_offset;
        next.differentiable = true;
        let mut validity = map.validity(options);
        if !validity.certified_positive {
            let (after, untangled) = map.untangle(validity, options, untangle);
            validity = after;
            report.untangled = untangled.moved;
            if untangled.moved > 0 {
                next.differentiable = false;
                next.correction = difference(&map.control, &raw);
                next.boundary_offset = next.boundary_offset.max(untangled.boundary_offset);
                report.boundary_offset = next.boundary_offset;
            }
        }
        Ok((map, report, validity, next))
    }
}

/// `a − b`, point by point, flat.
fn difference<const D: usize>(a: &[[f64; D]], b: &[[f64; D]]) -> Vec<f64> {
    a.iter()
        .zip(b)
        .flat_map(|(p, q)| (0..D).map(move |k| p[k] - q[k]))
        .collect()
}

/// What a spline map keeps of its fit for [`SplineMap::refit_tmesh`]: the rule, and the
/// correction an untangling made to the rule's control points, carried over to the refits so
/// that the map stays `P = A X + c` (see the module documentation) until an untangling runs
/// again.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FitRecord {
    /// The rule.
    pub rule: FitRule,
    /// The untangling's correction, `d` values per control point of the T-mesh's space (empty
    /// when the map was not untangled).
    pub correction: Vec<f64>,
    /// The largest move of a boundary control point by the untangling, relative to the
    /// bounding box (see [`UntangleOptions::boundary_offset`]).
    pub boundary_offset: f64,
    /// Whether the map is `A X + c` with the correction `c` of this record: its last fit or
    /// refit did not untangle (the untangling is a non-linear step), so the sensitivities of
    /// [`SplineMap::boundary_tangent`] apply.
    pub differentiable: bool,
}
