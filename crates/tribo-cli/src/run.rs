//! The pipeline of `tribo run`: validated case -> grid and initial gap -> normal contact
//! solution -> comparison with Hertz (where the gap is Hertzian).

use crate::case::{Case, Method, Shape, Window};
use crate::error::CliResult;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::time::{Duration, Instant};
use tribo::analysis::hertz_error::{pressure_errors, PressureErrors};
use tribo::geometry::initial_gap;
use tribo::kernels::hertz::{GapCurvature, HertzContact};
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
    Ok(Outcome {
        prepared,
        solution,
        hertz_pressure,
        error,
        solve_time,
    })
}
