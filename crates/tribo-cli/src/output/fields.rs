//! Surface fields as CSV (long format) and as VTK XML image data (ParaView).

use super::vtk::AppendedFile;
use tribo::SurfaceGrid;

/// A field in long format: a header line `x_m,y_m,{name}` and one line per element centre,
/// x varying fastest. `name` carries the unit (e.g. `pressure_Pa`).
pub fn csv(grid: &SurfaceGrid, name: &str, values: &[f64]) -> String {
    let mut s = String::with_capacity(48 * values.len() + 32);
    s.push_str("x_m,y_m,");
    s.push_str(name);
    s.push('\n');
    for iy in 0..grid.ny() {
        for ix in 0..grid.nx() {
            let v = values[grid.index(ix, iy)];
            s.push_str(&format!("{:e},{:e},{:e}\n", grid.x(ix), grid.y(iy), v));
        }
    }
    s
}

/// VTK XML ImageData (`.vti`, binary: raw appended little-endian data, see
/// [`super::vtk`]) with one cell per element: the image's points are the element corners,
/// `WholeExtent = 0 nx 0 ny 0 0`, `Origin` the window's lower-left corner,
/// `Spacing = dx dy dx`; each named array becomes a `CellData` array (x varying fastest, the
/// grid's layout, which is VTK's cell order).
pub fn vti(grid: &SurfaceGrid, arrays: &[(&str, &[f64])]) -> Vec<u8> {
    let (x0, y0) = grid.origin();
    let (nx, ny) = (grid.nx(), grid.ny());
    let mut f = AppendedFile::new("ImageData");
    f.xml(&format!(
        "  <ImageData WholeExtent=\"0 {nx} 0 {ny} 0 0\" Origin=\"{x0:e} {y0:e} 0\" Spacing=\"{:e} {:e} {:e}\">\n",
        grid.dx(),
        grid.dy(),
        grid.dx()
    ));
    f.xml(&format!("    <Piece Extent=\"0 {nx} 0 {ny} 0 0\">\n"));
    let first = arrays.first().map_or("", |a| a.0);
    f.xml(&format!("      <CellData Scalars=\"{first}\">\n"));
    for (name, values) in arrays {
        f.array("        ", name, 1, values.iter().copied());
    }
    f.xml("      </CellData>\n    </Piece>\n  </ImageData>\n");
    f.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_layout() {
        let g = SurfaceGrid::centred(4, 5, 2.0, 2.5).unwrap();
        let v: Vec<f64> = (0..20).map(|k| k as f64).collect();
        let text = csv(&g, "pressure_Pa", &v);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 21);
        assert_eq!(lines[0], "x_m,y_m,pressure_Pa");
        assert_eq!(lines[1], "-1.5e0,-2e0,0e0");
        assert_eq!(lines[2], "-5e-1,-2e0,1e0");
        let last: Vec<f64> = lines[20].split(',').map(|c| c.parse().unwrap()).collect();
        assert_eq!(last, vec![1.5, 2.0, 19.0]);
    }

    #[test]
    fn vti_counts() {
        let g = SurfaceGrid::centred(4, 5, 2.0, 2.5).unwrap();
        let v = vec![1.0; 20];
        let w: Vec<f64> = (0..20).map(|k| (k as f64).sqrt() - 1.7).collect();
        let (text, arrays) = super::super::vtk::read::parse(&vti(&g, &[("a", &v), ("b", &w)]));
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
}
