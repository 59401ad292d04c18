//! Output integrity: write failures on stdout/stderr (closed pipe, full disk) for every
//! subcommand, and the output directory's contract (safe temporaries, leftovers removed, the
//! earlier run's outputs removed, the summary gone while a run writes).
// Tests may unwrap: a panic here is a failed test (workspace lints deny it in library code).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::fs;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

mod common;
#[path = "common/summary.rs"]
mod summary;

const BIN: &str = env!("CARGO_BIN_EXE_tribo");

/// A small case: the steel ball on a flat on 16 x 16 elements.
fn small() -> String {
    common::example("sphere-on-flat").replace("n = 64", "n = 16")
}

fn manifest(p: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(p)
}

/// The argument lists of every subcommand that prints on stdout, each with a fresh output
/// directory under `dir` where it writes files; the text to feed on stdin. `validate` (the
/// whole verification suite, the slowest) only with `validate`.
fn commands(dir: &Path, validate: bool) -> Vec<(Vec<String>, Option<String>)> {
    let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>();
    let out = |n: &str| dir.join(n).display().to_string();
    let case = dir.join("case.toml");
    fs::write(&case, small()).unwrap();
    let diagram =
        fs::read_to_string(manifest("../tribo-case/examples/fatigue-diagram.toml")).unwrap();
    let data = manifest("examples/data/woehler-steel.csv")
        .display()
        .to_string();
    let mut c = vec![
        (s(&["--help"]), None),
        (s(&["--version"]), None),
        (s(&["example"]), None),
        (s(&["example", "sphere-on-flat"]), None),
        (
            s(&[
                "run",
                &case.display().to_string(),
                "-o",
                &out("run"),
                "--json",
            ]),
            None,
        ),
        (
            s(&[
                "run",
                &case.display().to_string(),
                "-o",
                &out("run_h"),
                "-q",
            ]),
            None,
        ),
        (s(&["run", &case.display().to_string(), "--dry-run"]), None),
        (s(&["fatigue", "fit", &data, "-o", &out("fit")]), None),
        (
            s(&["fatigue", "diagram", "-", "-o", &out("diagram"), "--json"]),
            Some(diagram),
        ),
    ];
    if validate {
        c.push((s(&["validate"]), None));
    }
    c
}

fn spawn(args: &[String], stdin: &Option<String>, stdout: Stdio, stderr: Stdio) -> Child {
    let mut child = Command::new(BIN)
        .args(args)
        .stdin(if stdin.is_some() {
            Stdio::piped()
        } else {
            Stdio::null()
        })
        .stdout(stdout)
        .stderr(stderr)
        .spawn()
        .unwrap();
    common::feed_stdin(&mut child, stdin.as_deref());
    child
}

fn dev_full() -> fs::File {
    fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap()
}

/// Every file the summary lists is present and complete (the run wrote everything before it
/// printed anything).
fn assert_complete(dir: &Path) {
    let s: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    for f in s["outputs"].as_array().unwrap() {
        let f = f.as_str().unwrap();
        assert!(fs::metadata(dir.join(f)).unwrap().len() > 0, "{f}");
    }
    assert!(leftovers(dir).is_empty());
}

fn leftovers(dir: &Path) -> Vec<String> {
    fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".tribo-tmp-") || n.starts_with(".tmp-"))
        .collect()
}

#[test]
fn a_closed_stdout_pipe_ends_quietly_with_exit_0() {
    let dir = tempfile::tempdir().unwrap();
    for (args, stdin) in commands(dir.path(), true) {
        let mut child = spawn(&args, &stdin, Stdio::piped(), Stdio::piped());
        // Close the read end before the child writes: its writes get EPIPE.
        drop(child.stdout.take());
        let out = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert_eq!(out.status.code(), Some(0), "{args:?}: {err}");
        assert!(err.is_empty(), "{args:?}: quiet, got {err}");
    }
    assert_complete(&dir.path().join("run"));
}

#[test]
fn a_full_disk_on_stdout_exits_1_with_a_message() {
    let dir = tempfile::tempdir().unwrap();
    for (args, stdin) in commands(dir.path(), true) {
        let child = spawn(&args, &stdin, Stdio::from(dev_full()), Stdio::piped());
        let out = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.contains("cannot write to standard output") && err.contains("No space left"),
            "{args:?}: {err}"
        );
    }
    // The files were written whole before the summary went to stdout.
    assert_complete(&dir.path().join("run"));
    assert_complete(&dir.path().join("run_h"));
}

#[test]
fn a_full_disk_on_stderr_exits_1_silently() {
    let dir = tempfile::tempdir().unwrap();
    // Errors (exit 2 when stderr works) whose message cannot be written.
    let missing = dir.path().join("missing.toml").display().to_string();
    for args in [
        vec!["run", missing.as_str()],
        vec!["example", "no-such-example"],
        vec!["fatigue", "fit", missing.as_str()],
        vec!["fatigue", "diagram", missing.as_str()],
    ] {
        let args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
        let out = spawn(&args, &None, Stdio::piped(), Stdio::from(dev_full()))
            .wait_with_output()
            .unwrap();
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        assert!(out.stdout.is_empty());
        // Both streams full: still exit 1, no panic (exit 101).
        let out = spawn(
            &args,
            &None,
            Stdio::from(dev_full()),
            Stdio::from(dev_full()),
        )
        .wait_with_output()
        .unwrap();
        assert_eq!(out.status.code(), Some(1), "{args:?}");
    }
    // Successful commands with a full stderr: progress and notes are best effort.
    for (args, stdin) in commands(dir.path(), false) {
        let out = spawn(&args, &stdin, Stdio::piped(), Stdio::from(dev_full()))
            .wait_with_output()
            .unwrap();
        assert_eq!(out.status.code(), Some(0), "{args:?}");
        assert!(!out.stdout.is_empty(), "{args:?}");
    }
}

#[test]
fn a_closed_stderr_does_not_stop_a_run() {
    // Progress (indicatif) and notes go to stderr; a closed stderr pipe must not panic.
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("case.toml");
    fs::write(&case, small()).unwrap();
    let out_dir = dir.path().join("out");
    let args: Vec<String> = [
        "run",
        case.to_str().unwrap(),
        "-o",
        out_dir.to_str().unwrap(),
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let mut child = spawn(&args, &None, Stdio::piped(), Stdio::piped());
    drop(child.stderr.take());
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0));
    assert_complete(&out_dir);
}

fn run_into(dir: &Path, case: &str) -> std::process::Output {
    let case_path = dir.with_extension("toml");
    fs::write(&case_path, case).unwrap();
    Command::new(BIN)
        .args([
            "run",
            case_path.to_str().unwrap(),
            "-q",
            "-o",
            dir.to_str().unwrap(),
        ])
        .output()
        .unwrap()
}

#[cfg(unix)]
#[test]
fn symlinks_planted_at_our_names_are_not_followed() {
    let base = tempfile::tempdir().unwrap();
    let out = base.path().join("out");
    fs::create_dir(&out).unwrap();
    let victim = base.path().join("victim.txt");
    fs::write(&victim, "precious").unwrap();
    // Every final name, the former predictable temporaries (.tmp-<pid>-NAME for the next
    // pids) and names with our temporary prefix.
    let names = common::CONTACT_FILES;
    let me = std::process::id();
    for n in names {
        std::os::unix::fs::symlink(&victim, out.join(n)).unwrap();
        for pid in me..me + 64 {
            std::os::unix::fs::symlink(&victim, out.join(format!(".tmp-{pid}-{n}"))).unwrap();
        }
        std::os::unix::fs::symlink(&victim, out.join(format!(".tribo-tmp-x-{n}"))).unwrap();
    }
    let o = run_into(&out, &small());
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(fs::read_to_string(&victim).unwrap(), "precious");
    for n in names {
        let m = fs::symlink_metadata(out.join(n)).unwrap();
        assert!(m.file_type().is_file(), "{n} is a regular file now");
    }
    assert_complete(&out);
}

#[test]
fn leftover_temporaries_are_removed_and_nothing_else() {
    let base = tempfile::tempdir().unwrap();
    let out = base.path().join("out");
    fs::create_dir(&out).unwrap();
    for n in [
        ".tribo-tmp-Ab12Cd34Ef56-pressure.csv",
        ".tribo-tmp-zz-summary.json",
        ".tmp-12345-fields.vti",
    ] {
        fs::write(out.join(n), "truncated").unwrap();
    }
    for n in ["notes.txt", ".tmpfoo", ".tmp-abc-x", ".tribo-other"] {
        fs::write(out.join(n), "mine").unwrap();
    }
    let o = run_into(&out, &small());
    assert_eq!(o.status.code(), Some(0));
    assert!(
        leftovers(&out).iter().all(|n| n == ".tmp-abc-x"),
        "{:?}",
        leftovers(&out)
    );
    for n in ["notes.txt", ".tmpfoo", ".tmp-abc-x", ".tribo-other"] {
        assert_eq!(fs::read_to_string(out.join(n)).unwrap(), "mine", "{n}");
    }
}

#[test]
fn the_earlier_runs_outputs_are_removed_and_nothing_else() {
    let base = tempfile::tempdir().unwrap();
    let out = base.path().join("out");
    // A run with friction writes traction.csv and two more plots; the next run, without
    // friction, must not leave them beside its own files.
    let friction = small().replace("[contact]\n", "[contact]\nfriction = 0.2\nsliding = true\n");
    let o = run_into(&out, &friction);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(out.join("traction.csv").is_file());
    let o = run_into(&out, &small());
    assert_eq!(o.status.code(), Some(0));
    for f in ["traction.csv", "stick_slip.png", "traction_profiles.png"] {
        assert!(!out.join(f).exists(), "stale {f}");
    }
    assert_complete(&out);

    // A forged summary: only bare names of plain files inside the directory are removed.
    let outside = base.path().join("outside.txt");
    fs::write(&outside, "keep").unwrap();
    fs::create_dir(out.join("subdir")).unwrap();
    fs::write(out.join("subdir/inner.png"), "keep").unwrap();
    fs::write(out.join("stale.png"), "old").unwrap();
    fs::write(out.join("unlisted.png"), "keep").unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(&outside, out.join("link.png")).unwrap();
    let forged = serde_json::json!({
        "outputs": [
            "stale.png", "../outside.txt", outside.to_str().unwrap(), "subdir",
            "subdir/inner.png", "link.png", ".", "..", ""
        ]
    });
    fs::write(out.join("summary.json"), forged.to_string()).unwrap();
    let o = run_into(&out, &small());
    assert_eq!(o.status.code(), Some(0));
    assert!(!out.join("stale.png").exists());
    assert_eq!(fs::read_to_string(&outside).unwrap(), "keep");
    assert_eq!(
        fs::read_to_string(out.join("subdir/inner.png")).unwrap(),
        "keep"
    );
    assert_eq!(
        fs::read_to_string(out.join("unlisted.png")).unwrap(),
        "keep"
    );
    #[cfg(unix)]
    assert!(fs::symlink_metadata(out.join("link.png"))
        .unwrap()
        .file_type()
        .is_symlink());
    assert_complete(&out);
}

/// Starts a run into `out` (which holds a complete earlier run) and waits until it is
/// writing its files (a temporary other than the summary's exists).
#[cfg(unix)]
fn start_and_catch_writing(out: &Path) -> Child {
    let case_path = out.with_extension("toml");
    // A larger grid: its plots take tens of milliseconds each to draw.
    let case = small().replace("n = 16", "n = 64");
    fs::write(&case_path, case).unwrap();
    let mut child = Command::new(BIN)
        .args([
            "run",
            case_path.to_str().unwrap(),
            "-q",
            "-o",
            out.to_str().unwrap(),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    loop {
        let writing = fs::read_dir(out).unwrap().any(|e| {
            let n = e.unwrap().file_name().to_string_lossy().into_owned();
            n.starts_with(".tribo-tmp-") && !n.ends_with("summary.json")
        });
        if writing {
            return child;
        }
        if let Some(status) = child.try_wait().unwrap() {
            let mut err = String::new();
            child
                .stderr
                .take()
                .unwrap()
                .read_to_string(&mut err)
                .unwrap();
            panic!("the run ended before it was caught writing: {status} {err}");
        }
        if start.elapsed() > Duration::from_secs(600) {
            let _ = child.kill();
            panic!("the run was not caught writing within 600 s");
        }
        std::thread::sleep(Duration::from_micros(200));
    }
}

#[cfg(unix)]
#[test]
fn a_run_killed_while_writing_leaves_no_summary() {
    let base = tempfile::tempdir().unwrap();
    let out = base.path().join("out");
    let o = run_into(&out, &small());
    assert_eq!(o.status.code(), Some(0));
    assert!(out.join("summary.json").is_file());
    let mut child = start_and_catch_writing(&out);
    // The earlier summary went first, before any new file.
    assert!(!out.join("summary.json").exists());
    child.kill().unwrap(); // SIGKILL: no handler runs.
    child.wait().unwrap();
    assert!(
        !out.join("summary.json").exists(),
        "a summary beside a killed run's files"
    );
    // The next run cleans up the killed run's temporaries and completes.
    let o = run_into(&out, &small());
    assert_eq!(o.status.code(), Some(0));
    assert_complete(&out);
}

#[cfg(unix)]
#[test]
fn sigint_and_sigterm_while_writing_remove_the_temporary() {
    use std::os::unix::process::ExitStatusExt;
    for sig in [libc::SIGINT, libc::SIGTERM] {
        let base = tempfile::tempdir().unwrap();
        let out = base.path().join("out");
        let o = run_into(&out, &small());
        assert_eq!(o.status.code(), Some(0));
        let mut child = start_and_catch_writing(&out);
        // SAFETY: sending a signal to our own child process.
        assert_eq!(unsafe { libc::kill(child.id() as libc::pid_t, sig) }, 0);
        let status = child.wait().unwrap();
        assert_eq!(status.signal(), Some(sig), "ended by the signal it got");
        assert!(leftovers(&out).is_empty(), "{sig}: {:?}", leftovers(&out));
        assert!(!out.join("summary.json").exists());
    }
}

/// Runs `case` into `out` (which must succeed) and reads its summary.json.
fn run_summary(out: &Path, case: &str) -> serde_json::Value {
    let o = run_into(out, case);
    assert_eq!(o.status.code(), Some(0), "{}", common::stderr(&o));
    common::read_json(&out.join("summary.json"))
}

#[test]
fn summaries_share_one_layout_and_give_every_unit() {
    let base = tempfile::tempdir().unwrap();
    let out = base.path().join("out");
    // Friction, a stress field and the Hertz comparison: most sections present.
    let case = small().replace("[contact]\n", "[contact]\nfriction = 0.2\nsliding = true\n")
        + "\n[field]\nn = [9, 9, 5]\n";
    let s = run_summary(&out, &case);
    summary::assert_layout(&s);
    assert_eq!(s["kind"], "halfspace");
    assert_eq!(s["units"]["contact.max_pressure"], "Pa");
    assert_eq!(s["units"]["gap.angle"], "deg");
    for stage in ["solve_s", "tangential_s", "stress_s", "write_s"] {
        assert!(s["timings"][stage].as_f64().is_some(), "{stage}");
    }
    // A 30 degree crossing: the gap angle in degrees, as the case gave it.
    let crossed = small()
        .replace("radii = [\"10 mm\", \"10 mm\"]", "radii = [0.01, 0.02]")
        .replace(
            "radii = [\"inf\", \"inf\"]",
            "radii = [0.05, \"inf\"]\nangle_deg = 30",
        );
    let s = run_summary(&out, &crossed);
    let angle = s["gap"]["angle"].as_f64().unwrap();
    assert!(
        angle.abs() <= 90.0 && angle.abs() > 1.0,
        "gap.angle {angle} in degrees"
    );
    summary::assert_layout(&s);
}
