//! Reading `.vtu` files: the XML through roxmltree, the arrays in any of VTK's storages (ASCII,
//! inline base64, appended raw or base64 data; uncompressed or zlib-compressed; `UInt32` or
//! `UInt64` headers; either byte order), every piece of the file.

use std::path::Path;

use roxmltree::Node;

use super::block::{Layout, Source};
use super::{DataArray, UnstructuredGrid};
use crate::error::{Error, Result};
use crate::io::gismo::{children, line};

/// The `<AppendedData>` section: its encoding and the bytes after its `_` marker.
struct Appended<'a> {
    raw: bool,
    data: &'a [u8],
}

/// Splits a file into its XML text and its appended data: raw appended data is not XML (any
/// byte may occur in it), so the XML parser sees the file with that section's content cut out.
fn split_appended(bytes: &[u8]) -> Result<(String, Option<&[u8]>)> {
    let utf8 = |b: &[u8]| {
        String::from_utf8(b.to_vec())
            .map_err(|e| Error::io(format!("not a VTK XML file: invalid UTF-8 ({e})")))
    };
    let Some(open) = find(bytes, b"<AppendedData") else {
        return Ok((utf8(bytes)?, None));
    };
    let tag_end = find(&bytes[open..], b">")
        .map(|i| open + i + 1)
        .ok_or_else(|| Error::io("the <AppendedData> tag is not closed"))?;
    let close = rfind(bytes, b"</AppendedData>")
        .filter(|&c| c >= tag_end)
        .ok_or_else(|| Error::io("<AppendedData> has no </AppendedData>"))?;
    let inner = &bytes[tag_end..close];
    let marker = inner
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .filter(|&i| inner[i] == b'_')
        .ok_or_else(|| Error::io("the appended data does not start with '_'"))?;
    let xml = [&bytes[..tag_end], &bytes[close..]].concat();
    Ok((utf8(&xml)?, Some(&inner[marker + 1..])))
}

fn find(haystack: &[u8], needle: &[u8]) -> Option<usize> {
    haystack.windows(needle.len()).position(|w| w == needle)
}

fn rfind(haystack: &[u8], needle: &[u8]) -> Option<usize> {
    haystack.windows(needle.len()).rposition(|w| w == needle)
}

/// Reads a `.vtu` file in any of the storages listed in the [module docs](super).
pub fn read(path: &Path) -> Result<UnstructuredGrid> {
    let bytes = std::fs::read(path)
        .map_err(|e| Error::io(format!("cannot read {}: {e}", path.display())))?;
    parse(&bytes).map_err(|e| Error::new(e.kind, format!("{}: {}", path.display(), e.message)))
}

/// Parses the bytes of a `.vtu` file.
pub fn parse(bytes: &[u8]) -> Result<UnstructuredGrid> {
    let (xml, appended) = split_appended(bytes)?;
    let doc = crate::io::gismo::parse(&xml)?;
    let root = doc.root_element();
    if !root.has_tag_name("VTKFile") || root.attribute("type") != Some("UnstructuredGrid") {
        return Err(Error::io(format!(
            "not a VTK UnstructuredGrid file (root <{} type=\"{}\">)",
            root.tag_name().name(),
            root.attribute("type").unwrap_or("")
        )));
    }
    let layout = layout(root)?;
    let appended = match (children(root, "AppendedData").next(), appended) {
        (Some(node), Some(data)) => Some(match node.attribute("encoding") {
            Some("raw") => Appended { raw: true, data },
            Some("base64") => Appended {
                raw: false,
                data: &data[..data
                    .iter()
                    .rposition(|b| !b.is_ascii_whitespace())
                    .map_or(0, |i| i + 1)],
            },
            other => {
                return Err(Error::io(format!(
                    "<AppendedData encoding=\"{}\"> is neither raw nor base64",
                    other.unwrap_or("")
                )))
            }
        }),
        _ => None,
    };
    let reader = Reader { layout, appended };
    let grid_node = children(root, "UnstructuredGrid")
        .next()
        .ok_or_else(|| Error::io("no <UnstructuredGrid> element"))?;
    let mut grid = UnstructuredGrid::default();
    for (i, piece) in children(grid_node, "Piece").enumerate() {
        reader.piece(piece, &mut grid, i == 0)?;
    }
    Ok(grid)
}

/// The header type, byte order and compressor of a `<VTKFile>`.
fn layout(root: Node<'_, '_>) -> Result<Layout> {
    let header_bytes = match root.attribute("header_type") {
        None | Some("UInt32") => 4,
        Some("UInt64") => 8,
        Some(other) => {
            return Err(Error::io(format!(
                "header_type \"{other}\" is not supported"
            )))
        }
    };
    let big_endian = match root.attribute("byte_order") {
        None | Some("LittleEndian") => false,
        Some("BigEndian") => true,
        Some(other) => {
            return Err(Error::io(format!(
                "byte_order \"{other}\" is not supported"
            )))
        }
    };
    let zlib = match root.attribute("compressor") {
        None | Some("") => false,
        Some("vtkZLibDataCompressor") => true,
        Some(other) => {
            return Err(Error::io(format!(
                "compressor \"{other}\" is not supported; write the file with vtkZLibDataCompressor (zlib) or none"
            )))
        }
    };
    Ok(Layout {
        header_bytes,
        big_endian,
        zlib,
    })
}

/// Decodes the arrays of one file.
struct Reader<'a> {
    layout: Layout,
    appended: Option<Appended<'a>>,
}

/// An array's values: integers are kept exact.
enum Values {
    Int(Vec<i64>),
    Float(Vec<f64>),
}

impl Values {
    fn floats(self) -> Vec<f64> {
        match self {
            Values::Int(v) => v.into_iter().map(|x| x as f64).collect(),
            Values::Float(v) => v,
        }
    }

    fn ints(self, name: &str) -> Result<Vec<i64>> {
        match self {
            Values::Int(v) => Ok(v),
            Values::Float(_) => Err(Error::io(format!("array `{name}` must hold integers"))),
        }
    }
}

/// Bytes of one value of a VTK scalar type, and whether it is a float.
fn scalar(ty: &str) -> Option<(usize, bool)> {
    Some(match ty {
        "Int8" | "UInt8" => (1, false),
        "Int16" | "UInt16" => (2, false),
        "Int32" | "UInt32" => (4, false),
        "Int64" | "UInt64" => (8, false),
        "Float32" => (4, true),
        "Float64" => (8, true),
        _ => return None,
    })
}

/// The values of little- or big-endian bytes of VTK type `ty`.
fn convert(ty: &str, bytes: &[u8], big_endian: bool) -> Result<Values> {
    fn each<const N: usize, T>(bytes: &[u8], big: bool, f: impl Fn([u8; N]) -> T) -> Vec<T> {
        bytes
            .chunks_exact(N)
            .map(|c| {
                let mut a: [u8; N] = c.try_into().expect("chunk of N bytes");
                if big {
                    a.reverse();
                }
                f(a)
            })
            .collect()
    }
    let b = big_endian;
    Ok(match ty {
        "Int8" => Values::Int(each(bytes, b, |a: [u8; 1]| i8::from_le_bytes(a) as i64)),
        "UInt8" => Values::Int(each(bytes, b, |a: [u8; 1]| a[0] as i64)),
        "Int16" => Values::Int(each(bytes, b, |a| i16::from_le_bytes(a) as i64)),
        "UInt16" => Values::Int(each(bytes, b, |a| u16::from_le_bytes(a) as i64)),
        "Int32" => Values::Int(each(bytes, b, |a| i32::from_le_bytes(a) as i64)),
        "UInt32" => Values::Int(each(bytes, b, |a| u32::from_le_bytes(a) as i64)),
        "Int64" => Values::Int(each(bytes, b, i64::from_le_bytes)),
        "UInt64" => Values::Int(
            each(bytes, b, u64::from_le_bytes)
                .into_iter()
                .map(|v| {
                    i64::try_from(v)
                        .map_err(|_| Error::io(format!("UInt64 value {v} is too large")))
                })
                .collect::<Result<_>>()?,
        ),
        "Float32" => Values::Float(each(bytes, b, |a| f32::from_le_bytes(a) as f64)),
        _ => Values::Float(each(bytes, b, f64::from_le_bytes)),
    })
}

/// The ASCII values of an array of type `ty`.
fn ascii(node: Node<'_, '_>, ty: &str, float: bool) -> Result<Values> {
    let text = crate::io::gismo::text(node);
    let bad = |t: &str| Error::io(format!("line {}: bad {ty} value `{t}`", line(node)));
    let tokens = text.split_ascii_whitespace();
    Ok(if float {
        Values::Float(
            tokens
                .map(|t| t.parse().map_err(|_| bad(t)))
                .collect::<Result<_>>()?,
        )
    } else {
        Values::Int(
            tokens
                .map(|t| t.parse().map_err(|_| bad(t)))
                .collect::<Result<_>>()?,
        )
    })
}

impl Reader<'_> {
    /// The values of a `<DataArray>`: `count` of them (tuples × components).
    fn array(&self, node: Node<'_, '_>, count: usize) -> Result<Values> {
        let name = node.attribute("Name").unwrap_or("");
        let context = |e: Error| {
            Error::new(
                e.kind,
                format!("line {}: array `{name}`: {}", line(node), e.message),
            )
        };
        self.values(node, count).map_err(context)
    }

    fn values(&self, node: Node<'_, '_>, count: usize) -> Result<Values> {
        let ty = node.attribute("type").unwrap_or("");
        let (size, float) =
            scalar(ty).ok_or_else(|| Error::io(format!("type \"{ty}\" is not supported")))?;
        let bytes = match node.attribute("format").unwrap_or("ascii") {
            "ascii" => {
                let values = ascii(node, ty, float)?;
                let len = match &values {
                    Values::Int(v) => v.len(),
                    Values::Float(v) => v.len(),
                };
                if len != count {
                    return Err(Error::io(format!(
                        "{len} values, the grid's size calls for {count}"
                    )));
                }
                return Ok(values);
            }
            "binary" => {
                let text: Vec<u8> = crate::io::gismo::text(node)
                    .bytes()
                    .filter(|b| !b.is_ascii_whitespace())
                    .collect();
                self.block(Source::Base64(&text), count, size)?
            }
            "appended" => {
                let appended = self.appended.as_ref().ok_or_else(|| {
                    Error::io("the array is appended but the file has no <AppendedData>")
                })?;
                let offset: usize = node
                    .attribute("offset")
                    .and_then(|o| o.trim().parse().ok())
                    .ok_or_else(|| Error::io("an appended array needs a valid offset"))?;
                let data = appended.data.get(offset..).ok_or_else(|| {
                    Error::io(format!("offset {offset} is past the appended data"))
                })?;
                let source = if appended.raw {
                    Source::Raw(data)
                } else {
                    Source::Base64(data)
                };
                self.block(source, count, size)?
            }
            other => return Err(Error::io(format!("format \"{other}\" is not supported"))),
        };
        convert(ty, &bytes, self.layout.big_endian)
    }

    /// The bytes of a binary block of `count` values of `size` bytes.
    fn block(&self, source: Source<'_>, count: usize, size: usize) -> Result<Vec<u8>> {
        let expected = count
            .checked_mul(size)
            .ok_or_else(|| Error::io("the array is too large"))?;
        self.layout.read(source, expected)
    }

    /// Appends one `<Piece>` to `grid`.
    fn piece(&self, piece: Node<'_, '_>, grid: &mut UnstructuredGrid, first: bool) -> Result<()> {
        let points = count_attribute(piece, "NumberOfPoints")?;
        let cells = count_attribute(piece, "NumberOfCells")?;
        let base = grid.point_count() as i64;
        let point_array = section_arrays(piece, "Points").next().ok_or_else(|| {
            Error::io(format!(
                "line {}: <Piece> has no <Points> array",
                line(piece)
            ))
        })?;
        if components(point_array)? != 3 {
            return Err(Error::io(format!(
                "line {}: points must have 3 components",
                line(point_array)
            )));
        }
        let xyz = self.array(point_array, values_of(points, 3)?)?.floats();
        let cell_array = |name: &str| {
            section_arrays(piece, "Cells")
                .find(|a| a.attribute("Name") == Some(name))
                .ok_or_else(|| Error::io(format!("line {}: no `{name}` cell array", line(piece))))
        };
        let types = self.array(cell_array("types")?, cells)?.ints("types")?;
        let offsets = self.array(cell_array("offsets")?, cells)?.ints("offsets")?;
        if offsets.windows(2).any(|w| w[1] < w[0]) || offsets.first().is_some_and(|&o| o < 0) {
            return Err(Error::io(
                "cell offsets must be non-negative and non-decreasing",
            ));
        }
        let length = offsets.last().map_or(0, |&o| o as usize);
        let conn = self
            .array(cell_array("connectivity")?, length)?
            .ints("connectivity")?;
        if let Some(&n) = conn.iter().find(|&&n| n < 0 || n as usize >= points) {
            return Err(Error::io(format!(
                "connectivity refers to point {n}, the piece has {points}"
            )));
        }
        let conn_base = grid.connectivity.len() as i64;
        grid.points.extend(xyz);
        grid.connectivity.extend(conn.iter().map(|&n| n + base));
        grid.offsets.extend(offsets.iter().map(|&o| o + conn_base));
        for t in types {
            grid.types.push(
                u8::try_from(t)
                    .map_err(|_| Error::io(format!("cell type {t} is not a VTK type")))?,
            );
        }
        for (section, tuples) in [("PointData", points), ("CellData", cells)] {
            for node in section_arrays(piece, section) {
                let array = DataArray {
                    name: node.attribute("Name").unwrap_or("").to_string(),
                    components: components(node)?,
                    values: Vec::new(),
                };
                let values = self
                    .array(node, values_of(tuples, array.components)?)?
                    .floats();
                if node.attribute("type") == Some("UInt8")
                    && !grid.uint8_arrays.contains(&array.name)
                {
                    grid.uint8_arrays.push(array.name.clone());
                }
                merge(grid, section == "PointData", array, values, first)?;
            }
        }
        Ok(())
    }
}

/// The number of values of `tuples` tuples of `components`.
fn values_of(tuples: usize, components: usize) -> Result<usize> {
    tuples.checked_mul(components).ok_or_else(|| {
        Error::io(format!(
            "{tuples} tuples of {components} values are too many"
        ))
    })
}

/// Adds one piece's values of an array to the grid's array of that name.
fn merge(
    grid: &mut UnstructuredGrid,
    points: bool,
    array: DataArray,
    values: Vec<f64>,
    first: bool,
) -> Result<()> {
    let arrays = if points {
        &mut grid.point_data
    } else {
        &mut grid.cell_data
    };
    match arrays.iter_mut().find(|a| a.name == array.name) {
        Some(a) if a.components == array.components && !first => a.values.extend(values),
        None if first => arrays.push(DataArray { values, ..array }),
        _ => {
            return Err(Error::io(format!(
                "the pieces of the file differ in array `{}`",
                array.name
            )))
        }
    }
    Ok(())
}

/// The `<DataArray>` children of section `name` (`Points`, `Cells`, `PointData`, `CellData`).
fn section_arrays<'a, 'input>(
    piece: Node<'a, 'input>,
    name: &'a str,
) -> impl Iterator<Item = Node<'a, 'input>> + 'a {
    children(piece, name).flat_map(|s| children(s, "DataArray"))
}

/// `NumberOfComponents` (1 when absent).
fn components(node: Node<'_, '_>) -> Result<usize> {
    match node.attribute("NumberOfComponents") {
        None => Ok(1),
        Some(_) => count_attribute(node, "NumberOfComponents").and_then(|c| {
            if c == 0 {
                Err(Error::io(format!(
                    "line {}: NumberOfComponents is 0",
                    line(node)
                )))
            } else {
                Ok(c)
            }
        }),
    }
}

/// A non-negative integer attribute.
fn count_attribute(node: Node<'_, '_>, key: &str) -> Result<usize> {
    node.attribute(key)
        .and_then(|v| v.trim().parse().ok())
        .ok_or_else(|| {
            Error::io(format!(
                "line {}: <{}> needs a non-negative integer {key}",
                line(node),
                node.tag_name().name()
            ))
        })
}
