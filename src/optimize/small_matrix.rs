//! Fixed-size vectors and matrices for d = 2, 3: the algebra of one Jacobian.
//!
//! Matrices are row-major arrays `[[f64; D]; D]`; `D` is a compile-time constant, so the
//! `match D` below folds away.

/// A point or direction in d-space.
pub type Vector<const D: usize> = [f64; D];
/// A d×d matrix, row-major.
pub type Matrix<const D: usize> = [[f64; D]; D];

/// The zero matrix.
pub fn zero<const D: usize>() -> Matrix<D> {
    [[0.0; D]; D]
}

/// The identity scaled by `s`.
pub fn scaled_identity<const D: usize>(s: f64) -> Matrix<D> {
    let mut m = zero::<D>();
    for (i, row) in m.iter_mut().enumerate() {
        row[i] = s;
    }
    m
}

/// Cube root of a positive finite number: a bit-level first guess refined by three Halley steps
/// (each triples the correct digits), several times faster than the portable `cbrt`.
pub fn cube_root(x: f64) -> f64 {
    if !(x > 0.0 && x.is_finite()) || x < 1e-290 {
        return x.cbrt();
    }
    let mut y = f64::from_bits(x.to_bits() / 3 + 0x2A9F_7893_782D_A1CE);
    for _ in 0..3 {
        let y3 = y * y * y;
        y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
    }
    y
}

/// Determinant.
pub fn det<const D: usize>(a: &Matrix<D>) -> f64 {
    match D {
        2 => a[0][0] * a[1][1] - a[0][1] * a[1][0],
        3 => {
            a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
                - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
                + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
        }
        _ => unreachable!("only d = 2 and 3 are supported"),
    }
}

/// Cofactor matrix: `cof[i][j] = ∂det(a)/∂a[i][j]`.
pub fn cofactor<const D: usize>(a: &Matrix<D>) -> Matrix<D> {
    let mut c = zero::<D>();
    match D {
        2 => {
            c[0][0] = a[1][1];
            c[0][1] = -a[1][0];
            c[1][0] = -a[0][1];
            c[1][1] = a[0][0];
        }
        3 => {
            for (i, row) in c.iter_mut().enumerate() {
                let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
                for (j, cij) in row.iter_mut().enumerate() {
                    let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
                    *cij = a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1];
                }
            }
        }
        _ => unreachable!("only d = 2 and 3 are supported"),
    }
    c
}

/// Inverse, or `None` when the matrix is singular.
pub fn inverse<const D: usize>(a: &Matrix<D>) -> Option<Matrix<D>> {
    let d = det(a);
    if d == 0.0 || !d.is_finite() {
        return None;
    }
    let c = cofactor(a);
    let mut inv = zero::<D>();
    for (i, row) in inv.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = c[j][i] / d;
        }
    }
    Some(inv)
}

/// Matrix product `a·b`.
pub fn mul<const D: usize>(a: &Matrix<D>, b: &Matrix<D>) -> Matrix<D> {
    let mut m = zero::<D>();
    for i in 0..D {
        for j in 0..D {
            m[i][j] = (0..D).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    m
}

/// Matrix–vector product `a·v`.
pub fn mul_vec<const D: usize>(a: &Matrix<D>, v: &Vector<D>) -> Vector<D> {
    let mut r = [0.0; D];
    for (ri, row) in r.iter_mut().zip(a) {
        *ri = dot(row, v);
    }
    r
}

/// Transposed product `aᵀ·v`.
pub fn mul_transpose_vec<const D: usize>(a: &Matrix<D>, v: &Vector<D>) -> Vector<D> {
    let mut r = [0.0; D];
    for (row, vi) in a.iter().zip(v) {
        for (rj, aij) in r.iter_mut().zip(row) {
            *rj += aij * vi;
        }
    }
    r
}

/// Corners of the box around the points.
pub fn bounding_box<const D: usize>(
    points: impl IntoIterator<Item = [f64; D]>,
) -> ([f64; D], [f64; D]) {
    points.into_iter().fold(
        ([f64::INFINITY; D], [f64::NEG_INFINITY; D]),
        |(lo, hi), p| {
            (
                std::array::from_fn(|k| lo[k].min(p[k])),
                std::array::from_fn(|k| hi[k].max(p[k])),
            )
        },
    )
}

/// `p` moved towards `anchor` until it is at most `radius` from it.
pub fn clip_to_ball<const D: usize>(p: Vector<D>, anchor: Vector<D>, radius: f64) -> Vector<D> {
    let o: Vector<D> = std::array::from_fn(|k| p[k] - anchor[k]);
    let length = dot(&o, &o).sqrt();
    if length <= radius {
        p
    } else {
        std::array::from_fn(|k| anchor[k] + o[k] * radius / length)
    }
}

/// Dot product.
pub fn dot<const D: usize>(a: &Vector<D>, b: &Vector<D>) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Squared Frobenius norm.
pub fn frobenius2<const D: usize>(a: &Matrix<D>) -> f64 {
    a.iter().flatten().map(|x| x * x).sum()
}

/// `a + x yᵀ`.
pub fn add_outer<const D: usize>(a: &Matrix<D>, x: &Vector<D>, y: &Vector<D>) -> Matrix<D> {
    let mut m = *a;
    for i in 0..D {
        for j in 0..D {
            m[i][j] += x[i] * y[j];
        }
    }
    m
}

/// Solves `h·p = b` for a symmetric `h` made positive definite by adding a multiple of the
/// identity (modified Cholesky, Nocedal & Wright Alg. 3.3). Rows/columns where `active` is
/// false are treated as identity rows with a zero right-hand side.
pub fn solve_spd_modified<const D: usize>(
    h: &Matrix<D>,
    b: &Vector<D>,
    active: &[bool; D],
) -> Vector<D> {
    let mut a = *h;
    let mut rhs = *b;
    for (i, _) in active.iter().enumerate().filter(|(_, &on)| !on) {
        for row in a.iter_mut() {
            row[i] = 0.0;
        }
        a[i] = [0.0; D];
        a[i][i] = 1.0;
        rhs[i] = 0.0;
    }
    let norm = frobenius2(&a).sqrt().max(f64::MIN_POSITIVE);
    let beta = 1e-3 * norm;
    let min_diag = (0..D).map(|i| a[i][i]).fold(f64::INFINITY, f64::min);
    let mut tau = if min_diag > 0.0 { 0.0 } else { beta - min_diag };
    for _ in 0..64 {
        let mut shifted = a;
        for (i, row) in shifted.iter_mut().enumerate() {
            row[i] += tau;
        }
        if let Some(l) = cholesky(&shifted) {
            return cholesky_solve(&l, &rhs);
        }
        tau = (2.0 * tau).max(beta);
    }
    // Only reached for non-finite input: a steepest-descent direction is still a descent one.
    rhs.map(|v| v / norm)
}

fn cholesky<const D: usize>(a: &Matrix<D>) -> Option<Matrix<D>> {
    let mut l = zero::<D>();
    for j in 0..D {
        let s = a[j][j] - (0..j).map(|k| l[j][k] * l[j][k]).sum::<f64>();
        if s <= 0.0 || !s.is_finite() {
            return None;
        }
        l[j][j] = s.sqrt();
        for i in j + 1..D {
            l[i][j] = (a[i][j] - (0..j).map(|k| l[i][k] * l[j][k]).sum::<f64>()) / l[j][j];
        }
    }
    Some(l)
}

fn cholesky_solve<const D: usize>(l: &Matrix<D>, b: &Vector<D>) -> Vector<D> {
    let mut y = [0.0; D];
    for i in 0..D {
        y[i] = (b[i] - (0..i).map(|k| l[i][k] * y[k]).sum::<f64>()) / l[i][i];
    }
    let mut x = [0.0; D];
    for i in (0..D).rev() {
        x[i] = (y[i] - (i + 1..D).map(|k| l[k][i] * x[k]).sum::<f64>()) / l[i][i];
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fast_cube_root_is_accurate() {
        for &x in &[1e-280, 1e-30, 2.2e-10, 0.3, 1.0, 8.0, 12345.678, 1e200] {
            let (fast, exact) = (cube_root(x), f64::cbrt(x));
            assert!(
                (fast - exact).abs() <= 4.0 * f64::EPSILON * exact,
                "{x}: {fast} vs {exact}"
            );
        }
    }

    #[test]
    fn inverse_and_cofactor_agree_with_determinant() {
        let a: Matrix<3> = [[2.0, 1.0, 0.5], [0.3, 3.0, -1.0], [0.1, 0.2, 1.5]];
        let inv = inverse(&a).unwrap();
        let p = mul(&a, &inv);
        for (i, row) in p.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                assert!((v - if i == j { 1.0 } else { 0.0 }).abs() < 1e-14);
            }
        }
        // Cofactor = derivative of the determinant.
        let c = cofactor(&a);
        let h = 1e-6;
        for i in 0..3 {
            for j in 0..3 {
                let mut b = a;
                b[i][j] += h;
                let fd = (det(&b) - det(&a)) / h;
                assert!((fd - c[i][j]).abs() < 1e-5);
            }
        }
    }

    #[test]
    fn modified_cholesky_gives_descent_direction_for_indefinite_matrix() {
        let h: Matrix<2> = [[1.0, 0.0], [0.0, -2.0]];
        let b = [1.0, 1.0];
        let p = solve_spd_modified(&h, &b, &[true, true]);
        assert!(dot(&p, &b) > 0.0);
        let q = solve_spd_modified(&h, &b, &[true, false]);
        assert_eq!(q[1], 0.0);
    }
}
