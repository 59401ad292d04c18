//! The files of `tribo fatigue`: `woehler.json` and `woehler.png` of a Woehler fit,
//! `limit_diagram.json` and `limit_diagram.png` of a limiting-state diagram. The JSON is
//! written last.

use crate::atomic::{prepare_dir, write_atomic};
use crate::error::{IoError, IoResult};
use crate::{WriteOptions, Written};
use std::path::Path;
use tribo_case::fatigue::{DiagramReport, FitReport, DIAGRAM_FILES, FIT_FILES};

/// Refuses a non-finite value among `values` (nothing is written).
fn check_finite(what: &str, values: &[f64]) -> IoResult<()> {
    match values.iter().find(|v| !v.is_finite()) {
        None => Ok(()),
        Some(v) => Err(IoError::NonFinite {
            what: what.into(),
            detail: format!("a result is {v} (refusing to write a non-finite number)"),
        }),
    }
}

/// The files written, in order of [`FIT_FILES`] or [`DIAGRAM_FILES`] (the JSON first, written
/// last); without `plots` the JSON only.
fn names(files: [&str; 2], plots: bool) -> Vec<String> {
    files
        .iter()
        .filter(|f| plots || !f.ends_with(".png"))
        .map(|f| f.to_string())
        .collect()
}

/// Writes `woehler.json` and `woehler.png` of a fit into `dir`.
pub fn write_fit(dir: &Path, report: &FitReport, opts: &WriteOptions) -> IoResult<Written<()>> {
    check_finite(FIT_FILES[0], &report.scalars())?;
    let json = crate::json::to_pretty(report, FIT_FILES[0])?;
    prepare_dir(dir, FIT_FILES[0], opts.remove_temporary_on_signal)?;
    #[cfg(feature = "png")]
    if opts.draws_plots() {
        crate::atomic::draw_atomic(dir, FIT_FILES[1], |p| {
            crate::plot::fatigue::woehler(p, report)
        })?;
    }
    write_atomic(dir, FIT_FILES[0], json.as_bytes())?;
    Ok(Written {
        summary: (),
        files: names(FIT_FILES, opts.draws_plots()),
    })
}

/// Writes `limit_diagram.json` and `limit_diagram.png` of a diagram into `dir`.
pub fn write_diagram(
    dir: &Path,
    report: &DiagramReport,
    opts: &WriteOptions,
) -> IoResult<Written<()>> {
    let mut v: Vec<f64> = report
        .diagram
        .points
        .iter()
        .flat_map(|p| [p.pressure_ratio, p.stress_ratio])
        .collect();
    if let Some(c) = &report.state {
        v.extend([c.load_factor, c.margin]);
    }
    check_finite(DIAGRAM_FILES[0], &v)?;
    let json = crate::json::to_pretty(report, DIAGRAM_FILES[0])?;
    prepare_dir(dir, DIAGRAM_FILES[0], opts.remove_temporary_on_signal)?;
    #[cfg(feature = "png")]
    if opts.draws_plots() {
        crate::atomic::draw_atomic(dir, DIAGRAM_FILES[1], |p| {
            crate::plot::fatigue::limit_diagram(p, report)
        })?;
    }
    write_atomic(dir, DIAGRAM_FILES[0], json.as_bytes())?;
    Ok(Written {
        summary: (),
        files: names(DIAGRAM_FILES, opts.draws_plots()),
    })
}
