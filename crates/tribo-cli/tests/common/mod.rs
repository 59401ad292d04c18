//! Helpers shared by the end-to-end tests.
#![allow(dead_code)] // each test crate uses part of them

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};

/// Run the `tribo` binary with `args`, feeding `stdin` if given.
pub fn tribo(args: &[&str], stdin: Option<&str>) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_tribo"));
    cmd.args(args).stdout(Stdio::piped()).stderr(Stdio::piped());
    cmd.stdin(if stdin.is_some() {
        Stdio::piped()
    } else {
        Stdio::null()
    });
    let mut child = cmd.spawn().expect("spawn tribo");
    feed_stdin(&mut child, stdin);
    child.wait_with_output().expect("wait for tribo")
}

/// Writes `stdin` (if any) to the child's stdin and closes it.
pub fn feed_stdin(child: &mut Child, stdin: Option<&str>) {
    if let Some(text) = stdin {
        use std::io::Write;
        child
            .stdin
            .take()
            .expect("a piped stdin")
            .write_all(text.as_bytes())
            .expect("stdin written");
    }
}

/// Every file of `names` is in `out`.
pub fn assert_files(out: &Path, names: &[&str]) {
    for f in names {
        assert!(out.join(f).is_file(), "{f} missing");
    }
}

/// The files every half-space run writes (the writer's list: the tests check the binary
/// writes them).
pub const CONTACT_FILES: [&str; 6] = tribo_io::halfspace::FILES;

/// The text of the embedded example `name` (the case files `tribo example NAME` prints).
pub fn example(name: &str) -> &'static str {
    tribo_case::examples::find(name)
        .unwrap_or_else(|| panic!("no example {name}"))
        .text
}

/// stderr as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// stdout as text.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// A JSON file.
pub fn read_json(path: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(path).unwrap();
    serde_json::from_str(&text).unwrap()
}

/// Run `tribo run CASE -o OUT ARGS` on `text` (written as case.toml in a fresh directory,
/// with the extra files `files`); the output, the output directory and the directory's
/// guard.
fn run_in_dir(
    text: &str,
    files: &[(&str, &str)],
    args: &[&str],
) -> (Output, PathBuf, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("case.toml");
    std::fs::write(&case, text).unwrap();
    for (name, content) in files {
        std::fs::write(dir.path().join(name), content).unwrap();
    }
    let out = dir.path().join("out");
    let mut all = vec!["run", case.to_str().unwrap(), "-o", out.to_str().unwrap()];
    all.extend_from_slice(args);
    let o = tribo(&all, None);
    (o, out, dir)
}

/// Run `tribo run CASE -o OUT --quiet EXTRA` on `text` (see `run_in_dir`).
pub fn run_case(
    text: &str,
    files: &[(&str, &str)],
    extra: &[&str],
) -> (Output, PathBuf, tempfile::TempDir) {
    let mut args = vec!["--quiet"];
    args.extend_from_slice(extra);
    run_in_dir(text, files, &args)
}

/// Like [`run_case`] without `--quiet`: the notes go to stderr.
pub fn run_case_loud(text: &str, files: &[(&str, &str)]) -> (Output, tempfile::TempDir) {
    let (o, _, dir) = run_in_dir(text, files, &[]);
    (o, dir)
}

/// The case `text` (with `files`) exits 2, names `field` on stderr and writes nothing;
/// stderr.
pub fn assert_bad_input(text: &str, files: &[(&str, &str)], field: &str) -> String {
    assert_refused(text, files, &[], &[field])
}

/// The case `text` (with `files`, run with the `extra` arguments) exits 2, its stderr holds
/// every one of `needles`, and it writes nothing; stderr.
pub fn assert_refused(
    text: &str,
    files: &[(&str, &str)],
    extra: &[&str],
    needles: &[&str],
) -> String {
    let (o, out, _dir) = run_case(text, files, extra);
    let err = stderr(&o);
    assert_eq!(
        o.status.code(),
        Some(2),
        "expected exit 2 for {needles:?}; stderr: {err}"
    );
    for needle in needles {
        assert!(
            err.contains(needle),
            "stderr does not name {needle:?}: {err}"
        );
    }
    assert!(
        !out.exists(),
        "bad input for {needles:?} wrote {}",
        out.display()
    );
    err
}
