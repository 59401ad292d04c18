//! The rules of a 2D BEM case, one function per section in the order of their dependencies:
//! the template, materials, regions and meshes, conditions, pairs, steps, solver, field,
//! damage, comparison, and the region names those refer to.

use std::collections::BTreeMap;
use std::path::Path;

use tribo::kernels::kelvin2d::PlaneCondition;
use tribo::operators::bem2d::SegmentShape;
use tribo::solvers::bem2d::contact::{ContactOptions, ContactPair};
use tribo::ElasticMaterial;

use super::dynamics::{self, RawTime};
use super::schema::{
    Limit, Plane, RawBemCase, RawCompare, RawDamage, RawField, RawMaterial, RawMesh, RawPair,
    RawRegion, RawSolver,
};
use super::{
    bad, conditions, join_keys, outline, BemCase, CompareSpec, DamageSpec, FieldSpec, MeshSpec,
    RegionSpec, StepSpec,
};
use crate::bem::pipeline::DamageUnit;
use crate::bem::template;
use crate::error::{CaseError, CaseResult};
use crate::units::{show, Density, Quantity};

pub(super) fn validate(
    mut raw: RawBemCase,
    source: &str,
    base_dir: &Path,
    echo: serde_json::Value,
) -> CaseResult<BemCase> {
    if raw.kind != "bem2d" {
        return Err(bad(
            "kind",
            show(&toml::Value::String(raw.kind.clone())),
            "must be \"bem2d\" for a boundary element case",
        ));
    }
    let plane = match raw.plane.as_ref().map_or(Plane::Strain, |p| p.value) {
        Plane::Strain => PlaneCondition::Strain,
        Plane::Stress => PlaneCondition::Stress,
    };
    let template_params = apply_template(&mut raw)?;
    let material_densities: BTreeMap<String, Option<Quantity<Density>>> = raw
        .materials
        .iter()
        .flatten()
        .map(|(k, m)| (k.clone(), m.density.clone()))
        .collect();
    let bc_times: Vec<(String, Option<RawTime>)> = raw
        .bc
        .iter()
        .flatten()
        .enumerate()
        .map(|(k, b)| (format!("bc[{k}]"), b.time.clone()))
        .collect();
    let (materials, material_sources) = materials(raw.materials.take(), template_params.as_ref())?;
    let regions = regions(&raw.regions.take().unwrap_or_default(), &materials)?;
    let meshes = meshes(raw.mesh.take().unwrap_or_default(), &materials, base_dir)?;
    if regions.is_empty() && meshes.is_empty() {
        return Err(bad(
            "regions",
            "(none)",
            "a model needs at least one [[regions]] outline, one [[mesh]] file or a [clamp_knife_base] section",
        ));
    }
    let (bcs, groups) = conditions::bcs(&raw.bc.take().unwrap_or_default())?;
    let pairs = pairs(&raw.contact.take().unwrap_or_default())?;
    let rigid = raw.rigid.take().unwrap_or_default();
    let rigid_times: Vec<(String, Option<RawTime>)> = raw
        .steps
        .iter()
        .flatten()
        .enumerate()
        .flat_map(|(k, s)| {
            s.rigid
                .iter()
                .flatten()
                .map(move |(seg, c)| (format!("steps[{k}].rigid.{seg}"), c.time.clone()))
        })
        .collect();
    let steps = conditions::steps(raw.steps.take(), &groups, &rigid)?;
    let options = solver(raw.solver.take())?;
    let field = field(raw.field.take())?;
    let damage = match raw.damage.take() {
        None => None,
        Some(d) => Some(damage(d, &steps)?),
    };
    let compare = match raw.compare.take() {
        None => None,
        Some(c) => Some(compare(c, &materials)?),
    };
    check_region_names(&regions, &meshes, &field, damage.as_ref(), compare.as_ref())?;
    let dynamics = {
        let locate_outlines = dynamics::outline_locator(&regions);
        let locate = |p: [f64; 2]| {
            // Probes in gmsh regions are located after the import (the pipeline).
            locate_outlines(p).or_else(|| (!meshes.is_empty()).then(String::new))
        };
        let mut region_materials: Vec<(String, String)> = regions
            .iter()
            .map(|r| (r.name.clone(), r.material.clone()))
            .collect();
        for m in &meshes {
            region_materials.extend(m.materials.iter().map(|(s, mat)| (s.clone(), mat.clone())));
        }
        let ctx = dynamics::DynamicsContext {
            densities: material_densities,
            regions: region_materials,
            bc_times,
            rigid_times,
            rigid: rigid.clone(),
            has_contact: !pairs.is_empty() || !rigid.is_empty(),
            load_steps: steps.len(),
            base_dir,
            locate: &locate,
            materials: &materials,
        };
        dynamics::validate(raw.dynamics.take(), raw.probe.take(), &ctx)?
    };
    if let Some(d) = &dynamics {
        dynamic_limits(d, &regions, &pairs, &rigid, compare.is_some())?;
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
        dynamics,
        echo,
    })
}

/// What the dynamic pipeline does not do yet, refused with the item named: rigid segments
/// with a Runge-Kutta method (the Radau march has no rigid-segment columns), `[compare]`,
/// body forces
/// (not in the Laplace-domain BEM) and initial velocities without contact pairs (a rigid-body
/// motion acts only through the contact it closes).
fn dynamic_limits(
    d: &dynamics::DynamicsSpec,
    regions: &[RegionSpec],
    pairs: &[ContactPair],
    rigid: &[String],
    compare: bool,
) -> CaseResult<()> {
    let refuse = |field: &str, value: &str, rule: &str| Err(bad(field, value, rule));
    if !rigid.is_empty() && d.method != dynamics::Method::Bdf2 {
        return refuse(
            "dynamics.method",
            d.method.name(),
            "rigid (guided) segments march with the multistep rule \"bdf2\" (their \
             translations are unknowns of each step, as the contact tractions): use \
             method = \"bdf2\" with rigid",
        );
    }
    if compare {
        return refuse(
            "dynamics",
            "(with [compare])",
            "the material comparison is a static study: remove [compare] from a dynamic case",
        );
    }
    if let Some(k) = regions.iter().position(|r| !r.body_forces.is_empty()) {
        return refuse(
            &format!("regions[{k}].body_force"),
            "(given)",
            "body forces are not supported by the dynamic (Laplace-domain) solver: remove \
             the body force or [dynamics]",
        );
    }
    if let Some(name) = d
        .initial_velocity
        .keys()
        .next()
        .filter(|_| pairs.is_empty())
    {
        return refuse(
            &format!("dynamics.initial_velocity.{name}"),
            "(given)",
            "an initial rigid-body velocity acts only through the contact it closes (an \
             impact; alone the uniform motion carries no stress): give the [[contact]] \
             pairs",
        );
    }
    Ok(())
}

/// `[clamp_knife_base]`: the template generates the regions, conditions, pairs and steps
/// (none of which may then be given).
fn apply_template(raw: &mut RawBemCase) -> CaseResult<Option<template::ClampKnifeBase>> {
    let Some(t) = raw.clamp_knife_base.take() else {
        return Ok(None);
    };
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
    let params = template::ClampKnifeBase::from_raw(&t)?;
    let generated = params.generate();
    raw.regions = Some(generated.regions);
    raw.bc = Some(generated.bcs);
    raw.contact = Some(generated.pairs);
    raw.steps = Some(generated.steps);
    if raw.materials.is_none() {
        raw.materials = Some(BTreeMap::new());
    }
    Ok(Some(params))
}

type Materials = BTreeMap<String, ElasticMaterial>;

/// `[materials.NAME]`: the elastic constants (and the template's roles name defined ones).
fn materials(
    raw: Option<BTreeMap<String, RawMaterial>>,
    template: Option<&template::ClampKnifeBase>,
) -> CaseResult<(Materials, BTreeMap<String, String>)> {
    let raw_materials = raw.ok_or_else(|| {
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
        let mat = ElasticMaterial::named(&field, m.e.si(), m.nu.si()).map_err(CaseError::from)?;
        crate::units::check_modulus(&format!("{field}.E"), m.e.written(), m.e.si())?;
        materials.insert(name.clone(), mat);
        if let Some(s) = &m.source {
            material_sources.insert(name.clone(), s.clone());
        }
    }
    if let Some(t) = template {
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
    Ok((materials, material_sources))
}

/// `[[regions]]`: named, of a defined material, with closed outlines (segment names unique
/// over the model).
fn regions(raw_regions: &[RawRegion], materials: &Materials) -> CaseResult<Vec<RegionSpec>> {
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
                format!("names no material (known: {})", join_keys(materials)),
            ));
        }
        let mut loops = vec![outline::parse_loop(
            &r.name, &field, &r.start, &r.outline, &mut owned,
        )?];
        for (h, hole) in r.holes.iter().flatten().enumerate() {
            let hf = format!("{field}.holes[{h}]");
            loops.push(outline::parse_loop(
                &r.name,
                &hf,
                &hole.start,
                &hole.outline,
                &mut owned,
            )?);
        }
        let body_forces = match &r.body_force {
            None => Vec::new(),
            Some(t) => outline::body_forces(&format!("{field}.body_force"), t)?,
        };
        regions.push(RegionSpec {
            name: r.name.clone(),
            material: r.material.clone(),
            loops,
            body_forces,
        });
    }
    Ok(regions)
}

/// `[[mesh]]`: gmsh files, their surfaces' materials and body forces, the corner angle.
fn meshes(raw: Vec<RawMesh>, materials: &Materials, base_dir: &Path) -> CaseResult<Vec<MeshSpec>> {
    let mut meshes = Vec::new();
    for (i, m) in raw.into_iter().enumerate() {
        for (surface, mat) in &m.materials {
            if !materials.contains_key(mat) {
                return Err(bad(
                    format!("mesh[{i}].materials.{surface}"),
                    format!("{mat:?}"),
                    format!("names no material (known: {})", join_keys(materials)),
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
            forces.insert(surface.clone(), outline::body_forces(&field, t)?);
        }
        let corner_angle_deg = match &m.corner_angle_deg {
            None => tribo::operators::bem2d::gmsh::CORNER_ANGLE_DEG,
            Some(v) => {
                let a = v.si();
                if !(a.is_finite() && a > 0.0 && a < 180.0) {
                    return Err(bad(
                        format!("mesh[{i}].corner_angle_deg"),
                        v,
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
    Ok(meshes)
}

/// `[[contact]]`: the pairs, friction finite and >= 0.
fn pairs(raw: &[RawPair]) -> CaseResult<Vec<ContactPair>> {
    let mut pairs = Vec::new();
    for (i, p) in raw.iter().enumerate() {
        let f = p.friction.si();
        if !(f.is_finite() && f >= 0.0) {
            return Err(bad(
                format!("contact[{i}].friction"),
                f,
                "must be finite and >= 0",
            ));
        }
        pairs.push(ContactPair::new(&p.slave, &p.master, f));
    }
    Ok(pairs)
}

/// `[solver]`: at least one iteration, tolerance in (0, 1).
fn solver(raw: Option<RawSolver>) -> CaseResult<ContactOptions> {
    let mut options = ContactOptions::default();
    if let Some(s) = raw {
        if let Some(v) = &s.max_iterations {
            if v.n == 0 {
                return Err(bad("solver.max_iterations", 0, "must be at least 1"));
            }
            options.max_iterations = v.n;
        }
        if let Some(v) = &s.tolerance {
            let t = v.si();
            if !(t.is_finite() && t > 0.0 && t < 1.0) {
                return Err(bad("solver.tolerance", t, "must be in (0, 1)"));
            }
            options.tolerance = t;
        }
    }
    Ok(options)
}

/// `[field]`: the triangle size (> 0) and the regions sampled.
fn field(raw: Option<RawField>) -> CaseResult<FieldSpec> {
    let Some(f) = raw else {
        return Ok(FieldSpec {
            size: None,
            regions: None,
        });
    };
    let size = match &f.size {
        Some(v) => {
            let h = v.si();
            if !(h.is_finite() && h > 0.0) {
                return Err(bad("field.size", v, "must be > 0"));
            }
            Some(h)
        }
        None => None,
    };
    Ok(FieldSpec {
        size,
        regions: f.regions,
    })
}

/// `[damage]`: a known quantity, its limit (> 0, in the quantity's unit), the sweep of the
/// limit and the step assessed.
fn damage(d: RawDamage, steps: &[StepSpec]) -> CaseResult<DamageSpec> {
    let vocabulary = crate::halfspace::damage_vocabulary();
    let qname = d.quantity.clone().unwrap_or_else(|| "sigma_int".into());
    let Some(q) = vocabulary.iter().find(|q| q.name() == qname).copied() else {
        let known: Vec<String> = vocabulary.iter().map(|q| q.name()).collect();
        return Err(bad(
            "damage.quantity",
            format!("{qname:?}"),
            format!("must be one of {}", known.join(", ")),
        ));
    };
    let dim_of = |field: &str, v: &Limit| -> CaseResult<f64> {
        match (v, DamageUnit::of(&q)) {
            (Limit::Number(x), _) => Ok(x.si()),
            (Limit::Pressure(p), DamageUnit::Pascal) => Ok(p.si()),
            (Limit::Pressure(p), unit) => Err(bad(
                field,
                p,
                format!("must be a number (the unit of {qname} is {unit})"),
            )),
        }
    };
    let limit = dim_of("damage.limit", &d.limit)?;
    if !(limit.is_finite() && limit > 0.0) {
        return Err(bad("damage.limit", d.limit.written(), "must be > 0"));
    }
    let sweep = match &d.sweep {
        None => None,
        Some(s) => {
            let a = dim_of("damage.sweep.from", &s.from)?;
            let b = dim_of("damage.sweep.to", &s.to)?;
            let n = s.points.n;
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
    Ok(DamageSpec {
        region: d.region,
        quantity: q,
        limit,
        sweep,
        step,
    })
}

/// `[compare]`: at least two defined materials.
fn compare(c: RawCompare, materials: &Materials) -> CaseResult<CompareSpec> {
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
                format!("names no material (known: {})", join_keys(materials)),
            ));
        }
    }
    Ok(CompareSpec {
        region: c.region,
        materials: c.materials,
    })
}

/// Region names used by field, damage, comparison (gmsh regions are checked after import).
fn check_region_names(
    regions: &[RegionSpec],
    meshes: &[MeshSpec],
    field: &FieldSpec,
    damage: Option<&DamageSpec>,
    compare: Option<&CompareSpec>,
) -> CaseResult<()> {
    let region_names: Vec<String> = regions.iter().map(|r| r.name.clone()).collect();
    let known_region = |name: &str| region_names.iter().any(|r| r == name) || !meshes.is_empty();
    let unknown = |key: String, name: &str| {
        bad(
            key,
            format!("{name:?}"),
            format!("names no region (regions: {})", region_names.join(", ")),
        )
    };
    if let Some(list) = &field.regions {
        for (i, r) in list.iter().enumerate() {
            if !known_region(r) {
                return Err(unknown(format!("field.regions[{i}]"), r));
            }
        }
    }
    if let Some(d) = damage {
        if !known_region(&d.region) {
            return Err(unknown("damage.region".into(), &d.region));
        }
    }
    if let Some(c) = compare {
        if !known_region(&c.region) {
            return Err(unknown("compare.region".into(), &c.region));
        }
    }
    Ok(())
}
