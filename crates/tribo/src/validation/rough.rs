//! Rows of the rough surfaces ([`crate::surface`]): the statistics of generated surfaces
//! against the spectrum they came from. Cheap: FFTs of 64^2 to 256^2 points, about 0.1 s in
//! all (release).

use super::{ErrorMeasure, ValidationRow};
use crate::error::Result;
use crate::surface::generate::plateau;
use crate::surface::statistics::{fit_power_law, moments, radial_psd, rms_slope_fd};
use crate::surface::{generate, wavenumber, GenerateParams, Method, Normalization, PowerSpectrum};
use std::f64::consts::PI;

/// The spectrum of the rows: period L = 1 mm, roll-off at 2 pi / L, power law from
/// 4 (2 pi / L) to `ks` (2 pi / L), Hurst 0.8.
fn spectrum(ks: f64) -> Result<PowerSpectrum> {
    let q0 = 2.0 * PI / 1e-3;
    PowerSpectrum::isotropic(q0, 4.0 * q0, ks * q0, 0.8)
}

/// The rows (see the module documentation and each row's source).
pub fn rough_rows() -> Result<Vec<ValidationRow>> {
    let mut rows = Vec::new();
    let l = 1e-3;
    // Random phases: the statistics are the spectrum's to round-off.
    let s = spectrum(40.0)?;
    let p = GenerateParams {
        nx: 128,
        ny: 128,
        periods: (l, l),
        spectrum: s,
        normalization: Normalization::RmsSlope(0.5),
        method: Method::RandomPhase,
        seed: 1,
    };
    let t = generate(&p)?;
    let c_r = plateau(&p)?;
    let (expect, _) = s.moments_discrete(128, 128, (l, l));
    let expect = expect.scaled(c_r);
    let got = moments(&t)?;
    let case = "self-affine H = 0.8, 128^2, random phases";
    let src = "the spectrum's discrete moments (exact amplitudes): round-off";
    rows.push(ValidationRow::new(
        case,
        "rms slope (spectral), target 0.5",
        0.5,
        got.rms_slope(),
        ErrorMeasure::Relative,
        1e-12,
        src,
    ));
    rows.push(ValidationRow::new(
        case,
        "rms height, m",
        expect.rms_height(),
        got.rms_height(),
        ErrorMeasure::Relative,
        1e-12,
        src,
    ));
    rows.push(ValidationRow::new(
        case,
        "rms curvature, 1/m",
        expect.rms_curvature(),
        got.rms_curvature(),
        ErrorMeasure::Relative,
        1e-12,
        src,
    ));
    // Forward differences: each mode through (2 sin(q d / 2) / d)^2.
    let d = l / 128.0;
    let dq2 = (2.0 * PI / l).powi(2);
    let mut fd2 = 0.0;
    for j in 0..128 {
        let qy = wavenumber(j, 128, l);
        for i in 0..128 {
            let qx = wavenumber(i, 128, l);
            fd2 += c_r
                * s.shape(qx, qy)
                * dq2
                * ((2.0 * (0.5 * qx * d).sin() / d).powi(2)
                    + (2.0 * (0.5 * qy * d).sin() / d).powi(2));
        }
    }
    rows.push(ValidationRow::new(
        case,
        "rms slope (forward differences)",
        fd2.sqrt(),
        rms_slope_fd(&t),
        ErrorMeasure::Relative,
        1e-12,
        "the spectral sum through the difference's transfer function: round-off",
    ));
    // The discrete sums against the closed-form integrals of the continuous spectrum.
    let s = spectrum(20.0)?;
    let (d, _) = s.moments_discrete(512, 512, (8.0 * l, 8.0 * l));
    let c = s.moments_continuous();
    let src = "closed-form spectral integrals (docs/theory/SURFACES.md sec. 1); first-order \
               quadrature error in dq = 2 pi / L (L = 8 mm: 1.5 %)";
    for (q, dv, cv) in [
        ("m00, m^2", d.m00, c.m00),
        ("m20", d.m20, c.m20),
        ("m40, 1/m^2", d.m40, c.m40),
    ] {
        rows.push(ValidationRow::new(
            "power law with roll-off, 512^2 modes over 8 mm",
            &format!("spectral moment {q}"),
            cv,
            dv,
            ErrorMeasure::Relative,
            0.015,
            src,
        ));
    }
    // Filtered noise: the mean over 32 seeds within 4 standard errors.
    let s = spectrum(16.0)?;
    let base = GenerateParams {
        nx: 64,
        ny: 64,
        spectrum: s,
        normalization: Normalization::RmsHeight(1e-6),
        method: Method::FilteredNoise,
        ..p
    };
    let c_r = plateau(&base)?;
    let (mean, sd) = s.moments_discrete(64, 64, (l, l));
    let seeds = 32u64;
    let mut m00 = 0.0;
    for seed in 0..seeds {
        m00 += moments(&generate(&GenerateParams { seed, ..base })?)?.m00;
    }
    m00 /= seeds as f64;
    let z = (m00 - mean.m00 * c_r) / (sd.m00 * c_r / (seeds as f64).sqrt());
    rows.push(ValidationRow::new(
        "self-affine H = 0.8, 64^2, filtered noise, 32 seeds",
        "|mean m00 - expected| / standard error",
        0.0,
        z.abs(),
        ErrorMeasure::Bound,
        4.0,
        "sampling error sqrt(2 sum a_q^2) per surface (docs/theory/SURFACES.md sec. 3)",
    ));
    // The Hurst exponent from the radially averaged PSD.
    let s = spectrum(110.0)?;
    let t = generate(&GenerateParams {
        nx: 256,
        ny: 256,
        spectrum: s,
        normalization: Normalization::RmsSlope(1.0),
        method: Method::RandomPhase,
        ..p
    })?;
    let q0 = 2.0 * PI / l;
    let fit = fit_power_law(&radial_psd(&t)?, 16.0 * q0, 110.0 * q0 / 1.2)?;
    rows.push(ValidationRow::new(
        "self-affine H = 0.8, 256^2, random phases",
        "Hurst exponent from the PSD slope -2(1 + H)",
        0.8,
        fit.hurst,
        ErrorMeasure::Absolute,
        0.01,
        "power-law fit over [16, 92] (2 pi / L): bin-averaging bias < 1e-3",
    ));
    Ok(rows)
}

#[cfg(test)]
mod tests {
    #[test]
    fn every_rough_row_passes() {
        for r in super::rough_rows().unwrap() {
            assert!(r.passed, "{r:?}");
        }
    }
}
