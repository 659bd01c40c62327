//! Spline calls: `igaparam_spline_*` on maps fitted to the live domains (plain and adaptive)
//! and read back from the files they write, with hostile points, indices, options and buffers.

use std::ptr::{null, null_mut};

use igaparam::capi::*;

use super::mesh::written_only_on_success;
use super::{hostile_path, ok, scratch, set_cancel_after, Choices, MAX_HANDLES, SENTINEL};

/// Elements beyond which the harness does not refine or certify a map (work per input).
const LARGE: usize = 1500;

/// The splines of one input; freed when dropped.
#[derive(Default)]
pub struct Splines {
    live: Vec<*mut igaparam_spline>,
}

impl Drop for Splines {
    fn drop(&mut self) {
        for s in self.live.drain(..) {
            igaparam_spline_free(s);
        }
    }
}

fn size(function: &str, f: impl FnOnce(*mut usize) -> igaparam_status) -> usize {
    let mut n = usize::MAX;
    assert!(
        ok(function, f(&mut n)),
        "{function} failed on a live spline"
    );
    n
}

fn dim(s: *const igaparam_spline) -> usize {
    size("igaparam_spline_dimension", |o| {
        igaparam_spline_dimension(s, o)
    })
}

fn basis(s: *const igaparam_spline) -> usize {
    size("igaparam_spline_basis_count", |o| {
        igaparam_spline_basis_count(s, o)
    })
}

fn elements(s: *const igaparam_spline) -> usize {
    size("igaparam_spline_element_count", |o| {
        igaparam_spline_element_count(s, o)
    })
}

fn control_points(s: *const igaparam_spline) -> Vec<f64> {
    let mut xyz = vec![0.0; basis(s) * dim(s)];
    let status = igaparam_spline_copy_control_points(s, xyz.as_mut_ptr(), xyz.len());
    assert!(ok("igaparam_spline_copy_control_points", status));
    xyz
}

/// The map's values at `params` (`n × d`), which must succeed.
fn values(s: *const igaparam_spline, params: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; params.len()];
    let n = params.len() / dim(s);
    let status = igaparam_spline_evaluate(s, n, params.as_ptr(), out.as_mut_ptr(), null_mut());
    assert!(
        ok("igaparam_spline_evaluate", status),
        "evaluation in [0,1]^d failed"
    );
    out
}

/// `n` parametric points in [0,1]^d of `d` coordinates each, some hostile when `hostile`.
fn params(c: &mut Choices, n: usize, d: usize, hostile: bool) -> Vec<f64> {
    (0..n * d)
        .map(|_| {
            if hostile && c.one_in(6) {
                c.pick(&[-1e-9, 1.0 + 1e-9, f64::NAN, f64::INFINITY, -0.0, 2.0])
            } else {
                c.unit()
            }
        })
        .collect()
}

/// Largest absolute coordinate of a list of values (a scale for tolerances).
fn extent(values: &[f64]) -> f64 {
    values.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

impl Splines {
    fn pick(&self, c: &mut Choices) -> *mut igaparam_spline {
        if self.live.is_empty() || c.one_in(10) {
            null_mut()
        } else {
            self.live[c.below(self.live.len())]
        }
    }

    fn push(&mut self, s: *mut igaparam_spline) {
        assert!(!s.is_null(), "a NULL spline handle");
        if self.live.len() == MAX_HANDLES {
            igaparam_spline_free(self.live.remove(0));
        }
        self.live.push(s);
    }

    /// One spline call; `domain` is a live domain or NULL, for the fits.
    pub fn call(&mut self, c: &mut Choices, domain: *mut igaparam_domain) {
        match c.below(10) {
            0 => self.fit(c, domain),
            1 => self.files(c),
            2 => self.copy(c),
            3 => self.extraction(c),
            4 => self.evaluate(c),
            5 => self.basis_at(c),
            6 => self.refine(c),
            7 => self.validity(c),
            8 => self.invert(c),
            _ => self.clone_or_free(c),
        }
    }

    fn fit(&mut self, c: &mut Choices, domain: *mut igaparam_domain) {
        let mut out = null_mut();
        let out_ptr = if c.one_in(12) {
            null_mut()
        } else {
            &mut out as *mut _
        };
        if c.one_in(3) {
            let mut o = igaparam_adapt_options_default();
            o.target_quality = c.pick(&[0.1, 0.0, 0.9, -1.0, f64::NAN]);
            o.max_rounds = c.pick(&[0, 1]);
            // Level 6 at most, or one the API must refuse (higher legal levels cost 4^level elements).
            o.max_level = c.pick(&[3, 5, 6, 17]);
            o.max_sweeps = c.pick(&[0, 10, 50]);
            o.threads = c.pick(&[0, 1, 2, 4096, 4097]);
            if c.one_in(3) {
                o.progress = Some(super::progress);
                set_cancel_after(c.pick(&[0, 1, 1000]));
            }
            let options = if c.one_in(8) { null() } else { &o as *const _ };
            let mut r = igaparam_adapt_report {
                rounds: 999,
                ..Default::default()
            };
            let status = igaparam_domain_fit_adaptive(domain, options, out_ptr, &mut r);
            if ok("igaparam_domain_fit_adaptive", status) {
                assert_eq!(r.elements, elements(out), "report: elements");
                assert_eq!(r.basis, basis(out), "report: basis");
                self.push(out);
            } else {
                assert!(out.is_null() && r.rounds == 999, "written on failure");
            }
            return;
        }
        let mut r = igaparam_fit_report {
            basis_count: 999,
            ..Default::default()
        };
        if ok(
            "igaparam_spline_fit_domain",
            igaparam_spline_fit_domain(domain, out_ptr, &mut r),
        ) {
            assert_eq!(r.basis_count, basis(out), "report: basis");
            assert_eq!(r.element_count, elements(out), "report: elements");
            self.push(out);
        } else {
            assert!(out.is_null() && r.basis_count == 999, "written on failure");
        }
    }

    /// Writes a map as G+Smo XML and `.vtu` and reads the XML back: the same map.
    fn files(&mut self, c: &mut Choices) {
        let s = self.pick(c);
        let path = if c.one_in(5) {
            hostile_path(c)
        } else {
            scratch("spline.xml")
        };
        if c.one_in(3) {
            let samples = c.pick(&[0, 1, 2, 33, u32::MAX]);
            let small =
                !s.is_null() && elements(s) * (samples.min(3) as usize).pow(dim(s) as u32) < 50_000;
            let samples = if small { samples } else { samples.max(33) };
            let status = igaparam_spline_write_vtu(s, scratch("spline.vtu").as_ptr(), samples);
            if ok("igaparam_spline_write_vtu", status) {
                let bytes =
                    std::fs::read(scratch("spline.vtu").to_str().unwrap()).expect("the file");
                igaparam::io::vtu::parse(&bytes)
                    .expect("igaparam_spline_write_vtu wrote a readable file");
            }
            return;
        }
        if !ok(
            "igaparam_spline_write_gismo",
            igaparam_spline_write_gismo(s, path.as_ptr()),
        ) {
            return;
        }
        let mut read = null_mut();
        let status = igaparam_spline_read_gismo(path.as_ptr(), &mut read);
        assert!(
            ok("igaparam_spline_read_gismo", status),
            "a written map does not read back"
        );
        assert_eq!(dim(read), dim(s));
        assert_eq!(elements(read), elements(s), "elements read back");
        assert_eq!(
            control_points(read),
            control_points(s),
            "control points read back"
        );
        self.push(read);
    }

    fn copy(&mut self, c: &mut Choices) {
        let s = self.pick(c);
        let (d, nb, ne) = if s.is_null() {
            (2, 16, 1)
        } else {
            (dim(s), basis(s), elements(s))
        };
        match c.below(3) {
            0 => {
                let len = c.len_around(nb * d);
                let mut buf = vec![SENTINEL; len];
                let status = igaparam_spline_copy_control_points(s, buf.as_mut_ptr(), len);
                written_only_on_success(
                    "igaparam_spline_copy_control_points",
                    status,
                    &buf,
                    f64::is_finite,
                    nb * d,
                );
            }
            1 => {
                let len = c.len_around(nb * d);
                let mut buf = vec![SENTINEL; len];
                let status = igaparam_spline_copy_greville_points(s, buf.as_mut_ptr(), len);
                written_only_on_success(
                    "igaparam_spline_copy_greville_points",
                    status,
                    &buf,
                    |u| (0.0..=1.0).contains(&u),
                    nb * d,
                );
            }
            _ => {
                let len = c.len_around(ne);
                let mut levels = vec![0xEEu8; len];
                let mut bounds = vec![SENTINEL; 2 * d * len];
                let pl = if c.one_in(3) {
                    null_mut()
                } else {
                    levels.as_mut_ptr()
                };
                let pb = if c.one_in(3) {
                    null_mut()
                } else {
                    bounds.as_mut_ptr()
                };
                let status = igaparam_spline_copy_elements(s, pl, pb, len);
                let nb_used = if pb.is_null() || status != igaparam_status::IGAPARAM_STATUS_OK {
                    0
                } else {
                    2 * d * ne
                };
                written_only_on_success(
                    "igaparam_spline_copy_elements",
                    status,
                    &bounds,
                    |u| (0.0..=1.0).contains(&u),
                    nb_used,
                );
                let nl = if pl.is_null() || status != igaparam_status::IGAPARAM_STATUS_OK {
                    0
                } else {
                    ne
                };
                assert!(
                    levels[nl..].iter().all(|&l| l == 0xEE),
                    "igaparam_spline_copy_elements: levels written past or on failure"
                );
            }
        }
    }

    fn extraction(&mut self, c: &mut Choices) {
        let s = self.pick(c);
        let (d, ne) = if s.is_null() {
            (2, 1)
        } else {
            (dim(s), elements(s))
        };
        let e = c.pick(&[0, ne.saturating_sub(1), ne, usize::MAX, ne / 2]);
        let mut m = usize::MAX;
        let status = igaparam_spline_element_function_count(s, e, &mut m);
        if !ok("igaparam_spline_element_function_count", status) {
            assert_eq!(m, usize::MAX, "written on failure");
            m = 16;
        }
        let columns = 1 << (2 * d);
        let lf = c.len_around(m);
        let lo = c.len_around(m * columns);
        let mut functions = vec![usize::MAX; lf];
        let mut operator = vec![SENTINEL; lo];
        let pf = if c.one_in(4) {
            null_mut()
        } else {
            functions.as_mut_ptr()
        };
        let po = if c.one_in(4) {
            null_mut()
        } else {
            operator.as_mut_ptr()
        };
        let status = igaparam_spline_copy_element_extraction(s, e, pf, lf, po, lo);
        let f = "igaparam_spline_copy_element_extraction";
        let success = status == igaparam_status::IGAPARAM_STATUS_OK;
        let n_op = if success && !po.is_null() {
            m * columns
        } else {
            0
        };
        written_only_on_success(f, status, &operator, f64::is_finite, n_op);
        let n_f = if success && !pf.is_null() { m } else { 0 };
        assert!(
            functions[..n_f].windows(2).all(|w| w[0] < w[1]),
            "{f}: functions not increasing"
        );
        assert!(
            functions[n_f..].iter().all(|&v| v == usize::MAX),
            "{f} wrote past or on failure"
        );
        if success && !po.is_null() {
            // The truncated basis is a partition of unity: the columns sum to 1.
            for k in 0..columns {
                let sum: f64 = (0..m).map(|i| operator[i * columns + k]).sum();
                assert!((sum - 1.0).abs() < 1e-9, "{f}: column {k} sums to {sum}");
            }
        }
    }

    fn evaluate(&mut self, c: &mut Choices) {
        let s = self.pick(c);
        let d = if s.is_null() { 2 } else { dim(s) };
        let n = c.below(5);
        let x = params(c, n, d, true);
        let mut points = vec![SENTINEL; n * d];
        let mut jac = vec![SENTINEL; n * d * d];
        let pp = if c.one_in(4) {
            null_mut()
        } else {
            points.as_mut_ptr()
        };
        let pj = if c.one_in(3) {
            null_mut()
        } else {
            jac.as_mut_ptr()
        };
        let px = if c.one_in(10) { null() } else { x.as_ptr() };
        let inside = x.iter().all(|v| (0.0..=1.0).contains(v));
        if c.one_in(3) {
            let mut q = vec![SENTINEL; n];
            let status = igaparam_spline_mean_ratio(s, n, px, q.as_mut_ptr());
            let f = "igaparam_spline_mean_ratio";
            written_only_on_success(f, status, &q, |v| (0.0..=1.0).contains(&v), n);
            assert!(
                status != igaparam_status::IGAPARAM_STATUS_OK || inside,
                "{f} accepted {x:?}"
            );
            return;
        }
        let status = igaparam_spline_evaluate(s, n, px, pp, pj);
        let success = status == igaparam_status::IGAPARAM_STATUS_OK;
        written_only_on_success(
            "igaparam_spline_evaluate",
            status,
            &points,
            f64::is_finite,
            if success && !pp.is_null() { n * d } else { 0 },
        );
        assert!(
            !success || inside,
            "igaparam_spline_evaluate accepted {x:?}"
        );
        if !success || pj.is_null() {
            assert!(
                jac.iter().all(|&v| v == SENTINEL),
                "Jacobians written on failure"
            );
        }
    }

    fn basis_at(&mut self, c: &mut Choices) {
        let s = self.pick(c);
        let d = if s.is_null() { 2 } else { dim(s) };
        let x = params(c, 1, d, true);
        let mut m = usize::MAX;
        let status = igaparam_spline_basis_count_at(s, x.as_ptr(), &mut m);
        if !ok("igaparam_spline_basis_count_at", status) {
            assert_eq!(m, usize::MAX, "written on failure");
            m = 16;
        }
        let len = c.len_around(m);
        let mut count = usize::MAX;
        let mut functions = vec![usize::MAX; len];
        let mut values = vec![SENTINEL; len];
        let mut gradients = vec![SENTINEL; len * d];
        let pf = if c.one_in(4) {
            null_mut()
        } else {
            functions.as_mut_ptr()
        };
        let pv = if c.one_in(4) {
            null_mut()
        } else {
            values.as_mut_ptr()
        };
        let pg = if c.one_in(4) {
            null_mut()
        } else {
            gradients.as_mut_ptr()
        };
        let status = igaparam_spline_basis_at(s, x.as_ptr(), &mut count, pf, pv, pg, len);
        let f = "igaparam_spline_basis_at";
        if ok(f, status) {
            assert_eq!(count, m, "{f}: count and basis_count_at differ");
            if !pv.is_null() {
                let sum: f64 = values[..m].iter().sum();
                assert!((sum - 1.0).abs() < 1e-9, "{f}: the values sum to {sum}");
                assert!(values[m..].iter().all(|&v| v == SENTINEL), "{f} wrote past");
            }
        } else {
            let too_small = status == igaparam_status::IGAPARAM_STATUS_BUFFER_TOO_SMALL;
            assert_eq!(
                count,
                if too_small { m } else { usize::MAX },
                "{f}: count on failure"
            );
            let untouched = values.iter().chain(&gradients).all(|&v| v == SENTINEL);
            assert!(
                untouched && functions.iter().all(|&v| v == usize::MAX),
                "{f} wrote on failure"
            );
        }
    }

    fn refine(&mut self, c: &mut Choices) {
        let s = self.pick(c);
        if !s.is_null() && elements(s) > LARGE {
            return;
        }
        let ne = if s.is_null() { 1 } else { elements(s) };
        let n = c.below(3);
        let list: Vec<usize> = (0..n)
            .map(|_| c.pick(&[0, ne / 2, ne.saturating_sub(1), ne, usize::MAX]))
            .collect();
        let ptr = if n == 0 && c.one_in(2) {
            null()
        } else {
            list.as_ptr()
        };
        let before = (!s.is_null()).then(|| {
            let x = params(c, 6, dim(s), false);
            let v = values(s, &x);
            (x, v, control_points(s))
        });
        let mut r = igaparam_fit_report {
            basis_count: 999,
            ..Default::default()
        };
        if ok(
            "igaparam_spline_refine",
            igaparam_spline_refine(s, n, ptr, &mut r),
        ) {
            let (x, v, _) = before.expect("a spline");
            let after = values(s, &x);
            let tol = 1e-9 * extent(&v).max(f64::MIN_POSITIVE);
            assert!(
                v.iter().zip(&after).all(|(a, b)| (a - b).abs() <= tol),
                "refinement changed the map"
            );
            assert_eq!(r.basis_count, basis(s), "report: basis");
        } else if let Some((_, _, cp)) = before {
            assert_eq!(
                control_points(s),
                cp,
                "igaparam_spline_refine failed and changed the map"
            );
            assert_eq!(r.basis_count, 999, "report written on failure");
        }
    }

    fn validity(&mut self, c: &mut Choices) {
        let s = self.pick(c);
        if !s.is_null() && elements(s) > LARGE {
            return;
        }
        let d = if s.is_null() { 2 } else { dim(s) };
        let ne = if s.is_null() { 1 } else { elements(s) };
        let mut o = igaparam_validity_options_default();
        o.max_depth = c.pick(&[0, 1, 5, 13, u32::MAX]);
        o.samples = c.pick(&[if d == 2 { 12 } else { 4 }, 2, 5, 0, 1, 65]);
        let options = if c.one_in(3) { null() } else { &o as *const _ };
        let len = c.len_around(ne);
        let mut bounds = vec![SENTINEL; len];
        let mut quality = vec![SENTINEL; len];
        let pb = if c.one_in(3) {
            null_mut()
        } else {
            bounds.as_mut_ptr()
        };
        let pq = if c.one_in(3) {
            null_mut()
        } else {
            quality.as_mut_ptr()
        };
        let mut r = igaparam_validity_report {
            uncertified: usize::MAX,
            ..Default::default()
        };
        let status = igaparam_spline_check_validity(s, options, &mut r, pb, pq, len);
        let f = "igaparam_spline_check_validity";
        let success = status == igaparam_status::IGAPARAM_STATUS_OK;
        let nq = if success && !pq.is_null() { ne } else { 0 };
        written_only_on_success(f, status, &quality, |q| (0.0..=1.0).contains(&q), nq);
        let nb = if success && !pb.is_null() { ne } else { 0 };
        assert!(
            bounds[nb..].iter().all(|&v| v == SENTINEL),
            "{f} wrote past or on failure"
        );
        if success {
            assert!(r.uncertified <= ne, "{r:?}");
            assert_eq!(r.certified_positive == 1, r.uncertified == 0, "{r:?}");
            assert!(
                (0.0..=1.0).contains(&r.min_quality) && r.min_quality <= r.mean_quality + 1e-12,
                "{r:?}"
            );
            if nb > 0 {
                let uncertified = bounds[..ne]
                    .iter()
                    .filter(|&&b| b.is_nan() || b <= 0.0)
                    .count();
                assert_eq!(
                    uncertified, r.uncertified,
                    "{f}: bounds and report disagree"
                );
            }
        } else {
            assert_eq!(r.uncertified, usize::MAX, "{f} wrote its report on failure");
        }
    }

    fn invert(&mut self, c: &mut Choices) {
        let s = self.pick(c);
        if !s.is_null() && elements(s) > LARGE {
            return;
        }
        let d = if s.is_null() { 2 } else { dim(s) };
        let n = 1 + c.below(3);
        let mut y = if s.is_null() {
            vec![0.5; n * d]
        } else {
            values(s, &params(c, n, d, false))
        };
        if c.one_in(4) {
            let j = c.below(y.len());
            y[j] = c.double();
        }
        let samples = c.pick(&[4, 2, 0, 1, 33, u32::MAX]);
        let mut x = vec![SENTINEL; n * d];
        let mut found = vec![-5i32; n];
        let pf = if c.one_in(3) {
            null_mut()
        } else {
            found.as_mut_ptr()
        };
        let status = igaparam_spline_invert(s, n, y.as_ptr(), samples, x.as_mut_ptr(), pf);
        if !ok("igaparam_spline_invert", status) {
            assert!(
                x.iter().all(|&v| v == SENTINEL) && found.iter().all(|&v| v == -5),
                "written on failure"
            );
            return;
        }
        let scale = extent(&control_points(s)).max(f64::MIN_POSITIVE);
        for i in 0..n {
            let p = &x[i * d..(i + 1) * d];
            let located = p.iter().all(|v| v.is_finite());
            if !pf.is_null() {
                assert_eq!(found[i], located as i32, "found and params disagree");
            }
            if located {
                let back = values(s, p);
                let gap = extent(
                    &back
                        .iter()
                        .zip(&y[i * d..])
                        .map(|(a, b)| a - b)
                        .collect::<Vec<_>>(),
                );
                assert!(gap <= 1e-9 * scale, "an inverted point maps {gap:e} away");
            }
        }
    }

    fn clone_or_free(&mut self, c: &mut Choices) {
        let s = self.pick(c);
        if c.one_in(2) {
            let mut out = null_mut();
            let out_ptr = if c.one_in(8) {
                null_mut()
            } else {
                &mut out as *mut _
            };
            if ok("igaparam_spline_clone", igaparam_spline_clone(s, out_ptr)) {
                assert_eq!(control_points(out), control_points(s), "the clone differs");
                self.push(out);
            } else {
                assert!(out.is_null(), "a handle written on failure");
            }
        } else if let Some(i) = self.live.iter().position(|&x| x == s) {
            igaparam_spline_free(self.live.remove(i));
        } else {
            igaparam_spline_free(null_mut());
        }
    }
}
