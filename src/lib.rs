//! igaparam: spline parameterizations of 2D and 3D domains by T-mesh optimization, and relocation
//! of the nodes of high-order quad/hex meshes whose boundary moved.
//!
//! The safe Rust API lives here; the C ABI (`include/igaparam.h`) is in [`capi`].
#![deny(missing_docs)]

pub mod boundary;
pub mod capi;
mod diagnostics;
pub mod domain;
pub mod error;
pub mod fe_mesh;
pub mod io;
pub mod optimize;
pub mod partition;
pub mod sparse;
pub mod spline;
pub mod threads;
pub mod tmesh;

pub use error::{Error, ErrorKind, Result};
pub use fe_mesh::{
    CellType, Mesh, Method, NodeOrder, Placement, RelocateOptions, RelocateReport, Stage,
};
pub use optimize::TargetKind;
