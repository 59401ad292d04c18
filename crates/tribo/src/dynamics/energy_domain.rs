//! Strain and kinetic energy of the bodies of a linear dynamic run from interior
//! evaluation on a triangulation (issue 13: the energy balance; docs/theory/DYNAMICS.md
//! sec. 5.8):
//!
//! ```text
//! U(t) = 1/2 int_A sigma : eps dA,     K(t) = 1/2 int_A rho |v|^2 dA     (J/m per unit thickness)
//! ```
//!
//! with sigma : eps = s_xx e_xx + s_yy e_yy + 2 s_xy e_xy (tensor shear strain; the
//! out-of-plane term s_zz e_zz is 0 in plane strain, e_zz = 0, and in plane stress,
//! s_zz = 0). The stress and velocity are given at the nodes of a triangulation of each
//! body (in the case: the field triangulation's nodes, the boundary nodes 1 % inside), the
//! strain by the region's Hooke's law.
//!
//! **Quadrature.** Each factor is interpolated linearly on each triangle and the product of
//! the two interpolants is integrated exactly (the linear triangle's consistent mass
//! matrix `int N_i N_j dA = A (1 + delta_ij) / 12`, from the area-coordinate integral
//! `int L1^a L2^b L3^c dA = 2 A a! b! c! / (a + b + c + 2)!`). The form is symmetric and non-negative (U and K are sums of
//! squares), so U >= 0 and K >= 0 whatever the data. Its error is the interpolation error:
//! for a smooth field O(h^2) relative (h the triangle size); at a wave front (a jump in
//! stress and velocity) the interpolants smear the jump over one triangle, an error of the
//! order of the front length times h times the jump's energy density, relative O(h / (c t))
//! for a front that has run c t. On a curved boundary the triangulation's polygon misses
//! area O(h^2 / R) relative (R the radius of curvature).
//!
//! **Near the boundary.** The stresses come from the Somigliana identity at interior points
//! (docs/theory/DYNAMICS.md sec. 5.5): its element integrals are nearly singular for a
//! point at a distance d much smaller than the element length l from the boundary. The static
//! interior rule subdivides those elements adaptively, and the Laplace-domain differences
//! (bounded kernels) need no care; the test
//! `near_boundary_stress_is_uniform_across_the_column` checks the band d / l from 0.5 down
//! to 1e-3 against the 1D column's uniform stress.

use crate::error::{Error, Result};

/// One triangulated body for the domain integrals: its triangles (node indices into the
/// body's own node list) with their areas, the node count and the density.
#[derive(Debug, Clone, PartialEq)]
pub struct EnergyMesh {
    triangles: Vec<([usize; 3], f64)>,
    nodes: usize,
    density: f64,
}

impl EnergyMesh {
    /// The mesh of a body with the nodes `nodes` (m) and the triangles `triangles`
    /// (counter-clockwise or not: the areas are taken absolute), density `density` (kg/m^3).
    ///
    /// Errors ([`Error::InvalidParameter`]): a node index out of range, a degenerate
    /// triangle (zero area), a non-finite node, a density not finite or not > 0.
    pub fn new(nodes: &[[f64; 2]], triangles: &[[usize; 3]], density: f64) -> Result<Self> {
        if !(density.is_finite() && density > 0.0) {
            return Err(Error::invalid(
                "energy.density",
                format!("{density:e} kg/m^3"),
                "must be finite and > 0",
            ));
        }
        if let Some(p) = nodes
            .iter()
            .find(|p| !(p[0].is_finite() && p[1].is_finite()))
        {
            return Err(Error::invalid(
                "energy.nodes",
                format!("{p:?}"),
                "must be finite",
            ));
        }
        let mut out = Vec::with_capacity(triangles.len());
        for (k, t) in triangles.iter().enumerate() {
            if t.iter().any(|&i| i >= nodes.len()) {
                return Err(Error::invalid(
                    format!("energy.triangles[{k}]"),
                    format!("{t:?}"),
                    format!("node indices must be below the node count {}", nodes.len()),
                ));
            }
            let [a, b, c] = [nodes[t[0]], nodes[t[1]], nodes[t[2]]];
            let area = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])).abs();
            if area <= 0.0 {
                return Err(Error::invalid(
                    format!("energy.triangles[{k}]"),
                    format!("{t:?}"),
                    "must have a positive area",
                ));
            }
            out.push((*t, area));
        }
        Ok(Self {
            triangles: out,
            nodes: nodes.len(),
            density,
        })
    }

    /// The node count.
    pub fn node_count(&self) -> usize {
        self.nodes
    }

    /// The area of the triangulation, m^2 (per unit thickness).
    pub fn area(&self) -> f64 {
        self.triangles.iter().map(|(_, a)| a).sum()
    }

    /// `sum_tri A/12 sum_(i,j) (1 + delta_ij) f(n_i, n_j)`: the exact integral of the
    /// product of the linear interpolants when `f(p, q)` is the product of the nodal
    /// values at p and q (module docs).
    fn form(&self, f: impl Fn(usize, usize) -> f64) -> f64 {
        let mut sum = 0.0;
        for (t, area) in &self.triangles {
            let mut s = 0.0;
            for (i, &p) in t.iter().enumerate() {
                for (j, &q) in t.iter().enumerate() {
                    s += if i == j { 2.0 } else { 1.0 } * f(p, q);
                }
            }
            sum += area / 12.0 * s;
        }
        sum
    }

    fn check(&self, what: &str, n: usize) -> Result<()> {
        if n != self.nodes {
            return Err(Error::invalid(
                format!("energy.{what}"),
                format!("{n} values"),
                format!("needs one value per mesh node ({})", self.nodes),
            ));
        }
        Ok(())
    }

    /// The strain energy `U = 1/2 int sigma : eps dA` (J/m) of the nodal stresses
    /// `stress` (`[s_xx, s_yy, s_xy]`, Pa) and strains `strain` (`[e_xx, e_yy, e_xy]`,
    /// tensor shear), module docs.
    ///
    /// Errors: a count other than the node count ([`Error::InvalidParameter`]).
    pub fn strain_energy(&self, stress: &[[f64; 3]], strain: &[[f64; 3]]) -> Result<f64> {
        self.check("stress", stress.len())?;
        self.check("strain", strain.len())?;
        Ok(0.5
            * self.form(|p, q| {
                let (s, e) = (stress[p], strain[q]);
                s[0] * e[0] + s[1] * e[1] + 2.0 * s[2] * e[2]
            }))
    }

    /// The kinetic energy `K = 1/2 int rho |v|^2 dA` (J/m) of the nodal velocities
    /// `velocity` (m/s), module docs.
    ///
    /// Errors: a count other than the node count ([`Error::InvalidParameter`]).
    pub fn kinetic_energy(&self, velocity: &[[f64; 2]]) -> Result<f64> {
        self.check("velocity", velocity.len())?;
        Ok(0.5
            * self.density
            * self.form(|p, q| velocity[p][0] * velocity[q][0] + velocity[p][1] * velocity[q][1]))
    }
}

/// The worst energy balance of a run relative to its largest input work:
/// `max_n |W_n - U_n - K_n - D_n| / max_n W_n` (D = 0 where `dissipation` is empty) and
/// the time of the worst, or None without input work (max W = 0) or with series of
/// unequal lengths. `times` s, the energies J/m.
pub fn worst_balance(
    times: &[f64],
    input_work: &[f64],
    strain: &[f64],
    kinetic: &[f64],
    dissipation: &[f64],
) -> Option<(f64, f64)> {
    let n = times.len();
    if input_work.len() != n
        || strain.len() != n
        || kinetic.len() != n
        || !(dissipation.is_empty() || dissipation.len() == n)
    {
        return None;
    }
    let w_max = input_work.iter().fold(0.0_f64, |m, &w| m.max(w));
    if w_max <= 0.0 {
        return None;
    }
    let mut worst = (0.0, times.first().copied().unwrap_or(0.0));
    for k in 0..n {
        let d = dissipation.get(k).copied().unwrap_or(0.0);
        let b = (input_work[k] - strain[k] - kinetic[k] - d).abs() / w_max;
        if b > worst.0 {
            worst = (b, times[k]);
        }
    }
    Some(worst)
}

#[cfg(test)]
#[path = "energy_domain_tests.rs"]
mod tests;
