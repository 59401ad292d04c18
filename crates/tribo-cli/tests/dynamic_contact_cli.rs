//! The dynamic contact case through the command line (issue 13): bad input is exit 2
//! naming the item, and a run whose stdout pipe is closed (`tribo run ... | head -1`) ends
//! without a panic, its files complete.
// Tests may unwrap: a panic here is a failed test.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::io::{BufRead, BufReader, Write};
use std::process::{Command, Output, Stdio};

fn rod_impact() -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_tribo"))
        .args(["example", "rod-impact"])
        .output()
        .unwrap();
    assert!(out.status.success());
    String::from_utf8(out.stdout).unwrap()
}

/// `tribo run - -q -o DIR` on `text`.
fn run(text: &str, dir: &std::path::Path) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_tribo"))
        .args(["run", "-", "-q", "-o"])
        .arg(dir)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let _ = child.stdin.take().unwrap().write_all(text.as_bytes());
    child.wait_with_output().unwrap()
}

/// Each edit of the rod impact example is refused with exit 2 and a message naming the
/// item: an initial velocity of a region that does not exist, a negative time step, a
/// probe outside both rods, a rigid segment.
#[test]
fn bad_dynamic_contact_input_is_exit_2_naming_the_item() {
    let base = rod_impact();
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "initial_velocity = { striker =",
            "initial_velocity = { hammer =",
            "dynamics.initial_velocity.hammer",
        ),
        (
            "time_step = \"0.5 us\"",
            "time_step = \"-0.5 us\"",
            "dynamics.time_step",
        ),
        (
            "at = [\"-50 mm\", \"12.5 mm\"]",
            "at = [\"-500 mm\", \"12.5 mm\"]",
            "probe[0].at",
        ),
        (
            "[[contact]]",
            "rigid = [\"t_back\"]\n\n[[contact]]",
            "rigid",
        ),
    ];
    for (from, to, item) in cases {
        assert!(base.contains(from), "{from}");
        let text = base.replacen(from, to, 1);
        let out = run(&text, &dir.path().join("bad"));
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{item}: {err}");
        assert!(err.contains(item), "{item}: {err}");
        assert!(!err.contains("panicked"), "{item}: {err}");
    }
}

/// `tribo run - -o DIR | head -1` on the rod impact (without snapshots): the reader takes
/// one line and closes the pipe; the run must end without a panic (exit 0: a closed
/// stdout is not an error) with every file written.
#[test]
fn a_closed_pipe_after_one_line_does_not_panic() {
    let text = rod_impact().replace("fields_every = 30\n", "");
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("rod");
    let mut child = Command::new(env!("CARGO_BIN_EXE_tribo"))
        .args(["run", "-", "-o"])
        .arg(&out_dir)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let _ = child.stdin.take().unwrap().write_all(text.as_bytes());
    {
        let mut reader = BufReader::new(child.stdout.take().unwrap());
        let mut line = String::new();
        reader.read_line(&mut line).unwrap();
        assert!(line.contains("rod impact"), "{line}");
    }
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(out.status.code(), Some(0), "{err}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("summary.json")).unwrap())
            .unwrap();
    assert_eq!(summary["dynamics"]["realisation"], "marching");
    for f in summary["outputs"].as_array().unwrap() {
        let f = f.as_str().unwrap();
        assert!(std::fs::metadata(out_dir.join(f)).unwrap().len() > 0, "{f}");
    }
    for f in ["contacts.csv", "energy.csv", "probes.csv"] {
        assert!(summary["outputs"]
            .as_array()
            .unwrap()
            .iter()
            .any(|x| x == f));
    }
}
