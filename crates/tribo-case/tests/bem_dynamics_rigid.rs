//! Rigid (guided) segments with `[dynamics]` end to end (issue 13): the column example
//! driven through a rigid end face (the 1D impedance solution), and a rigid punch pressed
//! slowly onto a base against the case's own static run (the same rigid segment).
// Tests may unwrap: a panic here is a failed test (workspace lints deny it in library code).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;

use tribo::dynamics::energy_domain::EnergyMesh;
use tribo_case::bem::dynamics::DynamicOutcome;
use tribo_case::bem::pipeline::BemOutcome;
use tribo_case::examples::find;
use tribo_case::{run, Case, Results, Silent};

/// Runs a case text and returns its 2D outcome.
fn outcome(text: &str, name: &str) -> BemOutcome {
    let case = Case::from_toml(text, name, Path::new(".")).expect("valid case");
    match run(&case, &mut Silent).expect("run") {
        Results::Bem2d(out) => *out,
        Results::HalfSpace(_) => panic!("not a 2D case"),
    }
}

/// The column example (steel, nu = 0, E = 200 GPa, rho = 8000: c = 5000 m/s; L = 1 m,
/// W = 0.25 m) with its loaded end a rigid segment under the sudden force F = 2.5 MN/m
/// (the example's 10 MPa over W) instead of the pressure, to t = 380 us < 2 L/c.
fn rigid_column() -> String {
    let text = find("column").unwrap().text.to_string();
    let text = text
        .replace(
            "[dynamics]",
            "rigid = [\"left\"]\n\n[[steps]]\nrigid.left = { fx = \"2.5 MN/m\", fy = 0 }\n\n[dynamics]",
        )
        .replace(
            "[[bc]]\nsegment = \"left\"\npressure = \"10 MPa\"\ntime = \"step\"\n",
            "",
        )
        .replace("duration = \"800 us\"", "duration = \"380 us\"")
        .replace("fields_every = 80\n", "");
    assert!(text.contains("rigid.left") && !text.contains("pressure = \"10 MPa\""));
    text
}

/// The rigid end face under a sudden force F: a plane-wave source into the column, so it
/// moves with v = F / (rho c W) = 0.25 m/s (Graff 1975, longitudinal waves in rods), the
/// front carries sigma_xx = -F / W = -10 MPa and the particle velocity 0.25 m/s: exactly
/// the pressure-loaded column's state (the example's closed form) until the reflection
/// returns at 2 L / c = 400 us. The static run (the force at its full value) is solved as
/// any case's.
///
/// Measured: see the printed line. Tolerances: the face's translation within 0.25 m/s *
/// (t + dt) (the BDF2 start-up offset dt/2 of a jump at t_0, library test
/// `rigid_end_of_a_column_moves_with_the_impedance_velocity`) and its velocity over
/// 150..350 us within 1 % (measured 0.24973 m/s); the mid probe's velocity and stress over
/// 180..260 us (behind the front, which passes at 100 us, before the reflection from the
/// fixed end returns at 300 us; measured 0.2495 m/s and -9.98 MPa at 200 us) within 2 %
/// (the pressure-loaded example's probes, 1D values to 1-2 %); the force equation to 1e-9
/// relative.
#[test]
fn rigid_end_face_drives_the_column_with_the_impedance_velocity() {
    let out = outcome(&rigid_column(), "rigid-column");
    let d: &DynamicOutcome = out.dynamics.as_ref().unwrap();
    let contact = d.contact.as_ref().unwrap();
    assert_eq!(contact.march_contact_unknowns, 0);
    let rigid = &contact.rigid[0];
    assert_eq!(rigid.segment, "left");
    let times = &d.history.times;
    let dt = d.time_step;
    let at = |t: f64| times.iter().position(|&x| (x - t).abs() < 1e-9).unwrap();
    let (a, b) = (at(150e-6), at(350e-6));
    let v_face = (rigid.translation[b][0] - rigid.translation[a][0]) / 200e-6;
    for (k, &t) in times.iter().enumerate() {
        assert!(
            (rigid.force[k][0] - 2.5e6).abs() < 1e-9 * 2.5e6,
            "{:?}",
            rigid.force[k]
        );
        assert!(rigid.translation[k][0] <= 0.25 * (t + dt) + 1e-12);
    }
    let mid = d.history.probes.iter().find(|p| p.name == "mid").unwrap();
    // The mid probe (x = L/2) between the front's passage (100 us, smeared over ~40 us)
    // and the reflection's return from x = L (300 us).
    let window: Vec<usize> = (at(180e-6)..=at(260e-6)).collect();
    let mean =
        |f: &dyn Fn(usize) -> f64| window.iter().map(|&k| f(k)).sum::<f64>() / window.len() as f64;
    let v_mid = mean(&|k| mid.velocity[k][0]);
    let s_mid = mean(&|k| mid.stress[k].xx);
    eprintln!(
        "rigid column: face U(350 us) {:.6e} m (0.25 t = {:.6e}), face velocity {v_face:.5} m/s, \
         mid v {v_mid:.5} m/s, mid sigma_xx {s_mid:.5e} Pa",
        rigid.translation[b][0],
        0.25 * 350e-6
    );
    assert!((v_face / 0.25 - 1.0).abs() < 0.01, "{v_face}");
    assert!((v_mid / 0.25 - 1.0).abs() < 0.02, "{v_mid}");
    assert!((s_mid / -10e6 - 1.0).abs() < 0.02, "{s_mid}");
    // The static run: the rigid face under the full force (a static column, 10 MPa).
    let st = &out.main.steps[0].rigid[0];
    assert!((st.force[0] - 2.5e6).abs() < 1e-6 * 2.5e6);
}

/// The slow rigid punch case (a steel block 20 x 10 mm on a base 40 x 20 mm, f = 0.3, the
/// top face rigid: guided in x, fy = -2 MN/m ramped over 2 ms, run to 3 ms).
fn slow_punch_text() -> String {
    r#"
kind = "bem2d"
title = "rigid punch pressed slowly"
rigid = ["block_top"]

[dynamics]
time_step = "20 us"
duration = "3 ms"

[materials.steel]
E = "200 GPa"
nu = 0.3
density = "8000 kg/m^3"

[[regions]]
name = "base"
material = "steel"
start = ["-20 mm", "-20 mm"]
outline = [
  { name = "base_bottom", to = ["20 mm", "-20 mm"], elements = 6 },
  { name = "base_right", to = ["20 mm", 0], elements = 3 },
  { name = "base_top", to = ["-20 mm", 0], elements = 12 },
  { name = "base_left", to = ["-20 mm", "-20 mm"], elements = 3 },
]
[[regions]]
name = "block"
material = "steel"
start = ["-10 mm", 0]
outline = [
  { name = "block_bottom", to = ["10 mm", 0], elements = 12 },
  { name = "block_right", to = ["10 mm", "10 mm"], elements = 3 },
  { name = "block_top", to = ["-10 mm", "10 mm"], elements = 4 },
  { name = "block_left", to = ["-10 mm", 0], elements = 3 },
]

[[bc]]
segment = "base_bottom"
ux = 0
uy = 0

[[contact]]
slave = "block_bottom"
master = "base_top"
friction = 0.3

[[steps]]
rigid.block_top = { ux = 0, fy = "-2 MN/m", time = { ramp = "2 ms" } }

[field]
size = "4 mm"
"#
    .to_string()
}

/// A block pressed onto a base through a rigid top face (guided in x, the force fy ramped
/// over 2 ms, about 40 shear transits of the block): at the end the punch's translation
/// and the contact force equal the case's static run (the same rigid segment at the full
/// force). Quasi-static error (T_tr / T0)^2 ~ 6e-4 plus the free vibration the ramp
/// leaves; the library test of the same statement measured 1.2e-3 (translation) and
/// 1.2e-3 of max p. Tolerance 1 %. The energies at the end: K ~ 0 (4e-15 of W); U see
/// below.
///
/// The strain energy at the end against the static run's strain energy on the same field
/// triangulation (the static sampler's values, the same quadrature): the recovery
/// evaluates the boundary nodes by the static sampler's rule (a boundary layer inside,
/// corners from the boundary solution), so what remains is the quasi-static error.
/// Measured: U = 10.50907 J/m against 10.51004 (U/U_static - 1 = -9.2e-5; the
/// translation's error 4.4e-5, doubled in U ~ u^2); before the rule (boundary nodes 1 %
/// inside their triangle) 14.65 J/m, +39 %. Tolerance 1e-3: ten times the measured, half the
/// quasi-static bound (T_tr/T0)^2 ~ 6e-4 doubled in U. The domain balance W - D - U - K at
/// the end: measured -2.04e-2 J/m = 1.9e-3 W (the static run's own U against W - D, the
/// field quadrature of the singular corners on 4 mm triangles); tolerance 5e-3 W.
#[test]
fn slow_rigid_punch_equals_the_static_run() {
    let text = slow_punch_text();
    let text = text.as_str();
    let out = outcome(text, "rigid-punch");
    let d = out.dynamics.as_ref().unwrap();
    let contact = d.contact.as_ref().unwrap();
    let rigid = &contact.rigid[0];
    let u = rigid.translation.last().unwrap();
    let st = &out.main.steps[0];
    let u_static = st.rigid[0].translation;
    let f_dyn = contact.pairs[0].peak_normal_force;
    let f_static = st.pairs[0].slave_force[1].abs();
    let eu = (u[1] / u_static[1] - 1.0).abs();
    eprintln!(
        "slow rigid punch: U_y {:.6e} vs static {:.6e} ({eu:.2e}); peak normal force {f_dyn:.6e} \
         vs static {f_static:.6e}",
        u[1], u_static[1]
    );
    assert!(eu < 0.01, "{eu}");
    assert!((f_dyn / f_static - 1.0).abs() < 0.01);
    assert!((rigid.force.last().unwrap()[1] + 2e6).abs() < 1e-9 * 2e6);
    // Energies: at the end of the ramp K ~ 0 and U = W - D (the quasi-static limit; the
    // friction dissipates little on this monotone path).
    let e = &contact.energy;
    let w = d.history.energy.input_work.as_ref().unwrap();
    let diss = d.history.energy.dissipation.as_ref().unwrap();
    let last = w.len() - 1;
    eprintln!(
        "slow punch energies: W {:.6e}, D {:.3e}, U {:.6e}, K {:.3e}, domain balance {:.3e}",
        w[last], diss[last], e.strain[last], e.kinetic[last], e.domain_balance[last]
    );
    // The static run's strain energy by the same quadrature on the same triangulation
    // (steel, plane strain: eps = (sigma - nu delta tr sigma)/(2 mu), tensor shear).
    let (young, nu) = (200e9, 0.3);
    let mu = young / (2.0 * (1.0 + nu));
    let mut u_static = 0.0;
    for f in &out.main.fields {
        let mesh = EnergyMesh::new(&f.nodes, &f.triangles, 8000.0).unwrap();
        let samples = f.samples.last().unwrap();
        let sig: Vec<[f64; 3]> = samples
            .iter()
            .map(|x| [x.stress.xx, x.stress.yy, x.stress.xy])
            .collect();
        let eps: Vec<[f64; 3]> = sig
            .iter()
            .map(|s| {
                let tr = s[0] + s[1];
                [
                    (s[0] - nu * tr) / (2.0 * mu),
                    (s[1] - nu * tr) / (2.0 * mu),
                    s[2] / (2.0 * mu),
                ]
            })
            .collect();
        u_static += mesh.strain_energy(&sig, &eps).unwrap();
    }
    eprintln!("slow punch: static strain energy on the same triangulation {u_static:.6e}");
    assert!(e.kinetic[last].abs() < 1e-2 * w[last]);
    let ratio = e.strain[last] / u_static;
    eprintln!("slow punch: U / U_static - 1 = {:.3e}", ratio - 1.0);
    assert!((ratio - 1.0).abs() < 1e-3, "{ratio}");
    assert!(e.domain_balance[last].abs() < 5e-3 * w[last]);
}

/// Strain and kinetic energy of the contact run (`energy.csv`'s `strain_energy`,
/// `deformation_kinetic`, `domain_balance`) on the rod impact example (without its
/// snapshots; field triangles 25 mm on rods 100 x 25 mm). Closed form (1D, by
/// characteristics): at t = L/c both rods move at v0/2 and are uniformly compressed, so
/// the translational energy is W/2, the kinetic energy of the deformation 0 and U = W/2;
/// after separation the target carries v0 (translational energy W) and nothing vibrates.
///
/// Measured: at t = L/c (20 us) U = 0.469 W (the fronts smeared over one 25 mm triangle of
/// the 100 mm rods: relative O(h/L)), K = -9e-5 W, K_rigid = 0.500 W; at the end U + K =
/// 1.7e-2 W (the boundary-work vibration, mechanical - translational, 4.7e-2 W: the march's
/// smeared release), translational 0.953 W; the worst |domain balance| 4.3e-2 W (9.0e-2
/// with the boundary nodes evaluated 1 % inside their triangle, before the static
/// sampler's rule). Tolerances: U within 10 % of W/2 (one triangle of four along the rod),
/// |K| below 1 % of W, K_rigid within 1 %, the end's vibration below 5 % of W and the
/// balance below 6 % (the measured 4.3e-2 and the margin of the time step's share of it).
#[test]
fn rod_impact_strain_and_kinetic_energy_after_separation() {
    let text = find("rod-impact")
        .unwrap()
        .text
        .replace("fields_every = 30\n", "");
    let out = outcome(&text, "rod-impact");
    let d = out.dynamics.as_ref().unwrap();
    let c = d.contact.as_ref().unwrap();
    let e = &c.energy;
    let w = d.history.energy.input_work.as_ref().unwrap();
    let n = w.len();
    assert_eq!(e.strain.len(), n);
    let w_max = w.iter().copied().fold(0.0_f64, f64::max);
    let worst = e
        .domain_balance
        .iter()
        .map(|b| b.abs())
        .fold(0.0_f64, f64::max)
        / w_max;
    let last = n - 1;
    let vib_boundary = e.mechanical[last] - e.translational_kinetic[last];
    let vib_domain = e.strain[last] + e.kinetic[last];
    // During contact (t = 20 us = L/c, both rods compressed over their whole length):
    // U = K = W/2 of the relative motion (1D: equal strain and kinetic energy densities
    // behind the fronts), i.e. U + K = W - K_rigid.
    let mid = d
        .history
        .times
        .iter()
        .position(|&t| (t - 20e-6).abs() < 1e-12)
        .unwrap();
    eprintln!(
        "rod impact energies: W {w_max:.6e}, end: U {:.4e}, K {:.4e}, U + K {vib_domain:.4e} vs \
         boundary vibration {vib_boundary:.4e}, translational {:.4e}; at 20 us U {:.4e} K {:.4e} \
         K_rigid {:.4e}; worst |domain balance| / W {worst:.3e}",
        e.strain[last],
        e.kinetic[last],
        e.translational_kinetic[last],
        e.strain[mid],
        e.kinetic[mid],
        e.translational_kinetic[mid],
    );
    assert!(worst < 0.06, "{worst}");
    assert!((e.strain[mid] / (0.5 * w_max) - 1.0).abs() < 0.1);
    assert!(e.kinetic[mid].abs() < 0.01 * w_max);
    assert!((e.translational_kinetic[mid] / (0.5 * w_max) - 1.0).abs() < 0.01);
    assert!(vib_domain < 0.05 * w_max && vib_boundary < 0.05 * w_max);
    assert!(e.translational_kinetic[last] > 0.9 * w_max);
}
