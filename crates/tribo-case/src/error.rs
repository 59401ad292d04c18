//! The errors of reading, validating and running a case.

use std::path::PathBuf;
use thiserror::Error;

/// An error of a case: bad input (a field breaking a rule, a file that is not TOML or does not
/// fit the schema, an unreadable or malformed data file) or an error of the tribo library while
/// running it. Front ends map these to their own reports (the `tribo` command line: exit 2 for
/// bad input, 3 for a solver that did not converge).
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum CaseError {
    /// A field of the case breaks a rule (named field, its value, the rule).
    #[error("{field} = {value}: {rule}")]
    Field {
        /// Dotted field name, e.g. `body1.nu`.
        field: String,
        /// The offending value as written.
        value: String,
        /// The rule.
        rule: String,
    },
    /// The case file is not valid TOML or does not fit the schema (unknown key, wrong type).
    #[error("{path}: {message}")]
    Parse {
        /// Case file (or `<embedded NAME>`).
        path: String,
        /// The parser's message (with line and column).
        message: String,
    },
    /// An input file could not be read.
    #[error("{field}: cannot read {}: {source}", path.display())]
    Unreadable {
        /// The field that names the file (or `case` for the case file itself).
        field: String,
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A data file (height map, fatigue data) has a bad line.
    #[error("{field}: {}, line {line}: {rule}", path.display())]
    DataFile {
        /// The field that names the file.
        field: String,
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        rule: String,
    },
    /// An error of the tribo library.
    #[error(transparent)]
    Library(#[from] tribo::Error),
}

impl CaseError {
    /// A field error.
    pub fn field(
        field: impl Into<String>,
        value: impl std::fmt::Display,
        rule: impl Into<String>,
    ) -> Self {
        CaseError::Field {
            field: field.into(),
            value: value.to_string(),
            rule: rule.into(),
        }
    }

    /// Whether the error is bad input (a rule of the case, the schema, a file), as opposed
    /// to a solver that did not converge or another failure of the computation.
    pub fn is_bad_input(&self) -> bool {
        match self {
            CaseError::Field { .. }
            | CaseError::Parse { .. }
            | CaseError::Unreadable { .. }
            | CaseError::DataFile { .. } => true,
            CaseError::Library(e) => matches!(
                e,
                tribo::Error::InvalidParameter { .. }
                    | tribo::Error::ContactReachesWindow { .. }
                    | tribo::Error::NoContact { .. }
            ),
        }
    }

    /// Whether the error is a solver that stopped before reaching its tolerance.
    pub fn is_not_converged(&self) -> bool {
        matches!(self, CaseError::Library(tribo::Error::NotConverged { .. }))
    }
}

/// A failed solve is the library's error (the solver's partial output is dropped; the
/// message, with the residual of a solver that did not converge, is the same).
impl<S> From<tribo::solvers::SolveError<S>> for CaseError {
    fn from(e: tribo::solvers::SolveError<S>) -> Self {
        CaseError::Library(e.kind)
    }
}

/// The result type of this crate.
pub type CaseResult<T> = Result<T, CaseError>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn input_and_convergence_classes() {
        assert!(CaseError::field("a", 1, "r").is_bad_input());
        let nc = tribo::Error::NotConverged {
            solver: "cg",
            iterations: 3,
            residual: 1e-3,
            tolerance: 1e-10,
        };
        let nc = CaseError::from(nc);
        assert!(nc.is_not_converged() && !nc.is_bad_input());
        assert!(CaseError::from(tribo::Error::invalid("x", 1, "r")).is_bad_input());
        let num = CaseError::from(tribo::Error::Numerical {
            context: "x",
            detail: "y".into(),
        });
        assert!(!num.is_bad_input() && !num.is_not_converged());
    }
}
