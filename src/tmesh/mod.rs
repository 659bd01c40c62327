//! Hierarchical T-meshes of \[0,1\]^d: a strongly 2:1 balanced quadtree/octree, its vertices with
//! hanging ones, and the quadratic cell maps the optimizer sees (corners and hanging vertices are
//! real nodes, the other lattice points virtual).

mod mesh;
mod tree;

pub use mesh::TMesh;
pub use tree::{Cell, Tree, MAX_LEVEL, UNIT};
