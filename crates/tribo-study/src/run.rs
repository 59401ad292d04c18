//! Running the points of a planned study.
//!
//! Each point runs the case library's one-call pipeline ([`tribo_case::run`]) on its case
//! (the base case with the point's parameters set), writes into a temporary directory
//! `points/.tmp-NNNNNN-<host>-<pid>-<n>` and renames it to `points/NNNNNN`: a point's
//! directory exists whole or not at all, so a study killed at any moment resumes by running
//! the points without one (the temporaries of the points it is about to run are removed
//! first). A point whose case is invalid, or whose solver fails, leaves
//! `points/NNNNNN.failed` with the reason instead (written atomically too), and the others
//! go on; a later run tries it again.
//!
//! Threads: `jobs` workers each run whole points, one at a time, each inside its own
//! one-thread rayon pool, so a point is computed by one thread whatever `jobs` is: its
//! numbers, and the results table, are the same bits for any `jobs`, chunking or machine.
//! Many points on few cores is the case this serves; a single big case is faster with
//! `tribo run`, which uses every core.

use crate::error::{StudyError, StudyResult};
use crate::plan::{case_table, point_name, StudyDir};
use crate::spec::{Outputs, Study};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Instant;
use tribo_case::{Case, Progress, Results, Silent};

/// The state of a point in a study directory.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum PointState {
    /// Computed: `points/NNNNNN/summary.json` exists.
    Done,
    /// Failed, with the reason (`points/NNNNNN.failed`).
    Failed(String),
    /// Neither.
    Missing,
}

/// What a run did.
#[derive(Debug, Clone, Default)]
pub struct RunReport {
    /// Points computed now.
    pub done: usize,
    /// Points that failed now, with the reasons.
    pub failed: Vec<(usize, String)>,
    /// Points skipped because they were already done.
    pub skipped: usize,
    /// Wall time, s.
    pub seconds: f64,
    /// The sum of the points' own wall times, s (compute + write).
    pub point_seconds: f64,
}

/// The state of every point, in point order.
pub fn states(sd: &StudyDir) -> StudyResult<Vec<PointState>> {
    let n = sd.study.len();
    let mut out = vec![PointState::Missing; n];
    let dir = sd.points_dir();
    let entries = match std::fs::read_dir(&dir) {
        Ok(e) => e,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(out),
        Err(e) => return Err(StudyError::file(&dir, e)),
    };
    let mut failed = Vec::new();
    for entry in entries {
        let entry = entry.map_err(|e| StudyError::file(&dir, e))?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let (stem, is_failed) = match name.strip_suffix(".failed") {
            Some(s) => (s.to_string(), true),
            None => (name.clone(), false),
        };
        let Some(i) = parse_index(&stem).filter(|&i| i < n) else {
            continue;
        };
        if is_failed {
            failed.push(i);
        } else if entry.path().join("summary.json").is_file() {
            out[i] = PointState::Done;
        }
    }
    for i in failed {
        if out[i] != PointState::Done {
            let path = dir.join(format!("{}.failed", point_name(i)));
            let reason = std::fs::read_to_string(&path).map_err(|e| StudyError::file(&path, e))?;
            out[i] = PointState::Failed(reason.trim_end().to_string());
        }
    }
    Ok(out)
}

/// A point directory's index from its name (six or more digits).
fn parse_index(name: &str) -> Option<usize> {
    (name.len() >= 6 && name.bytes().all(|b| b.is_ascii_digit()))
        .then(|| name.parse().ok())
        .flatten()
}

/// A name for temporaries unique to this process (host and pid) and call.
fn temp_tag() -> String {
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let host = std::fs::read_to_string("/proc/sys/kernel/hostname")
        .map(|h| h.trim().replace(['/', '.'], "_"))
        .unwrap_or_else(|_| "host".into());
    format!(
        "{host}-{}-{}",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    )
}

/// Removes the temporaries left by killed runs of the points in `todo`.
fn remove_stale(points: &Path, todo: &[usize]) -> StudyResult<()> {
    let wanted: std::collections::BTreeSet<usize> = todo.iter().copied().collect();
    let entries = std::fs::read_dir(points).map_err(|e| StudyError::file(points, e))?;
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some(rest) = name.strip_prefix(".tmp-") else {
            continue;
        };
        let idx: String = rest.chars().take_while(char::is_ascii_digit).collect();
        if parse_index(&idx).is_some_and(|i| wanted.contains(&i)) {
            let p = entry.path();
            let removed = if p.is_dir() {
                std::fs::remove_dir_all(&p)
            } else {
                std::fs::remove_file(&p)
            };
            removed.map_err(|e| StudyError::file(&p, e))?;
        }
    }
    Ok(())
}

/// Writes `text` to `dir/name` through a temporary and a rename.
fn write_atomic(dir: &Path, name: &str, text: &str) -> StudyResult<()> {
    let tmp = dir.join(format!(".tmp-{name}-{}", temp_tag()));
    std::fs::write(&tmp, text).map_err(|e| StudyError::file(&tmp, e))?;
    let target = dir.join(name);
    std::fs::rename(&tmp, &target).map_err(|e| StudyError::file(&target, e))
}

/// The outcome of one point: `Ok(Err(reason))` is the point's failure, `Err` the study's
/// (a file of the study directory that cannot be written).
type PointOutcome = StudyResult<Result<(), String>>;

/// Runs point `i` and writes its directory.
pub fn run_point(sd: &StudyDir, i: usize) -> PointOutcome {
    let study = &sd.study;
    let points = sd.points_dir();
    let name = point_name(i);
    let table = match case_table(study, i) {
        Ok(t) => t,
        Err(e) => return Ok(Err(e)),
    };
    let text = match toml::to_string(&table) {
        Ok(t) => t,
        Err(e) => return Ok(Err(format!("case: {e}"))),
    };
    let source = format!("{} point {name}", study.name);
    let case = match Case::from_toml(&text, &source, &study.base.dir) {
        Ok(c) => c,
        Err(e) => return Ok(Err(e.to_string())),
    };
    let results = match tribo_case::run(&case, &mut Silent) {
        Ok(r) => r,
        Err(e) => return Ok(Err(e.to_string())),
    };
    let tmp = points.join(format!(".tmp-{name}-{}", temp_tag()));
    std::fs::create_dir_all(&tmp).map_err(|e| StudyError::file(&tmp, e))?;
    let written = write_point(&tmp, study, &case, &results, &text);
    if let Err(e) = written {
        let _ = std::fs::remove_dir_all(&tmp);
        // A library error while deriving the outputs is the point's; a file error the study's.
        return match e {
            StudyError::Write(tribo_io::IoError::Case(c)) => Ok(Err(c.to_string())),
            other => Err(other),
        };
    }
    let target = points.join(&name);
    if let Err(e) = std::fs::rename(&tmp, &target) {
        let _ = std::fs::remove_dir_all(&tmp);
        // Another process finished the same point first: its directory stands.
        if !target.join("summary.json").is_file() {
            return Err(StudyError::file(&target, e));
        }
    }
    let failed = points.join(format!("{name}.failed"));
    if failed.exists() {
        std::fs::remove_file(&failed).map_err(|e| StudyError::file(&failed, e))?;
    }
    Ok(Ok(()))
}

/// Writes a point's files into `dir`: `case.toml`, and `summary.json` only or every file.
fn write_point(
    dir: &Path,
    study: &Study,
    case: &Case,
    results: &Results,
    text: &str,
) -> StudyResult<()> {
    let path = dir.join("case.toml");
    std::fs::write(&path, text).map_err(|e| StudyError::file(&path, e))?;
    let opts = tribo_io::WriteOptions {
        plots: true,
        remove_temporary_on_signal: false,
    };
    let summary = "summary.json";
    let json = match (case, results, study.outputs) {
        (Case::HalfSpace(c), Results::HalfSpace(r), Outputs::All) => {
            tribo_io::write_halfspace(dir, c, r, &opts)?;
            return Ok(());
        }
        (Case::Bem2d(c), Results::Bem2d(r), Outputs::All) => {
            tribo_io::write_bem(dir, c, r, &opts)?;
            return Ok(());
        }
        (Case::HalfSpace(c), Results::HalfSpace(r), Outputs::Summary) => {
            let mut s = tribo_io::halfspace::summary(c, r, false)?;
            s.outputs = vec![summary.into()];
            tribo_io::json::to_pretty(&s, summary)?
        }
        (Case::Bem2d(c), Results::Bem2d(r), Outputs::Summary) => {
            let s = tribo_case::bem::summary::BemSummary::new(c, r, vec![summary.into()])
                .map_err(tribo_io::IoError::Case)?;
            tribo_io::json::to_pretty(&s, summary)?
        }
        _ => {
            return Err(StudyError::Dir {
                dir: dir.to_path_buf(),
                detail: "the results are not of the case's kind".into(),
            })
        }
    };
    let path = dir.join(summary);
    std::fs::write(&path, json).map_err(|e| StudyError::file(&path, e))
}

/// Runs the points `selection` (all when `None`) of a planned study that are not done yet,
/// on `jobs` worker threads, reporting to `progress` (a stage counting the points; a note
/// per failed point). A failed point does not stop the others; a file of the study directory
/// that cannot be written does.
pub fn run(
    sd: &StudyDir,
    selection: Option<&[usize]>,
    jobs: usize,
    progress: &mut dyn Progress,
) -> StudyResult<RunReport> {
    run_until(sd, selection, jobs, progress, &AtomicBool::new(false))
}

/// [`run`], stopping early once `stop` is set (by `progress`, or by another thread): no
/// point starts after it, the points in flight finish and are written, and the report counts
/// what was done; the rest stay missing, so a later run resumes there. The Python package's
/// `Study.run` sets it on Ctrl-C or when its progress callback raises.
pub fn run_until(
    sd: &StudyDir,
    selection: Option<&[usize]>,
    jobs: usize,
    progress: &mut dyn Progress,
    stop: &AtomicBool,
) -> StudyResult<RunReport> {
    let start = Instant::now();
    let n = sd.study.len();
    let all: Vec<usize> = match selection {
        Some(s) => s.iter().copied().filter(|&i| i < n).collect(),
        None => (0..n).collect(),
    };
    let points = sd.points_dir();
    std::fs::create_dir_all(&points).map_err(|e| StudyError::file(&points, e))?;
    let st = states(sd)?;
    let todo: Vec<usize> = all
        .iter()
        .copied()
        .filter(|&i| st[i] != PointState::Done)
        .collect();
    let mut report = RunReport {
        skipped: all.len() - todo.len(),
        ..RunReport::default()
    };
    remove_stale(&points, &todo)?;
    progress.stage(&format!("{} points", todo.len()), Some(todo.len() as u64));
    let next = AtomicUsize::new(0);
    let (tx, rx) = std::sync::mpsc::channel::<(usize, PointOutcome, f64)>();
    let jobs = jobs.clamp(1, todo.len().max(1));
    let mut first_error: Option<StudyError> = None;
    std::thread::scope(|scope| {
        for _ in 0..jobs {
            let tx = tx.clone();
            let (next, todo) = (&next, &todo);
            scope.spawn(move || {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build();
                loop {
                    if stop.load(Ordering::Relaxed) {
                        break;
                    }
                    let k = next.fetch_add(1, Ordering::Relaxed);
                    let Some(&i) = todo.get(k) else { break };
                    let t0 = Instant::now();
                    let outcome = match &pool {
                        Ok(pool) => pool.install(|| guarded(sd, i)),
                        Err(e) => Ok(Err(format!("no thread pool: {e}"))),
                    };
                    let stop = outcome.is_err();
                    if tx.send((i, outcome, t0.elapsed().as_secs_f64())).is_err() || stop {
                        // The study stops: the others finish their points and stop too.
                        next.store(usize::MAX / 2, Ordering::Relaxed);
                        break;
                    }
                }
            });
        }
        drop(tx);
        let mut count = 0u64;
        for (i, outcome, secs) in rx {
            count += 1;
            report.point_seconds += secs;
            match outcome {
                Ok(Ok(())) => report.done += 1,
                Ok(Err(reason)) => {
                    let reason = format!("failed: {}", reason.replace(['\n', '\r'], " "));
                    match write_atomic(&points, &format!("{}.failed", point_name(i)), &reason) {
                        Ok(()) => {
                            progress.note(&format!("point {}: {reason}", point_name(i)));
                            report.failed.push((i, reason));
                        }
                        Err(e) => {
                            next.store(usize::MAX / 2, Ordering::Relaxed);
                            first_error.get_or_insert(e);
                        }
                    }
                }
                Err(e) => {
                    first_error.get_or_insert(e);
                }
            }
            progress.advance(count);
        }
    });
    progress.finish();
    report.seconds = start.elapsed().as_secs_f64();
    match first_error {
        Some(e) => Err(e),
        None => Ok(report),
    }
}

/// [`run_point`], a panic of the computation recorded as the point's failure.
fn guarded(sd: &StudyDir, i: usize) -> PointOutcome {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| run_point(sd, i))).unwrap_or_else(
        |p| {
            let msg = p
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| p.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown".into());
            Ok(Err(format!("internal error (panic): {msg}")))
        },
    )
}

/// The points of array task `task` with `chunk` points per task: `task * chunk` up to
/// `task * chunk + chunk - 1`, cut at the study's end.
pub fn chunk_points(n: usize, task: usize, chunk: usize) -> Vec<usize> {
    let start = task.saturating_mul(chunk);
    (start..start.saturating_add(chunk).min(n)).collect()
}

/// The number of array tasks of `chunk` points each.
pub fn chunks(n: usize, chunk: usize) -> usize {
    n.div_ceil(chunk.max(1))
}

/// Where point `i`'s directory is.
pub fn point_dir(sd: &StudyDir, i: usize) -> PathBuf {
    sd.points_dir().join(point_name(i))
}
