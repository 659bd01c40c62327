//! The morphs of the shape-optimization loop tests and benchmark: the puzzle piece whose knob
//! on the side u = 0 grows, and the 3D duck whose back face bulges; the fits they refit.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use igaparam::boundary::{
    read_gismo_curves, read_gismo_surfaces, BSplineCurve, BSplineSurface, BoundaryLoop2, Curve2,
    SolidBoundary,
};
use std::time::Instant;

use igaparam::domain::{CubeMap, Domain, DomainOptions, DomainReport, UpdateOptions, UpdateReport};
use igaparam::spline::{
    FitRecord, FitReport, SplineMap, UntangleOptions, ValidityOptions, ValidityReport,
};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/boundary")
        .join(name)
}

/// The four curves of the puzzle piece, as in its file.
pub fn puzzle_curves() -> Vec<BSplineCurve> {
    read_gismo_curves(data("puzzle3_bdry.xml")).expect("puzzle")
}

/// The six surfaces of the duck's B-rep, as in its file.
pub fn duck_surfaces() -> Vec<BSplineSurface> {
    read_gismo_surfaces(data("duck3d_BRep.xml")).expect("duck")
}

/// The knob of the puzzle's first curve (control points 9 to 26, the neck's ends at half
/// weight) scaled by `1 + 0.2 s` about the point where it joins the side: at `s = 1` it
/// reaches 20% further out.
pub fn grown_puzzle(curves: &[BSplineCurve], s: f64) -> Vec<BSplineCurve> {
    let mut out = curves.to_vec();
    let c = &curves[0];
    let centre = [0.07, 0.2];
    let mut coefs = Vec::with_capacity(2 * c.num_control_points());
    for i in 0..c.num_control_points() {
        let p = c.control_point(i);
        let weight = match i {
            10..=25 => 1.0,
            9 | 26 => 0.5,
            _ => 0.0,
        };
        let f = 1.0 + 0.2 * s * weight;
        coefs.extend((0..2).map(|k| centre[k] + f * (p[k] - centre[k])));
    }
    let kv = c.knot_vector();
    out[0] = BSplineCurve::new(
        kv.degree(),
        kv.knots().to_vec(),
        2,
        coefs,
        c.weights().map(<[f64]>::to_vec),
    )
    .expect("grown curve");
    out
}

/// The duck's back face (surface 5) with its inner control points scaled about their centroid
/// by `1 + 0.1 s w`, `w = 16 a(1 − a) b(1 − b)` of the control point's place `(a, b)` in the
/// net (1 in its middle, 0 on the edge rows, which stay, so the faces still share their edges):
/// at `s = 1` the face's middle moves 10% further from the centre.
pub fn scaled_duck(surfaces: &[BSplineSurface], s: f64) -> Vec<BSplineSurface> {
    let mut out = surfaces.to_vec();
    let f = &surfaces[5];
    let (nu, nv) = f.num_control_points();
    let points: Vec<[f64; 3]> = (0..nv)
        .flat_map(|j| (0..nu).map(move |i| (i, j)))
        .map(|(i, j)| f.control_point(i, j))
        .collect();
    let centre: [f64; 3] =
        std::array::from_fn(|k| points.iter().map(|p| p[k]).sum::<f64>() / points.len() as f64);
    let mut coefs = Vec::with_capacity(3 * points.len());
    for (n, p) in points.iter().enumerate() {
        let a = (n % nu) as f64 / (nu - 1) as f64;
        let b = (n / nu) as f64 / (nv - 1) as f64;
        let factor = 1.0 + 0.1 * s * 16.0 * a * (1.0 - a) * b * (1.0 - b);
        coefs.extend((0..3).map(|k| centre[k] + factor * (p[k] - centre[k])));
    }
    let (ku, kv) = (f.knot_vector_u(), f.knot_vector_v());
    out[5] = BSplineSurface::new(
        (ku.degree(), ku.knots().to_vec()),
        (kv.degree(), kv.knots().to_vec()),
        3,
        coefs,
        f.weights().map(<[f64]>::to_vec),
    )
    .expect("scaled face");
    out
}

/// The planar boundary of four curves.
pub fn planar(curves: &[BSplineCurve]) -> BoundaryLoop2 {
    let curves = curves
        .iter()
        .cloned()
        .map(Curve2::spline)
        .collect::<igaparam::Result<Vec<_>>>()
        .expect("curves");
    BoundaryLoop2::from_curves(curves).expect("loop")
}

/// The solid boundary of six surfaces.
pub fn solid(surfaces: &[BSplineSurface]) -> SolidBoundary {
    SolidBoundary::from_surfaces(surfaces.to_vec()).expect("solid")
}

/// The untangling options of a domain's fits: its own boundary offset.
pub fn untangle<const D: usize, B: CubeMap<D>>(domain: &Domain<D, B>) -> UntangleOptions {
    UntangleOptions {
        boundary_offset: domain.options().boundary_offset,
        ..Default::default()
    }
}

/// The checked fit of a domain (as the C API makes it) and its record for refits.
pub fn fit<const D: usize, B: CubeMap<D>>(domain: &Domain<D, B>) -> (SplineMap<D>, FitRecord) {
    let (map, report, _) = SplineMap::fit_tmesh_checked(
        domain.mesh(),
        domain.positions(),
        &ValidityOptions::default(),
        &untangle(domain),
    )
    .expect("fit");
    let record = map
        .fit_record(domain.mesh(), domain.positions(), &report)
        .expect("record");
    (map, record)
}

/// The levels and boxes of a map's elements.
pub fn elements<const D: usize>(map: &SplineMap<D>) -> Vec<(u8, [f64; D], [f64; D])> {
    (0..map.element_count())
        .map(|e| {
            let (lo, hi) = map.element_bounds(e);
            (map.element_level(e), lo, hi)
        })
        .collect()
}

/// A domain, its spline map and the map's fit record, run through the steps of a morph.
pub struct Loop<const D: usize, B> {
    pub domain: Domain<D, B>,
    pub map: SplineMap<D>,
    pub record: FitRecord,
    /// The report of the build.
    pub built: DomainReport,
    basis: usize,
    elements: Vec<(u8, [f64; D], [f64; D])>,
}

/// What one step of a [`Loop`] did.
pub struct Step {
    pub update: UpdateReport,
    pub refit: FitReport,
    pub validity: ValidityReport,
    pub update_seconds: f64,
    pub refit_seconds: f64,
}

impl<const D: usize, B: CubeMap<D>> Loop<D, B> {
    /// Builds the domain of `boundary` and fits its map.
    pub fn new(boundary: B, options: &DomainOptions) -> Self {
        let (domain, built) = Domain::build(boundary, options, &mut |_, _| true).expect("build");
        let (map, record) = fit(&domain);
        let (basis, elements) = (map.basis_count(), self::elements(&map));
        Loop {
            domain,
            map,
            record,
            built,
            basis,
            elements,
        }
    }

    /// Moves the domain onto `boundary` and refits the map; checks that the T-mesh stays valid,
    /// the rule, the basis and the elements stay, and the map is certified.
    pub fn step(&mut self, boundary: B, options: &UpdateOptions) -> Step {
        let clock = Instant::now();
        let update = self
            .domain
            .update(boundary, options, &mut |_, _| true)
            .expect("update");
        let update_seconds = clock.elapsed().as_secs_f64();
        let clock = Instant::now();
        let (refit, validity, next) = self
            .map
            .refit_tmesh(
                self.domain.mesh(),
                self.domain.positions(),
                Some(&self.record),
                &ValidityOptions::default(),
                &untangle(&self.domain),
            )
            .expect("refit");
        let refit_seconds = clock.elapsed().as_secs_f64();
        assert_eq!(update.domain.invalid_cells, 0, "folded T-mesh");
        assert_eq!(next.rule, self.record.rule, "the refit changed the rule");
        assert_eq!(self.map.basis_count(), self.basis, "basis count changed");
        assert!(elements(&self.map) == self.elements, "element list changed");
        assert!(validity.certified_positive, "not certified");
        self.record = next;
        Step {
            update,
            refit,
            validity,
            update_seconds,
            refit_seconds,
        }
    }
}
