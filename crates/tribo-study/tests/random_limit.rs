//! The study example `roller-random-limit` (the random intensity limit sampled run by run)
//! against the case `roller-shaft-probabilistic` (the same limit by a change of variables on
//! one field): docs/user/studies.md, "Random limits only". Reduced to 40 samples for CI (about
//! a CPU second each); the shipped 200 give 0.500 against the case's 0.5133.
#![allow(clippy::expect_used, clippy::unwrap_used)]

use tribo_study::plan::StudyDir;
use tribo_study::spec::Study;
use tribo_study::{examples, run, table};

/// Runs `text` in a temporary directory and returns the table.
fn gathered(tmp: &std::path::Path, name: &str, text: &str) -> table::Table {
    let study = Study::from_toml(text, name, tmp).expect("study");
    let sd = StudyDir::plan(&study, text, &tmp.join(name)).expect("plan");
    run::run(&sd, None, 2, &mut tribo_case::Silent).expect("run");
    table::gather(&sd).expect("gather")
}

/// Two checks, each of which fails if the sweep does not sample the case's limit:
///
/// 1. Per sample, psi_max * sigma_int*lim is the case's phi_max (the field does not depend on
///    the limit: psi_max = phi_max / L), to 1e-12 relative (the rounding of one division and
///    one multiplication; the limit goes through the case TOML as shortest round-trip text).
/// 2. The share of the 40 samples with psi_max >= 1 is the case's P(psi_max >= 1) = 0.5133
///    within 3 standard errors sqrt(P (1 - P) / 40) = 3 x 0.079 (a test that fails by chance
///    0.3 % of the time for a fresh seed; the seed is fixed, so it is deterministic). A sweep
///    that did not vary the limit gives 0 or 1 (6 standard errors away); one that drew the
///    limit with twice the scatter moves P by < 0.01 here (the median is where psi_max = 1
///    nearly), which check 1 catches instead (phi_max would be unchanged, the limits not).
#[test]
fn the_sweep_agrees_with_the_cases_change_of_variables() {
    let tmp = tempfile::tempdir().expect("tmp");
    // The case's own result through a one-point study that keeps [damage.probabilistic].
    let case = r#"
[study]
name = "case"
example = "roller-shaft-probabilistic"
collect = [
  "damage.criteria[0].probabilistic.phi_max",
  "damage.criteria[0].probabilistic.probability_psi_max_ge_1",
]
[[grid]]
key = "contact.load"
values = [2000.0]
"#;
    let t = gathered(tmp.path(), "case", case);
    assert_eq!(t.status, vec!["ok"]);
    let (phi_max, p_case) = (t.collected[0][0], t.collected[0][1]);
    assert!((p_case - 0.5133).abs() < 5e-4, "P(psi_max >= 1) = {p_case}");

    let text = examples::find("roller-random-limit")
        .expect("example")
        .text
        .replace("samples = 200", "samples = 40");
    assert!(text.contains("samples = 40"));
    let t = gathered(tmp.path(), "sweep", &text);
    assert_eq!(t.counts(), (40, 0, 0));
    let psi_col = 0;
    let mut exceed = 0;
    for (row, params) in t.collected.iter().zip(&t.parameters) {
        let limit = params[0].as_float().expect("the limit");
        let psi = row[psi_col];
        let rel = (psi * limit - phi_max).abs() / phi_max;
        assert!(
            rel < 1e-12,
            "psi_max {psi} x limit {limit} vs phi_max {phi_max}"
        );
        exceed += usize::from(psi >= 1.0);
    }
    let p = exceed as f64 / 40.0;
    let se = (p_case * (1.0 - p_case) / 40.0).sqrt();
    assert!(
        (p - p_case).abs() <= 3.0 * se,
        "sweep {p} vs case {p_case} (standard error {se})"
    );
}
