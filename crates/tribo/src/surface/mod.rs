//! Rough surfaces: generation of Gaussian self-affine surfaces from a power spectrum, their
//! statistics, detrending and resampling of measured topographies.
//!
//! - [`Topography`]: heights on a regular grid of `nx * ny` points, spacing `dx`, `dy` (m),
//!   point `(i, j)` at `x = i dx`, `y = j dy` with its height `heights[j * nx + i]` (x fastest,
//!   as in [`crate::grid`]). A generated surface is periodic with periods `nx dx`, `ny dy`;
//!   the spectral statistics treat any topography as one period of a periodic surface (detrend
//!   a measured one first: [`detrend`]).
//! - [`spectrum`]: the power spectral density, the isotropic power law with roll-off
//!   ([`PowerSpectrum`]), anisotropy by scaling the wavevector, and its spectral moments, both
//!   as the integrals of the continuous spectrum and as the sums over a grid's modes.
//! - [`mod@generate`]: a surface from a spectrum and a seed, by filtered white noise (the default)
//!   or random phases with exact amplitudes, normalised to a target rms height or rms slope.
//! - [`statistics`]: rms height, rms slope (spectral and finite-difference), rms curvature,
//!   the spectral moments (Nayak 1971), the radially averaged PSD with a power-law fit (the
//!   Hurst exponent), the autocorrelation.
//! - [`detrend`]: removal of the least-squares plane or polynomial of a given degree.
//! - [`resample`]: resampling onto another grid by Keys' bicubic convolution (C1).
//!
//! The conventions (the PSD's normalisation, the wavevector in rad/m) are those of
//! `docs/theory/SURFACES.md`, which also gives the sampling errors the tests use.

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

pub mod detrend;
pub(crate) mod fft;
pub mod generate;
pub mod resample;
pub mod spectrum;
pub mod statistics;
#[cfg(test)]
mod tests;

pub use generate::{generate, GenerateParams, Method, Normalization};
pub use spectrum::{PowerSpectrum, SpectralMoments};

/// Heights on a regular grid (see the module documentation for the layout), m.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Topography {
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    heights: Vec<f64>,
}

impl Topography {
    /// A topography of `nx * ny` heights (m), x fastest, spacings `dx`, `dy` (m).
    ///
    /// Errors: `nx`, `ny` >= 2; `heights.len() == nx * ny`; spacings finite and > 0; every
    /// height finite (an invalid point of a measurement must be refused or filled before).
    pub fn new(nx: usize, ny: usize, dx: f64, dy: f64, heights: Vec<f64>) -> Result<Self> {
        if nx < 2 || ny < 2 {
            return Err(Error::invalid(
                "topography",
                format!("{nx} x {ny} points"),
                "a topography needs at least 2 x 2 points",
            ));
        }
        let n = nx.checked_mul(ny).ok_or_else(|| {
            Error::invalid("topography", format!("{nx} x {ny}"), "too many points")
        })?;
        if heights.len() != n {
            return Err(Error::invalid(
                "topography.heights",
                format!("{} values", heights.len()),
                format!("expected nx * ny = {nx} * {ny} = {n} values"),
            ));
        }
        for (name, d) in [("topography.dx", dx), ("topography.dy", dy)] {
            if !(d.is_finite() && d > 0.0) {
                return Err(Error::invalid(
                    name,
                    d,
                    "the spacing must be finite and > 0 (m)",
                ));
            }
        }
        if let Some(k) = heights.iter().position(|h| !h.is_finite()) {
            return Err(Error::invalid(
                format!("topography.heights[row {}, column {}]", k / nx, k % nx),
                heights[k],
                "heights must be finite numbers (m)",
            ));
        }
        Ok(Self {
            nx,
            ny,
            dx,
            dy,
            heights,
        })
    }

    /// Points along x.
    pub fn nx(&self) -> usize {
        self.nx
    }
    /// Points along y.
    pub fn ny(&self) -> usize {
        self.ny
    }
    /// Spacings (dx, dy), m.
    pub fn spacing(&self) -> (f64, f64) {
        (self.dx, self.dy)
    }
    /// Periods (nx dx, ny dy), m: the size of the surface taken as one period.
    pub fn periods(&self) -> (f64, f64) {
        (self.nx as f64 * self.dx, self.ny as f64 * self.dy)
    }
    /// The heights, m, x fastest.
    pub fn heights(&self) -> &[f64] {
        &self.heights
    }
    /// The heights, consuming the topography.
    pub fn into_heights(self) -> Vec<f64> {
        self.heights
    }
    /// The height at point (i, j), m.
    pub fn at(&self, i: usize, j: usize) -> f64 {
        self.heights[j * self.nx + i]
    }
    /// The mean height, m.
    pub fn mean(&self) -> f64 {
        self.heights.iter().sum::<f64>() / self.heights.len() as f64
    }
    /// The same topography scaled: heights times `factor`.
    pub fn scaled(&self, factor: f64) -> Self {
        Self {
            heights: self.heights.iter().map(|h| h * factor).collect(),
            ..self.clone()
        }
    }
}

/// The wavenumber (rad/m) of FFT index `k` of `n` points over the period `period` (m):
/// `2 pi k' / period` with `k' = k` for `k <= n/2` and `k - n` above (the Nyquist index n/2 of
/// an even `n` counts as positive; its square, all that the statistics use, is the same).
pub fn wavenumber(k: usize, n: usize, period: f64) -> f64 {
    let kk = if 2 * k <= n {
        k as f64
    } else {
        k as f64 - n as f64
    };
    2.0 * std::f64::consts::PI * kk / period
}

/// Bytes of `count` values of `bytes_each`, or [`Error::OutOfMemory`] naming `what` when
/// the allocation fails (checked with `try_reserve`, so that a huge grid is refused rather
/// than aborting the process).
pub(crate) fn alloc<T: Clone>(count: usize, value: T, what: &str) -> Result<Vec<T>> {
    let mut v = Vec::new();
    v.try_reserve_exact(count).map_err(|_| Error::OutOfMemory {
        what: what.to_string(),
        bytes: count.saturating_mul(std::mem::size_of::<T>()),
    })?;
    v.resize(count, value);
    Ok(v)
}
