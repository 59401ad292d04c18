//! Damage over time in a dynamic run: the static measures of the paper's (21)-(24) and (36)
//! (seed paper Sec. 4; docs/theory/DESIGN.md part F; [`crate::analysis::damage`]) with
//! psi taken at every step of the run (issue 13 item 3).
//!
//! At each step time t_n the stress at the nodes of a triangulated region gives
//! psi_q(x, t_n) = phi_q(sigma(x, t_n)) / phi_q^lim (21), and with psi linear on each
//! triangle the step's dangerous area A_q(t_n) = |{psi_q >= 1}| (22) and damageability
//! Psi_q(t_n) = integral of psi_q over it (24, numerator), both exact per triangle
//! ([`crate::analysis::damage::dangerous_region`]). Over the run:
//!
//! - **the history per step**: A_q(t_n), Psi_q(t_n), max psi_q(t_n);
//! - **the peaks**: the largest dangerous area and its time, the largest psi_q, its time
//!   and place;
//! - **the accumulation of the paper** (23), (24), (36), exactly as the static load-cycle
//!   accumulation ([`crate::analysis::damage::accumulate_psi`], here step by step through
//!   [`DamageAccumulator`], the same bits): the time integral of psi_q per point
//!   d Psi_q^(t) = integral of psi_q dt (23), the integral of A_q dt, and
//!   Psi_q^(V, t) = integral over t of the integral over {psi_q(t) >= 1} of psi_q dA dt
//!   (23), (36) and its mean over the dangerous area (24), all by the trapezoid rule over
//!   the step times, the run being the "cycle" (the paper integrates over the load cycle;
//!   a dynamic run is one load event);
//! - **the envelope**: max over t of psi_q per point, and the area where it reaches 1 (the
//!   points dangerous at some instant; the union of the A_q(t_n)).
//!
//! **No cycle counting.** The paper's accumulation is the time integral above; it has no
//! S-N curve or cycle rule, and tribo has no rainflow counting (docs/theory/FATIGUE.md
//! sec. 5 lists it as a recommendation, not built). A linear (Miner) damage sum of counted
//! cycles is therefore not computed: its physics (a Woehler curve per point, mean-stress
//! rule) is not in the case's `[damage]`.

use crate::analysis::damage::{
    dangerous_region, CycleDamage, DamageMesh, Execution, Limit, StateDamage,
};
use crate::dynamics::history::DamageAccumulator;
use crate::error::{Error, Result};
use crate::kernels::subsurface::StressTensor;
use crate::material::ElasticMaterial;

/// The damage of one region over a dynamic run (module docs); areas per unit thickness,
/// m^2, times s, psi dimensionless.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct DynamicDamage {
    /// The quantity phi_q's name (e.g. `sigma_int`).
    pub quantity: String,
    /// Its unit (`Pa`, `1`, `J/m^3`).
    pub unit: &'static str,
    /// The limit phi_q^lim, in `unit`.
    pub limit: f64,
    /// The accumulation over the run (23), (24), (36): `states` one per step (time,
    /// dangerous area A_q, damageability Psi_q, max psi_q), the time integrals.
    pub accumulated: CycleDamage,
    /// The largest dangerous area over the run, m^2.
    pub peak_area: f64,
    /// Its (first) time, s.
    pub peak_area_time: f64,
    /// The largest psi_q over the points and steps.
    pub psi_max: f64,
    /// Its (first) time, s.
    pub psi_max_time: f64,
    /// Where, (x, y) m.
    pub psi_max_at: [f64; 2],
    /// max over t of psi_q per point (the mesh's nodes).
    pub envelope: Vec<f64>,
    /// The area where the envelope reaches 1 (dangerous at some instant), m^2.
    pub envelope_area: f64,
}

/// Accumulates [`DynamicDamage`] step by step: the stresses of one step in
/// ([`DamageOverTime::push`], which returns that step's psi), the result out
/// ([`DamageOverTime::finish`]). Holds one step's field at a time.
#[derive(Debug, Clone)]
pub struct DamageOverTime {
    mesh: DamageMesh,
    limit: Limit,
    material: ElasticMaterial,
    execution: Execution,
    accumulator: DamageAccumulator,
    envelope: Vec<f64>,
    peak_area: (f64, f64),
    psi_max: (f64, f64, usize),
}

impl DamageOverTime {
    /// An accumulator over the triangles of `mesh` (the points where the stresses are
    /// given) in `material`, psi = phi / `limit`.
    pub fn new(
        mesh: DamageMesh,
        limit: Limit,
        material: ElasticMaterial,
        execution: Execution,
    ) -> Self {
        let accumulator = DamageAccumulator::new(&mesh, execution);
        let n = mesh.node_count();
        DamageOverTime {
            mesh,
            limit,
            material,
            execution,
            accumulator,
            envelope: vec![f64::NEG_INFINITY; n],
            peak_area: (f64::NEG_INFINITY, 0.0),
            psi_max: (f64::NEG_INFINITY, 0.0, 0),
        }
    }

    /// The mesh.
    pub fn mesh(&self) -> &DamageMesh {
        &self.mesh
    }

    /// Adds the step at time `t` (s, after the previous one) with the stress at every mesh
    /// node (Pa) and returns psi_q there (21).
    ///
    /// Errors: a stress count other than the node count, a non-finite stress or time,
    /// a time not after the previous one ([`Error::InvalidParameter`]).
    pub fn push(&mut self, t: f64, stress: &[StressTensor]) -> Result<Vec<f64>> {
        if stress.len() != self.mesh.node_count() {
            return Err(Error::invalid(
                "damage.stress",
                format!("{} points", stress.len()),
                format!(
                    "needs one stress per mesh node ({})",
                    self.mesh.node_count()
                ),
            ));
        }
        let psi = crate::analysis::damage::relative_damage(&self.limit, stress, &self.material)?;
        self.accumulator.push(&self.mesh, t, psi.clone())?;
        let state = self
            .accumulator
            .states()
            .last()
            .copied()
            .ok_or_else(|| Error::invalid("damage.states", "none", "a state was just added"))?;
        if state.volume > self.peak_area.0 {
            self.peak_area = (state.volume, t);
        }
        for (i, (e, &p)) in self.envelope.iter_mut().zip(&psi).enumerate() {
            if p > *e {
                *e = p;
            }
            if p > self.psi_max.0 {
                self.psi_max = (p, t, i);
            }
        }
        Ok(psi)
    }

    /// The states so far (time, dangerous area, damageability, max psi per step).
    pub fn states(&self) -> &[StateDamage] {
        self.accumulator.states()
    }

    /// The damage over the run. Error: fewer than 2 steps pushed.
    pub fn finish(self) -> Result<DynamicDamage> {
        let accumulated = self.accumulator.finish(&self.mesh)?;
        let envelope_area = dangerous_region(&self.mesh, &self.envelope, self.execution)?.volume;
        let at = self.mesh.nodes()[self.psi_max.2];
        let q = self.limit.quantity();
        Ok(DynamicDamage {
            quantity: q.name(),
            unit: q.unit(),
            limit: self.limit.value(),
            accumulated,
            peak_area: self.peak_area.0,
            peak_area_time: self.peak_area.1,
            psi_max: self.psi_max.0,
            psi_max_time: self.psi_max.1,
            psi_max_at: [at[0], at[1]],
            envelope: self.envelope,
            envelope_area,
        })
    }
}

#[cfg(test)]
#[path = "damage_tests.rs"]
mod tests;
