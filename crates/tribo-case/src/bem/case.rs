//! The case file of a 2D boundary element model (`kind = "bem2d"`): materials, regions from
//! outlines of lines and arcs (or gmsh meshes), boundary conditions per named segment and
//! direction in load groups, contact pairs, rigid (guided) segments, load steps, and the
//! field, damage and comparison outputs. See `tribo example clamp-knife-base` and
//! docs/user/case-bem2d.md.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::Value;
use tribo::analysis::damage::DamageQuantity;
use tribo::kernels::kelvin2d::PlaneCondition;
use tribo::operators::bem2d::{BodyForce, Division, Grading, LoopItem, Segment, SegmentShape};
use tribo::solvers::bem2d::contact::{ContactOptions, ContactPair, Control};
use tribo::ElasticMaterial;

use super::template;
use crate::error::{CaseError, CaseResult};
use crate::units::{count, number, quantity, show, Dim};

// ---------------------------------------------------------------- raw (serde) layer

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawBemCase {
    pub kind: String,
    pub title: Option<String>,
    pub plane: Option<String>,
    pub materials: Option<BTreeMap<String, RawMaterial>>,
    pub clamp_knife_base: Option<toml::Table>,
    pub regions: Option<Vec<RawRegion>>,
    pub mesh: Option<Vec<RawMesh>>,
    pub bc: Option<Vec<RawBc>>,
    pub contact: Option<Vec<RawPair>>,
    pub rigid: Option<Vec<String>>,
    pub steps: Option<Vec<RawStep>>,
    pub solver: Option<RawSolver>,
    pub field: Option<RawField>,
    pub damage: Option<RawDamage>,
    pub compare: Option<RawCompare>,
}

#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMaterial {
    #[serde(rename = "E")]
    pub e: Value,
    pub nu: Value,
    pub source: Option<String>,
}

#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub(super) struct RawRegion {
    pub name: String,
    pub material: String,
    pub start: Value,
    pub outline: Vec<toml::Table>,
    pub holes: Option<Vec<RawLoop>>,
    pub body_force: Option<toml::Table>,
}

#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub(super) struct RawLoop {
    pub start: Value,
    pub outline: Vec<toml::Table>,
}

#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMesh {
    pub file: PathBuf,
    pub materials: BTreeMap<String, String>,
    pub body_forces: Option<BTreeMap<String, toml::Table>>,
    pub corner_angle_deg: Option<Value>,
}

#[derive(Debug, Deserialize, Clone, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawBc {
    pub segment: String,
    pub ux: Option<Value>,
    pub uy: Option<Value>,
    pub tx: Option<Value>,
    pub ty: Option<Value>,
    pub pressure: Option<Value>,
    pub group: Option<String>,
}

#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub(super) struct RawPair {
    pub slave: String,
    pub master: String,
    pub friction: Value,
}

#[derive(Debug, Deserialize, Clone, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawStep {
    pub name: Option<String>,
    pub factors: Option<toml::Table>,
    pub rigid: Option<toml::Table>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSolver {
    pub max_iterations: Option<Value>,
    pub tolerance: Option<Value>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawField {
    pub size: Option<Value>,
    pub regions: Option<Vec<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawDamage {
    pub region: String,
    pub quantity: Option<String>,
    pub limit: Value,
    pub sweep: Option<RawSweep>,
    pub step: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSweep {
    pub from: Value,
    pub to: Value,
    pub points: Value,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawCompare {
    pub region: String,
    pub materials: Vec<String>,
}

// ---------------------------------------------------------------- validated layer

/// A region built from outlines: geometry and the name of its material.
#[derive(Debug, Clone)]
pub struct RegionSpec {
    /// Region name.
    pub name: String,
    /// Material name (a key of [`BemCase::materials`]).
    pub material: String,
    /// Loops (the first is the outer boundary, counter-clockwise; holes clockwise).
    pub loops: Vec<Vec<LoopItem>>,
    /// Body forces (gravity, rotation), the volume terms of (9)-(12).
    pub body_forces: Vec<BodyForce>,
}

/// A gmsh mesh to import.
#[derive(Debug, Clone)]
pub struct MeshSpec {
    /// The .msh file (resolved against the case file's folder).
    pub path: PathBuf,
    /// Material name by physical surface name.
    pub materials: BTreeMap<String, String>,
    /// Body forces by physical surface name (every region of the surface).
    pub body_forces: BTreeMap<String, Vec<BodyForce>>,
    /// The turn (degrees) above which a boundary has a corner (segments are cut there).
    pub corner_angle_deg: f64,
}

/// A scalar distribution along a segment, before the geometry is known.
#[derive(Debug, Clone, PartialEq)]
pub enum ProfileSpec {
    /// Uniform.
    Uniform(f64),
    /// Linear from the segment's start to its end.
    Linear(f64, f64),
    /// Tabulated against the fraction t in [0, 1] of the segment's length from its start,
    /// linear in between (t increasing).
    Table(Vec<(f64, f64)>),
}

/// What one direction of a boundary condition prescribes.
#[derive(Debug, Clone, PartialEq)]
pub enum ComponentSpec {
    /// Displacement, m.
    Displacement(ProfileSpec),
    /// Traction, Pa.
    Traction(ProfileSpec),
}

/// One boundary condition.
#[derive(Debug, Clone, PartialEq)]
pub enum BcKind {
    /// Per direction.
    Components(ComponentSpec, ComponentSpec),
    /// Normal pressure, Pa (compressive positive).
    Pressure(ProfileSpec),
}

/// A boundary condition of a named segment in a load group.
#[derive(Debug, Clone, PartialEq)]
pub struct BcSpec {
    /// Segment name.
    pub segment: String,
    /// The condition.
    pub kind: BcKind,
    /// Load group (None: permanent, factor 1 in every step).
    pub group: Option<String>,
    /// Where it was written (for errors), e.g. `bc[2]`.
    pub origin: String,
}

/// One load step.
#[derive(Debug, Clone, PartialEq)]
pub struct StepSpec {
    /// Name (outputs are labelled with it).
    pub name: String,
    /// Factor of each load group (groups not listed: 0).
    pub factors: BTreeMap<String, f64>,
    /// Controls of the rigid segments: (segment, x, y).
    pub rigid: Vec<(String, Control, Control)>,
}

/// Output field settings.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldSpec {
    /// Target edge length of the interior triangles, m (None: 1/40 of the model's largest
    /// extent).
    pub size: Option<f64>,
    /// Regions sampled (None: all).
    pub regions: Option<Vec<String>>,
}

/// The damage assessment of one region.
#[derive(Debug, Clone, PartialEq)]
pub struct DamageSpec {
    /// Region assessed.
    pub region: String,
    /// The damage quantity phi (its limit makes psi = phi / phi_lim).
    pub quantity: DamageQuantity,
    /// The limit of the maps and of the comparison, in the quantity's unit.
    pub limit: f64,
    /// The sweep of the limit: from, to, points (linear).
    pub sweep: Option<(f64, f64, usize)>,
    /// The step assessed (index).
    pub step: usize,
}

/// Re-running the case with other materials of one region.
#[derive(Debug, Clone, PartialEq)]
pub struct CompareSpec {
    /// Region whose material changes.
    pub region: String,
    /// Materials (names), the first being the reference of the relative changes.
    pub materials: Vec<String>,
}

/// A validated 2D BEM case.
#[derive(Debug, Clone)]
pub struct BemCase {
    /// Title.
    pub title: String,
    /// Where the case came from.
    pub source: String,
    /// Plane strain or plane stress.
    pub plane: PlaneCondition,
    /// Materials by name.
    pub materials: BTreeMap<String, ElasticMaterial>,
    /// Where each material's values come from (optional text).
    pub material_sources: BTreeMap<String, String>,
    /// Regions from outlines.
    pub regions: Vec<RegionSpec>,
    /// Regions from gmsh files.
    pub meshes: Vec<MeshSpec>,
    /// Boundary conditions.
    pub bcs: Vec<BcSpec>,
    /// Load groups named by the conditions.
    pub groups: BTreeSet<String>,
    /// Contact pairs.
    pub pairs: Vec<ContactPair>,
    /// Rigid (guided) segments.
    pub rigid: Vec<String>,
    /// Load steps.
    pub steps: Vec<StepSpec>,
    /// Contact solver settings.
    pub options: ContactOptions,
    /// Field output.
    pub field: FieldSpec,
    /// Damage assessment.
    pub damage: Option<DamageSpec>,
    /// Material comparison.
    pub compare: Option<CompareSpec>,
    /// The template that generated the model, if any (its parameters in SI).
    pub template: Option<template::ClampKnifeBase>,
    /// The case as written (JSON), echoed in the summary.
    pub echo: serde_json::Value,
}

fn bad(
    field: impl Into<String>,
    value: impl std::fmt::Display,
    rule: impl Into<String>,
) -> CaseError {
    CaseError::field(field, value, rule)
}

/// Parse and validate the text of a `kind = "bem2d"` case.
pub fn parse(text: &str, source: &str, base_dir: &Path) -> CaseResult<BemCase> {
    let (raw, echo) = crate::case::parse_raw::<RawBemCase>(text, source)?;
    validate(raw, source, base_dir, echo)
}

fn validate(
    mut raw: RawBemCase,
    source: &str,
    base_dir: &Path,
    echo: serde_json::Value,
) -> CaseResult<BemCase> {
    if raw.kind != "bem2d" {
        return Err(bad(
            "kind",
            show(&Value::String(raw.kind.clone())),
            "must be \"bem2d\" for a boundary element case",
        ));
    }
    let plane = match raw.plane.as_deref().unwrap_or("strain") {
        "strain" => PlaneCondition::Strain,
        "stress" => PlaneCondition::Stress,
        other => {
            return Err(bad(
                "plane",
                format!("{other:?}"),
                "must be \"strain\" or \"stress\"",
            ))
        }
    };
    let mut template_params = None;
    if let Some(t) = raw.clamp_knife_base.take() {
        for (what, present) in [
            ("regions", raw.regions.is_some()),
            ("mesh", raw.mesh.is_some()),
            ("bc", raw.bc.is_some()),
            ("contact", raw.contact.is_some()),
            ("rigid", raw.rigid.is_some()),
            ("steps", raw.steps.is_some()),
        ] {
            if present {
                return Err(bad(
                    what,
                    "(given)",
                    "cannot be combined with [clamp_knife_base], which generates the model, its loads and its steps",
                ));
            }
        }
        let params = template::ClampKnifeBase::from_table(&t)?;
        let generated = params.generate();
        raw.regions = Some(generated.regions);
        raw.bc = Some(generated.bcs);
        raw.contact = Some(generated.pairs);
        raw.steps = Some(generated.steps);
        if raw.materials.is_none() {
            raw.materials = Some(BTreeMap::new());
        }
        template_params = Some(params);
    }
    // Materials.
    let raw_materials = raw.materials.ok_or_else(|| {
        bad(
            "materials",
            "(missing)",
            "a [materials.NAME] table with E and nu is required",
        )
    })?;
    let mut materials = BTreeMap::new();
    let mut material_sources = BTreeMap::new();
    for (name, m) in &raw_materials {
        let field = format!("materials.{name}");
        let e = quantity(&format!("{field}.E"), &m.e, Dim::Pressure)?;
        let nu = number(&format!("{field}.nu"), &m.nu)?;
        let mat = ElasticMaterial::named(&field, e, nu).map_err(CaseError::from)?;
        crate::units::check_modulus(&format!("{field}.E"), &m.e, e)?;
        materials.insert(name.clone(), mat);
        if let Some(s) = &m.source {
            material_sources.insert(name.clone(), s.clone());
        }
    }
    if let Some(t) = &template_params {
        for (role, name) in t.material_roles() {
            if !materials.contains_key(name) {
                return Err(bad(
                    format!("clamp_knife_base.{role}"),
                    format!("{name:?}"),
                    format!("names no material; define [materials.{name}]"),
                ));
            }
        }
    }
    // Regions from outlines.
    let raw_regions = raw.regions.unwrap_or_default();
    let mut regions = Vec::new();
    let mut owned: BTreeMap<String, SegmentShape> = BTreeMap::new();
    for (i, r) in raw_regions.iter().enumerate() {
        let field = format!("regions[{i}]");
        if r.name.trim().is_empty() {
            return Err(bad(format!("{field}.name"), "\"\"", "must not be empty"));
        }
        if !materials.contains_key(&r.material) {
            return Err(bad(
                format!("{field}.material"),
                format!("{:?}", r.material),
                format!("names no material (known: {})", join_keys(&materials)),
            ));
        }
        let mut loops = vec![parse_loop(
            &r.name, &field, &r.start, &r.outline, &mut owned,
        )?];
        for (h, hole) in r.holes.iter().flatten().enumerate() {
            let hf = format!("{field}.holes[{h}]");
            loops.push(parse_loop(
                &r.name,
                &hf,
                &hole.start,
                &hole.outline,
                &mut owned,
            )?);
        }
        let body_forces = match &r.body_force {
            None => Vec::new(),
            Some(t) => body_forces(&format!("{field}.body_force"), t)?,
        };
        regions.push(RegionSpec {
            name: r.name.clone(),
            material: r.material.clone(),
            loops,
            body_forces,
        });
    }
    // gmsh meshes.
    let mut meshes = Vec::new();
    for (i, m) in raw.mesh.unwrap_or_default().into_iter().enumerate() {
        for (surface, mat) in &m.materials {
            if !materials.contains_key(mat) {
                return Err(bad(
                    format!("mesh[{i}].materials.{surface}"),
                    format!("{mat:?}"),
                    format!("names no material (known: {})", join_keys(&materials)),
                ));
            }
        }
        let path = if m.file.is_absolute() {
            m.file.clone()
        } else {
            base_dir.join(&m.file)
        };
        let mut forces = BTreeMap::new();
        for (surface, t) in m.body_forces.iter().flatten() {
            let field = format!("mesh[{i}].body_forces.{surface}");
            if !m.materials.contains_key(surface) {
                return Err(bad(
                    field,
                    "(given)",
                    "names no surface of the mesh's materials (give the surface a material first)",
                ));
            }
            forces.insert(surface.clone(), body_forces(&field, t)?);
        }
        let corner_angle_deg = match &m.corner_angle_deg {
            None => tribo::operators::bem2d::gmsh::CORNER_ANGLE_DEG,
            Some(v) => {
                let a = number(&format!("mesh[{i}].corner_angle_deg"), v)?;
                if !(a.is_finite() && a > 0.0 && a < 180.0) {
                    return Err(bad(
                        format!("mesh[{i}].corner_angle_deg"),
                        show(v),
                        "must be in (0, 180) degrees: the turn above which a boundary has a \
                         corner (its segment is cut there)",
                    ));
                }
                a
            }
        };
        meshes.push(MeshSpec {
            path,
            materials: m.materials,
            body_forces: forces,
            corner_angle_deg,
        });
    }
    if regions.is_empty() && meshes.is_empty() {
        return Err(bad(
            "regions",
            "(none)",
            "a model needs at least one [[regions]] outline, one [[mesh]] file or a [clamp_knife_base] section",
        ));
    }
    // Boundary conditions.
    let mut bcs = Vec::new();
    let mut groups = BTreeSet::new();
    for (i, b) in raw.bc.unwrap_or_default().iter().enumerate() {
        let bc = bc_spec(&format!("bc[{i}]"), b)?;
        if let Some(g) = &bc.group {
            groups.insert(g.clone());
        }
        bcs.push(bc);
    }
    // Contact pairs.
    let mut pairs = Vec::new();
    for (i, p) in raw.contact.unwrap_or_default().iter().enumerate() {
        let f = number(&format!("contact[{i}].friction"), &p.friction)?;
        if !(f.is_finite() && f >= 0.0) {
            return Err(bad(
                format!("contact[{i}].friction"),
                f,
                "must be finite and >= 0",
            ));
        }
        pairs.push(ContactPair::new(&p.slave, &p.master, f));
    }
    let rigid = raw.rigid.unwrap_or_default();
    // Steps.
    let raw_steps = raw.steps.unwrap_or_else(|| vec![RawStep::default()]);
    if raw_steps.is_empty() {
        return Err(bad("steps", "[]", "at least one step is needed (omit [[steps]] for one step with every group at factor 1)"));
    }
    let mut steps = Vec::new();
    let mut names = BTreeSet::new();
    for (k, s) in raw_steps.iter().enumerate() {
        let field = format!("steps[{k}]");
        let name = s.name.clone().unwrap_or_else(|| format!("step{}", k + 1));
        if name.trim().is_empty() || !names.insert(name.clone()) {
            return Err(bad(
                format!("{field}.name"),
                format!("{name:?}"),
                "step names must be unique and not empty",
            ));
        }
        let mut factors = BTreeMap::new();
        match &s.factors {
            None => {
                for g in &groups {
                    factors.insert(g.clone(), 1.0);
                }
            }
            Some(t) => {
                for (g, v) in t {
                    if !groups.contains(g) {
                        return Err(bad(
                            format!("{field}.factors.{g}"),
                            show(v),
                            format!(
                                "names no load group (groups are named by the `group` of [[bc]] entries: {})",
                                if groups.is_empty() { "none".to_string() } else { groups.iter().cloned().collect::<Vec<_>>().join(", ") }
                            ),
                        ));
                    }
                    let f = number(&format!("{field}.factors.{g}"), v)?;
                    if !f.is_finite() {
                        return Err(bad(format!("{field}.factors.{g}"), f, "must be finite"));
                    }
                    factors.insert(g.clone(), f);
                }
            }
        }
        let mut controls = Vec::new();
        let given = s.rigid.clone().unwrap_or_default();
        for (seg, v) in &given {
            if !rigid.contains(seg) {
                return Err(bad(
                    format!("{field}.rigid.{seg}"),
                    show(v),
                    "names no rigid segment (declare it in `rigid = [...]`)",
                ));
            }
        }
        for seg in &rigid {
            let f = format!("{field}.rigid.{seg}");
            let Some(v) = given.get(seg) else {
                return Err(bad(
                    f,
                    "(missing)",
                    "every step must control every rigid segment: { fx or ux, fy or uy }",
                ));
            };
            let Value::Table(t) = v else {
                return Err(bad(f, show(v), "must be a table { fx or ux, fy or uy }"));
            };
            let x = control(&f, t, "fx", "ux")?;
            let y = control(&f, t, "fy", "uy")?;
            for key in t.keys() {
                if !["fx", "ux", "fy", "uy"].contains(&key.as_str()) {
                    return Err(bad(
                        format!("{f}.{key}"),
                        show(&t[key]),
                        "unknown key (fx, ux, fy, uy)",
                    ));
                }
            }
            controls.push((seg.clone(), x, y));
        }
        steps.push(StepSpec {
            name,
            factors,
            rigid: controls,
        });
    }
    // Solver.
    let mut options = ContactOptions::default();
    if let Some(s) = raw.solver {
        if let Some(v) = &s.max_iterations {
            let n = count("solver.max_iterations", v)?;
            if n == 0 {
                return Err(bad("solver.max_iterations", 0, "must be at least 1"));
            }
            options.max_iterations = n;
        }
        if let Some(v) = &s.tolerance {
            let t = number("solver.tolerance", v)?;
            if !(t.is_finite() && t > 0.0 && t < 1.0) {
                return Err(bad("solver.tolerance", t, "must be in (0, 1)"));
            }
            options.tolerance = t;
        }
    }
    // Field.
    let region_names: Vec<String> = regions.iter().map(|r| r.name.clone()).collect();
    let field = match raw.field {
        None => FieldSpec {
            size: None,
            regions: None,
        },
        Some(f) => {
            let size = match &f.size {
                Some(v) => {
                    let h = quantity("field.size", v, Dim::Length)?;
                    if !(h.is_finite() && h > 0.0) {
                        return Err(bad("field.size", show(v), "must be > 0"));
                    }
                    Some(h)
                }
                None => None,
            };
            FieldSpec {
                size,
                regions: f.regions,
            }
        }
    };
    // Damage.
    let damage = match raw.damage {
        None => None,
        Some(d) => {
            let vocabulary = crate::case::damage_vocabulary();
            let qname = d.quantity.clone().unwrap_or_else(|| "sigma_int".into());
            let Some(q) = vocabulary.iter().find(|q| q.name() == qname).copied() else {
                let known: Vec<String> = vocabulary.iter().map(|q| q.name()).collect();
                return Err(bad(
                    "damage.quantity",
                    format!("{qname:?}"),
                    format!("must be one of {}", known.join(", ")),
                ));
            };
            let dim_of = |field: &str, v: &Value| -> CaseResult<f64> {
                match q.unit() {
                    "Pa" => quantity(field, v, Dim::Pressure),
                    _ => number(field, v),
                }
            };
            let limit = dim_of("damage.limit", &d.limit)?;
            if !(limit.is_finite() && limit > 0.0) {
                return Err(bad("damage.limit", show(&d.limit), "must be > 0"));
            }
            let sweep = match &d.sweep {
                None => None,
                Some(s) => {
                    let a = dim_of("damage.sweep.from", &s.from)?;
                    let b = dim_of("damage.sweep.to", &s.to)?;
                    let n = count("damage.sweep.points", &s.points)?;
                    if !(a.is_finite() && a > 0.0 && b.is_finite() && b > a) {
                        return Err(bad(
                            "damage.sweep",
                            format!("from {a:e} to {b:e}"),
                            "needs 0 < from < to",
                        ));
                    }
                    if !(2..=1000).contains(&n) {
                        return Err(bad("damage.sweep.points", n, "must be in 2..=1000"));
                    }
                    Some((a, b, n))
                }
            };
            let step = match d.step.as_deref() {
                None | Some("last") => steps.len() - 1,
                Some(name) => steps.iter().position(|s| s.name == name).ok_or_else(|| {
                    bad(
                        "damage.step",
                        format!("{name:?}"),
                        format!(
                            "names no step (steps: {})",
                            steps
                                .iter()
                                .map(|s| s.name.as_str())
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    )
                })?,
            };
            Some(DamageSpec {
                region: d.region,
                quantity: q,
                limit,
                sweep,
                step,
            })
        }
    };
    // Comparison.
    let compare = match raw.compare {
        None => None,
        Some(c) => {
            if c.materials.len() < 2 {
                return Err(bad(
                    "compare.materials",
                    format!("{:?}", c.materials),
                    "needs at least two materials",
                ));
            }
            for (i, m) in c.materials.iter().enumerate() {
                if !materials.contains_key(m) {
                    return Err(bad(
                        format!("compare.materials[{i}]"),
                        format!("{m:?}"),
                        format!("names no material (known: {})", join_keys(&materials)),
                    ));
                }
            }
            Some(CompareSpec {
                region: c.region,
                materials: c.materials,
            })
        }
    };
    // Region names used by field, damage, comparison (gmsh regions are checked after import).
    let known_region = |name: &str| region_names.iter().any(|r| r == name) || !meshes.is_empty();
    if let Some(list) = &field.regions {
        for (i, r) in list.iter().enumerate() {
            if !known_region(r) {
                return Err(bad(
                    format!("field.regions[{i}]"),
                    format!("{r:?}"),
                    format!("names no region (regions: {})", region_names.join(", ")),
                ));
            }
        }
    }
    if let Some(d) = &damage {
        if !known_region(&d.region) {
            return Err(bad(
                "damage.region",
                format!("{:?}", d.region),
                format!("names no region (regions: {})", region_names.join(", ")),
            ));
        }
    }
    if let Some(c) = &compare {
        if !known_region(&c.region) {
            return Err(bad(
                "compare.region",
                format!("{:?}", c.region),
                format!("names no region (regions: {})", region_names.join(", ")),
            ));
        }
    }
    let title = raw.title.unwrap_or_else(|| match &template_params {
        Some(_) => "Clamp-knife-base of a harvester cutter bar (paper Sec. 7)".into(),
        None => "2D boundary element model".into(),
    });
    Ok(BemCase {
        title,
        source: source.to_string(),
        plane,
        materials,
        material_sources,
        regions,
        meshes,
        bcs,
        groups,
        pairs,
        rigid,
        steps,
        options,
        field,
        damage,
        compare,
        template: template_params,
        echo,
    })
}

fn join_keys<T>(m: &BTreeMap<String, T>) -> String {
    if m.is_empty() {
        "none".into()
    } else {
        m.keys().cloned().collect::<Vec<_>>().join(", ")
    }
}

fn point(field: &str, v: &Value) -> CaseResult<[f64; 2]> {
    match v {
        Value::Array(a) if a.len() == 2 => Ok([
            quantity(&format!("{field}[0]"), &a[0], Dim::Length)?,
            quantity(&format!("{field}[1]"), &a[1], Dim::Length)?,
        ]),
        other => Err(bad(field, show(other), "must be a point [x, y] (lengths)")),
    }
}

fn close_to(a: [f64; 2], b: [f64; 2], scale: f64) -> bool {
    (a[0] - b[0]).hypot(a[1] - b[1]) <= 1e-9 * scale
}

/// Parses one loop: each segment starts where the previous one ends (the first at `start`),
/// a shared item follows another region's segment backwards (that region must come first),
/// and the last item must end at `start` (a closed outline).
fn parse_loop(
    region: &str,
    field: &str,
    start: &Value,
    items: &[toml::Table],
    owned: &mut BTreeMap<String, SegmentShape>,
) -> CaseResult<Vec<LoopItem>> {
    if items.is_empty() {
        return Err(bad(
            format!("{field}.outline"),
            "[]",
            "an outline needs at least one segment",
        ));
    }
    let first = point(&format!("{field}.start"), start)?;
    let mut current = first;
    let mut scale = first[0].abs().max(first[1].abs());
    let mut out = Vec::new();
    for (k, t) in items.iter().enumerate() {
        let f = format!("{field}.outline[{k}]");
        if let Some(v) = t.get("shared") {
            for key in t.keys() {
                if key != "shared" {
                    return Err(bad(
                        format!("{f}.{key}"),
                        show(&t[key]),
                        "a shared item takes only `shared = \"SEGMENT\"`",
                    ));
                }
            }
            let Value::String(name) = v else {
                return Err(bad(
                    format!("{f}.shared"),
                    show(v),
                    "must be the name of an earlier region's segment",
                ));
            };
            let shape = owned.get(name).ok_or_else(|| {
                bad(format!("{f}.shared"), format!("{name:?}"), "names no segment of an earlier region (the region owning a bonded interface must come first)")
            })?;
            let (a, b) = (shape.point(0.0), shape.point(1.0));
            scale = scale.max(shape.length()).max(a[0].abs()).max(a[1].abs());
            // Traversed backwards: from the segment's end to its start.
            if !close_to(b, current, scale) {
                return Err(bad(
                    f,
                    format!("shared {name:?} runs from ({:e}, {:e}) back to ({:e}, {:e}) m", b[0], b[1], a[0], a[1]),
                    format!("region '{region}': a shared segment is followed backwards and must start where the previous item ends, at ({:e}, {:e}) m", current[0], current[1]),
                ));
            }
            out.push(LoopItem::Shared(name.clone()));
            current = a;
            continue;
        }
        for key in t.keys() {
            if ![
                "name",
                "to",
                "center",
                "clockwise",
                "elements",
                "size",
                "grading",
            ]
            .contains(&key.as_str())
            {
                return Err(bad(
                    format!("{f}.{key}"),
                    show(&t[key]),
                    "unknown key (name, to, center, clockwise, elements, size, grading; or shared)",
                ));
            }
        }
        let name = match t.get("name") {
            Some(Value::String(s)) if !s.trim().is_empty() => s.clone(),
            Some(other) => {
                return Err(bad(
                    format!("{f}.name"),
                    show(other),
                    "must be a non-empty string",
                ))
            }
            None => {
                return Err(bad(
                    format!("{f}.name"),
                    "(missing)",
                    "every segment needs a unique name",
                ))
            }
        };
        let to_value = t.get("to").ok_or_else(|| {
            bad(
                format!("{f}.to"),
                "(missing)",
                "the end point [x, y] of the segment",
            )
        })?;
        let to = point(&format!("{f}.to"), to_value)?;
        scale = scale.max(to[0].abs()).max(to[1].abs());
        let shape = match t.get("center") {
            None => {
                if let Some(c) = t.get("clockwise") {
                    return Err(bad(
                        format!("{f}.clockwise"),
                        show(c),
                        "only arcs (with `center`) have a direction",
                    ));
                }
                SegmentShape::Line {
                    start: current,
                    end: to,
                }
            }
            Some(c) => {
                let center = point(&format!("{f}.center"), c)?;
                let clockwise = match t.get("clockwise") {
                    None => false,
                    Some(Value::Boolean(b)) => *b,
                    Some(o) => {
                        return Err(bad(
                            format!("{f}.clockwise"),
                            show(o),
                            "must be true or false",
                        ))
                    }
                };
                let r0 = (current[0] - center[0]).hypot(current[1] - center[1]);
                let r1 = (to[0] - center[0]).hypot(to[1] - center[1]);
                if !(r0 > 0.0 && (r0 - r1).abs() <= 1e-9 * r0.max(r1)) {
                    return Err(bad(
                        format!("{f}.center"),
                        format!("[{:e}, {:e}]", center[0], center[1]),
                        format!("an arc's start and end must be equally far from its centre (radii {r0:e} and {r1:e} m)"),
                    ));
                }
                let a0 = (current[1] - center[1]).atan2(current[0] - center[0]);
                let mut a1 = (to[1] - center[1]).atan2(to[0] - center[0]);
                let tau = std::f64::consts::TAU;
                if clockwise {
                    while a1 >= a0 - 1e-12 {
                        a1 -= tau;
                    }
                } else {
                    while a1 <= a0 + 1e-12 {
                        a1 += tau;
                    }
                }
                SegmentShape::Arc {
                    center,
                    radius: r0,
                    start_angle: a0,
                    end_angle: a1,
                }
            }
        };
        let division = match (t.get("elements"), t.get("size")) {
            (Some(_), Some(_)) => {
                return Err(bad(
                    format!("{f}.size"),
                    show(&t["size"]),
                    "give `elements` or `size`, not both",
                ))
            }
            (Some(n), None) => Division::Count(count(&format!("{f}.elements"), n)?),
            (None, Some(h)) => Division::Size(quantity(&format!("{f}.size"), h, Dim::Length)?),
            (None, None) => Division::Count(4),
        };
        let grading_rule = "grading is { both = R }, { start = R } or { end = R } (R = largest / smallest element)";
        let grading = match t.get("grading") {
            None => Grading::Uniform,
            Some(Value::Table(g)) if g.len() == 1 => {
                let (k, v) = g
                    .iter()
                    .next()
                    .ok_or_else(|| bad(format!("{f}.grading"), "{}", grading_rule))?;
                let q = number(&format!("{f}.grading.{k}"), v)?;
                match k.as_str() {
                    "both" => Grading::BothEnds(q),
                    "start" => Grading::Start(q),
                    "end" => Grading::End(q),
                    _ => return Err(bad(format!("{f}.grading.{k}"), show(v), grading_rule)),
                }
            }
            Some(other) => return Err(bad(format!("{f}.grading"), show(other), grading_rule)),
        };
        if owned.insert(name.clone(), shape.clone()).is_some() {
            return Err(bad(
                format!("{f}.name"),
                format!("{name:?}"),
                "a segment is named twice (names must be unique in the model)",
            ));
        }
        out.push(LoopItem::Segment(Segment {
            name,
            shape,
            division,
            grading,
        }));
        current = to;
    }
    if !close_to(current, first, scale) {
        return Err(bad(
            format!("{field}.outline"),
            format!("ends at ({:e}, {:e}) m", current[0], current[1]),
            format!("region '{region}': the outline is open; its last segment must end at start = ({:e}, {:e}) m", first[0], first[1]),
        ));
    }
    Ok(out)
}

fn profile(field: &str, v: &Value, dim: Dim) -> CaseResult<ProfileSpec> {
    match v {
        Value::Table(t) => {
            if let Some(l) = t.get("linear") {
                if t.len() != 1 {
                    return Err(bad(
                        field,
                        show(v),
                        "a linear profile is { linear = [start, end] }",
                    ));
                }
                match l {
                    Value::Array(a) if a.len() == 2 => Ok(ProfileSpec::Linear(
                        quantity(&format!("{field}.linear[0]"), &a[0], dim)?,
                        quantity(&format!("{field}.linear[1]"), &a[1], dim)?,
                    )),
                    other => Err(bad(
                        format!("{field}.linear"),
                        show(other),
                        "must be [value at the segment's start, value at its end]",
                    )),
                }
            } else if let Some(tab) = t.get("table") {
                if t.len() != 1 {
                    return Err(bad(
                        field,
                        show(v),
                        "a tabulated profile is { table = [[t, value], ...] }",
                    ));
                }
                let Value::Array(rows) = tab else {
                    return Err(bad(
                        format!("{field}.table"),
                        show(tab),
                        "must be [[t, value], ...] with t the fraction of the segment's length",
                    ));
                };
                let mut out = Vec::new();
                for (i, r) in rows.iter().enumerate() {
                    let f = format!("{field}.table[{i}]");
                    let Value::Array(pair) = r else {
                        return Err(bad(f, show(r), "must be [t, value]"));
                    };
                    if pair.len() != 2 {
                        return Err(bad(f, show(r), "must be [t, value]"));
                    }
                    let t = number(&format!("{f}[0]"), &pair[0])?;
                    let value = quantity(&format!("{f}[1]"), &pair[1], dim)?;
                    if !(0.0..=1.0).contains(&t)
                        || out.last().is_some_and(|&(p, _): &(f64, f64)| t <= p)
                    {
                        return Err(bad(format!("{f}[0]"), t, "t must increase within [0, 1] (the fraction of the segment's length from its start)"));
                    }
                    out.push((t, value));
                }
                if out.len() < 2 || out[0].0 != 0.0 || out[out.len() - 1].0 != 1.0 {
                    return Err(bad(
                        format!("{field}.table"),
                        show(tab),
                        "needs at least two rows, the first at t = 0 and the last at t = 1",
                    ));
                }
                Ok(ProfileSpec::Table(out))
            } else {
                Err(bad(
                    field,
                    show(v),
                    "must be a value, { linear = [start, end] } or { table = [[t, value], ...] }",
                ))
            }
        }
        other => Ok(ProfileSpec::Uniform(quantity(field, other, dim)?)),
    }
}

fn bc_spec(field: &str, b: &RawBc) -> CaseResult<BcSpec> {
    let comp =
        |name: &str, u: &Option<Value>, t: &Option<Value>| -> CaseResult<Option<ComponentSpec>> {
            match (u, t) {
            (Some(_), Some(_)) => Err(bad(
                format!("{field}.{name}"),
                "(both displacement and traction)",
                "a direction takes either a displacement (ux/uy) or a traction (tx/ty), not both",
            )),
            (Some(u), None) => Ok(Some(ComponentSpec::Displacement(profile(
                &format!("{field}.u{name}"),
                u,
                Dim::Length,
            )?))),
            (None, Some(t)) => Ok(Some(ComponentSpec::Traction(profile(
                &format!("{field}.t{name}"),
                t,
                Dim::Pressure,
            )?))),
            (None, None) => Ok(None),
        }
        };
    let x = comp("x", &b.ux, &b.tx)?;
    let y = comp("y", &b.uy, &b.ty)?;
    let kind = match (&b.pressure, x, y) {
        (Some(p), None, None) => {
            BcKind::Pressure(profile(&format!("{field}.pressure"), p, Dim::Pressure)?)
        }
        (Some(_), _, _) => {
            return Err(bad(format!("{field}.pressure"), "(with ux/uy/tx/ty)", "a normal pressure is the whole condition of the segment; do not combine it with components"));
        }
        (None, None, None) => {
            return Err(bad(field, format!("segment {:?}", b.segment), "gives no condition (ux, uy, tx, ty or pressure); a segment without condition is traction-free"));
        }
        (None, x, y) => BcKind::Components(
            x.unwrap_or(ComponentSpec::Traction(ProfileSpec::Uniform(0.0))),
            y.unwrap_or(ComponentSpec::Traction(ProfileSpec::Uniform(0.0))),
        ),
    };
    if let Some(g) = &b.group {
        if g.trim().is_empty() {
            return Err(bad(format!("{field}.group"), "\"\"", "must not be empty"));
        }
    }
    Ok(BcSpec {
        segment: b.segment.clone(),
        kind,
        group: b.group.clone(),
        origin: field.to_string(),
    })
}

fn control(field: &str, t: &toml::Table, force: &str, disp: &str) -> CaseResult<Control> {
    match (t.get(force), t.get(disp)) {
        (Some(f), None) => Ok(Control::Force(quantity(&format!("{field}.{force}"), f, Dim::LineForce)?)),
        (None, Some(u)) => Ok(Control::Displacement(quantity(&format!("{field}.{disp}"), u, Dim::Length)?)),
        _ => Err(bad(field, show(&Value::Table(t.clone())), format!("needs exactly one of {force} (force per unit thickness, N/m) and {disp} (translation, m)"))),
    }
}

/// `body_force = { density = 7850, gravity = [gx, gy], angular_velocity = w, center = [x, y] }`:
/// gravity (m/s^2) and/or rotation (rad/s about the axis through `center`), density in
/// kg/m^3 (required). The library validates the values and names the region.
fn body_forces(field: &str, t: &toml::Table) -> CaseResult<Vec<BodyForce>> {
    for key in t.keys() {
        if !["density", "gravity", "angular_velocity", "center"].contains(&key.as_str()) {
            return Err(bad(
                format!("{field}.{key}"),
                show(&t[key]),
                "unknown key (density, gravity, angular_velocity, center)",
            ));
        }
    }
    let density = match t.get("density") {
        Some(v) => number(&format!("{field}.density"), v)?,
        None => {
            return Err(bad(
                format!("{field}.density"),
                "(missing)",
                "a body force needs the density, kg/m^3",
            ))
        }
    };
    let mut out = Vec::new();
    if let Some(g) = t.get("gravity") {
        let pair = match g {
            Value::Array(a) if a.len() == 2 => [
                number(&format!("{field}.gravity[0]"), &a[0])?,
                number(&format!("{field}.gravity[1]"), &a[1])?,
            ],
            other => {
                return Err(bad(
                    format!("{field}.gravity"),
                    show(other),
                    "must be [gx, gy] in m/s^2",
                ))
            }
        };
        out.push(BodyForce::gravity(density, pair));
    }
    match (t.get("angular_velocity"), t.get("center")) {
        (Some(w), Some(c)) => {
            let w = number(&format!("{field}.angular_velocity"), w)?;
            out.push(BodyForce::centrifugal(
                density,
                w,
                point(&format!("{field}.center"), c)?,
            ));
        }
        (None, None) => {}
        _ => {
            return Err(bad(
                field,
                show(&Value::Table(t.clone())),
                "a rotation needs both angular_velocity (rad/s) and center [x, y]",
            ))
        }
    }
    if out.is_empty() {
        return Err(bad(
            field,
            show(&Value::Table(t.clone())),
            "gives no body force: add gravity = [gx, gy] and/or angular_velocity with center",
        ));
    }
    Ok(out)
}

/// Whether a parsed TOML table is a boundary element case.
pub fn is_bem(table: &toml::Table) -> bool {
    table.get("kind").and_then(Value::as_str) == Some("bem2d")
}
