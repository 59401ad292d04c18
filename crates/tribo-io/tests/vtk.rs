//! Binary VTK: what the writer puts in the file reads back bit-equal with a reader of the
//! tests' own (tests/common), header and appended block checked.
// Tests may unwrap: a panic here is a failed test (workspace lints deny it in library code).
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use tribo::SurfaceGrid;
use tribo_io::vtk::{surface_vti, AppendedFile};

#[test]
fn round_trip_bit_equal() {
    let a = [1.5, -0.0, f64::MIN_POSITIVE, 1e300, -3.25e-7];
    let mut f = AppendedFile::new("ImageData");
    f.xml("  <ImageData>\n    <Piece>\n      <PointData>\n");
    f.array("        ", "a_Pa", 1, a.iter().copied());
    f.array("        ", "k", 1, [0i64, 3, -7].into_iter());
    f.array("        ", "t", 1, [5u8, 5].into_iter());
    f.array("        ", "r", 1, [-2i32, 9].into_iter());
    f.xml("      </PointData>\n    </Piece>\n  </ImageData>\n");
    let (header, arrays) = common::parse(&f.finish());
    assert!(header.contains("offset=\"0\""));
    assert_eq!(arrays.len(), 4);
    let back = arrays[0].f64s();
    assert!(back.iter().zip(&a).all(|(x, y)| x.to_bits() == y.to_bits()));
    assert_eq!(arrays[1].i64s(), vec![0, 3, -7]);
    assert_eq!(arrays[2].bytes, vec![5, 5]);
    assert_eq!(arrays[2].kind, "UInt8");
    assert_eq!(arrays[3].kind, "Int32");
    assert_eq!(
        arrays[3].bytes,
        [(-2i32).to_le_bytes(), 9i32.to_le_bytes()].concat()
    );
    assert!(arrays.iter().all(|a| a.components == 1));
    // Offsets: 8 + 40, then 8 + 24, then 8 + 2.
    assert!(header.contains("offset=\"48\""));
    assert!(header.contains("offset=\"80\""));
    assert!(header.contains("offset=\"90\""));
}

#[test]
fn an_empty_file_is_well_formed() {
    let mut f = AppendedFile::new("ImageData");
    f.xml("  <ImageData>\n  </ImageData>\n");
    let (header, arrays) = common::parse(&f.finish());
    assert!(header.contains("<VTKFile type=\"ImageData\""));
    assert!(arrays.is_empty());
}

#[test]
fn surface_vti_has_one_cell_per_element() {
    let g = SurfaceGrid::centred(4, 5, 2.0, 2.5).unwrap();
    let v = vec![1.0; 20];
    let w: Vec<f64> = (0..20).map(|k| (k as f64).sqrt() - 1.7).collect();
    let (text, arrays) = common::parse(&surface_vti(&g, &[("a", &v), ("b", &w)]));
    assert!(text.contains("WholeExtent=\"0 4 0 5 0 0\""));
    assert!(text.contains("Origin=\"-2e0 -2.5e0 0\""));
    assert!(text.contains("Spacing=\"1e0 1e0 1e0\""));
    assert!(text.contains("<CellData Scalars=\"a\">"));
    assert_eq!(text.matches("<DataArray").count(), 2);
    // Read back bit-equal, one value per cell (nx * ny).
    assert_eq!(arrays[0].name, "a");
    assert_eq!(arrays[0].f64s(), v);
    assert_eq!(arrays[1].name, "b");
    let back = arrays[1].f64s();
    assert_eq!(back.len(), 20);
    assert!(back.iter().zip(&w).all(|(x, y)| x.to_bits() == y.to_bits()));
}
