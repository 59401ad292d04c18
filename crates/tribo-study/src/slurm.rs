//! SLURM array scripts for a planned study: `slurm/array.sbatch` runs chunk
//! `$SLURM_ARRAY_TASK_ID` of the points (`tribo sweep run DIR --task I --chunk K`, as many
//! jobs as the task has CPUs), `slurm/gather.sbatch` gathers the table once the array has
//! ended (submitted with `--dependency=afterany:<array job>`, so failed or timed-out tasks
//! do not block it: `tribo sweep status` then names the tasks to resubmit).

use std::path::Path;

/// The settings of the scripts.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Slurm {
    /// Points per array task.
    pub chunk: usize,
    /// `--partition`, if any.
    pub partition: Option<String>,
    /// `--time` of an array task, `HH:MM:SS` (or `D-HH:MM:SS`).
    pub time: String,
    /// `--cpus-per-task`: the jobs of `tribo sweep run` in each task.
    pub cpus_per_task: usize,
    /// The `%K` limit of running array tasks, if any.
    pub max_running: Option<usize>,
}

/// The default points per task for `n` points: one, or as many as keep the array within
/// SLURM's default `MaxArraySize` (1001, i.e. task ids 0 to 1000).
pub fn default_chunk(n: usize) -> usize {
    n.div_ceil(1000).max(1)
}

/// A word quoted for the shell (single quotes).
pub fn sh_quote(s: &str) -> String {
    if !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || "/._-+=:,@%".contains(c))
    {
        s.to_string()
    } else {
        format!("'{}'", s.replace('\'', "'\\''"))
    }
}

/// Checks a `--time` value in SLURM's forms (sbatch(1), `--time`): minutes, `MM:SS`,
/// `HH:MM:SS`, `D-HH`, `D-HH:MM`, `D-HH:MM:SS`. The leading field of the forms without days
/// may be any number (90 minutes, 36 hours); a field after it is a minute or a second
/// (0 ... 59), and hours after days are 0 ... 23; at least one second in all.
pub fn valid_time(t: &str) -> bool {
    let digits = |p: &str| !p.is_empty() && p.len() <= 9 && p.bytes().all(|b| b.is_ascii_digit());
    let value = |p: &str| p.parse::<u64>().unwrap_or(u64::MAX);
    let (days, body) = match t.split_once('-') {
        Some((d, rest)) if digits(d) => (Some(value(d)), rest),
        Some(_) => return false,
        None => (None, t),
    };
    let parts: Vec<&str> = body.split(':').collect();
    if parts.len() > 3 || !parts.iter().all(|p| digits(p)) {
        return false;
    }
    let fields: Vec<u64> = parts.iter().map(|p| value(p)).collect();
    let trailing_ok = fields.iter().skip(1).all(|&v| v <= 59);
    let leading_ok = days.is_none() || fields[0] <= 23;
    let total = days.unwrap_or(0) + fields.iter().sum::<u64>();
    trailing_ok && leading_ok && total > 0
}

/// Checks a `--partition` value: one or more partition names separated by commas, each of
/// ASCII letters, digits, `_`, `-` and `.` (what SLURM's partition names are made of), at
/// most 256 characters in all. Anything else (a space, a quote, a newline: a newline would
/// end the `#SBATCH` line and make the rest shell code of the job) is refused.
pub fn valid_partition(p: &str) -> bool {
    p.len() <= 256
        && p.split(',').all(|name| {
            !name.is_empty()
                && name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || "_-.".contains(c))
        })
}

impl Slurm {
    /// Checks every setting, naming the option (`chunk`, `cpus_per_task`, `max_running`,
    /// `time`, `partition`) and its rule.
    pub fn validate(&self) -> crate::StudyResult<()> {
        use crate::StudyError;
        if self.chunk == 0 {
            return Err(StudyError::item("chunk", 0, "at least 1 point per task"));
        }
        if self.cpus_per_task == 0 {
            return Err(StudyError::item("cpus_per_task", 0, "at least 1"));
        }
        if self.max_running == Some(0) {
            return Err(StudyError::item("max_running", 0, "at least 1"));
        }
        if !valid_time(&self.time) {
            return Err(StudyError::item(
                "time",
                format!("{:?}", self.time),
                TIME_RULE,
            ));
        }
        if let Some(p) = &self.partition {
            if !valid_partition(p) {
                return Err(StudyError::item(
                    "partition",
                    format!("{p:?}"),
                    PARTITION_RULE,
                ));
            }
        }
        Ok(())
    }
}

/// The rule of [`valid_time`], as the errors state it.
pub const TIME_RULE: &str =
    "SLURM's minutes, MM:SS, HH:MM:SS, D-HH, D-HH:MM or D-HH:MM:SS (minutes and seconds 0-59 \
     after the first field, hours 0-23 after days, not zero)";

/// The rule of [`valid_partition`], as the errors state it.
pub const PARTITION_RULE: &str =
    "partition names of letters, digits, '_', '-' and '.', separated by commas (at most 256 \
     characters)";

/// A path written into a script: refused if it holds a control character (a newline would
/// end the `#SBATCH --output` line and make the rest shell code).
fn check_script_path(what: &str, path: &Path) -> crate::StudyResult<()> {
    let text = path.display().to_string();
    if text.chars().any(char::is_control) {
        return Err(crate::StudyError::item(
            what,
            format!("{text:?}"),
            "a path written into the SLURM scripts must not hold control characters",
        ));
    }
    Ok(())
}

/// The two scripts' texts: (`array.sbatch`, `gather.sbatch`). `tribo` is the binary's path
/// and `dir` the study directory, both absolute (the tasks run in another working folder).
pub fn scripts(s: &Slurm, name: &str, n: usize, tribo: &Path, dir: &Path) -> (String, String) {
    let tasks = crate::run::chunks(n, s.chunk);
    let exe = sh_quote(&tribo.display().to_string());
    let d = sh_quote(&dir.display().to_string());
    let logs = dir.join("slurm").join("logs");
    let job = format!("tribo-{}", name.replace(|c: char| c.is_whitespace(), "_"));
    let mut a = String::from("#!/bin/bash\n");
    a.push_str(&format!("#SBATCH --job-name={}\n", sh_quote(&job)));
    a.push_str(&format!(
        "#SBATCH --array=0-{}{}\n",
        tasks.saturating_sub(1),
        s.max_running.map(|k| format!("%{k}")).unwrap_or_default()
    ));
    a.push_str(&format!("#SBATCH --cpus-per-task={}\n", s.cpus_per_task));
    a.push_str(&format!("#SBATCH --time={}\n", s.time));
    if let Some(p) = &s.partition {
        a.push_str(&format!("#SBATCH --partition={}\n", sh_quote(p)));
    }
    a.push_str(&format!(
        "#SBATCH --output={}\n",
        sh_quote(&logs.join("array-%A_%a.out").display().to_string())
    ));
    a.push_str(&format!(
        "# {n} points in {tasks} tasks of {} (tribo sweep slurm)\n",
        s.chunk
    ));
    a.push_str("set -eu\n");
    a.push_str("# Threads from the allocation: one worker per CPU, each point on one thread.\n");
    a.push_str("export OMP_NUM_THREADS=\"${SLURM_CPUS_PER_TASK:-1}\"\n");
    a.push_str("export RAYON_NUM_THREADS=\"${SLURM_CPUS_PER_TASK:-1}\"\n");
    a.push_str(&format!(
        "exec {exe} sweep run {d} --task \"$SLURM_ARRAY_TASK_ID\" --chunk {} --jobs \"${{SLURM_CPUS_PER_TASK:-1}}\" --quiet\n",
        s.chunk
    ));
    let mut g = String::from("#!/bin/bash\n");
    g.push_str(&format!(
        "#SBATCH --job-name={}\n",
        sh_quote(&format!("{job}-gather"))
    ));
    g.push_str("#SBATCH --cpus-per-task=1\n");
    g.push_str("#SBATCH --time=00:30:00\n");
    if let Some(p) = &s.partition {
        g.push_str(&format!("#SBATCH --partition={}\n", sh_quote(p)));
    }
    g.push_str(&format!(
        "#SBATCH --output={}\n",
        sh_quote(&logs.join("gather-%j.out").display().to_string())
    ));
    g.push_str(
        "# Submitted with --dependency=afterany:<array job id> (tribo sweep slurm --submit).\n",
    );
    g.push_str("set -eu\n");
    g.push_str(&format!("{exe} sweep gather {d}\n"));
    g.push_str(&format!("exec {exe} sweep status {d}\n"));
    (a, g)
}

/// Writes the scripts of [`scripts`] for the planned study `sd` into `DIR/slurm`, with
/// `settings.json` (the chunk and the number of tasks, which `tribo sweep status` reads) and
/// the folder `slurm/logs`; each file atomically. `tribo` is the binary the tasks run
/// (absolute). Returns the paths of `array.sbatch` and `gather.sbatch`. (The files of
/// `tribo sweep slurm`: the Python package's `Study.slurm` writes them through this.)
pub fn write_scripts(
    sd: &crate::plan::StudyDir,
    s: &Slurm,
    tribo: &Path,
) -> crate::StudyResult<(std::path::PathBuf, std::path::PathBuf)> {
    use crate::StudyError;
    s.validate()?;
    let n = sd.study.len();
    let abs = std::path::absolute(&sd.dir).map_err(|e| StudyError::file(&sd.dir, e))?;
    check_script_path("study directory", &abs)?;
    check_script_path("tribo", tribo)?;
    let (array, gather) = scripts(s, &sd.study.name, n, tribo, &abs);
    let sdir = abs.join("slurm");
    std::fs::create_dir_all(sdir.join("logs")).map_err(|e| StudyError::file(&sdir, e))?;
    let settings = format!(
        "{{\n \"chunk\": {},\n \"tasks\": {}\n}}\n",
        s.chunk,
        crate::run::chunks(n, s.chunk)
    );
    for (name, text) in [
        ("array.sbatch", array.as_str()),
        ("gather.sbatch", gather.as_str()),
        ("settings.json", settings.as_str()),
    ] {
        tribo_io::atomic::write_atomic(&sdir, name, text.as_bytes())?;
    }
    Ok((sdir.join("array.sbatch"), sdir.join("gather.sbatch")))
}

/// The job id in sbatch's answer: `Submitted batch job 42` (or `--parsable`'s `42;cluster`).
pub fn job_id(answer: &str) -> Option<u64> {
    let line = answer.lines().find(|l| !l.trim().is_empty())?.trim();
    let word = line.rsplit(' ').next()?.split(';').next()?;
    word.parse().ok()
}

/// The task ids of a list, compressed into SLURM's `--array=` form: `0-3,7,9-10`.
pub fn ranges(ids: &[usize]) -> String {
    let mut out: Vec<String> = Vec::new();
    let mut k = 0;
    while k < ids.len() {
        let start = ids[k];
        let mut end = start;
        while k + 1 < ids.len() && ids[k + 1] == end + 1 {
            k += 1;
            end += 1;
        }
        out.push(if start == end {
            start.to_string()
        } else {
            format!("{start}-{end}")
        });
        k += 1;
    }
    out.join(",")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_ranges_times_quotes() {
        assert_eq!(job_id("Submitted batch job 42\n"), Some(42));
        assert_eq!(job_id("42;cluster\n"), Some(42));
        assert_eq!(job_id("error"), None);
        assert_eq!(ranges(&[0, 1, 2, 3, 7, 9, 10]), "0-3,7,9-10");
        assert_eq!(ranges(&[]), "");
        for ok in [
            "01:00:00",
            "2-00:00:00",
            "30",
            "10:00",
            "90",
            "36:00:00",
            "1-12",
            "1-12:30",
            "0:30",
            "00:59:59",
        ] {
            assert!(valid_time(ok), "{ok}");
        }
        for bad in [
            "",
            "1h",
            "a-01:00:00",
            "1:2:3:4",
            "01::00",
            "99:99:99",
            "1:60",
            "1-24:00:00",
            "0",
            "00:00:00",
            "0-0",
            "1\n2",
            "-1:00",
            "1e3",
        ] {
            assert!(!valid_time(bad), "{bad}");
        }
        for ok in ["compute", "gpu,cpu", "long-run.v2", "a_b"] {
            assert!(valid_partition(ok), "{ok}");
        }
        for bad in ["", "a\nrm -rf /tmp/x", "a b", "a'b", "a,,b", "a;b", "a$(x)"] {
            assert!(!valid_partition(bad), "{bad:?}");
        }
        let good = Slurm {
            chunk: 1,
            partition: Some("compute".into()),
            time: "01:00:00".into(),
            cpus_per_task: 1,
            max_running: None,
        };
        assert!(good.validate().is_ok());
        let injected = Slurm {
            partition: Some("a\nrm -rf /tmp/x".into()),
            ..good.clone()
        };
        let e = injected.validate().unwrap_err().to_string();
        assert!(e.starts_with("partition = "), "{e}");
        let late = Slurm {
            time: "99:99:99".into(),
            ..good
        };
        assert!(late
            .validate()
            .unwrap_err()
            .to_string()
            .starts_with("time = "));
        assert!(check_script_path("tribo", Path::new("/a\nb")).is_err());
        assert!(check_script_path("tribo", Path::new("/usr/bin/tribo")).is_ok());
        assert_eq!(sh_quote("/a/b"), "/a/b");
        assert_eq!(sh_quote("a b'c"), "'a b'\\''c'");
        assert_eq!(default_chunk(1000), 1);
        assert_eq!(default_chunk(1001), 2);
    }
}
