//! Normal contact: the verification table (every row group, the 2D BEM's included),
//! convergence under refinement, and the errors a solver must raise. Every number asserted here has its reference and tolerance stated in
//! `tribo::validation` (one source for `tribo validate` and the tests).
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    reason = "tests: a panic is a failed test"
)]

use tribo::kernels::hertz::{GapCurvature, HertzContact};
use tribo::solvers::normal::*;
use tribo::solvers::SolveError;
use tribo::validation::{self, ValidationRow};
use tribo::{Error, SurfaceGrid};

fn assert_rows(rows: &[ValidationRow]) {
    let failed: Vec<_> = rows.iter().filter(|r| !r.passed).collect();
    assert!(failed.is_empty(), "failed rows: {failed:#?}");
}

#[test]
fn kernel_rows_pass() {
    assert_rows(&validation::kernel_rows().unwrap());
}

#[test]
fn operator_rows_pass() {
    assert_rows(&validation::operator_rows().unwrap());
}

#[test]
fn paper_case_rows_pass() {
    let rows = validation::paper_case_rows().unwrap();
    assert_rows(&rows);
    // The independent implementation of docs/theory/HALFSPACE.md 4 gets eps_avg = 3.7e-3 at 21x21 with
    // 147 elements in contact; ours must agree to the digits quoted.
    let eps_avg = rows
        .iter()
        .find(|r| r.quantity == "eps_avg (17)")
        .unwrap()
        .computed;
    assert!((eps_avg - 3.7e-3).abs() < 0.05e-3, "{eps_avg}");
}

#[test]
fn convergence_rows_pass_and_errors_fall_at_every_level() {
    assert_rows(&validation::convergence_rows().unwrap());
    let levels = validation::paper_case_convergence(&[21, 41, 81, 161]).unwrap();
    for pair in levels.windows(2) {
        assert!(pair[1].eps_avg < pair[0].eps_avg, "{pair:?}");
        assert!(pair[1].approach_error < pair[0].approach_error, "{pair:?}");
        assert!(pair[1].area_error < pair[0].area_error, "{pair:?}");
    }
}

#[test]
fn hertz_family_rows_pass() {
    assert_rows(&validation::hertz_family_rows().unwrap());
}

fn paper_problem(n: usize, extent: f64) -> (SurfaceGrid, Vec<f64>, f64, HertzContact) {
    let (curvature, e_star) = validation::paper_case_curvature().unwrap();
    let hertz = HertzContact::from_load(&curvature, e_star, 2000.0).unwrap();
    let half = extent * hertz.semi_major;
    let grid = SurfaceGrid::centred(n, n, half, half).unwrap();
    let gap = grid.sample(|x, y| curvature.gap(x, y));
    (grid, gap, e_star, hertz)
}

#[test]
fn solvers_agree_under_approach_control_and_complementarity_holds() {
    let (grid, gap, e_star, _) = paper_problem(25, 1.5);
    let problem = NormalContactProblem {
        grid: &grid,
        initial_gap: &gap,
        composite_modulus: e_star,
        loading: NormalLoading::Approach(2.723e-5),
    };
    let params = NormalContactParams::default();
    let cg = solve_normal(&problem, &params, None, None).unwrap();
    let dense = solve_normal(
        &problem,
        &params.with_method(NormalMethod::ActiveSet),
        None,
        None,
    )
    .unwrap();
    let p0 = cg.max_pressure();
    for (a, b) in cg.pressure.iter().zip(&dense.pressure) {
        // Both at residual <= 1e-10; the pressures agree to ~10x that.
        assert!((a - b).abs() <= 1e-8 * p0);
    }
    assert_eq!(cg.contact_elements, dense.contact_elements);
    // Complementarity on the returned fields: p >= 0; gap >= -tol u_max; gap ~ 0 in contact.
    let u_scale = 2.723e-5;
    for (&p, &g) in cg.pressure.iter().zip(&cg.gap) {
        assert!(p >= 0.0);
        assert!(g >= -1e-9 * u_scale);
        if p > 0.0 {
            assert!(g.abs() <= 1e-9 * u_scale);
        }
    }
}

#[test]
fn serial_equals_parallel() {
    // The FFT path splits rows and columns over threads; each output is computed by the same
    // arithmetic regardless of the split, so one thread and two give identical bits.
    let (grid, gap, e_star, _) = paper_problem(48, 1.5);
    let problem = NormalContactProblem {
        grid: &grid,
        initial_gap: &gap,
        composite_modulus: e_star,
        loading: NormalLoading::Force(2000.0),
    };
    let params = NormalContactParams::default();
    let serial = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let parallel = rayon::ThreadPoolBuilder::new()
        .num_threads(3)
        .build()
        .unwrap();
    let a = serial.install(|| solve_normal(&problem, &params, None, None).unwrap());
    let b = parallel.install(|| solve_normal(&problem, &params, None, None).unwrap());
    assert_eq!(a.pressure, b.pressure);
    assert_eq!(a.iterations, b.iterations);
}

#[test]
fn a_window_the_contact_reaches_is_refused() {
    let (grid, gap, e_star, _) = paper_problem(21, 0.8);
    let problem = NormalContactProblem {
        grid: &grid,
        initial_gap: &gap,
        composite_modulus: e_star,
        loading: NormalLoading::Force(2000.0),
    };
    for method in [NormalMethod::ConjugateGradient, NormalMethod::ActiveSet] {
        let params = NormalContactParams::default().with_method(method);
        match solve_normal(&problem, &params, None, None) {
            // The refused solution comes with the error: converged, carrying the load, and
            // in contact on the window's border.
            Err(SolveError {
                kind: Error::ContactReachesWindow { .. },
                output: Some(refused),
            }) => {
                assert!(refused.residual <= params.tolerance, "{}", refused.residual);
                assert!((refused.normal_load / 2000.0 - 1.0).abs() < 1e-9);
                assert!(refused.pressure[grid.index(0, grid.ny() / 2)] > 0.0);
            }
            other => panic!("expected ContactReachesWindow, got {other:?}"),
        }
    }
}

#[test]
fn an_approach_without_contact_is_refused() {
    let (grid, gap, e_star, _) = paper_problem(21, 1.5);
    for approach in [-1e-6, 0.0] {
        let problem = NormalContactProblem {
            grid: &grid,
            initial_gap: &gap,
            composite_modulus: e_star,
            loading: NormalLoading::Approach(approach),
        };
        assert!(matches!(
            solve_normal(&problem, &NormalContactParams::default(), None, None),
            Err(SolveError {
                kind: Error::NoContact { .. },
                ..
            })
        ));
    }
}

#[test]
fn bad_loads_name_the_field() {
    let (grid, gap, e_star, _) = paper_problem(21, 1.5);
    for (loading, field) in [
        (NormalLoading::Force(0.0), "contact.load"),
        (NormalLoading::Force(-5.0), "contact.load"),
        (NormalLoading::Force(f64::NAN), "contact.load"),
        (NormalLoading::Approach(f64::INFINITY), "contact.approach"),
    ] {
        let problem = NormalContactProblem {
            grid: &grid,
            initial_gap: &gap,
            composite_modulus: e_star,
            loading,
        };
        match solve_normal(&problem, &NormalContactParams::default(), None, None) {
            Err(SolveError {
                kind: Error::InvalidParameter { field: f, .. },
                output: None,
            }) => assert_eq!(f, field),
            other => panic!("expected InvalidParameter({field}), got {other:?}"),
        }
    }
    let short = vec![0.0; 10];
    let problem = NormalContactProblem {
        grid: &grid,
        initial_gap: &short,
        composite_modulus: e_star,
        loading: NormalLoading::Force(1.0),
    };
    assert!(matches!(
        solve_normal(&problem, &NormalContactParams::default(), None, None),
        Err(SolveError {
            kind: Error::InvalidParameter { .. },
            ..
        })
    ));
}

/// A solve stopped by `max_iterations` returns the last iterate with the error: its
/// `residual` is the one reported (above the tolerance), its `iterations` the limit, p >= 0
/// (the projection; the active set drops its negative pressures). The CG's iterate carries
/// the load (it rescales the pressure to the load after every step, so to the sum's
/// round-off, 1e-12), and its observer saw every iteration, the reported residual last. (The
/// active set's first sweep, all elements active, has negative pressures: its partial is
/// that sweep with them dropped, which carries more than the load.)
#[test]
fn stopping_early_returns_the_partial_solution_with_its_residual() {
    let (grid, gap, e_star, _) = paper_problem(41, 1.5);
    let problem = NormalContactProblem {
        grid: &grid,
        initial_gap: &gap,
        composite_modulus: e_star,
        loading: NormalLoading::Force(2000.0),
    };
    for method in [NormalMethod::ConjugateGradient, NormalMethod::ActiveSet] {
        let params = NormalContactParams::new(1e-10, 1)
            .unwrap()
            .with_method(method);
        let mut seen = Vec::new();
        let result = solve_normal(
            &problem,
            &params,
            None,
            Some(&mut |k: usize, r: f64| seen.push((k, r))),
        );
        let Err(SolveError {
            kind:
                Error::NotConverged {
                    iterations,
                    residual,
                    tolerance,
                    ..
                },
            output: Some(partial),
        }) = result
        else {
            panic!("{method:?}: expected NotConverged with a partial solution, got {result:?}");
        };
        assert_eq!(iterations, 1, "{method:?}");
        assert!(
            residual > tolerance && residual.is_finite(),
            "{method:?}: {residual}"
        );
        assert_eq!(partial.residual, residual, "{method:?}");
        assert_eq!(partial.iterations, 1, "{method:?}");
        assert_eq!(partial.pressure.len(), grid.len());
        assert!(partial.pressure.iter().all(|&p| p >= 0.0), "{method:?}");
        assert!(partial.contact_elements > 0, "{method:?}");
        if method == NormalMethod::ConjugateGradient {
            assert!(
                (partial.normal_load / 2000.0 - 1.0).abs() < 1e-12,
                "{}",
                partial.normal_load
            );
            assert_eq!(seen.iter().map(|s| s.0).collect::<Vec<_>>(), [0, 1]);
            assert_eq!(seen.last().map(|s| s.1), Some(residual));
        }
        // `?` into tribo::Error keeps the message (the CLI's exit 3 line).
        let message = tribo::Error::from(SolveError::with_output(
            Error::NotConverged {
                solver: "s",
                iterations,
                residual,
                tolerance,
            },
            *partial,
        ))
        .to_string();
        assert!(message.contains("did not converge: residual"), "{message}");
    }
}

/// A prebuilt operator gives the same solution bit for bit; one for another grid or another
/// E* is refused, naming the operator.
#[test]
fn a_prebuilt_operator_is_used_and_checked() {
    let (grid, gap, e_star, _) = paper_problem(21, 1.5);
    let problem = NormalContactProblem {
        grid: &grid,
        initial_gap: &gap,
        composite_modulus: e_star,
        loading: NormalLoading::Force(2000.0),
    };
    let params = NormalContactParams::default();
    let own = solve_normal(&problem, &params, None, None).unwrap();
    let operator = normal_compliance_operator(&grid, e_star);
    let reused = solve_normal(&problem, &params, Some(&operator), None).unwrap();
    assert_eq!(own, reused);
    let other_modulus = normal_compliance_operator(&grid, 2.0 * e_star);
    let other_grid = normal_compliance_operator(
        &SurfaceGrid::centred(21, 20, grid.half_widths().0, grid.half_widths().1).unwrap(),
        e_star,
    );
    for wrong in [&other_modulus, &other_grid] {
        match solve_normal(&problem, &params, Some(wrong), None) {
            Err(SolveError {
                kind: Error::InvalidParameter { field, .. },
                ..
            }) => assert_eq!(field, "operator"),
            other => panic!("expected InvalidParameter(operator), got {other:?}"),
        }
    }
}

/// Params are checked by their constructor and setters, and by the solver on entry.
#[test]
fn params_keep_their_rules() {
    assert!(NormalContactParams::new(1e-8, 100).is_ok());
    for (tolerance, iterations) in [(0.0, 10), (1.0, 10), (f64::NAN, 10), (1e-8, 0)] {
        assert!(NormalContactParams::new(tolerance, iterations).is_err());
    }
    let params = NormalContactParams::default();
    assert!(params.with_tolerance(-1.0).is_err());
    assert!(params.with_max_iterations(0).is_err());
    assert_eq!(
        params.with_tolerance(1e-9).unwrap().tolerance,
        1e-9,
        "the setter sets"
    );
}

#[test]
fn curvature_from_radii_refuses_flat_pairs() {
    assert!(GapCurvature::from_radii([f64::INFINITY; 2], [f64::INFINITY; 2], 0.0).is_err());
    assert!(GapCurvature::from_radii([0.0, 0.01], [0.01, 0.01], 0.0).is_err());
}

#[test]
fn back_effect_rows_pass() {
    assert_rows(&validation::back_effect_rows().unwrap());
}

#[test]
fn back_effect_curve_is_monotone_and_passes_through_one() {
    // Compression raises the force, tension lowers it, monotonically; sigma = 0 gives 1.
    let ratios = [-1.0, -0.5, 0.0, 0.5, 1.0];
    let points = validation::back_effect_points(&ratios).unwrap();
    for kind in points.chunks(ratios.len()) {
        assert!((kind[2].force_ratio - 1.0).abs() < 1e-12);
        for pair in kind.windows(2) {
            assert!(pair[1].force_ratio < pair[0].force_ratio, "{pair:?}");
        }
    }
}

#[test]
fn stress_rows_pass() {
    assert_rows(&validation::stress_rows().unwrap());
}

#[test]
fn tangential_rows_pass() {
    assert_rows(&validation::tangential_rows().unwrap());
}

#[test]
fn damage_rows_pass() {
    let rows = validation::damage_rows().unwrap();
    assert_eq!(rows.len(), 4);
    assert_rows(&rows);
}

#[test]
fn coupled_rows_pass() {
    let rows = validation::coupled_rows().unwrap();
    assert_eq!(rows.len(), 4);
    assert_rows(&rows);
}

/// The free-direction partial-slip solver near gross slip against the dense block
/// Gauss-Seidel (issue 11 item 10).
#[test]
fn free_direction_rows_pass() {
    let rows = validation::free_direction_rows().unwrap();
    assert_eq!(rows.len(), 4);
    assert_rows(&rows);
}

#[test]
fn sliding_sphere_rows_pass() {
    assert_rows(&validation::sliding_sphere_rows().unwrap());
}

/// The 2D boundary element rows (Lame, Kirsch, cantilever, compound cylinder, rotating
/// annulus, 2D Hertz, flat punch, Cattaneo-Mindlin, Nowell-Hills, the graded patch far from
/// the origin).
#[test]
fn bem2d_rows_pass() {
    let rows = validation::bem2d_rows().unwrap();
    assert_eq!(rows.len(), 19);
    assert_rows(&rows);
}

/// Issue 11 item 1: the sliding sphere at the surface and below, whatever the alignment of
/// the field points with the element edges (piecewise-constant shear gave 1.04 p0 and
/// 1.74-1.86 p0 for the largest von Mises at f = 0.2 and 0.4 on the edges).
#[test]
fn sliding_sphere_surface_rows_pass() {
    let rows = validation::sliding_sphere_surface_rows().unwrap();
    assert_eq!(rows.len(), 45);
    for r in &rows {
        eprintln!(
            "{} | {}: {:.4e} (ref {:.4})",
            r.case, r.quantity, r.error, r.reference
        );
    }
    assert_rows(&rows);
}

/// Issue 11 item 1, the surface lines through the contact edge with the edge-aware
/// tractions: six rows (f = 0 ... 0.5, element-averaged Hertz), the solved contact on the
/// lines and on the whole square (within 5e-2 p0: the off-line gap), the
/// direct sum at the edges; the line rows within 2e-2 p0 of Hamilton.
#[test]
fn sliding_sphere_edge_rows_pass() {
    let rows = validation::sliding_sphere_edge_rows().unwrap();
    assert_eq!(rows.len(), 9);
    for r in &rows {
        eprintln!("{} | {}: {:.4e}", r.case, r.quantity, r.computed);
    }
    assert_rows(&rows);
}
