//! Opt-in: re-run Tamaas live and compare tribo's periodic solution with it (the stored
//! comparison is `tribo::validation::tamaas`, which needs no Tamaas).
//!
//! ```sh
//! TRIBO_TAMAAS_PYTHON=bench/.venv/bin/python cargo test --release -p tribo --test tamaas_live
//! ```
//!
//! `TRIBO_TAMAAS_PYTHON`: an interpreter with `tamaas` and `numpy` (bench/periodic.sh makes
//! bench/.venv). Unset, the test returns at once (it says so on stderr). `TRIBO_TAMAAS_N`:
//! the grid side (default 128). It runs bench/tamaas_periodic.py (the surface of issue 16's
//! benchmark, Tamaas's periodic PolonskyKeerRey at tolerance 1e-12) and checks what the stored
//! rows check: the pressures within 1e-9 of the maximum (so is any element in contact in one
//! answer only).

use std::path::PathBuf;
use std::process::Command;

use tribo::solvers::NormalContactParams;
use tribo::validation::tamaas::{compare_with_tamaas, decode_f64_le, MEAN_PRESSURE};

#[test]
fn tribo_matches_tamaas_run_live() {
    let Some(python) = std::env::var_os("TRIBO_TAMAAS_PYTHON") else {
        eprintln!("tamaas_live: TRIBO_TAMAAS_PYTHON is not set: skipped");
        return;
    };
    let n: usize = std::env::var("TRIBO_TAMAAS_N")
        .ok()
        .map(|v| v.parse().expect("TRIBO_TAMAAS_N must be an integer"))
        .unwrap_or(128);
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let dir = std::env::temp_dir().join(format!("tribo-tamaas-live-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temporary directory");
    let stem = dir.join("surface");
    let pressure = dir.join("pressure.bin");
    let output = Command::new(&python)
        .arg(root.join("bench/tamaas_periodic.py"))
        .args([
            "--n",
            &n.to_string(),
            "--tolerance",
            "1e-12",
            "--surface-out",
        ])
        .arg(&stem)
        .arg("--pressure-out")
        .arg(&pressure)
        .output()
        .expect("run TRIBO_TAMAAS_PYTHON");
    assert!(
        output.status.success(),
        "tamaas_periodic.py failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    eprintln!("tamaas: {}", String::from_utf8_lossy(&output.stdout).trim());
    let read = |path: PathBuf| {
        let bytes = std::fs::read(&path).expect("tamaas output");
        decode_f64_le(&bytes, n * n, &path.display().to_string()).expect("n * n f64")
    };
    let surface = read(stem.with_extension("bin"));
    let p_tamaas = read(pressure);
    let _ = std::fs::remove_dir_all(&dir);
    let c = compare_with_tamaas(
        n,
        &surface,
        &p_tamaas,
        MEAN_PRESSURE,
        &NormalContactParams::default(),
    )
    .expect("tribo solves");
    eprintln!(
        "N = {n}: max |dp| / max p = {:e}, contact mismatch {} of {}, residuals tribo {:?} tamaas {:?}",
        c.max_pressure_difference,
        c.contact_mismatch,
        c.tamaas_contact_elements,
        c.tribo_residuals,
        c.tamaas_residuals
    );
    // As the stored rows (crates/tribo/src/validation/tamaas.rs): ten times tribo's tolerance.
    assert!(c.max_pressure_difference < 1e-9, "{c:?}");
    // An element in contact in one answer only carries at most that difference: at 64^2 the
    // sets are equal (the stored row); at larger N an element at the edge of a patch may carry
    // ~1e-10 of the maximum in one answer and 0 in the other.
    assert!(c.mismatch_max_pressure < 1e-9, "{c:?}");
}
