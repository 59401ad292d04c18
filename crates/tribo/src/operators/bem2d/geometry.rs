//! Geometry of 2D boundary element models: regions bounded by closed loops of named line and
//! arc segments, each with its own element count (or size) and grading, or of curves given
//! by the nodes of a boundary mesh ([`MeshedCurve`], e.g. from [`super::gmsh`]).
//!
//! A [`BemModel`] is a list of [`Region`]s, each with one material. A region's first loop is
//! its outer boundary, counter-clockwise (the region on the left); further loops are holes,
//! clockwise. Two regions of one body share a bonded interface (the zonal homogeneity of the
//! paper's (7)) by the second region naming the first region's segment with
//! [`LoopItem::Shared`]: it is traversed backwards and meshed identically, so the interface
//! nodes coincide.

use std::sync::Arc;

use crate::error::{Error, Result};
use crate::kernels::kelvin2d::{finite_point, PlaneCondition};
use crate::material::ElasticMaterial;

/// The shape of a boundary segment.
#[derive(Debug, Clone, PartialEq)]
pub enum SegmentShape {
    /// A straight line from `start` to `end` (m).
    Line {
        /// Start point.
        start: [f64; 2],
        /// End point.
        end: [f64; 2],
    },
    /// A circular arc about `center` of radius `radius` (m) from polar angle `start_angle` to
    /// `end_angle` (rad); counter-clockwise where `end_angle > start_angle`.
    Arc {
        /// Centre.
        center: [f64; 2],
        /// Radius, > 0.
        radius: f64,
        /// Polar angle of the start point, rad.
        start_angle: f64,
        /// Polar angle of the end point, rad (|end - start| in (0, 2 pi]).
        end_angle: f64,
    },
    /// A curve given by the nodes of a boundary mesh (a gmsh import): a chain of quadratic
    /// pieces, each one element of the segment.
    Meshed(MeshedCurve),
}

/// A chain of quadratic curve pieces through given nodes: piece k runs through
/// `points[2k]`, `points[2k + 1]` (its middle node, at xi = 0) and `points[2k + 2]`, with the
/// standard quadratic shape functions (the isoparametric geometry of the boundary elements).
/// The segment parameter t runs along the chain in proportion to the arc length of the
/// pieces' ends and linearly in xi inside each piece.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshedCurve {
    points: Arc<[[f64; 2]]>,
    /// Arc length from the start to the end of each piece, m (`pieces + 1` values from 0).
    arc: Arc<[f64]>,
}

/// Length of the quadratic piece through p0, p1 (xi = 0), p2: the integral of |dx/dxi| by
/// 8-point Gauss-Legendre quadrature (exact to round-off for the near-uniform
/// parametrisations of mesh edges, whose speed |dx/dxi| is a smooth square root).
fn quadratic_piece_length(p: [[f64; 2]; 3]) -> f64 {
    let (x, w) = crate::kernels::quadrature::gauss_legendre(8);
    x.iter()
        .zip(&w)
        .map(|(&xi, &wi)| {
            let d = [xi - 0.5, -2.0 * xi, xi + 0.5];
            let tx = d[0] * p[0][0] + d[1] * p[1][0] + d[2] * p[2][0];
            let ty = d[0] * p[0][1] + d[1] * p[1][1] + d[2] * p[2][1];
            wi * tx.hypot(ty)
        })
        .sum()
}

impl MeshedCurve {
    /// A curve through `points` (m): 2 k + 1 points for k pieces (ends and middle nodes
    /// alternating). Errors: fewer than 3 points or an even count, a point that is not
    /// finite, a piece of zero length.
    pub fn new(points: Vec<[f64; 2]>) -> Result<Self> {
        if points.len() < 3 || points.len().is_multiple_of(2) {
            return Err(Error::invalid(
                "meshed curve points",
                points.len(),
                "a chain of quadratic pieces needs 2 k + 1 points (k >= 1)",
            ));
        }
        for (i, p) in points.iter().enumerate() {
            finite_point(&format!("meshed curve point {i}"), *p)?;
        }
        let scale = points
            .iter()
            .fold(0.0_f64, |m, p| m.max(p[0].abs()).max(p[1].abs()))
            .max(f64::MIN_POSITIVE);
        let mut arc = Vec::with_capacity(points.len() / 2 + 1);
        arc.push(0.0);
        for (k, w) in points.windows(3).step_by(2).enumerate() {
            let l = quadratic_piece_length([w[0], w[1], w[2]]);
            if l.is_nan() || l <= 1e-12 * scale {
                return Err(Error::invalid(
                    format!("meshed curve piece {k}"),
                    l,
                    "a piece has zero length (coincident nodes)",
                ));
            }
            arc.push(arc[k] + l);
        }
        Ok(Self {
            points: points.into(),
            arc: arc.into(),
        })
    }

    /// The nodes (ends and middle nodes alternating), m.
    pub fn points(&self) -> &[[f64; 2]] {
        &self.points
    }

    /// Number of quadratic pieces.
    pub fn pieces(&self) -> usize {
        self.points.len() / 2
    }

    /// The three nodes of piece k.
    fn piece(&self, k: usize) -> [[f64; 2]; 3] {
        [
            self.points[2 * k],
            self.points[2 * k + 1],
            self.points[2 * k + 2],
        ]
    }

    /// Segment parameter at the ends of each piece (`pieces + 1` values from 0 to 1).
    fn breakpoints(&self) -> Vec<f64> {
        let total = self.length();
        let mut t: Vec<f64> = self.arc.iter().map(|a| a / total).collect();
        if let Some(last) = t.last_mut() {
            *last = 1.0;
        }
        t
    }

    /// Total length, m.
    pub fn length(&self) -> f64 {
        self.arc[self.arc.len() - 1]
    }

    fn point(&self, t: f64) -> [f64; 2] {
        let s = t.clamp(0.0, 1.0) * self.length();
        let k = self
            .arc
            .partition_point(|&a| a <= s)
            .clamp(1, self.pieces())
            - 1;
        let xi = 2.0 * (s - self.arc[k]) / (self.arc[k + 1] - self.arc[k]) - 1.0;
        let m = [0.5 * xi * (xi - 1.0), 1.0 - xi * xi, 0.5 * xi * (xi + 1.0)];
        let p = self.piece(k);
        [
            m[0] * p[0][0] + m[1] * p[1][0] + m[2] * p[2][0],
            m[0] * p[0][1] + m[1] * p[1][1] + m[2] * p[2][1],
        ]
    }

    /// The parameter of the point of the chain nearest to `x` (through the two chords of each
    /// piece: exact for straight pieces, within the chord's sagitta for curved ones).
    fn nearest_parameter(&self, x: [f64; 2]) -> f64 {
        let total = self.length();
        let mut best = (f64::INFINITY, 0.0);
        for k in 0..self.pieces() {
            let p = self.piece(k);
            for half in 0..2 {
                let (a, b) = (p[half], p[half + 1]);
                let s = projection(a, b, x);
                let q = [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])];
                let d = (q[0] - x[0]).hypot(q[1] - x[1]);
                if d < best.0 {
                    // xi in [-1, 0] on the first chord, [0, 1] on the second.
                    let xi = half as f64 - 1.0 + s;
                    let arc = self.arc[k] + 0.5 * (xi + 1.0) * (self.arc[k + 1] - self.arc[k]);
                    best = (d, arc / total);
                }
            }
        }
        best.1
    }
}

/// The fraction s in [0, 1] of the point of the line segment ab nearest to x.
fn projection(a: [f64; 2], b: [f64; 2], x: [f64; 2]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let l2 = d[0] * d[0] + d[1] * d[1];
    if l2 == 0.0 {
        return 0.0;
    }
    (((x[0] - a[0]) * d[0] + (x[1] - a[1]) * d[1]) / l2).clamp(0.0, 1.0)
}

impl SegmentShape {
    /// The same shape translated by `-origin` (the mesh's model-local coordinates).
    pub(crate) fn shifted(&self, origin: [f64; 2]) -> Result<Self> {
        let sub = |p: [f64; 2]| [p[0] - origin[0], p[1] - origin[1]];
        Ok(match self {
            SegmentShape::Line { start, end } => SegmentShape::Line {
                start: sub(*start),
                end: sub(*end),
            },
            SegmentShape::Arc {
                center,
                radius,
                start_angle,
                end_angle,
            } => SegmentShape::Arc {
                center: sub(*center),
                radius: *radius,
                start_angle: *start_angle,
                end_angle: *end_angle,
            },
            SegmentShape::Meshed(c) => SegmentShape::Meshed(MeshedCurve::new(
                c.points().iter().map(|&p| sub(p)).collect(),
            )?),
        })
    }

    /// The points that span the shape's extent (line ends, an arc's centre +- its radius,
    /// a meshed curve's nodes).
    pub(crate) fn extent_points(&self) -> Vec<[f64; 2]> {
        match self {
            SegmentShape::Line { start, end } => vec![*start, *end],
            SegmentShape::Arc { center, radius, .. } => vec![
                [center[0] - radius, center[1] - radius],
                [center[0] + radius, center[1] + radius],
            ],
            SegmentShape::Meshed(c) => c.points().to_vec(),
        }
    }

    /// The point at parameter `t` in [0, 1] (proportional to arc length).
    pub fn point(&self, t: f64) -> [f64; 2] {
        match *self {
            SegmentShape::Line { start, end } => [
                start[0] + t * (end[0] - start[0]),
                start[1] + t * (end[1] - start[1]),
            ],
            SegmentShape::Arc {
                center,
                radius,
                start_angle,
                end_angle,
            } => {
                let a = start_angle + t * (end_angle - start_angle);
                [center[0] + radius * a.cos(), center[1] + radius * a.sin()]
            }
            SegmentShape::Meshed(ref c) => c.point(t),
        }
    }

    /// The parameter t in [0, 1] of the point of the segment nearest to `x` (for an arc:
    /// by the polar angle of `x`, the nearer end where it lies outside the arc's range).
    pub fn nearest_parameter(&self, x: [f64; 2]) -> f64 {
        match *self {
            SegmentShape::Line { start, end } => projection(start, end, x),
            SegmentShape::Arc {
                center,
                start_angle,
                end_angle,
                ..
            } => {
                let a = (x[1] - center[1]).atan2(x[0] - center[0]);
                let sweep = end_angle - start_angle;
                // Bring the angle next to the arc's range (a full turn is 2 pi / |sweep| in t).
                let period = std::f64::consts::TAU / sweep.abs();
                let mut rel = (a - start_angle) / sweep;
                while rel < -0.5 * (period - 1.0) {
                    rel += period;
                }
                while rel > 1.0 + 0.5 * (period - 1.0) {
                    rel -= period;
                }
                rel.clamp(0.0, 1.0)
            }
            SegmentShape::Meshed(ref c) => c.nearest_parameter(x),
        }
    }

    /// Length, m.
    pub fn length(&self) -> f64 {
        match *self {
            SegmentShape::Line { start, end } => (end[0] - start[0]).hypot(end[1] - start[1]),
            SegmentShape::Arc {
                radius,
                start_angle,
                end_angle,
                ..
            } => radius * (end_angle - start_angle).abs(),
            SegmentShape::Meshed(ref c) => c.length(),
        }
    }
}

/// How elements are distributed along a segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Grading {
    /// Equal elements.
    Uniform,
    /// Geometric grading toward both ends; `ratio` = largest / smallest element (>= 1).
    BothEnds(f64),
    /// Geometric grading toward the start; `ratio` = largest / smallest element (>= 1).
    Start(f64),
    /// Geometric grading toward the end; `ratio` = largest / smallest element (>= 1).
    End(f64),
}

/// Number of elements on a segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Division {
    /// A fixed count (>= 1).
    Count(usize),
    /// A target element size (m, > 0): ceil(length / size) elements.
    Size(f64),
}

/// A named boundary segment with its discretization.
#[derive(Debug, Clone, PartialEq)]
pub struct Segment {
    /// Unique name (boundary conditions and interfaces refer to it).
    pub name: String,
    /// Shape.
    pub shape: SegmentShape,
    /// Element count or size.
    pub division: Division,
    /// Grading of the element sizes.
    pub grading: Grading,
}

impl Segment {
    /// A straight segment with `elements` equal elements.
    pub fn line(name: &str, start: [f64; 2], end: [f64; 2], elements: usize) -> Self {
        Self {
            name: name.to_string(),
            shape: SegmentShape::Line { start, end },
            division: Division::Count(elements),
            grading: Grading::Uniform,
        }
    }

    /// A circular arc with `elements` equal elements (angles in rad).
    pub fn arc(
        name: &str,
        center: [f64; 2],
        radius: f64,
        start_angle: f64,
        end_angle: f64,
        elements: usize,
    ) -> Self {
        Self {
            name: name.to_string(),
            shape: SegmentShape::Arc {
                center,
                radius,
                start_angle,
                end_angle,
            },
            division: Division::Count(elements),
            grading: Grading::Uniform,
        }
    }

    /// A segment along the nodes of a boundary mesh: one quadratic element per piece of the
    /// curve (the division is the curve's pieces and the grading uniform; neither applies).
    pub fn meshed(name: &str, curve: MeshedCurve) -> Self {
        let pieces = curve.pieces();
        Self {
            name: name.to_string(),
            shape: SegmentShape::Meshed(curve),
            division: Division::Count(pieces),
            grading: Grading::Uniform,
        }
    }

    /// The same segment with another grading.
    pub fn graded(mut self, grading: Grading) -> Self {
        self.grading = grading;
        self
    }

    /// The same segment divided by element size instead of count.
    pub fn with_size(mut self, size: f64) -> Self {
        self.division = Division::Size(size);
        self
    }

    pub(crate) fn validate(&self) -> Result<()> {
        let field = |what: &str| format!("segment '{}'.{what}", self.name);
        if self.name.trim().is_empty() {
            return Err(Error::invalid("segment.name", "\"\"", "must not be empty"));
        }
        match self.shape {
            SegmentShape::Line { start, end } => {
                finite_point(&field("start"), start)?;
                finite_point(&field("end"), end)?;
                let scale = start[0]
                    .abs()
                    .max(start[1].abs())
                    .max(end[0].abs())
                    .max(end[1].abs());
                if self.shape.length() <= 1e-12 * scale.max(f64::MIN_POSITIVE) {
                    return Err(Error::invalid(
                        field("length"),
                        self.shape.length(),
                        "a line segment must have nonzero length (start != end)",
                    ));
                }
            }
            SegmentShape::Arc {
                center,
                radius,
                start_angle,
                end_angle,
            } => {
                finite_point(&field("center"), center)?;
                if !(radius.is_finite() && radius > 0.0) {
                    return Err(Error::invalid(
                        field("radius"),
                        radius,
                        "must be finite and > 0",
                    ));
                }
                let sweep = end_angle - start_angle;
                if !(start_angle.is_finite()
                    && end_angle.is_finite()
                    && sweep.abs() > 1e-12
                    && sweep.abs() <= 2.0 * std::f64::consts::PI * (1.0 + 1e-12))
                {
                    return Err(Error::invalid(
                        field("sweep"),
                        sweep,
                        "end_angle - start_angle must be finite, nonzero and at most 2 pi in magnitude",
                    ));
                }
            }
            SegmentShape::Meshed(ref c) => {
                if self.division != Division::Count(c.pieces()) || self.grading != Grading::Uniform
                {
                    return Err(Error::invalid(
                        field("division"),
                        format!("{:?}, {:?}", self.division, self.grading),
                        "a meshed curve keeps its mesh's elements: the division must be its \
                         piece count and the grading uniform (use Segment::meshed)",
                    ));
                }
            }
        }
        match self.division {
            Division::Count(n) if n == 0 || n > 100_000 => {
                return Err(Error::invalid(
                    field("elements"),
                    n,
                    "must be in 1..=100000",
                ))
            }
            Division::Size(h) if !(h.is_finite() && h > 0.0) => {
                return Err(Error::invalid(
                    field("element_size"),
                    h,
                    "must be finite and > 0",
                ))
            }
            Division::Size(h) if self.shape.length() / h > 100_000.0 => {
                return Err(Error::invalid(
                    field("element_size"),
                    h,
                    "gives more than 100000 elements on the segment",
                ))
            }
            _ => {}
        }
        match self.grading {
            Grading::Uniform => {}
            Grading::BothEnds(q) | Grading::Start(q) | Grading::End(q) => {
                if !(q.is_finite() && (1.0..=1e6).contains(&q)) {
                    return Err(Error::invalid(
                        field("grading"),
                        q,
                        "the ratio largest/smallest element must be in [1, 1e6]",
                    ));
                }
            }
        }
        Ok(())
    }

    /// Number of elements of the segment (its pieces for a meshed curve), computed without
    /// meshing (saturating for absurd divisions).
    pub fn element_count(&self) -> usize {
        if let SegmentShape::Meshed(c) = &self.shape {
            return c.pieces();
        }
        match self.division {
            Division::Count(n) => n,
            // A length that is a whole number of sizes up to rounding (1e-9) gives that
            // number, wherever the segment sits (its length is computed from translated
            // end points).
            Division::Size(h) => ((self.shape.length() / h - 1e-9).ceil() as usize).max(1),
        }
    }

    /// Element break points in the segment parameter t, from 0 to 1.
    pub(crate) fn breakpoints(&self) -> Vec<f64> {
        if let SegmentShape::Meshed(c) = &self.shape {
            return c.breakpoints();
        }
        let n = self.element_count();
        let weights: Vec<f64> = match self.grading {
            Grading::Uniform => vec![1.0; n],
            Grading::Start(q) | Grading::End(q) => {
                let g = if n > 1 {
                    q.powf(1.0 / (n - 1) as f64)
                } else {
                    1.0
                };
                let w: Vec<f64> = (0..n).map(|k| g.powi(k as i32)).collect();
                if matches!(self.grading, Grading::End(_)) {
                    w.into_iter().rev().collect()
                } else {
                    w
                }
            }
            Grading::BothEnds(q) => {
                let half = (n - 1) / 2;
                let g = if half > 0 {
                    q.powf(1.0 / half as f64)
                } else {
                    1.0
                };
                (0..n).map(|k| g.powi(k.min(n - 1 - k) as i32)).collect()
            }
        };
        let total: f64 = weights.iter().sum();
        let mut t = Vec::with_capacity(n + 1);
        let mut acc = 0.0;
        t.push(0.0);
        for w in &weights[..n - 1] {
            acc += w / total;
            t.push(acc);
        }
        t.push(1.0);
        t
    }
}

/// One item of a region's boundary loop.
#[derive(Debug, Clone, PartialEq)]
pub enum LoopItem {
    /// A segment owned by this region.
    Segment(Segment),
    /// The named segment of another region, traversed backwards: a bonded interface.
    Shared(String),
}

/// A body force acting on a region (the volume load q of the paper's (9)-(12)), N/m^3.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BodyForce {
    /// Gravity (or any uniform acceleration field): b = rho g.
    Gravity {
        /// Density rho, kg/m^3 (> 0).
        density: f64,
        /// Acceleration g = [gx, gy], m/s^2 (e.g. [0, -9.81]).
        acceleration: [f64; 2],
    },
    /// Steady rotation about the axis normal to the plane through `center` (the centrifugal
    /// load of the rotating frame): b = rho omega^2 (x - c).
    Centrifugal {
        /// Density rho, kg/m^3 (> 0).
        density: f64,
        /// Angular velocity omega, rad/s (its sign does not matter).
        angular_velocity: f64,
        /// A point c of the rotation axis, m.
        center: [f64; 2],
    },
}

impl BodyForce {
    /// Gravity: density (kg/m^3) and acceleration (m/s^2).
    pub fn gravity(density: f64, acceleration: [f64; 2]) -> Self {
        BodyForce::Gravity {
            density,
            acceleration,
        }
    }

    /// Rotation at `angular_velocity` (rad/s) about the axis through `center` (m).
    pub fn centrifugal(density: f64, angular_velocity: f64, center: [f64; 2]) -> Self {
        BodyForce::Centrifugal {
            density,
            angular_velocity,
            center,
        }
    }

    /// The body force at `x`, N/m^3.
    pub fn at(&self, x: [f64; 2]) -> [f64; 2] {
        match *self {
            BodyForce::Gravity {
                density,
                acceleration,
            } => [density * acceleration[0], density * acceleration[1]],
            BodyForce::Centrifugal {
                density,
                angular_velocity,
                center,
            } => {
                let k = density * angular_velocity * angular_velocity;
                [k * (x[0] - center[0]), k * (x[1] - center[1])]
            }
        }
    }

    /// Checks the parameters; errors name `field` (e.g. `region 'disc'.body_force[0]`).
    pub(crate) fn validate(&self, field: &str) -> Result<()> {
        let density = match *self {
            BodyForce::Gravity {
                density,
                acceleration,
            } => {
                finite_point(&format!("{field}.acceleration"), acceleration)?;
                density
            }
            BodyForce::Centrifugal {
                density,
                angular_velocity,
                center,
            } => {
                if !angular_velocity.is_finite() {
                    return Err(Error::invalid(
                        format!("{field}.angular_velocity"),
                        angular_velocity,
                        "must be finite (rad/s)",
                    ));
                }
                finite_point(&format!("{field}.center"), center)?;
                density
            }
        };
        if !(density.is_finite() && density > 0.0) {
            return Err(Error::invalid(
                format!("{field}.density"),
                density,
                "the density must be finite and > 0 (kg/m^3)",
            ));
        }
        Ok(())
    }
}

/// A homogeneous sub-region: one material, an outer loop (counter-clockwise) and holes
/// (clockwise), and the body forces acting on it.
#[derive(Debug, Clone, PartialEq)]
pub struct Region {
    /// Name (errors and results refer to it).
    pub name: String,
    /// Material.
    pub material: ElasticMaterial,
    /// Loops: the first is the outer boundary, the rest are holes.
    pub loops: Vec<Vec<LoopItem>>,
    /// Body forces (summed; none by default).
    pub body_forces: Vec<BodyForce>,
}

impl Region {
    /// A region bounded by one loop of its own segments.
    pub fn new(name: &str, material: ElasticMaterial, outer: Vec<Segment>) -> Self {
        Self {
            name: name.to_string(),
            material,
            loops: vec![outer.into_iter().map(LoopItem::Segment).collect()],
            body_forces: Vec::new(),
        }
    }

    /// Adds a hole (a clockwise loop of the region's own segments).
    pub fn with_hole(mut self, hole: Vec<Segment>) -> Self {
        self.loops
            .push(hole.into_iter().map(LoopItem::Segment).collect());
        self
    }

    /// Adds a body force (several add up: gravity and rotation together).
    pub fn with_body_force(mut self, force: BodyForce) -> Self {
        self.body_forces.push(force);
        self
    }
}

/// A 2D boundary element model: regions (bonded where they share segments) and the plane
/// condition.
#[derive(Debug, Clone, PartialEq)]
pub struct BemModel {
    /// Plane strain or plane stress.
    pub plane: PlaneCondition,
    /// The regions.
    pub regions: Vec<Region>,
}

impl BemModel {
    /// A model of the given regions.
    pub fn new(plane: PlaneCondition, regions: Vec<Region>) -> Self {
        Self { plane, regions }
    }

    /// Estimated peak memory (bytes) of meshing, assembling and solving the model
    /// ([`crate::solvers::bem2d::BemProblem::new`] then `solve`, or the contact solver),
    /// from the element counts alone (no meshing; saturating at usize::MAX).
    ///
    /// A segment of n quadratic elements has 2n + 1 functional nodes (two DOFs each) in
    /// every region whose loops hold it (its owner, and the region sharing it). With
    /// N_r DOFs in region r and N = sum N_r: the kept H and G take 16 sum N_r^2 bytes, and
    /// the solve the system matrix, its LU copy and the right-hand sides, at most 24 N^2
    /// (the contact solver factors the same system body by body, with one right-hand side
    /// per contact unknown). The small per-node data are neglected.
    pub fn memory_estimate(&self) -> usize {
        let nodes_of = |s: &Segment| s.element_count().saturating_mul(2).saturating_add(1);
        let owned: std::collections::HashMap<&str, usize> = self
            .regions
            .iter()
            .flat_map(|r| r.loops.iter().flatten())
            .filter_map(|it| match it {
                LoopItem::Segment(s) => Some((s.name.as_str(), nodes_of(s))),
                LoopItem::Shared(_) => None,
            })
            .collect();
        let mut kept: usize = 0;
        let mut total: usize = 0;
        for r in &self.regions {
            let nodes = r
                .loops
                .iter()
                .flatten()
                .map(|it| match it {
                    LoopItem::Segment(s) => nodes_of(s),
                    LoopItem::Shared(name) => owned.get(name.as_str()).copied().unwrap_or(0),
                })
                .fold(0usize, usize::saturating_add);
            let dof = nodes.saturating_mul(2);
            kept = kept.saturating_add(dof.saturating_mul(dof).saturating_mul(16));
            total = total.saturating_add(dof);
        }
        kept.saturating_add(total.saturating_mul(total).saturating_mul(24))
    }
}

/// Reference local coordinate of the end node of a segment's end element (a discontinuous
/// node, Brebbia & Dominguez sec. 5.8): collocation moves inside the element by a third of its
/// half-length, so that corners and changes of boundary condition carry no shared node.
pub const DISCONTINUOUS_OFFSET: f64 = 2.0 / 3.0;

/// One element of a segment in the segment's own direction, before numbering.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SegmentElement {
    /// Geometric nodes at xi = -1, 0, 1.
    pub geometry: [[f64; 2]; 3],
    /// Segment parameter t at xi = -1 and xi = 1.
    pub t_range: [f64; 2],
    /// Local coordinates of the three functional nodes.
    pub local: [f64; 3],
    /// Segment-local indices of the functional nodes.
    pub nodes: [usize; 3],
}

/// Meshes a segment: quadratic elements, continuous inside the segment, discontinuous
/// (offset nodes) at both ends. Returns the elements and the number of functional nodes.
pub(crate) fn mesh_segment(segment: &Segment) -> (Vec<SegmentElement>, usize) {
    let t = segment.breakpoints();
    let n = t.len() - 1;
    let mut out = Vec::with_capacity(n);
    for k in 0..n {
        let (t0, t1) = (t[k], t[k + 1]);
        let geometry = match &segment.shape {
            SegmentShape::Meshed(c) => c.piece(k),
            shape => [
                shape.point(t0),
                shape.point(0.5 * (t0 + t1)),
                shape.point(t1),
            ],
        };
        let first = if k == 0 { -DISCONTINUOUS_OFFSET } else { -1.0 };
        let last = if k == n - 1 {
            DISCONTINUOUS_OFFSET
        } else {
            1.0
        };
        out.push(SegmentElement {
            geometry,
            t_range: [t0, t1],
            local: [first, 0.0, last],
            nodes: [2 * k, 2 * k + 1, 2 * k + 2],
        });
    }
    (out, 2 * n + 1)
}
