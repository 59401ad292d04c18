//! ISO 25178-72 X3P files (the openGPS XML 3D surface format).
//!
//! An X3P file is a zip archive holding `main.xml` (the description: the axes, the matrix
//! size, the link to the point data) and, for binary data, the point data
//! (`bindata/data.bin`, little-endian) and optionally the valid-points buffer. What is read:
//!
//! - `Record1/FeatureType`: `SUR` (a surface; profiles `PRF` and point clouds `PCL` are
//!   refused);
//! - `Record1/Axes/CX`, `CY`: `AxisType` `I` (incremental: a regular grid) with `Increment`
//!   (m) — absolute x/y axes (`A`, coordinates per point) are refused;
//! - `Record1/Axes/CZ`: `DataType` `I` (int16), `L` (int32), `F` (float32) or `D` (float64),
//!   and `Increment`, `Offset` (default 1 and 0): the height is `Offset + Increment * value`
//!   (m);
//! - `Record3/MatrixDimension`: `SizeX`, `SizeY` (`SizeZ` must be 1), the points stored with x
//!   fastest;
//! - `Record3/DataLink/PointDataLink`: the binary data's path in the archive, or
//!   `Record3/DataList/Datum`: the heights inline, one per point (an empty `Datum` is an
//!   invalid point);
//! - `Record3/DataLink/ValidPointsLink` (optional): one bit per point, least significant bit
//!   first, set where the point is valid; NaN values of F and D data are invalid too.
//!
//! The MD5 checksums are verified where the file gives them (ISO 25178-72: `md5checksum.hex`,
//! the checksum of `main.xml`, named by `Record4/ChecksumFile`; `DataLink/MD5ChecksumPointData`
//! and `MD5ChecksumValidPoints`, those of the binary entries): a mismatch is an error naming
//! the entry (the file is corrupt); an absent or empty checksum is not (writers differ). The
//! zip archive is read with the crate `zip` (deflate decompression only; it checks each
//! entry's CRC-32 too), the XML with `roxmltree`, MD5 with `md-5`.

use super::TopographyResult;
use super::{checked_points, resolve_spacing, Measured, ReadOptions, TopographyError};
use roxmltree::{Document, Node};
use std::io::Read;
use std::path::Path;

/// Reads an X3P file (see the module documentation).
///
/// Errors: not a zip archive (or a truncated one), no `main.xml`, XML that does not parse, a
/// missing or unsupported element (named), point data of the wrong length, the memory limit.
pub fn read(path: &Path, options: &ReadOptions) -> TopographyResult<Measured> {
    let err = |p: String| TopographyError::new(path, p);
    super::check_regular(path)?;
    let file = std::fs::File::open(path).map_err(|e| err(format!("cannot read: {e}")))?;
    let mut archive = zip::ZipArchive::new(std::io::BufReader::new(file)).map_err(|e| {
        err(format!(
            "not a readable X3P archive (an X3P file is a zip archive; truncated?): {e}"
        ))
    })?;
    let xml = entry(path, &mut archive, "main.xml", 64 << 20)?;
    if archive.index_for_name("md5checksum.hex").is_some() {
        let sums = entry(path, &mut archive, "md5checksum.hex", 4096)?;
        // "<32 hex digits> *main.xml": the first word is the checksum.
        let sums = String::from_utf8_lossy(&sums);
        if let Some(want) = sums.split_whitespace().next() {
            verify_md5(path, "main.xml", &xml, want, "md5checksum.hex")?;
        }
    }
    let xml = String::from_utf8(xml).map_err(|_| err("main.xml is not UTF-8 text".into()))?;
    let doc = Document::parse(&xml).map_err(|e| err(format!("main.xml does not parse: {e}")))?;
    let root = doc.root_element();
    let record1 = child(path, root, "Record1")?;
    let feature = text(
        path,
        child(path, record1, "FeatureType")?,
        "Record1/FeatureType",
    )?;
    if feature != "SUR" {
        return Err(err(format!(
            "Record1/FeatureType = {feature}: only surfaces (SUR) are read, not profiles (PRF) \
             or point clouds (PCL)"
        )));
    }
    let axes = child(path, record1, "Axes")?;
    let mut spacing = [0.0; 2];
    for (k, name) in ["CX", "CY"].into_iter().enumerate() {
        let axis = child(path, axes, name)?;
        let kind = text(
            path,
            child(path, axis, "AxisType")?,
            &format!("Axes/{name}/AxisType"),
        )?;
        if kind != "I" {
            return Err(err(format!(
                "Axes/{name}/AxisType = {kind}: only incremental axes (I, a regular grid) are \
                 read"
            )));
        }
        spacing[k] = number(path, axis, "Increment", name)?
            .ok_or_else(|| err(format!("Axes/{name}/Increment is missing (the spacing, m)")))?;
    }
    let cz = child(path, axes, "CZ")?;
    let dtype = text(path, child(path, cz, "DataType")?, "Axes/CZ/DataType")?;
    let size = match dtype.as_str() {
        "I" => 2,
        "L" => 4,
        "F" => 4,
        "D" => 8,
        other => {
            return Err(err(format!(
                "Axes/CZ/DataType = {other}: unsupported (I, L, F or D)"
            )))
        }
    };
    let z_inc = number(path, cz, "Increment", "CZ")?.unwrap_or(1.0);
    let z_off = number(path, cz, "Offset", "CZ")?.unwrap_or(0.0);
    let record3 = child(path, root, "Record3")?;
    let dims = child(path, record3, "MatrixDimension")?;
    let dim = |name: &str| -> TopographyResult<usize> {
        let t = text(
            path,
            child(path, dims, name)?,
            &format!("MatrixDimension/{name}"),
        )?;
        t.parse()
            .map_err(|_| err(format!("MatrixDimension/{name} = {t}: not a count")))
    };
    let (nx, ny, nz) = (dim("SizeX")?, dim("SizeY")?, dim("SizeZ")?);
    if nz != 1 {
        return Err(err(format!(
            "MatrixDimension/SizeZ = {nz}: only one layer (SizeZ = 1) is read"
        )));
    }
    let n = checked_points(path, nx, ny, options)?;
    let (dx, dy) = resolve_spacing(path, Some((spacing[0], spacing[1])), options)?;
    let mut heights = Vec::new();
    heights
        .try_reserve_exact(n)
        .map_err(|_| err(format!("out of memory for {n} heights")))?;
    let link = record3.children().find(|c| is(c, "DataLink"));
    if let Some(link) = link {
        let data_path = text(
            path,
            child(path, link, "PointDataLink")?,
            "DataLink/PointDataLink",
        )?;
        let data = entry(path, &mut archive, &data_path, n * size)?;
        if let Some(want) = optional_text(link, "MD5ChecksumPointData") {
            verify_md5(
                path,
                &data_path,
                &data,
                &want,
                "DataLink/MD5ChecksumPointData",
            )?;
        }
        if data.len() != n * size {
            return Err(err(format!(
                "{data_path} has {} bytes, expected SizeX * SizeY * {size} = {nx} * {ny} * {size} \
                 = {} for data type {dtype}",
                data.len(),
                n * size
            )));
        }
        for c in data.chunks_exact(size) {
            let v = match dtype.as_str() {
                "I" => i16::from_le_bytes([c[0], c[1]]) as f64,
                "L" => i32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64,
                "F" => f32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64,
                _ => f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]),
            };
            heights.push(z_off + z_inc * v);
        }
        if let Some(valid) = link.children().find(|c| is(c, "ValidPointsLink")) {
            let valid_path = text(path, valid, "DataLink/ValidPointsLink")?;
            let bits = entry(path, &mut archive, &valid_path, n.div_ceil(8))?;
            if let Some(want) = optional_text(link, "MD5ChecksumValidPoints") {
                verify_md5(
                    path,
                    &valid_path,
                    &bits,
                    &want,
                    "DataLink/MD5ChecksumValidPoints",
                )?;
            }
            if bits.len() != n.div_ceil(8) {
                return Err(err(format!(
                    "{valid_path} has {} bytes, expected one bit per point: {}",
                    bits.len(),
                    n.div_ceil(8)
                )));
            }
            for (k, h) in heights.iter_mut().enumerate() {
                if bits[k / 8] >> (k % 8) & 1 == 0 {
                    *h = f64::NAN;
                }
            }
        }
    } else {
        let list = record3
            .children()
            .find(|c| is(c, "DataList"))
            .ok_or_else(|| err("Record3 has neither DataLink nor DataList".into()))?;
        for d in list.children().filter(|c| is(c, "Datum")) {
            let t = d.text().unwrap_or("").trim();
            let v = if t.is_empty() {
                f64::NAN
            } else {
                let v: f64 = t
                    .parse()
                    .map_err(|_| err(format!("DataList/Datum \"{t}\" is not a number")))?;
                z_off + z_inc * v
            };
            if heights.len() == n {
                return Err(err(format!(
                    "DataList has more than SizeX * SizeY = {n} Datum elements"
                )));
            }
            heights.push(v);
        }
        if heights.len() != n {
            return Err(err(format!(
                "DataList has {} Datum elements, expected SizeX * SizeY = {n}",
                heights.len()
            )));
        }
    }
    if let Some(k) = heights.iter().position(|h| h.is_infinite()) {
        return Err(err(format!(
            "an infinite height at row {}, column {}",
            k / nx,
            k % nx
        )));
    }
    Ok(Measured {
        nx,
        ny,
        dx,
        dy,
        heights,
        path: path.to_path_buf(),
    })
}

/// The trimmed text of `node`'s child element `name`, or None where it is absent or empty.
fn optional_text(node: Node, name: &str) -> Option<String> {
    let t = node.children().find(|c| is(c, name))?.text()?.trim();
    (!t.is_empty()).then(|| t.to_string())
}

/// Checks that the MD5 digest of `bytes` (the archive entry `name`) is the hexadecimal `want`
/// (given by `source`), case-insensitively.
fn verify_md5(
    path: &Path,
    name: &str,
    bytes: &[u8],
    want: &str,
    source: &str,
) -> TopographyResult<()> {
    use md5::{Digest, Md5};
    let got: String = Md5::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect();
    if got.eq_ignore_ascii_case(want) {
        Ok(())
    } else {
        Err(TopographyError::new(
            path,
            format!(
                "the MD5 checksum of {name} is {got}, but {source} says {want}: the file is \
                 corrupt (or was changed after it was written)"
            ),
        ))
    }
}

/// The bytes of the archive's entry `name`, refusing more than `limit` bytes.
fn entry<R: std::io::Read + std::io::Seek>(
    path: &Path,
    archive: &mut zip::ZipArchive<R>,
    name: &str,
    limit: usize,
) -> TopographyResult<Vec<u8>> {
    let err = |p: String| TopographyError::new(path, p);
    let mut f = archive.by_name(name).map_err(|e| match e {
        zip::result::ZipError::FileNotFound => err(format!("the archive has no {name}")),
        e => err(format!("cannot read {name} from the archive: {e}")),
    })?;
    let mut out = Vec::new();
    // One byte more than the limit, so that a longer entry is seen as such.
    (&mut f)
        .take(limit as u64 + 1)
        .read_to_end(&mut out)
        .map_err(|e| {
            err(format!(
                "cannot read {name} from the archive (truncated?): {e}"
            ))
        })?;
    Ok(out)
}

/// The child element `name` of `node` (by local name), or an error naming it.
fn child<'a, 'i>(path: &Path, node: Node<'a, 'i>, name: &str) -> TopographyResult<Node<'a, 'i>> {
    node.children().find(|c| is(c, name)).ok_or_else(|| {
        TopographyError::new(
            path,
            format!("main.xml: no {name} in {}", node.tag_name().name()),
        )
    })
}

/// The trimmed text of an element.
fn text(path: &Path, node: Node, what: &str) -> TopographyResult<String> {
    node.text()
        .map(|t| t.trim().to_string())
        .filter(|t| !t.is_empty())
        .ok_or_else(|| TopographyError::new(path, format!("main.xml: {what} is empty")))
}

/// The number in the optional child `name` of an axis.
fn number(path: &Path, axis: Node, name: &str, axis_name: &str) -> TopographyResult<Option<f64>> {
    let Some(c) = axis.children().find(|c| is(c, name)) else {
        return Ok(None);
    };
    let t = text(path, c, &format!("Axes/{axis_name}/{name}"))?;
    let v: f64 = t.parse().map_err(|_| {
        TopographyError::new(path, format!("Axes/{axis_name}/{name} = {t}: not a number"))
    })?;
    if !v.is_finite() {
        return Err(TopographyError::new(
            path,
            format!("Axes/{axis_name}/{name} = {t}: not finite"),
        ));
    }
    Ok(Some(v))
}

/// Whether `node` is the element `name` (by local name: the root's namespace prefix and any
/// default namespace ignored).
fn is(node: &Node, name: &str) -> bool {
    node.is_element() && node.tag_name().name() == name
}

/// An X3P archive (ISO 25178-72) of the topography `t`: `main.xml` (FeatureType SUR,
/// incremental x and y axes of the spacing, z absolute in metres, data type D) and the heights
/// as little-endian doubles in `bindata/data.bin`, x fastest, both stored uncompressed. The
/// MD5 checksums are left empty (the reader does not verify them; an instrument's own
/// software may). `comment` goes into Record2.
///
/// Errors: the zip writer's (none are expected writing into memory).
pub fn to_bytes(t: &tribo::surface::Topography, comment: &str) -> TopographyResult<Vec<u8>> {
    use std::io::Write;
    let (dx, dy) = t.spacing();
    let escaped: String = comment
        .chars()
        .map(|c| match c {
            '<' | '>' | '&' => ' ',
            c => c,
        })
        .collect();
    let xml = format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<p:ISO5436_2 xmlns:p="http://www.opengps.eu/2008/ISO5436_2" xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:schemaLocation="http://www.opengps.eu/2008/ISO5436_2 http://www.opengps.eu/2008/ISO5436_2/ISO5436_2.xsd">
  <Record1>
    <Revision>ISO5436 - 2000</Revision>
    <FeatureType>SUR</FeatureType>
    <Axes>
      <CX><AxisType>I</AxisType><DataType>D</DataType><Increment>{dx:e}</Increment><Offset>0.0</Offset></CX>
      <CY><AxisType>I</AxisType><DataType>D</DataType><Increment>{dy:e}</Increment><Offset>0.0</Offset></CY>
      <CZ><AxisType>A</AxisType><DataType>D</DataType><Increment>1.0</Increment><Offset>0.0</Offset></CZ>
    </Axes>
  </Record1>
  <Record2>
    <Date>2026-11-25T00:00:00+00:00</Date>
    <Instrument><Manufacturer>tribo</Manufacturer><Model>tribo example</Model><Serial>0</Serial><Version>{version}</Version></Instrument>
    <CalibrationDate>2026-11-25T00:00:00+00:00</CalibrationDate>
    <ProbingSystem><Type>NonContacting</Type><Identification>none</Identification></ProbingSystem>
    <Comment>{escaped}</Comment>
  </Record2>
  <Record3>
    <MatrixDimension><SizeX>{nx}</SizeX><SizeY>{ny}</SizeY><SizeZ>1</SizeZ></MatrixDimension>
    <DataLink><PointDataLink>bindata/data.bin</PointDataLink><MD5ChecksumPointData></MD5ChecksumPointData></DataLink>
  </Record3>
  <Record4><ChecksumFile>md5checksum.hex</ChecksumFile></Record4>
</p:ISO5436_2>
"#,
        version = env!("CARGO_PKG_VERSION"),
        nx = t.nx(),
        ny = t.ny(),
    );
    let data: Vec<u8> = t.heights().iter().flat_map(|h| h.to_le_bytes()).collect();
    let err = |e: &dyn std::fmt::Display| {
        TopographyError::new(
            Path::new("<x3p in memory>"),
            format!("writing the archive: {e}"),
        )
    };
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options =
        zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
    for (name, bytes) in [
        ("main.xml", xml.as_bytes()),
        ("bindata/data.bin", &data[..]),
    ] {
        zip.start_file(name, options).map_err(|e| err(&e))?;
        zip.write_all(bytes).map_err(|e| err(&e))?;
    }
    let cursor = zip.finish().map_err(|e| err(&e))?;
    Ok(cursor.into_inner())
}
