//! Layer 3: contact solvers. Each returns a solution that carries its convergence record.

pub mod back_effect;
pub mod bem2d;
pub mod coupled;
pub mod normal;
pub mod tangential;
pub mod tangential_2d;

/// The larger of `a` and `b`, NaN if either is NaN. `f64::max` returns the other operand
/// when one is NaN, so a max-norm folded with it reports a NaN field as small (a
/// "converged" residual of 0); residuals and norms use this instead.
#[inline]
pub(crate) fn nan_max(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

#[cfg(test)]
mod near_gross_slip;

pub use normal::{
    solve_normal_active_set, solve_normal_cg, solve_normal_cg_observed, NormalContactParams,
    NormalContactProblem, NormalContactSolution, NormalLoading,
};

#[cfg(test)]
mod tests {
    use super::*;

    /// A NaN anywhere makes a max-norm NaN (f64::max returns the other operand), so that a
    /// residual with a NaN is never below a tolerance (issue 11 item 2: the BEM printed
    /// "relative residual 0.000e0" for NaN kernels).
    #[test]
    fn nan_max_propagates_nan() {
        assert!(nan_max(1.0, f64::NAN).is_nan() && nan_max(f64::NAN, 0.0).is_nan());
        assert_eq!(nan_max(1.0, 2.0), 2.0);
        assert_eq!([0.5, 3.0, 1.0].into_iter().fold(0.0, nan_max), 3.0);
        assert!([0.5, f64::NAN, 1.0].into_iter().fold(0.0, nan_max).is_nan());
        // The half-space complementarity residual of a NaN pressure: was 0 ("converged"),
        // now not finite (infinite: the NaN makes the pressure scale undefined).
        let r = normal::complementarity_residual(&[1.0, f64::NAN], &[0.0, 0.0], 1.0);
        assert!(!r.is_finite(), "{r}");
        let r = normal::complementarity_residual(&[1.0, 0.0], &[0.0, f64::NAN], 1.0);
        assert!(r.is_nan(), "{r}");
    }
}
