#![allow(clippy::excessive_precision)] // reference values as printed (20 digits, mpmath)

use super::*;

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// Phi^-1 at the exact binary value of each p, from mpmath (60 digits: sqrt 2 erfinv(2p - 1),
/// and a root of ln Phi(z) = ln p in the far tail). AS 241 claims about 1e-16 relative; 2e-15
/// allows the final rounding of its rational functions (a few ulp) and fails on any wrong
/// coefficient (those change the result in the 8th digit or earlier).
#[test]
fn normal_quantile_matches_printed_values() {
    let cases = [
        (0.975, 1.959_963_984_540_053_9),
        (0.025, -1.959_963_984_540_054_2),
        (0.9, 1.281_551_565_544_600_6),
        (0.75, 0.674_489_750_196_081_7),
        (0.3, -0.524_400_512_708_040_8),
        (0.08, -1.405_071_560_309_632_5),
        (0.92, 1.405_071_560_309_632_8),
        (0.999_999, 4.753_424_308_817_087_8),
        (1.0 - 1e-12, 7.034_486_910_047_835),
        (1e-10, -6.361_340_902_404_056),
        (1e-20, -9.262_340_089_798_408),
        (1e-300, -37.047_096_299_361_2),
        (0.500_000_1, 2.506_628_273_311_648_3e-7),
    ];
    for (p, z) in cases {
        let got = normal_quantile(p);
        assert!(
            rel(got, z) < 2e-15,
            "p = {p:e}: {got} vs {z} ({:e})",
            rel(got, z)
        );
    }
    assert_eq!(normal_quantile(0.5), 0.0);
    assert_eq!(normal_quantile(0.0), f64::NEG_INFINITY);
    assert_eq!(normal_quantile(1.0), f64::INFINITY);
    assert!(normal_quantile(1.5).is_nan() && normal_quantile(-0.1).is_nan());
    assert!(normal_quantile(f64::NAN).is_nan());
}

/// The normal CDF at printed values (mpmath ncdf, 20 digits); the library's Phi is the
/// incomplete-gamma evaluation of woehler::stats, accurate to ~1e-14 relative.
#[test]
fn normal_cdf_matches_printed_values() {
    let d = Distribution::Normal { mean: 0.0, sd: 1.0 };
    assert!(rel(d.cdf(1.0), 0.841_344_746_068_542_9) < 1e-14);
    assert!(rel(d.cdf(-3.0), 1.349_898_031_630_094_5e-3) < 1e-13);
    assert!(rel(d.cdf(-8.0), 6.220_960_574_271_784e-16) < 1e-12);
    // The survival function keeps the upper tail that 1 - cdf loses.
    assert!(rel(d.survival(8.0), 6.220_960_574_271_784e-16) < 1e-12);
}

fn all_examples() -> Vec<Distribution> {
    vec![
        Distribution::Normal {
            mean: 1.5e9,
            sd: 2e8,
        },
        Distribution::Lognormal {
            median: 2.0,
            sigma_ln: 0.5,
        },
        Distribution::Uniform {
            low: -1.0,
            high: 3.0,
        },
        Distribution::Weibull {
            shape: 2.5,
            scale: 3.0,
            location: 1.0,
        },
        Distribution::Weibull {
            shape: 0.7,
            scale: 1e-3,
            location: 0.0,
        },
    ]
}

/// cdf(quantile(p)) = p and survival(quantile_upper(q)) = q over 1e-12 ... 1 - 1e-12; the
/// relative error bound 1e-12 is the CDF's own accuracy (1e-14) amplified by at most the
/// conditioning of the composed maps in the far tails (|d ln F / d ln x| up to ~50 here); an
/// absolute 1e-15 more covers the rounding of x itself where the support ends at a finite
/// nonzero point (uniform: x = low + 4e-12 carries only ~1e-16 absolute).
#[test]
fn cdf_and_quantile_are_inverse() {
    let ps = [
        1e-12, 1e-8, 1e-4, 0.01, 0.1, 0.25, 0.5, 0.75, 0.9, 0.99, 0.9999, 0.999_999,
    ];
    for d in all_examples() {
        d.validate().unwrap();
        for &p in &ps {
            let x = d.quantile(p);
            let ok = |v: f64| (v - p).abs() < 1e-12 * p + 1e-15;
            assert!(ok(d.cdf(x)), "{d:?} p = {p}: cdf = {}", d.cdf(x));
            let xu = d.quantile_upper(p);
            assert!(
                ok(d.survival(xu)),
                "{d:?} q = {p}: survival = {}",
                d.survival(xu)
            );
            // The two quantiles agree where both are well conditioned.
            if (0.01..=0.99).contains(&p) {
                let x1 = d.quantile(1.0 - p);
                assert!((xu - x1).abs() <= 1e-12 * (1.0 + x1.abs()), "{d:?} {p}");
            }
            assert!((d.cdf(x) + d.survival(x) - 1.0).abs() < 1e-15);
        }
        // Monotone.
        let xs: Vec<f64> = ps.iter().map(|&p| d.quantile(p)).collect();
        assert!(xs.windows(2).all(|w| w[0] < w[1]), "{d:?}");
    }
}

/// Moments against printed closed forms (mpmath, 20 digits): lognormal median 2, sigma_ln 0.5:
/// mean 2 exp(1/8), sd mean sqrt(exp(1/4) - 1); Weibull k = 2.5, lambda = 3, location 1: mean
/// 1 + 3 Gamma(1.4), sd 3 sqrt(Gamma(1.8) - Gamma(1.4)^2). Tolerance 1e-13: ln Gamma's 1e-14.
#[test]
fn moments_match_closed_forms() {
    let ln = Distribution::Lognormal {
        median: 2.0,
        sigma_ln: 0.5,
    };
    assert!(rel(ln.mean(), 2.266_296_906_133_652_6) < 1e-14);
    assert!(rel(ln.sd(), 1.207_801_066_421_762_5) < 1e-14);
    let wb = Distribution::Weibull {
        shape: 2.5,
        scale: 3.0,
        location: 1.0,
    };
    assert!(rel(wb.mean(), 3.661_791_452_509_225_9) < 1e-13);
    assert!(rel(wb.sd(), 1.138_999_649_767_729_2) < 1e-13);
    let u = Distribution::Uniform {
        low: -1.0,
        high: 3.0,
    };
    assert_eq!(u.mean(), 1.0);
    assert!(rel(u.sd(), 4.0 / 12f64.sqrt()) < 1e-15);
    // Weibull with shape 1 is the exponential: mean = sd = scale.
    let ex = Distribution::Weibull {
        shape: 1.0,
        scale: 2.0,
        location: 0.0,
    };
    assert!(rel(ex.mean(), 2.0) < 1e-14 && rel(ex.sd(), 2.0) < 1e-14);
}

/// Sampling by inversion reproduces the moments: the sample mean of quantile(uniform01) over
/// n = 200 000 lies within 4.5 standard errors (sd / sqrt n) of the mean, and the sample sd
/// within 3 % (its standard error is about sd sqrt((kurtosis - 1) / 4n) < 1 % for these).
#[test]
fn sampling_by_inversion_reproduces_moments() {
    let n = 200_000u64;
    for (stream, d) in all_examples().into_iter().enumerate() {
        let xs: Vec<f64> = (0..n)
            .map(|i| d.quantile(uniform01(7, stream as u64, i)))
            .collect();
        let m = xs.iter().sum::<f64>() / n as f64;
        let v = xs.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1) as f64;
        let se = d.sd() / (n as f64).sqrt();
        assert!(
            (m - d.mean()).abs() < 4.5 * se,
            "{d:?}: {m} vs {}",
            d.mean()
        );
        assert!(
            rel(v.sqrt(), d.sd()) < 0.03,
            "{d:?}: sd {} vs {}",
            v.sqrt(),
            d.sd()
        );
    }
}

/// Truncated normal N(0, 1) on [-0.5, 2]: cdf/quantile against mpmath (the 0.3 quantile
/// 0.022940762771432146), the mean (phi(a) - phi(b)) / (Phi(b) - Phi(a)) = 0.44574377827251484
/// by inversion sampling (4.5 standard errors); a far upper-tail truncation N(0, 1) on [8, inf)
/// whose median 8.084911007391544 is found only through the survival branch.
#[test]
fn truncation() {
    let t = Truncated {
        dist: Distribution::Normal { mean: 0.0, sd: 1.0 },
        low: Some(-0.5),
        high: Some(2.0),
    };
    t.validate().unwrap();
    assert!(rel(t.quantile(0.3), 0.022_940_762_771_432_146) < 1e-12);
    assert!((t.cdf(0.022_940_762_771_432_146) - 0.3).abs() < 1e-14);
    assert_eq!(t.cdf(-0.6), 0.0);
    assert_eq!(t.cdf(2.1), 1.0);
    assert_eq!(t.quantile(0.0), -0.5);
    assert!((t.quantile(1.0) - 2.0).abs() < 1e-15);
    let n = 100_000u64;
    let m = (0..n).map(|i| t.quantile(uniform01(3, 0, i))).sum::<f64>() / n as f64;
    let se = 0.613_672_417_611_249_6 / (n as f64).sqrt();
    assert!((m - 0.445_743_778_272_514_84).abs() < 4.5 * se, "{m}");

    let tail = Truncated {
        dist: Distribution::Normal { mean: 0.0, sd: 1.0 },
        low: Some(8.0),
        high: None,
    };
    tail.validate().unwrap();
    assert!(rel(tail.quantile(0.5), 8.084_911_007_391_544) < 1e-12);
    for p in [0.001, 0.1, 0.5, 0.9, 0.999] {
        let x = tail.quantile(p);
        assert!(x > 8.0 && x.is_finite());
        assert!((tail.cdf(x) - p).abs() < 1e-11, "{p}: {}", tail.cdf(x));
    }

    // Truncating a lognormal below its support end changes nothing.
    let ln = Distribution::Lognormal {
        median: 2.0,
        sigma_ln: 0.3,
    };
    let same = Truncated {
        dist: ln.clone(),
        low: Some(-1.0),
        high: None,
    };
    for p in [0.1, 0.5, 0.9] {
        assert!(rel(same.quantile(p), ln.quantile(p)) < 1e-15);
    }
    assert_eq!(Truncated::plain(ln.clone()).quantile(0.5), ln.quantile(0.5));
}

#[test]
fn validation_names_the_parameter_and_the_rule() {
    let bad = [
        (Distribution::Normal { mean: 0.0, sd: 0.0 }, "sd"),
        (
            Distribution::Normal {
                mean: f64::NAN,
                sd: 1.0,
            },
            "mean",
        ),
        (
            Distribution::Lognormal {
                median: -1.0,
                sigma_ln: 0.1,
            },
            "median",
        ),
        (
            Distribution::Lognormal {
                median: 1.0,
                sigma_ln: 0.0,
            },
            "sigma_ln",
        ),
        (
            Distribution::Uniform {
                low: 1.0,
                high: 1.0,
            },
            "high",
        ),
        (
            Distribution::Weibull {
                shape: -2.0,
                scale: 1.0,
                location: 0.0,
            },
            "shape",
        ),
        (
            Distribution::Weibull {
                shape: 2.0,
                scale: f64::INFINITY,
                location: 0.0,
            },
            "scale",
        ),
    ];
    for (d, p) in bad {
        let e = d.validate().unwrap_err();
        assert_eq!(e.parameter, p, "{d:?}");
        assert!(!e.rule.is_empty());
    }
    let t = Truncated {
        dist: Distribution::Uniform {
            low: 0.0,
            high: 1.0,
        },
        low: Some(2.0),
        high: Some(3.0),
    };
    let e = t.validate().unwrap_err();
    assert_eq!(e.parameter, "low");
    assert!(e.rule.contains("no probability"));
    let t = Truncated {
        dist: Distribution::Normal { mean: 0.0, sd: 1.0 },
        low: Some(1.0),
        high: Some(0.5),
    };
    assert_eq!(t.validate().unwrap_err().parameter, "high");
    let err = StatsError {
        parameter: "sd",
        value: -1.0,
        rule: "must be > 0",
    }
    .into_error("damage.probabilistic.limit");
    assert_eq!(
        err.to_string(),
        "damage.probabilistic.limit.sd = -1: must be > 0"
    );
}

#[test]
fn serde_names_the_distribution_by_dist() {
    let d: Distribution =
        serde_json::from_str(r#"{"dist": "weibull", "shape": 2.0, "scale": 1.0}"#).unwrap();
    assert_eq!(
        d,
        Distribution::Weibull {
            shape: 2.0,
            scale: 1.0,
            location: 0.0
        }
    );
    let d: Distribution =
        serde_json::from_str(r#"{"dist": "lognormal", "median": 3e8, "sigma_ln": 0.1}"#).unwrap();
    assert_eq!(d.name(), "lognormal");
    let back: Distribution = serde_json::from_str(&serde_json::to_string(&d).unwrap()).unwrap();
    assert_eq!(back, d);
    assert!(serde_json::from_str::<Distribution>(
        r#"{"dist": "normal", "mean": 1, "sd": 1, "x": 2}"#
    )
    .is_err());
    assert!(serde_json::from_str::<Distribution>(r#"{"dist": "gamma", "k": 1}"#).is_err());
    assert!(serde_json::from_str::<Distribution>(r#"{"dist": "normal", "mean": 1}"#).is_err());
}

/// The mapping of the 52 hashed bits: k = 0 and k = 2^52 - 1 give 2^-53 and 1 - 2^-53.
#[test]
fn uniform01_never_reaches_0_or_1() {
    assert_eq!(bits_to_open01(0), 2f64.powi(-53));
    assert_eq!(bits_to_open01(u64::MAX), 1.0 - 2f64.powi(-53));
    assert!(bits_to_open01(u64::MAX) < 1.0);
}

/// Counter-based: the same (seed, stream, index) gives the same number whatever was drawn
/// before (pinned values guard the formula: a change would change every study's points), and
/// the numbers are uniform: over 2^16 draws, the mean within 4.5 standard errors of 1/2
/// (se = 1/sqrt(12 n)), a chi-square over 64 bins below its 99.99 % point (~ 113 for 63 dof),
/// and neighbouring streams and seeds uncorrelated (|r| < 4.5 / sqrt n).
#[test]
fn uniform01_is_counter_based_and_uniform() {
    let a = uniform01(42, 0, 0);
    let _ = (0..100).map(|i| uniform01(1, 2, i)).sum::<f64>();
    assert_eq!(uniform01(42, 0, 0), a);
    assert_ne!(uniform01(42, 0, 1), a);
    assert_ne!(uniform01(42, 1, 0), a);
    assert_ne!(uniform01(43, 0, 0), a);
    let pinned = [
        uniform01(0, 0, 0),
        uniform01(1, 0, 0),
        uniform01(0, 1, 0),
        uniform01(0, 0, 1),
        uniform01(12345, 3, 999),
    ];
    assert_eq!(pinned, PINNED);
    let n = 1u64 << 16;
    let u: Vec<f64> = (0..n).map(|i| uniform01(2024, 0, i)).collect();
    assert!(u.iter().all(|&x| x > 0.0 && x < 1.0));
    let m = u.iter().sum::<f64>() / n as f64;
    assert!((m - 0.5).abs() < 4.5 / (12.0 * n as f64).sqrt(), "{m}");
    let mut bins = [0u32; 64];
    for &x in &u {
        bins[(x * 64.0) as usize] += 1;
    }
    let e = n as f64 / 64.0;
    let chi2: f64 = bins.iter().map(|&b| (b as f64 - e).powi(2) / e).sum();
    assert!(chi2 < 113.0, "chi2 = {chi2}");
    let corr = |v: &[f64], w: &[f64]| {
        let s: f64 = v.iter().zip(w).map(|(a, b)| (a - 0.5) * (b - 0.5)).sum();
        s / n as f64 * 12.0
    };
    let u_stream: Vec<f64> = (0..n).map(|i| uniform01(2024, 1, i)).collect();
    let u_seed: Vec<f64> = (0..n).map(|i| uniform01(2025, 0, i)).collect();
    let u_next: Vec<f64> = (0..n).map(|i| uniform01(2024, 0, i + 1)).collect();
    let lim = 4.5 / (n as f64).sqrt();
    for w in [&u_stream, &u_seed, &u_next] {
        assert!(corr(&u, w).abs() < lim, "r = {}", corr(&u, w));
    }
}

const PINNED: [f64; 5] = [
    0.160_559_998_147_336_12,
    0.499_897_692_724_281,
    0.706_250_621_457_655,
    0.912_041_004_311_617_5,
    0.483_446_394_870_816_86,
];
