//! VTK XML unstructured grids (`.vtu`) in ASCII format: enough to read the meshes the library
//! relocates and to write results that ParaView and VTK read.
//!
//! Binary and compressed `.vtu` files are refused with a clear message; the C++ example reads
//! every flavour through VTK itself.

use std::fmt::Write as _;
use std::path::Path;

use crate::error::{Error, Result};

/// A named data array with `components` values per tuple.
#[derive(Clone, Debug, PartialEq)]
pub struct DataArray {
    /// The array's `Name`.
    pub name: String,
    /// Values per tuple (`NumberOfComponents`, 1 when absent).
    pub components: usize,
    /// The values, tuple after tuple.
    pub values: Vec<f64>,
}

/// An unstructured grid: points, cells (VTK connectivity, offsets, types), point and cell data.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct UnstructuredGrid {
    /// `#points × 3` coordinates.
    pub points: Vec<f64>,
    /// Node indices of all cells, concatenated.
    pub connectivity: Vec<i64>,
    /// End of each cell in `connectivity`.
    pub offsets: Vec<i64>,
    /// VTK cell type of each cell.
    pub types: Vec<u8>,
    /// Point data arrays.
    pub point_data: Vec<DataArray>,
    /// Cell data arrays.
    pub cell_data: Vec<DataArray>,
}

impl UnstructuredGrid {
    /// The point data array called `name`.
    pub fn point_array(&self, name: &str) -> Option<&DataArray> {
        self.point_data.iter().find(|a| a.name == name)
    }

    /// Number of points.
    pub fn point_count(&self) -> usize {
        self.points.len() / 3
    }
}

/// Reads an ASCII `.vtu` file.
pub fn read(path: &Path) -> Result<UnstructuredGrid> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| Error::io(format!("cannot read {}: {e}", path.display())))?;
    parse(&text).map_err(|e| Error::io(format!("{}: {}", path.display(), e.message)))
}

/// Value of attribute `name` in the tag text `tag`.
fn attribute<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let start = tag.find(&key)? + key.len();
    let end = tag[start..].find('"')? + start;
    Some(&tag[start..end])
}

/// Parses the text of an ASCII `.vtu` file.
pub fn parse(text: &str) -> Result<UnstructuredGrid> {
    if !text.contains("type=\"UnstructuredGrid\"") {
        return Err(Error::io("not a VTK UnstructuredGrid file"));
    }
    let mut grid = UnstructuredGrid::default();
    let mut section = "";
    let mut rest = text;
    while let Some(open) = rest.find('<') {
        let close = rest[open..]
            .find('>')
            .ok_or_else(|| Error::io("unterminated tag"))?
            + open;
        let tag = &rest[open..=close];
        rest = &rest[close + 1..];
        for name in ["PointData", "CellData", "Points", "Cells"] {
            if tag.starts_with(&format!("<{name}")) {
                section = name;
            }
            if tag.starts_with(&format!("</{name}")) {
                section = "";
            }
        }
        if tag.starts_with("<AppendedData") {
            return Err(Error::io(
                "appended (binary) data is not supported; save the file as ASCII",
            ));
        }
        if !tag.starts_with("<DataArray") {
            continue;
        }
        let name = attribute(tag, "Name").unwrap_or("").to_string();
        if attribute(tag, "format") != Some("ascii") {
            return Err(Error::io(format!(
                "array `{name}` is not ASCII; only ASCII .vtu files are read here"
            )));
        }
        let components = attribute(tag, "NumberOfComponents")
            .map(|c| {
                c.parse::<usize>()
                    .map_err(|_| Error::io(format!("bad NumberOfComponents in `{name}`")))
            })
            .transpose()?
            .unwrap_or(1);
        let body_end = if tag.ends_with("/>") {
            0
        } else {
            rest.find("</DataArray>")
                .ok_or_else(|| Error::io(format!("array `{name}` is not closed")))?
        };
        // Values stop at the first nested element (VTK writes `<InformationKey>` there).
        let values_end = rest[..body_end].find('<').unwrap_or(body_end);
        let values = rest[..values_end]
            .split_ascii_whitespace()
            .map(|t| {
                t.parse::<f64>()
                    .map_err(|_| Error::io(format!("bad number `{t}` in array `{name}`")))
            })
            .collect::<Result<Vec<f64>>>()?;
        rest = &rest[body_end..];
        let integers = || values.iter().map(|&v| v as i64).collect::<Vec<i64>>();
        match (section, name.as_str()) {
            ("Points", _) => {
                if components != 3 {
                    return Err(Error::io("points must have 3 components"));
                }
                grid.points = values;
            }
            ("Cells", "connectivity") => grid.connectivity = integers(),
            ("Cells", "offsets") => grid.offsets = integers(),
            ("Cells", "types") => grid.types = values.iter().map(|&v| v as u8).collect(),
            ("PointData", _) => grid.point_data.push(DataArray {
                name,
                components,
                values,
            }),
            ("CellData", _) => grid.cell_data.push(DataArray {
                name,
                components,
                values,
            }),
            _ => {}
        }
    }
    if grid.offsets.len() != grid.types.len() {
        return Err(Error::io("offsets and types differ in length"));
    }
    Ok(grid)
}

fn write_array(
    out: &mut String,
    type_name: &str,
    name: &str,
    components: usize,
    values: impl Iterator<Item = String>,
) {
    let _ = writeln!(
        out,
        "        <DataArray type=\"{type_name}\" Name=\"{name}\" NumberOfComponents=\"{components}\" format=\"ascii\">"
    );
    for (i, v) in values.enumerate() {
        out.push_str(if i % 6 == 0 { "\n          " } else { " " });
        out.push_str(&v);
    }
    out.push_str("\n        </DataArray>\n");
}

/// Formats a grid as an ASCII `.vtu` document.
pub fn format(grid: &UnstructuredGrid) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "<?xml version=\"1.0\"?>");
    let _ = writeln!(
        out,
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">"
    );
    let _ = writeln!(out, "  <UnstructuredGrid>");
    let _ = writeln!(
        out,
        "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">",
        grid.point_count(),
        grid.types.len()
    );
    let float = |v: &f64| format!("{v:e}");
    for (tag, arrays) in [
        ("PointData", &grid.point_data),
        ("CellData", &grid.cell_data),
    ] {
        let _ = writeln!(out, "      <{tag}>");
        for a in arrays {
            write_array(
                &mut out,
                "Float64",
                &a.name,
                a.components,
                a.values.iter().map(float),
            );
        }
        let _ = writeln!(out, "      </{tag}>");
    }
    let _ = writeln!(out, "      <Points>");
    write_array(
        &mut out,
        "Float64",
        "Points",
        3,
        grid.points.iter().map(float),
    );
    let _ = writeln!(out, "      </Points>\n      <Cells>");
    let int = |v: &i64| v.to_string();
    write_array(
        &mut out,
        "Int64",
        "connectivity",
        1,
        grid.connectivity.iter().map(int),
    );
    write_array(
        &mut out,
        "Int64",
        "offsets",
        1,
        grid.offsets.iter().map(int),
    );
    write_array(
        &mut out,
        "UInt8",
        "types",
        1,
        grid.types.iter().map(|t| t.to_string()),
    );
    let _ = writeln!(
        out,
        "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>"
    );
    out
}

/// Writes a grid as an ASCII `.vtu` file.
pub fn write(path: &Path, grid: &UnstructuredGrid) -> Result<()> {
    std::fs::write(path, format(grid))
        .map_err(|e| Error::io(format!("cannot write {}: {e}", path.display())))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip() {
        let grid = UnstructuredGrid {
            points: vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0],
            connectivity: vec![0, 1, 2, 3],
            offsets: vec![4],
            types: vec![9],
            point_data: vec![DataArray {
                name: "m".into(),
                components: 1,
                values: vec![1.0, 2.0, 3.0, 0.5],
            }],
            cell_data: vec![DataArray {
                name: "quality".into(),
                components: 1,
                values: vec![0.75],
            }],
        };
        assert_eq!(parse(&format(&grid)).unwrap(), grid);
    }

    #[test]
    fn binary_files_are_refused_with_a_message() {
        let text = "<VTKFile type=\"UnstructuredGrid\"><Points><DataArray type=\"Float64\" Name=\"Points\" format=\"binary\">AAAA</DataArray></Points></VTKFile>";
        let e = parse(text).unwrap_err();
        assert!(e.message.contains("ASCII"));
    }
}
