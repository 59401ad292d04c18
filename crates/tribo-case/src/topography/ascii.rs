//! Plain ASCII/CSV grids of heights.
//!
//! One line per row of points: the first data line is y = 0, each next line one `dy`
//! further; along a line x increases by `dx`. Values are separated by blanks, tabs, commas
//! or semicolons; `NaN` (any case) marks an invalid point. Lines starting with `#` are the
//! header (or comments): `# Key: value` lines with these keys (case-insensitive) are read,
//! the others ignored:
//!
//! ```text
//! # dx: 0.5 um          spacing along x (tribo's header), value and unit (m if none)
//! # dy: 0.5 um          spacing along y
//! # Width: 64.0 µm      Gwyddion's "ASCII data matrix" header: the x size nx * dx ...
//! # Height: 32.0 µm     ... and the y size ny * dy (Gwyddion's real size is points
//!                       times spacing)
//! # Value units: nm     the unit of the heights (m if none)
//! ```
//!
//! Units: `m`, `mm`, `um` (also `µm`, `μm`), `nm`, `pm`. Without `dx`/`dy` or
//! `Width`/`Height` the caller gives the spacing ([`super::ReadOptions::spacing`]).

use super::TopographyResult;
use super::{checked_points, read_bytes, resolve_spacing, Measured, ReadOptions, TopographyError};
use std::path::Path;

/// Metres per unit, for the length units accepted.
fn unit_factor(unit: &str) -> Option<f64> {
    Some(match unit.trim() {
        "" | "m" => 1.0,
        "mm" => 1e-3,
        "um" | "µm" | "μm" => 1e-6,
        "nm" => 1e-9,
        "pm" => 1e-12,
        _ => return None,
    })
}

/// Reads an ASCII grid (see the module documentation).
///
/// Errors: a bad header value or unit, a value that is not a number, rows of unequal
/// length, fewer than 2 x 2 points, a missing spacing, the memory limit (the file larger than
/// 64 bytes per allowed height is refused unread).
pub fn read(path: &Path, options: &ReadOptions) -> TopographyResult<Measured> {
    let bytes = read_bytes(path, options.max_bytes.saturating_mul(8))?;
    let text = String::from_utf8(bytes)
        .map_err(|_| TopographyError::new(path, "not a text file (invalid UTF-8)"))?;
    parse(path, &text, options)
}

/// Parses the text of an ASCII grid (see [`read`]).
pub fn parse(path: &Path, text: &str, options: &ReadOptions) -> TopographyResult<Measured> {
    let err = |line: usize, p: String| TopographyError::new(path, format!("line {line}: {p}"));
    let (mut dx, mut dy, mut width, mut height) = (None, None, None, None);
    let mut value_unit = None;
    let mut rows: Vec<Vec<f64>> = Vec::new();
    let mut first_row_line = 0;
    for (k, line) in text.lines().enumerate() {
        let ln = k + 1;
        let t = line.trim();
        if t.is_empty() {
            continue;
        }
        if let Some(h) = t.strip_prefix('#') {
            let Some((key, value)) = h.split_once(':') else {
                continue;
            };
            let key = key.trim().to_ascii_lowercase();
            let slot = match key.as_str() {
                "dx" => &mut dx,
                "dy" => &mut dy,
                "width" => &mut width,
                "height" => &mut height,
                "value units" => {
                    let u = value.trim();
                    if value_unit.is_some() {
                        return Err(err(ln, "value units given twice".into()));
                    }
                    value_unit = Some(unit_factor(u).ok_or_else(|| {
                        err(
                            ln,
                            format!("unknown height unit \"{u}\" (m, mm, um, nm, pm)"),
                        )
                    })?);
                    continue;
                }
                _ => continue,
            };
            let v = value.trim();
            let (num, unit) = v.split_once(char::is_whitespace).unwrap_or((v, ""));
            let num: f64 = num
                .parse()
                .map_err(|_| err(ln, format!("{key}: \"{num}\" is not a number")))?;
            let f = unit_factor(unit)
                .ok_or_else(|| err(ln, format!("{key}: unknown unit \"{}\"", unit.trim())))?;
            if !(num.is_finite() && num > 0.0) {
                return Err(err(ln, format!("{key} = {num}: must be finite and > 0")));
            }
            if slot.is_some() {
                // Two headers of one key (a file and its edited copy pasted together): which
                // one is meant is not known, and taking either silently is a guess.
                return Err(err(ln, format!("{key} given twice")));
            }
            *slot = Some(num * f);
            continue;
        }
        let mut row = Vec::new();
        for tok in t
            .split(|c: char| c.is_whitespace() || c == ',' || c == ';')
            .filter(|s| !s.is_empty())
        {
            let v: f64 = tok
                .parse()
                .map_err(|_| err(ln, format!("\"{tok}\" is not a number")))?;
            if v.is_infinite() {
                return Err(err(ln, format!("an infinite height \"{tok}\"")));
            }
            row.push(v);
        }
        if let Some(first) = rows.first() {
            if row.len() != first.len() {
                return Err(err(
                    ln,
                    format!(
                        "{} values, expected {} as on line {first_row_line}",
                        row.len(),
                        first.len()
                    ),
                ));
            }
        } else {
            first_row_line = ln;
        }
        rows.push(row);
    }
    let ny = rows.len();
    let nx = rows.first().map_or(0, Vec::len);
    let n = checked_points(path, nx, ny, options)?;
    let from_file =
        match (dx, dy, width, height) {
            (Some(a), Some(b), _, _) => Some((a, b)),
            (None, None, Some(w), Some(h)) => Some((w / nx as f64, h / ny as f64)),
            (None, None, None, None) => None,
            _ => return Err(TopographyError::new(
                path,
                "the header gives only part of the spacing: give both dx and dy (or Gwyddion's \
                 Width and Height)",
            )),
        };
    let (dx, dy) = resolve_spacing(path, from_file, options)?;
    let unit = value_unit.unwrap_or(options.height_unit);
    let mut heights = Vec::new();
    heights
        .try_reserve_exact(n)
        .map_err(|_| TopographyError::new(path, format!("out of memory for {n} heights")))?;
    for r in rows {
        heights.extend(r.into_iter().map(|v| v * unit));
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
