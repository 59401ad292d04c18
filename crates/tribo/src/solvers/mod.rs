//! Layer 3: contact solvers. Each returns a solution that carries its convergence record.
//!
//! One entry point per algorithm, each taking a problem struct (the physics: grid, gaps,
//! bodies, loading) and a params struct (the numerics: tolerance, iteration limit, method),
//! plus what a caller may attach to a run: prebuilt operators (`Option<&...>`, to reuse them
//! over many solves) and a progress observer (`Option<&mut dyn FnMut(...)>`). Params are
//! plain data (`Copy`, serde), so that a case can store them; the observer is an argument, as
//! faer's conjugate gradient takes its callback.
//!
//! - [`normal::solve_normal`]: normal contact ([`normal::NormalMethod`]: Polonsky-Keer CG or
//!   the dense active set);
//! - [`tangential::solve_tangential`]: partial slip / sliding, traction parallel to the load;
//! - [`tangential_free::solve_tangential_free`]: partial slip, traction direction free;
//! - [`coupled::solve_coupled`]: normal and tangential problems of dissimilar bodies;
//! - [`back_effect::back_effect_curve`]: the contact force under bulk loads at a fixed approach.
//!
//! A failed solve returns what it has: the error is a [`SolveError`], whose `output` holds the
//! last iterate where the solver stopped with one (e.g. at its iteration limit, with the
//! residual it reached), and which converts into [`crate::Error`] with `?`.

pub mod back_effect;
pub mod bem2d;
pub mod coupled;
pub mod normal;
pub mod tangential;
pub mod tangential_free;

use crate::error::Error;

/// The error of a solve: what went wrong (`kind`) and what the solver had when it stopped
/// (`output`), the shape of fenris' `SolveError<T> { output, kind }`.
///
/// `output` is `Some` where the solver stopped with a complete iterate: at its iteration
/// limit ([`Error::NotConverged`], the iterate's own `residual` is the one reported) or with a
/// solution it refuses ([`Error::ContactReachesWindow`]); `None` where the input is refused
/// or the iteration broke down. `?` converts it into [`crate::Error`] (dropping the output),
/// so the message a caller prints is the same as before.
#[derive(Debug, Clone, PartialEq)]
pub struct SolveError<S> {
    /// What went wrong.
    pub kind: Error,
    /// The last iterate, where there is one.
    pub output: Option<Box<S>>,
}

impl<S> SolveError<S> {
    /// An error with the iterate the solver stopped at.
    pub fn with_output(kind: Error, output: S) -> Self {
        Self {
            kind,
            output: Some(Box::new(output)),
        }
    }

    /// The last iterate, if any (consumes the error).
    pub fn into_output(self) -> Option<S> {
        self.output.map(|b| *b)
    }

    /// The same error with its output mapped (e.g. to a larger solution that contains it).
    pub fn map_output<T>(self, f: impl FnOnce(S) -> T) -> SolveError<T> {
        SolveError {
            kind: self.kind,
            output: self.output.map(|b| Box::new(f(*b))),
        }
    }
}

impl<S> From<Error> for SolveError<S> {
    fn from(kind: Error) -> Self {
        Self { kind, output: None }
    }
}

impl<S> From<SolveError<S>> for Error {
    fn from(e: SolveError<S>) -> Self {
        e.kind
    }
}

impl<S> std::fmt::Display for SolveError<S> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.kind.fmt(f)
    }
}

impl<S: std::fmt::Debug> std::error::Error for SolveError<S> {}

/// The result of a solve: the solution, or a [`SolveError`] with what the solver had.
pub type SolveResult<S> = std::result::Result<S, SolveError<S>>;

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
    solve_normal, solve_normal_from, NormalContactParams, NormalContactProblem,
    NormalContactSolution, NormalLoading, NormalMethod,
};

/// The rule shared by the iterative solvers' params: a tolerance finite in (0, 1) and at
/// least one iteration (errors name the case keys `solver.tolerance` and
/// `solver.max_iterations`).
pub(crate) fn validate_iteration_params(
    tolerance: f64,
    max_iterations: usize,
) -> crate::error::Result<()> {
    if !(tolerance.is_finite() && tolerance > 0.0 && tolerance < 1.0) {
        return Err(Error::invalid(
            "solver.tolerance",
            tolerance,
            "must be in (0, 1)",
        ));
    }
    if max_iterations == 0 {
        return Err(Error::invalid(
            "solver.max_iterations",
            0,
            "must be at least 1",
        ));
    }
    Ok(())
}

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
