//! Studies from Python: the engine of `tribo sweep` (the crate `tribo-study`) bound as it is.
//! The study file is read, checked and expanded by [`tribo_study::spec::Study`], the points'
//! values and seeds are [`tribo_study::plan`]'s, the points run through
//! [`tribo_study::run::run_until`] (each point on a one-thread pool, into its own atomic
//! directory) with the interpreter released, and the table is [`tribo_study::table`]'s: the
//! same `results.csv` and `results.nc` bytes as `tribo sweep gather`. Nothing is expanded or
//! computed again here; the Python layer (python/tribo/study.py) turns the columns into a
//! pandas DataFrame or an xarray Dataset.

use crate::{case_error, input_error, to_toml, SolverError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use tribo_case::CaseError;
use tribo_study::plan::{point_seed, value, StudyDir};
use tribo_study::run::PointState;
use tribo_study::slurm::Slurm;
use tribo_study::spec::{Outputs, Study, Variation};
use tribo_study::StudyError;

/// The exception of a study error: bad input (an item of the study file, its base case, the
/// study directory) as [`crate::InputError`] naming the item, a file that cannot be read or
/// written as the `OSError` of its kind, the rest as [`SolverError`].
pub(crate) fn study_error(py: Python<'_>, e: &StudyError) -> PyErr {
    match e {
        StudyError::Item { item, value, rule } => input_error(py, e.to_string(), item, value, rule),
        StudyError::Parse { message, .. } => input_error(py, e.to_string(), "", "", message),
        StudyError::Base(CaseError::Field { field, value, rule }) => {
            input_error(py, e.to_string(), field, value, rule)
        }
        StudyError::Base(c) => {
            let err = case_error(py, c);
            // The message says that the base case is meant.
            let _ = err.value(py).setattr("args", (e.to_string(),));
            err
        }
        StudyError::Dir { dir, detail } => input_error(
            py,
            e.to_string(),
            "directory",
            &dir.display().to_string(),
            detail,
        ),
        StudyError::File { source, .. } => {
            PyErr::from(std::io::Error::new(source.kind(), e.to_string()))
        }
        _ => SolverError::new_err(e.to_string()),
    }
}

/// A parameter's value as a Python object: float, int, bool, str (other TOML values as
/// their TOML text, as `results.nc` has them).
fn py_value<'py>(py: Python<'py>, v: &toml::Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        toml::Value::Float(x) => x.into_pyobject(py)?.into_any(),
        toml::Value::Integer(k) => k.into_pyobject(py)?.into_any(),
        toml::Value::Boolean(b) => b.into_pyobject(py)?.to_owned().into_any(),
        toml::Value::String(s) => s.into_pyobject(py)?.into_any(),
        other => other.to_string().into_pyobject(py)?.into_any(),
    })
}

/// A checked study (`tribo._tribo.Study`): the study file's text and its expansion.
#[pyclass(module = "tribo._tribo", name = "Study", frozen)]
pub(crate) struct PyStudy {
    study: Study,
    text: String,
}

#[pymethods]
impl PyStudy {
    /// Parse and check a study file's text; `source` names it in errors (and gives the
    /// study's default name, its stem), `directory` resolves a relative `study.base`.
    #[staticmethod]
    #[pyo3(signature = (text, source="<string>", directory=None))]
    fn from_toml_text(
        py: Python<'_>,
        text: String,
        source: &str,
        directory: Option<PathBuf>,
    ) -> PyResult<Self> {
        let dir = directory.unwrap_or_default();
        let study = py
            .detach(|| Study::from_toml(&text, source, &dir))
            .map_err(|e| study_error(py, &e))?;
        Ok(PyStudy { study, text })
    }

    /// A study from nested dicts with the keys of a study file (`study`, `base`, `set`,
    /// `grid`, `zip`, `random`), written out as TOML and checked as a file.
    #[staticmethod]
    #[pyo3(signature = (data, source="<dict>", directory=None))]
    fn from_dict(
        py: Python<'_>,
        data: &Bound<'_, PyDict>,
        source: &str,
        directory: Option<PathBuf>,
    ) -> PyResult<Self> {
        let value = to_toml(py, data.as_any(), "")?;
        let text = toml::to_string(&value).map_err(|e| {
            input_error(
                py,
                format!("the dict is not a TOML table: {e}"),
                "",
                "",
                &e.to_string(),
            )
        })?;
        Self::from_toml_text(py, text, source, directory)
    }

    /// An embedded study file by name (`tribo sweep example` lists them).
    #[staticmethod]
    fn example(py: Python<'_>, name: &str) -> PyResult<Self> {
        let ex = tribo_study::examples::find(name).ok_or_else(|| {
            input_error(
                py,
                format!(
                    "no example study {name:?}; known: {}",
                    tribo_study::examples::names()
                ),
                "name",
                name,
                "the name of an embedded example study",
            )
        })?;
        Self::from_toml_text(py, ex.text.to_string(), name, None)
    }

    /// The study's name.
    #[getter]
    fn name(&self) -> String {
        self.study.name.clone()
    }

    /// The study seed.
    #[getter]
    fn seed(&self) -> u64 {
        self.study.seed
    }

    /// The study file's text.
    #[getter]
    fn text(&self) -> String {
        self.text.clone()
    }

    /// The kind of the base case: "halfspace" or "bem2d".
    #[getter]
    fn kind(&self) -> &'static str {
        match self.study.kind {
            tribo_study::spec::CaseKind::HalfSpace => "halfspace",
            tribo_study::spec::CaseKind::Bem2d => "bem2d",
        }
    }

    /// What each point writes: "summary" or "all".
    #[getter]
    fn outputs(&self) -> &'static str {
        match self.study.outputs {
            Outputs::Summary => "summary",
            Outputs::All => "all",
        }
    }

    /// The folder the base case's relative paths (height maps, meshes) resolve against.
    #[getter]
    fn base_dir(&self) -> PathBuf {
        self.study.base.dir.clone()
    }

    /// The base case's TOML text as given (before `set` and `unset`).
    #[getter]
    fn base_toml(&self) -> String {
        self.study.base.text.clone()
    }

    /// The parameters in column order: (key path, study file item, "values" or "random").
    #[getter]
    fn parameters(&self) -> Vec<(String, String, &'static str)> {
        self.study
            .parameters
            .iter()
            .map(|p| {
                let how = match p.variation {
                    Variation::Values(_) => "values",
                    Variation::Random(_) => "random",
                };
                (p.key.text.clone(), p.item.clone(), how)
            })
            .collect()
    }

    /// The collected numbers: (column, key path into the summary, unit).
    #[getter]
    fn collect(&self) -> Vec<(String, String, String)> {
        self.study
            .collect
            .iter()
            .map(|c| (c.column.clone(), c.key.text.clone(), c.unit.clone()))
            .collect()
    }

    fn __len__(&self) -> usize {
        self.study.len()
    }

    /// The points as columns (`points.csv`'s): a list of (name, list of values): `index`,
    /// `seed`, then each parameter by its key path.
    fn points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        points_columns(py, &self.study)
    }

    /// The case of point `i` (the base case with the point's parameters set) as TOML text.
    fn case_toml(&self, py: Python<'_>, i: usize) -> PyResult<String> {
        if i >= self.study.len() {
            return Err(input_error(
                py,
                format!("point {i}: the study has {} points", self.study.len()),
                "index",
                &i.to_string(),
                "a point index in [0, len(study))",
            ));
        }
        let table = tribo_study::plan::case_table(&self.study, i)
            .map_err(|e| input_error(py, e.clone(), "", "", &e))?;
        toml::to_string(&table).map_err(|e| SolverError::new_err(e.to_string()))
    }

    /// Plans the study into `directory` (`tribo sweep plan -o DIRECTORY`): a directory that
    /// already holds the same study is kept as it is, with its computed points.
    fn plan(&self, py: Python<'_>, directory: PathBuf) -> PyResult<PyStudyDir> {
        let sd = py
            .detach(|| StudyDir::plan(&self.study, &self.text, &directory))
            .map_err(|e| study_error(py, &e))?;
        Ok(PyStudyDir {
            sd,
            text: self.text.clone(),
        })
    }

    fn __repr__(&self) -> String {
        format!(
            "Study(name={:?}, points={}, parameters={})",
            self.study.name,
            self.study.len(),
            self.study.parameters.len()
        )
    }
}

/// The columns of `points.csv`.
fn points_columns<'py>(py: Python<'py>, study: &Study) -> PyResult<Bound<'py, PyList>> {
    let n = study.len();
    let out = PyList::empty(py);
    out.append(("index", (0..n).collect::<Vec<usize>>()))?;
    out.append((
        "seed",
        (0..n)
            .map(|i| point_seed(study.seed, i))
            .collect::<Vec<u64>>(),
    ))?;
    for (j, p) in study.parameters.iter().enumerate() {
        let col = PyList::empty(py);
        for i in 0..n {
            col.append(py_value(py, &value(study, j, i))?)?;
        }
        out.append((p.key.text.clone(), col))?;
    }
    Ok(out)
}

/// A planned study directory (`tribo._tribo.StudyDir`).
#[pyclass(module = "tribo._tribo", name = "StudyDir", frozen)]
pub(crate) struct PyStudyDir {
    sd: StudyDir,
    text: String,
}

/// The progress of a run as Python sees it: a callback `(done, total)` after each point, and
/// Ctrl-C (or an exception of the callback) stopping the run after the points in flight.
struct PyProgress<'a> {
    callback: Option<Py<PyAny>>,
    total: u64,
    stop: &'a AtomicBool,
    error: Option<PyErr>,
}

impl PyProgress<'_> {
    fn call(&mut self, done: u64) {
        if self.error.is_some() {
            return;
        }
        let total = self.total;
        let outcome = Python::attach(|py| -> PyResult<()> {
            py.check_signals()?;
            if let Some(cb) = &self.callback {
                cb.call1(py, (done, total))?;
            }
            Ok(())
        });
        if let Err(e) = outcome {
            self.stop.store(true, Ordering::Relaxed);
            self.error = Some(e);
        }
    }
}

impl tribo_case::Progress for PyProgress<'_> {
    fn stage(&mut self, _name: &str, total: Option<u64>) {
        self.total = total.unwrap_or(0);
        self.call(0);
    }

    fn advance(&mut self, done: u64) {
        self.call(done);
    }
}

#[pymethods]
impl PyStudyDir {
    /// Opens a planned study directory (`tribo sweep plan`'s, or `Study.plan`'s).
    #[staticmethod]
    fn open(py: Python<'_>, directory: PathBuf) -> PyResult<Self> {
        let sd = py
            .detach(|| StudyDir::open(&directory))
            .map_err(|e| study_error(py, &e))?;
        let path = sd.dir.join("study.toml");
        let text = std::fs::read_to_string(&path)
            .map_err(|e| study_error(py, &StudyError::file(&path, e)))?;
        Ok(PyStudyDir { sd, text })
    }

    /// The directory.
    #[getter]
    fn directory(&self) -> PathBuf {
        self.sd.dir.clone()
    }

    /// The study, as read back from the directory.
    #[getter]
    fn study(&self) -> PyStudy {
        PyStudy {
            study: self.sd.study.clone(),
            text: self.text.clone(),
        }
    }

    /// Runs the points (`points`, or all) that are not done yet on `jobs` threads (default:
    /// the CPUs available), the interpreter released; `progress(done, total)` is called after
    /// each point. Ctrl-C, or an exception of `progress`, stops the run once the points in
    /// flight are written, and is raised then. Returns a dict: `done`, `failed` (a list of
    /// (index, reason)), `skipped`, `seconds`, `point_seconds`.
    #[pyo3(signature = (points=None, jobs=None, progress=None))]
    fn run<'py>(
        &self,
        py: Python<'py>,
        points: Option<Vec<usize>>,
        jobs: Option<usize>,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let n = self.sd.study.len();
        if let Some(bad) = points.as_ref().and_then(|p| p.iter().find(|&&i| i >= n)) {
            return Err(input_error(
                py,
                format!(
                    "points: {bad} is not a point of the study (0 ... {})",
                    n.max(1) - 1
                ),
                "points",
                &bad.to_string(),
                "point indices in [0, len(study))",
            ));
        }
        let jobs = match jobs {
            Some(0) => {
                return Err(input_error(
                    py,
                    "jobs = 0: at least 1".into(),
                    "jobs",
                    "0",
                    "at least 1",
                ))
            }
            Some(j) => j,
            None => std::thread::available_parallelism().map_or(1, |p| p.get()),
        };
        let stop = AtomicBool::new(false);
        let mut bar = PyProgress {
            callback: progress,
            total: 0,
            stop: &stop,
            error: None,
        };
        let sd = &self.sd;
        let report =
            py.detach(|| tribo_study::run::run_until(sd, points.as_deref(), jobs, &mut bar, &stop));
        if let Some(e) = bar.error {
            return Err(e);
        }
        let report = report.map_err(|e| study_error(py, &e))?;
        let d = PyDict::new(py);
        d.set_item("done", report.done)?;
        d.set_item("failed", report.failed)?;
        d.set_item("skipped", report.skipped)?;
        d.set_item("seconds", report.seconds)?;
        d.set_item("point_seconds", report.point_seconds)?;
        d.set_item("jobs", jobs)?;
        Ok(d)
    }

    /// The state of every point, in point order: ("done", ""), ("failed", reason) or
    /// ("missing", "").
    fn states(&self, py: Python<'_>) -> PyResult<Vec<(&'static str, String)>> {
        let st = py
            .detach(|| tribo_study::run::states(&self.sd))
            .map_err(|e| study_error(py, &e))?;
        Ok(st
            .into_iter()
            .map(|s| match s {
                PointState::Done => ("done", String::new()),
                PointState::Failed(r) => ("failed", r),
                PointState::Missing => ("missing", String::new()),
            })
            .collect())
    }

    /// The results table gathered from the point directories (`tribo sweep gather`'s), and
    /// with `write` `results.csv` and `results.nc` written (atomically). A dict: `columns`, a
    /// list of (name, list of values) in the order of `results.csv` (collected numbers NaN
    /// where a point has none); `units` and `keys` of the collected columns; `attrs`, the
    /// global attributes of `results.nc`.
    #[pyo3(signature = (write=true))]
    fn gather<'py>(&self, py: Python<'py>, write: bool) -> PyResult<Bound<'py, PyDict>> {
        let sd = &self.sd;
        let t = py
            .detach(|| {
                if write {
                    tribo_study::table::write(sd)
                } else {
                    tribo_study::table::gather(sd)
                }
            })
            .map_err(|e| study_error(py, &e))?;
        let study = &sd.study;
        let n = t.status.len();
        let columns = PyList::empty(py);
        columns.append(("index", (0..n).collect::<Vec<usize>>()))?;
        columns.append((
            "seed",
            (0..n)
                .map(|i| point_seed(study.seed, i))
                .collect::<Vec<u64>>(),
        ))?;
        for (j, p) in study.parameters.iter().enumerate() {
            let col = PyList::empty(py);
            for row in &t.parameters {
                col.append(py_value(py, &row[j])?)?;
            }
            columns.append((p.key.text.clone(), col))?;
        }
        for (k, c) in study.collect.iter().enumerate() {
            let col: Vec<f64> = t.collected.iter().map(|r| r[k]).collect();
            columns.append((c.column.clone(), col))?;
        }
        columns.append(("status", t.status.clone()))?;
        let units = PyDict::new(py);
        let keys = PyDict::new(py);
        for c in &study.collect {
            units.set_item(&c.column, &c.unit)?;
            keys.set_item(&c.column, &c.key.text)?;
        }
        for p in &study.parameters {
            keys.set_item(&p.key.text, &p.key.text)?;
        }
        let attrs = PyDict::new(py);
        attrs.set_item("title", &study.name)?;
        attrs.set_item(
            "source",
            format!("tribo {} sweep gather", env!("CARGO_PKG_VERSION")),
        )?;
        attrs.set_item("base_case", &study.base.source)?;
        attrs.set_item("study_seed", study.seed)?;
        let d = PyDict::new(py);
        d.set_item("columns", columns)?;
        d.set_item("units", units)?;
        d.set_item("keys", keys)?;
        d.set_item("attrs", attrs)?;
        Ok(d)
    }

    /// Writes the SLURM array and gather scripts of `tribo sweep slurm` into `DIR/slurm`
    /// (with `settings.json`) for the binary `tribo` (an absolute path): `chunk` points per
    /// array task, `cpus_per_task` jobs in each, `time` `[D-]HH:MM:SS`, an optional
    /// `partition` and `max_running`. Returns the paths of the two scripts.
    #[pyo3(signature = (tribo, chunk=None, partition=None, time="01:00:00".to_string(), cpus_per_task=1, max_running=None))]
    #[allow(clippy::too_many_arguments)]
    fn slurm(
        &self,
        py: Python<'_>,
        tribo: PathBuf,
        chunk: Option<usize>,
        partition: Option<String>,
        time: String,
        cpus_per_task: usize,
        max_running: Option<usize>,
    ) -> PyResult<(PathBuf, PathBuf)> {
        let n = self.sd.study.len();
        let chunk = chunk.unwrap_or_else(|| tribo_study::slurm::default_chunk(n));
        let bad = |field: &str, value: String, rule: &str| {
            input_error(
                py,
                format!("{field} = {value}: {rule}"),
                field,
                &value,
                rule,
            )
        };
        let s = Slurm {
            chunk,
            partition,
            time,
            cpus_per_task,
            max_running,
        };
        // The settings' rules are the library's (the CLI's, by the same names).
        s.validate().map_err(|e| study_error(py, &e))?;
        if !tribo.is_absolute() || !tribo.is_file() {
            return Err(bad(
                "tribo",
                tribo.display().to_string(),
                "the absolute path of the tribo binary the array tasks run",
            ));
        }
        py.detach(|| tribo_study::slurm::write_scripts(&self.sd, &s, &tribo))
            .map_err(|e| study_error(py, &e))
    }

    fn __repr__(&self) -> String {
        format!(
            "StudyDir({:?}, name={:?}, points={})",
            self.sd.dir.display().to_string(),
            self.sd.study.name,
            self.sd.study.len()
        )
    }
}

/// SLURM's `--array=` form of a list of task ids (`0-3,7,9-10`).
#[pyfunction]
pub(crate) fn slurm_ranges(ids: Vec<usize>) -> String {
    tribo_study::slurm::ranges(&ids)
}

/// The job id in sbatch's answer (`Submitted batch job 42`, or `--parsable`'s `42;cluster`).
#[pyfunction]
pub(crate) fn slurm_job_id(answer: &str) -> Option<u64> {
    tribo_study::slurm::job_id(answer)
}

/// The names and one-line descriptions of the embedded study files.
#[pyfunction]
pub(crate) fn study_examples() -> Vec<(&'static str, &'static str)> {
    tribo_study::examples::STUDIES
        .iter()
        .map(|e| (e.name, e.description))
        .collect()
}
