//! The tangential traction (`traction.csv`) and the subsurface stress field (`stress.vti`,
//! sections as PNG).

use crate::run::Stress;
use tribo::analysis::stress_field::{energy_density, strain};
use tribo::SurfaceGrid;

/// `traction.csv`: x_m, y_m, q_x_Pa, q_y_Pa, stick (0/1) at element centres, x fastest.
pub fn traction_csv(grid: &SurfaceGrid, qx: &[f64], qy: &[f64], stick: &[bool]) -> String {
    let mut s = String::with_capacity(64 * qx.len() + 40);
    s.push_str("x_m,y_m,q_x_Pa,q_y_Pa,stick\n");
    for iy in 0..grid.ny() {
        for ix in 0..grid.nx() {
            let k = grid.index(ix, iy);
            s.push_str(&format!(
                "{:e},{:e},{:e},{:e},{}\n",
                grid.x(ix),
                grid.y(iy),
                qx[k] + 0.0,
                qy[k] + 0.0,
                u8::from(stick[k])
            ));
        }
    }
    s
}

/// The named point arrays of `stress.vti`, each one value per field point (x fastest, then
/// y, then z).
pub fn arrays(st: &Stress) -> Vec<(&'static str, Vec<f64>)> {
    let f = &st.field.stress;
    let m = &st.material;
    let col = |g: &dyn Fn(&tribo::kernels::subsurface::StressTensor) -> f64| -> Vec<f64> {
        f.iter().map(g).collect()
    };
    let strains: Vec<_> = f.iter().map(|s| strain(s, m)).collect();
    let energies: Vec<_> = f.iter().map(|s| energy_density(s, m)).collect();
    let principal: Vec<[f64; 3]> = f.iter().map(|s| s.principal()).collect();
    vec![
        ("sigma_xx", col(&|s| s.xx)),
        ("sigma_yy", col(&|s| s.yy)),
        ("sigma_zz", col(&|s| s.zz)),
        ("sigma_xy", col(&|s| s.xy)),
        ("sigma_yz", col(&|s| s.yz)),
        ("sigma_xz", col(&|s| s.xz)),
        ("von_mises", col(&|s| s.von_mises())),
        ("max_shear", col(&|s| s.max_shear())),
        ("principal_1", principal.iter().map(|p| p[0]).collect()),
        ("principal_2", principal.iter().map(|p| p[1]).collect()),
        ("principal_3", principal.iter().map(|p| p[2]).collect()),
        ("hydrostatic", col(&|s| s.hydrostatic())),
        ("octahedral_shear", col(&|s| s.octahedral_shear())),
        ("energy_density", energies.iter().map(|u| u.total).collect()),
        (
            "energy_volumetric",
            energies.iter().map(|u| u.volumetric).collect(),
        ),
        (
            "energy_distortional",
            energies.iter().map(|u| u.distortional).collect(),
        ),
        ("strain_xx", strains.iter().map(|e| e.xx).collect()),
        ("strain_yy", strains.iter().map(|e| e.yy).collect()),
        ("strain_zz", strains.iter().map(|e| e.zz).collect()),
        ("strain_xy", strains.iter().map(|e| e.xy).collect()),
        ("strain_yz", strains.iter().map(|e| e.yz).collect()),
        ("strain_xz", strains.iter().map(|e| e.xz).collect()),
    ]
}

fn spacing(v: &[f64]) -> f64 {
    match v {
        [first, .., last] => (last - first) / (v.len() - 1) as f64,
        _ => 1.0,
    }
}

/// VTK XML ImageData over the field points (uniform spacing; binary, raw appended data, see
/// [`super::vtk`]): `Origin = (-hx, -hy, 0)`, z the depth into the body; every array as
/// `PointData`.
pub fn vti(st: &Stress, arrays: &[(String, Vec<f64>)]) -> Vec<u8> {
    let g = &st.field.grid;
    let (nx, ny, nz) = (g.x.len(), g.y.len(), g.z.len());
    let mut f = super::vtk::AppendedFile::new("ImageData");
    let (x0, y0) = (
        g.x.first().copied().unwrap_or(0.0),
        g.y.first().copied().unwrap_or(0.0),
    );
    let ext = format!(
        "0 {} 0 {} 0 {}",
        nx.saturating_sub(1),
        ny.saturating_sub(1),
        nz.saturating_sub(1)
    );
    f.xml(&format!(
        "  <ImageData WholeExtent=\"{ext}\" Origin=\"{x0:e} {y0:e} 0\" Spacing=\"{:e} {:e} {:e}\">\n",
        spacing(&g.x),
        spacing(&g.y),
        spacing(&g.z)
    ));
    f.xml(&format!("    <Piece Extent=\"{ext}\">\n"));
    f.xml("      <PointData Scalars=\"von_mises\">\n");
    for (name, values) in arrays {
        f.array("        ", name, 1, values.iter().map(|v| v + 0.0));
    }
    f.xml("      </PointData>\n    </Piece>\n  </ImageData>\n");
    f.finish()
}

/// Index of the value of `v` nearest `t`.
pub fn nearest(v: &[f64], t: f64) -> usize {
    (0..v.len())
        .min_by(|&a, &b| (v[a] - t).abs().total_cmp(&(v[b] - t).abs()))
        .unwrap_or(0)
}

/// The plane `y = y[iy]` of `values`: (x fastest, z rows).
pub fn plane_y(st: &Stress, values: &[f64], iy: usize) -> Vec<f64> {
    let g = &st.field.grid;
    let mut out = Vec::with_capacity(g.x.len() * g.z.len());
    for iz in 0..g.z.len() {
        for ix in 0..g.x.len() {
            out.push(values[g.index(ix, iy, iz)]);
        }
    }
    out
}

/// The plane `x = x[ix]` of `values`: (y fastest, z rows).
pub fn plane_x(st: &Stress, values: &[f64], ix: usize) -> Vec<f64> {
    let g = &st.field.grid;
    let mut out = Vec::with_capacity(g.y.len() * g.z.len());
    for iz in 0..g.z.len() {
        for iy in 0..g.y.len() {
            out.push(values[g.index(ix, iy, iz)]);
        }
    }
    out
}

/// The plane `z = z[iz]` of `values`: (x fastest, y rows).
pub fn plane_z(st: &Stress, values: &[f64], iz: usize) -> Vec<f64> {
    let g = &st.field.grid;
    let n = g.x.len() * g.y.len();
    values[iz * n..(iz + 1) * n].to_vec()
}
