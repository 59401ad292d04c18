//! Dynamic frictional contact of 2D boundary element bodies by time marching on the
//! condensed contact compliance (issue 13 item 2; docs/theory/DYNAMICS.md sec. 4 and 5.4).
//!
//! # Condensation
//!
//! The bodies are linear; only the contact is not. With zero initial conditions (plus a
//! rigid initial velocity per body, below) the contact-node displacements are, in the
//! Laplace domain,
//!
//! ```text
//! u_c(s) = C(s) z(s) + E(s) f(s)
//! ```
//!
//! with `z = (p_i, q_i)` the contact pressure and shear at the slave nodes (the node-to-
//! segment pairs of [`crate::solvers::bem2d::contact`]: slave traction `p n + q tau`, master
//! traction its L2 transfer), `C(s)` the condensed compliance of both bodies (the
//! [`LaplaceBem`] with the contact DOFs as traction inputs, one assembly and LU per
//! frequency for all columns, [`LaplaceBem::respond_columns`]) and `E(s) f(s)` the response
//! to the prescribed loads (the boundary conditions' values times their time functions) with
//! the contact free. The outputs per slave node are the relative displacement (slave minus
//! master at the foot point) along n and tau, i.e. `g - g0` and the slip `s`, and the slave
//! displacement along n and tau (for the work of each body); per load column the
//! work-conjugate displacements (below).
//!
//! Convolution quadrature (Lubich 1988) of the whole map `[C E]` with the weights `W_j`
//! ([`cq_weights`], BDF1 or BDF2) gives at step n (t_n = n dt)
//!
//! ```text
//! u_c^n = W_0 [z^n; f^n] + sum_(j=1..n) W_j [z^(n-j); f^(n-j)]
//! ```
//!
//! (the history by [`CqHistory`], never truncated: 2D has no Huygens principle). The loads
//! go through the same weights as the contact tractions, so the marching is one consistent
//! CQ discretisation of the linear bodies. Each step is then a static-like contact problem
//! with the instantaneous compliance `W_0 = C(gamma(0)/dt)` (BDF2: `s0 = 1.5/dt`; real,
//! since the system is real and `s0` is real; to the contour's aliasing error) and the
//! known right-hand side, solved by the static solver's primal-dual active set method
//! (normal complementarity on the gap; Coulomb on the slip increment over the step, exact
//! stick; [`crate::solvers::bem2d::contact`], "Solver"). Unlike the static problem, `W_0` is
//! regular for bodies held only by contact: inertia holds them.
//!
//! Radau IIA (2 or 3 stages) marches the stage values instead: each step one block contact
//! problem for the S stage tractions (module `radau`, docs/theory/DYNAMICS.md sec. 5.10).
//!
//! # Rigid initial velocity
//!
//! A body moving with the uniform velocity v0 carries no stress (`u = v0 t` solves the
//! Navier equations with zero traction), so the motion is `v0 t` plus the elastic response
//! to the contact and the loads with zero initial conditions: the gap closes by
//! `(v_slave - v_master) . n t` and the slip grows by `(v_slave - v_master) . tau t`. A body
//! with an initial velocity may not have prescribed displacements.
//!
//! # Energy
//!
//! From boundary data (J/m, per unit thickness), each step by the discrete work:
//! - external work of the loads: per load column (the loads of one time function in one
//!   body) the work-conjugate displacements `y_u = sum_k w_k t_k u_k` over its prescribed
//!   tractions and `y_t = sum_k w_k u_k t_k` over its prescribed displacements
//!   (`w_k = int N_k ds`), `dW = f_mid dy_u + y_t,mid df` (trapezoidal);
//! - contact work on each body, with the step's tractions (backward): slave
//!   `sum_i w_i (p_i d(u_s . n) + q_i d(u_s . tau))`, master `-sum_i w_i (p_i d(u_m . n) +
//!   q_i d(u_m . tau))` (the transferred traction carries the slave force);
//! - frictional dissipation `D = -sum_i w_i q_i ds_i >= 0` (the discrete Coulomb law makes
//!   every term non-negative) and the normal contact work `W_N = sum_i w_i p_i dg_i <= 0`
//!   (zero in the continuous problem, where `p g = 0` for all t: the energy the time
//!   discretisation loses when a node closes);
//! - the mechanical energy `E = U + K = K_0 + W_ext + W_N - D` and per body `E_b` (the
//!   elastic and kinetic energies are not separable from boundary data);
//! - for a body without prescribed displacements the momentum `P_b = m v0 + int F dt`
//!   (contact and load resultants, trapezoidal) and the kinetic energy of its mean
//!   (translational) motion `|P_b|^2 / (2 m)`; `E_b` minus it is the energy left in
//!   vibration (and rotation): after an impact of identical rods exactly 0, so that a
//!   spurious contact oscillation shows there (docs/theory/DYNAMICS.md sec. 4).
//!
//! # Cost
//!
//! The weights: `L/2 + 1` Laplace-domain assemblies and LU solves (`L ~ M + 1` frequencies
//! for M steps), each with `2 n_c + n_loads` right-hand sides; memory `(L/2+1 + M + 1)
//! rows cols` values ([`DynamicContact::memory_estimate`], checked before allocating). The
//! history: `O(rows cols M^2 / 2)` multiply-adds (`rows = 4 n_c + 2 n_loads`,
//! `cols = 2 n_c + n_loads`). A step: a few dense LU of size `2 n_c`.

// Index loops over the two directions read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

mod compliance;
mod radau;
mod radau_step;
pub(crate) mod reference;
pub use radau::SampledMarch;
pub use reference::two_rods;
mod rigid;
pub use rigid::{DynamicRigid, DynamicRigidState};
mod step;

#[cfg(test)]
mod radau_tests;
#[cfg(test)]
mod rigid_tests;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod verify_impact;

use std::collections::HashMap;

use crate::dynamics::cq::{cq_weights, weights_memory_estimate, CqHistory, CqMethod, CqParams};
use crate::dynamics::history::{ContactSample, EnergySample};
use crate::dynamics::laplace::LaplaceBem;
use crate::dynamics::time_function::TimeFunction;
use crate::error::{Error, Result};
use crate::operators::bem2d::BemModel;
use crate::solvers::bem2d::contact::{pair_geometries, ContactOptions, ContactPair, ContactState};
use crate::solvers::bem2d::{region_bodies, BoundaryConditions};

use compliance::{
    contact_maps, node_weights, region_area, Combination, ContactCompliance, LoadColumn, NodeData,
};
use step::StepProblem;

/// The time function of the boundary condition of one segment (the condition's values are
/// multiplied by it).
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicLoad {
    /// Segment name (it has a boundary condition).
    pub segment: String,
    /// Its time function.
    pub time: TimeFunction,
}

/// The time discretisation and solver settings of a march.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicContactParams {
    /// CQ method: [`CqMethod::Bdf1`], [`CqMethod::Bdf2`] or Radau IIA (each step an S-stage
    /// block contact problem: [`DynamicContact::march_samples`]).
    pub method: CqMethod,
    /// Time step, s (> 0).
    pub dt: f64,
    /// Number of steps M (the march computes t_n = n dt, n = 0..=M).
    pub steps: usize,
    /// Contour parameters of the weights.
    pub cq: CqParams,
    /// Active-set settings of each step.
    pub options: ContactOptions,
    /// Largest allocation allowed for the weights and the history, bytes (None: no limit
    /// beyond the machine's).
    pub memory_limit: Option<usize>,
}

impl DynamicContactParams {
    /// BDF2 with time step `dt` (s) over `steps` steps, default contour and solver settings.
    pub fn new(dt: f64, steps: usize) -> Self {
        Self {
            method: CqMethod::Bdf2,
            dt,
            steps,
            cq: CqParams::default(),
            options: ContactOptions::default(),
            memory_limit: None,
        }
    }

    /// The same with another method.
    pub fn with_method(mut self, method: CqMethod) -> Self {
        self.method = method;
        self
    }
}

/// One slave node at one step.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct DynamicContactNode {
    /// Position (initial configuration), m.
    pub position: [f64; 2],
    /// Contact pressure, Pa.
    pub pressure: f64,
    /// Tangential traction on the slave along tau, Pa.
    pub shear: f64,
    /// Gap along the master normal, m (rigid motion included).
    pub gap: f64,
    /// Total relative tangential displacement (slave minus master) along tau, m.
    pub slip: f64,
    /// State.
    pub state: ContactState,
}

/// One contact pair at one step.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicPairState {
    /// The slave nodes that project onto the master (in the slave segment's direction).
    pub nodes: Vec<DynamicContactNode>,
    /// Resultant of the contact traction on the slave, N/m (the master receives the
    /// opposite).
    pub force: [f64; 2],
    /// Contact length, normal and tangential force, stick and slip extents (the extents
    /// are sums of the nodes' weights int N ds; frictionless contact counts as slip).
    pub sample: ContactSample,
}

/// The energy of one body (J/m).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct BodyEnergy {
    /// Mechanical energy (strain + kinetic) from the boundary work, J/m.
    pub mechanical: f64,
    /// Momentum per unit thickness, N s/m (None for a body with prescribed displacements).
    pub momentum: Option<[f64; 2]>,
    /// Kinetic energy of the mean translation `|P|^2 / (2 m)`, J/m (None as `momentum`).
    pub translational_kinetic: Option<f64>,
}

/// The energy balance at one step (J/m; module docs, "Energy").
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct DynamicContactEnergy {
    /// Kinetic energy of the initial rigid velocities.
    pub initial_kinetic: f64,
    /// Work of the prescribed loads since t = 0.
    pub external_work: f64,
    /// Work of the normal contact tractions on the gap (<= 0; 0 in the continuous problem).
    pub normal_contact_work: f64,
    /// Frictional dissipation since t = 0 (>= 0).
    pub dissipation: f64,
    /// Mechanical energy (strain + kinetic) of all bodies.
    pub mechanical: f64,
    /// Per body (in the order of [`DynamicContact::body_regions`]).
    pub bodies: Vec<BodyEnergy>,
}

/// The state after one step.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicContactStep {
    /// Step index n.
    pub step: usize,
    /// Time t_n = n dt, s.
    pub time: f64,
    /// Active-set iterations.
    pub iterations: usize,
    /// Complementarity residual (relative to the largest pressure).
    pub residual: f64,
    /// Per pair.
    pub pairs: Vec<DynamicPairState>,
    /// Per rigid segment (in the order given to [`DynamicContact::with_rigid`]).
    pub rigid: Vec<DynamicRigidState>,
    /// Energy balance.
    pub energy: DynamicContactEnergy,
}

impl DynamicContactStep {
    /// The samples of the pairs for [`crate::dynamics::history::StepRecord::contacts`].
    pub fn contact_samples(&self) -> Vec<ContactSample> {
        self.pairs.iter().map(|p| p.sample).collect()
    }

    /// The energies for [`crate::dynamics::history::StepRecord::energy`]: input work
    /// (initial kinetic energy plus the loads' work) and dissipation; strain and kinetic
    /// energy are `None` (only their sum, [`DynamicContactEnergy::mechanical`], follows from
    /// boundary data).
    pub fn energy_sample(&self) -> EnergySample {
        EnergySample {
            input_work: Some(self.energy.initial_kinetic + self.energy.external_work),
            strain_energy: None,
            kinetic_energy: None,
            dissipation: Some(self.energy.dissipation),
        }
    }
}

/// The result of a march.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicContactResult {
    /// Every step, n = 0..=M.
    pub steps: Vec<DynamicContactStep>,
    /// Largest active-set iteration count of a step.
    pub max_iterations: usize,
}

/// A dynamic contact problem: the Laplace-domain BEM of the bodies, the pairs' geometry,
/// the loads and the initial velocities, ready to march ([`DynamicContact::march`]).
#[derive(Debug, Clone)]
pub struct DynamicContact {
    compliance: ContactCompliance,
    nodes: Vec<NodeData>,
    npairs: usize,
    loads: Vec<TimeFunction>,
    load_columns: Vec<LoadColumn>,
    /// Regions of each body.
    bodies: Vec<Vec<usize>>,
    body_of: Vec<usize>,
    /// Per body: initial velocity (m/s), mass per unit thickness (kg/m), free (no
    /// prescribed displacement).
    velocity: Vec<[f64; 2]>,
    mass: Vec<f64>,
    free: Vec<bool>,
    /// Rigid segments and the conditions of the BEM (the rigid segments fixed).
    rigid: Vec<rigid::RigidData>,
    conditions: BoundaryConditions,
}

impl DynamicContact {
    /// The problem of `model` with mass densities `densities` (kg/m^3, per region),
    /// boundary conditions `bcs` (their values are the loads at factor 1; the contact
    /// segments must have none), contact `pairs` (slave, master, friction, as the static
    /// solver), the time functions of some segments' conditions `loads` (the conditions of
    /// the other segments are steps at t = 0: constant from t = 0 on) and a rigid initial
    /// velocity per region `velocities` (m/s; empty: all at rest; equal within a body).
    ///
    /// Errors ([`Error::InvalidParameter`] naming the item): as [`LaplaceBem::new`] and the
    /// pair checks of [`crate::solvers::bem2d::contact::ContactProblem::new`]; a load naming
    /// no segment with a boundary condition, or one segment twice; a velocity count that is
    /// not the region count, a velocity that is not finite, different velocities within a
    /// body, an initial velocity of a body with prescribed displacements.
    pub fn new(
        model: &BemModel,
        densities: &[f64],
        bcs: &BoundaryConditions,
        pairs: &[ContactPair],
        loads: &[DynamicLoad],
        velocities: &[[f64; 2]],
    ) -> Result<Self> {
        Self::with_rigid(model, densities, bcs, pairs, &[], loads, velocities)
    }

    /// [`DynamicContact::new`] with rigid (guided) segments `rigid` (module docs of
    /// `rigid.rs`, docs/theory/DYNAMICS.md sec. 5.4): each a displacement boundary of the
    /// BEM whose translation is an unknown (force control) or prescribed, both scaled by
    /// its time function. A body with a rigid segment counts as a body with prescribed
    /// displacements (no initial velocity, no momentum report). Errors as `new`, and
    /// ([`Error::InvalidParameter`] naming `rigid_segment[j]`) a rigid segment that names
    /// no segment, is a bonded interface, a contact segment or named twice, or has a
    /// boundary condition (the condition is then given twice), or a control that is not
    /// finite.
    pub fn with_rigid(
        model: &BemModel,
        densities: &[f64],
        bcs: &BoundaryConditions,
        pairs: &[ContactPair],
        rigid: &[DynamicRigid],
        loads: &[DynamicLoad],
        velocities: &[[f64; 2]],
    ) -> Result<Self> {
        let conditions = rigid::fixed_conditions(model, bcs, pairs, rigid)?;
        let bcs = &conditions;
        let bem = LaplaceBem::new(model, densities, bcs, &[])?;
        let problem = bem.static_problem();
        let mesh = &problem.mesh;
        let geometry = pair_geometries(problem, bcs, pairs)?;
        let (nodes, mut columns, mut rows) = contact_maps(&bem, &geometry)?;
        let nr = mesh.regions.len();
        // Bodies.
        let body_root = region_bodies(mesh);
        let mut roots: Vec<usize> = body_root.clone();
        roots.sort_unstable();
        roots.dedup();
        let body_of: Vec<usize> = body_root
            .iter()
            .map(|r| roots.binary_search(r).unwrap_or(0))
            .collect();
        let bodies: Vec<Vec<usize>> = (0..roots.len())
            .map(|b| (0..nr).filter(|&r| body_of[r] == b).collect())
            .collect();
        let mut free = vec![true; bodies.len()];
        for k in bem.known_dofs() {
            if k.displacement {
                free[body_of[k.region]] = false;
            }
        }
        // Velocities.
        if !velocities.is_empty() && velocities.len() != nr {
            return Err(Error::invalid(
                "initial_velocity",
                format!("{} values", velocities.len()),
                format!("must give one velocity per region ({nr}) or none"),
            ));
        }
        let mut velocity = vec![[0.0; 2]; bodies.len()];
        for (b, regions) in bodies.iter().enumerate() {
            for &r in regions {
                let v = velocities.get(r).copied().unwrap_or([0.0; 2]);
                let field = format!("initial_velocity of region '{}'", mesh.regions[r].name);
                if !(v[0].is_finite() && v[1].is_finite()) {
                    return Err(Error::invalid(
                        field,
                        format!("{v:?}"),
                        "must be finite (m/s)",
                    ));
                }
                if r != regions[0] && v != velocity[b] {
                    return Err(Error::invalid(
                        field,
                        format!("{v:?}"),
                        "regions bonded into one body must have the same initial velocity",
                    ));
                }
                velocity[b] = v;
            }
            if velocity[b] != [0.0; 2] && !free[b] {
                return Err(Error::invalid(
                    format!(
                        "initial_velocity of region '{}'",
                        mesh.regions[regions[0]].name
                    ),
                    format!("{:?}", velocity[b]),
                    "a body with prescribed displacements cannot have an initial velocity",
                ));
            }
        }
        let mass: Vec<f64> = bodies
            .iter()
            .map(|regions| {
                regions
                    .iter()
                    .map(|&r| densities[r] * region_area(&mesh.regions[r]))
                    .sum()
            })
            .collect();
        // Loads: the time function of every segment.
        let mut function_of: HashMap<usize, usize> = HashMap::new();
        for (j, l) in loads.iter().enumerate() {
            let field = format!("load[{j}].segment");
            let s = mesh.segment_index(&l.segment).ok_or_else(|| {
                Error::invalid(&field, &l.segment, "names no segment of the model")
            })?;
            if function_of.insert(s, j).is_some() {
                return Err(Error::invalid(field, &l.segment, "has two time functions"));
            }
        }
        let weights: Vec<Vec<f64>> = mesh.regions.iter().map(node_weights).collect();
        let mut load_columns: Vec<LoadColumn> = Vec::new();
        let mut key: HashMap<(usize, usize), usize> = HashMap::new();
        let mut used = vec![false; loads.len()];
        let mut work_u: Vec<Combination> = Vec::new();
        let mut work_t: Vec<Combination> = Vec::new();
        for (idx, (k, &v)) in bem
            .known_dofs()
            .iter()
            .zip(bem.static_known_values())
            .enumerate()
        {
            if v == 0.0 {
                continue;
            }
            let seg = mesh.regions[k.region].nodes[k.node].segment;
            let function = function_of.get(&seg).copied().unwrap_or(loads.len());
            if function < loads.len() {
                used[function] = true;
            }
            let body = body_of[k.region];
            let c = *key.entry((function, body)).or_insert_with(|| {
                load_columns.push(LoadColumn {
                    function,
                    body,
                    force: [0.0; 2],
                    rigid_rate: 0.0,
                });
                columns.push(Vec::new());
                work_u.push(Vec::new());
                work_t.push(Vec::new());
                load_columns.len() - 1
            });
            columns[2 * nodes.len() + c].push((idx, v));
            let w = weights[k.region][k.node];
            let out = bem
                .unknown_output(k.region, k.node, k.direction)
                .ok_or_else(|| Error::Numerical {
                    context: "dynamic contact",
                    detail: format!("no unknown for node {} of region {}", k.node, k.region),
                })?;
            if k.displacement {
                work_t[c].push((out, w * v));
            } else {
                work_u[c].push((out, w * v));
                load_columns[c].force[k.direction] += w * v;
                load_columns[c].rigid_rate += w * v * velocity[body][k.direction];
            }
        }
        if let Some(j) = used.iter().position(|u| !u) {
            return Err(Error::invalid(
                format!("load[{j}].segment"),
                &loads[j].segment,
                "the segment has no boundary condition with a non-zero value to scale",
            ));
        }
        for (u, t) in work_u.into_iter().zip(work_t) {
            rows.push(u);
            rows.push(t);
        }
        let (rigid, rigid_columns, rigid_rows) = rigid::rigid_maps(&bem, rigid, &body_of)?;
        columns.extend(rigid_columns);
        rows.extend(rigid_rows);
        Ok(Self {
            compliance: ContactCompliance { bem, columns, rows },
            npairs: pairs.len(),
            nodes,
            loads: loads.iter().map(|l| l.time.clone()).collect(),
            load_columns,
            bodies,
            body_of,
            velocity,
            mass,
            free,
            rigid,
            conditions: conditions.clone(),
        })
    }

    /// The boundary conditions of [`DynamicContact::bem`]: the given ones with every rigid
    /// segment fixed (a recovery model must be built with these).
    pub fn conditions(&self) -> &BoundaryConditions {
        &self.conditions
    }

    /// Number of contact unknowns (2 per slave node that projects onto its master).
    pub fn contact_unknowns(&self) -> usize {
        2 * self.nodes.len()
    }

    /// Inputs and outputs of the condensed map (the size of each CQ weight: outputs x
    /// inputs).
    pub fn weight_shape(&self) -> (usize, usize) {
        (self.compliance.rows.len(), self.compliance.columns.len())
    }

    /// The regions of each body (bonded regions form one body).
    pub fn body_regions(&self) -> &[Vec<usize>] {
        &self.bodies
    }

    /// The Laplace-domain BEM of the bodies.
    pub fn bem(&self) -> &LaplaceBem {
        &self.compliance.bem
    }

    /// The known values of [`DynamicContact::bem`] (its inputs, [`LaplaceBem::inputs`]) at
    /// one marched step: the prescribed values of the boundary conditions times their time
    /// functions at `step.time`, plus the step's contact tractions on the slave and master
    /// DOFs (the same combinations the condensed map convolves). A [`LaplaceBem`] of the same
    /// model, densities and conditions with probes, convolved with these values over the
    /// steps, gives the full boundary and interior state of the march at the probes (the
    /// bodies are linear), without the rigid motion `v0 t` of the initial velocities.
    ///
    /// Error ([`Error::InvalidParameter`]): a step whose pairs or node counts are not this
    /// problem's.
    pub fn boundary_inputs(&self, step: &DynamicContactStep) -> Result<Vec<f64>> {
        let n = self.nodes.len();
        if step.pairs.len() != self.npairs {
            return Err(Error::invalid(
                "step.pairs",
                step.pairs.len(),
                format!("the problem has {} contact pairs", self.npairs),
            ));
        }
        let mut next = vec![0usize; self.npairs];
        let mut y = vec![0.0; 2 * n + self.load_columns.len()];
        for (i, d) in self.nodes.iter().enumerate() {
            let node = step.pairs[d.pair].nodes.get(next[d.pair]).ok_or_else(|| {
                Error::invalid(
                    "step.pairs.nodes",
                    step.pairs[d.pair].nodes.len(),
                    "fewer nodes than the problem's pair",
                )
            })?;
            next[d.pair] += 1;
            y[i] = node.pressure;
            y[n + i] = node.shear;
        }
        for (c, col) in self.load_columns.iter().enumerate() {
            y[2 * n + c] = self
                .loads
                .get(col.function)
                .map_or(1.0, |tf| tf.value(step.time));
        }
        if step.rigid.len() != self.rigid.len() {
            return Err(Error::invalid(
                "step.rigid",
                step.rigid.len(),
                format!("the problem has {} rigid segments", self.rigid.len()),
            ));
        }
        y.extend(step.rigid.iter().flat_map(|r| r.translation));
        let mut known = vec![0.0; self.compliance.bem.inputs()];
        for (col, v) in self.compliance.columns.iter().zip(&y) {
            if *v != 0.0 {
                for &(k, c) in col {
                    known[k] += v * c;
                }
            }
        }
        Ok(known)
    }

    /// The mass per unit thickness of each body (in the order of
    /// [`DynamicContact::body_regions`]), kg/m.
    pub fn body_masses(&self) -> &[f64] {
        &self.mass
    }

    /// The rigid initial velocity of each region, m/s (equal within a body).
    pub fn region_velocities(&self) -> Vec<[f64; 2]> {
        self.body_of.iter().map(|&b| self.velocity[b]).collect()
    }

    /// Bytes the march allocates for the weights (with their contour spectra) and the
    /// history; None where the size overflows or the parameters are invalid.
    pub fn memory_estimate(&self, params: &DynamicContactParams) -> Option<usize> {
        if params.method.is_runge_kutta() {
            return self.stage_memory_estimate(params);
        }
        let (rows, cols) = self.weight_shape();
        let count = params.steps.checked_add(1)?;
        let w = weights_memory_estimate(params.method, cols, rows, count, &params.cq)?;
        w.checked_add(count.checked_mul(cols)?.checked_mul(8)?)
    }

    /// Marches `params.steps` steps; `observer` sees every step as it is solved (progress).
    ///
    /// Radau IIA marches by S-stage block steps ([`DynamicContact::march_samples`], which
    /// also keeps the stages).
    ///
    /// Errors: a time step that is not positive, zero steps
    /// ([`Error::InvalidParameter`]); [`Error::OutOfMemory`] where the estimate exceeds
    /// `params.memory_limit` or an allocation fails; the Laplace-domain solves' errors; a
    /// step whose active set does not converge ([`Error::NotConverged`] with the
    /// complementarity residual).
    pub fn march(
        &self,
        params: &DynamicContactParams,
        observer: &mut dyn FnMut(&DynamicContactStep),
    ) -> Result<DynamicContactResult> {
        if params.method.is_runge_kutta() {
            // Radau IIA: S-stage block steps (radau.rs).
            return self.march_samples(params, observer).map(|m| m.result);
        }
        check_march(
            params,
            self.memory_estimate(params),
            "the dynamic contact CQ weights and history",
        )?;
        let weights = cq_weights(
            &self.compliance,
            params.method,
            params.dt,
            params.steps + 1,
            &params.cq,
        )?;
        self.march_with(weights, params, observer)
    }

    fn march_with(
        &self,
        weights: crate::dynamics::cq::CqWeights,
        params: &DynamicContactParams,
        observer: &mut dyn FnMut(&DynamicContactStep),
    ) -> Result<DynamicContactResult> {
        let n = self.nodes.len();
        let (rows, cols) = (weights.rows(), weights.cols());
        let nl = self.load_columns.len();
        let w0 = weights.instantaneous().to_vec();
        // The contact block of W_0 (2n x 2n) and its load columns.
        let a: Vec<f64> = (0..2 * n)
            .flat_map(|i| w0[i * cols..i * cols + 2 * n].iter().copied())
            .collect();
        let mut rig = rigid::RigidStep::new(
            &self.rigid,
            &w0,
            cols,
            2 * n,
            rows - 2 * self.rigid.len(),
            2 * n + nl,
        )?;
        let a = rig.condensed(&w0, a);
        let friction: Vec<f64> = self.nodes.iter().map(|d| d.friction).collect();
        let rel_v = |d: &NodeData, dir: [f64; 2]| -> f64 {
            let (vs, vm) = (
                self.velocity[self.body_of[d.slave_region]],
                self.velocity[self.body_of[d.master_region]],
            );
            (vs[0] - vm[0]) * dir[0] + (vs[1] - vm[1]) * dir[1]
        };
        let slave_v = |d: &NodeData, dir: [f64; 2]| -> f64 {
            let vs = self.velocity[self.body_of[d.slave_region]];
            vs[0] * dir[0] + vs[1] * dir[1]
        };
        let nb = self.bodies.len();
        let initial_kinetic: Vec<f64> = (0..nb)
            .map(|b| {
                let v = self.velocity[b];
                0.5 * self.mass[b] * (v[0] * v[0] + v[1] * v[1])
            })
            .collect();
        let mut history = CqHistory::new(weights);
        let mut states = vec![ContactState::Open; n];
        let mut s_prev = vec![0.0; n];
        // Previous step's totals: relative n, t, slave n, t per node; load work outputs;
        // factors; forces per body.
        let mut prev_rel = vec![0.0; 4 * n];
        let mut prev_work = vec![0.0; 2 * nl];
        let mut prev_f = vec![0.0; nl];
        let mut prev_force = vec![[0.0; 2]; nb];
        let mut momentum: Vec<[f64; 2]> = (0..nb)
            .map(|b| {
                [
                    self.mass[b] * self.velocity[b][0],
                    self.mass[b] * self.velocity[b][1],
                ]
            })
            .collect();
        let (mut external, mut normal_work, mut dissipation) = (0.0, 0.0, 0.0);
        let mut body_work = vec![0.0; nb];
        let mut steps = Vec::with_capacity(params.steps + 1);
        let mut max_iterations = 0;
        for step in 0..=params.steps {
            let t = step as f64 * params.dt;
            let f: Vec<f64> = self
                .load_columns
                .iter()
                .map(|c| self.loads.get(c.function).map_or(1.0, |tf| tf.value(t)))
                .collect();
            let h = history.history()?;
            // Known part of the outputs: history + W_0 on the loads.
            let mut known: Vec<f64> = (0..rows)
                .map(|i| {
                    h[i] + (0..nl)
                        .map(|c| w0[i * cols + 2 * n + c] * f[c])
                        .sum::<f64>()
                })
                .collect();
            let u_rigid = rig.predict(&w0, &mut known, t);
            let g_pred: Vec<f64> = self
                .nodes
                .iter()
                .enumerate()
                .map(|(i, d)| d.initial_gap + known[i] + rel_v(d, d.normal) * t)
                .collect();
            let s_pred: Vec<f64> = self
                .nodes
                .iter()
                .enumerate()
                .map(|(i, d)| known[n + i] + rel_v(d, d.tangent) * t)
                .collect();
            let sol = StepProblem {
                a: &a,
                n,
                g_pred: &g_pred,
                s_pred: &s_pred,
                s_prev: &s_prev,
                friction: &friction,
            }
            .solve(step, states.clone(), &params.options)?;
            max_iterations = max_iterations.max(sol.iterations);
            let mut y = sol.z.clone();
            y.extend_from_slice(&f);
            let u_rigid = rig.translations(u_rigid, &sol.z);
            y.extend_from_slice(&u_rigid);
            let x0 = history
                .weights()
                .apply(0, &y)
                .ok_or_else(|| Error::Numerical {
                    context: "dynamic contact",
                    detail: "weight shape".into(),
                })?;
            history.push(&y)?;
            let out: Vec<f64> = x0.iter().zip(&h).map(|(a, b)| a + b).collect();
            // Totals with the rigid motion.
            let mut rel = vec![0.0; 4 * n];
            for (i, d) in self.nodes.iter().enumerate() {
                rel[i] = out[i] + rel_v(d, d.normal) * t;
                rel[n + i] = out[n + i] + rel_v(d, d.tangent) * t;
                rel[2 * n + i] = out[2 * n + i] + slave_v(d, d.normal) * t;
                rel[3 * n + i] = out[3 * n + i] + slave_v(d, d.tangent) * t;
            }
            // Energy: contact work per body, normal work, dissipation.
            let z = &sol.z;
            let mut force = vec![[0.0; 2]; nb];
            let mut pairs: Vec<DynamicPairState> = (0..self.npairs)
                .map(|_| DynamicPairState {
                    nodes: Vec::new(),
                    force: [0.0; 2],
                    sample: ContactSample {
                        length: 0.0,
                        normal_force: 0.0,
                        tangential_force: 0.0,
                        stick_length: 0.0,
                        slip_length: 0.0,
                    },
                })
                .collect();
            for (i, d) in self.nodes.iter().enumerate() {
                let (p, q, w) = (z[i], z[n + i], d.weight);
                let d_rel = |k: usize| rel[k] - prev_rel[k];
                normal_work += w * p * d_rel(i);
                dissipation -= w * q * d_rel(n + i);
                let ws = w * (p * d_rel(2 * n + i) + q * d_rel(3 * n + i));
                let wm =
                    w * (p * (d_rel(i) - d_rel(2 * n + i)) + q * (d_rel(n + i) - d_rel(3 * n + i)));
                body_work[self.body_of[d.slave_region]] += ws;
                body_work[self.body_of[d.master_region]] += wm;
                let fs = [
                    w * (p * d.normal[0] + q * d.tangent[0]),
                    w * (p * d.normal[1] + q * d.tangent[1]),
                ];
                for k in 0..2 {
                    force[self.body_of[d.slave_region]][k] += fs[k];
                    force[self.body_of[d.master_region]][k] -= fs[k];
                }
                let pair = &mut pairs[d.pair];
                for k in 0..2 {
                    pair.force[k] += fs[k];
                }
                let st = sol.states[i];
                let sample = &mut pair.sample;
                if !matches!(st, ContactState::Open | ContactState::Outside) {
                    sample.length += w;
                    if st == ContactState::Stick && d.friction > 0.0 {
                        sample.stick_length += w;
                    } else {
                        sample.slip_length += w;
                    }
                }
                sample.normal_force += w * p;
                sample.tangential_force += w * q;
                pair.nodes.push(DynamicContactNode {
                    position: d.position,
                    pressure: p,
                    shear: q,
                    gap: sol.gap[i],
                    slip: sol.slip[i],
                    state: st,
                });
            }
            // External work and load forces.
            let work = &out[4 * n..];
            for (c, col) in self.load_columns.iter().enumerate() {
                let yu = work[2 * c] + col.rigid_rate * t;
                let yt = work[2 * c + 1];
                let (yu0, yt0) = (prev_work[2 * c], prev_work[2 * c + 1]);
                let dw =
                    0.5 * (f[c] + prev_f[c]) * (yu - yu0) + 0.5 * (yt + yt0) * (f[c] - prev_f[c]);
                external += dw;
                body_work[col.body] += dw;
                prev_work[2 * c] = yu;
                prev_work[2 * c + 1] = yt;
                for k in 0..2 {
                    force[col.body][k] += f[c] * col.force[k];
                }
            }
            let (rigid, rigid_work) = rig.record(&u_rigid, &out, &mut body_work, &mut force);
            external += rigid_work;
            if step > 0 {
                for b in 0..nb {
                    for k in 0..2 {
                        momentum[b][k] += 0.5 * params.dt * (force[b][k] + prev_force[b][k]);
                    }
                }
            }
            let bodies = (0..nb)
                .map(|b| {
                    let free = self.free[b];
                    let pm = momentum[b];
                    BodyEnergy {
                        mechanical: initial_kinetic[b] + body_work[b],
                        momentum: free.then_some(pm),
                        translational_kinetic: free
                            .then(|| (pm[0] * pm[0] + pm[1] * pm[1]) / (2.0 * self.mass[b])),
                    }
                })
                .collect();
            let k0: f64 = initial_kinetic.iter().sum();
            let record = DynamicContactStep {
                step,
                time: t,
                iterations: sol.iterations,
                residual: sol.residual,
                pairs,
                rigid,
                energy: DynamicContactEnergy {
                    initial_kinetic: k0,
                    external_work: external,
                    normal_contact_work: normal_work,
                    dissipation,
                    mechanical: k0 + external + normal_work - dissipation,
                    bodies,
                },
            };
            observer(&record);
            steps.push(record);
            prev_rel = rel;
            prev_f = f;
            prev_force = force;
            s_prev = sol.slip;
            states = sol.states;
        }
        Ok(DynamicContactResult {
            steps,
            max_iterations,
        })
    }
}

/// The checks of a march's parameters shared by the multistep and the Radau IIA march:
/// a positive time step, at least one step, and the memory estimate `bytes` (None: it
/// overflows) within `params.memory_limit`, `what` naming the allocation.
///
/// Errors: [`Error::InvalidParameter`] (`dt`, `steps`); [`Error::OutOfMemory`].
fn check_march(params: &DynamicContactParams, bytes: Option<usize>, what: &str) -> Result<()> {
    if !(params.dt.is_finite() && params.dt > 0.0) {
        return Err(Error::invalid(
            "dt",
            params.dt,
            "the time step must be positive (s)",
        ));
    }
    if params.steps == 0 {
        return Err(Error::invalid("steps", 0, "at least one step"));
    }
    let bytes = bytes.unwrap_or(usize::MAX);
    if params.memory_limit.is_some_and(|limit| bytes > limit) {
        return Err(Error::OutOfMemory {
            what: what.into(),
            bytes,
        });
    }
    Ok(())
}
