//! Warm starts of the normal solver ([`tribo::solvers::normal::solve_normal_from`]): started
//! from a nearby solution it reaches the same solution (to the tolerance) in fewer
//! iterations; bad guesses are refused naming `initial_pressure`.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    reason = "tests: a panic is a failed test"
)]

use tribo::solvers::normal::*;
use tribo::SurfaceGrid;

/// A sphere (R = 10 mm) on a flat, E* = 115 GPa, on 64 x 64 elements over 1 mm.
fn sphere() -> (SurfaceGrid, Vec<f64>) {
    let grid = SurfaceGrid::centred(64, 64, 0.5e-3, 0.5e-3).unwrap();
    let gap = (0..grid.len())
        .map(|k| {
            let (x, y) = (grid.x(k % 64), grid.y(k / 64));
            (x * x + y * y) / (2.0 * 0.01)
        })
        .collect();
    (grid, gap)
}

fn solve(
    grid: &SurfaceGrid,
    gap: &[f64],
    loading: NormalLoading,
    guess: Option<&[f64]>,
) -> NormalContactSolution {
    let problem = NormalContactProblem {
        grid,
        initial_gap: gap,
        composite_modulus: 115e9,
        loading,
    };
    solve_normal_from(&problem, &NormalContactParams::default(), None, guess, None).unwrap()
}

/// Both solutions satisfy the complementarity conditions to the tolerance 1e-10 (relative to
/// p_max), so they differ by at most a few times that in pressure; 1e-8 p_max leaves room for
/// the conditioning of the contact edge and fails for any other solution (the next load step
/// differs by 1 % of p_max).
fn assert_same(a: &NormalContactSolution, b: &NormalContactSolution) {
    let scale = a.max_pressure();
    let worst = a
        .pressure
        .iter()
        .zip(&b.pressure)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(worst <= 1e-8 * scale, "{worst:e} vs p_max {scale:e}");
    assert_eq!(a.contact_elements, b.contact_elements);
}

#[test]
fn a_warm_start_reaches_the_same_solution_in_fewer_iterations() {
    let (grid, gap) = sphere();
    let first = solve(&grid, &gap, NormalLoading::Force(100.0), None);
    // Force control: the next load step (2 %) from the last solution. Measured with the
    // Python API on this kind of grid: about half the iterations (a 10 % step saves none:
    // the guess's contact area is too far off).
    let cold = solve(&grid, &gap, NormalLoading::Force(102.0), None);
    let warm = solve(
        &grid,
        &gap,
        NormalLoading::Force(102.0),
        Some(&first.pressure),
    );
    assert_same(&cold, &warm);
    assert!(
        warm.iterations < cold.iterations,
        "warm {} vs cold {}",
        warm.iterations,
        cold.iterations
    );
    // Approach control: from the solution at the same approach, slightly perturbed.
    let cold = solve(&grid, &gap, NormalLoading::Approach(first.approach), None);
    let guess: Vec<f64> = first.pressure.iter().map(|p| 1.001 * p).collect();
    let warm = solve(
        &grid,
        &gap,
        NormalLoading::Approach(first.approach),
        Some(&guess),
    );
    assert_same(&cold, &warm);
    assert!(
        warm.iterations < cold.iterations,
        "warm {} vs cold {}",
        warm.iterations,
        cold.iterations
    );
    // A guess carrying no load starts as a cold solve does: the same iterations.
    let zero = vec![0.0; grid.len()];
    let from_zero = solve(&grid, &gap, NormalLoading::Force(100.0), Some(&zero));
    assert_eq!(from_zero.iterations, first.iterations);
    assert_eq!(from_zero.pressure, first.pressure);
}

#[test]
fn bad_guesses_are_refused_naming_the_argument() {
    let (grid, gap) = sphere();
    let problem = NormalContactProblem {
        grid: &grid,
        initial_gap: &gap,
        composite_modulus: 115e9,
        loading: NormalLoading::Force(100.0),
    };
    let params = NormalContactParams::default();
    for guess in [vec![1.0; 10], {
        let mut g = vec![1.0; grid.len()];
        g[7] = f64::NAN;
        g
    }] {
        let e = solve_normal_from(&problem, &params, None, Some(&guess), None).unwrap_err();
        assert!(
            e.kind.to_string().contains("initial_pressure"),
            "{}",
            e.kind
        );
    }
}

/// A start with the whole load on one element while its neighbours overlap: under force
/// control the mean-free conjugate direction on a one-element contact set is zero, so the
/// conjugate gradient alone cannot move load (it stopped with "non-positive curvature 0",
/// the state of a rough surface's first small load step, where one asperity carries all).
/// The solver's Jacobi re-entry step restarts it; it must reach the cold start's solution
/// (the same discrete problem, so `assert_same`'s 1e-8 p_max).
#[test]
fn a_start_on_one_element_with_overlapping_neighbours_reaches_the_solution() {
    let (grid, gap) = sphere();
    let cold = solve(&grid, &gap, NormalLoading::Force(100.0), None);
    let centre = 32 * 64 + 32;
    let mut guess = vec![0.0; grid.len()];
    guess[centre] = 1.0;
    let warm = solve(&grid, &gap, NormalLoading::Force(100.0), Some(&guess));
    assert_same(&cold, &warm);
    assert!(warm.contact_elements > 100, "{}", warm.contact_elements);
}

/// Flat on flat, periodic: the uniform pressure p_mean is the exact solution (the gap is
/// zero everywhere), and on a periodic grid it carries no elastic displacement (the zero
/// mode), so the residual's displacement scale falls back to the heights' (module docs of
/// the solver). It must be returned at once, to round-off, by either kernel; before, the
/// undefined scale kept the residual infinite and the iteration stopped on a zero curvature.
#[test]
fn flat_on_flat_periodic_gives_the_uniform_pressure() {
    use tribo::kernels::periodic::PeriodicKernel;
    let grid = SurfaceGrid::centred(32, 32, 50e-6, 50e-6).unwrap();
    let (lx, ly) = (100e-6, 100e-6);
    let p_mean = 1.0e8;
    let gap = vec![0.0; grid.len()];
    for kernel in [PeriodicKernel::ElementIntegrated, PeriodicKernel::Spectral] {
        let operator = normal_compliance_operator_periodic(&grid, 115e9, kernel);
        let problem = NormalContactProblem {
            grid: &grid,
            initial_gap: &gap,
            composite_modulus: 115e9,
            loading: NormalLoading::Force(p_mean * lx * ly),
        };
        let solution = solve_normal_from(
            &problem,
            &NormalContactParams::default(),
            Some(&operator),
            None,
            None,
        )
        .unwrap();
        let worst = solution
            .pressure
            .iter()
            .map(|p| (p - p_mean).abs())
            .fold(0.0, f64::max);
        // Round-off of F / (n dA) and of the load scaling: a few ulps of p_mean.
        assert!(worst <= 1e-12 * p_mean, "{kernel:?}: {worst:e}");
        assert_eq!(solution.contact_elements, grid.len());
    }
}
