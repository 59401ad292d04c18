//! Atomic writes: every file is written whole or not at all. Its content goes to a temporary
//! file in the output directory (created exclusively under an unpredictable `.tribo-tmp-*`
//! name), which is then renamed over the final name. Before the first file, [`prepare_dir`]
//! removes the earlier run's summary and the files it lists; the writers write the new
//! summary last, so a directory without one is an incomplete run. An interrupted run
//! (SIGINT, SIGTERM, SIGHUP) removes the temporary being written ([`signals`]).

use crate::error::{IoError, IoResult};
use std::io::Write;
use std::path::Path;

/// The prefix of every temporary file tribo creates in an output directory:
/// `.tribo-tmp-<random>-<final name>`. A later run removes leftovers with this prefix (a run
/// killed with SIGKILL cannot clean up after itself).
pub const TEMP_PREFIX: &str = ".tribo-tmp-";

/// A new temporary file in `dir` for the final name `name`: created exclusively
/// (`O_CREAT | O_EXCL`, so a file or symlink planted at the name makes it pick another name
/// rather than follow it) under an unpredictable name. The final name stays the suffix:
/// plotters picks the image format from the extension. Removed when dropped unless persisted.
fn temp_file(dir: &Path, name: &str) -> IoResult<tempfile::NamedTempFile> {
    tempfile::Builder::new()
        .prefix(TEMP_PREFIX)
        .suffix(&format!("-{name}"))
        .rand_bytes(12)
        .make_in(dir, |path| {
            // Remembered before the file exists: a signal that arrives between its creation
            // and the first write still removes it (remembering it after creation left a
            // window in which a SIGINT left the temporary behind).
            signals::remember(path);
            let mut options = std::fs::OpenOptions::new();
            options.write(true).create_new(true);
            // Outputs are ordinary files: mode 0666 less the umask, as `File::create` makes
            // them (tempfile's default is 0600).
            #[cfg(unix)]
            std::os::unix::fs::OpenOptionsExt::mode(&mut options, 0o666);
            options.open(path)
        })
        .map_err(|source| {
            signals::forget();
            IoError::Write {
                path: dir.join(name),
                source,
            }
        })
}

/// Renames the temporary over `dir/name` (a symlink there is replaced, not followed).
fn commit(tmp: tempfile::NamedTempFile, dir: &Path, name: &str) -> IoResult<()> {
    let target = dir.join(name);
    let result = tmp.persist(&target);
    signals::forget();
    // On failure the error owns the temporary; dropping it removes the file.
    result.map(drop).map_err(|e| IoError::Write {
        path: target,
        source: e.error,
    })
}

/// Write `bytes` to `dir/name` atomically (exclusive temporary file + rename).
pub fn write_atomic(dir: &Path, name: &str, bytes: &[u8]) -> IoResult<()> {
    let mut tmp = temp_file(dir, name)?;
    let result = (|| {
        tmp.as_file_mut().write_all(bytes)?;
        tmp.as_file().sync_all()
    })();
    if let Err(source) = result {
        signals::forget();
        return Err(IoError::Write {
            path: dir.join(name),
            source,
        });
    }
    commit(tmp, dir, name)
}

/// Let `draw` write a file at a temporary path in `dir` (a plot: plotters writes to a path
/// and picks the format from its extension, which the temporary keeps) and rename it over
/// `dir/name` (whole or nothing). `draw`'s error becomes [`IoError::Draw`].
pub fn draw_atomic(
    dir: &Path,
    name: &str,
    draw: impl FnOnce(&Path) -> Result<(), String>,
) -> IoResult<()> {
    let tmp = temp_file(dir, name)?;
    if let Err(detail) = draw(tmp.path()) {
        signals::forget();
        return Err(IoError::Draw {
            what: name.to_string(),
            detail,
        });
    }
    commit(tmp, dir, name)
}

/// Is `name` one of our temporaries: `.tribo-tmp-*`, or `.tmp-<pid>-*` of earlier versions?
fn is_our_temporary(name: &str) -> bool {
    if name.starts_with(TEMP_PREFIX) {
        return true;
    }
    name.strip_prefix(".tmp-")
        .and_then(|rest| rest.split_once('-'))
        .is_some_and(|(pid, _)| !pid.is_empty() && pid.bytes().all(|b| b.is_ascii_digit()))
}

/// Is `name` a bare file name (no separator, not `.`/`..`, not empty)?
fn is_bare_name(name: &str) -> bool {
    !name.is_empty()
        && name != "."
        && name != ".."
        && !name.contains('/')
        && !name.contains('\\')
        && !name.contains('\0')
}

/// Removes `dir/name` if it is a plain file (never follows a symlink, never a directory).
fn remove_plain_file(dir: &Path, name: &str) -> IoResult<()> {
    let path = dir.join(name);
    match std::fs::symlink_metadata(&path) {
        Ok(m) if m.file_type().is_file() => {
            std::fs::remove_file(&path).map_err(|source| IoError::Write { path, source })
        }
        _ => Ok(()),
    }
}

/// Makes `dir` ready for a new run's files, before any of them is written:
///
/// 1. creates it if needed;
/// 2. reads the earlier run's summary `summary_name` (a plain file only) and removes it first, so
///    that a directory without a current summary is visibly incomplete until the new run
///    writes its summary last;
/// 3. removes the files that summary lists under `outputs` (plain files with bare names,
///    inside `dir` only; symlinks and anything not listed are left alone), so no stale plot
///    sits beside new ones;
/// 4. removes leftovers of our temporaries ([`TEMP_PREFIX`]) from interrupted runs;
/// 5. with `on_signal`, installs the SIGINT/SIGTERM/SIGHUP handler that removes the temporary
///    being written ([`signals`]; a program with handlers of its own, an interpreter, leaves
///    it off).
pub fn prepare_dir(dir: &Path, summary_name: &str, on_signal: bool) -> IoResult<()> {
    std::fs::create_dir_all(dir).map_err(|source| IoError::Write {
        path: dir.to_path_buf(),
        source,
    })?;
    let summary = dir.join(summary_name);
    let old: Vec<String> = match std::fs::symlink_metadata(&summary) {
        Ok(m) if m.file_type().is_file() => {
            let listed = std::fs::read(&summary)
                .ok()
                .and_then(|b| serde_json::from_slice::<serde_json::Value>(&b).ok())
                .and_then(|v| {
                    v.get("outputs").and_then(|o| o.as_array()).map(|a| {
                        a.iter()
                            .filter_map(|x| x.as_str().map(str::to_string))
                            .collect()
                    })
                })
                .unwrap_or_default();
            remove_plain_file(dir, summary_name)?;
            listed
        }
        _ => Vec::new(),
    };
    for name in old.iter().filter(|n| is_bare_name(n)) {
        remove_plain_file(dir, name)?;
    }
    let entries = std::fs::read_dir(dir).map_err(|source| IoError::Write {
        path: dir.to_path_buf(),
        source,
    })?;
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(name) = name.to_str() else { continue };
        if !is_our_temporary(name) {
            continue;
        }
        // Our own leftovers: plain files, or a link planted at such a name (the link itself).
        if let Ok(t) = entry.file_type() {
            if t.is_file() || t.is_symlink() {
                let path = entry.path();
                std::fs::remove_file(&path).map_err(|source| IoError::Write { path, source })?;
            }
        }
    }
    if on_signal {
        signals::install();
    }
    Ok(())
}

/// Removing the temporary being written when the run is interrupted (SIGINT, SIGTERM,
/// SIGHUP). The handler is async-signal-safe: it reads one atomic pointer to a
/// NUL-terminated path, `unlink`s it, restores the default action and re-raises the signal
/// (so the exit status still says which signal ended the run). Paths are leaked, never freed,
/// so the handler never reads freed memory (a few dozen short strings per run).
#[cfg(unix)]
pub mod signals {
    use std::ffi::CString;
    use std::os::unix::ffi::OsStrExt;
    use std::path::Path;
    use std::sync::atomic::{AtomicPtr, Ordering};
    use std::sync::Once;

    static CURRENT: AtomicPtr<libc::c_char> = AtomicPtr::new(std::ptr::null_mut());
    static INSTALL: Once = Once::new();
    const SIGNALS: [libc::c_int; 3] = [libc::SIGINT, libc::SIGTERM, libc::SIGHUP];

    extern "C" fn on_signal(sig: libc::c_int) {
        let p = CURRENT.swap(std::ptr::null_mut(), Ordering::SeqCst);
        // SAFETY: `p` is null or a leaked, never freed CString; unlink, signal and raise are
        // async-signal-safe (POSIX.1-2008, 2.4.3).
        unsafe {
            if !p.is_null() {
                libc::unlink(p);
            }
            libc::signal(sig, libc::SIG_DFL);
            libc::raise(sig);
        }
    }

    /// Installs the handler (once per process).
    pub fn install() {
        INSTALL.call_once(|| {
            for sig in SIGNALS {
                // SAFETY: installing a handler that only does async-signal-safe calls.
                unsafe {
                    libc::signal(sig, on_signal as *const () as libc::sighandler_t);
                }
            }
        });
    }

    /// The temporary now being written (removed if a signal arrives).
    pub fn remember(path: &Path) {
        if let Ok(c) = CString::new(path.as_os_str().as_bytes()) {
            CURRENT.store(c.into_raw(), Ordering::SeqCst);
        }
    }

    /// No temporary is being written any more.
    pub fn forget() {
        CURRENT.store(std::ptr::null_mut(), Ordering::SeqCst);
    }
}

/// No signal handling off Unix: the next run removes leftovers.
#[cfg(not(unix))]
pub mod signals {
    /// Nothing to install.
    pub fn install() {}
    /// Nothing remembered.
    pub fn remember(_: &std::path::Path) {}
    /// Nothing to forget.
    pub fn forget() {}
}
