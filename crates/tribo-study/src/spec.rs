//! The study file: a base case, the parameters that vary over it, what to collect.
//!
//! ```toml
//! [study]
//! name = "fig2a"                       # default: the file's stem
//! seed = 1                             # integer in [0, 2^53); default 0
//! base = "case.toml"                   # or example = "roller-shaft-bending", or a [base] table
//! samples = 100                        # with [[random]]: samples per grid/zip point
//! outputs = "summary"                  # "summary" (summary.json only) or "all" (every file)
//! unset = ["compare"]                  # key paths removed from the base case
//! collect = ["contact.max_pressure", "back_effect.operating.bending.force_ratio"]
//!
//! [set]                                # fixed changes to the base case, by key path
//! "bulk.points" = 3
//!
//! [[grid]]                             # a cartesian product over the [[grid]] entries
//! key = "bulk.stress"
//! from = -6.4e8                        # or values = [...]
//! to = 6.4e8
//! points = 9
//!
//! [[zip]]                              # lists of equal length, varied together
//! key = "body2.E"                      # (one group per `group` name, default "zip")
//! values = ["201 GPa", "165 GPa"]
//!
//! [[random]]                           # a distribution of tribo::stats, optionally truncated
//! key = "contact.load"
//! dist = "normal"
//! mean = 2000.0
//! sd = 100.0
//! truncate = { low = 1500.0 }
//! ```
//!
//! The points are the product of the grid axes (the first slowest), then the zip groups, then
//! the `samples` random samples (fastest). Every check that needs no run happens here: an
//! unknown key path, an empty grid, a zip of unequal lengths, invalid distribution parameters,
//! `samples = 0`, a seed out of range, a collected key that the summary of this kind of case
//! does not have.

use crate::error::{StudyError, StudyResult};
use crate::path::{self, KeyPath};
use serde::Deserialize;
use std::path::{Path, PathBuf};
use tribo::stats::{Distribution, Truncated};
use tribo_case::{Case, CaseError};

/// The largest study seed (exclusive): 2^53, so that every seed, and every point's seed, is
/// exact as a double (JSON, Python, NetCDF).
pub const SEED_LIMIT: u64 = 1 << 53;

/// The most points a study may have.
pub const MAX_POINTS: usize = 1_000_000;

/// What a point leaves in its directory besides `case.toml`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outputs {
    /// `summary.json` only (the fast default: a study's table needs nothing else).
    Summary,
    /// Every file `tribo run` writes for the case, plots included.
    All,
}

/// The kind of the base case, which decides the summary's unit table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CaseKind {
    /// A half-space case.
    HalfSpace,
    /// A 2D boundary element case.
    Bem2d,
}

/// How a parameter varies.
#[derive(Debug, Clone)]
pub enum Variation {
    /// A list of values (a grid axis or a member of a zip group).
    Values(Vec<toml::Value>),
    /// Random samples of a distribution.
    Random(Truncated),
}

/// A parameter of the study: a key path into the case and how it varies.
#[derive(Debug, Clone)]
pub struct Parameter {
    /// Where in the study file it is defined (`grid[0]`, `zip[1]`, `random[0]`).
    pub item: String,
    /// The key path into the case TOML.
    pub key: KeyPath,
    /// Its values.
    pub variation: Variation,
}

/// A collected number of the run's summary.
#[derive(Debug, Clone)]
pub struct Collected {
    /// The key path into `summary.json`.
    pub key: KeyPath,
    /// Its unit (from the summary's unit table; "1" dimensionless).
    pub unit: String,
    /// The column name: the key path and the unit (`contact.max_pressure_Pa`).
    pub column: String,
}

/// The base case of a study.
#[derive(Debug, Clone)]
pub struct Base {
    /// Its TOML text (as written, or the inline `[base]` table written out).
    pub text: String,
    /// Its name in errors (`case.toml`, `<embedded roller-shaft>`, `study.toml [base]`).
    pub source: String,
    /// The folder its relative paths (height maps, meshes) resolve against.
    pub dir: PathBuf,
}

/// A validated study.
#[derive(Debug, Clone)]
pub struct Study {
    /// Its name.
    pub name: String,
    /// The study seed, in [0, [`SEED_LIMIT`]).
    pub seed: u64,
    /// The base case as given (before `set`/`unset`).
    pub base: Base,
    /// The base case's table with `set` and `unset` applied.
    pub base_table: toml::Table,
    /// The kind of case.
    pub kind: CaseKind,
    /// The axes of the product, slowest first: each grid entry, then each zip group, then
    /// (when there are random parameters) the samples; each axis lists its parameters'
    /// indices into [`Study::parameters`].
    pub axes: Vec<(usize, Vec<usize>)>,
    /// Every parameter, in column order: grid, zip, random.
    pub parameters: Vec<Parameter>,
    /// Samples per grid/zip point (1 without random parameters).
    pub samples: usize,
    /// The collected numbers.
    pub collect: Vec<Collected>,
    /// What each point writes.
    pub outputs: Outputs,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawStudy {
    study: RawHeader,
    base: Option<toml::Table>,
    set: Option<toml::Table>,
    grid: Option<Vec<RawGrid>>,
    zip: Option<Vec<RawZip>>,
    random: Option<Vec<toml::Table>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawHeader {
    name: Option<String>,
    seed: Option<i64>,
    base: Option<String>,
    example: Option<String>,
    samples: Option<i64>,
    outputs: Option<String>,
    #[serde(default)]
    unset: Vec<String>,
    #[serde(default)]
    collect: Vec<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGrid {
    key: String,
    values: Option<Vec<toml::Value>>,
    from: Option<f64>,
    to: Option<f64>,
    points: Option<i64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawZip {
    key: String,
    values: Vec<toml::Value>,
    group: Option<String>,
}

/// The units of the numbers of a summary of `kind` (the tables `tribo_case` keeps beside
/// its summaries).
pub fn unit_table(kind: CaseKind) -> Vec<(&'static str, &'static str)> {
    match kind {
        CaseKind::HalfSpace => tribo_case::summary::UNITS.to_vec(),
        CaseKind::Bem2d => tribo_case::bem::summary::UNITS
            .iter()
            .chain(tribo_case::bem::dynamics_damage::UNITS)
            .copied()
            .collect(),
    }
}

fn key_path(item: &str, text: &str) -> StudyResult<KeyPath> {
    KeyPath::parse(text).map_err(|rule| StudyError::item(item, format!("{text:?}"), rule))
}

/// Every leaf of a table, by its dotted path (a `[set]` table written with dotted or nested
/// keys).
fn leaves(prefix: &str, t: &toml::Table, out: &mut Vec<(String, toml::Value)>) {
    for (k, v) in t {
        let p = if prefix.is_empty() {
            k.clone()
        } else {
            format!("{prefix}.{k}")
        };
        match v {
            toml::Value::Table(inner) => leaves(&p, inner, out),
            _ => out.push((p, v.clone())),
        }
    }
}

/// Removes the key at a plain dotted path; false where there is none.
fn remove(root: &mut toml::Table, path: &KeyPath) -> bool {
    let Some((last, parents)) = path.segments.split_last() else {
        return false;
    };
    if path.segments.iter().any(|s| !s.index.is_empty()) {
        return false;
    }
    let mut cur = root;
    for s in parents {
        match cur.get_mut(&s.name) {
            Some(toml::Value::Table(t)) => cur = t,
            _ => return false,
        }
    }
    cur.remove(&last.name).is_some()
}

/// Parses a point's (or the base's) case from its table.
pub fn parse_case(table: &toml::Table, source: &str, dir: &Path) -> Result<Case, CaseError> {
    let text = toml::to_string(table).map_err(|e| CaseError::Parse {
        path: source.to_string(),
        message: e.to_string(),
    })?;
    Case::from_toml(&text, source, dir)
}

impl Study {
    /// Parses and checks a study file's text. `source` names it in errors; `dir` is its
    /// folder (a `base` path is relative to it).
    pub fn from_toml(text: &str, source: &str, dir: &Path) -> StudyResult<Study> {
        Study::from_toml_with_base(text, source, dir, None)
    }

    /// As [`Study::from_toml`], with the base case given (a planned study's `base.toml`)
    /// instead of the one the study file names.
    pub fn from_toml_with_base(
        text: &str,
        source: &str,
        dir: &Path,
        given_base: Option<Base>,
    ) -> StudyResult<Study> {
        let raw: RawStudy = toml::from_str(text).map_err(|e| StudyError::Parse {
            path: source.to_string(),
            message: e.to_string(),
        })?;
        let h = &raw.study;
        let name = match &h.name {
            Some(n) if n.trim().is_empty() => {
                return Err(StudyError::item(
                    "study.name",
                    "\"\"",
                    "a name is not empty",
                ))
            }
            Some(n) => n.clone(),
            None => Path::new(source)
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .filter(|s| !s.starts_with('<') && !s.is_empty())
                .unwrap_or_else(|| "study".into()),
        };
        let seed = match h.seed {
            None => 0,
            Some(s) => u64::try_from(s)
                .ok()
                .filter(|&s| s < SEED_LIMIT)
                .ok_or_else(|| {
                    StudyError::item(
                        "study.seed",
                        s,
                        "a seed is an integer in [0, 2^53) (exact as a double)",
                    )
                })?,
        };
        let base = match given_base {
            Some(b) => b,
            None => base(&raw, source, dir)?,
        };
        let mut base_table: toml::Table = toml::from_str(&base.text).map_err(|e| {
            StudyError::Base(CaseError::Parse {
                path: base.source.clone(),
                message: e.to_string(),
            })
        })?;
        for (i, u) in h.unset.iter().enumerate() {
            let item = format!("study.unset[{i}]");
            let k = key_path(&item, u)?;
            if !remove(&mut base_table, &k) {
                return Err(StudyError::item(
                    item,
                    format!("{u:?}"),
                    "the base case has no such key (a plain dotted path of tables)",
                ));
            }
        }
        if let Some(set) = &raw.set {
            let mut list = Vec::new();
            leaves("", set, &mut list);
            for (p, v) in list {
                let item = format!("set.{p}");
                let k = key_path(&item, &p)?;
                path::set(&mut base_table, &k, v.clone())
                    .map_err(|rule| StudyError::item(&item, v, rule))?;
            }
        }
        let base_case =
            parse_case(&base_table, &base.source, &base.dir).map_err(StudyError::Base)?;
        let kind = match base_case {
            Case::HalfSpace(_) => CaseKind::HalfSpace,
            Case::Bem2d(_) => CaseKind::Bem2d,
        };
        let (parameters, axes, samples) = parameters(&raw)?;
        let mut study = Study {
            name,
            seed,
            base,
            base_table,
            kind,
            axes,
            parameters,
            samples,
            collect: Vec::new(),
            outputs: match h.outputs.as_deref() {
                None | Some("summary") => Outputs::Summary,
                Some("all") => Outputs::All,
                Some(o) => {
                    return Err(StudyError::item(
                        "study.outputs",
                        format!("{o:?}"),
                        "\"summary\" (summary.json only) or \"all\" (every file of tribo run)",
                    ))
                }
            },
        };
        study.collect = collect(&h.collect, kind)?;
        study.probe()?;
        Ok(study)
    }

    /// The number of points.
    pub fn len(&self) -> usize {
        self.axes.iter().map(|(n, _)| *n).product()
    }

    /// Whether the study has no points (never: every axis has at least one value).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Checks every parameter's key path against the case schema: the base case with the
    /// parameter set to its first value must parse. A schema error (an unknown key, a value
    /// of the wrong type) is the study's error; a value breaking a rule of the case is left
    /// to its point (reported there, the other points go on).
    fn probe(&self) -> StudyResult<()> {
        for (j, p) in self.parameters.iter().enumerate() {
            let value = crate::plan::value(self, j, 0);
            let mut t = self.base_table.clone();
            path::set(&mut t, &p.key, value.clone())
                .map_err(|rule| StudyError::item(format!("{}.key", p.item), &p.key, rule))?;
            if let Err(CaseError::Parse { message, .. }) =
                parse_case(&t, &format!("{} = {}", p.key, value), &self.base.dir)
            {
                return Err(StudyError::item(
                    format!("{}.key", p.item),
                    format!("{:?}", p.key.text),
                    format!("the case does not take this key or value: {message}"),
                ));
            }
        }
        Ok(())
    }
}

/// The base case from `study.base` (a path), `study.example` (an embedded example) or an
/// inline `[base]` table: exactly one.
fn base(raw: &RawStudy, source: &str, dir: &Path) -> StudyResult<Base> {
    let h = &raw.study;
    let given = usize::from(h.base.is_some())
        + usize::from(h.example.is_some())
        + usize::from(raw.base.is_some());
    if given != 1 {
        return Err(StudyError::item(
            "study.base",
            format!("{given} given"),
            "give exactly one base case: study.base = \"case.toml\", study.example = \"NAME\" \
             or an inline [base] table",
        ));
    }
    if let Some(p) = &h.base {
        let path = dir.join(p);
        let text = read_bounded(&path).map_err(|e| {
            StudyError::item(
                "study.base",
                format!("{p:?}"),
                format!("cannot read it: {e}"),
            )
        })?;
        let case_dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        return Ok(Base {
            text,
            source: path.display().to_string(),
            dir: absolute(&case_dir),
        });
    }
    if let Some(name) = &h.example {
        let ex = tribo_case::examples::find(name).ok_or_else(|| {
            StudyError::item(
                "study.example",
                format!("{name:?}"),
                format!(
                    "no example case of that name; `tribo example` lists them: {}",
                    tribo_case::examples::names()
                ),
            )
        })?;
        return Ok(Base {
            text: ex.text.to_string(),
            source: format!("<embedded {}>", ex.name),
            dir: absolute(dir),
        });
    }
    let table = raw.base.clone().unwrap_or_default();
    let text = toml::to_string(&table).map_err(|e| StudyError::Parse {
        path: format!("{source} [base]"),
        message: e.to_string(),
    })?;
    Ok(Base {
        text,
        source: format!("{source} [base]"),
        dir: absolute(dir),
    })
}

/// `dir` made absolute (a study directory is run from elsewhere: a SLURM node's working
/// folder); as given where the current folder is unknown.
fn absolute(dir: &Path) -> PathBuf {
    std::path::absolute(if dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        dir
    })
    .unwrap_or_else(|_| dir.to_path_buf())
}

type Parameters = (Vec<Parameter>, Vec<(usize, Vec<usize>)>, usize);

/// The parameters and the axes of the product.
fn parameters(raw: &RawStudy) -> StudyResult<Parameters> {
    let mut params = Vec::new();
    let mut axes = Vec::new();
    for (i, g) in raw.grid.iter().flatten().enumerate() {
        let item = format!("grid[{i}]");
        let key = key_path(&format!("{item}.key"), &g.key)?;
        let values = grid_values(&item, g)?;
        axes.push((values.len(), vec![params.len()]));
        params.push(Parameter {
            item,
            key,
            variation: Variation::Values(values),
        });
    }
    // Zip groups in the order of their first entry.
    let mut groups: Vec<(String, Vec<usize>)> = Vec::new();
    for (i, z) in raw.zip.iter().flatten().enumerate() {
        let item = format!("zip[{i}]");
        let key = key_path(&format!("{item}.key"), &z.key)?;
        if z.values.is_empty() {
            return Err(StudyError::item(
                format!("{item}.values"),
                "[]",
                "a zipped list has at least one value",
            ));
        }
        finite_values(&format!("{item}.values"), &z.values)?;
        let group = z.group.clone().unwrap_or_else(|| "zip".into());
        match groups.iter_mut().find(|(g, _)| *g == group) {
            Some((_, members)) => members.push(params.len()),
            None => groups.push((group, vec![params.len()])),
        }
        params.push(Parameter {
            item,
            key,
            variation: Variation::Values(z.values.clone()),
        });
    }
    for (group, members) in groups {
        let lens: Vec<usize> = members
            .iter()
            .map(|&m| match &params[m].variation {
                Variation::Values(v) => v.len(),
                Variation::Random(_) => 1,
            })
            .collect();
        if lens.iter().any(|&l| l != lens[0]) {
            let items: Vec<String> = members
                .iter()
                .zip(&lens)
                .map(|(&m, l)| format!("{} ({}): {l}", params[m].item, params[m].key))
                .collect();
            return Err(StudyError::item(
                format!("zip group {group:?}"),
                items.join(", "),
                "the lists of a zip group have equal lengths",
            ));
        }
        axes.push((lens[0], members));
    }
    let randoms = raw.random.as_deref().unwrap_or_default();
    let samples = match (raw.study.samples, randoms.is_empty()) {
        (None, true) => 1,
        (Some(n), true) => {
            return Err(StudyError::item(
                "study.samples",
                n,
                "samples are drawn for [[random]] parameters: there are none",
            ))
        }
        (None, false) => {
            return Err(StudyError::item(
                "study.samples",
                "missing",
                "[[random]] parameters need the number of samples, study.samples = N",
            ))
        }
        (Some(n), false) => usize::try_from(n)
            .ok()
            .filter(|&n| (1..=MAX_POINTS).contains(&n))
            .ok_or_else(|| {
                StudyError::item(
                    "study.samples",
                    n,
                    format!("the number of samples is in [1, {MAX_POINTS}]"),
                )
            })?,
    };
    let mut random_members = Vec::new();
    for (i, r) in randoms.iter().enumerate() {
        let item = format!("random[{i}]");
        random_members.push(params.len());
        params.push(random(&item, r)?);
    }
    if !random_members.is_empty() {
        axes.push((samples, random_members));
    }
    let mut total: usize = 1;
    for (n, _) in &axes {
        total = total.saturating_mul(*n);
    }
    if total > MAX_POINTS {
        return Err(StudyError::item(
            "study",
            format!("{total} points"),
            format!("a study has at most {MAX_POINTS} points: split it"),
        ));
    }
    if params.is_empty() {
        return Err(StudyError::item(
            "study",
            "no parameters",
            "a study varies at least one key: [[grid]], [[zip]] or [[random]]",
        ));
    }
    let mut seen = std::collections::BTreeSet::new();
    for p in &params {
        if !seen.insert(p.key.text.clone()) {
            return Err(StudyError::item(
                format!("{}.key", p.item),
                format!("{:?}", p.key.text),
                "each key varies in one place only",
            ));
        }
    }
    Ok((params, axes, samples))
}

/// A grid entry's values: `values = [...]`, or `from`, `to`, `points` (evenly spaced,
/// both ends included).
fn grid_values(item: &str, g: &RawGrid) -> StudyResult<Vec<toml::Value>> {
    match (&g.values, g.from, g.to, g.points) {
        (Some(v), None, None, None) => {
            if v.is_empty() {
                Err(StudyError::item(
                    format!("{item}.values"),
                    "[]",
                    "a grid has at least one value",
                ))
            } else {
                finite_values(&format!("{item}.values"), v)?;
                Ok(v.clone())
            }
        }
        (None, Some(from), Some(to), Some(points)) => {
            if !from.is_finite() || !to.is_finite() {
                return Err(StudyError::item(
                    format!("{item}.from"),
                    format!("{from}, to = {to}"),
                    "finite numbers (SI units)",
                ));
            }
            let n = usize::try_from(points)
                .ok()
                .filter(|&n| (1..=MAX_POINTS).contains(&n) && (n > 1 || from == to))
                .ok_or_else(|| {
                    StudyError::item(
                        format!("{item}.points"),
                        points,
                        "at least 2 points from `from` to `to` (1 where from = to)",
                    )
                })?;
            Ok((0..n)
                .map(|k| {
                    // Both ends exact: from at k = 0, to at k = n - 1.
                    let x = if k + 1 == n {
                        to
                    } else {
                        from + (to - from) * (k as f64) / ((n - 1).max(1) as f64)
                    };
                    toml::Value::Float(x)
                })
                .collect())
        }
        _ => Err(StudyError::item(
            item,
            format!("{:?}", g.key),
            "give either values = [...] or from, to and points",
        )),
    }
}

/// A study or case file's text, a regular file of at most
/// [`tribo_case::memory::MAX_CASE_FILE_BYTES`] (a larger file is refused with the limit, a
/// device such as the endless `/dev/zero` or a pipe before it is opened), UTF-8
/// ([`tribo_case::topography::read_regular`]).
pub fn read_bounded(path: &Path) -> std::io::Result<String> {
    use std::io::{Error, ErrorKind};
    use tribo_case::topography::{read_regular, BoundedReadError};
    let limit = tribo_case::memory::MAX_CASE_FILE_BYTES;
    let bytes = read_regular(path, limit).map_err(|e| match e {
        BoundedReadError::Io(e) => e,
        BoundedReadError::Directory | BoundedReadError::NotRegular => Error::new(
            ErrorKind::InvalidInput,
            "not a regular file (a directory, a device, a pipe or a socket)",
        ),
        BoundedReadError::TooLarge(_) => Error::new(
            ErrorKind::InvalidData,
            format!(
                "larger than {} (a study or case file is a few hundred lines of TOML)",
                tribo_case::memory::human(limit)
            ),
        ),
    })?;
    String::from_utf8(bytes).map_err(|e| Error::new(ErrorKind::InvalidData, e))
}

/// Refuses a float of a values list that is not finite (TOML's `nan`, `inf`), naming it
/// (`grid[0].values[1]`), inside arrays too: points.csv and the cases would hold it.
fn finite_values(item: &str, values: &[toml::Value]) -> StudyResult<()> {
    for (k, v) in values.iter().enumerate() {
        match v {
            toml::Value::Float(x) if !x.is_finite() => {
                return Err(StudyError::item(
                    format!("{item}[{k}]"),
                    x,
                    "a value must be a finite number",
                ))
            }
            toml::Value::Array(inner) => finite_values(&format!("{item}[{k}]"), inner)?,
            _ => {}
        }
    }
    Ok(())
}

/// A `[[random]]` entry: `key`, the distribution (`dist` and its parameters, as
/// [`tribo::stats::Distribution`] reads them) and the optional truncation
/// `truncate = { low, high }`.
fn random(item: &str, table: &toml::Table) -> StudyResult<Parameter> {
    let mut t = table.clone();
    let key = match t.remove("key") {
        Some(toml::Value::String(s)) => key_path(&format!("{item}.key"), &s)?,
        other => {
            return Err(StudyError::item(
                format!("{item}.key"),
                other.map_or("missing".into(), |v| v.to_string()),
                "the key path of the random parameter, a string",
            ))
        }
    };
    let (mut low, mut high) = (None, None);
    match t.remove("truncate") {
        None => {}
        Some(toml::Value::Table(b)) => {
            for (name, v) in b {
                let x = match v {
                    toml::Value::Float(x) => x,
                    toml::Value::Integer(x) => x as f64,
                    v => {
                        return Err(StudyError::item(
                            format!("{item}.truncate.{name}"),
                            v,
                            "a truncation bound is a number (SI units)",
                        ))
                    }
                };
                match name.as_str() {
                    "low" => low = Some(x),
                    "high" => high = Some(x),
                    _ => {
                        return Err(StudyError::item(
                            format!("{item}.truncate.{name}"),
                            x,
                            "the truncation is { low = .., high = .. } (either optional)",
                        ))
                    }
                }
            }
        }
        Some(v) => {
            return Err(StudyError::item(
                format!("{item}.truncate"),
                v,
                "the truncation is a table { low = .., high = .. } (either optional)",
            ))
        }
    }
    let dist: Distribution = toml::Value::Table(t).try_into().map_err(|e| {
        StudyError::item(
            item,
            format!("{:?}", key.text),
            format!(
                "a distribution: dist = \"normal\" (mean, sd), \"lognormal\" (median, \
                 sigma_ln), \"uniform\" (low, high) or \"weibull\" (shape, scale, location); \
                 {e}"
            ),
        )
    })?;
    let truncated = Truncated { dist, low, high };
    truncated
        .validate()
        .map_err(|e| StudyError::item(item, format!("{:?}", key.text), e.to_string()))?;
    // Every sample a point can draw must be a finite number: the samples are quantiles at
    // uniform01's values, which lie in [2^-53, 1 - 2^-53] (tribo::stats::uniform01), and the
    // quantile is monotone, so its two ends bound them all (a lognormal of sigma_ln 1e3 or a
    // Weibull of shape 1e-3 reach 0 and inf there, which points.csv would then hold).
    let edge = 2f64.powi(-53);
    for (end, p) in [("lowest", edge), ("highest", 1.0 - edge)] {
        let x = truncated.quantile(p);
        if !x.is_finite() {
            return Err(StudyError::item(
                item,
                format!("{:?}", key.text),
                format!(
                    "the distribution's {end} sample (its quantile at {p:e}) is {x}: every \
                     sample must be a finite number; narrow the distribution or truncate it"
                ),
            ));
        }
    }
    Ok(Parameter {
        item: item.to_string(),
        key,
        variation: Variation::Random(truncated),
    })
}

/// The collected keys, each checked against the unit table of the kind of case.
fn collect(list: &[String], kind: CaseKind) -> StudyResult<Vec<Collected>> {
    let table = unit_table(kind);
    let mut out: Vec<Collected> = Vec::new();
    for (i, text) in list.iter().enumerate() {
        let item = format!("study.collect[{i}]");
        let key = key_path(&item, text)?;
        let unit = path::unit_of(&table, &key).ok_or_else(|| {
            StudyError::item(
                &item,
                format!("{text:?}"),
                format!(
                    "not a number of the summary of a {} case (docs/user/outputs.md lists \
                     them; an array element needs its index, e.g. [0])",
                    match kind {
                        CaseKind::HalfSpace => "half-space",
                        CaseKind::Bem2d => "bem2d",
                    }
                ),
            )
        })?;
        // A unit given by another key ("damage.criteria[].unit") or a note stays out of the
        // column name; the attribute carries it.
        let last = key
            .segments
            .last()
            .map(|s| s.name.to_ascii_lowercase())
            .unwrap_or_default();
        let suffix = path::unit_suffix(unit);
        // A key that says its unit already (`dangerous_area_m2`, `peak_pressure_pa`) keeps
        // its name.
        let suffix = if unit.contains(['.', '(']) || last.ends_with(&suffix.to_ascii_lowercase()) {
            String::new()
        } else {
            suffix
        };
        let column = format!("{text}{suffix}");
        if out.iter().any(|c| c.column == column) {
            return Err(StudyError::item(
                item,
                format!("{text:?}"),
                "collected twice",
            ));
        }
        out.push(Collected {
            key,
            unit: unit.to_string(),
            column,
        });
    }
    Ok(out)
}
