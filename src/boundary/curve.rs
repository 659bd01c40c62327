//! Planar boundary curves parameterized on \[0,1\]: polylines (by chord length) and B-spline
//! curves (linearly reparameterized), with evaluation, derivatives, reversal and closest-point
//! projection.

use super::bspline::BSplineCurve;
use crate::error::{Error, ErrorKind, Result};

/// A point or vector of the plane.
pub type Point2 = [f64; 2];

fn sub(a: Point2, b: Point2) -> Point2 {
    [a[0] - b[0], a[1] - b[1]]
}

fn dot(a: Point2, b: Point2) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// The distance between two points.
pub fn distance(a: Point2, b: Point2) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// A planar polyline parameterized by chord length on \[0,1\].
#[derive(Clone, Debug, PartialEq)]
pub struct Polyline {
    points: Vec<Point2>,
    params: Vec<f64>,
}

impl Polyline {
    /// Builds a polyline through `points` (at least two distinct ones; finite coordinates;
    /// consecutive repeated points are dropped). Point i gets the parameter (length of the
    /// polyline up to it) / (total length).
    pub fn new(points: Vec<Point2>) -> Result<Self> {
        for (i, p) in points.iter().enumerate() {
            if !(p[0].is_finite() && p[1].is_finite()) {
                return Err(Error::new(
                    ErrorKind::NotFinite,
                    format!(
                        "polyline point {i} is ({}, {}), coordinates must be finite",
                        p[0], p[1]
                    ),
                ));
            }
        }
        let mut pts: Vec<Point2> = Vec::with_capacity(points.len());
        for p in points {
            if pts.last() != Some(&p) {
                pts.push(p);
            }
        }
        if pts.len() < 2 {
            return Err(Error::invalid(
                "a polyline needs at least two distinct points",
            ));
        }
        let mut params = Vec::with_capacity(pts.len());
        let mut s = 0.0;
        params.push(0.0);
        for w in pts.windows(2) {
            s += distance(w[0], w[1]);
            params.push(s);
        }
        for x in params.iter_mut() {
            *x /= s;
        }
        *params.last_mut().unwrap() = 1.0;
        Ok(Polyline {
            points: pts,
            params,
        })
    }

    /// The vertices.
    pub fn points(&self) -> &[Point2] {
        &self.points
    }

    /// The chord-length parameters of the vertices (0 first, 1 last).
    pub fn params(&self) -> &[f64] {
        &self.params
    }

    /// The total length.
    pub fn length(&self) -> f64 {
        self.points.windows(2).map(|w| distance(w[0], w[1])).sum()
    }

    /// The segment `i` (from vertex i to i+1) holding parameter `t` (clamped to \[0,1\]).
    fn segment(&self, t: f64) -> usize {
        let t = t.clamp(0.0, 1.0);
        let i = self.params.partition_point(|&s| s <= t);
        i.saturating_sub(1).min(self.points.len() - 2)
    }

    /// The point and the derivative with respect to the parameter at `t`; at a vertex the
    /// derivative is that of the following segment (of the last one at t = 1).
    pub fn eval_deriv(&self, t: f64) -> (Point2, Point2) {
        self.eval_deriv_side(t, false)
    }

    /// As [`eval_deriv`](Self::eval_deriv), with the derivative of the preceding segment at a
    /// vertex (of the first one at t = 0) when `left` is set.
    pub fn eval_deriv_side(&self, t: f64, left: bool) -> (Point2, Point2) {
        let t = t.clamp(0.0, 1.0);
        let i = if left {
            self.params
                .partition_point(|&s| s < t)
                .saturating_sub(1)
                .min(self.points.len() - 2)
        } else {
            self.segment(t)
        };
        let (a, b) = (self.points[i], self.points[i + 1]);
        let h = self.params[i + 1] - self.params[i];
        let r = (t - self.params[i]) / h;
        (
            [a[0] + r * (b[0] - a[0]), a[1] + r * (b[1] - a[1])],
            [(b[0] - a[0]) / h, (b[1] - a[1]) / h],
        )
    }
}

/// A planar spline curve linearly reparameterized from its knot domain to \[0,1\].
#[derive(Clone, Debug, PartialEq)]
pub struct SplineCurve2 {
    curve: BSplineCurve,
}

impl SplineCurve2 {
    /// Wraps a 2D B-spline curve (an error if its dimension is not 2).
    pub fn new(curve: BSplineCurve) -> Result<Self> {
        if curve.dim() != 2 {
            return Err(Error::invalid(format!(
                "a planar boundary curve must be 2D, this B-spline is {}D",
                curve.dim()
            )));
        }
        Ok(SplineCurve2 { curve })
    }

    /// The underlying B-spline curve (on its own knot domain).
    pub fn bspline(&self) -> &BSplineCurve {
        &self.curve
    }

    /// Point and derivatives with respect to t ∈ \[0,1\] up to order 2.
    fn derivs2(&self, t: f64) -> [Point2; 3] {
        let (a, b) = self.curve.domain();
        let h = b - a;
        let d = self.curve.derivs(a + t.clamp(0.0, 1.0) * h, 2);
        [
            [d[0][0], d[0][1]],
            [d[1][0] * h, d[1][1] * h],
            [d[2][0] * h * h, d[2][1] * h * h],
        ]
    }
}

/// The geometry of a boundary curve.
#[derive(Clone, Debug, PartialEq)]
pub enum CurveKind {
    /// A polyline by chord length.
    Polyline(Polyline),
    /// A B-spline curve.
    Spline(SplineCurve2),
}

/// The result of a closest-point projection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projection {
    /// The parameter in \[0,1\] of the nearest point found.
    pub t: f64,
    /// The nearest point found.
    pub point: Point2,
    /// Its distance to the projected point.
    pub distance: f64,
}

/// A planar boundary curve on the parameter interval \[0,1\], possibly traversed backwards.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve2 {
    kind: CurveKind,
    reversed: bool,
}

impl Curve2 {
    /// A polyline through `points`, parameterized by chord length (see [`Polyline::new`]).
    pub fn polyline(points: Vec<Point2>) -> Result<Self> {
        Ok(Curve2 {
            kind: CurveKind::Polyline(Polyline::new(points)?),
            reversed: false,
        })
    }

    /// A 2D B-spline curve, its knot domain mapped linearly to \[0,1\].
    pub fn spline(curve: BSplineCurve) -> Result<Self> {
        Ok(Curve2 {
            kind: CurveKind::Spline(SplineCurve2::new(curve)?),
            reversed: false,
        })
    }

    /// The geometry.
    pub fn kind(&self) -> &CurveKind {
        &self.kind
    }

    /// Whether the curve is traversed against its geometry's own direction.
    pub fn is_reversed(&self) -> bool {
        self.reversed
    }

    /// The same curve traversed backwards (`t ↦ 1 - t`).
    pub fn reversed(mut self) -> Self {
        self.reversed = !self.reversed;
        self
    }

    /// Point and derivatives up to order 2 at t ∈ \[0,1\] (clamped); polylines have zero second
    /// derivative.
    pub fn derivs2(&self, t: f64) -> [Point2; 3] {
        let t = t.clamp(0.0, 1.0);
        let s = if self.reversed { 1.0 - t } else { t };
        let mut d = match &self.kind {
            CurveKind::Polyline(p) => {
                // Going backwards, at a vertex the following segment is the geometry's previous one.
                let (pt, dv) = p.eval_deriv_side(s, self.reversed);
                [pt, dv, [0.0, 0.0]]
            }
            CurveKind::Spline(c) => c.derivs2(s),
        };
        if self.reversed {
            d[1] = [-d[1][0], -d[1][1]];
        }
        d
    }

    /// The point at t ∈ \[0,1\].
    pub fn eval(&self, t: f64) -> Point2 {
        self.derivs2(t)[0]
    }

    /// The point and the first derivative at t ∈ \[0,1\].
    pub fn eval_deriv(&self, t: f64) -> (Point2, Point2) {
        let d = self.derivs2(t);
        (d[0], d[1])
    }

    /// The point at t = 0.
    pub fn start(&self) -> Point2 {
        self.eval(0.0)
    }

    /// The point at t = 1.
    pub fn end(&self) -> Point2 {
        self.eval(1.0)
    }

    /// The unit direction of travel at t = 0 (or at t = 1 with `at_end`); when the derivative
    /// vanishes there (repeated control points) the direction of a nearby chord is used.
    pub fn end_direction(&self, at_end: bool) -> Point2 {
        let t = if at_end { 1.0 } else { 0.0 };
        let (p, d) = self.eval_deriv(t);
        let mut v = d;
        let mut n = v[0].hypot(v[1]);
        let mut h = 1e-6;
        while n <= 1e-12 * (1.0 + p[0].abs() + p[1].abs()) && h < 0.5 {
            let q = self.eval(if at_end { 1.0 - h } else { h });
            v = if at_end { sub(p, q) } else { sub(q, p) };
            n = v[0].hypot(v[1]);
            h *= 10.0;
        }
        if n == 0.0 {
            return [0.0, 0.0];
        }
        [v[0] / n, v[1] / n]
    }

    /// Points along the curve for area and bounding-box computations: the vertices of a
    /// polyline, or `n + 1` equally spaced parameters of a spline (in the direction of travel).
    pub fn sample(&self, n: usize) -> Vec<Point2> {
        match &self.kind {
            CurveKind::Polyline(p) => {
                let mut v = p.points.clone();
                if self.reversed {
                    v.reverse();
                }
                v
            }
            CurveKind::Spline(_) => (0..=n.max(1))
                .map(|i| self.eval(i as f64 / n.max(1) as f64))
                .collect(),
        }
    }

    /// The point of the curve nearest to `p`. Polylines are projected exactly segment by
    /// segment; splines by Newton's method on (C(t) − p)·C'(t) = 0 started from the best of
    /// a sampling (at least 8 samples per control point and 200 in all), never returning a
    /// point farther than the best sample or the end points.
    pub fn closest_point(&self, p: Point2) -> Projection {
        match &self.kind {
            CurveKind::Polyline(pl) => {
                let mut best = Projection {
                    t: 0.0,
                    point: pl.points[0],
                    distance: distance(p, pl.points[0]),
                };
                for i in 0..pl.points.len() - 1 {
                    let (a, b) = (pl.points[i], pl.points[i + 1]);
                    let ab = sub(b, a);
                    let r = (dot(sub(p, a), ab) / dot(ab, ab)).clamp(0.0, 1.0);
                    let q = [a[0] + r * ab[0], a[1] + r * ab[1]];
                    let d = distance(p, q);
                    if d < best.distance {
                        let s = pl.params[i] + r * (pl.params[i + 1] - pl.params[i]);
                        best = Projection {
                            t: if self.reversed { 1.0 - s } else { s },
                            point: q,
                            distance: d,
                        };
                    }
                }
                best
            }
            CurveKind::Spline(c) => {
                let n = (8 * c.curve.num_control_points()).max(200);
                let mut best = Projection {
                    t: 0.0,
                    point: self.eval(0.0),
                    distance: f64::INFINITY,
                };
                for i in 0..=n {
                    let t = i as f64 / n as f64;
                    let q = self.eval(t);
                    let d = distance(p, q);
                    if d < best.distance {
                        best = Projection {
                            t,
                            point: q,
                            distance: d,
                        };
                    }
                }
                let mut t = best.t;
                for _ in 0..50 {
                    let [c0, c1, c2] = self.derivs2(t);
                    let r = sub(c0, p);
                    let f = dot(r, c1);
                    let mut fp = dot(c1, c1) + dot(r, c2);
                    if fp <= 0.0 {
                        fp = dot(c1, c1);
                    }
                    if fp <= 0.0 {
                        break;
                    }
                    // Keep the step within a few samples of the start.
                    let step = (f / fp).clamp(-2.0 / n as f64, 2.0 / n as f64);
                    let tn = (t - step).clamp(0.0, 1.0);
                    let done = (tn - t).abs() < 1e-15;
                    t = tn;
                    if done {
                        break;
                    }
                }
                let q = self.eval(t);
                let d = distance(p, q);
                if d <= best.distance {
                    best = Projection {
                        t,
                        point: q,
                        distance: d,
                    };
                }
                best
            }
        }
    }
}
