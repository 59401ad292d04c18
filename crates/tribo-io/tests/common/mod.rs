//! A reader of what `tribo_io::vtk::AppendedFile` writes, for the tests: a slow, obviously
//! correct parse of the XML header (every `DataArray`'s attributes) and of the appended block
//! (each array's byte count at its offset), checking the structure on the way. Written apart
//! from the writer (no code shared with it).
#![allow(dead_code)]

/// One array as read back.
#[derive(Debug, Clone)]
pub struct Array {
    /// `type` attribute.
    pub kind: String,
    /// `Name` attribute (empty for Points).
    pub name: String,
    /// `NumberOfComponents`.
    pub components: usize,
    /// The raw little-endian bytes.
    pub bytes: Vec<u8>,
}

impl Array {
    /// The values as f64 (Float64 only).
    pub fn f64s(&self) -> Vec<f64> {
        assert_eq!(self.kind, "Float64");
        self.bytes
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
            .collect()
    }
    /// The values as i64 (Int64 only).
    pub fn i64s(&self) -> Vec<i64> {
        assert_eq!(self.kind, "Int64");
        self.bytes
            .chunks_exact(8)
            .map(|c| i64::from_le_bytes(c.try_into().unwrap()))
            .collect()
    }
}

fn attr(tag: &str, key: &str) -> Option<String> {
    let pat = format!(" {key}=\"");
    let start = tag.find(&pat)? + pat.len();
    let end = tag[start..].find('"')? + start;
    Some(tag[start..end].to_string())
}

/// The XML header (text before the `_` marker), the arrays in file order.
pub fn parse(file: &[u8]) -> (String, Vec<Array>) {
    let marker = b"<AppendedData encoding=\"raw\">\n   _";
    let at = file
        .windows(marker.len())
        .position(|w| w == marker)
        .expect("an AppendedData raw block");
    let header = std::str::from_utf8(&file[..at]).expect("XML header is UTF-8");
    assert!(header.starts_with("<?xml version=\"1.0\"?>\n<VTKFile "));
    assert!(header.contains("byte_order=\"LittleEndian\""));
    assert!(header.contains("header_type=\"UInt64\""));
    let data = &file[at + marker.len()..];
    let tail = b"\n  </AppendedData>\n</VTKFile>\n";
    assert!(data.ends_with(tail), "file ends with the closing tags");
    let data = &data[..data.len() - tail.len()];
    // Every element opened is closed (or self-closing), in order.
    let mut stack: Vec<String> = Vec::new();
    let mut arrays = Vec::new();
    let mut expected_offset = 0usize;
    let mut rest = header;
    while let Some(open) = rest.find('<') {
        let close = rest[open..].find('>').expect("tag closed") + open;
        let tag = &rest[open + 1..close];
        rest = &rest[close + 1..];
        if tag.starts_with('?') {
            continue;
        }
        if let Some(name) = tag.strip_prefix('/') {
            assert_eq!(stack.pop().as_deref(), Some(name), "closing tag matches");
            continue;
        }
        let name = tag.split_whitespace().next().unwrap().to_string();
        if name == "DataArray" {
            assert!(tag.ends_with('/'), "appended arrays are empty elements");
            assert_eq!(attr(tag, "format").as_deref(), Some("appended"));
            let offset: usize = attr(tag, "offset").unwrap().parse().unwrap();
            assert_eq!(offset, expected_offset, "offsets follow each other");
            let n = u64::from_le_bytes(data[offset..offset + 8].try_into().unwrap()) as usize;
            let bytes = data[offset + 8..offset + 8 + n].to_vec();
            expected_offset = offset + 8 + n;
            arrays.push(Array {
                kind: attr(tag, "type").unwrap(),
                name: attr(tag, "Name").unwrap_or_default(),
                components: attr(tag, "NumberOfComponents").unwrap().parse().unwrap(),
                bytes,
            });
        } else if !tag.ends_with('/') {
            stack.push(name);
        }
    }
    assert_eq!(
        expected_offset,
        data.len(),
        "the block holds the arrays, no more"
    );
    // Open: VTKFile (closed after the block).
    assert_eq!(stack, vec!["VTKFile".to_string()]);
    (header.to_string(), arrays)
}
