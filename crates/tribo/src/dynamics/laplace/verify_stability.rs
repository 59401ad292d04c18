//! Long-run stability of the chain LaplaceBem -> CQ: a clamped square hit by a short
//! pressure pulse, then free, over thousands of steps at c1 dt/h from 0.05 to 4 (BDF2 and
//! the 2-stage Radau IIA method).

use super::*;
use crate::dynamics::cq::CqMethod;
use crate::validation::dyn_verify::{stability_run, StabilityRun};

/// Runs and prints one case: (late/early, growth per transit).
fn measure(method: CqMethod, ratio: f64, steps: usize, n: usize) -> StabilityRun {
    let t0 = std::time::Instant::now();
    let run = stability_run(method, ratio, steps, n).unwrap();
    eprintln!(
        "stability {} n = {n} c1 dt/h = {ratio}, {steps} steps: early max {:.3e}, late max {:.3e} (ratio {:.2e}), growth {:.2e} per transit ({:.1} s)",
        method.name(),
        run.early,
        run.late,
        run.late / run.early,
        run.growth_per_transit,
        t0.elapsed().as_secs_f64()
    );
    run
}

/// Bounded (the last tenth below twice the first tenth's maximum: the first tenth holds the
/// pulse's response, which a free, non-growing system never exceeds much) and no
/// exponential growth (below 1e-3 per transit time h/c1: the unstable modes measured grow
/// by 2.5e-3 to 1.9e-1 per transit, [`radau_iia_2_grows_on_the_coarsest_square`]; the
/// bounded runs show at most +4e-4 (BDF2, 4 per side, c1 dt/h = 0.05, over 100 transits a
/// factor 1.04), most of them decay).
fn check(run: &StabilityRun) {
    assert!(
        run.late.is_finite() && run.late < 2.0 * run.early,
        "{run:?}"
    );
    assert!(run.growth_per_transit < 1e-3, "{run:?}");
}

/// BDF2, 2000 steps at c1 dt/h = 0.25, 1, 4 on the square with one element per side (the
/// cheap part; the 10^4-step sweep is [`ten_thousand_steps`]). Measured over 2000 steps:
/// late/early 8.2e-4, 1.5e-7, 1.1e-7; growth -1.6e-2, -9.0e-4, -2.2e-4 per transit (BDF2's
/// numerical dissipation). Over 10^4 steps c1 dt/h = 0.25 shows a slow growth (+2.5e-3 per
/// transit, from 2e-6 of the early maximum): a spurious mode of this coarse model
/// ([`super::verify_limits`]).
#[test]
fn bdf2_long_runs_stay_bounded() {
    for ratio in [0.25, 1.0, 4.0] {
        check(&measure(CqMethod::Bdf2, ratio, 2000, 1));
    }
}

/// Radau IIA 2 on the square with one element per side at c1 dt/h = 1 and 4, 2000 steps.
#[test]
fn radau_iia_2_long_runs_stay_bounded() {
    for ratio in [1.0, 4.0] {
        check(&measure(CqMethod::RadauIia2, ratio, 2000, 1));
    }
}

/// The limit found: with one element per side and c1 dt/h = 0.25, the 2-stage Radau IIA
/// run grows exponentially, 2.7e-2 per transit time (late/early 9.7e2 after 2000 steps),
/// while BDF2 on the same model decays. The semi-discrete (collocation) model of this very
/// coarse square has poles in Re s > 0 (the peaks of [`pole_scan_of_the_clamped_square`]
/// at Im s = 7.9 and 14.25 c1/h that shrink as Re s falls from 0.2 to 0.05): BDF2 at
/// c1 dt/h = 0.05 grows too (+1.6e-1 per transit), so it is the spatial discretisation, not
/// the time integrator; with 4 elements per side the growth is gone
/// ([`radau_iia_2_growth_vanishes_with_refinement`]; the criterion
/// [`super::verify_limits::coarse_regions`]). Ignored (20 s): it asserts the growth.
#[test]
#[ignore]
fn radau_iia_2_grows_on_the_coarsest_square() {
    let run = measure(CqMethod::RadauIia2, 0.25, 2000, 1);
    assert!(run.growth_per_transit > 1e-2, "{run:?}");
}

/// The CI part of the 10^4-step statement: BDF2 at c1 dt/h = 1 on the square with one
/// element per side, 10^4 steps (~5800 transit times h/c1; 30 s on the loaded two cores).
/// Measured: late/early 2.7e-8, growth -1.3e-4 per transit. Asserted as [`check`].
#[test]
fn ten_thousand_steps_bdf2_stay_bounded() {
    check(&measure(CqMethod::Bdf2, 1.0, 10_000, 1));
}

/// 10^4 steps at c1 dt/h = 0.05, 0.25, 1, 4, BDF2 and Radau IIA 2, one element per side
/// (the measured table is in docs/theory/DYNAMICS.md sec. 5.6). Asserted: every run that
/// [`super::verify_limits::coarse_regions`] does not flag is bounded ([`check`]), and every
/// run that grows is flagged (the criterion is conservative: it flags Radau IIA at every
/// step on a coarse region, measured bounded at c1 dt/h = 1, 4). Ignored: ~5000 Laplace
/// solves per run (10^4 for Radau IIA 2), up to 15 min for all on two loaded cores.
#[test]
#[ignore]
fn ten_thousand_steps() {
    use super::verify_limits::coarse_regions;
    use crate::solvers::bem2d::{Profile, SegmentBc};
    let model = crate::validation::dyn_verify::rectangle(1.0, 1.0, 1, 1).unwrap();
    let bcs = BoundaryConditions::new()
        .set("bottom", SegmentBc::fixed())
        .set("top", SegmentBc::Pressure(Profile::Uniform(1.0)));
    let bem = LaplaceBem::new(&model, &[1.0], &bcs, &[]).unwrap();
    for method in [CqMethod::Bdf2, CqMethod::RadauIia2] {
        for ratio in [0.05, 0.25, 1.0, 4.0] {
            let run = measure(method, ratio, 10_000, 1);
            let flagged = !coarse_regions(&bem, method, ratio / 3.0_f64.sqrt()).is_empty();
            if !flagged {
                check(&run);
            }
            if run.growth_per_transit > 1e-3 {
                assert!(flagged, "{method:?} {ratio}: {run:?}");
            }
        }
    }
}

/// Whether the Radau IIA 2 growth is a property of the coarse spatial discretisation: the
/// same run at c1 dt/h = 0.25, 2000 steps, with 1, 2 and 4 elements per side. Measured:
/// growth +2.7e-2 and +1.6e-2 per transit (late/early 9.7e2, 2.6e1) at 1 and 2, and
/// +2.3e-6 (late/early 0.99: bounded) at 4. Ignored: 4 min on the loaded two cores.
/// The threshold is [`super::verify_limits::MIN_ELEMENTS`].
#[test]
#[ignore]
fn radau_iia_2_growth_vanishes_with_refinement() {
    for n in [1, 2] {
        let run = measure(CqMethod::RadauIia2, 0.25, 2000, n);
        assert!(run.growth_per_transit > 1e-2, "{n}: {run:?}");
    }
    let run = measure(CqMethod::RadauIia2, 0.25, 2000, 4);
    assert!(
        run.late < 2.0 * run.early && run.growth_per_transit < 1e-4,
        "{run:?}"
    );
}

/// A quicker sweep of the same (2000 steps; ignored, run once).
#[test]
#[ignore]
fn stability_sweep() {
    for n in [1, 2] {
        for method in [CqMethod::Bdf2, CqMethod::RadauIia2] {
            for ratio in [0.05, 0.25, 1.0, 4.0] {
                measure(method, ratio, 2000, n);
            }
        }
    }
}

/// Where the Radau IIA growth comes from (ignored: a diagnosis, run once): the largest
/// nodal displacement of the clamped square's Laplace-domain response to the unit pressure,
/// |u(s)|, along the lines Re s = 0.02, 0.05, 0.2 for Im s up to 40 c1/h: a pole of the
/// discrete transfer function in Re s > 0 shows as a peak that sharpens as Re s falls
/// towards its real part; with 1 and 2 elements per side.
#[test]
#[ignore]
fn pole_scan_of_the_clamped_square() {
    use crate::dynamics::testing::{cavity_material, rectangle};
    use crate::solvers::bem2d::{Profile, SegmentBc};
    for n in [1, 2] {
        let model = rectangle(cavity_material(), 1.0, 1.0, n, n);
        let bcs = BoundaryConditions::new()
            .set("bottom", SegmentBc::fixed())
            .set("top", SegmentBc::Pressure(Profile::Uniform(1.0)));
        let bem = LaplaceBem::new(&model, &[1.0], &bcs, &[]).unwrap();
        let known: Vec<c64> = bem
            .static_known_values()
            .iter()
            .map(|&v| c64::new(v, 0.0))
            .collect();
        for sigma in [0.02, 0.05, 0.2] {
            let mut values = vec![];
            for k in 1..=800 {
                let s = c64::new(sigma, 0.05 * k as f64);
                let state = bem.respond_state(s, &known).unwrap();
                let m = state.displacement[0]
                    .iter()
                    .fold(0.0_f64, |m, u| m.max(u[0].norm()).max(u[1].norm()));
                values.push((s.im, m));
            }
            let mut peaks: Vec<(f64, f64)> = values
                .windows(3)
                .filter(|w| w[1].1 > w[0].1 && w[1].1 > w[2].1)
                .map(|w| w[1])
                .collect();
            peaks.sort_by(|a, b| b.1.total_cmp(&a.1));
            peaks.truncate(6);
            eprintln!("n = {n}, Re s = {sigma}: largest peaks (Im s, max |u|) {peaks:.3?}");
        }
    }
}
