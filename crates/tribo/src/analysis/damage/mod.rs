//! Volume damageability: limiting values, relative damage, dangerous volumes and their
//! accumulation in time, the paper's (19)-(24) and (36) (seed paper Sec. 4; docs/theory/DESIGN.md part F).
//! Written once for 3D fields (the half-space grid, [`DamageMesh::from_field_grid`]) and 2D
//! plane fields (triangles, [`DamageMesh::triangles`], [`DamageMesh::structured_2d`]; plane
//! strain stress by [`plane_strain_stress`]; measures are areas per unit thickness).
//!
//! # The chain
//!
//! 1. A [`DamageQuantity`] phi_q (tensor component, principal value, normal or shear
//!    magnitude, intensity, energy, effective energy) and its [`Limit`] phi_q^lim, from
//!    material data ([`Limit::new`]) or as the extreme of a field under the limiting load
//!    ([`Limit::from_limiting_field`], (19)-(20)).
//! 2. psi_q = phi_q / phi_q^lim at every node (21) ([`relative_damage`]).
//! 3. The dangerous volume V_q = measure of {psi_q >= 1} (22), the damageability
//!    Psi_q = integral of psi_q over it and Psi_q / V_q (24) ([`dangerous_region`]).
//! 4. Their time integrals over a load cycle (23), (24), (36) ([`accumulate`],
//!    [`RotatingBentShaft`], [`RollingContact`]).
//!
//! # Exact integration over the part of a simplex where psi >= 1
//!
//! psi is interpolated linearly on each simplex (triangle or tetrahedron; the hexahedra of a
//! grid are split into 6 Kuhn tetrahedra, quadrilaterals into 2 triangles). With
//! g_i = psi_i - 1 at the d + 1 vertices, {psi >= 1} is the part of the simplex on one side of
//! the plane g = 0, which crosses the edge from vertex i (g_i >= 0) to vertex j (g_j < 0) at
//! the fraction t_ij = g_i / (g_i - g_j) of the edge from i. Two facts give everything in
//! closed form:
//!
//! - a simplex with vertices at barycentric coordinates b_0..b_d of the parent has the
//!   measure |det[b_0; ...; b_d]| times the parent's, so the corner simplex at vertex i cut
//!   off by the plane has the fraction prod_j t_ij (product over the other vertices j);
//! - the integral of a linear function over a simplex is its measure times the mean of the
//!   vertex values (and psi = 1 at every cut point).
//!
//! Hence, with |T| the simplex measure and k the number of vertices with psi >= 1:
//!
//! - k = d + 1: V = |T|, Psi = |T| mean(psi_i); k = 0: nothing;
//! - k = 1 (vertex p): V = |T| f, f = prod_{j != p} t_pj, Psi = V (psi_p + d) / (d + 1);
//! - k = d (vertex m below 1): the complement of the corner at m, f = prod_{j != m} t_mj:
//!   V = |T| (1 - f), Psi = |T| [mean(psi_i) - f (psi_m + d) / (d + 1)];
//! - k = 2 in a tetrahedron (a, b above, c, e below): a wedge with triangles (a, P_ac, P_ae)
//!   and (b, P_bc, P_be), split into the tetrahedra (a, P_ac, P_ae, P_be),
//!   (a, P_ac, P_bc, P_be), (a, b, P_bc, P_be), each measured by its barycentric
//!   determinant (P_ij = (1 - t_ij) e_i + t_ij e_j).
//!
//! The result is exact for a psi linear on each simplex (e.g. pure bending, any grid), and
//! for a smooth psi its error is that of linear interpolation, O(h^2): the method is
//! second-order, where all-or-nothing cell counting is first-order. Vertices with psi = 1
//! exactly count as inside, so a field equal to its limit everywhere has V equal to the whole
//! volume, as (22) (psi >= 1) says.
//!
//! Sums over cells are exactly rounded (Shewchuk's non-overlapping partials, as Python's
//! `math.fsum`), so V and Psi are the same bits whatever the cell order and serial or
//! parallel ([`Execution`]).
//!
//! # Closed form: a round shaft in pure bending
//!
//! A disc section of radius R with sigma_x = sigma_max y / R and the limit
//! sigma_lim = sigma_max / k (k > 1): psi = k y / R, and {psi >= 1} is the circular segment
//! y >= h = R / k. Per unit length of shaft
//!
//! ```text
//! A   = R^2 acos(h/R) - h sqrt(R^2 - h^2),
//! Psi = (k / R) integral over the segment of y dA = (k / R) (2/3) (R^2 - h^2)^(3/2),
//! ```
//!
//! (integral of y dA over the segment = integral from h to R of y 2 sqrt(R^2 - y^2) dy
//! = (2/3)(R^2 - h^2)^(3/2)); a length L of shaft has V = L A and Psi = L Psi per length.
//! The tests compare this with the integration on disc meshes and report the order.

mod cycle;
mod faces;
mod mesh;
pub mod probabilistic;
mod quantity;
mod study;
pub(crate) mod sum;
#[cfg(test)]
mod tests;

pub use cycle::{
    accumulate, accumulate_psi, trapezoid_weights, CycleDamage, CyclesDamage, LoadHistory,
    RollingContact, RotatingBentShaft, StateDamage,
};
pub use faces::{faces_reached, BoxFace};
pub use mesh::{dangerous_region, DamageMesh, DangerousRegion, Execution};
pub use quantity::{
    assess, plane_strain_stress, relative_damage, Component, DamageAssessment, DamageQuantity,
    Limit, PrincipalIndex, Sense, TensorKind,
};
pub use study::{
    roller_shaft_study, roller_shaft_sweep, RollerShaftStudy, StudyLoading, StudyResult,
};

/// Per unit length of a round shaft of radius `radius` (m) in pure bending with
/// sigma_x = sigma_max y / R and the limit sigma_max / `ratio` (`ratio` = k > 1): the area of
/// the dangerous segment (m^2) and the integral of psi over it (m^2); see the module docs.
pub fn bending_segment_closed_form(radius: f64, ratio: f64) -> (f64, f64) {
    let h = radius / ratio;
    let c = (radius * radius - h * h).max(0.0);
    let area = radius * radius * (h / radius).acos() - h * c.sqrt();
    let psi = ratio / radius * 2.0 / 3.0 * c.powf(1.5);
    (area, psi)
}
