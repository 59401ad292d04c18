//! The 2D elastostatic boundary element solver: boundary conditions per named segment and
//! direction, bonded interfaces between regions (zonal homogeneity), the dense solve, and the
//! interior displacement, stress and strain, and body forces (the paper's (1), (2), (7), (9)-(11) for one body
//! made of bonded homogeneous zones; contact pairs (4), (5), (8) between bodies are in
//! [`contact`]).
//!
//! System. Each region r gives `H_r u_r = G_r t_r` (see [`crate::operators::bem2d::assemble()`]).
//! At every node and direction either u or t is prescribed; on a bonded interface both
//! sides share the displacement and the tractions are opposite (u_A = u_B, t_A + t_B = 0,
//! (7)), and the owner side's u and t are both unknown. Moving the known columns to the right
//! hand side gives a square system `A x = b`, solved by LU with partial pivoting (faer).
//! Traction unknowns are scaled by the largest shear modulus so that A's columns are of one
//! order.
//!
//! Rigid-body modes: a body (regions joined by interfaces) whose prescribed displacements do
//! not restrain both translations and the rotation is reported as an
//! [`Error::InvalidParameter`] naming the body and the free mode, before any factorization.
//! (In a contact problem a body that takes part in a contact pair may leave modes free: they
//! are held by contact and friction, see [`contact`].)
//!
//! Body forces (the volume terms `L^(V)(q)` of (9)-(12)): gravity `rho g` and rotation
//! `rho omega^2 (x - c)` per region ([`crate::operators::bem2d::BodyForce`],
//! `Region::with_body_force`), by particular integrals (Banerjee, *The Boundary Element
//! Methods in Engineering*, 1994, sec. 4.4; Henry & Banerjee, IJNME 26 (1988) 2061-2077):
//! `u = u_c + u_p` with the closed-form particular solution u_p, sigma_p of
//! [`crate::kernels::body_force2d`] (exact for these affine forces, in plane strain and plane
//! stress), so the domain stays boundary-only. The unknowns remain the *total* nodal u and t;
//! each region's equations become `H u = G t + (H u_p - G t_p)` with `t_p = sigma_p n` at the
//! nodes, which is the homogeneous BIE `H (u - u_p) = G (t - t_p)`. Boundary conditions and the
//! bonded-interface conditions (u_A = u_B, t_A + t_B = 0) are therefore written on the totals
//! unchanged: the jumps of the particular fields across an interface of two materials or
//! densities are absorbed by the complementary fields. Interior points add u_p, sigma_p at
//! the point to the Somigliana identities of `u - u_p`, `t - t_p`; strains follow from the
//! total stress by Hooke's law. In contact ([`contact`]) the body forces are external loads,
//! scaled with `LoadStep::external`. Measured (tests `body_force_tests`): a column under its
//! own weight (quadratic closed form, represented exactly) 2e-11 in u, stress and strain in
//! both plane conditions; a rotating annulus at 2/4/8/16 elements per quarter arc: nodal u_r
//! 5.1e-3, 1.8e-3, 4.1e-4, 7.1e-5 of max u_r, interior stresses 3.3e-3, 4.4e-4, 5.5e-5,
//! 5.6e-6 of max sigma_t (plane stress; plane strain alike); two bonded rotating rings
//! (steel/aluminium, plane strain) 2.8e-3, 3.6e-4, 4.4e-5 in u_r and 2.8e-4, 9.9e-5, 2.9e-5 in
//! stress (1 mm from the bond); a block on a base under gravity in contact: contact force =
//! weight to 1e-12 (rigid top segment) and 2e-13 (free block, automatic support), uniform
//! pressure to 1.3e-10.
//!
//! Interior points (11): the Somigliana identities for u and sigma with the adaptive
//! near-singular rule of the operators (pieces subdivided until their distance is at least
//! their length, to depth 40, 16 Gauss points on the nearest pieces). Near the boundary the
//! quadrature stays exact, but the discretized boundary data amplify: at an element junction
//! (a kink of the quadratic u) the error of the stress grows like the nodal error times h/d.
//! Measured on the Lame cylinder (tests): 1e-5 .. 6e-5 of sigma_t down to d = 1e-4 h, 6e-4
//! at 1e-6 h, O(1) at 1e-8 h. Therefore a point closer than [`BOUNDARY_LAYER`] = 1e-4 of the
//! nearest element's length (including points on the boundary, or just outside it) is
//! evaluated at that distance along the inward normal from its foot point: an O(1e-4 h
//! grad sigma) shift, far below the discretization error. A point that close to elements
//! of two segments (a corner or any segment junction, where the discontinuous end nodes let
//! the interpolated u jump by the nodal error) takes the boundary-recovered displacement
//! of those elements at its foot points, averaged, and at a corner the stress that the
//! tractions of its sides determine (sigma n_k = t_k, least squares), elsewhere their
//! averaged recovered stress (below): the identities near a jump of u carry an error
//! ~ G |jump| / d (measured on the Lame cylinder's corners: O(1) of sigma at 1e-4 h, 5e-2
//! at 1.4e-4 h off both sides), the corner tractions 1e-3 at n = 8. Interior
//! points closer than about 1e-2 h to a segment junction (but outside the layer) still see
//! that error; a triangulation from [`crate::analysis::bem_field`] has none so close. Boundary nodal stresses (in
//! [`BemSolution::segment_results`]) are recovered from the traction and the tangential
//! derivative of the boundary displacement (Hooke's law in the boundary frame; Brebbia &
//! Dominguez sec. 5.6).

// Index loops read like the tensor formulas they implement.
#![allow(clippy::needless_range_loop)]

use std::fmt;
use std::sync::Arc;

use faer::linalg::solvers::Solve;
use faer::Mat;

use crate::error::{Error, Result};
use crate::kernels::kelvin2d::Kelvin2d;
use crate::operators::bem2d::assemble::{matrix_bytes_of, probe_memory, try_zeros_of, BemScalar};
use crate::operators::bem2d::integrate::{element_interior, piece_distance};
use crate::operators::bem2d::mesh::{dist, Element};
use crate::operators::bem2d::{assemble, BemMesh, BemModel, RegionMesh, RegionOperators};
use crate::solvers::nan_max;

/// A scalar load or displacement distribution along a segment.
#[derive(Clone)]
pub enum Profile {
    /// The same value everywhere.
    Uniform(f64),
    /// Linear in arc length from `start` (segment start) to `end` (segment end).
    Linear {
        /// Value at the segment's start.
        start: f64,
        /// Value at the segment's end.
        end: f64,
    },
    /// Any function of position (m -> value); results must be finite.
    Function(Arc<dyn Fn([f64; 2]) -> f64 + Send + Sync>),
}

impl fmt::Debug for Profile {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Profile::Uniform(v) => write!(f, "Uniform({v})"),
            Profile::Linear { start, end } => write!(f, "Linear({start} -> {end})"),
            Profile::Function(_) => write!(f, "Function(..)"),
        }
    }
}

impl Profile {
    /// A profile from a closure.
    pub fn function(f: impl Fn([f64; 2]) -> f64 + Send + Sync + 'static) -> Self {
        Profile::Function(Arc::new(f))
    }

    fn value(&self, position: [f64; 2], param: f64) -> f64 {
        match self {
            Profile::Uniform(v) => *v,
            Profile::Linear { start, end } => start + (end - start) * param,
            Profile::Function(f) => f(position),
        }
    }
}

/// What is prescribed in one global direction.
#[derive(Debug, Clone)]
pub enum Component {
    /// Displacement (m).
    Displacement(Profile),
    /// Traction (Pa).
    Traction(Profile),
}

/// Boundary condition of one segment.
#[derive(Debug, Clone)]
pub enum SegmentBc {
    /// Traction-free (the default for segments without a condition).
    Free,
    /// Per global direction (x, y): displacement or traction.
    Components {
        /// x direction.
        x: Component,
        /// y direction.
        y: Component,
    },
    /// Normal pressure p (Pa, compressive positive): t = -p n.
    Pressure(Profile),
}

impl SegmentBc {
    /// u = 0 in both directions.
    pub fn fixed() -> Self {
        Self::displacement(Profile::Uniform(0.0), Profile::Uniform(0.0))
    }

    /// Prescribed displacement in both directions.
    pub fn displacement(ux: Profile, uy: Profile) -> Self {
        SegmentBc::Components {
            x: Component::Displacement(ux),
            y: Component::Displacement(uy),
        }
    }

    /// Prescribed traction in both directions.
    pub fn traction(tx: Profile, ty: Profile) -> Self {
        SegmentBc::Components {
            x: Component::Traction(tx),
            y: Component::Traction(ty),
        }
    }

    /// Symmetry (roller) on a line of constant x: u_x = 0, t_y = 0.
    pub fn roller_x() -> Self {
        SegmentBc::Components {
            x: Component::Displacement(Profile::Uniform(0.0)),
            y: Component::Traction(Profile::Uniform(0.0)),
        }
    }

    /// Symmetry (roller) on a line of constant y: u_y = 0, t_x = 0.
    pub fn roller_y() -> Self {
        SegmentBc::Components {
            x: Component::Traction(Profile::Uniform(0.0)),
            y: Component::Displacement(Profile::Uniform(0.0)),
        }
    }
}

/// Boundary conditions by segment name, each optionally in a named load group.
///
/// Load groups matter only for the load steps of [`contact::ContactProblem`], where each
/// group has its own factor ([`contact::LoadStep::groups`]; ungrouped conditions take
/// [`contact::LoadStep::external`]). [`BemProblem::solve`] applies every condition with
/// factor 1, whatever its group.
#[derive(Debug, Clone, Default)]
pub struct BoundaryConditions {
    /// (segment, condition, load group or None).
    entries: Vec<(String, SegmentBc, Option<String>)>,
}

impl BoundaryConditions {
    /// No conditions (every segment traction-free).
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds the condition of segment `name` (in no load group).
    pub fn set(mut self, name: &str, bc: SegmentBc) -> Self {
        self.entries.push((name.to_string(), bc, None));
        self
    }

    /// Adds the condition of segment `name` in load group `group` (scaled in each load step
    /// by that group's factor; see [`contact::LoadStep`]).
    pub fn set_in_group(mut self, name: &str, bc: SegmentBc, group: &str) -> Self {
        self.entries
            .push((name.to_string(), bc, Some(group.to_string())));
        self
    }

    /// The named load groups, in the order of their first use.
    pub fn groups(&self) -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        for (_, _, g) in &self.entries {
            if let Some(g) = g {
                if !out.contains(g) {
                    out.push(g.clone());
                }
            }
        }
        out
    }
}

/// In-plane stress plus sigma_zz (Pa), tension positive.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Stress2d {
    /// sigma_xx.
    pub xx: f64,
    /// sigma_yy.
    pub yy: f64,
    /// sigma_xy.
    pub xy: f64,
    /// sigma_zz (nu (sxx + syy) in plane strain, 0 in plane stress).
    pub zz: f64,
}

/// In-plane strain (tensor shear) plus eps_zz.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Strain2d {
    /// eps_xx.
    pub xx: f64,
    /// eps_yy.
    pub yy: f64,
    /// eps_xy (tensor component, half the engineering shear).
    pub xy: f64,
    /// eps_zz.
    pub zz: f64,
}

/// Results at one boundary node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoundaryResult {
    /// Position, m.
    pub position: [f64; 2],
    /// Outward normal (of the owner region).
    pub normal: [f64; 2],
    /// Segment parameter in [0, 1].
    pub param: f64,
    /// Displacement, m.
    pub displacement: [f64; 2],
    /// Traction on the owner region, Pa.
    pub traction: [f64; 2],
    /// Stress recovered from the traction and the tangential strain (element average).
    pub stress: Stress2d,
}

/// A meshed model with its assembled operators: the input of [`BemProblem::solve`]. The
/// per-region H and G and the node/segment maps are public so that a contact solver can
/// condense the system onto contact unknowns.
#[derive(Debug, Clone)]
pub struct BemProblem {
    /// The validated mesh.
    pub mesh: BemMesh,
    /// H and G per region.
    pub operators: Vec<RegionOperators>,
}

/// How one nodal DOF enters the system.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Dof {
    /// u unknown (column), t known.
    U { col: usize, t: f64 },
    /// t unknown (column, scaled), u known.
    T { col: usize, u: f64 },
    /// Interface: both unknown; traction = sign * owner traction.
    Interface {
        u_col: usize,
        t_col: usize,
        sign: f64,
    },
}

/// The solved boundary state.
#[derive(Debug, Clone, serde::Serialize)]
pub struct BemSolution {
    #[serde(skip)]
    mesh: BemMesh,
    /// Nodal displacements per region, m.
    pub displacement: Vec<Vec<[f64; 2]>>,
    /// Nodal tractions per region (on that region), Pa.
    pub traction: Vec<Vec<[f64; 2]>>,
    /// Relative residual ||A x - b||_inf / (||A||_inf ||x||_inf + ||b||_inf) of the solve.
    pub residual: f64,
    /// Factor on the regions' body forces in this state (1, or the load step's factor of
    /// the external loads in contact).
    #[serde(skip)]
    body_force_factor: f64,
}

impl BemProblem {
    /// Meshes, validates and assembles `model`.
    pub fn new(model: &BemModel) -> Result<Self> {
        let mesh = BemMesh::new(model)?;
        let operators = assemble(&mesh)?;
        Ok(Self { mesh, operators })
    }

    /// Number of boundary unknowns.
    pub fn dof(&self) -> usize {
        self.mesh.dof()
    }

    /// The body-force term of region `r`'s boundary equations, `H u_p - G t_p` (length 2n,
    /// row 2 i + d), with the particular solution's nodal displacements u_p and tractions
    /// t_p = sigma_p n (module docs); None for a region without body forces.
    pub(crate) fn body_force_rhs(&self, r: usize) -> Option<Vec<f64>> {
        let region = &self.mesh.regions[r];
        region.body_force?;
        let ops = &self.operators[r];
        let n2 = ops.h.nrows();
        let mut out = vec![0.0; n2];
        for i in 0..region.nodes.len() {
            let (up, tp) = region.particular_at_node(i);
            for d in 0..2 {
                let (hc, gc) = (ops.h.col(2 * i + d), ops.g.col(2 * i + d));
                for row in 0..n2 {
                    out[row] += hc[row] * up[d] - gc[row] * tp[d];
                }
            }
        }
        Some(out)
    }

    /// The DOF layout of `bcs`: per region, node and direction how the DOF enters the
    /// system (columns numbered by segment, owner node and direction), and the number of
    /// unknowns.
    pub(crate) fn dofs(&self, bcs: &BoundaryConditions) -> Result<(Vec<Vec<[Dof; 2]>>, usize)> {
        let mesh = &self.mesh;
        let mut given: Vec<Option<&SegmentBc>> = vec![None; mesh.segments.len()];
        for (name, bc, _) in &bcs.entries {
            let s = mesh.segment_index(name).ok_or_else(|| {
                Error::invalid(
                    "boundary_condition.segment",
                    name,
                    "names no segment of the model",
                )
            })?;
            if mesh.segments[s].partner.is_some() {
                return Err(Error::invalid(
                    "boundary_condition.segment",
                    name,
                    "is a bonded interface between regions; it takes no boundary condition",
                ));
            }
            if given[s].is_some() {
                return Err(Error::invalid(
                    "boundary_condition.segment",
                    name,
                    "has two boundary conditions",
                ));
            }
            given[s] = Some(bc);
        }
        let placeholder = Dof::U {
            col: usize::MAX,
            t: 0.0,
        };
        let mut dofs: Vec<Vec<[Dof; 2]>> = mesh
            .regions
            .iter()
            .map(|r| vec![[placeholder; 2]; r.nodes.len()])
            .collect();
        let mut col = 0;
        for (s, seg) in mesh.segments.iter().enumerate() {
            let region = &mesh.regions[seg.owner];
            if let Some((pr, pnodes)) = &seg.partner {
                for (&o, &q) in seg.owner_nodes.iter().zip(pnodes) {
                    for d in 0..2 {
                        let (u_col, t_col) = (col, col + 1);
                        col += 2;
                        dofs[seg.owner][o][d] = Dof::Interface {
                            u_col,
                            t_col,
                            sign: 1.0,
                        };
                        dofs[*pr][q][d] = Dof::Interface {
                            u_col,
                            t_col,
                            sign: -1.0,
                        };
                    }
                }
                continue;
            }
            let bc = given[s].unwrap_or(&SegmentBc::Free);
            for &o in &seg.owner_nodes {
                let node = &region.nodes[o];
                let value = |p: &Profile| -> Result<f64> {
                    let v = p.value(node.position, node.param);
                    if v.is_finite() {
                        Ok(v)
                    } else {
                        Err(Error::invalid(
                            format!("boundary_condition '{}'", seg.name),
                            v,
                            format!(
                                "the prescribed value at ({:.6e}, {:.6e}) must be finite",
                                node.position[0], node.position[1]
                            ),
                        ))
                    }
                };
                for d in 0..2 {
                    let dof = match bc {
                        SegmentBc::Free => Dof::U { col, t: 0.0 },
                        SegmentBc::Pressure(p) => Dof::U {
                            col,
                            t: -value(p)? * node.normal[d],
                        },
                        SegmentBc::Components { x, y } => match if d == 0 { x } else { y } {
                            Component::Displacement(p) => Dof::T { col, u: value(p)? },
                            Component::Traction(p) => Dof::U { col, t: value(p)? },
                        },
                    };
                    col += 1;
                    dofs[seg.owner][o][d] = dof;
                }
            }
        }
        Ok((dofs, col))
    }

    /// The bodies (regions joined by bonded interfaces), each as its sorted member regions,
    /// ordered by their union-find roots ([`region_bodies`]).
    fn bodies(&self) -> Vec<Vec<usize>> {
        let body = region_bodies(&self.mesh);
        (0..body.len())
            .filter(|&root| body[root] == root)
            .map(|root| (0..body.len()).filter(|&r| body[r] == root).collect())
            .collect()
    }

    /// Rigid-body check: every body (regions joined by interfaces) must have prescribed
    /// displacements that restrain x and y translation and the rotation.
    fn check_restraint(&self, dofs: &[Vec<[Dof; 2]>]) -> Result<()> {
        for members in self.bodies() {
            self.check_body_restraint(dofs, &members)?;
        }
        Ok(())
    }

    /// The rigid-body check of one body (its member regions).
    fn check_body_restraint(&self, dofs: &[Vec<[Dof; 2]>], members: &[usize]) -> Result<()> {
        let mesh = &self.mesh;
        {
            let mut rows: Vec<(usize, [f64; 2])> = Vec::new();
            for &r in members {
                for (node, d) in mesh.regions[r].nodes.iter().zip(&dofs[r]) {
                    for (dir, dof) in d.iter().enumerate() {
                        if matches!(dof, Dof::T { .. }) {
                            rows.push((dir, node.position));
                        }
                    }
                }
            }
            let names: Vec<&str> = members
                .iter()
                .map(|&r| mesh.regions[r].name.as_str())
                .collect();
            let field = format!("body [{}]", names.join(", "));
            // Columns: translation x, translation y, rotation about the centroid of the
            // constrained points (scaled by their spread).
            let k = rows.len().max(1) as f64;
            let c = rows
                .iter()
                .fold([0.0, 0.0], |a, (_, p)| [a[0] + p[0] / k, a[1] + p[1] / k]);
            let spread = rows
                .iter()
                .map(|(_, p)| dist(*p, c))
                .fold(0.0_f64, f64::max)
                .max(f64::MIN_POSITIVE);
            let cols: Vec<[f64; 3]> = rows
                .iter()
                .map(|(dir, p)| {
                    let rot = if *dir == 0 {
                        -(p[1] - c[1])
                    } else {
                        p[0] - c[0]
                    } / spread;
                    [(*dir == 0) as u8 as f64, (*dir == 1) as u8 as f64, rot]
                })
                .collect();
            // Gram-Schmidt on the three columns.
            let mut basis: Vec<Vec<f64>> = Vec::new();
            for (m, mode) in ["translation in x", "translation in y", "rotation"]
                .iter()
                .enumerate()
            {
                let mut v: Vec<f64> = cols.iter().map(|c| c[m]).collect();
                for b in &basis {
                    let dot: f64 = v.iter().zip(b).map(|(a, b)| a * b).sum();
                    v.iter_mut().zip(b).for_each(|(a, b)| *a -= dot * b);
                }
                let norm = v.iter().map(|a| a * a).sum::<f64>().sqrt();
                if norm < 1e-6 {
                    return Err(Error::invalid(
                        field,
                        format!("{} prescribed displacement components", rows.len()),
                        format!(
                            "the body is not restrained against rigid-body {mode}: prescribe \
                             displacements that fix both translations and the rotation"
                        ),
                    ));
                }
                basis.push(v.into_iter().map(|a| a / norm).collect());
            }
        }
        Ok(())
    }

    /// Solves for the boundary state under `bcs`.
    ///
    /// Errors: a condition on an unknown or interface segment, or one given twice; a
    /// non-finite prescribed value; an unrestrained body ([`Error::InvalidParameter`]); a
    /// singular or inaccurate solve ([`Error::Numerical`]).
    pub fn solve(&self, bcs: &BoundaryConditions) -> Result<BemSolution> {
        let (dofs, ncol) = self.dofs(bcs)?;
        self.check_restraint(&dofs)?;
        let known = known_values(&dofs);
        let ops: Vec<(&Mat<f64>, &Mat<f64>)> =
            self.operators.iter().map(|o| (&o.h, &o.g)).collect();
        let extra: Vec<Option<Vec<f64>>> = (0..self.operators.len())
            .map(|r| self.body_force_rhs(r))
            .collect();
        let (x, residual) = self.solve_system(&dofs, ncol, &ops, &known, &extra)?;
        let (displacement, traction) = self.unpack(&dofs, &x, &known);
        Ok(BemSolution {
            mesh: self.mesh.clone(),
            displacement,
            traction,
            residual,
            body_force_factor: 1.0,
        })
    }

    /// The scale of the traction unknowns: the largest shear modulus (Pa).
    pub(crate) fn traction_scale(&self) -> f64 {
        self.mesh
            .regions
            .iter()
            .map(|r| r.kernels.shear_modulus())
            .fold(0.0_f64, f64::max)
    }

    /// Builds and solves the square system `A x = b` of the DOF layout `dofs` (`ncol`
    /// unknowns) with the region matrices `ops` = (H_r, G_r), the known values `known`
    /// (per region, node and direction: the traction of a [`Dof::U`], the displacement of a
    /// [`Dof::T`]; ignored on interfaces) and optional extra right-hand sides per region
    /// (the body-force terms). Real (elastostatics) or complex (the Laplace-domain BEM).
    /// Returns the solution (traction unknowns scaled by [`BemProblem::traction_scale`])
    /// and the relative residual.
    ///
    /// Errors: [`Error::OutOfMemory`]; a singular or inaccurate solve ([`Error::Numerical`]).
    pub(crate) fn solve_system<T: BemScalar>(
        &self,
        dofs: &[Vec<[Dof; 2]>],
        ncol: usize,
        ops: &[(&Mat<T>, &Mat<T>)],
        known: &[Vec<[T; 2]>],
        extra: &[Option<Vec<f64>>],
    ) -> Result<(Mat<T>, f64)> {
        let (a, b) = self.assemble_system(dofs, ncol, ops, known, extra)?;
        self.solve_assembled(a, b)
    }

    /// The matrix `A` and right-hand side `b` of [`BemProblem::solve_system`] (the traction
    /// columns scaled by [`BemProblem::traction_scale`]).
    ///
    /// Errors: [`Error::OutOfMemory`].
    pub(crate) fn assemble_system<T: BemScalar>(
        &self,
        dofs: &[Vec<[Dof; 2]>],
        ncol: usize,
        ops: &[(&Mat<T>, &Mat<T>)],
        known: &[Vec<[T; 2]>],
        extra: &[Option<Vec<f64>>],
    ) -> Result<(Mat<T>, Mat<T>)> {
        let nrow = self.dof();
        debug_assert_eq!(nrow, ncol);
        let scale = self.traction_scale();
        let what = format!("the 2D BEM system matrix ({nrow} x {ncol})");
        let mut a = try_zeros_of::<T>(&what, nrow, ncol)?;
        let mut b = try_zeros_of::<T>(&what, nrow, 1)?;
        let mut offset = 0;
        for (r, (h, g)) in ops.iter().enumerate() {
            let n2 = h.nrows();
            for (node, d) in dofs[r].iter().enumerate() {
                for (dir, dof) in d.iter().enumerate() {
                    let c = 2 * node + dir;
                    let (hc, gc) = (h.col(c), g.col(c));
                    let value = known[r][node][dir];
                    match *dof {
                        Dof::U { col, .. } => {
                            for row in 0..n2 {
                                a[(offset + row, col)] += hc[row];
                                b[(offset + row, 0)] += gc[row] * value;
                            }
                        }
                        Dof::T { col, .. } => {
                            for row in 0..n2 {
                                a[(offset + row, col)] -= gc[row] * scale;
                                b[(offset + row, 0)] -= hc[row] * value;
                            }
                        }
                        Dof::Interface { u_col, t_col, sign } => {
                            for row in 0..n2 {
                                a[(offset + row, u_col)] += hc[row];
                                a[(offset + row, t_col)] -= gc[row] * sign * scale;
                            }
                        }
                    }
                }
            }
            if let Some(Some(bf)) = extra.get(r) {
                for (row, v) in bf.iter().enumerate() {
                    b[(offset + row, 0)] += T::from_f64(*v);
                }
            }
            offset += n2;
        }
        Ok((a, b))
    }

    /// LU-solves the assembled system `A x = b` (any number of right-hand sides) and checks
    /// it: returns the solution and the relative residual (infinity norms over all columns).
    ///
    /// Errors: [`Error::OutOfMemory`]; a singular or inaccurate solve ([`Error::Numerical`]).
    pub(crate) fn solve_assembled<T: BemScalar>(
        &self,
        a: Mat<T>,
        b: Mat<T>,
    ) -> Result<(Mat<T>, f64)> {
        let (nrow, ncol) = (a.nrows(), a.ncols());
        // The LU's copy of A and the residual check's product: allocated inside faer.
        probe_memory(
            &format!("the LU factorization of the 2D BEM system ({nrow} x {ncol})"),
            matrix_bytes_of::<T>(nrow, ncol),
        )?;
        let lu = a.partial_piv_lu();
        let x = lu.solve(&b);
        let res = &a * &x - &b;
        let inf = |m: &Mat<T>| {
            let mut v = 0.0_f64;
            for i in 0..m.nrows() {
                let row: f64 = (0..m.ncols()).map(|j| m[(i, j)].modulus()).sum();
                v = nan_max(v, row);
            }
            v
        };
        let (na, nx, nb, nr) = (inf(&a), inf(&x), inf(&b), inf(&res));
        let residual = nr / (na * nx + nb).max(f64::MIN_POSITIVE);
        if !(residual.is_finite() && residual < 1e-8)
            || (0..x.ncols()).any(|j| (0..ncol).any(|i| !x[(i, j)].finite()))
        {
            return Err(Error::Numerical {
                context: "2D BEM solve",
                detail: format!(
                    "the LU solve of the {nrow} x {ncol} system failed (relative residual \
                     {residual:.3e}); the system is singular or ill-conditioned"
                ),
            });
        }
        Ok((x, residual))
    }

    /// Nodal displacements and tractions per region from the solution `x` of
    /// [`BemProblem::solve_system`] and the known values.
    #[allow(clippy::type_complexity)]
    pub(crate) fn unpack<T: BemScalar>(
        &self,
        dofs: &[Vec<[Dof; 2]>],
        x: &Mat<T>,
        known: &[Vec<[T; 2]>],
    ) -> (Vec<Vec<[T; 2]>>, Vec<Vec<[T; 2]>>) {
        let scale = self.traction_scale();
        let mut displacement = Vec::new();
        let mut traction = Vec::new();
        for (d, kn) in dofs.iter().zip(known) {
            let mut u = Vec::with_capacity(d.len());
            let mut t = Vec::with_capacity(d.len());
            for (node, k) in d.iter().zip(kn) {
                let mut un = [T::default(); 2];
                let mut tn = [T::default(); 2];
                for dir in 0..2 {
                    match node[dir] {
                        Dof::U { col, .. } => {
                            un[dir] = x[(col, 0)];
                            tn[dir] = k[dir];
                        }
                        Dof::T { col, .. } => {
                            un[dir] = k[dir];
                            tn[dir] = x[(col, 0)] * scale;
                        }
                        Dof::Interface { u_col, t_col, sign } => {
                            un[dir] = x[(u_col, 0)];
                            tn[dir] = x[(t_col, 0)] * sign * scale;
                        }
                    }
                }
                u.push(un);
                t.push(tn);
            }
            displacement.push(u);
            traction.push(t);
        }
        (displacement, traction)
    }
}

/// The known values of a DOF layout (per region, node and direction: the prescribed
/// traction of a [`Dof::U`], displacement of a [`Dof::T`], 0 on interfaces).
pub(crate) fn known_values(dofs: &[Vec<[Dof; 2]>]) -> Vec<Vec<[f64; 2]>> {
    dofs.iter()
        .map(|d| {
            d.iter()
                .map(|node| {
                    node.map(|dof| match dof {
                        Dof::U { t, .. } => t,
                        Dof::T { u, .. } => u,
                        Dof::Interface { .. } => 0.0,
                    })
                })
                .collect()
        })
        .collect()
}

/// Where a point is evaluated (see [`locate_in_region`]).
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Site {
    /// The Somigliana identities at this point (inside the region).
    Interior([f64; 2]),
    /// A segment junction (corner): the boundary-recovered fields of these elements at
    /// these local coordinates, averaged.
    Junction(Vec<(usize, f64)>),
}

/// Points closer to the boundary than this fraction of the nearest element's length are
/// evaluated at this distance along the inward normal (see the module docs).
pub const BOUNDARY_LAYER: f64 = 1e-4;

impl BemSolution {
    /// The mesh the solution lives on.
    pub fn mesh(&self) -> &BemMesh {
        &self.mesh
    }

    fn nodal(&self, r: usize, e: &Element) -> ([[f64; 2]; 3], [[f64; 2]; 3]) {
        let u = e.nodes.map(|m| self.displacement[r][m]);
        let t = e.nodes.map(|m| self.traction[r][m]);
        (u, t)
    }

    /// The region holding `p` and the point to evaluate (p itself, or p moved to
    /// [`BOUNDARY_LAYER`] of an element length inside the boundary).
    fn locate(&self, p: [f64; 2]) -> Result<(usize, Site)> {
        finite(p)?;
        for r in 0..self.mesh.regions.len() {
            if let Some(q) = self.locate_in(r, p) {
                return Ok((r, q));
            }
        }
        Err(Error::invalid(
            "point",
            format!("({:.6e}, {:.6e})", p[0], p[1]),
            "lies outside every region of the model",
        ))
    }

    /// The site of `p` in region `r` ([`locate_in_region`]).
    fn locate_in(&self, r: usize, p: [f64; 2]) -> Option<Site> {
        locate_in_region(&self.mesh, r, p)
    }

    /// Displacement (m), stress (Pa) and strain at `p` in the known region `region`, without
    /// searching the other regions; the [`BOUNDARY_LAYER`] rule applies to the region's own
    /// boundary as in [`BemSolution::stress_at`]. The same bits as
    /// [`BemSolution::displacement_at`], [`BemSolution::stress_at`] and
    /// [`BemSolution::strain_at`] where `region` is the first region holding `p`.
    ///
    /// Errors: `region` out of range, `p` not finite, or `p` outside the region (farther
    /// than the boundary layer).
    pub(crate) fn fields_in_region(
        &self,
        region: usize,
        p: [f64; 2],
    ) -> Result<([f64; 2], Stress2d, Strain2d)> {
        let nr = self.mesh.regions.len();
        if region >= nr {
            return Err(Error::invalid(
                "region",
                region,
                format!("must be a region index < {nr} (the model's region count)"),
            ));
        }
        finite(p)?;
        let q = self.locate_in(region, p).ok_or_else(|| {
            Error::invalid(
                "point",
                format!("({:.6e}, {:.6e})", p[0], p[1]),
                format!("lies outside region '{}'", self.mesh.regions[region].name),
            )
        })?;
        let (u, s) = self.evaluate(region, &q);
        let k = &self.mesh.regions[region].kernels;
        Ok((u, self.stress2d(region, s), strain2d(k, s)))
    }

    fn stress2d(&self, r: usize, s: [f64; 3]) -> Stress2d {
        Stress2d {
            xx: s[0],
            yy: s[1],
            xy: s[2],
            zz: self.mesh.regions[r].kernels.sigma_zz(s[0], s[1]),
        }
    }

    /// Displacement at `p` (inside a region or on its boundary), m.
    pub fn displacement_at(&self, p: [f64; 2]) -> Result<[f64; 2]> {
        let (r, q) = self.locate(p)?;
        Ok(self.evaluate(r, &q).0)
    }

    /// Stress at `p` (inside a region or on its boundary), Pa.
    pub fn stress_at(&self, p: [f64; 2]) -> Result<Stress2d> {
        let (r, q) = self.locate(p)?;
        Ok(self.stress2d(r, self.evaluate(r, &q).1))
    }

    /// Strain at `p` (Hooke's law of the local material), dimensionless.
    pub fn strain_at(&self, p: [f64; 2]) -> Result<Strain2d> {
        let (r, q) = self.locate(p)?;
        let s = self.evaluate(r, &q).1;
        Ok(strain2d(&self.mesh.regions[r].kernels, s))
    }

    /// Displacement and in-plane stress [xx, yy, xy] at a located site of region r.
    fn evaluate(&self, r: usize, site: &Site) -> ([f64; 2], [f64; 3]) {
        match site {
            Site::Interior(p) => self.interior(r, *p),
            Site::Junction(feet) => junction_fields(
                &self.mesh.regions[r],
                feet,
                &self.displacement[r],
                &self.traction[r],
            ),
        }
    }

    /// Interior displacement and stress: the particular solution at p plus the Somigliana
    /// identities of the complementary boundary data u - u_p, t - t_p.
    fn interior(&self, r: usize, p: [f64; 2]) -> ([f64; 2], [f64; 3]) {
        let region = &self.mesh.regions[r];
        let lam = self.body_force_factor;
        let (mut u, mut s) = region.particular_at(p);
        u.iter_mut().for_each(|v| *v *= lam);
        s.iter_mut().for_each(|v| *v *= lam);
        let particular = region.body_force.is_some();
        // The Somigliana integrals in model-local coordinates (`RegionMesh::local_elements`).
        let o = self.mesh.origin;
        let pl = [p[0] - o[0], p[1] - o[1]];
        for e in &region.local_elements {
            let (mut ue, mut te) = self.nodal(r, e);
            if particular {
                for (k, &m) in e.nodes.iter().enumerate() {
                    let (up, tp) = region.particular_at_node(m);
                    for d in 0..2 {
                        ue[k][d] -= lam * up[d];
                        te[k][d] -= lam * tp[d];
                    }
                }
            }
            element_interior(&region.kernels, e, pl, &ue, &te, &mut u, &mut s);
        }
        (u, s)
    }

    /// Stress on element k of region r at xi from the traction and the tangential strain.
    fn boundary_stress(&self, r: usize, k: usize, xi: f64) -> [f64; 3] {
        let region = &self.mesh.regions[r];
        let e = &region.elements[k];
        let (u, t) = self.nodal(r, e);
        element_boundary_stress(&region.kernels, e, &u, &t, xi)
    }

    /// The resultant of the traction on segment `name` (on its owner region): the force
    /// (N per m of thickness) and its moment about `about` (N m per m, counter-clockwise
    /// positive), integrated over the segment's elements with 8 Gauss points each (exact for
    /// straight elements, whose traction is quadratic; the curved Jacobian's error is far
    /// below the discretization's). On a displacement-held segment this is the reaction of
    /// the support on the body.
    pub fn segment_resultant(&self, name: &str, about: [f64; 2]) -> Result<([f64; 2], f64)> {
        let s = self
            .mesh
            .segment_index(name)
            .ok_or_else(|| Error::invalid("segment", name, "names no segment of the model"))?;
        let r = self.mesh.segments[s].owner;
        let (gx, gw) = crate::kernels::quadrature::gauss_legendre(8);
        let (mut force, mut moment) = ([0.0; 2], 0.0);
        for e in self.mesh.regions[r]
            .elements
            .iter()
            .filter(|e| e.segment == s)
        {
            let (_, t) = self.nodal(r, e);
            for (&xi, &w) in gx.iter().zip(&gw) {
                let x = e.point(xi);
                let (_, jac) = e.normal_jacobian(xi);
                let nk = e.field_shape(xi);
                let tq: [f64; 2] = [0, 1].map(|d| (0..3).map(|m| nk[m] * t[m][d]).sum());
                force[0] += w * jac * tq[0];
                force[1] += w * jac * tq[1];
                moment += w * jac * ((x[0] - about[0]) * tq[1] - (x[1] - about[1]) * tq[0]);
            }
        }
        Ok((force, moment))
    }

    /// Nodal results along segment `name` (owner side), in the segment's direction.
    pub fn segment_results(&self, name: &str) -> Result<Vec<BoundaryResult>> {
        let s = self
            .mesh
            .segment_index(name)
            .ok_or_else(|| Error::invalid("segment", name, "names no segment of the model"))?;
        let seg = &self.mesh.segments[s];
        let r = seg.owner;
        let region = &self.mesh.regions[r];
        let kern: &Kelvin2d = &region.kernels;
        let mut out = Vec::with_capacity(seg.owner_nodes.len());
        for &o in &seg.owner_nodes {
            let node = &region.nodes[o];
            let mut acc = [0.0; 3];
            let mut count = 0.0;
            for (k, e) in region.elements.iter().enumerate() {
                if let Some(m) = e.nodes.iter().position(|&q| q == o) {
                    let st = self.boundary_stress(r, k, e.local[m]);
                    for c in 0..3 {
                        acc[c] += st[c];
                    }
                    count += 1.0;
                }
            }
            let st = acc.map(|v| v / count);
            out.push(BoundaryResult {
                position: node.position,
                normal: node.normal,
                param: node.param,
                displacement: self.displacement[r][o],
                traction: self.traction[r][o],
                stress: Stress2d {
                    xx: st[0],
                    yy: st[1],
                    xy: st[2],
                    zz: kern.sigma_zz(st[0], st[1]),
                },
            });
        }
        Ok(out)
    }
}

/// The in-plane stress [xx, yy, xy] (Pa) on element `e` at local coordinate `xi` from its
/// nodal displacements `u` (m) and tractions `t` (Pa) (Hooke's law is instantaneous, so the
/// same recovery serves the static and the dynamic BEM): the traction gives sigma_nn and
/// sigma_nt, the tangential derivative of u along the element the strain eps_tt, and
/// [`Kelvin2d::tangential_stress`] sigma_tt.
pub(crate) fn element_boundary_stress(
    kernels: &Kelvin2d,
    e: &Element,
    u: &[[f64; 2]; 3],
    t: &[[f64; 2]; 3],
    xi: f64,
) -> [f64; 3] {
    let (n, jac) = e.normal_jacobian(xi);
    let s = [-n[1], n[0]];
    let nk = e.field_shape(xi);
    let dn = e.field_shape_derivative(xi);
    let tt: [f64; 2] = [0, 1].map(|d| (0..3).map(|m| nk[m] * t[m][d]).sum());
    let du: [f64; 2] = [0, 1].map(|d| (0..3).map(|m| dn[m] * u[m][d]).sum::<f64>() / jac);
    let eps_tt = du[0] * s[0] + du[1] * s[1];
    let snn = tt[0] * n[0] + tt[1] * n[1];
    let snt = tt[0] * s[0] + tt[1] * s[1];
    let stt = kernels.tangential_stress(eps_tt, snn);
    let comp = |i: usize, j: usize| {
        snn * n[i] * n[j] + stt * s[i] * s[j] + snt * (n[i] * s[j] + s[i] * n[j])
    };
    [comp(0, 0), comp(1, 1), comp(0, 1)]
}

/// The displacement (m) and in-plane stress [xx, yy, xy] (Pa) at a segment junction of
/// `region` ([`Site::Junction`], module docs) from the region's nodal displacements
/// `u_nodal` (m) and tractions `t_nodal` (Pa), one per node: the displacement recovered on
/// each element at its foot point `feet` (element, xi), averaged; at a corner the stress
/// whose tractions on the sides are theirs (sigma n_k = t_k, least squares), along a smooth
/// junction the recovered stress ([`element_boundary_stress`]) averaged. Linear in the
/// boundary data and instantaneous (Hooke's law), so the Laplace-domain BEM applies the
/// same rule to its transformed boundary state. `feet` and the node arrays must be of
/// `region`.
pub(crate) fn junction_fields(
    region: &RegionMesh,
    feet: &[(usize, f64)],
    u_nodal: &[[f64; 2]],
    t_nodal: &[[f64; 2]],
) -> ([f64; 2], [f64; 3]) {
    let w = 1.0 / feet.len() as f64;
    let mut u = [0.0; 2];
    let mut s = [0.0; 3];
    // Normal equations of sigma n_k = t_k over the elements (unknowns sxx, syy,
    // sxy; rows [n_x, 0, n_y] and [0, n_y, n_x]).
    let mut ata = [[0.0; 3]; 3];
    let mut atb = [0.0; 3];
    let mut normals = Vec::with_capacity(feet.len());
    for &(k, xi) in feet {
        let e = &region.elements[k];
        let nk = e.field_shape(xi);
        let ue = e.nodes.map(|m| u_nodal[m]);
        let te = e.nodes.map(|m| t_nodal[m]);
        let mut t = [0.0; 2];
        for d in 0..2 {
            u[d] += w * (0..3).map(|m| nk[m] * ue[m][d]).sum::<f64>();
            t[d] = (0..3).map(|m| nk[m] * te[m][d]).sum::<f64>();
        }
        let st = element_boundary_stress(&region.kernels, e, &ue, &te, xi);
        for c in 0..3 {
            s[c] += w * st[c];
        }
        let (n, _) = e.normal_jacobian(xi);
        for (row, b) in [([n[0], 0.0, n[1]], t[0]), ([0.0, n[1], n[0]], t[1])] {
            for i in 0..3 {
                atb[i] += row[i] * b;
                for j in 0..3 {
                    ata[i][j] += row[i] * row[j];
                }
            }
        }
        normals.push(n);
    }
    // A corner (normals at least ~12 deg apart): the tractions of its two sides
    // determine the whole in-plane stress, more accurately than the tangential
    // strain of the discontinuous end elements (Lame corners: 1e-3 against
    // 5e-3 of sigma). Along a smooth junction: the mean recovered stress.
    let corner = normals
        .iter()
        .enumerate()
        .any(|(i, a)| normals[i + 1..].iter().any(|b| cross2(*a, *b).abs() > 0.2));
    if corner {
        if let Some(x) = solve3(ata, atb) {
            s = x;
        }
    }
    (u, s)
}

/// The point at which to evaluate `p` in region `r`: `p` moved to [`BOUNDARY_LAYER`] of
/// an element length inside the boundary where it is closer than that to one of the
/// region's elements (on the boundary or just outside it), `p` itself where it is
/// inside the region (winding number over 8 chords per element), `None` where it is
/// outside (the rule of the static field sampler, module docs; a [`Site::Junction`] where
/// the layer touches elements of two segments). `p` must be finite and `r` a region of
/// `mesh`.
pub(crate) fn locate_in_region(mesh: &BemMesh, r: usize, p: [f64; 2]) -> Option<Site> {
    let region = &mesh.regions[r];
    // Boundary proximity first: every element closer than BOUNDARY_LAYER of its length,
    // with its foot point and outward normal there.
    // (distance, foot, outward normal, layer, element, xi)
    type Near = (f64, [f64; 2], [f64; 2], f64, usize, f64);
    let mut near: Vec<Near> = Vec::new();
    for (k, e) in region.elements.iter().enumerate() {
        let (d, len) = piece_distance(e, p, -1.0, 1.0);
        if d < 0.6 * len {
            let xi = nearest_xi(e, p);
            let foot = e.point(xi);
            let dd = dist(foot, p);
            if dd < BOUNDARY_LAYER * len {
                let (n, _) = e.normal_jacobian(xi);
                near.push((dd, foot, n, BOUNDARY_LAYER * len, k, xi));
            }
        }
    }
    let first = near.first().map(|q| region.elements[q.4].segment);
    if near
        .iter()
        .any(|q| Some(region.elements[q.4].segment) != first)
    {
        // A junction of segments: their discontinuous end nodes make u jump there, and
        // the identities at distance d carry an error ~ G |jump| / d (module docs).
        return Some(Site::Junction(near.iter().map(|q| (q.4, q.5)).collect()));
    }
    if let Some(&(_, foot, n, h, _, _)) = near.iter().min_by(|a, b| a.0.total_cmp(&b.0)) {
        return Some(Site::Interior([foot[0] - h * n[0], foot[1] - h * n[1]]));
    }
    // Winding number over 8 chords per element.
    let mut wn = 0.0;
    for e in &region.elements {
        for m in 0..8 {
            let a = e.point(-1.0 + m as f64 / 4.0);
            let b = e.point(-1.0 + (m + 1) as f64 / 4.0);
            let (ax, ay) = (a[0] - p[0], a[1] - p[1]);
            let (bx, by) = (b[0] - p[0], b[1] - p[1]);
            wn += (ax * by - ay * bx).atan2(ax * bx + ay * by);
        }
    }
    (wn > std::f64::consts::PI).then_some(Site::Interior(p))
}

fn cross2(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// Solution of the 3 x 3 system a x = b by Cramer's rule, `None` where a is singular to
/// round-off.
fn solve3(a: [[f64; 3]; 3], b: [f64; 3]) -> Option<[f64; 3]> {
    let det = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(a);
    let scale = a.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
    if !d.is_finite() || d.abs() <= 1e-12 * scale.powi(3) {
        return None;
    }
    let mut x = [0.0; 3];
    for c in 0..3 {
        let mut m = a;
        for r in 0..3 {
            m[r][c] = b[r];
        }
        x[c] = det(m) / d;
    }
    Some(x)
}

fn finite(p: [f64; 2]) -> Result<()> {
    if p[0].is_finite() && p[1].is_finite() {
        Ok(())
    } else {
        Err(Error::invalid(
            "point",
            format!("({}, {})", p[0], p[1]),
            "must be finite",
        ))
    }
}

/// Strain of the in-plane stress `s` = [xx, yy, xy] (Pa) by the region's Hooke's law.
fn strain2d(k: &Kelvin2d, s: [f64; 3]) -> Strain2d {
    let e = k.strain_from_stress(s);
    Strain2d {
        xx: e[0],
        yy: e[1],
        xy: e[2],
        zz: k.eps_zz(s[0], s[1]),
    }
}

/// Local coordinate of the point of `e` nearest to `p` (sampling, then Newton).
fn nearest_xi(e: &Element, p: [f64; 2]) -> f64 {
    let mut best = (f64::INFINITY, 0.0);
    for m in 0..=64 {
        let xi = -1.0 + m as f64 / 32.0;
        let d = dist(e.point(xi), p);
        if d < best.0 {
            best = (d, xi);
        }
    }
    let mut xi = best.1;
    for _ in 0..20 {
        let x = e.point(xi);
        let t = e.tangent(xi);
        // Second derivative of the quadratic map.
        let g = &e.geometry;
        let tt = [
            g[0][0] - 2.0 * g[1][0] + g[2][0],
            g[0][1] - 2.0 * g[1][1] + g[2][1],
        ];
        let f = (x[0] - p[0]) * t[0] + (x[1] - p[1]) * t[1];
        let df = t[0] * t[0] + t[1] * t[1] + (x[0] - p[0]) * tt[0] + (x[1] - p[1]) * tt[1];
        if df.abs() < f64::MIN_POSITIVE {
            break;
        }
        let step = f / df;
        xi = (xi - step).clamp(-1.0, 1.0);
        if step.abs() < 1e-15 {
            break;
        }
    }
    xi
}

/// The region holding `p` (`region`, or where None the first region of `mesh` holding it)
/// and where to evaluate a field there, by the static field sampler's rule
/// ([`locate_in_region`], as [`BemSolution::stress_at`]): [`Site::Interior`] at `p` or `p`
/// moved [`BOUNDARY_LAYER`] inside the boundary, for Somigliana evaluations with other
/// boundary data (the Laplace-domain BEM's probes); [`Site::Junction`] at a segment junction,
/// evaluated from the boundary data ([`junction_fields`]).
///
/// Errors ([`Error::InvalidParameter`], field `probe`): `p` not finite, `region` out of
/// range, `p` outside that region or outside every region.
pub(crate) fn locate_site(
    mesh: &BemMesh,
    region: Option<usize>,
    p: [f64; 2],
) -> Result<(usize, Site)> {
    let at = format!("({:.6e}, {:.6e})", p[0], p[1]);
    if !(p[0].is_finite() && p[1].is_finite()) {
        return Err(Error::invalid("probe", at, "must be finite"));
    }
    match region {
        Some(r) => {
            let name = mesh
                .regions
                .get(r)
                .map(|x| x.name.as_str())
                .ok_or_else(|| {
                    Error::invalid(
                        "probe",
                        format!("region {r}"),
                        format!("must be a region index < {}", mesh.regions.len()),
                    )
                })?;
            locate_in_region(mesh, r, p)
                .map(|q| (r, q))
                .ok_or_else(|| Error::invalid("probe", at, format!("lies outside region '{name}'")))
        }
        None => (0..mesh.regions.len())
            .find_map(|r| locate_in_region(mesh, r, p).map(|q| (r, q)))
            .ok_or_else(|| Error::invalid("probe", at, "lies outside every region of the model")),
    }
}

/// The body of every region of `mesh` (regions joined by bonded interfaces): the root region
/// of its tree in a union-find over the interfaces (path halving), the one grouping that
/// [`BemProblem`]'s restraint check and the contact solver's bodies share.
pub(crate) fn region_bodies(mesh: &BemMesh) -> Vec<usize> {
    fn find(b: &mut [usize], i: usize) -> usize {
        let mut i = i;
        while b[i] != i {
            b[i] = b[b[i]];
            i = b[i];
        }
        i
    }
    let nr = mesh.regions.len();
    let mut parent: Vec<usize> = (0..nr).collect();
    for seg in &mesh.segments {
        if let Some((pr, _)) = &seg.partner {
            let (a, b) = (find(&mut parent, seg.owner), find(&mut parent, *pr));
            parent[a] = b;
        }
    }
    (0..nr).map(|r| find(&mut parent, r)).collect()
}

pub mod contact;

pub(crate) mod reference;

#[cfg(test)]
mod tests;

#[cfg(test)]
mod body_force_tests;

#[cfg(test)]
mod rigid_motion_tests;
