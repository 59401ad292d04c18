//! The whole chain LaplaceBem -> CQ on the cylindrical cavity (docs/theory/DYNAMICS.md 3.2):
//! convergence of the wall displacement in time (at each method's order, fixed mesh) and in
//! space (elements per circumference, fixed time grid), and the long times t c2/a = 5..20 of
//! the reference table on a ring too big for its echo to return.

use super::*;
use crate::dynamics::cq::{convolve, CqGrid, CqMethod, CqParams};
use crate::dynamics::testing::{CavityExact, CavityWall};

/// A C^3 load ramp from 0 to 1 over `t0` (the septic "smoothstep"
/// `x^4 (35 - 84 x + 70 x^2 - 20 x^3)`, x = t/t0, held at 1 after): its first three
/// derivatives vanish at both ends, so the response is smooth enough for every method's
/// full order (the (1 - cos)/2 ramp has a jump of f'' at its ends, which caps Radau IIA at
/// order 3 at best).
pub(crate) fn smooth_ramp(t: f64, t0: f64) -> f64 {
    let x = (t / t0).clamp(0.0, 1.0);
    x.powi(4) * (35.0 - 84.0 * x + 70.0 * x * x - 20.0 * x.powi(3))
}

/// The response's single output at the step times t_n = n dt, n = 0..=steps (0 at t = 0
/// for Runge-Kutta grids, whose samples start inside the first step), for the load
/// `f(t)` times the response's static pattern `pattern` (one value per input).
pub(crate) fn output_at_steps(
    response: &dyn LaplaceResponse,
    pattern: &[f64],
    method: CqMethod,
    dt: f64,
    steps: usize,
    f: &dyn Fn(f64) -> f64,
) -> Vec<f64> {
    let grid = CqGrid::new(method, dt, steps).unwrap();
    let mut data = Vec::new();
    for t in grid.sample_times() {
        let v = f(t);
        data.extend(pattern.iter().map(|p| p * v));
    }
    let series = convolve(response, &grid, &data, &CqParams::default()).unwrap();
    (0..=steps)
        .map(|n| series.at_step(n).map_or(0.0, |x| x[0]))
        .collect()
}

/// Max over the coarse step times of |coarse - fine| (fine has twice the steps), and the
/// step index of the max.
fn self_difference(coarse: &[f64], fine: &[f64]) -> (f64, usize) {
    coarse
        .iter()
        .enumerate()
        .map(|(n, c)| ((c - fine[2 * n]).abs(), n))
        .fold((0.0, 0), |a, b| if b.0 > a.0 { b } else { a })
}

/// Self-differences of the wall displacement for a ring, ramp and method at M, 2M, 4M
/// steps to `t_end`: (d1, d2, observed order), printed with where the max falls.
fn time_study(
    wall: &CavityWall,
    t0: f64,
    t_end: f64,
    method: CqMethod,
    m: usize,
) -> (f64, f64, f64) {
    let pattern = wall.bem.static_known_values().to_vec();
    let load = |t: f64| smooth_ramp(t, t0);
    let runs: Vec<Vec<f64>> = [m, 2 * m, 4 * m]
        .iter()
        .map(|&k| output_at_steps(wall, &pattern, method, t_end / k as f64, k, &load))
        .collect();
    let (d1, n1) = self_difference(&runs[0], &runs[1]);
    let (d2, n2) = self_difference(&runs[1], &runs[2]);
    let p = (d1 / d2).log2();
    eprintln!(
        "cavity time, {}, ramp {t0}, M = {m}..{}: self-differences {d1:.3e} (at t = {:.2}), {d2:.3e} (at t = {:.2}), order {p:.2}",
        method.name(),
        4 * m,
        n1 as f64 * t_end / m as f64,
        n2 as f64 * t_end / (2 * m) as f64,
    );
    (d1, d2, p)
}

/// Time convergence of the chain at a fixed mesh, by self-differences: the ring a = 1,
/// R = 2 (reflections from R included: the discrete model is the same at every dt), the
/// C^3 ramp over t0 = 2 a/c2, M = 15, 30, 60 steps to T = 3 a/c2 (dt = 0.2, 0.1, 0.05).
/// d(dt) = max_n |u_dt(t_n) - u_dt/2(t_n)| falls as dt^p, p the method's order (Lubich
/// 1988; Lubich & Ostermann 1993). Measured with 8 + 8 elements per half circle (outer +
/// hole; 4 + 8 gives the same to 3 digits): BDF1 3.83e-2, 2.07e-2 (order 0.89); BDF2
/// 2.26e-2, 6.73e-3 (1.75); Radau IIA 2 8.87e-4, 1.34e-4 (2.72): each approaching its
/// order from below (t0/dt = 10 to 40 is pre-asymptotic; a ramp over t0 = 1 to T = 2 gave
/// BDF1 0.56). Ignored: 430 s on two loaded cores;
/// [`cavity_wall_converges_in_time_at_the_methods_order`] is the cheap part.
#[test]
#[ignore]
fn cavity_time_study() {
    for (big, no, nh) in [(2.0, 8, 8), (2.0, 4, 8)] {
        let wall = CavityWall::new(1.0, big, no, nh);
        eprintln!("ring R = {big}, {no} + {nh} per half circle");
        for method in [CqMethod::Bdf1, CqMethod::Bdf2, CqMethod::RadauIia2] {
            time_study(&wall, 2.0, 3.0, method, 15);
        }
    }
}

/// The cheap part of [`cavity_time_study`]: BDF2 on the ring with 4 + 4 elements per half
/// circle (the time error does not depend on the mesh at these sizes, see there).
/// Measured: 2.260e-2, 6.729e-3, order 1.75 (Radau IIA 2 on the same ring: 8.858e-4,
/// 1.343e-4, order 2.72, in the ignored [`cavity_time_study_radau`]: together 200 s under
/// load). Asserted: the observed order within -0.35 .. +0.5 of 2: a first-order error
/// anywhere in the chain (a wrong weight or symbol, a sample-time shift) drops it to ~1.
#[test]
fn cavity_wall_converges_in_time_at_the_methods_order() {
    let wall = CavityWall::new(1.0, 2.0, 4, 4);
    let (_, _, p) = time_study(&wall, 2.0, 3.0, CqMethod::Bdf2, 15);
    assert!(p > 1.65 && p < 2.5, "bdf2: order {p:.2}");
}

/// Radau IIA 2 on the ring of [`cavity_wall_converges_in_time_at_the_methods_order`]
/// (ignored: 130 s under load). Asserted: the observed order within -0.35 .. +0.5 of 3.
#[test]
#[ignore]
fn cavity_time_study_radau() {
    let wall = CavityWall::new(1.0, 2.0, 4, 4);
    let (_, _, p) = time_study(&wall, 2.0, 3.0, CqMethod::RadauIia2, 15);
    assert!(p > 2.65 && p < 3.5, "radau_iia_2: order {p:.2}");
}

/// The spatial error of the chain on the cavity wall: the ring a = 1, R = 3 (8 elements
/// per half circle outside) with `n` quadratic elements per half circle on the hole, the
/// C^3 ramp over t0 = 1 a/c2, against the closed-form infinite-plane transfer function
/// convolved on the same grid ([`CavityExact`], BDF2, step `dt`): CQ is linear, so the
/// difference is CQ of (R_bem - R_exact), the spatial error alone (the time
/// discretisation error cancels). Max over the steps to t = 1.5 a/c2, well before the
/// reflection from R returns (2 (R - a)/c1 = 2.31 a/c2: BDF2 smears a delayed wave over a
/// few steps ahead of its arrival; up to t = 2 it showed at dt = 0.05).
fn cavity_space_error(n: usize, dt: f64) -> f64 {
    let (a, big, t_end) = (1.0, 3.0, 1.5);
    let load = |t: f64| smooth_ramp(t, 1.0);
    let wall = CavityWall::new(a, big, 8, n);
    let pattern = wall.bem.static_known_values().to_vec();
    let m = (t_end / dt).round() as usize;
    let bem = output_at_steps(&wall, &pattern, CqMethod::Bdf2, dt, m, &load);
    let exact = output_at_steps(&CavityExact(a), &[1.0], CqMethod::Bdf2, dt, m, &load);
    let e = bem
        .iter()
        .zip(&exact)
        .map(|(u, v)| (u - v).abs())
        .fold(0.0, f64::max);
    eprintln!(
        "cavity space: {n} elements per half circle, dt = {dt}: max |u_bem - u_exact| = {e:.3e} (u_r(a, 1.5) = {:.6})",
        exact[m]
    );
    e
}

/// Space convergence of the chain at a fixed time grid ([`cavity_space_error`]) with 4, 8,
/// 16 elements per half circle on the hole at dt = 0.1, and 4 at dt = 0.05 (dt does not
/// dominate: the coarse mesh's error is the same at half the step). Measured at dt = 0.05:
/// 4.154e-4, 2.752e-5, 1.783e-6 (ratios 15.1, 15.4: h^4, one order above the quadratic
/// elements' h^3 of the nodal values, tests.rs: the wall's mean u_r superconverges), and
/// 4.153e-4 at n = 4, dt = 0.025. Asserted: each halving of the element gains more than
/// h^3 (ratio > 8), the finest below 5e-6 of the static 0.5 (a wrong own-element integral
/// stalls at 1e-2), the coarse error at dt/2 within 5 %.
#[test]
fn cavity_wall_converges_in_space() {
    let errors: Vec<f64> = [4, 8, 16]
        .iter()
        .map(|&n| cavity_space_error(n, 0.1))
        .collect();
    let half_dt = cavity_space_error(4, 0.05);
    eprintln!("cavity space errors {errors:?}, n = 4 at dt/2: {half_dt:.3e}");
    assert!(
        (half_dt - errors[0]).abs() < 0.05 * errors[0],
        "the spatial error depends on dt: {} vs {half_dt}",
        errors[0]
    );
    for pair in errors.windows(2) {
        assert!(pair[1] < pair[0] / 8.0, "{errors:?}");
    }
    assert!(errors[2] < 5e-6, "{errors:?}");
}

/// The cavity to long times (table 3.2, t c2/a = 5, 10, 20) on a ring big enough to be
/// reflection-free to t = 20: R = 24 a (the outer boundary's echo returns at
/// 2 (R - a)/c1 = 26.6 a/c2; 8 elements per outer half circle, which the wave never
/// reaches and returns from before then), 16 per half circle on the hole, the sudden
/// pressure p0 H(t), BDF2 dt = 0.1 a/c2. The response tends to the static Lame value
/// p0 a/(2 mu) = 0.5 as the table does: u_r - 0.5 at t = 10, 20 against the table's
/// 2.4423e-3 and 6.116e-4. Measured: u_r(a) = 0.5133631, 0.5024344, 0.5006021 at t = 5,
/// 10, 20 (table 0.5142521, 0.5024423, 0.5006116): u - 0.5 within 3.2e-3 and 1.6e-2 of the
/// table's at t = 10, 20 (absolute 7.9e-6, 9.5e-6); with 8 + 8 elements 5.1e-5, 5.0e-5
/// (the late error is spatial: dt = 0.05 changes it by 1e-6; the early one, 1.2e-2 at
/// t = 1, is BDF2's error on the step: 6.5e-3 at dt = 0.05). Asserted: u - 0.5 within 2 %
/// and 5 % of the table's at t = 10, 20, and falling by more than 3 between them (the
/// table: 4.0).
#[test]
fn cavity_long_times_tend_to_the_static_solution() {
    let dt: f64 = 0.1;
    let wall = CavityWall::new(1.0, 24.0, 8, 16);
    let pattern = wall.bem.static_known_values().to_vec();
    let steps = (20.0 / dt).round() as usize;
    let u = output_at_steps(&wall, &pattern, CqMethod::Bdf2, dt, steps, &|_| 1.0);
    let mut approach = vec![];
    for (t, table) in [
        (5.0, 0.5142521471),
        (10.0, 0.5024423320),
        (20.0, 0.5006116322),
    ] {
        let v = u[(t / dt).round() as usize];
        let rel = ((v - 0.5) - (table - 0.5)) / (table - 0.5);
        eprintln!(
            "cavity R = 24: t = {t}: u_r(a) = {v:.7} (table {table:.7}), u - 0.5 off by {rel:.2e}"
        );
        approach.push((v - 0.5, rel));
    }
    assert!(approach[1].1.abs() < 0.02, "{approach:?}");
    assert!(approach[2].1.abs() < 0.05, "{approach:?}");
    assert!(
        approach[2].0 > 0.0 && approach[2].0 < approach[1].0 / 3.0,
        "{approach:?}"
    );
}
