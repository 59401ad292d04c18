//! End-to-end tests of 2D boundary element cases (`kind = "bem2d"`): closed forms through
//! the command line, the clamp-knife-base example against the paper's statements and
//! equilibrium, and bad input.

#![allow(clippy::needless_range_loop)] // step and pair indices read like the summary
mod common;
#[path = "common/summary.rs"]
mod summary;
#[path = "common/vtk.rs"]
mod vtk;
use common::tribo;
use std::path::{Path, PathBuf};
use std::process::Output;

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn run_case(text: &str, extra: &[&str]) -> (Output, PathBuf, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("case.toml");
    std::fs::write(&case, text).unwrap();
    let out = dir.path().join("out");
    let mut args = vec![
        "run",
        case.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--quiet",
    ];
    args.extend_from_slice(extra);
    let o = tribo(&args, None);
    (o, out, dir)
}

fn read_json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// A 10 mm square plate: u_x = 0 on the left, u_y = 0 on the bottom (rollers), a traction
/// on the right; `RIGHT` is replaced by the right face's condition.
const PLATE: &str = r#"
kind = "bem2d"
title = "plate in tension"
plane = "strain"
[materials.steel]
E = "200 GPa"
nu = 0.3
[[regions]]
name = "plate"
material = "steel"
start = [0, 0]
outline = [
  { name = "bottom", to = ["10 mm", 0], elements = 4 },
  { name = "right", to = ["10 mm", "10 mm"], elements = 4 },
  { name = "top", to = [0, "10 mm"], elements = 4 },
  { name = "left", to = [0, 0], elements = 4 },
]
[[bc]]
segment = "left"
ux = 0
[[bc]]
segment = "bottom"
uy = 0
[[bc]]
segment = "right"
RIGHT
[field]
size = "1 mm"
"#;

#[test]
fn a_plate_in_uniform_tension_gives_the_applied_stress_everywhere() {
    let text = PLATE.replace("RIGHT", "tx = \"100 MPa\"");
    let (o, out, _d) = run_case(&text, &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let s = read_json(&out.join("summary.json"));
    summary::assert_layout(&s);
    let r = &s["steps"][0]["regions"][0];
    // Uniform stress: quadratic elements represent the linear displacement exactly, so the
    // interior values carry only quadrature and round-off error (1e-6 relative is 100x
    // above what we measure and far below any discretization error a wrong method gives).
    let sxx = r["sigma_xx_max_abs"]["value"].as_f64().unwrap();
    assert!((sxx / 100e6 - 1.0).abs() < 1e-6, "sigma_xx {sxx}");
    // Plane strain: sigma_zz = nu sigma_xx = 30 MPa; von Mises of (100, 0, 30) MPa is
    // sqrt(7900) MPa.
    let sint = r["sigma_int_max"]["value"].as_f64().unwrap();
    assert!(
        (sint / (7900f64.sqrt() * 1e6) - 1.0).abs() < 1e-6,
        "sigma_int {sint}"
    );
    // Strain: eps_xx = (1 - nu^2) sigma / E in plane strain.
    let exx = r["eps_xx_max_abs"]["value"].as_f64().unwrap();
    assert!(
        (exx / (0.91 * 100e6 / 200e9) - 1.0).abs() < 1e-6,
        "eps_xx {exx}"
    );
    for f in [
        "summary.json",
        "fields_step1.vtu",
        "sigma_xx_step1.png",
        "sigma_int_step1.png",
    ] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    let vtu = vtk::read(&out.join("fields_step1.vtu"));
    assert!(vtu.header.contains("type=\"UnstructuredGrid\""));
    assert!(vtu.get("sigma_int_Pa").f64s().iter().all(|x| x.is_finite()));
    // Connectivity indexes the points; offsets step by 3 (triangles, VTK type 5).
    let npts = vtu.get("").tuples() as i64;
    assert!(vtu
        .get("connectivity")
        .i64s()
        .iter()
        .all(|&k| (0..npts).contains(&k)));
    let offsets = vtu.get("offsets").i64s();
    assert!(offsets
        .iter()
        .enumerate()
        .all(|(k, &o)| o == 3 * (k as i64 + 1)));
    assert!(vtu.get("types").bytes.iter().all(|&t| t == 5));
}

#[test]
fn tabulated_and_linear_profiles_agree() {
    // In-plane bending by a linear traction on the right face; the table with two rows is
    // the same function, so the results agree to round-off.
    let lin = PLATE.replace("RIGHT", "tx = { linear = [\"50 MPa\", \"-50 MPa\"] }");
    let tab = PLATE.replace(
        "RIGHT",
        "tx = { table = [[0, \"50 MPa\"], [0.5, 0], [1, \"-50 MPa\"]] }",
    );
    let (o1, out1, _d1) = run_case(&lin, &[]);
    let (o2, out2, _d2) = run_case(&tab, &[]);
    assert_eq!(o1.status.code(), Some(0), "{}", stderr(&o1));
    assert_eq!(o2.status.code(), Some(0), "{}", stderr(&o2));
    let a = read_json(&out1.join("summary.json"))["steps"][0]["regions"][0]["sigma_xx_max_abs"]
        ["value"]
        .as_f64()
        .unwrap();
    let b = read_json(&out2.join("summary.json"))["steps"][0]["regions"][0]["sigma_xx_max_abs"]
        ["value"]
        .as_f64()
        .unwrap();
    assert!((a / b - 1.0).abs() < 1e-12, "{a} vs {b}");
    assert!(a > 40e6 && a < 60e6, "{a}");
}

/// Runs the bad case and returns stderr, checking exit code 2 and that nothing was written.
fn refused(text: &str) -> String {
    let (o, out, _d) = run_case(text, &[]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "stdout {} stderr {}",
        stdout(&o),
        stderr(&o)
    );
    assert!(!out.exists(), "an invalid case must write nothing");
    stderr(&o)
}

#[test]
fn bad_models_are_refused_naming_the_item() {
    let ok = PLATE.replace("RIGHT", "tx = \"1 MPa\"");
    // Open outline.
    let e = refused(&ok.replace(
        "{ name = \"left\", to = [0, 0], elements = 4 }",
        "{ name = \"left\", to = [0, \"1 mm\"], elements = 4 }",
    ));
    assert!(
        e.contains("regions[0].outline") && e.contains("open"),
        "{e}"
    );
    // A segment named twice.
    let e = refused(&ok.replace("name = \"top\"", "name = \"bottom\""));
    assert!(e.contains("named twice"), "{e}");
    // A zero-length segment.
    let e = refused(&ok.replace(
        "{ name = \"left\", to = [0, 0], elements = 4 }",
        "{ name = \"left\", to = [0, 0], elements = 4 },\n  { name = \"dot\", to = [0, 0] }",
    ));
    assert!(e.contains("dot") && e.contains("length"), "{e}");
    // Self-intersecting outline (a bow tie).
    let bow = ok
        .replace("to = [\"10 mm\", \"10 mm\"]", "to = [0, \"10 mm\"]")
        .replace(
            "to = [0, \"10 mm\"], elements = 4 },\n  { name = \"left\"",
            "to = [\"10 mm\", \"10 mm\"], elements = 4 },\n  { name = \"left\"",
        );
    let e = refused(&bow);
    assert!(e.contains("crosses or touches itself"), "{e}");
    // Unknown material.
    let e = refused(&ok.replace("material = \"steel\"", "material = \"unobtanium\""));
    assert!(
        e.contains("regions[0].material") && e.contains("unobtanium"),
        "{e}"
    );
    // A load on an unknown segment.
    let e = refused(&ok.replace("segment = \"right\"", "segment = \"rigth\""));
    assert!(e.contains("bc[2].segment") && e.contains("rigth"), "{e}");
    // Displacement and traction in one direction.
    let e = refused(&ok.replace("tx = \"1 MPa\"", "tx = \"1 MPa\"\nux = 0"));
    assert!(e.contains("bc[2]") && e.contains("not both"), "{e}");
    // A factor of an unknown load group.
    let e = refused(&format!(
        "{ok}\n[[steps]]\nname = \"s\"\nfactors = {{ wind = 1 }}\n"
    ));
    assert!(e.contains("steps[0].factors.wind"), "{e}");
    // A contact pair naming an unknown segment.
    let e = refused(&format!(
        "{ok}\n[[contact]]\nslave = \"top\"\nmaster = \"lid\"\nfriction = 0.2\n"
    ));
    assert!(e.contains("lid"), "{e}");
    // Two bodies that overlap (a second plate 0.5 mm into the first).
    let second = r#"
[[regions]]
name = "lid"
material = "steel"
start = ["9.5 mm", 0]
outline = [
  { name = "lid_bottom", to = ["20 mm", 0], elements = 4 },
  { name = "lid_right", to = ["20 mm", "10 mm"], elements = 4 },
  { name = "lid_top", to = ["9.5 mm", "10 mm"], elements = 4 },
  { name = "lid_left", to = ["9.5 mm", 0], elements = 4 },
]
"#;
    let e = refused(&ok.replace(
        "[[bc]]\nsegment = \"left\"",
        &format!("{second}\n[[bc]]\nsegment = \"left\""),
    ));
    assert!(
        e.contains("'plate'") && e.contains("'lid'") && e.contains("overlap"),
        "{e}"
    );
    // Unrestrained: no displacement condition at all.
    let free = ok
        .replace("[[bc]]\nsegment = \"left\"\nux = 0\n", "")
        .replace("[[bc]]\nsegment = \"bottom\"\nuy = 0\n", "");
    let e = refused(&free);
    assert!(
        e.contains("plate") && (e.contains("restrain") || e.contains("rigid")),
        "{e}"
    );
}

#[test]
fn the_clamp_knife_base_example_prints_and_validates() {
    let o = tribo(&["example", "clamp-knife-base"], None);
    assert_eq!(o.status.code(), Some(0));
    let text = stdout(&o);
    assert!(text.contains("48.4 MPa") && text.contains("16.475 kN/m"));
    assert!(text.contains("ASSUMPTION"));
    let v = tribo(&["run", "-", "--dry-run"], Some(&text));
    assert_eq!(v.status.code(), Some(0), "{}", stderr(&v));
    assert!(stdout(&v).contains("knife_top_contact"));
    // Template parameters are checked.
    let e = refused(&text.replace("clamp_left = \"45 mm\"", "clamp_left = \"90 mm\""));
    assert!(e.contains("clamp_knife_base.clamp_left"), "{e}");
    let e = refused(&text.replace("knife_material = \"steel\"", "knife_material = \"bronze\""));
    assert!(
        e.contains("clamp_knife_base.knife_material") && e.contains("bronze"),
        "{e}"
    );
}

/// The generic case printed in the 2D case reference (docs/user/case-bem2d.md), run as
/// written: a block pressed on a base held only by contact and friction. The contact force
/// equals the applied pressure times the block's width (equilibrium of the free block: the
/// pressure is its only other load).
#[test]
fn the_readme_bem_case_runs_and_balances() {
    let readme = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../docs/user/case-bem2d.md"
    ))
    .unwrap();
    let start = readme
        .find("## A complete case")
        .expect("the reference's section");
    let body = &readme[start..];
    let open = body.find("```toml\n").expect("toml block") + "```toml\n".len();
    let close = open + body[open..].find("```").expect("block end");
    let text = &body[open..close];
    let (o, out, _d) = run_case(text, &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let s = read_json(&out.join("summary.json"));
    let pair = &s["steps"][0]["pairs"][0];
    let fy = pair["slave_force_n_per_m"][1].as_f64().unwrap();
    // 50 MPa on 20 mm: 1e6 N/m on the block (upward on the slave). The free block's
    // equilibrium is an equation of the contact problem: round-off plus the BEM's boundary
    // integration of the traction (1e-6 relative).
    assert!((fy / 1e6 - 1.0).abs() < 1e-6, "contact force {fy}");
    let fx = pair["slave_force_n_per_m"][0].as_f64().unwrap();
    assert!(fx.abs() < 1e-6 * 1e6, "tangential resultant {fx}");
    for f in [
        "interfaces.csv",
        "interfaces.png",
        "fields_clamping.vtu",
        "psi_sigma_int.png",
        "damage_sweep.csv",
        "damage_sweep.png",
    ] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
}

/// `tribo example clamp-knife-base | tribo run -`: equilibrium of the two bodies held by
/// contact, the paper's statements on Fig. 7b, the damage sweep and the comparison.
#[test]
fn the_clamp_knife_base_example_balances_and_shows_the_papers_effects() {
    let text = stdout(&tribo(&["example", "clamp-knife-base"], None));
    let (o, out, _d) = run_case(&text, &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let s = read_json(&out.join("summary.json"));
    summary::assert_layout(&s);
    let steps = s["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 2);
    let (bolt, cutting) = (48.4e6 * 12e-3, 16.475e3);
    let force = |k: usize, pair: usize, d: usize| {
        steps[k]["pairs"][pair]["slave_force_n_per_m"][d]
            .as_f64()
            .unwrap()
    };
    for k in 0..2 {
        // The clamp is held only by the knife: the knife-clamp contact force equals the bolt
        // force p_n w (a free-body equation of the contact problem: round-off, 1e-9).
        assert!(
            (-force(k, 1, 1) / bolt - 1.0).abs() < 1e-9,
            "step {k}: {}",
            force(k, 1, 1)
        );
        assert!(
            force(k, 1, 0).abs() < 1e-9 * bolt,
            "clamp friction resultant {}",
            force(k, 1, 0)
        );
        // The knife is free in y: base + clamp + cutting load balance (round-off).
        let cut = if k == 1 { cutting } else { 0.0 };
        let balance = force(k, 0, 1) + force(k, 1, 1) + cut;
        assert!(
            balance.abs() < 1e-9 * bolt,
            "step {k}: knife y balance {balance}"
        );
        // Both free bodies are reported.
        let names: Vec<&str> = steps[k]["free_bodies"]
            .as_array()
            .unwrap()
            .iter()
            .map(|b| b["body"].as_str().unwrap())
            .collect();
        assert_eq!(names, ["knife", "clamp"]);
        // The tractions on all segments balance (no body forces): each body's boundary is
        // in equilibrium, the free clamp's by its free-body equation (round-off), the base
        // to the discretization (measured 1.1e-5 of the bolt force), and the supports carry
        // the bolt and cutting loads: base_bottom's reaction is p_n w - p_b.
        let forces = steps[k]["segment_forces"].as_array().unwrap();
        let sum = |region: Option<&str>, d: usize| -> f64 {
            forces
                .iter()
                .filter(|f| region.is_none_or(|r| f["region"] == r))
                .map(|f| f["force_n_per_m"][d].as_f64().unwrap())
                .sum()
        };
        for d in 0..2 {
            assert!(
                sum(None, d).abs() < 1e-4 * bolt,
                "step {k}: net force {}",
                sum(None, d)
            );
            assert!(sum(Some("clamp"), d).abs() < 1e-9 * bolt, "step {k}: clamp");
        }
        let base = forces
            .iter()
            .find(|f| f["segment"] == "base_bottom")
            .unwrap();
        assert_eq!(base["support"], true);
        let fy = base["force_n_per_m"][1].as_f64().unwrap();
        assert!(
            (fy - (bolt - cut)).abs() < 1e-4 * bolt,
            "step {k}: base reaction {fy}"
        );
    }
    // Fig. 7b: the cutting load reduces the actual contact at both interfaces ...
    for pair in 0..2 {
        let l0 = steps[0]["pairs"][pair]["contact_length_m"]
            .as_f64()
            .unwrap();
        let l1 = steps[1]["pairs"][pair]["contact_length_m"]
            .as_f64()
            .unwrap();
        assert!(l1 < 0.95 * l0, "pair {pair}: contact {l0} -> {l1}");
    }
    // ... and raises the clamp-knife pressure sharply at the clamp's left edge (x = 45 mm),
    // the knife's rotation point.
    let p0 = &steps[0]["pairs"][1]["max_pressure"];
    let p1 = &steps[1]["pairs"][1]["max_pressure"];
    let x1 = p1["at_m"][0].as_f64().unwrap();
    assert!((x1 - 45e-3).abs() < 0.5e-3, "peak at x = {x1}");
    assert!(p1["value"].as_f64().unwrap() > 5.0 * p0["value"].as_f64().unwrap());
    // Damage sweep: psi = sigma_int / limit on one field, so psi_max scales as 1/limit
    // exactly (8.7 / 2.9 = 3, round-off), and V, Psi fall monotonically.
    let d = &s["damage"];
    assert_eq!(d["region"], "knife");
    let f = d["sweep_factors"].as_array().unwrap();
    assert!((f[2].as_f64().unwrap() - 3.0).abs() < 1e-9, "{f:?}");
    let sweep = d["sweep"].as_array().unwrap();
    assert_eq!(sweep.len(), 7);
    for w in sweep.windows(2) {
        assert!(w[1]["dangerous_area_m2"].as_f64() <= w[0]["dangerous_area_m2"].as_f64());
        assert!(w[1]["damageability_m2"].as_f64() < w[0]["damageability_m2"].as_f64());
    }
    assert_eq!(d["paper_sweep_factors"][0].as_f64(), Some(27.0));
    // Comparison: the cast-iron knife, 20 % softer, strains more (eps_int up by about the
    // modulus ratio where the load path is force-controlled); the paper's changes are listed.
    let c = &s["compare"];
    let rows = c["rows"].as_array().unwrap();
    assert_eq!(rows[0]["material"], "steel");
    assert_eq!(rows[1]["material"], "cast_iron");
    let metrics: Vec<&str> = c["metrics"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m.as_str().unwrap())
        .collect();
    let eps = metrics.iter().position(|m| *m == "eps_int_max").unwrap();
    let change = rows[1]["change_percent"][eps].as_f64().unwrap();
    assert!(change > 10.0 && change < 30.0, "eps_int change {change} %");
    assert!(c["paper_change_percent"].is_array());
    for f in [
        "interfaces.csv",
        "interfaces.png",
        "fields_clamping.vtu",
        "fields_clamping_cutting.vtu",
        "sigma_xx_clamping_cutting.png",
        "sigma_int_clamping_cutting.png",
        "psi_sigma_int.png",
        "damage_sweep.csv",
        "damage_sweep.png",
        "compare.csv",
        "compare.png",
    ] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    let vtu = vtk::read(&out.join("fields_clamping_cutting.vtu"));
    assert!(vtu.get("psi").f64s().iter().all(|x| x.is_finite()));
}

/// A steel block resting under its own weight on a fixed base, held only by contact and
/// friction: the contact force equals the weight rho g A per unit thickness (the free
/// block's equilibrium, round-off), and spinning the block about its centre adds no net
/// force (the centrifugal load of a rotation about the centroid has zero resultant).
#[test]
fn a_block_under_its_own_weight_rests_on_the_base_with_its_weight() {
    let case = |body_force: &str| {
        format!(
            r#"
kind = "bem2d"
[materials.steel]
E = "206 GPa"
nu = 0.3
[[regions]]
name = "base"
material = "steel"
start = [0, "-10 mm"]
outline = [
  {{ name = "base_bottom", to = ["30 mm", "-10 mm"], elements = 6 }},
  {{ name = "base_right", to = ["30 mm", 0], elements = 4 }},
  {{ name = "base_top", to = [0, 0], elements = 24 }},
  {{ name = "base_left", to = [0, "-10 mm"], elements = 4 }},
]
[[regions]]
name = "block"
material = "steel"
start = ["10 mm", 0]
outline = [
  {{ name = "block_bottom", to = ["20 mm", 0], elements = 16 }},
  {{ name = "block_right", to = ["20 mm", "10 mm"], elements = 4 }},
  {{ name = "block_top", to = ["10 mm", "10 mm"], elements = 4 }},
  {{ name = "block_left", to = ["10 mm", 0], elements = 4 }},
]
body_force = {body_force}
[[bc]]
segment = "base_bottom"
ux = 0
uy = 0
[[contact]]
slave = "block_bottom"
master = "base_top"
friction = 0.3
"#
        )
    };
    let weight = 7850.0 * 9.81 * 1e-4;
    for (bf, expected) in [
        ("{ density = 7850, gravity = [0, -9.81] }", weight),
        (
            "{ density = 7850, gravity = [0, -9.81], angular_velocity = 50, center = [\"15 mm\", \"5 mm\"] }",
            weight,
        ),
    ] {
        let (o, out, _d) = run_case(&case(bf), &[]);
        assert_eq!(o.status.code(), Some(0), "{bf}: {}", stderr(&o));
        let s = read_json(&out.join("summary.json"));
        let f = &s["steps"][0]["pairs"][0]["slave_force_n_per_m"];
        let fy = f[1].as_f64().unwrap();
        // Round-off of the free-body equation (1e-9 relative); a missing or doubled body
        // force would be off by 100 %.
        assert!((fy / expected - 1.0).abs() < 1e-9, "{bf}: contact force {fy} vs {expected}");
        assert!(f[0].as_f64().unwrap().abs() < 1e-9 * expected, "{bf}: {f}");
    }
    let e = refused(&case("{ gravity = [0, -9.81] }"));
    assert!(e.contains("regions[1].body_force.density"), "{e}");
    let e = refused(&case("{ density = 7850, angular_velocity = 50 }"));
    assert!(
        e.contains("regions[1].body_force") && e.contains("center"),
        "{e}"
    );
    let e = refused(&case("{ density = -1, gravity = [0, -9.81] }"));
    assert!(e.contains("block") && e.contains("density"), "{e}");
}

// ------------------------------------------------------------------------- gmsh meshes

/// The library's gmsh fixtures (made by gmsh 4.15.2, `crates/tribo/tests/fixtures/gmsh`).
fn gmsh_fixture(name: &str) -> String {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../tribo/tests/fixtures/gmsh")
        .join(name);
    // TOML basic strings take forward slashes on every platform.
    p.to_str().unwrap().replace('\\', "/")
}

/// Lame's ring from a second-order gmsh mesh (quarter ring a = 10 mm, b = 20 mm, internal
/// pressure 100 MPa, plane strain, symmetry rollers on the physical curves "y0" and "x0").
const GMSH_RING: &str = r#"
kind = "bem2d"
title = "Lame ring from gmsh"
plane = "strain"
[materials.steel]
E = "210 GPa"
nu = 0.3
[[mesh]]
file = "FILE"
materials = { ring = "steel" }
[[bc]]
segment = "y0"
uy = 0
[[bc]]
segment = "x0"
ux = 0
[[bc]]
segment = "inner"
pressure = "100 MPa"
[field]
size = "1 mm"
"#;

#[test]
fn a_gmsh_ring_gives_lames_stresses() {
    let text = GMSH_RING.replace("FILE", &gmsh_fixture("lame_o2_n8.msh"));
    let (o, out, _d) = run_case(&text, &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let s = read_json(&out.join("summary.json"));
    let m = &s["meshes"][0];
    assert_eq!(m["version"], "4.1");
    assert_eq!(m["order"], 2);
    assert_eq!(m["surfaces"]["ring"][0], "ring");
    assert_eq!(m["curves"]["inner"][0], "inner");
    // Lame (Timoshenko & Goodier sec. 28), at r = a: sigma_r = -p,
    // sigma_theta = p (b^2 + a^2)/(b^2 - a^2) = 166.67 MPa, sigma_z = nu (sigma_r +
    // sigma_theta) = 20 MPa (plane strain); the von Mises intensity there is 231.33 MPa and
    // the largest in the ring. The field samples the bore's nodes; the native ring at this
    // mesh recovers the boundary hoop stress to about 1e-3 (solver tests), so 0.5 %.
    let (p, a2, b2, nu): (f64, f64, f64, f64) = (100e6, 1e-4, 4e-4, 0.3);
    let hoop = p * (b2 + a2) / (b2 - a2);
    let sz = nu * (hoop - p);
    let (s1, s2, s3) = (hoop, sz, -p);
    let exact = (((s1 - s2).powi(2) + (s2 - s3).powi(2) + (s3 - s1).powi(2)) / 2.0).sqrt();
    let got = s["steps"][0]["regions"][0]["sigma_int_max"]["value"]
        .as_f64()
        .unwrap();
    assert!(
        (got - exact).abs() < 5e-3 * exact,
        "sigma_int max {got:e} against {exact:e}"
    );
    let at = &s["steps"][0]["regions"][0]["sigma_int_max"]["at_m"];
    let r = at[0].as_f64().unwrap().hypot(at[1].as_f64().unwrap());
    assert!((r - 0.010).abs() < 1e-6, "the largest intensity at r = {r}");
    // The rollers' reactions: the hoop force across a section of the ring, the integral
    // of sigma_t over [a, b] = p a (half the ring's equilibrium), carried by y0 as -y and by
    // x0 as -x (measured 9e-6 at this mesh).
    let forces = s["steps"][0]["segment_forces"].as_array().unwrap();
    let force = |name: &str, d: usize| {
        forces.iter().find(|f| f["segment"] == name).unwrap()["force_n_per_m"][d]
            .as_f64()
            .unwrap()
    };
    let pa = p * 0.010;
    assert!(
        (force("y0", 1) / pa + 1.0).abs() < 1e-4,
        "{}",
        force("y0", 1)
    );
    assert!(
        (force("x0", 0) / pa + 1.0).abs() < 1e-4,
        "{}",
        force("x0", 0)
    );
}

/// Two bonded rings from one gmsh file: a boundary condition on a physical curve that the
/// import cut into parts ("y0" spans both rings) applies to every part; the dry run lists
/// the parts.
#[test]
fn a_gmsh_curve_cut_into_parts_takes_its_conditions_on_every_part() {
    let text = GMSH_RING
        .replace("FILE", &gmsh_fixture("compound_o2_n4.msh"))
        .replace(
            "materials = { ring = \"steel\" }",
            "materials = { core = \"steel\", sleeve = \"aluminium\" }",
        )
        .replace("segment = \"inner\"", "segment = \"bore\"")
        .replace(
            "[[mesh]]",
            "[materials.aluminium]\nE = \"70 GPa\"\nnu = 0.33\n[[mesh]]",
        );
    let (o, _out, _d) = run_case(&text, &["--dry-run"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let listing = stdout(&o);
    assert!(listing.contains("boundary y0: y0.1, y0.2"), "{listing}");
    assert!(listing.contains("core|sleeve"), "{listing}");
    let (o, out, _d) = run_case(&text, &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let s = read_json(&out.join("summary.json"));
    let regions = &s["steps"][0]["regions"];
    assert_eq!(regions[0]["region"], "core");
    assert_eq!(regions[1]["region"], "sleeve");
    // Both rings are loaded (rollers on all four symmetry parts hold them): a ring left
    // without its rollers would be unrestrained and the run would fail.
    for r in 0..2 {
        let v = regions[r]["sigma_int_max"]["value"].as_f64().unwrap();
        assert!(v > 10e6, "region {r}: {v:e}");
    }
}

#[test]
fn bad_gmsh_input_is_refused_naming_the_item() {
    let ring = GMSH_RING.replace("FILE", &gmsh_fixture("lame_o2_n4.msh"));
    // A missing file.
    let e = refused(&GMSH_RING.replace("FILE", "no-such-mesh.msh"));
    assert!(
        e.contains("mesh[0].file") && e.contains("no-such-mesh.msh"),
        "{e}"
    );
    // A 3D mesh.
    let e = refused(&GMSH_RING.replace("FILE", &gmsh_fixture("box_3d.msh")));
    assert!(e.contains("mesh[0].file") && e.contains("not 2D"), "{e}");
    // No physical groups.
    let e = refused(&GMSH_RING.replace("FILE", &gmsh_fixture("square_without_groups.msh")));
    assert!(e.contains("no physical surfaces"), "{e}");
    // A surface without a material, and a material for a surface the file lacks.
    let e = refused(&ring.replace("ring = \"steel\"", "rim = \"steel\""));
    assert!(
        e.contains("physical surface 'ring'") && e.contains("material"),
        "{e}"
    );
    let e = refused(&ring.replace("ring = \"steel\"", "ring = \"steel\", rim = \"steel\""));
    assert!(
        e.contains("mesh[0].materials.rim") && e.contains("ring"),
        "{e}"
    );
    // A material name that is not defined.
    let e = refused(&ring.replace("ring = \"steel\"", "ring = \"brass\""));
    assert!(e.contains("mesh[0].materials.ring"), "{e}");
    // A load on an unknown segment; a region name that the mesh does not have.
    let e = refused(&ring.replace("segment = \"inner\"", "segment = \"bore\""));
    assert!(e.contains("bc[2].segment") && e.contains("bore"), "{e}");
    let e = refused(&format!(
        "{ring}\n[damage]\nregion = \"knife\"\nlimit = \"100 MPa\"\n"
    ));
    assert!(e.contains("damage.region") && e.contains("ring"), "{e}");
    // A corner angle out of range.
    let e = refused(&ring.replace(
        "materials = { ring = \"steel\" }",
        "materials = { ring = \"steel\" }\ncorner_angle_deg = 200",
    ));
    assert!(e.contains("mesh[0].corner_angle_deg"), "{e}");
    // A contact pair on a curve that the import cut into parts.
    let compound = ring
        .replace("lame_o2_n4.msh", "compound_o2_n4.msh")
        .replace("ring = \"steel\"", "core = \"steel\", sleeve = \"steel\"")
        .replace("segment = \"inner\"", "segment = \"bore\"");
    let e = refused(&format!(
        "{compound}\n[[contact]]\nslave = \"y0\"\nmaster = \"rim\"\nfriction = 0.1\n"
    ));
    assert!(
        e.contains("contact[0].slave") && e.contains("y0.1, y0.2"),
        "{e}"
    );
}

/// A gmsh plate of quadrangles (20 x 10 mm, a body force per physical surface) resting under
/// its own weight on an outline base, held only by contact and friction: the contact force
/// between the gmsh segment and the outline segment equals the weight rho g A per unit
/// thickness (the free plate's equilibrium, round-off).
#[test]
fn a_gmsh_plate_rests_on_an_outline_base_with_its_weight() {
    let text = format!(
        r#"
kind = "bem2d"
title = "gmsh plate on an outline base"
[materials.steel]
E = "210 GPa"
nu = 0.3
[[regions]]
name = "base"
material = "steel"
start = ["-5 mm", "-10 mm"]
outline = [
  {{ name = "base_bottom", to = ["25 mm", "-10 mm"], elements = 6 }},
  {{ name = "base_right", to = ["25 mm", 0], elements = 4 }},
  {{ name = "base_top", to = ["-5 mm", 0], elements = 6 }},
  {{ name = "base_left", to = ["-5 mm", "-10 mm"], elements = 4 }},
]
[[mesh]]
file = "{}"
materials = {{ plate = "steel" }}
body_forces = {{ plate = {{ density = 7850, gravity = [0, -9.81] }} }}
[[bc]]
segment = "base_bottom"
ux = 0
uy = 0
[[contact]]
slave = "bottom"
master = "base_top"
friction = 0.3
[field]
size = "1 mm"
"#,
        gmsh_fixture("plate_quad9.msh")
    );
    let (o, out, _d) = run_case(&text, &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let s = read_json(&out.join("summary.json"));
    let weight = 7850.0 * 9.81 * 2e-4;
    let f = &s["steps"][0]["pairs"][0]["slave_force_n_per_m"];
    let fy = f[1].as_f64().unwrap();
    // Round-off of the free-body equation (1e-9 relative); a body force lost on the way from
    // the case to the imported region would leave no contact at all.
    assert!(
        (fy / weight - 1.0).abs() < 1e-9,
        "contact force {fy} N/m against the weight {weight} N/m"
    );
    assert!(f[0].as_f64().unwrap().abs() < 1e-9 * weight, "{f}");
    // A body force on a surface the mesh's materials do not name is refused.
    let bad = text.replace("body_forces = { plate", "body_forces = { slab");
    let e = refused(&bad);
    assert!(e.contains("mesh[0].body_forces.slab"), "{e}");
}

/// The gmsh example `examples/gmsh/hertz-cylinder.toml`: a half cylinder meshed in gmsh
/// (second order, graded to 5 um at the contact) pressed on a block, frictionless, against
/// 2D Hertz (Johnson 1985 eq. 5.39-5.40): p0 = 2 P / (pi b), b = sqrt(4 P R / (pi E*)).
#[test]
fn the_gmsh_hertz_example_matches_hertz() {
    let case = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/gmsh/hertz-cylinder.toml");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = tribo(
        &[
            "run",
            case.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--quiet",
        ],
        None,
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let s = read_json(&out.join("summary.json"));
    let (e, nu, p, r): (f64, f64, f64, f64) = (210e9, 0.3, 1e5, 0.010);
    let e_star = e / (2.0 * (1.0 - nu * nu));
    let b = (4.0 * p * r / (std::f64::consts::PI * e_star)).sqrt();
    let p0 = 2.0 * p / (std::f64::consts::PI * b);
    let pair = &s["steps"][0]["pairs"][0];
    let f = |v: &serde_json::Value| v.as_f64().unwrap();
    // Measured -0.024 %; the native cylinder-on-block test reaches 0.02 % too.
    let pmax = f(&pair["max_pressure"]["value"]);
    assert!(
        (pmax / p0 - 1.0).abs() < 5e-3,
        "p_max {pmax:e} against p0 {p0:e}"
    );
    // The outermost slave nodes in contact lie within one element (about 5.5 um at the
    // contact) inside the Hertz edge: measured 103.3 um against b = 105.0 um.
    for x in pair["contact_x_range_m"].as_array().unwrap() {
        let d = b - f(x).abs();
        assert!(
            (0.0..6e-6).contains(&d),
            "contact edge {} against b = {b:e}",
            f(x)
        );
    }
    // The contact force balances the load on the guided face to the discretization's
    // accuracy (measured 1.4e-4; the face and the contact are integrated separately).
    let fy = f(&pair["slave_force_n_per_m"][1]);
    assert!((fy / p - 1.0).abs() < 1e-3, "contact force {fy}");
    assert_eq!(f(&pair["max_abs_shear"]["value"]), 0.0, "frictionless");
    // Nothing sticks on a frictionless pair: every node in contact is free to slip.
    assert_eq!(pair["friction"], 0.0);
    assert_eq!(pair["stick_nodes"], 0);
    assert_eq!(pair["slip_nodes"], pair["nodes_in_contact"]);
    assert_eq!(s["meshes"][0]["order"], 2);
}

/// `text` (a format 4.1 .msh) with every node moved by `shift` (m).
fn shift_msh41(text: &str, shift: [f64; 2]) -> String {
    let mut out = Vec::new();
    let mut lines = text.lines();
    while let Some(line) = lines.next() {
        out.push(line.to_string());
        if line.trim() != "$Nodes" {
            continue;
        }
        let head = lines.next().unwrap();
        out.push(head.to_string());
        let blocks: usize = head.split_whitespace().next().unwrap().parse().unwrap();
        for _ in 0..blocks {
            let b = lines.next().unwrap();
            out.push(b.to_string());
            let n: usize = b.split_whitespace().nth(3).unwrap().parse().unwrap();
            for _ in 0..n {
                out.push(lines.next().unwrap().to_string());
            }
            for _ in 0..n {
                let v: Vec<f64> = lines
                    .next()
                    .unwrap()
                    .split_whitespace()
                    .map(|x| x.parse().unwrap())
                    .collect();
                out.push(format!(
                    "{:e} {:e} {:e}",
                    v[0] + shift[0],
                    v[1] + shift[1],
                    v[2]
                ));
            }
        }
    }
    out.join("\n") + "\n"
}

/// The shipped gmsh Hertz example translated by (0.2, 0.1) m (its contact elements 5 um,
/// 2.5e-5 of their distance from the origin) failed its LU solve ("relative residual
/// 0.000e0" from NaN kernels); now its contact result matches the example in place: the
/// contact force and the contact's extent to 1e-9 (measured 3e-16), the peak pressure to
/// 1e-8. The translated file itself differs from the original by the rounding of each
/// node's coordinates (ulp(0.2) = 2.8e-17 m, independently per node), and a gap change dg
/// at a node changes its pressure by about E* dg / h: E* ulp / (h p0) = 1.15e11 * 2.8e-17 /
/// (5e-6 * 6.1e8) = 1.1e-9 of p0, as measured (1.1e-9); no method can do better on this
/// input.
#[test]
fn the_gmsh_hertz_example_moved_away_from_the_origin_gives_the_same_contact() {
    let ex = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/gmsh");
    let toml = std::fs::read_to_string(ex.join("hertz-cylinder.toml")).unwrap();
    let msh = std::fs::read_to_string(ex.join("hertz-cylinder.msh")).unwrap();
    let shift = [0.2, 0.1];
    let mut results = Vec::new();
    for s in [[0.0, 0.0], shift] {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("hertz-cylinder.msh"), shift_msh41(&msh, s)).unwrap();
        let case = dir.path().join("case.toml");
        std::fs::write(&case, &toml).unwrap();
        let out = dir.path().join("out");
        let o = tribo(
            &[
                "run",
                case.to_str().unwrap(),
                "-o",
                out.to_str().unwrap(),
                "--quiet",
            ],
            None,
        );
        assert_eq!(o.status.code(), Some(0), "shift {s:?}: {}", stderr(&o));
        results.push(read_json(&out.join("summary.json")));
    }
    let f = |v: &serde_json::Value| v.as_f64().unwrap();
    let (a, b) = (
        &results[0]["steps"][0]["pairs"][0],
        &results[1]["steps"][0]["pairs"][0],
    );
    let rel = |x: f64, y: f64, scale: f64| (x - y).abs() / scale;
    let p0 = f(&a["max_pressure"]["value"]);
    let ep = rel(p0, f(&b["max_pressure"]["value"]), p0);
    assert!(ep < 1e-8, "peak pressure {ep:.2e}");
    assert_eq!(a["nodes_in_contact"], b["nodes_in_contact"]);
    let (ra, rb) = (
        a["contact_x_range_m"].as_array().unwrap(),
        b["contact_x_range_m"].as_array().unwrap(),
    );
    let width = f(&ra[1]) - f(&ra[0]);
    for (x, y) in ra.iter().zip(rb) {
        assert!(rel(f(x) + shift[0], f(y), width) < 1e-9, "{x} vs {y}");
    }
    let fy = f(&a["slave_force_n_per_m"][1]);
    assert!(rel(fy, f(&b["slave_force_n_per_m"][1]), fy.abs()) < 1e-9);
}

/// Invalid geometry and corrupt meshes (issue 11 item 10): exit 2, naming the region or
/// line and the rule, writing nothing; and the documented grading range works.
#[test]
fn invalid_geometry_and_corrupt_meshes_exit_2_and_extreme_grading_solves() {
    let ok = PLATE.replace("RIGHT", "tx = \"1 MPa\"");
    // A bow tie crossing itself at a node (4 elements per side put a node on the crossing
    // point): old, exit 2 with "signed area" (misleading) or a silent solve.
    let bow = ok
        .replace("to = [\"10 mm\", \"10 mm\"]", "to = [0, \"10 mm\"]")
        .replace(
            "to = [0, \"10 mm\"], elements = 4 },\n  { name = \"left\"",
            "to = [\"10 mm\", \"10 mm\"], elements = 4 },\n  { name = \"left\"",
        );
    let e = refused(&bow);
    assert!(
        e.contains("region 'plate'") && e.contains("crosses or touches itself"),
        "{e}"
    );
    // A hole outside its region (old: exit 0, the hole ignored by nothing).
    let outside = ok.replace(
        "  { name = \"left\", to = [0, 0], elements = 4 },\n]\n",
        "  { name = \"left\", to = [0, 0], elements = 4 },\n]\nholes = [{ start = [\"20 mm\", \"2 mm\"], outline = [\n  { name = \"h1\", to = [\"20 mm\", \"8 mm\"], elements = 2 },\n  { name = \"h2\", to = [\"26 mm\", \"5 mm\"], elements = 2 },\n  { name = \"h3\", to = [\"20 mm\", \"2 mm\"], elements = 2 },\n] }]\n",
    );
    assert_ne!(outside, ok);
    let e = refused(&outside);
    assert!(
        e.contains("region 'plate' loop 1") && e.contains("outside the outer loop"),
        "{e}"
    );
    // Grading 1e6 on every side (inside the documented range; old: LU solve failed).
    let graded = ok.replace(
        "elements = 4 }",
        "elements = 10, grading = { both = 1e6 } }",
    );
    let (o, _, _d) = run_case(&graded, &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    // A corrupt gmsh mesh: a second $Nodes section.
    let dir = tempfile::tempdir().unwrap();
    let ring = std::fs::read_to_string(gmsh_fixture("lame_o2_n4.msh")).unwrap();
    let nodes = ring
        .split("$Nodes")
        .nth(1)
        .unwrap()
        .split("$EndNodes")
        .next()
        .unwrap();
    let bad = ring.replacen(
        "$EndNodes\n",
        &format!("$EndNodes\n$Nodes{nodes}$EndNodes\n"),
        1,
    );
    let file = dir.path().join("bad.msh");
    std::fs::write(&file, bad).unwrap();
    let e = refused(&GMSH_RING.replace("FILE", &file.to_str().unwrap().replace('\\', "/")));
    assert!(e.contains("msh line") && e.contains("second $Nodes"), "{e}");
}
