//! The command line's errors and their exit codes.

use std::path::PathBuf;
use thiserror::Error;

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
    /// A data file (height map) has a bad line.
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
    /// Writing an output failed.
    #[error("cannot write {}: {source}", path.display())]
    Write {
        /// The file or directory.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// Writing to standard output failed (a closed pipe ends quietly, see `term`).
    #[error("cannot write to standard output: {source}")]
    Stdout {
        /// Why.
        source: std::io::Error,
    },
    /// An output would contain a non-finite number, or a plot failed.
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

impl CliError {
    /// A field error.
    pub fn field(
        field: impl Into<String>,
        value: impl std::fmt::Display,
        rule: impl Into<String>,
    ) -> Self {
        CliError::Field {
            field: field.into(),
            value: value.to_string(),
            rule: rule.into(),
        }
    }

    /// The process exit code for this error (see the README, "Exit codes").
    pub fn exit_code(&self) -> u8 {
        match self {
            CliError::Field { .. }
            | CliError::Parse { .. }
            | CliError::Unreadable { .. }
            | CliError::DataFile { .. }
            | CliError::UnknownExample { .. } => EXIT_BAD_INPUT,
            CliError::Library(e) => match e {
                tribo::Error::InvalidParameter { .. }
                | tribo::Error::ContactReachesWindow { .. }
                | tribo::Error::NoContact { .. } => EXIT_BAD_INPUT,
                tribo::Error::NotConverged { .. } => EXIT_NOT_CONVERGED,
                _ => EXIT_OTHER,
            },
            CliError::Write { .. } | CliError::Stdout { .. } | CliError::Output { .. } => {
                EXIT_OTHER
            }
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
        assert_eq!(CliError::field("a", 1, "r").exit_code(), EXIT_BAD_INPUT);
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
    }
}
