//! VTK XML unstructured grids (`.vtu`): read in every storage VTK and meshio write — ASCII,
//! inline base64 (`binary`), appended raw or base64 data, uncompressed or zlib-compressed,
//! `UInt32` or `UInt64` headers, either byte order, several pieces — and written in any of them
//! ([`Format`]; zlib-compressed inline base64 by default).
//!
//! Why this is written here rather than taken from a crate: the one VTK crate, vtkio (0.7.0-rc2;
//! its last release, 0.6.3, is of 2021), reads the base64 storages but refuses appended raw
//! data — VTK's own default output — because its `Raw` encoding sits behind a cargo feature its
//! manifest does not declare. So the VTU layout (headers, blocks, offsets; `vtu/block.rs`) is written
//! here, on the crates that do the general work: roxmltree parses the XML, `base64` and `flate2`
//! decode and inflate the data.

mod block;
mod read;
mod write;

pub use read::{parse, read};
pub use write::{to_bytes, write, write_as};

/// How a `.vtu` file stores its arrays.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Encoding {
    /// Numbers as text (`format="ascii"`): large and slow, for reading by eye.
    Ascii,
    /// Base64 inside each `<DataArray>` (`format="binary"`): valid XML, read by every VTK reader
    /// and by meshio.
    Binary,
    /// Raw bytes in an `<AppendedData encoding="raw">` section: the smallest, VTK's default
    /// (not valid XML: some XML-based readers refuse it).
    Appended,
    /// Base64 in an `<AppendedData encoding="base64">` section.
    AppendedBase64,
}

impl Encoding {
    /// Every encoding, in the order above.
    pub fn all() -> [Encoding; 4] {
        use Encoding::*;
        [Ascii, Binary, Appended, AppendedBase64]
    }
}

/// The storage of a written `.vtu` file: an [`Encoding`] and, for the binary ones, zlib
/// compression (`compressor="vtkZLibDataCompressor"`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Format {
    /// How the arrays are stored.
    pub encoding: Encoding,
    /// zlib-compress the binary data (not with [`Encoding::Ascii`]).
    pub zlib: bool,
}

impl Default for Format {
    /// Inline base64, zlib-compressed: about a quarter of the ASCII size, valid XML, read by VTK,
    /// ParaView and meshio.
    fn default() -> Self {
        Format {
            encoding: Encoding::Binary,
            zlib: true,
        }
    }
}

impl Format {
    /// ASCII output.
    pub const ASCII: Format = Format {
        encoding: Encoding::Ascii,
        zlib: false,
    };
}

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
    /// Names of the point or cell data arrays stored as `UInt8` (masks, levels: integers in
    /// 0..=255); the others are written as `Float64`. The reader lists the `UInt8` arrays it
    /// read.
    pub uint8_arrays: Vec<String>,
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

#[cfg(test)]
mod tests {
    use super::*;

    fn grid() -> UnstructuredGrid {
        UnstructuredGrid {
            points: vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.1],
            connectivity: vec![0, 1, 2, 3],
            offsets: vec![4],
            types: vec![9],
            point_data: vec![
                DataArray {
                    name: "m".into(),
                    components: 1,
                    values: vec![1.0, 2.0, 3.0, 0.0],
                },
                DataArray {
                    name: "v<&>".into(),
                    components: 2,
                    values: vec![1.5, -2.0, 3e-300, 0.1, f64::MAX, 7.0, 8.0, -0.0],
                },
            ],
            cell_data: vec![DataArray {
                name: "quality".into(),
                components: 1,
                values: vec![0.75],
            }],
            uint8_arrays: vec!["m".into()],
        }
    }

    #[test]
    fn every_format_round_trips() {
        let g = grid();
        for encoding in Encoding::all() {
            for zlib in [false, true] {
                let f = Format { encoding, zlib };
                match to_bytes(&g, f) {
                    Ok(bytes) => assert_eq!(parse(&bytes).unwrap(), g, "{f:?}"),
                    Err(e) => assert!(encoding == Encoding::Ascii && zlib, "{f:?}: {e}"),
                }
            }
        }
    }

    #[test]
    fn bad_files_are_refused_with_a_message() {
        let e = parse(b"<VTKFile type=\"PolyData\"/>").unwrap_err();
        assert!(e.message.contains("UnstructuredGrid"), "{}", e.message);
        let text = String::from_utf8(to_bytes(&grid(), Format::ASCII).unwrap()).unwrap();
        let e = parse(text.replace("0 1 2 3", "0 1 2 7").as_bytes()).unwrap_err();
        assert!(e.message.contains("point 7"), "{}", e.message);
        let e = parse(
            text.replace(
                "header_type=\"UInt64\"",
                "compressor=\"vtkLZ4DataCompressor\"",
            )
            .as_bytes(),
        )
        .unwrap_err();
        assert!(e.message.contains("vtkLZ4DataCompressor"), "{}", e.message);
        let mut g = grid();
        g.point_data[0].values[0] = 0.5;
        assert!(to_bytes(&g, Format::default()).is_err());
    }
}
