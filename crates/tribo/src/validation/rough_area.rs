//! Rows of the contact area of self-affine rough surfaces at small loads: the true contact
//! area grows linearly with the load,
//!
//! ```text
//! A / A0 = kappa p_mean / (E* h'_rms),
//! ```
//!
//! `h'_rms = sqrt(<|grad h|^2>)` the rms slope of the surface (Hyun, Pei, Molinari & Robbins
//! 2004, Phys. Rev. E 70 026117). What the literature reports for kappa
//! (docs/theory/SURFACES.md section 7):
//! - Persson's theory (Persson 2001) at small loads: `kappa = sqrt(8 / pi) = 1.60`;
//! - Bush, Gibson & Thomas (1975), asperity theory at small loads: `kappa = sqrt(2 pi) = 2.51`;
//! - numerical solutions lie between the two: Hyun et al. (2004) find the area linear in the
//!   load at small loads with kappa near 2, and Yastrebov, Anciaux & Molinari (2017, JMPS 107)
//!   that at a given pressure the area decreases (logarithmically) with the spectrum's breadth
//!   (Nayak's parameter): a narrow spectrum sits towards the upper end.
//!
//! The expected range is therefore `[sqrt(8/pi), sqrt(2 pi)]` ([`kappa_range`]). The case: a
//! periodic surface, Hurst exponent 0.8, power from 4 to 32 wavelengths per period (a narrow
//! spectrum: Nayak's parameter 5.2 along x), rms slope 1, random phases, 256 x 256 elements (8
//! per shortest wavelength), three seeds, the mean pressures `p / (E* h'_rms)` = 0.005, 0.01,
//! 0.02, 0.04 (area fractions 1 % to 9 %), the area counted in elements in contact.
//! Measured: kappa 2.31 (seeds 2.39, 2.30, 2.24, element-integrated kernel; the spectral kernel
//! gives 1 % more); on the grid of 128^2 (4 elements per shortest wavelength) 2.51: counting
//! elements overestimates the area by a fraction of the elements on the patches' borders
//! (Yastrebov, Anciaux & Molinari 2017b), which falls as the grid is refined. The ratio
//! `A / A0 / p` falls by ~10 % from 1 % to 9 % area: the area is slightly sub-linear (the
//! power-law exponent of A against p is 0.95). Cost: 12 solves of 256^2, ~3 s on two cores.

use super::{ErrorMeasure, ValidationRow};
use crate::error::Result;
use crate::grid::SurfaceGrid;
use crate::kernels::periodic::PeriodicKernel;
use crate::solvers::normal::{
    normal_compliance_operator_periodic, solve_normal_from, NormalContactParams,
    NormalContactProblem, NormalLoading,
};
use crate::surface::statistics::rms_slope_spectral;
use crate::surface::{generate, GenerateParams, Method, Normalization, PowerSpectrum};
use std::f64::consts::PI;

/// Composite modulus of the rows, Pa (any value: the rows are dimensionless).
const E_STAR: f64 = 1.0e11;
/// The period, m.
const PERIOD: f64 = 1.0e-3;

/// The (lower, upper) bounds of kappa from the literature (module docs): Persson's
/// `sqrt(8/pi)` and Bush, Gibson & Thomas's `sqrt(2 pi)`.
pub fn kappa_range() -> (f64, f64) {
    ((8.0 / PI).sqrt(), (2.0 * PI).sqrt())
}

/// The mean pressures of the rows, `p_mean / (E* h'_rms)`.
pub const LOADS: [f64; 4] = [0.005, 0.01, 0.02, 0.04];

/// A self-affine surface: `n x n` points over one period, Hurst exponent `hurst`, power
/// from the roll-off `k_l` to the cutoff `k_s` (wavelengths per period), rms slope 1 (random
/// phases, exact amplitudes), `seed`.
fn surface(n: usize, hurst: f64, k_l: f64, k_s: f64, seed: u64) -> Result<Vec<f64>> {
    let q0 = 2.0 * PI / PERIOD;
    let spectrum = PowerSpectrum::isotropic(k_l * q0, k_l * q0, k_s * q0, hurst)?;
    let t = generate(&GenerateParams {
        nx: n,
        ny: n,
        periods: (PERIOD, PERIOD),
        spectrum,
        normalization: Normalization::RmsSlope(1.0),
        method: Method::RandomPhase,
        seed,
    })?;
    let slope = rms_slope_spectral(&t)?;
    Ok(t.heights().iter().map(|h| h / slope).collect())
}

/// The contact area fraction `A / A0` of the surface at each dimensionless mean pressure
/// `p_mean / (E* h'_rms)` of `loads` (increasing; each solve warm-started from the last).
pub fn area_fractions(
    n: usize,
    hurst: f64,
    band: (f64, f64),
    seed: u64,
    loads: &[f64],
    kernel: PeriodicKernel,
) -> Result<Vec<f64>> {
    let grid = SurfaceGrid::centred(n, n, 0.5 * PERIOD, 0.5 * PERIOD)?;
    let z = surface(n, hurst, band.0, band.1, seed)?;
    let h: Vec<f64> = z.iter().map(|z| -z).collect();
    let operator = normal_compliance_operator_periodic(&grid, E_STAR, kernel);
    let params = NormalContactParams::default().with_tolerance(1e-8)?;
    let mut start: Option<Vec<f64>> = None;
    let mut out = Vec::new();
    for &load in loads {
        let problem = NormalContactProblem {
            grid: &grid,
            initial_gap: &h,
            composite_modulus: E_STAR,
            loading: NormalLoading::Force(load * E_STAR * PERIOD * PERIOD),
        };
        let s = solve_normal_from(&problem, &params, Some(&operator), start.as_deref(), None)?;
        out.push(s.contact_elements as f64 / grid.len() as f64);
        start = Some(s.pressure);
    }
    Ok(out)
}

/// Least-squares slope through the origin of `y` against `x` and the rms relative deviation
/// of the points from it.
pub fn fit_through_origin(x: &[f64], y: &[f64]) -> (f64, f64) {
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| a * b).sum();
    let sxx: f64 = x.iter().map(|a| a * a).sum();
    let k = sxy / sxx;
    let r = x
        .iter()
        .zip(y)
        .map(|(a, b)| ((b - k * a) / (k * a)).powi(2))
        .sum::<f64>()
        / x.len() as f64;
    (k, r.sqrt())
}

/// The power-law exponent `beta` of `y = c x^beta`, by least squares in logarithms.
pub fn power_law_exponent(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    let lx: Vec<f64> = x.iter().map(|v| v.ln()).collect();
    let ly: Vec<f64> = y.iter().map(|v| v.ln()).collect();
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&ly).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = lx.iter().map(|a| (a - mx).powi(2)).sum();
    sxy / sxx
}

/// The rows (module docs).
pub fn rough_area_rows() -> Result<Vec<ValidationRow>> {
    let seeds = [0u64, 1, 2];
    let mut mean = [0.0; LOADS.len()];
    for &seed in &seeds {
        let a = area_fractions(
            256,
            0.8,
            (4.0, 32.0),
            seed,
            &LOADS,
            PeriodicKernel::ElementIntegrated,
        )?;
        for (m, v) in mean.iter_mut().zip(a) {
            *m += v / seeds.len() as f64;
        }
    }
    let (kappa, residual) = fit_through_origin(&LOADS, &mean);
    let beta = power_law_exponent(&LOADS, &mean);
    let (lo, hi) = kappa_range();
    let case = "self-affine H = 0.8, k = 4..32 per period, rms slope 1, 256^2, 3 seeds, \
                p/(E* h'rms) = 0.005..0.04 (area 1-9 %), periodic element kernel";
    let src = "Persson 2001 sqrt(8/pi) and Bush, Gibson & Thomas 1975 sqrt(2 pi) bound the \
               numerical values (Hyun et al. 2004; Yastrebov, Anciaux & Molinari 2017)";
    Ok(vec![
        // Pass when kappa lies in the literature's range: reference its middle, tolerance
        // its half-width (measured 2.31; a compliance off by 2 would give 1.2 or 4.6).
        ValidationRow::new(
            case,
            "kappa in A/A0 = kappa p/(E* h'rms), fit through the origin (range 1.60-2.51)",
            0.5 * (lo + hi),
            kappa,
            ErrorMeasure::Absolute,
            0.5 * (hi - lo),
            src,
        ),
        // Linear at small loads: the exponent of a power-law fit is 1 within 0.1 (measured
        // 0.95: the ratio A/p falls ~10 % over the range, the onset of the sub-linear growth).
        ValidationRow::new(
            case,
            "exponent beta of A/A0 ~ p^beta",
            1.0,
            beta,
            ErrorMeasure::Absolute,
            0.1,
            "Hyun et al. 2004 (area linear in load at small loads)",
        ),
        // The through-origin fit's rms relative residual (measured 0.060, the sub-linear
        // trend of +-5 % over the range); bound 0.1.
        ValidationRow::new(
            case,
            "rms relative residual of the linear fit through the origin",
            0.0,
            residual,
            ErrorMeasure::Bound,
            0.1,
            "Hyun et al. 2004 (area linear in load at small loads)",
        ),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_rough_area_row_passes() {
        for r in rough_area_rows().unwrap() {
            eprintln!("{} = {} (error {})", r.quantity, r.computed, r.error);
            assert!(r.passed, "{r:?}");
        }
    }

    #[test]
    fn fits_recover_known_laws() {
        let x = [1.0, 2.0, 4.0];
        let y: Vec<f64> = x.iter().map(|v| 3.0 * v).collect();
        let (k, r) = fit_through_origin(&x, &y);
        assert!((k - 3.0).abs() < 1e-14 && r < 1e-14);
        let y: Vec<f64> = x.iter().map(|v: &f64| 2.0 * v.powf(0.9)).collect();
        assert!((power_law_exponent(&x, &y) - 0.9).abs() < 1e-14);
    }

    #[test]
    fn the_nayak_parameter_of_the_rows_spectrum() {
        let q0 = 2.0 * PI / PERIOD;
        let s = PowerSpectrum::isotropic(4.0 * q0, 4.0 * q0, 32.0 * q0, 0.8).unwrap();
        let alpha = s.moments_continuous().bandwidth();
        // The value quoted in the module docs.
        assert!((alpha - 5.23).abs() < 0.05, "{alpha}");
    }
}
