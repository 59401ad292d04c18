//! The linear dynamic run of a 2D BEM case with `[dynamics]` (issue 13 items 3 and 4;
//! docs/user/case-bem2d-dynamics.md, docs/theory/DYNAMICS.md sec. 1.1 and 5).
//!
//! The model of the static case is solved in the Laplace domain
//! ([`tribo::dynamics::laplace::LaplaceBem`], a density per region) and convolved by
//! convolution quadrature, all steps at once ([`tribo::dynamics::cq::convolve`]: one complex
//! solve per contour frequency and stage, in parallel). The load is linear in the
//! conditions: each `[[bc]]` b contributes its own static pattern `y_b` (its values at the
//! load step's group factor, every other condition at zero, the same DOFs known) scaled by
//! its time function, `y(t) = sum_b f_b(t) y_b`
//! ([`tribo::dynamics::laplace::LaplaceBem::known_values_of`]).
//!
//! **Outputs.** Displacements at the probes and (with `fields_at` / `fields_every`) at the
//! nodes of the static field's triangulation, from the transformed Somigliana identity.
//! Velocities are the CQ of `s U(s)`: for the multistep rules exactly the rule's own
//! backward difference of the displacement sequence (`delta(zeta)/dt` is the generating
//! function of the BDF2 difference, u_(-1) = u_(-2) = 0 at rest), for Radau IIA
//! `A^-1 (U_n - 1 u_(n-1)) / dt` at the stages (the symbol `Delta(zeta)`, Lubich & Ostermann
//! 1993), the last stage the step's end. Stresses (and strains by each region's Hooke's law)
//! at the probes and the snapshot points come from the Laplace-domain interior stress
//! kernels ([`LaplaceBem::with_stress_probes`], docs/theory/DYNAMICS.md sec. 5.5), convolved
//! with the displacements; they cost about as much again per point as the displacements.
//!
//! **Energies.** The input work W of the boundary tractions, and the strain and kinetic
//! energy U, K of the bodies integrated over the field triangulation (sampled for this also
//! without snapshots; [`domain_energies`], [`tribo::dynamics::energy_domain`]) at every
//! step, with the balance W - U - K (docs/theory/DYNAMICS.md sec. 5.8).
//!
//! Field snapshot points on the boundary are evaluated as the static field sampler
//! evaluates them ([`tribo::analysis::bem_field::sample_region`], each in its own region,
//! [`LaplaceBem::with_field_points`]): a node on a segment is taken a boundary layer (1e-4
//! of an element length) inside by the Somigliana identity, a node at a segment junction (a
//! corner) from the boundary solution itself (the tractions of the sides give the whole
//! in-plane stress; Hooke's law is instantaneous, so the static rule holds at every time).
//! The strain energy of a run pressed slowly thus equals the static run's on the same
//! triangulation (docs/theory/DYNAMICS.md sec. 5.8).

use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use tribo::analysis::bem_field::{sample_region, triangulate_region, FieldSample};
use tribo::dynamics::cq::{convolve, CqGrid, CqMethod, CqParams, CqSeries, LaplaceResponse, C64};
use tribo::dynamics::history::{
    ContactSample, DynamicHistory, EnergySample, EnergyTerms, ProbeSample, SnapshotMesh,
    SnapshotRegion, StepRecord,
};
use tribo::dynamics::laplace::LaplaceBem;
use tribo::solvers::bem2d::{BemSolution, Strain2d, Stress2d};

use super::case::dynamics::{model_locator, DynamicsSpec, Method};
use super::case::BemCase;
use super::pipeline::{self, BuiltModel};
use crate::error::{CaseError, CaseResult};
use crate::progress::Progress;

/// The peaks of one probe's histories.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ProbePeak {
    /// Probe name.
    pub name: String,
    /// Largest displacement magnitude |u|, m.
    pub max_displacement: f64,
    /// Its time, s.
    pub max_displacement_time: f64,
    /// Largest velocity magnitude |v|, m/s.
    pub max_velocity: f64,
    /// Its time, s.
    pub max_velocity_time: f64,
    /// The static displacement there under the loads at their full values (the static run
    /// of the case), m.
    pub static_displacement: [f64; 2],
}

/// Timings of the dynamic run, s.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct DynamicTimings {
    /// Meshing, static operators, the load patterns and the field triangulation.
    pub setup: f64,
    /// The Laplace-domain solves and the FFTs.
    pub convolution: f64,
}

/// The result of the dynamic run of a case.
#[derive(Debug, Clone, serde::Serialize)]
pub struct DynamicOutcome {
    /// The histories (probes, snapshots, the energies W, U, K; no contact in a linear run).
    pub history: DynamicHistory,
    /// The convolution quadrature's rule.
    pub method: Method,
    /// Time step, s.
    pub time_step: f64,
    /// Number of steps.
    pub steps: usize,
    /// Duration, s.
    pub duration: f64,
    /// Laplace-domain solves (contour frequencies times stages).
    pub laplace_solves: usize,
    /// Boundary unknowns (2 per node).
    pub dof: usize,
    /// Points whose displacement is convolved (probes and snapshot points).
    pub points: usize,
    /// Peaks per probe.
    pub peaks: Vec<ProbePeak>,
    /// The damage over time (`[damage]`; [`super::dynamics_damage`]).
    pub damage: Option<super::dynamics_damage::DynamicDamageOutcome>,
    /// Timings.
    pub timings: DynamicTimings,
    /// The contact march (contact pairs or initial velocities; None for a linear run).
    pub contact: Option<super::dynamics_contact::ContactOutcome>,
}

/// The library's CQ rule of a case's method.
pub fn cq_method(m: Method) -> CqMethod {
    match m {
        Method::Bdf2 => CqMethod::Bdf2,
        Method::RadauIia2 => CqMethod::RadauIia2,
        Method::RadauIia3 => CqMethod::RadauIia3,
    }
}

/// The material name of each region of the built model (outline regions by their
/// `[[regions]]` entry, gmsh regions by their physical surface).
pub(crate) fn region_materials(case: &BemCase, built: &BuiltModel) -> CaseResult<Vec<String>> {
    built
        .model
        .regions
        .iter()
        .map(|r| {
            if let Some(spec) = case.regions.iter().find(|s| s.name == r.name) {
                return Ok(spec.material.clone());
            }
            for (m, info) in case.meshes.iter().zip(&built.meshes) {
                for (surface, names) in &info.surfaces {
                    if names.contains(&r.name) {
                        if let Some(mat) = m.materials.get(surface) {
                            return Ok(mat.clone());
                        }
                    }
                }
            }
            Err(CaseError::field(
                "regions",
                format!("{:?}", r.name),
                "has no material known to the dynamic run",
            ))
        })
        .collect()
}

/// The convolution in a scoped thread, the progress advanced from this one as the
/// Laplace-domain solves complete.
struct Counted<'a> {
    bem: &'a LaplaceBem,
    done: &'a AtomicUsize,
}

impl LaplaceResponse for Counted<'_> {
    fn inputs(&self) -> usize {
        self.bem.inputs()
    }
    fn outputs(&self) -> usize {
        LaplaceResponse::outputs(self.bem)
    }
    fn respond(&self, s: C64, inputs: &[C64]) -> tribo::Result<Vec<C64>> {
        let out = self.bem.respond(s, inputs);
        self.done.fetch_add(1, Ordering::Relaxed);
        out
    }
}

/// The velocity of the displacement samples `u` (one channel; entry-major samples of
/// `grid`) consistent with the CQ of `s U(s)` (module docs), at every sample.
pub fn cq_velocity(grid: &CqGrid, u: &[f64]) -> Vec<f64> {
    let dt = grid.dt();
    let method = grid.method();
    match method {
        CqMethod::Bdf1 => (0..u.len())
            .map(|n| (u[n] - if n > 0 { u[n - 1] } else { 0.0 }) / dt)
            .collect(),
        CqMethod::Bdf2 => (0..u.len())
            .map(|n| {
                let at = |k: usize| n.checked_sub(k).map_or(0.0, |i| u[i]);
                (1.5 * at(0) - 2.0 * at(1) + 0.5 * at(2)) / dt
            })
            .collect(),
        _ => {
            let s = method.stages();
            let a = method.butcher_a();
            let a_inv = invert(&a, s);
            let mut v = vec![0.0; u.len()];
            for n in 0..u.len() / s {
                let prev = if n > 0 { u[n * s - 1] } else { 0.0 };
                for i in 0..s {
                    v[n * s + i] = (0..s)
                        .map(|j| a_inv[i * s + j] * (u[n * s + j] - prev))
                        .sum::<f64>()
                        / dt;
                }
            }
            v
        }
    }
}

/// The inverse of the s x s matrix `a` (row-major; Gauss-Jordan with partial pivoting; the
/// Radau IIA matrices are well conditioned, s <= 3).
fn invert(a: &[f64], s: usize) -> Vec<f64> {
    let mut m: Vec<f64> = a.to_vec();
    let mut inv = vec![0.0; s * s];
    for i in 0..s {
        inv[i * s + i] = 1.0;
    }
    for c in 0..s {
        let p = (c..s)
            .max_by(|&x, &y| m[x * s + c].abs().total_cmp(&m[y * s + c].abs()))
            .unwrap_or(c);
        for k in 0..s {
            m.swap(c * s + k, p * s + k);
            inv.swap(c * s + k, p * s + k);
        }
        let d = m[c * s + c];
        for k in 0..s {
            m[c * s + k] /= d;
            inv[c * s + k] /= d;
        }
        for r in 0..s {
            if r != c {
                let f = m[r * s + c];
                for k in 0..s {
                    m[r * s + k] -= f * m[c * s + k];
                    inv[r * s + k] -= f * inv[c * s + k];
                }
            }
        }
    }
    inv
}

/// Runs the linear dynamic analysis of `case` (its `[dynamics]`) on the model `built`;
/// `statics` (the static run's solution, the same model; None for an impact) gives each
/// probe's static
/// displacement. With contact pairs or initial velocities the case marches instead
/// ([`super::dynamics_contact::run`]).
pub fn run(
    case: &BemCase,
    spec: &DynamicsSpec,
    built: &BuiltModel,
    statics: Option<&BemSolution>,
    progress: &mut dyn Progress,
) -> CaseResult<DynamicOutcome> {
    for note in &spec.notes {
        progress.note(note);
    }
    if super::dynamics_contact::marches(case, spec) {
        return super::dynamics_contact::run(case, spec, built, statics, progress);
    }
    let t0 = Instant::now();
    progress.stage("dynamics: Laplace-domain model and load patterns", None);
    check_probes(spec, built)?;
    let materials = region_materials(case, built)?;
    let densities: Vec<f64> = materials.iter().map(|m| spec.densities[m]).collect();
    let factors = &case.steps[0].factors;
    let all = pipeline::scaled_conditions(case, built, factors, &|_| 1.0)?;
    // The field triangulation always: the strain and kinetic energies integrate over it.
    let (output, snapshot) = output_points_with(case, spec, built, true)?;
    // Stresses at every point (probes and snapshot points): three more outputs each.
    let bem = recovery_bem(built, &densities, &all, &output)?;
    let points = output.points;
    let mut patterns = Vec::with_capacity(case.bcs.len());
    for b in 0..case.bcs.len() {
        let only = pipeline::scaled_conditions(case, built, factors, &|k| {
            if k == b {
                1.0
            } else {
                0.0
            }
        })?;
        patterns.push(bem.known_values_of(&only)?);
    }
    let grid = CqGrid::new(cq_method(spec.method), spec.time_step, spec.steps)?;
    let times = grid.sample_times();
    let ni = bem.inputs();
    let mut data = vec![0.0; times.len() * ni];
    for (k, &t) in times.iter().enumerate() {
        let row = &mut data[k * ni..(k + 1) * ni];
        for (pattern, f) in patterns.iter().zip(&spec.bc_time) {
            let ft = f.value(t);
            if ft != 0.0 {
                for (d, p) in row.iter_mut().zip(pattern) {
                    *d += ft * p;
                }
            }
        }
    }
    let setup = t0.elapsed().as_secs_f64();
    let t1 = Instant::now();
    let (series, solves) = convolve_counted(&bem, &grid, &data, spec.steps, progress)?;
    let convolution = t1.elapsed().as_secs_f64();
    let history = DynamicHistory::new(
        spec.probes.iter().map(|p| (p.name.clone(), p.at)).collect(),
        Vec::new(),
        EnergyTerms {
            input_work: true,
            strain_energy: true,
            kinetic_energy: true,
            ..EnergyTerms::default()
        },
    );
    let mut energy = super::dynamics_damage::energy(&bem, &data, &series)?;
    let domain = domain_energies(&bem, &series, &grid, &points, &snapshot, &densities)?;
    for (e, (u, k)) in energy.iter_mut().zip(domain) {
        e.strain_energy = Some(u);
        e.kinetic_energy = Some(k);
    }
    let mut damage = super::dynamics_damage::start(case, &snapshot, spec.probes.len(), &bem)?;
    let mut history = record(
        history,
        &Recovery {
            bem: &bem,
            series: &series,
            grid: &grid,
            points: &points,
            region_velocity: &[],
        },
        spec,
        snapshot,
        damage.as_mut(),
        &mut |n| Ok((Vec::new(), energy.get(n).copied().unwrap_or_default())),
    )?;
    let damage = damage.map(|d| d.finish(&mut history)).transpose()?;
    let peaks = probe_peaks(&history, spec, statics)?;
    Ok(DynamicOutcome {
        history,
        method: spec.method,
        time_step: spec.time_step,
        steps: spec.steps,
        duration: spec.duration,
        laplace_solves: solves,
        dof: bem.static_problem().dof(),
        points: points.len(),
        peaks,
        damage,
        timings: DynamicTimings { setup, convolution },
        contact: None,
    })
}

/// Every probe must lie in a region of the built model (gmsh regions are located there).
pub(crate) fn check_probes(spec: &DynamicsSpec, built: &BuiltModel) -> CaseResult<()> {
    let locate = model_locator(&built.model);
    for (k, p) in spec.probes.iter().enumerate() {
        if locate(p.at).is_none() {
            return Err(CaseError::field(
                format!("probe[{k}].at"),
                format!("[{:e}, {:e}]", p.at[0], p.at[1]),
                "lies outside every region of the model (a probe records the field inside a \
                 body)",
            ));
        }
    }
    Ok(())
}

/// The points whose histories are convolved: the probes, then the nodes of the static
/// field's triangulation of every sampled region (with snapshots, `[damage]`, or where
/// `always`: the domain energies; boundary nodes evaluated by the static sampler's rule,
/// module docs), each with its region (None for the probes: the first region holding
/// them), and the snapshot mesh over them.
pub(crate) fn output_points_with(
    case: &BemCase,
    spec: &DynamicsSpec,
    built: &BuiltModel,
    always: bool,
) -> CaseResult<(OutputPoints, SnapshotMesh)> {
    let mut snapshot = SnapshotMesh::default();
    let mut points: Vec<[f64; 2]> = spec.probes.iter().map(|p| p.at).collect();
    let mut regions: Vec<Option<usize>> = vec![None; points.len()];
    if always || !spec.field_steps.is_empty() || super::dynamics_damage::needs_points(case) {
        let mesh = tribo::operators::bem2d::BemMesh::new(&built.model)?;
        let size = case
            .field
            .size
            .unwrap_or_else(|| pipeline::default_field_size(&mesh));
        for r in pipeline::field_regions(case, &mesh, None)? {
            let tri = triangulate_region(&mesh, r, size)?;
            points.extend_from_slice(&tri.nodes);
            regions.extend(std::iter::repeat_n(Some(r), tri.nodes.len()));
            snapshot.regions.push(SnapshotRegion {
                region: mesh.regions[r].name.clone(),
                index: r,
                nodes: tri.nodes,
                triangles: tri.triangles,
            });
        }
    }
    Ok((OutputPoints { points, regions }, snapshot))
}

/// The points of a dynamic run's recovery ([`output_points_with`]): positions (m) and the
/// region of each (None: the first region holding it).
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct OutputPoints {
    /// Positions, m: the probes, then the snapshot nodes.
    pub points: Vec<[f64; 2]>,
    /// The region of each point.
    pub regions: Vec<Option<usize>>,
}

/// The Laplace-domain BEM of `built` with the densities, the boundary conditions `bcs` and
/// the displacement and stress probes at `points` (module docs).
pub(crate) fn recovery_bem(
    built: &BuiltModel,
    densities: &[f64],
    bcs: &tribo::solvers::bem2d::BoundaryConditions,
    points: &OutputPoints,
) -> CaseResult<LaplaceBem> {
    Ok(LaplaceBem::new(&built.model, densities, bcs, &[])?
        .with_field_points(&points.points, &points.regions)?)
}

/// The strain and kinetic energy (J/m) of the bodies at every step t_n = n dt, n =
/// 0..=steps ([`tribo::dynamics::energy_domain`]): the stresses convolved at the snapshot
/// points (the field triangulation's nodes, after the probes in `points`), the strains by
/// each region's Hooke's law, the velocities by the rule's own difference of the
/// displacements ([`cq_velocity`]); at rest before the first sample. Regions the
/// triangulation leaves out (`[field] regions`) are not integrated.
pub fn domain_energies(
    bem: &LaplaceBem,
    series: &CqSeries,
    grid: &CqGrid,
    points: &[[f64; 2]],
    snapshot: &SnapshotMesh,
    densities: &[f64],
) -> CaseResult<Vec<(f64, f64)>> {
    use tribo::dynamics::energy_domain::EnergyMesh;
    let steps = grid.steps();
    let no = series.channels;
    let first_snapshot: usize = points.len().saturating_sub(
        snapshot
            .regions
            .iter()
            .map(|r| r.nodes.len())
            .sum::<usize>(),
    );
    if snapshot.regions.is_empty() {
        return Ok(vec![(0.0, 0.0); steps + 1]);
    }
    let first_point = bem.first_stress_output() - 2 * points.len();
    let samples = grid.sample_times().len();
    // Per region: its mesh, its first point, its kernels; the velocities per point.
    let mut meshes = Vec::with_capacity(snapshot.regions.len());
    let mut start = first_snapshot;
    for r in &snapshot.regions {
        let density = densities.get(r.index).copied().ok_or_else(|| {
            CaseError::field(
                "regions",
                r.region.clone(),
                "has no density in the dynamic run",
            )
        })?;
        meshes.push((
            EnergyMesh::new(&r.nodes, &r.triangles, density)?,
            start,
            r.index,
        ));
        start += r.nodes.len();
    }
    let velocity: Vec<[Vec<f64>; 2]> = (first_snapshot..points.len())
        .map(|i| {
            [0, 1].map(|d| {
                let c = first_point + 2 * i + d;
                let u: Vec<f64> = (0..samples).map(|k| series.values[k * no + c]).collect();
                cq_velocity(grid, &u)
            })
        })
        .collect();
    let mut out = Vec::with_capacity(steps + 1);
    for n in 0..=steps {
        let Some(k) = grid.step_sample(n) else {
            out.push((0.0, 0.0));
            continue;
        };
        let stress = bem.stress_probe_values(&series.values[k * no..(k + 1) * no])?;
        let (mut u, mut kin) = (0.0, 0.0);
        for (mesh, start, region) in &meshes {
            let kernels = &bem.static_problem().mesh.regions[*region].kernels;
            let range = *start..*start + mesh.node_count();
            let s: Vec<[f64; 3]> = stress[range.clone()]
                .iter()
                .map(|s| [s.xx, s.yy, s.xy])
                .collect();
            let e: Vec<[f64; 3]> = s.iter().map(|s| kernels.strain_from_stress(*s)).collect();
            let v: Vec<[f64; 2]> = range
                .map(|i| {
                    let v = &velocity[i - first_snapshot];
                    [v[0][k], v[1][k]]
                })
                .collect();
            u += mesh.strain_energy(&s, &e)?;
            kin += mesh.kinetic_energy(&v)?;
        }
        out.push((u, kin));
    }
    Ok(out)
}

/// The end values and the worst balance of a history with input work, strain and kinetic
/// energy (the linear run's; [`tribo::dynamics::energy_domain::worst_balance`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnergyBalance {
    /// U at the end, J/m.
    pub strain_end: f64,
    /// K at the end, J/m.
    pub kinetic_end: f64,
    /// max |W - U - K - D| / max W.
    pub worst: f64,
    /// Its time, s.
    pub worst_time: f64,
}

/// The [`EnergyBalance`] of `h`; None without the three series or without input work.
pub fn energy_balance(h: &DynamicHistory) -> Option<EnergyBalance> {
    let e = &h.energy;
    let (w, u, k) = (
        e.input_work.as_deref()?,
        e.strain_energy.as_deref()?,
        e.kinetic_energy.as_deref()?,
    );
    let d = e.dissipation.as_deref().unwrap_or(&[]);
    let (worst, worst_time) = tribo::dynamics::energy_domain::worst_balance(&h.times, w, u, k, d)?;
    Some(EnergyBalance {
        strain_end: u.last().copied()?,
        kinetic_end: k.last().copied()?,
        worst,
        worst_time,
    })
}

/// The convolution of `bem` with the known values `data` (sample-major) on `grid`, in a
/// scoped thread, the progress advanced from this one as the Laplace-domain solves
/// complete; also the number of solves.
pub(crate) fn convolve_counted(
    bem: &LaplaceBem,
    grid: &CqGrid,
    data: &[f64],
    steps: usize,
    progress: &mut dyn Progress,
) -> CaseResult<(CqSeries, usize)> {
    let params = CqParams::default();
    let (l, _) = params.contour(grid.entries())?;
    let solves = (l / 2 + 1) * grid.method().stages();
    progress.stage(
        &format!(
            "dynamics: {solves} Laplace-domain solves ({} boundary unknowns, {steps} steps)",
            bem.static_problem().dof(),
        ),
        Some(solves as u64),
    );
    let done = AtomicUsize::new(0);
    let counted = Counted { bem, done: &done };
    let series = std::thread::scope(|scope| {
        let job = scope.spawn(|| convolve(&counted, grid, data, &params));
        while !job.is_finished() {
            std::thread::sleep(Duration::from_millis(50));
            progress.advance(done.load(Ordering::Relaxed) as u64);
        }
        job.join()
    })
    .map_err(|_| CaseError::field("dynamics", "(run)", "the convolution thread panicked"))??;
    progress.finish();
    Ok((series, solves))
}

/// The convolved point histories and what they belong to.
pub(crate) struct Recovery<'a> {
    /// The Laplace-domain BEM with the points as displacement and stress probes.
    pub bem: &'a LaplaceBem,
    /// Its convolved outputs.
    pub series: &'a CqSeries,
    /// The grid of the convolution.
    pub grid: &'a CqGrid,
    /// The points (probes first, then the snapshot points).
    pub points: &'a [[f64; 2]],
    /// The rigid initial velocity of each region of the model, m/s (empty: all at rest);
    /// `v t` is added to the displacements and `v` to the velocities of its points.
    pub region_velocity: &'a [[f64; 2]],
}

/// Fills `history` (created with the probes, pairs and energy terms) from the convolved
/// points at every step t_n = n dt and the snapshots at `spec.field_steps`; `per_step(n)`
/// gives the step's contact and energy samples; `damage` (a linear run's `[damage]`) takes
/// the points' stresses of every step.
pub(super) fn record(
    mut history: DynamicHistory,
    rec: &Recovery<'_>,
    spec: &DynamicsSpec,
    snapshot: SnapshotMesh,
    mut damage: Option<&mut super::dynamics_damage::DamageRun>,
    per_step: &mut dyn FnMut(usize) -> CaseResult<(Vec<ContactSample>, EnergySample)>,
) -> CaseResult<DynamicHistory> {
    let (bem, series, grid, points) = (rec.bem, rec.series, rec.grid, rec.points);
    let times = grid.sample_times();
    // The histories at the step times t_n = n dt.
    let no = series.channels;
    let first_point = if points.is_empty() {
        0
    } else {
        bem.first_stress_output() - 2 * points.len()
    };
    // The region of every point (its stress probe's), for the rigid motion.
    let velocity_of = |i: usize| -> [f64; 2] {
        bem.stress_probe_region(i)
            .and_then(|r| rec.region_velocity.get(r))
            .copied()
            .unwrap_or([0.0; 2])
    };
    // The stresses (Pa) and strains of every point at sample k (same order as `points`).
    let stresses_at = |k: usize| -> CaseResult<Vec<(Stress2d, Strain2d)>> {
        let values = bem.stress_probe_values(&series.values[k * no..(k + 1) * no])?;
        values
            .into_iter()
            .enumerate()
            .map(|(i, s)| {
                let r = bem.stress_probe_region(i).ok_or_else(|| {
                    CaseError::field("probe", format!("{i}"), "has no stress probe")
                })?;
                let kernels = &bem.static_problem().mesh.regions[r].kernels;
                let e = kernels.strain_from_stress([s.xx, s.yy, s.xy]);
                let strain = Strain2d {
                    xx: e[0],
                    yy: e[1],
                    xy: e[2],
                    zz: kernels.eps_zz(s.xx, s.yy),
                };
                Ok((s, strain))
            })
            .collect()
    };
    let channel = |c: usize| -> Vec<f64> {
        (0..times.len())
            .map(|k| series.values[k * no + c])
            .collect()
    };
    history.set_snapshot_mesh(snapshot)?;
    let mut probe_series = Vec::with_capacity(spec.probes.len());
    for k in 0..spec.probes.len() {
        let ux = channel(first_point + 2 * k);
        let uy = channel(first_point + 2 * k + 1);
        let vx = cq_velocity(grid, &ux);
        let vy = cq_velocity(grid, &uy);
        probe_series.push([ux, uy, vx, vy]);
    }
    let zero_stress = Stress2d {
        xx: 0.0,
        yy: 0.0,
        xy: 0.0,
        zz: 0.0,
    };
    let zero_strain = Strain2d {
        xx: 0.0,
        yy: 0.0,
        xy: 0.0,
        zz: 0.0,
    };
    let mut next_field = spec.field_steps.iter().peekable();
    let at_rest = vec![(zero_stress, zero_strain); points.len()];
    for n in 0..=spec.steps {
        let t = n as f64 * spec.time_step;
        let sample = grid.step_sample(n);
        // Before the first sample (t = 0 of a grid without it) the body is at rest.
        let point_stresses = match sample {
            Some(k) if !points.is_empty() => stresses_at(k)?,
            _ => at_rest.clone(),
        };
        if let Some(d) = damage.as_mut() {
            d.push(t, &point_stresses, next_field.peek() == Some(&&n))?;
        }
        let probes = probe_series
            .iter()
            .zip(&point_stresses)
            .enumerate()
            .map(|(i, ([ux, uy, vx, vy], (stress, _)))| {
                let at = |s: &Vec<f64>| sample.map_or(0.0, |k| s[k]);
                let v0 = velocity_of(i);
                ProbeSample {
                    displacement: [at(ux) + v0[0] * t, at(uy) + v0[1] * t],
                    velocity: [at(vx) + v0[0], at(vy) + v0[1]],
                    stress: *stress,
                }
            })
            .collect();
        let (contacts, energy) = per_step(n)?;
        history.push_step(StepRecord {
            time: t,
            probes,
            contacts,
            energy,
        })?;
        if next_field.peek() == Some(&&n) {
            next_field.next();
            let mut offset = first_point + 2 * spec.probes.len();
            let mut point = spec.probes.len();
            let mut samples = Vec::new();
            for r in &history.snapshot_mesh.regions {
                let values = r
                    .nodes
                    .iter()
                    .enumerate()
                    .map(|(j, _)| {
                        let c = offset + 2 * j;
                        let v0 = velocity_of(point + j);
                        let u = sample.map_or([0.0; 2], |k| {
                            [series.values[k * no + c], series.values[k * no + c + 1]]
                        });
                        let (stress, strain) = point_stresses[point + j];
                        FieldSample {
                            displacement: [u[0] + v0[0] * t, u[1] + v0[1] * t],
                            stress,
                            strain,
                        }
                    })
                    .collect::<Vec<_>>();
                offset += 2 * r.nodes.len();
                point += r.nodes.len();
                samples.push(values);
            }
            history.push_snapshot(samples)?;
        }
    }
    Ok(history)
}

/// The peaks of the probes' histories and their static displacements.
pub(crate) fn probe_peaks(
    history: &DynamicHistory,
    spec: &DynamicsSpec,
    statics: Option<&BemSolution>,
) -> CaseResult<Vec<ProbePeak>> {
    history
        .probes
        .iter()
        .zip(&spec.probes)
        .map(|(p, ps)| {
            let peak = |v: &[[f64; 2]]| {
                v.iter()
                    .zip(&history.times)
                    .map(|(x, &t)| (x[0].hypot(x[1]), t))
                    .fold((0.0, 0.0), |m, x| if x.0 > m.0 { x } else { m })
            };
            let (u, tu) = peak(&p.displacement);
            let (v, tv) = peak(&p.velocity);
            Ok(ProbePeak {
                name: p.name.clone(),
                max_displacement: u,
                max_displacement_time: tu,
                max_velocity: v,
                max_velocity_time: tv,
                static_displacement: match statics {
                    Some(st) => static_at(st, &ps.region, ps.at)?,
                    None => [0.0; 2],
                },
            })
        })
        .collect()
}

/// The static displacement at a probe (in the region the case's outlines name, else the
/// first region of the model holding it), m.
fn static_at(statics: &BemSolution, region: &str, p: [f64; 2]) -> CaseResult<[f64; 2]> {
    let mesh = statics.mesh();
    let index = mesh.regions.iter().position(|r| r.name == region);
    let candidates: Vec<usize> = match index {
        Some(i) => vec![i],
        None => (0..mesh.regions.len()).collect(),
    };
    let mut last = None;
    for r in candidates {
        match sample_region(statics, r, &[p]) {
            Ok(s) => return Ok(s[0].displacement),
            Err(e) => last = Some(e),
        }
    }
    Err(last.map_or_else(
        || CaseError::field("probe", format!("{p:?}"), "lies in no region"),
        CaseError::from,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The consistent velocity of u = t^2 (a polynomial the rules differentiate exactly
    /// beyond their start-up): BDF2 is exact for quadratics once two past values exist
    /// (n >= 2): v = 2 t; the Radau IIA stage derivative is exact for polynomials of degree
    /// <= S (stage order S), here 2 t at every stage of every step, u(0) = 0 being the rest
    /// state.
    #[test]
    fn cq_velocity_is_exact_on_quadratics() {
        for method in [CqMethod::Bdf2, CqMethod::RadauIia2, CqMethod::RadauIia3] {
            let grid = CqGrid::new(method, 0.1, 20).unwrap();
            let times = grid.sample_times();
            let u: Vec<f64> = times.iter().map(|t| t * t).collect();
            let v = cq_velocity(&grid, &u);
            let skip = if method == CqMethod::Bdf2 { 2 } else { 0 };
            for (k, (t, v)) in times.iter().zip(&v).enumerate().skip(skip) {
                assert!(
                    (v - 2.0 * t).abs() < 1e-11,
                    "{method:?} sample {k}: {v} vs {}",
                    2.0 * t
                );
            }
        }
    }
}
