//! The rules of a half-space case on the library's errors: every bad input is refused as bad
//! input ([`tribo_case::CaseError::is_bad_input`], exit 2 at the command line) with a
//! message naming the field (and, where it says so, the rule); rules that need the solution
//! (a contact that reaches the window, |Q| >= f F_N) are refused by the run. The command-line
//! tests keep a sample of these for the exit code and the files not written.
// Tests may unwrap: a panic here is a failed test (workspace lints deny it in library code).
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use common::{assert_refused, energy_case, example, height_map, paper, parse, sphere, DAMAGE_BASE};

/// Parses `text` with the files `files` in a fresh directory (the case's base directory).
fn parse_with_files(
    text: &str,
    files: &[(&str, &str)],
) -> Result<tribo_case::case::HalfSpaceCase, tribo_case::CaseError> {
    let dir = tempfile::tempdir().expect("a temporary directory");
    for (name, content) in files {
        std::fs::write(dir.path().join(name), content).expect("written");
    }
    tribo_case::case::parse_case(text, "case.toml", dir.path())
}

fn assert_file_refused(text: &str, files: &[(&str, &str)], field: &str) {
    let e = parse_with_files(text, files).expect_err("refused");
    assert!(e.is_bad_input(), "{field}: {e}");
    assert!(e.to_string().contains(field), "{field}: {e}");
}

#[test]
fn every_bad_input_rule_names_the_field() {
    let p = paper("", "");
    let cases: Vec<(String, &str)> = vec![
        (p.replacen("E = 2.01e11", "E = 0.0", 1), "body1.E"),
        (p.replacen("E = 2.01e11", "E = -2.01e11", 1), "body1.E"),
        (p.replacen("E = 2.01e11", "E = inf", 1), "body1.E"),
        (p.replacen("E = 2.01e11", "E = nan", 1), "body1.E"),
        (
            p.replacen("nu = 0.3", "nu = 0.55", 1),
            "body1.nu = 0.55: Poisson's ratio must be in (-1, 0.5)",
        ),
        (p.replacen("nu = 0.3", "nu = -1.2", 1), "body1.nu"),
        (p.replace("[-0.01, 0.01]", "[-0.01, 0.0]"), "body2.radii[1]"),
        (
            p.replace("load = 2000.0", "load = 2000.0\napproach = 2.7e-5"),
            "contact.load",
        ),
        (p.replace("load = 2000.0", ""), "contact"),
        (p.replace("load = 2000.0", "load = 0.0"), "contact.load"),
        (p.replace("load = 2000.0", "load = -10.0"), "contact.load"),
        (
            p.replace("load = 2000.0", "approach = 0.0"),
            "contact.approach",
        ),
        (
            p.replace("load = 2000.0", "approach = -1e-6"),
            "contact.approach",
        ),
        (p.replace("n = 21", "n = 3"), "grid.n"),
        (p.replace("n = 21", "n = 1000000"), "grid.n"),
        (p.replace("n = 21", "n = [21, 2]"), "grid.n[1]"),
        (
            p.replace("[0.005, 0.05]", "[\"inf\", \"inf\"]")
                .replace("[-0.01, 0.01]", "[\"inf\", \"inf\"]"),
            "radii",
        ),
        (p.replace("nu = 0.3", "nu = 0.3\nnuu = 0.3"), "nuu"),
        (p.replace("[grid]", "[gird]"), "gird"),
        (p.replace("extent = 1.5", "extnt = 1.5"), "extnt"),
        (p.replace("extent = 1.5", "extent = 0.5"), "grid.extent"),
        (p.clone() + "[solver]\nmethod = \"newton\"\n", "newton"),
        (p.replace("title = ", "title = = "), "case.toml"),
    ];
    for (text, field) in &cases {
        assert_refused(text, field);
    }
}

#[test]
fn bad_height_maps_name_the_file_and_line() {
    let file = height_map("file = \"map.csv\"");
    let ok = "0,1,0\n1,0,1\n0,1,0\n";
    assert!(parse_with_files(&file, &[("map.csv", ok)]).is_ok());
    assert_file_refused(&file, &[], "body1.surface.file");
    for (content, field) in [
        ("0,1,0\n1,0\n0,1,0\n", "map.csv, line 2"),
        ("0,1,0\n1,x,1\n0,1,0\n", "map.csv, line 2"),
        ("# h\n0,1,0\n1,0,1\nnan,1,0\n", "map.csv, line 4"),
        ("", "map.csv"),
    ] {
        assert_file_refused(&file, &[("map.csv", content)], field);
    }
    // A surface needs grid.half_width (extent is defined only for Hertzian gaps).
    let t = file.replace("half_width = 1e-4", "extent = 1.5");
    assert_file_refused(&t, &[("map.csv", ok)], "grid.extent");
}

#[test]
fn bad_bulk_input_names_the_field() {
    let base = paper("", "[bulk]\nstress_max = 6.4e8\n");
    for (extra, field) in [
        ("shaft_radius = -0.01", "bulk.shaft_radius"),
        ("shaft_radius = \"-10 mm\"", "bulk.shaft_radius"),
        ("points = 2", "bulk.points"),
        ("points = 4", "bulk.points"),
        ("kind = \"torsion\"", "bulk.kind"),
        ("kind = \"tension_compression\"", "bulk.kind"),
        ("shaft = \"roller\"", "bulk.shaft"),
        ("stress = inf", "bulk.stress"),
        ("sigma_max = 6.4e8", "sigma_max"),
    ] {
        assert_refused(&format!("{base}{extra}\n"), field);
    }
    assert_refused(&paper("", "[bulk]\nstress_max = 0\n"), "bulk.stress_max");
    // Compression so large that the contact reaches the window (refused by the run).
    assert_refused(
        &paper("", "[bulk]\nstress_max = \"3 GPa\"\npoints = 3\n"),
        "bulk.stress_max",
    );
    assert_refused(
        &paper("", "[bulk]\nkind = \"bending\"\n"),
        "bulk.stress_max",
    );
    assert_refused(
        &paper("", "[bulk]\nshaft = \"body1\"\nstress_max = 6.4e8\n"),
        "bulk.shaft_radius",
    );
    // The bending stress from a force and a span: each item checked.
    let bending = "[bulk]\nkind = \"bending\"\nstress_max = 6.4e8\npoints = 3\n\
                   bending_force = \"5 kN\"\nspan = \"200 mm\"\n";
    for (extra, field) in [
        ("stress = 1e8\n", "bulk.stress"),
        ("span = 0.0\n", "bulk.span"),
        ("support = \"pinned\"\n", "bulk.support"),
        ("bending_side = \"top\"\n", "bulk.bending_side"),
    ] {
        let text = paper("", &format!("{bending}{extra}")).replacen(
            "span = \"200 mm\"\n",
            "",
            usize::from(extra.starts_with("span")),
        );
        assert_refused(&text, field);
    }
    assert_refused(
        &paper(
            "",
            "[bulk]\nkind = \"both\"\nstress_max = 6.4e8\nbending_force = 5e3\nspan = 0.2\n",
        ),
        "bulk.bending_force",
    );
    assert_refused(
        &paper(
            "",
            "[bulk]\nkind = \"bending\"\nstress_max = 6.4e8\nbending_force = 5e3\n",
        ),
        "bulk.span",
    );
}

#[test]
fn bad_friction_and_field_input_names_the_field() {
    for (extra, field) in [
        ("friction = -0.1\nsliding = true\n", "contact.friction"),
        ("friction = \"nan\"\nsliding = true\n", "contact.friction"),
        ("friction = 0.2\n", "contact.friction"),
        ("tangential_load = 5.0\n", "contact.tangential_load"),
        ("sliding = true\n", "contact.sliding"),
        ("friction = 0.2\nsliding = 1\n", "contact.sliding"),
        (
            "friction = 0.2\nsliding = true\ntangential_load = 5.0\n",
            "contact.tangential_load",
        ),
        (
            "friction = 0.2\ntangential_load = -1.0\n",
            "contact.tangential_load",
        ),
        (
            "friction = 0.2\ntangential_load = 5.0\ntangential_angle_deg = \"x\"\n",
            "contact.tangential_angle_deg",
        ),
        // Q >= f F_N: the library's message (full sliding, and how to ask for it).
        (
            "friction = 0.2\ntangential_load = 20.0\n",
            "contact.tangential_load",
        ),
        (
            "friction = 0.2\ntangential_load = 5.0\ntraction_direction = \"sideways\"\n",
            "contact.traction_direction",
        ),
    ] {
        assert_refused(&sphere(16, extra, ""), field);
    }
    let beyond = sphere(16, "friction = 0.2\ntangential_load = 25.0\n", "");
    let case = parse(&beyond).expect("valid until solved");
    let e = tribo_case::pipeline::run(&case, &mut tribo_case::Silent).expect_err("refused");
    assert!(e.to_string().contains("sliding = true"), "{e}");
    // At f F_N partial slip is refused for both traction directions.
    for direction in ["", "traction_direction = \"free\"\n"] {
        assert_refused(
            &sphere(
                16,
                &format!("friction = 0.3\ntangential_load = 30.0\n{direction}"),
                "",
            ),
            "contact.tangential_load",
        );
    }
    let flat = example("sphere-on-flat");
    for (section, field) in [
        ("[field]\nn = [39, 39]", "field.n"),
        ("[field]\nn = [39, 39, 1]", "field.n[2]"),
        ("[field]\nn = [512, 512, 20]", "field.n"),
        ("[field]\nextent = 0", "field.extent"),
        ("[field]\ndepth = -1", "field.depth"),
        ("[field]\ndepth = 1\ndepth_m = 1e-4", "field.depth"),
        ("[field]\nbody = \"body3\"", "field.body"),
    ] {
        assert_refused(&format!("{flat}{section}\n"), field);
    }
    for (section, field) in [
        ("[field]\npoints = \"nodes\"\n", "field.points"),
        ("[field]\npoints = \"centres\"\nn = [9, 9, 5]\n", "field.n"),
        (
            "[field]\npoints = \"centres\"\nextent = 1.0\n",
            "field.extent",
        ),
        ("[field]\nlayers = 5\n", "field.layers"),
        (
            "[field]\npoints = \"centres\"\nlayers = 1\n",
            "field.layers",
        ),
        (
            "[field]\npoints = \"centres\"\ndepth = -1.0\n",
            "field.depth",
        ),
    ] {
        assert_refused(&paper("", section), field);
    }
}

#[test]
fn bad_damage_and_cycle_input_names_the_field() {
    let field = "[field]\nn = [5, 5, 3]\n";
    for (section, name) in [
        ("[damage]\nlimit_over_p0 = 0.2\n", "damage"),
        (
            "FIELD[damage]\ncriteria = [\"sigma_vm\"]\nlimit_over_p0 = 0.2\n",
            "damage.criteria[0]",
        ),
        (
            "FIELD[damage]\ncriteria = [\"u\"]\nlimit_over_p0 = 0.2\n",
            "damage.limits.u",
        ),
        (
            "FIELD[damage]\ncriteria = [\"sigma_int\"]\n",
            "damage.limits.sigma_int",
        ),
        (
            "FIELD[damage]\ncriteria = [\"sigma_xx-\"]\n[damage.limits]\n\"sigma_xx-\" = 1e8\n",
            "damage.limits.sigma_xx-",
        ),
        (
            "FIELD[damage]\ncriteria = [\"sigma_int\"]\n[damage.limits]\nu = 1e6\n",
            "damage.limits.u",
        ),
        (
            "FIELD[damage]\nlimit_over_p0 = -1.0\n",
            "damage.limit_over_p0",
        ),
        ("FIELD[damage]\nlimit_load = 0.0\n", "damage.limit_load"),
        (
            "FIELD[damage]\nlimit_over_p0 = 0.2\n[damage.study]\nbending_over_p0 = [0.1]\n",
            "damage.study",
        ),
        (
            "FIELD[bulk]\nstress_max = 1e8\n[damage]\nlimit_over_p0 = 0.2\n[damage.study]\n\
             bending_over_p0 = [0.1, 0.05]\n",
            "damage.study.bending_over_p0[1]",
        ),
        (
            "FIELD[damage]\nlimit_over_p0 = 0.2\nlimit_load = 4000.0\n",
            "damage.limit_load",
        ),
        (
            "FIELD[damage]\nlimit_over_p0 = nan\n",
            "damage.limit_over_p0",
        ),
    ] {
        assert_refused(&paper(DAMAGE_BASE, &section.replace("FIELD", field)), name);
    }
    // Two default limits: the message names both and says "not both".
    let both = paper(
        DAMAGE_BASE,
        &format!("{field}[damage]\nlimit_over_p0 = 0.2\nlimit_load = 4000.0\n"),
    );
    let e = parse(&both).expect_err("refused").to_string();
    assert!(
        e.contains("not both") && e.contains("damage.limit_over_p0"),
        "{e}"
    );
    let cycle = paper(
        DAMAGE_BASE,
        "[bulk]\nkind = \"bending\"\nstress_max = 6.4e8\n[field]\nn = [5, 5, 3]\n\
         [damage]\nlimit_over_p0 = 0.186\n[damage.cycle]\n",
    );
    for (extra, name) in [
        ("kind = \"spinning\"\nperiod = 1.0\n", "damage.cycle.kind"),
        (
            "kind = \"rotating-bending\"\nperiod = 1.0\n",
            "damage.cycle.amplitude",
        ),
        (
            "kind = \"rotating-bending\"\namplitude = 1e8\n",
            "damage.cycle.period",
        ),
        (
            "kind = \"rotating-bending\"\namplitude = 1e8\nperiod = 1.0\nsteps = 1\n",
            "damage.cycle.steps",
        ),
        (
            "kind = \"rotating-bending\"\namplitude = 1e8\nperiod = 1.0\ncycles = 0\n",
            "damage.cycle.cycles",
        ),
        ("kind = \"rolling\"\nperiod = 1.0\n", "damage.cycle.speed"),
        (
            "kind = \"rolling\"\nspeed = 0.0\nperiod = 1.0\n",
            "damage.cycle.speed",
        ),
    ] {
        assert_refused(&format!("{cycle}{extra}"), name);
    }
    let u0 = 5.0e6;
    let energy = energy_case(u0);
    for (extra, name) in [
        ("a_n = -1.0\n", "damage.energy.a_n"),
        ("temperature = -5.0\n", "damage.energy.temperature"),
    ] {
        assert_refused(&energy.replace("temperature = 300.0\n", extra), name);
    }
    assert_refused(
        &energy.replace(
            &format!("[damage.energy]\nu0 = {u0}\n"),
            "[damage.energy]\n",
        ),
        "damage.energy.u0",
    );
}

/// Issue 11 item 10: non-finite TOML floats (passed as numbers, echoed as null) and absurd
/// values within the old rules (E = 1e-308, load = 1e308, which ended as "numerical
/// failure" naming no field) are refused by their physical ranges, naming the field and the
/// rule.
#[test]
fn non_finite_and_absurd_values_are_refused_by_their_physical_range() {
    let roller = paper("", "");
    let map = height_map("heights = [[0, 1, 0], [1, 2, 1], [0, 1, 0]]");
    // (case, the text replaced, its replacement, the field, the rule; "": not stated).
    let cases = [
        (
            &roller,
            "[-0.01, 0.01]",
            "[-inf, 0.01]",
            "body2.radii[0]",
            "",
        ),
        (
            &roller,
            "[-0.01, 0.01]",
            "[nan, 0.01]",
            "body2.radii[0]",
            "",
        ),
        (
            &roller,
            "[-0.01, 0.01]",
            "[-0.01, \"-inf m\"]",
            "body2.radii[1]",
            "",
        ),
        (&roller, "extent = 1.5", "extent = inf", "grid.extent", ""),
        (&roller, "load = 2000.0", "load = inf", "contact.load", ""),
        (
            &roller,
            "load = 2000.0",
            "load = \"inf kN\"",
            "contact.load",
            "",
        ),
        (
            &roller,
            "E = 2.01e11",
            "E = 1e-308",
            "body1.E = 1e-308",
            "[1e2, 1e13] Pa",
        ),
        (
            &roller,
            "E = 2.01e11",
            "E = \"1e5 GPa\"",
            "body1.E",
            "[1e2, 1e13] Pa",
        ),
        (
            &roller,
            "load = 2000.0",
            "load = 1e308",
            "contact.load",
            "p0/E*",
        ),
        (
            &roller,
            "load = 2000.0",
            "load = 1e-300",
            "contact.load",
            "p0/E*",
        ),
        // 2 MN on a 10 mm steel roller: p0/E* = 0.28.
        (
            &roller,
            "load = 2000.0",
            "load = \"2 MN\"",
            "contact.load",
            "small strains",
        ),
        (
            &roller,
            "load = 2000.0",
            "approach = 1e300",
            "contact.approach",
            "p0/E*",
        ),
        (
            &roller,
            "[-0.01, 0.01]",
            "[-0.01, 1e-300]",
            "body2.radii[1]",
            "[1e-9, 1e6] m",
        ),
        (
            &roller,
            "[-0.01, 0.01]",
            "[-1e300, 0.01]",
            "body2.radii[0]",
            "[1e-9, 1e6] m",
        ),
        (
            &map,
            "half_width = 1e-4",
            "half_width = 1e-12",
            "grid.half_width[0]",
            "[1e-9, 1e6] m",
        ),
        (
            &map,
            "load = 10.0",
            "load = 1e12",
            "contact.load",
            "mean pressure",
        ),
    ];
    for (case, from, to, field, rule) in cases {
        assert!(case.contains(from), "{from}");
        let text = case.replacen(from, to, 1);
        assert_refused(&text, field);
        let e = match parse(&text) {
            Err(e) => e,
            Ok(case) => tribo_case::pipeline::run(&case, &mut tribo_case::Silent)
                .expect_err("refused by the run"),
        };
        assert!(e.to_string().contains(rule), "{field}, {rule}: {e}");
    }
}
