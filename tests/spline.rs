//! THB-spline spaces over balanced trees: basis properties, interpolation, refinement,
//! certification and output.

mod common;

use common::Lcg;
use igaparam::spline::{SplineMap, SplineSpace, ThbSpace};
use igaparam::tmesh::{Tree, UNIT};

/// A balanced tree refined `steps` times at random leaves (at most `max_level` deep).
fn random_tree<const D: usize>(seed: u64, steps: usize, max_level: u8) -> Tree<D> {
    let mut rng = Lcg(seed);
    let mut tree = Tree::<D>::new();
    tree.refine_uniformly(1).unwrap();
    for _ in 0..steps {
        let p: [i64; D] = std::array::from_fn(|_| ((rng.next() + 1.0) * 0.5 * UNIT as f64) as i64);
        let leaf = tree.leaf_at(&p).unwrap();
        if tree.cells()[leaf].level < max_level {
            tree.refine(leaf).unwrap();
        }
        tree.balance().unwrap();
    }
    tree
}

/// A few points of [0,1]^d, corners and faces included.
fn probe_points<const D: usize>(seed: u64, count: usize) -> Vec<[f64; D]> {
    let mut rng = Lcg(seed);
    let mut out: Vec<[f64; D]> = (0..count)
        .map(|_| std::array::from_fn(|_| (rng.next() + 1.0) * 0.5))
        .collect();
    out.push([0.0; D]);
    out.push([1.0; D]);
    out.push(std::array::from_fn(|k| if k == 0 { 1.0 } else { 0.3 }));
    out
}

fn cubic<const D: usize>(x: [f64; D]) -> [f64; D] {
    std::array::from_fn(|a| {
        let mut v = 0.3 * a as f64 + x[a];
        for b in 0..D {
            v += 0.2 * x[b].powi(3) * (a + b + 1) as f64 - 0.4 * x[b] * x[(b + 1) % D] * x[a];
        }
        v
    })
}

fn reproduces_cubics<const D: usize>(seeds: &[u64], steps: usize, max_level: u8) {
    for &seed in seeds {
        let space = ThbSpace::new(random_tree::<D>(seed, steps, max_level)).unwrap();
        let (map, report) = SplineMap::fit(space, |x| Some(cubic(x))).unwrap();
        println!("d = {D}, seed {seed}: {report:?}");
        assert!(report.residual < 1e-11, "{report:?}");
        for x in probe_points::<D>(seed + 1, 200) {
            let (y, _) = map.eval_with_jacobian(x).unwrap();
            let e = cubic(x);
            for k in 0..D {
                assert!((y[k] - e[k]).abs() < 1e-11, "{x:?}: {y:?} vs {e:?}");
            }
        }
    }
}

#[test]
fn cubic_maps_are_reproduced_on_random_balanced_trees() {
    reproduces_cubics::<2>(&[1, 2, 3, 4], 30, 6);
    reproduces_cubics::<3>(&[5, 6], 8, 4);
}

fn basis_properties<const D: usize>(seed: u64, steps: usize, max_level: u8) {
    let space = ThbSpace::new(random_tree::<D>(seed, steps, max_level)).unwrap();
    for x in probe_points::<D>(seed, 300) {
        let b = space.basis_at(x).unwrap();
        let sum: f64 = b.values.iter().sum();
        assert!((sum - 1.0).abs() < 1e-13, "partition of unity at {x:?}: {sum}");
        assert!(b.values.iter().all(|&v| v >= -1e-15), "negative value at {x:?}");
        for g in 0..D {
            let s: f64 = b.gradients.iter().map(|d| d[g]).sum();
            assert!(s.abs() < 1e-10, "gradients sum to {s}");
        }
    }
    // Linear independence: the Greville collocation matrix is non-singular.
    let (_, report) = SplineMap::fit(space.clone(), |x| Some(x)).unwrap();
    assert!(report.residual < 1e-12);
    // Nested spaces: the map of a coarse space is reproduced by the refined one.
    let (coarse, _) = SplineMap::fit(space, |x| {
        Some(std::array::from_fn(|k| (3.0 * x[k]).sin() + x[(k + 1) % D].powi(2)))
    })
    .unwrap();
    let marked: Vec<usize> = (0..coarse.element_count()).step_by(3).collect();
    let (fine, _) = coarse.refine(&marked).unwrap();
    assert!(fine.basis_count() > coarse.basis_count());
    assert!(fine.space().tree().is_balanced());
    for x in probe_points::<D>(seed + 7, 200) {
        let (a, b) = (coarse.eval(x).unwrap(), fine.eval(x).unwrap());
        for k in 0..D {
            assert!((a[k] - b[k]).abs() < 1e-12, "{x:?}: {a:?} vs {b:?}");
        }
    }
}

#[test]
fn thb_basis_is_a_non_negative_partition_of_unity_linearly_independent_and_nested() {
    for seed in [11, 12, 13] {
        basis_properties::<2>(seed, 25, 6);
    }
    basis_properties::<3>(14, 6, 4);
}
