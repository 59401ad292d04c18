//! JSON outputs: pretty-printed, as `summary.json` and the fatigue reports are written.

use crate::error::{IoError, IoResult};
use serde::Serialize;

/// `value` as pretty-printed JSON (two-space indent, no trailing newline); `what` names the
/// output in the error.
pub fn to_pretty<T: Serialize + ?Sized>(value: &T, what: &str) -> IoResult<String> {
    serde_json::to_string_pretty(value).map_err(|e| IoError::Json {
        what: what.into(),
        detail: e.to_string(),
    })
}
