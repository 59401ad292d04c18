//! The input work of linear runs against the 1D column's closed form
//! (docs/theory/DYNAMICS.md sec. 3.1).

use super::*;
use crate::dynamics::cq::{convolve, CqGrid, CqMethod, CqParams};
use crate::kernels::kelvin2d::PlaneCondition;
use crate::material::ElasticMaterial;
use crate::operators::bem2d::{BemModel, Region, Segment};
use crate::solvers::bem2d::{BoundaryConditions, Profile, SegmentBc};

/// Column L = 1 x A = 0.25 (per unit thickness), E = 1, nu = 0, rho = 1 (c = 1): 16 x 2
/// quadratic elements, p0 = 1 on x = 0, rollers at x = L (the time tests' model).
fn column() -> LaplaceBem {
    let m = ElasticMaterial::new(1.0, 0.0).unwrap();
    let (l, w, nx, ny) = (1.0, 0.25, 16, 2);
    let model = BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "column",
            m,
            vec![
                Segment::line("bottom", [0.0, 0.0], [l, 0.0], nx),
                Segment::line("right", [l, 0.0], [l, w], ny),
                Segment::line("top", [l, w], [0.0, w], nx),
                Segment::line("left", [0.0, w], [0.0, 0.0], ny),
            ],
        )],
    );
    let bcs = BoundaryConditions::new()
        .set(
            "left",
            SegmentBc::traction(Profile::Uniform(1.0), Profile::Uniform(0.0)),
        )
        .set("right", SegmentBc::roller_x());
    LaplaceBem::new(&model, &[1.0], &bcs, &[]).unwrap()
}

/// u_x(0, t) of the column under p0 H(t) (p0 = E = c = L = 1): the triangle wave of
/// docs/theory/DYNAMICS.md 3.1, t for t < 2, 4 - t for 2 < t < 4, period 4.
fn end_displacement(t: f64) -> f64 {
    let t = t.rem_euclid(4.0);
    if t < 2.0 {
        t
    } else {
        4.0 - t
    }
}

/// The input work of the column under the sudden pressure: W(t) = p0 A u(0, t) (a dead
/// load's work; = p0^2 A c t/E = 0.25 t before the reflection returns at 2 L/c, and the
/// strain plus kinetic energy of the exact solution at all times). Max |W - exact| over
/// all steps to 4 L/c relative to the peak W = 0.5 at 80, 160, 320 BDF2 steps: 5.98e-2,
/// 3.53e-2, 2.11e-2 (ratios 1.69, 1.67: order ~0.75 as the displacements of the time tests,
/// the step's start and the kink of u(0, t) at 2 L/c smeared by CQ). Asserted: below 2.5 %
/// at 320 steps and falling by 1.45x per halving (a wrong sign, factor or time rule is O(1)
/// or does not fall).
#[test]
fn column_input_work_is_the_dead_load_work() {
    let bem = column();
    let mut errors = vec![];
    for steps in [80, 160, 320] {
        let dt = 4.0 / steps as f64;
        let grid = CqGrid::new(CqMethod::Bdf2, dt, steps).unwrap();
        let pattern = bem.static_known_values().to_vec();
        let data: Vec<f64> = grid
            .sample_times()
            .iter()
            .flat_map(|_| pattern.iter().copied())
            .collect();
        let series = convolve(&bem, &grid, &data, &CqParams::default()).unwrap();
        let work = input_work(&bem, &data, &series).unwrap();
        assert_eq!(work.len(), steps + 1);
        assert_eq!(work[0], 0.0);
        let mut err = 0.0_f64;
        for (n, w) in work.iter().enumerate() {
            let t = n as f64 * dt;
            err = err.max((w - 0.25 * end_displacement(t)).abs());
        }
        errors.push(err / 0.5);
        let samples = energy_samples(&work);
        assert_eq!(samples[steps].input_work, Some(work[steps]));
        assert!(samples[steps].kinetic_energy.is_none());
    }
    eprintln!("column input work: errors {errors:?} of the peak");
    assert!(errors[2] < 0.025, "{errors:?}");
    for pair in errors.windows(2) {
        assert!(pair[1] < pair[0] / 1.45, "{errors:?}");
    }
}

/// The boundary form integrates exactly: oint 1 . 1 dG over a constant field is the
/// perimeter (2 (L + A) = 2.5), and the trapezoid rule of a constant traction gives the
/// dead-load work p . u_n whatever the path.
#[test]
fn boundary_form_and_trapezoid_are_exact_where_they_should_be() {
    let bem = column();
    let form = BoundaryForm::new(&bem);
    let nodes = bem.static_problem().mesh.regions[0].nodes.len();
    let ones = vec![vec![[1.0, 0.0]; nodes]];
    let perimeter = form.apply(&ones, &ones).unwrap();
    assert!((perimeter - 2.5).abs() < 1e-13, "{perimeter}");
    // u_n = n^2 (0.1, 0.2) everywhere, t = (1, -1): W_n = oint t . u_n = -0.1 n^2 * 2.5.
    let fields: Vec<BoundaryFields> = (0..5)
        .map(|n| {
            let q = (n * n) as f64;
            BoundaryFields {
                displacement: vec![vec![[0.1 * q, 0.2 * q]; nodes]],
                traction: vec![vec![[1.0, -1.0]; nodes]],
            }
        })
        .collect();
    let work = input_work_of_fields(&form, &fields).unwrap();
    for (n, w) in work.iter().enumerate() {
        let exact = -0.1 * (n * n) as f64 * 2.5;
        assert!((w - exact).abs() < 1e-12, "{n}: {w} vs {exact}");
    }
    assert!(form.apply(&ones, &[]).is_err());
}
