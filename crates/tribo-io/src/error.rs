//! The writers' errors.

use std::path::PathBuf;
use thiserror::Error;
use tribo_case::CaseError;

/// An error of writing a run's outputs. Nothing is left half-written: a file is written
/// whole or not at all ([`crate::atomic`]), and the numbers are checked before the first file.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum IoError {
    /// Deriving what the outputs show failed (a library error while evaluating it).
    #[error(transparent)]
    Case(#[from] CaseError),
    /// Creating, writing or renaming a file or directory failed (a full disk, no permission).
    #[error("cannot write {}: {source}", path.display())]
    Write {
        /// The file or directory.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// An output would contain a non-finite number (nothing is written).
    #[error("output {what}: {detail}")]
    NonFinite {
        /// Which output.
        what: String,
        /// Which value.
        detail: String,
    },
    /// The results do not have the shape an output needs (arrays of the wrong length, a
    /// missing field).
    #[error("output {what}: {detail}")]
    Shape {
        /// Which output.
        what: String,
        /// What is missing or wrong.
        detail: String,
    },
    /// Drawing a plot failed.
    #[error("output {what}: {detail}")]
    Draw {
        /// The file.
        what: String,
        /// The plotting library's message.
        detail: String,
    },
    /// Serializing a JSON output failed.
    #[error("output {what}: {detail}")]
    Json {
        /// The file.
        what: String,
        /// serde_json's message.
        detail: String,
    },
}

/// The writers' result type.
pub type IoResult<T> = Result<T, IoError>;

impl From<tribo::Error> for IoError {
    fn from(e: tribo::Error) -> Self {
        IoError::Case(CaseError::Library(e))
    }
}

/// Refuses a non-finite value among `values`, naming the output and the value's index.
pub fn check_finite(what: &str, values: &[f64]) -> IoResult<()> {
    match values.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(k) => Err(IoError::NonFinite {
            what: what.to_string(),
            detail: format!(
                "value {k} is {} (refusing to write a non-finite result)",
                values[k]
            ),
        }),
    }
}
