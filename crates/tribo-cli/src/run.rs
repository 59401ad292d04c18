//! The pipeline of `tribo run`: validated case -> grid and initial gap -> normal contact
//! solution -> comparison with Hertz (where the gap is Hertzian).

use crate::case::{Case, Method, Shape, Window};
use crate::error::CliResult;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde::Serialize;
use std::time::{Duration, Instant};
use tribo::geometry::initial_gap;
use tribo::kernels::hertz::{GapCurvature, HertzContact};
use tribo::solvers::{
    solve_normal_active_set, solve_normal_cg, NormalContactProblem, NormalContactSolution,
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

/// The paper's error measures (17) of a computed pressure against Hertz.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct HertzError {
    /// max |eps_i| over all elements, eps_i = (p_H,i - p_i) / p0_H at element centres.
    pub eps_max: f64,
    /// mean |eps_i| over all nx * ny elements of the grid.
    pub eps_avg: f64,
    /// max |eps_i| over the elements whose centre lies strictly inside the Hertz ellipse.
    pub eps_max_inside: f64,
    /// Centre (x, y) of the element where eps_max occurs, m.
    pub eps_max_at: [f64; 2],
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
    pub error: Option<HertzError>,
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
        (Window::Extent(_), None) => {
            unreachable!("validation allows extent only for Hertzian gaps")
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
    let result = match case.method {
        Method::Cg => solve_normal_cg(&problem, &case.params),
        Method::ActiveSet => solve_normal_active_set(&problem, &case.params),
    };
    let solve_time = start.elapsed();
    pb.finish_and_clear();
    let solution = result?;
    let (hertz_pressure, error) = match &prepared.hertz {
        Some(h) => {
            let ph = prepared.grid.sample(|x, y| h.contact.pressure(x, y));
            let err = hertz_error(&prepared.grid, &solution.pressure, &ph, &h.contact);
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

/// The error measures of the paper's (17): eps_i = (p_H,i - p_i)/p0_H at element centres.
///
/// Computed here until `tribo::analysis::hertz_error` provides it; the definitions are the
/// same (max over all elements, mean over all nx * ny elements, max over the centres strictly
/// inside the Hertz ellipse). The element centred on the contact edge dominates eps_max:
/// Hertz gives 0 there while the element carries a finite mean pressure.
pub fn hertz_error(
    grid: &SurfaceGrid,
    pressure: &[f64],
    hertz_pressure: &[f64],
    h: &HertzContact,
) -> HertzError {
    let p0 = h.max_pressure;
    let (s, c) = h.angle.sin_cos();
    let mut out = HertzError {
        eps_max: 0.0,
        eps_avg: 0.0,
        eps_max_inside: 0.0,
        eps_max_at: [0.0; 2],
    };
    let mut sum = 0.0;
    for iy in 0..grid.ny() {
        for ix in 0..grid.nx() {
            let k = grid.index(ix, iy);
            let (x, y) = (grid.x(ix), grid.y(iy));
            let eps = ((hertz_pressure[k] - pressure[k]) / p0).abs();
            sum += eps;
            if eps > out.eps_max {
                out.eps_max = eps;
                out.eps_max_at = [x, y];
            }
            let (xp, yp) = (c * x + s * y, -s * x + c * y);
            let r2 = (xp / h.semi_major).powi(2) + (yp / h.semi_minor).powi(2);
            if r2 < 1.0 - 1e-9 {
                out.eps_max_inside = out.eps_max_inside.max(eps);
            }
        }
    }
    out.eps_avg = sum / grid.len() as f64;
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hertz_error_definitions() {
        let grid = SurfaceGrid::centred(4, 4, 2.0, 2.0).unwrap();
        let h = HertzContact {
            semi_major: 1.0,
            semi_minor: 1.0,
            max_pressure: 10.0,
            approach: 0.0,
            normal_load: 0.0,
            angle: 0.0,
            composite_modulus: 1.0,
        };
        // Centres at +-0.5 (inside) and +-1.5 (outside).
        let ph = vec![1.0; 16];
        let mut p = vec![1.0; 16];
        p[grid.index(1, 1)] = 0.0; // inside: eps = 0.1
        p[grid.index(0, 0)] = 3.0; // outside: eps = 0.2
        let e = hertz_error(&grid, &p, &ph, &h);
        assert!((e.eps_max - 0.2).abs() < 1e-15);
        assert!((e.eps_max_inside - 0.1).abs() < 1e-15);
        assert!((e.eps_avg - 0.3 / 16.0).abs() < 1e-15);
        assert_eq!(e.eps_max_at, [-1.5, -1.5]);
    }
}
