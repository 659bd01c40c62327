//! The generator of `src/capi/options_gen.rs` and `src/capi/reports_gen.rs`, the C mirrors of
//! the core option and report structs: their fields (names, types, order), their doc comments
//! and the conversions, read from the core structs' sources with `syn`. It depends on `syn`
//! only, not on the crate, so that it runs when a changed core struct has made the checked-in
//! mirrors fail to compile (`tools/c_structs/main.rs`); `tests/c_structs.rs` checks the
//! checked-in files with it.
//!
//! The rules, so that the C layout of the existing structs is what it was:
//! - `f64` and `u32` stay; `u8` (a level) becomes `uint32_t`, saturating to 255 on the way in
//!   (the core's range check then refuses it);
//! - `usize` stays `size_t`, except the counts named in [`U32_COUNTS`], which are `uint32_t`;
//! - `bool` becomes `int` (non-zero is true), or the type [`TYPE_OVERRIDES`] names;
//! - an enum of [`ENUMS`] becomes its C integer type, checked on the way in (an error names the
//!   `IGAPARAM_*` values allowed), and its field's C doc ends with the values and the default;
//! - a struct that has a mirror itself becomes that mirror;
//! - an array whose length is a constant of [`ARRAY_LENGTHS`] stays an array, of that length's C
//!   constant;
//! - a field of [`Mirror::flatten`] is replaced by the fields of its nested struct (the fields
//!   named there, under their C names), each by these rules; the C options' `to_core` gathers
//!   them again, the nested fields C does not hold keeping the core's defaults;
//! - anything else fails here, naming the field.
//!
//! The C-only fields (the progress callback and its user pointer) are appended from
//! [`Mirror::c_only`]; a C struct leaves out the core fields of [`Mirror::skip`] (C options keep
//! the core's defaults for them); a report is only converted from the core. A field's C doc is
//! its core doc, unless [`DOC_OVERRIDES`] gives one (a field whose meaning in C is not the
//! core's, as a C sentinel value). Rustdoc links of the core docs become plain names, the names cbindgen
//! renames (`cbindgen.toml`, `[export.rename]`) take their C names, and each paragraph is
//! filled again to the width of the file (so write the core docs as prose paragraphs). Plain
//! `//` comments of the core fields stay in the core. The tables (which structs, which enums,
//! the type rules' exceptions) are in `spec.rs`.

use std::collections::HashMap;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;
use std::process::{Command, Stdio};

// What is generated: the structs, their rules, the enums and the heads of the files.
include!("spec.rs");

/// A field of a core struct, or of a nested core struct that its C struct flattens.
struct Field {
    /// Its name in C: the core's, or the flattening's rename.
    name: String,
    /// Its path from the core struct: its name, or `nested.name` for a flattened field.
    path: String,
    /// The last segment of its type's path (of the element type of an array).
    ty: String,
    /// The length of an array, `[ty; len]`: the name of a constant.
    len: Option<String>,
    doc: Vec<String>,
    /// The flattening it comes from.
    nested: Option<&'static Flatten>,
}

fn parse(root: &Path, source: &str) -> syn::File {
    let text =
        std::fs::read_to_string(root.join(source)).unwrap_or_else(|e| panic!("{source}: {e}"));
    syn::parse_file(&text).unwrap_or_else(|e| panic!("{source}: {e}"))
}

/// The lines of the `///` comments among `attrs`, one leading space removed.
fn doc_lines(attrs: &[syn::Attribute]) -> Vec<String> {
    attrs
        .iter()
        .filter(|a| a.path().is_ident("doc"))
        .filter_map(|a| match &a.meta {
            syn::Meta::NameValue(syn::MetaNameValue {
                value:
                    syn::Expr::Lit(syn::ExprLit {
                        lit: syn::Lit::Str(s),
                        ..
                    }),
                ..
            }) => Some(s.value()),
            _ => None,
        })
        .flat_map(|s| {
            s.lines()
                .map(|l| l.strip_prefix(' ').unwrap_or(l).to_string())
                .collect::<Vec<_>>()
        })
        .collect()
}

fn last_ident(ty: &syn::Type) -> String {
    match ty {
        syn::Type::Path(p) => p.path.segments.last().unwrap().ident.to_string(),
        syn::Type::Array(a) => last_ident(&a.elem),
        _ => String::new(),
    }
}

/// The length of an array type whose length is a constant.
fn array_len(ty: &syn::Type) -> Option<String> {
    match ty {
        syn::Type::Array(syn::TypeArray {
            len: syn::Expr::Path(p),
            ..
        }) => Some(p.path.segments.last().unwrap().ident.to_string()),
        _ => None,
    }
}

fn core_struct(file: &syn::File, name: &str) -> Vec<Field> {
    let found = file.items.iter().find_map(|item| match item {
        syn::Item::Struct(s) if s.ident == name => Some(s),
        _ => None,
    });
    let s = found.unwrap_or_else(|| panic!("no struct {name}"));
    s.fields
        .iter()
        .filter(|f| matches!(f.vis, syn::Visibility::Public(_)))
        .map(|f| {
            let name = f.ident.as_ref().unwrap().to_string();
            Field {
                path: name.clone(),
                name,
                ty: last_ident(&f.ty),
                len: array_len(&f.ty),
                doc: doc_lines(&f.attrs),
                nested: None,
            }
        })
        .collect()
}

/// The variants of enum `name`, and the one marked `#[default]` if any.
fn core_enum(file: &syn::File, name: &str) -> (Vec<String>, Option<String>) {
    let found = file.items.iter().find_map(|item| match item {
        syn::Item::Enum(e) if e.ident == name => Some(e),
        _ => None,
    });
    let e = found.unwrap_or_else(|| panic!("no enum {name}"));
    let variants = e.variants.iter().map(|v| v.ident.to_string()).collect();
    let default = e
        .variants
        .iter()
        .find(|v| v.attrs.iter().any(|a| a.path().is_ident("default")))
        .map(|v| v.ident.to_string());
    (variants, default)
}

/// The fields of `Default::default()` of struct `name` that are paths `Enum::Variant`.
fn default_variants(file: &syn::File, name: &str) -> HashMap<String, String> {
    let mut out = HashMap::new();
    for item in &file.items {
        let syn::Item::Impl(i) = item else { continue };
        let is_default = i
            .trait_
            .as_ref()
            .is_some_and(|(_, p, _)| p.is_ident("Default"));
        if !is_default || last_ident(&i.self_ty) != name {
            continue;
        }
        for impl_item in &i.items {
            let syn::ImplItem::Fn(f) = impl_item else {
                continue;
            };
            let Some(syn::Stmt::Expr(syn::Expr::Struct(s), _)) = f.block.stmts.last() else {
                continue;
            };
            for field in &s.fields {
                let (syn::Member::Named(member), syn::Expr::Path(p)) = (&field.member, &field.expr)
                else {
                    continue;
                };
                if p.path.segments.len() == 2 {
                    out.insert(member.to_string(), p.path.segments[1].ident.to_string());
                }
            }
        }
    }
    out
}

/// `QuasiInterpolation` → `QUASI_INTERPOLATION`.
fn upper_snake(name: &str) -> String {
    let mut out = String::new();
    for (i, c) in name.chars().enumerate() {
        if c.is_uppercase() && i > 0 {
            out.push('_');
        }
        out.push(c.to_ascii_uppercase());
    }
    out
}

/// The names cbindgen gives the crate's constants (`[export.rename]` of `cbindgen.toml`).
fn renames(root: &Path) -> Vec<(String, String)> {
    let text = std::fs::read_to_string(root.join("cbindgen.toml")).unwrap();
    let section = text.split("[export.rename]").nth(1).unwrap_or("");
    section
        .lines()
        .take_while(|l| !l.starts_with('['))
        .filter_map(|l| l.split_once('='))
        .map(|(a, b)| {
            (
                a.trim().trim_matches('"').to_string(),
                b.trim().trim_matches('"').to_string(),
            )
        })
        .collect()
}

/// A doc line as C reads it: rustdoc links become their text, renamed constants their C names.
fn plain(line: &str, renames: &[(String, String)]) -> String {
    let mut out = String::new();
    let mut rest = line;
    while let Some(start) = rest.find("[`") {
        let Some(end) = rest[start..].find("`]").map(|e| start + e) else {
            break;
        };
        out.push_str(&rest[..start]);
        out.push_str(&rest[start + 1..end + 1]);
        rest = &rest[end + 2..];
        if rest.starts_with('(') {
            rest = &rest[rest.find(')').map_or(0, |e| e + 1)..];
        }
    }
    out.push_str(rest);
    for (rust, c) in renames {
        out = out.replace(&format!("`{rust}`"), &format!("`{c}`"));
    }
    out
}

/// The paragraphs of `lines` (separated by empty lines) filled again to 92 characters, the
/// width of a field's doc comment within 100 columns: a link made plain changes the length of
/// its line.
fn reflow(lines: &[String]) -> Vec<String> {
    let text = lines.join("\n");
    let paragraphs: Vec<Vec<String>> = text
        .split("\n\n")
        .map(|p| wrap(&p.split_whitespace().collect::<Vec<_>>().join(" ")))
        .collect();
    paragraphs.join(&String::new())
}

/// `text` in lines of at most 92 characters (a field's doc comment within 100 columns).
fn wrap(text: &str) -> Vec<String> {
    let mut lines = vec![String::new()];
    for word in text.split(' ') {
        let line = lines.last_mut().unwrap();
        if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > 92 {
            lines.push(word.to_string());
        } else {
            if !line.is_empty() {
                line.push(' ');
            }
            line.push_str(word);
        }
    }
    lines
}

fn doc_comment(out: &mut String, lines: &[String]) {
    for line in lines {
        match line.is_empty() {
            true => out.push_str("///\n"),
            false => writeln!(out, "/// {line}").unwrap(),
        }
    }
}

/// How one core field is held in C: its type and the two conversions (`o` is the core struct,
/// `self` the C one), and what its C doc adds.
struct Conversion {
    c_type: String,
    to_c: String,
    to_core: String,
    doc_tail: Option<String>,
}

fn conversion(g: &Generator, mirror: &Mirror, field: &Field) -> Conversion {
    let (f, p) = (&field.name, &field.path);
    let plain = |c_type: &str, to_c: String, to_core: String| Conversion {
        c_type: c_type.into(),
        to_c,
        to_core,
        doc_tail: None,
    };
    let overridden = TYPE_OVERRIDES
        .iter()
        .find(|(s, n, _)| *s == mirror.c_name && n == f)
        .map(|(_, _, t)| *t);
    if let Some(len) = &field.len {
        let c_len = ARRAY_LENGTHS.iter().find(|(core, _)| core == len);
        return match (field.ty.as_str(), c_len) {
            ("f64" | "u32" | "usize", Some((_, c_len))) => plain(
                &format!("[{}; {c_len}]", field.ty),
                format!("o.{p}"),
                format!("self.{f}"),
            ),
            _ => panic!(
                "{}.{p}: no C form of an array of `{}` of length `{len}` (see ARRAY_LENGTHS)",
                mirror.core, field.ty
            ),
        };
    }
    match field.ty.as_str() {
        "f64" | "u32" => plain(&field.ty, format!("o.{p}"), format!("self.{f}")),
        "u8" => plain(
            "u32",
            format!("u32::from(o.{p})"),
            format!("u8::try_from(self.{f}).unwrap_or(u8::MAX)"),
        ),
        "usize" if U32_COUNTS.contains(&f.as_str()) => plain(
            "u32",
            format!("u32::try_from(o.{p}).unwrap_or(u32::MAX)"),
            format!("self.{f} as usize"),
        ),
        "usize" => plain("usize", format!("o.{p}"), format!("self.{f}")),
        "bool" => {
            let ty = overridden.unwrap_or("c_int");
            plain(ty, format!("{ty}::from(o.{p})"), format!("self.{f} != 0"))
        }
        ty => {
            if let Some(e) = ENUMS.iter().find(|e| e.core == ty) {
                let default = g.enum_default(mirror, e, p);
                return Conversion {
                    c_type: e.c_type.into(),
                    to_c: format!("c_{}(o.{p})", e.from_c),
                    to_core: format!("{}(self.{f})?", e.from_c),
                    doc_tail: Some(g.values_sentence(e, default.as_deref())),
                };
            }
            if let Some(m) = MIRRORS.iter().find(|m| m.core == ty) {
                return plain(
                    m.c_name,
                    format!("{}::from(&o.{p})", m.c_name),
                    format!("self.{f}.to_core()?"),
                );
            }
            panic!(
                "{}.{p}: no C form of type `{ty}` (see the rules of tests/c_structs.rs)",
                mirror.core
            )
        }
    }
}

/// The core sources the tables name.
fn sources() -> impl Iterator<Item = &'static str> {
    let nested = MIRRORS
        .iter()
        .flat_map(|m| m.flatten.iter().map(|n| n.source));
    MIRRORS
        .iter()
        .map(|m| m.source)
        .chain(nested)
        .chain(ENUMS.iter().map(|e| e.source))
}

/// Panics unless every name of `names` is a field of core struct `core` (`fields`).
fn check_names<'a>(core: &str, fields: &[Field], names: impl Iterator<Item = &'a &'static str>) {
    for name in names {
        assert!(
            fields.iter().any(|f| f.name == *name),
            "{core}.{name}: no such field (see the tables of spec.rs)"
        );
    }
}

/// What the generator has read: the parsed sources and cbindgen's renames.
struct Generator {
    files: HashMap<&'static str, syn::File>,
    renames: Vec<(String, String)>,
}

impl Generator {
    fn read(root: &Path) -> Generator {
        Generator {
            files: sources().map(|s| (s, parse(root, s))).collect(),
            renames: renames(root),
        }
    }

    fn constant(&self, e: &CEnum, variant: &str) -> String {
        let name = e
            .renames
            .iter()
            .find(|(v, _)| *v == variant)
            .map_or_else(|| upper_snake(variant), |(_, c)| c.to_string());
        format!("{}{name}", e.prefix)
    }

    /// The default of enum field `field` of a mirror's core: that of the core's `Default`, else
    /// the enum's `#[default]` variant.
    fn enum_default(&self, mirror: &Mirror, e: &CEnum, field: &str) -> Option<String> {
        let file = &self.files[mirror.source];
        default_variants(file, mirror.core)
            .remove(field)
            .or_else(|| core_enum(&self.files[e.source], e.core).1)
    }

    /// "One of `A` (default), `B` or `C`."
    fn values_sentence(&self, e: &CEnum, default: Option<&str>) -> String {
        let (variants, _) = core_enum(&self.files[e.source], e.core);
        let names: Vec<String> = variants
            .iter()
            .map(|v| {
                let mark = if Some(v.as_str()) == default {
                    " (default)"
                } else {
                    ""
                };
                format!("`{}`{mark}", self.constant(e, v))
            })
            .collect();
        match names.split_last() {
            Some((last, [only])) => format!("Either {only} or {last}."),
            Some((last, first)) => format!("One of {} or {last}.", first.join(", ")),
            None => panic!("enum {} has no variant", e.core),
        }
    }

    /// The fields of mirror `m` in C order: the core's but those of [`Mirror::skip`], the
    /// fields of a nested struct of [`Mirror::flatten`] in its place.
    fn fields(&self, m: &Mirror) -> Vec<Field> {
        let core = core_struct(&self.files[m.source], m.core);
        let names = m.skip.iter().chain(m.flatten.iter().map(|n| &n.field));
        check_names(m.core, &core, names);
        let mut out = Vec::new();
        for field in core {
            if m.skip.contains(&field.name.as_str()) {
                continue;
            }
            match m.flatten.iter().find(|n| n.field == field.name) {
                Some(n) => out.extend(self.flattened(n)),
                None => out.push(field),
            }
        }
        out
    }

    /// The fields of the nested struct of `n` that its C struct holds, under their C names.
    fn flattened(&self, n: &'static Flatten) -> Vec<Field> {
        let nested = core_struct(&self.files[n.source], n.core);
        let names = n
            .only
            .iter()
            .chain(n.skip)
            .chain(n.renames.iter().map(|(a, _)| a));
        check_names(n.core, &nested, names);
        let held = |f: &Field| {
            (n.only.is_empty() || n.only.contains(&f.name.as_str()))
                && !n.skip.contains(&f.name.as_str())
        };
        nested
            .into_iter()
            .filter(held)
            .map(|mut f| {
                f.path = format!("{}.{}", n.field, f.name);
                if let Some((_, c)) = n.renames.iter().find(|(core, _)| *core == f.name) {
                    f.name = c.to_string();
                }
                f.nested = Some(n);
                f
            })
            .collect()
    }

    /// The C doc of field `f` of mirror `m`: that of [`DOC_OVERRIDES`], else the core's made
    /// plain, with what its conversion adds.
    fn field_doc(&self, m: &Mirror, f: &Field, c: &Conversion) -> Vec<String> {
        let overridden = DOC_OVERRIDES
            .iter()
            .find(|(s, n, _)| *s == m.c_name && *n == f.name);
        let mut text: Vec<String> = match overridden {
            Some((_, _, doc)) => doc.lines().map(String::from).collect(),
            None => f.doc.iter().map(|l| plain(l, &self.renames)).collect(),
        };
        text.extend(c.doc_tail.clone());
        reflow(&text)
    }

    fn mirror(&self, out: &mut String, m: &Mirror) {
        let fields = self.fields(m);
        let conversions: Vec<Conversion> = fields.iter().map(|f| conversion(self, m, f)).collect();
        doc_comment(out, &m.doc.lines().map(String::from).collect::<Vec<_>>());
        writeln!(
            out,
            "#[repr(C)]\n#[derive(Clone, Copy, Debug{})]\npub struct {} {{",
            if m.report { ", Default" } else { "" },
            m.c_name
        )
        .unwrap();
        for (f, c) in fields.iter().zip(&conversions) {
            doc_comment(out, &self.field_doc(m, f, c));
            writeln!(out, "pub {}: {},", f.name, c.c_type).unwrap();
        }
        for f in m.c_only {
            doc_comment(out, &f.doc.lines().map(String::from).collect::<Vec<_>>());
            writeln!(out, "pub {}: {},", f.name, f.ty).unwrap();
        }
        out.push_str("}\n\n");
        writeln!(
            out,
            "impl From<&{0}> for {1} {{\nfn from(o: &{0}) -> Self {{\n{1} {{",
            m.core_path, m.c_name
        )
        .unwrap();
        for (f, c) in fields.iter().zip(&conversions) {
            writeln!(out, "{}: {},", f.name, c.to_c).unwrap();
        }
        for f in m.c_only {
            writeln!(out, "{}: {},", f.name, f.init).unwrap();
        }
        out.push_str("}\n}\n}\n\n");
        if !m.report {
            self.to_core(out, m, &fields, &conversions);
        }
    }

    /// The `to_core` of the C options of `m`: the fields of a flattened struct are gathered
    /// into it again, and the fields C does not hold keep the core's defaults.
    fn to_core(&self, out: &mut String, m: &Mirror, fields: &[Field], conversions: &[Conversion]) {
        writeln!(out, "impl {} {{", m.c_name).unwrap();
        out.push_str("/// The core options of these C options: a conversion (an enum's value is checked; the\n/// core's `validate` checks the others).\n");
        writeln!(
            out,
            "pub(crate) fn to_core(self) -> Result<{0}> {{\nOk({0} {{",
            m.core_path
        )
        .unwrap();
        let pairs: Vec<(&Field, &Conversion)> = fields.iter().zip(conversions).collect();
        for (i, (f, c)) in pairs.iter().enumerate() {
            let Some(n) = f.nested else {
                writeln!(out, "{}: {},", f.name, c.to_core).unwrap();
                continue;
            };
            let in_n = |f: &Field| f.nested.is_some_and(|x| x.field == n.field);
            if i > 0 && in_n(pairs[i - 1].0) {
                continue;
            }
            writeln!(out, "{}: {} {{", n.field, n.core_path).unwrap();
            let group: Vec<_> = pairs[i..].iter().take_while(|(f, _)| in_n(f)).collect();
            for (g, d) in &group {
                writeln!(out, "{}: {},", &g.path[n.field.len() + 1..], d.to_core).unwrap();
            }
            if group.len() < core_struct(&self.files[n.source], n.core).len() {
                writeln!(out, "..{}::default().{}", m.core_path, n.field).unwrap();
            }
            out.push_str("},\n");
        }
        if !m.skip.is_empty() {
            writeln!(out, "..{}::default()", m.core_path).unwrap();
        }
        out.push_str("})\n}\n}\n\n");
    }

    fn conversions(&self, out: &mut String, e: &CEnum) {
        let (variants, _) = core_enum(&self.files[e.source], e.core);
        let constants: Vec<String> = variants.iter().map(|v| self.constant(e, v)).collect();
        writeln!(out, "/// The `{}*` value of `value`.", e.prefix).unwrap();
        writeln!(
            out,
            "pub(crate) fn c_{}(value: {}) -> {} {{\nmatch value {{",
            e.from_c, e.core_path, e.c_type
        )
        .unwrap();
        for (v, c) in variants.iter().zip(&constants) {
            writeln!(out, "{}::{v} => {c},", e.core_path).unwrap();
        }
        out.push_str("}\n}\n\n");
        if e.existing {
            return;
        }
        let allowed: Vec<String> = constants
            .iter()
            .map(|c| format!("(\"{c}\", {c})"))
            .collect();
        writeln!(
            out,
            "/// The {} of C value `code`; an error names the values allowed.",
            e.what
        )
        .unwrap();
        writeln!(
            out,
            "pub(crate) fn {}(code: {}) -> Result<{}> {{\nmatch code {{",
            e.from_c, e.c_type, e.core_path
        )
        .unwrap();
        for (v, c) in variants.iter().zip(&constants) {
            writeln!(out, "{c} => Ok({}::{v}),", e.core_path).unwrap();
        }
        writeln!(
            out,
            "_ => Err(not_one_of(\"{}\", code, &[{}])),",
            e.what,
            allowed.join(", ")
        )
        .unwrap();
        out.push_str("}\n}\n\n");
    }

    /// The generated files: the options with the enums' conversions, and the reports.
    fn generate(&self) -> [(&'static str, String); 2] {
        let mut options = format!("{GENERATED}{OPTIONS_HEAD}\n");
        let mut reports = format!("{GENERATED}{REPORTS_HEAD}\n");
        for m in MIRRORS {
            self.mirror(if m.report { &mut reports } else { &mut options }, m);
        }
        for e in ENUMS {
            self.conversions(&mut options, e);
        }
        [
            (OPTIONS_FILE, rustfmt(&options)),
            (REPORTS_FILE, rustfmt(&reports)),
        ]
    }
}

fn rustfmt(source: &str) -> String {
    let mut child = Command::new("rustfmt")
        .args(["--edition", "2021", "--emit", "stdout"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .expect("cannot run rustfmt");
    child
        .stdin
        .take()
        .unwrap()
        .write_all(source.as_bytes())
        .unwrap();
    let output = child.wait_with_output().unwrap();
    assert!(
        output.status.success(),
        "rustfmt failed on the generated source:\n{source}"
    );
    String::from_utf8(output.stdout).unwrap()
}

/// The lines of `old` and `new` that differ, for the message of a stale file.
pub fn diff(old: &str, new: &str) -> String {
    let (old, new): (Vec<&str>, Vec<&str>) = (old.lines().collect(), new.lines().collect());
    let start = old.iter().zip(&new).take_while(|(a, b)| a == b).count();
    let common_end = old[start..]
        .iter()
        .rev()
        .zip(new[start..].iter().rev())
        .take_while(|(a, b)| a == b)
        .count();
    let mut out = format!("@@ line {} @@\n", start + 1);
    for line in &old[start..old.len() - common_end] {
        writeln!(out, "-{line}").unwrap();
    }
    for line in &new[start..new.len() - common_end] {
        writeln!(out, "+{line}").unwrap();
    }
    out
}

/// The generated C options (and enum conversions) and C reports, under the crate's root.
pub const OPTIONS_FILE: &str = "src/capi/options_gen.rs";
pub const REPORTS_FILE: &str = "src/capi/reports_gen.rs";

/// The files the generator reads, under the crate's root.
// Used by tests/c_structs.rs, not by main.rs.
#[allow(dead_code)]
pub fn inputs() -> Vec<&'static str> {
    let mut files: Vec<&str> = sources().collect();
    files.push("cbindgen.toml");
    files.sort_unstable();
    files.dedup();
    files
}

/// The generated files (path under `root`, source) from the core sources under `root`.
pub fn generate(root: &Path) -> [(&'static str, String); 2] {
    Generator::read(root).generate()
}
