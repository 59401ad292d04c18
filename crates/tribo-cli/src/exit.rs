//! The command line's errors and their exit codes: the case's own errors
//! ([`tribo_case::CaseError`]), the writers' ([`tribo_io::IoError`]) and those of the front
//! end (stdout, names).

use thiserror::Error;
use tribo_case::CaseError;
use tribo_io::IoError;

/// Exit code: success.
pub const EXIT_OK: u8 = 0;
/// Exit code: any failure not listed below (output not writable, numerical failure, ...).
pub const EXIT_OTHER: u8 = 1;
/// Exit code: bad input (case file syntax, a field breaking a rule, an unreadable file,
/// a window the contact reaches, a load producing no contact).
pub const EXIT_BAD_INPUT: u8 = 2;
/// Exit code: the solver stopped before reaching its tolerance.
pub const EXIT_NOT_CONVERGED: u8 = 3;
/// Exit code: `tribo validate` found a failing row.
pub const EXIT_VALIDATION_FAILED: u8 = 1;

/// Errors of the `tribo` command line.
#[derive(Debug, Error)]
pub enum CliError {
    /// An error of the case: bad input, or the library failing while running it.
    #[error(transparent)]
    Case(#[from] CaseError),
    /// Writing the outputs failed.
    #[error(transparent)]
    Io(#[from] IoError),
    /// Writing to standard output failed (a closed pipe ends quietly, see `term`).
    #[error("cannot write to standard output: {source}")]
    Stdout {
        /// Why.
        source: std::io::Error,
    },
    /// Printing an output failed (its JSON could not be made).
    #[error("output {what}: {detail}")]
    Output {
        /// Which output.
        what: String,
        /// What went wrong.
        detail: String,
    },
    /// An unknown example name.
    #[error("no example named {name:?}; `tribo example` lists them: {known}")]
    UnknownExample {
        /// The name asked for.
        name: String,
        /// Known names, comma separated.
        known: String,
    },
}

impl From<tribo::Error> for CliError {
    fn from(e: tribo::Error) -> Self {
        CliError::Case(CaseError::Library(e))
    }
}

impl CliError {
    /// The process exit code for this error (see docs/user/cli.md, "Exit codes").
    pub fn exit_code(&self) -> u8 {
        let case = match self {
            CliError::Case(e) | CliError::Io(IoError::Case(e)) => Some(e),
            _ => None,
        };
        match (self, case) {
            (_, Some(e)) if e.is_bad_input() => EXIT_BAD_INPUT,
            (_, Some(e)) if e.is_not_converged() => EXIT_NOT_CONVERGED,
            (CliError::UnknownExample { .. }, _) => EXIT_BAD_INPUT,
            _ => EXIT_OTHER,
        }
    }
}

/// The command line's result type.
pub type CliResult<T> = Result<T, CliError>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exit_codes() {
        assert_eq!(
            CliError::from(CaseError::field("a", 1, "r")).exit_code(),
            EXIT_BAD_INPUT
        );
        let nc = tribo::Error::NotConverged {
            solver: "cg",
            iterations: 3,
            residual: 1e-3,
            tolerance: 1e-10,
        };
        assert_eq!(CliError::from(nc).exit_code(), EXIT_NOT_CONVERGED);
        assert_eq!(
            CliError::from(tribo::Error::invalid("x", 1, "r")).exit_code(),
            EXIT_BAD_INPUT
        );
        let num = tribo::Error::Numerical {
            context: "x",
            detail: "y".into(),
        };
        assert_eq!(CliError::from(num).exit_code(), EXIT_OTHER);
        let unknown = CliError::UnknownExample {
            name: "x".into(),
            known: "y".into(),
        };
        assert_eq!(unknown.exit_code(), EXIT_BAD_INPUT);
        // A library error while deriving the outputs keeps its code.
        let nc = tribo::Error::NotConverged {
            solver: "cg",
            iterations: 3,
            residual: 1e-3,
            tolerance: 1e-10,
        };
        assert_eq!(
            CliError::from(IoError::from(nc)).exit_code(),
            EXIT_NOT_CONVERGED
        );
        let write = IoError::Write {
            path: "x".into(),
            source: std::io::Error::other("full"),
        };
        assert_eq!(CliError::from(write).exit_code(), EXIT_OTHER);
    }
}
