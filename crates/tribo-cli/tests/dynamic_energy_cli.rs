//! The energy balance of a dynamic run and the range rules of the dynamic inputs through
//! the command line (issue 13): `energy.csv`'s columns and the summary's worst balance in
//! the linear run; an initial velocity at or above the shear wave speed (exit 2, the field
//! named, nothing written) and a note above 1 % of it; the probe of the other dynamic
//! inputs at extreme values (each exit 2 naming the item). The numbers against the closed
//! form: crates/tribo/src/dynamics/energy_domain_tests.rs.
// Tests may unwrap: a panic here is a failed test (workspace lints deny it in library code).
#![allow(clippy::unwrap_used, clippy::expect_used)]
mod common;
use common::{assert_bad_input, example, read_json, run_case, run_case_loud, stderr};

/// The column example (BDF2, 160 steps to 4 L/c): energy.csv has W, U, K and the balance;
/// U + K follows W (the worst balance a few per cent of max W: BDF2's damping at the
/// smeared front and the coarse 125 mm triangles, docs/theory/DYNAMICS.md sec. 5.8) and
/// before the reflection (t < L/c = 200 us) U and K are each about W/2.
#[test]
fn the_linear_run_writes_strain_and_kinetic_energy_and_their_balance() {
    let (o, out, _d) = run_case(example("column"), &[], &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let csv = std::fs::read_to_string(out.join("energy.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some(
            "time_s,input_work_J_per_m,strain_energy_J_per_m,kinetic_energy_J_per_m,\
             balance_J_per_m"
        )
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 161);
    // p0 = 10 MPa, A = 0.25 m, c = 5000 m/s, E = 200 GPa: W = p0^2 A c t / E = 6.25e5 t.
    let r = &rows[20]; // t = 100 us
    assert!((r[0] - 1e-4).abs() < 1e-12);
    let w = 6.25e5 * r[0];
    assert!((r[1] / w - 1.0).abs() < 0.03, "W {} vs {w}", r[1]);
    for (name, v) in [("U", r[2]), ("K", r[3])] {
        assert!(
            (v / (0.5 * w) - 1.0).abs() < 0.1,
            "{name} {v} vs {}",
            0.5 * w
        );
    }
    for r in &rows {
        assert!((r[1] - r[2] - r[3] - r[4]).abs() <= 1e-9 * r[1].abs().max(1.0));
    }
    let s = read_json(&out.join("summary.json"));
    let e = &s["dynamics"]["energy"];
    let worst = e["balance_worst_relative"].as_f64().unwrap();
    eprintln!(
        "column: worst balance {worst:e} of max W at {}",
        e["balance_worst_time_s"]
    );
    assert!(worst > 0.0 && worst < 0.1, "{worst}");
    assert!(e["strain_energy_end_j_per_m"].as_f64().unwrap() > 0.0);
    assert_eq!(s["units"]["dynamics.energy.balance_worst_relative"], "1");
}

/// `initial_velocity = [1e300, 0]` used to reach the convolution ("numerical failure in
/// cq::convolve", exit 1): now exit 2 naming `dynamics.initial_velocity.striker` and the
/// shear wave speed, nothing written; also at c2 itself and with a NaN component.
#[test]
fn an_initial_velocity_at_or_above_the_shear_wave_speed_is_refused() {
    let rod = example("rod-impact");
    let from = "initial_velocity = { striker = [\"1 m/s\", 0] }";
    assert!(rod.contains(from));
    // Steel, nu = 0: c2 = sqrt(E / (2 rho)) = sqrt(200e9 / 16000) = 3535.5 m/s.
    for v in [
        "[1e300, 0]",
        "[\"3600 m/s\", 0]",
        "[0, \"-3536 m/s\"]",
        "[nan, 0]",
    ] {
        let text = rod.replacen(from, &format!("initial_velocity = {{ striker = {v} }}"), 1);
        let err = assert_bad_input(&text, &[], "dynamics.initial_velocity.striker");
        let first = err.lines().next().unwrap_or("");
        assert!(
            first.contains("shear wave speed c2") || first.contains("finite"),
            "{v}: {first}"
        );
    }
}

/// 50 m/s (1.4 % of c2) runs, with a note naming the item.
#[test]
fn an_initial_velocity_above_one_percent_of_c2_gets_a_note() {
    let rod = example("rod-impact").replacen(
        "initial_velocity = { striker = [\"1 m/s\", 0] }",
        "initial_velocity = { striker = [\"50 m/s\", 0] }",
        1,
    );
    let (o, _d) = run_case_loud(&rod, &[]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(
        err.contains("note: dynamics.initial_velocity.striker: |v| = 5e1 m/s is 1.4 %"),
        "{err}"
    );
}

/// The probe of the other dynamic inputs (issue 13): each extreme value exits 2 naming the
/// item and writes nothing. (dt = 1e-300 s, density 0 and 1e300, a negative ramp:
/// dyn_cli.rs.)
#[test]
fn extreme_dynamic_inputs_exit_2_naming_the_item() {
    let cavity = example("cavity");
    let nan_csv = "t,f\n0,0\n1e-5,NaN\n";
    let big_csv = "t,f\n0,0\n1e-5,1e308\n";
    for (from, to, files, field) in [
        // 1e12 steps: over the limit of 1e6 (the history memory grows as M).
        (
            "duration = \"96 us\"",
            "steps = 1000000000000",
            &[][..],
            "dynamics.steps",
        ),
        // 96 us / 0.7 us is not a whole number of steps.
        (
            "time_step = \"0.8 us\"",
            "time_step = \"0.7 us\"",
            &[][..],
            "dynamics.duration",
        ),
        // A time table with 1e308 factors (the load times 1e308 overflows).
        (
            "time = \"step\"",
            "time = { points = [[0, 0], [\"10 us\", 1e308]] }",
            &[][..],
            "bc[2].time.points[1][1]",
        ),
        (
            "time = \"step\"",
            "time = { csv = \"big.csv\" }",
            &[("big.csv", big_csv)][..],
            "bc[2].time.csv",
        ),
        // A NaN factor in a tabulated CSV.
        (
            "time = \"step\"",
            "time = { csv = \"pulse.csv\" }",
            &[("pulse.csv", nan_csv)][..],
            "bc[2].time.csv",
        ),
        // A probe at 1e300.
        (
            "at = [\"141.4213562373095 mm\", \"141.4213562373095 mm\"]",
            "at = [1e300, 0]",
            &[][..],
            "probe[1].at",
        ),
        (
            "density = \"8192 kg/m^3\"",
            "density = \"1e-300 kg/m^3\"",
            &[][..],
            "materials.steel.density",
        ),
    ] {
        assert!(cavity.contains(from), "{from}");
        let text = cavity.replacen(from, to, 1);
        assert_bad_input(&text, files, field);
    }
}
