//! The pipeline of `tribo run`: validated case -> grid and initial gap -> normal contact
//! solution -> comparison with Hertz (where the gap is Hertzian) -> the back effect of bulk
//! loading (where the case has `[bulk]`).

use crate::case::{Case, LoadKind, Method, Shape, Window};
use crate::error::CliResult;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::time::{Duration, Instant};
use tribo::analysis::hertz_error::{pressure_errors, PressureErrors};
use tribo::geometry::initial_gap;
use tribo::kernels::hertz::{GapCurvature, HertzContact};
use tribo::solvers::back_effect::{back_effect_curve_observed, BackEffectPoint};
use tribo::solvers::{
    solve_normal_active_set, solve_normal_cg_observed, NormalContactProblem, NormalContactSolution,
    NormalLoading,
};
use tribo::SurfaceGrid;

/// The Hertz solution of a case whose gap is Hertzian.
#[derive(Debug, Clone, Copy)]
pub struct HertzReference {
    /// Gap coefficients.
    pub curvature: GapCurvature,
    /// Contact under the case's load (or approach).
    pub contact: HertzContact,
}

/// Everything needed to solve: grid, initial gap, E*, Hertz reference.
#[derive(Debug, Clone)]
pub struct Prepared {
    /// The window.
    pub grid: SurfaceGrid,
    /// Initial gap at element centres, m.
    pub initial_gap: Vec<f64>,
    /// Composite modulus E*, Pa.
    pub composite_modulus: f64,
    /// Hertz, where the gap is Hertzian.
    pub hertz: Option<HertzReference>,
}

/// A solved case.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// Inputs of the solver.
    pub prepared: Prepared,
    /// The solution.
    pub solution: NormalContactSolution,
    /// Hertz pressure at element centres, Pa (Hertzian gaps only).
    pub hertz_pressure: Option<Vec<f64>>,
    /// Error measures (Hertzian gaps only).
    pub error: Option<PressureErrors>,
    /// Wall time of the solve.
    pub solve_time: Duration,
    /// The back effect of bulk loading (cases with `[bulk]`).
    pub back_effect: Option<BackEffect>,
}

/// Where the fixed rigid approach of the back effect comes from.
pub const APPROACH_FROM_CASE: &str = "contact.approach";
/// Where the fixed rigid approach of the back effect comes from, under force control.
pub const APPROACH_FROM_SOLUTION: &str = "the normal solution under contact.load";

/// The back effect of bulk loading, the paper's (18) and Fig. 2a: the contact force at a
/// fixed rigid approach against the bulk stress of the shaft.
#[derive(Debug, Clone)]
pub struct BackEffect {
    /// The fixed rigid approach delta_0, m.
    pub reference_approach: f64,
    /// Where delta_0 comes from ([`APPROACH_FROM_CASE`] or [`APPROACH_FROM_SOLUTION`]).
    pub approach_from: &'static str,
    /// F_N at delta_0 without bulk load, N.
    pub reference_load: f64,
    /// sigma / sigma_max of the curve points.
    pub ratios: Vec<f64>,
    /// One curve per load kind, points in the order of `ratios`.
    pub curves: Vec<(LoadKind, Vec<BackEffectPoint>)>,
    /// At the operating stress `bulk.stress`, one point per load kind.
    pub operating: Vec<(LoadKind, BackEffectPoint)>,
    /// CG iterations over all points.
    pub iterations: usize,
    /// Wall time, s.
    pub time: Duration,
}

/// Build the grid and the initial gap, and the Hertz reference where the gap is Hertzian.
pub fn prepare(case: &Case) -> CliResult<Prepared> {
    let e_star = case.composite_modulus();
    let hertz = match (&case.body1.shape, &case.body2.shape) {
        (
            Shape::Radii {
                radii: r1,
                angle: a1,
            },
            Shape::Radii {
                radii: r2,
                angle: a2,
            },
        ) => {
            let curvature = GapCurvature::from_radii(*r1, *r2, a2 - a1)?;
            let contact = match case.loading {
                NormalLoading::Force(f) => HertzContact::from_load(&curvature, e_star, f)?,
                NormalLoading::Approach(d) => HertzContact::from_approach(&curvature, e_star, d)?,
            };
            Some(HertzReference { curvature, contact })
        }
        _ => None,
    };
    let half_widths = match (case.window, &hertz) {
        (Window::HalfWidth(hw), _) => hw,
        (Window::Extent(e), Some(h)) => [e * h.contact.semi_major; 2],
        (Window::Extent(e), None) => {
            // Validation allows extent only for Hertzian gaps; kept as an error, not a panic.
            return Err(crate::error::CliError::field(
                "grid.extent",
                e,
                "extent needs a Hertzian gap (both bodies given by radii); give grid.half_width",
            ));
        }
    };
    let grid = SurfaceGrid::centred(case.n[0], case.n[1], half_widths[0], half_widths[1])?;
    let gap = match &hertz {
        Some(h) => grid.sample(|x, y| h.curvature.gap(x, y)),
        None => initial_gap(
            &grid,
            &case.body1.profile("body1")?,
            &case.body2.profile("body2")?,
        )?,
    };
    Ok(Prepared {
        grid,
        initial_gap: gap,
        composite_modulus: e_star,
        hertz,
    })
}

/// A spinner on stderr while the solver runs (hidden with `quiet` or when stderr is not a
/// terminal).
pub fn spinner(quiet: bool, message: String) -> ProgressBar {
    let pb = if quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr())
    };
    if let Ok(style) = ProgressStyle::with_template("{spinner} {msg} [{elapsed}]") {
        pb.set_style(style);
    }
    pb.set_message(message);
    pb.enable_steady_tick(Duration::from_millis(100));
    pb
}

/// Solve the prepared case with the case's method, and compare with Hertz.
pub fn solve(case: &Case, prepared: Prepared, quiet: bool) -> CliResult<Outcome> {
    let problem = NormalContactProblem {
        grid: &prepared.grid,
        initial_gap: &prepared.initial_gap,
        composite_modulus: prepared.composite_modulus,
        loading: case.loading,
    };
    let pb = spinner(
        quiet,
        format!(
            "solving normal contact ({} x {} elements, {})",
            prepared.grid.nx(),
            prepared.grid.ny(),
            case.method.name()
        ),
    );
    let start = Instant::now();
    let tolerance = case.params.tolerance;
    let (nx, ny) = (prepared.grid.nx(), prepared.grid.ny());
    let mut report = |iteration: usize, residual: f64| {
        pb.set_message(format!(
            "solving normal contact ({nx} x {ny} elements, cg): iteration {iteration}, \
             residual {residual:.2e} (tolerance {tolerance:.0e})"
        ));
    };
    let result = match case.method {
        Method::Cg => solve_normal_cg_observed(&problem, &case.params, &mut report),
        Method::ActiveSet => solve_normal_active_set(&problem, &case.params),
    };
    let solve_time = start.elapsed();
    pb.finish_and_clear();
    let solution = result?;
    let (hertz_pressure, error) = match &prepared.hertz {
        Some(h) => {
            let ph = prepared.grid.sample(|x, y| h.contact.pressure(x, y));
            let err = pressure_errors(&prepared.grid, &solution.pressure, &h.contact);
            (Some(ph), Some(err))
        }
        None => (None, None),
    };
    let mut outcome = Outcome {
        prepared,
        solution,
        hertz_pressure,
        error,
        solve_time,
        back_effect: None,
    };
    outcome.back_effect = back_effect(case, &outcome, quiet)?;
    Ok(outcome)
}

/// The back effect of the case's `[bulk]` section (None without one): every curve point and
/// the operating stress solved on one FFT operator at the fixed rigid approach, which is
/// `contact.approach` under approach control and the approach the normal solution found
/// under force control.
pub fn back_effect(case: &Case, out: &Outcome, quiet: bool) -> CliResult<Option<BackEffect>> {
    let Some(bulk) = &case.bulk else {
        return Ok(None);
    };
    let (reference_approach, approach_from) = match case.loading {
        NormalLoading::Approach(d) => (d, APPROACH_FROM_CASE),
        NormalLoading::Force(_) => (out.solution.approach, APPROACH_FROM_SOLUTION),
    };
    let ratios = bulk.ratios();
    let mut loads = Vec::new();
    for &kind in &bulk.kinds {
        loads.extend(ratios.iter().map(|r| kind.load(r * bulk.stress_max)));
    }
    if let Some(sigma) = bulk.stress {
        loads.extend(bulk.kinds.iter().map(|k| k.load(sigma)));
    }
    let pb = if quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::with_draw_target(Some(loads.len() as u64 + 1), ProgressDrawTarget::stderr())
    };
    if let Ok(style) =
        ProgressStyle::with_template("{spinner} {msg} [{bar:30}] {pos}/{len} [{elapsed}]")
    {
        pb.set_style(style.progress_chars("=> "));
    }
    pb.set_message(format!(
        "back effect of bulk loading ({} contact solutions at delta_0 = {reference_approach:.4e} m)",
        loads.len() + 1
    ));
    pb.enable_steady_tick(Duration::from_millis(100));
    let p = &out.prepared;
    let start = Instant::now();
    let result = back_effect_curve_observed(
        &p.grid,
        &p.initial_gap,
        p.composite_modulus,
        &case.body(bulk.shaft).material,
        bulk.shaft_radius,
        reference_approach,
        &loads,
        &case.params,
        &mut |done, _| pb.set_position(done as u64),
    );
    let time = start.elapsed();
    pb.finish_and_clear();
    let points = result.map_err(|e| match e {
        tribo::Error::ContactReachesWindow { detail } => {
            let (field, value) = match bulk.stress {
                Some(s) if s.abs() > bulk.stress_max => ("bulk.stress", s),
                _ => ("bulk.stress_max", bulk.stress_max),
            };
            crate::error::CliError::field(
                field,
                value,
                format!(
                    "under this bulk stress (compression) the approach delta_0 + u_z grows the \
                     contact to the edge of the window ({detail}); lower the stress or enlarge \
                     the window (grid.extent or grid.half_width)"
                ),
            )
        }
        e => e.into(),
    })?;
    let n = ratios.len();
    let curves: Vec<(LoadKind, Vec<BackEffectPoint>)> = bulk
        .kinds
        .iter()
        .enumerate()
        .map(|(k, &kind)| (kind, points[k * n..(k + 1) * n].to_vec()))
        .collect();
    let operating = bulk
        .kinds
        .iter()
        .zip(&points[bulk.kinds.len() * n..])
        .map(|(&kind, p)| (kind, *p))
        .collect();
    // The middle point is sigma = 0 (points is odd): its load is F_N(0).
    let reference_load = curves
        .first()
        .and_then(|(_, c)| c.get(n / 2))
        .map_or(0.0, |p| p.normal_load);
    Ok(Some(BackEffect {
        reference_approach,
        approach_from,
        reference_load,
        ratios,
        curves,
        operating,
        iterations: points.iter().map(|p| p.iterations).sum(),
        time,
    }))
}
