//! Dense assembly of the collocation matrices H and G of each region.
//!
//! For every functional node i of a region (collocation point p_i) the discretized direct
//! boundary integral equation (Brebbia & Dominguez eq. 5.41; the paper's operators (10) with
//! the Kelvin influence functions) reads
//!
//! ```text
//! c_ij(p_i) u_j(p_i) + sum_e sum_k [int_e T_ij N_k dG] u_j^k = sum_e sum_k [int_e U_ij N_k dG] t_j^k
//! ```
//!
//! i.e. `H u = G t` with H including the free term. The diagonal 2x2 blocks of H (c_ij plus
//! the strongly singular integrals) come from rigid-body translation, H 1 = 0 for a bounded
//! region: H_ii = -sum_{j != i} H_ij (Brebbia & Dominguez sec. 5.7). Rows of node pairs are
//! independent and are assembled in parallel (rayon).

// Index loops read like the tensor formulas they implement.
#![allow(clippy::needless_range_loop)]

use faer::Mat;
use rayon::prelude::*;

use super::integrate::element_hg;
use super::mesh::{BemMesh, RegionMesh};

/// The collocation matrices of one region: 2n x 2n for n functional nodes, DOF 2 i + d for
/// node i and direction d (0 = x, 1 = y), row 2 i + d the equation collocated at node i in
/// direction d. `h * u = g * t` holds for the region's nodal displacements u and tractions t.
#[derive(Debug, Clone)]
pub struct RegionOperators {
    /// H (dimensionless), including the free term.
    pub h: Mat<f64>,
    /// G (m/Pa).
    pub g: Mat<f64>,
}

/// Assembles H and G of every region of `mesh`.
pub fn assemble(mesh: &BemMesh) -> Vec<RegionOperators> {
    mesh.regions.iter().map(assemble_region).collect()
}

/// Assembles H and G of one region.
pub fn assemble_region(region: &RegionMesh) -> RegionOperators {
    let n = region.nodes.len();
    let dof = 2 * n;
    // For each node: its two H rows then its two G rows, row-major.
    let rows: Vec<Vec<f64>> = (0..n)
        .into_par_iter()
        .map(|i| {
            let p = region.nodes[i].position;
            let mut buf = vec![0.0; 4 * dof];
            for e in &region.elements {
                let singular = e.nodes.iter().position(|&m| m == i);
                let (h, g) = element_hg(&region.kernels, e, p, singular);
                for (k, &m) in e.nodes.iter().enumerate() {
                    for a in 0..2 {
                        for b in 0..2 {
                            buf[a * dof + 2 * m + b] += h[a][2 * k + b];
                            buf[(2 + a) * dof + 2 * m + b] += g[a][2 * k + b];
                        }
                    }
                }
            }
            // Rigid-body translation: the diagonal block closes the row sums of H.
            for a in 0..2 {
                for b in 0..2 {
                    let mut sum = 0.0;
                    for m in (0..n).filter(|&m| m != i) {
                        sum += buf[a * dof + 2 * m + b];
                    }
                    buf[a * dof + 2 * i + b] = -sum;
                }
            }
            buf
        })
        .collect();
    let h = Mat::from_fn(dof, dof, |r, c| rows[r / 2][(r % 2) * dof + c]);
    let g = Mat::from_fn(dof, dof, |r, c| rows[r / 2][(2 + r % 2) * dof + c]);
    RegionOperators { h, g }
}
