//! Frictional contact between 2D boundary element bodies: the paper's contact conditions
//! (4), (5) in the form (8) (Coulomb friction with stick and slip zones), solved on top of
//! the elastostatic BEM of [`super`] (equations (9)-(12) for n bodies).
//!
//! # Contact pairs and the node-to-segment rule
//!
//! A [`ContactPair`] joins a *slave* segment of one body to a *master* segment of another.
//! The contact unknowns are the normal pressure p_i >= 0 and the tangential traction q_i at
//! the slave nodes. Each slave node x_i is projected (closest point, on the quadratic
//! isoparametric master elements) onto the master segment, giving the foot point, the master
//! outward normal n_i (pointing into the slave) and the tangent tau_i = (-n_y, n_x). Then
//!
//! * initial gap `g0_i = (x_i - foot_i) . n_i` (from the geometry, along the master normal);
//! * gap `g_i = g0_i + (u_s(x_i) - u_m(foot_i)) . n_i`, with u_m interpolated by the master
//!   element's shape functions; slip `s_i = (u_s(x_i) - u_m(foot_i)) . tau_i` (small
//!   displacements: the projection is made once, in the initial configuration);
//! * slave traction `t_s = p n_i + q tau_i` (nodal values, interpolated as u and t are);
//! * master traction: the L2 projection of `-t_s` onto the master's quadratic traction space,
//!   `t_m = -M_m^{-1} D t_s` with `M_m = int N_m N_m^T ds` and `D = int N_m(foot(x)) N_s(x)^T
//!   ds` (Gauss points on the slave elements). Because the master shape functions sum to one,
//!   the force the master receives equals the force of the slave traction over the covered
//!   part to round-off (a mortar-type transfer of the tractions; the constraints themselves
//!   are collocated at the slave nodes).
//!
//! The transfer integrals are split where the master element ends project onto a slave
//! element (the master shape functions have kinks there; without the split, Gauss rules left
//! 4 % pressure spikes wherever the two meshes' nodes coincide). [`GapRule::Weighted`]
//! replaces the collocated gap and slip by their averages weighted with the slave shape
//! function (a mortar-type gap); the collocated rule is the default, being the more
//! accurate of the two on the Hertz case (0.21 % against 0.97 % of p0).
//!
//! Slave nodes whose projection falls outside the master segment are [`ContactState::Outside`]
//! and carry no traction. **Which side is the slave**: the finer mesh. Node-to-segment
//! schemes keep slave nodes out of the master, not master nodes out of the slave; with a
//! coarser slave the master nodes penetrate between slave nodes and the stick/slip sub-zones
//! come out wrong (Blázquez, París, Mantič, EABE 21 (1998) 361-375, BEM2D.md sec. 1). The
//! pair is taken as given; the rule is the caller's (documented) responsibility.
//!
//! # Condensation
//!
//! Every body (regions joined by bonded interfaces) is factored once: contact-segment nodes
//! take their traction as a parameter and rigid-load segments (below) their displacement, so
//! `A_b x_b = b_b(external) + B_b c_b` with c_b the body's contact tractions and rigid
//! translations. One LU of A_b and `1 + dim c_b` solves give the response of the contact-node
//! displacements and of the rigid-segment force resultants: a dense flexibility of the
//! slave-node gaps, slips and rigid forces on the contact unknowns (p, q, rigid translations)
//! z, `g = g0 + lambda g_ext + W_n z`, `s = lambda s_ext + W_t z`, `F = lambda F_ext + K z`.
//! Each load step then solves only small dense systems of size dim z.
//!
//! # Loads, rigid-body modes and steps
//!
//! A body held only by contact (a cylinder pressed on a block) is loaded through a *rigid
//! segment*: a named segment that moves as a rigid translation (no rotation: a guided face),
//! each component either force-controlled (the resultant of the traction on the segment is
//! prescribed, the translation unknown) or displacement-controlled. This removes the body's
//! rigid-body modes from the BEM system (the segment is a displacement boundary for the
//! factorization) and returns them to the contact problem, where contact and friction hold
//! them. A force-controlled component that neither contact nor friction restrains (a
//! frictionless pair pushed sideways) makes the step's system singular and is reported as an
//! [`Error::Numerical`]; a body with no displacement condition and no rigid segment at all is
//! rejected before factorization (the BEM restraint check, an [`Error::InvalidParameter`]).
//!
//! Friction is path dependent, so loads are applied in [`LoadStep`]s: each sets the factor of
//! the external boundary conditions (and of the regions' body forces, which enter the same
//! external column; the displacements are totals, so the gaps include the particular
//! solution) and the controls of every rigid segment. The Coulomb law
//! is written on the slip increment of the step, `ds_i = s_i - s_i(previous step)`:
//!
//! * open: `p = 0, q = 0` (g >= 0);
//! * stick: `g = 0, ds = 0, |q| <= f p`;
//! * slip: `g = 0, q = -f p sign(ds)`.
//!
//! # Solver
//!
//! A primal-dual active set method (the semi-smooth Newton method of the nonlinear
//! complementarity functions of Alart & Curnier 1991; Hüeber, Stadler & Wohlmuth, SIAM J.
//! Sci. Comput. 30 (2008) 572-596): with `pn = p - c_n g` and `qt = q - c_t ds` (c = the
//! inverse diagonal flexibility of the node), a node is open where pn <= 0, in stick where
//! |qt| < f pn, in slip otherwise with sign(qt). For fixed sets the conditions are linear, one
//! dense LU per iteration; the iteration stops when the sets repeat, and then every condition
//! holds exactly (no penalty or regularization: stick is exact stick). Where the sets return
//! to an earlier state (cycling) or the iteration limit is reached, the solver stops with
//! [`Error::NotConverged`] carrying the complementarity residual
//! `max_i max(|p - max(0, pn)|, |q - proj_[-f max(0,pn), f max(0,pn)](qt)|) / max_i p`.
//! With f = 0 the tangential tractions are fixed to zero (the frictionless problem, exactly).
//!
//! # Equilibrium
//!
//! The force-controlled resultants on rigid segments are equations of the step system and
//! hold to round-off; the transferred master traction carries exactly the slave's force
//! (round-off); the balance of a body's whole boundary (contact force against the loaded
//! face) holds to the BEM discretization error (1e-5 relative in the Hertz test).
//!
//! # Verification (tests in `contact/tests.rs`)
//!
//! | case | quantity | measured |
//! |---|---|---|
//! | Hertz, cylinder on block, 24/20 elements across | b, p0, max abs(p - p_H)/p0 (abs(x) < 0.9 b) | -0.09 %, +0.02 %, 0.21 % |
//! | same, 48/40 across | max abs(p - p_H)/p0 | 0.05 % |
//! | Hertz, two cylinders | b, p0, p(x) | -0.09 %, +0.02 %, 0.21 % |
//! | Hertz subsurface (McEwen) | sigma_y on the axis; tau_max | 1e-4 p0; 0.304 vs 0.3003 p0 |
//! | flat punch (stiff block) | p pi sqrt(a^2 - x^2) / P - 1 over abs(x) <= 0.8 a / 0.9 a | 0.52 % / 1.4 % |
//! | Cattaneo-Mindlin, Q = 0.5 f P | c/a | 0.7124 vs 0.7071 |
//! | Nowell-Hills with bulk stress | c/a, e/a | 0.2225 vs 0.2202, 0.1988 vs 0.1993 |
//! | unloading to Q = 0 | reverse-slip c'/a | 0.854 vs 0.866 |
//! | f = 1e-9 vs f = 0 | pressure difference | 8e-11 p0 |
//! | block of two bonded regions vs one piece | pressure difference | 1.2e-5 p0 |
//!
//! Timing (`contact_timing`, release, 2 cores shared with other builds, load average 4.4):
//! 932 BEM DOF / 196 contact unknowns: assembly 0.04 s, factorization + condensation 0.09 s,
//! a load step 0.0016 s; 1284 / 388: 0.09 s, 0.17 s, 0.009 s; 1988 / 772: 0.22 s, 0.74 s,
//! 0.043 s (about 10 active-set iterations per step, each a dense LU of the unknowns of the
//! nodes in contact). Condensation costs one LU per body plus one solve per contact-node
//! component, O(N^2 n_c); a step is independent of N.
//!
//! References: Johnson, *Contact Mechanics* (1985), ch. 4 (Hertz, flat punch: p = P /
//! (pi sqrt(a^2 - x^2))) and ch. 7 (Cattaneo-Mindlin, c = a sqrt(1 - Q/(f P))); Nowell &
//! Hills, Wear 136 (1990) and J. Mech. Phys. Solids 35 (1987) (shift of the stick zone by a
//! bulk stress, e = a sigma / (4 f p0)); `shared/references/BEM2D.md` A4-A6.

// Index loops read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use std::collections::HashMap;

use faer::linalg::solvers::Solve;
use faer::Mat;

use super::{nearest_xi, BemProblem, BemSolution, BoundaryConditions, Dof, SegmentBc};
use crate::error::{Error, Result};
use crate::kernels::quadrature::gauss_legendre;
use crate::operators::bem2d::{BemModel, Element};

/// How the gap and slip of a slave node are measured (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GapRule {
    /// Collocated at the slave node: the node projected onto the master segment. The
    /// default (Hertz, 24/20 elements across the contact: max pressure error 0.21 % of p0).
    NodeToSegment,
    /// Weighted with the slave node's shape function over its support (every slave
    /// quadrature point projected onto the master segment), divided by int N_i ds: a
    /// mortar-type average of the node-to-segment gap. Smoother, but it smears the contact
    /// edge (same Hertz case: 0.97 %), and at a singular edge on uniform non-matching
    /// elements (flat punch) the quadratic weights make the active set cycle (reported as
    /// [`Error::NotConverged`]; test `cycling_is_reported_with_the_residual`).
    Weighted,
}

/// A contact pair: the slave segment (the finer mesh), the master segment, and the Coulomb
/// friction coefficient.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactPair {
    /// Slave segment (its nodes carry the contact unknowns).
    pub slave: String,
    /// Master segment (the slave nodes are projected onto it).
    pub master: String,
    /// Coulomb friction coefficient f >= 0 (0: frictionless).
    pub friction: f64,
    /// Gap rule ([`GapRule::NodeToSegment`] by default).
    pub rule: GapRule,
}

impl ContactPair {
    /// A pair of segments with friction coefficient `friction` and the node-to-segment rule.
    pub fn new(slave: &str, master: &str, friction: f64) -> Self {
        Self {
            slave: slave.to_string(),
            master: master.to_string(),
            friction,
            rule: GapRule::NodeToSegment,
        }
    }

    /// The same pair with another gap rule.
    pub fn with_rule(mut self, rule: GapRule) -> Self {
        self.rule = rule;
        self
    }
}

/// How one component of a rigid segment's motion is controlled in a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Control {
    /// The resultant force per unit thickness of the traction on the segment, N/m (the
    /// translation is unknown).
    Force(f64),
    /// The translation, m.
    Displacement(f64),
}

/// The control of one rigid segment in one step.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidControl {
    /// The segment (declared as rigid in [`ContactProblem::new`]).
    pub segment: String,
    /// x component.
    pub x: Control,
    /// y component.
    pub y: Control,
}

impl RigidControl {
    /// A control of segment `segment`.
    pub fn new(segment: &str, x: Control, y: Control) -> Self {
        Self {
            segment: segment.to_string(),
            x,
            y,
        }
    }
}

/// One load step.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadStep {
    /// Factor on the external boundary conditions given to [`ContactProblem::new`].
    pub external: f64,
    /// The control of every rigid segment.
    pub rigid: Vec<RigidControl>,
}

/// Solver settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactOptions {
    /// Active-set iterations allowed per step (>= 1).
    pub max_iterations: usize,
    /// Complementarity residual accepted (relative to the largest pressure).
    pub tolerance: f64,
}

impl Default for ContactOptions {
    fn default() -> Self {
        Self {
            max_iterations: 200,
            tolerance: 1e-9,
        }
    }
}

/// The state of a slave node.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ContactState {
    /// Its projection misses the master segment: no contact possible.
    Outside,
    /// Not in contact.
    Open,
    /// In contact, sticking (or in contact on a frictionless pair).
    Stick,
    /// In contact, slipping in the positive tangent direction (friction along -tau).
    SlipPositive,
    /// In contact, slipping in the negative tangent direction (friction along +tau).
    SlipNegative,
}

/// Results at one slave node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactNode {
    /// Position (initial configuration), m.
    pub position: [f64; 2],
    /// Slave segment parameter in [0, 1].
    pub param: f64,
    /// Master outward normal at the projection (points into the slave); zero where the
    /// node is [`ContactState::Outside`].
    pub normal: [f64; 2],
    /// Tangent tau = (-n_y, n_x).
    pub tangent: [f64; 2],
    /// Contact pressure p >= 0, Pa (the slave traction is p n + q tau).
    pub pressure: f64,
    /// Tangential traction q on the slave along tau, Pa.
    pub shear: f64,
    /// Initial gap g0 along the master normal, m (None where the node is outside the master).
    pub initial_gap: Option<f64>,
    /// Gap, m (None where the node is outside the master).
    pub gap: Option<f64>,
    /// Total tangential relative displacement (slave minus master) along tau, m.
    pub slip: f64,
    /// Its increment in this step, m.
    pub slip_increment: f64,
    /// State.
    pub state: ContactState,
}

/// Results of one pair in one step.
#[derive(Debug, Clone, PartialEq)]
pub struct PairResult {
    /// Slave segment.
    pub slave: String,
    /// Master segment.
    pub master: String,
    /// Slave nodes, in the slave segment's direction.
    pub nodes: Vec<ContactNode>,
    /// Resultant of the contact traction on the slave (over the part covered by the master,
    /// by the quadrature of the transfer), N/m.
    pub slave_force: [f64; 2],
    /// Resultant of the transferred traction on the master, N/m (= -slave_force to
    /// round-off).
    pub master_force: [f64; 2],
    /// Whether a contact node is the first or last node of the slave segment (the contact
    /// may extend beyond the slave segment: enlarge it unless the edge is a real corner).
    pub touches_slave_end: bool,
}

/// A rigid segment's motion and force in one step.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidResult {
    /// Segment.
    pub segment: String,
    /// Translation, m.
    pub translation: [f64; 2],
    /// Resultant of the traction on the segment, N/m.
    pub force: [f64; 2],
}

/// The solved state after one load step.
#[derive(Debug, Clone)]
pub struct ContactStepResult {
    /// Active-set iterations used.
    pub iterations: usize,
    /// Complementarity residual reached (see the module docs).
    pub residual: f64,
    /// Per pair.
    pub pairs: Vec<PairResult>,
    /// Per rigid segment.
    pub rigid: Vec<RigidResult>,
    /// The full boundary state of all bodies (interior stresses via
    /// [`BemSolution::stress_at`]).
    pub solution: BemSolution,
}

/// A slave node's geometric data.
#[derive(Debug, Clone)]
struct SlaveNode {
    region_node: usize,
    position: [f64; 2],
    param: f64,
    normal: [f64; 2],
    tangent: [f64; 2],
    gap0: f64,
    /// Master segment-local nodes and shape values at the foot point.
    master: Option<([usize; 3], [f64; 3])>,
}

#[derive(Debug, Clone)]
struct PairData {
    pair: ContactPair,
    slave_seg: usize,
    master_seg: usize,
    /// Offset of this pair's nodes in the global slave-node numbering.
    offset: usize,
    nodes: Vec<SlaveNode>,
    /// Master traction (per master segment node) = -proj * slave traction (per slave node).
    proj: Mat<f64>,
    /// Slave force weights (int N_b ds over the covered part).
    slave_weights: Vec<f64>,
    /// D = int N_m(foot(x)) N_s(x)^T ds (master x slave), covered part.
    dmat: Mat<f64>,
    /// Slave mass int N_s N_s^T ds over the covered part.
    smass: Mat<f64>,
    /// Master force weights (int N_a ds).
    master_weights: Vec<f64>,
}

/// What a body parameter is.
#[derive(Debug, Clone, Copy)]
enum Param {
    /// Traction on contact node (region, node) in direction d.
    Traction {
        region: usize,
        node: usize,
        d: usize,
    },
    /// Translation of rigid segment j in direction d.
    Rigid { j: usize, d: usize },
}

#[derive(Debug, Clone)]
struct Body {
    /// Regions and their row offset in the body system.
    regions: Vec<(usize, usize)>,
    /// Global columns of the body's unknowns (body-local index -> global column).
    cols: Vec<usize>,
    /// Global parameter indices of the body.
    params: Vec<usize>,
    /// Solutions: column 0 for the external loads (factor 1), column 1 + k for unit
    /// parameter k of the body.
    x: Mat<f64>,
}

/// A condensed contact problem: the bodies factored once, the flexibility of the contact
/// unknowns computed, ready for load steps.
#[derive(Debug, Clone)]
pub struct ContactProblem {
    problem: BemProblem,
    dofs: Vec<Vec<[Dof; 2]>>,
    ncol: usize,
    scale: f64,
    length: f64,
    pairs: Vec<PairData>,
    rigid: Vec<(String, usize)>,
    params: Vec<Param>,
    bodies: Vec<Body>,
    /// Unknowns z = [p (n), q (n), rigid translations (2 per rigid segment)].
    n: usize,
    /// Map z -> parameters.
    pz: Mat<f64>,
    wn: Mat<f64>,
    wt: Mat<f64>,
    kf: Mat<f64>,
    gn_ext: Vec<f64>,
    st_ext: Vec<f64>,
    f_ext: Vec<f64>,
    /// Largest relative residual of the body factorizations.
    lu_residual: f64,
    /// Total slip at the end of the last solved step (path memory).
    slip: Vec<f64>,
    states: Vec<ContactState>,
}

fn seg_elements(problem: &BemProblem, seg: usize) -> Vec<Element> {
    let owner = problem.mesh.segments[seg].owner;
    problem.mesh.regions[owner]
        .elements
        .iter()
        .filter(|e| e.segment == seg)
        .copied()
        .collect()
}

/// Closest point of the master elements to `p`: (element index, xi), or None where the
/// closest point is an end of the segment and `p` lies beyond it.
fn project(elements: &[Element], p: [f64; 2]) -> Option<(usize, f64)> {
    let mut best: Option<(f64, usize, f64)> = None;
    for (k, e) in elements.iter().enumerate() {
        let xi = nearest_xi(e, p);
        let f = e.point(xi);
        let d = (f[0] - p[0]).hypot(f[1] - p[1]);
        if best.map_or(true, |b| d < b.0) {
            best = Some((d, k, xi));
        }
    }
    let (_, k, xi) = best?;
    let last = elements.len() - 1;
    let at_end = (k == 0 && xi <= -1.0 + 1e-12) || (k == last && xi >= 1.0 - 1e-12);
    if at_end {
        let e = &elements[k];
        let f = e.point(xi);
        let t = e.tangent(xi);
        let tl = t[0].hypot(t[1]);
        let off = ((p[0] - f[0]) * t[0] + (p[1] - f[1]) * t[1]) / tl;
        if off.abs() > 1e-9 * e.chord_length() {
            return None;
        }
    }
    Some((k, xi))
}

impl ContactProblem {
    /// Meshes and assembles `model`, validates the pairs and rigid segments, factors every
    /// body once and condenses the BEM systems onto the contact unknowns.
    ///
    /// `bcs` are the external boundary conditions (scaled by [`LoadStep::external`]); they
    /// must not name contact or rigid segments. `rigid` names the rigid (load) segments.
    ///
    /// Errors ([`Error::InvalidParameter`] naming the item): an unknown segment in a pair or
    /// in `rigid`; a segment used twice (in two pairs, as rigid and contact, or with a boundary
    /// condition); a bonded interface used as contact or rigid segment; slave and master in the
    /// same body; a friction coefficient that is negative or not finite; a pair whose slave
    /// nodes all miss the master; initial penetration deeper than 1e-6 of the slave's
    /// smallest element; an unrestrained body. [`Error::Numerical`] where a factorization
    /// fails.
    pub fn new(
        model: &BemModel,
        bcs: &BoundaryConditions,
        pairs: &[ContactPair],
        rigid: &[&str],
    ) -> Result<Self> {
        let problem = BemProblem::new(model)?;
        Self::from_problem(problem, bcs, pairs, rigid)
    }

    /// As [`ContactProblem::new`], from an assembled problem.
    pub fn from_problem(
        problem: BemProblem,
        bcs: &BoundaryConditions,
        pairs: &[ContactPair],
        rigid: &[&str],
    ) -> Result<Self> {
        let mesh = &problem.mesh;
        // --- validation of names and roles.
        let mut role: HashMap<usize, String> = HashMap::new();
        let mut claim = |name: &str, what: String, field: &str| -> Result<usize> {
            let s = mesh.segment_index(name).ok_or_else(|| {
                Error::invalid(field.to_string(), name, "names no segment of the model")
            })?;
            if mesh.segments[s].partner.is_some() {
                return Err(Error::invalid(
                    field.to_string(),
                    name,
                    "is a bonded interface between regions; it cannot be a contact or rigid segment",
                ));
            }
            if let Some(prev) = role.get(&s) {
                return Err(Error::invalid(
                    field.to_string(),
                    name,
                    format!("the segment is already used as {prev}"),
                ));
            }
            role.insert(s, what);
            Ok(s)
        };
        let mut pair_segs = Vec::new();
        for (k, p) in pairs.iter().enumerate() {
            let fname = format!("contact_pair[{k}]");
            if !(p.friction.is_finite() && p.friction >= 0.0) {
                return Err(Error::invalid(
                    format!("{fname}.friction"),
                    p.friction,
                    "the friction coefficient must be finite and >= 0",
                ));
            }
            let s = claim(
                &p.slave,
                format!("the slave of contact pair {k}"),
                &format!("{fname}.slave"),
            )?;
            let m = claim(
                &p.master,
                format!("the master of contact pair {k}"),
                &format!("{fname}.master"),
            )?;
            pair_segs.push((s, m));
        }
        let mut rigid_segs = Vec::new();
        for (j, name) in rigid.iter().enumerate() {
            let s = claim(name, format!("rigid segment {j}"), "rigid_segment")?;
            rigid_segs.push((name.to_string(), s));
        }
        for (name, _) in &bcs.entries {
            if let Some(s) = mesh.segment_index(name) {
                if let Some(what) = role.get(&s) {
                    return Err(Error::invalid(
                        "boundary_condition.segment",
                        name,
                        format!("is {what}; it takes no boundary condition"),
                    ));
                }
            }
        }
        // --- bodies (regions joined by bonded interfaces).
        let nr = mesh.regions.len();
        let mut parent: Vec<usize> = (0..nr).collect();
        fn find(b: &mut [usize], i: usize) -> usize {
            let mut i = i;
            while b[i] != i {
                b[i] = b[b[i]];
                i = b[i];
            }
            i
        }
        for seg in &mesh.segments {
            if let Some((pr, _)) = &seg.partner {
                let (a, b) = (find(&mut parent, seg.owner), find(&mut parent, *pr));
                parent[a] = b;
            }
        }
        let body_of: Vec<usize> = (0..nr).map(|r| find(&mut parent, r)).collect();
        for (k, &(s, m)) in pair_segs.iter().enumerate() {
            if body_of[mesh.segments[s].owner] == body_of[mesh.segments[m].owner] {
                return Err(Error::invalid(
                    format!("contact_pair[{k}]"),
                    format!("'{}' / '{}'", pairs[k].slave, pairs[k].master),
                    "slave and master belong to the same body (self-contact is not supported)",
                ));
            }
        }
        // --- DOF classification: contact segments traction-type, rigid segments
        // displacement-type (both with zero values; their values are parameters).
        let mut full = bcs.clone();
        for &(s, m) in &pair_segs {
            full = full
                .set(&mesh.segments[s].name, SegmentBc::Free)
                .set(&mesh.segments[m].name, SegmentBc::Free);
        }
        for (name, _) in &rigid_segs {
            full = full.set(name, SegmentBc::fixed());
        }
        let (dofs, ncol) = problem.dofs(&full)?;
        problem.check_restraint(&dofs)?;
        let scale = mesh
            .regions
            .iter()
            .map(|r| r.kernels.shear_modulus())
            .fold(0.0_f64, f64::max);
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for r in &mesh.regions {
            for n in &r.nodes {
                for d in 0..2 {
                    lo[d] = lo[d].min(n.position[d]);
                    hi[d] = hi[d].max(n.position[d]);
                }
            }
        }
        let length = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(f64::MIN_POSITIVE);

        // --- pair geometry: projection, initial gaps, traction transfer.
        let (gx, gw) = gauss_legendre(8);
        let mut pdata = Vec::new();
        let mut offset = 0;
        for (k, &(s, m)) in pair_segs.iter().enumerate() {
            let sseg = &mesh.segments[s];
            let mseg = &mesh.segments[m];
            let sregion = &mesh.regions[sseg.owner];
            let selems = seg_elements(&problem, s);
            let melems = seg_elements(&problem, m);
            let mut m_local = HashMap::new();
            for (a, &o) in mseg.owner_nodes.iter().enumerate() {
                m_local.insert(o, a);
            }
            let mut s_local = HashMap::new();
            for (b, &o) in sseg.owner_nodes.iter().enumerate() {
                s_local.insert(o, b);
            }
            let hmin = selems
                .iter()
                .map(|e| e.chord_length())
                .fold(f64::INFINITY, f64::min);
            let mut nodes = Vec::new();
            let mut any = false;
            for &o in &sseg.owner_nodes {
                let node = &sregion.nodes[o];
                let x = node.position;
                let mut sn = SlaveNode {
                    region_node: o,
                    position: x,
                    param: node.param,
                    normal: [0.0, 0.0],
                    tangent: [0.0, 0.0],
                    gap0: f64::INFINITY,
                    master: None,
                };
                if let Some((ke, xi)) = project(&melems, x) {
                    let e = &melems[ke];
                    let f = e.point(xi);
                    let (n, _) = e.normal_jacobian(xi);
                    let g0 = (x[0] - f[0]) * n[0] + (x[1] - f[1]) * n[1];
                    if g0 < -1e-6 * hmin {
                        return Err(Error::invalid(
                            format!("contact_pair[{k}]"),
                            format!("initial gap {g0:.3e} m at ({:.6e}, {:.6e})", x[0], x[1]),
                            "the bodies overlap: a slave node lies inside the master body \
                             (initial penetration beyond 1e-6 of the slave's smallest element)",
                        ));
                    }
                    sn.normal = n;
                    sn.tangent = [-n[1], n[0]];
                    sn.gap0 = g0;
                    sn.master = Some((e.nodes.map(|q| m_local[&q]), e.field_shape(xi)));
                    any = true;
                }
                nodes.push(sn);
            }
            if !any {
                return Err(Error::invalid(
                    format!("contact_pair[{k}]"),
                    format!("'{}' / '{}'", pairs[k].slave, pairs[k].master),
                    "no slave node projects onto the master segment",
                ));
            }
            // Transfer: D (master x slave) on the slave elements, M on the master elements.
            let nm = mseg.owner_nodes.len();
            let ns = sseg.owner_nodes.len();
            let mut dmat = Mat::<f64>::zeros(nm, ns);
            let mut smass = Mat::<f64>::zeros(ns, ns);
            let mut slave_weights = vec![0.0; ns];
            let mut full_weights = vec![0.0; ns];
            let mut weighted_gap = vec![0.0; ns];
            for e in &selems {
                // Split the slave element where master element ends project onto it: the
                // master shape functions have kinks there, which Gauss rules integrate
                // poorly (measured: 4 % pressure spikes on the Hertz case without the split).
                let mut cuts = vec![-1.0, 1.0];
                for em in &melems {
                    for q in [em.geometry[0], em.geometry[2]] {
                        let xi = nearest_xi(e, q);
                        let f = e.point(xi);
                        if xi > -1.0 + 1e-9
                            && xi < 1.0 - 1e-9
                            && (f[0] - q[0]).hypot(f[1] - q[1]) < e.chord_length()
                        {
                            cuts.push(xi);
                        }
                    }
                }
                cuts.sort_by(f64::total_cmp);
                cuts.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
                let points: Vec<(f64, f64)> = cuts
                    .windows(2)
                    .flat_map(|c| {
                        let (lo, hi) = (c[0], c[1]);
                        gx.iter().zip(&gw).map(move |(&t, &w)| {
                            (0.5 * (lo + hi) + 0.5 * (hi - lo) * t, 0.5 * (hi - lo) * w)
                        })
                    })
                    .collect();
                for (xi, w) in points {
                    let x = e.point(xi);
                    let (_, jac) = e.normal_jacobian(xi);
                    let nsh = e.field_shape(xi);
                    for b in 0..3 {
                        full_weights[s_local[&e.nodes[b]]] += w * jac * nsh[b];
                    }
                    if let Some((ke, xm)) = project(&melems, x) {
                        let em = &melems[ke];
                        let nmsh = em.field_shape(xm);
                        let f = em.point(xm);
                        let (nn, _) = em.normal_jacobian(xm);
                        let g0 = (x[0] - f[0]) * nn[0] + (x[1] - f[1]) * nn[1];
                        for b in 0..3 {
                            let bl = s_local[&e.nodes[b]];
                            slave_weights[bl] += w * jac * nsh[b];
                            weighted_gap[bl] += w * jac * nsh[b] * g0;
                            for a in 0..3 {
                                let al = m_local[&em.nodes[a]];
                                dmat[(al, bl)] += w * jac * nmsh[a] * nsh[b];
                            }
                            for c in 0..3 {
                                let cl = s_local[&e.nodes[c]];
                                smass[(bl, cl)] += w * jac * nsh[b] * nsh[c];
                            }
                        }
                    }
                }
            }
            if pairs[k].rule == GapRule::Weighted {
                // Only nodes whose whole support is covered by the master take part.
                for (b, sn) in nodes.iter_mut().enumerate() {
                    let full = full_weights[b];
                    if sn.master.is_some() && full > 0.0 && slave_weights[b] >= (1.0 - 1e-9) * full
                    {
                        sn.gap0 = weighted_gap[b] / slave_weights[b];
                    } else {
                        sn.master = None;
                        sn.gap0 = f64::INFINITY;
                    }
                }
                if nodes.iter().all(|sn| sn.master.is_none()) {
                    return Err(Error::invalid(
                        format!("contact_pair[{k}]"),
                        format!("'{}' / '{}'", pairs[k].slave, pairs[k].master),
                        "no slave node's support lies on the master segment",
                    ));
                }
            }
            let mut mass = Mat::<f64>::zeros(nm, nm);
            let mut master_weights = vec![0.0; nm];
            for e in &melems {
                for (&xi, &w) in gx.iter().zip(&gw) {
                    let (_, jac) = e.normal_jacobian(xi);
                    let nsh = e.field_shape(xi);
                    for a in 0..3 {
                        let al = m_local[&e.nodes[a]];
                        master_weights[al] += w * jac * nsh[a];
                        for b in 0..3 {
                            let bl = m_local[&e.nodes[b]];
                            mass[(al, bl)] += w * jac * nsh[a] * nsh[b];
                        }
                    }
                }
            }
            let proj = mass.partial_piv_lu().solve(&dmat);
            if (0..nm).any(|a| (0..ns).any(|b| !proj[(a, b)].is_finite())) {
                return Err(Error::Numerical {
                    context: "2D BEM contact",
                    detail: format!(
                        "the traction transfer of contact pair {k} is singular (master mass matrix)"
                    ),
                });
            }
            let count = nodes.len();
            pdata.push(PairData {
                pair: pairs[k].clone(),
                slave_seg: s,
                master_seg: m,
                offset,
                nodes,
                proj,
                slave_weights,
                dmat,
                smass,
                master_weights,
            });
            offset += count;
        }
        let n = offset;
        let nrig = 2 * rigid_segs.len();
        let nz = 2 * n + nrig;

        // --- parameters and the map z -> parameters.
        let mut params: Vec<Param> = Vec::new();
        let mut param_of: HashMap<(usize, usize, usize), usize> = HashMap::new();
        let mut add_seg = |seg: usize, params: &mut Vec<Param>| {
            let info = &mesh.segments[seg];
            for &o in &info.owner_nodes {
                for d in 0..2 {
                    param_of.insert((info.owner, o, d), params.len());
                    params.push(Param::Traction {
                        region: info.owner,
                        node: o,
                        d,
                    });
                }
            }
        };
        for p in &pdata {
            add_seg(p.slave_seg, &mut params);
            add_seg(p.master_seg, &mut params);
        }
        let rigid_base = params.len();
        for j in 0..rigid_segs.len() {
            for d in 0..2 {
                params.push(Param::Rigid { j, d });
            }
        }
        let np = params.len();
        let mut pz = Mat::<f64>::zeros(np, nz);
        for p in &pdata {
            let sinfo = &mesh.segments[p.slave_seg];
            let minfo = &mesh.segments[p.master_seg];
            for (b, sn) in p.nodes.iter().enumerate() {
                let i = p.offset + b;
                for d in 0..2 {
                    let row = param_of[&(sinfo.owner, sn.region_node, d)];
                    pz[(row, i)] = sn.normal[d];
                    pz[(row, n + i)] = sn.tangent[d];
                    for (a, &o) in minfo.owner_nodes.iter().enumerate() {
                        let w = p.proj[(a, b)];
                        if w != 0.0 {
                            let mrow = param_of[&(minfo.owner, o, d)];
                            pz[(mrow, i)] -= w * sn.normal[d];
                            pz[(mrow, n + i)] -= w * sn.tangent[d];
                        }
                    }
                }
            }
        }
        for j in 0..nrig {
            pz[(rigid_base + j, 2 * n + j)] = 1.0;
        }

        // --- bodies: assemble, factor once, solve for the external load and unit params.
        let mut roots: Vec<usize> = body_of.clone();
        roots.sort_unstable();
        roots.dedup();
        let mut bodies = Vec::new();
        let mut lu_residual = 0.0_f64;
        for &root in &roots {
            let members: Vec<usize> = (0..nr).filter(|&r| body_of[r] == root).collect();
            let mut regions = Vec::new();
            let mut rows = 0;
            let mut cols = Vec::new();
            for &r in &members {
                regions.push((r, rows));
                rows += problem.operators[r].h.nrows();
                for d in &dofs[r] {
                    for dof in d {
                        match *dof {
                            Dof::U { col, .. } | Dof::T { col, .. } => cols.push(col),
                            Dof::Interface { u_col, t_col, .. } => {
                                cols.push(u_col);
                                cols.push(t_col);
                            }
                        }
                    }
                }
            }
            cols.sort_unstable();
            cols.dedup();
            let local: HashMap<usize, usize> =
                cols.iter().enumerate().map(|(i, &c)| (c, i)).collect();
            if cols.len() != rows {
                return Err(Error::Numerical {
                    context: "2D BEM contact",
                    detail: format!("body system is {rows} x {} (not square)", cols.len()),
                });
            }
            let bparams: Vec<usize> = (0..np)
                .filter(|&k| match params[k] {
                    Param::Traction { region, .. } => body_of[region] == root,
                    Param::Rigid { j, .. } => body_of[mesh.segments[rigid_segs[j].1].owner] == root,
                })
                .collect();
            let bp_index: HashMap<usize, usize> =
                bparams.iter().enumerate().map(|(i, &k)| (k, i)).collect();
            let mut a = Mat::<f64>::zeros(rows, rows);
            let mut rhs = Mat::<f64>::zeros(rows, 1 + bparams.len());
            for &(r, off) in &regions {
                let ops = &problem.operators[r];
                let n2 = ops.h.nrows();
                for (node, d) in dofs[r].iter().enumerate() {
                    for (dir, dof) in d.iter().enumerate() {
                        let c = 2 * node + dir;
                        let (hc, gc) = (ops.h.col(c), ops.g.col(c));
                        match *dof {
                            Dof::U { col, t } => {
                                let lc = local[&col];
                                let pk = param_of.get(&(r, node, dir)).map(|k| bp_index[k]);
                                for row in 0..n2 {
                                    a[(off + row, lc)] += hc[row];
                                    rhs[(off + row, 0)] += gc[row] * t;
                                    if let Some(pk) = pk {
                                        rhs[(off + row, 1 + pk)] += gc[row];
                                    }
                                }
                            }
                            Dof::T { col, u } => {
                                let lc = local[&col];
                                let seg = self_segment(&problem, r, node);
                                let rj = rigid_segs.iter().position(|&(_, s)| s == seg);
                                for row in 0..n2 {
                                    a[(off + row, lc)] -= gc[row] * scale;
                                    rhs[(off + row, 0)] -= hc[row] * u;
                                }
                                if let Some(j) = rj {
                                    let pk = bp_index[&(rigid_base + 2 * j + dir)];
                                    for row in 0..n2 {
                                        rhs[(off + row, 1 + pk)] -= hc[row];
                                    }
                                }
                            }
                            Dof::Interface { u_col, t_col, sign } => {
                                let (lu_, lt) = (local[&u_col], local[&t_col]);
                                for row in 0..n2 {
                                    a[(off + row, lu_)] += hc[row];
                                    a[(off + row, lt)] -= sign * gc[row] * scale;
                                }
                            }
                        }
                    }
                }
            }
            // Body forces are external loads: their term H u_p - G t_p joins column 0.
            for &(r, off) in &regions {
                for (row, v) in problem.body_force_rhs(r).into_iter().flatten().enumerate() {
                    rhs[(off + row, 0)] += v;
                }
            }
            let lu = a.partial_piv_lu();
            let x = lu.solve(&rhs);
            // Accuracy check on the external-load column and two parameter columns (a
            // full check would cost as much as the solves), plus finiteness of all.
            let k = rhs.ncols().min(3);
            let xs = Mat::from_fn(rows, k, |i, j| x[(i, j)]);
            let bs = Mat::from_fn(rows, k, |i, j| rhs[(i, j)]);
            let res = &a * &xs - &bs;
            let na = (0..rows)
                .map(|i| (0..rows).map(|c| a[(i, c)].abs()).sum::<f64>())
                .fold(0.0_f64, f64::max);
            let mut worst = 0.0_f64;
            for j in 0..k {
                let (mut nr_, mut nx, mut nb) = (0.0_f64, 0.0_f64, 0.0_f64);
                for i in 0..rows {
                    nr_ = nr_.max(res[(i, j)].abs());
                    nx = nx.max(xs[(i, j)].abs());
                    nb = nb.max(bs[(i, j)].abs());
                }
                worst = worst.max(nr_ / (na * nx + nb).max(f64::MIN_POSITIVE));
            }
            let finite = (0..x.ncols()).all(|j| (0..rows).all(|i| x[(i, j)].is_finite()));
            if !finite {
                worst = f64::INFINITY;
            }
            if worst.is_nan() || worst >= 1e-8 {
                let names: Vec<&str> = members
                    .iter()
                    .map(|&r| mesh.regions[r].name.as_str())
                    .collect();
                return Err(Error::Numerical {
                    context: "2D BEM contact",
                    detail: format!(
                        "the LU solve of body [{}] failed (relative residual {worst:.3e})",
                        names.join(", ")
                    ),
                });
            }
            lu_residual = lu_residual.max(worst);
            bodies.push(Body {
                regions,
                cols,
                params: bparams,
                x,
            });
        }

        let mut this = Self {
            problem,
            dofs,
            ncol,
            scale,
            length,
            pairs: pdata,
            rigid: rigid_segs,
            params,
            bodies,
            n,
            pz,
            wn: Mat::zeros(0, 0),
            wt: Mat::zeros(0, 0),
            kf: Mat::zeros(0, 0),
            gn_ext: Vec::new(),
            st_ext: Vec::new(),
            f_ext: Vec::new(),
            lu_residual,
            slip: vec![0.0; n],
            states: Vec::new(),
        };
        this.condense();
        this.reset();
        Ok(this)
    }

    /// Response of the displacement component (region, node, d) as (external, per body
    /// parameter) coefficients: the body and its row.
    fn displacement_row(&self, region: usize, node: usize, d: usize) -> (usize, usize) {
        let col = match self.dofs[region][node][d] {
            Dof::U { col, .. } => col,
            _ => unreachable!("contact nodes carry traction-type DOFs"),
        };
        let b = self
            .bodies
            .iter()
            .position(|b| b.regions.iter().any(|&(r, _)| r == region))
            .expect("every region is in a body");
        let row = self.bodies[b]
            .cols
            .binary_search(&col)
            .expect("column of the body");
        (b, row)
    }

    /// Builds W_n, W_t, K and the external-load responses.
    fn condense(&mut self) {
        let n = self.n;
        let nz = self.pz.ncols();
        // A row in parameter space (length np) + external coefficient, for a displacement.
        let urow =
            |this: &Self, region: usize, node: usize, d: usize| -> (f64, Vec<(usize, f64)>) {
                let (b, row) = this.displacement_row(region, node, d);
                let body = &this.bodies[b];
                let ext = body.x[(row, 0)];
                let coef = body
                    .params
                    .iter()
                    .enumerate()
                    .map(|(k, &gp)| (gp, body.x[(row, 1 + k)]))
                    .collect();
                (ext, coef)
            };
        // Relative displacement rows in parameter space.
        let np = self.params.len();
        let mut rel = Mat::<f64>::zeros(2 * n, np);
        let mut rel_ext = vec![0.0; 2 * n];
        for p in &self.pairs {
            let sinfo = &self.problem.mesh.segments[p.slave_seg];
            let minfo = &self.problem.mesh.segments[p.master_seg];
            for (b, sn) in p.nodes.iter().enumerate() {
                let Some((mn, sh)) = sn.master else { continue };
                let i = p.offset + b;
                if p.pair.rule == GapRule::Weighted {
                    // (sum_b' Ms[b][b'] u_s(b') - sum_a D[a][b] u_m(a)) / int N_b ds.
                    let wb = p.slave_weights[b];
                    for d in 0..2 {
                        for (b2, &o) in sinfo.owner_nodes.iter().enumerate() {
                            let m = p.smass[(b, b2)];
                            if m == 0.0 {
                                continue;
                            }
                            let (e, c) = urow(self, sinfo.owner, o, d);
                            rel_ext[2 * i + d] += m / wb * e;
                            for (gp, v) in c {
                                rel[(2 * i + d, gp)] += m / wb * v;
                            }
                        }
                        for (a, &o) in minfo.owner_nodes.iter().enumerate() {
                            let m = p.dmat[(a, b)];
                            if m == 0.0 {
                                continue;
                            }
                            let (e, c) = urow(self, minfo.owner, o, d);
                            rel_ext[2 * i + d] -= m / wb * e;
                            for (gp, v) in c {
                                rel[(2 * i + d, gp)] -= m / wb * v;
                            }
                        }
                    }
                    continue;
                }
                for d in 0..2 {
                    let (e, c) = urow(self, sinfo.owner, sn.region_node, d);
                    rel_ext[2 * i + d] += e;
                    for (gp, v) in c {
                        rel[(2 * i + d, gp)] += v;
                    }
                    for a in 0..3 {
                        let o = minfo.owner_nodes[mn[a]];
                        let (e, c) = urow(self, minfo.owner, o, d);
                        rel_ext[2 * i + d] -= sh[a] * e;
                        for (gp, v) in c {
                            rel[(2 * i + d, gp)] -= sh[a] * v;
                        }
                    }
                }
            }
        }
        let relz = &rel * &self.pz;
        let mut wn = Mat::<f64>::zeros(n, nz);
        let mut wt = Mat::<f64>::zeros(n, nz);
        let mut gn_ext = vec![0.0; n];
        let mut st_ext = vec![0.0; n];
        for p in &self.pairs {
            for (b, sn) in p.nodes.iter().enumerate() {
                let i = p.offset + b;
                for d in 0..2 {
                    gn_ext[i] += sn.normal[d] * rel_ext[2 * i + d];
                    st_ext[i] += sn.tangent[d] * rel_ext[2 * i + d];
                    for c in 0..nz {
                        wn[(i, c)] += sn.normal[d] * relz[(2 * i + d, c)];
                        wt[(i, c)] += sn.tangent[d] * relz[(2 * i + d, c)];
                    }
                }
            }
        }
        // Rigid force rows: F_d = sum_node w_node * t_d(node).
        let nrig = 2 * self.rigid.len();
        let mut frow = Mat::<f64>::zeros(nrig, np);
        let mut f_ext = vec![0.0; nrig];
        for (j, (_, seg)) in self.rigid.iter().enumerate() {
            let info = &self.problem.mesh.segments[*seg];
            let weights = node_weights(&self.problem, *seg);
            for (k, &o) in info.owner_nodes.iter().enumerate() {
                for d in 0..2 {
                    let col = match self.dofs[info.owner][o][d] {
                        Dof::T { col, .. } => col,
                        _ => unreachable!("rigid nodes carry displacement-type DOFs"),
                    };
                    let b = self
                        .bodies
                        .iter()
                        .position(|b| b.regions.iter().any(|&(r, _)| r == info.owner))
                        .expect("body");
                    let body = &self.bodies[b];
                    let row = body.cols.binary_search(&col).expect("column");
                    let w = weights[k] * self.scale;
                    f_ext[2 * j + d] += w * body.x[(row, 0)];
                    for (kk, &gp) in body.params.iter().enumerate() {
                        frow[(2 * j + d, gp)] += w * body.x[(row, 1 + kk)];
                    }
                }
            }
        }
        self.kf = &frow * &self.pz;
        self.wn = wn;
        self.wt = wt;
        self.gn_ext = gn_ext;
        self.st_ext = st_ext;
        self.f_ext = f_ext;
    }

    /// Forgets the load history (slips and states) so that steps start from the unloaded
    /// state again.
    pub fn reset(&mut self) {
        self.slip = vec![0.0; self.n];
        let mut states = Vec::with_capacity(self.n);
        // Start each pair with its closest node(s) in contact (sticking), so that a body held
        // only by contact is restrained in the first iteration.
        for p in &self.pairs {
            let gmin = p
                .nodes
                .iter()
                .filter(|s| s.master.is_some())
                .map(|s| s.gap0)
                .fold(f64::INFINITY, f64::min);
            let hmin = seg_elements(&self.problem, p.slave_seg)
                .iter()
                .map(|e| e.chord_length())
                .fold(f64::INFINITY, f64::min);
            for s in &p.nodes {
                states.push(if s.master.is_none() {
                    ContactState::Outside
                } else if s.gap0 <= gmin + 1e-9 * hmin {
                    ContactState::Stick
                } else {
                    ContactState::Open
                });
            }
        }
        self.states = states;
    }

    /// Number of contact unknowns (2 per slave node plus 2 per rigid segment).
    pub fn contact_unknowns(&self) -> usize {
        self.pz.ncols()
    }

    /// The assembled BEM problem.
    pub fn bem(&self) -> &BemProblem {
        &self.problem
    }

    /// Largest relative residual of the body factorizations (condensation accuracy).
    pub fn factorization_residual(&self) -> f64 {
        self.lu_residual
    }

    /// Solves the load steps in order, continuing from the state left by earlier calls
    /// (use [`ContactProblem::reset`] to start again from the unloaded state).
    ///
    /// Errors: a step that misses or repeats a rigid segment, or names an unknown one, or a
    /// non-finite load ([`Error::InvalidParameter`]); [`Error::NotConverged`] with the
    /// complementarity residual when the active sets cycle or the iteration limit is
    /// reached; [`Error::NoContact`] when no node is in contact and a force-controlled body
    /// floats; [`Error::Numerical`] for a singular step system (a rigid-body mode that
    /// neither contact, friction nor a displacement control restrains);
    /// [`Error::ContactReachesWindow`] when the contact reaches a slave node whose
    /// projection misses the master segment.
    pub fn solve_steps(
        &mut self,
        steps: &[LoadStep],
        options: &ContactOptions,
    ) -> Result<Vec<ContactStepResult>> {
        if options.max_iterations == 0 {
            return Err(Error::invalid(
                "contact_options.max_iterations",
                0,
                "must be at least 1",
            ));
        }
        if !(options.tolerance.is_finite() && options.tolerance > 0.0) {
            return Err(Error::invalid(
                "contact_options.tolerance",
                options.tolerance,
                "must be finite and > 0",
            ));
        }
        let mut out = Vec::with_capacity(steps.len());
        for (k, step) in steps.iter().enumerate() {
            out.push(self.solve_step(k, step, options)?);
        }
        Ok(out)
    }

    fn controls(&self, k: usize, step: &LoadStep) -> Result<Vec<Control>> {
        let field = format!("load_step[{k}]");
        if !step.external.is_finite() {
            return Err(Error::invalid(
                format!("{field}.external"),
                step.external,
                "must be finite",
            ));
        }
        let mut ctl: Vec<Option<Control>> = vec![None; 2 * self.rigid.len()];
        for rc in &step.rigid {
            let j = self
                .rigid
                .iter()
                .position(|(name, _)| *name == rc.segment)
                .ok_or_else(|| {
                    Error::invalid(
                        format!("{field}.rigid"),
                        &rc.segment,
                        "is not a rigid segment of the contact problem",
                    )
                })?;
            if ctl[2 * j].is_some() {
                return Err(Error::invalid(
                    format!("{field}.rigid"),
                    &rc.segment,
                    "is controlled twice in the step",
                ));
            }
            for (d, c) in [rc.x, rc.y].into_iter().enumerate() {
                let v = match c {
                    Control::Force(v) | Control::Displacement(v) => v,
                };
                if !v.is_finite() {
                    return Err(Error::invalid(
                        format!("{field}.rigid '{}'", rc.segment),
                        v,
                        "the load must be finite",
                    ));
                }
                ctl[2 * j + d] = Some(c);
            }
        }
        ctl.into_iter()
            .enumerate()
            .map(|(i, c)| {
                c.ok_or_else(|| {
                    Error::invalid(
                        format!("{field}.rigid"),
                        &self.rigid[i / 2].0,
                        "every rigid segment needs a control in every step",
                    )
                })
            })
            .collect()
    }

    fn friction_of(&self) -> Vec<f64> {
        let mut f = vec![0.0; self.n];
        for p in &self.pairs {
            for b in 0..p.nodes.len() {
                f[p.offset + b] = p.pair.friction;
            }
        }
        f
    }

    fn solve_step(
        &mut self,
        k: usize,
        step: &LoadStep,
        options: &ContactOptions,
    ) -> Result<ContactStepResult> {
        let ctl = self.controls(k, step)?;
        let n = self.n;
        let nz = self.pz.ncols();
        let lam = step.external;
        let fric = self.friction_of();
        let g0: Vec<f64> = self
            .pairs
            .iter()
            .flat_map(|p| p.nodes.iter().map(|s| s.gap0))
            .collect();
        let cn: Vec<f64> = (0..n)
            .map(|i| 1.0 / self.wn[(i, i)].abs().max(1e-300))
            .collect();
        let ct: Vec<f64> = (0..n)
            .map(|i| 1.0 / self.wt[(i, n + i)].abs().max(1e-300))
            .collect();
        // Column scales: tractions by the shear modulus, translations by the model size.
        let colscale: Vec<f64> = (0..nz)
            .map(|c| if c < 2 * n { self.scale } else { self.length })
            .collect();
        let mut states = self.states.clone();
        let mut history: Vec<Vec<ContactState>> = Vec::new();
        let mut single = false;
        let mut z = vec![0.0; nz];
        let mut residual;
        let mut iterations = 0;
        let evaluate = |z: &[f64]| -> (Vec<f64>, Vec<f64>) {
            let mut g = vec![0.0; n];
            let mut s = vec![0.0; n];
            for i in 0..n {
                let (mut a, mut b) = (g0[i] + lam * self.gn_ext[i], lam * self.st_ext[i]);
                for c in 0..nz {
                    a += self.wn[(i, c)] * z[c];
                    b += self.wt[(i, c)] * z[c];
                }
                g[i] = a;
                s[i] = b;
            }
            (g, s)
        };
        loop {
            iterations += 1;
            // Build the linear system of the current sets.
            let mut a = Mat::<f64>::zeros(nz, nz);
            let mut rhs = vec![0.0; nz];
            let mut any_active = false;
            for i in 0..n {
                match states[i] {
                    ContactState::Outside | ContactState::Open => {
                        a[(i, i)] = 1.0;
                        a[(n + i, n + i)] = 1.0;
                    }
                    st => {
                        any_active = true;
                        for c in 0..nz {
                            a[(i, c)] = self.wn[(i, c)];
                        }
                        rhs[i] = -(g0[i] + lam * self.gn_ext[i]);
                        if fric[i] == 0.0 {
                            a[(n + i, n + i)] = 1.0;
                        } else if st == ContactState::Stick {
                            for c in 0..nz {
                                a[(n + i, c)] = self.wt[(i, c)];
                            }
                            rhs[n + i] = self.slip[i] - lam * self.st_ext[i];
                        } else {
                            let sigma = if st == ContactState::SlipPositive {
                                -1.0
                            } else {
                                1.0
                            };
                            // q = sigma f p (slip along +tau: friction along -tau).
                            a[(n + i, n + i)] = 1.0;
                            a[(n + i, i)] = -sigma * fric[i];
                        }
                    }
                }
            }
            for (j, c) in ctl.iter().enumerate() {
                let row = 2 * n + j;
                match *c {
                    Control::Force(f) => {
                        for cc in 0..nz {
                            a[(row, cc)] = self.kf[(j, cc)];
                        }
                        rhs[row] = f - lam * self.f_ext[j];
                    }
                    Control::Displacement(u) => {
                        a[(row, row)] = 1.0;
                        rhs[row] = u;
                    }
                }
            }
            // Open and outside nodes have p = q = 0: only the unknowns of contact nodes and the
            // rigid translations enter the solve. Equilibrate: columns by the unknowns'
            // scales, rows by their largest entry.
            let act: Vec<usize> = (0..nz)
                .filter(|&c| {
                    c >= 2 * n
                        || !matches!(states[c % n], ContactState::Open | ContactState::Outside)
                })
                .collect();
            let m = act.len();
            let mut am = Mat::<f64>::zeros(m, m);
            let mut bm = Mat::<f64>::zeros(m, 1);
            for (r, &ra) in act.iter().enumerate() {
                let mut rmax = 0.0_f64;
                for &c in &act {
                    rmax = rmax.max((a[(ra, c)] * colscale[c]).abs());
                }
                let rs = if rmax > 0.0 { 1.0 / rmax } else { 1.0 };
                for (cc, &c) in act.iter().enumerate() {
                    am[(r, cc)] = a[(ra, c)] * colscale[c] * rs;
                }
                bm[(r, 0)] = rhs[ra] * rs;
            }
            let y = am.partial_piv_lu().solve(&bm);
            let chk = &am * &y - &bm;
            let mut bad = false;
            let (mut rn, mut yn) = (0.0_f64, 0.0_f64);
            for r in 0..m {
                if !y[(r, 0)].is_finite() {
                    bad = true;
                }
                rn = rn.max(chk[(r, 0)].abs());
                yn = yn.max(y[(r, 0)].abs());
            }
            if bad || rn > 1e-8 * (yn + 1.0) {
                if !any_active {
                    return Err(Error::NoContact {
                        detail: format!(
                            "load step {k}: no slave node is in contact and a force-controlled \
                             body is left floating"
                        ),
                    });
                }
                return Err(Error::Numerical {
                    context: "2D BEM contact step",
                    detail: format!(
                        "load step {k}: the contact system is singular (residual {rn:.3e}): a \
                         rigid-body mode is restrained by neither contact, friction nor a \
                         displacement control (e.g. a force-controlled tangential load on a \
                         frictionless pair)"
                    ),
                });
            }
            z.iter_mut().for_each(|v| *v = 0.0);
            for (r, &c) in act.iter().enumerate() {
                z[c] = y[(r, 0)] * colscale[c];
            }
            if let Some(j) = (0..nz - 2 * n).find(|&j| z[2 * n + j].abs() > self.length) {
                return Err(Error::Numerical {
                    context: "2D BEM contact step",
                    detail: format!(
                        "load step {k}: rigid segment '{}' moves {:.3e} m, more than the model \
                         size: a rigid-body mode is restrained by neither contact, friction nor a \
                         displacement control (e.g. a force-controlled tangential load on a \
                         frictionless pair); the step system is singular up to discretization error",
                        self.rigid[j / 2].0,
                        z[2 * n + j]
                    ),
                });
            }
            let (g, s) = evaluate(&z);
            // New sets and the complementarity residual.
            let mut new_states = states.clone();
            let mut rmax = 0.0_f64;
            let pmax = (0..n).map(|i| z[i]).fold(0.0_f64, f64::max);
            for i in 0..n {
                if states[i] == ContactState::Outside {
                    continue;
                }
                let (p, q) = (z[i], z[n + i]);
                let ds = s[i] - self.slip[i];
                let pn = p - cn[i] * g[i];
                let qt = q - ct[i] * ds;
                let bound = fric[i] * pn.max(0.0);
                rmax = rmax
                    .max((p - pn.max(0.0)).abs())
                    .max((q - qt.clamp(-bound, bound)).abs());
                new_states[i] = if pn <= 0.0 {
                    ContactState::Open
                } else if fric[i] == 0.0 || qt.abs() <= bound {
                    ContactState::Stick
                } else if qt < 0.0 {
                    ContactState::SlipPositive
                } else {
                    ContactState::SlipNegative
                };
            }
            residual = rmax / pmax.max(f64::MIN_POSITIVE);
            if pmax == 0.0 {
                residual = rmax;
            }
            if new_states == states && residual <= options.tolerance {
                break;
            }
            let cycled = history.contains(&new_states);
            if iterations >= options.max_iterations || (cycled && single) {
                return Err(Error::NotConverged {
                    solver: "2D BEM frictional contact (active set)",
                    iterations,
                    residual,
                    tolerance: options.tolerance,
                });
            }
            if cycled {
                // Cycling guard: from now on change one node per iteration, the first that
                // violates its conditions (Murty's least-index rule, finite for P-matrix
                // LCPs); a second cycle is reported as NotConverged.
                single = true;
                history.clear();
            }
            history.push(states.clone());
            if single {
                if let Some(i) = (0..n).find(|&i| new_states[i] != states[i]) {
                    states[i] = new_states[i];
                }
            } else {
                states = new_states;
            }
        }
        // Contact beyond the master segment.
        for p in &self.pairs {
            for b in 0..p.nodes.len() {
                let i = p.offset + b;
                let active = !matches!(states[i], ContactState::Open | ContactState::Outside);
                if active {
                    let nb = [b.wrapping_sub(1), b + 1];
                    for m in nb {
                        if m < p.nodes.len() && states[p.offset + m] == ContactState::Outside {
                            return Err(Error::ContactReachesWindow {
                                detail: format!(
                                    "contact pair '{}' / '{}': the contact reaches the end of \
                                     the master segment; extend the master segment",
                                    p.pair.slave, p.pair.master
                                ),
                            });
                        }
                    }
                }
            }
        }
        let (g, s) = evaluate(&z);
        let mut pairs = Vec::new();
        for p in &self.pairs {
            let mut nodes = Vec::new();
            let mut sf = [0.0; 2];
            let mut mf = [0.0; 2];
            let mut touches = false;
            let last = p.nodes.len() - 1;
            let nm = p.master_weights.len();
            let mut tm = vec![[0.0; 2]; nm];
            for (b, sn) in p.nodes.iter().enumerate() {
                let i = p.offset + b;
                let t = [
                    z[i] * sn.normal[0] + z[n + i] * sn.tangent[0],
                    z[i] * sn.normal[1] + z[n + i] * sn.tangent[1],
                ];
                for d in 0..2 {
                    sf[d] += p.slave_weights[b] * t[d];
                }
                for a in 0..nm {
                    for d in 0..2 {
                        tm[a][d] -= p.proj[(a, b)] * t[d];
                    }
                }
                let st = states[i];
                if (b == 0 || b == last)
                    && !matches!(st, ContactState::Open | ContactState::Outside)
                {
                    touches = true;
                }
                let (gap, slip, inc) = if sn.master.is_some() {
                    (Some(g[i]), s[i], s[i] - self.slip[i])
                } else {
                    (None, 0.0, 0.0)
                };
                nodes.push(ContactNode {
                    position: sn.position,
                    param: sn.param,
                    normal: sn.normal,
                    tangent: sn.tangent,
                    pressure: z[i],
                    shear: z[n + i],
                    initial_gap: sn.master.map(|_| sn.gap0),
                    gap,
                    slip,
                    slip_increment: inc,
                    state: st,
                });
            }
            for a in 0..nm {
                for d in 0..2 {
                    mf[d] += p.master_weights[a] * tm[a][d];
                }
            }
            pairs.push(PairResult {
                slave: p.pair.slave.clone(),
                master: p.pair.master.clone(),
                nodes,
                slave_force: sf,
                master_force: mf,
                touches_slave_end: touches,
            });
        }
        let mut rigid = Vec::new();
        for (j, (name, _)) in self.rigid.iter().enumerate() {
            let mut force = [0.0; 2];
            for d in 0..2 {
                let mut f = lam * self.f_ext[2 * j + d];
                for c in 0..nz {
                    f += self.kf[(2 * j + d, c)] * z[c];
                }
                force[d] = f;
            }
            rigid.push(RigidResult {
                segment: name.clone(),
                translation: [z[2 * n + 2 * j], z[2 * n + 2 * j + 1]],
                force,
            });
        }
        let solution = self.boundary_state(lam, &z);
        // Path memory for the next step.
        for i in 0..n {
            if states[i] != ContactState::Outside {
                self.slip[i] = s[i];
            }
        }
        self.states = states;
        Ok(ContactStepResult {
            iterations,
            residual,
            pairs,
            rigid,
            solution,
        })
    }

    /// The full boundary state for external factor `lam` and contact unknowns `z`.
    fn boundary_state(&self, lam: f64, z: &[f64]) -> BemSolution {
        let np = self.params.len();
        let mut param = vec![0.0; np];
        for k in 0..np {
            let mut v = 0.0;
            for c in 0..z.len() {
                v += self.pz[(k, c)] * z[c];
            }
            param[k] = v;
        }
        let mut x = vec![0.0; self.ncol];
        for body in &self.bodies {
            for (li, &col) in body.cols.iter().enumerate() {
                let mut v = lam * body.x[(li, 0)];
                for (k, &gp) in body.params.iter().enumerate() {
                    v += body.x[(li, 1 + k)] * param[gp];
                }
                x[col] = v;
            }
        }
        let mut over_t: HashMap<(usize, usize, usize), f64> = HashMap::new();
        let mut over_u: HashMap<(usize, usize, usize), f64> = HashMap::new();
        for (k, p) in self.params.iter().enumerate() {
            match *p {
                Param::Traction { region, node, d } => {
                    over_t.insert((region, node, d), param[k]);
                }
                Param::Rigid { j, d } => {
                    let info = &self.problem.mesh.segments[self.rigid[j].1];
                    for &o in &info.owner_nodes {
                        over_u.insert((info.owner, o, d), param[k]);
                    }
                }
            }
        }
        let mut displacement = Vec::new();
        let mut traction = Vec::new();
        for (r, d) in self.dofs.iter().enumerate() {
            let mut u = Vec::with_capacity(d.len());
            let mut t = Vec::with_capacity(d.len());
            for (node, dn) in d.iter().enumerate() {
                let mut un = [0.0; 2];
                let mut tn = [0.0; 2];
                for dir in 0..2 {
                    match dn[dir] {
                        Dof::U { col, t } => {
                            un[dir] = x[col];
                            tn[dir] = over_t.get(&(r, node, dir)).copied().unwrap_or(lam * t);
                        }
                        Dof::T { col, u } => {
                            un[dir] = over_u.get(&(r, node, dir)).copied().unwrap_or(lam * u);
                            tn[dir] = x[col] * self.scale;
                        }
                        Dof::Interface { u_col, t_col, sign } => {
                            un[dir] = x[u_col];
                            tn[dir] = sign * x[t_col] * self.scale;
                        }
                    }
                }
                u.push(un);
                t.push(tn);
            }
            displacement.push(u);
            traction.push(t);
        }
        BemSolution {
            mesh: self.problem.mesh.clone(),
            displacement,
            traction,
            residual: self.lu_residual,
            body_force_factor: lam,
        }
    }
}

/// The segment of node `node` of region `r`.
fn self_segment(problem: &BemProblem, r: usize, node: usize) -> usize {
    problem.mesh.regions[r].nodes[node].segment
}

/// int N_k ds over the segment's elements, per segment node (owner order).
fn node_weights(problem: &BemProblem, seg: usize) -> Vec<f64> {
    let info = &problem.mesh.segments[seg];
    let local: HashMap<usize, usize> = info
        .owner_nodes
        .iter()
        .enumerate()
        .map(|(k, &o)| (o, k))
        .collect();
    let (gx, gw) = gauss_legendre(8);
    let mut w = vec![0.0; info.owner_nodes.len()];
    for e in seg_elements(problem, seg) {
        for (&xi, &wq) in gx.iter().zip(&gw) {
            let (_, jac) = e.normal_jacobian(xi);
            let nsh = e.field_shape(xi);
            for a in 0..3 {
                w[local[&e.nodes[a]]] += wq * jac * nsh[a];
            }
        }
    }
    w
}

#[cfg(test)]
mod tests;
