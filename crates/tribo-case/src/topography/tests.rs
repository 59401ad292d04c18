//! The readers against the fixtures of crates/tribo-case/tests/data/topography (written by
//! make_fixtures.py there: the .npy files by numpy's own writer, the X3P archives from the
//! format's layout with Python's zipfile). Every grid is 5 x 4 points with
//! h(i, j) = 1e-7 (i + 10 j) + 1e-8 i j (m) at (i dx, j dy), dx = 0.5 um, dy = 0.25 um.

use super::*;
use std::path::PathBuf;

const NX: usize = 5;
const NY: usize = 4;
const DX: f64 = 0.5e-6;
const DY: f64 = 0.25e-6;

fn h(i: usize, j: usize) -> f64 {
    1e-7 * (i + 10 * j) as f64 + 1e-8 * (i * j) as f64
}

fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/topography")
        .join(name)
}

/// Checks the grid, the spacing and every height (within `tol` m; NaN at `invalid`).
fn check(m: &Measured, tol: f64, invalid: &[(usize, usize)]) {
    assert_eq!((m.nx, m.ny), (NX, NY), "{}", m.path.display());
    assert!(
        (m.dx - DX).abs() < 1e-18 && (m.dy - DY).abs() < 1e-18,
        "{} {}",
        m.dx,
        m.dy
    );
    for j in 0..NY {
        for i in 0..NX {
            let v = m.heights[j * NX + i];
            if invalid.contains(&(i, j)) {
                assert!(v.is_nan(), "{}: ({i}, {j}) = {v}", m.path.display());
            } else {
                assert!(
                    (v - h(i, j)).abs() <= tol,
                    "{}: ({i}, {j}) = {v:e} vs {:e}",
                    m.path.display(),
                    h(i, j)
                );
            }
        }
    }
    assert_eq!(m.invalid_count(), invalid.len());
}

fn error(name: &str, options: &ReadOptions) -> String {
    let e = read(&fixture(name), options).unwrap_err();
    let s = e.to_string();
    assert!(s.contains(name), "the error names the file: {s}");
    s
}

fn given() -> ReadOptions {
    ReadOptions {
        spacing: Some((DX, DY)),
        ..ReadOptions::default()
    }
}

/// X3P: float64 (deflated) with a NaN; float32 without Increment/Offset (f32 round-off,
/// 1e-7 of 4e-6 m); int16 counts of 1 nm with an offset and the valid-points bits (the
/// values are the nearest nanometre: 0.5 nm); int32 counts of 0.1 nm; inline data with an
/// empty Datum.
#[test]
fn x3p_reads_every_data_type() {
    let o = ReadOptions::default();
    check(&read(&fixture("grid_d.x3p"), &o).unwrap(), 1e-22, &[(2, 1)]);
    check(
        &read(&fixture("grid_f.x3p"), &o).unwrap(),
        4e-6 * 1.2e-7,
        &[],
    );
    check(
        &read(&fixture("grid_i_valid.x3p"), &o).unwrap(),
        0.5e-9 + 1e-20,
        &[(4, 0), (0, 3)],
    );
    check(
        &read(&fixture("grid_l.x3p"), &o).unwrap(),
        0.5e-10 + 1e-20,
        &[],
    );
    check(
        &read(&fixture("grid_list.x3p"), &o).unwrap(),
        1e-22,
        &[(1, 2)],
    );
    // The spacing given must agree with the file's.
    assert!(read(&fixture("grid_f.x3p"), &given()).is_ok());
    let bad = ReadOptions {
        spacing: Some((1e-6, DY)),
        ..ReadOptions::default()
    };
    assert!(error("grid_f.x3p", &bad).contains("differs"));
}

#[test]
fn x3p_errors_name_the_file_and_the_problem() {
    let o = ReadOptions::default();
    assert!(error("truncated.x3p", &o).contains("not a readable X3P archive"));
    assert!(error("no_main.x3p", &o).contains("no main.xml"));
    let s = error("short_data.x3p", &o);
    assert!(
        s.contains("152 bytes, expected") && s.contains("160"),
        "{s}"
    );
    assert!(error("profile.x3p", &o).contains("FeatureType = PRF"));
    assert!(error("absolute_x.x3p", &o).contains("CX/AxisType = A"));
    assert!(error("bad_dtype.x3p", &o).contains("DataType = Q"));
    // grid_d.x3p with one bit of the first height flipped after its MD5 was taken, and with
    // md5checksum.hex of a different main.xml (make_fixtures.py, checksum_fixtures).
    let s = error("bad_md5_data.x3p", &o);
    assert!(
        s.contains("MD5 checksum of bindata/data.bin") && s.contains("corrupt"),
        "{s}"
    );
    let s = error("bad_md5_main.x3p", &o);
    assert!(
        s.contains("MD5 checksum of main.xml") && s.contains("md5checksum.hex"),
        "{s}"
    );
    let tiny = ReadOptions {
        max_bytes: 100,
        ..ReadOptions::default()
    };
    assert!(error("grid_d.x3p", &tiny).contains("above the limit"));
}

/// npy written by numpy: C order f8, Fortran order big-endian f4, i4 in nanometres (the
/// unit given), format versions 2 and 3.
#[test]
fn npy_reads_numpy_files() {
    let o = given();
    check(&read(&fixture("c_f8.npy"), &o).unwrap(), 1e-22, &[]);
    check(
        &read(&fixture("fortran_f4_big.npy"), &o).unwrap(),
        4e-6 * 1.2e-7,
        &[],
    );
    let nm = ReadOptions {
        height_unit: 1e-9,
        ..given()
    };
    check(
        &read(&fixture("c_i4_nm.npy"), &nm).unwrap(),
        0.5e-9 + 1e-20,
        &[],
    );
    check(&read(&fixture("v2_f8.npy"), &o).unwrap(), 1e-22, &[]);
    check(&read(&fixture("v3_f8_big.npy"), &o).unwrap(), 1e-22, &[]);
    // Errors.
    assert!(error("c_f8.npy", &ReadOptions::default()).contains("does not give the spacing"));
    assert!(error("three_d.npy", &o).contains("2D array"));
    assert!(error("f2.npy", &o).contains("unsupported dtype '<f2'"));
    assert!(error("short.npy", &o).contains("152 bytes, expected"));
    let s = npy::parse(&fixture("x.npy"), b"PK\x03\x04 not numpy", &o).unwrap_err();
    assert!(s.to_string().contains("not a numpy .npy file"), "{s}");
}

/// ASCII: tribo's header (um heights, nm spacing), Gwyddion's export (Width/Height over the
/// point counts, µm with the micro sign), a headerless CSV with a NaN and the spacing given.
#[test]
fn ascii_reads_headers_and_plain_grids() {
    check(
        &read(&fixture("tribo_header.txt"), &ReadOptions::default()).unwrap(),
        1e-20,
        &[],
    );
    check(
        &read(&fixture("gwyddion.txt"), &ReadOptions::default()).unwrap(),
        1e-22,
        &[],
    );
    check(
        &read(&fixture("headerless.csv"), &given()).unwrap(),
        1e-22,
        &[(3, 1)],
    );
    let s = error("ragged.csv", &given());
    assert!(
        s.contains("line 3: 2 values, expected 3 as on line 1"),
        "{s}"
    );
    let e = ascii::parse(&fixture("t.txt"), "# dx: 1 furlong\n1 2\n3 4\n", &given()).unwrap_err();
    assert!(e.to_string().contains("unknown unit \"furlong\""), "{e}");
    let e = ascii::parse(&fixture("t.txt"), "1 2\n3 x\n", &given()).unwrap_err();
    assert!(
        e.to_string().contains("line 2: \"x\" is not a number"),
        "{e}"
    );
    assert!(error("gwyddion.x", &ReadOptions::default()).contains("unknown topography format"));
    // A header given twice was taken silently (the last one won).
    let e = ascii::parse(
        &fixture("t.txt"),
        "# dx: 1e-6\n# dy: 1e-6\n# dx: 2e-6\n1 2\n3 4\n",
        &ReadOptions::default(),
    )
    .unwrap_err();
    assert!(e.to_string().contains("line 3: dx given twice"), "{e}");
}

/// Invalid points are refused, naming the count and the first; a complete grid becomes a
/// topography that the library's tools take (here: the plane fit removes the linear part).
#[test]
fn invalid_points_are_refused_and_valid_grids_convert() {
    let m = read(&fixture("grid_d.x3p"), &ReadOptions::default()).unwrap();
    let e = m.into_topography().unwrap_err().to_string();
    assert!(
        e.contains("1 of 20 points are invalid") && e.contains("row 1, column 2"),
        "{e}"
    );
    let t = read(&fixture("c_f8.npy"), &given())
        .unwrap()
        .into_topography()
        .unwrap();
    assert_eq!(t.nx(), NX);
    let r = tribo::surface::detrend::detrend_polynomial(&t, 2).unwrap();
    // h is a quadratic (bilinear) polynomial: nothing is left.
    assert!(r.residual.heights().iter().all(|v| v.abs() < 1e-20));
    let ce = TopographyError::new(&fixture("a.x3p"), "bad").into_case_error("body1.surface.file");
    assert!(ce.to_string().starts_with("body1.surface.file = "), "{ce}");
}
