//! Verification of the 2D BEM contact solver against closed forms (Johnson 1985 ch. 4 and 7;
//! docs/theory/BEM2D.md A4-A6).

use std::f64::consts::PI;

use super::reference::{
    block, cylinder_on_block, cylinder_on_block_model, cylinder_on_block_rule, fit_pair,
    flat_punch, half_cylinder, hertz, nowell_hills, nowell_hills_exact, press, press_face,
    punch_step, shear_step, stick_zone, NOWELL_HILLS, P, PUNCH_A, R,
};
use super::*;
use crate::kernels::kelvin2d::PlaneCondition;
use crate::kernels::quadrature::gauss_legendre;
use crate::material::ElasticMaterial;
use crate::operators::bem2d::{Grading, Region, Segment};
use crate::solvers::bem2d::{Component, Profile};

fn steel() -> ElasticMaterial {
    ElasticMaterial::new(210e9, 0.3).unwrap()
}

fn pressure_error(pr: &PairResult, b: f64, p0: f64, within: f64) -> f64 {
    let mut emax = 0.0_f64;
    for n in &pr.nodes {
        let x = n.position[0];
        if x.abs() < within * b {
            let ph = p0 * (1.0 - x * x / (b * b)).sqrt();
            emax = emax.max((n.pressure - ph).abs() / p0);
        }
    }
    emax
}

/// Frictionless Hertz, steel half cylinder R = 10 mm on a steel block, P = 100 N/mm
/// (docs/theory/BEM2D.md A4: b = 0.10505 mm, p0 = 606.04 MPa). Slave: 48 elements over |x| <= 2b
/// (24 across the contact), master: 40 (20 across). Measured (weighted rule): b and p0 from
/// the least-squares semi-ellipse within 0.3 %, max |p - p_H| / p0 = 0.97 % over |x| < 0.9 b
/// (the largest next to the edge, where the sqrt profile is not polynomial); the collocated
/// node-to-segment rule gives the same to 0.1 %. Tolerances: 1 % on b and p0, 1.5 % on
/// p(x) (the brief's "about 1 %" with the edge element's interpolation error).
#[test]
fn hertz_cylinder_on_block() {
    let estar = 210e9 / (2.0 * (1.0 - 0.09));
    let (b, p0) = hertz(R, estar, P);
    assert!((b - 0.10505e-3).abs() < 1e-7 && (p0 - 606.04e6).abs() < 0.1e6);
    for rule in [GapRule::Weighted, GapRule::NodeToSegment] {
        let mut cp = cylinder_on_block_rule(0.0, 48, 40, rule).unwrap();
        let res = cp
            .solve_steps(&[press(P)], &ContactOptions::default())
            .unwrap();
        let step = &res[0];
        let pr = &step.pairs[0];
        let (p0f, bf) = fit_pair(pr);
        let ep = pressure_error(pr, b, p0, 0.9);
        eprintln!(
            "Hertz cylinder/block {rule:?}: b {:+.2e}, p0 {:+.2e}, max |p - pH|/p0 {ep:.2e}, \
             iterations {}, residual {:.1e}",
            bf / b - 1.0,
            p0f / p0 - 1.0,
            step.iterations,
            step.residual
        );
        assert!((bf / b - 1.0).abs() < 0.01, "b {bf:e} vs {b:e}");
        assert!((p0f / p0 - 1.0).abs() < 0.01, "p0 {p0f:e} vs {p0:e}");
        assert!(ep < 0.015, "p(x) error {ep:.3e}");
        assert!(step.residual < 1e-10);
        assert!(pr.nodes.iter().all(|n| n.shear == 0.0));
        // Equilibrium: the rigid face carries the applied force (a solved equation: round-off),
        // the master receives exactly the slave's force (the transfer conserves it: round-off),
        // and the cylinder's BEM equilibrium (contact force vs face force) holds to the
        // discretization error (measured 9e-6).
        let f = step.rigid[0].force;
        assert!(
            (f[1] + P).abs() < 1e-10 * P && f[0].abs() < 1e-10 * P,
            "{f:?}"
        );
        for d in 0..2 {
            assert!((pr.slave_force[d] + pr.master_force[d]).abs() < 1e-10 * P);
        }
        assert!(
            (pr.slave_force[1] - P).abs() < 1e-4 * P,
            "{:?}",
            pr.slave_force
        );
    }
    // The full boundary state of the step gives the subsurface field (McEwen; docs/theory/BEM2D.md A4):
    // on the axis sigma_z = -p0 / sqrt(1 + z'^2), and max |sigma_x - sigma_z| / 2 =
    // 0.3003 p0 at z = 0.7862 b. Measured: sigma_y within 1e-4 p0; sigma_x offset by a
    // near-uniform +0.0075 p0 at every depth (the finite 10 mm block's own global stress, which
    // the half-plane solution lacks); tau_max 0.304 p0. Tolerance 1 % of p0.
    let mut cp = cylinder_on_block(0.0, 48, 40).unwrap();
    let res = cp
        .solve_steps(&[press(P)], &ContactOptions::default())
        .unwrap();
    let sol = &res[0].solution;
    for zr in [0.5, 0.7862, 1.0, 2.0] {
        let s = sol.stress_at([0.0, -zr * b]).unwrap();
        let sz = -p0 / (1.0 + zr * zr).sqrt();
        let sx = -p0 * ((1.0 + 2.0 * zr * zr) / (1.0 + zr * zr).sqrt() - 2.0 * zr);
        eprintln!(
            "McEwen z/b {zr}: sigma_y {:.4} ({:.4}), sigma_x {:.4} ({:.4}) p0",
            s.yy / p0,
            sz / p0,
            s.xx / p0,
            sx / p0
        );
        assert!((s.yy - sz).abs() < 0.01 * p0 && (s.xx - sx).abs() < 0.01 * p0);
    }
    let s = sol.stress_at([0.0, -0.7862 * b]).unwrap();
    let tau = 0.5 * (s.xx - s.yy).hypot(2.0 * s.xy);
    assert!(
        (tau / p0 - 0.3003).abs() < 0.01,
        "tau_max {:.4} p0",
        tau / p0
    );
    // Refinement: 96 / 80 elements (measured 0.05 %).
    let mut cp = cylinder_on_block(0.0, 96, 80).unwrap();
    let res = cp
        .solve_steps(&[press(P)], &ContactOptions::default())
        .unwrap();
    let ep = pressure_error(&res[0].pairs[0], b, p0, 0.9);
    eprintln!("Hertz cylinder/block 96/80: max |p - pH|/p0 {ep:.2e}");
    assert!(ep < 0.005, "refined p(x) error {ep:.3e}");
}

/// Two steel half cylinders R1 = R2 = 10 mm, P = 100 N/mm (docs/theory/BEM2D.md A4: b = 0.07428 mm,
/// p0 = 857.07 MPa), 48 / 40 elements over |x| <= 2 b. Same tolerances as above.
#[test]
fn hertz_two_cylinders() {
    let estar = 210e9 / (2.0 * (1.0 - 0.09));
    let (b, p0) = hertz(R / 2.0, estar, P);
    assert!((b - 0.07428e-3).abs() < 1e-7 && (p0 - 857.07e6).abs() < 0.1e6);
    let c = 2.0 * b;
    let model = BemModel::new(
        PlaneCondition::Strain,
        vec![
            half_cylinder("lower", steel(), R, c, 40, false),
            half_cylinder("upper", steel(), R, c, 48, true),
        ],
    );
    let bcs = BoundaryConditions::new().set("lower_face", SegmentBc::fixed());
    let mut cp = ContactProblem::new(
        &model,
        &bcs,
        &[ContactPair::new("upper_contact", "lower_contact", 0.0)],
        &["upper_face"],
    )
    .unwrap();
    let res = cp
        .solve_steps(&[press_face("upper_face", P)], &ContactOptions::default())
        .unwrap();
    let pr = &res[0].pairs[0];
    let (p0f, bf) = fit_pair(pr);
    let ep = pressure_error(pr, b, p0, 0.9);
    eprintln!(
        "Hertz two cylinders: b {:+.2e}, p0 {:+.2e}, max |p - pH|/p0 {ep:.2e}, iterations {}",
        bf / b - 1.0,
        p0f / p0 - 1.0,
        res[0].iterations
    );
    assert!((bf / b - 1.0).abs() < 0.01);
    assert!((p0f / p0 - 1.0).abs() < 0.01);
    assert!(ep < 0.015, "p(x) error {ep:.3e}");
}

/// Flat punch (Johnson 1985 sec. 5.2, eq. 5.31 with 2D plane strain; docs/theory/BEM2D.md A6): a block
/// 1000 times stiffer than the base, half-width a = 1 mm, pressed with P = 100 N/mm on a
/// steel block 40 a x 20 a. Frictionless: p = P / (pi sqrt(a^2 - x^2)). Both contact
/// segments span exactly |x| <= a and are graded toward the punch corners (ratio 4; with
/// uniform, non-matching elements the singular edge makes the pressure oscillate by 5-20 %
/// over the outer 20 %). Measured: 0.52 % over |x| <= 0.8 a, p(0) pi a / P = 1.0043, 1.5 %
/// over |x| <= 0.9 a. The FEM reference of docs/theory/BEM2D.md reaches 0.3-0.5 % at 0.5 a and 2.2 % at
/// 0.9 a with h = a/100. Tolerances: 1 % (0.8 a) and 2 % (0.9 a), the finite block and the
/// punch's finite stiffness (1e-3) adding a few 0.1 %.
#[test]
fn flat_punch_edge_singularity() {
    let a = PUNCH_A;
    let mut cp = flat_punch(a, Grading::BothEnds(4.0), GapRule::NodeToSegment).unwrap();
    let res = cp
        .solve_steps(&[punch_step()], &ContactOptions::default())
        .unwrap();
    let pr = &res[0].pairs[0];
    let mut emax = 0.0_f64;
    let mut emax9 = 0.0_f64;
    for n in &pr.nodes {
        let x = n.position[0];
        let exact = P / (PI * (a * a - x * x).sqrt());
        if x.abs() <= 0.8 * a {
            emax = emax.max((n.pressure / exact - 1.0).abs());
        }
        if x.abs() <= 0.9 * a {
            emax9 = emax9.max((n.pressure / exact - 1.0).abs());
        }
    }
    let p_mid = pr.nodes[pr.nodes.len() / 2].pressure * PI * a / P;
    eprintln!(
        "flat punch: max |p/p_exact - 1| over |x| <= 0.8a {emax:.2e}, 0.9a {emax9:.2e}, p(0) pi a / P = {p_mid:.4}, \
         touches the slave end {}, iterations {}",
        pr.touches_slave_end, res[0].iterations
    );
    assert!(pr.nodes.iter().all(|n| n.state == ContactState::Stick));
    assert!(emax < 0.01, "punch pressure error {emax:.3e}");
    assert!(emax9 < 0.02, "punch pressure error {emax9:.3e} (0.9 a)");
}

/// 2D Cattaneo-Mindlin (Johnson 1985 sec. 7.1, eq. 7.7-7.9): P then Q = 0.5 f P with
/// f = 0.3, same material: stick zone c = a sqrt(1 - Q/(f P)) = 0.7071 a, centred. Two
/// steps (friction is path dependent: the normal load first). Measured: c/a = 0.7124
/// (+0.74 %), centre -0.002 a, q(x) within 1 % of f p0 except the nodes next to the
/// stick/slip boundary (4 %: the sqrt kink of q there). Tolerance 3 % on c (a node spacing
/// is 4 % of a; the semi-ellipse fit of f p - |q| interpolates between nodes).
#[test]
fn cattaneo_mindlin_partial_slip() {
    let estar = 210e9 / (2.0 * (1.0 - 0.09));
    let (a, _) = hertz(R, estar, P);
    let f = 0.3;
    let q = 0.5 * f * P;
    let mut cp = cylinder_on_block(f, 48, 40).unwrap();
    let steps = [shear_step(0.0), shear_step(q)];
    let res = cp.solve_steps(&steps, &ContactOptions::default()).unwrap();
    let pr = &res[1].pairs[0];
    let (c, x0) = stick_zone(pr, f);
    let c_exact = a * (1.0 - q / (f * P)).sqrt();
    let nslip = pr
        .nodes
        .iter()
        .filter(|n| {
            matches!(
                n.state,
                ContactState::SlipPositive | ContactState::SlipNegative
            )
        })
        .count();
    eprintln!(
        "Cattaneo-Mindlin: c/a {:.4} (exact {:.4}, error {:+.2e}), centre {:+.2e} a, slip nodes \
         {nslip}, iterations {} / {}, residual {:.1e}",
        c / a,
        c_exact / a,
        c / c_exact - 1.0,
        x0 / a,
        res[0].iterations,
        res[1].iterations,
        res[1].residual
    );
    assert!(
        (c / c_exact - 1.0).abs() < 0.03,
        "c = {c:e}, exact {c_exact:e}"
    );
    assert!(x0.abs() < 0.03 * a);
    assert!(nslip > 0);
    // The tangential resultant is the applied Q (solved equation) and the slip zones obey
    // |q| = f p to round-off.
    assert!((res[1].rigid[0].force[0] - q).abs() < 1e-9 * P);
    for n in &pr.nodes {
        if matches!(
            n.state,
            ContactState::SlipPositive | ContactState::SlipNegative
        ) {
            assert!((n.shear.abs() - f * n.pressure).abs() < 1e-9 * f * n.pressure.max(1.0));
        }
        if n.state == ContactState::Stick {
            assert!(n.shear.abs() <= f * n.pressure * (1.0 + 1e-12));
            assert!(n.slip_increment.abs() < 1e-12 * a);
        }
    }
}

/// Nowell & Hills (Wear 136, 1990; docs/theory/BEM2D.md A5): the fretting benchmark E = 72.1 GPa,
/// nu = 0.33, R = 10 mm, P = 135750 N/m, f = 0.3, Q = 38750 N/m and a bulk stress
/// sigma = 100 MPa in the specimen: a = 0.20670 mm, p0 = 418.104 MPa, stick zone
/// c = a sqrt(1 - Q/(f P)) = 0.22022 a shifted by e = a sigma / (4 f p0) = 0.1993 a. The
/// specimen is a block 20 mm x 10 mm (97 a x 48 a) with rollers on its left end and bottom
/// and the bulk traction on its right end; the pad is a half cylinder loaded through its guided face:
/// step 1 P, step 2 P with Q and sigma together. 72 / 60 elements over |x| <= 1.5 a (a slave
/// node every 0.021 a). Measured: c/a = 0.2225 (+1.0 %), e/a = +0.1988 (-0.3 %; the stick
/// zone moves toward +x, the sense of Q and of the bulk tension here). Tolerances: 2 % of a
/// on c and e (the stick zone spans only 0.44 a, about 20 nodes, and the fit interpolates
/// between them).
#[test]
fn nowell_hills_stick_zone_shift() {
    let (.., f, _, _) = NOWELL_HILLS;
    let (a, p0, c_exact, e_exact) = nowell_hills_exact();
    assert!((a - 0.20670e-3).abs() < 1e-7 && (p0 - 418.104e6).abs() < 0.01e6);
    let (mut cp, steps) = nowell_hills().unwrap();
    let res = cp.solve_steps(&steps, &ContactOptions::default()).unwrap();
    let pr = &res[1].pairs[0];
    let (c, x0) = stick_zone(pr, f);
    eprintln!(
        "Nowell-Hills: c/a {:.4} (exact {:.4}), shift e/a {:+.4} (exact magnitude {:.4}), \
         iterations {} / {}",
        c / a,
        c_exact / a,
        x0 / a,
        e_exact / a,
        res[0].iterations,
        res[1].iterations
    );
    assert!((c - c_exact).abs() < 0.02 * a, "c/a = {}", c / a);
    assert!((x0.abs() - e_exact).abs() < 0.02 * a, "e/a = {}", x0 / a);
}

/// Path dependence (Johnson 1985 sec. 7.2, Mindlin-Deresiewicz in 2D): load P, then Q* =
/// 0.5 f P, then unload to Q = 0. On unloading, reverse slip spreads from the edges over
/// c' <= |x| <= a with c' = a sqrt(1 - (Q* - Q)/(2 f P)) = 0.866 a at Q = 0; inside, the
/// tractions of the loaded state stay locked in, so q != 0 with zero resultant. c' is taken
/// midway between the outermost stick node and the next slip node (node spacing 0.042 a).
/// Measured: c'/a = 0.854 (exact 0.866), locked-in max |q| = 0.49 f p0, the reverse slip in
/// the opposite sense. Tolerance 0.05 a (about one node spacing).
#[test]
fn unloading_leaves_locked_in_shear() {
    let estar = 210e9 / (2.0 * (1.0 - 0.09));
    let (a, p0) = hertz(R, estar, P);
    let f = 0.3;
    let qs = 0.5 * f * P;
    let mut cp = cylinder_on_block(f, 48, 40).unwrap();
    let res = cp
        .solve_steps(
            &[shear_step(0.0), shear_step(qs), shear_step(0.0)],
            &ContactOptions::default(),
        )
        .unwrap();
    let pr = &res[2].pairs[0];
    let mut stick_max = 0.0_f64;
    let mut slip_min = f64::INFINITY;
    for n in &pr.nodes {
        let x = n.position[0].abs();
        match n.state {
            ContactState::Stick => stick_max = stick_max.max(x),
            ContactState::SlipPositive | ContactState::SlipNegative => slip_min = slip_min.min(x),
            _ => {}
        }
    }
    let c_rev = 0.5 * (stick_max + slip_min);
    let exact = a * (1.0 - qs / (2.0 * f * P)).sqrt();
    let locked = pr.nodes.iter().map(|n| n.shear.abs()).fold(0.0, f64::max);
    // The reverse slip is opposite to the loading slip.
    let load_dir = res[1].pairs[0]
        .nodes
        .iter()
        .find(|n| {
            matches!(
                n.state,
                ContactState::SlipPositive | ContactState::SlipNegative
            )
        })
        .map(|n| n.state);
    let unload_dir = pr
        .nodes
        .iter()
        .find(|n| {
            matches!(
                n.state,
                ContactState::SlipPositive | ContactState::SlipNegative
            )
        })
        .map(|n| n.state);
    eprintln!(
        "unloading: c'/a {:.4} (exact {:.4}), locked-in max |q| {:.3} f p0, Q {:.2e} N/m, \
         slip {load_dir:?} then {unload_dir:?}",
        c_rev / a,
        exact / a,
        locked / (f * p0),
        res[2].rigid[0].force[0]
    );
    assert!((c_rev - exact).abs() < 0.05 * a, "c'/a = {}", c_rev / a);
    assert!(locked > 0.1 * f * p0);
    assert!(res[2].rigid[0].force[0].abs() < 1e-9 * P);
    assert!(load_dir.is_some() && unload_dir.is_some() && load_dir != unload_dir);
}

/// A body made of bonded regions (zonal homogeneity, (7)) takes part in contact as one
/// body: the block split into a 2 mm top layer and the rest, both steel, bonded, gives the
/// Hertz pressure of the one-piece block (measured difference 1.2e-5 p0, the interface's own
/// discretization; tolerance 1e-3 p0).
#[test]
fn bonded_block_in_contact_matches_one_piece() {
    let estar = 210e9 / (2.0 * (1.0 - 0.09));
    let (b, p0) = hertz(R, estar, P);
    let c = 2.0 * b;
    let (l, d, h) = (0.010, 0.010, 0.002);
    let ratio = (l - c) / (c / 40.0) / 4.0;
    let lower = Region::new(
        "lower",
        steel(),
        vec![
            Segment::line("lower_bottom", [-l, -d], [l, -d], 12),
            Segment::line("lower_right", [l, -d], [l, -h], 8),
            Segment::line("iface", [l, -h], [-l, -h], 16),
            Segment::line("lower_left", [-l, -h], [-l, -d], 8),
        ],
    );
    let mut upper = Region::new(
        "upper",
        steel(),
        vec![
            Segment::line("upper_right", [l, -h], [l, 0.0], 4),
            Segment::line("upper_top_right", [l, 0.0], [c, 0.0], 24).graded(Grading::End(ratio)),
            Segment::line("upper_contact", [c, 0.0], [-c, 0.0], 40),
            Segment::line("upper_top_left", [-c, 0.0], [-l, 0.0], 24).graded(Grading::Start(ratio)),
            Segment::line("upper_left", [-l, 0.0], [-l, -h], 4),
        ],
    );
    upper.loops[0].insert(0, crate::operators::bem2d::LoopItem::Shared("iface".into()));
    let model = BemModel::new(
        PlaneCondition::Strain,
        vec![lower, upper, half_cylinder("cyl", steel(), R, c, 48, true)],
    );
    let bcs = BoundaryConditions::new().set("lower_bottom", SegmentBc::fixed());
    let mut cp = ContactProblem::new(
        &model,
        &bcs,
        &[ContactPair::new("cyl_contact", "upper_contact", 0.0)],
        &["cyl_face"],
    )
    .unwrap();
    let res = cp
        .solve_steps(&[press(P)], &ContactOptions::default())
        .unwrap();
    let mut one = cylinder_on_block(0.0, 48, 40).unwrap();
    let r1 = one
        .solve_steps(&[press(P)], &ContactOptions::default())
        .unwrap();
    let diff = res[0].pairs[0]
        .nodes
        .iter()
        .zip(&r1[0].pairs[0].nodes)
        .map(|(x, y)| (x.pressure - y.pressure).abs())
        .fold(0.0, f64::max);
    let ep = pressure_error(&res[0].pairs[0], b, p0, 0.9);
    eprintln!(
        "bonded block: max pressure difference to one piece {:.2e} p0, Hertz error {ep:.2e}",
        diff / p0
    );
    assert!(diff < 1e-3 * p0);
}

/// f = 0 is the frictionless problem exactly: all q = 0, complementarity holds to
/// round-off, and the result is path independent (one step or four give the same state to
/// round-off); a tiny friction coefficient changes the pressure continuously.
#[test]
fn zero_friction_is_frictionless_and_path_independent() {
    let mut one = cylinder_on_block(0.0, 32, 24).unwrap();
    let r1 = one
        .solve_steps(&[press(P)], &ContactOptions::default())
        .unwrap();
    let mut four = cylinder_on_block(0.0, 32, 24).unwrap();
    let steps: Vec<LoadStep> = (1..=4).map(|k| press(P * k as f64 / 4.0)).collect();
    let r4 = four
        .solve_steps(&steps, &ContactOptions::default())
        .unwrap();
    let (a, b) = (&r1[0].pairs[0], &r4[3].pairs[0]);
    let pmax = a.nodes.iter().map(|n| n.pressure).fold(0.0, f64::max);
    for (x, y) in a.nodes.iter().zip(&b.nodes) {
        assert_eq!(x.shear, 0.0);
        assert!((x.pressure - y.pressure).abs() < 1e-9 * pmax);
        assert!(x.pressure >= 0.0);
        let gap = x.gap.unwrap();
        if x.state == ContactState::Open {
            assert!(gap >= 0.0 && x.pressure == 0.0);
        } else {
            // Closed: zero gap to round-off of the 1e-6 m scale of the approach.
            assert!(gap.abs() < 1e-16, "gap {gap:e}");
        }
    }
    let mut tiny = cylinder_on_block(1e-9, 32, 24).unwrap();
    let steps = [shear_step(0.0)];
    let rt = tiny
        .solve_steps(&steps, &ContactOptions::default())
        .unwrap();
    let dmax = rt[0].pairs[0]
        .nodes
        .iter()
        .zip(&a.nodes)
        .map(|(x, y)| (x.pressure - y.pressure).abs())
        .fold(0.0, f64::max);
    eprintln!(
        "f = 1e-9 vs f = 0: max pressure difference {:.2e} p0",
        dmax / pmax
    );
    assert!(dmax < 1e-6 * pmax);
}

/// The solver stops with NotConverged and its residual when the iteration limit is hit
/// (the Hertz case needs about 10 active-set iterations from the single initial contact
/// node).
#[test]
fn iteration_limit_is_not_converged_with_residual() {
    let mut cp = cylinder_on_block(0.0, 32, 24).unwrap();
    let opts = ContactOptions {
        max_iterations: 2,
        ..ContactOptions::default()
    };
    match cp.solve_steps(&[press(P)], &opts) {
        Err(Error::NotConverged {
            iterations,
            residual,
            ..
        }) => {
            assert_eq!(iterations, 2);
            assert!(residual.is_finite() && residual > 1e-9, "{residual:e}");
        }
        other => panic!("expected NotConverged, got {other:?}"),
    }
}

fn err_text<T: std::fmt::Debug>(r: Result<T>) -> String {
    format!("{}", r.unwrap_err())
}

#[test]
fn bad_contact_input_is_reported() {
    let estar = 210e9 / (2.0 * (1.0 - 0.09));
    let (b, _) = hertz(R, estar, P);
    let c = 2.0 * b;
    let model = BemModel::new(
        PlaneCondition::Strain,
        vec![
            block("block", steel(), 0.010, 0.010, c, 10),
            half_cylinder("cyl", steel(), R, c, 10, true),
        ],
    );
    let bcs = BoundaryConditions::new().set("block_bottom", SegmentBc::fixed());
    let pair = ContactPair::new("cyl_contact", "block_contact", 0.2);
    let e = err_text(ContactProblem::new(
        &model,
        &bcs,
        &[ContactPair::new("nope", "block_contact", 0.2)],
        &["cyl_face"],
    ));
    assert!(e.contains("nope") && e.contains("no segment"), "{e}");
    let e = err_text(ContactProblem::new(
        &model,
        &bcs,
        &[ContactPair::new("cyl_contact", "block_contact", -0.1)],
        &["cyl_face"],
    ));
    assert!(e.contains("friction"), "{e}");
    let e = err_text(ContactProblem::new(
        &model,
        &bcs,
        &[ContactPair::new("cyl_contact", "cyl_right", 0.1)],
        &["cyl_face"],
    ));
    assert!(e.contains("same body"), "{e}");
    let e = err_text(ContactProblem::new(
        &model,
        &bcs,
        std::slice::from_ref(&pair),
        &["cyl_contact"],
    ));
    assert!(e.contains("already used"), "{e}");
    let bad = bcs.clone().set("block_contact", SegmentBc::fixed());
    let e = err_text(ContactProblem::new(
        &model,
        &bad,
        std::slice::from_ref(&pair),
        &["cyl_face"],
    ));
    assert!(
        e.contains("block_contact") && e.contains("no boundary condition"),
        "{e}"
    );
    // A body held by nothing at all (free and in no contact pair): a clear error before any
    // factorization.
    let e = err_text(ContactProblem::new(&model, &bcs, &[], &[]));
    assert!(e.contains("cyl") && e.contains("not restrained"), "{e}");
    // A free body in a pair but with no load: nothing presses it onto the contact.
    let mut floating = ContactProblem::new(&model, &bcs, std::slice::from_ref(&pair), &[]).unwrap();
    let e = err_text(floating.solve_steps(&[LoadStep::new(1.0)], &ContactOptions::default()));
    assert!(e.contains("no contact") && e.contains("cyl"), "{e}");
    // Overlapping bodies.
    let sunk = BemModel::new(
        PlaneCondition::Strain,
        vec![
            block("block", steel(), 0.010, 0.010, c, 10),
            Region::new(
                "cyl",
                steel(),
                half_cylinder("cyl", steel(), R, c, 10, true).loops[0]
                    .iter()
                    .map(|it| match it {
                        crate::operators::bem2d::LoopItem::Segment(s) => {
                            let mut s = s.clone();
                            s.shape = match s.shape {
                                crate::operators::bem2d::SegmentShape::Arc {
                                    center,
                                    radius,
                                    start_angle,
                                    end_angle,
                                } => crate::operators::bem2d::SegmentShape::Arc {
                                    center: [center[0], center[1] - 1e-5],
                                    radius,
                                    start_angle,
                                    end_angle,
                                },
                                crate::operators::bem2d::SegmentShape::Line { start, end } => {
                                    crate::operators::bem2d::SegmentShape::Line {
                                        start: [start[0], start[1] - 1e-5],
                                        end: [end[0], end[1] - 1e-5],
                                    }
                                }
                                crate::operators::bem2d::SegmentShape::Meshed(_) => {
                                    unreachable!("the half cylinder has lines and arcs")
                                }
                            };
                            s
                        }
                        _ => unreachable!(),
                    })
                    .collect(),
            ),
        ],
    );
    let e = err_text(ContactProblem::new(
        &sunk,
        &bcs,
        std::slice::from_ref(&pair),
        &["cyl_face"],
    ));
    assert!(e.contains("overlap"), "{e}");
    // Steps: a missing rigid control, and a frictionless pair pushed sideways by a force
    // (the x mode held by nothing: a singular step system, reported).
    let mut cp = ContactProblem::new(
        &model,
        &bcs,
        &[ContactPair::new("cyl_contact", "block_contact", 0.0)],
        &["cyl_face"],
    )
    .unwrap();
    let e = err_text(cp.solve_steps(
        &[LoadStep {
            external: 1.0,
            rigid: vec![],
            groups: vec![],
        }],
        &ContactOptions::default(),
    ));
    assert!(e.contains("cyl_face") && e.contains("control"), "{e}");
    let e = err_text(cp.solve_steps(
        &[LoadStep {
            external: 1.0,
            rigid: vec![RigidControl::new(
                "cyl_face",
                Control::Force(1e3),
                Control::Force(-P),
            )],
            groups: vec![],
        }],
        &ContactOptions::default(),
    ));
    assert!(
        e.contains("singular") || e.contains("did not converge"),
        "{e}"
    );
    // Pulling the bodies apart under force control: no contact.
    cp.reset();
    let e = err_text(cp.solve_steps(
        &[LoadStep {
            external: 1.0,
            rigid: vec![RigidControl::new(
                "cyl_face",
                Control::Displacement(0.0),
                Control::Force(P),
            )],
            groups: vec![],
        }],
        &ContactOptions::default(),
    ));
    assert!(e.contains("no contact") || e.contains("singular"), "{e}");
}

/// Timing of condensation vs one contact step (cylinder on block). Run with
/// `cargo test --release -p tribo --lib contact_timing -- --ignored --nocapture`.
#[test]
#[ignore]
fn contact_timing() {
    for (ns, nm) in [(48, 40), (96, 80), (192, 160)] {
        let t0 = std::time::Instant::now();
        let problem = BemProblem::new(&cylinder_on_block_model(ns, nm).unwrap()).unwrap();
        let ta = t0.elapsed().as_secs_f64();
        let t0 = std::time::Instant::now();
        let bcs = BoundaryConditions::new().set("block_bottom", SegmentBc::fixed());
        let mut cp = ContactProblem::from_problem(
            problem,
            &bcs,
            &[ContactPair::new("cyl_contact", "block_contact", 0.3)],
            &["cyl_face"],
        )
        .unwrap();
        let tc = t0.elapsed().as_secs_f64();
        let q = 0.5 * 0.3 * P;
        let steps = [shear_step(0.0), shear_step(q)];
        let t1 = std::time::Instant::now();
        let res = cp.solve_steps(&steps, &ContactOptions::default()).unwrap();
        let ts = t1.elapsed().as_secs_f64() / 2.0;
        println!(
            "BEM DOF {:5}, contact unknowns {:4}: mesh + assembly {ta:.3} s, LU + condensation {tc:.3} s, \
             per step {ts:.4} s (iterations {} and {}), threads {}",
            cp.bem().dof(),
            cp.contact_unknowns(),
            res[0].iterations,
            res[1].iterations,
            rayon::current_num_threads()
        );
    }
}

/// A case where the active set cycles: the flat punch with uniform, non-matching elements
/// and the weighted gap rule (its quadratic weights make the discrete LCP lose the P-matrix
/// property next to the singular edge; pressures oscillate in sign). The sets repeat, the
/// guard switches to single-node updates (Murty), which do not settle either, and the solver
/// stops at the iteration limit with NotConverged and its residual instead of looping. The
/// collocated rule solves the same case in 3 iterations.
#[test]
fn cycling_is_reported_with_the_residual() {
    let a = PUNCH_A;
    let step = punch_step();
    let opts = ContactOptions {
        max_iterations: 60,
        ..ContactOptions::default()
    };
    let mut cp = flat_punch(1.2 * a, Grading::Uniform, GapRule::Weighted).unwrap();
    match cp.solve_steps(std::slice::from_ref(&step), &opts) {
        Err(Error::NotConverged {
            iterations,
            residual,
            ..
        }) => {
            eprintln!("cycling: stopped after {iterations} iterations, residual {residual:.3e}");
            assert!(iterations <= 60 && residual.is_finite() && residual > 1e-9);
        }
        other => panic!(
            "expected NotConverged, got {:?}",
            other.map(|r| r[0].iterations)
        ),
    }
    let mut cp = flat_punch(1.2 * a, Grading::Uniform, GapRule::NodeToSegment).unwrap();
    let r = cp.solve_steps(&[step], &opts).unwrap();
    assert!(r[0].residual < 1e-10);
}

// ---------------------------------------------------------------------------------------
// Bodies held only by contact (free rigid-body modes) and load groups.

/// Resultant force and moment (about `c`) of the boundary tractions of region `name` in the
/// solved state, by a 16-point Gauss rule per element over the interpolated tractions (an
/// integration independent of the solver's 8-point weights).
fn resultant(sol: &BemSolution, name: &str, c: [f64; 2]) -> ([f64; 2], f64) {
    let mesh = sol.mesh();
    let r = mesh.regions.iter().position(|x| x.name == name).unwrap();
    let (gx, gw) = gauss_legendre(16);
    let (mut f, mut m) = ([0.0; 2], 0.0);
    for e in &mesh.regions[r].elements {
        if mesh.segments[e.segment].partner.is_some() {
            continue;
        }
        for (&xi, &w) in gx.iter().zip(&gw) {
            let x = e.point(xi);
            let (_, jac) = e.normal_jacobian(xi);
            let nsh = e.field_shape(xi);
            let mut t = [0.0; 2];
            for a in 0..3 {
                for d in 0..2 {
                    t[d] += nsh[a] * sol.traction[r][e.nodes[a]][d];
                }
            }
            f[0] += w * jac * t[0];
            f[1] += w * jac * t[1];
            m += w * jac * ((x[0] - c[0]) * t[1] - (x[1] - c[1]) * t[0]);
        }
    }
    (f, m)
}

/// A steel base [x0, w] x [-d, 0] (top: `base_top`, the master) and a steel block [x0, w] x
/// [0, h] (bottom: `blk_bottom`, the slave) of the same width, touching along y = 0.
fn stack(x0: f64, w: f64, d: f64, h: f64) -> BemModel {
    let base = Region::new(
        "base",
        steel(),
        vec![
            Segment::line("base_bottom", [x0, -d], [w, -d], 8),
            Segment::line("base_right", [w, -d], [w, 0.0], 6),
            Segment::line("base_top", [w, 0.0], [x0, 0.0], 9),
            Segment::line("base_left", [x0, 0.0], [x0, -d], 6),
        ],
    );
    let blk = Region::new(
        "blk",
        steel(),
        vec![
            Segment::line("blk_bottom", [x0, 0.0], [w, 0.0], 12),
            Segment::line("blk_right", [w, 0.0], [w, h], 6),
            Segment::line("blk_top", [w, h], [x0, h], 8),
            Segment::line("blk_left", [x0, h], [x0, 0.0], 6),
        ],
    );
    BemModel::new(PlaneCondition::Strain, vec![base, blk])
}

/// (a), (d): a block pressed by a uniform pressure p on its top onto a base of the same
/// material, held only by contact. The base has rollers on its left end and bottom, so the
/// exact solution is the uniform state sigma_yy = -p in both bodies with u = (eps_xx (x -
/// x0), eps_yy (y + d)), plane strain eps_yy = -(1 - nu^2) p / E, eps_xx = nu (1 + nu) p /
/// E (Hooke's law): the contact pressure is p, the shear 0, and the block's least-squares
/// rigid motion is u at its boundary centroid with zero rotation (the field is linear and
/// the rectangle symmetric). Quadratic elements represent this state exactly, so only the
/// quadrature of the operators and the LU round-off remain: tolerance 1e-7 relative
/// (measured below). Two variants: a symmetric half model, frictionless, whose block has
/// u_x = 0 on its left face (x and rotation restrained, y free); the full model with
/// friction f = 0.3, whose block is free in x, y and rotation (x held by friction). The
/// contact force equals p w and the block's boundary tractions are in equilibrium (force and
/// moment, integrated independently) to round-off.
#[test]
fn block_held_only_by_contact_uniform_state() {
    let (w, d, h, p) = (0.010, 0.010, 0.004, 50e6);
    let (e, nu) = (210e9, 0.3);
    let eyy = -(1.0 - nu * nu) * p / e;
    let exx = nu * (1.0 + nu) * p / e;
    for (x0, f) in [(0.0, 0.0), (-w, 0.3)] {
        let width = w - x0;
        let mut bcs = BoundaryConditions::new()
            .set("base_left", SegmentBc::roller_x())
            .set("base_bottom", SegmentBc::roller_y())
            .set("blk_top", SegmentBc::Pressure(Profile::Uniform(p)));
        if x0 == 0.0 {
            bcs = bcs.set("blk_left", SegmentBc::roller_x());
        }
        let mut cp = ContactProblem::new(
            &stack(x0, w, d, h),
            &bcs,
            &[ContactPair::new("blk_bottom", "base_top", f)],
            &[],
        )
        .unwrap();
        let res = cp
            .solve_steps(&[LoadStep::new(1.0)], &ContactOptions::default())
            .unwrap();
        let step = &res[0];
        let pr = &step.pairs[0];
        let ep = pr
            .nodes
            .iter()
            .map(|n| (n.pressure / p - 1.0).abs())
            .fold(0.0, f64::max);
        let eq = pr
            .nodes
            .iter()
            .map(|n| n.shear.abs() / p)
            .fold(0.0, f64::max);
        assert!(pr.nodes.iter().all(|n| n.state == ContactState::Stick));
        let fb = &step.free_bodies[0];
        let c = fb.reference_point;
        assert!((c[0] - 0.5 * (x0 + w)).abs() < 1e-12 && (c[1] - 0.5 * h).abs() < 1e-12);
        let exact = [exx * (c[0] - x0), eyy * (c[1] + d)];
        let et = (fb.translation[0] - exact[0])
            .abs()
            .max((fb.translation[1] - exact[1]).abs())
            / exact[1].abs();
        let (force, moment) = resultant(&step.solution, "blk", c);
        eprintln!(
            "block on base (f = {f}): modes {:?}, max |p/p_exact - 1| {ep:.2e}, max |q|/p {eq:.2e}, \
             translation error {et:.2e} of u_y, rotation {:.2e}, contact force / (p w) - 1 \
             {:.2e}, resultant ({:.2e}, {:.2e}) p w, moment {:.2e} p w h, support force {:?}, \
             iterations {}",
            fb.free_modes,
            fb.rotation,
            pr.slave_force[1] / (p * width) - 1.0,
            force[0] / (p * width),
            force[1] / (p * width),
            moment / (p * width * h),
            fb.support_force,
            step.iterations
        );
        assert_eq!(fb.body, "blk");
        assert!(ep < 1e-7 && eq < 1e-7, "{ep:e} {eq:e}");
        assert!(et < 1e-7, "{:?} vs {exact:?}", fb.translation);
        assert!(fb.rotation.abs() < 1e-7 * eyy.abs());
        assert!((pr.slave_force[1] - p * width).abs() < 1e-10 * p * width);
        assert!(pr.slave_force[0].abs() < 1e-10 * p * width);
        if x0 == 0.0 {
            assert_eq!(fb.free_modes, vec!["translation in y".to_string()]);
            assert!(force[1].abs() < 1e-10 * p * width);
        } else {
            assert_eq!(fb.free_modes.len(), 3);
            assert!(force[0].abs() < 1e-10 * p * width && force[1].abs() < 1e-10 * p * width);
            assert!(moment.abs() < 1e-10 * p * width * h);
        }
    }
}

/// (b), (d): the 2D Hertz case of `hertz_cylinder_on_block` (steel, R = 10 mm, P = 100 N/mm,
/// b = 0.10505 mm, p0 = 606.04 MPa, 48 / 40 elements over abs(x) <= 2 b) with the cylinder
/// loaded by a uniform traction t_y = -P / (2 R) on its flat cut face and held only by
/// contact: no rigid segment. Frictionless with u_x = 0 on the cut face (x restrained; y and
/// the rotation about a point of the face free, the rotation held by the contact pressure);
/// with friction f = 0.3 and a pure pressure on the face (x, y and rotation free; x held by
/// friction). Same tolerances as the rigid-segment test: 1 % on b and p0, 1.5 % of p0 on
/// p(x) within 0.9 b. The free cylinder's boundary tractions are in equilibrium in its free
/// modes to round-off (1e-10 of P: the equilibrium rows are solved equations), and the
/// artificial supports carry only the BEM's own equilibrium defect (measured below; bound
/// 1e-4 P, the bound of the rigid-segment test's BEM balance).
///
/// (A symmetric half model with the symmetry line through the contact is not used here: its
/// corner at the first contact node perturbs the two nearest nodes by 4-6 % of p0, with a
/// rigid segment as much as with the free body; beyond 0.15 b the two agree to 1e-3 p0.)
#[test]
fn hertz_cylinder_held_only_by_contact() {
    let estar = 210e9 / (2.0 * (1.0 - 0.09));
    let (b, p0) = hertz(R, estar, P);
    let ty = -P / (2.0 * R);
    for full in [false, true] {
        let face = if full {
            SegmentBc::Pressure(Profile::Uniform(-ty))
        } else {
            SegmentBc::Components {
                x: Component::Displacement(Profile::Uniform(0.0)),
                y: Component::Traction(Profile::Uniform(ty)),
            }
        };
        let f = if full { 0.3 } else { 0.0 };
        let model = cylinder_on_block_model(48, 40).unwrap();
        let bcs = BoundaryConditions::new()
            .set("block_bottom", SegmentBc::fixed())
            .set("cyl_face", face);
        let mut cp = ContactProblem::new(
            &model,
            &bcs,
            &[ContactPair::new("cyl_contact", "block_contact", f)],
            &[],
        )
        .unwrap();
        let res = cp
            .solve_steps(&[LoadStep::new(1.0)], &ContactOptions::default())
            .unwrap();
        let step = &res[0];
        let pr = &step.pairs[0];
        let (p0f, bf) = fit_pair(pr);
        let ep = pressure_error(pr, b, p0, 0.9);
        let fb = &step.free_bodies[0];
        let load = P;
        let (force, moment) = resultant(&step.solution, "cyl", fb.reference_point);
        eprintln!(
            "Hertz, free cylinder (full model {full}, f = {f}): modes {:?}, b {:+.2e}, p0 \
             {:+.2e}, max |p - pH|/p0 {ep:.2e}, resultant ({:.1e}, {:.1e}) P, moment {:.1e} P R, \
             support force {:.1e} P, translation {:?}, rotation {:.2e}, iterations {}",
            fb.free_modes,
            bf / b - 1.0,
            p0f / p0 - 1.0,
            force[0] / load,
            force[1] / load,
            moment / (load * R),
            fb.support_force[0].hypot(fb.support_force[1]) / load,
            fb.translation,
            fb.rotation,
            step.iterations
        );
        assert!((bf / b - 1.0).abs() < 0.01, "b {bf:e} vs {b:e}");
        assert!((p0f / p0 - 1.0).abs() < 0.01, "p0 {p0f:e} vs {p0:e}");
        assert!(ep < 0.015, "p(x) error {ep:.3e}");
        assert!(step.residual < 1e-9);
        assert!((pr.slave_force[1] - load).abs() < 1e-10 * load);
        assert!(force[1].abs() < 1e-10 * load);
        assert!(fb.support_force[0].hypot(fb.support_force[1]) < 1e-4 * load);
        assert!(fb.translation[1] < 0.0);
        if full {
            assert_eq!(fb.free_modes.len(), 3);
            assert!(force[0].abs() < 1e-10 * load);
        } else {
            assert_eq!(fb.free_modes.len(), 2);
            assert_eq!(fb.free_modes[0], "translation in y");
            assert!(fb.free_modes[1].starts_with("rotation about"));
        }
        // The free rotation's equilibrium: the moment about any point (the modes span the
        // rotation in both cases).
        assert!(moment.abs() < 1e-10 * load * R);
    }
}

/// (c): a free body whose free mode neither contact nor friction holds is a clear error
/// naming the body and the mode (the block of the uniform-state test, full model, f = 0,
/// pushed sideways by a traction on its right face); so is a frictionless free body even
/// without a sideways load (its x position is undetermined).
#[test]
fn unheld_free_mode_is_reported() {
    let (w, d, h, p) = (0.010, 0.010, 0.004, 50e6);
    for side in [0.0, -0.1 * p] {
        let bcs = BoundaryConditions::new()
            .set("base_left", SegmentBc::roller_x())
            .set("base_bottom", SegmentBc::roller_y())
            .set("blk_top", SegmentBc::Pressure(Profile::Uniform(p)))
            .set(
                "blk_right",
                SegmentBc::traction(Profile::Uniform(side), Profile::Uniform(0.0)),
            );
        let mut cp = ContactProblem::new(
            &stack(-w, w, d, h),
            &bcs,
            &[ContactPair::new("blk_bottom", "base_top", 0.0)],
            &[],
        )
        .unwrap();
        let e = err_text(cp.solve_steps(&[LoadStep::new(1.0)], &ContactOptions::default()));
        eprintln!("{e}");
        assert!(
            e.contains("body [blk]")
                && e.contains("translation in x")
                && e.contains("neither contact nor friction"),
            "{e}"
        );
    }
}

/// The model of the load-group tests: the Hertz case (cylinder on block, 48 / 40 elements)
/// with the cylinder held only by contact and by u_x = 0 on its cut face, whose traction
/// t_y = -P / (2 R) is group "bolt", and a bulk tension sigma = 150 MPa on both end faces of
/// the block (bottom fixed) in group "bulk".
fn grouped_model(f: f64) -> ContactProblem {
    let sigma = 150e6;
    let bcs = BoundaryConditions::new()
        .set("block_bottom", SegmentBc::fixed())
        .set_in_group(
            "cyl_face",
            SegmentBc::Components {
                x: Component::Displacement(Profile::Uniform(0.0)),
                y: Component::Traction(Profile::Uniform(-P / (2.0 * R))),
            },
            "bolt",
        )
        .set_in_group(
            "block_right",
            SegmentBc::traction(Profile::Uniform(sigma), Profile::Uniform(0.0)),
            "bulk",
        )
        .set_in_group(
            "block_left",
            SegmentBc::traction(Profile::Uniform(-sigma), Profile::Uniform(0.0)),
            "bulk",
        );
    ContactProblem::new(
        &cylinder_on_block_model(48, 40).unwrap(),
        &bcs,
        &[ContactPair::new("cyl_contact", "block_contact", f)],
        &[],
    )
    .unwrap()
}

fn max_diff(a: &ContactStepResult, b: &ContactStepResult) -> (f64, f64, f64) {
    let (mut dp, mut dq) = (0.0_f64, 0.0_f64);
    for (x, y) in a.pairs[0].nodes.iter().zip(&b.pairs[0].nodes) {
        dp = dp.max((x.pressure - y.pressure).abs());
        dq = dq.max((x.shear - y.shear).abs());
    }
    let mut du = 0.0_f64;
    for (ra, rb) in a.solution.displacement.iter().zip(&b.solution.displacement) {
        for (x, y) in ra.iter().zip(rb) {
            du = du.max((x[0] - y[0]).abs()).max((x[1] - y[1]).abs());
        }
    }
    (dp, dq, du)
}

/// Load groups. Frictionless (f = 0, path independent): "bolt" then "bolt + bulk" in two
/// steps gives the single step "bolt + bulk" to round-off (1e-9 of p0 and of the largest
/// displacement), and "bolt + bulk" then "bolt" gives the single step "bolt". With friction
/// (f = 0.3) the second path differs, and only through path dependence (the same two paths
/// agree to round-off without friction): removing the bulk stress leaves the shear locked in
/// by the slip it caused (Johnson 1985 sec. 7.2: unloading does not retrace loading), more
/// than 0.1 f p0 of shear difference (measured 0.36 f p0), while the pressure stays within
/// 1 % of p0 (same materials decouple normal and tangential tractions), both states obey
/// Coulomb's law and carry the bolt force P to round-off.
#[test]
fn load_groups_superpose_without_friction_and_differ_by_path_with_friction() {
    let estar = 210e9 / (2.0 * (1.0 - 0.09));
    let (_, p0) = hertz(R, estar, P);
    let opts = ContactOptions::default();
    let bolt = LoadStep::new(0.0).with_group("bolt", 1.0);
    let both = LoadStep::new(0.0)
        .with_group("bolt", 1.0)
        .with_group("bulk", 1.0);
    let mut cp = grouped_model(0.0);
    let two = cp
        .solve_steps(&[bolt.clone(), both.clone()], &opts)
        .unwrap();
    cp.reset();
    let one = cp.solve_steps(std::slice::from_ref(&both), &opts).unwrap();
    let (dp, dq, du) = max_diff(&two[1], &one[0]);
    let umax = one[0]
        .solution
        .displacement
        .iter()
        .flatten()
        .map(|u| u[0].abs().max(u[1].abs()))
        .fold(0.0, f64::max);
    cp.reset();
    let back = cp
        .solve_steps(&[both.clone(), bolt.clone()], &opts)
        .unwrap();
    cp.reset();
    let only = cp.solve_steps(std::slice::from_ref(&bolt), &opts).unwrap();
    let (dp2, _, du2) = max_diff(&back[1], &only[0]);
    eprintln!(
        "groups, f = 0: two steps vs one: dp {:.1e} p0, dq {dq:.1e}, du {:.1e} umax; unloaded \
         bulk vs bolt only: dp {:.1e} p0, du {:.1e} umax; bulk changes p by {:.2e} p0",
        dp / p0,
        du / umax,
        dp2 / p0,
        du2 / umax,
        max_diff(&two[0], &two[1]).0 / p0
    );
    assert!(dp < 1e-9 * p0 && dq == 0.0 && du < 1e-9 * umax);
    assert!(dp2 < 1e-9 * p0 && du2 < 1e-9 * umax);
    // The groups did change the state (the test is not vacuous).
    assert!(max_diff(&two[0], &two[1]).2 > 1e-3 * umax);

    let f = 0.3;
    let mut cp = grouped_model(f);
    let back = cp.solve_steps(&[both, bolt.clone()], &opts).unwrap();
    cp.reset();
    let only = cp.solve_steps(&[bolt], &opts).unwrap();
    let (dp, dq, _) = max_diff(&back[1], &only[0]);
    let q_only = only[0].pairs[0]
        .nodes
        .iter()
        .map(|n| n.shear.abs())
        .fold(0.0, f64::max);
    let nslip = back[0].pairs[0]
        .nodes
        .iter()
        .filter(|n| {
            matches!(
                n.state,
                ContactState::SlipPositive | ContactState::SlipNegative
            )
        })
        .count();
    let qres = back[1].pairs[0].slave_force[0];
    eprintln!(
        "groups, f = {f}: after removing the bulk load: locked-in dq {:.3} f p0, dp {:.2e} p0, \
         shear resultant {:.1e} P, slip nodes under bulk {nslip}; bolt only: max |q| {:.1e} f p0",
        dq / (f * p0),
        dp / p0,
        qres / P,
        q_only / (f * p0)
    );
    assert!(nslip > 0);
    assert!(
        dq > 0.1 * f * p0,
        "locked-in shear {:.3e} f p0",
        dq / (f * p0)
    );
    assert!(dp < 0.01 * p0);
    for r in [&back[1], &only[0]] {
        for n in &r.pairs[0].nodes {
            assert!(n.shear.abs() <= f * n.pressure * (1.0 + 1e-9) + 1e-9 * p0);
        }
    }
    // The cut face restrains x, so only the y resultant is a free-body equation: P in both.
    for r in [&back[1], &only[0]] {
        assert!((r.pairs[0].slave_force[1] - P).abs() < 1e-10 * P);
    }
}

#[test]
fn bad_load_groups_are_reported() {
    let mut cp = grouped_model(0.0);
    let opts = ContactOptions::default();
    let e = err_text(cp.solve_steps(&[LoadStep::new(0.0).with_group("blot", 1.0)], &opts));
    assert!(
        e.contains("blot") && e.contains("no load group") && e.contains("bolt"),
        "{e}"
    );
    let e = err_text(
        cp.solve_steps(
            &[LoadStep::new(0.0)
                .with_group("bolt", 1.0)
                .with_group("bolt", 2.0)],
            &opts,
        ),
    );
    assert!(e.contains("bolt") && e.contains("twice"), "{e}");
    let e = err_text(cp.solve_steps(&[LoadStep::new(0.0).with_group("bolt", f64::NAN)], &opts));
    assert!(e.contains("bolt") && e.contains("finite"), "{e}");
    assert_eq!(cp.load_groups(), ["bolt".to_string(), "bulk".to_string()]);
    let model = stack(-0.01, 0.01, 0.01, 0.004);
    let e = err_text(ContactProblem::new(
        &model,
        &BoundaryConditions::new()
            .set("base_bottom", SegmentBc::fixed())
            .set_in_group("blk_top", SegmentBc::Pressure(Profile::Uniform(1.0)), " "),
        &[ContactPair::new("blk_bottom", "base_top", 0.3)],
        &[],
    ));
    assert!(e.contains("blk_top") && e.contains("group"), "{e}");
}

/// The eigen-solver used for the free-mode analysis (faer's self-adjoint decomposition):
/// A v = lambda v to round-off on a symmetric 4 x 4 matrix, orthonormal vectors, and a
/// double eigenvalue.
#[test]
fn small_symmetric_eigen() {
    let a = vec![
        vec![4.0, 1.0, -2.0, 0.5],
        vec![1.0, 3.0, 0.0, 1.0],
        vec![-2.0, 0.0, 5.0, -1.0],
        vec![0.5, 1.0, -1.0, 2.0],
    ];
    let (vals, vecs) = symmetric_eigen(&a, "test").unwrap();
    for k in 0..4 {
        for i in 0..4 {
            let av: f64 = (0..4).map(|j| a[i][j] * vecs[j][k]).sum();
            assert!((av - vals[k] * vecs[i][k]).abs() < 1e-12);
        }
        for l in 0..4 {
            let dot: f64 = (0..4).map(|i| vecs[i][k] * vecs[i][l]).sum();
            assert!((dot - if k == l { 1.0 } else { 0.0 }).abs() < 1e-12);
        }
    }
    let (vals, _) = symmetric_eigen(&[vec![1.0, 0.0], vec![0.0, 1.0]], "test").unwrap();
    assert_eq!(vals, vec![1.0, 1.0]);
    assert!(symmetric_eigen(&[vec![f64::NAN]], "test").is_err());
}

/// Two bodies held only by contact in a chain (a clamp plate pressed by a uniform "bolt"
/// pressure onto a knife, the knife onto a base; both with u_x = 0 on their left faces, so
/// free in y): the exact solution is again the uniform state sigma_yy = -p in all three
/// (same material, rollers on the base), so both contacts carry p (tolerance 1e-7 as in the
/// single block) and each body's reported y translation is eps_yy (y_c + d) at its boundary
/// centroid. The free modes of the two bodies are held only jointly through the chain.
#[test]
fn two_free_bodies_in_a_chain() {
    let (w, d, h, p) = (0.010, 0.010, 0.003, 40e6);
    let eyy = -(1.0 - 0.09) * p / 210e9;
    let layer = |name: &str, y0: f64, y1: f64, nb: usize, nt: usize| {
        Region::new(
            name,
            steel(),
            vec![
                Segment::line(&format!("{name}_bottom"), [0.0, y0], [w, y0], nb),
                Segment::line(&format!("{name}_right"), [w, y0], [w, y1], 4),
                Segment::line(&format!("{name}_top"), [w, y1], [0.0, y1], nt),
                Segment::line(&format!("{name}_left"), [0.0, y1], [0.0, y0], 4),
            ],
        )
    };
    let model = BemModel::new(
        PlaneCondition::Strain,
        vec![
            layer("base", -d, 0.0, 6, 8),
            layer("knife", 0.0, h, 10, 8),
            layer("plate", h, 2.0 * h, 11, 6),
        ],
    );
    let bcs = BoundaryConditions::new()
        .set("base_left", SegmentBc::roller_x())
        .set("base_bottom", SegmentBc::roller_y())
        .set("knife_left", SegmentBc::roller_x())
        .set("plate_left", SegmentBc::roller_x())
        .set_in_group(
            "plate_top",
            SegmentBc::Pressure(Profile::Uniform(p)),
            "bolt",
        );
    let mut cp = ContactProblem::new(
        &model,
        &bcs,
        &[
            ContactPair::new("knife_bottom", "base_top", 0.0),
            ContactPair::new("plate_bottom", "knife_top", 0.0),
        ],
        &[],
    )
    .unwrap();
    let res = cp
        .solve_steps(
            &[LoadStep::new(0.0).with_group("bolt", 1.0)],
            &ContactOptions::default(),
        )
        .unwrap();
    let step = &res[0];
    let ep = step
        .pairs
        .iter()
        .flat_map(|pr| pr.nodes.iter())
        .map(|n| (n.pressure / p - 1.0).abs())
        .fold(0.0, f64::max);
    eprintln!(
        "chain: max |p/p_exact - 1| {ep:.2e}, free bodies {:?}",
        step.free_bodies
            .iter()
            .map(|fb| (fb.body.clone(), fb.translation[1]))
            .collect::<Vec<_>>()
    );
    assert!(ep < 1e-7);
    let names: Vec<&str> = step.free_bodies.iter().map(|fb| fb.body.as_str()).collect();
    assert_eq!(names, ["knife", "plate"]);
    for fb in &step.free_bodies {
        let exact = eyy * (fb.reference_point[1] + d);
        assert!((fb.translation[1] / exact - 1.0).abs() < 1e-7, "{fb:?}");
        assert_eq!(fb.free_modes, ["translation in y"]);
    }
    for pr in &step.pairs {
        assert!((pr.slave_force[1] - p * w).abs() < 1e-10 * p * w);
    }
}

/// A free block (all three modes free, f = 0.3) pressed by a "bolt" pressure and then pushed
/// sideways by a "cut" traction on its right face with resultant Q (two load groups, two
/// steps). Below the friction limit (Q = 0.6 f P) the block is held by friction with partial
/// slip at the contact edges: Coulomb's law holds at every node (slip nodes abs(q) = f p,
/// stick nodes abs(q) <= f p with zero slip increment, to round-off) and the block is in
/// equilibrium in force and moment (the tipping moment Q h / 2 taken by the pressure) to
/// round-off. Above it (Q = 1.1 f P, gross slip) the step stops with the error naming the
/// body and the x translation.
#[test]
fn free_block_pushed_sideways_with_friction() {
    let (w, d, h, p) = (0.010, 0.010, 0.004, 50e6);
    let f = 0.3;
    let load = 2.0 * w * p;
    for ratio in [0.6, 1.1] {
        let q = ratio * f * load;
        let bcs = BoundaryConditions::new()
            .set("base_left", SegmentBc::roller_x())
            .set("base_bottom", SegmentBc::roller_y())
            .set_in_group("blk_top", SegmentBc::Pressure(Profile::Uniform(p)), "bolt")
            .set_in_group(
                "blk_right",
                SegmentBc::traction(Profile::Uniform(-q / h), Profile::Uniform(0.0)),
                "cut",
            );
        let mut cp = ContactProblem::new(
            &stack(-w, w, d, h),
            &bcs,
            &[ContactPair::new("blk_bottom", "base_top", f)],
            &[],
        )
        .unwrap();
        let bolt = LoadStep::new(0.0).with_group("bolt", 1.0);
        let steps = [bolt.clone(), bolt.with_group("cut", 1.0)];
        let r = cp.solve_steps(&steps, &ContactOptions::default());
        if ratio > 1.0 {
            let e = err_text(r);
            assert!(
                e.contains("body [blk]") && e.contains("translation in x"),
                "{e}"
            );
            continue;
        }
        let r = r.unwrap();
        let s = &r[1];
        let pr = &s.pairs[0];
        let nslip = pr
            .nodes
            .iter()
            .filter(|n| {
                matches!(
                    n.state,
                    ContactState::SlipPositive | ContactState::SlipNegative
                )
            })
            .count();
        let (force, moment) = resultant(&s.solution, "blk", s.free_bodies[0].reference_point);
        eprintln!(
            "free block, Q = {ratio} f P: slip nodes {nslip} / {}, iterations {}, contact force \
             {:?}, resultant ({:.1e}, {:.1e}) P, moment {:.1e} P h, rotation {:.2e}",
            pr.nodes.len(),
            s.iterations,
            pr.slave_force,
            force[0] / load,
            force[1] / load,
            moment / (load * h),
            s.free_bodies[0].rotation
        );
        assert!(nslip > 0 && nslip < pr.nodes.len());
        assert!((pr.slave_force[0] - q).abs() < 1e-10 * load);
        assert!((pr.slave_force[1] - load).abs() < 1e-10 * load);
        assert!(force[0].abs() < 1e-10 * load && force[1].abs() < 1e-10 * load);
        assert!(moment.abs() < 1e-10 * load * h);
        for n in &pr.nodes {
            match n.state {
                ContactState::SlipPositive | ContactState::SlipNegative => {
                    assert!((n.shear.abs() - f * n.pressure).abs() < 1e-9 * f * p)
                }
                ContactState::Stick => {
                    assert!(n.shear.abs() <= f * n.pressure + 1e-9 * f * p);
                    assert!(n.slip_increment.abs() < 1e-12 * h);
                }
                _ => {}
            }
        }
    }
}

/// A contact growing past the master segment (the cylinder's contact arc, narrower than the
/// block's contact segment) is refused with the window error, which says what to change.
#[test]
fn contact_past_a_smooth_master_end_is_refused() {
    let bcs = BoundaryConditions::new().set("block_bottom", SegmentBc::fixed());
    let estar = 210e9 / (2.0 * (1.0 - 0.09));
    let (b, _) = hertz(R, estar, P);
    // The block's contact segment (the slave) spans 4 b, the cylinder's arc (the master) 2 b;
    // under 40 P the Hertz half-width is 6.3 b.
    let model = BemModel::new(
        PlaneCondition::Strain,
        vec![
            block("block", steel(), 0.010, 0.010, 4.0 * b, 48),
            half_cylinder("cyl", steel(), R, 2.0 * b, 24, true),
        ],
    );
    let mut cp = ContactProblem::new(
        &model,
        &bcs,
        &[ContactPair::new("block_contact", "cyl_contact", 0.0)],
        &["cyl_face"],
    )
    .unwrap();
    match cp.solve_steps(&[press(40.0 * P)], &ContactOptions::default()) {
        Err(err @ Error::ContactReachesWindow { .. }) => {
            assert!(err.to_string().contains("end the slave segment"), "{err}")
        }
        Err(other) => panic!("expected the window error, got {other}"),
        Ok(_) => panic!("a contact past a smooth master end was accepted"),
    }
}
