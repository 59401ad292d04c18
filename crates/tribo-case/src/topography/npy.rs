//! numpy `.npy` files (the NPY format, numpy's `numpy.lib.format`, versions 1.0, 2.0, 3.0).
//!
//! Layout: the magic `\x93NUMPY`, the major and minor version bytes, the header length
//! (u16 little-endian in version 1, u32 in versions 2 and 3), the header (a Python dict
//! literal, ASCII in versions 1 and 2, UTF-8 in 3) `{'descr': '<f8', 'fortran_order': False,
//! 'shape': (ny, nx), }`, then the data. A 2D array's first index is the row: y (`ny` rows),
//! the second the column: x. Supported dtypes: floats `f4`, `f8` and signed integers `i2`,
//! `i4`, `i8`, little- (`<`) or big-endian (`>`; `|` for one byte is not a supported size);
//! C order (row-major) or Fortran order (column-major). NaN heights are invalid points.

use super::TopographyResult;
use super::{checked_points, read_bytes, resolve_spacing, Measured, ReadOptions, TopographyError};
use std::path::Path;

/// Reads a 2D `.npy` array of heights; the spacing and the height unit come from `options`.
///
/// Errors: not an NPY file (bad magic), an unsupported version, a header that does not parse,
/// an unsupported dtype, a shape that is not 2D, a data length that does not match the shape,
/// the memory limit.
pub fn read(path: &Path, options: &ReadOptions) -> TopographyResult<Measured> {
    let bytes = read_bytes(
        path,
        options.max_bytes.saturating_mul(2).saturating_add(1 << 20),
    )?;
    parse(path, &bytes, options)
}

/// Parses the bytes of an `.npy` file (see [`read`]).
pub fn parse(path: &Path, bytes: &[u8], options: &ReadOptions) -> TopographyResult<Measured> {
    let err = |p: String| TopographyError::new(path, p);
    if bytes.len() < 10 || &bytes[..6] != b"\x93NUMPY" {
        return Err(err(
            "not a numpy .npy file (the magic \\x93NUMPY is missing)".into(),
        ));
    }
    let major = bytes[6];
    let (header_len, start): (usize, usize) = match major {
        1 => (u16::from_le_bytes([bytes[8], bytes[9]]) as usize, 10),
        2 | 3 => {
            if bytes.len() < 12 {
                return Err(err("truncated .npy header".into()));
            }
            (
                u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize,
                12,
            )
        }
        v => {
            return Err(err(format!(
                "unsupported .npy format version {v}.{}",
                bytes[7]
            )))
        }
    };
    let end = start
        .checked_add(header_len)
        .filter(|&e| e <= bytes.len())
        .ok_or_else(|| err("truncated .npy header".into()))?;
    let header = std::str::from_utf8(&bytes[start..end])
        .map_err(|_| err("the .npy header is not text".into()))?;
    let descr = dict_value(header, "descr")
        .and_then(quoted)
        .ok_or_else(|| err(format!("no 'descr' in the .npy header {header:?}")))?;
    let fortran = match dict_value(header, "fortran_order") {
        Some(v) if v.starts_with("True") => true,
        Some(v) if v.starts_with("False") => false,
        _ => {
            return Err(err(format!(
                "no 'fortran_order' in the .npy header {header:?}"
            )))
        }
    };
    let shape = dict_value(header, "shape")
        .and_then(tuple)
        .ok_or_else(|| err(format!("no 'shape' in the .npy header {header:?}")))?;
    let [ny, nx] = shape[..] else {
        return Err(err(format!(
            "the array has shape {shape:?}: a 2D array of heights (rows along y, columns along \
             x) is expected"
        )));
    };
    let (big, kind, size) = dtype(descr).ok_or_else(|| {
        err(format!(
            "unsupported dtype '{descr}': expected f4, f8, i2, i4 or i8, little- or big-endian"
        ))
    })?;
    let n = checked_points(path, nx, ny, options)?;
    let data = &bytes[end..];
    if data.len() != n * size {
        return Err(err(format!(
            "the data has {} bytes, expected {ny} x {nx} x {size} = {} for shape ({ny}, {nx}) \
             and dtype '{descr}'",
            data.len(),
            n * size
        )));
    }
    let (dx, dy) = resolve_spacing(path, None, options)?;
    let value = |k: usize| -> f64 {
        let mut b = [0u8; 8];
        b[..size].copy_from_slice(&data[k * size..(k + 1) * size]);
        if big {
            b[..size].reverse();
        }
        match (kind, size) {
            ('f', 4) => f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            ('f', _) => f64::from_le_bytes(b),
            (_, 2) => i16::from_le_bytes([b[0], b[1]]) as f64,
            (_, 4) => i32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            _ => i64::from_le_bytes(b) as f64,
        }
    };
    let mut heights = Vec::new();
    heights
        .try_reserve_exact(n)
        .map_err(|_| err(format!("out of memory for {n} heights")))?;
    for j in 0..ny {
        for i in 0..nx {
            // Row j (y), column i (x): C order stores rows contiguously, Fortran columns.
            let k = if fortran { i * ny + j } else { j * nx + i };
            heights.push(value(k) * options.height_unit);
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

/// The text after `'key':` in a Python dict literal.
fn dict_value<'a>(header: &'a str, key: &str) -> Option<&'a str> {
    for q in ['\'', '"'] {
        let pat = format!("{q}{key}{q}");
        if let Some(p) = header.find(&pat) {
            let rest = &header[p + pat.len()..];
            let colon = rest.find(':')?;
            return Some(rest[colon + 1..].trim_start());
        }
    }
    None
}

/// The contents of the quoted string at the start of `s`.
fn quoted(s: &str) -> Option<&str> {
    let q = s.chars().next().filter(|c| *c == '\'' || *c == '"')?;
    let rest = &s[1..];
    rest.find(q).map(|e| &rest[..e])
}

/// The integers of the tuple at the start of `s`, e.g. `(3, 4)`, `(5,)`.
fn tuple(s: &str) -> Option<Vec<usize>> {
    let s = s.strip_prefix('(')?;
    let inner = &s[..s.find(')')?];
    inner
        .split(',')
        .map(str::trim)
        .filter(|t| !t.is_empty())
        .map(|t| t.trim_end_matches('L').parse().ok())
        .collect()
}

/// (big-endian, kind 'f' or 'i', size in bytes) of a dtype string.
fn dtype(descr: &str) -> Option<(bool, char, usize)> {
    let mut c = descr.chars();
    let big = match c.next()? {
        '<' => false,
        '>' => true,
        '=' => cfg!(target_endian = "big"),
        _ => return None,
    };
    let kind = c.next()?;
    let size: usize = c.as_str().parse().ok()?;
    match (kind, size) {
        ('f', 4 | 8) | ('i', 2 | 4 | 8) => Some((big, kind, size)),
        _ => None,
    }
}
