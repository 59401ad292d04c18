//! The coarse-grid start of the conjugate gradient ([`super::NormalContactParams::coarse_start`]):
//! solve the problem on the grid coarsened by 2 (recursively, down to [`MIN_COARSE_SIDE`]
//! elements per side), interpolate the pressure to the fine grid and start the fine
//! iteration from it. A nested-iteration (full multigrid style) start: the coarse solution
//! already holds the contact area and the smooth part of the pressure, so the fine
//! conjugate gradient only has to correct what the coarse grid cannot represent, and needs
//! far fewer iterations than from Polonsky & Keer's uniform start.
//!
//! The coarse problem is built from what [`NormalContactProblem`] carries, the gap at the
//! fine element centres: the coarse gap is the mean of each 2 x 2 block (the coarse
//! element's mean gap, second order in the element size). Only the start depends on it: the
//! fine iteration solves the fine problem, whose linear complementarity problem has one
//! solution (K symmetric positive definite), and accepts it on its own residual, so the fine
//! solution is the same to the tolerance whatever the start (tested).

use super::{
    normal_compliance_operator, normal_compliance_operator_periodic, solve_normal_from,
    NormalContactParams, NormalContactProblem,
};
use crate::grid::SurfaceGrid;
use crate::kernels::periodic::PeriodicKernel;

/// The smallest coarse grid side: below ~64 elements across the window the contact area of
/// a concentrated contact spans a few elements and the coarse solution says little about
/// the fine one, while the fine solve is already cheap (milliseconds).
pub const MIN_COARSE_SIDE: usize = 64;

/// Tolerance of the coarse solves (at least the caller's): the coarse solution differs from
/// the fine one by the discretization error, O(dx) at the contact edge (~1e-2 relative on
/// the coarse grids used here), so converging it below ~1e-3 buys nothing. Measured on the
/// paper's case at 1024^2 (bench/README.md): 1e-3 costs 2-7 iterations per coarse level and
/// the fine iteration takes 126 iterations; 1e-6 costs 21-36 per level for 121 fine ones.
const COARSE_TOLERANCE: f64 = 1e-3;

/// A coarse-grid start: the interpolated pressure (Pa, on the fine grid) and the CG
/// iterations of each coarse level, `(side, iterations)`, finest first.
pub type CoarseStart = (Vec<f64>, Vec<(usize, usize)>);

/// The coarse-grid start: the pressure on `problem`'s grid interpolated from the solution on
/// the grid coarsened by 2 (itself started the same way), with the CG iterations of each
/// coarse level (finest first); `None` where the grid cannot be coarsened (an odd side, or
/// a coarse side below [`MIN_COARSE_SIDE`]) or the coarse solve fails (no contact on the
/// coarse grid, contact reaching its border, no convergence): the caller then starts cold.
pub fn coarse_grid_start(
    problem: &NormalContactProblem<'_>,
    params: &NormalContactParams,
) -> Option<CoarseStart> {
    coarse_grid_start_on(problem, params, None)
}

/// [`coarse_grid_start`] for the non-periodic operator (`periodic` = `None`) or the
/// periodic one of the given kernel ([`normal_compliance_operator_periodic`]): the coarse
/// grid has the same window, so on a periodic grid the same period, and the coarse
/// problems are solved on the same kind of operator as the fine one.
pub fn coarse_grid_start_on(
    problem: &NormalContactProblem<'_>,
    params: &NormalContactParams,
    periodic: Option<PeriodicKernel>,
) -> Option<CoarseStart> {
    let grid = problem.grid;
    let (nx, ny) = (grid.nx(), grid.ny());
    if !nx.is_multiple_of(2)
        || !ny.is_multiple_of(2)
        || nx / 2 < MIN_COARSE_SIDE
        || ny / 2 < MIN_COARSE_SIDE
    {
        return None;
    }
    let (cx, cy) = (nx / 2, ny / 2);
    let (hx, hy) = grid.half_widths();
    let coarse_grid = SurfaceGrid::centred(cx, cy, hx, hy).ok()?;
    let h = problem.initial_gap;
    let coarse_gap: Vec<f64> = (0..cx * cy)
        .map(|k| {
            let (ix, iy) = (2 * (k % cx), 2 * (k / cx));
            0.25 * (h[iy * nx + ix]
                + h[iy * nx + ix + 1]
                + h[(iy + 1) * nx + ix]
                + h[(iy + 1) * nx + ix + 1])
        })
        .collect();
    let coarse_problem = NormalContactProblem {
        grid: &coarse_grid,
        initial_gap: &coarse_gap,
        ..*problem
    };
    let coarse_params = NormalContactParams {
        tolerance: params.tolerance.max(COARSE_TOLERANCE),
        ..*params
    };
    // The next level down first (recursion depth log2(n / MIN_COARSE_SIDE)).
    let (start, mut levels) = match coarse_grid_start_on(&coarse_problem, &coarse_params, periodic)
    {
        Some((p, levels)) => (Some(p), levels),
        None => (None, Vec::new()),
    };
    let operator = match periodic {
        None => normal_compliance_operator(&coarse_grid, problem.composite_modulus),
        Some(kernel) => {
            normal_compliance_operator_periodic(&coarse_grid, problem.composite_modulus, kernel)
        }
    };
    let solution = solve_normal_from(
        &coarse_problem,
        &coarse_params,
        Some(&operator),
        start.as_deref(),
        None,
    )
    .ok()?;
    levels.insert(0, (cx, solution.iterations));
    Some((prolong(&solution.pressure, cx, cy), levels))
}

/// Bilinear interpolation of a cell-centred field from a `cx x cy` grid to the grid refined
/// by 2 (fine centre `2k` lies a quarter coarse element before coarse centre `k`, `2k + 1`
/// a quarter after: weights 3/4 and 1/4 along each axis, the outer neighbour clamped at the
/// border). A convex combination, so p >= 0 stays; each coarse value's weights sum to 4
/// fine elements of a quarter of its area, so the load sum p dA is kept exactly.
fn prolong(coarse: &[f64], cx: usize, cy: usize) -> Vec<f64> {
    let (nx, ny) = (2 * cx, 2 * cy);
    // The two coarse indices and the weight of the first along one axis, for fine index i.
    let axis = |i: usize, n: usize| -> (usize, usize) {
        let k = i / 2;
        let other = if i.is_multiple_of(2) {
            k.saturating_sub(1)
        } else {
            (k + 1).min(n - 1)
        };
        (k, other)
    };
    let mut fine = vec![0.0; nx * ny];
    for iy in 0..ny {
        let (ky, oy) = axis(iy, cy);
        for ix in 0..nx {
            let (kx, ox) = axis(ix, cx);
            fine[iy * nx + ix] = 0.5625 * coarse[ky * cx + kx]
                + 0.1875 * (coarse[ky * cx + ox] + coarse[oy * cx + kx])
                + 0.0625 * coarse[oy * cx + ox];
        }
    }
    fine
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solvers::normal::{solve_normal, NormalLoading};

    /// The coarse-grid start changes the start, not the solution: a Hertz-like point contact
    /// (h = 50 x^2 + 60 y^2, 2000 N, E* = 1.1044e11 Pa, the paper's case) on 128^2 solved
    /// cold and from the 64^2 solution agree to the tolerance, under both loadings.
    #[test]
    fn coarse_start_gives_the_cold_solution_in_fewer_iterations() {
        let a = 5.2964e-4;
        let grid = SurfaceGrid::centred(128, 128, 1.5 * a, 1.5 * a).unwrap();
        let gap = grid.sample(|x, y| 50.0 * x * x + 60.0 * y * y);
        let cold = NormalContactParams::default().with_coarse_start(false);
        let warm = NormalContactParams::default();
        assert!(warm.coarse_start, "on by default");
        // The approach of the force-controlled solution, for the approach-controlled pair.
        let mut approach = 0.0;
        for loading in [NormalLoading::Force(2000.0), NormalLoading::Approach(0.0)] {
            let loading = match loading {
                NormalLoading::Approach(_) => NormalLoading::Approach(approach),
                other => other,
            };
            let problem = NormalContactProblem {
                grid: &grid,
                initial_gap: &gap,
                composite_modulus: 1.1044e11,
                loading,
            };
            let (levels_pressure, levels) = coarse_grid_start(&problem, &warm).unwrap();
            assert_eq!(levels.len(), 1, "128 -> 64 only: {levels:?}");
            assert_eq!(levels_pressure.len(), grid.len());
            let a = solve_normal(&problem, &cold, None, None).unwrap();
            let b = solve_normal(&problem, &warm, None, None).unwrap();
            approach = a.approach;
            let p_max = a.max_pressure();
            let dp = a
                .pressure
                .iter()
                .zip(&b.pressure)
                .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
                / p_max;
            // Both meet the min-map residual 1e-10 (pressure in units of p_max, gap in units
            // of u_max); the complementarity problem is well conditioned on the contact set
            // at this size (K's condition number ~ n = 128), so the two pressures can differ
            // by ~1e2 x 1e-10 relative; 1e-7 leaves a margin of 1e3 and still fails if the
            // warm solve stopped on anything looser than ~1e-7.
            assert!(dp <= 1e-7, "{loading:?}: max |dp| / p_max = {dp:e}");
            assert!(
                (a.approach / b.approach - 1.0).abs() <= 1e-8,
                "{loading:?}: approach {} vs {}",
                a.approach,
                b.approach
            );
            assert_eq!(a.contact_elements, b.contact_elements, "{loading:?}");
            assert!(
                b.iterations < a.iterations,
                "{loading:?}: {} fine iterations from the coarse start, {} cold",
                b.iterations,
                a.iterations
            );
        }
    }

    /// Odd sides and small grids start cold.
    #[test]
    fn grids_that_do_not_coarsen_start_cold() {
        for (nx, ny) in [(129, 128), (128, 127), (64, 64), (128, 100)] {
            let grid = SurfaceGrid::centred(nx, ny, 1e-3, 1e-3).unwrap();
            let gap = grid.sample(|x, y| 50.0 * x * x + 60.0 * y * y);
            let problem = NormalContactProblem {
                grid: &grid,
                initial_gap: &gap,
                composite_modulus: 1.1044e11,
                loading: NormalLoading::Force(2000.0),
            };
            assert!(
                coarse_grid_start(&problem, &NormalContactParams::default()).is_none(),
                "{nx} x {ny}"
            );
        }
    }

    #[test]
    fn prolongation_keeps_the_load_and_the_sign_and_is_exact_on_linear_fields() {
        let (cx, cy) = (6, 4);
        let coarse: Vec<f64> = (0..cx * cy).map(|k| ((k * 37) % 11) as f64).collect();
        let fine = prolong(&coarse, cx, cy);
        // Load: sum over the fine grid (element area 1/4) = sum over the coarse grid.
        let (sc, sf): (f64, f64) = (coarse.iter().sum(), fine.iter().sum());
        assert!((0.25 * sf - sc).abs() <= 1e-12 * sc, "{sf} {sc}");
        assert!(fine.iter().all(|&v| v >= 0.0));
        // Interior of a linear field a + b x + c y: bilinear interpolation is exact.
        let lin = |x: f64, y: f64| 1.0 + 2.0 * x - 3.0 * y;
        let coarse: Vec<f64> = (0..cx * cy)
            .map(|k| lin((k % cx) as f64 + 0.5, (k / cx) as f64 + 0.5))
            .collect();
        let fine = prolong(&coarse, cx, cy);
        for iy in 1..2 * cy - 1 {
            for ix in 1..2 * cx - 1 {
                let want = lin((ix as f64 + 0.5) / 2.0, (iy as f64 + 0.5) / 2.0);
                let got = fine[iy * 2 * cx + ix];
                assert!((got - want).abs() <= 1e-12, "({ix}, {iy}): {got} vs {want}");
            }
        }
    }
}
