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

use super::geometry::{
    mesh_segment, BemModel, BodyForce, LoopItem, Region, Segment, SegmentElement, SegmentShape,
};
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

    /// The vector x(xi) - p, formed from the element's own differences
    /// sum_a M_a(xi) (x_a - p) (the shape functions sum to 1), so that its rounding error
    /// is relative to the element's size and distance from p, not to |x| (a model far from
    /// the origin loses no accuracy).
    pub fn offset_from(&self, xi: f64, p: [f64; 2]) -> [f64; 2] {
        let m = geometry_shape(xi);
        let g = &self.geometry;
        let mut r = [0.0; 2];
        for d in 0..2 {
            r[d] = m[0] * (g[0][d] - p[d]) + m[1] * (g[1][d] - p[d]) + m[2] * (g[2][d] - p[d]);
        }
        r
    }

    /// The chord x(xi_s + dxi) - x(xi_s) from the element's own differences: with the
    /// quadratic shape functions, M_a(xi_s + dxi) - M_a(xi_s) = dxi c_a with
    /// c = [(2 xi_s + dxi - 1)/2, -(2 xi_s + dxi), (2 xi_s + dxi + 1)/2] (summing to 0), so
    /// the chord is dxi [c_0 (x_0 - x_1) + c_2 (x_2 - x_1)]: accurate to rounding relative
    /// to its own length however small dxi is and wherever the element sits (the singular
    /// rule evaluates the kernels at |dxi| down to 1e-12).
    pub fn chord(&self, xi_s: f64, dxi: f64) -> [f64; 2] {
        let s = 2.0 * xi_s + dxi;
        let (c0, c2) = (0.5 * (s - 1.0), 0.5 * (s + 1.0));
        let g = &self.geometry;
        let mut r = [0.0; 2];
        for d in 0..2 {
            r[d] = dxi * (c0 * (g[0][d] - g[1][d]) + c2 * (g[2][d] - g[1][d]));
        }
        r
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
    /// The elements in model-local coordinates (relative to [`BemMesh::origin`]), as
    /// generated from the model's segments shifted there: the element integrals and the
    /// contact geometry use these, so that a model far from the origin loses no accuracy
    /// (the global `elements` carry the rounding of their absolute coordinates).
    pub local_elements: Vec<Element>,
    /// The node positions relative to [`BemMesh::origin`], m.
    pub local_positions: Vec<[f64; 2]>,
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
    /// The model-local origin (m): the centre of the bounding box of the segments'
    /// defining points. [`RegionMesh::local_elements`] and
    /// [`RegionMesh::local_positions`] are relative to it.
    pub origin: [f64; 2],
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
        let origin = model_origin(model);
        let mut table = segment_table(model, origin)?;
        let mut regions = Vec::with_capacity(model.regions.len());
        for (r, region) in model.regions.iter().enumerate() {
            regions.push(mesh_region(model.plane, r, region, &mut table, origin)?);
        }
        super::overlap::check_overlap(&regions)?;
        Ok(Self {
            plane: model.plane,
            regions,
            segments: table.info,
            origin,
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

/// The model-local origin: the centre of the bounding box of the segments' defining points
/// (the origin itself when no point is finite). The elements are generated from the segments
/// shifted to it, so that the mesh's own differences (element lengths, node spacings, kernel
/// distances) carry no rounding of large absolute coordinates (issue 11 item 2).
fn model_origin(model: &BemModel) -> [f64; 2] {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for item in model.regions.iter().flat_map(|r| r.loops.iter().flatten()) {
        if let LoopItem::Segment(s) = item {
            for p in s.shape.extent_points() {
                if p[0].is_finite() && p[1].is_finite() {
                    for d in 0..2 {
                        lo[d] = lo[d].min(p[d]);
                        hi[d] = hi[d].max(p[d]);
                    }
                }
            }
        }
    }
    if lo[0] <= hi[0] && lo[1] <= hi[1] {
        [0.5 * lo[0] + 0.5 * hi[0], 0.5 * lo[1] + 0.5 * hi[1]]
    } else {
        [0.0, 0.0]
    }
}

/// The model's segments, each meshed once in its owner's direction in model-local
/// coordinates; the regions' loops take their elements and nodes from here.
struct SegmentTable {
    /// The segments, in model order (owner nodes and partners filled in by the regions).
    info: Vec<SegmentInfo>,
    /// The elements of each segment and its number of functional nodes.
    meshes: Vec<(Vec<SegmentElement>, usize)>,
    /// Segment index by name.
    by_name: HashMap<String, usize>,
}

/// The segment table of `model` (first pass over the regions' own segments), checking that
/// region names are unique, that every region has loops and every loop a segment, that every
/// segment is valid and that no segment is named twice.
fn segment_table(model: &BemModel, origin: [f64; 2]) -> Result<SegmentTable> {
    let mut segments: Vec<SegmentInfo> = Vec::new();
    let mut seg_mesh = Vec::new();
    let mut by_name: HashMap<String, usize> = HashMap::new();
    let mut region_names: HashMap<&str, usize> = HashMap::new();
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
                let local = Segment {
                    shape: s.shape.shifted(origin)?,
                    ..s.clone()
                };
                let (elements, n_nodes) = mesh_segment(&local);
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
    Ok(SegmentTable {
        info: segments,
        meshes: seg_mesh,
        by_name,
    })
}

/// The mesh of region `r`: its boundary (model-local, checked), moved back to global
/// coordinates with the local copies kept, and its body forces summed.
fn mesh_region(
    plane: PlaneCondition,
    r: usize,
    region: &Region,
    table: &mut SegmentTable,
    origin: [f64; 2],
) -> Result<RegionMesh> {
    let (mut elements, mut nodes) = region_boundary(r, region, table, origin)?;
    let (centroid, local_elements, local_positions) = to_global(&mut elements, &mut nodes, origin);
    let origin_bf = body_force_origin(region, centroid);
    let body_force = affine_body_force(&region.name, &region.body_forces, origin_bf)?;
    Ok(RegionMesh {
        name: region.name.clone(),
        material: region.material,
        kernels: Kelvin2d::new(&region.material, plane),
        elements,
        nodes,
        body_force,
        local_elements,
        local_positions,
    })
}

/// The elements and nodes of region `r` in model-local coordinates, loop by loop, recording
/// the owner nodes and partners in `table`; then the checks: each loop closed, the boundary
/// not self-intersecting, the outer loop counter-clockwise and the holes clockwise.
fn region_boundary(
    r: usize,
    region: &Region,
    table: &mut SegmentTable,
    origin: [f64; 2],
) -> Result<(Vec<Element>, Vec<Node>)> {
    let mut elements = Vec::new();
    let mut nodes: Vec<Node> = Vec::new();
    let mut loop_ranges = Vec::new();
    for (l, lp) in region.loops.iter().enumerate() {
        let loop_start = elements.len();
        for item in lp {
            let (s, reversed) = resolve_loop_item(r, &region.name, item, table)?;
            let (els, n_nodes) = &table.meshes[s];
            let n_nodes = *n_nodes;
            let base = nodes.len();
            let new_elements = oriented_elements(s, reversed, els, n_nodes, base);
            nodes.extend(segment_nodes(
                s,
                reversed,
                &new_elements,
                els,
                n_nodes,
                base,
            )?);
            let matching: Vec<usize> = (0..n_nodes)
                .map(|q| region_node(base, n_nodes, reversed, q))
                .collect();
            if reversed {
                table.info[s].partner = Some((r, matching));
            } else {
                table.info[s].owner_nodes = matching;
            }
            elements.extend(new_elements);
        }
        check_loop(
            &region.name,
            l,
            &elements[loop_start..],
            &table.info,
            origin,
        )?;
        loop_ranges.push(loop_start..elements.len());
    }
    check_region_geometry(&region.name, &elements, &loop_ranges, &table.info, origin)?;
    for (l, range) in loop_ranges.into_iter().enumerate() {
        check_orientation(&region.name, l, &elements[range])?;
    }
    Ok((elements, nodes))
}

/// The segment index of a loop item of region `r` and whether the region traverses it
/// reversed (a shared segment); errors for a shared name that is unknown, the region's own
/// segment or a segment already shared.
fn resolve_loop_item(
    r: usize,
    region: &str,
    item: &LoopItem,
    table: &SegmentTable,
) -> Result<(usize, bool)> {
    match item {
        LoopItem::Segment(s) => Ok((table.by_name[&s.name], false)),
        LoopItem::Shared(name) => {
            let field = format!("region '{region}'.shared");
            let &s = table
                .by_name
                .get(name)
                .ok_or_else(|| Error::invalid(&field, name, "names no segment of the model"))?;
            if table.info[s].owner == r {
                return Err(Error::invalid(
                    &field,
                    name,
                    "a region cannot share its own segment",
                ));
            }
            if table.info[s].partner.is_some() {
                return Err(Error::invalid(
                    &field,
                    name,
                    "the segment is already shared by another region",
                ));
            }
            Ok((s, true))
        }
    }
}

/// Region-local index of segment-local node `q` of a segment with `n_nodes` nodes whose
/// first region node is `base`.
fn region_node(base: usize, n_nodes: usize, reversed: bool, q: usize) -> usize {
    base + if reversed { n_nodes - 1 - q } else { q }
}

/// The elements of segment `s` in the region's traversal order, with region-local node
/// indices from `base` (reversed: each element flipped and the order reversed).
fn oriented_elements(
    s: usize,
    reversed: bool,
    els: &[SegmentElement],
    n_nodes: usize,
    base: usize,
) -> Vec<Element> {
    let local_of = |q: usize| region_node(base, n_nodes, reversed, q);
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
    new_elements
}

/// The `n_nodes` functional nodes of segment `s` (region-local indices from `base`):
/// position, normal and parameter (in the owner's direction) from the first element of
/// `new_elements` that holds each; `els` are the same elements in the segment's own order.
fn segment_nodes(
    s: usize,
    reversed: bool,
    new_elements: &[Element],
    els: &[SegmentElement],
    n_nodes: usize,
    base: usize,
) -> Result<Vec<Node>> {
    let mut fresh = vec![None; n_nodes];
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
                let param =
                    se.t_range[0] + 0.5 * (xi_owner + 1.0) * (se.t_range[1] - se.t_range[0]);
                fresh[idx] = Some(Node {
                    position: e.point(xi),
                    normal,
                    segment: s,
                    param,
                });
            }
        }
    }
    let fresh: Option<Vec<Node>> = fresh.into_iter().collect();
    fresh.ok_or_else(|| Error::Numerical {
        context: "BEM mesh",
        detail: format!("a node of segment {s} is on none of its elements"),
    })
}

/// Moves a region's model-local elements and nodes back to global coordinates; returns the
/// global centroid of the nodes and the local copies of the elements and node positions
/// (kept for the integrals).
fn to_global(
    elements: &mut [Element],
    nodes: &mut [Node],
    origin: [f64; 2],
) -> ([f64; 2], Vec<Element>, Vec<[f64; 2]>) {
    let k = nodes.len().max(1) as f64;
    let centroid = nodes.iter().fold([0.0, 0.0], |c, n| {
        [c[0] + n.position[0] / k, c[1] + n.position[1] / k]
    });
    let centroid = [centroid[0] + origin[0], centroid[1] + origin[1]];
    let local_elements = elements.to_vec();
    let local_positions: Vec<[f64; 2]> = nodes.iter().map(|n| n.position).collect();
    let add = |p: [f64; 2]| [p[0] + origin[0], p[1] + origin[1]];
    for e in elements.iter_mut() {
        e.geometry = e.geometry.map(add);
    }
    for n in nodes.iter_mut() {
        n.position = add(n.position);
    }
    (centroid, local_elements, local_positions)
}

/// The particular solution's origin: the common centre where every body force is a rotation
/// about one centre (no constant part: the axisymmetric field alone), else the `centroid` of
/// the nodes. Both move with the model.
fn body_force_origin(region: &Region, centroid: [f64; 2]) -> [f64; 2] {
    let centers: Vec<[f64; 2]> = region
        .body_forces
        .iter()
        .filter_map(|f| match *f {
            BodyForce::Centrifugal { center, .. } => Some(center),
            BodyForce::Gravity { .. } => None,
        })
        .collect();
    match centers.first() {
        Some(&c)
            if centers.len() == region.body_forces.len()
                && centers.iter().all(|&d| d == c)
                && c[0].is_finite()
                && c[1].is_finite() =>
        {
            c
        }
        _ => centroid,
    }
}

/// Closure and zero-length elements of one loop.
fn check_loop(
    region: &str,
    l: usize,
    elements: &[Element],
    segments: &[SegmentInfo],
    origin: [f64; 2],
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
                    a.geometry[2][0] + origin[0],
                    a.geometry[2][1] + origin[1],
                    b.geometry[0][0] + origin[0],
                    b.geometry[0][1] + origin[1]
                ),
            ));
        }
    }
    Ok(())
}

/// Orientation of a closed loop: the outer loop counter-clockwise, holes clockwise.
fn check_orientation(region: &str, l: usize, elements: &[Element]) -> Result<()> {
    // Signed area (shoelace over the chords through all geometric nodes).
    // Relative to the loop's first point: no cancellation far from the origin.
    let o = elements.first().map_or([0.0; 2], |e| e.geometry[0]);
    let mut area = 0.0;
    for e in elements {
        for c in 0..2 {
            let (p, q) = (e.geometry[c], e.geometry[c + 1]);
            let (p, q) = ([p[0] - o[0], p[1] - o[1]], [q[0] - o[0], q[1] - o[1]]);
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

/// Closest distance between the segments pq and rs (0 where they cross or touch) and a
/// point of pq where it is reached.
fn chord_distance(p: [f64; 2], q: [f64; 2], r: [f64; 2], s: [f64; 2]) -> (f64, [f64; 2]) {
    // Coordinates relative to p, so that far from the origin nothing is lost.
    let sub = |a: [f64; 2]| [a[0] - p[0], a[1] - p[1]];
    let (q, r, s) = (sub(q), sub(r), sub(s));
    let o = [0.0, 0.0];
    let orient = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    };
    let back = |a: [f64; 2]| [a[0] + p[0], a[1] + p[1]];
    let (d1, d2, d3, d4) = (
        orient(r, s, o),
        orient(r, s, q),
        orient(o, q, r),
        orient(o, q, s),
    );
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        let t = d1 / (d1 - d2);
        return (0.0, back([t * q[0], t * q[1]]));
    }
    let foot = |x: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let l2 = dx * dx + dy * dy;
        let t = if l2 > 0.0 {
            (((x[0] - a[0]) * dx + (x[1] - a[1]) * dy) / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let f = [a[0] + t * dx, a[1] + t * dy];
        (dist(x, f), f)
    };
    let mut best = foot(o, r, s);
    best.1 = o;
    let (dq, _) = foot(q, r, s);
    if dq < best.0 {
        best = (dq, q);
    }
    for x in [r, s] {
        let (d, f) = foot(x, o, q);
        if d < best.0 {
            best = (d, f);
        }
    }
    (best.0, back(best.1))
}

/// Pieces per element in the geometry checks (refined where two pieces come close).
const CHECK_CHORDS: usize = 8;

/// Two parts of a region's boundary closer than this fraction of the shorter of their
/// elements touch: the collocation cannot resolve a narrower gap.
pub const TOUCH_TOLERANCE: f64 = 1e-3;

/// A piece xi in [t0, t1] of an element's quadratic curve: its chord and the largest
/// distance of the curve from the chord (for a quadratic curve exactly the distance at the
/// middle parameter, the deviation being c (t - t0)(t1 - t)).
fn curve_piece(e: &Element, t0: f64, t1: f64) -> ([f64; 2], [f64; 2], f64) {
    let (a, b) = (e.point(t0), e.point(t1));
    let m = e.offset_from(0.5 * (t0 + t1), [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]);
    (a, b, m[0].hypot(m[1]))
}

/// Whether the curve pieces [ti0, ti1] of `ei` and [tj0, tj1] of `ej` come within `tol`
/// of each other, and a point where; bisection while the chords' distance is within the
/// pieces' deviation from their chords (depth-limited at 2^-20 of an element).
fn pieces_touch(
    ei: &Element,
    ti: (f64, f64),
    ej: &Element,
    tj: (f64, f64),
    tol: f64,
    depth: u32,
) -> Option<[f64; 2]> {
    let (a, b, si) = curve_piece(ei, ti.0, ti.1);
    let (c, d, sj) = curve_piece(ej, tj.0, tj.1);
    let (dist, x) = chord_distance(a, b, c, d);
    if dist - si - sj > tol {
        return None;
    }
    if si + sj <= 0.1 * tol || depth >= 20 {
        return (dist <= tol + si + sj).then_some(x);
    }
    let (mi, mj) = (0.5 * (ti.0 + ti.1), 0.5 * (tj.0 + tj.1));
    for pi in [(ti.0, mi), (mi, ti.1)] {
        for pj in [(tj.0, mj), (mj, tj.1)] {
            if let Some(x) = pieces_touch(ei, pi, ej, pj, tol, depth + 1) {
                return Some(x);
            }
        }
    }
    None
}

/// Winding angle of a loop's elements around `p` (+-2 pi inside, 0 outside), formed from
/// differences to p.
fn loop_winding(elements: &[Element], p: [f64; 2]) -> f64 {
    let mut wn = 0.0;
    for e in elements {
        for m in 0..CHECK_CHORDS {
            let a = e.offset_from(-1.0 + 2.0 * m as f64 / CHECK_CHORDS as f64, p);
            let b = e.offset_from(-1.0 + 2.0 * (m + 1) as f64 / CHECK_CHORDS as f64, p);
            wn += (a[0] * b[1] - a[1] * b[0]).atan2(a[0] * b[0] + a[1] * b[1]);
        }
    }
    wn
}

/// The region's loops must be simple closed curves, every hole strictly inside the outer
/// loop and outside the other holes, and no two of them may touch, at a node or between
/// nodes: on the discretized geometry (each element's quadratic curve, as [`CHECK_CHORDS`]
/// pieces bisected where close), any two pieces that are not neighbours along a loop must
/// stay apart by more than [`TOUCH_TOLERANCE`] of the shorter of their elements. Errors
/// ([`Error::InvalidParameter`]) name the region, the segments or the loops, the point and
/// the rule.
fn check_region_geometry(
    region: &str,
    elements: &[Element],
    loops: &[std::ops::Range<usize>],
    segments: &[SegmentInfo],
    origin: [f64; 2],
) -> Result<()> {
    struct Chord {
        /// Parameter interval on its element.
        t: (f64, f64),
        element: usize,
        lp: usize,
        /// Position in its loop's chord sequence.
        index: usize,
        tol: f64,
        bbox: [f64; 4],
    }
    let mut chords = Vec::with_capacity(CHECK_CHORDS * elements.len());
    let mut loop_len = Vec::with_capacity(loops.len());
    for (l, range) in loops.iter().enumerate() {
        let mut index = 0;
        for k in range.clone() {
            let e = &elements[k];
            let tol = TOUCH_TOLERANCE * e.chord_length();
            for m in 0..CHECK_CHORDS {
                let t = (
                    -1.0 + 2.0 * m as f64 / CHECK_CHORDS as f64,
                    -1.0 + 2.0 * (m + 1) as f64 / CHECK_CHORDS as f64,
                );
                let (a, b, sag) = curve_piece(e, t.0, t.1);
                let pad = tol + sag;
                let bbox = [
                    a[0].min(b[0]) - pad,
                    a[1].min(b[1]) - pad,
                    a[0].max(b[0]) + pad,
                    a[1].max(b[1]) + pad,
                ];
                chords.push(Chord {
                    t,
                    element: k,
                    lp: l,
                    index,
                    tol,
                    bbox,
                });
                index += 1;
            }
        }
        loop_len.push(index);
    }
    // Sweep over the chords sorted by the left edge of their boxes.
    let mut order: Vec<usize> = (0..chords.len()).collect();
    order.sort_by(|&i, &j| chords[i].bbox[0].total_cmp(&chords[j].bbox[0]));
    for (oi, &i) in order.iter().enumerate() {
        let ci = &chords[i];
        for &j in &order[oi + 1..] {
            let cj = &chords[j];
            if cj.bbox[0] > ci.bbox[2] {
                break;
            }
            if cj.bbox[1] > ci.bbox[3] || ci.bbox[1] > cj.bbox[3] {
                continue;
            }
            if ci.lp == cj.lp {
                let n = loop_len[ci.lp];
                let gap = ci.index.abs_diff(cj.index);
                if gap == 1 || gap + 1 == n {
                    continue;
                }
            }
            let (ei, ej) = (&elements[ci.element], &elements[cj.element]);
            if let Some(x) = pieces_touch(ei, ci.t, ej, cj.t, ci.tol.min(cj.tol), 0) {
                let (sa, sb) = (&segments[ei.segment].name, &segments[ej.segment].name);
                let what = match (ci.lp.min(cj.lp), ci.lp.max(cj.lp)) {
                    (a, b) if a == b && a == 0 => "the outer loop crosses or touches itself".into(),
                    (a, b) if a == b => format!("hole {a} (loop {a}) crosses or touches itself"),
                    (0, b) => format!("hole {b} (loop {b}) crosses or touches the outer loop"),
                    (a, b) => format!("holes {a} and {b} (loops {a} and {b}) cross or touch"),
                };
                let x = [x[0] + origin[0], x[1] + origin[1]];
                return Err(Error::invalid(
                    format!("region '{region}'"),
                    format!(
                        "segments '{sa}' and '{sb}' at ({:.6e}, {:.6e}) m",
                        x[0], x[1]
                    ),
                    format!(
                        "{what}: every loop must be a simple closed curve and every hole lie \
                         strictly inside the outer loop, no two parts of the boundary touching \
                         (at a node or between nodes) or closer than {TOUCH_TOLERANCE} of their \
                         element length"
                    ),
                ));
            }
        }
    }
    // With no crossings, one point per hole tells where the whole hole lies.
    for (l, range) in loops.iter().enumerate().skip(1) {
        let p = elements[range.start].geometry[1];
        let seg = &segments[elements[range.start].segment].name;
        if loop_winding(&elements[loops[0].clone()], p).abs() < std::f64::consts::PI {
            return Err(Error::invalid(
                format!("region '{region}' loop {l}"),
                format!("hole through segment '{seg}'"),
                "the hole lies outside the outer loop: a hole must lie strictly inside its \
                 region's outline",
            ));
        }
        for (m, other) in loops.iter().enumerate().skip(1) {
            if m != l && loop_winding(&elements[other.clone()], p).abs() > std::f64::consts::PI {
                return Err(Error::invalid(
                    format!("region '{region}' loop {l}"),
                    format!("hole through segment '{seg}'"),
                    format!("the hole lies inside hole {m} (loop {m}): holes may not nest"),
                ));
            }
        }
    }
    Ok(())
}
