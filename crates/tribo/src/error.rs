//! The library's error type. Every fallible public function returns [`Result`].

use thiserror::Error as ThisError;

/// Errors of the tribo library.
///
/// Input errors name the offending field and the rule it breaks; solver failures carry the
/// residual they reached, so that a caller can report it (and the solvers return the
/// iterate they stopped at beside it, [`crate::solvers::SolveError`]). Non-exhaustive: a
/// later version may add kinds, so a `match` needs a wildcard arm.
#[derive(Debug, Clone, PartialEq, ThisError)]
#[non_exhaustive]
pub enum Error {
    /// A parameter breaks a rule (the field, its value as text, and the rule).
    #[error("{field} = {value}: {rule}")]
    InvalidParameter {
        /// Name of the parameter, e.g. `body1.nu`.
        field: String,
        /// The offending value, formatted.
        value: String,
        /// The rule it breaks, e.g. "Poisson's ratio must be in (-1, 0.5)".
        rule: String,
    },
    /// An iterative solver stopped before reaching its tolerance.
    #[error(
        "{solver} did not converge: residual {residual:.3e} after {iterations} iterations \
         (tolerance {tolerance:.1e})"
    )]
    NotConverged {
        /// Which solver.
        solver: &'static str,
        /// Iterations done.
        iterations: usize,
        /// Residual reached (the solver's documented measure).
        residual: f64,
        /// Tolerance asked for.
        tolerance: f64,
    },
    /// The contact area reaches the edge of the computational window.
    #[error(
        "the contact area reaches the edge of the computational window ({detail}); \
         enlarge the window (grid.extent or grid.half_width)"
    )]
    ContactReachesWindow {
        /// Where it touches, in words.
        detail: String,
    },
    /// The load or approach produces no contact.
    #[error("no contact: {detail}")]
    NoContact {
        /// Why, in words.
        detail: String,
    },
    /// A large allocation failed: the machine (or the process's memory limit) does not have
    /// `bytes` for `what`. Returned instead of aborting, e.g. by the 2D BEM's dense matrices
    /// ([`crate::operators::bem2d::BemModel::memory_estimate`] tells beforehand).
    #[error(
        "out of memory: {what} needs {bytes} bytes ({:.2} GiB) that could not be allocated; \
         reduce the model (fewer elements) or run it where more memory is available",
        *bytes as f64 / 1073741824.0
    )]
    OutOfMemory {
        /// What was being allocated, in words.
        what: String,
        /// Bytes asked for (usize::MAX where the size itself overflows).
        bytes: usize,
    },
    /// A numerical operation failed (e.g. a singular factorization).
    #[error("numerical failure in {context}: {detail}")]
    Numerical {
        /// Where.
        context: &'static str,
        /// What happened.
        detail: String,
    },
}

impl Error {
    /// Shorthand for [`Error::InvalidParameter`].
    pub fn invalid(
        field: impl Into<String>,
        value: impl std::fmt::Display,
        rule: impl Into<String>,
    ) -> Self {
        Error::InvalidParameter {
            field: field.into(),
            value: value.to_string(),
            rule: rule.into(),
        }
    }
}

/// The library's result type.
pub type Result<T, E = Error> = std::result::Result<T, E>;
