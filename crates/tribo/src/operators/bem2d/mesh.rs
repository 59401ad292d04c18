//! Boundary meshes of quadratic isoparametric (3-node) elements, built and validated from a
//! [`BemModel`].
//!
//! Geometry: x(xi) = sum_a M_a(xi) x_a with the standard quadratic shape functions
//! M = [xi(xi-1)/2, 1-xi^2, xi(xi+1)/2] on nodes xi = -1, 0, 1. Fields (u, t): the Lagrange
//! polynomials N_k through the element's three functional nodes, which are the geometric nodes
//! except at the two ends of every segment, where the end node moves to
//! xi = +-[`DISCONTINUOUS_OFFSET`](super::geometry::DISCONTINUOUS_OFFSET) (a discontinuous node; Brebbia & Dominguez sec. 5.8). So
//! u and t are continuous inside a segment, may jump between segments (corners, changes of
//! boundary condition), and no collocation point sits on a corner.

// Index loops read like the tensor formulas they implement.
#![allow(clippy::needless_range_loop)]

use std::collections::HashMap;

use super::geometry::{mesh_segment, BemModel, BodyForce, LoopItem, SegmentShape};
use crate::error::{Error, Result};
use crate::kernels::body_force2d::AffineBodyForce;
use crate::kernels::kelvin2d::{Kelvin2d, PlaneCondition};
use crate::material::ElasticMaterial;

/// Standard quadratic shape functions on xi = -1, 0, 1.
pub(crate) fn geometry_shape(xi: f64) -> [f64; 3] {
    [0.5 * xi * (xi - 1.0), 1.0 - xi * xi, 0.5 * xi * (xi + 1.0)]
}

fn geometry_shape_derivative(xi: f64) -> [f64; 3] {
    [xi - 0.5, -2.0 * xi, xi + 0.5]
}

/// A quadratic boundary element of one region.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Element {
    /// Geometric nodes at xi = -1, 0, 1 (m), in the region's traversal direction.
    pub geometry: [[f64; 2]; 3],
    /// Local coordinates of the three functional nodes.
    pub local: [f64; 3],
    /// Region-local indices of the three functional nodes.
    pub nodes: [usize; 3],
    /// Index of the segment in [`BemMesh::segments`].
    pub segment: usize,
}

impl Element {
    /// Point x(xi).
    pub fn point(&self, xi: f64) -> [f64; 2] {
        let m = geometry_shape(xi);
        let g = &self.geometry;
        [
            m[0] * g[0][0] + m[1] * g[1][0] + m[2] * g[2][0],
            m[0] * g[0][1] + m[1] * g[1][1] + m[2] * g[2][1],
        ]
    }

    /// Tangent dx/dxi.
    pub fn tangent(&self, xi: f64) -> [f64; 2] {
        let m = geometry_shape_derivative(xi);
        let g = &self.geometry;
        [
            m[0] * g[0][0] + m[1] * g[1][0] + m[2] * g[2][0],
            m[0] * g[0][1] + m[1] * g[1][1] + m[2] * g[2][1],
        ]
    }

    /// Outward unit normal and Jacobian |dx/dxi| at xi (the region lies left of the
    /// traversal direction, so the outward normal is the tangent turned clockwise).
    pub fn normal_jacobian(&self, xi: f64) -> ([f64; 2], f64) {
        let d = self.tangent(xi);
        let j = d[0].hypot(d[1]);
        ([d[1] / j, -d[0] / j], j)
    }

    /// Field shape functions N_k(xi) (Lagrange through the functional nodes).
    pub fn field_shape(&self, xi: f64) -> [f64; 3] {
        let [a, b, c] = self.local;
        [
            (xi - b) * (xi - c) / ((a - b) * (a - c)),
            (xi - a) * (xi - c) / ((b - a) * (b - c)),
            (xi - a) * (xi - b) / ((c - a) * (c - b)),
        ]
    }

    /// Derivatives dN_k/dxi.
    pub fn field_shape_derivative(&self, xi: f64) -> [f64; 3] {
        let [a, b, c] = self.local;
        [
            (2.0 * xi - b - c) / ((a - b) * (a - c)),
            (2.0 * xi - a - c) / ((b - a) * (b - c)),
            (2.0 * xi - a - b) / ((c - a) * (c - b)),
        ]
    }

    /// Approximate length (sum of the two chords), m.
    pub fn chord_length(&self) -> f64 {
        let g = &self.geometry;
        dist(g[0], g[1]) + dist(g[1], g[2])
    }
}

pub(crate) fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// A functional (collocation) node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Node {
    /// Position, m.
    pub position: [f64; 2],
    /// Outward unit normal of the region at the node.
    pub normal: [f64; 2],
    /// Index of the segment in [`BemMesh::segments`].
    pub segment: usize,
    /// Segment parameter t in [0, 1] (arc-length fraction from the segment's start, in the
    /// owner's direction).
    pub param: f64,
}

/// The mesh of one region.
#[derive(Debug, Clone, PartialEq)]
pub struct RegionMesh {
    /// Name of the region.
    pub name: String,
    /// Material.
    pub material: ElasticMaterial,
    /// Kernels of the material under the model's plane condition.
    pub kernels: Kelvin2d,
    /// Elements, loop by loop, in traversal order.
    pub elements: Vec<Element>,
    /// Functional nodes (region-local numbering; DOF 2 i + d for direction d).
    pub nodes: Vec<Node>,
    /// The region's body forces summed into one affine field about the centroid of its
    /// nodes (None without body forces).
    pub body_force: Option<AffineBodyForce>,
}

impl RegionMesh {
    /// The particular solution of the region's body force at `x`: displacement (m) and
    /// in-plane stress [sigma_xx, sigma_yy, sigma_xy] (Pa); zero without body forces
    /// ([`AffineBodyForce::particular`]).
    pub fn particular_at(&self, x: [f64; 2]) -> ([f64; 2], [f64; 3]) {
        match &self.body_force {
            Some(f) => f.particular(&self.kernels, x),
            None => ([0.0; 2], [0.0; 3]),
        }
    }

    /// The particular displacement u_p (m) and traction t_p = sigma_p n (Pa) at node `i`.
    pub fn particular_at_node(&self, i: usize) -> ([f64; 2], [f64; 2]) {
        let node = &self.nodes[i];
        let (u, s) = self.particular_at(node.position);
        let n = node.normal;
        (u, [s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1]])
    }
}

/// Sums the body forces of a region into one affine field about `origin`; errors name the
/// region and the item.
fn affine_body_force(
    region: &str,
    forces: &[BodyForce],
    origin: [f64; 2],
) -> Result<Option<AffineBodyForce>> {
    if forces.is_empty() {
        return Ok(None);
    }
    let mut constant = [0.0; 2];
    let mut radial = 0.0;
    for (k, f) in forces.iter().enumerate() {
        f.validate(&format!("region '{region}'.body_force[{k}]"))?;
        let b = f.at(origin);
        constant[0] += b[0];
        constant[1] += b[1];
        if let BodyForce::Centrifugal {
            density,
            angular_velocity,
            ..
        } = *f
        {
            radial += density * angular_velocity * angular_velocity;
        }
    }
    if !(constant[0].is_finite() && constant[1].is_finite() && radial.is_finite()) {
        return Err(Error::invalid(
            format!("region '{region}'.body_force"),
            format!(
                "b = ({:e}, {:e}) N/m^3, rho omega^2 = {radial:e} N/m^4",
                constant[0], constant[1]
            ),
            "the body force overflows (density times acceleration must be finite)",
        ));
    }
    Ok(Some(AffineBodyForce {
        origin,
        constant,
        radial,
    }))
}

/// A named segment of the mesh and where its nodes are.
#[derive(Debug, Clone, PartialEq)]
pub struct SegmentInfo {
    /// Name.
    pub name: String,
    /// Shape.
    pub shape: SegmentShape,
    /// Region that owns it.
    pub owner: usize,
    /// Owner-region node indices, in the segment's direction.
    pub owner_nodes: Vec<usize>,
    /// For a bonded interface: the other region and its node indices, matching
    /// `owner_nodes` one to one.
    pub partner: Option<(usize, Vec<usize>)>,
}

/// A meshed, validated model.
#[derive(Debug, Clone, PartialEq)]
pub struct BemMesh {
    /// Plane condition.
    pub plane: PlaneCondition,
    /// Regions.
    pub regions: Vec<RegionMesh>,
    /// Segments.
    pub segments: Vec<SegmentInfo>,
}

impl BemMesh {
    /// Meshes and validates `model`.
    ///
    /// Errors ([`Error::InvalidParameter`], naming the item): no regions; a region without
    /// loops; a segment named twice; a bad segment (zero length, nonpositive radius, bad
    /// division or grading); a shared segment that is unknown, shared twice or shared by its
    /// owner; a loop that is not closed (naming the two segments that do not meet); an outer
    /// loop that is not counter-clockwise or a hole that is not clockwise; an element of zero
    /// length; a self-intersecting region boundary (naming the two segments); a body force
    /// with a density that is not finite and > 0, or a non-finite acceleration, angular
    /// velocity or centre (naming `region 'NAME'.body_force[K].FIELD`).
    pub fn new(model: &BemModel) -> Result<Self> {
        if model.regions.is_empty() {
            return Err(Error::invalid(
                "model.regions",
                0,
                "at least one region is needed",
            ));
        }
        let mut segments: Vec<SegmentInfo> = Vec::new();
        let mut seg_mesh = Vec::new();
        let mut by_name: HashMap<String, usize> = HashMap::new();
        let mut region_names: HashMap<&str, usize> = HashMap::new();
        // First pass: own segments.
        for (r, region) in model.regions.iter().enumerate() {
            if region_names.insert(region.name.as_str(), r).is_some() {
                return Err(Error::invalid(
                    "region.name",
                    &region.name,
                    "a region name must be unique",
                ));
            }
            if region.loops.is_empty() || region.loops.iter().any(|l| l.is_empty()) {
                return Err(Error::invalid(
                    format!("region '{}'.loops", region.name),
                    region.loops.len(),
                    "a region needs an outer loop and every loop at least one segment",
                ));
            }
            for item in region.loops.iter().flatten() {
                if let LoopItem::Segment(s) = item {
                    s.validate()?;
                    if by_name.contains_key(&s.name) {
                        return Err(Error::invalid(
                            "segment.name",
                            &s.name,
                            "a segment is named twice (names must be unique in the model)",
                        ));
                    }
                    by_name.insert(s.name.clone(), segments.len());
                    let (elements, n_nodes) = mesh_segment(s);
                    seg_mesh.push((elements, n_nodes));
                    segments.push(SegmentInfo {
                        name: s.name.clone(),
                        shape: s.shape.clone(),
                        owner: r,
                        owner_nodes: Vec::new(),
                        partner: None,
                    });
                }
            }
        }
        let mut regions = Vec::with_capacity(model.regions.len());
        for (r, region) in model.regions.iter().enumerate() {
            let mut elements = Vec::new();
            let mut nodes: Vec<Node> = Vec::new();
            let mut loop_ranges = Vec::new();
            for (l, lp) in region.loops.iter().enumerate() {
                let loop_start = elements.len();
                for item in lp {
                    let (s, reversed) = match item {
                        LoopItem::Segment(s) => (by_name[&s.name], false),
                        LoopItem::Shared(name) => {
                            let field = format!("region '{}'.shared", region.name);
                            let &s = by_name.get(name).ok_or_else(|| {
                                Error::invalid(&field, name, "names no segment of the model")
                            })?;
                            if segments[s].owner == r {
                                return Err(Error::invalid(
                                    &field,
                                    name,
                                    "a region cannot share its own segment",
                                ));
                            }
                            if segments[s].partner.is_some() {
                                return Err(Error::invalid(
                                    &field,
                                    name,
                                    "the segment is already shared by another region",
                                ));
                            }
                            (s, true)
                        }
                    };
                    let (els, n_nodes) = &seg_mesh[s];
                    let base = nodes.len();
                    // Region-local index of segment-local node q.
                    let local_of = |q: usize| base + if reversed { n_nodes - 1 - q } else { q };
                    let mut new_elements: Vec<Element> = els
                        .iter()
                        .map(|e| {
                            if reversed {
                                Element {
                                    geometry: [e.geometry[2], e.geometry[1], e.geometry[0]],
                                    local: [-e.local[2], -e.local[1], -e.local[0]],
                                    nodes: [
                                        local_of(e.nodes[2]),
                                        local_of(e.nodes[1]),
                                        local_of(e.nodes[0]),
                                    ],
                                    segment: s,
                                }
                            } else {
                                Element {
                                    geometry: e.geometry,
                                    local: e.local,
                                    nodes: e.nodes.map(local_of),
                                    segment: s,
                                }
                            }
                        })
                        .collect();
                    if reversed {
                        new_elements.reverse();
                    }
                    // Nodes: position, normal and parameter from the element that holds them.
                    let mut fresh = vec![None; *n_nodes];
                    for (e, se) in new_elements.iter().zip(if reversed {
                        els.iter().rev().collect::<Vec<_>>()
                    } else {
                        els.iter().collect()
                    }) {
                        for k in 0..3 {
                            let idx = e.nodes[k] - base;
                            if fresh[idx].is_none() {
                                let xi = e.local[k];
                                let (normal, _) = e.normal_jacobian(xi);
                                // Parameter in the owner's direction.
                                let xi_owner = if reversed { -xi } else { xi };
                                let param = se.t_range[0]
                                    + 0.5 * (xi_owner + 1.0) * (se.t_range[1] - se.t_range[0]);
                                fresh[idx] = Some(Node {
                                    position: e.point(xi),
                                    normal,
                                    segment: s,
                                    param,
                                });
                            }
                        }
                    }
                    nodes.extend(
                        fresh
                            .into_iter()
                            .map(|n| n.expect("every node is on an element")),
                    );
                    let matching: Vec<usize> = (0..*n_nodes).map(local_of).collect();
                    if reversed {
                        segments[s].partner = Some((r, matching));
                    } else {
                        segments[s].owner_nodes = matching;
                    }
                    elements.extend(new_elements);
                }
                check_loop(&region.name, l, &elements[loop_start..], &segments)?;
                loop_ranges.push(loop_start..elements.len());
            }
            check_self_intersection(&region.name, &elements, &segments)?;
            for (l, range) in loop_ranges.into_iter().enumerate() {
                check_orientation(&region.name, l, &elements[range])?;
            }
            let k = nodes.len().max(1) as f64;
            let centroid = nodes.iter().fold([0.0, 0.0], |c, n| {
                [c[0] + n.position[0] / k, c[1] + n.position[1] / k]
            });
            let body_force = affine_body_force(&region.name, &region.body_forces, centroid)?;
            regions.push(RegionMesh {
                name: region.name.clone(),
                material: region.material,
                kernels: Kelvin2d::new(&region.material, model.plane),
                elements,
                nodes,
                body_force,
            });
        }
        super::overlap::check_overlap(&regions)?;
        Ok(Self {
            plane: model.plane,
            regions,
            segments,
        })
    }

    /// Index of the segment called `name`.
    pub fn segment_index(&self, name: &str) -> Option<usize> {
        self.segments.iter().position(|s| s.name == name)
    }

    /// Number of boundary unknowns of the assembled system (two per node per region).
    pub fn dof(&self) -> usize {
        self.regions.iter().map(|r| 2 * r.nodes.len()).sum()
    }
}

/// Closure and zero-length elements of one loop.
fn check_loop(
    region: &str,
    l: usize,
    elements: &[Element],
    segments: &[SegmentInfo],
) -> Result<()> {
    let scale = elements
        .iter()
        .flat_map(|e| e.geometry.iter())
        .fold(0.0_f64, |m, p| m.max(p[0].abs()).max(p[1].abs()))
        .max(f64::MIN_POSITIVE);
    let mut span = 0.0_f64;
    for e in elements {
        span = span.max(e.chord_length());
        if e.chord_length() <= 1e-12 * scale {
            return Err(Error::invalid(
                format!("segment '{}'", segments[e.segment].name),
                e.chord_length(),
                "an element has zero length (too many elements or too strong grading)",
            ));
        }
    }
    let n = elements.len();
    let tol = 1e-9 * scale;
    for k in 0..n {
        let (a, b) = (&elements[k], &elements[(k + 1) % n]);
        if dist(a.geometry[2], b.geometry[0]) > tol {
            let (sa, sb) = (&segments[a.segment].name, &segments[b.segment].name);
            return Err(Error::invalid(
                format!("region '{region}' loop {l}"),
                format!("'{sa}' -> '{sb}'"),
                format!(
                    "the loop is open: the end ({:.6e}, {:.6e}) of '{sa}' is not the start \
                     ({:.6e}, {:.6e}) of '{sb}'",
                    a.geometry[2][0], a.geometry[2][1], b.geometry[0][0], b.geometry[0][1]
                ),
            ));
        }
    }
    Ok(())
}

/// Orientation of a closed loop: the outer loop counter-clockwise, holes clockwise.
fn check_orientation(region: &str, l: usize, elements: &[Element]) -> Result<()> {
    // Signed area (shoelace over the chords through all geometric nodes).
    let mut area = 0.0;
    for e in elements {
        for c in 0..2 {
            let (p, q) = (e.geometry[c], e.geometry[c + 1]);
            area += 0.5 * (p[0] * q[1] - q[0] * p[1]);
        }
    }
    let outer = l == 0;
    if (outer && area <= 0.0) || (!outer && area >= 0.0) {
        return Err(Error::invalid(
            format!("region '{region}' loop {l}"),
            format!("signed area {area:.6e}"),
            if outer {
                "the outer loop must run counter-clockwise (the region on its left)"
            } else {
                "a hole must run clockwise (the region on its left)"
            },
        ));
    }
    Ok(())
}

/// Whether the closed segments pq and rs intersect.
fn segments_cross(p: [f64; 2], q: [f64; 2], r: [f64; 2], s: [f64; 2]) -> bool {
    let orient = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    };
    let d1 = orient(r, s, p);
    let d2 = orient(r, s, q);
    let d3 = orient(p, q, r);
    let d4 = orient(p, q, s);
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    let on = |a: [f64; 2], b: [f64; 2], c: [f64; 2], d: f64| {
        d == 0.0
            && c[0] >= a[0].min(b[0])
            && c[0] <= a[0].max(b[0])
            && c[1] >= a[1].min(b[1])
            && c[1] <= a[1].max(b[1])
    };
    on(r, s, p, d1) || on(r, s, q, d2) || on(p, q, r, d3) || on(p, q, s, d4)
}

/// No two non-adjacent chords of a region's boundary may touch.
fn check_self_intersection(
    region: &str,
    elements: &[Element],
    segments: &[SegmentInfo],
) -> Result<()> {
    // Chords with their element index; adjacency = consecutive chords in a loop (shared end
    // point). Chords that share an end point exactly are skipped.
    let mut chords: Vec<([f64; 2], [f64; 2], usize)> = Vec::with_capacity(2 * elements.len());
    for (k, e) in elements.iter().enumerate() {
        chords.push((e.geometry[0], e.geometry[1], k));
        chords.push((e.geometry[1], e.geometry[2], k));
    }
    let bbox = |a: [f64; 2], b: [f64; 2]| {
        [
            a[0].min(b[0]),
            a[1].min(b[1]),
            a[0].max(b[0]),
            a[1].max(b[1]),
        ]
    };
    let boxes: Vec<[f64; 4]> = chords.iter().map(|c| bbox(c.0, c.1)).collect();
    let scale = boxes.iter().fold(0.0_f64, |m, b| {
        m.max(b[0].abs())
            .max(b[1].abs())
            .max(b[2].abs())
            .max(b[3].abs())
    });
    let close = |a: [f64; 2], b: [f64; 2]| dist(a, b) <= 1e-9 * scale;
    for i in 0..chords.len() {
        for j in i + 1..chords.len() {
            let (bi, bj) = (&boxes[i], &boxes[j]);
            if bi[2] < bj[0] || bj[2] < bi[0] || bi[3] < bj[1] || bj[3] < bi[1] {
                continue;
            }
            let (p, q, ei) = chords[i];
            let (r, s, ej) = chords[j];
            if close(q, r) || close(s, p) || close(p, r) || close(q, s) {
                continue;
            }
            if segments_cross(p, q, r, s) {
                let (a, b) = (
                    &segments[elements[ei].segment].name,
                    &segments[elements[ej].segment].name,
                );
                return Err(Error::invalid(
                    format!("region '{region}'"),
                    format!("'{a}' and '{b}'"),
                    "the boundary intersects itself (segments cross or touch)",
                ));
            }
        }
    }
    Ok(())
}
