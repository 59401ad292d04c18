//! Invariance of the 2D BEM under rigid motions of the model (issue 11 item 2): a model
//! translated by up to 1e3 times its size and rotated gives the same displacements,
//! tractions and stresses transformed accordingly (u' = R u, t' = R t, sigma' = R sigma R^T),
//! with and without contact. Inputs given in global axes (body forces, boundary tractions,
//! rigid-segment forces) are rotated with the model.
//!
//! Tolerance 1e-9 relative to the largest value of each field: the models are the same up
//! to the rounding of their translated and rotated input coordinates (relative 1e-16 of the
//! translation, i.e. 1e-13 of the model size at 1e3 times its size and 1e-11 of the
//! smallest element, graded 1:50), which the solution amplifies by the condition number of
//! the system (~1e2-1e3 for these models). Before the element-local integrals the block
//! translated by 90 mm (a 1e-4 element-to-distance ratio) failed its LU solve with NaN.
//!
//! Contact pressures are more sensitive to that rounding (a gap change dg moves a pressure
//! by about E* dg / h): inexact motions are bounded by [`inexact_bound`], measured on the
//! model at rest with perturbed points; exact motions (points on a 2^-40 m grid, grid
//! translations, quarter turns) agree to 1e-9 at any distance
//! ([`contact_is_invariant_under_exact_rigid_motions`]), which shows that nothing in the
//! contact solver depends on where the model sits. The free-body integrals (equilibrium
//! rows, artificial supports, boundary centroid and motion) use model-local coordinates
//! too (an outline model on the grid translated by (20, -13) m: contact tractions
//! bit-identical, 3.5e-12 before; crates/tribo-case/tests/bem_rigid_motion.rs).

use std::f64::consts::{FRAC_PI_2, PI};

use proptest::prelude::*;

use super::contact::reference::{hertz, P, R};
use super::contact::{ContactOptions, RigidControl};
use super::contact::{ContactPair, ContactProblem, ContactStepResult, Control, LoadStep};
use super::*;
use crate::kernels::kelvin2d::PlaneCondition;
use crate::material::ElasticMaterial;
use crate::operators::bem2d::SegmentShape;
use crate::operators::bem2d::{BodyForce, Grading, LoopItem, MeshedCurve, Region, Segment};

/// A rigid motion x' = R(theta) x + shift.
#[derive(Debug, Clone, Copy)]
struct Motion {
    theta: f64,
    shift: [f64; 2],
}

/// (sin, cos) of `theta`, exact for the multiples of 90 degrees (so that a quarter turn
/// maps a point exactly, with no rounding of cos(pi/2) = 6e-17).
fn sin_cos(theta: f64) -> (f64, f64) {
    let q = theta / FRAC_PI_2;
    if q == q.round() {
        match (q as i64).rem_euclid(4) {
            0 => (0.0, 1.0),
            1 => (1.0, 0.0),
            2 => (0.0, -1.0),
            _ => (-1.0, 0.0),
        }
    } else {
        theta.sin_cos()
    }
}

impl Motion {
    fn rot(&self, v: [f64; 2]) -> [f64; 2] {
        let (s, c) = sin_cos(self.theta);
        [c * v[0] - s * v[1], s * v[0] + c * v[1]]
    }
    fn point(&self, x: [f64; 2]) -> [f64; 2] {
        let r = self.rot(x);
        [r[0] + self.shift[0], r[1] + self.shift[1]]
    }
    /// R sigma R^T of [xx, yy, xy].
    fn stress(&self, s: [f64; 3]) -> [f64; 3] {
        let (sn, c) = sin_cos(self.theta);
        let (xx, yy, xy) = (s[0], s[1], s[2]);
        [
            c * c * xx - 2.0 * sn * c * xy + sn * sn * yy,
            sn * sn * xx + 2.0 * sn * c * xy + c * c * yy,
            sn * c * (xx - yy) + (c * c - sn * sn) * xy,
        ]
    }
    fn segment(&self, s: &Segment) -> Segment {
        let mut out = s.clone();
        out.shape = match &s.shape {
            SegmentShape::Line { start, end } => SegmentShape::Line {
                start: self.point(*start),
                end: self.point(*end),
            },
            SegmentShape::Arc {
                center,
                radius,
                start_angle,
                end_angle,
            } => SegmentShape::Arc {
                center: self.point(*center),
                radius: *radius,
                start_angle: start_angle + self.theta,
                end_angle: end_angle + self.theta,
            },
            SegmentShape::Meshed(c) => SegmentShape::Meshed(
                MeshedCurve::new(c.points().iter().map(|&p| self.point(p)).collect()).unwrap(),
            ),
        };
        out
    }
    fn model(&self, m: &BemModel) -> BemModel {
        let regions = m
            .regions
            .iter()
            .map(|r| Region {
                name: r.name.clone(),
                material: r.material,
                loops: r
                    .loops
                    .iter()
                    .map(|l| {
                        l.iter()
                            .map(|it| match it {
                                LoopItem::Segment(s) => LoopItem::Segment(self.segment(s)),
                                LoopItem::Shared(n) => LoopItem::Shared(n.clone()),
                            })
                            .collect()
                    })
                    .collect(),
                body_forces: r
                    .body_forces
                    .iter()
                    .map(|f| match *f {
                        BodyForce::Gravity {
                            density,
                            acceleration,
                        } => BodyForce::gravity(density, self.rot(acceleration)),
                        BodyForce::Centrifugal {
                            density,
                            angular_velocity,
                            center,
                        } => BodyForce::centrifugal(density, angular_velocity, self.point(center)),
                    })
                    .collect(),
            })
            .collect();
        BemModel::new(m.plane, regions)
    }
}

fn steel() -> ElasticMaterial {
    ElasticMaterial::new(210e9, 0.3).unwrap()
}

/// A 20 mm x 10 mm block with a circular hole (r = 3 mm), centred at the origin, every outer
/// segment graded 1:50 toward both ends, under a body force: the left face fixed, the right
/// face loaded by a traction (given in global axes, rotated with the model).
fn holed_block() -> BemModel {
    let g = Grading::BothEnds(50.0);
    let (a, b) = (0.010, 0.005);
    BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "blk",
            steel(),
            vec![
                Segment::line("bottom", [-a, -b], [a, -b], 10).graded(g),
                Segment::line("right", [a, -b], [a, b], 6).graded(g),
                Segment::line("top", [a, b], [-a, b], 10).graded(g),
                Segment::line("left", [-a, b], [-a, -b], 6).graded(g),
            ],
        )
        .with_hole(vec![
            Segment::arc("hole_a", [0.0, 0.0], 0.003, PI, 0.0, 8),
            Segment::arc("hole_b", [0.0, 0.0], 0.003, 2.0 * PI, PI, 8),
        ])
        .with_body_force(BodyForce::gravity(7800.0, [2e5, -9e5]))],
    )
}

fn block_bcs(m: &Motion) -> BoundaryConditions {
    let t = m.rot([40e6, 15e6]);
    BoundaryConditions::new()
        .set("left", SegmentBc::fixed())
        .set(
            "right",
            SegmentBc::traction(Profile::Uniform(t[0]), Profile::Uniform(t[1])),
        )
}

fn max_abs<'a>(v: impl Iterator<Item = &'a f64>) -> f64 {
    v.fold(0.0_f64, |m, x| {
        assert!(x.is_finite());
        m.max(x.abs())
    })
}

/// max |R a - b| / max |a| over nodal vectors (same node numbering).
fn vector_error(m: &Motion, a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = max_abs(a.iter().flatten());
    let mut e = 0.0_f64;
    for (x, y) in a.iter().zip(b) {
        let rx = m.rot(*x);
        e = e.max((rx[0] - y[0]).abs()).max((rx[1] - y[1]).abs());
    }
    e / scale
}

/// Relative errors (u, t, sigma) of the block moved by `m` against the block at the origin.
fn block_errors(m: &Motion) -> (f64, f64, f64) {
    let id = Motion {
        theta: 0.0,
        shift: [0.0; 2],
    };
    let base = BemProblem::new(&holed_block())
        .unwrap()
        .solve(&block_bcs(&id))
        .unwrap();
    let moved = BemProblem::new(&m.model(&holed_block()))
        .unwrap()
        .solve(&block_bcs(m))
        .unwrap();
    let eu = vector_error(m, &base.displacement[0], &moved.displacement[0]);
    let et = vector_error(m, &base.traction[0], &moved.traction[0]);
    let pts = [
        [0.0, 0.0045],
        [-0.008, -0.004],
        [0.0062, 0.0],
        [0.0095, 0.0049],
    ];
    let mut es = 0.0_f64;
    let mut scale = 0.0_f64;
    for p in pts {
        let s0 = base.stress_at(p).unwrap();
        let s1 = moved.stress_at(m.point(p)).unwrap();
        let want = m.stress([s0.xx, s0.yy, s0.xy]);
        scale = scale.max(s0.xx.abs()).max(s0.yy.abs()).max(s0.xy.abs());
        for (a, b) in want.iter().zip([s1.xx, s1.yy, s1.xy]) {
            es = es.max((a - b).abs());
        }
    }
    (eu, et, es / scale)
}

/// The reproduction of the issue: the graded block moved to x in [-100, -80] mm (its
/// smallest elements 1e-4 of their distance from the origin) solved with "LU solve failed"
/// (NaN kernels from r rounded to 0 in the singular rule).
#[test]
fn graded_block_far_from_origin_matches_block_at_origin() {
    for shift in [[-0.090, 0.0], [0.2, 0.1], [-20.0, 13.0]] {
        let m = Motion { theta: 0.0, shift };
        let (eu, et, es) = block_errors(&m);
        assert!(
            eu < 1e-9 && et < 1e-9 && es < 1e-9,
            "shift {shift:?}: u {eu:.2e}, t {et:.2e}, sigma {es:.2e}"
        );
    }
}

/// The cylinder-on-block Hertz model ([`super::contact::reference::cylinder_on_block_model`],
/// friction 0.3) under force control in both directions (P down and 0.1 P along x, given in
/// global axes and rotated with the model).
fn contact_result(m: &Motion) -> ContactStepResult {
    contact_result_of(
        &super::contact::reference::cylinder_on_block_model(24, 30).unwrap(),
        m,
    )
}

/// [`contact_result`] of the model `base` moved by `m`.
fn contact_result_of(base: &BemModel, m: &Motion) -> ContactStepResult {
    let bcs = BoundaryConditions::new().set("block_bottom", SegmentBc::fixed());
    let mut cp = ContactProblem::new(
        &m.model(base),
        &bcs,
        &[ContactPair::new("cyl_contact", "block_contact", 0.3)],
        &["cyl_face"],
    )
    .unwrap();
    let f = m.rot([0.1 * P, -P]);
    let step = LoadStep {
        external: 1.0,
        rigid: vec![RigidControl::new(
            "cyl_face",
            Control::Force(f[0]),
            Control::Force(f[1]),
        )],
        groups: vec![],
    };
    cp.solve_steps(&[step], &ContactOptions::default())
        .unwrap()
        .remove(0)
}

/// Relative errors (pressure, shear, contact width, rigid translation) of the contact
/// model moved by `m`.
fn contact_errors(base: &ContactStepResult, m: &Motion) -> (f64, f64, f64, f64) {
    moved_contact_errors(base, &contact_result(m), m)
}

/// Relative errors (pressure, shear, contact width, rigid translation) of `moved` (the
/// result of the model moved by `m`) against `base`.
fn moved_contact_errors(
    base: &ContactStepResult,
    moved: &ContactStepResult,
    m: &Motion,
) -> (f64, f64, f64, f64) {
    let (a, b) = (&base.pairs[0].nodes, &moved.pairs[0].nodes);
    assert_eq!(a.len(), b.len());
    let pmax = max_abs(a.iter().map(|n| &n.pressure));
    let ep = a
        .iter()
        .zip(b)
        .fold(0.0_f64, |e, (x, y)| e.max((x.pressure - y.pressure).abs()))
        / pmax;
    let eq = a
        .iter()
        .zip(b)
        .fold(0.0_f64, |e, (x, y)| e.max((x.shear - y.shear).abs()))
        / pmax;
    let width = |nodes: &[super::contact::ContactNode], m: &Motion| {
        // Extent of the contact nodes along the rotated x axis, relative to the shift.
        let ax = m.rot([1.0, 0.0]);
        let xs: Vec<f64> = nodes
            .iter()
            .filter(|n| n.pressure > 0.0)
            .map(|n| (n.position[0] - m.shift[0]) * ax[0] + (n.position[1] - m.shift[1]) * ax[1])
            .collect();
        let hi = xs.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        let lo = xs.iter().cloned().fold(f64::INFINITY, f64::min);
        hi - lo
    };
    let id = Motion {
        theta: 0.0,
        shift: [0.0; 2],
    };
    let (w0, w1) = (width(a, &id), width(b, m));
    let ew = (w0 - w1).abs() / w0;
    let (t0, t1) = (m.rot(base.rigid[0].translation), moved.rigid[0].translation);
    let et = (t0[0] - t1[0]).abs().max((t0[1] - t1[1]).abs()) / t0[0].hypot(t0[1]);
    (ep, eq, ew, et)
}

/// The bound on the relative change of the contact pressures and shears of a model moved
/// inexactly by a shift of length `dist` (m), where the moved model's defining points are
/// rounded independently (up to ulp(dist) / 2 = 1.1e-16 dist each): measured on the model
/// at rest with every defining point perturbed at random by +-1.8e-15 m (the rounding at
/// 20 m), the pressures change by 1.2e-9 of p0 (shears 3.6e-10), i.e. 6.7e5 per metre of
/// input error, or 7.4e-11 dist/m; 5e-10 dist/m leaves a factor of about 7 for unlucky
/// roundings, and 1e-9 covers the rounding of the rotation itself. A pressure is this
/// sensitive because a gap change dg moves it by about E* dg / h (E* = 115 GPa, h = 5 um:
/// 2.3e16 Pa/m, i.e. 4e7 p0 per metre at most). Exact motions stay within 1e-9 at any
/// distance ([`contact_is_invariant_under_exact_rigid_motions`]).
fn inexact_bound(dist: f64) -> f64 {
    1e-9 + 5e-10 * dist
}

/// Contact under translation (the shipped gmsh example failed at a shift of (0.2, 0.1) m):
/// contact width and the rigid face's motion agree to 1e-9, pressures and shears to
/// [`inexact_bound`] (the moved model's points are rounded).
#[test]
fn contact_far_from_origin_matches_contact_at_origin() {
    let estar = 210e9 / (2.0 * (1.0 - 0.09));
    let (b, _) = hertz(R, estar, P);
    let id = Motion {
        theta: 0.0,
        shift: [0.0; 2],
    };
    let base = contact_result(&id);
    assert!(base.pairs[0].nodes.iter().any(|n| n.pressure > 0.0));
    for (theta, shift) in [(0.0, [0.2, 0.1]), (FRAC_PI_2 / 3.0, [-3.0, 7.0])] {
        let m = Motion { theta, shift };
        let (ep, eq, ew, et) = contact_errors(&base, &m);
        let tol = inexact_bound(shift[0].hypot(shift[1]));
        assert!(
            ep < tol && eq < tol && ew < 1e-9 && et < 1e-9,
            "theta {theta}, shift {shift:?} (b = {b:.3e} m): p {ep:.2e}, q {eq:.2e}, \
             width {ew:.2e}, translation {et:.2e}"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(8))]

    /// Random rigid motions (any rotation, translations up to 1e3 times the 20 mm model
    /// size) of the graded, holed block under a body force and a traction.
    #[test]
    fn block_is_invariant_under_random_rigid_motions(
        theta in 0.0..(2.0 * PI),
        dir in 0.0..(2.0 * PI),
        log_dist in -3.0_f64..1.3,
    ) {
        let d = 10f64.powf(log_dist);
        let m = Motion { theta, shift: [d * dir.cos(), d * dir.sin()] };
        let (eu, et, es) = block_errors(&m);
        prop_assert!(
            eu < 1e-9 && et < 1e-9 && es < 1e-9,
            "{m:?}: u {eu:.2e}, t {et:.2e}, sigma {es:.2e}"
        );
    }

    /// Random rigid motions of the frictional contact model (translations up to 1e3 times
    /// its 20 mm size).
    #[test]
    fn contact_is_invariant_under_random_rigid_motions(
        theta in 0.0..(2.0 * PI),
        dir in 0.0..(2.0 * PI),
        log_dist in -3.0_f64..1.3,
    ) {
        let id = Motion { theta: 0.0, shift: [0.0; 2] };
        let base = contact_result(&id);
        let d = 10f64.powf(log_dist);
        let m = Motion { theta, shift: [d * dir.cos(), d * dir.sin()] };
        let (ep, eq, ew, et) = contact_errors(&base, &m);
        // Pressures and shears to `inexact_bound` (the moved model's defining points are
        // rounded; 1.1e-8 at 20 m, measured up to 1.4e-9); width and translation to 1e-9.
        let tol = inexact_bound(d);
        prop_assert!(
            ep < tol && eq < tol && ew < 1e-9 && et < 1e-9,
            "{m:?}: p {ep:.2e}, q {eq:.2e}, width {ew:.2e}, translation {et:.2e}"
        );
    }
}
/// Snaps a coordinate to the grid of 2^-40 m (0.9 pm): the points of a model on this grid
/// move exactly under translations on the grid up to 2^12 m (45 significant bits).
fn snap(x: f64) -> f64 {
    let g = (-40f64).exp2();
    (x / g).round() * g
}

/// [`super::contact::reference::cylinder_on_block_model`] with its line ends and arc
/// centres snapped to the grid of [`snap`] (its arcs' radii need no snapping: an arc moves
/// with its centre).
fn snapped_contact_model() -> BemModel {
    let sp = |p: [f64; 2]| [snap(p[0]), snap(p[1])];
    let mut out = super::contact::reference::cylinder_on_block_model(24, 30).unwrap();
    for r in &mut out.regions {
        for it in r.loops.iter_mut().flatten() {
            if let LoopItem::Segment(s) = it {
                s.shape = match &s.shape {
                    SegmentShape::Line { start, end } => SegmentShape::Line {
                        start: sp(*start),
                        end: sp(*end),
                    },
                    SegmentShape::Arc {
                        center,
                        radius,
                        start_angle,
                        end_angle,
                    } => SegmentShape::Arc {
                        center: sp(*center),
                        radius: *radius,
                        start_angle: *start_angle,
                        end_angle: *end_angle,
                    },
                    SegmentShape::Meshed(c) => SegmentShape::Meshed(
                        MeshedCurve::new(c.points().iter().map(|&p| sp(p)).collect()).unwrap(),
                    ),
                };
            }
        }
    }
    out
}

/// Exact rigid motions (translations on the grid of [`snap`] up to 1e3 times the model
/// size, quarter turns) of the frictional contact model: the moved model is the same model,
/// so that everything the solver does is covariant only if the results agree to 1e-9
/// (measured 3e-11 to 4e-11 for pressures, 1e-14 to 8e-14 for the translation, the same at
/// 0.25 m as at 24 m: no loss with distance; the model-local origin moves by the translation
/// only up to the rounding of the arcs' extents, radius 10 mm, which leaves this floor: a
/// perturbation of the points by 1e-18 m gives the same 5e-11). A random rotation (0.3 rad) at rest gives
/// 8e-11 (only the arc nodes round); the same rotation with the shift (20, -13) m gives 1.3e-9
/// (the rounding of the moved points, [`inexact_bound`]).
#[test]
fn contact_is_invariant_under_exact_rigid_motions() {
    let model = snapped_contact_model();
    let id = Motion {
        theta: 0.0,
        shift: [0.0; 2],
    };
    let base = contact_result_of(&model, &id);
    for (theta, shift) in [
        (0.0, [0.25, 0.125]),
        (0.0, [snap(0.2), snap(0.1)]),
        (0.0, [snap(-3.0), snap(7.0)]),
        (0.0, [snap(20.0), snap(-13.0)]),
        (FRAC_PI_2, [0.0, 0.0]),
        (PI, [snap(-17.3), snap(4.1)]),
        (3.0 * FRAC_PI_2, [snap(20.0), snap(-13.0)]),
    ] {
        let m = Motion { theta, shift };
        let moved = contact_result_of(&model, &m);
        let (ep, eq, ew, et) = moved_contact_errors(&base, &moved, &m);
        assert!(
            ep < 1e-9 && eq < 1e-9 && ew < 1e-9 && et < 1e-9,
            "theta {theta}, shift {shift:?}: p {ep:.2e}, q {eq:.2e}, width {ew:.2e}, \
             translation {et:.2e}"
        );
    }
}

/// The Hertz cylinder of [`contact_result`] held only by contact and friction (f = 0.3; a
/// pressure P / (2R) on its cut face, no rigid segment: all three rigid modes free, held by
/// the contact pressure and by stick) in the model moved by `m`.
fn free_contact_result(m: &Motion) -> ContactStepResult {
    let base = super::contact::reference::cylinder_on_block_model(24, 30).unwrap();
    let bcs = BoundaryConditions::new()
        .set("block_bottom", SegmentBc::fixed())
        .set(
            "cyl_face",
            SegmentBc::Pressure(Profile::Uniform(P / (2.0 * R))),
        );
    let mut cp = ContactProblem::new(
        &m.model(&base),
        &bcs,
        &[ContactPair::new("cyl_contact", "block_contact", 0.3)],
        &[],
    )
    .unwrap();
    cp.solve_steps(&[LoadStep::new(1.0)], &ContactOptions::default())
        .unwrap()
        .remove(0)
}

/// A body held only by contact (free rigid modes, removed by artificial supports) turned by
/// angles that are not multiples of 90 deg, at rest: contact pressures and shears agree to
/// 1e-9 of p_max ([`inexact_bound`] at no shift: only the turned points round; measured
/// 5.7e-11 to 6.6e-11), the free body's least-squares translation (rotated) and rotation
/// (as R times it) to 1e-9 of the translation (measured up to 1.7e-11). With the supports
/// along the global x and y axes (before) 0.3 rad gave shears 1.5e-8 of p_max apart and
/// translations 1.9e-7 (the symmetric load leaves the pressures at 4.6e-10; the CLI's
/// free block, loaded off its centre line, differed by 2.7e-4 of p_max): the supports'
/// reactions, the BEM's equilibrium defect, acted along directions that did not turn with
/// the model; the supports now turn with the body (a node's whole displacement and a second
/// node's component normal to the line between them).
#[test]
fn free_body_contact_is_invariant_under_any_rotation() {
    let id = Motion {
        theta: 0.0,
        shift: [0.0; 2],
    };
    let base = free_contact_result(&id);
    assert_eq!(base.free_bodies[0].free_modes.len(), 3);
    for theta in [0.3, 2.1, -1.0] {
        let m = Motion {
            theta,
            shift: [0.0; 2],
        };
        let moved = free_contact_result(&m);
        let (a, b) = (&base.pairs[0].nodes, &moved.pairs[0].nodes);
        assert_eq!(a.len(), b.len());
        let pmax = max_abs(a.iter().map(|n| &n.pressure));
        let ep = a
            .iter()
            .zip(b)
            .fold(0.0_f64, |e, (x, y)| e.max((x.pressure - y.pressure).abs()))
            / pmax;
        let eq = a
            .iter()
            .zip(b)
            .fold(0.0_f64, |e, (x, y)| e.max((x.shear - y.shear).abs()))
            / pmax;
        let (f0, f1) = (&base.free_bodies[0], &moved.free_bodies[0]);
        let t0 = m.rot(f0.translation);
        let et = (t0[0] - f1.translation[0])
            .abs()
            .max((t0[1] - f1.translation[1]).abs())
            / t0[0].hypot(t0[1]);
        // The rotation (near 0: the load is symmetric) as the motion R dphi of the
        // cylinder's surface, relative to the translation.
        let er = (f0.rotation - f1.rotation).abs() * R / t0[0].hypot(t0[1]);
        let tol = inexact_bound(0.0);
        assert!(
            ep < tol && eq < tol && et < 1e-9 && er < 1e-9,
            "theta {theta}: p {ep:.2e}, q {eq:.2e}, translation {et:.2e}, rotation {er:.2e}"
        );
        eprintln!("theta {theta}: p {ep:.2e}, q {eq:.2e}, translation {et:.2e}, rotation {er:.2e}");
    }
}
