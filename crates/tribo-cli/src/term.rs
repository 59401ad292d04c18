//! Fallible writes to stdout and stderr. `println!`/`eprintln!` panic when the stream is a
//! closed pipe or a full disk (exit 101); everything the command line prints goes through
//! here instead.
//!
//! The contract (docs/user/cli.md, "Exit codes"): a closed pipe on stdout (`tribo run --json | head`)
//! ends the command quietly with exit 0, like most command-line tools; any other write error
//! on stdout (a full disk: `tribo example > /dev/full`) exits 1 with a message on stderr; when
//! stderr itself cannot be written, the command exits 1 silently. Notes on stderr are best
//! effort: a failing stderr never stops a run.

use crate::exit::{CliError, CliResult};
use std::io::Write;

/// Writes `text` to stdout and flushes it.
pub fn out(text: &str) -> CliResult<()> {
    let mut o = std::io::stdout().lock();
    o.write_all(text.as_bytes())
        .and_then(|()| o.flush())
        .map_err(|source| CliError::Stdout { source })
}

/// Writes `text` and a newline to stdout.
pub fn outln(text: &str) -> CliResult<()> {
    let mut s = String::with_capacity(text.len() + 1);
    s.push_str(text);
    s.push('\n');
    out(&s)
}

/// A line on stderr (a note or a warning), best effort: an error writing it is ignored.
pub fn note(text: &str) {
    let mut e = std::io::stderr().lock();
    let _ = writeln!(e, "{text}").and_then(|()| e.flush());
}

/// Reports `error` on stderr and returns the exit code: 0 for a closed pipe on stdout
/// (nothing reported), 1 when stderr cannot be written either, else the error's own code.
pub fn report(error: &CliError) -> u8 {
    if let CliError::Stdout { source } = error {
        if source.kind() == std::io::ErrorKind::BrokenPipe {
            return crate::exit::EXIT_OK;
        }
    }
    let mut e = std::io::stderr().lock();
    match writeln!(e, "error: {error}").and_then(|()| e.flush()) {
        Ok(()) => error.exit_code(),
        Err(_) => crate::exit::EXIT_OTHER,
    }
}
