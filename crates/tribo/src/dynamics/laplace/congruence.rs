//! Congruent regions (issue 13 "Speed"): a region that is a translate of an earlier one,
//! with the same elements, node numbering and dynamic kernel, has the same Laplace-domain
//! operators H(s), G(s): both depend only on the differences of the points (the kernels
//! are functions of r = x - y, the static rigid-body blocks of the element geometry) and
//! on the material. [`LaplaceBem`](super::LaplaceBem) then assembles the operators once
//! per frequency and uses them for both regions (the two strips of an impact: half the
//! assembly, and one LU for both bodies where their boundary conditions agree).
//!
//! The test is exact up to the rounding of the coordinates: every geometry point and
//! collocation point of the later region, minus the translation (the difference of the
//! first collocation points), equals the earlier region's within [`CONGRUENCE_ULPS`] ulps of
//! the largest coordinate; the element structure (node indices, functional-node
//! positions) must be equal, the kernels (material, density, plane condition) bit for bit.
//! Within that rounding the shared operators equal the region's own to the element
//! quadrature's rule-switch differences (the Gauss rule is picked by distance/length ratios
//! that a uniform mesh puts on the thresholds, where the rounding decides): ~4e-11 of the
//! transfer matrix (congruence_tests.rs).

use crate::dynamics::kernel::LaplaceKelvin2d;
use crate::operators::bem2d::mesh::RegionMesh;

/// The geometric tolerance of the congruence test, in units of the rounding of the
/// largest coordinate (f64::EPSILON times it): a mesh generated from translated segment
/// ends differs from the translate by a few ulps (the subdivision's `a + t (b - a)`).
pub(super) const CONGRUENCE_ULPS: f64 = 32.0;

/// Whether `b` is `a` translated (module docs), with the kernels `ka`, `kb`.
pub(super) fn congruent(
    a: &RegionMesh,
    ka: &LaplaceKelvin2d,
    b: &RegionMesh,
    kb: &LaplaceKelvin2d,
) -> bool {
    if ka != kb
        || a.body_force.is_some()
        || b.body_force.is_some()
        || a.nodes.len() != b.nodes.len()
        || a.local_elements.len() != b.local_elements.len()
        || a.local_positions.len() != b.local_positions.len()
        || a.local_positions.is_empty()
    {
        return false;
    }
    let (pa, pb) = (a.local_positions[0], b.local_positions[0]);
    let t = [pb[0] - pa[0], pb[1] - pa[1]];
    let mut largest = 0.0_f64;
    let points_a = a
        .local_elements
        .iter()
        .flat_map(|e| e.geometry.iter())
        .chain(&a.local_positions);
    let points_b = b
        .local_elements
        .iter()
        .flat_map(|e| e.geometry.iter())
        .chain(&b.local_positions);
    for p in points_a.clone().chain(points_b.clone()) {
        largest = largest.max(p[0].abs()).max(p[1].abs());
    }
    if !largest.is_finite() {
        return false;
    }
    let tol = CONGRUENCE_ULPS * f64::EPSILON * largest;
    let structure = a
        .local_elements
        .iter()
        .zip(&b.local_elements)
        .all(|(ea, eb)| ea.nodes == eb.nodes && ea.local == eb.local);
    structure
        && points_a
            .zip(points_b)
            .all(|(p, q)| (q[0] - t[0] - p[0]).abs() <= tol && (q[1] - t[1] - p[1]).abs() <= tol)
}

/// For each region the index of the first region it is congruent to (itself where none
/// is): the region whose operators it uses.
pub(super) fn operator_sources(regions: &[RegionMesh], kernels: &[LaplaceKelvin2d]) -> Vec<usize> {
    let mut source: Vec<usize> = Vec::with_capacity(regions.len());
    for (r, region) in regions.iter().enumerate() {
        let s = (0..r)
            .filter(|&q| source[q] == q)
            .find(|&q| congruent(&regions[q], &kernels[q], region, &kernels[r]))
            .unwrap_or(r);
        source.push(s);
    }
    source
}
