//! The domain energies against exact integrals and the 1D column's closed form
//! (docs/theory/DYNAMICS.md sec. 3.1 and 5.8).

use super::*;
use crate::dynamics::cq::{convolve, CqGrid, CqMethod, CqParams};
use crate::dynamics::laplace::LaplaceBem;
use crate::dynamics::testing::column;

/// The unit square as two triangles.
fn square() -> (Vec<[f64; 2]>, Vec<[usize; 3]>) {
    (
        vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        vec![[0, 1, 2], [0, 2, 3]],
    )
}

/// The rule is exact for products of linear fields: a uniform stress s_xx = 2, s_xy = 1
/// with strains e = (1, 0, 0.5) gives U = 1/2 (2 + 2 * 0.5) = 1.5 on the unit square; the
/// velocity v = (x, y) gives K = rho/2 int x^2 + y^2 dA = rho/3 (rho = 3: 1). A factor 2 on
/// the shear term, a wrong diagonal weight or the density left out is off by O(1).
#[test]
fn products_of_linear_fields_are_exact() {
    let (nodes, triangles) = square();
    let mesh = EnergyMesh::new(&nodes, &triangles, 3.0).unwrap();
    assert!((mesh.area() - 1.0).abs() < 1e-15);
    let u = mesh
        .strain_energy(&[[2.0, 0.0, 1.0]; 4], &[[1.0, 0.0, 0.5]; 4])
        .unwrap();
    assert!((u - 1.5).abs() < 1e-14, "{u}");
    let v: Vec<[f64; 2]> = nodes.clone();
    let k = mesh.kinetic_energy(&v).unwrap();
    assert!((k - 1.0).abs() < 1e-14, "{k}");
    // Wrong shapes and data are errors, not panics.
    assert!(mesh.kinetic_energy(&v[..3]).is_err());
    assert!(EnergyMesh::new(&nodes, &[[0, 1, 4]], 1.0).is_err());
    assert!(EnergyMesh::new(&nodes, &[[0, 1, 1]], 1.0).is_err());
    assert!(EnergyMesh::new(&nodes, &triangles, 0.0).is_err());
    assert!(EnergyMesh::new(&nodes, &triangles, f64::NAN).is_err());
}

/// The worst balance and its time; None without work or with ragged series.
#[test]
fn worst_balance_is_relative_to_the_largest_work() {
    let t = [0.0, 1.0, 2.0];
    let (w, u, k) = ([0.0, 2.0, 4.0], [0.0, 1.0, 1.5], [0.0, 0.9, 2.0]);
    let (b, at) = worst_balance(&t, &w, &u, &k, &[]).unwrap();
    assert!((b - 0.5 / 4.0).abs() < 1e-15 && at == 2.0, "{b} {at}");
    let (b, _) = worst_balance(&t, &w, &u, &k, &[0.0, 0.1, 0.5]).unwrap();
    assert!(b.abs() < 1e-15, "{b}");
    assert!(worst_balance(&t, &[0.0; 3], &u, &k, &[]).is_none());
    assert!(worst_balance(&t, &w[..2], &u, &k, &[]).is_none());
}

/// W, U, K of the column (the validation rows' model).
fn column_energies(nx: usize, size: f64, steps: usize, t_end: f64) -> [Vec<f64>; 3] {
    crate::validation::dyn_energy::column_energies(nx, size, steps, t_end).unwrap()
}

/// The 1D column's travelling front (docs/theory/DYNAMICS.md sec. 3.1, 5.8; the bar under
/// a suddenly applied end load, Graff 1975, longitudinal waves in rods): for t < L/c the
/// front at x = c t
/// leaves the strain s = -p0/E and the particle velocity p0/(rho c) behind it, so the
/// strain and kinetic energy densities are equal, p0^2/(2E) = rho (p0/(rho c))^2 / 2 (E =
/// rho c^2), and per unit thickness U = K = p0^2 A c t/(2E) = W/2, W = p0 A u(0, t) =
/// p0^2 A c t/E = 0.25 t here. After the reflections U and K exchange but W = U + K stays
/// (no dissipation in the exact solution).
///
/// Measured (BDF2, 16 elements along; dt = 0.025, triangles h = 0.0625 / dt = 0.0125,
/// h = 0.03125): max over t = 0.5, 0.75 of |U/(W/2) - 1|, |K/(W/2) - 1| 2.00e-2 / 1.26e-2,
/// the balance max_n |W - U - K| / max W over the run to 2 L/c 6.31e-3 / 4.17e-3. The
/// front is smeared by CQ's dispersion over a few c dt and by the P1 interpolant over one
/// triangle: relative O((c dt + h)/(c t)), here 0.175 / 0.0875 at t = 0.5, with measured
/// constants 0.11 / 0.14. Asserted: the front error below 0.25 (c dt + h)/(c t) and the
/// balance below 0.12 (c dt + h)/L at both resolutions, both falling with the refinement.
/// A factor 2 on either energy or a missing density is O(1); the first-order velocity
/// difference instead of BDF2's leaves K off by its O(dt) lag at the front.
#[test]
fn column_strain_and_kinetic_energy_halve_the_work_before_the_reflection() {
    let mut errs = Vec::new();
    for (steps, size) in [(80, 0.0625), (160, 0.03125)] {
        let t_end = 2.0;
        let [w, u, k] = column_energies(16, size, steps, t_end);
        let dt = t_end / steps as f64;
        let at = |t: f64| (t / dt).round() as usize;
        let mut front = 0.0_f64;
        for t in [0.5, 0.75] {
            let n = at(t);
            let half = 0.125 * t;
            front = front
                .max((u[n] / half - 1.0).abs())
                .max((k[n] / half - 1.0).abs());
        }
        let w_max = w.iter().fold(0.0_f64, |m, &x| m.max(x));
        let balance = w
            .iter()
            .zip(&u)
            .zip(&k)
            .map(|((w, u), k)| (w - u - k).abs() / w_max)
            .fold(0.0_f64, f64::max);
        eprintln!(
            "column steps {steps} size {size}: U, K vs W/2 {front:.3e}, balance {balance:.3e}; \
             t = 0.5: W {:.5} U {:.5} K {:.5}",
            w[at(0.5)],
            u[at(0.5)],
            k[at(0.5)]
        );
        errs.push((front, balance));
    }
    for ((front, balance), (dt, h)) in errs.iter().zip([(0.025, 0.0625), (0.0125, 0.03125)]) {
        assert!(*front < 0.25 * (dt + h) / 0.5, "{errs:?}");
        assert!(*balance < 0.12 * (dt + h), "{errs:?}");
    }
    assert!(errs[1].0 < errs[0].0 && errs[1].1 < errs[0].1, "{errs:?}");
}

/// Near-boundary band: after the front has passed (t = 0.8 at x = 0.25), the exact stress
/// is uniform across the column, s_xx = -p0, s_yy = s_xy = 0. Points at distances
/// d = 0.5 l .. 1e-3 l from the free face y = 0.25 (l = 1/16 the element length) must show
/// it as well as the centre line does (the nearly singular element integrals are
/// subdivided). Measured: the centre line -1.00185 (the CQ time error at dt = 0.0125), the
/// largest deviation from it 8.1e-3 of p0 at d = 1e-3 l above a node (s_xx -0.99373), 7e-4
/// between nodes; asserted below 1.2e-2 p0 (a failed near-singular integral is O(1) or
/// grows as d falls).
#[test]
fn near_boundary_stress_is_uniform_across_the_column() {
    let (model, bcs) = column(16, 2);
    let l = 1.0 / 16.0;
    let ds = [0.5, 0.1, 1e-2, 1e-3];
    let mut points = vec![[0.25, 0.125]];
    // Between two nodes (x = 0.25 + l/4) and at a node (x = 0.25) of the face y = 0.25.
    for x in [0.25 + 0.25 * l, 0.25] {
        points.extend(ds.iter().map(|d| [x, 0.25 - d * l]));
    }
    let bem = LaplaceBem::new(&model, &[1.0], &bcs, &points)
        .unwrap()
        .with_stress_probes(&points)
        .unwrap();
    let (steps, t_end) = (64, 0.8);
    let grid = CqGrid::new(CqMethod::Bdf2, t_end / steps as f64, steps).unwrap();
    let pattern = bem.static_known_values().to_vec();
    let data: Vec<f64> = grid
        .sample_times()
        .iter()
        .flat_map(|_| pattern.iter().copied())
        .collect();
    let series = convolve(&bem, &grid, &data, &CqParams::default()).unwrap();
    let no = series.channels;
    let k = grid.step_sample(steps).unwrap();
    let s = bem
        .stress_probe_values(&series.values[k * no..(k + 1) * no])
        .unwrap();
    let centre = s[0];
    for (p, si) in points.iter().zip(&s).skip(1) {
        let dev = (si.xx - centre.xx).abs().max(si.yy.abs()).max(si.xy.abs());
        eprintln!(
            "near boundary {p:?}: s = ({:.5}, {:.2e}, {:.2e}), centre s_xx {:.5}",
            si.xx, si.yy, si.xy, centre.xx
        );
        assert!(dev < 1.2e-2, "{p:?}: {si:?} vs {centre:?}");
    }
}
