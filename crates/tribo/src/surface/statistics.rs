//! Statistics of a topography: rms height, slope and curvature, the spectral moments, the
//! radially averaged power spectrum with a power-law fit, and the autocorrelation.
//!
//! The spectral statistics take the topography as one period of a periodic surface: its
//! Fourier coefficients `h_q = (1/N) sum_x h(x) e^{-i q.x}` (the mean, `q = 0`, excluded),
//! with `sum_q |h_q|^2` the variance (Parseval). The derivatives are those of the
//! trigonometric interpolant (`i q_x h_q`); [`rms_slope_fd`] is the finite-difference
//! alternative, which sees each mode through the transfer function `2 sin(q dx/2) / dx`.
//! Conventions as in [`super::spectrum`] and `docs/theory/SURFACES.md`.

use super::fft::{coefficients, fft2};
use super::spectrum::SpectralMoments;
use super::{alloc, wavenumber, Topography};
use crate::error::{Error, Result};
use rustfft::num_complex::Complex64;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The rms height about the mean, `sqrt(mean((h - mean h)^2))`, m.
pub fn rms_height(t: &Topography) -> f64 {
    let m = t.mean();
    let n = t.heights().len() as f64;
    (t.heights().iter().map(|h| (h - m) * (h - m)).sum::<f64>() / n).sqrt()
}

/// The spectral moments of the topography, `m_pq = sum_q q_x^p q_y^q |h_q|^2` (see
/// [`SpectralMoments`]).
///
/// Errors: the memory for the transform ([`Error::OutOfMemory`]).
pub fn moments(t: &Topography) -> Result<SpectralMoments> {
    let (nx, ny) = (t.nx(), t.ny());
    let (lx, ly) = t.periods();
    let c = coefficients(t.heights(), nx, ny)?;
    let mut m = SpectralMoments::default();
    for j in 0..ny {
        let qy = wavenumber(j, ny, ly);
        for i in 0..nx {
            if i == 0 && j == 0 {
                continue;
            }
            m.accumulate(wavenumber(i, nx, lx), qy, c[j * nx + i].norm_sqr());
        }
    }
    Ok(m)
}

/// The rms slope `sqrt(<|grad h|^2>)` of the trigonometric interpolant (spectral).
///
/// Errors: as [`moments`].
pub fn rms_slope_spectral(t: &Topography) -> Result<f64> {
    Ok(moments(t)?.rms_slope())
}

/// The rms of the mean curvature `(h_xx + h_yy)/2` of the trigonometric interpolant, 1/m.
///
/// Errors: as [`moments`].
pub fn rms_curvature(t: &Topography) -> Result<f64> {
    Ok(moments(t)?.rms_curvature())
}

/// The rms slope by periodic forward differences, `sqrt(mean(((h_{i+1,j} - h_ij)/dx)^2 +
/// ((h_{i,j+1} - h_ij)/dy)^2))`. Mode by mode this is the spectral slope with `q_x^2`
/// replaced by `(2 sin(q_x dx / 2) / dx)^2` (and likewise in y): lower, by up to a factor
/// `2/pi` at the Nyquist wavenumber.
pub fn rms_slope_fd(t: &Topography) -> f64 {
    let (nx, ny) = (t.nx(), t.ny());
    let (dx, dy) = t.spacing();
    let mut sum = 0.0;
    for j in 0..ny {
        for i in 0..nx {
            let h = t.at(i, j);
            let sx = (t.at((i + 1) % nx, j) - h) / dx;
            let sy = (t.at(i, (j + 1) % ny) - h) / dy;
            sum += sx * sx + sy * sy;
        }
    }
    (sum / (nx * ny) as f64).sqrt()
}

/// One bin of the radially averaged power spectrum.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PsdBin {
    /// The mean wavenumber |q| of the bin's modes, rad/m.
    pub q: f64,
    /// The mean PSD of the bin's modes, `|h_q|^2 / dq^2`, m^4.
    pub psd: f64,
    /// Number of modes in the bin.
    pub modes: usize,
}

/// The radially averaged PSD: the modes `q != 0` with `|q|` up to the smaller Nyquist
/// wavenumber `pi / max(dx, dy)`, in bins of width `2 pi / min(L_x, L_y)` (the coarser
/// mode spacing), each bin's `C = |h_q|^2 / dq^2` averaged (`dq^2 = (2 pi)^2 / (L_x L_y)`).
/// Empty bins are left out.
///
/// Errors: as [`moments`].
pub fn radial_psd(t: &Topography) -> Result<Vec<PsdBin>> {
    let (nx, ny) = (t.nx(), t.ny());
    let (lx, ly) = t.periods();
    let (dx, dy) = t.spacing();
    let c = coefficients(t.heights(), nx, ny)?;
    let dq2 = (2.0 * PI).powi(2) / (lx * ly);
    let width = 2.0 * PI / lx.min(ly);
    let q_max = PI / dx.max(dy);
    let nbins = (q_max / width).floor() as usize + 1;
    let mut acc = vec![(0.0, 0.0, 0usize); nbins];
    for j in 0..ny {
        let qy = wavenumber(j, ny, ly);
        for i in 0..nx {
            if i == 0 && j == 0 {
                continue;
            }
            let q = wavenumber(i, nx, lx).hypot(qy);
            if q > q_max * (1.0 + 1e-12) {
                continue;
            }
            let b = ((q / width).round() as usize).min(nbins - 1);
            acc[b].0 += q;
            acc[b].1 += c[j * nx + i].norm_sqr() / dq2;
            acc[b].2 += 1;
        }
    }
    Ok(acc
        .into_iter()
        .filter(|a| a.2 > 0)
        .map(|(q, p, n)| PsdBin {
            q: q / n as f64,
            psd: p / n as f64,
            modes: n,
        })
        .collect())
}

/// A least-squares power law `C = A q^e` through PSD bins.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PowerLawFit {
    /// The exponent `e` (`-2 (1 + H)` for a self-affine surface).
    pub exponent: f64,
    /// The Hurst exponent `H = -e/2 - 1`.
    pub hurst: f64,
    /// The prefactor `A`, m^4 (rad/m)^(-e).
    pub prefactor: f64,
    /// Bins used.
    pub bins: usize,
}

/// Fits `ln C = ln A + e ln q` by least squares over the bins with `q_min <= q <= q_max`
/// (rad/m), each bin weighted by its number of modes (the variance of a bin's mean PSD is
/// inversely proportional to it).
///
/// Errors: fewer than 2 bins with a positive PSD in the range.
pub fn fit_power_law(bins: &[PsdBin], q_min: f64, q_max: f64) -> Result<PowerLawFit> {
    let used: Vec<&PsdBin> = bins
        .iter()
        .filter(|b| b.q >= q_min && b.q <= q_max && b.psd > 0.0)
        .collect();
    if used.len() < 2 {
        return Err(Error::invalid(
            "fit range",
            format!("[{q_min:e}, {q_max:e}] rad/m"),
            format!("{} usable bins: at least 2 needed", used.len()),
        ));
    }
    let (mut sw, mut sx, mut sy, mut sxx, mut sxy) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for b in &used {
        let (w, x, y) = (b.modes as f64, b.q.ln(), b.psd.ln());
        sw += w;
        sx += w * x;
        sy += w * y;
        sxx += w * x * x;
        sxy += w * x * y;
    }
    let det = sw * sxx - sx * sx;
    if !(det.is_finite() && det > 0.0) {
        return Err(Error::invalid(
            "fit range",
            format!("[{q_min:e}, {q_max:e}] rad/m"),
            "the bins span a single wavenumber",
        ));
    }
    let e = (sw * sxy - sx * sy) / det;
    let ln_a = (sy - e * sx) / sw;
    Ok(PowerLawFit {
        exponent: e,
        hurst: -0.5 * e - 1.0,
        prefactor: ln_a.exp(),
        bins: used.len(),
    })
}

/// The (periodic) autocorrelation `R(r) = mean_x (h(x) - mean h)(h(x + r) - mean h)` at the
/// lags `r = (i dx, j dy)`, `i < nx`, `j < ny` (lags beyond half the period are the negative
/// ones, wrapped), m^2, by FFT (Wiener-Khinchin: `R(r) = sum_q |h_q|^2 e^{i q.r}`). `R(0)`
/// is the variance.
///
/// Errors: as [`moments`].
pub fn autocorrelation(t: &Topography) -> Result<Vec<f64>> {
    let (nx, ny) = (t.nx(), t.ny());
    let c = coefficients(t.heights(), nx, ny)?;
    let mut p = alloc(c.len(), Complex64::new(0.0, 0.0), "the autocorrelation")?;
    for (p, c) in p.iter_mut().zip(&c).skip(1) {
        p.re = c.norm_sqr();
    }
    fft2(&mut p, nx, ny, false)?;
    Ok(p.iter().map(|z| z.re).collect())
}
