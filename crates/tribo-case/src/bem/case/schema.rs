//! The 2D BEM case file as serde reads it: every table typed, its leaves [`Quantity`],
//! [`Count`], [`Flag`], enums, and the leaves below whose form selects their meaning (a
//! point, a profile that is a value or a `{ linear = ... }` table, a grading, a damage limit).
//! The rules (closed outlines, known names, ranges) are in `validate.rs`, `outline.rs` and
//! `conditions.rs`. [`super::super::template`] and [`super::super::builder`] build these
//! structs in code; they serialize back to the case as written (the echo of a built case).

use super::dynamics::{RawDynamics, RawProbe, RawTime};
use crate::schema::{deserialize_leaf, items, Choice, Choices, Count, Flag, FromToml, Refusal};
use crate::units::{
    Angle, Density, Dimension, Dimensionless, Length, LineForce, Pressure, Quantity,
};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::collections::BTreeMap;
use std::path::PathBuf;
use toml::Value;

/// A plain finite number.
pub(in crate::bem) type Number = Quantity<Dimensionless>;

/// `plane`: plane strain or plane stress.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub(in crate::bem) enum Plane {
    Strain,
    Stress,
}

impl Choices for Plane {
    const RULE: &'static str = "must be \"strain\" or \"stress\"";
}

#[derive(Debug, Clone, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawBemCase {
    pub kind: String,
    pub title: Option<String>,
    pub plane: Option<Choice<Plane>>,
    pub materials: Option<BTreeMap<String, RawMaterial>>,
    pub clamp_knife_base: Option<RawClampKnifeBase>,
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
    pub dynamics: Option<RawDynamics>,
    pub probe: Option<Vec<RawProbe>>,
}

#[derive(Debug, Deserialize, Serialize, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawMaterial {
    #[serde(rename = "E")]
    pub e: Quantity<Pressure>,
    pub nu: Number,
    pub source: Option<String>,
    pub density: Option<Quantity<Density>>,
}

/// `[clamp_knife_base]`: every parameter optional (the template's defaults).
#[derive(Debug, Deserialize, Serialize, Clone, Default, PartialEq)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawClampKnifeBase {
    pub knife_length: Option<Quantity<Length>>,
    pub knife_thickness: Option<Quantity<Length>>,
    pub bevel_length: Option<Quantity<Length>>,
    pub edge_thickness: Option<Quantity<Length>>,
    pub cutting_length: Option<Quantity<Length>>,
    pub base_left: Option<Quantity<Length>>,
    pub base_thickness: Option<Quantity<Length>>,
    pub clamp_left: Option<Quantity<Length>>,
    pub clamp_thickness: Option<Quantity<Length>>,
    pub bolt_center: Option<Quantity<Length>>,
    pub bolt_width: Option<Quantity<Length>>,
    pub bolt_pressure: Option<Quantity<Pressure>>,
    pub cutting_load: Option<Quantity<LineForce>>,
    pub friction: Option<Number>,
    pub contact_element_size: Option<Quantity<Length>>,
    pub element_size: Option<Quantity<Length>>,
    pub knife_material: Option<String>,
    pub clamp_material: Option<String>,
    pub base_material: Option<String>,
}

#[derive(Debug, Deserialize, Serialize, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawRegion {
    pub name: String,
    pub material: String,
    pub start: Point,
    pub outline: Vec<RawItem>,
    pub holes: Option<Vec<RawLoop>>,
    pub body_force: Option<RawBodyForce>,
}

#[derive(Debug, Deserialize, Serialize, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawLoop {
    pub start: Point,
    pub outline: Vec<RawItem>,
}

/// An item of an outline: a named line or arc (`name`, `to`, ...) or a shared segment
/// (`shared` alone; a rule).
#[derive(Debug, Deserialize, Serialize, Clone, Default, PartialEq)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawItem {
    pub shared: Option<String>,
    pub name: Option<String>,
    pub to: Option<Point>,
    pub center: Option<Point>,
    pub clockwise: Option<Flag>,
    pub elements: Option<Count>,
    pub size: Option<Quantity<Length>>,
    pub grading: Option<RawGrading>,
}

/// `body_force = { density, gravity, angular_velocity, center }`.
#[derive(Debug, Deserialize, Serialize, Clone, Default, PartialEq)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawBodyForce {
    pub density: Option<Number>,
    pub gravity: Option<Gravity>,
    pub angular_velocity: Option<Number>,
    pub center: Option<Point>,
}

#[derive(Debug, Deserialize, Serialize, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawMesh {
    pub file: PathBuf,
    pub materials: BTreeMap<String, String>,
    pub body_forces: Option<BTreeMap<String, RawBodyForce>>,
    pub corner_angle_deg: Option<Quantity<Angle>>,
}

#[derive(Debug, Deserialize, Serialize, Clone, Default, PartialEq)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawBc {
    pub segment: String,
    pub ux: Option<Profile<Length>>,
    pub uy: Option<Profile<Length>>,
    pub tx: Option<Profile<Pressure>>,
    pub ty: Option<Profile<Pressure>>,
    pub pressure: Option<Profile<Pressure>>,
    pub group: Option<String>,
    pub time: Option<RawTime>,
}

#[derive(Debug, Deserialize, Serialize, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawPair {
    pub slave: String,
    pub master: String,
    pub friction: Number,
}

#[derive(Debug, Deserialize, Serialize, Clone, Default, PartialEq)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawStep {
    pub name: Option<String>,
    pub factors: Option<BTreeMap<String, Number>>,
    pub rigid: Option<BTreeMap<String, RawControl>>,
}

/// The control of a rigid segment in a step: a force (N/m) or a translation (m) per
/// direction (exactly one of each pair: a rule).
#[derive(Debug, Deserialize, Serialize, Clone, Default, PartialEq)]
#[serde(deny_unknown_fields, expecting = "a table { fx or ux, fy or uy }")]
pub(in crate::bem) struct RawControl {
    pub fx: Option<Quantity<LineForce>>,
    pub ux: Option<Quantity<Length>>,
    pub fy: Option<Quantity<LineForce>>,
    pub uy: Option<Quantity<Length>>,
    /// The time function of the values (a dynamic case only).
    pub time: Option<RawTime>,
}

#[derive(Debug, Deserialize, Serialize, Clone, Default, PartialEq)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawSolver {
    pub max_iterations: Option<Count>,
    pub tolerance: Option<Number>,
}

#[derive(Debug, Deserialize, Serialize, Clone, Default, PartialEq)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawField {
    pub size: Option<Quantity<Length>>,
    pub regions: Option<Vec<String>>,
}

#[derive(Debug, Deserialize, Serialize, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawDamage {
    pub region: String,
    pub quantity: Option<String>,
    pub limit: Limit,
    pub sweep: Option<RawSweep>,
    pub step: Option<String>,
}

#[derive(Debug, Deserialize, Serialize, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawSweep {
    pub from: Limit,
    pub to: Limit,
    pub points: Count,
}

#[derive(Debug, Deserialize, Serialize, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub(in crate::bem) struct RawCompare {
    pub region: String,
    pub materials: Vec<String>,
}

// ------------------------------------------------------------------------------ leaves

/// Two quantities `[x, y]`; `rule` names what the pair is where it is not an array of two.
fn two<D: Dimension>(value: &Value, rule: &str) -> Result<[Quantity<D>; 2], Refusal> {
    match value {
        Value::Array(a) if a.len() == 2 => items::<Quantity<D>>(a)?
            .try_into()
            .map_err(|_| Refusal::new(value, rule)),
        other => Err(Refusal::new(other, rule)),
    }
}

/// A point `[x, y]`, lengths.
#[derive(Debug, Clone, PartialEq)]
pub(in crate::bem) struct Point(pub [Quantity<Length>; 2]);

impl Point {
    /// The point (m), as a program gives it.
    pub fn from_si(p: [f64; 2]) -> Self {
        Point(p.map(Quantity::from_si))
    }

    /// x and y, m.
    pub fn si(&self) -> [f64; 2] {
        [self.0[0].si(), self.0[1].si()]
    }
}

impl FromToml for Point {
    fn from_toml(value: &Value) -> Result<Self, Refusal> {
        two(value, "must be a point [x, y] (lengths)").map(Point)
    }
}

/// Gravity `[gx, gy]`, m/s^2.
#[derive(Debug, Clone, PartialEq)]
pub(in crate::bem) struct Gravity(pub [Number; 2]);

impl FromToml for Gravity {
    fn from_toml(value: &Value) -> Result<Self, Refusal> {
        two(value, "must be [gx, gy] in m/s^2").map(Gravity)
    }
}

/// A scalar distribution along a segment as written: a value, `{ linear = [start, end] }`
/// or `{ table = [[t, value], ...] }` (the rules on t are in `conditions.rs`).
#[derive(Debug, Clone, PartialEq)]
pub(in crate::bem) enum Profile<D> {
    Uniform(Quantity<D>),
    Linear([Quantity<D>; 2]),
    Table(Vec<(Number, Quantity<D>)>),
}

impl<D: Dimension> Profile<D> {
    fn table_rows(rows: &Value) -> Result<Vec<(Number, Quantity<D>)>, Refusal> {
        let Value::Array(rows) = rows else {
            return Err(Refusal::new(
                rows,
                "must be [[t, value], ...] with t the fraction of the segment's length",
            )
            .within(".table"));
        };
        let mut out = Vec::new();
        for (i, r) in rows.iter().enumerate() {
            let at = format!(".table[{i}]");
            let pair = match r {
                Value::Array(pair) if pair.len() == 2 => pair,
                _ => return Err(Refusal::new(r, "must be [t, value]").within(at)),
            };
            let t = Number::from_toml(&pair[0]).map_err(|e| e.within(format!("{at}[0]")))?;
            let v = Quantity::<D>::from_toml(&pair[1]).map_err(|e| e.within(format!("{at}[1]")))?;
            out.push((t, v));
        }
        Ok(out)
    }
}

impl<D: Dimension> FromToml for Profile<D> {
    fn from_toml(value: &Value) -> Result<Self, Refusal> {
        let Value::Table(t) = value else {
            return Quantity::from_toml(value).map(Profile::Uniform);
        };
        if let Some(l) = t.get("linear") {
            if t.len() != 1 {
                return Err(Refusal::new(
                    value,
                    "a linear profile is { linear = [start, end] }",
                ));
            }
            match l {
                Value::Array(a) if a.len() == 2 => Ok(Profile::Linear(
                    two(l, "").map_err(|e| e.within(".linear"))?,
                )),
                other => Err(Refusal::new(
                    other,
                    "must be [value at the segment's start, value at its end]",
                )
                .within(".linear")),
            }
        } else if let Some(rows) = t.get("table") {
            if t.len() != 1 {
                return Err(Refusal::new(
                    value,
                    "a tabulated profile is { table = [[t, value], ...] }",
                ));
            }
            Self::table_rows(rows).map(Profile::Table)
        } else {
            Err(Refusal::new(
                value,
                "must be a value, { linear = [start, end] } or { table = [[t, value], ...] }",
            ))
        }
    }
}

impl<D> Serialize for Profile<D> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        match self {
            Profile::Uniform(q) => q.serialize(serializer),
            Profile::Linear(ends) => {
                let mut m = serializer.serialize_map(Some(1))?;
                m.serialize_entry("linear", ends)?;
                m.end()
            }
            Profile::Table(rows) => {
                let mut m = serializer.serialize_map(Some(1))?;
                m.serialize_entry("table", rows)?;
                m.end()
            }
        }
    }
}

/// `grading = { AT = R }` as written: one key (the rule names `both`, `start`, `end`).
#[derive(Debug, Clone, PartialEq)]
pub(in crate::bem) struct RawGrading {
    pub at: String,
    pub ratio: Number,
}

/// What a grading is.
pub(in crate::bem) const GRADING_RULE: &str =
    "grading is { both = R }, { start = R } or { end = R } (R = largest / smallest element)";

impl FromToml for RawGrading {
    fn from_toml(value: &Value) -> Result<Self, Refusal> {
        match value {
            Value::Table(g) if g.len() == 1 => {
                let Some((k, v)) = g.iter().next() else {
                    return Err(Refusal::new(value, GRADING_RULE));
                };
                let ratio = Number::from_toml(v).map_err(|e| e.within(format!(".{k}")))?;
                Ok(RawGrading {
                    at: k.clone(),
                    ratio,
                })
            }
            other => Err(Refusal::new(other, GRADING_RULE)),
        }
    }
}

impl Serialize for RawGrading {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut m = serializer.serialize_map(Some(1))?;
        m.serialize_entry(&self.at, &self.ratio)?;
        m.end()
    }
}

/// A damage limit, in the unit of the damage quantity (a rule): a plain number, or a
/// pressure with its unit (`"300 MPa"`, for quantities in Pa).
#[derive(Debug, Clone, PartialEq)]
pub(in crate::bem) enum Limit {
    Number(Number),
    Pressure(Quantity<Pressure>),
}

impl Limit {
    /// The limit as written.
    pub fn written(&self) -> &str {
        match self {
            Limit::Number(q) => q.written(),
            Limit::Pressure(q) => q.written(),
        }
    }
}

impl FromToml for Limit {
    fn from_toml(value: &Value) -> Result<Self, Refusal> {
        match value {
            Value::String(_) => Quantity::from_toml(value).map(Limit::Pressure),
            _ => Number::from_toml(value).map(Limit::Number),
        }
    }
}

impl Serialize for Limit {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Limit::Number(q) => q.serialize(serializer),
            Limit::Pressure(q) => q.serialize(serializer),
        }
    }
}

macro_rules! leaf {
    ($($t:ty),*) => {$(
        impl<'de> Deserialize<'de> for $t {
            fn deserialize<De: Deserializer<'de>>(deserializer: De) -> Result<Self, De::Error> {
                deserialize_leaf(deserializer)
            }
        }
    )*};
}
leaf!(Point, Gravity, RawGrading, Limit);

impl<'de, D: Dimension> Deserialize<'de> for Profile<D> {
    fn deserialize<De: Deserializer<'de>>(deserializer: De) -> Result<Self, De::Error> {
        deserialize_leaf(deserializer)
    }
}

impl Serialize for Point {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.0.serialize(serializer)
    }
}

impl Serialize for Gravity {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.0.serialize(serializer)
    }
}

/// A part of a case as written, for an error message (`{ density = 7850 }`).
pub(in crate::bem) fn written<T: Serialize>(part: &T) -> String {
    Value::try_from(part).map_or_else(|_| "(given)".into(), |v| crate::units::show(&v))
}
