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
//! displacement is a parameter u_pin = R_pin a with a the body's free-mode amplitudes, chosen
//! by pivoting (the component whose rigid-mode row has the largest part orthogonal to the rows
//! already chosen; among near ties the one farthest from the contact), i.e. a statically
//! determinate set of supports far apart. With the supports the body's BEM system is regular
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
use crate::operators::bem2d::{BemModel, Element};
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

/// The motion of a body held only by contact and friction (a body with free rigid-body
/// modes, see the module docs) in one step.
#[derive(Debug, Clone, PartialEq)]
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

/// The elements of segment `seg` in model-local coordinates (`RegionMesh::local_elements`:
/// the pair geometry, gaps and transfer are formed there, free of the rounding of large
/// absolute coordinates).
fn seg_elements(problem: &BemProblem, seg: usize) -> Vec<Element> {
    let owner = problem.mesh.segments[seg].owner;
    problem.mesh.regions[owner]
        .local_elements
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
        if best.is_none_or(|b| d < b.0) {
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

    /// As [`ContactProblem::new`], from an assembled problem.
    pub fn from_problem(
        problem: BemProblem,
        bcs: &BoundaryConditions,
        pairs: &[ContactPair],
        rigid: &[&str],
    ) -> Result<Self> {
        let mesh = &problem.mesh;
        let origin = mesh.origin;
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
        for (name, _, _) in &bcs.entries {
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
        let (mut dofs, ncol) = problem.dofs(&full)?;
        // --- load groups: column 0 ungrouped, 1 + g for named group g.
        let groups = bcs.groups();
        let mut seg_group = vec![0; mesh.segments.len()];
        for (name, _, g) in &bcs.entries {
            if let Some(g) = g {
                if g.trim().is_empty() {
                    return Err(Error::invalid(
                        format!("boundary_condition '{name}'.group"),
                        "\"\"",
                        "a load group name must not be empty",
                    ));
                }
                if let Some(s) = mesh.segment_index(name) {
                    seg_group[s] = 1 + groups.iter().position(|x| x == g).unwrap_or(0);
                }
            }
        }
        let next = 1 + groups.len();
        // --- restraint: a body in no contact pair must be restrained by its displacement
        // conditions; a body in a pair may leave rigid modes free (held by contact).
        let mut in_pair = vec![false; mesh.regions.len()];
        for &(s, m) in &pair_segs {
            in_pair[mesh.segments[s].owner] = true;
            in_pair[mesh.segments[m].owner] = true;
        }
        let mut free: Vec<FreeBody> = Vec::new();
        for members in problem.bodies() {
            if !members.iter().any(|&r| in_pair[r]) {
                problem.check_body_restraint(&dofs, &members)?;
                continue;
            }
            if let Some(fb) = free_body(&problem, &mut dofs, &members, &role, &seg_group)? {
                free.push(fb);
            }
        }
        let scale = mesh
            .regions
            .iter()
            .map(|r| r.kernels.shear_modulus())
            .fold(0.0_f64, f64::max);
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for r in &mesh.regions {
            for x in &r.local_positions {
                for d in 0..2 {
                    lo[d] = lo[d].min(x[d]);
                    hi[d] = hi[d].max(x[d]);
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
                // Model-local position for the geometry; the global one for the results.
                let x = sregion.local_positions[o];
                let mut sn = SlaveNode {
                    region_node: o,
                    position: node.position,
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
                            format!(
                                "initial gap {g0:.3e} m at ({:.6e}, {:.6e})",
                                node.position[0], node.position[1]
                            ),
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
        let mut nz = 2 * n + nrig;
        for fb in free.iter_mut() {
            fb.zcol = nz;
            nz += fb.modes.len();
        }

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
        for (f, fb) in free.iter_mut().enumerate() {
            fb.param0 = params.len();
            for _ in 0..fb.modes.len() {
                params.push(Param::Free { f });
            }
        }
        let mut pin_of: HashMap<(usize, usize, usize), (usize, usize)> = HashMap::new();
        for (f, fb) in free.iter().enumerate() {
            for (q, pin) in fb.pins.iter().enumerate() {
                pin_of.insert((pin.region, pin.node, pin.d), (f, q));
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
        for fb in &free {
            for k in 0..fb.modes.len() {
                pz[(fb.param0 + k, fb.zcol + k)] = 1.0;
            }
        }

        // --- free-body equilibrium: for each free mode r_k, the virtual work of the
        // boundary tractions, sum_i (int N_i r_k ds) . t_i = 0, over the prescribed tractions
        // (the pins' included) and the contact tractions (the parameters).
        let mtot: usize = free.iter().map(|fb| fb.modes.len()).sum();
        let mut eq_param = Mat::<f64>::zeros(mtot, np);
        let mut eq_ext = Mat::<f64>::zeros(mtot, next);
        let mut row0 = 0;
        for fb in &free {
            for &r in &fb.regions {
                for e in &mesh.regions[r].local_elements {
                    if mesh.segments[e.segment].partner.is_some() {
                        continue;
                    }
                    for (&xi, &w) in gx.iter().zip(&gw) {
                        let x = e.point(xi);
                        let (_, jac) = e.normal_jacobian(xi);
                        let nsh = e.field_shape(xi);
                        for a in 0..3 {
                            let o = e.nodes[a];
                            for d in 0..2 {
                                let rr = rigid_row(d, x, fb.center, fb.size);
                                for (k, mode) in fb.modes.iter().enumerate() {
                                    let wk = w * jac * nsh[a] * dot3(rr, *mode);
                                    if let Some(&(f, q)) = pin_of.get(&(r, o, d)) {
                                        let pin = &free[f].pins[q];
                                        eq_ext[(row0 + k, pin.group)] += wk * pin.t;
                                    } else if let Some(&pk) = param_of.get(&(r, o, d)) {
                                        eq_param[(row0 + k, pk)] += wk;
                                    } else if let Dof::U { t, .. } = dofs[r][o][d] {
                                        let g = seg_group[self_segment(&problem, r, o)];
                                        eq_ext[(row0 + k, g)] += wk * t;
                                    }
                                }
                            }
                        }
                    }
                }
            }
            // Body forces (ungrouped column 0): int_V b . r_k dV = -int_S t_p . r_k ds
            // (div sigma_p = -b and r_k a rigid mode: Gauss's theorem), over every region
            // boundary of the body, interfaces included (t_p jumps there).
            for &r in &fb.regions {
                let region = &mesh.regions[r];
                if region.body_force.is_none() {
                    continue;
                }
                for e in &region.local_elements {
                    for (&xi, &w) in gx.iter().zip(&gw) {
                        let x = e.point(xi);
                        let (n, jac) = e.normal_jacobian(xi);
                        let (_, sp) = region.particular_at([x[0] + origin[0], x[1] + origin[1]]);
                        let tp = [sp[0] * n[0] + sp[2] * n[1], sp[2] * n[0] + sp[1] * n[1]];
                        for d in 0..2 {
                            let rr = rigid_row(d, x, fb.center, fb.size);
                            for (k, mode) in fb.modes.iter().enumerate() {
                                eq_ext[(row0 + k, 0)] -= w * jac * tp[d] * dot3(rr, *mode);
                            }
                        }
                    }
                }
            }
            row0 += fb.modes.len();
        }
        let eq_z = &eq_param * &pz;
        let mut group_load = vec![0.0_f64; next];
        for (r, region) in mesh.regions.iter().enumerate() {
            for (o, node) in region.nodes.iter().enumerate() {
                if role.contains_key(&node.segment) {
                    continue;
                }
                let g = seg_group[node.segment];
                for d in 0..2 {
                    let v = match dofs[r][o][d] {
                        Dof::U { t, .. } => t.abs(),
                        Dof::T { u, .. } => scale * u.abs() / length,
                        Dof::Interface { .. } => 0.0,
                    };
                    group_load[g] = group_load[g].max(v);
                }
            }
        }
        for fb in &free {
            for pin in &fb.pins {
                group_load[pin.group] = group_load[pin.group].max(pin.t.abs());
            }
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
                    Param::Free { f, .. } => body_of[free[f].regions[0]] == root,
                })
                .collect();
            let bp_index: HashMap<usize, usize> =
                bparams.iter().enumerate().map(|(i, &k)| (k, i)).collect();
            let what = format!("the 2D BEM contact body system ({rows} x {rows})");
            let mut a = try_zeros(&what, rows, rows)?;
            let mut rhs = try_zeros(&what, rows, next + bparams.len())?;
            for &(r, off) in &regions {
                let ops = &problem.operators[r];
                let n2 = ops.h.nrows();
                for (node, d) in dofs[r].iter().enumerate() {
                    for (dir, dof) in d.iter().enumerate() {
                        let c = 2 * node + dir;
                        let (hc, gc) = (ops.h.col(c), ops.g.col(c));
                        let seg = self_segment(&problem, r, node);
                        let grp = seg_group[seg];
                        match *dof {
                            Dof::U { col, t } => {
                                let lc = local[&col];
                                let pk = param_of.get(&(r, node, dir)).map(|k| bp_index[k]);
                                for row in 0..n2 {
                                    a[(off + row, lc)] += hc[row];
                                    rhs[(off + row, grp)] += gc[row] * t;
                                    if let Some(pk) = pk {
                                        rhs[(off + row, next + pk)] += gc[row];
                                    }
                                }
                            }
                            Dof::T { col, u } => {
                                let lc = local[&col];
                                let rj = rigid_segs.iter().position(|&(_, s)| s == seg);
                                for row in 0..n2 {
                                    a[(off + row, lc)] -= gc[row] * scale;
                                    rhs[(off + row, grp)] -= hc[row] * u;
                                }
                                if let Some(j) = rj {
                                    let pk = bp_index[&(rigid_base + 2 * j + dir)];
                                    for row in 0..n2 {
                                        rhs[(off + row, next + pk)] -= hc[row];
                                    }
                                }
                                if let Some(&(f, q)) = pin_of.get(&(r, node, dir)) {
                                    let fb = &free[f];
                                    for (k, &v) in fb.pins[q].row.iter().enumerate() {
                                        let pk = bp_index[&(fb.param0 + k)];
                                        for row in 0..n2 {
                                            rhs[(off + row, next + pk)] -= hc[row] * v;
                                        }
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
            // The LU's copy of the matrix and the solution, allocated inside faer.
            probe_memory(
                &format!(
                    "the LU factorization of the 2D BEM contact body system ({rows} x {rows})"
                ),
                matrix_bytes(rows, rows + next + bparams.len()),
            )?;
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
                .fold(0.0_f64, nan_max);
            let mut worst = 0.0_f64;
            for j in 0..k {
                let (mut nr_, mut nx, mut nb) = (0.0_f64, 0.0_f64, 0.0_f64);
                for i in 0..rows {
                    nr_ = nan_max(nr_, res[(i, j)].abs());
                    nx = nan_max(nx, xs[(i, j)].abs());
                    nb = nan_max(nb, bs[(i, j)].abs());
                }
                worst = nan_max(worst, nr_ / nan_max(na * nx + nb, f64::MIN_POSITIVE));
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
        let next = self.next();
        // A row in parameter space (length np) + external coefficients (per load group), for
        // a displacement.
        let urow =
            |this: &Self, region: usize, node: usize, d: usize| -> (Vec<f64>, Vec<(usize, f64)>) {
                let (b, row) = this.displacement_row(region, node, d);
                let body = &this.bodies[b];
                let ext = (0..next).map(|g| body.x[(row, g)]).collect();
                let coef = body
                    .params
                    .iter()
                    .enumerate()
                    .map(|(k, &gp)| (gp, body.x[(row, next + k)]))
                    .collect();
                (ext, coef)
            };
        // Relative displacement rows in parameter space.
        let np = self.params.len();
        let mut rel = Mat::<f64>::zeros(2 * n, np);
        let mut rel_ext = Mat::<f64>::zeros(2 * n, next);
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
                            for g in 0..next {
                                rel_ext[(2 * i + d, g)] += m / wb * e[g];
                            }
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
                            for g in 0..next {
                                rel_ext[(2 * i + d, g)] -= m / wb * e[g];
                            }
                            for (gp, v) in c {
                                rel[(2 * i + d, gp)] -= m / wb * v;
                            }
                        }
                    }
                    continue;
                }
                for d in 0..2 {
                    let (e, c) = urow(self, sinfo.owner, sn.region_node, d);
                    for g in 0..next {
                        rel_ext[(2 * i + d, g)] += e[g];
                    }
                    for (gp, v) in c {
                        rel[(2 * i + d, gp)] += v;
                    }
                    for a in 0..3 {
                        let o = minfo.owner_nodes[mn[a]];
                        let (e, c) = urow(self, minfo.owner, o, d);
                        for g in 0..next {
                            rel_ext[(2 * i + d, g)] -= sh[a] * e[g];
                        }
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
        let mut gn_ext = Mat::<f64>::zeros(n, next);
        let mut st_ext = Mat::<f64>::zeros(n, next);
        for p in &self.pairs {
            for (b, sn) in p.nodes.iter().enumerate() {
                let i = p.offset + b;
                for d in 0..2 {
                    for g in 0..next {
                        gn_ext[(i, g)] += sn.normal[d] * rel_ext[(2 * i + d, g)];
                        st_ext[(i, g)] += sn.tangent[d] * rel_ext[(2 * i + d, g)];
                    }
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
        let mut f_ext = Mat::<f64>::zeros(nrig, next);
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
                    for g in 0..next {
                        f_ext[(2 * j + d, g)] += w * body.x[(row, g)];
                    }
                    for (kk, &gp) in body.params.iter().enumerate() {
                        frow[(2 * j + d, gp)] += w * body.x[(row, next + kk)];
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

    /// Solves the load steps in order, continuing from the state left by earlier calls
    /// (use [`ContactProblem::reset`] to start again from the unloaded state).
    ///
    /// Errors: a step that misses or repeats a rigid segment, or names an unknown one, or a
    /// non-finite load, or names an unknown load group or one twice
    /// ([`Error::InvalidParameter`]); a free rigid-body mode that neither contact nor
    /// friction holds ([`Error::InvalidParameter`] naming the body and the mode); a free
    /// body whose loads do not press it onto a contact ([`Error::NoContact`]); [`Error::NotConverged`] with the
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

    /// The rigid controls of a step and its load factors per load-group column.
    fn controls(&self, k: usize, step: &LoadStep) -> Result<(Vec<Control>, Vec<f64>)> {
        let field = format!("load_step[{k}]");
        if !step.external.is_finite() {
            return Err(Error::invalid(
                format!("{field}.external"),
                step.external,
                "must be finite",
            ));
        }
        let mut lamv = vec![0.0; self.next()];
        lamv[0] = step.external;
        let mut seen = vec![false; self.groups.len()];
        for (name, f) in &step.groups {
            let g = self.groups.iter().position(|x| x == name).ok_or_else(|| {
                Error::invalid(
                    format!("{field}.groups"),
                    name,
                    format!(
                        "names no load group of the boundary conditions (groups: [{}])",
                        self.groups.join(", ")
                    ),
                )
            })?;
            if seen[g] {
                return Err(Error::invalid(
                    format!("{field}.groups"),
                    name,
                    "is given twice in the step",
                ));
            }
            if !f.is_finite() {
                return Err(Error::invalid(
                    format!("{field}.groups '{name}'"),
                    f,
                    "the factor must be finite",
                ));
            }
            seen[g] = true;
            lamv[1 + g] = *f;
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
        let ctl = ctl
            .into_iter()
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
            .collect::<Result<Vec<_>>>()?;
        Ok((ctl, lamv))
    }

    /// A combination of free-mode amplitudes (unit vector over all free bodies' amplitudes)
    /// that the contact rows of the current sets do not hold, if any: the eigenvector of the
    /// smallest eigenvalue of M^T M, M = the amplitude columns of the gap rows of the nodes in
    /// contact and of the stick rows (f > 0), where its singular value is below 1e-8 (the
    /// entries are dimensionless, O(1): a translation moves every node by its amplitude).
    fn unheld_mode(&self, states: &[ContactState], fric: &[f64]) -> Option<Vec<f64>> {
        let first = self.free.first()?;
        let c0 = first.zcol;
        let nz = self.pz.ncols();
        let m = nz - c0;
        let mut gram = vec![vec![0.0; m]; m];
        let mut add = |row: &dyn Fn(usize) -> f64| {
            for a in 0..m {
                let ra = row(c0 + a);
                if ra == 0.0 {
                    continue;
                }
                for b in 0..m {
                    gram[a][b] += ra * row(c0 + b);
                }
            }
        };
        for (i, st) in states.iter().enumerate() {
            if matches!(st, ContactState::Open | ContactState::Outside) {
                continue;
            }
            add(&|c| self.wn[(i, c)]);
            if fric[i] > 0.0 && *st == ContactState::Stick {
                add(&|c| self.wt[(i, c)]);
            }
        }
        let (vals, vecs) = symmetric_eigen(gram);
        let k = (0..m).min_by(|&a, &b| vals[a].total_cmp(&vals[b]))?;
        // Relative to the largest eigenvalue: the smallest of a rank-deficient Gram matrix
        // is round-off of the largest, whose scale is that of the weights (an absolute
        // threshold took a mode held by one node's normal and tangential rows together
        // with another as held, or not, by the rounding of the geometry).
        let largest = vals.iter().cloned().fold(0.0_f64, nan_max);
        if largest.is_nan() || largest <= 0.0 || vals[k].max(0.0).sqrt() < 1e-7 * largest.sqrt() {
            Some((0..m).map(|i| vecs[i][k]).collect())
        } else {
            None
        }
    }

    /// The free body and rigid motion that dominate amplitude combination `v`.
    fn name_mode(&self, v: &[f64]) -> (&FreeBody, String) {
        let c0 = self.free[0].zcol;
        let mut best = (0.0, 0);
        for (f, fb) in self.free.iter().enumerate() {
            let a = fb.zcol - c0;
            let w: f64 = (0..fb.modes.len()).map(|k| v[a + k] * v[a + k]).sum();
            if w > best.0 {
                best = (w, f);
            }
        }
        let fb = &self.free[best.1];
        let a = fb.zcol - c0;
        let mut mode = [0.0; 3];
        for (k, m) in fb.modes.iter().enumerate() {
            for c in 0..3 {
                mode[c] += v[a + k] * m[c];
            }
        }
        let c = to_global(&self.problem.mesh, fb.center);
        (fb, describe_mode(mode, c, fb.size))
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
        let (ctl, lamv) = self.controls(k, step)?;
        let n = self.n;
        let nz = self.pz.ncols();
        let nrig = 2 * self.rigid.len();
        let next = self.next();
        let ext = |m: &Mat<f64>, i: usize| -> f64 { (0..next).map(|g| lamv[g] * m[(i, g)]).sum() };
        let gl: Vec<f64> = (0..n).map(|i| ext(&self.gn_ext, i)).collect();
        let sl: Vec<f64> = (0..n).map(|i| ext(&self.st_ext, i)).collect();
        let fric = self.friction_of();
        // The step's load scale (Pa): prescribed tractions, displacements and rigid controls.
        let mut load_scale = (0..next)
            .map(|g| lamv[g].abs() * self.group_load[g])
            .fold(0.0_f64, f64::max);
        for c in &ctl {
            load_scale = load_scale.max(match *c {
                Control::Force(f) => f.abs() / self.length,
                Control::Displacement(u) => self.scale * u.abs() / self.length,
            });
        }
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
                let (mut a, mut b) = (g0[i] + gl[i], sl[i]);
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
            // A body held only by contact: while the sets leave one of its free modes unheld,
            // bring the open node that would hold it with the smallest gap into contact. If
            // none can, the mode is held by neither contact nor friction: a clear error.
            if !self.free.is_empty() {
                let mut checked = false;
                while let Some(v) = self.unheld_mode(&states, &fric) {
                    let c0 = self.free[0].zcol;
                    let (g, _) = evaluate(&z);
                    let weight = |i: usize, w: &Mat<f64>| -> f64 {
                        (0..v.len()).map(|a| w[(i, c0 + a)] * v[a]).sum::<f64>()
                    };
                    if !checked && iterations > 1 {
                        // The last solve left no contact node of the body with a pressure
                        // above round-off of the step's loads: its loads do not press it onto
                        // a contact (or vanish).
                        let (fb, _) = self.name_mode(&v);
                        let touching = (0..n).any(|i| {
                            !matches!(states[i], ContactState::Open | ContactState::Outside)
                                && load_scale > 0.0
                                && z[i] > 1e-9 * load_scale
                                && (0..fb.modes.len())
                                    .any(|a| self.wn[(i, fb.zcol + a)].abs() > 1e-6)
                        });
                        if !touching {
                            let (fb, mode) = self.name_mode(&v);
                            return Err(Error::NoContact {
                                detail: format!(
                                    "load step {k}: {} is held only by contact and friction \
                                     (free rigid-body {mode}), but its loads do not press it \
                                     onto a contact: every contact node opens",
                                    fb.field
                                ),
                            });
                        }
                    }
                    checked = true;
                    let mut best: Option<(f64, usize)> = None;
                    for i in 0..n {
                        if states[i] != ContactState::Open {
                            continue;
                        }
                        let hold = weight(i, &self.wn).abs().max(if fric[i] > 0.0 {
                            weight(i, &self.wt).abs()
                        } else {
                            0.0
                        });
                        if hold > 1e-6 && best.is_none_or(|b| g[i] < b.0) {
                            best = Some((g[i], i));
                        }
                    }
                    match best {
                        Some((_, i)) => states[i] = ContactState::Stick,
                        None => {
                            let (fb, mode) = self.name_mode(&v);
                            return Err(Error::invalid(
                                fb.field.clone(),
                                format!("free rigid-body {mode}"),
                                format!(
                                    "in load step {k} neither contact nor friction holds this \
                                     mode of a body held only by contact (a frictionless contact \
                                     holds no tangential motion; with friction, every contact \
                                     node slips: the tangential load reaches the friction limit): \
                                     add friction, a symmetry or displacement condition, or a \
                                     rigid segment, or reduce the tangential load"
                                ),
                            ));
                        }
                    }
                }
            }
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
                        rhs[i] = -(g0[i] + gl[i]);
                        if fric[i] == 0.0 {
                            a[(n + i, n + i)] = 1.0;
                        } else if st == ContactState::Stick {
                            for c in 0..nz {
                                a[(n + i, c)] = self.wt[(i, c)];
                            }
                            rhs[n + i] = self.slip[i] - sl[i];
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
                        rhs[row] = f - ext(&self.f_ext, j);
                    }
                    Control::Displacement(u) => {
                        a[(row, row)] = 1.0;
                        rhs[row] = u;
                    }
                }
            }
            // Free-body equilibrium in every free mode.
            for q in 0..self.eq_z.nrows() {
                let row = 2 * n + nrig + q;
                for cc in 0..nz {
                    a[(row, cc)] = self.eq_z[(q, cc)];
                }
                rhs[row] = -ext(&self.eq_ext, q);
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
                rn = nan_max(rn, chk[(r, 0)].abs());
                yn = nan_max(yn, y[(r, 0)].abs());
            }
            if bad || rn.is_nan() || rn > 1e-8 * (yn + 1.0) {
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
            if let Some(fb) = self
                .free
                .iter()
                .find(|fb| (0..fb.modes.len()).any(|k| z[fb.zcol + k].abs() > self.length))
            {
                return Err(Error::Numerical {
                    context: "2D BEM contact step",
                    detail: format!(
                        "load step {k}: {} (held only by contact) moves more than the model \
                         size: a free rigid-body mode is held by neither contact nor friction",
                        fb.field
                    ),
                });
            }
            if let Some(j) = (0..nrig).find(|&j| z[2 * n + j].abs() > self.length) {
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
            let pmax = (0..n).map(|i| z[i]).fold(0.0_f64, nan_max);
            for i in 0..n {
                if states[i] == ContactState::Outside {
                    continue;
                }
                let (p, q) = (z[i], z[n + i]);
                let ds = s[i] - self.slip[i];
                let pn = p - cn[i] * g[i];
                let qt = q - ct[i] * ds;
                let bound = fric[i] * pn.max(0.0);
                let r = if pn.is_nan() || qt.is_nan() || bound.is_nan() {
                    f64::NAN
                } else {
                    (p - pn.max(0.0))
                        .abs()
                        .max((q - qt.clamp(-bound, bound)).abs())
                };
                rmax = nan_max(rmax, r);
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
            residual = rmax / nan_max(pmax, f64::MIN_POSITIVE);
            if pmax == 0.0 {
                residual = rmax;
            }
            if !residual.is_finite() {
                return Err(Error::Numerical {
                    context: "2D BEM contact step",
                    detail: format!(
                        "load step {k}, iteration {iterations}: the complementarity residual is \
                         {residual} (a non-finite contact pressure, shear, gap or slip)"
                    ),
                });
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
                                    "contact pair '{}' / '{}': the contact reaches an end of \
                                     the master segment; extend the master segment, or, where \
                                     the master ends at a corner of its body (a punch edge), \
                                     end the slave segment at the same place",
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
                let mut f = ext(&self.f_ext, 2 * j + d);
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
        let (solution, pin_traction) = self.boundary_state(&lamv, &z);
        let free_bodies = self.free_results(&solution, &lamv, &pin_traction);
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
            free_bodies,
            solution,
        })
    }

    /// The least-squares rigid motion of each free body's boundary displacement and its
    /// support reactions.
    fn free_results(
        &self,
        solution: &BemSolution,
        lamv: &[f64],
        pin_traction: &[Vec<f64>],
    ) -> Vec<FreeBodyResult> {
        let mesh = &self.problem.mesh;
        let (gx, gw) = gauss_legendre(8);
        let mut out = Vec::new();
        for (f, fb) in self.free.iter().enumerate() {
            let c = fb.center;
            let (mut len, mut ru2, mut rxu) = (0.0, 0.0, 0.0);
            let mut um = [0.0; 2];
            for &r in &fb.regions {
                for e in &mesh.regions[r].local_elements {
                    if mesh.segments[e.segment].partner.is_some() {
                        continue;
                    }
                    for (&xi, &w) in gx.iter().zip(&gw) {
                        let x = e.point(xi);
                        let (_, jac) = e.normal_jacobian(xi);
                        let nsh = e.field_shape(xi);
                        let mut u = [0.0; 2];
                        for a in 0..3 {
                            for d in 0..2 {
                                u[d] += nsh[a] * solution.displacement[r][e.nodes[a]][d];
                            }
                        }
                        let ds = w * jac;
                        let rv = [x[0] - c[0], x[1] - c[1]];
                        len += ds;
                        um[0] += u[0] * ds;
                        um[1] += u[1] * ds;
                        ru2 += (rv[0] * rv[0] + rv[1] * rv[1]) * ds;
                        rxu += (rv[0] * u[1] - rv[1] * u[0]) * ds;
                    }
                }
            }
            let mut support = [0.0; 2];
            for (q, pin) in fb.pins.iter().enumerate() {
                support[pin.d] += pin.weight * (pin_traction[f][q] - lamv[pin.group] * pin.t);
            }
            out.push(FreeBodyResult {
                body: fb.name.clone(),
                translation: [um[0] / len, um[1] / len],
                rotation: rxu / ru2.max(f64::MIN_POSITIVE),
                reference_point: to_global(mesh, c),
                free_modes: fb
                    .modes
                    .iter()
                    .map(|m| describe_mode(*m, to_global(mesh, fb.center), fb.size))
                    .collect(),
                support_force: support,
            });
        }
        out
    }

    /// The full boundary state for load factors `lamv` (per load-group column) and contact
    /// unknowns `z`, and the BEM traction at every pin (per free body, per pin). Pins report
    /// their prescribed traction in the state (see the module docs).
    fn boundary_state(&self, lamv: &[f64], z: &[f64]) -> (BemSolution, Vec<Vec<f64>>) {
        let next = self.next();
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
                let mut v = 0.0;
                for g in 0..next {
                    v += lamv[g] * body.x[(li, g)];
                }
                for (k, &gp) in body.params.iter().enumerate() {
                    v += body.x[(li, next + k)] * param[gp];
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
                Param::Free { .. } => {}
            }
        }
        let mut pin_traction = Vec::with_capacity(self.free.len());
        for fb in &self.free {
            let mut tp = Vec::with_capacity(fb.pins.len());
            for pin in &fb.pins {
                let u: f64 = (0..fb.modes.len())
                    .map(|k| pin.row[k] * param[fb.param0 + k])
                    .sum();
                over_u.insert((pin.region, pin.node, pin.d), u);
                over_t.insert((pin.region, pin.node, pin.d), lamv[pin.group] * pin.t);
                if let Dof::T { col, .. } = self.dofs[pin.region][pin.node][pin.d] {
                    tp.push(x[col] * self.scale);
                } else {
                    tp.push(0.0);
                }
            }
            pin_traction.push(tp);
        }
        let mut displacement = Vec::new();
        let mut traction = Vec::new();
        for (r, d) in self.dofs.iter().enumerate() {
            let mut u = Vec::with_capacity(d.len());
            let mut t = Vec::with_capacity(d.len());
            for (node, dn) in d.iter().enumerate() {
                let mut un = [0.0; 2];
                let mut tn = [0.0; 2];
                let lam = lamv[self.seg_group[self_segment(&self.problem, r, node)]];
                for dir in 0..2 {
                    match dn[dir] {
                        Dof::U { col, t } => {
                            un[dir] = x[col];
                            tn[dir] = over_t.get(&(r, node, dir)).copied().unwrap_or(lam * t);
                        }
                        Dof::T { col, u } => {
                            un[dir] = over_u.get(&(r, node, dir)).copied().unwrap_or(lam * u);
                            tn[dir] = over_t
                                .get(&(r, node, dir))
                                .copied()
                                .unwrap_or(x[col] * self.scale);
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
        (
            BemSolution {
                mesh: self.problem.mesh.clone(),
                displacement,
                traction,
                residual: self.lu_residual,
                body_force_factor: lamv[0],
            },
            pin_traction,
        )
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

/// The displacement of node component d at `p` per unit amplitude of the rigid modes
/// (translation x, translation y, rotation about `c` scaled by `size`: amplitude = size *
/// angle, so that all three are lengths).
fn rigid_row(d: usize, p: [f64; 2], c: [f64; 2], size: f64) -> [f64; 3] {
    if d == 0 {
        [1.0, 0.0, -(p[1] - c[1]) / size]
    } else {
        [0.0, 1.0, (p[0] - c[0]) / size]
    }
}

/// A model-local point (relative to [`BemMesh::origin`](crate::operators::bem2d::BemMesh))
/// in global coordinates, m.
fn to_global(mesh: &crate::operators::bem2d::BemMesh, x: [f64; 2]) -> [f64; 2] {
    [x[0] + mesh.origin[0], x[1] + mesh.origin[1]]
}

fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Eigenvalues and eigenvectors (columns: `v[i][k]` is component i of vector k) of a small
/// symmetric matrix by the cyclic Jacobi method (Golub & Van Loan, *Matrix Computations*,
/// 4th ed., alg. 8.5.3).
fn symmetric_eigen(mut a: Vec<Vec<f64>>) -> (Vec<f64>, Vec<Vec<f64>>) {
    let m = a.len();
    let mut v: Vec<Vec<f64>> = (0..m)
        .map(|i| (0..m).map(|j| if i == j { 1.0 } else { 0.0 }).collect())
        .collect();
    let norm: f64 = a.iter().flatten().map(|x| x * x).sum::<f64>().sqrt();
    for _ in 0..60 {
        let off: f64 = (0..m)
            .flat_map(|i| (0..m).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[i][j] * a[i][j])
            .sum::<f64>()
            .sqrt();
        if off <= 1e-15 * norm || off == 0.0 {
            break;
        }
        for p in 0..m {
            for q in p + 1..m {
                if a[p][q] == 0.0 {
                    continue;
                }
                let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for k in 0..m {
                    let (akp, akq) = (a[k][p], a[k][q]);
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for k in 0..m {
                    let (apk, aqk) = (a[p][k], a[q][k]);
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
                for k in 0..m {
                    let (vkp, vkq) = (v[k][p], v[k][q]);
                    v[k][p] = c * vkp - s * vkq;
                    v[k][q] = s * vkp + c * vkq;
                }
            }
        }
    }
    ((0..m).map(|i| a[i][i]).collect(), v)
}

/// The rigid modes (tx, ty, size * rotation about `c`) that the prescribed displacement
/// components `rows` (direction, position) leave free: an orthonormal basis of the null space
/// of the constraint matrix (eigenvalues of its Gram matrix below 1e-12 per row, i.e. the
/// 1e-6 of the BEM restraint check), built from the projections of tx, ty and the rotation in
/// turn (largest first), so that a single free translation or rotation comes out as itself.
fn free_modes(rows: &[(usize, [f64; 2])], c: [f64; 2], size: f64) -> Vec<[f64; 3]> {
    let mut gram = vec![vec![0.0; 3]; 3];
    for (d, p) in rows {
        let r = rigid_row(*d, *p, c, size);
        for i in 0..3 {
            for j in 0..3 {
                gram[i][j] += r[i] * r[j];
            }
        }
    }
    let (vals, vecs) = symmetric_eigen(gram);
    let tol = 1e-12 * rows.len().max(1) as f64;
    let null: Vec<[f64; 3]> = (0..3)
        .filter(|&k| vals[k] <= tol)
        .map(|k| [vecs[0][k], vecs[1][k], vecs[2][k]])
        .collect();
    let mut basis: Vec<[f64; 3]> = Vec::new();
    for _ in 0..null.len() {
        let mut best = (0.0, [0.0; 3]);
        for e in 0..3 {
            let mut w = [0.0; 3];
            for nv in &null {
                for i in 0..3 {
                    w[i] += nv[e] * nv[i];
                }
            }
            for b in &basis {
                let d = dot3(w, *b);
                for i in 0..3 {
                    w[i] -= d * b[i];
                }
            }
            let nw = dot3(w, w).sqrt();
            if nw > best.0 + 1e-12 {
                best = (nw, w.map(|x| x / nw));
            }
        }
        basis.push(best.1);
    }
    basis
}

/// A rigid motion (tx, ty, size * rotation about `c`) in words.
fn describe_mode(mode: [f64; 3], c: [f64; 2], size: f64) -> String {
    let nrm = dot3(mode, mode).sqrt().max(f64::MIN_POSITIVE);
    let [a, b, r] = mode.map(|x| x / nrm);
    if r.abs() < 1e-6 {
        if b.abs() < 1e-6 {
            "translation in x".to_string()
        } else if a.abs() < 1e-6 {
            "translation in y".to_string()
        } else {
            let h = a.hypot(b);
            format!("translation along ({:.4}, {:.4})", a / h, b / h)
        }
    } else {
        // u = (a - theta (y - cy), b + theta (x - cx)) vanishes at the centre.
        let theta = r / size;
        format!(
            "rotation about ({:.6e}, {:.6e}) m",
            c[0] - b / theta,
            c[1] + a / theta
        )
    }
}

/// Arc-length centroid of a body's boundary (its regions' elements off bonded interfaces)
/// and the largest distance of a boundary point from it, m.
fn boundary_centroid(problem: &BemProblem, members: &[usize]) -> ([f64; 2], f64) {
    let mesh = &problem.mesh;
    let (gx, gw) = gauss_legendre(8);
    let (mut len, mut sx, mut sy) = (0.0, 0.0, 0.0);
    for &r in members {
        for e in &mesh.regions[r].local_elements {
            if mesh.segments[e.segment].partner.is_some() {
                continue;
            }
            for (&xi, &w) in gx.iter().zip(&gw) {
                let x = e.point(xi);
                let (_, jac) = e.normal_jacobian(xi);
                len += w * jac;
                sx += w * jac * x[0];
                sy += w * jac * x[1];
            }
        }
    }
    let c = [sx / len, sy / len];
    let mut size = 0.0_f64;
    for &r in members {
        for e in &mesh.regions[r].local_elements {
            for g in &e.geometry {
                size = size.max((g[0] - c[0]).hypot(g[1] - c[1]));
            }
        }
    }
    (c, size.max(f64::MIN_POSITIVE))
}

/// int N ds of node `o` of region `r` (over the elements that hold it), m.
fn node_weight(problem: &BemProblem, r: usize, o: usize) -> f64 {
    let (gx, gw) = gauss_legendre(8);
    let mut w = 0.0;
    for e in &problem.mesh.regions[r].local_elements {
        if let Some(a) = e.nodes.iter().position(|&q| q == o) {
            for (&xi, &wq) in gx.iter().zip(&gw) {
                let (_, jac) = e.normal_jacobian(xi);
                w += wq * jac * e.field_shape(xi)[a];
            }
        }
    }
    w
}

/// The free rigid-body modes of a body that takes part in a contact pair, and its artificial
/// supports: for each free mode one traction-type node component off the contact and rigid
/// segments, chosen by pivoting (the component whose rigid-mode row has the largest part
/// orthogonal to the rows chosen before; among near ties, the one farthest from the contact),
/// so that the supports are statically determinate and far apart. The chosen components
/// become displacement unknowns-as-parameters in `dofs`. None where the body is restrained.
fn free_body(
    problem: &BemProblem,
    dofs: &mut [Vec<[Dof; 2]>],
    members: &[usize],
    role: &HashMap<usize, String>,
    seg_group: &[usize],
) -> Result<Option<FreeBody>> {
    let mesh = &problem.mesh;
    let (center, size) = boundary_centroid(problem, members);
    let mut rows = Vec::new();
    for &r in members {
        for (x, d) in mesh.regions[r].local_positions.iter().zip(&dofs[r]) {
            for (dir, dof) in d.iter().enumerate() {
                if matches!(dof, Dof::T { .. }) {
                    rows.push((dir, *x));
                }
            }
        }
    }
    let modes = free_modes(&rows, center, size);
    if modes.is_empty() {
        return Ok(None);
    }
    let names: Vec<&str> = members
        .iter()
        .map(|&r| mesh.regions[r].name.as_str())
        .collect();
    let field = format!("body [{}]", names.join(", "));
    let contact: Vec<[f64; 2]> = members
        .iter()
        .flat_map(|&r| {
            let region = &mesh.regions[r];
            region.nodes.iter().zip(&region.local_positions)
        })
        .filter(|(n, _)| role.contains_key(&n.segment))
        .map(|(_, x)| *x)
        .collect();
    let mut cand: Vec<(usize, usize, usize, Vec<f64>, f64)> = Vec::new();
    for &r in members {
        for (o, node) in mesh.regions[r].nodes.iter().enumerate() {
            if role.contains_key(&node.segment) || mesh.segments[node.segment].partner.is_some() {
                continue;
            }
            for d in 0..2 {
                if let Dof::U { .. } = dofs[r][o][d] {
                    let x = mesh.regions[r].local_positions[o];
                    let rr = rigid_row(d, x, center, size);
                    let row: Vec<f64> = modes.iter().map(|m| dot3(rr, *m)).collect();
                    let far = contact
                        .iter()
                        .map(|p| (p[0] - x[0]).hypot(p[1] - x[1]))
                        .fold(f64::INFINITY, f64::min);
                    cand.push((r, o, d, row, far));
                }
            }
        }
    }
    let mut basis: Vec<Vec<f64>> = Vec::new();
    let mut pins = Vec::new();
    for step in 0..modes.len() {
        let resid: Vec<Vec<f64>> = cand
            .iter()
            .map(|c| {
                let mut v = c.3.clone();
                for b in &basis {
                    let dt: f64 = v.iter().zip(b).map(|(x, y)| x * y).sum();
                    v.iter_mut().zip(b).for_each(|(x, y)| *x -= dt * y);
                }
                v
            })
            .collect();
        let norms: Vec<f64> = resid
            .iter()
            .map(|v| v.iter().map(|x| x * x).sum::<f64>().sqrt())
            .collect();
        let best = norms.iter().cloned().fold(0.0_f64, f64::max);
        if best < 1e-6 {
            return Err(Error::invalid(
                field,
                format!(
                    "free rigid-body {}",
                    describe_mode(
                        modes[step.min(modes.len() - 1)],
                        to_global(mesh, center),
                        size
                    )
                ),
                "the body is held only by contact, and it has no traction-loaded boundary node off \
                 its contact segments to carry the artificial support of this mode",
            ));
        }
        let mut pick = usize::MAX;
        for i in 0..cand.len() {
            if norms[i] >= 0.999 * best && (pick == usize::MAX || cand[i].4 > cand[pick].4) {
                pick = i;
            }
        }
        basis.push(resid[pick].iter().map(|x| x / norms[pick]).collect());
        let (r, o, d, row, _) = cand.swap_remove(pick);
        let (col, t) = match dofs[r][o][d] {
            Dof::U { col, t } => (col, t),
            _ => unreachable!("candidates are traction-type"),
        };
        dofs[r][o][d] = Dof::T { col, u: 0.0 };
        pins.push(Pin {
            region: r,
            node: o,
            d,
            t,
            group: seg_group[mesh.regions[r].nodes[o].segment],
            row,
            weight: node_weight(problem, r, o),
        });
    }
    Ok(Some(FreeBody {
        name: mesh.regions[members[0]].name.clone(),
        field,
        regions: members.to_vec(),
        center,
        size,
        modes,
        zcol: 0,
        param0: 0,
        pins,
    }))
}

pub(crate) mod reference;

#[cfg(test)]
mod tests;
