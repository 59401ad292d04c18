//! The result of a dynamic run: histories over the sample times, filled step by step by the
//! solver and read by the writers (and by Python through serde).
//!
//! [`DynamicHistory`] holds, over the sample times t_n (s):
//! - per probe ([`ProbeHistory`]): displacement (m), velocity (m/s), stress (Pa);
//! - per contact pair ([`ContactHistory`]): contact length (m), normal and tangential force
//!   per unit thickness (N/m), stick and slip extents (m);
//! - the energies ([`EnergyHistory`], J/m per unit thickness): input work, elastic strain
//!   energy, kinetic energy, frictional dissipation, each `None` where the solver does not
//!   compute it;
//! - field snapshots at chosen times ([`FieldSnapshot`] on one [`SnapshotMesh`]): the static
//!   pipeline's [`FieldSample`] (displacement, stress, strain) at the sampled points;
//! - per assessed region the damage over time ([`DamageHistory`]): the static
//!   [`CycleDamage`] of the paper's (23), (24), (36), psi taken at each step (accumulated step
//!   by step by [`DamageAccumulator`], the same bits as [`accumulate_psi`] over all steps).
//!
//! The solver creates the history with its probes, pairs and energy terms
//! ([`DynamicHistory::new`]), then calls [`DynamicHistory::push_step`] once per step and
//! [`DynamicHistory::push_snapshot`] at the output times; each push checks its own shape.
//! [`DynamicHistory::check`] checks every invariant at once (equal lengths, increasing
//! times, finite numbers): the writers call it before writing anything.
//!
//! [`accumulate_psi`]: crate::analysis::damage::accumulate_psi

use serde::Serialize;

use crate::analysis::bem_field::FieldSample;
use crate::analysis::damage::sum::ExactSum;
use crate::analysis::damage::{dangerous_region, CycleDamage, DamageMesh, Execution, StateDamage};
use crate::error::{Error, Result};
use crate::solvers::bem2d::Stress2d;

/// The histories at one probe point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ProbeHistory {
    /// The probe's name (from the case).
    pub name: String,
    /// Where, (x, y) m.
    pub point: [f64; 2],
    /// Displacement (u_x, u_y) at each sample time, m.
    pub displacement: Vec<[f64; 2]>,
    /// Velocity (v_x, v_y) at each sample time, m/s.
    pub velocity: Vec<[f64; 2]>,
    /// Stress at each sample time, Pa (tension positive).
    pub stress: Vec<Stress2d>,
}

/// The histories of one contact pair (forces per unit thickness).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ContactHistory {
    /// The slave segment.
    pub slave: String,
    /// The master segment.
    pub master: String,
    /// Length of the closed part of the interface (stick + slip), m.
    pub length: Vec<f64>,
    /// Normal force on the slave (compression positive), N/m.
    pub normal_force: Vec<f64>,
    /// Tangential force on the slave along the master's tangent, N/m.
    pub tangential_force: Vec<f64>,
    /// Length of the sticking part, m.
    pub stick_length: Vec<f64>,
    /// Length of the slipping part, m.
    pub slip_length: Vec<f64>,
}

/// The energy histories, J/m (per unit thickness); `None` where not computed. With all of
/// them the balance W - U - K - D is the energy error ([`EnergyHistory::balance`]): a
/// spurious contact oscillation shows as its drift.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct EnergyHistory {
    /// Work of the boundary loads and prescribed displacements since t = 0 (plus the initial
    /// kinetic energy of an impact), J/m.
    pub input_work: Option<Vec<f64>>,
    /// Elastic strain energy in the bodies, J/m.
    pub strain_energy: Option<Vec<f64>>,
    /// Kinetic energy of the bodies, J/m.
    pub kinetic_energy: Option<Vec<f64>>,
    /// Energy dissipated by friction since t = 0, J/m.
    pub dissipation: Option<Vec<f64>>,
}

/// Which energy terms a solver computes (the `Some` series of [`EnergyHistory`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct EnergyTerms {
    /// Input work.
    pub input_work: bool,
    /// Strain energy.
    pub strain_energy: bool,
    /// Kinetic energy.
    pub kinetic_energy: bool,
    /// Frictional dissipation.
    pub dissipation: bool,
}

impl EnergyHistory {
    fn new(terms: EnergyTerms) -> Self {
        let series = |on: bool| on.then(Vec::new);
        EnergyHistory {
            input_work: series(terms.input_work),
            strain_energy: series(terms.strain_energy),
            kinetic_energy: series(terms.kinetic_energy),
            dissipation: series(terms.dissipation),
        }
    }

    /// The series with their names and units (`input_work_J_per_m`, ...), those computed.
    pub fn series(&self) -> Vec<(&'static str, &[f64])> {
        [
            ("input_work_J_per_m", &self.input_work),
            ("strain_energy_J_per_m", &self.strain_energy),
            ("kinetic_energy_J_per_m", &self.kinetic_energy),
            ("dissipation_J_per_m", &self.dissipation),
        ]
        .into_iter()
        .filter_map(|(name, s)| s.as_deref().map(|s| (name, s)))
        .collect()
    }

    /// The balance W - U - K - D at each sample time (J/m; 0 for an exact energy-conserving
    /// solution), where all four series are computed.
    pub fn balance(&self) -> Option<Vec<f64>> {
        let (w, u, k, d) = (
            self.input_work.as_ref()?,
            self.strain_energy.as_ref()?,
            self.kinetic_energy.as_ref()?,
            self.dissipation.as_ref()?,
        );
        Some(
            w.iter()
                .zip(u)
                .zip(k)
                .zip(d)
                .map(|(((w, u), k), d)| w - u - k - d)
                .collect(),
        )
    }
}

/// One region of the snapshot mesh: its sampled points and the triangles over them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SnapshotRegion {
    /// The region's name.
    pub region: String,
    /// The region's index in the model.
    pub index: usize,
    /// The sampled points, (x, y) m.
    pub nodes: Vec<[f64; 2]>,
    /// Triangles over `nodes` (indices into them).
    pub triangles: Vec<[usize; 3]>,
}

/// The points where the field snapshots are sampled (the same at every snapshot).
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct SnapshotMesh {
    /// The sampled regions.
    pub regions: Vec<SnapshotRegion>,
}

/// The interior field at one time: per region of the [`SnapshotMesh`], one sample per node.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FieldSnapshot {
    /// Time, s.
    pub time: f64,
    /// The index of the sample time (into [`DynamicHistory::times`]).
    pub step: usize,
    /// Per region of the mesh (same order), per node: displacement, stress, strain.
    pub samples: Vec<Vec<FieldSample>>,
}

/// The damage of one region over the run: the static accumulation (23), (24), (36) with psi
/// at each sample time (its `states` one per time).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DamageHistory {
    /// The region assessed.
    pub region: String,
    /// The damage quantity phi's name (e.g. `sigma_int`).
    pub quantity: String,
    /// Its limit phi_lim, in the quantity's unit.
    pub limit: f64,
    /// The accumulated measures and the per-step states.
    pub damage: CycleDamage,
}

/// What one sample time adds to a probe.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProbeSample {
    /// Displacement, m.
    pub displacement: [f64; 2],
    /// Velocity, m/s.
    pub velocity: [f64; 2],
    /// Stress, Pa.
    pub stress: Stress2d,
}

/// What one sample time adds to a contact pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactSample {
    /// Contact length, m.
    pub length: f64,
    /// Normal force, N/m.
    pub normal_force: f64,
    /// Tangential force, N/m.
    pub tangential_force: f64,
    /// Stick extent, m.
    pub stick_length: f64,
    /// Slip extent, m.
    pub slip_length: f64,
}

/// What one sample time adds to the energies (J/m); `Some` exactly for the terms the
/// history was created with.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct EnergySample {
    /// Input work.
    pub input_work: Option<f64>,
    /// Strain energy.
    pub strain_energy: Option<f64>,
    /// Kinetic energy.
    pub kinetic_energy: Option<f64>,
    /// Dissipation.
    pub dissipation: Option<f64>,
}

/// One sample time's values, in the order of the history's probes and pairs.
#[derive(Debug, Clone, PartialEq)]
pub struct StepRecord {
    /// Time, s (greater than the previous one).
    pub time: f64,
    /// One per probe.
    pub probes: Vec<ProbeSample>,
    /// One per contact pair.
    pub contacts: Vec<ContactSample>,
    /// The energies.
    pub energy: EnergySample,
}

/// The result of a dynamic run (see the module docs): every series has one value per
/// sample time.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DynamicHistory {
    /// The sample times, s (strictly increasing).
    pub times: Vec<f64>,
    /// The probes.
    pub probes: Vec<ProbeHistory>,
    /// The contact pairs.
    pub contacts: Vec<ContactHistory>,
    /// The energies.
    pub energy: EnergyHistory,
    /// Where the snapshots are sampled.
    pub snapshot_mesh: SnapshotMesh,
    /// The field snapshots, times increasing.
    pub snapshots: Vec<FieldSnapshot>,
    /// The damage per assessed region.
    pub damage: Vec<DamageHistory>,
    /// Whether the solver computes stresses (and strains): at the probes and in the
    /// snapshots. Without them ([`DynamicHistory::without_stresses`]) the probes' `stress`
    /// series stay empty, the snapshots' stresses and strains are not results (zero
    /// placeholders) and the writers leave those columns and arrays out.
    pub stresses: bool,
}

fn shape(
    what: impl Into<String>,
    detail: impl std::fmt::Display,
    rule: impl Into<String>,
) -> Error {
    Error::invalid(what, detail, rule)
}

/// `v` must be finite; errors name `what`.
fn finite_all(what: &str, v: impl IntoIterator<Item = f64>) -> Result<()> {
    match v.into_iter().enumerate().find(|(_, x)| !x.is_finite()) {
        None => Ok(()),
        Some((k, x)) => Err(shape(
            format!("{what}[{k}]"),
            x,
            "a dynamic result must be finite",
        )),
    }
}

impl DynamicHistory {
    /// An empty history of the probes (name, point in m), the contact pairs (slave,
    /// master) and the energy terms the solver computes.
    pub fn new(
        probes: Vec<(String, [f64; 2])>,
        pairs: Vec<(String, String)>,
        energy: EnergyTerms,
    ) -> Self {
        DynamicHistory {
            times: Vec::new(),
            probes: probes
                .into_iter()
                .map(|(name, point)| ProbeHistory {
                    name,
                    point,
                    displacement: Vec::new(),
                    velocity: Vec::new(),
                    stress: Vec::new(),
                })
                .collect(),
            contacts: pairs
                .into_iter()
                .map(|(slave, master)| ContactHistory {
                    slave,
                    master,
                    length: Vec::new(),
                    normal_force: Vec::new(),
                    tangential_force: Vec::new(),
                    stick_length: Vec::new(),
                    slip_length: Vec::new(),
                })
                .collect(),
            energy: EnergyHistory::new(energy),
            snapshot_mesh: SnapshotMesh::default(),
            snapshots: Vec::new(),
            damage: Vec::new(),
            stresses: true,
        }
    }

    /// The history of a solver that computes displacements and velocities only: the
    /// samples' stresses are ignored and nothing is written for them (see
    /// [`DynamicHistory::stresses`]). Error: steps already recorded.
    pub fn without_stresses(mut self) -> Result<Self> {
        if !self.times.is_empty() {
            return Err(shape(
                "history.stresses",
                self.times.len(),
                "the stress setting is chosen before the first step",
            ));
        }
        self.stresses = false;
        Ok(self)
    }

    /// The number of sample times.
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// Whether no step was recorded.
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }

    /// Appends one sample time. Errors (nothing appended): the time not finite or not after
    /// the previous one, a count of probes or pairs that differs from the history's, an
    /// energy term given that the history does not hold or missing one it does.
    pub fn push_step(&mut self, record: StepRecord) -> Result<()> {
        let t = record.time;
        if !t.is_finite() || self.times.last().is_some_and(|&p| t <= p) {
            return Err(shape(
                "history.time",
                t,
                format!(
                    "sample times must be finite and increase (the last is {:?} s)",
                    self.times.last()
                ),
            ));
        }
        if record.probes.len() != self.probes.len() || record.contacts.len() != self.contacts.len()
        {
            return Err(shape(
                "history.step",
                format!(
                    "{} probes, {} pairs",
                    record.probes.len(),
                    record.contacts.len()
                ),
                format!(
                    "a step needs one sample per probe ({}) and per contact pair ({})",
                    self.probes.len(),
                    self.contacts.len()
                ),
            ));
        }
        let e = &record.energy;
        let terms = [
            ("input_work", self.energy.input_work.is_some(), e.input_work),
            (
                "strain_energy",
                self.energy.strain_energy.is_some(),
                e.strain_energy,
            ),
            (
                "kinetic_energy",
                self.energy.kinetic_energy.is_some(),
                e.kinetic_energy,
            ),
            (
                "dissipation",
                self.energy.dissipation.is_some(),
                e.dissipation,
            ),
        ];
        for (name, held, given) in terms {
            if held != given.is_some() {
                return Err(shape(
                    format!("history.energy.{name}"),
                    format!("{given:?}"),
                    if held {
                        "the history holds this energy term: every step must give it"
                    } else {
                        "the history was created without this energy term"
                    },
                ));
            }
        }
        self.times.push(t);
        for (h, s) in self.probes.iter_mut().zip(&record.probes) {
            h.displacement.push(s.displacement);
            h.velocity.push(s.velocity);
            if self.stresses {
                h.stress.push(s.stress);
            }
        }
        for (h, s) in self.contacts.iter_mut().zip(&record.contacts) {
            h.length.push(s.length);
            h.normal_force.push(s.normal_force);
            h.tangential_force.push(s.tangential_force);
            h.stick_length.push(s.stick_length);
            h.slip_length.push(s.slip_length);
        }
        let push = |series: &mut Option<Vec<f64>>, v: Option<f64>| {
            if let (Some(s), Some(v)) = (series.as_mut(), v) {
                s.push(v);
            }
        };
        push(&mut self.energy.input_work, e.input_work);
        push(&mut self.energy.strain_energy, e.strain_energy);
        push(&mut self.energy.kinetic_energy, e.kinetic_energy);
        push(&mut self.energy.dissipation, e.dissipation);
        Ok(())
    }

    /// Sets the mesh of the snapshots (before the first one). Error: snapshots already
    /// taken, a triangle naming a node that does not exist.
    pub fn set_snapshot_mesh(&mut self, mesh: SnapshotMesh) -> Result<()> {
        if !self.snapshots.is_empty() {
            return Err(shape(
                "history.snapshot_mesh",
                format!("{} snapshots", self.snapshots.len()),
                "the snapshot mesh is set before the first snapshot",
            ));
        }
        check_mesh(&mesh)?;
        self.snapshot_mesh = mesh;
        Ok(())
    }

    /// Appends a field snapshot taken at the latest sample time. Errors: no step yet, a
    /// snapshot of that step already taken, sample counts that differ from the mesh's.
    pub fn push_snapshot(&mut self, samples: Vec<Vec<FieldSample>>) -> Result<()> {
        let Some(&time) = self.times.last() else {
            return Err(shape(
                "history.snapshot",
                "(no step)",
                "a snapshot is taken after its step is pushed",
            ));
        };
        let step = self.times.len() - 1;
        if self.snapshots.last().is_some_and(|s| s.step == step) {
            return Err(shape(
                "history.snapshot",
                step,
                "one snapshot per sample time",
            ));
        }
        let snapshot = FieldSnapshot {
            time,
            step,
            samples,
        };
        check_snapshot(&self.snapshot_mesh, &snapshot, self.snapshots.len())?;
        self.snapshots.push(snapshot);
        Ok(())
    }

    /// Every invariant, in one place: times finite and strictly increasing; every series
    /// one value per time; every number finite; snapshots at sample times (their step's
    /// time), increasing, shaped as the mesh; damage states one per time at the same times.
    pub fn check(&self) -> Result<()> {
        let n = self.times.len();
        finite_all("history.times", self.times.iter().copied())?;
        if let Some(k) = self.times.windows(2).position(|w| w[1] <= w[0]) {
            return Err(shape(
                format!("history.times[{}]", k + 1),
                self.times[k + 1],
                "sample times must increase strictly",
            ));
        }
        let length = |what: String, len: usize| -> Result<()> {
            if len == n {
                Ok(())
            } else {
                Err(shape(
                    what,
                    format!("{len} values"),
                    format!("needs one value per sample time ({n})"),
                ))
            }
        };
        for p in &self.probes {
            let what = format!("history.probes.{}", p.name);
            length(format!("{what}.displacement"), p.displacement.len())?;
            length(format!("{what}.velocity"), p.velocity.len())?;
            if self.stresses {
                length(format!("{what}.stress"), p.stress.len())?;
            } else if !p.stress.is_empty() {
                return Err(shape(
                    format!("{what}.stress"),
                    format!("{} values", p.stress.len()),
                    "a history without stresses holds none",
                ));
            }
            finite_all(&format!("{what}.point"), p.point)?;
            finite_all(
                &what,
                p.displacement
                    .iter()
                    .chain(&p.velocity)
                    .flatten()
                    .copied()
                    .chain(p.stress.iter().flat_map(|s| [s.xx, s.yy, s.xy, s.zz])),
            )?;
        }
        for c in &self.contacts {
            let what = format!("history.contacts.{}-{}", c.slave, c.master);
            for (name, s) in [
                ("length", &c.length),
                ("normal_force", &c.normal_force),
                ("tangential_force", &c.tangential_force),
                ("stick_length", &c.stick_length),
                ("slip_length", &c.slip_length),
            ] {
                length(format!("{what}.{name}"), s.len())?;
                finite_all(&format!("{what}.{name}"), s.iter().copied())?;
            }
        }
        for (name, s) in self.energy.series() {
            length(format!("history.energy.{name}"), s.len())?;
            finite_all(&format!("history.energy.{name}"), s.iter().copied())?;
        }
        check_mesh(&self.snapshot_mesh)?;
        for (k, s) in self.snapshots.iter().enumerate() {
            if s.step >= n || self.times[s.step] != s.time {
                return Err(shape(
                    format!("history.snapshots[{k}].time"),
                    s.time,
                    "a snapshot is taken at a sample time (its step's)",
                ));
            }
            if k > 0 && s.step <= self.snapshots[k - 1].step {
                return Err(shape(
                    format!("history.snapshots[{k}].step"),
                    s.step,
                    "snapshots must be in increasing time",
                ));
            }
            check_snapshot(&self.snapshot_mesh, s, k)?;
        }
        for d in &self.damage {
            let what = format!("history.damage.{}", d.region);
            length(format!("{what}.states"), d.damage.states.len())?;
            if let Some(k) = d
                .damage
                .states
                .iter()
                .zip(&self.times)
                .position(|(s, t)| s.time != *t)
            {
                return Err(shape(
                    format!("{what}.states[{k}].time"),
                    d.damage.states[k].time,
                    "damage states are taken at the sample times",
                ));
            }
        }
        Ok(())
    }
}

fn check_mesh(mesh: &SnapshotMesh) -> Result<()> {
    for r in &mesh.regions {
        finite_all(
            &format!("history.snapshot_mesh.{}.nodes", r.region),
            r.nodes.iter().flatten().copied(),
        )?;
        let n = r.nodes.len();
        if let Some(k) = r.triangles.iter().position(|t| t.iter().any(|&i| i >= n)) {
            return Err(shape(
                format!("history.snapshot_mesh.{}.triangles[{k}]", r.region),
                format!("{:?}", r.triangles[k]),
                format!("a triangle's nodes must be < {n} (the region's node count)"),
            ));
        }
    }
    Ok(())
}

fn check_snapshot(mesh: &SnapshotMesh, s: &FieldSnapshot, k: usize) -> Result<()> {
    let what = format!("history.snapshots[{k}]");
    if s.samples.len() != mesh.regions.len() {
        return Err(shape(
            format!("{what}.samples"),
            format!("{} regions", s.samples.len()),
            format!(
                "needs one sample list per region of the snapshot mesh ({})",
                mesh.regions.len()
            ),
        ));
    }
    for (r, samples) in mesh.regions.iter().zip(&s.samples) {
        if samples.len() != r.nodes.len() {
            return Err(shape(
                format!("{what}.samples.{}", r.region),
                format!("{} samples", samples.len()),
                format!("needs one sample per node ({})", r.nodes.len()),
            ));
        }
        finite_all(
            &format!("{what}.samples.{}", r.region),
            samples.iter().flat_map(|x| {
                [
                    x.displacement[0],
                    x.displacement[1],
                    x.stress.xx,
                    x.stress.yy,
                    x.stress.xy,
                    x.stress.zz,
                    x.strain.xx,
                    x.strain.yy,
                    x.strain.xy,
                    x.strain.zz,
                ]
            }),
        )?;
    }
    Ok(())
}

/// The damage of one region accumulated step by step: psi at each sample time goes in
/// ([`DamageAccumulator::push`]), [`CycleDamage`] comes out ([`DamageAccumulator::finish`]),
/// the same bits as [`crate::analysis::damage::accumulate_psi`] over all steps at once (the
/// trapezoid weight of step k needs t_k+1, so step k's contribution is added when step k+1
/// arrives, in the same order and with the same arithmetic). Holds one psi field, not all.
#[derive(Debug, Clone)]
pub struct DamageAccumulator {
    execution: Execution,
    t0: Option<f64>,
    /// (t_k-1, the step before the pending one).
    before: Option<f64>,
    /// The latest step (time, psi, its dangerous region), its weight not yet known.
    pending: Option<(f64, Vec<f64>, crate::analysis::damage::DangerousRegion)>,
    node_integral: Vec<f64>,
    volume: ExactSum,
    damageability: ExactSum,
    any_dangerous: bool,
    states: Vec<StateDamage>,
}

impl DamageAccumulator {
    /// An accumulator over `mesh` (its node count fixes psi's length).
    pub fn new(mesh: &DamageMesh, execution: Execution) -> Self {
        DamageAccumulator {
            execution,
            t0: None,
            before: None,
            pending: None,
            node_integral: vec![0.0; mesh.node_count()],
            volume: ExactSum::default(),
            damageability: ExactSum::default(),
            any_dangerous: false,
            states: Vec::new(),
        }
    }

    /// The states so far (time, V, Psi, psi_max per step).
    pub fn states(&self) -> &[StateDamage] {
        &self.states
    }

    /// Adds psi (one value per mesh node) at time `t` (s, after the previous one).
    pub fn push(&mut self, mesh: &DamageMesh, t: f64, psi: Vec<f64>) -> Result<()> {
        if psi.len() != self.node_integral.len() {
            return Err(shape(
                "damage.psi",
                format!("{} values", psi.len()),
                format!(
                    "needs one value per mesh node ({})",
                    self.node_integral.len()
                ),
            ));
        }
        let last = self.pending.as_ref().map(|p| p.0);
        if !t.is_finite() || last.is_some_and(|p| t <= p) {
            return Err(shape(
                "damage.time",
                t,
                "times must be finite and strictly increasing (s)",
            ));
        }
        let region = dangerous_region(mesh, &psi, self.execution)?;
        if let Some(p) = self.pending.take() {
            self.settle(p, Some(t));
        }
        self.t0.get_or_insert(t);
        self.states.push(StateDamage {
            time: t,
            volume: region.volume,
            damageability: region.damageability,
            psi_max: region.psi_max,
        });
        self.pending = Some((t, psi, region));
        Ok(())
    }

    /// Adds the pending step with its trapezoid weight ([`crate::analysis::damage::trapezoid_weights`]'s
    /// expression), `next` the following time (None: the last step).
    fn settle(
        &mut self,
        (t, psi, region): (f64, Vec<f64>, crate::analysis::damage::DangerousRegion),
        next: Option<f64>,
    ) {
        let left = self.before.map_or(0.0, |b| t - b);
        let right = next.map_or(0.0, |n| n - t);
        let w = 0.5 * (left + right);
        self.any_dangerous |= region.volume > 0.0;
        self.volume.add(w * region.volume);
        self.damageability.add(w * region.damageability);
        self.node_integral
            .iter_mut()
            .zip(&psi)
            .for_each(|(a, p)| *a += w * p);
        self.before = Some(t);
    }

    /// The accumulated damage (23), (24), (36). Error: fewer than 2 steps pushed.
    pub fn finish(mut self, mesh: &DamageMesh) -> Result<CycleDamage> {
        if self.states.len() < 2 {
            return Err(shape(
                "damage.times",
                format!("{} states", self.states.len()),
                "needs at least 2 states",
            ));
        }
        if let Some(p) = self.pending.take() {
            self.settle(p, None);
        }
        let times = (self.t0.unwrap_or(0.0), self.before.unwrap_or(0.0));
        let period = times.1 - times.0;
        let (volume_time_integral, damageability_time_integral) =
            (self.volume.value(), self.damageability.value());
        let mean_volume = volume_time_integral / period;
        let ni = &self.node_integral;
        let mut best = 0;
        for (i, &v) in ni.iter().enumerate() {
            if v > ni[best] {
                best = i;
            }
        }
        Ok(CycleDamage {
            period,
            states: self.states,
            volume_time_integral,
            mean_volume,
            damageability_time_integral,
            average: (self.any_dangerous && mean_volume > 0.0)
                .then(|| damageability_time_integral / mean_volume),
            node_time_integral_max: ni.get(best).copied().unwrap_or(0.0),
            node_time_integral_max_at: mesh.nodes().get(best).copied().unwrap_or([0.0; 3]),
            node_time_integral: self.node_integral,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::damage::accumulate_psi;
    use crate::solvers::bem2d::Strain2d;

    fn stress(s: f64) -> Stress2d {
        Stress2d {
            xx: s,
            yy: 0.0,
            xy: 0.0,
            zz: 0.0,
        }
    }

    fn record(t: f64) -> StepRecord {
        StepRecord {
            time: t,
            probes: vec![ProbeSample {
                displacement: [t, 0.0],
                velocity: [1.0, 0.0],
                stress: stress(t),
            }],
            contacts: vec![],
            energy: EnergySample {
                input_work: Some(t),
                ..Default::default()
            },
        }
    }

    fn history() -> DynamicHistory {
        DynamicHistory::new(
            vec![("a".into(), [0.0, 0.0])],
            vec![],
            EnergyTerms {
                input_work: true,
                ..Default::default()
            },
        )
    }

    #[test]
    fn steps_fill_every_series() {
        let mut h = history();
        for k in 0..4 {
            h.push_step(record(k as f64 * 0.5)).unwrap();
        }
        assert_eq!(h.len(), 4);
        assert_eq!(h.probes[0].displacement[3], [1.5, 0.0]);
        assert_eq!(
            h.energy.input_work.as_deref(),
            Some(&[0.0, 0.5, 1.0, 1.5][..])
        );
        assert!(h.energy.strain_energy.is_none() && h.energy.balance().is_none());
        assert_eq!(h.energy.series().len(), 1);
        h.check().unwrap();
        // What a consumer (Python, JSON) reads: plain arrays, null where not computed.
        let json = serde_json::to_value(&h).unwrap();
        assert_eq!(json["times"][3], 1.5);
        assert_eq!(json["probes"][0]["displacement"][3][0], 1.5);
        assert_eq!(json["probes"][0]["stress"][2]["xx"], 1.0);
        assert!(json["energy"]["strain_energy"].is_null());
    }

    #[test]
    fn bad_steps_are_refused_and_leave_the_history_unchanged() {
        let mut h = history();
        h.push_step(record(1.0)).unwrap();
        let e = h.push_step(record(1.0)).unwrap_err().to_string();
        assert!(
            e.starts_with("history.time") && e.contains("increase"),
            "{e}"
        );
        assert!(h.push_step(record(f64::NAN)).is_err());
        let mut r = record(2.0);
        r.probes.clear();
        assert!(h
            .push_step(r)
            .unwrap_err()
            .to_string()
            .contains("per probe"));
        let mut r = record(2.0);
        r.energy.kinetic_energy = Some(1.0);
        let e = h.push_step(r).unwrap_err().to_string();
        assert!(e.starts_with("history.energy.kinetic_energy"), "{e}");
        let mut r = record(2.0);
        r.energy.input_work = None;
        assert!(h.push_step(r).is_err());
        assert_eq!(h.len(), 1);
        h.check().unwrap();
    }

    #[test]
    fn check_finds_every_broken_invariant() {
        let mut h = history();
        for k in 0..3 {
            h.push_step(record(k as f64)).unwrap();
        }
        let mut bad = h.clone();
        bad.probes[0].velocity.pop();
        let e = bad.check().unwrap_err().to_string();
        assert!(e.starts_with("history.probes.a.velocity = 2 values"), "{e}");
        let mut bad = h.clone();
        bad.times[2] = 0.5;
        assert!(bad
            .check()
            .unwrap_err()
            .to_string()
            .starts_with("history.times[2]"));
        let mut bad = h.clone();
        bad.probes[0].stress[1].xy = f64::NAN;
        assert!(bad.check().unwrap_err().to_string().contains("finite"));
        let mut bad = h.clone();
        bad.energy.input_work.as_mut().unwrap().push(1.0);
        assert!(bad.check().is_err());
    }

    #[test]
    fn snapshots_follow_steps_and_the_mesh() {
        let mut h = history();
        let mesh = SnapshotMesh {
            regions: vec![SnapshotRegion {
                region: "r".into(),
                index: 0,
                nodes: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
                triangles: vec![[0, 1, 2]],
            }],
        };
        let sample = FieldSample {
            displacement: [0.0, 0.0],
            stress: stress(1.0),
            strain: Strain2d {
                xx: 0.0,
                yy: 0.0,
                xy: 0.0,
                zz: 0.0,
            },
        };
        assert!(h.push_snapshot(vec![vec![sample; 3]]).is_err());
        h.set_snapshot_mesh(mesh.clone()).unwrap();
        h.push_step(record(0.0)).unwrap();
        h.push_snapshot(vec![vec![sample; 3]]).unwrap();
        assert!(h.push_snapshot(vec![vec![sample; 3]]).is_err());
        h.push_step(record(1.0)).unwrap();
        assert!(h.push_snapshot(vec![vec![sample; 2]]).is_err());
        h.push_snapshot(vec![vec![sample; 3]]).unwrap();
        assert_eq!((h.snapshots[1].time, h.snapshots[1].step), (1.0, 1));
        assert!(h.set_snapshot_mesh(mesh).is_err());
        h.check().unwrap();
        let mut bad = h.clone();
        bad.snapshot_mesh.regions[0].triangles[0] = [0, 1, 3];
        assert!(bad.check().is_err());
    }

    /// The step-by-step accumulator gives the same bits as accumulate_psi over all steps
    /// (an uneven time grid, psi crossing 1 on part of a 2 x 2 square).
    #[test]
    fn damage_accumulator_is_accumulate_psi() {
        let nodes = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5]];
        let tris = vec![[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]];
        let mesh = DamageMesh::triangles(nodes, tris).unwrap();
        let times = [0.0, 0.1, 0.35, 0.4, 1.0];
        let psi = |k: usize| -> Vec<f64> {
            (0..5)
                .map(|i| 0.3 + 0.4 * k as f64 * (1.0 + i as f64) / 5.0)
                .collect()
        };
        let whole = accumulate_psi(&mesh, &times, |k| Ok(psi(k)), Execution::Serial).unwrap();
        let mut acc = DamageAccumulator::new(&mesh, Execution::Serial);
        for (k, &t) in times.iter().enumerate() {
            acc.push(&mesh, t, psi(k)).unwrap();
        }
        assert_eq!(acc.states().len(), 5);
        assert!(acc.push(&mesh, 0.5, psi(0)).is_err());
        assert!(acc.push(&mesh, 2.0, vec![0.0; 4]).is_err());
        let streamed = acc.finish(&mesh).unwrap();
        assert!(whole.damageability_time_integral > 0.0);
        assert_eq!(streamed, whole);
        let one = DamageAccumulator::new(&mesh, Execution::Serial);
        assert!(one.finish(&mesh).is_err());
    }
}
