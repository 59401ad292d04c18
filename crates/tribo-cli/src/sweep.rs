//! `tribo sweep`: studies over many cases (docs/user/studies.md). The engine is the crate
//! `tribo-study`; here are the command line, the progress bar with its ETA and `sbatch`.
//!
//! - `plan STUDY.toml [-o DIR]`: the study checked and expanded into DIR;
//! - `run DIR [--jobs N] [--points 0-9,12] [--task I --chunk K]`: the points not done yet;
//! - `slurm DIR [--submit] ...`: the SLURM array and gather scripts (and their submission);
//! - `status DIR`: done, failed (with the reasons), missing, and the tasks to resubmit;
//! - `gather DIR`: `results.csv`, `results.nc` and the plots in `plots/`;
//! - `example [NAME]`: the embedded study files.
//!
//! Exit codes as the rest of the command line: 2 for bad input (the study file, its base
//! case, the directory, an option), naming the item; 1 for anything else. A point that
//! fails is not an error of the command: it is recorded and reported.

use crate::exit::{CliResult, EXIT_BAD_INPUT, EXIT_OK, EXIT_OTHER};
use crate::term;
use clap::{Args, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::path::{Path, PathBuf};
use std::time::Duration;
use tribo_study::plan::StudyDir;
use tribo_study::run::PointState;
use tribo_study::slurm::{self, Slurm};
use tribo_study::spec::Study;
use tribo_study::{examples, StudyError};

/// `tribo sweep ...`.
#[derive(Debug, Subcommand)]
pub enum SweepCommand {
    /// Check a study file and expand it into a directory of points (points.csv).
    Plan {
        /// The study file (TOML; `tribo sweep example NAME` prints one).
        study: PathBuf,
        /// The study directory; default: the study file's stem beside it.
        #[arg(short = 'o', long = "out", value_name = "DIR")]
        out: Option<PathBuf>,
    },
    /// Run the points of a planned study that are not done yet (a killed run resumes).
    Run {
        /// The study directory.
        dir: PathBuf,
        #[command(flatten)]
        run: RunOpts,
    },
    /// Write the SLURM array and gather scripts into DIR/slurm (and submit them).
    Slurm {
        /// The study directory.
        dir: PathBuf,
        #[command(flatten)]
        opts: SlurmOpts,
    },
    /// Done, failed (with the reasons) and missing points; the array tasks to resubmit.
    Status {
        /// The study directory.
        dir: PathBuf,
        /// Points per array task for the resubmission list (default: the one of
        /// `tribo sweep slurm`, else 1).
        #[arg(long, value_name = "K")]
        chunk: Option<usize>,
    },
    /// Gather the points into DIR/results.csv and DIR/results.nc (NetCDF-3), with plots in
    /// DIR/plots.
    Gather {
        /// The study directory.
        dir: PathBuf,
    },
    /// List the example studies, or print one (`tribo sweep example NAME > study.toml`).
    Example {
        /// Study example name; omit to list them.
        name: Option<String>,
    },
}

/// The options of `tribo sweep run`.
#[derive(Debug, Args)]
pub struct RunOpts {
    /// Points computed at once, each on one thread (default: the CPUs available).
    #[arg(long, value_name = "N")]
    jobs: Option<usize>,
    /// Only these points: indices and ranges, `0-9,12`.
    #[arg(long, value_name = "LIST", conflicts_with = "task")]
    points: Option<String>,
    /// Run array task I: points I*K ... I*K+K-1 (with --chunk K).
    #[arg(long, value_name = "I", requires = "chunk")]
    task: Option<usize>,
    /// Points per array task (with --task).
    #[arg(long, value_name = "K", requires = "task")]
    chunk: Option<usize>,
    /// No progress on stderr.
    #[arg(short, long)]
    quiet: bool,
}

/// The options of `tribo sweep slurm`.
#[derive(Debug, Args)]
pub struct SlurmOpts {
    /// Submit the scripts with sbatch (the gather job after the array, afterany).
    #[arg(long)]
    submit: bool,
    /// The partition (--partition); default: the cluster's.
    #[arg(long, value_name = "P")]
    partition: Option<String>,
    /// Wall time of one array task, [D-]HH:MM:SS.
    #[arg(long, value_name = "HH:MM:SS", default_value = "01:00:00")]
    time: String,
    /// CPUs per array task: the points it computes at once.
    #[arg(long, value_name = "C", default_value_t = 1)]
    cpus_per_task: usize,
    /// At most K array tasks running at once (--array=...%K).
    #[arg(long, value_name = "K")]
    max_running: Option<usize>,
    /// Points per array task (default: 1, or enough to keep the array within 1001 tasks).
    #[arg(long, value_name = "K")]
    chunk: Option<usize>,
}

/// Runs `tribo sweep ...`.
pub fn run(cmd: SweepCommand) -> CliResult<u8> {
    let result = match cmd {
        SweepCommand::Plan { study, out } => plan(&study, out.as_deref()),
        SweepCommand::Run { dir, run } => run_points(&dir, &run),
        SweepCommand::Slurm { dir, opts } => slurm_cmd(&dir, &opts),
        SweepCommand::Status { dir, chunk } => status(&dir, chunk),
        SweepCommand::Gather { dir } => gather(&dir),
        SweepCommand::Example { name } => return example(name.as_deref()),
    };
    match result {
        Ok(r) => r,
        Err(e) => {
            term::note(&format!("error: {e}"));
            Ok(if e.is_bad_input() {
                EXIT_BAD_INPUT
            } else {
                EXIT_OTHER
            })
        }
    }
}

/// A bad option: exit 2 naming it.
fn bad_option(option: &str, value: impl std::fmt::Display, rule: &str) -> StudyError {
    StudyError::item(option, value, rule)
}

type Outcome = Result<CliResult<u8>, StudyError>;

fn plan(path: &Path, out: Option<&Path>) -> Outcome {
    let text = tribo_study::spec::read_bounded(path)
        .map_err(|e| bad_option("study", path.display(), &format!("cannot read it: {e}")))?;
    let dir_of = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let study = Study::from_toml(&text, &path.display().to_string(), &dir_of)?;
    let dir = match out {
        Some(d) => d.to_path_buf(),
        None => {
            let stem = path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_else(|| "study".into());
            dir_of.join(stem)
        }
    };
    let sd = StudyDir::plan(&study, &text, &dir)?;
    let n = sd.study.len();
    Ok(term::out(&format!(
        "{}: {n} points ({} parameters, {} collected) planned into {}\n  points: {}\n  next: tribo sweep run {}\n",
        sd.study.name,
        sd.study.parameters.len(),
        sd.study.collect.len(),
        dir.display(),
        dir.join("points.csv").display(),
        dir.display()
    ))
    .map(|()| EXIT_OK))
}

/// `0-9,12` -> [0, ..., 9, 12].
fn parse_points(list: &str, n: usize) -> Result<Vec<usize>, StudyError> {
    let bad = || {
        bad_option(
            "--points",
            list,
            &format!("indices and ranges of points in [0, {n}), e.g. 0-9,12"),
        )
    };
    let mut out = Vec::new();
    for part in list.split(',') {
        let (a, b) = match part.split_once('-') {
            Some((a, b)) => (a.trim(), b.trim()),
            None => (part.trim(), part.trim()),
        };
        let a: usize = a.parse().map_err(|_| bad())?;
        let b: usize = b.parse().map_err(|_| bad())?;
        if a > b || b >= n {
            return Err(bad());
        }
        out.extend(a..=b);
    }
    out.sort_unstable();
    out.dedup();
    Ok(out)
}

fn run_points(dir: &Path, o: &RunOpts) -> Outcome {
    let sd = StudyDir::open(dir)?;
    let n = sd.study.len();
    let selection = match (&o.points, o.task, o.chunk) {
        (Some(list), _, _) => Some(parse_points(list, n)?),
        (None, Some(task), Some(chunk)) => {
            if chunk == 0 {
                return Err(bad_option("--chunk", 0, "at least 1 point per task"));
            }
            let pts = tribo_study::run::chunk_points(n, task, chunk);
            if pts.is_empty() {
                return Err(bad_option(
                    "--task",
                    task,
                    &format!(
                        "the study has {} tasks of {chunk} points (0 ... {})",
                        tribo_study::run::chunks(n, chunk),
                        tribo_study::run::chunks(n, chunk).saturating_sub(1)
                    ),
                ));
            }
            Some(pts)
        }
        _ => None,
    };
    let jobs = match o.jobs {
        Some(0) => return Err(bad_option("--jobs", 0, "at least 1")),
        Some(j) => j,
        None => std::thread::available_parallelism().map_or(1, |p| p.get()),
    };
    let mut bar = EtaBar::new(o.quiet);
    let report = tribo_study::run::run(&sd, selection.as_deref(), jobs, &mut bar)?;
    drop(bar);
    let mut text = format!(
        "{}: {} points computed, {} failed, {} already done; {:.1} s wall, {:.1} s in points ({} jobs)\n",
        sd.study.name,
        report.done,
        report.failed.len(),
        report.skipped,
        report.seconds,
        report.point_seconds,
        jobs
    );
    for (i, reason) in report.failed.iter().take(10) {
        text.push_str(&format!("  point {i}: {reason}\n"));
    }
    if report.failed.len() > 10 {
        text.push_str(&format!(
            "  ... and {} more (tribo sweep status {})\n",
            report.failed.len() - 10,
            dir.display()
        ));
    }
    Ok(term::out(&text).map(|()| EXIT_OK))
}

/// The settings `tribo sweep slurm` wrote (the chunk), if any.
fn saved_chunk(dir: &Path) -> Option<usize> {
    let text = std::fs::read_to_string(dir.join("slurm").join("settings.json")).ok()?;
    let v: serde_json::Value = serde_json::from_str(&text).ok()?;
    v.get("chunk")?
        .as_u64()
        .and_then(|c| usize::try_from(c).ok())
}

fn slurm_cmd(dir: &Path, o: &SlurmOpts) -> Outcome {
    let sd = StudyDir::open(dir)?;
    let n = sd.study.len();
    let chunk = o.chunk.unwrap_or_else(|| slurm::default_chunk(n));
    let exe = std::env::current_exe().map_err(|e| StudyError::file("tribo", e))?;
    let s = Slurm {
        chunk,
        partition: o.partition.clone(),
        time: o.time.clone(),
        cpus_per_task: o.cpus_per_task,
        max_running: o.max_running,
    };
    // The library's rules, named by the command's options (`cpus_per_task` -> --cpus-per-task).
    s.validate().map_err(|e| match e {
        StudyError::Item { item, value, rule } => {
            StudyError::item(format!("--{}", item.replace('_', "-")), value, rule)
        }
        other => other,
    })?;
    let (a, g) = slurm::write_scripts(&sd, &s, &exe)?;
    let sdir = a.parent().map(Path::to_path_buf).unwrap_or_default();
    let tasks = tribo_study::run::chunks(n, chunk);
    let mut text = format!(
        "{}: {n} points in {tasks} array tasks of {chunk}; scripts in {}\n",
        sd.study.name,
        sdir.display()
    );
    if !o.submit {
        text.push_str(&format!(
            "  sbatch {}\n  sbatch --dependency=afterany:<array job id> {}\n",
            slurm::sh_quote(&a.display().to_string()),
            slurm::sh_quote(&g.display().to_string())
        ));
        return Ok(term::out(&text).map(|()| EXIT_OK));
    }
    let array_id = sbatch(&[a.display().to_string()])?;
    text.push_str(&format!("  array job {array_id}\n"));
    let gather_id = sbatch(&[
        format!("--dependency=afterany:{array_id}"),
        g.display().to_string(),
    ])?;
    text.push_str(&format!(
        "  gather job {gather_id} (after the array)\n  tribo sweep status {}\n",
        dir.display()
    ));
    Ok(term::out(&text).map(|()| EXIT_OK))
}

/// Runs `sbatch ARGS` and returns the job id it answers.
fn sbatch(args: &[String]) -> Result<u64, StudyError> {
    let out = std::process::Command::new("sbatch")
        .args(args)
        .output()
        .map_err(|e| StudyError::file("sbatch", e))?;
    let answer = String::from_utf8_lossy(&out.stdout);
    if !out.status.success() {
        return Err(StudyError::file(
            "sbatch",
            std::io::Error::other(format!(
                "{} ({}): {}",
                out.status,
                args.join(" "),
                String::from_utf8_lossy(&out.stderr).trim()
            )),
        ));
    }
    slurm::job_id(&answer).ok_or_else(|| {
        StudyError::file(
            "sbatch",
            std::io::Error::other(format!("no job id in its answer {:?}", answer.trim())),
        )
    })
}

fn status(dir: &Path, chunk: Option<usize>) -> Outcome {
    let sd = StudyDir::open(dir)?;
    let n = sd.study.len();
    let chunk = chunk.or_else(|| saved_chunk(dir)).unwrap_or(1);
    if chunk == 0 {
        return Err(bad_option("--chunk", 0, "at least 1 point per task"));
    }
    let st = tribo_study::run::states(&sd)?;
    let done = st.iter().filter(|s| **s == PointState::Done).count();
    let failed: Vec<(usize, &str)> = st
        .iter()
        .enumerate()
        .filter_map(|(i, s)| match s {
            PointState::Failed(r) => Some((i, r.as_str())),
            _ => None,
        })
        .collect();
    let missing: Vec<usize> = st
        .iter()
        .enumerate()
        .filter(|(_, s)| **s == PointState::Missing)
        .map(|(i, _)| i)
        .collect();
    let mut text = format!(
        "{}: {n} points: {done} done, {} failed, {} missing\n",
        sd.study.name,
        failed.len(),
        missing.len()
    );
    for (i, r) in &failed {
        text.push_str(&format!("  point {i}: {r}\n"));
    }
    if !missing.is_empty() {
        text.push_str(&format!("  missing: {}\n", slurm::ranges(&missing)));
    }
    let mut tasks: Vec<usize> = failed
        .iter()
        .map(|(i, _)| *i)
        .chain(missing.iter().copied())
        .map(|i| i / chunk)
        .collect();
    tasks.sort_unstable();
    tasks.dedup();
    if tasks.is_empty() {
        text.push_str("  nothing to resubmit\n");
    } else {
        text.push_str(&format!(
            "  resubmit (chunk {chunk}): sbatch --array={} {}\n",
            slurm::ranges(&tasks),
            dir.join("slurm").join("array.sbatch").display()
        ));
    }
    Ok(term::out(&text).map(|()| EXIT_OK))
}

fn gather(dir: &Path) -> Outcome {
    let sd = StudyDir::open(dir)?;
    let t = tribo_study::table::write(&sd)?;
    let plots = tribo_study::plots::write(&sd, &t)?;
    let (done, failed, missing) = t.counts();
    Ok(term::out(&format!(
        "{}: {} points ({done} ok, {failed} failed, {missing} missing) -> {}, {}; {} plots in {}\n",
        sd.study.name,
        t.status.len(),
        dir.join("results.csv").display(),
        dir.join("results.nc").display(),
        plots.len(),
        dir.join("plots").display()
    ))
    .map(|()| EXIT_OK))
}

fn example(name: Option<&str>) -> CliResult<u8> {
    match name {
        None => {
            let width = examples::STUDIES
                .iter()
                .map(|e| e.name.len())
                .max()
                .unwrap_or(0);
            let mut text = String::from(
                "Example studies (print one with `tribo sweep example NAME > study.toml`, then \
                 `tribo sweep plan study.toml`):\n",
            );
            for e in examples::STUDIES {
                text.push_str(&format!("  {:<width$}  {}\n", e.name, e.description));
            }
            term::out(&text)?;
            Ok(EXIT_OK)
        }
        Some(n) => match examples::find(n) {
            Some(e) => {
                term::out(e.text)?;
                Ok(EXIT_OK)
            }
            None => {
                term::note(&format!(
                    "error: no example study named {n:?}; `tribo sweep example` lists them: {}",
                    examples::names()
                ));
                Ok(EXIT_BAD_INPUT)
            }
        },
    }
}

/// Progress of a sweep on stderr: a bar over the points with the elapsed time and the ETA
/// (hidden with `--quiet` or when stderr is not a terminal); failed points as `note:` lines.
struct EtaBar {
    quiet: bool,
    bar: Option<ProgressBar>,
}

impl EtaBar {
    fn new(quiet: bool) -> Self {
        EtaBar { quiet, bar: None }
    }
}

impl tribo_case::Progress for EtaBar {
    fn stage(&mut self, name: &str, total: Option<u64>) {
        self.finish();
        if self.quiet {
            return;
        }
        let pb = ProgressBar::with_draw_target(total, ProgressDrawTarget::stderr());
        if let Ok(style) = ProgressStyle::with_template(
            "{spinner} {msg} [{bar:30}] {pos}/{len} [{elapsed} elapsed, ETA {eta}]",
        ) {
            pb.set_style(style.progress_chars("=> "));
        }
        pb.set_message(name.to_string());
        pb.enable_steady_tick(Duration::from_millis(200));
        self.bar = Some(pb);
    }

    fn advance(&mut self, done: u64) {
        if let Some(pb) = &self.bar {
            pb.set_position(done);
        }
    }

    fn finish(&mut self) {
        if let Some(pb) = self.bar.take() {
            pb.finish_and_clear();
        }
    }

    fn note(&mut self, text: &str) {
        if self.quiet {
            return;
        }
        let line = format!("note: {text}");
        match &self.bar {
            Some(pb) => pb.suspend(|| term::note(&line)),
            None => term::note(&line),
        }
    }
}

impl Drop for EtaBar {
    fn drop(&mut self) {
        tribo_case::Progress::finish(self);
    }
}
