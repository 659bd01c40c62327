//! One face of a solid's boundary as a map of its cube face's in-plane coordinates `(a, b)`:
//! a B-spline surface in one of the eight orientations of the square, or a triangulation with
//! a parameter point per vertex (located through a bucket grid).

// Index loops over coordinates and corners read best in this numerical code.
#![allow(clippy::needless_range_loop)]

use super::bspline::{BSplineSurface, Vec3};

/// How a face's in-plane coordinates `(a, b)` become the surface's unit parameters `(s, t)`:
/// `(x, y) = swap ? (b, a) : (a, b)`, then `s = flip_s ? 1 − x : x`, `t = flip_t ? 1 − y : y`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Orientation {
    pub(super) swap: bool,
    pub(super) flip_s: bool,
    pub(super) flip_t: bool,
}

impl Orientation {
    pub(super) fn all() -> impl Iterator<Item = Orientation> {
        (0..8).map(|k| Orientation {
            swap: k & 1 != 0,
            flip_s: k & 2 != 0,
            flip_t: k & 4 != 0,
        })
    }

    pub(super) fn apply(self, a: f64, b: f64) -> (f64, f64) {
        let (x, y) = if self.swap { (b, a) } else { (a, b) };
        (
            if self.flip_s { 1.0 - x } else { x },
            if self.flip_t { 1.0 - y } else { y },
        )
    }
}

/// A face given by a B-spline surface whose knot domain is rescaled to \[0,1\]^2.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct SplineFace {
    pub(super) surface: BSplineSurface,
    pub(super) orientation: Orientation,
    /// The surface's place in the list the solid was made from.
    pub(super) origin: usize,
}

impl SplineFace {
    /// The surface's parameters at the in-plane coordinates `(a, b)`.
    pub(super) fn parameters(&self, a: f64, b: f64) -> (f64, f64) {
        let (s, t) = self.orientation.apply(a, b);
        let ((u0, u1), (v0, v1)) = self.surface.domain();
        // (1 − s)·u0 + s·u1 is exact at both ends of the domain.
        ((1.0 - s) * u0 + s * u1, (1.0 - t) * v0 + t * v1)
    }

    pub(super) fn eval(&self, a: f64, b: f64) -> Vec3 {
        let (u, v) = self.parameters(a, b);
        self.surface.eval(u, v)
    }
}

/// A face given by a triangulation with a parameter point `(a, b)` for every vertex and a
/// uniform bucket grid over \[0,1\]^2 to locate the triangle holding a parameter point.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct MeshFace {
    pub(super) uv: Vec<[f64; 2]>,
    points: Vec<Vec3>,
    triangles: Vec<[usize; 3]>,
    grid_n: usize,
    buckets: Vec<Vec<u32>>,
}

fn cross2(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

fn sub2(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

impl MeshFace {
    pub(super) fn new(uv: Vec<[f64; 2]>, points: Vec<Vec3>, triangles: Vec<[usize; 3]>) -> Self {
        let grid_n = ((triangles.len() as f64 / 2.0).sqrt().ceil() as usize).clamp(1, 1024);
        let mut buckets: Vec<Vec<u32>> = vec![Vec::new(); grid_n * grid_n];
        let cell = |x: f64| ((x * grid_n as f64).floor().max(0.0) as usize).min(grid_n - 1);
        for (k, t) in triangles.iter().enumerate() {
            let p = t.map(|i| uv[i]);
            let lo = [0, 1].map(|d| p.iter().map(|q| q[d]).fold(f64::INFINITY, f64::min));
            let hi = [0, 1].map(|d| p.iter().map(|q| q[d]).fold(f64::NEG_INFINITY, f64::max));
            for j in cell(lo[1])..=cell(hi[1]) {
                for i in cell(lo[0])..=cell(hi[0]) {
                    buckets[i + j * grid_n].push(k as u32);
                }
            }
        }
        MeshFace {
            uv,
            points,
            triangles,
            grid_n,
            buckets,
        }
    }

    /// Barycentric coordinates of `q` in triangle `k` (exactly a unit vector at a vertex).
    fn barycentric(&self, k: usize, q: [f64; 2]) -> [f64; 3] {
        let t = self.triangles[k];
        let (p0, p1, p2) = (self.uv[t[0]], self.uv[t[1]], self.uv[t[2]]);
        let e1 = sub2(p1, p0);
        let e2 = sub2(p2, p0);
        let d = sub2(q, p0);
        let det = cross2(e1, e2);
        let l1 = cross2(d, e2) / det;
        let l2 = cross2(e1, d) / det;
        [1.0 - l1 - l2, l1, l2]
    }

    /// The triangle among `cands` whose smallest barycentric coordinate of `q` is largest; a
    /// triangle with `q` as a vertex wins at once, with that vertex's unit coordinates.
    fn best(&self, cands: impl Iterator<Item = usize>, q: [f64; 2]) -> Option<(usize, [f64; 3])> {
        let mut best: Option<(usize, [f64; 3], f64)> = None;
        for k in cands {
            if let Some(v) = self.triangles[k].iter().position(|&i| self.uv[i] == q) {
                let mut l = [0.0; 3];
                l[v] = 1.0;
                return Some((k, l));
            }
            let l = self.barycentric(k, q);
            let m = l[0].min(l[1]).min(l[2]);
            if best.is_none_or(|b| m > b.2) {
                best = Some((k, l, m));
            }
        }
        best.map(|b| (b.0, b.1))
    }

    pub(super) fn eval(&self, a: f64, b: f64) -> Vec3 {
        let q = [a, b];
        let n = self.grid_n;
        let i = ((a * n as f64).floor().max(0.0) as usize).min(n - 1);
        let j = ((b * n as f64).floor().max(0.0) as usize).min(n - 1);
        let mut found = self.best(self.buckets[i + j * n].iter().map(|&k| k as usize), q);
        if found.is_none_or(|(_, l)| l[0].min(l[1]).min(l[2]) < -1e-12) {
            // Outside every triangle of the bucket (only by round-off on the square's boundary):
            // the triangle nearest in the barycentric sense over the whole face.
            found = self.best(0..self.triangles.len(), q);
        }
        let (k, l) = found.expect("a face has at least one triangle");
        let mut l = l.map(|x| x.max(0.0));
        let sum = l[0] + l[1] + l[2];
        if sum != 1.0 {
            l = l.map(|x| x / sum);
        }
        let t = self.triangles[k];
        let mut out = [0.0; 3];
        for d in 0..3 {
            out[d] = l[0] * self.points[t[0]][d]
                + l[1] * self.points[t[1]][d]
                + l[2] * self.points[t[2]][d];
        }
        out
    }
}

#[derive(Clone, Debug, PartialEq)]
pub(super) enum Face {
    Spline(SplineFace),
    Mesh(MeshFace),
}

impl Face {
    pub(super) fn eval(&self, a: f64, b: f64) -> Vec3 {
        match self {
            Face::Spline(f) => f.eval(a, b),
            Face::Mesh(f) => f.eval(a, b),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orientations_are_the_square_symmetries() {
        let imgs: Vec<_> = Orientation::all()
            .map(|o| [o.apply(0.0, 0.0), o.apply(1.0, 0.0), o.apply(0.0, 1.0)])
            .collect();
        for i in 0..8 {
            for j in 0..i {
                assert_ne!(imgs[i], imgs[j]);
            }
        }
    }
}
