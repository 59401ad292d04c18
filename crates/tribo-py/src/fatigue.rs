//! Fatigue on arrays: the Woehler fits of `tribo fatigue fit` and the limiting-state diagram
//! of `tribo fatigue diagram`, through [`tribo_case::fatigue`] (the CLI's functions); the
//! reports cross as JSON text (the CLI's `--json`), the Python layer makes pandas of them.

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use std::path::PathBuf;
use tribo::analysis::woehler::{FatigueTest, LoadMeasure, TestKind};

use crate::{case_error, input_error, to_toml, SolverError};

/// A test kind by its symbol: "sigma", "p", "sigma_p", "p_sigma" (the paper's Fig. 3).
fn kind(py: Python<'_>, name: &str) -> PyResult<TestKind> {
    TestKind::ALL
        .into_iter()
        .find(|k| k.symbol() == name)
        .ok_or_else(|| {
            input_error(
                py,
                format!("kind = {name:?}: one of \"sigma\", \"p\", \"sigma_p\", \"p_sigma\""),
                "kind",
                name,
                "one of \"sigma\", \"p\", \"sigma_p\", \"p_sigma\"",
            )
        })
}

/// A load measure by name: "amplitude", "range", "contact_pressure".
fn measure(py: Python<'_>, name: &str) -> PyResult<LoadMeasure> {
    match name {
        "amplitude" => Ok(LoadMeasure::Amplitude),
        "range" => Ok(LoadMeasure::Range),
        "contact_pressure" | "contact-pressure" => Ok(LoadMeasure::ContactPressure),
        other => Err(input_error(
            py,
            format!("measure = {other:?}: one of \"amplitude\", \"range\", \"contact_pressure\""),
            "measure",
            other,
            "one of \"amplitude\", \"range\", \"contact_pressure\"",
        )),
    }
}

/// The Woehler fits of `tribo fatigue fit` (the ASTM E739 regression and the maximum
/// likelihood of pyLife's `MaxLikeFull` model) of the tests (`load` Pa in the measure,
/// `cycles`, `runout` true for a specimen that did not fail), as the JSON text of
/// `woehler.json`. `kind`: "sigma", "p", "sigma_p" or "p_sigma"; `measure`: "amplitude",
/// "range" or "contact_pressure" (None: the kind's default); `confidence` of the E739 bands
/// in (0, 1).
#[pyfunction]
#[pyo3(signature = (load, cycles, runout, kind_name="sigma", measure_name=None, confidence=0.95, source="<arrays>"))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fatigue_fit(
    py: Python<'_>,
    load: Vec<f64>,
    cycles: Vec<f64>,
    runout: Vec<bool>,
    kind_name: &str,
    measure_name: Option<&str>,
    confidence: f64,
    source: &str,
) -> PyResult<String> {
    let kind = kind(py, kind_name)?;
    let measure = match measure_name {
        Some(m) => measure(py, m)?,
        None => kind.default_measure(),
    };
    if cycles.len() != load.len() || runout.len() != load.len() {
        return Err(input_error(
            py,
            format!(
                "load, cycles and runout have {}, {} and {} values",
                load.len(),
                cycles.len(),
                runout.len()
            ),
            "cycles",
            &cycles.len().to_string(),
            "one value per test in each of load, cycles and runout",
        ));
    }
    let tests: Vec<FatigueTest> = load
        .iter()
        .zip(&cycles)
        .zip(&runout)
        .map(|((&load, &cycles), &runout)| FatigueTest {
            load,
            cycles,
            runout,
        })
        .collect();
    let report = py
        .detach(|| tribo_case::fatigue::fit(kind, measure, tests, confidence, source))
        .map_err(|e| case_error(py, &e))?;
    serde_json::to_string(&report).map_err(|e| SolverError::new_err(e.to_string()))
}

/// The limiting-state diagram of `tribo fatigue diagram` (the paper's Fig. 4) from its input
/// (the TOML text of `tribo example fatigue-diagram`, or a dict with its keys), as the JSON
/// text of `limit_diagram.json`. `base_dir` resolves the data files of fitted limits.
#[pyfunction]
#[pyo3(signature = (data, base_dir=None))]
pub(crate) fn fatigue_diagram(
    py: Python<'_>,
    data: &Bound<'_, PyAny>,
    base_dir: Option<PathBuf>,
) -> PyResult<String> {
    let text = if let Ok(s) = data.cast::<PyString>() {
        s.to_string()
    } else if let Ok(d) = data.cast::<PyDict>() {
        let value = to_toml(py, d.as_any(), "")?;
        toml::to_string(&value).map_err(|e| {
            input_error(
                py,
                format!("the dict is not a TOML table: {e}"),
                "",
                "",
                &e.to_string(),
            )
        })?
    } else {
        return Err(input_error(
            py,
            "the diagram's input is a TOML text or a dict".into(),
            "data",
            "",
            "a str or a dict",
        ));
    };
    let base = base_dir.unwrap_or_else(|| PathBuf::from("."));
    let input = tribo_case::fatigue::parse_limits(&text, "<python>", &base)
        .map_err(|e| case_error(py, &e))?;
    let report = tribo_case::fatigue::diagram(input).map_err(|e| case_error(py, &e))?;
    serde_json::to_string(&report).map_err(|e| SolverError::new_err(e.to_string()))
}
