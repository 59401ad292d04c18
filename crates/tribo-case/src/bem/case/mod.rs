//! The case file of a 2D boundary element model (`kind = "bem2d"`): materials, regions from
//! outlines of lines and arcs (or gmsh meshes), boundary conditions per named segment and
//! direction in load groups, contact pairs, rigid (guided) segments, load steps, and the
//! field, damage and comparison outputs. See `tribo example clamp-knife-base` and
//! docs/user/case-bem2d.md.
mod conditions;
pub mod dynamics;
mod outline;
pub mod rigid;
mod schema;
mod validate;

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use toml::Value;
use tribo::analysis::damage::DamageQuantity;
use tribo::kernels::kelvin2d::PlaneCondition;
use tribo::operators::bem2d::{BodyForce, LoopItem};
use tribo::solvers::bem2d::contact::{ContactOptions, ContactPair, Control};
use tribo::ElasticMaterial;

use super::template;
use crate::error::{CaseError, CaseResult};
pub(in crate::bem) use schema::{
    Gravity, Plane, Point, Profile, RawBc, RawBemCase, RawBodyForce, RawClampKnifeBase, RawField,
    RawGrading, RawItem, RawMaterial, RawMesh, RawPair, RawRegion, RawStep,
};

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
    /// The dynamic settings (`[dynamics]`, `[[probe]]`, the time functions and densities);
    /// None for a static case.
    pub dynamics: Option<dynamics::DynamicsSpec>,
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
    let (raw, echo) = crate::halfspace::parse_raw::<schema::RawBemCase>(text, source)?;
    validate::validate(raw, source, base_dir, echo)
}

/// Validate a case built in code (the schema's structs); the echo is the case as a file
/// would write it.
pub(in crate::bem) fn from_raw(
    raw: schema::RawBemCase,
    source: &str,
    base_dir: &Path,
) -> CaseResult<BemCase> {
    let echo = match Value::try_from(&raw) {
        Ok(v) => crate::halfspace::echo_json(&v),
        Err(e) => {
            return Err(CaseError::Parse {
                path: source.to_string(),
                message: e.to_string(),
            })
        }
    };
    validate::validate(raw, source, base_dir, echo)
}

fn join_keys<T>(m: &BTreeMap<String, T>) -> String {
    if m.is_empty() {
        "none".into()
    } else {
        m.keys().cloned().collect::<Vec<_>>().join(", ")
    }
}

/// Whether a parsed TOML table is a boundary element case.
pub fn is_bem(table: &toml::Table) -> bool {
    table.get("kind").and_then(Value::as_str) == Some("bem2d")
}
