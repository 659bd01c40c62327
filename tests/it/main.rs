//! The integration tests, one binary: each module is the suite of one part of the library
//! (`cargo test --release --test it MODULE::` runs one). A single binary links the library once
//! rather than once per suite, and its tests share the cores as one pool.

#[path = "../common/mod.rs"]
mod common;
#[path = "../common/morph.rs"]
mod morph_cases;

mod boundary;
mod boundary_distance;
mod boundary_image;
mod boundary_sensitivity;
mod c_api;
mod determinism;
mod domain;
mod fit_options;
mod gismo_xml;
mod limits;
mod morph;
mod partition;
mod peers;
mod quality_bound;
mod quality_bound_domains;
mod relocate;
mod scale;
mod sensitivity;
mod solid;
mod spline;
mod spline_adapt;
mod spline_domains;
mod structure;
mod tmesh;
mod wing;
