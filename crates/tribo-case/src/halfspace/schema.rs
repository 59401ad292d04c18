//! The half-space case file as serde reads it: every table and key of the schema (see the
//! module doc of [`super`]) with its type. Numbers with a dimension are [`Quantity`]s (`2e11`
//! or `"201 GPa"`), choices are enums, and unknown keys are refused (`deny_unknown_fields`);
//! the rules between values (ranges, exclusive keys, defaults) are checked in
//! [`super::validate`].

use super::model::{FieldMethod, FieldPoints};
use crate::schema::{
    items, leaf_deserialize, Choice, Choices, Count, Flag, FromToml, Pair, Refusal,
};
use crate::units::{self, Angle, Dimensionless, Force, Pressure, Quantity};
use serde::Deserialize;
use toml::Value;
use tribo::solvers::NormalMethod;

/// A plain finite number.
pub(super) type Number = Quantity<Dimensionless>;
/// A length, m.
pub(super) type Metres = Quantity<units::Length>;
/// An angle, deg.
pub(super) type Degrees = Quantity<Angle>;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawCase {
    pub title: Option<String>,
    pub body1: RawBody,
    pub body2: RawBody,
    pub contact: RawContact,
    pub grid: Option<RawGrid>,
    pub solver: Option<RawSolver>,
    pub bulk: Option<RawBulk>,
    pub field: Option<RawField>,
    pub damage: Option<RawDamage>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawBody {
    #[serde(rename = "E")]
    pub e: Quantity<Pressure>,
    pub nu: Number,
    pub radii: Option<Radii>,
    pub angle_deg: Option<Degrees>,
    pub surface: Option<RawSurface>,
}

/// `[bodyN.surface]`: one table for both kinds; which keys apply to which kind is a rule
/// ([`super::validate`]), so that every error names its key (serde's internally tagged
/// enums lose the path below the tag).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSurface {
    pub kind: Choice<SurfaceKind>,
    // roller
    pub radius: Option<Metres>,
    pub length: Option<Metres>,
    pub crown: Option<Choice<CrownKind>>,
    pub crown_radius: Option<Metres>,
    pub flat_length: Option<Metres>,
    pub design_load: Option<Quantity<Force>>,
    pub crown_drop: Option<Metres>,
    /// `[bodyN.surface.roughness]`: a roughness on the roller, the keys of a surface of kind
    /// "rough" or "measured" (a rule of [`super::validate`]: only in a roller).
    pub roughness: Option<Box<RawSurface>>,
    // height map
    pub file: Option<String>,
    pub heights: Option<Vec<Vec<Number>>>,
    pub spacing: Option<Pair<Metres>>,
    pub scale: Option<Number>,
    // rough (generated)
    pub hurst: Option<Number>,
    pub rolloff_wavelength: Option<Metres>,
    pub long_wavelength: Option<Metres>,
    pub short_wavelength: Option<Metres>,
    pub rms_height: Option<Metres>,
    pub rms_slope: Option<Number>,
    pub anisotropy: Option<Pair<Number>>,
    pub seed: Option<Count>,
    pub method: Option<Choice<RoughMethod>>,
    // measured
    pub format: Option<Choice<TopographyFormat>>,
    pub detrend: Option<Detrend>,
    pub periodic: Option<Flag>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub(super) enum SurfaceKind {
    Roller,
    HeightMap,
    Rough,
    Measured,
}

impl Choices for SurfaceKind {
    const RULE: &'static str =
        "must be \"roller\", \"height_map\", \"rough\" (generated) or \"measured\" (a file)";
}

/// `[bodyN.surface] method` of a generated rough surface.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub(super) enum RoughMethod {
    FilteredNoise,
    RandomPhase,
}

impl Choices for RoughMethod {
    const RULE: &'static str = "must be \"filtered_noise\" (Gaussian Fourier amplitudes, the \
                                default) or \"random_phase\" (exact amplitudes)";
}

/// `[bodyN.surface] format` of a measured surface (default: by the file's extension).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub(super) enum TopographyFormat {
    X3p,
    Ascii,
    Npy,
}

impl Choices for TopographyFormat {
    const RULE: &'static str = "must be \"x3p\", \"ascii\" (CSV/text grids) or \"npy\"";
}

/// `[bodyN.surface] detrend`: `"none"`, `"plane"` or a polynomial degree (the range is a
/// rule of [`super::validate`]).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Detrend {
    /// The degree, `None` for `"none"`.
    pub degree: Option<usize>,
    /// As written.
    pub written: String,
}

impl FromToml for Detrend {
    fn from_toml(value: &Value) -> Result<Self, Refusal> {
        let written = units::show(value);
        match value {
            Value::String(s) if s == "none" => Ok(Detrend {
                degree: None,
                written,
            }),
            Value::String(s) if s == "plane" => Ok(Detrend {
                degree: Some(1),
                written,
            }),
            Value::String(_) => Err(Refusal::new(
                value,
                "must be \"none\", \"plane\" (the default) or a polynomial degree 0 ... 10",
            )),
            _ => Count::from_toml(value).map(|c| Detrend {
                degree: Some(c.n),
                written,
            }),
        }
    }
}

leaf_deserialize!(Detrend);

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub(super) enum CrownKind {
    None,
    Circular,
    Logarithmic,
}

impl Choices for CrownKind {
    const RULE: &'static str = "must be \"none\", \"circular\" or \"logarithmic\"";
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawContact {
    pub load: Option<Quantity<Force>>,
    pub approach: Option<Metres>,
    pub friction: Option<Number>,
    pub tangential_load: Option<Quantity<Force>>,
    pub tangential_angle_deg: Option<Degrees>,
    pub sliding: Option<Flag>,
    pub sliding_angle_deg: Option<Degrees>,
    pub traction_direction: Option<Choice<TractionDirection>>,
    pub mean_pressure: Option<Quantity<Pressure>>,
    pub load_steps: Option<Count>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub(super) enum TractionDirection {
    Parallel,
    Free,
}

impl Choices for TractionDirection {
    const RULE: &'static str = "must be \"parallel\" (q along the load, Cattaneo-Mindlin's \
                                assumption) or \"free\" (the full 2D partial-slip problem)";
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawGrid {
    pub n: Option<Pair<Count>>,
    pub extent: Option<Number>,
    pub half_width: Option<Pair<Metres>>,
    pub periodic: Option<Flag>,
    pub period: Option<Pair<Metres>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSolver {
    pub method: Option<Choice<NormalMethod>>,
    pub tolerance: Option<Number>,
    pub max_iterations: Option<Count>,
}

impl Choices for NormalMethod {
    const RULE: &'static str = "must be \"cg\" (constrained conjugate gradients, Polonsky-Keer) \
                                or \"active_set\" (dense, small grids)";
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawBulk {
    pub shaft: Option<Choice<ShaftBody>>,
    pub shaft_radius: Option<Metres>,
    pub kind: Option<Choice<BulkKind>>,
    pub stress_max: Option<Quantity<Pressure>>,
    pub points: Option<Count>,
    pub stress: Option<Quantity<Pressure>>,
    pub bending_force: Option<Quantity<Force>>,
    pub span: Option<Metres>,
    pub support: Option<Choice<Support>>,
    pub bending_side: Option<Choice<BendingSide>>,
}

/// "body1" or "body2": the results' body enum, [`crate::pipeline::FieldBody`] (one enum for
/// the case's `field.body`, `bulk.shaft` and the stress results).
pub(super) use crate::pipeline::FieldBody as BodyId;

/// `bulk.shaft`: the body that is the shaft.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(transparent)]
pub(super) struct ShaftBody(pub BodyId);

impl Choices for ShaftBody {
    const RULE: &'static str = "must be \"body1\" or \"body2\" (the body that is the shaft)";
}

/// `field.body`: the body the field is computed in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(transparent)]
pub(super) struct FieldBody(pub BodyId);

impl Choices for FieldBody {
    const RULE: &'static str = "must be \"body1\" or \"body2\" (the body the field is computed in)";
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub(super) enum BulkKind {
    TensionCompression,
    Bending,
    Both,
}

impl Choices for BulkKind {
    const RULE: &'static str = "must be \"tension-compression\", \"bending\" or \"both\"";
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub(super) enum Support {
    SimplySupported,
    Cantilever,
}

impl Choices for Support {
    const RULE: &'static str = "must be \"simply-supported\" (force at mid-span, M = F L/4) or \
                                \"cantilever\" (force at the free end, M = F L)";
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub(super) enum BendingSide {
    Tension,
    Compression,
}

impl Choices for BendingSide {
    const RULE: &'static str = "must be \"tension\" or \"compression\" (the side of the shaft \
                                the contact is on)";
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawField {
    pub points: Option<Choice<FieldPoints>>,
    pub method: Option<Choice<FieldMethod>>,
    pub layers: Option<Count>,
    pub n: Option<FieldN>,
    pub extent: Option<Number>,
    pub half_width: Option<Metres>,
    pub depth: Option<Number>,
    pub depth_m: Option<Metres>,
    pub body: Option<Choice<FieldBody>>,
    pub edge_refinement: Option<Refinement>,
}

/// `[field] edge_refinement`: `"band"` (the default), `"none"` (the factor 1) or a count
/// (the range is checked in [`super::validate`]).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Refinement {
    /// The factor, `None` for `"band"`.
    pub n: Option<usize>,
}

impl FromToml for Refinement {
    fn from_toml(value: &Value) -> Result<Self, Refusal> {
        match value {
            Value::String(s) if s == "band" => Ok(Refinement { n: None }),
            Value::String(s) if s == "none" => Ok(Refinement { n: Some(1) }),
            Value::String(_) => Err(Refusal::new(
                value,
                "must be \"band\" (the default), \"none\" or an integer in 1 ... 16",
            )),
            _ => Count::from_toml(value).map(|c| Refinement { n: Some(c.n) }),
        }
    }
}

leaf_deserialize!(Refinement);

impl Choices for FieldPoints {
    const RULE: &'static str = "must be \"uniform\" (n points over the extent, direct sum) or \
                                \"centres\" (the contact grid's element centres, FFT)";
}

impl Choices for FieldMethod {
    const RULE: &'static str = "must be \"fft\" (FFT on the extended contact grid + cubic \
                                interpolation, the default) or \"direct\" (the exact direct \
                                sum, slow)";
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawDamage {
    pub criteria: Option<Criteria>,
    pub limit_over_p0: Option<Number>,
    pub limit_load: Option<Quantity<Force>>,
    /// Limits by criterion name; the unit depends on the criterion (a rule).
    pub limits: Option<toml::Table>,
    pub study: Option<RawStudy>,
    pub cycle: Option<RawCycle>,
    pub energy: Option<RawEnergy>,
    /// Random limits (`[damage.probabilistic]`), hand-parsed by [`crate::probabilistic`].
    pub probabilistic: Option<toml::Table>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawEnergy {
    pub a_n: Option<Number>,
    pub a_tau: Option<Number>,
    pub a_t: Option<Number>,
    pub a_tau_n: Option<Number>,
    pub a_m_t: Option<Number>,
    pub temperature: Option<Number>,
    pub u0: Option<Number>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawCycle {
    pub kind: Option<Choice<CycleKindName>>,
    pub amplitude: Option<Quantity<Pressure>>,
    pub amplitude_over_p0: Option<Number>,
    pub speed: Option<Number>,
    pub period: Option<Number>,
    pub steps: Option<Count>,
    pub cycles: Option<Number>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub(super) enum CycleKindName {
    RotatingBending,
    Rolling,
}

impl Choices for CycleKindName {
    const RULE: &'static str = "must be \"rotating-bending\" (a bent shaft turning under the \
                                roller) or \"rolling\" (the contact moving along y)";
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawStudy {
    pub bending_over_p0: Option<Ratios>,
    pub limit_over_p0: Option<Number>,
}

/// A principal radius of curvature, m: a number, a unit string, or infinite (flat) written
/// as the string "inf" or the TOML float `inf` (both echoed as "inf" in summary.json). A
/// negative infinity or a NaN is refused: a concave flat direction is not a different shape,
/// and the sign convention asks for an explicit "inf". Zero and the length range are rules.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Radius {
    pub metres: f64,
    pub written: String,
}

impl FromToml for Radius {
    fn from_toml(v: &Value) -> Result<Self, Refusal> {
        let written = units::show(v);
        let infinite = match v {
            Value::String(s) => {
                let t = s.trim();
                t.eq_ignore_ascii_case("inf") || t.eq_ignore_ascii_case("infinity")
            }
            Value::Float(x) => *x == f64::INFINITY,
            _ => false,
        };
        if infinite {
            return Ok(Radius {
                metres: f64::INFINITY,
                written,
            });
        }
        if matches!(v, Value::Float(x) if !x.is_finite()) {
            return Err(Refusal::new(
                v,
                "a radius must be a finite number in m, or inf / \"inf\" (flat); -inf and nan \
                 are refused",
            ));
        }
        let metres = Metres::from_value(v)
            .map_err(|_| {
                Refusal::new(
                    v,
                    "a radius must be a number in m (< 0 concave), a string like \"10 mm\", or \
                     \"inf\" (flat)",
                )
            })?
            .si();
        Ok(Radius { metres, written })
    }
}

/// `radii = [Rx, Ry]`.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Radii(pub [Radius; 2]);

impl FromToml for Radii {
    fn from_toml(v: &Value) -> Result<Self, Refusal> {
        let rule = "must be an array of two principal radii [Rx, Ry] (m, or \"inf\")";
        match v {
            Value::Array(a) if a.len() == 2 => Ok(Radii(
                items(a)?.try_into().map_err(|_| Refusal::new(v, rule))?,
            )),
            _ => Err(Refusal::new(v, rule)),
        }
    }
}

/// `field.n = [nx, ny, nz]`.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct FieldN(pub [usize; 3]);

impl FromToml for FieldN {
    fn from_toml(v: &Value) -> Result<Self, Refusal> {
        let rule = "must be [nx, ny, nz], three point counts";
        match v {
            Value::Array(a) if a.len() == 3 => {
                let n: Vec<Count> = items(a)?;
                Ok(FieldN([n[0].n, n[1].n, n[2].n]))
            }
            _ => Err(Refusal::new(v, rule)),
        }
    }
}

/// `damage.criteria`: a non-empty list of quantity names (which names is a rule).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Criteria(pub Vec<String>);

impl FromToml for Criteria {
    fn from_toml(v: &Value) -> Result<Self, Refusal> {
        match v {
            Value::Array(a) if !a.is_empty() => a
                .iter()
                .enumerate()
                .map(|(k, item)| match item {
                    Value::String(s) => Ok(s.clone()),
                    _ => Err(Refusal::new(
                        item,
                        "must be the name of a quantity, e.g. \"sigma_int\"",
                    )
                    .within(format!("[{k}]"))),
                })
                .collect::<Result<_, _>>()
                .map(Criteria),
            _ => Err(Refusal::new(
                v,
                "must be a non-empty list of quantity names, e.g. [\"sigma_int\", \"u\"]",
            )),
        }
    }
}

/// `damage.study.bending_over_p0`: 1 ... 101 numbers (their order and sign are a rule).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Ratios(pub Vec<Number>);

impl FromToml for Ratios {
    fn from_toml(v: &Value) -> Result<Self, Refusal> {
        match v {
            Value::Array(a) if !a.is_empty() && a.len() <= 101 => Ok(Ratios(items(a)?)),
            _ => Err(Refusal::new(
                v,
                "must be a list of 1 ... 101 values sigma_b / p0",
            )),
        }
    }
}

leaf_deserialize!(Radius, Radii, FieldN, Criteria, Ratios);
