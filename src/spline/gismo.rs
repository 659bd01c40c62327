//! G+Smo XML for THB-spline maps: `<Geometry type="THBSpline2">` (or `3`) holding a
//! `<Basis type="THBSplineBasis2">` — the level-0 tensor basis and one `<box level="l">` per
//! leaf of level ≥ 1, lower then upper corner in the level's knot-span indices — and the
//! control points in `<coefs geoDim="d">`, in the basis order (by level, direction 0 fastest).
//! The reader takes what the writer writes, and level-0 bases with `2^s` uniform spans; it
//! parses the XML with roxmltree (comments, CDATA, entities) and reads each patch's boxes from
//! that patch alone.

use std::fmt::Write as _;
use std::path::Path;

use roxmltree::Node;

use super::map::SplineMap;
use super::space::SplineSpace;
use super::thb::ThbSpace;
use crate::error::{Error, Result};
use crate::io::gismo::{self as xml, line};
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

/// The child `<Basis>` of `node` whose type is `ty`.
fn basis<'a, 'input>(node: Node<'a, 'input>, ty: &str) -> Result<Node<'a, 'input>> {
    xml::children(node, "Basis")
        .find(|b| b.attribute("type") == Some(ty))
        .ok_or_else(|| {
            Error::io(format!(
                "line {}: <{}> has no <Basis type=\"{ty}\">",
                line(node),
                node.tag_name().name()
            ))
        })
}

/// The base-2 logarithm of the number of spans of the level-0 knot vectors of a tensor basis,
/// which must be cubic, clamped and uniform on \[0,1\] with `2^s` spans, the same in every
/// direction; the direction of each `<Basis>` is its `index` attribute, else its place.
fn level0_shift<const D: usize>(tensor: Node<'_, '_>) -> Result<u8> {
    let mut bases: Vec<(usize, Node)> = xml::children(tensor, "Basis")
        .enumerate()
        .map(|(i, b)| {
            (
                b.attribute("index")
                    .and_then(|v| v.parse().ok())
                    .unwrap_or(i),
                b,
            )
        })
        .collect();
    bases.sort_by_key(|&(i, _)| i);
    if bases.len() != D {
        return Err(Error::io(format!(
            "line {}: the tensor basis needs {D} univariate bases, it has {}",
            line(tensor),
            bases.len()
        )));
    }
    let mut shift = None;
    for (_, b) in bases {
        if b.attribute("type") != Some("BSplineBasis") {
            return Err(Error::io(format!(
                "line {}: a univariate basis of the tensor basis must be of type \"BSplineBasis\", not {:?}",
                line(b),
                b.attribute("type").unwrap_or("")
            )));
        }
        let kv = xml::children(b, "KnotVector")
            .next()
            .ok_or_else(|| Error::io(format!("line {}: <Basis> has no <KnotVector>", line(b))))?;
        let at = line(kv);
        if kv.attribute("degree").map(str::trim) != Some("3") {
            return Err(Error::io(format!("line {at}: only degree 3 is read")));
        }
        let k = xml::numbers(kv, "knot vector")?;
        let spans = k.len().saturating_sub(7);
        let uniform = spans >= 1
            && spans.is_power_of_two()
            && k[..4].iter().all(|&v| v == 0.0)
            && k[k.len() - 4..].iter().all(|&v| v == 1.0)
            && (1..spans).all(|i| (k[3 + i] - i as f64 / spans as f64).abs() < 1e-12);
        if !uniform {
            return Err(Error::io(format!(
                "line {at}: the level-0 knots must be clamped and uniform on [0,1] with 2^s spans"
            )));
        }
        let s = spans.trailing_zeros() as u8;
        if shift.is_some_and(|t| t != s) {
            return Err(Error::io(format!(
                "line {at}: the level-0 knot vectors differ"
            )));
        }
        shift = Some(s);
    }
    Ok(shift.unwrap_or(0))
}

/// The `<box level="l">` children of a THB basis: each leaf of level ≥ 1 (the level counted
/// from the tree's root, `shift` added) with its lower then upper corner in the level's
/// knot-span indices.
fn boxes<const D: usize>(thb: Node<'_, '_>, shift: u8) -> Result<Vec<(u8, Vec<f64>)>> {
    let mut out = Vec::new();
    for b in xml::children(thb, "box") {
        let at = line(b);
        let level: u8 = b
            .attribute("level")
            .and_then(|v| v.trim().parse().ok())
            .ok_or_else(|| Error::io(format!("line {at}: a <box> has no level")))?;
        let level = level.saturating_add(shift);
        let corners = xml::numbers(b, "box")?;
        if corners.len() != 2 * D || level > MAX_LEVEL {
            return Err(Error::io(format!(
                "line {at}: bad box: level {level}, {} corner values (2 x {D} expected)",
                corners.len()
            )));
        }
        check_box_corners::<D>(&corners, level)
            .map_err(|m| Error::io(format!("line {at}: {m}")))?;
        out.push((level, corners));
    }
    Ok(out)
}

/// Why the corners of a box of (absolute) level `level` are not a box of that level's knot
/// spans: each a whole span index in `[0, 2^level]`, the lower corner below the upper one in
/// every direction.
fn check_box_corners<const D: usize>(
    corners: &[f64],
    level: u8,
) -> std::result::Result<(), String> {
    let spans = (1u64 << level) as f64;
    if let Some(v) = corners
        .iter()
        .find(|v| v.fract() != 0.0 || !(0.0..=spans).contains(*v))
    {
        return Err(format!(
            "bad box: corner value {v} is not a knot-span index of level {level} (a whole number from 0 to {spans})"
        ));
    }
    if let Some(k) = (0..D).find(|&k| corners[k] >= corners[D + k]) {
        return Err(format!(
            "bad box: in direction {k} its lower corner {} is not below its upper corner {}",
            corners[k],
            corners[D + k]
        ));
    }
    Ok(())
}

/// Refuses, before anything is refined, a file whose level-0 basis and boxes would make far
/// more cells than its coefficients can describe: a valid file gives a coefficient per basis
/// function, and the cells of a refined region carry about as many functions as cells (thin
/// boxes carry fewer, hence the allowance of 2^20 cells). A few kilobytes of knots or one box
/// could otherwise ask for 4^20 cells.
fn check_cells<const D: usize>(
    shift: u8,
    boxes: &[(u8, Vec<f64>)],
    functions: usize,
) -> Result<()> {
    let spans = |level: u8| (1u64 << level) as f64;
    let mut cells = spans(shift).powi(D as i32);
    for (_, corners) in boxes {
        // The corners are checked (`check_box_corners`): whole, in range, lower below upper.
        let extent = |k: usize| corners[D + k] - corners[k];
        cells += (0..D).map(extent).product::<f64>();
    }
    let limit = 16.0 * functions as f64 + (1u64 << 20) as f64;
    if cells > limit {
        return Err(Error::io(format!(
            "the level-0 basis and the <box> entries make at least {cells:.3e} cells, more than \
             {functions} basis functions (the coefficients given) can describe"
        )));
    }
    Ok(())
}

/// Refines `tree` to hold the given boxes.
fn apply_boxes<const D: usize>(tree: &mut Tree<D>, boxes: &[(u8, Vec<f64>)]) -> Result<()> {
    for (level, corners) in boxes {
        let level = *level;
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
    Ok(())
}

/// One `<Geometry type="THBSpline{D}">` element as a map.
fn read_thb_geometry<const D: usize>(geometry: Node<'_, '_>) -> Result<SplineMap<D, ThbSpace<D>>> {
    let thb = basis(geometry, &format!("THBSplineBasis{D}"))?;
    let shift = level0_shift::<D>(basis(thb, &format!("TensorBSplineBasis{D}"))?)?;
    let coefs = xml::children(geometry, "coefs")
        .next()
        .ok_or_else(|| Error::io(format!("line {}: no <coefs>", line(geometry))))?;
    if coefs.attribute("geoDim").map(str::trim) != Some(&D.to_string()) {
        return Err(Error::io(format!(
            "line {}: <coefs> must have geoDim=\"{D}\"",
            line(coefs)
        )));
    }
    let values = xml::numbers(coefs, "coefs")?;
    let boxes = boxes::<D>(thb, shift)?;
    check_cells::<D>(shift, &boxes, values.len() / D)
        .map_err(|e| Error::io(format!("line {}: {}", line(thb), e.message)))?;
    let mut tree = Tree::<D>::new();
    tree.refine_uniformly(shift)?;
    // The file's tree as it is: G+Smo does not balance its trees, and balancing would add
    // functions the file has no coefficients for.
    apply_boxes(&mut tree, &boxes)?;
    let space = ThbSpace::new(tree)?;
    if values.len() != D * space.basis_count() {
        return Err(Error::io(format!(
            "line {}: {} coefficients for {} basis functions of dimension {D}",
            line(coefs),
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

/// Reads the first `THBSpline{D}` patch of a G+Smo document: a map written by
/// [`write_gismo_thb`], or any `THBSpline2/3` of degree 3 on \[0,1\]^d whose level-0 knots are
/// clamped and uniform with `2^s` spans. Other patches of the file are not read (see
/// [`SplineMap::parse_gismo_patches`]).
pub fn read_gismo_thb<const D: usize>(text: &str) -> Result<SplineMap<D, ThbSpace<D>>> {
    let doc = xml::parse(text)?;
    let kind = format!("THBSpline{D}");
    let geometry = xml::patches(&doc)?
        .into_iter()
        .find(|g| g.attribute("type") == Some(kind.as_str()))
        .ok_or_else(|| Error::io(format!("no <Geometry type=\"{kind}\">")))?;
    read_thb_geometry::<D>(geometry)
}

impl<const D: usize> SplineMap<D, ThbSpace<D>> {
    /// Writes the map to a G+Smo XML file.
    pub fn write_gismo(&self, path: &Path) -> Result<()> {
        std::fs::write(path, write_gismo_thb(self))
            .map_err(|e| Error::io(format!("cannot write {}: {e}", path.display())))
    }

    /// Every `THBSpline{D}` patch of a G+Smo document (the patches its `<MultiPatch>` names, or
    /// every geometry), in patch order, each with its own boxes.
    pub fn parse_gismo_patches(text: &str) -> Result<Vec<Self>> {
        let doc = xml::parse(text)?;
        let kind = format!("THBSpline{D}");
        xml::patches(&doc)?
            .into_iter()
            .filter(|g| g.attribute("type") == Some(kind.as_str()))
            .map(read_thb_geometry::<D>)
            .collect()
    }

    /// Reads a map from a G+Smo XML file (see [`read_gismo_thb`]).
    pub fn read_gismo(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| Error::io(format!("cannot read {}: {e}", path.display())))?;
        read_gismo_thb(&text)
    }
}
