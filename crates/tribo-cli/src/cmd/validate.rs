//! `tribo validate`: the library's verification suite as a table (or JSON).

use crate::exit::{CliError, CliResult, EXIT_OK, EXIT_VALIDATION_FAILED};

/// Runs `tribo::validation::run_all` and prints its rows; exit 1 when a row fails.
pub fn run(json: bool) -> CliResult<u8> {
    let rows = tribo::validation::run_all()?;
    if json {
        let text = serde_json::to_string_pretty(&rows).map_err(|e| CliError::Output {
            what: "validation rows".into(),
            detail: e.to_string(),
        })?;
        crate::term::outln(&text)?;
    } else {
        crate::term::out(&crate::human::validation_table(&rows))?;
    }
    Ok(if rows.iter().all(|r| r.passed) {
        EXIT_OK
    } else {
        EXIT_VALIDATION_FAILED
    })
}
