//! The surface displacement of a half-space under any field of surface tractions (p, q_x,
//! q_y), all three components in one call: the discretized operator (10) of the paper for
//! the full traction vector.
//!
//! Nine influence functions (u_x, u_y, u_z of uniform p, q_x, q_y on an element; Love 1929,
//! Pohrt & Li 2014, [`crate::kernels::love`]) are convolved non-periodically with the
//! tractions on the grid's element centres by [`SpectralConvolution`]: the tractions are
//! transformed once, each kernel once, the products summed per displacement component in the
//! spectral domain, and each component transformed back once.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::analysis::stress_field::SurfaceTractions;
use crate::error::Result;
use crate::kernels::love;
use crate::material::ElasticMaterial;
use crate::operators::{fill_kernel_table, Parity, SpectralConvolution, Spectrum};

/// Surface displacements at the element centres, m (grid layout).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SurfaceDisplacement {
    /// u_x, m.
    pub x: Vec<f64>,
    /// u_y, m.
    pub y: Vec<f64>,
    /// u_z (positive into the body), m.
    pub z: Vec<f64>,
}

/// Parities (in x, in y) of u_x, u_y, u_z for uniform p, q_x, q_y on a centred rectangle:
/// reflecting x -> -x flips u_x and q_x, so the pressure's u_x is odd in x and its u_y, u_z
/// even; q_x's u_x is even, its u_y, u_z odd; likewise in y.
const DISPLACEMENT_PARITY: [[(Parity, Parity); 3]; 3] = {
    use Parity::{Even as E, Odd as O};
    [
        [(O, E), (E, O), (E, E)],
        [(E, E), (O, O), (O, E)],
        [(O, O), (E, E), (E, O)],
    ]
};

/// The surface displacement `[u_x, u_y, u_z]` at every element centre of `tractions.grid` of
/// one half-space of `material` loaded by the tractions (p compressive in +z, q acting on the
/// body), by non-periodic FFT convolution with the closed-form rectangle solutions. Exact
/// for piecewise-constant tractions (round-off only; tested against the direct sum).
pub fn surface_displacement(
    tractions: &SurfaceTractions<'_>,
    material: &ElasticMaterial,
) -> Result<SurfaceDisplacement> {
    tractions.validate()?;
    let grid = tractions.grid;
    let (nx, ny) = (grid.nx(), grid.ny());
    let (dx, dy) = (grid.dx(), grid.dy());
    let (hx, hy) = (0.5 * dx, 0.5 * dy);
    let (g, nu) = (material.shear_modulus(), material.poisson_ratio());
    let mut plan = SpectralConvolution::new(grid);
    let mut accumulated: Vec<Spectrum> = (0..3).map(|_| plan.zero_spectrum()).collect();
    let mut traction_spectrum = plan.zero_spectrum();
    let mut kernel_spectrum = plan.zero_spectrum();
    let mut quadrant = vec![[0.0; 3]; nx * ny];
    let mut component = vec![0.0; nx * ny];
    let sources = [
        Some(tractions.pressure),
        tractions.shear_x,
        tractions.shear_y,
    ];
    for (source, traction) in sources.iter().enumerate() {
        let Some(traction) = traction else { continue };
        plan.input_spectrum(traction, &mut traction_spectrum);
        quadrant
            .par_chunks_mut(nx)
            .enumerate()
            .for_each(|(dj, row)| {
                let y = dj as f64 * dy;
                for (di, value) in row.iter_mut().enumerate() {
                    let x = di as f64 * dx;
                    *value = match source {
                        0 => love::pressure_displacement(x, y, hx, hy, g, nu),
                        1 => love::shear_x_displacement(x, y, hx, hy, g, nu),
                        _ => love::shear_y_displacement(x, y, hx, hy, g, nu),
                    };
                }
            });
        for (c, acc) in accumulated.iter_mut().enumerate() {
            component
                .par_iter_mut()
                .zip(quadrant.par_iter())
                .for_each(|(v, u)| *v = u[c]);
            fill_kernel_table(
                &component,
                nx,
                ny,
                DISPLACEMENT_PARITY[source][c],
                plan.kernel_table(),
            );
            plan.kernel_spectrum(&mut kernel_spectrum);
            acc.add_product(&kernel_spectrum, &traction_spectrum);
        }
    }
    let mut out: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; nx * ny]);
    for (acc, u) in accumulated.iter_mut().zip(out.iter_mut()) {
        plan.inverse_into(acc, u);
    }
    let [x, y, z] = out;
    Ok(SurfaceDisplacement { x, y, z })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::SurfaceGrid;

    /// Against the direct O(N^2) sum of the same rectangle solutions, on a non-square grid
    /// with three different traction patterns (a wrong parity of any of the nine kernels
    /// changes the result at O(1)): round-off, 1e-12 of the largest displacement.
    #[test]
    fn one_call_equals_the_direct_sum_of_all_nine_responses() {
        let grid = SurfaceGrid::centred(13, 9, 1e-3, 0.7e-3).unwrap();
        let (nx, ny) = (grid.nx(), grid.ny());
        let n = nx * ny;
        let p: Vec<f64> = (0..n).map(|k| 1e8 * (1.0 + (k % 5) as f64)).collect();
        let qx: Vec<f64> = (0..n).map(|k| 3e7 * ((k % 7) as f64 - 3.0)).collect();
        let qy: Vec<f64> = (0..n).map(|k| -2e7 * ((k % 3) as f64 + 0.5)).collect();
        let steel = ElasticMaterial::new(2.1e11, 0.3).unwrap();
        let tractions = SurfaceTractions {
            grid: &grid,
            pressure: &p,
            shear_x: Some(&qx),
            shear_y: Some(&qy),
        };
        let u = surface_displacement(&tractions, &steel).unwrap();
        let (g, nu) = (steel.shear_modulus(), steel.poisson_ratio());
        let (hx, hy) = (0.5 * grid.dx(), 0.5 * grid.dy());
        let mut expected = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
        for i in 0..n {
            let mut sums = [0.0; 3];
            for j in 0..n {
                let x = grid.x(i % nx) - grid.x(j % nx);
                let y = grid.y(i / nx) - grid.y(j / nx);
                let up = love::pressure_displacement(x, y, hx, hy, g, nu);
                let ux = love::shear_x_displacement(x, y, hx, hy, g, nu);
                let uy = love::shear_y_displacement(x, y, hx, hy, g, nu);
                for (c, sum) in sums.iter_mut().enumerate() {
                    *sum += up[c] * p[j] + ux[c] * qx[j] + uy[c] * qy[j];
                }
            }
            for (e, sum) in expected.iter_mut().zip(sums) {
                e[i] = sum;
            }
        }
        let scale = expected
            .iter()
            .flatten()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        for (computed, reference) in [&u.x, &u.y, &u.z].iter().zip(&expected) {
            for (a, b) in computed.iter().zip(reference) {
                assert!((a - b).abs() <= 1e-12 * scale, "{a:e} vs {b:e}");
            }
        }
    }

    /// Bad tractions are an error naming the field.
    #[test]
    fn wrong_lengths_are_errors() {
        let grid = SurfaceGrid::centred(4, 4, 1e-3, 1e-3).unwrap();
        let p = vec![0.0; 15];
        let steel = ElasticMaterial::new(2.1e11, 0.3).unwrap();
        let t = SurfaceTractions {
            grid: &grid,
            pressure: &p,
            shear_x: None,
            shear_y: None,
        };
        let e = surface_displacement(&t, &steel).unwrap_err();
        assert!(e.to_string().starts_with("pressure"), "{e}");
    }
}
