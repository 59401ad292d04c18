//! Measured topographies: readers for the formats instrument users have, into a
//! [`Measured`] grid of heights that the library's surface tools
//! ([`tribo::surface`]: detrending, resampling, statistics) then take.
//!
//! Formats (`docs/theory/SURFACES.md` sec. 5 describes each):
//! - ISO 25178-72 **X3P** ([`x3p`]): a zip archive with `main.xml` and the binary or inline
//!   point data; data types D, F, L, I; the invalid points as NaN (D, F) or by the
//!   valid-points bit buffer. Read with the crates `zip` (deflate only) and `roxmltree`.
//! - plain **ASCII/CSV** grids ([`ascii`]): tribo's `# spacing = dx dy` header, or Gwyddion's
//!   "ASCII data matrix" export with its `# Width:` / `# Height:` comment header, or no
//!   header with the spacing given by the caller;
//! - numpy **`.npy`** ([`npy`]): format versions 1, 2 and 3, little- or big-endian f4, f8,
//!   i2, i4, i8, C or Fortran order; the spacing given by the caller.
//!
//! Invalid points (a measurement's dropouts) are kept as NaN in [`Measured`] and refused by
//! [`Measured::into_topography`], which names how many there are and where the first is:
//! filling them would invent data under the contact, and the contact runs need every height.
//! Crop the measurement or fill it in the instrument's software.
//!
//! Every error names the file and the problem ([`TopographyError`]); a grid too large for
//! the memory limit ([`ReadOptions::max_bytes`]) is refused before it is allocated.

use std::path::{Path, PathBuf};
use thiserror::Error;
use tribo::surface::Topography;

use crate::error::CaseError;

pub mod ascii;
pub mod npy;
#[cfg(test)]
mod tests;
pub mod x3p;

/// A file that could not be read as a topography: the file and the problem.
#[derive(Debug, Error)]
#[error("{}: {problem}", path.display())]
pub struct TopographyError {
    /// The file.
    pub path: PathBuf,
    /// What is wrong with it.
    pub problem: String,
}

impl TopographyError {
    pub(crate) fn new(path: &Path, problem: impl Into<String>) -> Self {
        Self {
            path: path.to_path_buf(),
            problem: problem.into(),
        }
    }

    /// The case error of a case field `field` that names the file: [`CaseError::Field`] with
    /// the file as the value and the problem as the rule.
    pub fn into_case_error(self, field: &str) -> CaseError {
        CaseError::field(field, self.path.display(), self.problem)
    }
}

/// The result type of the readers.
pub type TopographyResult<T> = Result<T, TopographyError>;

/// Options of the readers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReadOptions {
    /// The spacing (dx, dy), m, for formats that do not carry it (npy, a headerless grid).
    /// A file that carries its own spacing must agree with it (relative 1e-9) if given.
    pub spacing: Option<(f64, f64)>,
    /// Metres per unit of the stored heights for formats without units (npy, a headerless
    /// grid; default 1: metres). X3P stores metres; the ASCII headers name their unit.
    pub height_unit: f64,
    /// Largest memory the heights may take, bytes (default 2 GiB): a larger grid is refused
    /// before it is read.
    pub max_bytes: usize,
}

impl Default for ReadOptions {
    fn default() -> Self {
        Self {
            spacing: None,
            height_unit: 1.0,
            max_bytes: 2 << 30,
        }
    }
}

/// A measured topography: heights on a regular grid, NaN at invalid points.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    /// Points along x (the fastest index).
    pub nx: usize,
    /// Points along y.
    pub ny: usize,
    /// Spacing along x, m.
    pub dx: f64,
    /// Spacing along y, m.
    pub dy: f64,
    /// Heights, m, `[j * nx + i]` for the point at (i dx, j dy); NaN where invalid.
    pub heights: Vec<f64>,
    /// The file it came from.
    pub path: PathBuf,
}

impl Measured {
    /// Number of invalid (NaN) points.
    pub fn invalid_count(&self) -> usize {
        self.heights.iter().filter(|h| h.is_nan()).count()
    }

    /// The topography, refusing invalid points (see the module documentation).
    ///
    /// Errors: invalid points (their count and the first one's row and column); the grid
    /// rules of [`Topography::new`].
    pub fn into_topography(self) -> TopographyResult<Topography> {
        let bad = self.invalid_count();
        if bad > 0 {
            let k = self.heights.iter().position(|h| h.is_nan()).unwrap_or(0);
            return Err(TopographyError::new(
                &self.path,
                format!(
                    "{bad} of {} points are invalid (no height measured; the first at row {}, \
                     column {}): crop the measurement or fill them before using it",
                    self.heights.len(),
                    k / self.nx,
                    k % self.nx
                ),
            ));
        }
        let path = self.path;
        Topography::new(self.nx, self.ny, self.dx, self.dy, self.heights)
            .map_err(|e| TopographyError::new(&path, e.to_string()))
    }
}

/// Reads a topography, the format chosen by the extension: `.x3p`; `.npy`; `.csv`, `.txt`,
/// `.asc`, `.dat` (ASCII grids).
///
/// Errors: an unknown extension, and those of each reader.
pub fn read(path: &Path, options: &ReadOptions) -> TopographyResult<Measured> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
        .unwrap_or_default();
    match ext.as_str() {
        "x3p" => x3p::read(path, options),
        "npy" => npy::read(path, options),
        "csv" | "txt" | "asc" | "dat" => ascii::read(path, options),
        _ => Err(TopographyError::new(
            path,
            format!(
                "unknown topography format \"{ext}\": expected .x3p, .npy, or an ASCII grid \
                 (.csv, .txt, .asc, .dat)"
            ),
        )),
    }
}

/// Checks that `nx * ny` heights fit the memory limit (8 bytes each) and returns the count.
pub(crate) fn checked_points(
    path: &Path,
    nx: usize,
    ny: usize,
    options: &ReadOptions,
) -> TopographyResult<usize> {
    if nx < 2 || ny < 2 {
        return Err(TopographyError::new(
            path,
            format!("a {nx} x {ny} grid: at least 2 x 2 points are needed"),
        ));
    }
    let n = nx
        .checked_mul(ny)
        .filter(|n| n.checked_mul(8).is_some())
        .ok_or_else(|| TopographyError::new(path, format!("a {nx} x {ny} grid is too large")))?;
    if n * 8 > options.max_bytes {
        return Err(TopographyError::new(
            path,
            format!(
                "a {nx} x {ny} grid needs {:.2} GiB for its heights, above the limit of {:.2} GiB",
                (n * 8) as f64 / (1u64 << 30) as f64,
                options.max_bytes as f64 / (1u64 << 30) as f64
            ),
        ));
    }
    Ok(n)
}

/// The spacing: the file's, checked against the caller's if both are given, or the caller's.
pub(crate) fn resolve_spacing(
    path: &Path,
    from_file: Option<(f64, f64)>,
    options: &ReadOptions,
) -> TopographyResult<(f64, f64)> {
    let s = match (from_file, options.spacing) {
        (Some(f), Some(g)) => {
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs());
            if !(close(f.0, g.0) && close(f.1, g.1)) {
                return Err(TopographyError::new(
                    path,
                    format!(
                        "the file's spacing ({:e}, {:e}) m differs from the one given ({:e}, {:e}) m",
                        f.0, f.1, g.0, g.1
                    ),
                ));
            }
            f
        }
        (Some(f), None) => f,
        (None, Some(g)) => g,
        (None, None) => {
            return Err(TopographyError::new(
                path,
                "the file does not give the spacing: give it (dx, dy in m)",
            ))
        }
    };
    if !(s.0.is_finite() && s.0 > 0.0 && s.1.is_finite() && s.1 > 0.0) {
        return Err(TopographyError::new(
            path,
            format!(
                "the spacing ({:e}, {:e}) m must be finite and > 0",
                s.0, s.1
            ),
        ));
    }
    Ok(s)
}

/// Why [`read_regular`] refused a file.
#[derive(Debug)]
pub enum BoundedReadError {
    /// The file cannot be opened or read.
    Io(std::io::Error),
    /// A directory, not a file.
    Directory,
    /// A device, a pipe or a socket: its size is not known beforehand (`/dev/zero` never
    /// ends, a pipe blocks the open until a writer comes).
    NotRegular,
    /// The file has this many bytes (at least), above the limit.
    TooLarge(u64),
}

/// The metadata of a regular file (after links), or why it is not one.
fn regular(path: &Path) -> Result<std::fs::Metadata, BoundedReadError> {
    let meta = std::fs::metadata(path).map_err(BoundedReadError::Io)?;
    if meta.is_dir() {
        Err(BoundedReadError::Directory)
    } else if !meta.is_file() {
        Err(BoundedReadError::NotRegular)
    } else {
        Ok(meta)
    }
}

/// Reads a whole regular file of at most `limit` bytes: a directory, a device, a pipe or a
/// socket is refused before it is opened, and a larger file (also one that grows beyond the
/// limit while it is read) is refused without reading past the limit. The one bounded
/// reader of the case's input files (topographies, height maps) and of study files.
pub fn read_regular(path: &Path, limit: u64) -> Result<Vec<u8>, BoundedReadError> {
    use std::io::Read;
    let meta = regular(path)?;
    if meta.len() > limit {
        return Err(BoundedReadError::TooLarge(meta.len()));
    }
    let file = std::fs::File::open(path).map_err(BoundedReadError::Io)?;
    let mut bytes = Vec::new();
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(BoundedReadError::Io)?;
    if bytes.len() as u64 > limit {
        return Err(BoundedReadError::TooLarge(bytes.len() as u64));
    }
    Ok(bytes)
}

/// [`BoundedReadError`] as a topography reader states it.
fn topography_error(path: &Path, limit: u64, e: BoundedReadError) -> TopographyError {
    match e {
        BoundedReadError::Io(e) => TopographyError::new(path, format!("cannot read: {e}")),
        BoundedReadError::Directory => {
            TopographyError::new(path, "cannot read: a directory, not a file")
        }
        BoundedReadError::NotRegular => TopographyError::new(
            path,
            "not a regular file (a device, a pipe or a socket): give the topography file itself",
        ),
        BoundedReadError::TooLarge(len) => TopographyError::new(
            path,
            format!("the file has {len} bytes, above the limit of {limit} bytes"),
        ),
    }
}

/// Refuses what is not a regular file (after links): a directory, or a device, a pipe or a
/// socket ([`BoundedReadError`]).
pub(crate) fn check_regular(path: &Path) -> TopographyResult<std::fs::Metadata> {
    regular(path).map_err(|e| topography_error(path, 0, e))
}

/// Reads a whole regular file, refusing one larger than `limit` bytes ([`read_regular`]).
pub(crate) fn read_bytes(path: &Path, limit: usize) -> TopographyResult<Vec<u8>> {
    read_regular(path, limit as u64).map_err(|e| topography_error(path, limit as u64, e))
}
