//! Regular surface grids of rectangular elements.
//!
//! Layout of every surface field in this crate: a flat slice of length `nx * ny`, element
//! `(ix, iy)` at index `iy * nx + ix` (x varies fastest). Element centres are
//! `x_i = x_min + (i + 1/2) dx`, `y_j = y_min + (j + 1/2) dy`; fields are piecewise constant
//! over elements (tractions) and collocated at element centres (displacements, gaps).

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// The largest number of elements per grid side accepted, so that a typo (`n = 1e6`) is an
/// error rather than an out-of-memory crash. 8192^2 elements need about 4 GiB in the FFT path.
pub const MAX_ELEMENTS_PER_SIDE: usize = 8192;

/// A window of `nx * ny` rectangular elements on the surface z = 0, centred on the origin.
///
/// Validated on construction ([`SurfaceGrid::centred`]) and on deserialization: the
/// serialized fields `nx, ny, x_min, y_min, dx, dy` must describe a grid `centred` accepts
/// (`nx`, `ny` in `[4, MAX_ELEMENTS_PER_SIDE]`, `x_min = -half_width_x < 0`, and
/// `dx = 2 half_width_x / nx` to a few ulp; likewise in y), and the grid is rebuilt from them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawSurfaceGrid")]
pub struct SurfaceGrid {
    nx: usize,
    ny: usize,
    x_min: f64,
    y_min: f64,
    dx: f64,
    dy: f64,
}

/// The serialized form of [`SurfaceGrid`], checked on the way in.
#[derive(Deserialize)]
struct RawSurfaceGrid {
    nx: usize,
    ny: usize,
    x_min: f64,
    y_min: f64,
    dx: f64,
    dy: f64,
}

impl TryFrom<RawSurfaceGrid> for SurfaceGrid {
    type Error = Error;

    fn try_from(raw: RawSurfaceGrid) -> Result<Self> {
        let grid = Self::centred(raw.nx, raw.ny, -raw.x_min, -raw.y_min)?;
        // The element sizes are derived: they must be those of the window, to the round-off
        // of the division that makes them (a few ulp; a written-out `dx` may be the decimal
        // nearest to it, not the same double).
        for (field, given, derived) in [("grid.dx", raw.dx, grid.dx), ("grid.dy", raw.dy, grid.dy)]
        {
            if !(given.is_finite() && (given - derived).abs() <= 4.0 * f64::EPSILON * derived) {
                return Err(Error::invalid(
                    field,
                    given,
                    format!(
                        "must be 2 half_width / n = {derived:e} m for the window (the grid is \
                         centred on the origin)"
                    ),
                ));
            }
        }
        Ok(grid)
    }
}

impl SurfaceGrid {
    /// A grid centred on the origin covering `[-half_width_x, half_width_x] x
    /// [-half_width_y, half_width_y]` (m) with `nx * ny` elements.
    ///
    /// Errors: `nx`, `ny` in `[4, MAX_ELEMENTS_PER_SIDE]`; half widths finite and > 0.
    pub fn centred(nx: usize, ny: usize, half_width_x: f64, half_width_y: f64) -> Result<Self> {
        for (field, n) in [("grid.nx", nx), ("grid.ny", ny)] {
            if n < 4 {
                return Err(Error::invalid(
                    field,
                    n,
                    "at least 4 elements per side are needed",
                ));
            }
            if n > MAX_ELEMENTS_PER_SIDE {
                return Err(Error::invalid(
                    field,
                    n,
                    format!("at most {MAX_ELEMENTS_PER_SIDE} elements per side (memory)"),
                ));
            }
        }
        for (field, w) in [
            ("grid.half_width_x", half_width_x),
            ("grid.half_width_y", half_width_y),
        ] {
            if !(w.is_finite() && w > 0.0) {
                return Err(Error::invalid(
                    field,
                    w,
                    "the half width must be finite and > 0 (m)",
                ));
            }
        }
        Ok(Self {
            nx,
            ny,
            x_min: -half_width_x,
            y_min: -half_width_y,
            dx: 2.0 * half_width_x / nx as f64,
            dy: 2.0 * half_width_y / ny as f64,
        })
    }

    /// Elements along x.
    pub fn nx(&self) -> usize {
        self.nx
    }
    /// Elements along y.
    pub fn ny(&self) -> usize {
        self.ny
    }
    /// Number of elements `nx * ny`.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }
    /// Always false (a grid has at least 16 elements); for clippy's `len_without_is_empty`.
    pub fn is_empty(&self) -> bool {
        false
    }
    /// Element size along x, m.
    pub fn dx(&self) -> f64 {
        self.dx
    }
    /// Element size along y, m.
    pub fn dy(&self) -> f64 {
        self.dy
    }
    /// Element area dx * dy, m^2.
    pub fn element_area(&self) -> f64 {
        self.dx * self.dy
    }
    /// Lower-left corner of the window (x_min, y_min), m.
    pub fn origin(&self) -> (f64, f64) {
        (self.x_min, self.y_min)
    }
    /// Half widths of the window (x, y), m.
    pub fn half_widths(&self) -> (f64, f64) {
        (-self.x_min, -self.y_min)
    }
    /// Centre x of element column `ix`, m.
    pub fn x(&self, ix: usize) -> f64 {
        self.x_min + (ix as f64 + 0.5) * self.dx
    }
    /// Centre y of element row `iy`, m.
    pub fn y(&self, iy: usize) -> f64 {
        self.y_min + (iy as f64 + 0.5) * self.dy
    }
    /// Flat index of element `(ix, iy)`.
    pub fn index(&self, ix: usize, iy: usize) -> usize {
        iy * self.nx + ix
    }
    /// Evaluate `f(x, y)` at every element centre, in the grid's layout.
    pub fn sample(&self, f: impl Fn(f64, f64) -> f64) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.len());
        for iy in 0..self.ny {
            let y = self.y(iy);
            for ix in 0..self.nx {
                out.push(f(self.x(ix), y));
            }
        }
        out
    }
    /// Whether element `(ix, iy)` lies on the window's border.
    pub fn is_border(&self, ix: usize, iy: usize) -> bool {
        ix == 0 || iy == 0 || ix + 1 == self.nx || iy + 1 == self.ny
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn papers_grid_has_centres_on_the_contact_edge() {
        // 21 elements over [-1.5a, 1.5a]: dx = a/7 and centres fall on x = +-a (docs/theory/HALFSPACE.md 2.4.6).
        let a = 5.2964e-4;
        let g = SurfaceGrid::centred(21, 21, 1.5 * a, 1.5 * a).unwrap();
        assert!((g.x(10)).abs() < 1e-18);
        assert!((g.x(3) + a).abs() < 1e-15 && (g.x(17) - a).abs() < 1e-15);
        assert_eq!(g.index(2, 1), 23);
    }

    /// Deserialization keeps the invariants: the serialized form round-trips exactly, and
    /// grids `centred` refuses or whose element sizes do not fit the window are refused from
    /// JSON too (before: accepted as is, e.g. nx = 0 or dx = -1).
    #[test]
    fn deserialization_checks_the_rules() {
        let g = SurfaceGrid::centred(21, 16, 7.9e-4, 5.0e-4).unwrap();
        let json = serde_json::to_string(&g).unwrap();
        assert_eq!(serde_json::from_str::<SurfaceGrid>(&json).unwrap(), g);
        let written = r#"{"nx":20,"ny":20,"x_min":-1e-3,"y_min":-1e-3,"dx":1e-4,"dy":1e-4}"#;
        let read = serde_json::from_str::<SurfaceGrid>(written).unwrap();
        assert_eq!(read, SurfaceGrid::centred(20, 20, 1e-3, 1e-3).unwrap());
        for (bad, field) in [
            (
                r#"{"nx":2,"ny":20,"x_min":-1e-3,"y_min":-1e-3,"dx":1e-3,"dy":1e-4}"#,
                "grid.nx",
            ),
            (
                r#"{"nx":20,"ny":20,"x_min":1e-3,"y_min":-1e-3,"dx":1e-4,"dy":1e-4}"#,
                "grid.half_width_x",
            ),
            (
                r#"{"nx":20,"ny":20,"x_min":-1e-3,"y_min":-1e-3,"dx":-1e-4,"dy":1e-4}"#,
                "grid.dx",
            ),
            (
                r#"{"nx":20,"ny":20,"x_min":-1e-3,"y_min":-1e-3,"dx":1e-4,"dy":2e-4}"#,
                "grid.dy",
            ),
        ] {
            let err = serde_json::from_str::<SurfaceGrid>(bad).unwrap_err();
            assert!(err.to_string().starts_with(field), "{bad}: {err}");
        }
    }

    #[test]
    fn bad_grids_are_refused() {
        assert!(SurfaceGrid::centred(3, 21, 1.0, 1.0).is_err());
        assert!(SurfaceGrid::centred(21, 1 << 20, 1.0, 1.0).is_err());
        assert!(SurfaceGrid::centred(21, 21, 0.0, 1.0).is_err());
        assert!(SurfaceGrid::centred(21, 21, 1.0, f64::INFINITY).is_err());
    }
}
