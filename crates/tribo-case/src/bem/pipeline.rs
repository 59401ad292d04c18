//! Solving a 2D boundary element case: the model, the contact steps, the interior fields on
//! a triangulation of each region, the damage of one region and the material comparison.

use std::collections::BTreeMap;
use std::time::Instant;

use tribo::analysis::bem_field::{sample_region, triangulate_region, FieldSample};
use tribo::analysis::damage::{
    dangerous_region, DamageMesh, DamageQuantity, DangerousRegion, Execution, TensorKind,
};
use tribo::kernels::kelvin2d::PlaneCondition;
use tribo::kernels::subsurface::StressTensor;
use tribo::operators::bem2d::{gmsh, BemMesh, BemModel, LoopItem, Region, SegmentShape};
use tribo::solvers::bem2d::contact::{
    ContactProblem, FreeBodyResult, LoadStep, PairResult, RigidControl, RigidResult,
};
use tribo::solvers::bem2d::{
    BemProblem, BemSolution, BoundaryConditions, Component, Profile, SegmentBc, Stress2d,
};
use tribo::ElasticMaterial;

use super::case::{BcKind, BemCase, ComponentSpec, ProfileSpec};
use crate::error::{CaseError, CaseResult};
use crate::progress::Progress;

/// One solved step.
#[derive(Debug, Clone, serde::Serialize)]
pub struct StepOutcome {
    /// Step name.
    pub name: String,
    /// Active-set iterations (0 without contact).
    pub iterations: usize,
    /// Complementarity residual (0 without contact).
    pub residual: f64,
    /// Contact pairs.
    pub pairs: Vec<PairResult>,
    /// Rigid segments.
    pub rigid: Vec<RigidResult>,
    /// Bodies held by contact only: their rigid motion.
    pub free_bodies: Vec<FreeBodyResult>,
    /// The boundary solution.
    pub solution: BemSolution,
}

/// The field of one region: its triangulation and the samples of every step.
#[derive(Debug, Clone, serde::Serialize)]
pub struct RegionField {
    /// Region name.
    pub region: String,
    /// Region index in the mesh.
    pub index: usize,
    /// Material.
    pub material: ElasticMaterial,
    /// Triangle vertices, m.
    pub nodes: Vec<[f64; 2]>,
    /// Triangles (counter-clockwise).
    pub triangles: Vec<[usize; 3]>,
    /// Samples per step, per node.
    pub samples: Vec<Vec<FieldSample>>,
}

/// Extremes of one region in one step.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Extremes {
    /// max |sigma_xx|, Pa, and where.
    pub sigma_xx: (f64, [f64; 2]),
    /// max sigma_int (von Mises), Pa, and where.
    pub sigma_int: (f64, [f64; 2]),
    /// max |eps_xx|, and where.
    pub eps_xx: (f64, [f64; 2]),
    /// max eps_int (strain intensity), and where.
    pub eps_int: (f64, [f64; 2]),
}

/// The unit of a damage quantity's values and limits (serialized as its symbol).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum DamageUnit {
    /// Pa: stresses.
    #[serde(rename = "Pa")]
    Pascal,
    /// 1: strains.
    #[serde(rename = "1")]
    One,
    /// J/m^3: strain energy densities.
    #[serde(rename = "J/m^3")]
    JoulePerCubicMetre,
}

impl DamageUnit {
    /// The unit of `quantity` ([`DamageQuantity::unit`]'s symbol; a test checks every
    /// quantity of the vocabulary).
    pub fn of(quantity: &DamageQuantity) -> Self {
        match quantity.unit() {
            "Pa" => DamageUnit::Pascal,
            "1" => DamageUnit::One,
            _ => DamageUnit::JoulePerCubicMetre,
        }
    }

    /// Its symbol: "Pa", "1" or "J/m^3".
    pub fn symbol(self) -> &'static str {
        match self {
            DamageUnit::Pascal => "Pa",
            DamageUnit::One => "1",
            DamageUnit::JoulePerCubicMetre => "J/m^3",
        }
    }
}

impl std::fmt::Display for DamageUnit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.symbol())
    }
}

/// The damage of one region.
#[derive(Debug, Clone, serde::Serialize)]
pub struct DamageOutcome {
    /// Region.
    pub region: String,
    /// Step assessed.
    pub step: String,
    /// Quantity name (e.g. sigma_int).
    pub quantity: String,
    /// Its unit.
    pub unit: DamageUnit,
    /// The limit of the maps, in `unit`.
    pub limit: f64,
    /// psi at the field nodes of the region at `limit`.
    pub psi: Vec<f64>,
    /// Dangerous area, damageability and psi_max at `limit`.
    pub at_limit: DangerousRegion,
    /// The sweep: (limit, result).
    pub sweep: Vec<(f64, DangerousRegion)>,
}

/// Timings, s.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct Timings {
    /// Meshing, assembly, factorization and condensation.
    pub setup: f64,
    /// All load steps.
    pub steps: f64,
    /// Triangulation and field sampling.
    pub fields: f64,
    /// Damage and sweep.
    pub damage: f64,
}

/// One run of the model (the case's materials, or one material of the comparison).
#[derive(Debug, Clone, serde::Serialize)]
pub struct Variant {
    /// The material of the compared region (None: the case as written).
    pub material: Option<String>,
    /// The boundary mesh (not serialised: geometry and kernels; the fields' triangulations
    /// and the steps' solutions carry the results).
    #[serde(skip)]
    pub mesh: BemMesh,
    /// What the gmsh files gave the model.
    pub meshes: Vec<MeshImportInfo>,
    /// Boundary unknowns (2 per node).
    pub dof: usize,
    /// Contact unknowns of the condensed problem (0 without contact).
    pub contact_unknowns: usize,
    /// Steps.
    pub steps: Vec<StepOutcome>,
    /// Fields.
    pub fields: Vec<RegionField>,
    /// Damage.
    pub damage: Option<DamageOutcome>,
    /// Timings.
    pub timings: Timings,
}

/// A solved case.
#[derive(Debug, Clone, serde::Serialize)]
pub struct BemOutcome {
    /// The case as written.
    pub main: Variant,
    /// The comparison: (material name, its run), in the order of `compare.materials`.
    pub compare: Vec<(String, Variant)>,
    /// The dynamic run (`[dynamics]`); the static run above is then the response to the
    /// loads at their full values (every time function at 1), the long-time limit of
    /// steps and ramps.
    pub dynamics: Option<super::dynamics::DynamicOutcome>,
}

/// What one gmsh file gave the model (for the summary).
#[derive(Debug, Clone, serde::Serialize)]
pub struct MeshImportInfo {
    /// The file.
    pub file: String,
    /// Its format version.
    pub version: String,
    /// Geometric order of its 2D elements.
    pub order: usize,
    /// Nodes in the file.
    pub nodes: usize,
    /// 2D elements read.
    pub surface_elements: usize,
    /// Region names by physical surface.
    pub surfaces: BTreeMap<String, Vec<String>>,
    /// Segment names by boundary name (physical curves, and the generated `REGION.boundary`
    /// and `REGION_A|REGION_B` names): boundary conditions may name either.
    pub curves: BTreeMap<String, Vec<String>>,
}

/// The library model of a case and the names its gmsh files add.
#[derive(Debug, Clone)]
pub struct BuiltModel {
    /// The model.
    pub model: BemModel,
    /// Segment names by the boundary names of the gmsh files (a name cut into parts lists
    /// them all).
    pub curves: BTreeMap<String, Vec<String>>,
    /// One entry per gmsh file.
    pub meshes: Vec<MeshImportInfo>,
}

/// Builds the library model, with the material of region `swap.0` replaced by `swap.1`;
/// imports the case's gmsh files and checks the region and segment names the case uses.
pub fn model(case: &BemCase, swap: Option<(&str, &str)>) -> CaseResult<BuiltModel> {
    let material = |region: &str, name: &str| -> ElasticMaterial {
        let chosen = match swap {
            Some((r, m)) if r == region => m,
            _ => name,
        };
        case.materials[chosen]
    };
    let mut regions: Vec<Region> = case
        .regions
        .iter()
        .map(|r| Region {
            name: r.name.clone(),
            material: material(&r.name, &r.material),
            loops: r.loops.clone(),
            body_forces: r.body_forces.clone(),
        })
        .collect();
    let mut curves: BTreeMap<String, Vec<String>> = BTreeMap::new();
    let mut meshes = Vec::new();
    for (i, m) in case.meshes.iter().enumerate() {
        let field = format!("mesh[{i}].file");
        let text = std::fs::read_to_string(&m.path).map_err(|source| CaseError::Unreadable {
            field: field.clone(),
            path: m.path.clone(),
            source,
        })?;
        let lookup = |surface: &str| -> Option<ElasticMaterial> {
            m.materials.get(surface).map(|name| material(surface, name))
        };
        let options = gmsh::GmshOptions {
            corner_angle_deg: m.corner_angle_deg,
        };
        let imported = gmsh::import_msh_with(&text, &lookup, &options)
            .map_err(|e| CaseError::field(field.clone(), m.path.display(), format!("{e}")))?;
        for surface in m.materials.keys() {
            if !imported.surfaces.contains_key(surface) {
                return Err(CaseError::field(
                    format!("mesh[{i}].materials.{surface}"),
                    format!("{surface:?}"),
                    format!(
                        "names no physical surface of {} (its surfaces: {})",
                        m.path.display(),
                        imported
                            .surfaces
                            .keys()
                            .cloned()
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                ));
            }
        }
        let mut imported = imported;
        for (surface, forces) in &m.body_forces {
            for name in &imported.surfaces[surface] {
                if let Some(r) = imported.regions.iter_mut().find(|r| &r.name == name) {
                    r.body_forces.extend(forces.iter().copied());
                }
            }
        }
        for (name, parts) in &imported.curves {
            curves
                .entry(name.clone())
                .or_default()
                .extend(parts.iter().cloned());
        }
        meshes.push(MeshImportInfo {
            file: m.path.display().to_string(),
            version: imported.version.clone(),
            order: imported.order,
            nodes: imported.nodes,
            surface_elements: imported.surface_elements,
            surfaces: imported.surfaces.clone(),
            curves: imported.curves.clone(),
        });
        regions.extend(imported.regions);
    }
    let model = BemModel::new(case.plane, regions);
    let built = BuiltModel {
        model,
        curves,
        meshes,
    };
    check_names(case, &built)?;
    Ok(built)
}

/// The region names of the field, damage and comparison, and the segment names of the
/// contact pairs and rigid segments, against the built model (gmsh files add names that the
/// case parser cannot see).
fn check_names(case: &BemCase, built: &BuiltModel) -> CaseResult<()> {
    let regions: Vec<&str> = built
        .model
        .regions
        .iter()
        .map(|r| r.name.as_str())
        .collect();
    let region = |field: String, name: &str| -> CaseResult<()> {
        if regions.contains(&name) {
            return Ok(());
        }
        Err(CaseError::field(
            field,
            format!("{name:?}"),
            format!("names no region (regions: {})", regions.join(", ")),
        ))
    };
    for (i, r) in case.field.regions.iter().flatten().enumerate() {
        region(format!("field.regions[{i}]"), r)?;
    }
    if let Some(d) = &case.damage {
        region("damage.region".into(), &d.region)?;
    }
    if let Some(c) = &case.compare {
        region("compare.region".into(), &c.region)?;
    }
    // A pair or a rigid face needs one segment: a gmsh name cut into parts is refused with
    // the parts to choose from.
    let shapes = segment_shapes(&built.model);
    let single = |field: String, name: &str| -> CaseResult<()> {
        if shapes.contains_key(name) {
            return Ok(());
        }
        match built.curves.get(name) {
            Some(parts) => Err(CaseError::field(
                field,
                format!("{name:?}"),
                format!(
                    "the gmsh curve was cut into {} (at corners or where its neighbouring \
                     region changes); name one of them",
                    parts.join(", ")
                ),
            )),
            None => Ok(()),
        }
    };
    for (i, p) in case.pairs.iter().enumerate() {
        single(format!("contact[{i}].slave"), &p.slave)?;
        single(format!("contact[{i}].master"), &p.master)?;
    }
    for (i, r) in case.rigid.iter().enumerate() {
        single(format!("rigid[{i}]"), r)?;
    }
    Ok(())
}

pub(crate) fn segment_shapes(model: &BemModel) -> BTreeMap<String, SegmentShape> {
    let mut out = BTreeMap::new();
    for r in &model.regions {
        for l in &r.loops {
            for item in l {
                if let LoopItem::Segment(s) = item {
                    out.insert(s.name.clone(), s.shape.clone());
                }
            }
        }
    }
    out
}

fn library_profile(
    spec: &ProfileSpec,
    factor: f64,
    shape: Option<&SegmentShape>,
    origin: &str,
) -> CaseResult<Profile> {
    Ok(match spec {
        ProfileSpec::Uniform(v) => Profile::Uniform(factor * v),
        ProfileSpec::Linear(a, b) => Profile::Linear {
            start: factor * a,
            end: factor * b,
        },
        ProfileSpec::Table(rows) => {
            let Some(shape) = shape else {
                return Err(CaseError::field(
                    origin,
                    "table",
                    "tabulated profiles need a segment of the model",
                ));
            };
            let rows = rows.clone();
            let shape = shape.clone();
            Profile::function(move |p| {
                let t = shape.nearest_parameter(p);
                let k = rows.partition_point(|r| r.0 <= t).clamp(1, rows.len() - 1);
                let (t0, v0) = rows[k - 1];
                let (t1, v1) = rows[k];
                factor * (v0 + (v1 - v0) * (t - t0) / (t1 - t0))
            })
        }
    })
}

fn library_bc(
    kind: &BcKind,
    factor: f64,
    shape: Option<&SegmentShape>,
    origin: &str,
) -> CaseResult<SegmentBc> {
    let comp = |c: &ComponentSpec| -> CaseResult<Component> {
        Ok(match c {
            ComponentSpec::Displacement(p) => {
                Component::Displacement(library_profile(p, factor, shape, origin)?)
            }
            ComponentSpec::Traction(p) => {
                Component::Traction(library_profile(p, factor, shape, origin)?)
            }
        })
    };
    Ok(match kind {
        BcKind::Components(x, y) => SegmentBc::Components {
            x: comp(x)?,
            y: comp(y)?,
        },
        BcKind::Pressure(p) => SegmentBc::Pressure(library_profile(p, factor, shape, origin)?),
    })
}

/// The boundary conditions: with `factors` = None as load groups (for the contact solver),
/// else scaled by the step's factors (for the plain BEM solve).
fn conditions(
    case: &BemCase,
    built: &BuiltModel,
    factors: Option<&BTreeMap<String, f64>>,
) -> CaseResult<BoundaryConditions> {
    let shapes = segment_shapes(&built.model);
    let mut bcs = BoundaryConditions::new();
    for b in &case.bcs {
        // A segment, or a gmsh boundary name standing for its parts.
        let targets: Vec<&str> = if shapes.contains_key(&b.segment) {
            vec![b.segment.as_str()]
        } else if let Some(parts) = built.curves.get(&b.segment) {
            parts.iter().map(String::as_str).collect()
        } else {
            return Err(CaseError::field(
                format!("{}.segment", b.origin),
                format!("{:?}", b.segment),
                "names no segment of the model",
            ));
        };
        for segment in targets {
            let shape = shapes.get(segment);
            match (factors, &b.group) {
                (None, Some(g)) => {
                    bcs = bcs.set_in_group(segment, library_bc(&b.kind, 1.0, shape, &b.origin)?, g);
                }
                (None, None) => bcs = bcs.set(segment, library_bc(&b.kind, 1.0, shape, &b.origin)?),
                (Some(f), group) => {
                    let factor = group
                        .as_ref()
                        .map_or(1.0, |g| f.get(g).copied().unwrap_or(0.0));
                    bcs = bcs.set(segment, library_bc(&b.kind, factor, shape, &b.origin)?);
                }
            }
        }
    }
    Ok(bcs)
}

/// The boundary conditions of a dynamic run: condition b (index into `case.bcs`) at its
/// group's factor in `factors` times `scale(b)` (the same DOFs known whatever the scale).
pub(crate) fn scaled_conditions(
    case: &BemCase,
    built: &BuiltModel,
    factors: &BTreeMap<String, f64>,
    scale: &dyn Fn(usize) -> f64,
) -> CaseResult<BoundaryConditions> {
    let shapes = segment_shapes(&built.model);
    let mut bcs = BoundaryConditions::new();
    for (k, b) in case.bcs.iter().enumerate() {
        let targets: Vec<&str> = if shapes.contains_key(&b.segment) {
            vec![b.segment.as_str()]
        } else if let Some(parts) = built.curves.get(&b.segment) {
            parts.iter().map(String::as_str).collect()
        } else {
            return Err(CaseError::field(
                format!("{}.segment", b.origin),
                format!("{:?}", b.segment),
                "names no segment of the model",
            ));
        };
        let group = b
            .group
            .as_ref()
            .map_or(1.0, |g| factors.get(g).copied().unwrap_or(0.0));
        for segment in targets {
            let shape = shapes.get(segment);
            bcs = bcs.set(
                segment,
                library_bc(&b.kind, group * scale(k), shape, &b.origin)?,
            );
        }
    }
    Ok(bcs)
}

/// The default edge of the field triangles: 1/40 of the model's largest extent.
pub(crate) fn default_field_size(mesh: &BemMesh) -> f64 {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for n in mesh.regions.iter().flat_map(|r| r.nodes.iter()) {
        for d in 0..2 {
            lo[d] = lo[d].min(n.position[d]);
            hi[d] = hi[d].max(n.position[d]);
        }
    }
    let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    if extent.is_finite() && extent > 0.0 {
        extent / 40.0
    } else {
        1e-3
    }
}

/// The region names of the fields to sample.
pub(crate) fn field_regions(
    case: &BemCase,
    mesh: &BemMesh,
    only: Option<&[&str]>,
) -> CaseResult<Vec<usize>> {
    let all: Vec<String> = mesh.regions.iter().map(|r| r.name.clone()).collect();
    let wanted: Vec<String> = match (only, &case.field.regions) {
        (Some(list), _) => list.iter().map(|s| s.to_string()).collect(),
        (None, Some(list)) => list.clone(),
        (None, None) => all.clone(),
    };
    wanted
        .iter()
        .map(|w| {
            all.iter().position(|a| a == w).ok_or_else(|| {
                CaseError::field(
                    "field.regions",
                    format!("{w:?}"),
                    format!("names no region (regions: {})", all.join(", ")),
                )
            })
        })
        .collect()
}

/// The stress tensor of a 2D sample (sigma_zz from the plane condition).
pub fn tensor(s: &Stress2d) -> StressTensor {
    StressTensor::new(s.xx, s.yy, s.zz, s.xy, 0.0, 0.0)
}

/// Extremes of a region's samples.
pub fn extremes(field: &RegionField, step: usize) -> Extremes {
    let int_stress = DamageQuantity::Intensity {
        tensor: TensorKind::Stress,
    };
    let int_strain = DamageQuantity::Intensity {
        tensor: TensorKind::Strain,
    };
    let mut e = Extremes {
        sigma_xx: (0.0, [0.0; 2]),
        sigma_int: (0.0, [0.0; 2]),
        eps_xx: (0.0, [0.0; 2]),
        eps_int: (0.0, [0.0; 2]),
    };
    for (s, p) in field.samples[step].iter().zip(&field.nodes) {
        let t = tensor(&s.stress);
        let upd = |slot: &mut (f64, [f64; 2]), v: f64| {
            if v > slot.0 {
                *slot = (v, *p);
            }
        };
        upd(&mut e.sigma_xx, s.stress.xx.abs());
        upd(&mut e.sigma_int, int_stress.value(&t, &field.material));
        upd(&mut e.eps_xx, s.strain.xx.abs());
        upd(&mut e.eps_int, int_strain.value(&t, &field.material));
    }
    e
}

/// Runs the model once.
pub fn run_variant(
    case: &BemCase,
    swap: Option<(&str, &str)>,
    only_regions: Option<&[&str]>,
    progress: &mut dyn Progress,
) -> CaseResult<Variant> {
    let label = swap
        .map(|(r, m)| format!(" ({r}: {m})"))
        .unwrap_or_default();
    let t0 = Instant::now();
    let built = model(case, swap)?;
    let model = &built.model;
    progress.stage(&format!("meshing, assembling and factoring{label}"), None);
    let use_contact = !case.pairs.is_empty() || !case.rigid.is_empty();
    let mut steps = Vec::new();
    let (dof, contact_unknowns, setup, steps_time, mesh);
    if use_contact {
        let bcs = conditions(case, &built, None)?;
        let rigid: Vec<&str> = case.rigid.iter().map(String::as_str).collect();
        let mut problem = ContactProblem::new(model, &bcs, &case.pairs, &rigid)?;
        setup = t0.elapsed().as_secs_f64();
        dof = problem.bem().dof();
        contact_unknowns = problem.contact_unknowns();
        mesh = problem.bem().mesh.clone();
        progress.stage(&format!("contact steps{label}"), None);
        let load_steps: Vec<LoadStep> = case
            .steps
            .iter()
            .map(|s| {
                let mut step = LoadStep::new(1.0);
                for g in &case.groups {
                    step = step.with_group(g, s.factors.get(g).copied().unwrap_or(0.0));
                }
                for (seg, x, y) in &s.rigid {
                    step = step.with_rigid(RigidControl::new(seg, *x, *y));
                }
                step
            })
            .collect();
        let t1 = Instant::now();
        let results = problem.solve_steps(&load_steps, &case.options)?;
        steps_time = t1.elapsed().as_secs_f64();
        for (s, r) in case.steps.iter().zip(results) {
            steps.push(StepOutcome {
                name: s.name.clone(),
                iterations: r.iterations,
                residual: r.residual,
                pairs: r.pairs,
                rigid: r.rigid,
                free_bodies: r.free_bodies,
                solution: r.solution,
            });
        }
    } else {
        let problem = BemProblem::new(model)?;
        setup = t0.elapsed().as_secs_f64();
        dof = problem.dof();
        contact_unknowns = 0;
        mesh = problem.mesh.clone();
        let t1 = Instant::now();
        for s in &case.steps {
            progress.stage(&format!("step {}{label}", s.name), None);
            let bcs = conditions(case, &built, Some(&s.factors))?;
            let solution = problem.solve(&bcs)?;
            steps.push(StepOutcome {
                name: s.name.clone(),
                iterations: 0,
                residual: 0.0,
                pairs: Vec::new(),
                rigid: Vec::new(),
                free_bodies: Vec::new(),
                solution,
            });
        }
        steps_time = t1.elapsed().as_secs_f64();
    }
    progress.stage(&format!("interior fields{label}"), None);
    let t2 = Instant::now();
    let fields = region_fields(case, &mesh, &steps, only_regions)?;
    let fields_time = t2.elapsed().as_secs_f64();
    // Damage.
    let t3 = Instant::now();
    let damage = match &case.damage {
        // An impact solves no static step (its dynamic run has the damage over time).
        None => None,
        Some(_) if steps.is_empty() => None,
        Some(d) => Some(region_damage(case, d, &fields)?),
    };
    let damage_time = t3.elapsed().as_secs_f64();
    progress.finish();
    Ok(Variant {
        material: swap.map(|(_, m)| m.to_string()),
        mesh,
        meshes: built.meshes,
        dof,
        contact_unknowns,
        steps,
        fields,
        damage,
        timings: Timings {
            setup,
            steps: steps_time,
            fields: fields_time,
            damage: damage_time,
        },
    })
}

/// The interior fields of the sampled regions (`[field]`): each region triangulated and its
/// stresses and strains sampled at the nodes in every step.
fn region_fields(
    case: &BemCase,
    mesh: &BemMesh,
    steps: &[StepOutcome],
    only_regions: Option<&[&str]>,
) -> CaseResult<Vec<RegionField>> {
    let field_size = case.field.size.unwrap_or_else(|| default_field_size(mesh));
    let mut fields = Vec::new();
    for r in field_regions(case, mesh, only_regions)? {
        let tri = triangulate_region(mesh, r, field_size)?;
        let mut samples = Vec::with_capacity(steps.len());
        for s in steps {
            samples.push(sample_region(&s.solution, r, &tri.nodes)?);
        }
        fields.push(RegionField {
            region: mesh.regions[r].name.clone(),
            index: r,
            material: mesh.regions[r].material,
            nodes: tri.nodes,
            triangles: tri.triangles,
            samples,
        });
    }
    Ok(fields)
}

/// The damage of the region `d` names in its step: psi = phi / limit at the field nodes,
/// the dangerous region at the limit and over the sweep.
fn region_damage(
    case: &BemCase,
    d: &super::case::DamageSpec,
    fields: &[RegionField],
) -> CaseResult<DamageOutcome> {
    let Some(f) = fields.iter().find(|f| f.region == d.region) else {
        return Err(CaseError::field(
            "damage.region",
            format!("{:?}", d.region),
            "is not among field.regions (its field is needed)",
        ));
    };
    let dm = DamageMesh::triangles(f.nodes.clone(), f.triangles.clone())?;
    let phi: Vec<f64> = f.samples[d.step]
        .iter()
        .map(|s| d.quantity.value(&tensor(&s.stress), &f.material))
        .collect();
    let region_at = |limit: f64| -> CaseResult<(Vec<f64>, DangerousRegion)> {
        let psi: Vec<f64> = phi.iter().map(|v| v / limit).collect();
        let r = dangerous_region(&dm, &psi, Execution::Parallel)?;
        Ok((psi, r))
    };
    let (psi, at_limit) = region_at(d.limit)?;
    let mut sweep = Vec::new();
    if let Some((a, b, n)) = d.sweep {
        for k in 0..n {
            let limit = a + (b - a) * k as f64 / (n - 1) as f64;
            sweep.push((limit, region_at(limit)?.1));
        }
    }
    Ok(DamageOutcome {
        region: d.region.clone(),
        step: case.steps[d.step].name.clone(),
        quantity: d.quantity.name(),
        unit: DamageUnit::of(&d.quantity),
        limit: d.limit,
        psi,
        at_limit,
        sweep,
    })
}

/// Solves the case and its comparison.
pub fn solve(case: &BemCase, progress: &mut dyn Progress) -> CaseResult<BemOutcome> {
    // An impact (initial velocities) has no static counterpart: the static run then only
    // builds the model (no load step; its bodies may be held by nothing but the impact).
    let main = match &case.dynamics {
        Some(d) if !d.initial_velocity.is_empty() => {
            let mut bare = case.clone();
            bare.steps.clear();
            run_variant(&bare, None, None, progress)?
        }
        _ => run_variant(case, None, None, progress)?,
    };
    let mut compare = Vec::new();
    if let Some(c) = &case.compare {
        let own = main
            .mesh
            .regions
            .iter()
            .position(|r| r.name == c.region)
            .ok_or_else(|| {
                CaseError::field(
                    "compare.region",
                    format!("{:?}", c.region),
                    "names no region of the model",
                )
            })?;
        let mut only = vec![c.region.as_str()];
        if let Some(d) = &case.damage {
            if d.region != c.region {
                only.push(d.region.as_str());
            }
        }
        for m in &c.materials {
            let same = case.materials[m] == main.mesh.regions[own].material;
            let v = if same {
                // The case's own material: the main run is reused, at no extra time.
                let mut v = main.clone();
                v.material = Some(m.clone());
                v.timings = Timings::default();
                v
            } else {
                run_variant(case, Some((&c.region, m)), Some(&only), progress)?
            };
            compare.push((m.clone(), v));
        }
    }
    let dynamics = match &case.dynamics {
        None => None,
        Some(spec) => {
            let built = model(case, None)?;
            let statics = main.steps.last().map(|s| &s.solution);
            Some(super::dynamics::run(case, spec, &built, statics, progress)?)
        }
    };
    Ok(BemOutcome {
        main,
        compare,
        dynamics,
    })
}

/// The plane condition's name.
pub fn plane_name(p: PlaneCondition) -> &'static str {
    match p {
        PlaneCondition::Strain => "strain",
        PlaneCondition::Stress => "stress",
    }
}

#[cfg(test)]
mod tests {
    use super::DamageUnit;

    /// The typed unit is the library's unit of every quantity a case may assess.
    #[test]
    fn damage_units_are_the_quantities_units() {
        let vocabulary = crate::halfspace::damage_vocabulary();
        assert!(vocabulary.len() > 5);
        for q in &vocabulary {
            assert_eq!(DamageUnit::of(q).symbol(), q.unit(), "{}", q.name());
            let json = serde_json::to_value(DamageUnit::of(q)).unwrap_or_default();
            assert_eq!(json, serde_json::Value::String(q.unit().into()));
        }
    }
}
