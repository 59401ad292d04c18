//! Resampling a topography onto another grid by Keys' bicubic convolution (a = -1/2, the
//! Catmull-Rom spline; Keys 1981), the interpolant of [`crate::geometry::HeightMap`]: it
//! passes through the points, is C1 (its slope at a point is the central difference there,
//! from either side) and reproduces quadratics. A periodic topography wraps its neighbours
//! around ([`Boundary::Periodic`]: C1 across the period too); a bounded one (a measurement)
//! takes Keys' quadratic extrapolation at its borders ([`Boundary::Bounded`]) and is
//! undefined outside them.

use super::Topography;
use crate::error::{Error, Result};
use crate::geometry::{catmull_rom, extended};
use serde::{Deserialize, Serialize};

/// What lies beyond the topography's points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Boundary {
    /// The topography is one period of a periodic surface (a generated one).
    Periodic,
    /// Nothing: defined on `[0, (nx-1) dx] x [0, (ny-1) dy]` only (a measured one).
    Bounded,
}

/// The four neighbours' indices and the fraction along one direction of `n` points at the
/// fractional index `f`, periodic.
fn periodic_stencil(n: usize, f: f64) -> ([usize; 4], f64) {
    let fl = f.floor();
    let t = f - fl;
    let k = (fl as i64).rem_euclid(n as i64) as usize;
    let at = |d: i64| ((k as i64 + d).rem_euclid(n as i64)) as usize;
    ([at(-1), k, at(1), at(2)], t)
}

/// The interpolated height (m) at `(x, y)` (m) in the topography's frame (point (i, j) at
/// `(i dx, j dy)`); `None` outside the points for [`Boundary::Bounded`].
pub fn height_at(t: &Topography, boundary: Boundary, x: f64, y: f64) -> Option<f64> {
    let (nx, ny) = (t.nx(), t.ny());
    let (dx, dy) = t.spacing();
    let (fx, fy) = (x / dx, y / dy);
    if !(fx.is_finite() && fy.is_finite()) {
        return None;
    }
    match boundary {
        Boundary::Periodic => {
            let (ix, tx) = periodic_stencil(nx, fx);
            let (iy, ty) = periodic_stencil(ny, fy);
            let row = |j: usize| catmull_rom(ix.map(|i| t.at(i, j)), tx);
            Some(catmull_rom(iy.map(row), ty))
        }
        Boundary::Bounded => {
            let tol = 1e-12;
            let (mx, my) = ((nx - 1) as f64, (ny - 1) as f64);
            if !(fx >= -tol * mx
                && fx <= mx * (1.0 + tol)
                && fy >= -tol * my
                && fy <= my * (1.0 + tol))
            {
                return None;
            }
            let (fx, fy) = (fx.clamp(0.0, mx), fy.clamp(0.0, my));
            let i = (fx.floor() as usize).min(nx - 2);
            let j = (fy.floor() as usize).min(ny - 2);
            let (tx, ty) = (fx - i as f64, fy - j as f64);
            let row = |jj: usize| catmull_rom(extended(nx, i, |ii| t.at(ii, jj)), tx);
            Some(catmull_rom(extended(ny, j, row), ty))
        }
    }
}

/// The topography resampled onto `nx * ny` points of spacing `(dx, dy)` (m) starting at the
/// same origin: point (i, j) of the result is [`height_at`]`(i dx, j dy)`.
///
/// Errors: fewer than 2 points per direction, spacings not finite and > 0; for
/// [`Boundary::Bounded`], a new grid reaching beyond the topography's extent.
pub fn resample(
    t: &Topography,
    boundary: Boundary,
    nx: usize,
    ny: usize,
    spacing: (f64, f64),
) -> Result<Topography> {
    let (dx, dy) = spacing;
    for (f, d) in [("resample.dx", dx), ("resample.dy", dy)] {
        if !(d.is_finite() && d > 0.0) {
            return Err(Error::invalid(
                f,
                d,
                "the spacing must be finite and > 0 (m)",
            ));
        }
    }
    if nx < 2 || ny < 2 {
        return Err(Error::invalid(
            "resample.n",
            format!("{nx} x {ny}"),
            "at least 2 x 2 points",
        ));
    }
    let n = nx
        .checked_mul(ny)
        .ok_or_else(|| Error::invalid("resample.n", format!("{nx} x {ny}"), "too many points"))?;
    let mut h = super::alloc(n, 0.0, "the resampled topography")?;
    for j in 0..ny {
        for i in 0..nx {
            let (x, y) = (i as f64 * dx, j as f64 * dy);
            h[j * nx + i] = height_at(t, boundary, x, y).ok_or_else(|| {
                let (sx, sy) = t.spacing();
                Error::invalid(
                    "resample",
                    format!("{:e} x {:e} m", (nx - 1) as f64 * dx, (ny - 1) as f64 * dy),
                    format!(
                        "the new grid reaches beyond the measured extent {:e} x {:e} m",
                        (t.nx() - 1) as f64 * sx,
                        (t.ny() - 1) as f64 * sy
                    ),
                )
            })?;
        }
    }
    Topography::new(nx, ny, dx, dy, h)
}
