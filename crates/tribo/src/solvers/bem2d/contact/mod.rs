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
//! come out wrong (Blázquez, París, Mantič, EABE 21 (1998) 361-375, docs/theory/BEM2D.md sec. 1). The
//! pair is taken as given; the rule is the caller's (documented) responsibility.
//!
//! # Condensation
//!
//! Every body (regions joined by bonded interfaces) is factored once: contact-segment nodes
//! take their traction as a parameter, rigid-load segments (below) and the artificial supports
//! of free bodies (below) their displacement, so `A_b x_b = sum_g b_b,g + B_b c_b` with b_b,g
//! the right-hand side of load group g (the ungrouped conditions are group 0) and c_b the
//! body's contact tractions, rigid translations and free-mode amplitudes. One LU of A_b and
//! `n_groups + dim c_b` solves give the response of the contact-node displacements and of the
//! rigid-segment force resultants: a dense flexibility of the slave-node gaps, slips and
//! rigid forces on the contact unknowns z (p, q, rigid translations, free-mode amplitudes),
//! `g = g0 + sum_g lambda_g g_g + W_n z`, `s = sum_g lambda_g s_g + W_t z`, `F = sum_g
//! lambda_g F_g + K z`, lambda_g the step's factor of group g. Each load step then solves only
//! small dense systems of size dim z.
//!
//! # Loads, rigid-body modes and steps
//!
//! A body held only by contact (a cylinder pressed on a block, a clamp plate pressed by a bolt
//! onto a knife) is loaded either through a *rigid segment* or by ordinary traction and
//! pressure conditions.
//!
//! *Rigid segment*: a named segment that moves as a rigid translation (no rotation: a guided
//! face), each component either force-controlled (the resultant of the traction on the
//! segment is prescribed, the translation unknown) or displacement-controlled. This removes
//! the body's rigid-body modes from the BEM system (the segment is a displacement boundary
//! for the factorization) and returns them to the contact problem. A force-controlled
//! component that neither contact nor friction restrains makes the step's system singular
//! and is reported as an [`Error::Numerical`].
//!
//! *Free bodies* (automatic rigid-body modes): a body that takes part in a contact pair and
//! whose displacement conditions leave rigid modes free. The free modes are the null space of
//! the prescribed displacement components on the rigid modes r = (x translation, y
//! translation, rotation about the boundary centroid scaled by the body size L, so that all
//! three amplitudes are lengths), found from the eigenvalues of the 3 x 3 Gram matrix
//! (threshold: the 1e-6 of the BEM restraint check); u_x = 0 on a vertical face leaves y free,
//! no condition leaves all three. For each free mode one traction-type boundary node
//! component off the contact and rigid segments becomes an *artificial support*: its
//! displacement is a parameter u_pin = R_pin a with a the body's free-mode amplitudes, a
//! statically determinate set of supports far apart. Where all three modes are free, the
//! supports turn with the body: the whole displacement of a node A and the component of a
//! node B normal to AB (the pair of nodes that maximizes far(A) far(B) |AB|, far = distance
//! from the contact; B's two DOFs taken along that normal and along AB), so that results do
//! not depend on how the model is turned (supports along the global axes made the contact
//! tractions of a turned model differ by up to 2.7e-4 of p_max). Where one or two modes
//! are free (displacement conditions along the global axes), the supports are node components
//! along the global axes chosen by pivoting (the component whose rigid-mode row has the
//! largest part orthogonal to the rows already chosen; among near ties the one farthest from
//! the contact). With the supports the body's BEM system is regular
//! (one LU as before) and a joins z. The equations that determine a are the free body's
//! equilibrium in each free mode k, the virtual work of all its boundary tractions on r_k,
//!
//! `sum_i (int N_i r_k ds) . t_i = 0`,
//!
//! summed over the prescribed tractions (at the supports their prescribed values; scaled by
//! the step's group factors), the body forces (`int_V b . r_k dV = -int_S t_p . r_k ds`,
//! ungrouped) and the contact tractions (slave p n + q tau, master the
//! transferred traction), the interpolated fields integrated by 8-point Gauss rules
//! (prescribed displacement components do no work on a free mode). So the contact tractions
//! balance the applied loads in every free mode to round-off. The supports' own reactions
//! (their BEM tractions minus the prescribed values) are then the BEM's equilibrium defect of
//! the body (the discrete `H u = G t` balances only to discretization error): the step result
//! reports their resultant ([`FreeBodyResult::support_force`]; measured 6e-6 and 8e-5 of the
//! load in the Hertz tests, 1e-13 in the uniform state) and the boundary state reports the
//! prescribed traction at the supports. The alternative, prescribing the supports' tractions
//! exactly and leaving equilibrium to the BEM, moves the same defect into the balance of
//! contact and applied forces; the choice here makes the contact force equal the applied load.
//! The reported motion ([`FreeBodyResult`]) is the least-squares rigid motion of the body's
//! boundary displacement (independent of the supports): translation = arc-length mean of u,
//! rotation = `int r x u ds / int abs(r)^2 ds` about the boundary centroid.
//!
//! A free mode must be held by the contact rows of the step (the gap rows of nodes in contact
//! and the stick rows): in each active-set iteration, while the amplitude columns of these
//! rows are rank deficient (smallest singular value below 1e-8; the entries are
//! dimensionless), the open node with the smallest gap whose rows act on the deficient
//! combination is brought into contact (a single initial contact node does not hold the
//! rotation of a free cylinder). Where no node can, the step stops with an
//! [`Error::InvalidParameter`] naming the body and the mode (e.g. "body \[blk\] = free
//! rigid-body translation in x": a frictionless contact holds no tangential motion, also
//! without a tangential load, since the position is then undetermined; use a symmetry or
//! displacement condition); where the last solve opened every contact node of the body (its
//! loads pull it off or vanish), with [`Error::NoContact`]. A body with free modes that is in
//! no contact pair is rejected before factorization (the BEM restraint check, an
//! [`Error::InvalidParameter`]).
//!
//! Friction is path dependent, so loads are applied in [`LoadStep`]s: each sets the factors of
//! the external boundary conditions per *load group* and the controls of every rigid segment.
//! Conditions set with [`BoundaryConditions::set`] are ungrouped (factor
//! [`LoadStep::external`]); those set with [`BoundaryConditions::set_in_group`] take their
//! group's factor from [`LoadStep::groups`], 0 where the step does not list the group (so a
//! step 1 "bolt" and a step 2 "bolt + cut" are `LoadStep::new(0.0).with_group("bolt", 1.0)`
//! and the same `.with_group("cut", 1.0)`). A displacement condition in a group is scaled
//! too. The regions' body forces are external loads of the ungrouped column (factor
//! [`LoadStep::external`]); the displacements are totals, so the gaps include the particular
//! solution. The Coulomb law is written on the slip increment of the step,
//! `ds_i = s_i - s_i(previous step)`:
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
//! face) holds to the BEM discretization error (1e-5 relative in the Hertz test), except for
//! free bodies, whose equilibrium in their free modes is an equation (round-off, see above).
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
//! | free block on base, uniform pressure (exact uniform state), f = 0 (y free) and 0.3 (all free) | p, q, rigid motion; force, moment | 1.6e-10 p, 1e-11 p, 2e-11; 1e-15, 1e-13 |
//! | free plate on free knife on base (chain) | p, rigid y motions | 1.6e-10 p, < 1e-7 |
//! | Hertz, cylinder held only by contact (face load), f = 0 (y, rotation free) / 0.3 (all free) | b, p0, max abs(p - p_H)/p0; support force | -0.09 %, +0.02 %, 0.21 % / 0.18 %; 8e-5 / 6e-6 P |
//! | free block pushed sideways, f = 0.3, Q = 0.6 f P (groups bolt, cut) | Coulomb at every node; force, moment | round-off; 1e-16, 5e-16 |
//! | free cylinder (f = 0.3, all free) turned by 0.3, 2.1, -1 rad (`rigid_motion_tests.rs`) | p, q; motion | 6.6e-11, 1.7e-12 p_max; 1.7e-11 (supports along global axes: 1.5e-8 q, 1.9e-7 motion at 0.3 rad) |
//! | free mode that nothing holds (f = 0 pushed sideways or not; f = 0.3, Q = 1.1 f P) | error naming body and mode | yes |
//! | load groups, f = 0: two steps vs one, and unloading a group | p, u | identical (0) |
//! | load groups, f = 0.3: bulk load applied and removed vs never applied | locked-in q | 0.37 f p0 (p within 0.5 % p0) |
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
//! bulk stress, e = a sigma / (4 f p0)); `docs/theory/BEM2D.md` A4-A6.

// Index loops read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use std::collections::HashMap;

use faer::linalg::solvers::Solve;
use faer::Mat;

use super::{nearest_xi, BemProblem, BemSolution, BoundaryConditions, Dof, SegmentBc};
use crate::error::{Error, Result};
use crate::kernels::quadrature::gauss_legendre;
use crate::operators::bem2d::assemble::{matrix_bytes, probe_memory, try_zeros};
use crate::operators::bem2d::{BemMesh, BemModel, Element};
use crate::solvers::nan_max;

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
///
/// The boundary conditions given to [`ContactProblem::new`] are scaled per load group: the
/// ungrouped ones (set with [`BoundaryConditions::set`]) by `external`, those of a named group
/// (set with [`BoundaryConditions::set_in_group`]) by that group's factor in `groups`. **A
/// group not listed in a step has factor 0 in that step** (a group is off unless the step
/// turns it on, so that adding a group to a model never changes steps written before it).
#[derive(Debug, Clone, PartialEq)]
pub struct LoadStep {
    /// Factor on the ungrouped external boundary conditions.
    pub external: f64,
    /// The control of every rigid segment.
    pub rigid: Vec<RigidControl>,
    /// Factor of each named load group (unlisted groups: 0). Each name must be a group of the
    /// boundary conditions and appear once.
    pub groups: Vec<(String, f64)>,
}

impl LoadStep {
    /// A step with factor `external` on the ungrouped conditions, no rigid controls and every
    /// named group at factor 0.
    pub fn new(external: f64) -> Self {
        Self {
            external,
            rigid: Vec::new(),
            groups: Vec::new(),
        }
    }

    /// The same step with load group `name` at factor `factor`.
    pub fn with_group(mut self, name: &str, factor: f64) -> Self {
        self.groups.push((name.to_string(), factor));
        self
    }

    /// The same step with one more rigid-segment control.
    pub fn with_rigid(mut self, control: RigidControl) -> Self {
        self.rigid.push(control);
        self
    }
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
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
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
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
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
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
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
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct RigidResult {
    /// Segment.
    pub segment: String,
    /// Translation, m.
    pub translation: [f64; 2],
    /// Resultant of the traction on the segment, N/m.
    pub force: [f64; 2],
}

/// The motion of a body held only by contact and friction (a body with free rigid-body
/// modes, see the module docs) in one step.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct FreeBodyResult {
    /// The name of the body's first region.
    pub body: String,
    /// Translation of the reference point under the least-squares rigid motion of the body's
    /// boundary displacement (the arc-length mean of u over the boundary), m.
    pub translation: [f64; 2],
    /// Rotation of that least-squares rigid motion, rad, counter-clockwise positive:
    /// `int (r x u) ds / int abs(r)^2 ds` with r = x - reference_point.
    pub rotation: f64,
    /// The arc-length centroid of the body's boundary (initial configuration), m.
    pub reference_point: [f64; 2],
    /// The rigid-body modes left free by the body's displacement conditions (held by contact
    /// and friction), in words.
    pub free_modes: Vec<String>,
    /// Resultant of the reactions of the body's artificial supports, N/m: the BEM's own
    /// equilibrium defect of the body, small against the contact force (see the module docs).
    pub support_force: [f64; 2],
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
    /// Per body with free rigid-body modes (in the order of the bodies).
    pub free_bodies: Vec<FreeBodyResult>,
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
    /// Amplitude of a free mode of free body f.
    Free { f: usize },
}

/// An artificial support of a free body: a traction-type node component made a
/// displacement unknown-as-parameter, u = row . a (a: the body's free-mode amplitudes).
#[derive(Debug, Clone)]
struct Pin {
    region: usize,
    node: usize,
    d: usize,
    /// Prescribed traction at factor 1 of its load group, Pa.
    t: f64,
    /// Load-group column of the prescribed traction.
    group: usize,
    /// Displacement per unit amplitude of each free mode.
    row: Vec<f64>,
    /// int N ds of the node, m.
    weight: f64,
    /// Directions of the node's two components `d` = 0, 1 (rows, unit vectors) where they
    /// are not the global axes: the support along the normal to the line between two
    /// supported nodes (see [`bodies::free_body`]). Both DOFs of such a node are in this
    /// frame (the other component keeps its prescribed traction along its direction).
    frame: Option<[[f64; 2]; 2]>,
}

impl Pin {
    /// Global direction of the supported component (unit vector).
    fn direction(&self) -> [f64; 2] {
        match self.frame {
            Some(f) => f[self.d],
            None if self.d == 0 => [1.0, 0.0],
            None => [0.0, 1.0],
        }
    }
}

/// A body whose displacement conditions leave rigid-body modes free.
#[derive(Debug, Clone)]
struct FreeBody {
    /// Name of the first region.
    name: String,
    /// "body [regions]".
    field: String,
    regions: Vec<usize>,
    /// Arc-length centroid of the boundary in model-local coordinates (relative to
    /// `BemMesh::origin`), m.
    center: [f64; 2],
    /// Largest distance of a boundary node from the centroid, m (scales the rotation).
    size: f64,
    /// Orthonormal basis of the free modes in (tx, ty, size * rotation).
    modes: Vec<[f64; 3]>,
    /// Column of the first amplitude in z.
    zcol: usize,
    /// Index of the first amplitude parameter.
    param0: usize,
    pins: Vec<Pin>,
}

#[derive(Debug, Clone)]
struct Body {
    /// Regions and their row offset in the body system.
    regions: Vec<(usize, usize)>,
    /// Global columns of the body's unknowns (body-local index -> global column).
    cols: Vec<usize>,
    /// Global parameter indices of the body.
    params: Vec<usize>,
    /// Solutions: column g for load group g (0: ungrouped; factor 1), column `next + k` for
    /// unit parameter k of the body (next = 1 + number of named groups).
    x: Mat<f64>,
}

/// The segments claimed by the contact pairs and the rigid segments.
#[derive(Debug, Clone)]
struct Roles {
    /// The role of every claimed segment, in words (for error messages).
    role: HashMap<usize, String>,
    /// (slave, master) segment of each pair.
    pair_segs: Vec<(usize, usize)>,
    /// Name and segment of each rigid segment.
    rigid_segs: Vec<(String, usize)>,
}

/// The body parameters and the map from the contact unknowns z to them.
#[derive(Debug, Clone)]
struct Params {
    params: Vec<Param>,
    /// Parameter of the traction component (region, node, d) of a contact node.
    param_of: HashMap<(usize, usize, usize), usize>,
    /// (free body, support) of a supported component (region, node, d).
    pin_of: HashMap<(usize, usize, usize), (usize, usize)>,
    /// Index of the first rigid-translation parameter.
    rigid_base: usize,
    /// Parameters = pz z.
    pz: Mat<f64>,
}

/// A candidate for an artificial support of a free body: a traction-type node component.
#[derive(Debug, Clone)]
struct PinCandidate {
    region: usize,
    node: usize,
    d: usize,
    /// Displacement of the component per unit amplitude of each free mode.
    row: Vec<f64>,
    /// Distance from the nearest contact node of the body, m.
    far: f64,
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
    /// Named load groups (column 1 + index).
    groups: Vec<String>,
    /// Load-group column of every segment (0: ungrouped).
    seg_group: Vec<usize>,
    /// Bodies with free rigid-body modes.
    free: Vec<FreeBody>,
    /// Unknowns z = [p (n), q (n), rigid translations (2 per rigid segment), free-mode
    /// amplitudes (per free body)].
    n: usize,
    /// Map z -> parameters.
    pz: Mat<f64>,
    wn: Mat<f64>,
    wt: Mat<f64>,
    kf: Mat<f64>,
    /// External responses, one column per load group.
    gn_ext: Mat<f64>,
    st_ext: Mat<f64>,
    f_ext: Mat<f64>,
    /// Free-body equilibrium rows: eq_z z + eq_ext lambda = 0.
    eq_z: Mat<f64>,
    eq_ext: Mat<f64>,
    /// Largest prescribed traction of each load group at factor 1 (a prescribed displacement
    /// counted as shear modulus * u / model size), Pa: the load scale of a step.
    group_load: Vec<f64>,
    /// Largest relative residual of the body factorizations.
    lu_residual: f64,
    /// Total slip at the end of the last solved step (path memory).
    slip: Vec<f64>,
    states: Vec<ContactState>,
}

mod bodies;
mod condense;
mod geometry;
mod linalg;
mod setup;
mod step;

use bodies::{find_free_bodies, free_body_equilibrium, node_frame};
use condense::BodyAssembly;
pub use geometry::{pair_geometries, PairGeometry, SlaveNodeGeometry};
use linalg::{dot3, symmetric_eigen};
use setup::{
    check_pair_bodies, claim_roles, classify_dofs, group_loads, load_groups, model_scales,
    node_weights, pair_geometry, parameters, seg_elements, self_segment,
};

impl ContactProblem {
    /// Meshes and assembles `model`, validates the pairs and rigid segments, factors every
    /// body once and condenses the BEM systems onto the contact unknowns.
    ///
    /// `bcs` are the external boundary conditions (scaled per load group: ungrouped ones by
    /// [`LoadStep::external`], grouped ones by [`LoadStep::groups`]); they must not name
    /// contact or rigid segments. `rigid` names the rigid (load) segments. A body in a contact
    /// pair may leave rigid-body modes free (held by contact and friction; see the module
    /// docs).
    ///
    /// Errors ([`Error::InvalidParameter`] naming the item): an unknown segment in a pair or
    /// in `rigid`; a segment used twice (in two pairs, as rigid and contact, or with a boundary
    /// condition); a bonded interface used as contact or rigid segment; slave and master in the
    /// same body; a friction coefficient that is negative or not finite; a pair whose slave
    /// nodes all miss the master; initial penetration deeper than 1e-6 of the slave's
    /// smallest element; an unrestrained body in no contact pair; an empty load-group name; a
    /// free body with no traction-loaded node off its contact segments for an artificial
    /// support. [`Error::Numerical`] where a factorization fails.
    pub fn new(
        model: &BemModel,
        bcs: &BoundaryConditions,
        pairs: &[ContactPair],
        rigid: &[&str],
    ) -> Result<Self> {
        let problem = BemProblem::new(model)?;
        Self::from_problem(problem, bcs, pairs, rigid)
    }

    /// As [`ContactProblem::new`], from an assembled problem. The phases, in order: roles of
    /// the named segments, bodies, DOF classification, load groups, free bodies and their
    /// supports, pair geometry, parameters, free-body equilibrium, load scales, the body
    /// factorizations, then the condensation (see "Condensation" in the module docs).
    pub fn from_problem(
        problem: BemProblem,
        bcs: &BoundaryConditions,
        pairs: &[ContactPair],
        rigid: &[&str],
    ) -> Result<Self> {
        let mesh = &problem.mesh;
        let roles = claim_roles(mesh, bcs, pairs, rigid)?;
        let body_of = super::region_bodies(mesh);
        check_pair_bodies(mesh, pairs, &roles.pair_segs, &body_of)?;
        let (mut dofs, ncol) = classify_dofs(&problem, bcs, &roles)?;
        let (groups, seg_group) = load_groups(mesh, bcs)?;
        let next = 1 + groups.len();
        let mut free = find_free_bodies(&problem, &mut dofs, &roles, &seg_group)?;
        let (scale, length) = model_scales(mesh);
        let pdata = pair_geometry(&problem, pairs, &roles.pair_segs)?;
        // The contact unknowns z: p (n), q (n), rigid translations (2 per rigid segment),
        // free-mode amplitudes (per free body).
        let n: usize = pdata.iter().map(|p| p.nodes.len()).sum();
        let nrig = 2 * roles.rigid_segs.len();
        let mut nz = 2 * n + nrig;
        for fb in free.iter_mut() {
            fb.zcol = nz;
            nz += fb.modes.len();
        }
        let prm = parameters(mesh, &pdata, nrig, &mut free, n, nz);
        let (eq_param, eq_ext) =
            free_body_equilibrium(&problem, &free, &dofs, &seg_group, &prm, next);
        let eq_z = &eq_param * &prm.pz;
        let group_load = group_loads(
            mesh,
            &dofs,
            &roles,
            &seg_group,
            &free,
            next,
            (scale, length),
        );
        let (bodies, lu_residual) = BodyAssembly {
            problem: &problem,
            dofs: &dofs,
            body_of: &body_of,
            prm: &prm,
            free: &free,
            rigid_segs: &roles.rigid_segs,
            seg_group: &seg_group,
            scale,
            next,
        }
        .factor_bodies()?;
        let Params { params, pz, .. } = prm;
        let rigid_segs = roles.rigid_segs;
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
            groups,
            seg_group,
            free,
            n,
            pz,
            wn: Mat::zeros(0, 0),
            wt: Mat::zeros(0, 0),
            kf: Mat::zeros(0, 0),
            gn_ext: Mat::zeros(0, 0),
            st_ext: Mat::zeros(0, 0),
            f_ext: Mat::zeros(0, 0),
            eq_z,
            eq_ext,
            group_load,
            lu_residual,
            slip: vec![0.0; n],
            states: Vec::new(),
        };
        this.condense();
        this.reset();
        Ok(this)
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

    /// Number of external-load columns: 1 (ungrouped) + the named load groups.
    fn next(&self) -> usize {
        1 + self.groups.len()
    }

    /// The named load groups of the boundary conditions, in the order of their first use.
    pub fn load_groups(&self) -> &[String] {
        &self.groups
    }

    /// Number of contact unknowns (2 per slave node, 2 per rigid segment, and one per free
    /// rigid-body mode of each body held only by contact).
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
}

pub(crate) mod reference;

#[cfg(test)]
mod tests;
