//! Fatigue fits and the limiting-state diagram on typed results ([`FitReport`],
//! [`DiagramReport`]): the fits against pyLife's numbers recorded in
//! `tests/fixtures/pylife_woehler.json` (provenance inside), the diagram's closed-form
//! quotients and its state check. These are the checks that used to run `tribo fatigue` and
//! read its JSON by string keys (crates/tribo-cli/tests/fatigue_cli.rs).
// Tests may unwrap: a panic here is a failed test (workspace lints deny it in library code).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use serde_json::Value;
use std::path::{Path, PathBuf};
use tribo::analysis::woehler::{LoadMeasure, TestKind};
use tribo_case::examples;
use tribo_case::fatigue::{diagram, fit, parse_csv, parse_limits, FitReport};

/// The example data set of `tribo fatigue fit` (crates/tribo-cli/examples/data).
fn data_set() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../tribo-cli/examples/data/woehler-steel.csv")
}

/// Both fits of the example data set as `kind` measured as `measure`, at the CLI's default
/// confidence 0.95.
fn fit_data(kind: TestKind, measure: LoadMeasure) -> FitReport {
    let path = data_set();
    let text = std::fs::read_to_string(&path).expect("the data set");
    let tests = parse_csv(&text, &path).expect("valid data");
    fit(kind, measure, tests, 0.95, "woehler-steel.csv").expect("both fits run")
}

fn num(v: &Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} is not a number: {v}"))
}

#[test]
fn fatigue_fit_agrees_with_pylife() {
    let t = fit_data(TestKind::MechanicalFatigue, LoadMeasure::Amplitude);
    let fixture: Value =
        serde_json::from_str(include_str!("fixtures/pylife_woehler.json")).expect("the fixture");
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();

    // Elementary vs the E739 regression with the transition limit: the same closed-form
    // least squares and the same midpoint rule, so only summation order differs (1e-12).
    let el = &fixture["elementary"];
    let curve = t
        .regression
        .as_ref()
        .and_then(|r| r.curve.as_ref())
        .expect("a regression curve");
    assert!(rel(curve.fatigue_limit(), num(el, "SD")) < 1e-12);
    assert!(rel(curve.slope(), num(el, "k_1")) < 1e-12);
    assert!(rel(curve.knee_cycles(), num(el, "ND")) < 1e-12);

    // MaxLikeFull vs tribo's maximum likelihood: the same likelihood, different Nelder-Mead
    // runs. pyLife stops scipy's fmin at xtol = ftol = 1e-4 (absolute, raw parameters);
    // a -log-likelihood within 1e-4 of the optimum leaves each parameter within about
    // sqrt(2e-4) = 0.014 standard errors of it. With SE(log10 SD) = 0.0098, SE(m) = 0.33,
    // SE(log10 ND) = 0.072 and SE(ln s) = 0.16, 0.32 (tribo's JSON), that is 3e-4 relative
    // in SD, 5e-3 in m... we allow 1e-3 relative for SD, m, TN, TS and 5e-3 for ND. (They
    // agree to ~1e-8 in fact.) tribo's own optimum must be at least as likely as pyLife's.
    let ml = &fixture["max_like_full"];
    let m = t.max_likelihood.as_ref().expect("a maximum-likelihood fit");
    assert!(rel(m.curve.fatigue_limit(), num(ml, "SD")) < 1e-3);
    assert!(rel(m.curve.slope(), num(ml, "k_1")) < 1e-3);
    assert!(rel(m.curve.knee_cycles(), num(ml, "ND")) < 5e-3);
    assert!(rel(m.scatter_cycles, num(ml, "TN")) < 1e-3);
    assert!(rel(m.scatter_load, num(ml, "TS")) < 1e-3);
    let (ll, ll_py) = (m.log_likelihood, num(ml, "log_likelihood"));
    assert!(ll >= ll_py - 1e-9, "tribo {ll} < pyLife {ll_py}");
    assert!(ll - ll_py < 1e-4);
    assert_eq!(t.measure, LoadMeasure::Amplitude);
    assert_eq!(t.unit, "Pa");
    // The report is plain data: its JSON carries the same numbers.
    let json = serde_json::to_value(&t).expect("the report serialises");
    assert_eq!(json["measure"], "amplitude");
    assert_eq!(json["kind"], "sigma");
    assert_eq!(
        json["max_likelihood"]["curve"]["fatigue_limit"].as_f64(),
        Some(m.curve.fatigue_limit())
    );
}

#[test]
fn the_measure_and_kind_are_carried_by_the_fit() {
    // The same numbers read as ranges: the fitted limit is a range.
    let t = fit_data(TestKind::MechanicalFatigue, LoadMeasure::Range);
    assert_eq!(t.measure, LoadMeasure::Range);
    let m = t.max_likelihood.as_ref().expect("a maximum-likelihood fit");
    assert_eq!(m.curve.measure(), LoadMeasure::Range);
    // The p curve in contact pressure.
    let t = fit_data(
        TestKind::RollingFatigue,
        TestKind::RollingFatigue.default_measure(),
    );
    assert_eq!(t.measure, LoadMeasure::ContactPressure);
    assert_eq!(t.limit_symbol, "p_f");
}

#[test]
fn fatigue_diagram_from_the_example() {
    let ex = examples::find("fatigue-diagram").expect("embedded");
    let input = parse_limits(ex.text, ex.name, Path::new(".")).expect("valid limits");
    let t = diagram(input).expect("a diagram");
    let d = &t.diagram;
    // 403/260 and 1586/1300, correctly rounded quotients.
    assert!((d.direct_effect - 403.0 / 260.0).abs() < 1e-12);
    assert!((d.back_effect - 1586.0 / 1300.0).abs() < 1e-12);
    let names: Vec<&str> = d.points.iter().map(|p| p.name).collect();
    assert_eq!(names, ["A", "B", "C", "D"]);
    // State (150 MPa, 1000 MPa): x = 10/13, y = 15/26, direction (2, 1.5) up to scale.
    // BC from B = (800/1300, 1.55) to C = (1.22, 80/260); lambda = (B x e) / (d x e).
    let (bx, by, cx, cy) = (800.0 / 1300.0, 1.55, 1.22, 80.0 / 260.0);
    let (dx, dy) = (1000.0 / 1300.0, 150.0 / 260.0);
    let (ex, ey) = (cx - bx, cy - by);
    let lambda = (bx * ey - by * ex) / (dx * ey - dy * ex);
    let st = t.state.expect("a state check");
    assert!((st.load_factor - lambda).abs() < 1e-9, "{st:?}");
    assert!(st.inside);
    assert_eq!(st.segment, "BC");
}

#[test]
fn fatigue_diagram_with_a_limit_fitted_from_data() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    std::fs::copy(data_set(), dir.path().join("sigma.csv")).expect("copied");
    // The limits inline: sigma_-1 fitted from the data file, the others given.
    let toml =
        "limits = { sigma_1 = { data = \"sigma.csv\" }, p_f = 1.3e9, sigma_1p = \"403 MPa\", \
                p_f_sigma = \"1586 MPa\", sigma_p_contact_pressure = \"800 MPa\", \
                p_sigma_stress_amplitude = \"80 MPa\" }\n";
    let input = parse_limits(toml, "limits.toml", dir.path()).expect("valid limits");
    let t = diagram(input).expect("a diagram");
    // The maximum-likelihood limit of the data set (262.26 MPa, see the pyLife test).
    let s1 = t.diagram.limits.sigma_1;
    assert!((s1 / 262.2625e6 - 1.0).abs() < 1e-5, "{s1}");
    assert_eq!(t.sources[0].method, Some("max-likelihood"));
    assert!(t.state.is_none());
}
