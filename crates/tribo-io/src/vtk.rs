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
//!
//! The files of the runs: [`surface_vti`] (`fields.vti`), [`stress_vti`] (`stress.vti`) and
//! [`bem_vtu`] (`fields_<step>.vtu`).

use tribo::SurfaceGrid;
use tribo_case::bem::pipeline::Variant;
use tribo_case::pipeline::Stress;

/// A VTK XML file being built: the XML part and the appended block.
#[derive(Debug, Clone, Default)]
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

/// VTK XML ImageData (`.vti`, binary: raw appended little-endian data) with one cell per
/// element: the image's points are the element corners, `WholeExtent = 0 nx 0 ny 0 0`,
/// `Origin` the window's lower-left corner, `Spacing = dx dy dx`; each named array becomes a
/// `CellData` array (x varying fastest, the grid's layout, which is VTK's cell order).
pub fn surface_vti(grid: &SurfaceGrid, arrays: &[(&str, &[f64])]) -> Vec<u8> {
    let (x0, y0) = grid.origin();
    let (nx, ny) = (grid.nx(), grid.ny());
    let mut f = AppendedFile::new("ImageData");
    f.xml(&format!(
        "  <ImageData WholeExtent=\"0 {nx} 0 {ny} 0 0\" Origin=\"{x0:e} {y0:e} 0\" Spacing=\"{:e} {:e} {:e}\">\n",
        grid.dx(),
        grid.dy(),
        grid.dx()
    ));
    f.xml(&format!("    <Piece Extent=\"0 {nx} 0 {ny} 0 0\">\n"));
    let first = arrays.first().map_or("", |a| a.0);
    f.xml(&format!("      <CellData Scalars=\"{first}\">\n"));
    for (name, values) in arrays {
        f.array("        ", name, 1, values.iter().copied());
    }
    f.xml("      </CellData>\n    </Piece>\n  </ImageData>\n");
    f.finish()
}

/// The mean spacing of equally spaced coordinates (1 for fewer than two).
fn spacing(v: &[f64]) -> f64 {
    match v {
        [first, .., last] => (last - first) / (v.len() - 1) as f64,
        _ => 1.0,
    }
}

/// VTK XML ImageData over the stress field's points (uniform spacing; binary, raw appended
/// data): `Origin = (-hx, -hy, 0)`, z the depth into the body; every array as `PointData`
/// (`-0` written as `0`).
pub fn stress_vti(st: &Stress, arrays: &[(String, Vec<f64>)]) -> Vec<u8> {
    let g = &st.field.grid;
    let (nx, ny, nz) = (g.x.len(), g.y.len(), g.z.len());
    let mut f = AppendedFile::new("ImageData");
    let (x0, y0) = (
        g.x.first().copied().unwrap_or(0.0),
        g.y.first().copied().unwrap_or(0.0),
    );
    let ext = format!(
        "0 {} 0 {} 0 {}",
        nx.saturating_sub(1),
        ny.saturating_sub(1),
        nz.saturating_sub(1)
    );
    f.xml(&format!(
        "  <ImageData WholeExtent=\"{ext}\" Origin=\"{x0:e} {y0:e} 0\" Spacing=\"{:e} {:e} {:e}\">\n",
        spacing(&g.x),
        spacing(&g.y),
        spacing(&g.z)
    ));
    f.xml(&format!("    <Piece Extent=\"{ext}\">\n"));
    f.xml("      <PointData Scalars=\"von_mises\">\n");
    for (name, values) in arrays {
        f.array("        ", name, 1, values.iter().map(|v| v + 0.0));
    }
    f.xml("      </PointData>\n    </Piece>\n  </ImageData>\n");
    f.finish()
}

/// VTK XML unstructured grid of the sampled regions of a 2D run in one step (binary, raw
/// appended data): points (z = 0), triangles (VTK type 5), cell data `region`, point data
/// displacement, stresses, strains, intensities
/// ([`tribo_case::bem::summary::point_scalars`]) and, with `psi` = (region, values), the
/// damage psi of that region (0 elsewhere).
pub fn bem_vtu(v: &Variant, step: usize, psi: Option<(&str, &[f64])>) -> Vec<u8> {
    let fields = &v.fields;
    let npts: usize = fields.iter().map(|f| f.nodes.len()).sum();
    let ncells: usize = fields.iter().map(|f| f.triangles.len()).sum();
    let mut s = AppendedFile::new("UnstructuredGrid");
    s.xml(&format!(
        "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"{npts}\" NumberOfCells=\"{ncells}\">\n      <Points>\n"
    ));
    let points: Vec<f64> = fields
        .iter()
        .flat_map(|f| f.nodes.iter().flat_map(|p| [p[0], p[1], 0.0]))
        .collect();
    s.array("        ", "", 3, points.into_iter());
    s.xml("      </Points>\n      <Cells>\n");
    let mut connectivity: Vec<i64> = Vec::with_capacity(3 * ncells);
    let mut offset = 0;
    for f in fields {
        for t in &f.triangles {
            connectivity.extend(t.iter().map(|&k| (k + offset) as i64));
        }
        offset += f.nodes.len();
    }
    s.array("        ", "connectivity", 1, connectivity.into_iter());
    s.array(
        "        ",
        "offsets",
        1,
        (1..ncells + 1).map(|k| 3 * k as i64),
    );
    s.array("        ", "types", 1, std::iter::repeat_n(5u8, ncells));
    s.xml("      </Cells>\n      <CellData Scalars=\"region\">\n");
    let region: Vec<i32> = fields
        .iter()
        .flat_map(|f| std::iter::repeat_n(f.index as i32, f.triangles.len()))
        .collect();
    s.array("        ", "region", 1, region.into_iter());
    s.xml("      </CellData>\n      <PointData Scalars=\"sigma_int_Pa\" Vectors=\"displacement_m\">\n");
    let displacement: Vec<f64> = fields
        .iter()
        .flat_map(|f| {
            f.samples[step]
                .iter()
                .flat_map(|x| [x.displacement[0], x.displacement[1], 0.0])
        })
        .collect();
    s.array("        ", "displacement_m", 3, displacement.into_iter());
    for (name, values) in tribo_case::bem::summary::point_scalars(v, step) {
        s.array("        ", name, 1, values.into_iter());
    }
    if let Some((region, values)) = psi {
        let mut all: Vec<f64> = Vec::with_capacity(npts);
        for f in fields {
            if f.region == region {
                all.extend_from_slice(values);
            } else {
                all.extend(std::iter::repeat_n(0.0, f.nodes.len()));
            }
        }
        s.array("        ", "psi", 1, all.into_iter());
    }
    s.xml("      </PointData>\n    </Piece>\n  </UnstructuredGrid>\n");
    s.finish()
}
