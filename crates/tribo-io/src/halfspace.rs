//! The files of a half-space run: `summary.json`, `pressure.csv`, `gap.csv`, `fields.vti`,
//! `pressure_map.png`, `pressure_profiles.png`; with `[bulk]` also `back_effect.csv` and
//! `back_effect.png`; with friction `traction.csv`, `stick_slip.png`,
//! `traction_profiles.png`; with `[field]` `stress.vti` and sections; with `[damage]` the
//! psi sections and (the Sec. 6 study) `sec6.csv`, `sec6.png`.
//!
//! Every number is checked finite before anything is written; `summary.json` is written last
//! (see [`crate::atomic`]).

use crate::atomic::{prepare_dir, write_atomic};
use crate::error::{check_finite, IoError, IoResult};
use crate::{WriteOptions, Written};
use std::path::Path;
use tribo_case::case::HalfSpaceCase;
use tribo_case::derived::{stress_arrays, traction_along_y, BackEffectSeries};
use tribo_case::pipeline::{BackEffect, Outcome, Stress};
use tribo_case::summary::Summary;

/// Names of the files every run writes, in order (`summary.json` first in this list, written
/// last).
pub const FILES: [&str; 6] = [
    "summary.json",
    "pressure.csv",
    "gap.csv",
    "fields.vti",
    "pressure_map.png",
    "pressure_profiles.png",
];

/// Names of the files the back effect adds (cases with `[bulk]`).
pub const BACK_EFFECT_FILES: [&str; 2] = ["back_effect.csv", "back_effect.png"];

/// Names of the files friction adds (cases with `contact.friction`).
pub const TANGENTIAL_FILES: [&str; 3] = ["traction.csv", "stick_slip.png", "traction_profiles.png"];

/// Names of the files the stress field adds (cases with `[field]`).
pub const STRESS_FILES: [&str; 4] = [
    "stress.vti",
    "sigma_xx_y0.png",
    "sigma_xx_z05a.png",
    "von_mises_y0.png",
];

/// Sections in the plane x = 0, written besides those in y = 0 when the friction traction
/// acts mainly along y (sliding or a tangential force along y): the plane y = 0 then misses
/// the plane in which friction acts.
pub const STRESS_X0_FILES: [&str; 2] = ["sigma_yy_x0.png", "von_mises_x0.png"];

/// Files of the load sweep (cases with `contact.load_steps`, a periodic grid or a rough
/// surface): the table per load, the final load's patches, and their plots.
pub const SWEEP_FILES: [&str; 4] = [
    "load_sweep.csv",
    "patches.csv",
    "contact_patches.png",
    "area_vs_load.png",
];

/// Files of a rough or measured surface: its PSD and the plot.
pub const ROUGH_FILES: [&str; 2] = ["psd.csv", "psd.png"];

/// Files of the Sec. 6 study.
pub const STUDY_FILES: [&str; 2] = ["sec6.csv", "sec6.png"];

/// A quantity name as a file and VTK array name: `sigma_1+` -> `sigma_1_tension`.
pub fn safe_name(name: &str) -> String {
    name.replace('+', "_tension").replace('-', "_compression")
}

/// The psi section of a criterion, like the paper's Fig. 6.
pub fn damage_plot_name(name: &str) -> String {
    format!("psi_{}_y0.png", safe_name(name))
}

/// The psi section of a criterion in the plane x = 0 (with [`STRESS_X0_FILES`]).
pub fn damage_plot_name_x0(name: &str) -> String {
    format!("psi_{}_x0.png", safe_name(name))
}

/// Names of the files a run of this outcome writes (`summary.json` first); without `plots`,
/// no PNG.
pub fn files(out: &Outcome, plots: bool) -> Vec<String> {
    let mut f: Vec<String> = FILES.iter().map(|f| f.to_string()).collect();
    if out.back_effect.is_some() {
        f.extend(BACK_EFFECT_FILES.iter().map(|f| f.to_string()));
    }
    if out.tangential.is_some() {
        f.extend(TANGENTIAL_FILES.iter().map(|f| f.to_string()));
    }
    if out.sweep.is_some() {
        f.extend(SWEEP_FILES.iter().map(|f| f.to_string()));
    }
    if out.prepared.rough.is_some() {
        f.extend(ROUGH_FILES.iter().map(|f| f.to_string()));
    }
    let x0 = traction_along_y(out);
    if out.stress.is_some() {
        f.extend(STRESS_FILES.iter().map(|f| f.to_string()));
        if x0 {
            f.extend(STRESS_X0_FILES.iter().map(|f| f.to_string()));
        }
    }
    if let Some(d) = &out.damage {
        f.extend(
            d.criteria
                .iter()
                .map(|c| damage_plot_name(&c.assessment.name)),
        );
        if x0 && out.stress.is_some() {
            f.extend(
                d.criteria
                    .iter()
                    .map(|c| damage_plot_name_x0(&c.assessment.name)),
            );
        }
        if d.study.is_some() {
            f.extend(STUDY_FILES.iter().map(|f| f.to_string()));
        }
        if d.criteria.iter().any(|c| c.probabilistic.is_some()) {
            f.extend(
                crate::probabilistic::PROBABILISTIC_FILES
                    .iter()
                    .map(|f| f.to_string()),
            );
        }
    }
    if !plots {
        f.retain(|name| !name.ends_with(".png"));
    }
    f
}

/// The summary of a solved case ([`Summary::new`] with the files of [`files`]), its numbers
/// checked finite.
pub fn summary(case: &HalfSpaceCase, out: &Outcome, plots: bool) -> IoResult<Summary> {
    let s = Summary::new(case, out, files(out, plots));
    let c = &s.contact;
    let mut scalars = vec![
        c.normal_load,
        c.approach,
        c.max_pressure,
        c.contact_area,
        c.residual,
        s.materials.composite_modulus,
        s.solver.time_s,
    ];
    if let Some(h) = &c.hertz {
        scalars.extend([
            h.a,
            h.b,
            h.p0,
            h.approach,
            h.normal_load,
            h.contact_area,
            h.angle,
        ]);
    }
    if let Some(e) = &c.error_vs_hertz {
        scalars.extend([
            e.eps_max,
            e.eps_avg,
            e.eps_max_inside,
            e.eps_max_element_averaged,
        ]);
    }
    if let Some(b) = &s.back_effect {
        scalars.extend(b.scalars());
    }
    if let Some(t) = &s.tangential {
        scalars.extend(t.scalars());
    }
    if let Some(t) = &s.stress {
        scalars.extend(t.scalars());
    }
    if let Some(d) = &s.damage {
        scalars.extend(d.scalars());
    }
    if let Some(r) = &s.roughness {
        scalars.extend(r.composite.scalars());
        for b in &r.bodies {
            scalars.extend(b.statistics.scalars());
            scalars.extend(b.plateau);
        }
    }
    if let Some(w) = &s.load_sweep {
        scalars.extend(w.scalars());
    }
    check_finite("summary.json", &scalars)?;
    Ok(s)
}

/// Every number of `back_effect.csv` and of the summary's back-effect part, for the
/// finiteness check.
fn back_effect_values(b: &BackEffect) -> Vec<f64> {
    b.curves
        .iter()
        .flat_map(|(_, c)| c.iter())
        .chain(b.operating.iter().map(|(_, p)| p))
        .flat_map(|p| {
            [
                p.stress,
                p.approach_change,
                p.normal_load,
                p.force_ratio,
                p.force_ratio_hertz,
            ]
        })
        .chain([b.reference_approach, b.reference_load])
        .collect()
}

/// The stress field's point arrays for `stress.vti` (with the damage criteria's psi),
/// checked finite.
fn stress_vti_arrays(out: &Outcome, st: &Stress) -> IoResult<Vec<(String, Vec<f64>)>> {
    let mut arrays: Vec<(String, Vec<f64>)> = stress_arrays(st)
        .into_iter()
        .map(|(n, v)| (n.to_string(), v))
        .collect();
    if let Some(d) = &out.damage {
        for c in &d.criteria {
            arrays.push((
                format!("psi_{}", safe_name(&c.assessment.name)),
                c.psi.clone(),
            ));
        }
    }
    for (name, v) in &arrays {
        check_finite(&format!("stress.vti {name}"), v)?;
    }
    Ok(arrays)
}

/// The data files (CSV, VTK) of a run, built and checked before anything is written, and
/// what the plots draw beside the results (unread without the feature `png`).
#[cfg_attr(not(feature = "png"), allow(dead_code))]
pub(crate) struct DataFiles {
    /// (file name, content) in the order of writing.
    pub(crate) files: Vec<(&'static str, Vec<u8>)>,
    /// The stress field's point arrays (the sections are drawn from them).
    pub(crate) stress_arrays: Option<Vec<(String, Vec<f64>)>>,
    /// The back-effect plot's series (cases with `[bulk]`).
    pub(crate) back_effect_series: Vec<BackEffectSeries>,
}

/// Builds every data file of the run, checking every number finite first.
fn data_files(case: &HalfSpaceCase, out: &Outcome) -> IoResult<DataFiles> {
    let grid = &out.prepared.grid;
    let sol = &out.solution;
    check_finite("pressure", &sol.pressure)?;
    check_finite("gap", &sol.gap)?;
    check_finite("initial gap", &out.prepared.initial_gap)?;
    if let Some(ph) = &out.hertz_pressure {
        check_finite("hertz pressure", ph)?;
    }
    let n = grid.len();
    for (what, len) in [("pressure", sol.pressure.len()), ("gap", sol.gap.len())] {
        if len != n {
            return Err(IoError::Shape {
                what: what.into(),
                detail: format!("{len} values for {n} elements"),
            });
        }
    }
    let mut files = vec![
        (
            FILES[1],
            crate::csv::surface_field(grid, "pressure_Pa", &sol.pressure).into_bytes(),
        ),
        (
            FILES[2],
            crate::csv::surface_field(grid, "gap_m", &sol.gap).into_bytes(),
        ),
    ];
    let mut arrays: Vec<(&str, &[f64])> = vec![
        ("pressure_Pa", &sol.pressure),
        ("gap_m", &sol.gap),
        ("initial_gap_m", &out.prepared.initial_gap),
    ];
    if let Some(ph) = &out.hertz_pressure {
        arrays.push(("hertz_pressure_Pa", ph));
    }
    let stick_f: Vec<f64>;
    let mut traction = None;
    if let Some(t) = &out.tangential {
        let s = &t.solution;
        check_finite("traction", &s.traction_x)?;
        check_finite("traction", &s.traction_y)?;
        stick_f = s.stick.iter().map(|&b| f64::from(u8::from(b))).collect();
        arrays.push(("traction_x_Pa", &s.traction_x));
        arrays.push(("traction_y_Pa", &s.traction_y));
        arrays.push(("stick", &stick_f));
        traction = Some(crate::csv::traction(
            grid,
            &s.traction_x,
            &s.traction_y,
            &s.stick,
        ));
    }
    let stress = match &out.stress {
        Some(st) => {
            let arrays = stress_vti_arrays(out, st)?;
            Some((crate::vtk::stress_vti(st, &arrays), arrays))
        }
        None => None,
    };
    files.push((FILES[3], crate::vtk::surface_vti(grid, &arrays)));
    let mut back_effect_series = Vec::new();
    if let Some(b) = &out.back_effect {
        check_finite("back_effect.csv", &back_effect_values(b))?;
        // The plot's Hertz series, checked here so that nothing is written when it fails.
        back_effect_series = tribo_case::derived::back_effect_series(case, b)?;
        for s in &back_effect_series {
            let v: Vec<f64> = s.hertz.iter().flat_map(|p| [p.0, p.1]).collect();
            check_finite("back_effect.png", &v)?;
        }
        files.push((
            BACK_EFFECT_FILES[0],
            crate::csv::back_effect(b).into_bytes(),
        ));
    }
    if let Some(csv) = traction {
        files.push((TANGENTIAL_FILES[0], csv.into_bytes()));
    }
    if let Some(w) = &out.sweep {
        let steps: Vec<f64> = w.steps.iter().flat_map(|t| t.scalars()).collect();
        check_finite("load_sweep.csv", &steps)?;
        let patches: Vec<f64> = w
            .patches
            .iter()
            .flat_map(|p| [p.area, p.equivalent_radius, p.load, p.max_pressure])
            .collect();
        check_finite("patches.csv", &patches)?;
        files.push((
            SWEEP_FILES[0],
            crate::csv::load_sweep(&w.steps).into_bytes(),
        ));
        files.push((SWEEP_FILES[1], crate::csv::patches(&w.patches).into_bytes()));
    }
    if let Some(r) = &out.prepared.rough {
        let mut values: Vec<f64> = r.psd.iter().flat_map(|b| [b.q, b.psd]).collect();
        values.extend(r.psd.iter().filter_map(|b| r.input_psd(b.q)));
        check_finite("psd.csv", &values)?;
        files.push((ROUGH_FILES[0], crate::csv::psd(r).into_bytes()));
    }
    let stress_arrays = match stress {
        Some((vti, arrays)) => {
            files.push((STRESS_FILES[0], vti));
            Some(arrays)
        }
        None => None,
    };
    Ok(DataFiles {
        files,
        stress_arrays,
        back_effect_series,
    })
}

/// Writes every file of a half-space run into `dir` (created if needed; the earlier run's
/// files removed, see [`prepare_dir`]) and returns the summary (`summary.json`, written
/// last) with the files' names.
pub fn write_halfspace(
    dir: &Path,
    case: &HalfSpaceCase,
    out: &Outcome,
    opts: &WriteOptions,
) -> IoResult<Written<Summary>> {
    let plots = opts.draws_plots();
    let data = data_files(case, out)?;
    let mut summary = summary(case, out, plots)?;
    prepare_dir(dir, FILES[0], opts.remove_temporary_on_signal)?;
    let write_start = std::time::Instant::now();
    for (name, bytes) in &data.files {
        write_atomic(dir, name, bytes)?;
    }
    if let Some(study) = summary.damage.as_ref().and_then(|d| d.study.as_ref()) {
        write_atomic(dir, STUDY_FILES[0], crate::csv::study(study).as_bytes())?;
    }
    if let Some(d) = &out.damage {
        crate::probabilistic::write_case_probabilistic(dir, d, opts)?;
    }
    #[cfg(feature = "png")]
    if plots {
        crate::plot::halfspace::write_plots(dir, case, out, &summary, &data)?;
    }
    summary.timings.write_s = write_start.elapsed().as_secs_f64();
    let json = crate::json::to_pretty(&summary, FILES[0])?;
    // Last: a summary.json in the directory means the whole run was written.
    write_atomic(dir, FILES[0], json.as_bytes())?;
    let files = summary.outputs.clone();
    Ok(Written { summary, files })
}
