//! Special functions for the fatigue statistics: log-gamma, the regularized incomplete gamma
//! and beta functions, the normal distribution (log-CDF accurate in the far tails), Student's
//! t (CDF and quantile) and the F(2, d) quantile.
//!
//! Algorithms: Lanczos' approximation of ln Gamma (Lanczos 1964, SIAM J. Numer. Anal. B 1, with
//! the g = 7, 9-term coefficients of Godfrey); the incomplete gamma function by its power series
//! and its Legendre continued fraction, the incomplete beta function by its continued fraction
//! evaluated with the modified Lentz method (Abramowitz & Stegun 6.5.29, 6.5.31, 26.5.8; the
//! evaluation strategy of Press et al., *Numerical Recipes*, 3rd ed., Sec. 6.2 and 6.4). Written
//! here, not copied; accuracy is checked against printed tables in the tests.

/// ln Gamma(x) for x > 0 (Lanczos, g = 7; relative error below 1e-14 for x > 0).
pub fn ln_gamma(x: f64) -> f64 {
    const G: f64 = 7.0;
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        // Reflection: Gamma(x) Gamma(1 - x) = pi / sin(pi x).
        let pi = std::f64::consts::PI;
        return (pi / (pi * x).sin()).abs().ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + G + 0.5;
    for (i, c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    0.5 * (2.0 * std::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

const EPS: f64 = 1e-16;
const TINY: f64 = 1e-300;

/// ln Q(a, x), the log of the upper regularized incomplete gamma function, for a > 0, x >= 0.
/// Series for P when x < a + 1 (A&S 6.5.29), continued fraction for Q otherwise (A&S 6.5.31);
/// the continued fraction branch is evaluated in logs so that far tails do not underflow.
pub fn ln_gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    let ln_front = -x + a * x.ln() - ln_gamma(a);
    if x < a + 1.0 {
        // P by the series sum x^n / (a (a+1) ... (a+n)).
        let mut term = 1.0 / a;
        let mut sum = term;
        let mut ap = a;
        for _ in 0..1000 {
            ap += 1.0;
            term *= x / ap;
            sum += term;
            if term.abs() < sum.abs() * EPS {
                break;
            }
        }
        let p = (ln_front + sum.ln()).exp();
        (1.0 - p).max(0.0).ln()
    } else {
        // Q by the continued fraction 1/(x+1-a- 1(1-a)/(x+3-a- 2(2-a)/(x+5-a- ...))), Lentz.
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / TINY;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..1000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < TINY {
                d = TINY;
            }
            c = b + an / c;
            if c.abs() < TINY {
                c = TINY;
            }
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < EPS {
                break;
            }
        }
        ln_front + h.ln()
    }
}

/// ln Phi(z), the log of the standard normal CDF, accurate in both tails:
/// Phi(z) = erfc(-z / sqrt 2) / 2 and erfc(x) = Q(1/2, x^2), so Phi(z) = Q(1/2, z^2/2) / 2
/// for z < 0 (A&S chapters 6, 7 and 26.2).
pub fn ln_normal_cdf(z: f64) -> f64 {
    if z.is_nan() {
        return f64::NAN;
    }
    if z < 0.0 {
        ln_gamma_q(0.5, 0.5 * z * z) - std::f64::consts::LN_2
    } else {
        // 1 - Phi(-z); ln_1p keeps the precision when the tail is small.
        let tail = (ln_gamma_q(0.5, 0.5 * z * z) - std::f64::consts::LN_2).exp();
        (-tail).ln_1p()
    }
}

/// Phi(z), the standard normal CDF.
pub fn normal_cdf(z: f64) -> f64 {
    ln_normal_cdf(z).exp()
}

/// ln of the normal density with mean `mu` and standard deviation `sigma` at `x`.
pub fn ln_normal_pdf(x: f64, mu: f64, sigma: f64) -> f64 {
    let z = (x - mu) / sigma;
    -0.5 * z * z - sigma.ln() - 0.5 * (2.0 * std::f64::consts::PI).ln()
}

/// I_x(a, b), the regularized incomplete beta function, a, b > 0, x in [0, 1]
/// (continued fraction A&S 26.5.8 with the symmetry I_x(a,b) = 1 - I_{1-x}(b,a)).
pub fn incomplete_beta(a: f64, b: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    if x >= 1.0 {
        return 1.0;
    }
    let ln_front = ln_gamma(a + b) - ln_gamma(a) - ln_gamma(b) + a * x.ln() + b * (1.0 - x).ln();
    if x < (a + 1.0) / (a + b + 2.0) {
        ln_front.exp() * beta_cf(a, b, x) / a
    } else {
        1.0 - ln_front.exp() * beta_cf(b, a, 1.0 - x) / b
    }
}

/// The continued fraction of I_x(a, b) (A&S 26.5.8), modified Lentz evaluation.
fn beta_cf(a: f64, b: f64, x: f64) -> f64 {
    let (qab, qap, qam) = (a + b, a + 1.0, a - 1.0);
    let mut c = 1.0;
    let mut d = 1.0 - qab * x / qap;
    if d.abs() < TINY {
        d = TINY;
    }
    d = 1.0 / d;
    let mut h = d;
    for m in 1..10_000 {
        let m = m as f64;
        let m2 = 2.0 * m;
        // Even step d_{2m}.
        let aa = m * (b - m) * x / ((qam + m2) * (a + m2));
        d = 1.0 + aa * d;
        if d.abs() < TINY {
            d = TINY;
        }
        c = 1.0 + aa / c;
        if c.abs() < TINY {
            c = TINY;
        }
        d = 1.0 / d;
        h *= d * c;
        // Odd step d_{2m+1}.
        let aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
        d = 1.0 + aa * d;
        if d.abs() < TINY {
            d = TINY;
        }
        c = 1.0 + aa / c;
        if c.abs() < TINY {
            c = TINY;
        }
        d = 1.0 / d;
        let del = d * c;
        h *= del;
        if (del - 1.0).abs() < EPS {
            break;
        }
    }
    h
}

/// CDF of Student's t distribution with `dof` > 0 degrees of freedom:
/// P(T <= t) = 1 - I_{dof/(dof+t^2)}(dof/2, 1/2) / 2 for t >= 0 (A&S Sec. 26.7).
pub fn student_t_cdf(t: f64, dof: f64) -> f64 {
    let tail = 0.5 * incomplete_beta(0.5 * dof, 0.5, dof / (dof + t * t));
    if t >= 0.0 {
        1.0 - tail
    } else {
        tail
    }
}

/// The quantile t_{p, dof} of Student's t distribution: P(T <= t) = p, for p in (0, 1).
/// Solved by bracketing and bisection of [`student_t_cdf`] to the resolution of f64.
/// Returns NaN for p outside (0, 1) or dof <= 0 (callers validate first).
pub fn student_t_quantile(p: f64, dof: f64) -> f64 {
    if !(p > 0.0 && p < 1.0 && dof > 0.0) {
        return f64::NAN;
    }
    if p == 0.5 {
        return 0.0;
    }
    if p < 0.5 {
        return -student_t_quantile(1.0 - p, dof);
    }
    let mut hi = 1.0;
    while student_t_cdf(hi, dof) < p {
        hi *= 2.0;
        if hi > 1e300 {
            return f64::INFINITY;
        }
    }
    let mut lo = 0.0;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if student_t_cdf(mid, dof) < p {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The quantile of the F distribution with (2, d2) degrees of freedom, in closed form: its CDF
/// is 1 - (1 + 2x/d2)^(-d2/2), so x_p = (d2/2) ((1-p)^(-2/d2) - 1). Used by the ASTM E739
/// (Working-Hotelling) confidence band for the whole line.
pub fn f2_quantile(p: f64, d2: f64) -> f64 {
    0.5 * d2 * ((1.0 - p).powf(-2.0 / d2) - 1.0)
}

/// 2 Phi^-1(0.9): converts a log10 standard deviation s into the scatter T = 10^(2.5631 s)
/// between the 10 % and 90 % quantiles (DIN 50100:2016-12; the same constant as pyLife's
/// `std_to_scattering_range`). Phi^-1(0.9) = 1.2815515655446004 (A&S Table 26.5).
pub const SCATTER_FACTOR: f64 = 2.563_103_131_089_200_7;

/// Scatter T (10 % / 90 % ratio) from the standard deviation of log10.
pub fn std_to_scatter(std_log10: f64) -> f64 {
    10f64.powf(SCATTER_FACTOR * std_log10)
}

/// Standard deviation of log10 from the scatter T (10 % / 90 % ratio).
pub fn scatter_to_std(scatter: f64) -> f64 {
    scatter.log10() / SCATTER_FACTOR
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ln_gamma_of_integers_and_one_half() {
        // Gamma(n) = (n-1)!, Gamma(1/2) = sqrt(pi): exact values; Lanczos g=7 is good to
        // ~1e-15 relative, 1e-12 leaves room for the summation.
        assert!((ln_gamma(1.0)).abs() < 1e-12);
        assert!((ln_gamma(5.0) - 24f64.ln()).abs() < 1e-12);
        assert!((ln_gamma(0.5) - std::f64::consts::PI.sqrt().ln()).abs() < 1e-12);
        assert!((ln_gamma(101.0) - 363.739_375_555_563_5).abs() < 1e-9);
    }

    #[test]
    fn normal_cdf_against_tables() {
        // A&S Table 26.1 values (15 digits printed); 1e-13 absolute is well above f64 noise.
        assert!((normal_cdf(0.0) - 0.5).abs() < 1e-14);
        assert!((normal_cdf(1.0) - 0.841_344_746_068_542_9).abs() < 1e-13);
        assert!((normal_cdf(-1.96) - 0.024_997_895_148_220_43).abs() < 1e-13);
        assert!((normal_cdf(1.281_551_565_544_600_4) - 0.9).abs() < 1e-13);
        // Far tail: Phi(-40) = 3.655893540915e-350 underflows, its log does not:
        // ln Phi(-40) = -804.608442013754 (Mills ratio asymptotics, 12 digits).
        assert!((ln_normal_cdf(-40.0) + 804.608_442_013_754).abs() < 1e-8);
        assert!(ln_normal_cdf(40.0).abs() < 1e-300);
    }

    #[test]
    fn student_t_quantiles_against_table() {
        // Two-sided 95 % and 99 % values of Student's t table (e.g. NIST/SEMATECH e-Handbook
        // 1.3.6.7.2, printed to 3 decimals): tolerance half a unit of the last printed digit.
        let table = [
            (0.975, 1.0, 12.706),
            (0.975, 2.0, 4.303),
            (0.975, 5.0, 2.571),
            (0.975, 10.0, 2.228),
            (0.975, 30.0, 2.042),
            (0.95, 30.0, 1.697),
            (0.995, 20.0, 2.845),
            (0.90, 3.0, 1.638),
            (0.999, 100.0, 3.174),
        ];
        for (p, dof, t) in table {
            let q = student_t_quantile(p, dof);
            assert!((q - t).abs() <= 5e-4, "t({p}, {dof}) = {q}, table {t}");
            assert!((student_t_quantile(1.0 - p, dof) + q).abs() < 1e-12);
        }
        // dof = 1 is the Cauchy distribution: t_p = tan(pi (p - 1/2)), exact.
        let q = student_t_quantile(0.9, 1.0);
        assert!((q - (std::f64::consts::PI * 0.4).tan()).abs() < 1e-10);
        assert!(student_t_quantile(1.0, 3.0).is_nan());
    }

    #[test]
    fn f2_quantile_matches_its_cdf_and_table() {
        // F_{0.95}(2, 10) = 4.10 (F table, 3 digits printed).
        assert!((f2_quantile(0.95, 10.0) - 4.10).abs() < 5e-3);
        let x = f2_quantile(0.9, 7.0);
        assert!(((1.0 - (1.0 + 2.0 * x / 7.0).powf(-3.5)) - 0.9).abs() < 1e-13);
    }

    #[test]
    fn scatter_conversion_round_trips() {
        assert!((scatter_to_std(std_to_scatter(0.07)) - 0.07).abs() < 1e-15);
        assert!((SCATTER_FACTOR - 2.0 * 1.281_551_565_544_600_4).abs() < 1e-15);
    }
}
