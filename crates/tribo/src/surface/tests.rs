//! Tests of the surface module: the generated statistics against the spectrum they came from.

use super::detrend::{detrend_plane, detrend_polynomial};
use super::generate::plateau;
use super::resample::{height_at, resample, Boundary};
use super::statistics::{
    autocorrelation, fit_power_law, moments, radial_psd, rms_height, rms_slope_fd,
    rms_slope_spectral,
};
use super::*;
use std::f64::consts::PI;

/// A spectrum in units of the fundamental `2 pi / L` of a period `l`: roll-off at `kl`,
/// power law from `kr` to `ks`.
fn spectrum(l: f64, kl: f64, kr: f64, ks: f64, h: f64) -> PowerSpectrum {
    let q0 = 2.0 * PI / l;
    PowerSpectrum::isotropic(kl * q0, kr * q0, ks * q0, h).unwrap()
}

fn params(
    n: usize,
    l: f64,
    s: PowerSpectrum,
    norm: Normalization,
    method: Method,
) -> GenerateParams {
    GenerateParams {
        nx: n,
        ny: n,
        periods: (l, l),
        spectrum: s,
        normalization: norm,
        method,
        seed: 7,
    }
}

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// Random phases with exact amplitudes: every spectral moment of the surface equals the
/// spectrum's discrete moment (round-off: FFT error ~ 1e-15 log N, bound 1e-11), on an
/// anisotropic spectrum over a non-square grid too; the rms height or slope equals its
/// target. The finite-difference slope equals the spectral sum through the forward
/// difference's transfer function `(2 sin(q dx/2)/dx)^2`, exactly as well.
#[test]
fn random_phase_statistics_are_exact() {
    let (nx, ny, lx, ly) = (96usize, 64usize, 2e-3, 1.5e-3);
    for (aniso, norm) in [
        ([1.0, 1.0], Normalization::RmsHeight(1e-6)),
        ([1.0, 2.5], Normalization::RmsSlope(0.2)),
    ] {
        let s = PowerSpectrum::isotropic(
            2.0 * PI / lx,
            4.0 * 2.0 * PI / lx,
            40.0 * 2.0 * PI / lx,
            0.7,
        )
        .unwrap()
        .with_anisotropy(aniso)
        .unwrap();
        let p = GenerateParams {
            nx,
            ny,
            periods: (lx, ly),
            spectrum: s,
            normalization: norm,
            method: Method::RandomPhase,
            seed: 11,
        };
        let t = generate(&p).unwrap();
        let c_r = plateau(&p).unwrap();
        let (expect, _) = s.moments_discrete(nx, ny, (lx, ly));
        let expect = expect.scaled(c_r);
        let got = moments(&t).unwrap();
        for (name, g, e) in [
            ("m00", got.m00, expect.m00),
            ("m20", got.m20, expect.m20),
            ("m02", got.m02, expect.m02),
            ("m40", got.m40, expect.m40),
            ("m04", got.m04, expect.m04),
            ("m22", got.m22, expect.m22),
        ] {
            assert!(rel(g, e) < 1e-11, "{aniso:?} {name}: {g:e} vs {e:e}");
        }
        assert!(got.m11.abs() < 1e-11 * got.m20, "m11 {:e}", got.m11);
        match norm {
            Normalization::RmsHeight(s) => assert!(rel(rms_height(&t), s) < 1e-11),
            Normalization::RmsSlope(s) => assert!(rel(rms_slope_spectral(&t).unwrap(), s) < 1e-11),
        }
        // The forward differences, mode by mode.
        let (dx, dy) = t.spacing();
        let dq2 = (2.0 * PI).powi(2) / (lx * ly);
        let mut fd2 = 0.0;
        for j in 0..ny {
            let qy = wavenumber(j, ny, ly);
            for i in 0..nx {
                let qx = wavenumber(i, nx, lx);
                let a = c_r * s.shape(qx, qy) * dq2;
                fd2 += a
                    * ((2.0 * (0.5 * qx * dx).sin() / dx).powi(2)
                        + (2.0 * (0.5 * qy * dy).sin() / dy).powi(2));
            }
        }
        assert!(rel(rms_slope_fd(&t), fd2.sqrt()) < 1e-11);
        // Anisotropy elongates the features along y: the slope along y is smaller.
        if aniso[1] > 1.0 {
            assert!(got.m02 < 0.5 * got.m20, "{:e} {:e}", got.m02, got.m20);
        }
    }
}

/// The discrete moments converge to the closed-form integrals of the continuous spectrum
/// as the mode spacing dq = 2 pi / L shrinks: the sums are a lattice quadrature of a
/// spectrum with jumps at q_l, q_r and q_s, first order in dq/q_l, with the fluctuations of
/// lattice-point counts in annuli (Gauss's circle problem), so the error is not monotone
/// from one grid to the next. Fixed q_l, q_r, q_s; L and N doubled together (dq/q_l = 1,
/// 1/2, 1/4, 1/8): the errors of m00, m20 and m40 stay below 0.05 dq/q_l (measured at most
/// 0.043 dq/q_l) and fall by more than 3 over the eightfold refinement (measured 3.5 to 35).
#[test]
fn discrete_moments_converge_to_the_continuous_integrals() {
    let s = PowerSpectrum::isotropic(
        2.0 * PI / 1e-3,
        3.0 * 2.0 * PI / 1e-3,
        20.0 * 2.0 * PI / 1e-3,
        0.8,
    )
    .unwrap();
    let c = s.moments_continuous();
    let mut errors = Vec::new();
    for k in 0..4 {
        let f = 1usize << k;
        let (n, l) = (64 * f, 1e-3 * f as f64);
        let (d, _) = s.moments_discrete(n, n, (l, l));
        let e = [rel(d.m00, c.m00), rel(d.m20, c.m20), rel(d.m40, c.m40)];
        for m in e {
            assert!(m < 0.05 / f as f64, "dq/q_l = 1/{f}: {e:?}");
        }
        errors.push(e);
    }
    for m in 0..3 {
        assert!(errors[0][m] / errors[3][m] > 3.0, "{errors:?}");
    }
    // Isotropy: m40 = m04 = 3 m22 (angular integrals 3 pi/4 and pi/4).
    assert!(rel(c.m40, 3.0 * c.m22) < 1e-14 && rel(c.m20, c.m02) < 1e-14);
}

/// Filtered white noise: over 64 seeds, the mean of each statistic (the squared rms height,
/// slope and curvature) lies within 4 standard errors of the spectrum's value, the standard
/// error being the predicted standard deviation `sqrt(2 sum a_q^2)` (of one realisation, from
/// the exponential distribution of |h_q|^2) over sqrt(64); and the sample standard
/// deviation agrees with the prediction within 35 % (the relative standard error of a sample
/// standard deviation of 64 near-Gaussian values is 1/sqrt(2 * 63) = 9 %: 35 % is about 4 of
/// those).
#[test]
fn filtered_noise_statistics_within_the_sampling_error() {
    let (n, l) = (64usize, 1e-3);
    let s = spectrum(l, 1.0, 2.0, 16.0, 0.8);
    let base = params(
        n,
        l,
        s,
        Normalization::RmsHeight(1e-6),
        Method::FilteredNoise,
    );
    let c_r = plateau(&base).unwrap();
    let (mean, sd) = s.moments_discrete(n, n, (l, l));
    let (mean, sd) = (mean.scaled(c_r), sd.scaled(c_r));
    let seeds = 64;
    let mut samples: Vec<[f64; 3]> = Vec::new();
    for seed in 0..seeds {
        let t = generate(&GenerateParams { seed, ..base }).unwrap();
        let m = moments(&t).unwrap();
        samples.push([m.m00, m.m20 + m.m02, m.m40 + 2.0 * m.m22 + m.m04]);
    }
    // The sd of a sum of moments: sqrt(2 sum (w1 + w2)^2 a^2) needs the cross terms, so the
    // prediction for slope^2 and curvature^2 is computed mode by mode here.
    let dq2 = (2.0 * PI / l).powi(2);
    let (mut v_slope, mut v_curv) = (0.0, 0.0);
    for j in 0..n {
        let qy = wavenumber(j, n, l);
        for i in 0..n {
            let qx = wavenumber(i, n, l);
            let a = c_r * s.shape(qx, qy) * dq2;
            let q2 = qx * qx + qy * qy;
            v_slope += 2.0 * (q2 * a).powi(2);
            v_curv += 2.0 * (q2 * q2 * a).powi(2);
        }
    }
    let expect = [
        (mean.m00, sd.m00),
        (mean.m20 + mean.m02, v_slope.sqrt()),
        (mean.m40 + 2.0 * mean.m22 + mean.m04, v_curv.sqrt()),
    ];
    for (k, (e, sd)) in expect.into_iter().enumerate() {
        let xs: Vec<f64> = samples.iter().map(|s| s[k]).collect();
        let m = xs.iter().sum::<f64>() / seeds as f64;
        let var = xs.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (seeds - 1) as f64;
        let se = sd / (seeds as f64).sqrt();
        assert!(
            (m - e).abs() < 4.0 * se,
            "stat {k}: mean {m:e} vs {e:e} (se {se:e})"
        );
        assert!(
            rel(var.sqrt(), sd) < 0.35,
            "stat {k}: sd {:e} vs {sd:e}",
            var.sqrt()
        );
        // The fluctuation is real: a realisation is not exact (unlike the random phases).
        assert!(sd > 1e-3 * e);
    }
}

/// The radially averaged PSD of a random-phase surface follows the power law with exponent
/// -2(1 + H): the fit over [2 q_r, q_s / 1.2] recovers H within 0.01 (the bins average C over
/// annuli of width dq; at q >= 2 q_r = 16 dq the convexity bias of ln C is below 1e-3). For
/// filtered noise (one 256^2 surface per seed, 4 seeds) within 0.05: the fit uses about 100
/// bins of 50 to 500 modes each, each bin's ln C with a standard deviation of about
/// 1/sqrt(modes / 2) <= 0.2, which puts the slope's standard error near 0.01.
#[test]
fn psd_slope_recovers_the_hurst_exponent() {
    let (n, l) = (256usize, 1e-3);
    for h in [0.3, 0.8] {
        let s = spectrum(l, 1.0, 8.0, 110.0, h);
        let q0 = 2.0 * PI / l;
        let t = generate(&params(
            n,
            l,
            s,
            Normalization::RmsSlope(1.0),
            Method::RandomPhase,
        ))
        .unwrap();
        let fit = fit_power_law(&radial_psd(&t).unwrap(), 16.0 * q0, 110.0 * q0 / 1.2).unwrap();
        assert!((fit.hurst - h).abs() < 0.01, "H = {h}: {fit:?}");
        assert!(rel(fit.exponent, -2.0 * (1.0 + h)) < 0.01 / (1.0 + h));
        for seed in 1..5 {
            let t = generate(&GenerateParams {
                seed,
                ..params(n, l, s, Normalization::RmsSlope(1.0), Method::FilteredNoise)
            })
            .unwrap();
            let fit = fit_power_law(&radial_psd(&t).unwrap(), 16.0 * q0, 110.0 * q0 / 1.2).unwrap();
            assert!(
                (fit.hurst - h).abs() < 0.05,
                "H = {h}, seed {seed}: {fit:?}"
            );
        }
    }
}

/// The FFT autocorrelation equals the direct periodic sum (round-off), R(0) is the variance.
#[test]
fn autocorrelation_matches_the_direct_sum() {
    let (nx, ny) = (8usize, 6usize);
    let h: Vec<f64> = (0..nx * ny)
        .map(|k| ((k * 7919) % 17) as f64 / 17.0 - 0.3)
        .collect();
    let t = Topography::new(nx, ny, 0.1, 0.2, h).unwrap();
    let r = autocorrelation(&t).unwrap();
    let m = t.mean();
    for dj in 0..ny {
        for di in 0..nx {
            let mut s = 0.0;
            for j in 0..ny {
                for i in 0..nx {
                    s += (t.at(i, j) - m) * (t.at((i + di) % nx, (j + dj) % ny) - m);
                }
            }
            s /= (nx * ny) as f64;
            assert!((r[dj * nx + di] - s).abs() < 1e-14, "{di} {dj}");
        }
    }
    assert!(rel(r[0], rms_height(&t).powi(2)) < 1e-13);
}

/// A surface depends only on its parameters and seed; another seed gives another surface;
/// both methods give zero-mean, real surfaces.
#[test]
fn generation_is_deterministic() {
    let s = spectrum(1e-3, 1.0, 2.0, 12.0, 0.8);
    for method in [Method::FilteredNoise, Method::RandomPhase] {
        let p = params(32, 1e-3, s, Normalization::RmsHeight(1e-6), method);
        let a = generate(&p).unwrap();
        let b = generate(&p).unwrap();
        assert_eq!(a, b);
        let c = generate(&GenerateParams { seed: 8, ..p }).unwrap();
        assert_ne!(a, c);
        assert!(a.mean().abs() < 1e-12 * 1e-6 * 1e3);
    }
    // Errors name the field.
    let bad = params(
        32,
        1e-3,
        s,
        Normalization::RmsHeight(-1.0),
        Method::RandomPhase,
    );
    assert!(generate(&bad)
        .unwrap_err()
        .to_string()
        .contains("rms_height"));
    // A band beyond the grid's Nyquist wavenumber has no mode.
    let high = spectrum(1e-3, 100.0, 200.0, 300.0, 0.8);
    let e = generate(&params(
        32,
        1e-3,
        high,
        Normalization::RmsHeight(1e-6),
        Method::RandomPhase,
    ))
    .unwrap_err();
    assert!(e.to_string().contains("no mode"), "{e}");
    assert!(PowerSpectrum::isotropic(1.0, 2.0, 1.5, 0.8).is_err());
    assert!(PowerSpectrum::isotropic(1.0, 2.0, 3.0, 1.5).is_err());
}

/// Detrending removes a polynomial of the fitted degree to round-off, leaves the residual
/// orthogonal to the removed basis (least squares), and the plane fit of a tilted
/// zero-mean periodic surface recovers the tilt.
#[test]
fn detrending_removes_polynomials() {
    let (nx, ny, d) = (40usize, 30usize, 1e-5);
    let s = spectrum(nx as f64 * d, 1.0, 2.0, 10.0, 0.8);
    let rough = generate(&GenerateParams {
        nx,
        ny,
        periods: (nx as f64 * d, ny as f64 * d),
        ..params(
            nx,
            1.0,
            s,
            Normalization::RmsHeight(1e-7),
            Method::RandomPhase,
        )
    })
    .unwrap();
    let poly =
        |x: f64, y: f64| 2e-6 + 0.01 * x - 0.02 * y + 30.0 * x * x - 10.0 * x * y + 5.0 * y * y;
    let h: Vec<f64> = (0..nx * ny)
        .map(|k| poly((k % nx) as f64 * d, (k / nx) as f64 * d))
        .collect();
    let pure = Topography::new(nx, ny, d, d, h.clone()).unwrap();
    let r = detrend_polynomial(&pure, 2).unwrap();
    let worst = r
        .residual
        .heights()
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(worst < 1e-12 * 2e-6, "{worst:e}");
    // A plane leaves the quadratic part.
    let r1 = detrend_plane(&pure).unwrap();
    assert!(rms_height(&r1.residual) > 1e-9);
    // Rough plus quadric: the residual is orthogonal to 1, x, y, x^2, xy, y^2.
    let sum: Vec<f64> = h.iter().zip(rough.heights()).map(|(a, b)| a + b).collect();
    let t = Topography::new(nx, ny, d, d, sum).unwrap();
    let r = detrend_polynomial(&t, 2).unwrap();
    for (p, q) in [(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2)] {
        let dot: f64 = (0..nx * ny)
            .map(|k| {
                let (x, y) = ((k % nx) as f64 / nx as f64, (k / nx) as f64 / ny as f64);
                r.residual.heights()[k] * x.powi(p) * y.powi(q)
            })
            .sum();
        assert!(
            dot.abs() < 1e-12 * (nx * ny) as f64 * 1e-7,
            "x^{p} y^{q}: {dot:e}"
        );
    }
    assert!(detrend_polynomial(&t, 11).is_err());
    assert!(
        detrend_polynomial(&Topography::new(3, 3, 1.0, 1.0, vec![0.0; 9]).unwrap(), 3).is_err()
    );
}

/// Keys' interpolation: the points themselves are reproduced; a periodic sine converges at
/// third order (Keys 1981: O(h^3)), the error falling by about 8 per halving (> 6 asserted);
/// the bounded variant reproduces a quadratic up to the border and refuses points outside.
#[test]
fn resampling_is_third_order_and_exact_on_quadratics() {
    let mut errs = Vec::new();
    for n in [16usize, 32, 64] {
        let l = 1.0;
        let d = l / n as f64;
        let f = |x: f64, y: f64| (2.0 * PI * x).sin() * (2.0 * PI * 2.0 * y).cos();
        let h: Vec<f64> = (0..n * n)
            .map(|k| f((k % n) as f64 * d, (k / n) as f64 * d))
            .collect();
        let t = Topography::new(n, n, d, d, h).unwrap();
        assert_eq!(
            height_at(&t, Boundary::Periodic, 3.0 * d, 5.0 * d),
            Some(t.at(3, 5))
        );
        let mut e = 0.0f64;
        for k in 0..200 {
            let (x, y) = (
                (k as f64 * 0.618_034) % 1.3 - 0.15,
                (k as f64 * 0.754_878) % 1.0,
            );
            e = e.max((height_at(&t, Boundary::Periodic, x, y).unwrap() - f(x, y)).abs());
        }
        errs.push(e);
    }
    assert!(
        errs[0] / errs[1] > 6.0 && errs[1] / errs[2] > 6.0,
        "{errs:?}"
    );
    let q = |x: f64, y: f64| 1.0 + x - 2.0 * y + 0.5 * x * x + 0.3 * x * y - 0.7 * y * y;
    let (nx, ny, d) = (7usize, 5usize, 0.25);
    let h: Vec<f64> = (0..nx * ny)
        .map(|k| q((k % nx) as f64 * d, (k / nx) as f64 * d))
        .collect();
    let t = Topography::new(nx, ny, d, d, h).unwrap();
    let r = resample(&t, Boundary::Bounded, 13, 9, (0.125, 0.125)).unwrap();
    for j in 0..9 {
        for i in 0..13 {
            let v = q(i as f64 * 0.125, j as f64 * 0.125);
            assert!((r.at(i, j) - v).abs() < 1e-12, "{i} {j}");
        }
    }
    assert!(resample(&t, Boundary::Bounded, 14, 9, (0.125, 0.125)).is_err());
    assert_eq!(height_at(&t, Boundary::Bounded, -0.01, 0.0), None);
}
