//! Atomic writes: a file is written whole or not at all; an error leaves neither a partial
//! file nor a temporary behind; the earlier run's listed files are removed first.
// Tests may unwrap: a panic here is a failed test (workspace lints deny it in library code).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;
use tribo_io::atomic::{draw_atomic, prepare_dir, write_atomic, TEMP_PREFIX};
use tribo_io::IoError;

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn a_write_replaces_the_file_whole() {
    let dir = tempfile::tempdir().unwrap();
    write_atomic(dir.path(), "a.csv", b"old\n").unwrap();
    write_atomic(dir.path(), "a.csv", b"new\n").unwrap();
    assert_eq!(std::fs::read(dir.path().join("a.csv")).unwrap(), b"new\n");
    assert_eq!(names(dir.path()), vec!["a.csv"]);
}

#[test]
fn a_failed_draw_leaves_no_partial_file_and_keeps_the_old_one() {
    let dir = tempfile::tempdir().unwrap();
    write_atomic(dir.path(), "p.png", b"the earlier plot").unwrap();
    let err = draw_atomic(dir.path(), "p.png", |tmp| {
        // Half a file, then the failure (a plotting error, a full disk).
        std::fs::write(tmp, b"half").unwrap();
        Err("the backend failed".into())
    })
    .unwrap_err();
    assert!(matches!(err, IoError::Draw { .. }), "{err}");
    assert_eq!(err.to_string(), "output p.png: the backend failed");
    // No temporary left, the earlier file intact.
    assert_eq!(names(dir.path()), vec!["p.png"]);
    assert_eq!(
        std::fs::read(dir.path().join("p.png")).unwrap(),
        b"the earlier plot"
    );
}

#[test]
fn an_unwritable_directory_is_an_error_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("missing");
    let err = write_atomic(&missing, "a.csv", b"x").unwrap_err();
    assert!(matches!(err, IoError::Write { .. }), "{err}");
    assert!(err.to_string().starts_with("cannot write "), "{err}");
    assert!(!missing.exists());
}

#[cfg(target_os = "linux")]
#[test]
fn a_full_disk_is_an_error_and_leaves_nothing() {
    // /dev/full is not a directory: the temporary cannot be created there, an error.
    let err = write_atomic(Path::new("/dev/full"), "a.csv", b"x").unwrap_err();
    assert!(matches!(err, IoError::Write { .. }), "{err}");
}

#[test]
fn prepare_dir_removes_the_listed_files_and_our_temporaries_only() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path().join("out");
    std::fs::create_dir(&d).unwrap();
    std::fs::write(
        d.join("summary.json"),
        br#"{"outputs": ["a.csv", "../escape.txt", "summary.json"]}"#,
    )
    .unwrap();
    std::fs::write(d.join("a.csv"), b"1").unwrap();
    std::fs::write(d.join("mine.txt"), b"keep").unwrap();
    std::fs::write(d.join(format!("{TEMP_PREFIX}abc-b.csv")), b"left over").unwrap();
    std::fs::write(dir.path().join("escape.txt"), b"outside").unwrap();
    prepare_dir(&d, "summary.json", false).unwrap();
    assert_eq!(names(&d), vec!["mine.txt"]);
    assert!(dir.path().join("escape.txt").exists());
    // A directory that does not exist yet is created.
    let fresh = dir.path().join("a/b");
    prepare_dir(&fresh, "summary.json", false).unwrap();
    assert!(fresh.is_dir());
}
