//! The errors of a study: bad input in the study file (named item, its value, the rule), a
//! base case that is itself invalid, a study directory that is not what it should be, and
//! files that cannot be read or written. The failure of one point is not an error of the
//! study: it is recorded with the point (`points/NNNNNN.failed`) and the others go on.

use std::path::PathBuf;
use thiserror::Error;
use tribo_case::CaseError;

/// An error of a study.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum StudyError {
    /// An item of the study file breaks a rule (`grid[1].key`, `study.seed`, ...).
    #[error("{item} = {value}: {rule}")]
    Item {
        /// The item, as a key path into the study file (`random[0].sd`).
        item: String,
        /// The offending value as written.
        value: String,
        /// The rule.
        rule: String,
    },
    /// The study file is not valid TOML or does not fit the study schema.
    #[error("{path}: {message}")]
    Parse {
        /// The study file (or `<embedded NAME>`).
        path: String,
        /// The parser's message.
        message: String,
    },
    /// The base case is invalid (before any parameter is applied).
    #[error("base case: {0}")]
    Base(#[source] CaseError),
    /// A study directory is missing a file, or holds another study.
    #[error("{}: {detail}", dir.display())]
    Dir {
        /// The study directory.
        dir: PathBuf,
        /// What is wrong.
        detail: String,
    },
    /// A file could not be read or written.
    #[error("{}: {source}", path.display())]
    File {
        /// The file or directory.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// Writing a point's outputs failed.
    #[error(transparent)]
    Write(#[from] tribo_io::IoError),
}

impl StudyError {
    /// An item error.
    pub fn item(
        item: impl Into<String>,
        value: impl std::fmt::Display,
        rule: impl Into<String>,
    ) -> Self {
        StudyError::Item {
            item: item.into(),
            value: value.to_string(),
            rule: rule.into(),
        }
    }

    /// A file error.
    pub fn file(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        StudyError::File {
            path: path.into(),
            source,
        }
    }

    /// Whether the error is bad input (the study file, its base case, the study directory
    /// named on the command line), as opposed to a failure to read or write files.
    pub fn is_bad_input(&self) -> bool {
        match self {
            StudyError::Item { .. } | StudyError::Parse { .. } | StudyError::Dir { .. } => true,
            StudyError::Base(e) => e.is_bad_input(),
            StudyError::File { .. } | StudyError::Write(_) => false,
        }
    }
}

/// The result type of this crate.
pub type StudyResult<T> = Result<T, StudyError>;
