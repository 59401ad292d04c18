//! The points of a study and the study directory.
//!
//! Point `i` (0-based) takes, along each axis of the product (grid entries first and
//! slowest, then zip groups, then the random samples fastest), the coordinate of `i` written
//! in the mixed radix of the axes' lengths. A random parameter's value at point `i` is the
//! quantile of `tribo::stats::uniform01(study seed, r, i)`, `r` its position among the
//! `[[random]]` entries: a pure function of the study seed, the point's index and the
//! parameter, so the table never depends on which process, thread or chunk computes a point.
//! The point's own seed (a column of `points.csv`, for cases that sample) is
//! [`point_seed`]`(study seed, i)`.
//!
//! A planned study is a directory:
//! - `study.toml`: the study file as given; `base.toml`: its base case as given;
//! - `plan.json`: the format version, the study's name, the number of points, the folder
//!   the base case's relative paths resolve against;
//! - `points.csv`: `index,seed,<parameter keys>`, one row per point;
//! - `points/NNNNNN/`: a computed point (`case.toml`, `summary.json`, and with
//!   `outputs = "all"` every file of the run), `points/NNNNNN.failed`: a failed one (why);
//! - `results.csv`, `results.nc` (after `gather`), `slurm/` (after `slurm`).

use crate::error::{StudyError, StudyResult};
use crate::spec::{Base, Study, Variation};
use std::path::{Path, PathBuf};

/// The format of `plan.json` (bumped when the directory layout changes).
pub const FORMAT: u64 = 1;

/// The coordinate of point `i` along every axis.
fn coordinates(study: &Study, i: usize) -> Vec<usize> {
    let mut rest = i;
    let mut c = vec![0; study.axes.len()];
    for (a, (n, _)) in study.axes.iter().enumerate().rev() {
        c[a] = rest % n;
        rest /= n;
    }
    c
}

/// The value of parameter `j` at point `i`.
pub fn value(study: &Study, j: usize, i: usize) -> toml::Value {
    let coords = coordinates(study, i);
    let axis = study
        .axes
        .iter()
        .position(|(_, members)| members.contains(&j))
        .unwrap_or(0);
    match &study.parameters[j].variation {
        Variation::Values(v) => v[coords[axis].min(v.len() - 1)].clone(),
        Variation::Random(t) => {
            let r = study.parameters[..j]
                .iter()
                .filter(|p| matches!(p.variation, Variation::Random(_)))
                .count();
            let u = tribo::stats::uniform01(study.seed, r as u64, i as u64);
            toml::Value::Float(t.quantile(u))
        }
    }
}

/// The SplitMix64 finaliser (Steele et al. 2014): a bijection of u64 that mixes every
/// input bit into every output bit.
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The seed of point `i`: the SplitMix64 finaliser of the study seed and the index, cut to
/// 53 bits (exact as a double).
pub fn point_seed(seed: u64, i: usize) -> u64 {
    mix(mix(seed).wrapping_add(0x9e37_79b9_7f4a_7c15_u64.wrapping_mul(i as u64 + 1)))
        & (crate::spec::SEED_LIMIT - 1)
}

/// The case table of point `i`: the base case with every parameter set.
pub fn case_table(study: &Study, i: usize) -> Result<toml::Table, String> {
    let mut t = study.base_table.clone();
    for (j, p) in study.parameters.iter().enumerate() {
        crate::path::set(&mut t, &p.key, value(study, j, i))
            .map_err(|e| format!("{}: {e}", p.key))?;
    }
    Ok(t)
}

/// A parameter value as a CSV cell: numbers in Rust's shortest round-trip form, strings
/// quoted where they need it, arrays in TOML's inline form.
pub fn cell(v: &toml::Value) -> String {
    match v {
        toml::Value::Float(x) => format!("{:e}", x + 0.0),
        toml::Value::Integer(n) => n.to_string(),
        toml::Value::Boolean(b) => b.to_string(),
        toml::Value::String(s) => quote(s),
        other => quote(&other.to_string()),
    }
}

/// A CSV field quoted where it holds a comma, a quote or a line break (RFC 4180); line
/// breaks become spaces.
pub fn quote(s: &str) -> String {
    let s = s.replace(['\n', '\r'], " ");
    if s.contains([',', '"']) || s.starts_with(' ') || s.ends_with(' ') {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s
    }
}

/// The text of `points.csv`.
pub fn points_csv(study: &Study) -> String {
    let mut s = String::from("index,seed");
    for p in &study.parameters {
        s.push(',');
        s.push_str(&quote(&p.key.text));
    }
    s.push('\n');
    for i in 0..study.len() {
        s.push_str(&format!("{i},{}", point_seed(study.seed, i)));
        for j in 0..study.parameters.len() {
            s.push(',');
            s.push_str(&cell(&value(study, j, i)));
        }
        s.push('\n');
    }
    s
}

/// The name of point `i`'s directory (and, with `.failed`, of its failure record).
pub fn point_name(i: usize) -> String {
    format!("{i:06}")
}

/// A planned study: its directory and the study read back from it.
#[derive(Debug, Clone)]
pub struct StudyDir {
    /// The directory.
    pub dir: PathBuf,
    /// The study.
    pub study: Study,
}

#[derive(Debug, serde::Serialize, serde::Deserialize)]
struct PlanJson {
    format: u64,
    name: String,
    points: usize,
    base_source: String,
    base_dir: PathBuf,
    tribo_version: String,
}

fn read(path: &Path) -> StudyResult<String> {
    std::fs::read_to_string(path).map_err(|e| StudyError::file(path, e))
}

fn write(path: &Path, text: &str) -> StudyResult<()> {
    let dir = path.parent().unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    tribo_io::atomic::write_atomic(dir, &name, text.as_bytes())?;
    Ok(())
}

impl StudyDir {
    /// Plans `study` (from the study file's `text`) into `dir`: writes `study.toml`,
    /// `base.toml`, `plan.json` and `points.csv`. A directory that already holds the same
    /// study is kept as it is (its computed points too); one holding another study, or other
    /// files, is refused.
    pub fn plan(study: &Study, text: &str, dir: &Path) -> StudyResult<StudyDir> {
        let existing = dir.join("study.toml");
        if existing.exists() {
            let same = read(&existing)? == text && read(&dir.join("base.toml"))? == study.base.text;
            if !same {
                return Err(StudyError::Dir {
                    dir: dir.to_path_buf(),
                    detail: "holds another study (its study.toml or base.toml differ): plan \
                             into a new directory (-o) or remove this one"
                        .into(),
                });
            }
        } else if dir.exists() {
            let not_empty = std::fs::read_dir(dir)
                .map_err(|e| StudyError::file(dir, e))?
                .next()
                .is_some();
            if not_empty {
                return Err(StudyError::Dir {
                    dir: dir.to_path_buf(),
                    detail: "exists and is not a study directory: plan into a new or empty \
                             directory"
                        .into(),
                });
            }
        }
        std::fs::create_dir_all(dir.join("points")).map_err(|e| StudyError::file(dir, e))?;
        write(&dir.join("base.toml"), &study.base.text)?;
        let plan = PlanJson {
            format: FORMAT,
            name: study.name.clone(),
            points: study.len(),
            base_source: study.base.source.clone(),
            base_dir: study.base.dir.clone(),
            tribo_version: env!("CARGO_PKG_VERSION").into(),
        };
        let json = serde_json::to_string_pretty(&plan).map_err(|e| StudyError::Dir {
            dir: dir.to_path_buf(),
            detail: format!("plan.json: {e}"),
        })?;
        write(&dir.join("plan.json"), &json)?;
        write(&dir.join("points.csv"), &points_csv(study))?;
        // Last: a directory with study.toml is a complete plan.
        write(&dir.join("study.toml"), text)?;
        Ok(StudyDir {
            dir: dir.to_path_buf(),
            study: study.clone(),
        })
    }

    /// Opens a planned study: the study re-read from `study.toml` with the base case of
    /// `base.toml`, checked against `plan.json` and `points.csv`.
    pub fn open(dir: &Path) -> StudyResult<StudyDir> {
        let bad = |detail: String| StudyError::Dir {
            dir: dir.to_path_buf(),
            detail,
        };
        if !dir.join("study.toml").is_file() {
            return Err(bad(
                "not a planned study (no study.toml): run `tribo sweep plan STUDY.toml -o DIR` \
                 first"
                    .into(),
            ));
        }
        let text = read(&dir.join("study.toml"))?;
        let plan: PlanJson = serde_json::from_str(&read(&dir.join("plan.json"))?)
            .map_err(|e| bad(format!("plan.json: {e}")))?;
        if plan.format != FORMAT {
            return Err(bad(format!(
                "plan.json: format {} (this tribo reads {FORMAT}): plan it again",
                plan.format
            )));
        }
        let base = Base {
            text: read(&dir.join("base.toml"))?,
            source: plan.base_source.clone(),
            dir: plan.base_dir.clone(),
        };
        let source = dir.join("study.toml").display().to_string();
        let mut study = Study::from_toml_with_base(&text, &source, dir, Some(base))?;
        study.name = plan.name.clone();
        if study.len() != plan.points {
            return Err(bad(format!(
                "plan.json says {} points, the study has {}: plan it again",
                plan.points,
                study.len()
            )));
        }
        if read(&dir.join("points.csv"))? != points_csv(&study) {
            return Err(bad(
                "points.csv differs from the study's points (another tribo version or an \
                 edited file): plan it again"
                    .into(),
            ));
        }
        Ok(StudyDir {
            dir: dir.to_path_buf(),
            study,
        })
    }

    /// The folder of the points.
    pub fn points_dir(&self) -> PathBuf {
        self.dir.join("points")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn point_seeds_are_distinct_and_in_range() {
        let mut seen = std::collections::BTreeSet::new();
        for i in 0..10_000 {
            let s = point_seed(7, i);
            assert!(s < crate::spec::SEED_LIMIT);
            assert!(seen.insert(s));
        }
        assert_ne!(point_seed(7, 0), point_seed(8, 0));
    }

    #[test]
    fn quoting() {
        assert_eq!(quote("ok"), "ok");
        assert_eq!(quote("a, b"), "\"a, b\"");
        assert_eq!(quote("say \"x\""), "\"say \"\"x\"\"\"");
        assert_eq!(cell(&toml::Value::Float(-0.0)), "0e0");
        assert_eq!(cell(&toml::Value::Float(2.5e8)), "2.5e8");
    }
}
