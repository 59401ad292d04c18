//! Stresses of the Laplace-domain BEM and its CQ histories against closed forms: the
//! cylindrical cavity under sudden pressure (docs/theory/DYNAMICS.md sec. 3.2: wall hoop
//! stress table, the Laplace-domain sigma_rr, sigma_tt at r = 1.5 a, 2 a) and the 1D column
//! (sec. 3.1: sigma_xx = -p0 behind the front).

use std::f64::consts::PI;

use complex_bessel::besselk_scaled;

use super::*;
use crate::dynamics::cq::{convolve, CqGrid, CqMethod, CqParams};
use crate::kernels::kelvin2d::PlaneCondition;
use crate::material::ElasticMaterial;
use crate::operators::bem2d::{BemModel, Region, Segment};
use crate::solvers::bem2d::{BoundaryConditions, Profile, SegmentBc};

/// The ring a = 1, R = `big` (nu = 0.25, mu = rho = 1: c2 = 1, c1 = sqrt(3)) under the
/// internal pressure p0 = 1, `n` quadratic elements per half circle on both circles, with
/// stress probes at `probes`.
fn cavity(big: f64, n: usize, probes: &[[f64; 2]]) -> LaplaceBem {
    let (mu, nu) = (1.0, 0.25);
    let m = ElasticMaterial::new(2.0 * mu * (1.0 + nu), nu).unwrap();
    let model = BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "ring",
            m,
            vec![
                Segment::arc("outer_a", [0.0, 0.0], big, 0.0, PI, n),
                Segment::arc("outer_b", [0.0, 0.0], big, PI, 2.0 * PI, n),
            ],
        )
        .with_hole(vec![
            Segment::arc("hole_a", [0.0, 0.0], 1.0, PI, 0.0, n),
            Segment::arc("hole_b", [0.0, 0.0], 1.0, 2.0 * PI, PI, n),
        ])],
    );
    let bcs = BoundaryConditions::new()
        .set("hole_a", SegmentBc::Pressure(Profile::Uniform(1.0)))
        .set("hole_b", SegmentBc::Pressure(Profile::Uniform(1.0)));
    LaplaceBem::new(&model, &[1.0], &bcs, &[])
        .unwrap()
        .with_stress_probes(probes)
        .unwrap()
}

/// The infinite plane's cavity stresses per unit pressure in the Laplace domain
/// (docs/theory/DYNAMICS.md 3.2): `(sigma_rr, sigma_tt)(r, s) / p(s)` with
/// `D = (lam + 2 mu) K0(ka) + 2 mu K1(ka)/(ka)`, k = s/c1, a = 1, lam = mu = 1; the scaled
/// Bessel functions with the factor exp(-k (r - a)) of their ratio.
fn cavity_exact(r: f64, s: c64) -> (c64, c64) {
    let (lam, mu, c1) = (1.0, 1.0, 3f64.sqrt());
    let k = s / c1;
    let ka = k;
    let kr = k * r;
    let k0a = besselk_scaled(0.0, ka).unwrap();
    let k1a = besselk_scaled(1.0, ka).unwrap();
    let k0r = besselk_scaled(0.0, kr).unwrap();
    let k1r = besselk_scaled(1.0, kr).unwrap();
    let d = k0a * (lam + 2.0 * mu) + k1a / ka * (2.0 * mu);
    let e = (-k * (r - 1.0)).exp();
    let srr = -(k0r * (lam + 2.0 * mu) + k1r / kr * (2.0 * mu)) * e / d;
    let stt = -(k0r * lam - k1r / kr * (2.0 * mu)) * e / d;
    (srr, stt)
}

/// Radial and hoop components of [xx, yy, xy] at the polar angle `theta`.
fn polar<T>(s: [T; 3], theta: f64) -> (T, T)
where
    T: Copy + std::ops::Mul<f64, Output = T> + std::ops::Add<Output = T>,
{
    let (c, sn) = (theta.cos(), theta.sin());
    let rr = s[0] * (c * c) + s[1] * (sn * sn) + s[2] * (2.0 * sn * c);
    let tt = s[0] * (sn * sn) + s[1] * (c * c) + s[2] * (-2.0 * sn * c);
    (rr, tt)
}

/// Probe points at r = 1.5 and 2 at two angles (away from the segment junctions).
fn cavity_probes() -> Vec<([f64; 2], f64, f64)> {
    let mut v = vec![];
    for r in [1.5, 2.0] {
        for th in [0.3, 2.2] {
            v.push(([r * f64::cos(th), r * f64::sin(th)], r, th));
        }
    }
    v
}

/// The Laplace-domain probe stresses against the closed form at Re s >= 10, where the
/// reflection from R = 3 is damped by exp(-2 Re s (R - r)/c1) < 1e-7 (the ring is the
/// infinite plane): at 4, 8, 16 elements per half circle the error relative to
/// |sigma_rr(1.5)| falls like h^3 (measured printed; the wall displacement converges so,
/// tests.rs). Asserted: below 1e-3 at 16 elements and a ratio > 4 per halving.
#[test]
fn laplace_probe_stresses_match_the_cavity_closed_form() {
    let probes = cavity_probes();
    let points: Vec<[f64; 2]> = probes.iter().map(|p| p.0).collect();
    for s in [c64::new(10.0, 0.0), c64::new(10.0, 10.0)] {
        let mut errors = vec![];
        for n in [4, 8, 16] {
            let bem = cavity(3.0, n, &points);
            let known: Vec<c64> = bem
                .static_known_values()
                .iter()
                .map(|v| c64::new(*v, 0.0))
                .collect();
            let out = bem.respond(s, &known).unwrap();
            let first = bem.first_stress_output();
            let scale = cavity_exact(1.5, s).0.norm();
            let mut err = 0.0_f64;
            for (i, &(_, r, th)) in probes.iter().enumerate() {
                let v = [
                    out[first + 3 * i],
                    out[first + 3 * i + 1],
                    out[first + 3 * i + 2],
                ];
                let (srr, stt) = polar(v, th);
                let (xr, xt) = cavity_exact(r, s);
                err = err.max((srr - xr).norm()).max((stt - xt).norm());
            }
            errors.push(err / scale);
        }
        eprintln!("cavity probe stresses, s = {s}: errors {errors:?} of |sigma_rr(1.5)|");
        assert!(errors[2] < 1e-3, "{errors:?}");
        assert!(
            errors[1] < errors[0] / 4.0 && errors[2] < errors[1] / 4.0,
            "{errors:?}"
        );
    }
}

/// The BEM-CQ run of the cavity (R = 4, 16 elements per half circle) under p0 H(t):
/// `(bem, data, series)` with `steps` BDF2 steps of `dt`.
fn cavity_run(
    steps: usize,
    dt: f64,
    method: CqMethod,
    probes: &[[f64; 2]],
) -> (LaplaceBem, Vec<f64>, CqSeries) {
    let bem = cavity(4.0, 16, probes);
    let grid = CqGrid::new(method, dt, steps).unwrap();
    let pattern = bem.static_known_values().to_vec();
    let data: Vec<f64> = grid
        .sample_times()
        .iter()
        .flat_map(|_| pattern.iter().copied())
        .collect();
    let series = convolve(&bem, &grid, &data, &CqParams::default()).unwrap();
    (bem, data, series)
}

/// The hoop stress sigma_tt (Pa) at every wall node (r = a) at step n of a cavity run.
fn wall_hoop(bem: &LaplaceBem, stresses: &[Vec<Vec<[f64; 3]>>], n: usize) -> Vec<f64> {
    let region = &bem.static_problem().mesh.regions[0];
    region
        .nodes
        .iter()
        .zip(&stresses[n][0])
        .filter(|(node, _)| (node.position[0].hypot(node.position[1]) - 1.0).abs() < 1e-9)
        .map(|(node, s)| polar(*s, node.position[1].atan2(node.position[0])).1)
        .collect()
}

/// The cavity wall's hoop stress from the boundary stress recovery of the CQ histories
/// against the reference table of docs/theory/DYNAMICS.md 3.2 (Talbot at 30 digits) at
/// t c2/a = 0.25 ... 3 (before the outer reflection returns at 3.46), every wall node,
/// BDF2 with the step sampled as 1 at t = 0 (first order). Measured max |sigma_tt - ref|
/// over the times and the 64 wall nodes (p0 units; static value 1): printed; the error
/// halves with dt (first order, largest at t = 0.25 where the step's start dominates).
/// Measured: 3.34e-2 (dt = 0.05), 1.71e-2 (dt = 0.025), ratio 1.95; at t = 2 and 3 below
/// 3e-3; the spread over the nodes 2.4e-4. Asserted: ratio > 1.7 per halving and the values
/// at dt = 0.025 within 2 % of p0.
#[test]
fn cavity_wall_hoop_stress_matches_the_reference_table() {
    let reference = [
        (0.25, 0.0340943323),
        (0.5, 0.3562757796),
        (1.0, 0.8385724981),
        (2.0, 1.2348961564),
        (3.0, 1.2184404522),
    ];
    let mut errors = vec![];
    for steps in [60, 120] {
        let dt = 3.0 / steps as f64;
        let (bem, data, series) = cavity_run(steps, dt, CqMethod::Bdf2, &[]);
        let stresses = boundary_stress_history(&bem, &data, &series).unwrap();
        let mut err = 0.0_f64;
        for (t, s_ref) in reference {
            let n = (t / dt).round() as usize;
            let hoop = wall_hoop(&bem, &stresses, n);
            let (lo, hi) = hoop
                .iter()
                .fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(*v), b.max(*v)));
            eprintln!("cavity hoop dt = {dt}: t = {t}: {lo:.5} .. {hi:.5}, reference {s_ref:.5}");
            for v in hoop {
                err = err.max((v - s_ref).abs());
            }
        }
        errors.push(err);
    }
    eprintln!("cavity wall hoop stress: max errors {errors:?} (static value 1)");
    assert!(errors[1] < errors[0] / 1.7, "{errors:?}");
    assert!(errors[1] < 0.02, "{errors:?}");
}

/// The long-time limit: BDF1 with a long step (dt = 5 a/c2, 40 steps) damps the ring's
/// free vibrations numerically (amplification 1/|1 - i omega dt| per step), so the CQ
/// solution under p0 H(t) settles to R(0) p0, the static solution of the ring a = 1, R = 4:
/// Lame's sigma_tt(a) = p0 (R^2 + a^2)/(R^2 - a^2) = 17/15 and u_r(a) = ... from the static
/// BEM. Measured: 1.4e-4 at every wall node (the static BEM's nodal recovery on this mesh);
/// asserted within 5e-4.
#[test]
fn cavity_hoop_stress_settles_to_lame() {
    let (bem, data, series) = cavity_run(40, 5.0, CqMethod::Bdf1, &[]);
    let stresses = boundary_stress_history(&bem, &data, &series).unwrap();
    let lame = 17.0 / 15.0;
    let hoop = wall_hoop(&bem, &stresses, 40);
    let err = hoop.iter().fold(0.0_f64, |m, v| m.max((v - lame).abs()));
    eprintln!(
        "long-time hoop stress: max |sigma_tt - Lame| {err:.2e} over {} nodes",
        hoop.len()
    );
    assert!(err < 5e-4, "{err}");
}

/// Probe stress histories at r = 1.5 a, 2 a (two angles each): the BEM-CQ probe outputs
/// (ring a = 1, R = 4, 16 elements per half circle, BDF2, p0 H(t)) against the Talbot
/// inversion (Abate & Valko 2004, M = 24) of the Laplace-domain closed form of
/// docs/theory/DYNAMICS.md 3.2 at t c2/a = 1 and 2 (before the reflection from R = 4 reaches
/// r = 2 at 2.89). Measured max |sigma_rr - exact|, |sigma_tt - exact| (p0 units):
/// 2.78e-2 at dt = 0.05, 6.8e-3 at dt = 0.025 (ratio 4.1; the largest at r = 2, t = 1, 0.42
/// after the front's arrival, where the step's smeared jump still shows). The same probes
/// in the Laplace domain converge like h^4 (test above), so this is the CQ error.
/// Asserted: ratio > 3 and below 1e-2 at dt = 0.025.
#[test]
fn probe_stress_histories_match_the_cavity_closed_form() {
    let probes = cavity_probes();
    let points: Vec<[f64; 2]> = probes.iter().map(|p| p.0).collect();
    let talbot = |r: f64, t: f64| -> (f64, f64) {
        // Fixed Talbot, M = 24, of sigma(r, s) p0/s.
        let m = 24;
        let rt = 2.0 * m as f64 / (5.0 * t);
        let f = |s: c64| {
            let (a, b) = cavity_exact(r, s);
            (a / s, b / s)
        };
        let (a0, b0) = f(c64::new(rt, 0.0));
        let mut acc = (
            0.5 * (a0 * (rt * t).exp()).re,
            0.5 * (b0 * (rt * t).exp()).re,
        );
        for k in 1..m {
            let th = k as f64 * PI / m as f64;
            let cot = th.cos() / th.sin();
            let sk = c64::new(rt * th * cot, rt * th);
            let sigma = th + (th * cot - 1.0) * cot;
            let fac = (sk * t).exp() * c64::new(1.0, sigma);
            let (a, b) = f(sk);
            acc.0 += (a * fac).re;
            acc.1 += (b * fac).re;
        }
        (acc.0 * rt / m as f64, acc.1 * rt / m as f64)
    };
    let mut errors = vec![];
    for steps in [40, 80] {
        let dt = 2.0 / steps as f64;
        let (bem, _, series) = cavity_run(steps, dt, CqMethod::Bdf2, &points);
        let mut err = 0.0_f64;
        for n in [steps / 2, steps] {
            let t = n as f64 * dt;
            let out = series.at_step(n).unwrap();
            let values = bem.stress_probe_values(out).unwrap();
            for (i, &(_, r, th)) in probes.iter().enumerate() {
                let st = values[i];
                let (srr, stt) = polar([st.xx, st.yy, st.xy], th);
                let (xr, xt) = talbot(r, t);
                eprintln!(
                    "dt = {dt} r = {r} theta = {th} t = {t}: sigma_rr {srr:.5} (exact {xr:.5}), \
                     sigma_tt {stt:.5} (exact {xt:.5})"
                );
                err = err.max((srr - xr).abs()).max((stt - xt).abs());
            }
        }
        errors.push(err);
    }
    eprintln!("probe stress vs Talbot: {errors:?}");
    assert!(errors[1] < errors[0] / 3.0, "{errors:?}");
    assert!(errors[1] < 1e-2, "{errors:?}");
}

/// Column L = 1 x W = 0.25, E = 1, nu = 0, rho = 1 (c = 1): 16 x 2 quadratic elements,
/// sudden end pressure p0 = 1 at x = 0, x = L on rollers (the time tests' model).
fn column(probes: &[[f64; 2]]) -> LaplaceBem {
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
    LaplaceBem::new(&model, &[1.0], &bcs, &[])
        .unwrap()
        .with_stress_probes(probes)
        .unwrap()
}

/// The column's load f(t): the smooth ramp (1 - cos(pi t/T0))/2 over T0 = 0.5 L/c.
fn column_ramp(t: f64) -> f64 {
    let t0 = 0.5;
    if t <= 0.0 {
        0.0
    } else if t < t0 {
        0.5 * (1.0 - (PI * t / t0).cos())
    } else {
        1.0
    }
}

/// The column `bem` under p0 [`column_ramp`] by BDF2 in `steps` steps to t = 2.5: the data
/// and the convolved series.
fn column_ramp_run(bem: &LaplaceBem, steps: usize) -> (Vec<f64>, CqSeries) {
    let grid = CqGrid::new(CqMethod::Bdf2, 2.5 / steps as f64, steps).unwrap();
    let pattern = bem.static_known_values().to_vec();
    let data: Vec<f64> = grid
        .sample_times()
        .iter()
        .flat_map(|&t| pattern.iter().map(move |v| v * column_ramp(t)))
        .collect();
    let series = convolve(bem, &grid, &data, &CqParams::default()).unwrap();
    (data, series)
}

/// The 1D column (docs/theory/DYNAMICS.md 3.1) under an end pressure p0 f(t) rising as the
/// smooth ramp f = (1 - cos(pi t/T0))/2 over T0 = 0.5 L/c: at the probe x = 0.5 the exact
/// stress is the incident wave plus its reflection from the fixed end (doubling),
/// `sigma_xx = -p0 [f(t - x/c) + f(t - (2L - x)/c)]` for t < (2L + x)/c = 2.5 (then the
/// reflection from the loaded end), sigma_yy = sigma_xy = 0 (nu = 0): sigma_xx = -p0 behind
/// the front, -2 p0 after the reflection. BDF2 with 100 and 200 steps to t = 2.5. Max error
/// over all steps and components (p0 units): 4.66e-2, 1.64e-2 (ratio 2.84, order 1.5: the
/// ramp's fronts are resolved by few elements of the 16 along L; a step's jump would leave
/// first-order errors ~ dt/(t - t_front), 6.4e-2 at 160 steps 0.3 L/c behind the front).
/// Asserted: the error falls by at least 2.4x per halving and is below 2e-2 at 200 steps.
#[test]
fn column_stress_behind_the_front_is_the_pressure() {
    let bem = column(&[[0.5, 0.125]]);
    let f = column_ramp;
    let mut errors = vec![];
    for steps in [100, 200] {
        let dt = 2.5 / steps as f64;
        let (_, series) = column_ramp_run(&bem, steps);
        let mut err = 0.0_f64;
        for n in 0..=steps {
            let t = n as f64 * dt;
            let exact = -(f(t - 0.5) + f(t - 1.5));
            let s = bem.stress_probe_values(series.at_step(n).unwrap()).unwrap()[0];
            err = err
                .max((s.xx - exact).abs())
                .max(s.yy.abs())
                .max(s.xy.abs());
        }
        errors.push(err);
    }
    eprintln!("column probe stress, smooth ramp: max errors {errors:?} of p0");
    assert!(errors[1] < errors[0] / 2.4, "{errors:?}");
    assert!(errors[1] < 2e-2, "{errors:?}");
}

/// Probes on the boundary by the static field sampler's rule, on the column of
/// [`column_stress_behind_the_front_is_the_pressure`] (the same ramp, BDF2, 200 steps to
/// t = 2.5): the corner (L, 0) (a junction of "bottom" and "right": the junction rule, the
/// stress from the tractions of the two sides) carries the incident wave and its
/// reflection at once, sigma_xx = -2 p0 f(t - L/c) (the stress doubling at the fixed
/// end); the corner (0, 0) the load itself, sigma_xx = -p0 f(t) (its tractions are the
/// data); the point (0.5, 0) on "bottom" (within the boundary layer: evaluated 1e-4 of an
/// element length inside) sigma_xx = -p0 [f(t - 0.5) + f(t - 1.5)]; sigma_yy = sigma_xy =
/// 0 everywhere (nu = 0). The junction's history equals the junction rule applied to the
/// boundary fields of every step ([`boundary_field_history`]): the rule is linear and
/// instantaneous, so it commutes with the convolution. Measured: max errors 2.50e-2 p0 at
/// (L, 0), 1.7e-9 p0 at (0, 0), 1.92e-2 p0 at (0.5, 0); the rule against the fields
/// 8.9e-13 p0. Tolerances: (0, 0) 1e-8 p0 (the data, exact but for the rounding of the
/// convolution's FFTs over 200 steps), (0.5, 0) 2e-2 p0 (the interior probe's bound in the
/// test above: the fronts smeared over the elements), (L, 0) 4e-2 p0 (the same smearing of
/// a front of twice the amplitude: incident and reflected arrive together), the rule 1e-10
/// p0 (rounding).
#[test]
fn boundary_probes_follow_the_static_sampler_rule() {
    let corner = [1.0, 0.0];
    let bem = column(&[corner, [0.0, 0.0], [0.5, 0.0]]);
    let mesh = &bem.static_problem().mesh;
    let feet = match crate::solvers::bem2d::locate_site(mesh, None, corner)
        .unwrap()
        .1
    {
        Site::Junction(feet) => feet,
        other => panic!("(L, 0) is a corner: {other:?}"),
    };
    let f = column_ramp;
    let steps = 200;
    let dt = 2.5 / steps as f64;
    let (data, series) = column_ramp_run(&bem, steps);
    let fields = boundary_field_history(&bem, &data, &series).unwrap();
    let mut errors = [0.0_f64; 4];
    for (n, fields) in fields.iter().enumerate() {
        let t = n as f64 * dt;
        let s = bem.stress_probe_values(series.at_step(n).unwrap()).unwrap();
        let exact = [-2.0 * f(t - 1.0), -f(t), -(f(t - 0.5) + f(t - 1.5))];
        for (k, (s, exact)) in s.iter().zip(exact).enumerate() {
            errors[k] = errors[k]
                .max((s.xx - exact).abs())
                .max(s.yy.abs())
                .max(s.xy.abs());
        }
        let (_, rule) = crate::solvers::bem2d::junction_fields(
            &mesh.regions[0],
            &feet,
            &fields.displacement[0],
            &fields.traction[0],
        );
        errors[3] = errors[3]
            .max((s[0].xx - rule[0]).abs())
            .max((s[0].yy - rule[1]).abs())
            .max((s[0].xy - rule[2]).abs());
    }
    eprintln!(
        "boundary probes: max errors (p0) corner (L, 0) {:.3e}, corner (0, 0) {:.3e}, \
         bottom (0.5, 0) {:.3e}; corner vs the junction rule on the fields {:.3e}",
        errors[0], errors[1], errors[2], errors[3]
    );
    assert!(errors[0] < 4e-2, "{errors:?}");
    assert!(errors[1] < 1e-8, "{errors:?}");
    assert!(errors[2] < 2e-2, "{errors:?}");
    assert!(errors[3] < 1e-10, "{errors:?}");
}

/// Bad input: a stress probe outside the body, and fields or rows of the wrong shape.
#[test]
fn stress_api_refuses_bad_shapes() {
    let bem = column(&[]);
    assert!(column(&[]).with_stress_probes(&[[2.0, 0.1]]).is_err());
    // Field points: one region per point, an existing region, the point inside it.
    let p = [[0.5, 0.1]];
    assert!(column(&[]).with_field_points(&p, &[Some(0)]).is_ok());
    assert!(column(&[]).with_field_points(&p, &[]).is_err());
    assert!(column(&[]).with_field_points(&p, &[Some(1)]).is_err());
    assert!(column(&[])
        .with_field_points(&[[2.0, 0.1]], &[Some(0)])
        .is_err());
    assert!(bem.boundary_fields(&[0.0; 3], &[]).is_err());
    assert!(bem.stress_probe_values(&[0.0; 2]).is_err());
    let fields = BoundaryFields {
        displacement: vec![],
        traction: vec![],
    };
    assert!(bem.boundary_stresses(&fields).is_err());
}
