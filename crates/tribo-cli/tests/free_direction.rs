//! `traction_direction = "free"` near gross slip (issue 11 item 10, valid input that fails):
//! the free-direction partial-slip solver covers 0 < |Q| < (1 - 1e-10) f F_N like the
//! load-parallel one (before: refused above 0.7 f F_N, and "the stick zone vanished", exit
//! 1, from about 0.77 f F_N before that cap).

mod common;
use common::tribo;
use std::path::PathBuf;
use std::process::Output;

/// Steel sphere R = 10 mm on a steel flat, 100 N.
const SPHERE: &str = r#"
[body1]
E = 2.1e11
nu = 0.3
radii = [0.01, 0.01]
[body2]
E = 2.1e11
nu = 0.3
radii = ["inf", "inf"]
[contact]
load = 100.0
friction = 0.3
traction_direction = "free"
"#;

/// Run `tribo run` on `text` in a fresh directory; the output, its directory and the guard.
fn run_case(text: &str) -> (Output, PathBuf, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("case.toml");
    std::fs::write(&case, text).unwrap();
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
    (o, out, dir)
}

/// The summary's tangential part after a run that must succeed, with the checks every
/// free-direction partial slip must pass: the force Q along its direction (1e-8 relative:
/// the solver's 1e-10 tolerance and the JSON's digits), the residual within the tolerance,
/// a stick zone smaller than Cattaneo-Mindlin's ellipse grown by two elements, and a
/// traction file without NaN whose |q| never exceeds f p_max (the traction file has no p;
/// the library tests check |q| <= f p element by element).
fn run_free(text: &str, q: f64, angle_deg: f64, n: usize) -> serde_json::Value {
    let (o, out, _d) = run_case(text);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(0), "Q = {q}: {err}");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let t = s["tangential"].clone();
    assert_eq!(t["traction_direction"], "free", "{t}");
    assert_eq!(t["mode"], "partial_slip", "{t}");
    let (sin, cos) = angle_deg.to_radians().sin_cos();
    let fx = t["tangential_force"][0].as_f64().unwrap();
    let fy = t["tangential_force"][1].as_f64().unwrap();
    assert!(
        (fx - q * cos).abs() <= 1e-8 * q && (fy - q * sin).abs() <= 1e-8 * q,
        "Q = {q}: force ({fx}, {fy})"
    );
    assert!(t["residual"].as_f64().unwrap() <= 1e-10, "{t}");
    let c = t["stick_semi_major"].as_f64().unwrap();
    let cm = t["stick_semi_major_cattaneo_mindlin"].as_f64().unwrap();
    let dx = 2.0 * s["grid"]["half_width"][0].as_f64().unwrap() / n as f64;
    assert!(
        c <= cm + 2.0 * dx,
        "Q = {q}: stick {c} vs Cattaneo-Mindlin {cm}"
    );
    let csv = std::fs::read_to_string(out.join("traction.csv")).unwrap();
    assert!(!csv.contains("NaN") && !csv.contains("inf"));
    let p_max = s["contact"]["max_pressure"].as_f64().unwrap();
    let f = t["friction"].as_f64().unwrap();
    let q_max = t["max_traction"].as_f64().unwrap();
    assert!(
        q_max <= f * p_max * (1.0 + 1e-12),
        "{q_max} > f p_max {p_max}"
    );
    t
}

/// Q = 0.99 f F_N on the sphere, along x and at 30 deg (exit 0; before: exit 2 above the
/// 0.7 cap): the stick zone is a few elements (Cattaneo-Mindlin c = 0.215 a), and
/// Q = (1 - 1e-9) f F_N, where every element slips and the traction is f p to 1e-4 f p0.
#[test]
fn free_direction_runs_near_gross_slip() {
    let n = 32;
    for (ratio, angle) in [(0.99, 0.0), (0.99, 30.0), (1.0 - 1e-9, 0.0)] {
        let q = ratio * 0.3 * 100.0;
        let text = format!(
            "{SPHERE}tangential_load = {q:?}\ntangential_angle_deg = {angle}\n[grid]\nn = {n}\n"
        );
        let t = run_free(&text, q, angle, n);
        let stick = t["stick_area"].as_f64().unwrap();
        let slip = t["slip_area"].as_f64().unwrap();
        assert!(slip > 0.0 && stick < 0.05 * (stick + slip), "{t}");
        if ratio > 0.999 {
            assert_eq!(stick, 0.0, "{t}");
        }
    }
    // At f F_N partial slip is refused as for the load-parallel solver: exit 2 naming the
    // field, nothing written.
    let (o, out, _d) = run_case(&format!(
        "{SPHERE}tangential_load = 30.0\n[grid]\nn = {n}\n"
    ));
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("contact.tangential_load"));
    assert!(!out.exists());
}

/// The coupled path (steel sphere on aluminium: the normal and tangential problems are
/// solved by alternation with the free-direction solver) at Q = 0.99 f F_N: exit 0, the
/// checks of `run_free`, and the coupling reported.
#[test]
fn free_direction_runs_near_gross_slip_for_dissimilar_materials() {
    let n = 24;
    let q = 0.99 * 0.3 * 100.0;
    let text = SPHERE.replacen(
        "E = 2.1e11\nnu = 0.3\nradii = [\"inf\"",
        "E = 7.0e10\nnu = 0.33\nradii = [\"inf\"",
        1,
    );
    assert!(text.contains("7.0e10"));
    let text = format!("{text}tangential_load = {q:?}\n[grid]\nn = {n}\n");
    let t = run_free(&text, q, 0.0, n);
    assert!(
        t["coupling"].as_str().unwrap().contains("alternation"),
        "{t}"
    );
}
