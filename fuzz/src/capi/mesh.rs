//! Mesh calls: `igaparam_mesh_*` on small structured grids of every cell type, with hostile
//! coordinates, connectivities, masks, motions, options and buffers.

use std::ptr::{null, null_mut};

use igaparam::capi::*;

use super::{ok, scratch, set_cancel_after, Choices, MAX_HANDLES, SENTINEL};

/// Cell type codes with their node counts; the last three are not cell types.
pub const CELL_CODES: [(igaparam_cell_type, usize); 9] = [
    (IGAPARAM_CELL_QUAD4, 4),
    (IGAPARAM_CELL_QUAD8, 8),
    (IGAPARAM_CELL_QUAD9, 9),
    (IGAPARAM_CELL_HEX8, 8),
    (IGAPARAM_CELL_HEX20, 20),
    (IGAPARAM_CELL_HEX27, 27),
    (0, 4),
    (-1, 9),
    (1000, 8),
];

/// A live mesh and what the checks need to know of it.
struct Handle {
    ptr: *mut igaparam_mesh,
}

/// The meshes of one input; freed when dropped.
#[derive(Default)]
pub struct Meshes {
    live: Vec<Handle>,
}

impl Drop for Meshes {
    fn drop(&mut self) {
        for h in self.live.drain(..) {
            igaparam_mesh_free(h.ptr);
        }
    }
}

/// What a mesh holds, read through the API.
#[derive(Debug, PartialEq)]
struct Snapshot {
    positions: Vec<u64>,
    reference: Vec<u64>,
    fixed: Vec<u8>,
}

fn count(function: &str, f: impl FnOnce(*mut usize) -> igaparam_status) -> usize {
    let mut n = usize::MAX;
    assert!(
        ok(function, f(&mut n)),
        "{function} failed on a live handle"
    );
    n
}

fn node_count(m: *const igaparam_mesh) -> usize {
    count("igaparam_mesh_node_count", |o| {
        igaparam_mesh_node_count(m, o)
    })
}

fn cell_count(m: *const igaparam_mesh) -> usize {
    count("igaparam_mesh_cell_count", |o| {
        igaparam_mesh_cell_count(m, o)
    })
}

fn positions(m: *const igaparam_mesh, reference: bool) -> Vec<f64> {
    let mut xyz = vec![0.0; 3 * node_count(m)];
    let (function, status) = if reference {
        let s = igaparam_mesh_copy_reference(m, xyz.as_mut_ptr(), xyz.len());
        ("igaparam_mesh_copy_reference", s)
    } else {
        let s = igaparam_mesh_copy_positions(m, xyz.as_mut_ptr(), xyz.len());
        ("igaparam_mesh_copy_positions", s)
    };
    assert!(ok(function, status), "{function} failed on a live mesh");
    xyz
}

fn fixed(m: *const igaparam_mesh) -> Vec<u8> {
    let mut mask = vec![0u8; node_count(m)];
    let status = igaparam_mesh_copy_fixed(m, mask.as_mut_ptr(), mask.len());
    assert!(ok("igaparam_mesh_copy_fixed", status));
    mask
}

fn snapshot(m: *const igaparam_mesh) -> Snapshot {
    let bits = |v: Vec<f64>| v.into_iter().map(f64::to_bits).collect();
    Snapshot {
        positions: bits(positions(m, false)),
        reference: bits(positions(m, true)),
        fixed: fixed(m),
    }
}

/// The local node coordinates of a cell type in an order, each in {-1, 0, 1}.
fn local_nodes(code: igaparam_cell_type, order: igaparam_node_order) -> Option<Vec<Vec<i64>>> {
    let mut n = 0;
    if igaparam_cell_type_node_count(code, &mut n) != igaparam_status::IGAPARAM_STATUS_OK {
        return None;
    }
    let d = if matches!(
        code,
        IGAPARAM_CELL_HEX8 | IGAPARAM_CELL_HEX20 | IGAPARAM_CELL_HEX27
    ) {
        3
    } else {
        2
    };
    let mut xi = vec![0.0; n * d];
    let status = igaparam_cell_type_copy_node_coordinates(code, order, xi.as_mut_ptr(), xi.len());
    (status == igaparam_status::IGAPARAM_STATUS_OK).then(|| {
        xi.chunks(d)
            .map(|p| p.iter().map(|&v| v as i64).collect())
            .collect()
    })
}

/// A structured grid of `n^d` cells on a `(2n+1)^d` lattice, scaled by `scale` and sheared:
/// `xyz` and the connectivity of the cells whose local nodes are `local`.
fn grid(n: usize, local: &[Vec<i64>], scale: f64, shear: f64) -> (Vec<f64>, Vec<i64>) {
    let d = local[0].len();
    let m = 2 * n + 1;
    let count = m.pow(d as u32);
    let mut xyz = Vec::with_capacity(3 * count);
    for i in 0..count {
        let c: Vec<f64> = (0..3)
            .map(|k| {
                if k < d {
                    (i / m.pow(k as u32) % m) as f64 / (m - 1) as f64
                } else {
                    0.0
                }
            })
            .collect();
        xyz.extend([(c[0] + shear * c[1]) * scale, c[1] * scale, c[2] * scale]);
    }
    let mut conn = Vec::new();
    for cell in 0..n.pow(d as u32) {
        let base: Vec<i64> = (0..d)
            .map(|k| (2 * (cell / n.pow(k as u32) % n)) as i64)
            .collect();
        for xi in local {
            let index = (0..d)
                .rev()
                .fold(0, |acc, k| acc * m as i64 + base[k] + xi[k] + 1);
            conn.push(index);
        }
    }
    (xyz, conn)
}

impl Meshes {
    /// One mesh call.
    pub fn call(&mut self, c: &mut Choices) {
        match c.below(8) {
            0 | 1 => self.new_mesh(c),
            2 => self.set_fixed(c),
            3 => self.move_nodes(c),
            4 => self.relocate(c),
            5 => self.copy(c),
            6 => self.file(c),
            _ => self.other(c),
        }
    }

    /// A live mesh, or NULL now and then (or when there is none).
    fn pick(&self, c: &mut Choices) -> Option<usize> {
        if self.live.is_empty() || c.one_in(10) {
            None
        } else {
            Some(c.below(self.live.len()))
        }
    }

    fn ptr(&self, i: Option<usize>) -> *mut igaparam_mesh {
        i.map_or(null_mut(), |i| self.live[i].ptr)
    }

    fn push(&mut self, h: Handle) {
        if self.live.len() == MAX_HANDLES {
            igaparam_mesh_free(self.live.remove(0).ptr);
        }
        self.live.push(h);
    }

    fn new_mesh(&mut self, c: &mut Choices) {
        let (code, per_cell) = c.pick(&CELL_CODES);
        let order = c.pick(&[IGAPARAM_ORDER_VTK, IGAPARAM_ORDER_GMSH, 2, -1]);
        let local = local_nodes(code, order.clamp(0, 1))
            .unwrap_or_else(|| vec![vec![-1, -1], vec![1, -1], vec![1, 1], vec![-1, 1]]);
        let three = local[0].len() == 3;
        let n = 1 + c.below(if three { 2 } else { 3 });
        let scale = c.pick(&[1.0, 1.0, 1e-6, 1e6, 1e-150, 1e150, 3.5]);
        let (mut xyz, mut conn) = grid(n, &local, scale, c.pick(&[0.0, 0.3, -0.9]));
        if c.one_in(4) {
            let i = c.below(xyz.len());
            xyz[i] = c.double();
        }
        if c.one_in(4) {
            let i = c.below(conn.len());
            let nodes = (xyz.len() / 3) as i64;
            conn[i] = c.pick(&[-1, nodes, i64::MAX, i64::MIN, conn[(i + 1) % conn.len()]]);
        }
        let num_nodes = xyz.len() / 3 - usize::from(c.one_in(8));
        let num_cells = if c.one_in(10) {
            0
        } else {
            conn.len() / per_cell.max(1)
        };
        let mut out: *mut igaparam_mesh = null_mut();
        let out_ptr = if c.one_in(12) {
            null_mut()
        } else {
            &mut out as *mut _
        };
        let xyz_ptr = if c.one_in(12) { null() } else { xyz.as_ptr() };
        let (status, function) = if c.one_in(2) {
            let s = igaparam_mesh_new(code, num_nodes, xyz_ptr, num_cells, conn.as_ptr(), out_ptr);
            (s, "igaparam_mesh_new")
        } else {
            let s = igaparam_mesh_new_ordered(
                code,
                order,
                num_nodes,
                xyz_ptr,
                num_cells,
                conn.as_ptr(),
                out_ptr,
            );
            (s, "igaparam_mesh_new_ordered")
        };
        if ok(function, status) {
            assert!(!out.is_null(), "{function} gave a NULL handle");
            assert_eq!(node_count(out), num_nodes);
            assert_eq!(cell_count(out), num_cells);
            self.push(Handle { ptr: out });
        } else {
            assert!(out.is_null(), "{function} wrote a handle on failure");
        }
    }

    fn set_fixed(&mut self, c: &mut Choices) {
        let i = self.pick(c);
        let m = self.ptr(i);
        let nodes = if m.is_null() { 4 } else { node_count(m) };
        let len = c.len_around(nodes);
        let mask: Vec<u8> = if c.one_in(3) {
            (0..len)
                .map(|_| c.pick(&[0, 1, 2, 3, 4, 7, 8, 255]))
                .collect()
        } else {
            boundary_mask(m, len)
        };
        let ptr = if c.one_in(10) { null() } else { mask.as_ptr() };
        let before = (!m.is_null()).then(|| snapshot(m));
        if !ok(
            "igaparam_mesh_set_fixed",
            igaparam_mesh_set_fixed(m, len, ptr),
        ) {
            if let Some(before) = before {
                assert_eq!(
                    snapshot(m),
                    before,
                    "igaparam_mesh_set_fixed failed and changed the mesh"
                );
            }
        } else {
            assert_eq!(fixed(m), mask, "the mask read back differs");
        }
    }

    fn move_nodes(&mut self, c: &mut Choices) {
        let i = self.pick(c);
        let m = self.ptr(i);
        if m.is_null() {
            let xyz = [0.0; 3];
            let status = igaparam_mesh_move_nodes(m, 1, null(), xyz.as_ptr());
            assert!(
                !ok("igaparam_mesh_move_nodes", status),
                "NULL mesh accepted"
            );
            return;
        }
        let before = snapshot(m);
        let now = positions(m, false);
        let mask = fixed(m);
        let nodes = mask.len();
        // Turn the constrained nodes about the centre of the box, or move hostile nodes.
        let angle = c.pick(&[0.1f64, 0.5, 1.5, 3.1]);
        let (sin, cos) = angle.sin_cos();
        let mut indices: Vec<i64> = (0..nodes as i64)
            .filter(|&k| mask[k as usize] != 0)
            .collect();
        if indices.is_empty() || c.one_in(3) {
            indices = (0..1 + c.below(3)).map(|_| c.below(nodes) as i64).collect();
        }
        let (lo, hi) = bounds(&now);
        let centre: Vec<f64> = (0..3).map(|k| 0.5 * (lo[k] + hi[k])).collect();
        let mut xyz = Vec::new();
        for &k in &indices {
            let p = &now[3 * k as usize..3 * k as usize + 3];
            let (x, y) = (p[0] - centre[0], p[1] - centre[1]);
            xyz.extend([
                centre[0] + cos * x - sin * y,
                centre[1] + sin * x + cos * y,
                p[2],
            ]);
        }
        if c.one_in(4) {
            let j = c.below(xyz.len());
            xyz[j] = c.double();
        }
        if c.one_in(4) {
            let j = c.below(indices.len());
            indices[j] = c.pick(&[-1, nodes as i64, i64::MAX, i64::MIN]);
        }
        let idx = if c.one_in(6) {
            null()
        } else {
            indices.as_ptr()
        };
        let status = igaparam_mesh_move_nodes(m, indices.len(), idx, xyz.as_ptr());
        if !ok("igaparam_mesh_move_nodes", status) {
            assert_eq!(
                snapshot(m),
                before,
                "igaparam_mesh_move_nodes failed and changed the mesh"
            );
        }
    }

    fn relocate(&mut self, c: &mut Choices) {
        let i = self.pick(c);
        let m = self.ptr(i);
        let mut o = igaparam_relocate_options_default();
        o.target = c.pick(&[
            IGAPARAM_TARGET_INITIAL,
            IGAPARAM_TARGET_INITIAL,
            IGAPARAM_TARGET_MASTER,
            2,
        ]);
        o.placement = c.pick(&[IGAPARAM_PLACEMENT_LAPLACIAN, IGAPARAM_PLACEMENT_CURRENT, 7]);
        o.optimize = c.pick(&[1, 1, 0, -3]);
        o.max_sweeps = c.pick(&[0, 1, 5, 30]);
        if c.one_in(4) {
            o.move_tolerance = c.double();
        }
        if c.one_in(4) {
            o.gradient_tolerance = c.double();
        }
        o.max_newton_iterations = c.pick(&[150, 0, 1, 10]);
        if c.one_in(3) {
            o.relaxation = c.pick(&[1.0, 1.99, 2.0, 0.5, f64::NAN]);
        }
        // Any legal count (capped to the cores), or one the API refuses.
        o.threads = c.pick(&[0, 1, 2, 4096, 4097, u32::MAX]);
        if c.one_in(3) {
            o.progress = Some(super::progress);
            set_cancel_after(c.pick(&[0, 1, 3, 1000]));
        }
        let options = if c.one_in(8) { null() } else { &o as *const _ };
        let mut report = igaparam_relocate_report {
            sweeps: 12345,
            ..Default::default()
        };
        let report_ptr = if c.one_in(4) {
            null_mut()
        } else {
            &mut report as *mut _
        };
        let before = (!m.is_null()).then(|| snapshot(m));
        if ok(
            "igaparam_mesh_relocate",
            igaparam_mesh_relocate(m, options, report_ptr),
        ) {
            if !report_ptr.is_null() {
                self.check_report(i.expect("a mesh"), &report);
            }
        } else {
            assert_eq!(
                report.sweeps, 12345,
                "igaparam_mesh_relocate wrote its report on failure"
            );
            if let Some(before) = before {
                assert_eq!(
                    snapshot(m),
                    before,
                    "igaparam_mesh_relocate failed and changed the mesh"
                );
            }
        }
    }

    fn check_report(&self, i: usize, r: &igaparam_relocate_report) {
        let m = self.live[i].ptr;
        assert_eq!(r.cells, cell_count(m));
        assert_eq!(r.nodes, node_count(m));
        assert!(
            r.invalid_after <= r.cells && r.invalid_before <= r.cells,
            "{r:?}"
        );
        assert!((0.0..=1.0).contains(&r.min_quality), "{r:?}");
        assert!(
            r.min_quality <= r.mean_quality + 1e-12 && r.mean_quality <= 1.0,
            "{r:?}"
        );
        // At every scale (the mesh is optimized in coordinates scaled to its own size).
        let invalid = count("igaparam_mesh_invalid_cell_count", |o| {
            igaparam_mesh_invalid_cell_count(m, o)
        });
        assert_eq!(
            invalid, r.invalid_after,
            "report and invalid cell count differ"
        );
    }

    fn copy(&mut self, c: &mut Choices) {
        let i = self.pick(c);
        let m = self.ptr(i);
        let (nodes, cells, per_cell) = if m.is_null() {
            (4, 1, 4)
        } else {
            let mut t = 0;
            assert!(ok(
                "igaparam_mesh_cell_type",
                igaparam_mesh_cell_type(m, &mut t)
            ));
            let per = CELL_CODES.iter().find(|e| e.0 == t).expect("a cell type").1;
            (node_count(m), cell_count(m), per)
        };
        match c.below(5) {
            0 | 1 => {
                let len = c.len_around(3 * nodes);
                let mut buf = vec![SENTINEL; len];
                let ptr = if c.one_in(8) {
                    null_mut()
                } else {
                    buf.as_mut_ptr()
                };
                let (status, f) = if c.one_in(2) {
                    (
                        igaparam_mesh_copy_positions(m, ptr, len),
                        "igaparam_mesh_copy_positions",
                    )
                } else {
                    (
                        igaparam_mesh_copy_reference(m, ptr, len),
                        "igaparam_mesh_copy_reference",
                    )
                };
                written_only_on_success(f, status, &buf, |v| v.is_finite(), 3 * nodes);
            }
            2 => {
                let len = c.len_around(cells);
                let mut buf = vec![SENTINEL; len];
                let target = c.pick(&[IGAPARAM_TARGET_INITIAL, IGAPARAM_TARGET_MASTER, 5]);
                let status = igaparam_mesh_copy_cell_quality(m, target, buf.as_mut_ptr(), len);
                let f = "igaparam_mesh_copy_cell_quality";
                written_only_on_success(f, status, &buf, |q| (0.0..=1.0).contains(&q), cells);
            }
            3 => {
                let len = c.len_around(nodes);
                let mut buf = vec![0xEEu8; len];
                let status = igaparam_mesh_copy_fixed(m, buf.as_mut_ptr(), len);
                if ok("igaparam_mesh_copy_fixed", status) {
                    assert!(
                        buf[..nodes].iter().all(|&b| b <= 7)
                            && buf[nodes..].iter().all(|&b| b == 0xEE)
                    );
                } else {
                    assert!(
                        buf.iter().all(|&b| b == 0xEE),
                        "igaparam_mesh_copy_fixed wrote on failure"
                    );
                }
            }
            _ => {
                let len = c.len_around(cells * per_cell);
                let mut buf = vec![i64::MIN; len];
                let order = c.pick(&[IGAPARAM_ORDER_VTK, IGAPARAM_ORDER_GMSH, 9]);
                let status = igaparam_mesh_copy_connectivity(m, order, buf.as_mut_ptr(), len);
                let f = "igaparam_mesh_copy_connectivity";
                if ok(f, status) {
                    let n = cells * per_cell;
                    assert!(
                        buf[..n].iter().all(|&v| (0..nodes as i64).contains(&v)),
                        "{f}"
                    );
                    assert!(
                        buf[n..].iter().all(|&v| v == i64::MIN),
                        "{f} wrote past the cells"
                    );
                } else {
                    assert!(buf.iter().all(|&v| v == i64::MIN), "{f} wrote on failure");
                }
            }
        }
    }

    /// Writes a mesh in a hostile format to a file (or a hostile path) and reads it back.
    fn file(&mut self, c: &mut Choices) {
        let i = self.pick(c);
        let m = self.ptr(i);
        let format = c.pick(&[0, 1, 2, 3, 17, 18, 19, 16, 4, -1]);
        let path = if c.one_in(6) {
            super::hostile_path(c)
        } else {
            scratch("mesh.vtu")
        };
        let status = igaparam_mesh_write_vtu_format(m, path.as_ptr(), format);
        if !ok("igaparam_mesh_write_vtu_format", status) {
            return;
        }
        let mut read = null_mut();
        let status = igaparam_mesh_read_vtu(path.as_ptr(), &mut read);
        assert!(
            ok("igaparam_mesh_read_vtu", status),
            "a written mesh does not read back"
        );
        let written = positions(m, false);
        let back = positions(read, true);
        assert!(
            written
                .iter()
                .zip(&back)
                .all(|(a, b)| a.to_bits() == b.to_bits() || a == b),
            "format {format}: the positions read back differ"
        );
        assert_eq!(
            fixed(read),
            fixed(m),
            "format {format}: the masks read back differ"
        );
        self.push(Handle { ptr: read });
    }

    fn other(&mut self, c: &mut Choices) {
        let i = self.pick(c);
        let m = self.ptr(i);
        match c.below(5) {
            0 => {
                let before = (!m.is_null()).then(|| snapshot(m));
                if ok(
                    "igaparam_mesh_reset_reference",
                    igaparam_mesh_reset_reference(m),
                ) {
                    let s = snapshot(m);
                    assert_eq!(
                        s.reference, s.positions,
                        "the reference is not the positions"
                    );
                    assert_eq!(Some(s.positions), before.map(|b| b.positions));
                }
            }
            1 => {
                let mut d = 77;
                let out = if c.one_in(4) {
                    null_mut()
                } else {
                    &mut d as *mut _
                };
                if ok("igaparam_mesh_dimension", igaparam_mesh_dimension(m, out)) {
                    assert!(d == 2 || d == 3, "dimension {d}");
                }
            }
            2 => {
                let mut o = 77;
                if ok("igaparam_mesh_order", igaparam_mesh_order(m, &mut o)) {
                    assert!(
                        o == IGAPARAM_ORDER_VTK || o == IGAPARAM_ORDER_GMSH,
                        "order {o}"
                    );
                }
            }
            3 => {
                let mut n = usize::MAX;
                if ok(
                    "igaparam_mesh_invalid_cell_count",
                    igaparam_mesh_invalid_cell_count(m, &mut n),
                ) {
                    assert!(n <= cell_count(m));
                }
            }
            _ => {
                if let Some(i) = i {
                    igaparam_mesh_free(self.live.remove(i).ptr);
                } else {
                    igaparam_mesh_free(null_mut());
                }
            }
        }
    }
}

/// A mask fixing the nodes on the bounding box's boundary (all coordinates).
fn boundary_mask(m: *const igaparam_mesh, len: usize) -> Vec<u8> {
    if m.is_null() {
        return vec![3; len];
    }
    let xyz = positions(m, false);
    let (lo, hi) = bounds(&xyz);
    let mut d = 2;
    assert!(ok(
        "igaparam_mesh_dimension",
        igaparam_mesh_dimension(m, &mut d)
    ));
    (0..len)
        .map(|k| {
            let p = xyz.get(3 * k..3 * k + 3).unwrap_or(&[0.0; 3]);
            let on = (0..d as usize).any(|a| p[a] == lo[a] || p[a] == hi[a]);
            if on {
                if d == 2 {
                    3
                } else {
                    7
                }
            } else {
                0
            }
        })
        .collect()
}

fn bounds(xyz: &[f64]) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in xyz.chunks(3) {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

/// After a copy into `buf` (filled with [`SENTINEL`]): on success the first `n` values pass
/// `valid` and the rest are untouched; on failure nothing was written.
pub fn written_only_on_success(
    function: &str,
    status: igaparam_status,
    buf: &[f64],
    valid: impl Fn(f64) -> bool,
    n: usize,
) {
    if ok(function, status) {
        assert!(buf[..n].iter().all(|&v| valid(v)), "{function}: bad values");
        assert!(
            buf[n..].iter().all(|&v| v == SENTINEL),
            "{function} wrote past its output"
        );
    } else {
        assert!(
            buf.iter().all(|&v| v == SENTINEL),
            "{function} wrote on failure"
        );
    }
}
