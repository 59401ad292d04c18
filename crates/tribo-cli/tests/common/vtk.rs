//! A reader of tribo's binary VTK XML files (raw appended data, UInt64 headers) for the
//! tests: a slow, deliberately plain parse, independent of the writer. It checks that the XML
//! header is well formed (balanced, properly nested tags, quoted attributes), that every
//! `DataArray` is appended with offsets that follow each other with no gap or overlap, that
//! each array's byte count matches its type, component count and the piece's size, and that
//! the appended block ends exactly after the last array.

#![allow(dead_code)] // each test crate uses part of the reader

use std::path::Path;

/// One `DataArray` read back.
#[derive(Debug, Clone)]
pub struct Array {
    /// `Name` (empty for the Points array).
    pub name: String,
    /// `type`: Float64, Int64, Int32, UInt8.
    pub kind: String,
    /// `NumberOfComponents`.
    pub components: usize,
    /// The enclosing element: `PointData`, `CellData`, `Points`, `Cells`.
    pub parent: String,
    /// Raw little-endian bytes.
    pub bytes: Vec<u8>,
}

impl Array {
    /// Float64 values.
    pub fn f64s(&self) -> Vec<f64> {
        assert_eq!(self.kind, "Float64", "{}", self.name);
        self.bytes
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
            .collect()
    }

    /// Int64 values.
    pub fn i64s(&self) -> Vec<i64> {
        assert_eq!(self.kind, "Int64", "{}", self.name);
        self.bytes
            .chunks_exact(8)
            .map(|c| i64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
            .collect()
    }

    /// Number of tuples.
    pub fn tuples(&self) -> usize {
        let size = match self.kind.as_str() {
            "Float64" | "Int64" => 8,
            "Int32" => 4,
            "UInt8" => 1,
            k => panic!("unexpected type {k}"),
        };
        assert_eq!(
            self.bytes.len() % (size * self.components),
            0,
            "{}",
            self.name
        );
        self.bytes.len() / (size * self.components)
    }
}

/// A file read back: the XML header and the arrays in file order.
#[derive(Debug)]
pub struct VtkFile {
    /// The XML before the appended data.
    pub header: String,
    /// The arrays.
    pub arrays: Vec<Array>,
}

impl VtkFile {
    /// The array named `name`.
    pub fn get(&self, name: &str) -> &Array {
        self.arrays
            .iter()
            .find(|a| a.name == name)
            .unwrap_or_else(|| panic!("no array {name}"))
    }

    /// Names of the arrays under `parent` (`PointData`, `CellData`).
    pub fn names(&self, parent: &str) -> Vec<&str> {
        self.arrays
            .iter()
            .filter(|a| a.parent == parent)
            .map(|a| a.name.as_str())
            .collect()
    }
}

fn attr(tag: &str, key: &str) -> Option<String> {
    let pat = format!(" {key}=\"");
    let start = tag.find(&pat)? + pat.len();
    let len = tag[start..].find('"')?;
    Some(tag[start..start + len].to_string())
}

fn extent_points_cells(extent: &str) -> (usize, usize) {
    let e: Vec<i64> = extent
        .split_whitespace()
        .map(|t| t.parse().unwrap())
        .collect();
    assert_eq!(e.len(), 6, "extent {extent}");
    let n: Vec<usize> = (0..3).map(|k| (e[2 * k + 1] - e[2 * k]) as usize).collect();
    let points = (n[0] + 1) * (n[1] + 1) * (n[2] + 1);
    let cells = n.iter().map(|&m| m.max(1)).product();
    (points, cells)
}

/// Reads and checks `path`.
pub fn read(path: &Path) -> VtkFile {
    let file = std::fs::read(path).unwrap();
    let marker = b"<AppendedData encoding=\"raw\">";
    let at = file
        .windows(marker.len())
        .position(|w| w == marker)
        .unwrap_or_else(|| panic!("{}: no raw AppendedData", path.display()));
    // Between the element's '>' and the data: whitespace, then the '_' marker.
    let mut start = at + marker.len();
    while file[start].is_ascii_whitespace() {
        start += 1;
    }
    assert_eq!(file[start], b'_', "the appended data starts with '_'");
    let data_start = start + 1;
    let header = std::str::from_utf8(&file[..at]).expect("XML header is UTF-8");
    assert!(header.starts_with("<?xml version=\"1.0\"?>"));
    let root = &header[header.find("<VTKFile").expect("VTKFile element")..];
    let root_tag = &root[..root.find('>').unwrap()];
    assert_eq!(
        attr(root_tag, "byte_order").as_deref(),
        Some("LittleEndian")
    );
    assert_eq!(attr(root_tag, "header_type").as_deref(), Some("UInt64"));
    let kind = attr(root_tag, "type").unwrap();

    // Walk the tags.
    let mut stack: Vec<String> = Vec::new();
    let mut arrays = Vec::new();
    let mut offsets = Vec::new();
    let (mut points, mut cells) = (0usize, 0usize);
    let mut rest = &header[header.find("?>").unwrap() + 2..];
    while let Some(open) = rest.find('<') {
        assert!(rest[..open].trim().is_empty(), "text outside elements");
        let close = open + rest[open..].find('>').expect("unclosed tag");
        let tag = &rest[open + 1..close];
        rest = &rest[close + 1..];
        assert_eq!(
            tag.matches('"').count() % 2,
            0,
            "unbalanced quotes in <{tag}>"
        );
        if let Some(name) = tag.strip_prefix('/') {
            assert_eq!(stack.pop().as_deref(), Some(name.trim()), "mismatched tags");
            continue;
        }
        let self_closing = tag.ends_with('/');
        let name = tag.split_whitespace().next().unwrap().trim_end_matches('/');
        if name == "Piece" {
            if let Some(e) = attr(tag, "Extent") {
                (points, cells) = extent_points_cells(&e);
            } else {
                points = attr(tag, "NumberOfPoints").unwrap().parse().unwrap();
                cells = attr(tag, "NumberOfCells").unwrap().parse().unwrap();
            }
        }
        if name == "DataArray" {
            assert!(self_closing, "appended DataArray elements are empty");
            assert_eq!(attr(tag, "format").as_deref(), Some("appended"));
            offsets.push(attr(tag, "offset").unwrap().parse::<usize>().unwrap());
            arrays.push(Array {
                name: attr(tag, "Name").unwrap_or_default(),
                kind: attr(tag, "type").unwrap(),
                components: attr(tag, "NumberOfComponents").map_or(1, |c| c.parse().unwrap()),
                parent: stack.last().cloned().unwrap_or_default(),
                bytes: Vec::new(),
            });
        }
        if !self_closing {
            stack.push(name.to_string());
        }
    }
    assert_eq!(stack, ["VTKFile"], "only VTKFile open at the data");
    let data = &file[data_start..];
    let mut pos = 0usize;
    for (a, &off) in arrays.iter_mut().zip(&offsets) {
        assert_eq!(off, pos, "{}: offset {off}, expected {pos}", a.name);
        let n = u64::from_le_bytes(data[pos..pos + 8].try_into().unwrap()) as usize;
        a.bytes = data[pos + 8..pos + 8 + n].to_vec();
        pos += 8 + n;
    }
    let closing = std::str::from_utf8(&data[pos..]).expect("closing tags after the data");
    let closing: Vec<&str> = closing.split_whitespace().collect();
    assert_eq!(closing, ["</AppendedData>", "</VTKFile>"]);
    // Sizes match the piece.
    for a in &arrays {
        let expected = match (kind.as_str(), a.parent.as_str(), a.name.as_str()) {
            (_, "PointData" | "Points", _) => points,
            (_, "CellData", _) => cells,
            ("UnstructuredGrid", "Cells", "connectivity") => 3 * cells,
            ("UnstructuredGrid", "Cells", _) => cells,
            (k, p, n) => panic!("unexpected array {n} under {p} in {k}"),
        };
        assert_eq!(a.tuples(), expected, "{}: tuples", a.name);
    }
    VtkFile {
        header: header.to_string(),
        arrays,
    }
}
