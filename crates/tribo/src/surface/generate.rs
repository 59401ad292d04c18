//! Generation of Gaussian rough surfaces from a power spectrum, periodic by construction.
//!
//! Two methods (`docs/theory/SURFACES.md` sec. 2):
//!
//! - [`Method::FilteredNoise`] (the default, as Tamaas's `SurfaceGeneratorFilter`): white
//!   Gaussian noise `w(x)` on the grid, transformed, multiplied by `sqrt(C(q) dq^2)`,
//!   transformed back. Every Fourier coefficient is then a complex Gaussian with
//!   `E|h_q|^2 = C(q) dq^2`: a realisation of the Gaussian random process the theories of
//!   rough contact assume (Nayak 1971; Persson 2001). Its statistics fluctuate about the
//!   spectrum's, with the standard deviations of [`super::PowerSpectrum::moments_discrete`].
//! - [`Method::RandomPhase`]: exact amplitudes `|h_q| = sqrt(C(q) dq^2)` and uniform random
//!   phases. The spectral statistics (rms height, spectral slope and curvature, every moment)
//!   equal the spectrum's exactly for every seed; the heights are Gaussian only through the
//!   central limit theorem. For tests, and where one surface must carry the target statistics
//!   without sampling error.
//!
//! The random numbers are counter-based ([`crate::stats::uniform01`] of (seed, stream, index),
//! normals by inversion): a surface depends only on its parameters and the seed, never on the
//! thread count or the order of evaluation.
//!
//! The normalisation fixes the plateau `C_r` so that the target statistic is the expectation
//! over the grid's discrete modes (exact for the random-phase method): the rms height
//! `sqrt(m_00)` or the rms slope `sqrt(m_20 + m_02)`, both computed spectrally.

use super::fft::fft2;
use super::spectrum::PowerSpectrum;
use super::{alloc, wavenumber, Topography};
use crate::error::{Error, Result};
use crate::stats::{normal_quantile, uniform01};
use rustfft::num_complex::Complex64;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Stream of the white noise in [`uniform01`].
const STREAM_NOISE: u64 = 0x5u64 << 32 | 0x0f;
/// Stream of the random phases.
const STREAM_PHASE: u64 = 0x5u64 << 32 | 0x1f;

/// How a surface is drawn (see the module documentation).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Method {
    /// Filtered white Gaussian noise: Gaussian Fourier amplitudes (the default).
    #[default]
    FilteredNoise,
    /// Exact amplitudes with random phases.
    RandomPhase,
}

/// The statistic that fixes the spectrum's level.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Normalization {
    /// Target rms height, m.
    RmsHeight(f64),
    /// Target rms slope `sqrt(<|grad h|^2>)`, dimensionless.
    RmsSlope(f64),
}

/// What to generate: the grid, the spectrum, the level, the method and the seed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GenerateParams {
    /// Points along x.
    pub nx: usize,
    /// Points along y.
    pub ny: usize,
    /// Periods (L_x, L_y), m: the spacing is `L_x / nx`, `L_y / ny`.
    pub periods: (f64, f64),
    /// The power spectrum's shape.
    pub spectrum: PowerSpectrum,
    /// Its level.
    pub normalization: Normalization,
    /// The method.
    pub method: Method,
    /// The seed.
    pub seed: u64,
}

/// The plateau `C_r` (m^4) that gives `params.normalization` on the grid's discrete modes.
///
/// Errors: a target not finite and > 0; no power on the grid (the band `[q_l, q_s]` holds no
/// mode: the short cutoff below `2 pi / L` or the roll-off above the Nyquist wavenumber).
pub fn plateau(params: &GenerateParams) -> Result<f64> {
    let (m, _) = params
        .spectrum
        .moments_discrete(params.nx, params.ny, params.periods);
    let (target, field, sum) = match params.normalization {
        Normalization::RmsHeight(s) => (s, "normalization.rms_height", m.m00),
        Normalization::RmsSlope(s) => (s, "normalization.rms_slope", m.m20 + m.m02),
    };
    if !(target.is_finite() && target > 0.0) {
        return Err(Error::invalid(
            field,
            target,
            "the target must be finite and > 0",
        ));
    }
    if !(sum.is_finite() && sum > 0.0) {
        return Err(Error::invalid(
            "spectrum",
            format!(
                "q_l = {:e}, q_s = {:e} rad/m",
                params.spectrum.rolloff, params.spectrum.cutoff
            ),
            format!(
                "no mode of the {} x {} grid lies in the spectrum's band (the grid resolves \
                 2 pi / L = {:e} to pi / dx = {:e} rad/m)",
                params.nx,
                params.ny,
                2.0 * PI / params.periods.0.max(params.periods.1),
                PI * (params.nx as f64 / params.periods.0).min(params.ny as f64 / params.periods.1)
            ),
        ));
    }
    Ok(target * target / sum)
}

/// A rough surface drawn from `params` (see the module documentation).
///
/// Errors: fewer than 2 points per direction; periods not finite and > 0; a spectrum or
/// target that breaks its rules ([`PowerSpectrum::validated`], [`plateau`]); the memory for
/// the grid (16 bytes per point for the transform, 8 for the heights) not available
/// ([`Error::OutOfMemory`]).
pub fn generate(params: &GenerateParams) -> Result<Topography> {
    let (nx, ny) = (params.nx, params.ny);
    if nx < 2 || ny < 2 {
        return Err(Error::invalid(
            "generate.n",
            format!("{nx} x {ny}"),
            "at least 2 x 2 points",
        ));
    }
    let (lx, ly) = params.periods;
    for (f, l) in [("generate.periods[0]", lx), ("generate.periods[1]", ly)] {
        if !(l.is_finite() && l > 0.0) {
            return Err(Error::invalid(
                f,
                l,
                "the period must be finite and > 0 (m)",
            ));
        }
    }
    let spectrum = params.spectrum.validated()?;
    let n = nx
        .checked_mul(ny)
        .ok_or_else(|| Error::invalid("generate.n", format!("{nx} x {ny}"), "too many points"))?;
    let c_r = plateau(params)?;
    let dq2 = (2.0 * PI).powi(2) / (lx * ly);
    let amplitude = |i: usize, j: usize| -> f64 {
        let a = spectrum.shape(wavenumber(i, nx, lx), wavenumber(j, ny, ly)) * c_r * dq2;
        a.sqrt()
    };
    let mut data = alloc(n, Complex64::new(0.0, 0.0), "the transform of the surface")?;
    match params.method {
        Method::FilteredNoise => {
            for (k, d) in data.iter_mut().enumerate() {
                d.re = normal_quantile(uniform01(params.seed, STREAM_NOISE, k as u64));
            }
            fft2(&mut data, nx, ny, true)?;
            let norm = 1.0 / (n as f64).sqrt();
            for j in 0..ny {
                for i in 0..nx {
                    data[j * nx + i] *= norm * amplitude(i, j);
                }
            }
        }
        Method::RandomPhase => {
            for j in 0..ny {
                let jm = (ny - j) % ny;
                for i in 0..nx {
                    let im = (nx - i) % nx;
                    let (k, km) = (j * nx + i, jm * nx + im);
                    // One draw per pair {q, -q}, at the smaller index; the partner is its
                    // conjugate, so that the heights are real.
                    let canonical = k.min(km) as u64;
                    let a = amplitude(i, j);
                    let u = uniform01(params.seed, STREAM_PHASE, canonical);
                    data[k] = if k == km {
                        Complex64::new(if u < 0.5 { -a } else { a }, 0.0)
                    } else {
                        let c = Complex64::from_polar(a, 2.0 * PI * u);
                        if k < km {
                            c
                        } else {
                            c.conj()
                        }
                    };
                }
            }
        }
    }
    fft2(&mut data, nx, ny, false)?;
    let heights: Vec<f64> = data.iter().map(|c| c.re).collect();
    Topography::new(nx, ny, lx / nx as f64, ly / ny as f64, heights)
}
