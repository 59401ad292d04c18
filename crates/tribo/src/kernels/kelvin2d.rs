//! Kelvin's fundamental solution of 2D elastostatics (a line load in an infinite plane):
//! the displacement, traction and interior-stress kernels of the direct boundary integral
//! equation, in plane strain and plane stress.
//!
//! Source: Brebbia & Dominguez, *Boundary Elements: An Introductory Course* (2nd ed., 1992),
//! sec. 5.3 (U, T; eqs. 5.30-5.31 there) and sec. 5.6 (interior stress kernels D, S); Becker,
//! *The Boundary Element Method in Engineering* (1992), ch. 8. In the paper (see the crate docs) these
//! are the influence functions G of the surface operators L^(S,u) and L_sigma(L^(S,u)) of (10),
//! with the interior state (11) written as the Somigliana identity
//!
//! ```text
//! u_i(p)       = int_G U_ij(p,x) t_j(x) dG - int_G T_ij(p,x) u_j(x) dG
//! sigma_ij(p)  = int_G D_kij(p,x) t_k(x) dG - int_G S_kij(p,x) u_k(x) dG
//! ```
//!
//! Conventions: `p` is the source (load or collocation) point, `x` the field point on the
//! boundary, `r = x - p`, `r,i = r_i / |r|`, `n` the outward unit normal at `x`,
//! `dr/dn = r,i n_i`. Plane stress uses the plane-strain formulas with the effective Poisson
//! ratio `nu' = nu / (1 + nu)` and the same shear modulus (Brebbia & Dominguez sec. 5.3).

// Index loops read like the tensor formulas they implement.
#![allow(clippy::needless_range_loop)]

use std::f64::consts::PI;

use crate::error::{Error, Result};
use crate::material::ElasticMaterial;
use serde::{Deserialize, Serialize};

/// The 2D idealization: plane strain (thick bodies, eps_zz = 0) or plane stress (thin
/// plates, sigma_zz = 0).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum PlaneCondition {
    /// eps_zz = 0; sigma_zz = nu (sigma_xx + sigma_yy).
    Strain,
    /// sigma_zz = 0; eps_zz = -nu/E (sigma_xx + sigma_yy).
    Stress,
}

/// Kelvin's 2D fundamental solution for one material and plane condition.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kelvin2d {
    /// Shear modulus mu, Pa.
    mu: f64,
    /// Effective Poisson ratio: nu (plane strain) or nu/(1+nu) (plane stress).
    nu: f64,
    /// Poisson ratio of the material (for sigma_zz and eps_zz).
    nu_material: f64,
    plane: PlaneCondition,
}

impl Kelvin2d {
    /// The kernels of `material` under `plane`.
    pub fn new(material: &ElasticMaterial, plane: PlaneCondition) -> Self {
        let nu_material = material.poisson_ratio();
        let nu = match plane {
            PlaneCondition::Strain => nu_material,
            PlaneCondition::Stress => nu_material / (1.0 + nu_material),
        };
        Self {
            mu: material.shear_modulus(),
            nu,
            nu_material,
            plane,
        }
    }

    /// Shear modulus mu, Pa.
    pub fn shear_modulus(&self) -> f64 {
        self.mu
    }

    /// Effective Poisson ratio used in the kernels (nu, or nu/(1+nu) in plane stress).
    pub fn effective_poisson(&self) -> f64 {
        self.nu
    }

    /// The plane condition.
    pub fn plane(&self) -> PlaneCondition {
        self.plane
    }

    /// Displacement kernel U_ij (m per N/m): displacement in direction j at `p + r` due to a
    /// unit line load in direction i at `p`,
    /// `U_ij = [(3 - 4 nu) ln(1/r) delta_ij + r,i r,j] / (8 pi mu (1 - nu))`.
    pub fn displacement(&self, r: [f64; 2]) -> [[f64; 2]; 2] {
        let rr = r[0].hypot(r[1]);
        let d = [r[0] / rr, r[1] / rr];
        let c = 1.0 / (8.0 * PI * self.mu * (1.0 - self.nu));
        let log = -(3.0 - 4.0 * self.nu) * rr.ln();
        let mut u = [[0.0; 2]; 2];
        for (i, row) in u.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = c * (if i == j { log } else { 0.0 } + d[i] * d[j]);
            }
        }
        u
    }

    /// Traction kernel T_ij (1/m): traction in direction j on a surface of outward normal `n`
    /// at `p + r` due to a unit line load in direction i at `p`,
    /// `T_ij = -[dr/dn ((1 - 2nu) delta_ij + 2 r,i r,j) - (1 - 2nu)(r,i n_j - r,j n_i)]
    ///         / (4 pi (1 - nu) r)`.
    pub fn traction(&self, r: [f64; 2], n: [f64; 2]) -> [[f64; 2]; 2] {
        let rr = r[0].hypot(r[1]);
        let d = [r[0] / rr, r[1] / rr];
        let drdn = d[0] * n[0] + d[1] * n[1];
        let a = 1.0 - 2.0 * self.nu;
        let c = -1.0 / (4.0 * PI * (1.0 - self.nu) * rr);
        let mut t = [[0.0; 2]; 2];
        for (i, row) in t.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                let delta = if i == j { 1.0 } else { 0.0 };
                *v = c * (drdn * (a * delta + 2.0 * d[i] * d[j]) - a * (d[i] * n[j] - d[j] * n[i]));
            }
        }
        t
    }

    /// Interior stress kernel D_kij (1/m): stress sigma_ij at `p` due to a unit traction in
    /// direction k at `p + r`,
    /// `D_kij = [(1 - 2nu)(delta_ki r,j + delta_kj r,i - delta_ij r,k) + 2 r,i r,j r,k]
    ///          / (4 pi (1 - nu) r)`. Indexed `[k][i][j]`.
    pub fn stress_from_traction(&self, r: [f64; 2]) -> [[[f64; 2]; 2]; 2] {
        let rr = r[0].hypot(r[1]);
        let d = [r[0] / rr, r[1] / rr];
        let a = 1.0 - 2.0 * self.nu;
        let c = 1.0 / (4.0 * PI * (1.0 - self.nu) * rr);
        let delta = |a: usize, b: usize| if a == b { 1.0 } else { 0.0 };
        let mut out = [[[0.0; 2]; 2]; 2];
        for (k, plane) in out.iter_mut().enumerate() {
            for (i, row) in plane.iter_mut().enumerate() {
                for (j, v) in row.iter_mut().enumerate() {
                    *v = c
                        * (a * (delta(k, i) * d[j] + delta(k, j) * d[i] - delta(i, j) * d[k])
                            + 2.0 * d[i] * d[j] * d[k]);
                }
            }
        }
        out
    }

    /// Interior stress kernel S_kij (Pa/m): stress sigma_ij at `p` due to a unit displacement
    /// discontinuity in direction k at `p + r` on a surface of outward normal `n`
    /// (Brebbia & Dominguez sec. 5.6):
    /// `S_kij = mu / (2 pi (1 - nu) r^2) { 2 dr/dn [(1-2nu) delta_ij r,k + nu (delta_ik r,j +
    /// delta_jk r,i) - 4 r,i r,j r,k] + 2 nu (n_i r,j r,k + n_j r,i r,k) + (1-2nu)(2 n_k r,i r,j +
    /// n_j delta_ik + n_i delta_jk) - (1-4nu) n_k delta_ij }`. Indexed `[k][i][j]`.
    pub fn stress_from_displacement(&self, r: [f64; 2], n: [f64; 2]) -> [[[f64; 2]; 2]; 2] {
        let rr = r[0].hypot(r[1]);
        let d = [r[0] / rr, r[1] / rr];
        let drdn = d[0] * n[0] + d[1] * n[1];
        let nu = self.nu;
        let a = 1.0 - 2.0 * nu;
        let c = self.mu / (2.0 * PI * (1.0 - nu) * rr * rr);
        let delta = |a: usize, b: usize| if a == b { 1.0 } else { 0.0 };
        let mut out = [[[0.0; 2]; 2]; 2];
        for (k, plane) in out.iter_mut().enumerate() {
            for (i, row) in plane.iter_mut().enumerate() {
                for (j, v) in row.iter_mut().enumerate() {
                    *v = c
                        * (2.0
                            * drdn
                            * (a * delta(i, j) * d[k]
                                + nu * (delta(i, k) * d[j] + delta(j, k) * d[i])
                                - 4.0 * d[i] * d[j] * d[k])
                            + 2.0 * nu * (n[i] * d[j] * d[k] + n[j] * d[i] * d[k])
                            + a * (2.0 * n[k] * d[i] * d[j]
                                + n[j] * delta(i, k)
                                + n[i] * delta(j, k))
                            - (1.0 - 4.0 * nu) * n[k] * delta(i, j));
                }
            }
        }
        out
    }

    /// In-plane strain [eps_xx, eps_yy, eps_xy] (tensor shear) from in-plane stress
    /// [s_xx, s_yy, s_xy]: eps_ij = (sigma_ij - nu' delta_ij sigma_kk) / (2 mu), valid in both
    /// plane conditions with the effective ratio nu'.
    pub fn strain_from_stress(&self, s: [f64; 3]) -> [f64; 3] {
        let tr = s[0] + s[1];
        let g2 = 2.0 * self.mu;
        [
            (s[0] - self.nu * tr) / g2,
            (s[1] - self.nu * tr) / g2,
            s[2] / g2,
        ]
    }

    /// Out-of-plane stress sigma_zz: nu (s_xx + s_yy) in plane strain, 0 in plane stress.
    pub fn sigma_zz(&self, sxx: f64, syy: f64) -> f64 {
        match self.plane {
            PlaneCondition::Strain => self.nu_material * (sxx + syy),
            PlaneCondition::Stress => 0.0,
        }
    }

    /// Out-of-plane strain eps_zz: 0 in plane strain, -nu/E (s_xx + s_yy) in plane stress.
    pub fn eps_zz(&self, sxx: f64, syy: f64) -> f64 {
        match self.plane {
            PlaneCondition::Strain => 0.0,
            PlaneCondition::Stress => {
                let e = 2.0 * self.mu * (1.0 + self.nu_material);
                -self.nu_material / e * (sxx + syy)
            }
        }
    }

    /// Tangential stress sigma_tt on a boundary from the tangential strain eps_tt and the
    /// normal stress sigma_nn (Hooke's law in the boundary frame):
    /// `sigma_tt = (2 mu eps_tt + nu' sigma_nn) / (1 - nu')`.
    pub fn tangential_stress(&self, eps_tt: f64, sigma_nn: f64) -> f64 {
        (2.0 * self.mu * eps_tt + self.nu * sigma_nn) / (1.0 - self.nu)
    }
}

/// Checks that a point is finite; the error names `field`.
pub(crate) fn finite_point(field: &str, p: [f64; 2]) -> Result<()> {
    if p[0].is_finite() && p[1].is_finite() {
        Ok(())
    } else {
        Err(Error::invalid(
            field,
            format!("({}, {})", p[0], p[1]),
            "coordinates must be finite",
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kernels(plane: PlaneCondition) -> Kelvin2d {
        Kelvin2d::new(&ElasticMaterial::new(2.1e11, 0.3).unwrap(), plane)
    }

    /// Stress at `x` of the displacement field u_j(x) = U_ij(x - p) (load direction i), from
    /// central differences and Hooke's law with the effective ratio.
    fn fd_stress_of_u(k: &Kelvin2d, i: usize, r: [f64; 2]) -> [[f64; 2]; 2] {
        let h = 1e-6;
        let mut grad = [[0.0; 2]; 2]; // grad[j][m] = d u_j / d x_m
        for m in 0..2 {
            let mut rp = r;
            let mut rm = r;
            rp[m] += h;
            rm[m] -= h;
            let up = k.displacement(rp);
            let um = k.displacement(rm);
            for j in 0..2 {
                grad[j][m] = (up[i][j] - um[i][j]) / (2.0 * h);
            }
        }
        let nu = k.effective_poisson();
        let lambda = 2.0 * k.shear_modulus() * nu / (1.0 - 2.0 * nu);
        let div = grad[0][0] + grad[1][1];
        let mut s = [[0.0; 2]; 2];
        for a in 0..2 {
            for b in 0..2 {
                s[a][b] = k.shear_modulus() * (grad[a][b] + grad[b][a])
                    + if a == b { lambda * div } else { 0.0 };
            }
        }
        s
    }

    /// T_ij is the traction of the stress field of U_i. (i: load direction.)
    #[test]
    fn traction_kernel_is_the_traction_of_the_displacement_kernel() {
        for plane in [PlaneCondition::Strain, PlaneCondition::Stress] {
            let k = kernels(plane);
            for (r, n) in [
                ([0.7, -0.4], [0.6, 0.8]),
                ([-0.3, 0.9], [-1.0, 0.0]),
                ([1.2, 0.5], [0.0, 1.0]),
            ] {
                let t = k.traction(r, n);
                for i in 0..2 {
                    let s = fd_stress_of_u(&k, i, r);
                    for j in 0..2 {
                        let fd = s[j][0] * n[0] + s[j][1] * n[1];
                        // Central differences with h = 1e-6 on an O(1) field: error ~1e-9
                        // relative; 1e-6 leaves room for round-off in the difference.
                        assert!(
                            (t[i][j] - fd).abs() < 1e-6 * t[i][j].abs().max(0.1),
                            "{plane:?} T[{i}][{j}] = {} vs FD {fd}",
                            t[i][j]
                        );
                    }
                }
            }
        }
    }

    /// D_kij and S_kij are the stresses at the source point of the Somigliana densities
    /// U_ik and T_ik: D_kij = lambda' delta_ij dU_mk/dp_m + mu (dU_ik/dp_j + dU_jk/dp_i),
    /// likewise S from T (derivatives with respect to the source point p, i.e. -d/dr).
    #[test]
    fn stress_kernels_are_source_derivatives_of_u_and_t() {
        for plane in [PlaneCondition::Strain, PlaneCondition::Stress] {
            let k = kernels(plane);
            let nu = k.effective_poisson();
            let mu = k.shear_modulus();
            let lambda = 2.0 * mu * nu / (1.0 - 2.0 * nu);
            for (r, n) in [([0.7, -0.4], [0.6, 0.8]), ([-0.3, 0.9], [0.0, -1.0])] {
                let h = 1e-6;
                // dU[m][i][k] = dU_ik / dp_m = -dU_ik/dr_m
                let mut du = [[[0.0; 2]; 2]; 2];
                let mut dt = [[[0.0; 2]; 2]; 2];
                for m in 0..2 {
                    let mut rp = r;
                    let mut rm = r;
                    rp[m] += h;
                    rm[m] -= h;
                    let (up, um) = (k.displacement(rp), k.displacement(rm));
                    let (tp, tm) = (k.traction(rp, n), k.traction(rm, n));
                    for i in 0..2 {
                        for kk in 0..2 {
                            du[m][i][kk] = -(up[i][kk] - um[i][kk]) / (2.0 * h);
                            dt[m][i][kk] = -(tp[i][kk] - tm[i][kk]) / (2.0 * h);
                        }
                    }
                }
                let d = k.stress_from_traction(r);
                let s = k.stress_from_displacement(r, n);
                for kk in 0..2 {
                    for i in 0..2 {
                        for j in 0..2 {
                            let delta = if i == j { 1.0 } else { 0.0 };
                            let fd_d = lambda * delta * (du[0][0][kk] + du[1][1][kk])
                                + mu * (du[j][i][kk] + du[i][j][kk]);
                            let fd_s = lambda * delta * (dt[0][0][kk] + dt[1][1][kk])
                                + mu * (dt[j][i][kk] + dt[i][j][kk]);
                            // Same finite-difference budget as above, scaled by mu for S.
                            assert!(
                                (d[kk][i][j] - fd_d).abs() < 1e-6 * d[kk][i][j].abs().max(0.1),
                                "{plane:?} D[{kk}][{i}][{j}] {} vs {fd_d}",
                                d[kk][i][j]
                            );
                            assert!(
                                (s[kk][i][j] - fd_s).abs() < 1e-6 * mu,
                                "{plane:?} S[{kk}][{i}][{j}] {} vs {fd_s}",
                                s[kk][i][j]
                            );
                        }
                    }
                }
            }
        }
    }
}
