//! The 2D BEM case file as serde reads it. Materials, solver, field and mesh settings are
//! typed ([`Quantity`], [`Count`], enums); the outlines, boundary conditions, pairs and steps
//! keep TOML values where [`super::super::template`] generates them and where the value's form
//! selects its meaning (a uniform value or a `{ linear = ... }` profile, a shared item or a
//! segment); their rules are in `outline.rs` and `conditions.rs`.

use crate::schema::{Choice, Choices, Count};
use crate::units::{Angle, Dimensionless, Length, Pressure, Quantity};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::PathBuf;
use toml::Value;

/// A plain finite number.
pub(super) type Number = Quantity<Dimensionless>;

/// `plane`: plane strain or plane stress.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(in crate::bem) enum Plane {
    Strain,
    Stress,
}

impl Choices for Plane {
    const RULE: &'static str = "must be \"strain\" or \"stress\"";
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawBemCase {
    pub kind: String,
    pub title: Option<String>,
    pub plane: Option<Choice<Plane>>,
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
pub(in crate::bem) struct RawMaterial {
    #[serde(rename = "E")]
    pub e: Quantity<Pressure>,
    pub nu: Number,
    pub source: Option<String>,
}

#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawRegion {
    pub name: String,
    pub material: String,
    pub start: Value,
    pub outline: Vec<toml::Table>,
    pub holes: Option<Vec<RawLoop>>,
    pub body_force: Option<toml::Table>,
}

#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawLoop {
    pub start: Value,
    pub outline: Vec<toml::Table>,
}

#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawMesh {
    pub file: PathBuf,
    pub materials: BTreeMap<String, String>,
    pub body_forces: Option<BTreeMap<String, toml::Table>>,
    pub corner_angle_deg: Option<Quantity<Angle>>,
}

#[derive(Debug, Deserialize, Clone, Default)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawBc {
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
pub(in crate::bem) struct RawPair {
    pub slave: String,
    pub master: String,
    pub friction: Value,
}

#[derive(Debug, Deserialize, Clone, Default)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawStep {
    pub name: Option<String>,
    pub factors: Option<toml::Table>,
    pub rigid: Option<toml::Table>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawSolver {
    pub max_iterations: Option<Count>,
    pub tolerance: Option<Number>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawField {
    pub size: Option<Quantity<Length>>,
    pub regions: Option<Vec<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawDamage {
    pub region: String,
    pub quantity: Option<String>,
    /// In the unit of the damage quantity (a rule).
    pub limit: Value,
    pub sweep: Option<RawSweep>,
    pub step: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawSweep {
    /// In the unit of the damage quantity (a rule).
    pub from: Value,
    /// In the unit of the damage quantity (a rule).
    pub to: Value,
    pub points: Count,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawCompare {
    pub region: String,
    pub materials: Vec<String>,
}
