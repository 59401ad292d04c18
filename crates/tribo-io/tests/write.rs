//! The writers on a real run: the files listed in the summary are exactly the files in the
//! directory, `summary.json` last and parseable; without plots no PNG is written or listed.
// Tests may unwrap: a panic here is a failed test (workspace lints deny it in library code).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;
use tribo_case::{examples, Case, Results, Silent};
use tribo_io::{write_halfspace, WriteOptions};

fn solved(
    name: &str,
) -> (
    tribo_case::case::HalfSpaceCase,
    tribo_case::pipeline::Outcome,
) {
    let ex = examples::find(name).expect("an embedded example");
    let case = Case::from_toml(ex.text, ex.name, Path::new(".")).expect("a valid case");
    let results = tribo_case::run(&case, &mut Silent).expect("solved");
    match (case, results) {
        (Case::HalfSpace(c), Results::HalfSpace(r)) => (*c, *r),
        _ => panic!("{name} is a half-space example"),
    }
}

fn listed(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn the_summary_lists_exactly_the_files_written() {
    let (case, out) = solved("sphere-on-flat");
    let dir = tempfile::tempdir().unwrap();
    let no_plots = WriteOptions {
        plots: false,
        ..WriteOptions::default()
    };
    let w = write_halfspace(dir.path(), &case, &out, &no_plots).unwrap();
    assert!(
        w.files.iter().all(|f| !f.ends_with(".png")),
        "{:?}",
        w.files
    );
    assert_eq!(w.files, w.summary.outputs);
    let mut expected = w.files.clone();
    expected.sort();
    assert_eq!(listed(dir.path()), expected);
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("summary.json")).unwrap()).unwrap();
    assert_eq!(json["outputs"].as_array().unwrap().len(), w.files.len());
    let header = std::fs::read_to_string(dir.path().join("pressure.csv")).unwrap();
    assert!(header.starts_with("x_m,y_m,pressure_Pa\n"));

    // With plots (feature png): the PNGs too, and the earlier run's files replaced.
    if cfg!(feature = "png") {
        let w = write_halfspace(dir.path(), &case, &out, &WriteOptions::default()).unwrap();
        assert!(w.files.iter().any(|f| f == "pressure_map.png"));
        let mut expected = w.files.clone();
        expected.sort();
        assert_eq!(listed(dir.path()), expected);
        let png = std::fs::read(dir.path().join("pressure_map.png")).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    }
}
