//! Reader for the B-spline geometries of G+Smo XML files (`<Geometry type="BSpline">` or `"Nurbs"`
//! curves and `<Geometry type="TensorBSpline2">` or `"TensorNurbs2"` surfaces), through the XML
//! parser of [`crate::io::gismo`]: comments, CDATA and entities are read as XML says, and the
//! patches are those a `<MultiPatch>` names by id, or every geometry of the file.

use std::path::Path;

use roxmltree::Node;

use super::bspline::{BSplineCurve, BSplineSurface};
use crate::error::{Error, Result};
use crate::io::gismo::{self as xml, descendants, line};

/// One geometry read from a G+Smo XML file.
#[derive(Clone, Debug, PartialEq)]
pub enum GismoGeometry {
    /// A `BSpline` curve.
    Curve(BSplineCurve),
    /// A `TensorBSpline2` surface.
    Surface(BSplineSurface),
}

/// The non-negative integer attribute `key` of `node`.
fn count_attribute(node: Node<'_, '_>, key: &str) -> Result<usize> {
    let line = line(node);
    let name = node.tag_name().name();
    let value = node
        .attribute(key)
        .ok_or_else(|| Error::io(format!("line {line}: <{name}> has no {key} attribute")))?;
    value.trim().parse().map_err(|_| {
        Error::io(format!(
            "line {line}: <{name}> {key} '{value}' is not a non-negative integer"
        ))
    })
}

fn parse_knot_vector(kv: Node<'_, '_>) -> Result<(usize, Vec<f64>)> {
    Ok((
        count_attribute(kv, "degree")?,
        xml::numbers(kv, "knot vector")?,
    ))
}

fn parse_coefs(geometry: Node<'_, '_>, what: &str) -> Result<(usize, Vec<f64>)> {
    let el = *descendants(geometry, "coefs").first().ok_or_else(|| {
        Error::io(format!(
            "line {}: {what} has no <coefs> element",
            line(geometry)
        ))
    })?;
    let dim = count_attribute(el, "geoDim")?;
    let values = xml::numbers(el, "control points")?;
    if dim == 0 || values.len() % dim != 0 {
        return Err(Error::io(format!(
            "line {}: {} coefficient values are not a whole number of {dim}D points",
            line(el),
            values.len()
        )));
    }
    Ok((dim, values))
}

/// The `<weights>` of a rational geometry (required when `rational`, refused otherwise).
fn parse_weights(geometry: Node<'_, '_>, rational: bool) -> Result<Option<Vec<f64>>> {
    match (descendants(geometry, "weights").first(), rational) {
        (Some(&w), true) => Ok(Some(xml::numbers(w, "weights")?)),
        (None, true) => Err(Error::io(format!(
            "line {}: rational geometry has no <weights> element",
            line(geometry)
        ))),
        (Some(&w), false) => Err(Error::io(format!(
            "line {}: <weights> in a non-rational geometry",
            line(w)
        ))),
        (None, false) => Ok(None),
    }
}

/// The basis types a curve or surface of a B-rep is made of.
const BASIS_TYPES: [&str; 4] = [
    "BSplineBasis",
    "NurbsBasis",
    "TensorBSplineBasis2",
    "TensorNurbsBasis2",
];

/// Refuses a `<Basis>` inside geometry `g` whose type is none of [`BASIS_TYPES`] (its knot
/// vectors would otherwise be read as if it were a B-spline basis).
fn check_basis_types(g: Node<'_, '_>) -> Result<()> {
    match descendants(g, "Basis")
        .into_iter()
        .find(|b| !BASIS_TYPES.contains(&b.attribute("type").unwrap_or("")))
    {
        Some(b) => Err(Error::io(format!(
            "line {}: basis type {:?} is not supported (only {})",
            line(b),
            b.attribute("type").unwrap_or(""),
            BASIS_TYPES.join(", ")
        ))),
        None => Ok(()),
    }
}

/// One `<Geometry>` element as a curve or surface.
fn parse_geometry(g: Node<'_, '_>) -> Result<GismoGeometry> {
    let line = line(g);
    let ty = g.attribute("type").unwrap_or("");
    let context = |e: Error| Error::new(e.kind, format!("line {line}: Geometry: {}", e.message));
    let knots = descendants(g, "KnotVector");
    match ty {
        "BSpline" | "Nurbs" => {
            check_basis_types(g)?;
            let kv = knots.first().ok_or_else(|| {
                Error::io(format!("line {line}: BSpline geometry has no <KnotVector>"))
            })?;
            let (degree, knots) = parse_knot_vector(*kv)?;
            let (dim, coefs) = parse_coefs(g, "BSpline geometry")?;
            let weights = parse_weights(g, ty == "Nurbs")?;
            Ok(GismoGeometry::Curve(
                BSplineCurve::new(degree, knots, dim, coefs, weights).map_err(context)?,
            ))
        }
        "TensorBSpline2" | "TensorNurbs2" => {
            check_basis_types(g)?;
            let [k1, k2] = knots[..] else {
                return Err(Error::io(format!(
                    "line {line}: TensorBSpline2 geometry needs two <KnotVector> elements, it has {}",
                    knots.len()
                )));
            };
            let ku = parse_knot_vector(k1)?;
            let kv = parse_knot_vector(k2)?;
            let (dim, coefs) = parse_coefs(g, "TensorBSpline2 geometry")?;
            let weights = parse_weights(g, ty == "TensorNurbs2")?;
            Ok(GismoGeometry::Surface(
                BSplineSurface::new(ku, kv, dim, coefs, weights).map_err(context)?,
            ))
        }
        other => Err(Error::io(format!(
            "line {line}: Geometry type '{other}' is not supported (only BSpline, Nurbs, TensorBSpline2 and TensorNurbs2)"
        ))),
    }
}

/// Reads the B-spline or NURBS curves (`BSpline`, `Nurbs`) and tensor-product surfaces
/// (`TensorBSpline2`, `TensorNurbs2`, with `<weights>` in the rational basis) of a G+Smo XML
/// document: the patches its first `<MultiPatch>` names (`<patches type="id_range">` or
/// `"id_index"`, by `id`), in that order, or else every `<Geometry>` in file order.
/// Other geometry types are an [`ErrorKind::Io`](crate::ErrorKind::Io) error naming the type and
/// line, and so is text that is not XML; invalid splines keep the kind of their validation error,
/// with the line prepended.
pub fn parse_gismo_xml(text: &str) -> Result<Vec<GismoGeometry>> {
    let doc = xml::parse(text)?;
    xml::patches(&doc)?
        .into_iter()
        .map(parse_geometry)
        .collect()
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
