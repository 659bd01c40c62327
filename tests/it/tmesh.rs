//! T-mesh properties: strong balance after every refinement, hanging vertices, and the optimizer
//! on T-meshes (the identity map is a fixed point; perturbed maps are repaired).

use crate::common;

use common::Lcg;
use igaparam::optimize::{invalid_cells, optimize, NodeSolverOptions, Problem, SweepOptions};
use igaparam::tmesh::{TMesh, Tree, UNIT};

fn random_tree<const D: usize>(refinements: usize, seed: u64) -> Tree<D> {
    let mut tree = Tree::<D>::new();
    tree.refine_uniformly(1).unwrap();
    let mut rng = Lcg(seed);
    for _ in 0..refinements {
        let point: [i64; D] =
            std::array::from_fn(|_| ((rng.next() + 1.0) * 0.5 * UNIT as f64) as i64);
        let leaf = tree.leaf_at(&point).unwrap();
        if tree.cells()[leaf].level < 6 {
            tree.refine(leaf).unwrap();
        }
        tree.balance().unwrap();
        assert!(tree.is_balanced());
    }
    tree
}

#[test]
fn balance_holds_after_every_refinement() {
    let t2 = random_tree::<2>(60, 3);
    assert!(t2.leaves().len() > 60);
    let t3 = random_tree::<3>(25, 5);
    assert!(t3.leaves().len() > 100);
}

#[test]
fn refining_one_cell_of_a_grid_adds_hanging_vertices() {
    let mut tree = Tree::<2>::new();
    tree.refine_uniformly(1).unwrap();
    let before = TMesh::new(tree.clone()).unwrap().vertex_count();
    assert_eq!(before, 9);
    let leaf = tree.leaf_at(&[0, 0]).unwrap();
    tree.refine(leaf).unwrap();
    let mesh = TMesh::new(tree).unwrap();
    assert_eq!(mesh.vertex_count(), 14);
    let hanging = (0..mesh.vertex_count())
        .filter(|&v| mesh.is_hanging(v))
        .count();
    assert_eq!(hanging, 2);
    // Cells next to the refined one see the hanging vertex as a real mid-edge node.
    let real_counts: Vec<usize> = (0..mesh.cell_count())
        .map(|c| mesh.cell_vertices(c).0.len())
        .collect();
    assert_eq!(real_counts.iter().filter(|&&n| n == 5).count(), 2);
    // In a hanging vertex's objective the coarse cell weighs 2, each of the two fine ones 1.
    let problem = mesh.problem().unwrap();
    let mut terms = Vec::new();
    for v in (0..mesh.vertex_count()).filter(|&v| mesh.is_hanging(v)) {
        let (weight_sum, _) = problem.node_terms(v, &mesh.parametric(), &mut terms);
        assert_eq!(weight_sum, 4.0);
    }
}

fn sweep_options() -> SweepOptions {
    SweepOptions {
        max_sweeps: 200,
        move_tolerance: 1e-6,
        node: NodeSolverOptions {
            gradient_tolerance: 1e-9,
            max_iterations: 50,
            relaxation: 1.0,
            power: 1.0,
        },
    }
}

/// The T-mesh of a tree, its optimization problem and a pool of two threads.
fn setup<const D: usize>(tree: Tree<D>) -> (TMesh<D>, Problem<D>, rayon::ThreadPool) {
    let mesh = TMesh::new(tree).unwrap();
    let problem = mesh.problem().unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    (mesh, problem, pool)
}

fn check_identity_is_fixed<const D: usize>(tree: Tree<D>) {
    let (mesh, problem, pool) = setup(tree);
    let mut x = mesh.parametric();
    let before = x.clone();
    optimize(&pool, &problem, &mut x, &sweep_options(), &mut |_, _| true).unwrap();
    let worst = x
        .iter()
        .zip(&before)
        .flat_map(|(a, b)| (0..D).map(move |k| (a[k] - b[k]).abs()))
        .fold(0.0, f64::max);
    assert!(worst < 1e-12, "identity moved by {worst}");
    assert!((0..problem.cell_count()).all(|c| (problem.cell_quality(c, &x) - 1.0).abs() < 1e-12));
}

#[test]
fn the_identity_is_a_fixed_point_of_t_meshes() {
    check_identity_is_fixed(random_tree::<2>(40, 11));
    check_identity_is_fixed(random_tree::<3>(12, 13));
}

#[test]
fn perturbed_t_meshes_are_repaired() {
    let (mesh, problem, pool) = setup(random_tree::<2>(40, 17));
    let mut x = mesh.parametric();
    let mut rng = Lcg(99);
    for (v, p) in x.iter_mut().enumerate() {
        if !mesh.on_boundary(v) {
            // Up to 45% of the smallest cell around the vertex.
            let smallest = (0..mesh.cell_count())
                .filter(|&c| mesh.cell_vertices(c).1.contains(&(v as u32)))
                .map(|c| {
                    let (lo, hi) = mesh.cell_bounds(c);
                    hi[0] - lo[0]
                })
                .fold(f64::INFINITY, f64::min);
            for c in p.iter_mut() {
                *c += 0.45 * smallest * rng.next();
            }
        }
    }
    assert!(
        !invalid_cells(&pool, &problem, &x).is_empty(),
        "the perturbation tangles nothing"
    );
    optimize(&pool, &problem, &mut x, &sweep_options(), &mut |_, _| true).unwrap();
    assert!(invalid_cells(&pool, &problem, &x).is_empty());
    let min = (0..problem.cell_count())
        .map(|c| problem.cell_quality(c, &x))
        .fold(1.0, f64::min);
    assert!(min > 0.9, "min quality {min}");
}
