//! G+Smo XML THB-spline maps (`igaparam::spline::read_gismo_thb`, `parse_gismo_patches`), in 2D
//! and 3D. An accepted map must evaluate to finite points, and what the library writes of it
//! must read back as the same map.

use igaparam::spline::{read_gismo_thb, write_gismo_thb, SplineMap, ThbSpace};

use crate::common::{assert_finite, checked, params, text};

/// Reads `data` as a 2D and as a 3D THB map, first patch and every patch.
pub fn run(data: &[u8]) {
    let Some(text) = text(data) else { return };
    check::<2>(text);
    check::<3>(text);
}

fn check<const D: usize>(text: &str) {
    if let Some(maps) = checked(
        "parse_gismo_patches",
        SplineMap::<D, ThbSpace<D>>::parse_gismo_patches(text),
    ) {
        maps.iter().for_each(check_map);
    }
    let Some(map) = checked("read_gismo_thb", read_gismo_thb::<D>(text)) else {
        return;
    };
    check_map(&map);
    let written = write_gismo_thb(&map);
    let again = read_gismo_thb::<D>(&written)
        .unwrap_or_else(|e| panic!("a written map does not read back: {}", e.message));
    assert_eq!(again.element_count(), map.element_count(), "elements");
    assert_eq!(
        again.control_points(),
        map.control_points(),
        "control points"
    );
}

/// Values at a grid of points are finite (the basis is a partition of unity on finite control
/// points), and every element lies in [0,1]^d.
fn check_map<const D: usize>(map: &SplineMap<D, ThbSpace<D>>) {
    for e in 0..map.element_count() {
        let (lo, hi) = map.element_bounds(e);
        for k in 0..D {
            assert!(
                0.0 <= lo[k] && lo[k] < hi[k] && hi[k] <= 1.0,
                "element {e}: {lo:?} {hi:?}"
            );
        }
    }
    let n = if D == 2 { 4 } else { 2 };
    for i in 0..(n + 1usize).pow(D as u32) {
        let x: [f64; D] =
            std::array::from_fn(|k| params(n).nth(i / (n + 1).pow(k as u32) % (n + 1)).unwrap());
        let y = map
            .eval(x)
            .unwrap_or_else(|| panic!("no value at {x:?} in [0,1]^{D}"));
        assert_finite("THB map value", &y);
    }
}
