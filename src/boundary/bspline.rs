//! B-spline and NURBS curves and tensor-product surfaces: validation, evaluation (de Boor /
//! Cox–de Boor) and derivatives.

// Index loops mirror the textbook algorithms.
#![allow(clippy::needless_range_loop)]

use crate::error::{check_finite, Error, Result};

/// A point or vector with up to three components; components beyond the geometry's dimension are 0.
pub type Vec3 = [f64; 3];

/// A validated knot vector with its degree.
#[derive(Clone, Debug, PartialEq)]
pub struct KnotVector {
    degree: usize,
    knots: Vec<f64>,
}

impl KnotVector {
    /// Validates `knots` for B-splines of degree `degree`: finite, non-decreasing, at least
    /// `2(degree+1)` knots, no interior knot repeated more than `degree+1` times, and a non-empty
    /// parameter domain `[knots[p], knots[n]]`.
    pub fn new(degree: usize, knots: Vec<f64>) -> Result<Self> {
        check_finite("knot vector", &knots)?;
        if knots.len() < 2 * (degree + 1) {
            return Err(Error::invalid(format!(
                "a knot vector of degree {degree} needs at least {} knots, got {}",
                2 * (degree + 1),
                knots.len()
            )));
        }
        if let Some(i) = knots.windows(2).position(|w| w[1] < w[0]) {
            return Err(Error::invalid(format!(
                "knot vector must be non-decreasing, but knot {} = {} is below knot {} = {}",
                i + 1,
                knots[i + 1],
                i,
                knots[i]
            )));
        }
        let mut run = 1;
        for i in 1..knots.len() {
            run = if knots[i] == knots[i - 1] { run + 1 } else { 1 };
            if run > degree + 1 {
                return Err(Error::invalid(format!(
                    "knot {} is repeated more than degree + 1 = {} times",
                    knots[i],
                    degree + 1
                )));
            }
        }
        let kv = KnotVector { degree, knots };
        let (a, b) = kv.domain();
        if b <= a {
            return Err(Error::invalid(format!(
                "knot vector has an empty parameter domain [{a}, {b}]"
            )));
        }
        Ok(kv)
    }

    /// The polynomial degree p.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The knots.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The number of basis functions, `#knots - p - 1`.
    pub fn num_basis(&self) -> usize {
        self.knots.len() - self.degree - 1
    }

    /// The parameter domain `[knots[p], knots[n]]` with n the number of basis functions.
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.num_basis()])
    }

    /// Whether the first and the last knot are repeated `p+1` times (the curve interpolates its
    /// end control points).
    pub fn is_clamped(&self) -> bool {
        let p = self.degree;
        let k = &self.knots;
        let m = k.len();
        k[..=p].iter().all(|&x| x == k[0]) && k[m - p - 1..].iter().all(|&x| x == k[m - 1])
    }

    /// The knot span index `i` with `knots[i] <= t < knots[i+1]`, `p <= i < n`; parameters outside
    /// the domain are clamped to it, and `t` at the domain's end belongs to the last non-empty span.
    pub fn find_span(&self, t: f64) -> usize {
        let p = self.degree;
        let n = self.num_basis();
        let k = &self.knots;
        if t >= k[n] {
            let mut i = n - 1;
            while i > p && k[i] >= k[n] {
                i -= 1;
            }
            return i;
        }
        if t <= k[p] {
            let mut i = p;
            while k[i + 1] <= k[p] {
                i += 1;
            }
            return i;
        }
        // k[lo] <= t < k[hi]
        let (mut lo, mut hi) = (p, n);
        while hi - lo > 1 {
            let mid = (lo + hi) / 2;
            if t < k[mid] {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        lo
    }

    /// The `p+1` non-zero basis functions at `t` and their derivatives up to order `nder`
    /// (The NURBS Book, algorithm A2.3): returns the span `i` and `ders[k][j]` = k-th derivative of
    /// basis function `i - p + j`. `t` is clamped to the domain.
    pub fn basis_derivs(&self, t: f64, nder: usize) -> (usize, Vec<Vec<f64>>) {
        let p = self.degree;
        let (a, b) = self.domain();
        let t = t.clamp(a, b);
        let span = self.find_span(t);
        let k = &self.knots;
        let mut ndu = vec![vec![0.0; p + 1]; p + 1];
        let mut left = vec![0.0; p + 1];
        let mut right = vec![0.0; p + 1];
        ndu[0][0] = 1.0;
        for j in 1..=p {
            left[j] = t - k[span + 1 - j];
            right[j] = k[span + j] - t;
            let mut saved = 0.0;
            for r in 0..j {
                ndu[j][r] = right[r + 1] + left[j - r];
                let temp = ndu[r][j - 1] / ndu[j][r];
                ndu[r][j] = saved + right[r + 1] * temp;
                saved = left[j - r] * temp;
            }
            ndu[j][j] = saved;
        }
        let mut ders = vec![vec![0.0; p + 1]; nder + 1];
        for j in 0..=p {
            ders[0][j] = ndu[j][p];
        }
        let mut a = vec![vec![0.0; p + 1]; 2];
        for r in 0..=p {
            let (mut s1, mut s2) = (0usize, 1usize);
            a[0][0] = 1.0;
            for kk in 1..=nder.min(p) {
                let mut d = 0.0;
                let rk = r as isize - kk as isize;
                let pk = p - kk;
                if r >= kk {
                    a[s2][0] = a[s1][0] / ndu[pk + 1][rk as usize];
                    d = a[s2][0] * ndu[rk as usize][pk];
                }
                let j1 = if rk >= -1 { 1 } else { (-rk) as usize };
                let j2 = if r as isize - 1 <= pk as isize {
                    kk - 1
                } else {
                    p - r
                };
                for j in j1..=j2 {
                    let idx = (rk + j as isize) as usize;
                    a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][idx];
                    d += a[s2][j] * ndu[idx][pk];
                }
                if r <= pk {
                    a[s2][kk] = -a[s1][kk - 1] / ndu[pk + 1][r];
                    d += a[s2][kk] * ndu[r][pk];
                }
                ders[kk][r] = d;
                std::mem::swap(&mut s1, &mut s2);
            }
        }
        let mut factor = p as f64;
        for (kk, row) in ders.iter_mut().enumerate().skip(1) {
            for v in row.iter_mut() {
                *v *= factor;
            }
            factor *= p.saturating_sub(kk) as f64;
        }
        (span, ders)
    }
}

fn check_weights(weights: &Option<Vec<f64>>, count: usize) -> Result<()> {
    if let Some(w) = weights {
        if w.len() != count {
            return Err(Error::invalid(format!(
                "{} weights given for {count} control points",
                w.len()
            )));
        }
        check_finite("weights", w)?;
        if let Some(i) = w.iter().position(|&x| x <= 0.0) {
            return Err(Error::invalid(format!(
                "weight {i} is {}, every weight must be positive",
                w[i]
            )));
        }
    }
    Ok(())
}

fn check_dim(dim: usize) -> Result<()> {
    if !(1..=3).contains(&dim) {
        return Err(Error::invalid(format!(
            "geometric dimension must be 1, 2 or 3, got {dim}"
        )));
    }
    Ok(())
}

fn binom(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// Turns homogeneous derivatives `aders[k]` (of Σ N w P) and `wders[k]` (of Σ N w) into the
/// derivatives of the rational map (The NURBS Book, A4.2).
fn rational_derivs(aders: &[Vec3], wders: &[f64]) -> Vec<Vec3> {
    let mut out: Vec<Vec3> = Vec::with_capacity(aders.len());
    for k in 0..aders.len() {
        let mut v = aders[k];
        for i in 1..=k {
            let c = binom(k, i) * wders[i];
            for (vd, od) in v.iter_mut().zip(out[k - i].iter()) {
                *vd -= c * od;
            }
        }
        for vd in v.iter_mut() {
            *vd /= wders[0];
        }
        out.push(v);
    }
    out
}

/// A B-spline (or, with weights, NURBS) curve in 1, 2 or 3 dimensions.
#[derive(Clone, Debug, PartialEq)]
pub struct BSplineCurve {
    knots: KnotVector,
    dim: usize,
    coefs: Vec<f64>,
    weights: Option<Vec<f64>>,
}

impl BSplineCurve {
    /// Builds and validates a curve: `coefs` holds the control points one after another
    /// (`dim` values each, `#knots - degree - 1` points), `weights` (one per control point,
    /// positive) makes it rational.
    pub fn new(
        degree: usize,
        knots: Vec<f64>,
        dim: usize,
        coefs: Vec<f64>,
        weights: Option<Vec<f64>>,
    ) -> Result<Self> {
        check_dim(dim)?;
        let knots = KnotVector::new(degree, knots)?;
        let n = knots.num_basis();
        if coefs.len() != n * dim {
            return Err(Error::invalid(format!(
                "a curve of degree {degree} with {} knots needs {n} control points ({} values in {dim}D), got {} values",
                knots.knots().len(),
                n * dim,
                coefs.len()
            )));
        }
        check_finite("control points", &coefs)?;
        check_weights(&weights, n)?;
        Ok(BSplineCurve {
            knots,
            dim,
            coefs,
            weights,
        })
    }

    /// The knot vector.
    pub fn knot_vector(&self) -> &KnotVector {
        &self.knots
    }

    /// The degree.
    pub fn degree(&self) -> usize {
        self.knots.degree()
    }

    /// The geometric dimension (1, 2 or 3).
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// The number of control points.
    pub fn num_control_points(&self) -> usize {
        self.knots.num_basis()
    }

    /// Control point `i` (components beyond [`dim`](Self::dim) are 0).
    pub fn control_point(&self, i: usize) -> Vec3 {
        let mut p = [0.0; 3];
        p[..self.dim].copy_from_slice(&self.coefs[i * self.dim..(i + 1) * self.dim]);
        p
    }

    /// Multiplies the control points' coordinates by `factors` axis by axis, as
    /// [`BSplineSurface::scale`] does: the curve becomes exactly its image.
    pub fn scale(&mut self, factors: Vec3) -> Result<()> {
        super::scale::scale_points(&mut self.coefs, self.dim, factors)
    }

    /// The weights, if the curve is rational.
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }

    /// The parameter domain.
    pub fn domain(&self) -> (f64, f64) {
        self.knots.domain()
    }

    /// Whether the knot vector is clamped (open), so that the curve starts and ends at its first
    /// and last control points.
    pub fn is_clamped(&self) -> bool {
        self.knots.is_clamped()
    }

    /// The point and its derivatives up to order `nder` at `t` (clamped to the domain).
    pub fn derivs(&self, t: f64, nder: usize) -> Vec<Vec3> {
        let p = self.degree();
        let (span, ders) = self.knots.basis_derivs(t, nder);
        let mut aders = vec![[0.0; 3]; nder + 1];
        let mut wders = vec![0.0; nder + 1];
        for j in 0..=p {
            let i = span - p + j;
            let w = self.weights.as_ref().map_or(1.0, |w| w[i]);
            let cp = self.control_point(i);
            for k in 0..=nder {
                let c = ders[k][j] * w;
                wders[k] += c;
                for d in 0..3 {
                    aders[k][d] += c * cp[d];
                }
            }
        }
        if self.weights.is_some() {
            rational_derivs(&aders, &wders)
        } else {
            aders
        }
    }

    /// The point at `t` (clamped to the domain).
    pub fn eval(&self, t: f64) -> Vec3 {
        self.derivs(t, 0)[0]
    }

    /// The point and the first derivative at `t`.
    pub fn eval_deriv(&self, t: f64) -> (Vec3, Vec3) {
        let d = self.derivs(t, 1);
        (d[0], d[1])
    }

    /// The same curve traversed backwards over the same domain `[a, b]` (`t ↦ a + b - t`).
    pub fn reversed(&self) -> BSplineCurve {
        let (a, b) = self.domain();
        let mut knots: Vec<f64> = self
            .knots
            .knots()
            .iter()
            .rev()
            .map(|&k| a + b - k)
            .collect();
        // Exact end knots despite rounding.
        for k in knots.iter_mut() {
            *k = k.clamp(self.knots.knots()[0], *self.knots.knots().last().unwrap());
        }
        let n = self.num_control_points();
        let mut coefs = Vec::with_capacity(self.coefs.len());
        for i in (0..n).rev() {
            coefs.extend_from_slice(&self.coefs[i * self.dim..(i + 1) * self.dim]);
        }
        BSplineCurve {
            knots: KnotVector {
                degree: self.degree(),
                knots,
            },
            dim: self.dim,
            coefs,
            weights: self
                .weights
                .as_ref()
                .map(|w| w.iter().rev().copied().collect()),
        }
    }
}

/// A tensor-product B-spline (or NURBS) surface; control point `(i, j)` is number `i + j·n_u`
/// (the first parameter runs fastest, as in G+Smo).
#[derive(Clone, Debug, PartialEq)]
pub struct BSplineSurface {
    knots_u: KnotVector,
    knots_v: KnotVector,
    dim: usize,
    coefs: Vec<f64>,
    weights: Option<Vec<f64>>,
}

impl BSplineSurface {
    /// Builds and validates a surface from its two knot vectors (with degrees), its control points
    /// (`dim` values each, `n_u · n_v` points, u fastest) and optional positive weights.
    pub fn new(
        (degree_u, knots_u): (usize, Vec<f64>),
        (degree_v, knots_v): (usize, Vec<f64>),
        dim: usize,
        coefs: Vec<f64>,
        weights: Option<Vec<f64>>,
    ) -> Result<Self> {
        check_dim(dim)?;
        let knots_u = KnotVector::new(degree_u, knots_u)?;
        let knots_v = KnotVector::new(degree_v, knots_v)?;
        let n = knots_u.num_basis() * knots_v.num_basis();
        if coefs.len() != n * dim {
            return Err(Error::invalid(format!(
                "a tensor-product surface with {} × {} basis functions needs {n} control points ({} values in {dim}D), got {} values",
                knots_u.num_basis(),
                knots_v.num_basis(),
                n * dim,
                coefs.len()
            )));
        }
        check_finite("control points", &coefs)?;
        check_weights(&weights, n)?;
        Ok(BSplineSurface {
            knots_u,
            knots_v,
            dim,
            coefs,
            weights,
        })
    }

    /// The knot vector of the first parameter.
    pub fn knot_vector_u(&self) -> &KnotVector {
        &self.knots_u
    }

    /// The knot vector of the second parameter.
    pub fn knot_vector_v(&self) -> &KnotVector {
        &self.knots_v
    }

    /// The geometric dimension.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// The number of control points in each direction.
    pub fn num_control_points(&self) -> (usize, usize) {
        (self.knots_u.num_basis(), self.knots_v.num_basis())
    }

    /// Control point `(i, j)`.
    pub fn control_point(&self, i: usize, j: usize) -> Vec3 {
        let k = i + j * self.knots_u.num_basis();
        let mut p = [0.0; 3];
        p[..self.dim].copy_from_slice(&self.coefs[k * self.dim..(k + 1) * self.dim]);
        p
    }

    /// The weights (one per control point, in the order of the control points), if the
    /// surface is rational.
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }

    /// The parameter domain `((u0, u1), (v0, v1))`.
    pub fn domain(&self) -> ((f64, f64), (f64, f64)) {
        (self.knots_u.domain(), self.knots_v.domain())
    }

    /// The point and the partial derivatives `(S, ∂S/∂u, ∂S/∂v)` at `(u, v)` (clamped to the domain).
    pub fn eval_derivs(&self, u: f64, v: f64) -> (Vec3, Vec3, Vec3) {
        let (pu, pv) = (self.knots_u.degree(), self.knots_v.degree());
        let (su, du) = self.knots_u.basis_derivs(u, 1);
        let (sv, dv) = self.knots_v.basis_derivs(v, 1);
        // homogeneous sums: index 0 value, 1 d/du, 2 d/dv
        let mut a = [[0.0; 3]; 3];
        let mut w = [0.0; 3];
        for jb in 0..=pv {
            let j = sv - pv + jb;
            for ib in 0..=pu {
                let i = su - pu + ib;
                let k = i + j * self.knots_u.num_basis();
                let wk = self.weights.as_ref().map_or(1.0, |w| w[k]);
                let cp = self.control_point(i, j);
                let c = [
                    du[0][ib] * dv[0][jb] * wk,
                    du[1][ib] * dv[0][jb] * wk,
                    du[0][ib] * dv[1][jb] * wk,
                ];
                for r in 0..3 {
                    w[r] += c[r];
                    for d in 0..3 {
                        a[r][d] += c[r] * cp[d];
                    }
                }
            }
        }
        if self.weights.is_some() {
            let s = a[0].map(|x| x / w[0]);
            let d = |r: usize| {
                let mut out = [0.0; 3];
                for k in 0..3 {
                    out[k] = (a[r][k] - w[r] * s[k]) / w[0];
                }
                out
            };
            (s, d(1), d(2))
        } else {
            (a[0], a[1], a[2])
        }
    }

    /// The point at `(u, v)`.
    pub fn eval(&self, u: f64, v: f64) -> Vec3 {
        self.eval_derivs(u, v).0
    }

    /// Multiplies the control points' coordinates by `factors`, axis by axis (the first
    /// [`BSplineSurface::dim`] factors are used). Weights and knots stay: the surface becomes
    /// exactly its image under the scaling, for B-splines and NURBS alike (a rational map is a
    /// weighted average of its control points). An error if a factor is not finite and
    /// positive; then nothing changes.
    pub fn scale(&mut self, factors: Vec3) -> Result<()> {
        super::scale::scale_points(&mut self.coefs, self.dim, factors)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn partition_of_unity_and_derivative_sum() {
        let kv =
            KnotVector::new(3, vec![0., 0., 0., 0., 0.2, 0.5, 0.5, 0.9, 1., 1., 1., 1.]).unwrap();
        for i in 0..=100 {
            let t = i as f64 / 100.0;
            let (_, d) = kv.basis_derivs(t, 2);
            assert!((d[0].iter().sum::<f64>() - 1.0).abs() < 1e-13, "t={t}");
            assert!(d[1].iter().sum::<f64>().abs() < 1e-10);
            assert!(d[0].iter().all(|&x| x >= -1e-15));
        }
    }

    #[test]
    fn rejects_bad_input() {
        let e = KnotVector::new(2, vec![0., 0., 0., 0.5, 0.4, 1., 1., 1.]).unwrap_err();
        assert!(e.message.contains("non-decreasing"), "{}", e.message);
        let e = BSplineCurve::new(1, vec![0., 0., 1., 1.], 2, vec![0.; 6], None).unwrap_err();
        assert!(e.message.contains("control points"), "{}", e.message);
        let e = BSplineCurve::new(1, vec![0., 0., 1., 1.], 2, vec![0., f64::NAN, 1., 1.], None)
            .unwrap_err();
        assert_eq!(e.kind, crate::ErrorKind::NotFinite);
        let e = BSplineCurve::new(1, vec![0., 0., 1., 1.], 2, vec![0.; 4], Some(vec![1., -1.]))
            .unwrap_err();
        assert!(e.message.contains("positive"));
    }

    #[test]
    fn reversed_curve_runs_backwards() {
        let c = BSplineCurve::new(
            2,
            vec![0., 0., 0., 0.3, 1., 1., 1.],
            2,
            vec![0., 0., 1., 2., 3., 1., 4., 4.],
            None,
        )
        .unwrap();
        let r = c.reversed();
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            let (a, b) = (c.eval(t), r.eval(1.0 - t));
            assert!((a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12);
        }
    }
}
