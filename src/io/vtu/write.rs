//! Writing `.vtu` files in ASCII, inline base64, or appended raw or base64 data, binary data
//! optionally zlib-compressed (little-endian, `UInt64` headers).

use std::fmt::Write as _;
use std::path::Path;

use super::block;
use super::{Encoding, Format, UnstructuredGrid};
use crate::error::{Error, Result};

/// One array to write: its attributes and little-endian bytes (or ASCII text).
struct Array<'a> {
    name: &'a str,
    ty: &'static str,
    components: usize,
    bytes: Vec<u8>,
    ascii: String,
}

fn floats<'a>(name: &'a str, components: usize, values: &[f64], f: Format) -> Array<'a> {
    let ascii = if f.encoding == Encoding::Ascii {
        join(values.iter().map(|v| format!("{v:?}")))
    } else {
        String::new()
    };
    let bytes = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    Array {
        name,
        ty: "Float64",
        components,
        bytes,
        ascii,
    }
}

fn join(items: impl Iterator<Item = String>) -> String {
    let mut out = String::new();
    for (i, item) in items.enumerate() {
        out.push_str(if i % 6 == 0 { "\n          " } else { " " });
        out.push_str(&item);
    }
    out.push_str("\n        ");
    out
}

/// XML-escapes an attribute value.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Point or cell data arrays (`list` names which in messages).
fn data_arrays<'a>(
    grid: &UnstructuredGrid,
    list: &str,
    arrays: &'a [super::DataArray],
    f: Format,
) -> Result<Vec<Array<'a>>> {
    arrays
        .iter()
        .map(|a| {
            if !grid.uint8_arrays.contains(&a.name) {
                return Ok(floats(&a.name, a.components, &a.values, f));
            }
            let bytes = a
                .values
                .iter()
                .map(|&v| {
                    (v.fract() == 0.0 && (0.0..=255.0).contains(&v))
                        .then_some(v as u8)
                        .ok_or_else(|| {
                            Error::invalid(format!(
                                "{list} array `{}` is written as UInt8 but holds {v}",
                                a.name
                            ))
                        })
                })
                .collect::<Result<Vec<u8>>>()?;
            Ok(uint8(&a.name, a.components, bytes, f))
        })
        .collect()
}

/// The arrays of a grid by section, in the order they are written.
fn arrays(grid: &UnstructuredGrid, f: Format) -> Result<Vec<(&'static str, Vec<Array<'_>>)>> {
    let data = |list, arrays| data_arrays(grid, list, arrays, f);
    let ints = |name: &'static str, values: &[i64]| Array {
        name,
        ty: "Int64",
        components: 1,
        bytes: values.iter().flat_map(|v| v.to_le_bytes()).collect(),
        ascii: if f.encoding == Encoding::Ascii {
            join(values.iter().map(|v| v.to_string()))
        } else {
            String::new()
        },
    };
    Ok(vec![
        ("PointData", data("point", &grid.point_data)?),
        ("CellData", data("cell", &grid.cell_data)?),
        ("Points", vec![floats("Points", 3, &grid.points, f)]),
        (
            "Cells",
            vec![
                ints("connectivity", &grid.connectivity),
                ints("offsets", &grid.offsets),
                uint8("types", 1, grid.types.clone(), f),
            ],
        ),
    ])
}

fn uint8(name: &str, components: usize, bytes: Vec<u8>, f: Format) -> Array<'_> {
    let ascii = if f.encoding == Encoding::Ascii {
        join(bytes.iter().map(|v| v.to_string()))
    } else {
        String::new()
    };
    Array {
        name,
        ty: "UInt8",
        components,
        bytes,
        ascii,
    }
}

/// Writes a grid as a `.vtu` file in the default [`Format`] (zlib-compressed base64).
pub fn write(path: &Path, grid: &UnstructuredGrid) -> Result<()> {
    write_as(path, grid, Format::default())
}

/// Writes a grid as a `.vtu` file in format `format`.
pub fn write_as(path: &Path, grid: &UnstructuredGrid, format: Format) -> Result<()> {
    let bytes = to_bytes(grid, format)?;
    std::fs::write(path, bytes)
        .map_err(|e| Error::io(format!("cannot write {}: {e}", path.display())))
}

/// The bytes of a `.vtu` document of `grid` in format `f`.
pub fn to_bytes(grid: &UnstructuredGrid, f: Format) -> Result<Vec<u8>> {
    if f.zlib && f.encoding == Encoding::Ascii {
        return Err(Error::invalid("ASCII .vtu files cannot be compressed"));
    }
    let mut xml = String::new();
    let compressor = if f.zlib {
        " compressor=\"vtkZLibDataCompressor\""
    } else {
        ""
    };
    let _ = writeln!(xml, "<?xml version=\"1.0\"?>");
    let _ = writeln!(
        xml,
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\"{compressor}>"
    );
    let _ = writeln!(
        xml,
        "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">",
        grid.point_count(),
        grid.types.len()
    );
    let mut appended: Vec<u8> = Vec::new();
    for (section, list) in arrays(grid, f)? {
        let _ = writeln!(xml, "      <{section}>");
        for a in list {
            let _ = write!(
                xml,
                "        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"{}\"",
                a.ty,
                escape(a.name),
                a.components,
                match f.encoding {
                    Encoding::Ascii => "ascii",
                    Encoding::Binary => "binary",
                    Encoding::Appended | Encoding::AppendedBase64 => "appended",
                }
            );
            match f.encoding {
                Encoding::Ascii => {
                    let _ = writeln!(xml, ">{}</DataArray>", a.ascii);
                }
                Encoding::Binary => {
                    let (header, payload) = block::pack(&a.bytes, f.zlib)?;
                    let text = block::base64(&header, &payload, f.zlib);
                    let _ = writeln!(xml, ">\n          {text}\n        </DataArray>");
                }
                Encoding::Appended | Encoding::AppendedBase64 => {
                    let _ = writeln!(xml, " offset=\"{}\"/>", appended.len());
                    let (header, payload) = block::pack(&a.bytes, f.zlib)?;
                    if f.encoding == Encoding::Appended {
                        appended.extend(header);
                        appended.extend(payload);
                    } else {
                        appended.extend(block::base64(&header, &payload, f.zlib).into_bytes());
                    }
                }
            }
        }
        let _ = writeln!(xml, "      </{section}>");
    }
    let _ = writeln!(xml, "    </Piece>\n  </UnstructuredGrid>");
    let mut out = xml.into_bytes();
    if matches!(f.encoding, Encoding::Appended | Encoding::AppendedBase64) {
        let encoding = if f.encoding == Encoding::Appended {
            "raw"
        } else {
            "base64"
        };
        out.extend(format!("  <AppendedData encoding=\"{encoding}\">\n   _").into_bytes());
        out.extend(appended);
        out.extend(b"\n  </AppendedData>\n");
    }
    out.extend(b"</VTKFile>\n");
    Ok(out)
}
