//! The certified lower bound of a spline map's mean ratio: exact on affine maps, below every
//! densely evaluated value and close to the sampled minimum on curved maps, 0 where det J
//! touches 0, the same for any thread count.

use igaparam::spline::{QualityBound, QualityBoundOptions, SplineMap, ThbSpace};
use igaparam::tmesh::Tree;
use igaparam::ErrorKind;

fn uniform_space<const D: usize>(level: u8) -> ThbSpace<D> {
    let mut tree = Tree::<D>::new();
    tree.refine_uniformly(level).unwrap();
    ThbSpace::new(tree).unwrap()
}

/// `d·det(J)^{2/d}/‖J‖²` computed here (independently of the library), 0 where `det J ≤ 0`.
pub fn mean_ratio<const D: usize>(j: &[[f64; D]; D]) -> f64 {
    let d = match D {
        2 => j[0][0] * j[1][1] - j[0][1] * j[1][0],
        _ => {
            j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1])
                - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
                + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0])
        }
    };
    let n: f64 = j.iter().flatten().map(|v| v * v).sum();
    if d > 0.0 {
        D as f64 * d.powf(2.0 / D as f64) / n
    } else {
        0.0
    }
}

/// The smallest mean ratio at `n` points per direction and element.
fn dense_min<const D: usize>(map: &SplineMap<D>, n: usize) -> f64 {
    let mut min = f64::INFINITY;
    for e in 0..map.element_count() {
        let (lo, hi) = map.element_bounds(e);
        for s in 0..n.pow(D as u32) {
            let x = std::array::from_fn(|a| {
                let i = s / n.pow(a as u32) % n;
                lo[a] + (hi[a] - lo[a]) * i as f64 / (n - 1) as f64
            });
            min = min.min(mean_ratio(&map.eval_with_jacobian(x).unwrap().1));
        }
    }
    min
}

#[test]
fn the_bound_is_exact_on_affine_maps() {
    let affine = |x: [f64; 2]| Some([2.0 * x[0] + 0.5 * x[1] - 1.0, -0.3 * x[0] + 1.5 * x[1]]);
    let (map, _) = SplineMap::fit(uniform_space::<2>(2), affine).unwrap();
    let j = [[2.0, 0.5], [-0.3, 1.5]];
    let exact = mean_ratio(&j);
    let b = map.quality_bound(&QualityBoundOptions::default()).unwrap();
    assert!((b.lower_bound - exact).abs() < 1e-12, "{b:?} vs {exact}");
    assert!((b.sampled_min - exact).abs() < 1e-12, "{b:?} vs {exact}");
    let affine3 = |x: [f64; 3]| Some([x[0] + 0.2 * x[2], 0.5 * x[1], 2.0 * x[2] - 0.4 * x[0]]);
    let (map, _) = SplineMap::fit(uniform_space::<3>(1), affine3).unwrap();
    let exact = mean_ratio(&[[1.0, 0.0, 0.2], [0.0, 0.5, 0.0], [-0.4, 0.0, 2.0]]);
    let b = map.quality_bound(&QualityBoundOptions::default()).unwrap();
    assert!((b.lower_bound - exact).abs() < 1e-12, "{b:?} vs {exact}");
}

/// A curved planar map: a quarter annulus with a bulge.
fn bulged_annulus([u, v]: [f64; 2]) -> Option<[f64; 2]> {
    let (r, t) = (
        1.0 + u + 0.3 * u * (1.0 - u) * v,
        std::f64::consts::FRAC_PI_2 * v,
    );
    Some([r * t.cos(), r * t.sin()])
}

/// A curved solid: the bulged annulus extruded, with a twist of its height.
fn twisted_shell([u, v, w]: [f64; 3]) -> Option<[f64; 3]> {
    let [x, y] = bulged_annulus([u, v])?;
    Some([x + 0.1 * w * v, y, w * (1.0 + 0.3 * u * v)])
}

/// The bound of `map` under `options`, checked to lie below the smallest mean ratio at `n`
/// points per direction and element, which lies below the sampled minimum, and to be at least
/// `ratio` times the sampled minimum.
fn bracketed<const D: usize>(
    map: &SplineMap<D>,
    options: &QualityBoundOptions,
    n: usize,
    ratio: f64,
) -> QualityBound {
    let b = map.quality_bound(options).unwrap();
    let dense = dense_min(map, n);
    println!(
        "{D}D: {:.6} <= dense {dense:.6} <= sampled {:.6}",
        b.lower_bound, b.sampled_min
    );
    assert!(
        b.lower_bound <= dense && dense <= b.sampled_min,
        "{b:?}, dense {dense}"
    );
    assert!(
        b.lower_bound >= ratio * b.sampled_min,
        "a loose bound: {b:?}"
    );
    b
}

#[test]
fn the_bound_is_below_every_dense_value_and_near_the_sampled_minimum() {
    let (map, _) = SplineMap::fit(uniform_space::<2>(3), bulged_annulus).unwrap();
    let b = bracketed(&map, &QualityBoundOptions::default(), 33, 0.9);
    assert_eq!(b.elements.len(), map.element_count());
    assert_eq!(b.elements[b.element], b.lower_bound);
    // No subdivision: the bound of whole elements, lower.
    let coarse = QualityBoundOptions {
        max_depth: 0,
        ..Default::default()
    };
    let b0 = map.quality_bound(&coarse).unwrap();
    assert!(
        b0.lower_bound <= b.lower_bound && b0.lower_bound > 0.0,
        "{b0:?}"
    );

    let (map, _) = SplineMap::fit(uniform_space::<3>(1), twisted_shell).unwrap();
    let options = QualityBoundOptions {
        max_depth: 3,
        ..Default::default()
    };
    bracketed(&map, &options, 13, 0.8);
}

#[test]
fn the_bound_is_zero_where_det_j_touches_zero() {
    // det J = 3(y − 1/2)², zero along y = 1/2, positive elsewhere.
    let cusp = |x: [f64; 2]| Some([x[0], (x[1] - 0.5).powi(3)]);
    let (map, _) = SplineMap::fit(uniform_space::<2>(1), cusp).unwrap();
    let b = map.quality_bound(&QualityBoundOptions::default()).unwrap();
    assert_eq!(b.lower_bound, 0.0, "{b:?}");
}

#[test]
fn the_bound_does_not_depend_on_the_thread_count() {
    let (map, _) = SplineMap::fit(uniform_space::<2>(3), bulged_annulus).unwrap();
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| map.quality_bound(&QualityBoundOptions::default()).unwrap())
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one.lower_bound.to_bits(), two.lower_bound.to_bits());
    assert_eq!(one.elements, two.elements);
}

#[test]
fn bad_options_are_refused() {
    let (map, _) = SplineMap::fit(uniform_space::<2>(1), bulged_annulus).unwrap();
    for options in [
        QualityBoundOptions {
            max_depth: igaparam::spline::MAX_BOUND_DEPTH + 1,
            ..Default::default()
        },
        QualityBoundOptions {
            samples: 1,
            ..Default::default()
        },
        QualityBoundOptions {
            gap: 1.0,
            ..Default::default()
        },
        QualityBoundOptions {
            gap: f64::NAN,
            ..Default::default()
        },
    ] {
        let e = map.quality_bound(&options).unwrap_err();
        assert_eq!(e.kind, ErrorKind::InvalidArgument, "{options:?}");
    }
}
