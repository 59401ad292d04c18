//! `tribo example`: the embedded example cases, listed or printed.

use crate::exit::{CliError, CliResult, EXIT_OK};
use std::path::Path;
use tribo_case::examples;
use tribo_io::atomic::write_atomic;
use tribo_io::IoError;

/// Lists the examples (no name), prints one, or (with `out`) writes it as `out/NAME.toml`
/// with the data files it reads.
pub fn run(name: Option<&str>, out: Option<&Path>) -> CliResult<u8> {
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
            let files = examples::data_files(ex.name)?;
            match out {
                None => {
                    if !files.is_empty() {
                        let names: Vec<&str> = files.iter().map(|f| f.0).collect();
                        crate::term::note(&format!(
                            "this example reads {}: write the case with its data by \
                             `tribo example {} -o DIR`",
                            names.join(", "),
                            ex.name
                        ));
                    }
                    crate::term::out(ex.text)?;
                }
                Some(dir) => {
                    std::fs::create_dir_all(dir).map_err(|source| IoError::Write {
                        path: dir.to_path_buf(),
                        source,
                    })?;
                    for (file, bytes) in &files {
                        write_atomic(dir, file, bytes)?;
                    }
                    let case = format!("{}.toml", ex.name);
                    write_atomic(dir, &case, ex.text.as_bytes())?;
                    crate::term::outln(&format!("wrote {}", dir.join(&case).display()))?;
                }
            }
            Ok(EXIT_OK)
        }
    }
}
