//! End-to-end tests of `tribo fatigue fit` and `tribo fatigue diagram`: the files written,
//! `--json`, the options, and bad input (exit code 2 naming the field). The fits against
//! pyLife and the diagram's numbers on typed results: crates/tribo-case/tests/fatigue.rs.
// Tests may unwrap: a panic here is a failed test (workspace lints deny it in library code).
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;
use common::tribo;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Output;

fn data_set() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/data/woehler-steel.csv")
}

fn json_of(o: &Output) -> Value {
    assert!(
        o.status.success(),
        "exit {:?}: {}",
        o.status.code(),
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).expect("JSON on stdout")
}

fn num(v: &Value, path: &[&str]) -> f64 {
    let mut x = v;
    for p in path {
        x = &x[*p];
    }
    x.as_f64()
        .unwrap_or_else(|| panic!("{path:?} is not a number: {x}"))
}

fn is_png(path: &Path) -> bool {
    std::fs::read(path).is_ok_and(|b| b.starts_with(b"\x89PNG"))
}

/// `tribo fatigue fit DATA -o DIR --json` prints the report, writes the same report to
/// woehler.json and the S-N plot.
#[test]
fn fatigue_fit_writes_its_report_and_plot() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fit");
    let o = tribo(
        &[
            "fatigue",
            "fit",
            data_set().to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--json",
        ],
        None,
    );
    let t = json_of(&o);
    assert_eq!(t["measure"], "amplitude");
    assert_eq!(t["kind"], "sigma");
    assert_eq!(t["unit"], "Pa");
    assert!(num(&t["max_likelihood"]["curve"], &["fatigue_limit"]) > 0.0);
    assert!(num(&t["regression"]["curve"], &["fatigue_limit"]) > 0.0);
    assert!(is_png(&out.join("woehler.png")));
    let written: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("woehler.json")).unwrap()).unwrap();
    assert_eq!(written, t);
}

#[test]
fn fatigue_fit_human_summary_and_measure() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fit");
    let data = data_set();
    let args = |extra: &[&'static str]| {
        let mut a = vec![
            "fatigue".to_string(),
            "fit".into(),
            data.to_str().unwrap().into(),
            "-o".into(),
            out.to_str().unwrap().into(),
        ];
        a.extend(extra.iter().map(|s| s.to_string()));
        a
    };
    let run = |extra: &[&'static str]| {
        let a = args(extra);
        let a: Vec<&str> = a.iter().map(String::as_str).collect();
        tribo(&a, None)
    };
    let o = run(&[]);
    assert!(o.status.success());
    let s = String::from_utf8_lossy(&o.stdout);
    assert!(
        s.contains("sigma_-1") && s.contains("maximum likelihood"),
        "{s}"
    );
    // The same numbers read as ranges: the fitted limit is a range, the same number.
    let t = json_of(&run(&["--measure", "range", "--json"]));
    assert_eq!(t["measure"], "range");
    assert_eq!(t["max_likelihood"]["curve"]["measure"], "range");
    // A rolling curve measured as a stress amplitude: bad input naming the field.
    let o = run(&["--kind", "p", "--measure", "amplitude"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("measure = amplitude"));
    // The p curve in contact pressure is fine.
    let t = json_of(&run(&["--kind", "p", "--json"]));
    assert_eq!(t["measure"], "contact_pressure");
    assert_eq!(t["limit_symbol"], "p_f");
}

fn fit_text(text: &str) -> (Output, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("d.csv");
    std::fs::write(&csv, text).unwrap();
    let out = dir.path().join("out");
    let o = tribo(
        &[
            "fatigue",
            "fit",
            csv.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ],
        None,
    );
    (o, dir)
}

#[test]
fn fatigue_fit_bad_input_exits_2_naming_the_field() {
    let cases = [
        (
            "load_MPa,cycles,runout\n400,1e5,false\n300,0,false\n250,1e6,false\n",
            "data[1].cycles = 0",
        ),
        (
            "load_MPa,cycles,runout\n400,1e5,false\n400,2e5,false\n300,3e5,false\n250,1e7,true\n",
            "data = 3 fractures at 2 distinct load levels",
        ),
        (
            "load_MPa,cycles,runout\n-400,1e5,false\n300,2e5,false\n250,1e6,false\n",
            "data[0].load",
        ),
        ("load_MPa,cycles,runout\n400,abc,false\n", "line 2"),
        ("load_MPa,cycles\n400,1e5\n", "no runout"),
        ("load_MPa,cycles,runout\n400,1e5,maybe\n", "flag"),
    ];
    for (text, want) in cases {
        let (o, dir) = fit_text(text);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{text}: {err}");
        assert!(err.contains(want), "{text}: expected {want:?} in {err}");
        assert!(
            !dir.path().join("out").exists(),
            "nothing written on bad input"
        );
    }
    let o = tribo(&["fatigue", "fit", "/nonexistent/x.csv"], None);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn fatigue_diagram_from_the_example() {
    let example = tribo(&["example", "fatigue-diagram"], None);
    assert!(example.status.success());
    let text = String::from_utf8_lossy(&example.stdout).into_owned();
    assert!(text.contains("[limits]"));
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("d");
    let t = json_of(&tribo(
        &[
            "fatigue",
            "diagram",
            "-",
            "-o",
            out.to_str().unwrap(),
            "--json",
        ],
        Some(&text),
    ));
    // The diagram and the state check (their numbers: the library test
    // `fatigue_diagram_from_the_example`).
    assert_eq!(t["diagram"]["points"].as_array().map(Vec::len), Some(4));
    assert!(t["state"]["load_factor"].is_number());
    assert!(is_png(&out.join("limit_diagram.png")));
    assert!(out.join("limit_diagram.json").exists());
}

#[test]
fn fatigue_diagram_with_a_limit_fitted_from_data() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(data_set(), dir.path().join("sigma.csv")).unwrap();
    let toml = r#"
[limits]
sigma_1 = { data = "sigma.csv" }
p_f = 1.3e9
sigma_1p = "403 MPa"
p_f_sigma = "1586 MPa"
sigma_p_contact_pressure = "800 MPa"
p_sigma_stress_amplitude = "80 MPa"
"#;
    let path = dir.path().join("limits.toml");
    std::fs::write(&path, toml).unwrap();
    let out = dir.path().join("o");
    let t = json_of(&tribo(
        &[
            "fatigue",
            "diagram",
            path.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--json",
        ],
        None,
    ));
    // The data file is found next to the limits file (its value: the library test
    // `fatigue_diagram_with_a_limit_fitted_from_data`).
    assert!(num(&t["diagram"]["limits"], &["sigma_1"]) > 0.0);
    assert_eq!(t["sources"][0]["method"], "max-likelihood");
    assert!(t["state"].is_null());
}

#[test]
fn fatigue_diagram_bad_input_exits_2_naming_the_field() {
    let good = "[limits]\nsigma_1 = 2e8\np_f = 1e9\nsigma_1p = 3e8\np_f_sigma = 1.2e9\n\
                sigma_p_contact_pressure = 5e8\np_sigma_stress_amplitude = 6e7\n";
    assert!(tribo(
        &["fatigue", "diagram", "-", "-o", "/dev/null/x"],
        Some(good)
    )
    .status
    .code()
    .is_some_and(|c| c != 2));
    let cases = [
        (good.replace("p_f = 1e9", "p_f = 0"), "limits.p_f = 0"),
        (good.replace("p_f_sigma = 1.2e9\n", ""), "limits.p_f_sigma"),
        (
            good.replace("sigma_1 = 2e8", "sigma_1 = \"2 m\""),
            "limits.sigma_1",
        ),
        (format!("{good}bogus = 1\n"), "limits.bogus"),
        (
            format!("{good}[state]\nstress_amplitude = -1\ncontact_pressure = 1e8\n"),
            "state.stress_amplitude",
        ),
        (
            good.replace("sigma_1 = 2e8", "sigma_1 = { data = \"missing.csv\" }"),
            "limits.sigma_1.data",
        ),
        ("[limits\n".to_string(), "<stdin>"),
    ];
    for (text, want) in cases {
        let o = tribo(
            &["fatigue", "diagram", "-", "-o", "/tmp/never-written"],
            Some(&text),
        );
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{text}: {err}");
        assert!(err.contains(want), "expected {want:?} in {err}");
    }
}
