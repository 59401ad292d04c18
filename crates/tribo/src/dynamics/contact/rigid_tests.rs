//! Rigid segments in the dynamic march (`rigid.rs`): the 1D column driven through a rigid
//! end face (impedance rho c A), and a rigid punch pressed slowly onto a base against the
//! static contact solver with the same rigid segment.

use super::*;
use crate::dynamics::testing::{column_material, rectangle};
use crate::kernels::kelvin2d::PlaneCondition;
use crate::material::ElasticMaterial;
use crate::operators::bem2d::{Region, Segment};
use crate::solvers::bem2d::contact::{ContactProblem, Control, LoadStep, RigidControl};
use crate::solvers::bem2d::SegmentBc;

/// The column L = 1 x W = 0.25 (E = rho = 1, nu = 0: c = 1, the 1D solution exact in plane
/// strain) with its end face x = 0 ("left") a rigid segment, the far end on rollers.
fn rigid_column(nx: usize, ny: usize, x: Control, time: TimeFunction) -> DynamicContact {
    let model = rectangle(column_material(), 1.0, 0.25, nx, ny);
    let bcs = BoundaryConditions::new().set("right", SegmentBc::roller_x());
    let rigid = DynamicRigid::new("left", x, Control::Displacement(0.0))
        .unwrap()
        .with_time(time);
    DynamicContact::with_rigid(&model, &[1.0], &bcs, &[], &[rigid], &[], &[]).unwrap()
}

/// A sudden force F on the rigid end face of the column (nu = 0): the face is a plane
/// wave source into a medium of impedance rho c, so it moves with v = F / (rho c A)
/// (A = W per unit thickness) until the reflection from the fixed end returns at
/// t = 2 L / c: U(t) = F t / (rho c A) (Graff 1975, longitudinal waves in rods). F = 0.25,
/// A = 0.25: U = t. Displacement control with U = t gives the reaction F = rho c A v = 0.25.
///
/// Measured (BDF2, dt = 0.05, 8 x 2 elements): force control U - t = 0.0249, 0.0250,
/// 0.0246 at t = 0.5, 1, 1.5: the BDF2 start-up offset of a jump sampled at t_0 (the load
/// acts as if applied dt/2 earlier; first order at a jump, docs/theory/DYNAMICS.md sec. 5.8
/// "The start"), the velocity between t = 1 and 1.5 0.99922, the force equation to
/// round-off (2e-12); the reaction of the displacement control within 2 % of 0.25 over
/// t = 0.5 .. 1.5, 2.4 % high at 1.65 (the BDF2-smeared precursor of the reflection that
/// returns at 2 L / c). Tolerances: U within dt of t (the start-up offset is dt/2), the
/// velocity within 2 %, the force row 1e-11, the reaction within 2 % over 0.5 .. 1.5. A wrong sign of the force row or a missing
/// Schur complement gives O(1) errors; a wrong weight w_k a wrong impedance.
#[test]
fn rigid_end_of_a_column_moves_with_the_impedance_velocity() {
    let dt = 0.05;
    let steps = 38; // t = 1.9 < 2 L / c
    let force = rigid_column(
        8,
        2,
        Control::Force(0.25),
        TimeFunction::constant(1.0).unwrap(),
    );
    let params = DynamicContactParams::new(dt, steps);
    let res = force.march(&params, &mut |_| {}).unwrap();
    let at = |t: f64| &res.steps[(t / dt).round() as usize];
    let mut worst = 0.0_f64;
    for t in [0.5, 1.0, 1.5] {
        let s = at(t);
        let u = s.rigid[0].translation;
        eprintln!(
            "force control t = {t}: U = {:?}, F = {:?}",
            u, s.rigid[0].force
        );
        worst = worst.max((u[0] - t).abs());
        assert!((s.rigid[0].force[0] - 0.25).abs() < 1e-11);
        assert!(u[1].abs() < 1e-14);
    }
    let v = (at(1.5).rigid[0].translation[0] - at(1.0).rigid[0].translation[0]) / 0.5;
    eprintln!("force control: max |U - t| {worst:.3e}, velocity {v:.5}");
    assert!(worst < dt, "{worst}");
    assert!((v - 1.0).abs() < 0.02, "{v}");
    // The work of the rigid force is the input: trapezoidal from rest, W = F U_n - F U_0 / 2
    // (the jump at t_0 takes half its step's work, as a load's step does).
    let last = at(1.5);
    let w = last.energy.external_work;
    let u0 = res.steps[0].rigid[0].translation[0];
    let expected = 0.25 * (last.rigid[0].translation[0] - 0.5 * u0);
    assert!((w - expected).abs() < 1e-12, "work {w} vs {expected}");

    let ramp = TimeFunction::table(vec![[0.0, 0.0], [10.0, 10.0]]).unwrap();
    let disp = rigid_column(8, 2, Control::Displacement(1.0), ramp);
    let res = disp.march(&params, &mut |_| {}).unwrap();
    for s in res.steps.iter().skip(10).take(21) {
        let r = s.rigid[0];
        assert!((r.translation[0] - s.time).abs() < 1e-12);
        assert!(
            (r.force[0] - 0.25).abs() < 0.02 * 0.25,
            "t = {}: reaction {:?}",
            s.time,
            r.force
        );
    }
    eprintln!(
        "displacement control: reaction at t = 1.5: {:?}",
        res.steps[30].rigid[0].force
    );
}

/// A block (1 x 0.5) pressed onto a base (2 x 1, bottom fixed) through its top face, a
/// rigid segment guided in x and force-controlled in y (E = 1, nu = 0.3, f = 0.3).
fn punch_on_base() -> (BemModel, BoundaryConditions, ContactPair) {
    let m = ElasticMaterial::new(1.0, 0.3).unwrap();
    let base = Region::new(
        "base",
        m,
        vec![
            Segment::line("base_bottom", [-1.0, -1.0], [1.0, -1.0], 6),
            Segment::line("base_right", [1.0, -1.0], [1.0, 0.0], 3),
            Segment::line("base_top", [1.0, 0.0], [-1.0, 0.0], 12),
            Segment::line("base_left", [-1.0, 0.0], [-1.0, -1.0], 3),
        ],
    );
    let block = Region::new(
        "block",
        m,
        vec![
            Segment::line("block_bottom", [-0.5, 0.0], [0.5, 0.0], 12),
            Segment::line("block_right", [0.5, 0.0], [0.5, 0.5], 3),
            Segment::line("block_top", [0.5, 0.5], [-0.5, 0.5], 4),
            Segment::line("block_left", [-0.5, 0.5], [-0.5, 0.0], 3),
        ],
    );
    let model = BemModel::new(PlaneCondition::Strain, vec![base, block]);
    let bcs = BoundaryConditions::new().set("base_bottom", SegmentBc::fixed());
    (
        model,
        bcs,
        ContactPair::new("block_bottom", "base_top", 0.3),
    )
}

/// A rigid punch pressed slowly (force ramp (1 - cos)/2 over 40, about 30 transit times)
/// equals the static solution with the same rigid segment (20 load increments, the same
/// monotone path): the punch's translation, the reaction, and p, q at every slave node.
/// Measured: see the printed line (the quasi-static error (T_tr / T0)^2 ~ 3e-3 plus the
/// free vibration left by the ramp). Tolerances: translation 1 %, p and q 1 % of max p
/// (as the slow ramp without rigid segments, `slow_ramp_reproduces_the_static_contact_solution`);
/// the force equation to round-off. A wrong Schur complement or prediction gives the
/// punch a wrong stiffness: errors of order one.
#[test]
fn slow_rigid_punch_reproduces_the_static_solution() {
    let (model, bcs, pair) = punch_on_base();
    let fy = -0.01;
    let mut stat =
        ContactProblem::new(&model, &bcs, std::slice::from_ref(&pair), &["block_top"]).unwrap();
    let increments: Vec<LoadStep> = (1..=20)
        .map(|k| {
            LoadStep::new(1.0).with_rigid(RigidControl::new(
                "block_top",
                Control::Displacement(0.0),
                Control::Force(fy * k as f64 / 20.0),
            ))
        })
        .collect();
    let res = stat
        .solve_steps(&increments, &ContactOptions::default())
        .unwrap();
    let last_static = res.last().unwrap();
    let reference = &last_static.pairs[0];
    let u_static = last_static.rigid[0].translation;
    let rigid = DynamicRigid::new("block_top", Control::Displacement(0.0), Control::Force(fy))
        .unwrap()
        .with_time(TimeFunction::ramp(0.0, 40.0).unwrap());
    let problem =
        DynamicContact::with_rigid(&model, &[1.0, 1.0], &bcs, &[pair], &[rigid], &[], &[]).unwrap();
    let dynamic = problem
        .march(&DynamicContactParams::new(0.5, 90), &mut |_| {})
        .unwrap();
    let end = dynamic.steps.last().unwrap();
    let last = &end.pairs[0];
    let u = end.rigid[0].translation;
    assert!((end.rigid[0].force[1] - fy).abs() < 1e-12 * fy.abs());
    assert!(u[0].abs() < 1e-15);
    let pmax = reference
        .nodes
        .iter()
        .map(|n| n.pressure)
        .fold(0.0_f64, f64::max);
    let (mut ep, mut eq) = (0.0_f64, 0.0_f64);
    let covered: Vec<_> = reference
        .nodes
        .iter()
        .filter(|n| n.state != ContactState::Outside)
        .collect();
    assert_eq!(last.nodes.len(), covered.len());
    for (d, s) in last.nodes.iter().zip(&covered) {
        ep = ep.max((d.pressure - s.pressure).abs());
        eq = eq.max((d.shear - s.shear).abs());
    }
    let eu = (u[1] / u_static[1] - 1.0).abs();
    eprintln!(
        "slow rigid punch vs static: U_y {:.6e} vs {:.6e} ({eu:.2e}), max |p - ps| {:.3e}, \
         |q - qs| {:.3e} of p_max {pmax:.4e}; normal force {:.6e}",
        u[1],
        u_static[1],
        ep / pmax,
        eq / pmax,
        last.sample.normal_force
    );
    assert!(eu < 0.01, "{eu}");
    assert!(ep < 0.01 * pmax && eq < 0.01 * pmax);
}

/// Bad rigid segments are errors naming the item.
#[test]
fn bad_rigid_segments_are_refused() {
    let (model, bcs, pair) = punch_on_base();
    let cases: [(DynamicRigid, &str); 3] = [
        (
            DynamicRigid::new("nowhere", Control::Force(0.0), Control::Force(0.0)).unwrap(),
            "names no segment",
        ),
        (
            DynamicRigid::new("block_bottom", Control::Force(0.0), Control::Force(0.0)).unwrap(),
            "contact pair",
        ),
        (
            DynamicRigid::new("block_top", Control::Force(f64::NAN), Control::Force(0.0)).unwrap(),
            "finite",
        ),
    ];
    for (r, rule) in cases {
        let e = DynamicContact::with_rigid(
            &model,
            &[1.0, 1.0],
            &bcs,
            std::slice::from_ref(&pair),
            &[r],
            &[],
            &[],
        )
        .unwrap_err();
        let text = e.to_string();
        assert!(
            text.contains("rigid_segment[0]") && text.contains(rule),
            "{text}"
        );
    }
}
