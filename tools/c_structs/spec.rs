// The tables of the generator (included by `generate.rs`): the C structs generated and the core
// structs they mirror, the exceptions to the type rules, the enums held as integers, and the
// heads of the generated files. Adding a field to a core struct needs nothing here; a new C
// struct, a new enum, a C-only field or a C doc of its own does.

/// A C struct generated from a core struct.
struct Mirror {
    /// The C struct's name.
    c_name: &'static str,
    /// The core struct's name, its path in the crate and the file that defines it.
    core: &'static str,
    core_path: &'static str,
    source: &'static str,
    /// The C struct's own doc comment (the entry points it belongs to are C names).
    doc: &'static str,
    /// Fields of the C struct only, appended after the core's.
    c_only: &'static [CField],
    /// A report: converted from the core only.
    report: bool,
    /// Core fields C leaves out (the C options keep the core's defaults for them).
    skip: &'static [&'static str],
    /// Core fields holding a nested core struct whose fields the C struct holds in its place.
    flatten: &'static [Flatten],
}

/// A core field holding a nested core struct that its C struct flattens: the nested fields
/// take the place of the field, in the nested struct's order.
struct Flatten {
    /// The core field, and the nested struct's name, path and file.
    field: &'static str,
    core: &'static str,
    core_path: &'static str,
    source: &'static str,
    /// The nested fields C holds (the others keep the core's defaults): those named here, or,
    /// when this is empty, all but those of `skip`.
    only: &'static [&'static str],
    skip: &'static [&'static str],
    /// Nested fields whose C name is not theirs: (nested field, C name).
    renames: &'static [(&'static str, &'static str)],
}

/// A field of a C struct that the core struct does not have.
struct CField {
    name: &'static str,
    ty: &'static str,
    /// Its value in the mirror of core options.
    init: &'static str,
    doc: &'static str,
}

/// An enum of the core that a C struct holds as an integer with `IGAPARAM_*` constants.
struct CEnum {
    core: &'static str,
    core_path: &'static str,
    source: &'static str,
    /// The C type and the prefix of its constants.
    c_type: &'static str,
    prefix: &'static str,
    /// Variants whose constant is not their name in upper snake case.
    renames: &'static [(&'static str, &'static str)],
    /// The conversion from C: generated under this name, or `existing` when it is hand-written.
    from_c: &'static str,
    existing: bool,
    /// What a value is called in the error message.
    what: &'static str,
}

/// `usize` fields of the core declared `uint32_t` in C.
const U32_COUNTS: &[&str] = &["threads", "samples"];

/// C types other than the rule's: (C struct, field, type).
const TYPE_OVERRIDES: &[(&str, &str, &str)] = &[
    ("igaparam_domain_update_options", "refine", "i32"),
    ("igaparam_domain_update_report", "tolerance_met", "i32"),
    ("igaparam_fit_report", "least_squares", "i32"),
    ("igaparam_fit_report", "quasi_interpolation", "i32"),
    ("igaparam_validity_report", "certified_positive", "i32"),
];

/// The C constants of the core's array lengths: (core constant, C constant).
const ARRAY_LENGTHS: &[(&str, &str)] = &[("HISTOGRAM_BINS", "IGAPARAM_HISTOGRAM_BINS")];

/// C docs of their own, for the fields whose meaning in C is not the core's: (C struct, C
/// field, doc).
const DOC_OVERRIDES: &[(&str, &str, &str)] = &[
    // A C sentinel: `fit_options` in `capi/spline/fit_with.rs` replaces a negative value.
    (
        "igaparam_fit_options",
        "boundary_offset",
        "Largest move of a boundary control point by the untangling, relative to the bounding
box; negative (default) uses the `boundary_offset` the domain was built with, 0 keeps the
boundary.",
    ),
    // `DomainOptions::max_sweeps` is that of a build's stages.
    (
        "igaparam_adapt_options",
        "max_sweeps",
        "Largest number of optimization sweeps after each refinement (default 200).",
    ),
];

/// The progress callback's user pointer, the last field of the options with a callback.
const PROGRESS_USER: CField = CField {
    name: "progress_user",
    ty: "*mut c_void",
    init: "std::ptr::null_mut()",
    doc: "Passed to `progress` as its first argument.",
};

/// A progress callback field documented by `doc`.
const fn progress(doc: &'static str) -> CField {
    CField {
        name: "progress",
        ty: "igaparam_progress_fn",
        init: "None",
        doc,
    }
}

const MIRRORS: &[Mirror] = &[
    Mirror {
        c_name: "igaparam_domain_options",
        core: "DomainOptions",
        core_path: "crate::domain::DomainOptions",
        source: "src/domain/options.rs",
        doc: "Options of `igaparam_domain_build`; get the defaults from `igaparam_domain_options_default`\n(planar) or `igaparam_domain_options_default_solid`.",
        c_only: &[
            progress("Progress callback, or NULL (default). Called with `IGAPARAM_STAGE_OPTIMIZATION`, `done`\nsweeps so far and `total` 0, also between the rounds of the adaptation of the tree (with\n`done` 0); returning non-zero cancels the build."),
            PROGRESS_USER,
        ],
        report: false,
        skip: &[],
        flatten: &[],
    },
    Mirror {
        c_name: "igaparam_domain_update_options",
        core: "UpdateOptions",
        core_path: "crate::domain::UpdateOptions",
        source: "src/domain/update.rs",
        doc: "Options of `igaparam_domain_update`; get the defaults from\n`igaparam_domain_update_options_default`. The boundary tolerance, levels, repair rounds and\nboundary offset are those the domain was built with.",
        c_only: &[
            progress("Progress callback, or NULL (default). Called with `IGAPARAM_STAGE_OPTIMIZATION`, `done`\nsweeps so far and `total` 0; returning non-zero cancels the update."),
            PROGRESS_USER,
        ],
        report: false,
        skip: &[],
        flatten: &[],
    },
    Mirror {
        c_name: "igaparam_relocate_options",
        core: "RelocateOptions",
        core_path: "crate::fe_mesh::RelocateOptions",
        source: "src/fe_mesh/relocate.rs",
        doc: "Options of `igaparam_mesh_relocate`; get the defaults from `igaparam_relocate_options_default`.",
        c_only: &[progress("Progress callback, or NULL (default)."), PROGRESS_USER],
        report: false,
        skip: &[],
        flatten: &[],
    },
    Mirror {
        c_name: "igaparam_validity_options",
        core: "ValidityOptions",
        core_path: "crate::spline::ValidityOptions",
        source: "src/spline/validity.rs",
        doc: "Options of `igaparam_spline_check_validity`; get the defaults from\n`igaparam_validity_options_default`.",
        c_only: &[],
        report: false,
        skip: &[],
        flatten: &[],
    },
    Mirror {
        c_name: "igaparam_quality_bound_options",
        core: "QualityBoundOptions",
        core_path: "crate::spline::QualityBoundOptions",
        source: "src/spline/quality_bound.rs",
        doc: "Options of `igaparam_spline_quality_bound`; get the defaults from\n`igaparam_quality_bound_options_default`.",
        c_only: &[],
        report: false,
        skip: &[],
        flatten: &[],
    },
    Mirror {
        c_name: "igaparam_domain_report",
        core: "DomainReport",
        core_path: "crate::domain::DomainReport",
        source: "src/domain/options.rs",
        doc: "What `igaparam_domain_build` did. Quality is the inverse mean distortion of a cell against its\nparametric (square) cell: 1 is a square, 0 an inverted cell.",
        c_only: &[],
        report: true,
        skip: &["repair_rounds", "stages", "swapped"],
        flatten: &[],
    },
    Mirror {
        c_name: "igaparam_domain_update_report",
        core: "UpdateReport",
        core_path: "crate::domain::UpdateReport",
        source: "src/domain/update.rs",
        doc: "What `igaparam_domain_update` did.",
        c_only: &[],
        report: true,
        skip: &[],
        flatten: &[],
    },
    Mirror {
        c_name: "igaparam_relocate_report",
        core: "RelocateReport",
        core_path: "crate::fe_mesh::RelocateReport",
        source: "src/fe_mesh/relocate.rs",
        doc: "What `igaparam_mesh_relocate` did. Quality is the inverse mean distortion of a cell against its\ntarget over its Gauss–Lobatto points: 1 is the target shape, 0 an inverted cell.",
        c_only: &[],
        report: true,
        skip: &[],
        flatten: &[],
    },
    Mirror {
        c_name: "igaparam_quality_bound_report",
        core: "QualityBound",
        core_path: "crate::spline::QualityBound",
        source: "src/spline/quality_bound.rs",
        doc: "What `igaparam_spline_quality_bound` found: the true smallest mean ratio of the map lies in\n`[lower_bound, sampled_min]`.",
        c_only: &[],
        report: true,
        skip: &["elements"],
        flatten: &[],
    },
    Mirror {
        c_name: "igaparam_fit_options",
        core: "FitOptions",
        core_path: "crate::spline::FitOptions",
        source: "src/spline/fit_options.rs",
        doc: "Options of `igaparam_spline_fit_domain_with`; get the defaults (those of\n`igaparam_spline_fit_domain`) from `igaparam_fit_options_default`.",
        c_only: &[
            progress("Progress callback, or NULL (default): called on the calling thread with\n`IGAPARAM_STAGE_FIT` (`done` of `total` fits and certifications),\n`IGAPARAM_STAGE_UNTANGLING` (rounds) and `IGAPARAM_STAGE_SMOOTHING` (sweeps); returning\nnon-zero cancels (`IGAPARAM_STATUS_CANCELLED`, nothing written)."),
            PROGRESS_USER,
        ],
        report: false,
        skip: &[],
        flatten: &[Flatten {
            field: "untangle",
            core: "UntangleOptions",
            core_path: "crate::spline::UntangleOptions",
            source: "src/spline/untangle.rs",
            only: &[],
            skip: &["samples", "rings"],
            renames: &[("rounds", "untangle_rounds"), ("sweeps", "untangle_sweeps")],
        }],
    },
    Mirror {
        c_name: "igaparam_adapt_options",
        core: "AdaptOptions",
        core_path: "crate::spline::AdaptOptions",
        source: "src/spline/adapt.rs",
        doc: "Options of `igaparam_domain_fit_adaptive`; get the defaults from\n`igaparam_adapt_options_default`.",
        c_only: &[
            progress("Progress callback, or NULL (default). Called with `IGAPARAM_STAGE_ADAPTATION`, `done`\nrounds and `total` = `max_rounds` before each refinement; returning non-zero cancels."),
            PROGRESS_USER,
        ],
        report: false,
        // The certification is the default one, that `igaparam_spline_check_validity` keeps.
        skip: &["validity"],
        flatten: &[Flatten {
            field: "domain",
            core: "DomainOptions",
            core_path: "crate::domain::DomainOptions",
            source: "src/domain/options.rs",
            // The loop uses these two; the others are those the domain was built with.
            only: &["max_sweeps", "threads"],
            skip: &[],
            renames: &[],
        }],
    },
    Mirror {
        c_name: "igaparam_fit_report",
        core: "FitReport",
        core_path: "crate::spline::FitReport",
        source: "src/spline/fit.rs",
        doc: "What a fit (`igaparam_spline_fit_domain`, `igaparam_spline_refine`) did.",
        c_only: &[],
        report: true,
        skip: &["reciprocal_condition", "stages"],
        flatten: &[],
    },
    Mirror {
        c_name: "igaparam_validity_report",
        core: "ValidityReport",
        core_path: "crate::spline::ValidityReport",
        source: "src/spline/validity.rs",
        doc: "Certified validity and quality of a spline map.",
        c_only: &[],
        report: true,
        // Given by `igaparam_spline_check_validity` in arrays of the caller's.
        skip: &["elements"],
        flatten: &[],
    },
    Mirror {
        c_name: "igaparam_partition_report",
        core: "PartitionReport",
        core_path: "crate::partition::PartitionReport",
        source: "src/partition/relocate.rs",
        doc: "What `igaparam_partition_relocate` did.",
        c_only: &[],
        report: true,
        skip: &[],
        flatten: &[],
    },
];

const ENUMS: &[CEnum] = &[
    CEnum {
        core: "TargetKind",
        core_path: "crate::optimize::TargetKind",
        source: "src/optimize/problem.rs",
        c_type: "igaparam_target",
        prefix: "IGAPARAM_TARGET_",
        renames: &[("Reference", "INITIAL")],
        // Hand-written in `capi/mesh.rs`, which the mesh's entry points share.
        from_c: "target",
        existing: true,
        what: "target",
    },
    CEnum {
        core: "Placement",
        core_path: "crate::fe_mesh::Placement",
        source: "src/fe_mesh/relocate.rs",
        c_type: "igaparam_placement",
        prefix: "IGAPARAM_PLACEMENT_",
        renames: &[],
        from_c: "placement",
        existing: false,
        what: "placement",
    },
    CEnum {
        core: "Method",
        core_path: "crate::fe_mesh::Method",
        source: "src/fe_mesh/relocate.rs",
        c_type: "igaparam_method",
        prefix: "IGAPARAM_METHOD_",
        renames: &[],
        from_c: "method",
        existing: false,
        what: "method",
    },
    CEnum {
        core: "FitChoice",
        core_path: "crate::spline::FitChoice",
        source: "src/spline/fit_options.rs",
        c_type: "igaparam_fit_choice",
        prefix: "IGAPARAM_FIT_CHOICE_",
        renames: &[],
        from_c: "fit_choice",
        existing: false,
        what: "choice",
    },
];

/// What both generated files say first.
const GENERATED: &str =
    "//! GENERATED by `tools/c_structs/generate.rs` from the core structs: do not edit. Change
//! the core struct (its fields and their doc comments) and run
//! `IGAPARAM_BLESS=1 cargo test --release --test c_structs` (or, when this file no longer
//! compiles, `cargo run --release --manifest-path tools/c_structs/Cargo.toml`), then bless the
//! header (`IGAPARAM_BLESS=1 cargo test --release --test header`).
//!
";

/// The rest of the head of `options_gen.rs`.
const OPTIONS_HEAD: &str = "//! The C mirrors of the core options: `#[repr(C)]` structs whose field docs are the core's, the
//! mirror of core options (`From`), the core options of a mirror (`to_core`, a conversion only:
//! the core's `validate` checks the values) and the conversions of the enums they hold.
// The docs are the header's comments, plain text: an interval such as `[1, 2)` is no link.
#![allow(rustdoc::broken_intra_doc_links)]

use std::ffi::{c_int, c_void};

use super::mesh::{igaparam_target, target, IGAPARAM_TARGET_INITIAL, IGAPARAM_TARGET_MASTER};
use super::option_enums::*;
use super::progress::igaparam_progress_fn;
use crate::error::Result;
";

/// The rest of the head of `reports_gen.rs`.
const REPORTS_HEAD: &str = "//! The C mirrors of the core reports: `#[repr(C)]` structs whose field docs are the core's, and
//! the mirror of a core report (`From`).
// The docs are the header's comments, plain text: an interval such as `[1, 2)` is no link.
#![allow(rustdoc::broken_intra_doc_links)]

use std::ffi::c_int;

use super::option_enums::IGAPARAM_HISTOGRAM_BINS;
";
