//! The optimizer kernel shared by every path of the library: cells seen as quadratic Lagrange maps
//! (3^d nodes, some of them virtual), the regularised mean-ratio distortion integrated at the
//! 3-point Gauss–Lobatto points, one Newton solve per node, and coloured Gauss–Seidel sweeps.
//!
//! Written once for d = 2 and 3 through const generics.

pub mod affine;
mod aggregation;
pub mod amg;
pub mod block_rows;
pub mod blocks;
pub mod cg;
pub mod colour;
pub mod csr;
pub mod distortion;
pub mod exact;
pub mod global;
pub mod implicit;
pub mod laplace;
pub mod lattice;
pub mod metric;
pub mod motion;
pub mod node;
pub mod path;
pub mod pattern;
pub mod problem;
pub mod single;
pub mod small_matrix;
pub mod solver;
pub mod sparse;
mod spectrum;
pub mod stationary;
mod subtrees;
mod supernodal;
pub mod sweep;
pub mod team;

pub use node::NodeSolverOptions;
pub use pattern::CellPattern;
pub use problem::{CellSpec, Problem, TargetKind};
pub use sweep::{invalid_cells, optimize, QualitySummary, SweepOptions, SweepStats};
