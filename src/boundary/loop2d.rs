//! A planar domain bounded by four curves, mapped onto the boundary of the unit square, and the
//! coastline format (one closed polyline with four corner indices).

use std::path::Path;

use super::crossing::TaggedPolygon;
use super::curve::{distance, Curve2, CurveKind, Point2};
use super::gismo_xml::read_gismo_curves;
use crate::error::{Error, ErrorKind, Result};
use crate::optimize::small_matrix::bounding_box;

/// Refuses a loop that crosses or touches itself: the polygon of the chained curves (a
/// polyline's own vertices, a spline sampled at 16 points per control point and at least 256)
/// must be simple. `chain` holds the curves head to tail with their given indices.
fn check_simple(chain: &[(usize, Curve2)]) -> Result<()> {
    let mut polygon = TaggedPolygon::default();
    for (index, curve) in chain {
        let samples = match curve.kind() {
            CurveKind::Polyline(_) => curve.sample(0),
            CurveKind::Spline(s) => curve.sample((16 * s.bspline().num_control_points()).max(256)),
        };
        // The last point is the next curve's first, to the loop's tolerance.
        for &p in &samples[..samples.len() - 1] {
            polygon.push(p, *index);
        }
    }
    match polygon.first_crossing() {
        None => Ok(()),
        Some(c) => Err(Error::invalid(format!(
            "the boundary loop crosses itself: curve {} meets curve {} at {} (edges {} and {} of \
             its {}-point polygon); the boundary of a domain must be a simple closed curve",
            polygon.tag(c.first),
            polygon.tag(c.second),
            fmt_point(c.at),
            c.first,
            c.second,
            polygon.point_count()
        ))),
    }
}

/// A side of the unit square.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Side {
    /// u = 0, running with v.
    U0,
    /// u = 1, running with v.
    U1,
    /// v = 0, running with u.
    V0,
    /// v = 1, running with u.
    V1,
}

impl Side {
    /// The four sides in the order U0, U1, V0, V1 (G+Smo's west, east, south, north).
    // A function rather than an associated constant, which cbindgen would put in the C header.
    pub fn all() -> [Side; 4] {
        [Side::U0, Side::U1, Side::V0, Side::V1]
    }

    /// The index in [`Side::all`].
    pub fn index(self) -> usize {
        self as usize
    }

    /// The point of the unit square's boundary at parameter `t` of this side.
    pub fn unit_square_point(self, t: f64) -> Point2 {
        match self {
            Side::U0 => [0.0, t],
            Side::U1 => [1.0, t],
            Side::V0 => [t, 0.0],
            Side::V1 => [t, 1.0],
        }
    }
}

/// Options of [`BoundaryLoop2::from_curves_with`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopOptions {
    /// End points closer than this fraction of the bounding-box diagonal are the same point.
    pub rel_tol: f64,
    /// The largest interior angle allowed at a corner, in degrees (below 180 for a convex corner).
    pub max_corner_angle_deg: f64,
}

impl Default for LoopOptions {
    fn default() -> Self {
        LoopOptions {
            rel_tol: 1e-6,
            max_corner_angle_deg: 180.0,
        }
    }
}

/// Four curves bounding a planar domain, oriented counter-clockwise and assigned to the sides of
/// the unit square: the boundary map sends (side, t) to a point, each side running in the
/// direction of increasing u or v, so that the corners (0,0), (1,0), (1,1), (0,1) are met
/// counter-clockwise.
#[derive(Clone, Debug, PartialEq)]
pub struct BoundaryLoop2 {
    sides: [Curve2; 4],
    /// The place of each side's curve in the list the loop was made from.
    origin: [usize; 4],
    corner_angles: [f64; 4],
    tolerance: f64,
}

fn fmt_point(p: Point2) -> String {
    format!("({:.6}, {:.6})", p[0], p[1])
}

/// Checks that there are four curves and that the options are finite, the tolerance
/// non-negative.
fn check_loop_input(curves: &[Curve2], options: &LoopOptions) -> Result<()> {
    if curves.len() != 4 {
        return Err(Error::invalid(format!(
            "a boundary loop needs exactly 4 curves, got {}",
            curves.len()
        )));
    }
    if !(options.rel_tol.is_finite()
        && options.rel_tol >= 0.0
        && options.max_corner_angle_deg.is_finite())
    {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "loop options must be finite and the tolerance non-negative",
        ));
    }
    Ok(())
}

/// The diagonal of the bounding box of the curves' samples (the scale of the tolerance); fails
/// on a non-finite sample.
fn sampled_diagonal(curves: &[Curve2]) -> Result<f64> {
    let samples: Vec<Point2> = curves.iter().flat_map(|c| c.sample(64)).collect();
    if samples
        .iter()
        .any(|p| !(p[0].is_finite() && p[1].is_finite()))
    {
        return Err(Error::new(
            ErrorKind::NotFinite,
            "a boundary curve evaluates to a non-finite point",
        ));
    }
    let (lo, hi) = bounding_box(samples.iter().copied());
    Ok(distance(lo, hi))
}

/// The curves chained head to tail (each with its index as given), starting with curve 0 as
/// given, each next one the curve with the nearest end, reversed where needed; fails where an
/// end meets no curve within `tol` or the chain does not close.
fn chain_curves(curves: Vec<Curve2>, tol: f64) -> Result<Vec<(usize, Curve2)>> {
    let mut slots: Vec<Option<Curve2>> = curves.into_iter().map(Some).collect();
    let mut chain: Vec<(usize, Curve2)> = vec![(0, slots[0].take().unwrap())];
    while chain.len() < 4 {
        let (last_index, last) = chain.last().unwrap();
        let end = last.end();
        let mut best: Option<(f64, usize, bool)> = None;
        for (j, slot) in slots.iter().enumerate() {
            if let Some(c) = slot {
                for (d, rev) in [
                    (distance(c.start(), end), false),
                    (distance(c.end(), end), true),
                ] {
                    if best.is_none_or(|b| d < b.0) {
                        best = Some((d, j, rev));
                    }
                }
            }
        }
        let (d, j, rev) = best.unwrap();
        if d > tol {
            return Err(Error::invalid(format!(
                "boundary loop is open: the end {} of curve {last_index} meets no other curve \
                 (nearest end point at distance {d:.3e}, tolerance {tol:.3e})",
                fmt_point(end)
            )));
        }
        let c = slots[j].take().unwrap();
        chain.push((j, if rev { c.reversed() } else { c }));
    }
    let gap = distance(chain[3].1.end(), chain[0].1.start());
    if gap > tol {
        return Err(Error::invalid(format!(
            "boundary loop is not closed: curve {} ends at {} but curve {} starts at {} \
             (gap {gap:.3e}, tolerance {tol:.3e})",
            chain[3].0,
            fmt_point(chain[3].1.end()),
            chain[0].0,
            fmt_point(chain[0].1.start())
        )));
    }
    Ok(chain)
}

/// The closed chain turned counter-clockwise (by the signed area of the sampled loop) and
/// rotated so that the first given curve comes last: `[v=0, u=1, v=1 backwards, u=0
/// backwards]`. Fails on a loop of no area (relative to the diagonal `diag`).
fn counter_clockwise(mut chain: Vec<(usize, Curve2)>, diag: f64) -> Result<Vec<(usize, Curve2)>> {
    let pts: Vec<Point2> = chain.iter().flat_map(|(_, c)| c.sample(256)).collect();
    let mut area = 0.0;
    for i in 0..pts.len() {
        let (a, b) = (pts[i], pts[(i + 1) % pts.len()]);
        area += a[0] * b[1] - a[1] * b[0];
    }
    area *= 0.5;
    if area.abs() <= 1e-12 * diag * diag {
        return Err(Error::invalid(
            "boundary loop encloses no area (degenerate or self-overlapping curves)",
        ));
    }
    if area < 0.0 {
        chain = chain
            .into_iter()
            .rev()
            .map(|(i, c)| (i, c.reversed()))
            .collect();
    }
    let k = chain.iter().position(|(i, _)| *i == 0).unwrap();
    chain.rotate_left((k + 1) % 4);
    Ok(chain)
}

/// The interior angle in degrees at each corner k of the counter-clockwise chain (where
/// `chain[k-1]` ends and `chain[k]` starts); fails at a corner that is not convex or reaches
/// `max_angle`.
fn corner_angles(chain: &[(usize, Curve2)], max_angle: f64) -> Result<[f64; 4]> {
    let mut corner_angles = [0.0; 4];
    for k in 0..4 {
        let din = chain[(k + 3) % 4].1.end_direction(true);
        let dout = chain[k].1.end_direction(false);
        let cross = din[0] * dout[1] - din[1] * dout[0];
        let dotp = din[0] * dout[0] + din[1] * dout[1];
        let interior = 180.0 - cross.atan2(dotp).to_degrees();
        corner_angles[k] = interior;
        if interior >= max_angle || interior <= 0.0 {
            let names = ["(0,0)", "(1,0)", "(1,1)", "(0,1)"];
            return Err(Error::invalid(format!(
                "corner {} of the boundary loop, at {}, has an interior angle of {interior:.2}°; \
                 each corner must be convex (interior angle between 0° and {max_angle}°)",
                names[k],
                fmt_point(chain[k].1.start()),
            )));
        }
    }
    Ok(corner_angles)
}

impl BoundaryLoop2 {
    /// [`from_curves_with`](Self::from_curves_with) with default options.
    pub fn from_curves(curves: Vec<Curve2>) -> Result<Self> {
        Self::from_curves_with(curves, LoopOptions::default())
    }

    /// Orders and orients four curves into a closed counter-clockwise loop by matching their end
    /// points (reversing curves as needed), and assigns them to sides: the first given curve
    /// becomes side u = 0, the others follow counter-clockwise from corner (0,0): v = 0, u = 1,
    /// v = 1. Errors (`InvalidArgument`): not four curves, an end point that meets no other curve
    /// or a loop that does not close (naming the curve and the gap), a degenerate loop of zero
    /// area, a corner whose interior angle reaches `max_corner_angle_deg` (naming the corner, its
    /// position and angle), a loop that crosses or touches itself (naming the curves and the
    /// point). Non-finite coordinates are refused when the curves are built (`NotFinite`).
    pub fn from_curves_with(curves: Vec<Curve2>, options: LoopOptions) -> Result<Self> {
        check_loop_input(&curves, &options)?;
        let diag = sampled_diagonal(&curves)?;
        let tol = options.rel_tol * diag;
        let chain = chain_curves(curves, tol)?;
        let chain = counter_clockwise(chain, diag)?;
        let corner_angles = corner_angles(&chain, options.max_corner_angle_deg)?;
        check_simple(&chain)?;
        let from: Vec<usize> = chain.iter().map(|(i, _)| *i).collect();
        let mut it = chain.into_iter().map(|(_, c)| c);
        let v0 = it.next().unwrap();
        let u1 = it.next().unwrap();
        let v1 = it.next().unwrap().reversed();
        let u0 = it.next().unwrap().reversed();
        Ok(BoundaryLoop2 {
            sides: [u0, u1, v0, v1],
            origin: [from[3], from[1], from[0], from[2]],
            corner_angles,
            tolerance: tol,
        })
    }

    /// Reads a G+Smo XML file of four B-spline curves and builds the loop.
    pub fn from_gismo_file(path: impl AsRef<Path>) -> Result<Self> {
        let path = path.as_ref();
        let curves = read_gismo_curves(path)?
            .into_iter()
            .map(Curve2::spline)
            .collect::<Result<Vec<_>>>()?;
        Self::from_curves(curves)
            .map_err(|e| Error::new(e.kind, format!("{}: {}", path.display(), e.message)))
    }

    /// Builds the loop of a coastline: its four polylines between the corners.
    pub fn from_coastline(coast: &Coastline) -> Result<Self> {
        Self::from_curves(coast.curves()?.to_vec())
    }

    /// The place of a side's curve in the list the loop was made from.
    pub(super) fn origin(&self, side: Side) -> usize {
        self.origin[side.index()]
    }

    /// The curve of a side, running with increasing u (sides v = 0, 1) or v (sides u = 0, 1).
    pub fn side(&self, side: Side) -> &Curve2 {
        &self.sides[side.index()]
    }

    /// The boundary map: the point of side `side` at parameter t ∈ \[0,1\].
    pub fn eval(&self, side: Side, t: f64) -> Point2 {
        self.sides[side.index()].eval(t)
    }

    /// The point and its derivative with respect to t of side `side`.
    pub fn eval_deriv(&self, side: Side, t: f64) -> (Point2, Point2) {
        self.sides[side.index()].eval_deriv(t)
    }

    /// The boundary map at a point `(u, v)` of the unit square's boundary (one coordinate 0 or 1
    /// within `1e-12`, the other in \[0,1\]); an error for any other point.
    pub fn eval_at(&self, uv: Point2) -> Result<Point2> {
        let [u, v] = uv;
        let eps = 1e-12;
        let inside = |x: f64| (-eps..=1.0 + eps).contains(&x);
        if !(u.is_finite() && v.is_finite()) {
            return Err(Error::new(
                ErrorKind::NotFinite,
                format!("({u}, {v}) is not a finite point"),
            ));
        }
        let side = if u.abs() <= eps && inside(v) {
            Side::U0
        } else if (u - 1.0).abs() <= eps && inside(v) {
            Side::U1
        } else if v.abs() <= eps && inside(u) {
            Side::V0
        } else if (v - 1.0).abs() <= eps && inside(u) {
            Side::V1
        } else {
            return Err(Error::invalid(format!(
                "({u}, {v}) is not on the boundary of the unit square"
            )));
        };
        let t = match side {
            Side::U0 | Side::U1 => v,
            Side::V0 | Side::V1 => u,
        };
        Ok(self.eval(side, t.clamp(0.0, 1.0)))
    }

    /// The images of the corners (0,0), (1,0), (1,1), (0,1).
    pub fn corners(&self) -> [Point2; 4] {
        [
            self.side(Side::V0).start(),
            self.side(Side::V0).end(),
            self.side(Side::V1).end(),
            self.side(Side::V1).start(),
        ]
    }

    /// The interior angles in degrees at the corners (0,0), (1,0), (1,1), (0,1).
    pub fn corner_angles_deg(&self) -> [f64; 4] {
        self.corner_angles
    }

    /// The absolute tolerance used to match end points.
    pub fn tolerance(&self) -> f64 {
        self.tolerance
    }
}

/// A closed counter-clockwise polyline with the indices of the points that map to the corners
/// (0,0), (1,0), (1,1), (0,1) of the unit square.
#[derive(Clone, Debug, PartialEq)]
pub struct Coastline {
    /// The points; the last one joins the first.
    pub points: Vec<Point2>,
    /// The corner indices, in the order (0,0), (1,0), (1,1), (0,1).
    pub corners: [usize; 4],
}

impl Coastline {
    /// Parses the coastline text format: `#` comment lines, one `corners i0 i1 i2 i3` line, then
    /// one `x y` line per point. Malformed lines are `Io` errors with their line number,
    /// non-finite coordinates `NotFinite`, corner indices out of range or not in cyclic order
    /// `InvalidArgument`.
    pub fn parse(text: &str) -> Result<Self> {
        let mut points = Vec::new();
        let mut corners: Option<[usize; 4]> = None;
        for (ln, line) in text.lines().enumerate() {
            let ln = ln + 1;
            let line = line.trim();
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let toks: Vec<&str> = line.split_whitespace().collect();
            if toks[0] == "corners" {
                if corners.is_some() {
                    return Err(Error::io(format!("line {ln}: a second 'corners' line")));
                }
                let idx: Vec<usize> = toks[1..]
                    .iter()
                    .map(|t| t.parse::<usize>())
                    .collect::<std::result::Result<_, _>>()
                    .map_err(|_| {
                        Error::io(format!(
                            "line {ln}: corner indices must be non-negative integers"
                        ))
                    })?;
                if idx.len() != 4 {
                    return Err(Error::io(format!(
                        "line {ln}: 'corners' needs 4 indices, got {}",
                        idx.len()
                    )));
                }
                corners = Some([idx[0], idx[1], idx[2], idx[3]]);
                continue;
            }
            if toks.len() != 2 {
                return Err(Error::io(format!(
                    "line {ln}: expected 'x y', got '{line}'"
                )));
            }
            let mut xy = [0.0; 2];
            for d in 0..2 {
                xy[d] = toks[d]
                    .parse::<f64>()
                    .map_err(|_| Error::io(format!("line {ln}: '{}' is not a number", toks[d])))?;
            }
            if !(xy[0].is_finite() && xy[1].is_finite()) {
                return Err(Error::new(
                    ErrorKind::NotFinite,
                    format!("line {ln}: point ({}, {}) is not finite", xy[0], xy[1]),
                ));
            }
            points.push(xy);
        }
        let corners = corners.ok_or_else(|| Error::io("coastline has no 'corners' line"))?;
        if points.len() > 1 && points.first() == points.last() {
            points.pop();
        }
        let n = points.len();
        if n < 4 {
            return Err(Error::invalid(format!(
                "a coastline needs at least 4 points, got {n}"
            )));
        }
        if let Some(&c) = corners.iter().find(|&&c| c >= n) {
            return Err(Error::invalid(format!(
                "corner index {c} is out of range (the coastline has {n} points)"
            )));
        }
        // Cyclic order: the forward distances from corner 0 must increase strictly.
        let rel = corners.map(|c| (c + n - corners[0]) % n);
        if !(rel[0] < rel[1] && rel[1] < rel[2] && rel[2] < rel[3]) {
            return Err(Error::invalid(format!(
                "corner indices {corners:?} are not distinct and in counter-clockwise order"
            )));
        }
        Ok(Coastline { points, corners })
    }

    /// Reads and parses a coastline file.
    pub fn read(path: impl AsRef<Path>) -> Result<Self> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path)
            .map_err(|e| Error::io(format!("cannot read {}: {e}", path.display())))?;
        Self::parse(&text)
            .map_err(|e| Error::new(e.kind, format!("{}: {}", path.display(), e.message)))
    }

    /// The points from corner `a` to corner `b` (inclusive), going forward cyclically.
    fn run(&self, a: usize, b: usize) -> Vec<Point2> {
        let n = self.points.len();
        let len = (b + n - a) % n;
        (0..=len).map(|k| self.points[(a + k) % n]).collect()
    }

    /// The four sides as chord-length polylines in the order u = 0, u = 1, v = 0, v = 1, each
    /// running with increasing u or v.
    pub fn curves(&self) -> Result<[Curve2; 4]> {
        let [c0, c1, c2, c3] = self.corners;
        Ok([
            Curve2::polyline(self.run(c3, c0))?.reversed(),
            Curve2::polyline(self.run(c1, c2))?,
            Curve2::polyline(self.run(c0, c1))?,
            Curve2::polyline(self.run(c2, c3))?.reversed(),
        ])
    }
}
