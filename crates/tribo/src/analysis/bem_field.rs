//! Fields of a solved 2D BEM model on a triangle mesh of a region's interior: for field
//! output (VTK, PNG) and for the damage layer ([`crate::analysis::damage`]).
//!
//! # Triangulation ([`triangulate_region`])
//!
//! The region's boundary is sampled on its quadratic elements: each element at
//! m = max(2, ceil(L_e / h)) points equally spaced in its local coordinate xi (L_e its chord
//! length, h the target size), so at its three geometric nodes where h >= L_e / 2 and finer
//! where the elements are long compared with h; every boundary vertex lies exactly on an
//! element (x(xi) of [`crate::operators::bem2d::Element::point`]). The closed polygons (the
//! outer loop and the holes) are the constraint edges of a constrained Delaunay
//! triangulation refined by Ruppert's algorithm (the `spade` crate; Ruppert, J. Algorithms
//! 18 (1995) 548; Shewchuk, Comput. Geom. 22 (2002) 21) with
//!
//! - a minimum angle of [`MIN_ANGLE_DEG`] (circumradius to shortest edge ratio
//!   1 / (2 sin 25 deg) = 1.18) and
//! - a maximum area sqrt(3)/4 h^2 (the equilateral triangle of edge h),
//!
//! so that interior triangles have edges of about h (measured in the tests: a mean edge of
//! 0.83 h, the longest 1.34 h). Triangles outside the outer loop or inside a hole are dropped. The
//! constraint edges are kept (never split), so no vertex is ever added on a chord between
//! two boundary samples, where it would lie off the curved boundary (outside the region on
//! a hole's arc); Ruppert's refinement inserts no circumcentre that encroaches a kept
//! constraint edge, so every added vertex is strictly inside the polygon and outside every
//! chord's diametral circle, hence inside the region.
//!
//! Grading: no explicit grading. Where the boundary elements are shorter than h (e.g. graded
//! toward a contact zone) the boundary samples are as dense as the elements' geometric nodes
//! and the angle bound grades the triangles from that spacing to h over a few layers.
//!
//! Area: the triangulation's area is that of the sampled polygon, to round-off. It differs
//! from the area enclosed by the quadratic elements by the parabolic segments between each
//! boundary chord and its element: for a chord over xi in [xi_a, xi_a + D] the signed
//! segment area is (x'(xi) x x'') D^3 / 12 (x'' = x_1 - 2 x_2 + x_3 is constant and
//! x' x x'' is independent of xi on a parabola; Archimedes' quadrature of the parabola),
//! about L h^2 / (12 R) for a boundary of length L and radius of curvature R.
//!
//! # Sampling ([`sample_region`])
//!
//! Displacement, stress (Somigliana identities, the paper's (11)) and strain at given points
//! of one known region, rayon-parallel over the points. Points on the boundary or closer to
//! it than [`crate::solvers::bem2d::BOUNDARY_LAYER`] of an element length are evaluated at
//! that distance inside (see [`crate::solvers::bem2d`]). Each point is independent, so
//! serial and parallel give the same bits.

use rayon::prelude::*;
use spade::handles::{FixedFaceHandle, InnerTag};
use spade::{
    AngleLimit, ConstrainedDelaunayTriangulation, Point2, RefinementParameters, Triangulation,
};
use std::collections::HashSet;

use crate::analysis::damage::sum::ExactSum;
use crate::analysis::damage::{DamageMesh, Execution};
use crate::error::{Error, Result};
use crate::operators::bem2d::{BemMesh, Element, RegionMesh};
use crate::solvers::bem2d::{BemSolution, Strain2d, Stress2d};

/// Largest number of triangles [`triangulate_region`] will make (estimated from the region's
/// area and the target size before triangulating): 2e6 triangles, about 1e6 nodes, is
/// about 100 MB of nodes, triangles and field samples and, at tens of microseconds per BEM
/// interior evaluation, already minutes of sampling.
pub const MAX_TRIANGLES: usize = 2_000_000;

/// Minimum angle of the refinement, degrees. Ruppert's algorithm terminates for bounds up to
/// about 20.7 deg in theory and in practice up to about 33 deg; 25 deg leaves margin and still
/// bounds the linear-interpolation constants of the damage integration.
pub const MIN_ANGLE_DEG: f64 = 25.0;

/// A triangle mesh of one region's interior.
#[derive(Debug, Clone, PartialEq)]
pub struct RegionTriangulation {
    /// Index of the region in [`BemMesh::regions`].
    pub region: usize,
    /// Node coordinates (x, y), m: first the boundary samples, loop by loop (outer loop
    /// first, each loop in the region's traversal direction), then the interior nodes.
    pub nodes: Vec<[f64; 2]>,
    /// Counter-clockwise triangles (indices into `nodes`).
    pub triangles: Vec<[usize; 3]>,
    /// Number of boundary nodes: `nodes[..boundary_nodes]` lie on the region's boundary
    /// elements, the rest inside.
    pub boundary_nodes: usize,
}

impl RegionTriangulation {
    /// Total area of the triangles, m^2 (per unit thickness).
    pub fn area(&self) -> f64 {
        let mut s = ExactSum::default();
        for t in &self.triangles {
            s.add(signed_area(
                self.nodes[t[0]],
                self.nodes[t[1]],
                self.nodes[t[2]],
            ));
        }
        s.value()
    }

    /// The triangles as a [`DamageMesh`] (for [`crate::analysis::damage::dangerous_region`]).
    pub fn damage_mesh(&self) -> Result<DamageMesh> {
        DamageMesh::triangles(self.nodes.clone(), self.triangles.clone())
    }
}

fn signed_area(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The region's elements split into closed loops (outer loop first, then the holes, as the
/// mesh stores them): a loop ends at the element whose end meets the loop's first element's
/// start (within the mesh's closure tolerance, 1e-9 of the coordinate scale).
fn loops(region: &RegionMesh) -> Vec<&[Element]> {
    let els = &region.elements;
    let scale = els
        .iter()
        .flat_map(|e| e.geometry.iter())
        .fold(0.0_f64, |m, p| m.max(p[0].abs()).max(p[1].abs()))
        .max(f64::MIN_POSITIVE);
    let tol = 1e-9 * scale;
    let mut out = Vec::new();
    let mut start = 0;
    for k in 0..els.len() {
        let e = &els[k];
        let first = els[start].geometry[0];
        if (e.geometry[2][0] - first[0]).hypot(e.geometry[2][1] - first[1]) <= tol {
            out.push(&els[start..=k]);
            start = k + 1;
        }
    }
    if start < els.len() {
        // Not reached for a validated mesh (every loop is closed); keep the rest as a loop.
        out.push(&els[start..]);
    }
    out
}

/// Number of boundary sub-intervals of element `e` for target size `h`.
fn element_divisions(e: &Element, h: f64) -> usize {
    let m = (e.chord_length() / h).ceil();
    if m.is_finite() {
        (m as usize).max(2)
    } else {
        2
    }
}

/// The area enclosed by region `region`'s quadratic boundary elements, m^2 (per unit
/// thickness): (1/2) of the boundary integral of x dy - y dx (Green's theorem), the outer
/// loop counter-clockwise and the holes clockwise, so holes are subtracted. The integrand
/// x(xi) x x'(xi) is a cubic polynomial in xi on a quadratic element, so 2-point Gauss
/// quadrature is exact.
pub fn region_area(mesh: &BemMesh, region: usize) -> Result<f64> {
    let r = check_region(mesh, region)?;
    let g = 1.0 / 3.0_f64.sqrt();
    let mut s = ExactSum::default();
    for e in &r.elements {
        for xi in [-g, g] {
            s.add(0.5 * cross(e.point(xi), e.tangent(xi)));
        }
    }
    Ok(s.value())
}

fn check_region(mesh: &BemMesh, region: usize) -> Result<&RegionMesh> {
    mesh.regions.get(region).ok_or_else(|| {
        Error::invalid(
            "region",
            region,
            format!(
                "must be a region index < {} (the model's region count)",
                mesh.regions.len()
            ),
        )
    })
}

/// A quality triangulation of the interior of region `region` (holes excluded) with
/// interior edges of about `target_size` (m), its boundary sampled on the region's boundary
/// elements; see the module docs for the method, the boundary sampling, grading and the
/// area it covers.
///
/// Errors ([`Error::InvalidParameter`]): `region` out of range; `target_size` not finite or
/// not > 0, or so small for the region that the estimated triangle count (area over the
/// area sqrt(3)/4 h^2 of the target triangle, plus the boundary samples) exceeds
/// [`MAX_TRIANGLES`]. [`Error::Numerical`]: the sampled boundary crosses itself (loops closer
/// than the sampling resolves) or the refinement does not finish within its vertex budget.
pub fn triangulate_region(
    mesh: &BemMesh,
    region: usize,
    target_size: f64,
) -> Result<RegionTriangulation> {
    let r = check_region(mesh, region)?;
    let (target_area, estimate) = triangle_estimate(mesh, region, r, target_size)?;
    let (points, edges) = boundary_samples(r, target_size);
    let nb = points.len();
    let (centre, scale) = spade_frame(&points);
    let (cdt, excluded) = refined_cdt(
        &r.name,
        &points,
        edges,
        (centre, scale),
        target_area,
        estimate,
    )?;
    let (nodes, triangles) = inner_triangles(&r.name, &cdt, &excluded, points, (centre, scale))?;
    Ok(RegionTriangulation {
        region,
        nodes,
        triangles,
        boundary_nodes: nb,
    })
}

/// The target triangle area sqrt(3)/4 h^2 for `target_size` h and the estimated triangle
/// count of region `region` (`r`): its area over the target area plus the boundary samples.
/// Errors: h not finite or not > 0, or an estimate over [`MAX_TRIANGLES`] (naming the
/// smallest h that fits).
fn triangle_estimate(
    mesh: &BemMesh,
    region: usize,
    r: &RegionMesh,
    target_size: f64,
) -> Result<(f64, f64)> {
    if !(target_size.is_finite() && target_size > 0.0) {
        return Err(Error::invalid(
            "target_size",
            target_size,
            "must be finite and > 0 (m)",
        ));
    }
    let h = target_size;
    let area = region_area(mesh, region)?;
    let target_area = 3.0_f64.sqrt() / 4.0 * h * h;
    let boundary_estimate: f64 = r
        .elements
        .iter()
        .map(|e| (e.chord_length() / h).ceil().max(2.0))
        .sum();
    let estimate = area / target_area + boundary_estimate;
    if !estimate.is_finite() || estimate > MAX_TRIANGLES as f64 {
        // Smallest h with area / (sqrt(3)/4 h^2) <= MAX_TRIANGLES (ignoring the boundary).
        let h_min = (area / (MAX_TRIANGLES as f64 * 3.0_f64.sqrt() / 4.0)).sqrt();
        return Err(Error::invalid(
            "target_size",
            format!("{h:e} m"),
            format!(
                "gives about {estimate:.3e} triangles for region '{}' (area {area:.3e} m^2), \
                 more than the cap {MAX_TRIANGLES}; use a target size of at least about \
                 {h_min:.3e} m",
                r.name
            ),
        ));
    }
    Ok((target_area, estimate))
}

/// Boundary samples of region `r` at spacing about `h`, loop by loop, and the constraint
/// edges closing each loop.
fn boundary_samples(r: &RegionMesh, h: f64) -> (Vec<[f64; 2]>, Vec<[usize; 2]>) {
    let mut points: Vec<[f64; 2]> = Vec::new();
    let mut edges: Vec<[usize; 2]> = Vec::new();
    for lp in loops(r) {
        let first = points.len();
        for e in lp {
            let m = element_divisions(e, h);
            for k in 0..m {
                points.push(e.point(-1.0 + 2.0 * k as f64 / m as f64));
            }
        }
        let last = points.len();
        for i in first..last {
            edges.push([i, if i + 1 < last { i + 1 } else { first }]);
        }
    }
    (points, edges)
}

/// The frame spade works in: coordinates centred on the bounding box of `points` and scaled
/// by its size (well inside spade's allowed coordinate range whatever the units); returns the
/// centre and the scale.
fn spade_frame(points: &[[f64; 2]]) -> ([f64; 2], f64) {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        for d in 0..2 {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
        }
    }
    let centre = [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])];
    let scale = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(f64::MIN_POSITIVE);
    (centre, scale)
}

/// The triangulation spade builds and refines.
type Cdt = ConstrainedDelaunayTriangulation<Point2<f64>>;

/// Nodes (m) and counter-clockwise triangles of a triangulation.
type NodesTriangles = (Vec<[f64; 2]>, Vec<[usize; 3]>);

/// An [`Error::Numerical`] of [`triangulate_region`].
fn numerical(detail: String) -> Error {
    Error::Numerical {
        context: "triangulate_region",
        detail,
    }
}

/// The constrained Delaunay triangulation of the boundary samples `points` and `edges` of
/// region `name` in the spade `frame` (centre, scale), refined by Ruppert's algorithm to the
/// target area within a vertex budget of 4 `estimate` + 1000; returns it and its excluded
/// (outer) faces. Errors: samples that are not valid vertices, a boundary that crosses or
/// touches itself, a refinement that does not finish.
fn refined_cdt(
    name: &str,
    points: &[[f64; 2]],
    edges: Vec<[usize; 2]>,
    frame: ([f64; 2], f64),
    target_area: f64,
    estimate: f64,
) -> Result<(Cdt, HashSet<FixedFaceHandle<InnerTag>>)> {
    let (centre, scale) = frame;
    let nb = points.len();
    let vertices: Vec<Point2<f64>> = points
        .iter()
        .map(|p| Point2::new((p[0] - centre[0]) / scale, (p[1] - centre[1]) / scale))
        .collect();
    let mut conflicts = 0usize;
    let mut cdt =
        ConstrainedDelaunayTriangulation::<Point2<f64>>::try_bulk_load_cdt(vertices, edges, |_| {
            conflicts += 1
        })
        .map_err(|e| {
            numerical(format!(
                "the boundary samples are not valid vertices: {e:?}"
            ))
        })?;
    if conflicts > 0 || cdt.num_vertices() != nb {
        return Err(numerical(format!(
            "the sampled boundary of region '{name}' crosses or touches itself ({conflicts} \
             crossing edges, {} coincident samples); refine the boundary mesh where loops \
             come close",
            nb - cdt.num_vertices().min(nb)
        )));
    }
    let budget = (4.0 * estimate) as usize + 1000;
    let params = RefinementParameters::<f64>::new()
        .exclude_outer_faces(true)
        .keep_constraint_edges()
        .with_angle_limit(AngleLimit::from_deg(MIN_ANGLE_DEG))
        .with_max_allowed_area(target_area / (scale * scale))
        .with_max_additional_vertices(budget);
    let result = cdt.refine(params);
    if !result.refinement_complete {
        return Err(numerical(format!(
            "the refinement of region '{name}' did not finish within {budget} added vertices"
        )));
    }
    let excluded: HashSet<_> = result.excluded_faces.into_iter().collect();
    Ok((cdt, excluded))
}

/// The inner faces of `cdt` (less `excluded`) as counter-clockwise triangles of region
/// `name`: the boundary nodes `points` as sampled (exact coordinates), the interior nodes
/// mapped back from the spade `frame` in order of first use. Errors: a triangle of zero area
/// after the mapping, no triangle at all.
fn inner_triangles(
    name: &str,
    cdt: &Cdt,
    excluded: &HashSet<FixedFaceHandle<InnerTag>>,
    points: Vec<[f64; 2]>,
    frame: ([f64; 2], f64),
) -> Result<NodesTriangles> {
    let (centre, scale) = frame;
    let nb = points.len();
    let mut index: Vec<usize> = (0..cdt.num_vertices())
        .map(|v| if v < nb { v } else { usize::MAX })
        .collect();
    let mut nodes = points;
    let mut triangles = Vec::with_capacity(cdt.num_inner_faces());
    for face in cdt.inner_faces() {
        if excluded.contains(&face.fix()) {
            continue;
        }
        let mut tri = [0usize; 3];
        for (slot, v) in tri.iter_mut().zip(face.vertices()) {
            let i = v.fix().index();
            if index[i] == usize::MAX {
                let p = v.position();
                index[i] = nodes.len();
                nodes.push([centre[0] + p.x * scale, centre[1] + p.y * scale]);
            }
            *slot = index[i];
        }
        let a = signed_area(nodes[tri[0]], nodes[tri[1]], nodes[tri[2]]);
        if a < 0.0 {
            tri.swap(1, 2);
        }
        if a == 0.0 || !a.is_finite() {
            return Err(numerical(format!(
                "a triangle of region '{name}' has zero area after mapping back to model \
                 coordinates"
            )));
        }
        triangles.push(tri);
    }
    if triangles.is_empty() {
        return Err(numerical(format!("no triangle inside region '{name}'")));
    }
    Ok((nodes, triangles))
}

/// Displacement, stress and strain at one point.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct FieldSample {
    /// Displacement (u_x, u_y), m.
    pub displacement: [f64; 2],
    /// Stress, Pa (sigma_zz from the plane condition).
    pub stress: Stress2d,
    /// Strain (Hooke's law of the region's material), dimensionless.
    pub strain: Strain2d,
}

/// Displacement, stress and strain of `solution` at `points` (m) of region `region`,
/// rayon-parallel over the points (the same bits as serial:
/// [`sample_region_with`]). Points on the region's boundary or within
/// [`crate::solvers::bem2d::BOUNDARY_LAYER`] of an element length of it (inside or out) are
/// evaluated that distance inside; see the module docs.
///
/// Errors ([`Error::InvalidParameter`]): `region` out of range; a point not finite or
/// outside the region (named `points[i]`).
pub fn sample_region(
    solution: &BemSolution,
    region: usize,
    points: &[[f64; 2]],
) -> Result<Vec<FieldSample>> {
    sample_region_with(solution, region, points, Execution::Parallel)
}

/// [`sample_region`], serial or parallel.
pub fn sample_region_with(
    solution: &BemSolution,
    region: usize,
    points: &[[f64; 2]],
    execution: Execution,
) -> Result<Vec<FieldSample>> {
    check_region(solution.mesh(), region)?;
    let one = |(i, p): (usize, &[f64; 2])| -> Result<FieldSample> {
        let (displacement, stress, strain) =
            solution.fields_in_region(region, *p).map_err(|e| match e {
                Error::InvalidParameter { value, rule, .. } => Error::InvalidParameter {
                    field: format!("points[{i}]"),
                    value,
                    rule,
                },
                other => other,
            })?;
        Ok(FieldSample {
            displacement,
            stress,
            strain,
        })
    };
    match execution {
        Execution::Serial => points.iter().enumerate().map(one).collect(),
        Execution::Parallel => points.par_iter().enumerate().map(one).collect(),
    }
}

#[cfg(test)]
mod tests;
