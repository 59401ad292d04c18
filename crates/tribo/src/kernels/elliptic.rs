//! Complete elliptic integrals of the first and second kind.
//!
//! Parameter convention: `m = k^2` (the *parameter*, as scipy/Boost), not the modulus k
//! (docs/theory/HALFSPACE.md pitfall 5). Johnson (1985, *Contact Mechanics*, sec. 4.2) writes K(e), E(e)
//! with the modulus e; his e^2 is our m.
//!
//! Method: the arithmetic-geometric mean (Abramowitz & Stegun 1964, *Handbook of Mathematical
//! Functions*, 17.6.1-17.6.4; DLMF 19.8.1 and 19.8.6):
//! a_0 = 1, b_0 = sqrt(1 - m), c_0^2 = m; a_{n+1} = (a_n + b_n)/2, b_{n+1} = sqrt(a_n b_n),
//! c_{n+1} = (a_n - b_n)/2 = c_n^2 / (4 a_{n+1});
//! K(m) = pi / (2 a_inf), E(m) = K(m) (1 - S), S = sum_{n >= 0} 2^{n-1} c_n^2.
//! The recurrence c_{n+1} = c_n^2 / (4 a_{n+1}) avoids the cancellation of a_n - b_n, and
//! K - E = K S is formed without subtracting K and E (needed by Hertz theory as m -> 0).

/// Complete elliptic integral of the first kind K(m) = int_0^{pi/2} (1 - m sin^2 t)^{-1/2} dt,
/// for `m < 1` (dimensionless; AGM method, Abramowitz & Stegun 17.6.3).
///
/// K(0) = pi/2; K(m) -> infinity as m -> 1 (K(1) = +inf); NaN for m > 1 or NaN.
/// Accurate to a few units in the last place (relative ~1e-15) for m < 1.
pub fn complete_first_kind(m: f64) -> f64 {
    complete_integrals(m).0
}

/// Complete elliptic integral of the second kind E(m) = int_0^{pi/2} (1 - m sin^2 t)^{1/2} dt,
/// for `m <= 1` (dimensionless; AGM method, Abramowitz & Stegun 17.6.4).
///
/// E(0) = pi/2, E(1) = 1; NaN for m > 1 or NaN. Relative accuracy ~1e-15.
pub fn complete_second_kind(m: f64) -> f64 {
    complete_integrals(m).1
}

/// Both complete elliptic integrals `(K(m), E(m))` of parameter `m = k^2` from one AGM
/// sequence (Abramowitz & Stegun 17.6.3-17.6.4). Same domain and accuracy as
/// [`complete_first_kind`] and [`complete_second_kind`].
pub fn complete_integrals(m: f64) -> (f64, f64) {
    if m.is_nan() || m > 1.0 {
        return (f64::NAN, f64::NAN);
    }
    if m == 1.0 {
        return (f64::INFINITY, 1.0);
    }
    let (k, k_minus_e) = first_kind_and_difference(m, 1.0 - m);
    (k, k - k_minus_e)
}

/// `(K(m), K(m) - E(m))` from the parameter `m` and its complement `complement = 1 - m`,
/// each supplied to full precision by the caller (so that both m -> 0 and m -> 1 keep their
/// relative accuracy). Requires `m < 1`, `complement > 0` and `m + complement == 1` up to
/// rounding. K - E is formed as K S without cancellation (see the module docs).
pub(crate) fn first_kind_and_difference(m: f64, complement: f64) -> (f64, f64) {
    let (k, s) = agm_first_kind_and_sum(m, complement);
    (k, k * s)
}

/// `(K(m), S)` with S = sum_{n >= 0} 2^{n-1} c_n^2 (so E = K (1 - S)); see the module docs.
pub(crate) fn agm_first_kind_and_sum(m: f64, complement: f64) -> (f64, f64) {
    let mut a = 1.0_f64;
    let mut b = complement.sqrt();
    let mut c_squared = m;
    let mut weight = 0.5_f64;
    let mut sum = weight * c_squared;
    // Quadratic convergence: |c_{n+1}| = c_n^2 / (4 a_{n+1}); 8 steps suffice for m <= 0.999999,
    // about 12 for complement ~ 1e-300. The cap only guards against NaN input.
    for _ in 0..64 {
        let a_next = 0.5 * (a + b);
        let b_next = (a * b).sqrt();
        let c_next = c_squared / (4.0 * a_next);
        c_squared = c_next * c_next;
        weight *= 2.0;
        sum += weight * c_squared;
        a = a_next;
        b = b_next;
        if weight * c_squared <= 1e-17 * sum.abs() || c_squared == 0.0 {
            break;
        }
    }
    // At convergence a = b = AGM(1, sqrt(1 - m)); take their mean for the last rounding.
    let agm = 0.5 * (a + b);
    (std::f64::consts::FRAC_PI_2 / agm, sum)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    // Tolerance 1e-14 relative: the AGM takes at most ~8 steps for these m, each adding about
    // one rounding (1.1e-16) to a_n, and K = pi/(2 a), E = K (1 - S) with 1 - S >= 0.4 here;
    // the accumulated error is a few 1e-16, so 1e-14 leaves a factor > 10 of margin while still
    // catching any formula error (which would show at 1e-3 or worse).
    const TOL: f64 = 1e-14;

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    #[test]
    fn values_at_zero() {
        assert_eq!(complete_first_kind(0.0), FRAC_PI_2);
        assert_eq!(complete_second_kind(0.0), FRAC_PI_2);
    }

    #[test]
    fn published_values() {
        // Abramowitz & Stegun table 17.1 / scipy.special.ellipk, ellipe (parameter m).
        let cases = [
            (0.5, 1.8540746773013719, 1.3506438810476755),
            (0.9, 2.5780921133481733, 1.1047747327040733),
            // mpmath ellipk(0.1), ellipe(0.1) at 30 digits
            (0.1, 1.6124413487202194, 1.5307576368977632),
        ];
        for (m, k, e) in cases {
            assert!(
                rel(complete_first_kind(m), k) < TOL,
                "K({m}) = {}",
                complete_first_kind(m)
            );
            assert!(
                rel(complete_second_kind(m), e) < TOL,
                "E({m}) = {}",
                complete_second_kind(m)
            );
        }
    }

    #[test]
    fn limit_at_one() {
        assert_eq!(complete_second_kind(1.0), 1.0);
        assert_eq!(complete_first_kind(1.0), f64::INFINITY);
        // Near m = 1: K ~ ln(4/sqrt(1-m)) (A&S 17.3.26), E -> 1.
        let mc = 1e-12_f64;
        let (k, _) = first_kind_and_difference(1.0 - mc, mc);
        assert!((k - (4.0 / mc.sqrt()).ln()).abs() < 1e-10, "{k}");
        assert!(complete_first_kind(1.5).is_nan());
        assert!(complete_second_kind(f64::NAN).is_nan());
    }

    #[test]
    fn legendre_relation() {
        // E(m) K(1-m) + E(1-m) K(m) - K(m) K(1-m) = pi/2 (A&S 17.3.13).
        for m in [1e-6, 0.01, 0.1, 0.25, 0.5, 0.7, 0.9, 0.99, 0.999] {
            let (k, e) = complete_integrals(m);
            let (kc, ec) = complete_integrals(1.0 - m);
            let lhs = e * kc + ec * k - k * kc;
            assert!(rel(lhs, FRAC_PI_2) < 1e-14, "m = {m}: {lhs}");
        }
    }

    #[test]
    fn difference_has_no_cancellation_for_small_m() {
        // K - E = pi m / 4 (1 + 3 m / 8 + ...) (series of A&S 17.3.11-17.3.12).
        for m in [1e-12, 1e-9, 1e-6] {
            let (_, d) = first_kind_and_difference(m, 1.0 - m);
            let series = std::f64::consts::FRAC_PI_4 * m * (1.0 + 3.0 * m / 8.0);
            assert!(rel(d, series) < 1e-12, "m = {m}: {d} vs {series}");
        }
    }

    #[test]
    fn negative_parameter() {
        // K(-1) = 1.3110287771460599, E(-1) = 1.9100988945138560 (mpmath, 30 digits).
        let (k, e) = complete_integrals(-1.0);
        assert!(rel(k, 1.3110287771460599) < TOL, "{k}");
        assert!(rel(e, 1.910_098_894_513_856) < TOL, "{e}");
    }
}
