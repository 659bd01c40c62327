//! The twisted wing of the bundled data: 12,250 H27 cells, 982 inverted after the boundary moves.
//! Slow in debug builds; the test suite runs with `--release`.

use crate::common;

use igaparam::RelocateOptions;

#[test]
fn the_twisted_wing_is_untangled() {
    let mut mesh = common::load_case("wing_0012_h27.vtu");
    assert_eq!((mesh.cell_count(), mesh.node_count()), (12250, 105060));
    let report = mesh
        .relocate(&RelocateOptions::default(), &mut |_, _, _| true)
        .unwrap();
    assert_eq!(report.invalid_before, 982);
    assert_eq!(report.invalid_after, 0, "{report:?}");
    // The default method on this mesh (33.6 million Hessian values) is Newton's, with
    // multigrid-preconditioned steps: the result is a stationary point of the summed distortion,
    // of min quality 0.974 (the sweeps stop at 0.954).
    assert_eq!(report.sweeps, 0, "{report:?}");
    assert!(
        report.converged && report.gradient_norm <= 1e-8,
        "{report:?}"
    );
    assert!(report.min_quality > 0.97, "{report:?}");
}
