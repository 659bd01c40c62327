//! G+Smo XML for THB-spline maps: `<Geometry type="THBSpline2">` (or `3`) holding a
//! `<Basis type="THBSplineBasis2">` — the level-0 tensor basis and one `<box level="l">` per
//! leaf of level ≥ 1, lower then upper corner in the level's knot-span indices — and the
//! control points in `<coefs geoDim="d">`, in the basis order (by level, direction 0 fastest).
//! The reader takes what the writer writes, and level-0 bases with `2^s` uniform spans.

use std::fmt::Write as _;
use std::path::Path;

use super::map::SplineMap;
use super::space::SplineSpace;
use super::thb::ThbSpace;
use crate::error::{Error, Result};
use crate::tmesh::{Tree, MAX_LEVEL};

/// Writes a THB map as G+Smo XML text.
pub fn write_gismo_thb<const D: usize>(map: &SplineMap<D, ThbSpace<D>>) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<xml>");
    let _ = writeln!(s, " <Geometry type=\"THBSpline{D}\" id=\"0\">");
    let _ = writeln!(s, "  <Basis type=\"THBSplineBasis{D}\">");
    let _ = writeln!(s, "   <Basis type=\"TensorBSplineBasis{D}\">");
    for k in 0..D {
        let _ = writeln!(s, "    <Basis type=\"BSplineBasis\" index=\"{k}\">");
        let _ = writeln!(
            s,
            "     <KnotVector degree=\"3\">0 0 0 0 1 1 1 1</KnotVector>"
        );
        let _ = writeln!(s, "    </Basis>");
    }
    let _ = writeln!(s, "   </Basis>");
    let space = map.space();
    for e in 0..space.element_count() {
        let level = space.element_level(e);
        if level == 0 {
            continue;
        }
        let (lo, hi) = space.element_bounds(e);
        let scale = (1u64 << level) as f64;
        let corners: Vec<String> = lo
            .iter()
            .chain(hi.iter())
            .map(|v| ((v * scale).round() as u64).to_string())
            .collect();
        let _ = writeln!(s, "   <box level=\"{level}\">{}</box>", corners.join(" "));
    }
    let _ = writeln!(s, "  </Basis>");
    let _ = writeln!(s, "  <coefs geoDim=\"{D}\">");
    for p in map.control_points() {
        let row: Vec<String> = p.iter().map(|v| format!("{v:?}")).collect();
        let _ = writeln!(s, "   {}", row.join(" "));
    }
    let _ = writeln!(s, "  </coefs>\n </Geometry>\n</xml>");
    s
}

/// The attribute text and content of every `<tag ...>content</tag>` (elements that do not
/// nest).
fn elements<'a>(text: &'a str, tag: &str) -> Result<Vec<(&'a str, &'a str)>> {
    let open = format!("<{tag}");
    let close = format!("</{tag}>");
    let mut out = Vec::new();
    let mut pos = 0;
    while let Some(rel) = text[pos..].find(&open) {
        let start = pos + rel + open.len();
        if !text[start..].starts_with(|c: char| c.is_whitespace() || c == '>') {
            pos = start;
            continue;
        }
        let gt = start
            + text[start..]
                .find('>')
                .ok_or_else(|| Error::io(format!("<{tag} is not closed")))?;
        let end = gt
            + text[gt..]
                .find(&close)
                .ok_or_else(|| Error::io(format!("<{tag}> has no {close}")))?;
        out.push((&text[start..gt], &text[gt + 1..end]));
        pos = end + close.len();
    }
    Ok(out)
}

fn attribute<'a>(attrs: &'a str, name: &str) -> Option<&'a str> {
    let key = format!("{name}=\"");
    let start = attrs.find(&key)? + key.len();
    let len = attrs[start..].find('"')?;
    Some(&attrs[start..start + len])
}

fn numbers(text: &str) -> Result<Vec<f64>> {
    text.split_whitespace()
        .map(|t| {
            t.parse::<f64>()
                .map_err(|_| Error::io(format!("'{t}' is not a number")))
        })
        .collect()
}

/// Reads a THB map written by [`write_gismo_thb`] (or any `THBSpline2/3` of degree 3 on
/// [0,1]^d whose level-0 knots are clamped and uniform with `2^s` spans).
pub fn read_gismo_thb<const D: usize>(text: &str) -> Result<SplineMap<D, ThbSpace<D>>> {
    let kind = format!("THBSpline{D}");
    let geometry = text
        .find(&format!("type=\"{kind}\""))
        .ok_or_else(|| Error::io(format!("no <Geometry type=\"{kind}\">")))?;
    let text = &text[geometry..];
    let knots = elements(text, "KnotVector")?;
    if knots.len() < D {
        return Err(Error::io(format!("{kind} needs {D} knot vectors")));
    }
    let mut shift = None;
    for (attrs, content) in &knots[..D] {
        if attribute(attrs, "degree") != Some("3") {
            return Err(Error::io("only degree 3 is read"));
        }
        let k = numbers(content)?;
        let spans = k.len().saturating_sub(7);
        let uniform = spans >= 1
            && spans.is_power_of_two()
            && k[..4].iter().all(|&v| v == 0.0)
            && k[k.len() - 4..].iter().all(|&v| v == 1.0)
            && (1..spans).all(|i| (k[3 + i] - i as f64 / spans as f64).abs() < 1e-12);
        if !uniform {
            return Err(Error::io(
                "the level-0 knots must be clamped and uniform on [0,1] with 2^s spans",
            ));
        }
        let s = spans.trailing_zeros() as u8;
        if shift.is_some_and(|t| t != s) {
            return Err(Error::io("the level-0 knot vectors differ"));
        }
        shift = Some(s);
    }
    let shift = shift.unwrap_or(0);
    let mut tree = Tree::<D>::new();
    tree.refine_uniformly(shift)?;
    for (attrs, content) in elements(text, "box")? {
        let level: u8 = attribute(attrs, "level")
            .and_then(|v| v.parse().ok())
            .ok_or_else(|| Error::io("a <box> has no level"))?;
        let level = level + shift;
        let corners = numbers(content)?;
        if corners.len() != 2 * D || level > MAX_LEVEL {
            return Err(Error::io(format!("bad box: level {level}, {content}")));
        }
        let unit = crate::tmesh::UNIT as u64 >> level;
        tree.refine_while(false, |tree, c| {
            let cell = tree.cells()[c];
            cell.level < level
                && (0..D).all(|k| {
                    let lo = cell.lower[k] as u64 / unit;
                    let hi = (cell.lower[k] + cell.side()) as u64 / unit;
                    (lo as f64) < corners[D + k] && corners[k] < hi as f64
                })
        })?;
    }
    tree.balance()?;
    let space = ThbSpace::new(tree)?;
    let (attrs, content) = *elements(text, "coefs")?
        .first()
        .ok_or_else(|| Error::io("no <coefs>"))?;
    if attribute(attrs, "geoDim") != Some(&D.to_string()) {
        return Err(Error::io(format!("<coefs> must have geoDim=\"{D}\"")));
    }
    let values = numbers(content)?;
    if values.len() != D * space.basis_count() {
        return Err(Error::io(format!(
            "{} coefficients for {} basis functions of dimension {D}",
            values.len(),
            space.basis_count()
        )));
    }
    let control = values
        .chunks_exact(D)
        .map(|c| std::array::from_fn(|k| c[k]))
        .collect();
    SplineMap::new(space, control)
}

impl<const D: usize> SplineMap<D, ThbSpace<D>> {
    /// Writes the map to a G+Smo XML file.
    pub fn write_gismo(&self, path: &Path) -> Result<()> {
        std::fs::write(path, write_gismo_thb(self))
            .map_err(|e| Error::io(format!("cannot write {}: {e}", path.display())))
    }

    /// Reads a map from a G+Smo XML file (see [`read_gismo_thb`]).
    pub fn read_gismo(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| Error::io(format!("cannot read {}: {e}", path.display())))?;
        read_gismo_thb(&text)
    }
}
