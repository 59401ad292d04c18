//! A dynamic 2D case through the command line (issue 13): the human summary (the method as
//! the case writes it, the damage and input-work lines), the damage and energy files, the
//! dry run's cost lines, and bad dynamic input whose first line names the field and the
//! rule. The numbers: crates/tribo-case/tests/dyn_damage.rs.
// Tests may unwrap: a panic here is a failed test (workspace lints deny it in library code).
#![allow(clippy::unwrap_used, clippy::expect_used)]
mod common;
use common::{assert_files, example, read_json, run_case, stderr, stdout, tribo};

/// The column example (160 steps, BDF2) with `[damage]` of sigma_int at 15 MPa: the
/// reflected wave doubles the stress to 20 MPa, psi 4/3 (the static run: 2/3).
fn column_with_damage() -> String {
    example("column").replace("fields_every = 80", "fields_every = 40")
        + "\n[damage]\nregion = \"column\"\nquantity = \"sigma_int\"\nlimit = \"15 MPa\"\n"
}

#[test]
fn a_dynamic_run_with_damage_prints_and_writes_the_damage_and_the_input_work() {
    let (o, out, _d) = run_case(&column_with_damage(), &[], &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(text.contains("(bdf2, all steps at once"), "{text}");
    assert!(!text.contains("Bdf2"), "{text}");
    assert!(text.contains("damage of column (sigma_int at"), "{text}");
    assert!(text.contains("x static"), "{text}");
    assert!(text.contains("input work:"), "{text}");
    assert_files(&out, &["damage.csv", "energy.csv", "summary.json"]);
    let csv = std::fs::read_to_string(out.join("damage.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("time_s,region,quantity,dangerous_area_m2,damageability_m2,psi_max")
    );
    assert_eq!(lines.count(), 161);
    let energy = std::fs::read_to_string(out.join("energy.csv")).unwrap();
    assert_eq!(
        energy.lines().next(),
        Some(
            "time_s,input_work_J_per_m,strain_energy_J_per_m,kinetic_energy_J_per_m,\
             balance_J_per_m"
        )
    );
    let s = read_json(&out.join("summary.json"));
    let d = &s["dynamics"]["damage"];
    assert_eq!(d["region"], "column");
    assert_eq!(d["unit"], "Pa");
    let ratio = d["psi_max_over_static"].as_f64().unwrap();
    assert!((1.9..2.6).contains(&ratio), "{ratio}");
    assert!(s["units"]["dynamics.damage.peak_dangerous_area_m2"] == "m^2");
    assert!(
        s["dynamics"]["energy"]["input_work_end_j_per_m"]
            .as_f64()
            .unwrap()
            > 0.0
    );
    // psi in every snapshot.
    let vtu = std::fs::read(out.join("fields_0000.vtu")).unwrap();
    let head = String::from_utf8_lossy(&vtu[..vtu.len().min(4000)]).into_owned();
    assert!(head.contains("Name=\"psi\""), "{head}");
}

/// `--dry-run` of a dynamic case lists the Laplace-domain solves and, for Radau IIA, the
/// cost against BDF2 (radau_iia_3 on the cavity runs ~6 x BDF2: minutes, not a hang).
#[test]
fn the_dry_run_of_a_dynamic_case_states_its_cost() {
    let cavity = example("cavity");
    let o = tribo(&["run", "-", "--dry-run"], Some(cavity));
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(
        text.contains("dynamics: 120 steps")
            && text.contains("Laplace-domain solves (61 frequencies x 1 stages)"),
        "{text}"
    );
    let radau = cavity.replace("method = \"bdf2\"", "method = \"radau_iia_3\"");
    let o = tribo(&["run", "-", "--dry-run"], Some(&radau));
    let text = stdout(&o);
    assert!(text.contains("(radau_iia_3)"), "{text}");
    assert!(text.contains("x 3 stages"), "{text}");
    assert!(
        text.contains("about 5.8 x the same run with method = \"bdf2\""),
        "{text}"
    );
}

/// Bad dynamic input: exit 2, and the first line of stderr names the field and the rule
/// (`error: <field> = <value>: <rule>`), for the values a user gets wrong.
#[test]
fn bad_dynamic_input_names_the_field_and_the_rule_on_the_first_line() {
    let cavity = example("cavity");
    for (from, to, field, rule) in [
        (
            "time_step = \"0.8 us\"",
            "time_step = \"-0.8 us\"",
            "dynamics.time_step",
            "> 0",
        ),
        (
            "time_step = \"0.8 us\"",
            "time_step = nan",
            "dynamics.time_step",
            "finite",
        ),
        (
            "time_step = \"0.8 us\"",
            "time_step = \"1e-300 s\"",
            "dynamics.duration",
            "time steps; must be in [1, 1000000]",
        ),
        (
            "density = \"8192 kg/m^3\"",
            "density = 0",
            "materials.steel.density",
            "[1e0, 1e5]",
        ),
        (
            "density = \"8192 kg/m^3\"",
            "density = \"7800 g\"",
            "materials.steel.density",
            "must be a density",
        ),
        (
            "method = \"bdf2\"",
            "method = \"Bdf2\"",
            "dynamics.method",
            "\"radau_iia_2\"",
        ),
        (
            "fields_at = [\"32 us\", \"96 us\"]",
            "fields_at = [\"32 us\", \"200 us\"]",
            "dynamics.fields_at[1]",
            "in [0, duration",
        ),
        (
            "time = \"step\"",
            "time = { ramp = \"-5 us\" }",
            "bc[2].time.ramp",
            "must be > 0",
        ),
    ] {
        assert!(cavity.contains(from), "{from}");
        let (o, out, _d) = run_case(&cavity.replacen(from, to, 1), &[], &[]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{to}: {err}");
        assert!(!out.exists(), "{to}: wrote files");
        let first = err.lines().next().unwrap_or("");
        assert!(
            first.starts_with(&format!("error: {field} = ")) && first.contains(rule),
            "{to}: {first}"
        );
    }
}
