//! Reader for the B-spline geometries of G+Smo XML files (`<Geometry type="BSpline">` or `"Nurbs"`
//! curves and `<Geometry type="TensorBSpline2">` or `"TensorNurbs2"` surfaces), by a small tag scanner: the format is regular
//! enough that no XML library is needed.

use std::path::Path;

use super::bspline::{BSplineCurve, BSplineSurface};
use crate::error::{Error, Result};

/// One geometry read from a G+Smo XML file.
#[derive(Clone, Debug, PartialEq)]
pub enum GismoGeometry {
    /// A `BSpline` curve.
    Curve(BSplineCurve),
    /// A `TensorBSpline2` surface.
    Surface(BSplineSurface),
}

/// An element found by the scanner: its attributes text, its content and where it ends.
struct Element<'a> {
    attrs: &'a str,
    content: &'a str,
    /// Byte offset of the content's start.
    content_start: usize,
    /// Byte offset of the opening `<`.
    start: usize,
    /// Byte offset just after the closing tag.
    end: usize,
}

fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

/// Finds the next element `<name ...>...</name>` (or `<name .../>`) at or after `from`; elements
/// of the same name must not nest.
fn find_element<'a>(
    text: &'a str,
    name: &str,
    from: usize,
    to: usize,
) -> Result<Option<Element<'a>>> {
    let open = format!("<{name}");
    let mut pos = from;
    while let Some(rel) = text[pos..to].find(&open) {
        let start = pos + rel;
        let after = start + open.len();
        let next = text[after..].chars().next();
        if !matches!(next, Some(c) if c.is_whitespace() || c == '>' || c == '/') {
            pos = after;
            continue;
        }
        let gt = text[after..to].find('>').ok_or_else(|| {
            Error::io(format!(
                "line {}: tag <{name} is not closed by '>'",
                line_of(text, start)
            ))
        })? + after;
        if text[..gt].ends_with('/') {
            return Ok(Some(Element {
                attrs: &text[after..gt - 1],
                content: "",
                content_start: gt + 1,
                start,
                end: gt + 1,
            }));
        }
        let close = format!("</{name}");
        let crel = text[gt + 1..to].find(&close).ok_or_else(|| {
            Error::io(format!(
                "line {}: <{name}> has no closing </{name}>",
                line_of(text, start)
            ))
        })?;
        let cstart = gt + 1 + crel;
        let cend = text[cstart..to]
            .find('>')
            .map(|i| cstart + i + 1)
            .ok_or_else(|| {
                Error::io(format!(
                    "line {}: closing </{name} is not ended by '>'",
                    line_of(text, cstart)
                ))
            })?;
        return Ok(Some(Element {
            attrs: &text[after..gt],
            content: &text[gt + 1..cstart],
            content_start: gt + 1,
            start,
            end: cend,
        }));
    }
    Ok(None)
}

/// The value of attribute `key` in an attribute string (`key="value"` or `key='value'`).
fn attribute<'a>(attrs: &'a str, key: &str) -> Option<&'a str> {
    let mut rest = attrs;
    while let Some(i) = rest.find(key) {
        let before_ok = i == 0 || rest[..i].ends_with(|c: char| c.is_whitespace());
        let after = rest[i + key.len()..].trim_start();
        if before_ok {
            if let Some(after_eq) = after.strip_prefix('=') {
                let after_eq = after_eq.trim_start();
                let quote = after_eq.chars().next()?;
                if quote == '"' || quote == '\'' {
                    let body = &after_eq[1..];
                    let end = body.find(quote)?;
                    return Some(&body[..end]);
                }
                return None;
            }
        }
        rest = &rest[i + key.len()..];
    }
    None
}

fn parse_numbers(text: &str, what: &str, line: usize) -> Result<Vec<f64>> {
    text.split_whitespace()
        .map(|tok| {
            tok.parse::<f64>()
                .map_err(|_| Error::io(format!("line {line}: {what}: '{tok}' is not a number")))
        })
        .collect()
}

fn parse_knot_vector(text: &str, el: &Element) -> Result<(usize, Vec<f64>)> {
    let line = line_of(text, el.start);
    let degree = attribute(el.attrs, "degree")
        .ok_or_else(|| Error::io(format!("line {line}: <KnotVector> has no degree attribute")))?;
    let degree: usize = degree.trim().parse().map_err(|_| {
        Error::io(format!(
            "line {line}: <KnotVector> degree '{degree}' is not a non-negative integer"
        ))
    })?;
    Ok((degree, parse_numbers(el.content, "knot vector", line)?))
}

fn parse_coefs(text: &str, from: usize, to: usize, what: &str) -> Result<(usize, Vec<f64>)> {
    let el = find_element(text, "coefs", from, to)?.ok_or_else(|| {
        Error::io(format!(
            "line {}: {what} has no <coefs> element",
            line_of(text, from)
        ))
    })?;
    let line = line_of(text, el.start);
    let dim = attribute(el.attrs, "geoDim")
        .ok_or_else(|| Error::io(format!("line {line}: <coefs> has no geoDim attribute")))?;
    let dim: usize = dim.trim().parse().map_err(|_| {
        Error::io(format!(
            "line {line}: <coefs> geoDim '{dim}' is not a positive integer"
        ))
    })?;
    let values = parse_numbers(el.content, "control points", line)?;
    if dim == 0 || values.len() % dim != 0 {
        return Err(Error::io(format!(
            "line {line}: {} coefficient values are not a whole number of {dim}D points",
            values.len()
        )));
    }
    Ok((dim, values))
}

/// The `<weights>` of a rational geometry (required when `rational`, refused otherwise).
fn parse_weights(
    text: &str,
    from: usize,
    to: usize,
    rational: bool,
    line: usize,
) -> Result<Option<Vec<f64>>> {
    match (find_element(text, "weights", from, to)?, rational) {
        (Some(w), true) => Ok(Some(parse_numbers(
            w.content,
            "weights",
            line_of(text, w.start),
        )?)),
        (None, true) => Err(Error::io(format!(
            "line {line}: rational geometry has no <weights> element"
        ))),
        (Some(w), false) => Err(Error::io(format!(
            "line {}: <weights> in a non-rational geometry",
            line_of(text, w.start)
        ))),
        (None, false) => Ok(None),
    }
}

/// Reads every B-spline or NURBS curve (`BSpline`, `Nurbs`) and tensor-product surface
/// (`TensorBSpline2`, `TensorNurbs2`, with `<weights>` in the rational basis) of a G+Smo XML
/// document, in file order.
/// Other geometry types are an [`ErrorKind::Io`](crate::ErrorKind::Io) error naming the type and
/// line; invalid splines keep the kind of their validation error, with the line prepended.
pub fn parse_gismo_xml(text: &str) -> Result<Vec<GismoGeometry>> {
    let mut out = Vec::new();
    let mut pos = 0;
    while let Some(g) = find_element(text, "Geometry", pos, text.len())? {
        pos = g.end;
        let line = line_of(text, g.start);
        let ty = attribute(g.attrs, "type").unwrap_or("");
        let (from, to) = (g.content_start, g.content_start + g.content.len());
        let context =
            |e: Error| Error::new(e.kind, format!("line {line}: Geometry: {}", e.message));
        match ty {
            "BSpline" | "Nurbs" => {
                let kv = find_element(text, "KnotVector", from, to)?.ok_or_else(|| {
                    Error::io(format!("line {line}: BSpline geometry has no <KnotVector>"))
                })?;
                let (degree, knots) = parse_knot_vector(text, &kv)?;
                let (dim, coefs) = parse_coefs(text, from, to, "BSpline geometry")?;
                let weights = parse_weights(text, from, to, ty == "Nurbs", line)?;
                out.push(GismoGeometry::Curve(
                    BSplineCurve::new(degree, knots, dim, coefs, weights).map_err(context)?,
                ));
            }
            "TensorBSpline2" | "TensorNurbs2" => {
                let k1 = find_element(text, "KnotVector", from, to)?;
                let k2 = match &k1 {
                    Some(k) => find_element(text, "KnotVector", k.end, to)?,
                    None => None,
                };
                let (Some(k1), Some(k2)) = (k1, k2) else {
                    return Err(Error::io(format!(
                        "line {line}: TensorBSpline2 geometry needs two <KnotVector> elements"
                    )));
                };
                let ku = parse_knot_vector(text, &k1)?;
                let kv = parse_knot_vector(text, &k2)?;
                let (dim, coefs) = parse_coefs(text, from, to, "TensorBSpline2 geometry")?;
                let weights = parse_weights(text, from, to, ty == "TensorNurbs2", line)?;
                out.push(GismoGeometry::Surface(
                    BSplineSurface::new(ku, kv, dim, coefs, weights).map_err(context)?,
                ));
            }
            other => {
                return Err(Error::io(format!(
                    "line {line}: Geometry type '{other}' is not supported (only BSpline, Nurbs, TensorBSpline2 and TensorNurbs2)"
                )))
            }
        }
    }
    Ok(out)
}

/// Reads a G+Smo XML file with [`parse_gismo_xml`]; I/O failures are
/// [`ErrorKind::Io`](crate::ErrorKind::Io) errors naming the file.
pub fn read_gismo_xml(path: impl AsRef<Path>) -> Result<Vec<GismoGeometry>> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path)
        .map_err(|e| Error::io(format!("cannot read {}: {e}", path.display())))?;
    parse_gismo_xml(&text)
        .map_err(|e| Error::new(e.kind, format!("{}: {}", path.display(), e.message)))
}

/// The curves of a G+Smo XML file, in file order; an error if it holds anything else.
pub fn read_gismo_curves(path: impl AsRef<Path>) -> Result<Vec<BSplineCurve>> {
    let path = path.as_ref();
    read_gismo_xml(path)?
        .into_iter()
        .map(|g| match g {
            GismoGeometry::Curve(c) => Ok(c),
            GismoGeometry::Surface(_) => Err(Error::io(format!(
                "{}: expected only B-spline curves, found a surface",
                path.display()
            ))),
        })
        .collect()
}

/// The surfaces of a G+Smo XML file, in file order; an error if it holds anything else.
pub fn read_gismo_surfaces(path: impl AsRef<Path>) -> Result<Vec<BSplineSurface>> {
    let path = path.as_ref();
    read_gismo_xml(path)?
        .into_iter()
        .map(|g| match g {
            GismoGeometry::Surface(s) => Ok(s),
            GismoGeometry::Curve(_) => Err(Error::io(format!(
                "{}: expected only tensor-product B-spline surfaces, found a curve",
                path.display()
            ))),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scans_attributes_and_elements() {
        assert_eq!(attribute(r#" type="BSpline" id='3'"#, "id"), Some("3"));
        assert_eq!(
            attribute(r#" mytype="x" type = "BSpline""#, "type"),
            Some("BSpline")
        );
        let text = "<a><KnotVectorX/><KnotVector\n degree=\"1\">0 0\n1 1</KnotVector></a>";
        let el = find_element(text, "KnotVector", 0, text.len())
            .unwrap()
            .unwrap();
        assert_eq!(attribute(el.attrs, "degree"), Some("1"));
        assert_eq!(el.content, "0 0\n1 1");
    }

    #[test]
    fn reports_bad_numbers_with_line() {
        let text = "<xml>\n<Geometry type=\"BSpline\"><Basis type=\"BSplineBasis\">\n<KnotVector degree=\"1\">0 0 x 1</KnotVector></Basis><coefs geoDim=\"2\">0 0 1 1</coefs></Geometry></xml>";
        let e = parse_gismo_xml(text).unwrap_err();
        assert!(
            e.message.contains("line 3") && e.message.contains("'x'"),
            "{}",
            e.message
        );
    }
}
