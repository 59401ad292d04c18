//! End-to-end tests of 2D boundary element cases (`kind = "bem2d"`) through the command
//! line: the files written, the summary's derived numbers (segment forces, contact lengths,
//! node counts), the dry run's listing, and bad input (exit 2 naming the item). The physics
//! values on typed results: crates/tribo-case/tests/bem.rs.
// Tests may unwrap: a panic here is a failed test (workspace lints deny it in library code).
#![allow(clippy::unwrap_used, clippy::expect_used)]
#![allow(clippy::needless_range_loop)] // step and pair indices read like the summary
mod common;
#[path = "common/summary.rs"]
mod summary;
#[path = "common/vtk.rs"]
mod vtk;
use common::{assert_files, example, read_json, run_case, stderr, stdout, tribo};
use std::path::Path;

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

/// A plate run writes the summary (in the shared layout), the field file (a well-formed
/// unstructured grid of triangles) and the maps. (Its numbers: the library test
/// `a_built_plate_equals_its_toml_twin_and_gives_the_applied_stress_everywhere`.)
#[test]
fn a_plate_run_writes_its_files() {
    let text = PLATE.replace("RIGHT", "tx = \"100 MPa\"");
    let (o, out, _d) = run_case(&text, &[], &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let s = read_json(&out.join("summary.json"));
    summary::assert_layout(&s);
    assert!(s["steps"][0]["regions"][0]["sigma_xx_max_abs"]["value"].is_number());
    assert_files(
        &out,
        &[
            "summary.json",
            "fields_step1.vtu",
            "sigma_xx_step1.png",
            "sigma_int_step1.png",
        ],
    );
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

/// Runs the bad case and returns stderr, checking exit code 2 and that nothing was written.
fn refused(text: &str) -> String {
    let (o, out, _d) = run_case(text, &[], &[]);
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

/// `tribo example clamp-knife-base | tribo run -`: the summary's derived numbers (the
/// segment forces balance, the cutting load shortens both contacts, the damage sweep's
/// factors, the comparison's rows) and the files. (The contact forces, the peak pressure,
/// the sweep and the comparison on typed results: the library test
/// `the_clamp_knife_base_example_balances_and_shows_the_papers_effects`.)
#[test]
fn the_clamp_knife_base_run_derives_its_summary_and_writes_its_files() {
    let (o, out, _d) = run_case(example("clamp-knife-base"), &[], &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let s = read_json(&out.join("summary.json"));
    summary::assert_layout(&s);
    // The numbers (equilibrium, Fig. 7b, the sweep, the comparison) are checked on the
    // typed summary in tribo-case's tests/bem.rs; here, that summary.json carries them.
    assert_eq!(s["steps"].as_array().unwrap().len(), 2);
    for key in ["segment_forces", "pairs"] {
        assert!(s["steps"][1][key].is_array(), "steps[1].{key}");
    }
    assert_eq!(s["damage"]["sweep"].as_array().unwrap().len(), 7);
    assert!(s["compare"]["rows"].is_array());
    assert_files(
        &out,
        &[
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
        ],
    );
    let vtu = vtk::read(&out.join("fields_clamping_cutting.vtu"));
    assert!(vtu.get("psi").f64s().iter().all(|x| x.is_finite()));
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

/// Lame's ring: the summary lists the mesh it read and the rollers' segment forces (their
/// values, the hoop force p a: the library test
/// `a_gmsh_rings_summary_gives_the_rollers_reactions`; the stresses:
/// `a_gmsh_ring_gives_lames_stresses`).
#[test]
fn a_gmsh_ring_reports_its_mesh_and_the_rollers_reactions() {
    let text = GMSH_RING.replace("FILE", &gmsh_fixture("lame_o2_n8.msh"));
    let (o, out, _d) = run_case(&text, &[], &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let s = read_json(&out.join("summary.json"));
    let m = &s["meshes"][0];
    assert_eq!(m["version"], "4.1");
    assert_eq!(m["order"], 2);
    assert_eq!(m["surfaces"]["ring"][0], "ring");
    assert_eq!(m["curves"]["inner"][0], "inner");
    // The reactions' values: tribo-case's tests/bem.rs
    // (`a_gmsh_rings_summary_gives_the_rollers_reactions`).
    let forces = s["steps"][0]["segment_forces"].as_array().unwrap();
    for name in ["x0", "y0"] {
        assert!(forces.iter().any(|f| f["segment"] == name), "{name}");
    }
}

/// Two bonded rings from one gmsh file: the dry run lists the parts of a physical curve
/// that the import cut ("y0" spans both rings). (That a condition takes every part: the
/// library test `a_gmsh_curve_cut_into_parts_takes_its_conditions_on_every_part`.)
#[test]
fn a_gmsh_curve_cut_into_parts_is_listed_by_the_dry_run() {
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
    let (o, _out, _d) = run_case(&text, &[], &["--dry-run"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let listing = stdout(&o);
    assert!(listing.contains("boundary y0: y0.1, y0.2"), "{listing}");
    assert!(listing.contains("core|sleeve"), "{listing}");
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

/// The gmsh example `examples/gmsh/hertz-cylinder.toml`, run from its path (its mesh
/// relative to it): the summary's node counts of a frictionless pair (nothing sticks, every
/// node in contact slips) and the mesh's order. (Against 2D Hertz: the library test
/// `the_gmsh_hertz_example_matches_hertz`.)
#[test]
fn the_gmsh_hertz_example_runs_from_its_path() {
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
    let pair = &s["steps"][0]["pairs"][0];
    // Nothing sticks on a frictionless pair: every node in contact is free to slip.
    assert_eq!(pair["friction"], 0.0);
    assert_eq!(pair["stick_nodes"], 0);
    assert_eq!(pair["slip_nodes"], pair["nodes_in_contact"]);
    assert_eq!(s["meshes"][0]["order"], 2);
}

/// Invalid geometry and corrupt meshes (issue 11 item 10): exit 2, naming the region or
/// line and the rule, writing nothing. (The extreme grading that solves: the library test
/// `extreme_grading_solves`.)
#[test]
fn invalid_geometry_and_corrupt_meshes_exit_2() {
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

/// Bad dynamic input (`[dynamics]`, docs/user/case-bem2d-dynamics.md): exit 2, nothing
/// written, the error naming the item: a time step that is not positive, a density missing,
/// a time table that is not increasing, a probe outside every body.
#[test]
fn bad_dynamic_input_is_refused_naming_the_item() {
    let ok = PLATE.replace(
        "RIGHT",
        "tx = \"1 MPa\"\ntime = { points = [[0, 0], [\"10 us\", 1]] }",
    ) + "[dynamics]\ntime_step = \"1 us\"\nsteps = 20\n[[probe]]\nname = \"c\"\nat = [\"5 mm\", \"5 mm\"]\n";
    let ok = ok.replace("nu = 0.3\n", "nu = 0.3\ndensity = \"7850 kg/m^3\"\n");
    // The base is valid (a dry run: nothing solved).
    let o = tribo(&["run", "-", "--dry-run", "--quiet"], Some(&ok));
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let e = refused(&ok.replace("time_step = \"1 us\"", "time_step = \"-1 us\""));
    assert!(e.contains("dynamics.time_step") && e.contains("> 0"), "{e}");
    let e = refused(&ok.replace("density = \"7850 kg/m^3\"\n", ""));
    assert!(
        e.contains("materials.steel.density") && e.contains("(missing)"),
        "{e}"
    );
    let e = refused(&ok.replace("[\"10 us\", 1]", "[\"10 us\", 1], [\"5 us\", 0]"));
    assert!(
        e.contains("bc[2].time.points[2][0]") && e.contains("increase"),
        "{e}"
    );
    let e = refused(&ok.replace("at = [\"5 mm\", \"5 mm\"]", "at = [\"15 mm\", \"5 mm\"]"));
    assert!(
        e.contains("probe[0].at") && e.contains("outside every region"),
        "{e}"
    );
}
