//! The dynamic frictional contact run of a 2D BEM case with `[dynamics]` and `[[contact]]`
//! pairs (issue 13; docs/user/case-bem2d-dynamics.md, docs/theory/DYNAMICS.md sec. 4 and
//! 5.4).
//!
//! The case marches with [`DynamicContact`] (convolution quadrature on the condensed
//! contact compliance, one static-like active-set contact problem per step, Coulomb friction
//! of each pair; BDF2, or Radau IIA with one block problem for the S stage tractions per
//! step, docs/theory/DYNAMICS.md sec. 5.10): every `[[bc]]` scaled by its own time function on its segments (as the
//! linear run), the rigid initial velocity of a region as a closing gap. Each step gives the
//! pairs' contact length, forces and stick/slip extents and the energy balance.
//!
//! **Full state at the probes and snapshot points.** The condensed map knows only the
//! contact unknowns. The bodies are linear, so the boundary data of every step (the loads
//! at their factors and the marched contact tractions, [`DynamicContact::boundary_inputs`])
//! are convolved afterwards, all steps at once, through the Laplace-domain BEM with the
//! probes and snapshot points (the same rule, contour and time step as the march: the
//! same discrete convolution; for Radau IIA the data of every stage), plus the rigid motion `v0 t` of each region. This costs one
//! more set of Laplace-domain solves (as many as the march's weights) and is skipped where
//! there are neither probes nor snapshots; the march itself carries only the contact
//! unknowns.

use std::time::Instant;

use serde::Serialize;
use tribo::dynamics::contact::{DynamicContact, DynamicContactParams, DynamicLoad};
use tribo::dynamics::cq::CqGrid;
use tribo::dynamics::history::{DynamicHistory, EnergyTerms};
use tribo::solvers::bem2d::contact::ContactOptions;
use tribo::solvers::bem2d::BemSolution;

use super::case::dynamics::DynamicsSpec;
use super::case::BemCase;
use super::dynamics::{
    check_probes, convolve_counted, cq_method, domain_energies, output_points_with, probe_peaks,
    record, recovery_bem, region_materials, DynamicOutcome, DynamicTimings, Recovery,
};
use super::pipeline::{self, BuiltModel};
use crate::error::{CaseError, CaseResult};
use crate::progress::Progress;

/// Whether the dynamic run of `case` marches (it has contact pairs or rigid segments).
pub fn marches(case: &BemCase, _spec: &DynamicsSpec) -> bool {
    !case.pairs.is_empty() || !case.rigid.is_empty()
}

/// The peaks and times of one contact pair over the march.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PairPeaks {
    /// Slave segment.
    pub slave: String,
    /// Master segment.
    pub master: String,
    /// Coulomb friction coefficient.
    pub friction: f64,
    /// Largest normal force per unit thickness, N/m.
    pub peak_normal_force: f64,
    /// Its time, s.
    pub peak_normal_force_time: f64,
    /// Largest nodal contact pressure, Pa.
    pub peak_pressure: f64,
    /// Its time, s.
    pub peak_pressure_time: f64,
    /// Where (the slave node), m.
    pub peak_pressure_at: [f64; 2],
    /// The first step time with a positive normal force, s (None: never in contact). A
    /// node closed at zero pressure (faces touching at rest, before any load) is not
    /// contact: the pair is in contact at a step where it transmits a force.
    pub first_contact: Option<f64>,
    /// The first step time after `first_contact` with no normal force, s (None: still
    /// in contact at the end, or never in contact).
    pub first_separation: Option<f64>,
    /// `first_separation - first_contact` (to the end of the run where it does not
    /// separate; 0 where it never touches), s.
    pub contact_duration: f64,
    /// The number of steps with a positive normal force.
    pub steps_in_contact: usize,
}

/// One body (bonded regions) at the end of the march.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BodyState {
    /// Its regions.
    pub regions: Vec<String>,
    /// Mass per unit thickness, kg/m.
    pub mass: f64,
    /// Initial rigid velocity, m/s.
    pub initial_velocity: [f64; 2],
    /// Mean velocity at the end (momentum over mass), m/s (None for a body with prescribed
    /// displacements).
    pub final_velocity: Option<[f64; 2]>,
    /// Mechanical (strain + kinetic) energy at the end, J/m.
    pub final_energy: f64,
    /// Kinetic energy of its mean translation at the end, J/m (None as `final_velocity`).
    pub final_translational_energy: Option<f64>,
}

/// The energy series of the march beyond [`DynamicHistory::energy`] (J/m, one value per
/// step): what follows from boundary data (module docs of
/// [`tribo::dynamics::contact`], "Energy").
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct ContactEnergy {
    /// Mechanical energy (strain + kinetic) of all bodies: the sum of the bodies' boundary
    /// work and initial kinetic energy.
    pub mechanical: Vec<f64>,
    /// Kinetic energy of the mean translation of the bodies without prescribed
    /// displacements.
    pub translational_kinetic: Vec<f64>,
    /// Work of the normal contact tractions on the gap (<= 0: the energy the time
    /// discretisation loses when nodes close; 0 in the continuous problem).
    pub normal_contact_work: Vec<f64>,
    /// input work - mechanical - dissipation.
    pub balance: Vec<f64>,
    /// Strain energy U of the bodies, integrated over the field triangulation
    /// (docs/theory/DYNAMICS.md sec. 5.8, "The contact run").
    pub strain: Vec<f64>,
    /// Kinetic energy of the deformation: the bodies' kinetic energy less that of each
    /// free body's mean translation (docs/theory/DYNAMICS.md sec. 5.8, "The contact run").
    pub kinetic: Vec<f64>,
    /// input work - U - K - dissipation - translational kinetic energy: 0 for an exact
    /// solution; the discretisation error (time, field quadrature) and the normal contact
    /// work otherwise.
    pub domain_balance: Vec<f64>,
}

impl ContactEnergy {
    /// The columns `energy.csv` adds for a contact run (name with unit, values).
    pub fn columns(&self) -> Vec<(&'static str, &[f64])> {
        vec![
            ("mechanical_energy_J_per_m", &self.mechanical),
            ("translational_kinetic_J_per_m", &self.translational_kinetic),
            ("normal_contact_work_J_per_m", &self.normal_contact_work),
            ("balance_J_per_m", &self.balance),
            ("strain_energy_J_per_m", &self.strain),
            ("deformation_kinetic_J_per_m", &self.kinetic),
            ("domain_balance_J_per_m", &self.domain_balance),
        ]
    }
}

/// What the contact march adds to a dynamic run.
#[derive(Debug, Clone, Serialize)]
pub struct ContactOutcome {
    /// The march's contact unknowns: 2 per slave node that projects onto its master (the
    /// static model's `contact_unknowns` also count the rigid segments and the free
    /// rigid-body modes of bodies held only by contact).
    pub march_contact_unknowns: usize,
    /// Largest active-set iteration count of a step.
    pub max_iterations: usize,
    /// Largest complementarity residual of a step (relative to the largest pressure).
    pub max_residual: f64,
    /// Per pair.
    pub pairs: Vec<PairPeaks>,
    /// Per body.
    pub bodies: Vec<BodyState>,
    /// The energy series.
    pub energy: ContactEnergy,
    /// Per rigid segment (`rigid`), its translation and force at every step.
    pub rigid: Vec<super::case::rigid::RigidHistory>,
    /// The march (weights and steps), s.
    pub march_s: f64,
    /// The recovery of the probes and snapshots (0 without them), s.
    pub recovery_s: f64,
}

/// The time function of every loaded segment: each `[[bc]]` with a time function other
/// than the default (constant 1) on each of its target segments, with the origin of the
/// condition for error messages.
fn segment_loads(
    case: &BemCase,
    spec: &DynamicsSpec,
    built: &BuiltModel,
) -> CaseResult<(Vec<DynamicLoad>, Vec<String>)> {
    let constant = tribo::dynamics::time_function::TimeFunction::constant(1.0)?;
    let shapes = pipeline::segment_shapes(&built.model);
    let mut loads = Vec::new();
    let mut origins = Vec::new();
    for (b, f) in case.bcs.iter().zip(&spec.bc_time) {
        if *f == constant {
            continue;
        }
        let targets: Vec<String> = if shapes.contains_key(&b.segment) {
            vec![b.segment.clone()]
        } else if let Some(parts) = built.curves.get(&b.segment) {
            parts.clone()
        } else {
            return Err(CaseError::field(
                format!("{}.segment", b.origin),
                format!("{:?}", b.segment),
                "names no segment of the model",
            ));
        };
        for segment in targets {
            loads.push(DynamicLoad {
                segment,
                time: f.clone(),
            });
            origins.push(b.origin.clone());
        }
    }
    Ok((loads, origins))
}

/// A library error about `load[j]` renamed to the condition it comes from.
fn rename_load_error(e: tribo::Error, origins: &[String]) -> CaseError {
    if let tribo::Error::InvalidParameter { field, value, rule } = &e {
        if let Some(j) = field
            .strip_prefix("load[")
            .and_then(|r| r.split(']').next())
            .and_then(|j| j.parse::<usize>().ok())
        {
            if let Some(origin) = origins.get(j) {
                return CaseError::field(format!("{origin}.time"), value, rule);
            }
        }
    }
    CaseError::from(e)
}

/// Runs the dynamic contact analysis of `case` (its `[dynamics]` and `[[contact]]` pairs) on
/// the model `built`; `statics` (the static run's solution) gives each probe's static
/// displacement.
pub fn run(
    case: &BemCase,
    spec: &DynamicsSpec,
    built: &BuiltModel,
    statics: Option<&BemSolution>,
    progress: &mut dyn Progress,
) -> CaseResult<DynamicOutcome> {
    let t0 = Instant::now();
    progress.stage("dynamics: contact compliance and loads", None);
    check_probes(spec, built)?;
    let materials = region_materials(case, built)?;
    let densities: Vec<f64> = materials.iter().map(|m| spec.densities[m]).collect();
    let factors = &case.steps[0].factors;
    let bcs = pipeline::scaled_conditions(case, built, factors, &|_| 1.0)?;
    let (loads, origins) = segment_loads(case, spec, built)?;
    let regions = &built.model.regions;
    let velocities: Vec<[f64; 2]> = regions
        .iter()
        .map(|r| {
            spec.initial_velocity
                .get(&r.name)
                .copied()
                .unwrap_or([0.0; 2])
        })
        .collect();
    let rigid = super::case::rigid::segments(case, spec)?;
    let problem = DynamicContact::with_rigid(
        &built.model,
        &densities,
        &bcs,
        &case.pairs,
        &rigid,
        &loads,
        &velocities,
    )
    .map_err(|e| match &e {
        tribo::Error::InvalidParameter { field, value, rule }
            if field.starts_with("initial_velocity of region '") =>
        {
            let name = field
                .trim_start_matches("initial_velocity of region '")
                .trim_end_matches('\'');
            CaseError::field(format!("dynamics.initial_velocity.{name}"), value, rule)
        }
        tribo::Error::InvalidParameter { field, .. } if field.starts_with("rigid_segment[") => {
            super::case::rigid::rename_error(e, case)
        }
        _ => rename_load_error(e, &origins),
    })?;
    let setup = t0.elapsed().as_secs_f64();

    // The march, one progress tick per step.
    let params = DynamicContactParams {
        method: cq_method(spec.method),
        options: ContactOptions {
            max_iterations: case.options.max_iterations,
            tolerance: case.options.tolerance,
        },
        ..DynamicContactParams::new(spec.time_step, spec.steps)
    };
    progress.stage(
        &format!(
            "dynamics: contact march ({} nodal contact unknowns, {} boundary unknowns, {} \
             steps)",
            problem.contact_unknowns(),
            problem.bem().static_problem().dof(),
            spec.steps
        ),
        Some(spec.steps as u64 + 1),
    );
    let t1 = Instant::now();
    let sampled = problem.march_samples(&params, &mut |s| progress.advance(s.step as u64 + 1))?;
    let result = &sampled.result;
    progress.finish();
    let march_s = t1.elapsed().as_secs_f64();

    // The history: contact samples and energies per step, probes and snapshots recovered.
    let pair_names: Vec<(String, String)> = case
        .pairs
        .iter()
        .map(|p| (p.slave.clone(), p.master.clone()))
        .collect();
    let history = DynamicHistory::new(
        spec.probes.iter().map(|p| (p.name.clone(), p.at)).collect(),
        pair_names,
        EnergyTerms {
            input_work: true,
            dissipation: true,
            ..EnergyTerms::default()
        },
    );
    let mut per_step = |n: usize| {
        let s = &result.steps[n];
        Ok((s.contact_samples(), s.energy_sample()))
    };
    let t2 = Instant::now();
    // The field triangulation always: the strain and kinetic energies integrate over it.
    let (output, snapshot) = output_points_with(case, spec, built, true)?;
    let points = &output.points;
    // `[damage]`: the damage triangulation is among the points (`output_points_with`), so the
    // damage run starts with the recovery model below.
    let mut damage = None;
    let mut domain = Vec::new();
    let (history, solves, dof) = if points.is_empty() {
        let grid = CqGrid::new(params.method, spec.time_step, spec.steps)?;
        let empty = tribo::dynamics::cq::CqSeries {
            grid,
            times: grid.sample_times(),
            channels: 0,
            values: Vec::new(),
        };
        let dof = problem.bem().static_problem().dof();
        let bem = problem.bem();
        let h = record(
            history,
            &Recovery {
                bem,
                series: &empty,
                grid: &grid,
                points,
                region_velocity: &velocities,
            },
            spec,
            snapshot,
            None,
            &mut per_step,
        )?;
        (h, 0, dof)
    } else {
        let bem = recovery_bem(built, &densities, problem.conditions(), &output)?;
        let ni = bem.inputs();
        if ni != problem.bem().inputs() {
            return Err(CaseError::field(
                "dynamics",
                format!("{ni} inputs vs {}", problem.bem().inputs()),
                "the recovery model's inputs differ from the march's",
            ));
        }
        let grid = CqGrid::new(params.method, spec.time_step, spec.steps)?;
        let mut data = Vec::with_capacity(grid.samples() * ni);
        for step in &sampled.samples {
            data.extend(problem.boundary_inputs(step)?);
        }
        let (series, solves) = convolve_counted(&bem, &grid, &data, spec.steps, progress)?;
        domain = domain_energies(&bem, &series, &grid, points, &snapshot, &densities)?;
        damage = super::dynamics_damage::start(case, &snapshot, spec.probes.len(), &bem)?;
        let h = record(
            history,
            &Recovery {
                bem: &bem,
                series: &series,
                grid: &grid,
                points,
                region_velocity: &velocities,
            },
            spec,
            snapshot,
            damage.as_mut(),
            &mut per_step,
        )?;
        (h, solves, bem.static_problem().dof())
    };
    let mut history = history;
    let damage = damage.map(|d| d.finish(&mut history)).transpose()?;
    let recovery_s = t2.elapsed().as_secs_f64();
    let peaks = probe_peaks(&history, spec, statics)?;
    let mut contact = summarise(case, &problem, result, built)?;
    deformation_energies(&problem, result, &domain, &mut contact.energy);
    Ok(DynamicOutcome {
        history,
        method: spec.method,
        time_step: spec.time_step,
        steps: spec.steps,
        duration: spec.duration,
        laplace_solves: solves,
        dof,
        points: points.len(),
        peaks,
        damage,
        timings: DynamicTimings {
            setup,
            convolution: march_s + recovery_s,
        },
        contact: Some(ContactOutcome {
            march_s,
            recovery_s,
            ..contact
        }),
    })
}

/// The pairs' peaks and times, the bodies at the end and the energy series.
fn summarise(
    case: &BemCase,
    problem: &DynamicContact,
    result: &tribo::dynamics::contact::DynamicContactResult,
    built: &BuiltModel,
) -> CaseResult<ContactOutcome> {
    let mut pairs: Vec<PairPeaks> = case
        .pairs
        .iter()
        .map(|p| PairPeaks {
            slave: p.slave.clone(),
            master: p.master.clone(),
            friction: p.friction,
            peak_normal_force: 0.0,
            peak_normal_force_time: 0.0,
            peak_pressure: 0.0,
            peak_pressure_time: 0.0,
            peak_pressure_at: [0.0; 2],
            first_contact: None,
            first_separation: None,
            contact_duration: 0.0,
            steps_in_contact: 0,
        })
        .collect();
    let mut energy = ContactEnergy::default();
    let mut max_residual = 0.0_f64;
    for s in &result.steps {
        max_residual = max_residual.max(s.residual);
        for (peaks, state) in pairs.iter_mut().zip(&s.pairs) {
            let sample = &state.sample;
            if sample.normal_force > peaks.peak_normal_force {
                peaks.peak_normal_force = sample.normal_force;
                peaks.peak_normal_force_time = s.time;
            }
            for node in &state.nodes {
                if node.pressure > peaks.peak_pressure {
                    peaks.peak_pressure = node.pressure;
                    peaks.peak_pressure_time = s.time;
                    peaks.peak_pressure_at = node.position;
                }
            }
            // In contact: a positive normal force (not merely closed nodes at zero
            // pressure, e.g. faces touching at rest before the load).
            let touching = sample.normal_force > 0.0;
            if touching {
                peaks.steps_in_contact += 1;
                if peaks.first_contact.is_none() {
                    peaks.first_contact = Some(s.time);
                }
            } else if peaks.first_contact.is_some() && peaks.first_separation.is_none() {
                peaks.first_separation = Some(s.time);
            }
        }
        let e = &s.energy;
        let mechanical: f64 = e.bodies.iter().map(|b| b.mechanical).sum();
        let input = e.initial_kinetic + e.external_work;
        energy.mechanical.push(mechanical);
        energy.translational_kinetic.push(
            e.bodies
                .iter()
                .filter_map(|b| b.translational_kinetic)
                .sum(),
        );
        energy.normal_contact_work.push(e.normal_contact_work);
        energy.balance.push(input - mechanical - e.dissipation);
    }
    let end = result.steps.last().map_or(0.0, |s| s.time);
    for p in &mut pairs {
        p.contact_duration = match (p.first_contact, p.first_separation) {
            (Some(a), Some(b)) => b - a,
            (Some(a), None) => end - a,
            _ => 0.0,
        };
    }
    let last = result
        .steps
        .last()
        .ok_or_else(|| CaseError::field("dynamics.steps", 0, "the march returned no step"))?;
    let velocities = problem.region_velocities();
    let bodies = problem
        .body_regions()
        .iter()
        .zip(&last.energy.bodies)
        .zip(problem.body_masses())
        .map(|((regions, e), &mass)| BodyState {
            regions: regions
                .iter()
                .map(|&r| built.model.regions[r].name.clone())
                .collect(),
            mass,
            initial_velocity: regions.first().map_or([0.0; 2], |&r| velocities[r]),
            final_velocity: e.momentum.map(|p| [p[0] / mass, p[1] / mass]),
            final_energy: e.mechanical,
            final_translational_energy: e.translational_kinetic,
        })
        .collect();
    Ok(ContactOutcome {
        march_contact_unknowns: problem.contact_unknowns(),
        max_iterations: result.max_iterations,
        max_residual,
        pairs,
        bodies,
        energy,
        rigid: super::case::rigid::histories(case, result),
        march_s: 0.0,
        recovery_s: 0.0,
    })
}

/// The strain energy U and the kinetic energy of the deformation K of the march at every
/// step into `energy` (docs/theory/DYNAMICS.md sec. 5.4 "Energy", 5.8), from `domain` (the
/// recovery's U and K_e on the field triangulation, [`domain_energies`]; empty without a
/// recovery: the series stay empty). K_e is the kinetic energy of the convolved (elastic)
/// velocities v_e, the rigid initial velocity v0 left out; the body's velocity is
/// v0 + v_e and its mean (mass-weighted) velocity V = P / m from the march's momentum, so
/// the kinetic energy relative to the mean, 1/2 int rho |v0 + v_e - V|^2, is
/// K_e - m |V - v0|^2 / 2 (int rho v_e dA = m (V - v0): the momentum balance) for a free
/// body, K_e for one with prescribed displacements (v0 = 0, no mean translation). The
/// balance W - U - K - D - K_rigid, K_rigid the translational kinetic energy |P|^2 / (2 m)
/// of the free bodies.
fn deformation_energies(
    problem: &DynamicContact,
    result: &tribo::dynamics::contact::DynamicContactResult,
    domain: &[(f64, f64)],
    energy: &mut ContactEnergy,
) {
    if domain.len() != result.steps.len() {
        return;
    }
    let masses = problem.body_masses();
    let v0: Vec<[f64; 2]> = {
        let regions = problem.region_velocities();
        problem
            .body_regions()
            .iter()
            .map(|r| r.first().map_or([0.0; 2], |&i| regions[i]))
            .collect()
    };
    for (s, &(u, ke)) in result.steps.iter().zip(domain) {
        let e = &s.energy;
        let mut k = ke;
        let mut k_rigid = 0.0;
        for ((b, &m), v0) in e.bodies.iter().zip(masses).zip(&v0) {
            if let Some(p) = b.momentum {
                let mean = [p[0] / m, p[1] / m];
                let d = [mean[0] - v0[0], mean[1] - v0[1]];
                k -= 0.5 * m * (d[0] * d[0] + d[1] * d[1]);
                k_rigid += b.translational_kinetic.unwrap_or(0.0);
            }
        }
        let input = e.initial_kinetic + e.external_work;
        energy.strain.push(u);
        energy.kinetic.push(k);
        energy
            .domain_balance
            .push(input - u - k - e.dissipation - k_rigid);
    }
}
