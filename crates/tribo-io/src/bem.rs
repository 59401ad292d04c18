//! The files of a 2D boundary element run: `summary.json`, `interfaces.csv`/`.png`, per step
//! `fields_<step>.vtu` and the maps `sigma_xx_<step>.png`, `sigma_int_<step>.png`; with
//! `[damage]` `psi_<quantity>.png` and `damage_sweep.csv`/`.png`; with `[compare]`
//! `compare.csv`/`.png`; with `[dynamics]` the files of [`crate::dynamics`] (`probes.csv`,
//! `fields_NNNN.vtu`, `fields.pvd`, ...).

use crate::atomic::{prepare_dir, write_atomic};
use crate::error::{IoError, IoResult};
use crate::{WriteOptions, Written};
use std::path::Path;
use tribo_case::bem::case::BemCase;
use tribo_case::bem::pipeline::BemOutcome;
use tribo_case::bem::summary::BemSummary;

/// The summary's file name (written last).
pub const SUMMARY: &str = "summary.json";

/// File-name form of a step name: ASCII letters, digits, `-` and `_` kept, anything else
/// `_`.
pub fn file_name(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// The damage map's file name of a quantity: `psi_sigma_1_.png` for `sigma_1+`.
pub fn psi_file(quantity: &str) -> String {
    format!("psi_{}.png", quantity.replace(['+', '-'], "_"))
}

/// Names of the files a run writes, in the order of writing (`summary.json` last); without
/// `plots`, no PNG.
pub fn files(out: &BemOutcome, summary: &BemSummary, plots: bool) -> Vec<String> {
    let v = &out.main;
    let mut f: Vec<String> = Vec::new();
    if v.steps.iter().any(|s| !s.pairs.is_empty()) {
        f.extend(["interfaces.csv".into(), "interfaces.png".into()]);
    }
    if !v.fields.is_empty() {
        for st in &v.steps {
            let name = file_name(&st.name);
            f.push(format!("fields_{name}.vtu"));
            f.push(format!("sigma_xx_{name}.png"));
            f.push(format!("sigma_int_{name}.png"));
        }
    }
    if let Some(d) = &v.damage {
        f.push(psi_file(&d.quantity));
        if !d.sweep.is_empty() {
            f.extend(["damage_sweep.csv".into(), "damage_sweep.png".into()]);
        }
    }
    if summary.compare.is_some() {
        f.extend(["compare.csv".into(), "compare.png".into()]);
    }
    if let Some(d) = &out.dynamics {
        f.extend(crate::dynamics::dynamics_files(&d.history, true));
    }
    f.push(SUMMARY.into());
    if !plots {
        f.retain(|name| !name.ends_with(".png"));
    }
    f
}

/// Refuses a non-finite value among `values` (nothing is written).
fn finite_all(what: &str, values: impl IntoIterator<Item = f64>) -> IoResult<()> {
    if values.into_iter().all(f64::is_finite) {
        Ok(())
    } else {
        Err(IoError::NonFinite {
            what: what.to_string(),
            detail: "a value is not finite (nothing was written)".into(),
        })
    }
}

/// Checks every number the files show before anything is written.
fn check(out: &BemOutcome, summary: &BemSummary) -> IoResult<()> {
    let v = &out.main;
    for st in &summary.steps {
        finite_all(
            "segment forces",
            st.segment_forces
                .iter()
                .flat_map(|f| f.force_n_per_m.into_iter().chain([f.moment_about_origin_n])),
        )?;
    }
    for st in &v.steps {
        finite_all(
            "contact tractions",
            st.pairs
                .iter()
                .flat_map(|p| p.nodes.iter().flat_map(|n| [n.pressure, n.shear, n.slip])),
        )?;
    }
    for f in &v.fields {
        for step in &f.samples {
            finite_all(
                "fields",
                step.iter().flat_map(|x| {
                    [
                        x.stress.xx,
                        x.stress.yy,
                        x.stress.xy,
                        x.stress.zz,
                        x.displacement[0],
                        x.displacement[1],
                    ]
                }),
            )?;
        }
    }
    if let Some(d) = &v.damage {
        finite_all("damage", d.psi.iter().copied())?;
    }
    if let Some(d) = &out.dynamics {
        crate::dynamics::check(&d.history)?;
    }
    Ok(())
}

/// Writes the CSV and VTK files of a run.
fn write_data(dir: &Path, case: &BemCase, out: &BemOutcome, summary: &BemSummary) -> IoResult<()> {
    let v = &out.main;
    if v.steps.iter().any(|s| !s.pairs.is_empty()) {
        write_atomic(dir, "interfaces.csv", crate::csv::interfaces(v).as_bytes())?;
    }
    let psi_of = v
        .damage
        .as_ref()
        .map(|d| (d.region.as_str(), d.psi.as_slice()));
    let damage_step = case.damage.as_ref().map(|d| d.step);
    if !v.fields.is_empty() {
        for (k, st) in v.steps.iter().enumerate() {
            let psi = if damage_step == Some(k) { psi_of } else { None };
            let file = format!("fields_{}.vtu", file_name(&st.name));
            write_atomic(dir, &file, &crate::vtk::bem_vtu(v, k, psi))?;
        }
    }
    if let Some(d) = &summary.damage {
        if !d.sweep.is_empty() {
            let csv = crate::csv::damage_sweep(d.unit.symbol(), &d.sweep);
            write_atomic(dir, "damage_sweep.csv", csv.as_bytes())?;
        }
    }
    if let Some(c) = &summary.compare {
        write_atomic(dir, "compare.csv", crate::csv::compare(c).as_bytes())?;
    }
    Ok(())
}

/// Writes every file of a 2D run into `dir` (created if needed; the earlier run's files
/// removed, see [`prepare_dir`]) and returns the summary (`summary.json`, written last)
/// with the files' names.
pub fn write_bem(
    dir: &Path,
    case: &BemCase,
    out: &BemOutcome,
    opts: &WriteOptions,
) -> IoResult<Written<BemSummary>> {
    let plots = opts.draws_plots();
    let mut summary = BemSummary::new(case, out, Vec::new())?;
    summary.outputs = files(out, &summary, plots);
    check(out, &summary)?;
    prepare_dir(dir, SUMMARY, opts.remove_temporary_on_signal)?;
    write_data(dir, case, out, &summary)?;
    if let Some(d) = &out.dynamics {
        let psi: Vec<_> = d
            .damage
            .iter()
            .map(|x| ("psi".into(), x.snapshot_psi.clone()))
            .collect();
        let columns = d
            .contact
            .as_ref()
            .map(|c| c.energy.columns())
            .unwrap_or_default();
        crate::dynamics::write_dynamics_with(dir, &d.history, &psi, &columns, opts)?;
    }
    #[cfg(feature = "png")]
    if plots {
        crate::plot::bem::write_plots(dir, case, out, &summary)?;
    }
    let text = crate::json::to_pretty(&summary, "summary")?;
    write_atomic(dir, SUMMARY, text.as_bytes())?;
    let files = summary.outputs.clone();
    Ok(Written { summary, files })
}
