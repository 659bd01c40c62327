//! Domain calls: `igaparam_domain_*` on planar domains from polylines (squares at several
//! scales, concave and self-crossing loops) and the bundled boundary files, and on solids from
//! small cube triangulations and the bundled B-rep, with hostile options and buffers.

use std::ptr::{null, null_mut};

use igaparam::capi::*;

use super::mesh::written_only_on_success;
use super::{
    data_path, hostile_path, ok, scratch, set_cancel_after, Choices, MAX_HANDLES, SENTINEL,
};

/// The domains of one input; freed when dropped.
#[derive(Default)]
pub struct Domains {
    live: Vec<*mut igaparam_domain>,
}

impl Drop for Domains {
    fn drop(&mut self) {
        for d in self.live.drain(..) {
            igaparam_domain_free(d);
        }
    }
}

fn size_of(function: &str, f: impl FnOnce(*mut usize) -> igaparam_status) -> Option<usize> {
    let mut n = usize::MAX;
    ok(function, f(&mut n)).then_some(n)
}

fn is_built(d: *const igaparam_domain) -> bool {
    let mut b = -1;
    assert!(ok(
        "igaparam_domain_is_built",
        igaparam_domain_is_built(d, &mut b)
    ));
    assert!(b == 0 || b == 1, "is_built {b}");
    b == 1
}

fn dimension(d: *const igaparam_domain) -> usize {
    size_of("igaparam_domain_dimension", |o| {
        igaparam_domain_dimension(d, o)
    })
    .expect("a dimension")
}

/// What a built domain holds, read through the API: cells and vertex positions.
fn snapshot(d: *const igaparam_domain) -> Option<(usize, Vec<u64>)> {
    if !is_built(d) {
        return None;
    }
    let cells = size_of("igaparam_domain_cell_count", |o| {
        igaparam_domain_cell_count(d, o)
    })?;
    let vertices = size_of("igaparam_domain_vertex_count", |o| {
        igaparam_domain_vertex_count(d, o)
    })?;
    let mut xyz = vec![0.0; vertices * dimension(d)];
    let status = igaparam_domain_copy_vertices(d, null_mut(), xyz.as_mut_ptr(), xyz.len());
    assert!(ok("igaparam_domain_copy_vertices", status));
    Some((cells, xyz.into_iter().map(f64::to_bits).collect()))
}

/// Four polylines: a quadrilateral's sides at a scale, an inner point of one moved.
fn polylines(c: &mut Choices) -> Vec<Vec<f64>> {
    let shapes: [[[f64; 2]; 4]; 5] = [
        [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        [[0.0, 0.0], [4.0, 0.0], [3.0, 1.0], [0.5, 2.0]],
        // Concave at its third corner.
        [[0.0, 0.0], [2.0, 0.0], [0.6, 0.6], [0.0, 2.0]],
        // Side 2 crosses side 0 (issue 17 item 7).
        [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]],
        [[0.0, 0.0], [1.0, 0.0], [1.0, 1e-9], [0.0, 1e-9]],
    ];
    let corners = c.pick(&shapes);
    let scale = c.pick(&[1.0, 1.0, 1e-7, 1e7, 1e-200, 1e200]);
    let mut sides: Vec<Vec<f64>> = (0..4)
        .map(|k| {
            let (a, b) = (corners[k], corners[(k + 1) % 4]);
            let n = 2 + c.below(4);
            (0..n)
                .flat_map(|i| {
                    let t = i as f64 / (n - 1) as f64;
                    [
                        (a[0] + t * (b[0] - a[0])) * scale,
                        (a[1] + t * (b[1] - a[1])) * scale,
                    ]
                })
                .collect()
        })
        .collect();
    if c.one_in(3) {
        let k = c.below(4);
        let j = c.below(sides[k].len());
        sides[k][j] = if c.one_in(2) {
            c.double()
        } else {
            sides[k][j] + (c.unit() - 0.5) * scale
        };
    }
    if c.one_in(3) {
        sides.swap(0, 1 + c.below(3));
    }
    sides
}

/// Six faces of the unit cube, two triangles each: vertices and triangles per face.
fn cube_faces() -> Vec<(Vec<f64>, Vec<u32>)> {
    (0..6)
        .map(|face| {
            let (axis, side) = (face / 2, (face % 2) as f64);
            let (a, b) = [(1, 2), (0, 2), (0, 1)][axis];
            let mut xyz = Vec::new();
            for (u, v) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
                let mut p = [0.0; 3];
                p[axis] = side;
                p[a] = u;
                p[b] = v;
                xyz.extend(p);
            }
            (xyz, vec![0, 1, 2, 0, 2, 3])
        })
        .collect()
}

impl Domains {
    /// A live domain, or NULL now and then (or when there is none).
    pub fn pick(&self, c: &mut Choices) -> *mut igaparam_domain {
        if self.live.is_empty() || c.one_in(10) {
            null_mut()
        } else {
            self.live[c.below(self.live.len())]
        }
    }

    fn push(&mut self, d: *mut igaparam_domain) {
        assert!(!d.is_null(), "a NULL domain handle");
        if self.live.len() == MAX_HANDLES {
            igaparam_domain_free(self.live.remove(0));
        }
        self.live.push(d);
    }

    /// One domain call.
    pub fn call(&mut self, c: &mut Choices) {
        match c.below(8) {
            0 => self.new_from_polylines(c),
            1 => self.new_from_file(c),
            2 => self.solid(c),
            3 | 4 => self.build(c),
            5 => self.copy(c),
            6 => self.write(c),
            _ => {
                if !self.live.is_empty() && c.one_in(2) {
                    let i = c.below(self.live.len());
                    igaparam_domain_free(self.live.remove(i));
                } else {
                    igaparam_domain_free(null_mut());
                }
            }
        }
    }

    fn new_from_polylines(&mut self, c: &mut Choices) {
        let sides = polylines(c);
        let mut counts: Vec<usize> = sides.iter().map(|s| s.len() / 2).collect();
        if c.one_in(8) {
            let k = c.below(4);
            counts[k] = c.below(2);
        }
        let mut points: Vec<*const f64> = sides.iter().map(|s| s.as_ptr()).collect();
        if c.one_in(10) {
            points[c.below(4)] = null();
        }
        let mut out = null_mut();
        let counts_ptr = if c.one_in(16) {
            null()
        } else {
            counts.as_ptr()
        };
        let status = igaparam_domain_new_from_polylines(counts_ptr, points.as_ptr(), &mut out);
        if ok("igaparam_domain_new_from_polylines", status) {
            self.push(out);
        } else {
            assert!(out.is_null(), "a handle written on failure");
        }
    }

    fn new_from_file(&mut self, c: &mut Choices) {
        let files = [
            "boundary/puzzle3_bdry.xml",
            "boundary/rotor_bdry.xml",
            "boundary/duck2d_BRep.xml",
            "boundary/tenerife.txt",
            "boundary/duck3d_BRep.xml",
            "boundary/README.md",
        ];
        let path = if c.one_in(4) {
            hostile_path(c)
        } else {
            data_path(c.pick(&files))
        };
        let mut out = null_mut();
        let out_ptr = if c.one_in(12) {
            null_mut()
        } else {
            &mut out as *mut _
        };
        if ok(
            "igaparam_domain_new_from_file",
            igaparam_domain_new_from_file(path.as_ptr(), out_ptr),
        ) {
            self.push(out);
        } else {
            assert!(out.is_null(), "a handle written on failure");
        }
    }

    fn solid(&mut self, c: &mut Choices) {
        let mut out = null_mut();
        if c.one_in(3) {
            let scale = [
                c.pick(&[1.0, 2.0, 0.0, -1.0, f64::NAN, 1e300]),
                1.0,
                c.pick(&[1.0, 1e-3]),
            ];
            let scale_ptr = if c.one_in(2) { null() } else { scale.as_ptr() };
            let path = if c.one_in(4) {
                hostile_path(c)
            } else {
                data_path("boundary/duck3d_BRep.xml")
            };
            let status =
                igaparam_domain_new_solid_from_file_scaled(path.as_ptr(), scale_ptr, &mut out);
            if ok("igaparam_domain_new_solid_from_file_scaled", status) {
                self.push(out);
            } else {
                assert!(out.is_null(), "a handle written on failure");
            }
            return;
        }
        let mut faces = cube_faces();
        if c.one_in(3) {
            let f = c.below(6);
            let j = c.below(faces[f].0.len());
            faces[f].0[j] = if c.one_in(2) {
                c.double()
            } else {
                faces[f].0[j] + 0.25
            };
        }
        if c.one_in(4) {
            let f = c.below(6);
            let j = c.below(6);
            faces[f].1[j] = c.pick(&[4, u32::MAX, faces[f].1[(j + 1) % 6]]);
        }
        let scale = c.pick(&[1.0, 1.0, 1e-9, 1e9]);
        for face in faces.iter_mut() {
            face.0.iter_mut().for_each(|v| *v *= scale);
        }
        let mut vertex_counts: Vec<usize> = faces.iter().map(|f| f.0.len() / 3).collect();
        let mut triangle_counts: Vec<usize> = faces.iter().map(|f| f.1.len() / 3).collect();
        if c.one_in(8) {
            vertex_counts[c.below(6)] = c.below(4);
        }
        if c.one_in(8) {
            triangle_counts[c.below(6)] = c.below(2);
        }
        let xyz: Vec<*const f64> = faces.iter().map(|f| f.0.as_ptr()).collect();
        let mut triangles: Vec<*const u32> = faces.iter().map(|f| f.1.as_ptr()).collect();
        if c.one_in(10) {
            triangles[c.below(6)] = null();
        }
        let status = igaparam_domain_new_solid_from_triangulations(
            vertex_counts.as_ptr(),
            xyz.as_ptr(),
            triangle_counts.as_ptr(),
            triangles.as_ptr(),
            &mut out,
        );
        if ok("igaparam_domain_new_solid_from_triangulations", status) {
            self.push(out);
        } else {
            assert!(out.is_null(), "a handle written on failure");
        }
    }

    fn build(&mut self, c: &mut Choices) {
        let d = self.pick(c);
        let solid = !d.is_null() && dimension(d) == 3;
        let mut o = if solid {
            igaparam_domain_options_default_solid()
        } else {
            igaparam_domain_options_default()
        };
        if c.one_in(2) {
            o.tolerance = c.pick(&[1e-3, 1e-2, 1e-7, 0.0, -1.0, f64::NAN, f64::INFINITY]);
        }
        // Any legal level (up to 16), or values the API must refuse; a small cell budget keeps
        // deep builds short: they are refused (IGAPARAM_STATUS_LIMIT_EXCEEDED) before they
        // grow past it.
        o.min_level = c.pick(&[0, 1, 2, 5, 16, 17, u32::MAX]);
        o.max_level = c.pick(&[0, 1, 2, 3, 4, 5, 16, 17, u32::MAX]);
        o.max_cells = c.pick(&[if solid { 600 } else { 4000 }, 400, 16, 0]);
        o.max_sweeps = c.pick(&[0, 1, 10, 50]);
        o.max_total_sweeps = c.pick(&[300, 1, 0, u32::MAX]);
        o.threads = c.pick(&[0, 1, 2, 4096, 4097, u32::MAX]);
        o.repair_rounds = c.pick(&[0, 1, 2]);
        if c.one_in(3) {
            o.boundary_offset = c.pick(&[0.0, 0.5, -1.0, f64::NAN, 1e300]);
        }
        if c.one_in(3) {
            o.progress = Some(super::progress);
            set_cancel_after(c.pick(&[0, 1, 5, 1000]));
        }
        let options = if c.one_in(10) && !solid {
            null()
        } else {
            &o as *const _
        };
        let mut r = igaparam_domain_report {
            sweeps: 54321,
            ..Default::default()
        };
        let report = if c.one_in(4) {
            null_mut()
        } else {
            &mut r as *mut _
        };
        let before = (!d.is_null()).then(|| snapshot(d));
        if ok(
            "igaparam_domain_build",
            igaparam_domain_build(d, options, report),
        ) {
            assert!(is_built(d), "built but not built");
            let (cells, _) = snapshot(d).expect("a built domain");
            if !report.is_null() {
                assert_eq!(r.cells, cells, "report: cells");
                assert!(r.invalid_cells <= r.cells, "{r:?}");
                assert!((0.0..=1.0).contains(&r.min_quality), "{r:?}");
                assert!(
                    r.min_quality <= r.mean_quality + 1e-12 && r.mean_quality <= 1.0,
                    "{r:?}"
                );
            }
        } else {
            assert_eq!(
                r.sweeps, 54321,
                "igaparam_domain_build wrote its report on failure"
            );
            if let Some(before) = before {
                assert_eq!(
                    snapshot(d),
                    before,
                    "igaparam_domain_build failed and changed the domain"
                );
            }
        }
    }

    fn copy(&mut self, c: &mut Choices) {
        let d = self.pick(c);
        let built = !d.is_null() && is_built(d);
        let dim = if d.is_null() { 2 } else { dimension(d) };
        let cells = if built {
            size_of("igaparam_domain_cell_count", |o| {
                igaparam_domain_cell_count(d, o)
            })
            .unwrap()
        } else {
            1
        };
        let vertices = if built {
            size_of("igaparam_domain_vertex_count", |o| {
                igaparam_domain_vertex_count(d, o)
            })
            .unwrap()
        } else {
            4
        };
        match c.below(4) {
            0 => {
                let len = c.len_around(dim * vertices);
                let mut a = vec![SENTINEL; len];
                let mut b = vec![SENTINEL; len];
                let pa = if c.one_in(3) {
                    null_mut()
                } else {
                    a.as_mut_ptr()
                };
                let pb = if c.one_in(3) {
                    null_mut()
                } else {
                    b.as_mut_ptr()
                };
                let status = igaparam_domain_copy_vertices(d, pa, pb, len);
                let f = "igaparam_domain_copy_vertices";
                let n = if status == igaparam_status::IGAPARAM_STATUS_OK {
                    dim * vertices
                } else {
                    0
                };
                let pa_n = if pa.is_null() { 0 } else { n };
                let pb_n = if pb.is_null() { 0 } else { n };
                written_only_on_success(f, status, &a, |u| (0.0..=1.0).contains(&u), pa_n);
                assert!(
                    b[..pb_n].iter().all(|v| v.is_finite())
                        && b[pb_n..].iter().all(|&v| v == SENTINEL),
                    "{f}"
                );
            }
            1 => {
                let len = c.len_around(cells);
                let mut q = vec![SENTINEL; len];
                let status = igaparam_domain_copy_cell_quality(d, q.as_mut_ptr(), len);
                written_only_on_success(
                    "igaparam_domain_copy_cell_quality",
                    status,
                    &q,
                    |v| (0.0..=1.0).contains(&v),
                    cells,
                );
            }
            2 => {
                let len = c.len_around(cells);
                let mut levels = vec![0xEEu8; len];
                let mut bounds = vec![SENTINEL; 2 * dim * len];
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
                let status = igaparam_domain_copy_cells(d, pl, pb, len);
                let f = "igaparam_domain_copy_cells";
                if ok(f, status) {
                    let nb = if pb.is_null() { 0 } else { 2 * dim * cells };
                    assert!(
                        bounds[..nb].iter().all(|v| (0.0..=1.0).contains(v)),
                        "{f}: bounds"
                    );
                    assert!(
                        bounds[nb..].iter().all(|&v| v == SENTINEL),
                        "{f} wrote past the cells"
                    );
                } else {
                    assert!(
                        levels.iter().all(|&v| v == 0xEE) && bounds.iter().all(|&v| v == SENTINEL),
                        "{f} wrote on failure"
                    );
                }
            }
            _ => {
                let len = c.len_around(cells << dim);
                let mut corners = vec![usize::MAX; len];
                let status = igaparam_domain_copy_cell_corners(d, corners.as_mut_ptr(), len);
                let f = "igaparam_domain_copy_cell_corners";
                if ok(f, status) {
                    let n = cells << dim;
                    assert!(
                        corners[..n].iter().all(|&v| v < vertices),
                        "{f}: a corner out of range"
                    );
                    assert!(
                        corners[n..].iter().all(|&v| v == usize::MAX),
                        "{f} wrote past the cells"
                    );
                } else {
                    assert!(
                        corners.iter().all(|&v| v == usize::MAX),
                        "{f} wrote on failure"
                    );
                }
            }
        }
    }

    fn write(&mut self, c: &mut Choices) {
        let d = self.pick(c);
        let path = if c.one_in(4) {
            hostile_path(c)
        } else {
            scratch("domain.vtu")
        };
        let path_ptr = if c.one_in(8) { null() } else { path.as_ptr() };
        let status = igaparam_domain_write_vtu(d, path_ptr);
        if ok("igaparam_domain_write_vtu", status) {
            let bytes = std::fs::read(path.to_str().unwrap()).expect("the written file");
            igaparam::io::vtu::parse(&bytes)
                .expect("igaparam_domain_write_vtu wrote a readable file");
        }
    }
}
