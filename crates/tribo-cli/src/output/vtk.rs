//! VTK XML files with their arrays in one raw appended block (binary, little-endian), the
//! layout ParaView and VTK's own readers expect:
//!
//! ```text
//! <VTKFile type="ImageData" version="1.0" byte_order="LittleEndian" header_type="UInt64">
//!   ... <DataArray type="Float64" Name="p" format="appended" offset="0"/> ...
//!   <AppendedData encoding="raw">
//!    _[u64 byte count][bytes of array 0][u64 byte count][bytes of array 1]...
//!   </AppendedData>
//! </VTKFile>
//! ```
//!
//! Each array's `offset` is the position of its byte-count header after the `_` marker
//! (VTK File Formats, "XML File Formats", appended data section). A 15-77 MB ASCII file
//! becomes about 8 bytes per value.

/// A VTK XML file being built: the XML part and the appended block.
pub struct AppendedFile {
    xml: String,
    data: Vec<u8>,
}

/// A numeric type VTK reads from the appended block.
pub trait VtkScalar: Copy {
    /// VTK's type name (`Float64`, ...).
    const NAME: &'static str;
    /// Little-endian bytes.
    fn put(self, out: &mut Vec<u8>);
}

impl VtkScalar for f64 {
    const NAME: &'static str = "Float64";
    fn put(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

impl VtkScalar for i64 {
    const NAME: &'static str = "Int64";
    fn put(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

impl VtkScalar for i32 {
    const NAME: &'static str = "Int32";
    fn put(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

impl VtkScalar for u8 {
    const NAME: &'static str = "UInt8";
    fn put(self, out: &mut Vec<u8>) {
        out.push(self);
    }
}

impl AppendedFile {
    /// Starts a file of the VTK dataset type `kind` (`ImageData`, `UnstructuredGrid`).
    pub fn new(kind: &str) -> Self {
        AppendedFile {
            xml: format!(
                "<?xml version=\"1.0\"?>\n<VTKFile type=\"{kind}\" version=\"1.0\" \
                 byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
            ),
            data: Vec::new(),
        }
    }

    /// Appends XML text (elements other than data arrays).
    pub fn xml(&mut self, text: &str) {
        self.xml.push_str(text);
    }

    /// A `DataArray` element; its values go to the appended block. `name` empty: no `Name`
    /// attribute (the `Points` array).
    pub fn array<T: VtkScalar>(
        &mut self,
        indent: &str,
        name: &str,
        components: usize,
        values: impl ExactSizeIterator<Item = T>,
    ) {
        let offset = self.data.len();
        let name_attr = if name.is_empty() {
            String::new()
        } else {
            format!(" Name=\"{name}\"")
        };
        self.xml.push_str(&format!(
            "{indent}<DataArray type=\"{}\"{name_attr} NumberOfComponents=\"{components}\" \
             format=\"appended\" offset=\"{offset}\"/>\n",
            T::NAME
        ));
        let bytes = values.len() * std::mem::size_of::<T>();
        self.data.extend_from_slice(&(bytes as u64).to_le_bytes());
        self.data.reserve(bytes);
        for v in values {
            v.put(&mut self.data);
        }
    }

    /// The whole file: the XML, then the appended block, then the closing tags.
    pub fn finish(self) -> Vec<u8> {
        let mut out = self.xml.into_bytes();
        out.extend_from_slice(b"  <AppendedData encoding=\"raw\">\n   _");
        out.extend_from_slice(&self.data);
        out.extend_from_slice(b"\n  </AppendedData>\n</VTKFile>\n");
        out
    }
}

/// A reader of what [`AppendedFile`] writes, for the tests: a slow, obviously correct parse
/// of the XML header (every `DataArray`'s attributes) and of the appended block (each
/// array's byte count at its offset), checking the structure on the way.
#[cfg(test)]
pub mod read {
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
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_bit_equal() {
        let a = [1.5, -0.0, f64::MIN_POSITIVE, 1e300, -3.25e-7];
        let mut f = AppendedFile::new("ImageData");
        f.xml("  <ImageData>\n    <Piece>\n      <PointData>\n");
        f.array("        ", "a_Pa", 1, a.iter().copied());
        f.array("        ", "k", 1, [0i64, 3, -7].into_iter());
        f.array("        ", "t", 1, [5u8, 5].into_iter());
        f.xml("      </PointData>\n    </Piece>\n  </ImageData>\n");
        let (header, arrays) = read::parse(&f.finish());
        assert!(header.contains("offset=\"0\""));
        assert_eq!(arrays.len(), 3);
        let back = arrays[0].f64s();
        assert!(back.iter().zip(&a).all(|(x, y)| x.to_bits() == y.to_bits()));
        assert_eq!(arrays[1].i64s(), vec![0, 3, -7]);
        assert_eq!(arrays[2].bytes, vec![5, 5]);
        assert_eq!(arrays[2].kind, "UInt8");
        assert!(arrays.iter().all(|a| a.components == 1));
        // Offsets: 8 + 40, then 8 + 24.
        assert!(header.contains("offset=\"48\""));
        assert!(header.contains("offset=\"80\""));
    }
}
