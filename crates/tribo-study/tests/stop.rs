//! `run::run_until`: a run stopped by its flag starts no point after it, writes the points in
//! flight whole, and resumes; `slurm::write_scripts` writes the scripts and settings of
//! `tribo sweep slurm`. (The Python package's `Study.run` and `Study.slurm` are these.)
#![allow(clippy::expect_used)]

use std::sync::atomic::{AtomicBool, Ordering};
use tribo_study::plan::StudyDir;
use tribo_study::run::{run_until, states, PointState};
use tribo_study::spec::Study;

const STUDY: &str = r#"
[study]
name = "balls"
collect = ["contact.max_pressure"]

[base]
[base.body1]
E = "210 GPa"
nu = 0.3
radii = ["10 mm", "10 mm"]
[base.body2]
E = "210 GPa"
nu = 0.3
radii = ["inf", "inf"]
[base.contact]
load = 100.0
[base.grid]
n = 16

[[grid]]
key = "contact.load"
values = [10.0, 20.0, 30.0, 40.0, 50.0, 60.0]
"#;

fn planned(dir: &std::path::Path) -> StudyDir {
    let study = Study::from_toml(STUDY, "balls.toml", dir).expect("study");
    StudyDir::plan(&study, STUDY, &dir.join("s")).expect("plan")
}

fn done(sd: &StudyDir) -> Vec<usize> {
    states(sd)
        .expect("states")
        .iter()
        .enumerate()
        .filter(|(_, s)| **s == PointState::Done)
        .map(|(i, _)| i)
        .collect()
}

/// Sets the flag when `after` points are done (as the Python progress does on Ctrl-C).
struct StopAfter<'a> {
    after: u64,
    stop: &'a AtomicBool,
}

impl tribo_case::Progress for StopAfter<'_> {
    fn advance(&mut self, done: u64) {
        if done >= self.after {
            self.stop.store(true, Ordering::Relaxed);
        }
    }
}

#[test]
fn a_stopped_run_starts_no_point_after_the_flag_and_resumes() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let sd = planned(tmp.path());

    // Set before the run: nothing is computed.
    let stop = AtomicBool::new(true);
    let r = run_until(&sd, None, 2, &mut tribo_case::Silent, &stop).expect("run");
    assert_eq!((r.done, r.skipped), (0, 0));
    assert!(done(&sd).is_empty());

    // Set after the first point, one worker: the point in flight then (at most one) is
    // finished and written, none starts after it.
    let stop = AtomicBool::new(false);
    let mut progress = StopAfter {
        after: 1,
        stop: &stop,
    };
    let r = run_until(&sd, None, 1, &mut progress, &stop).expect("run");
    let first = done(&sd);
    assert!(first == [0] || first == [0, 1], "{first:?}");
    assert_eq!(r.done, first.len());
    // No temporary is left behind: the points are whole directories or absent.
    let leftovers: Vec<_> = std::fs::read_dir(sd.points_dir())
        .expect("points")
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().starts_with(".tmp-"))
        .collect();
    assert!(leftovers.is_empty());

    // Resumed without a stop: the rest.
    let r = tribo_study::run::run(&sd, None, 2, &mut tribo_case::Silent).expect("run");
    assert_eq!((r.done, r.skipped), (6 - first.len(), first.len()));
    assert_eq!(done(&sd), (0..6).collect::<Vec<_>>());
}

#[test]
fn write_scripts_writes_the_scripts_and_settings() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let sd = planned(tmp.path());
    let s = tribo_study::slurm::Slurm {
        chunk: 4,
        partition: None,
        time: "00:05:00".into(),
        cpus_per_task: 2,
        max_running: None,
    };
    let tribo = std::path::Path::new("/opt/tribo/bin/tribo");
    let (array, gather) = tribo_study::slurm::write_scripts(&sd, &s, tribo).expect("write");
    let abs = std::path::absolute(&sd.dir).expect("absolute");
    let (a, g) = tribo_study::slurm::scripts(&s, "balls", 6, tribo, &abs);
    assert_eq!(std::fs::read_to_string(&array).expect("array"), a);
    assert_eq!(std::fs::read_to_string(&gather).expect("gather"), g);
    assert!(a.contains("#SBATCH --array=0-1\n"));
    let settings = std::fs::read_to_string(abs.join("slurm").join("settings.json")).expect("json");
    let v: serde_json::Value = serde_json::from_str(&settings).expect("settings.json");
    assert_eq!(
        (v["chunk"].as_u64(), v["tasks"].as_u64()),
        (Some(4), Some(2))
    );
    assert!(abs.join("slurm").join("logs").is_dir());
}
