//! `tribo example`: the embedded example cases, listed or printed.

use crate::exit::{CliError, CliResult, EXIT_OK};
use tribo_case::examples;

/// Lists the examples (no name) or prints one.
pub fn run(name: Option<&str>) -> CliResult<u8> {
    match name {
        None => {
            let width = examples::EXAMPLES
                .iter()
                .map(|e| e.name.len())
                .max()
                .unwrap_or(0);
            let mut text = String::from("Example cases (print one with `tribo example NAME`, run it with `tribo example NAME | tribo run -`):\n");
            for e in examples::EXAMPLES {
                text.push_str(&format!("  {:<width$}  {}\n", e.name, e.description));
            }
            crate::term::out(&text)?;
            Ok(EXIT_OK)
        }
        Some(n) => {
            let ex = examples::find(n).ok_or_else(|| CliError::UnknownExample {
                name: n.into(),
                known: examples::names(),
            })?;
            crate::term::out(ex.text)?;
            Ok(EXIT_OK)
        }
    }
}
