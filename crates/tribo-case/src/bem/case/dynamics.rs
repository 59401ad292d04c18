//! The dynamic keys of a 2D BEM case (issue 13 item 4; docs/user/case-bem2d-dynamics.md):
//! `[dynamics]` (time step, duration or number of steps, method, realisation, field output
//! times, initial rigid-body velocities), `[[probe]]` points, a `time` function on each
//! `[[bc]]` and a `density` per material.
//!
//! Wired into the root schema (`schema.rs`): `dynamics` and `probe` of the root raw case,
//! `time` of the raw `[[bc]]`, `density` of the raw material; `validate.rs` calls
//! `validate` after the static rules, with a `DynamicsContext` built from the validated
//! case and the locator of its outlines ([`outline_locator`]; probes in gmsh regions are
//! checked against the built model by the pipeline, [`model_locator`]).
//!
//! Every rule's error names the item (`dynamics.time_step`, `probe[1].at`,
//! `bc[2].time.ramp`, `materials.steel.density`, `regions[0]`).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::Value;
use tribo::dynamics::time_function::TimeFunction;
use tribo::operators::bem2d::{BemModel, LoopItem, SegmentShape};
use tribo::ElasticMaterial;

use super::RegionSpec;
use crate::error::{CaseError, CaseResult};
use crate::schema::{Choice, Choices, Count, FromToml, Refusal};
use crate::units::{Angle, Density, Dimensionless, Length, Quantity, Time, Velocity};

/// The most time steps accepted. 2D has no Huygens principle: the convolution history is
/// never truncated (docs/theory/DYNAMICS.md sec. 0), so the marching cost grows as M^2 and
/// the history memory as M; 10^6 steps is far beyond the goal (10^3 in 2 minutes).
pub const MAX_STEPS: usize = 1_000_000;

/// Densities accepted, kg/m^3: from 1 (the lightest aerogels) to 1e5 (osmium, the densest
/// element, is 2.26e4); outside, the value is a unit mistake.
pub const DENSITY_RANGE: [f64; 2] = [1.0, 1e5];

/// Largest relative mismatch between `duration` and a whole number of `time_step`s
/// (decimal unit strings make 2 ms / 1 us = 2000.0000000000002).
const MULTIPLE_TOLERANCE: f64 = 1e-9;

// ---------------------------------------------------------------- raw schema

/// `method`: the convolution quadrature's multistep or Runge-Kutta rule.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// BDF2 (order 2; one Laplace solve per frequency), the default.
    Bdf2,
    /// Radau IIA with 2 stages (order 3; 2 Laplace solves per frequency).
    #[serde(rename = "radau_iia_2")]
    RadauIia2,
    /// Radau IIA with 3 stages (order 5, saturating near 1e-8: docs/theory/DYNAMICS.md
    /// sec. 0).
    #[serde(rename = "radau_iia_3")]
    RadauIia3,
}

impl Method {
    /// The case file's name of the method (`"bdf2"`, `"radau_iia_2"`, `"radau_iia_3"`).
    pub fn name(self) -> &'static str {
        match self {
            Method::Bdf2 => "bdf2",
            Method::RadauIia2 => "radau_iia_2",
            Method::RadauIia3 => "radau_iia_3",
        }
    }
}

impl Choices for Method {
    const RULE: &'static str = "must be \"bdf2\" (order 2, the default), \"radau_iia_2\" \
        (Radau IIA 2-stage, order 3) or \"radau_iia_3\" (Radau IIA 3-stage, order 5)";
}

/// `realisation`: how the convolution is evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Realisation {
    /// All steps at once where the problem is linear (no contact pairs), marching otherwise.
    Auto,
    /// All steps at once: one complex solve per frequency (linear problems only).
    AllAtOnce,
    /// Time marching: one static-like solve per step with a history right-hand side.
    Marching,
}

impl Choices for Realisation {
    const RULE: &'static str = "must be \"auto\" (the default), \"all_at_once\" (linear \
        problems: no contact) or \"marching\"";
}

/// `[dynamics]` as serde reads it.
#[derive(Debug, Clone, Default, Deserialize, serde::Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawDynamics {
    /// `time_step = "1 us"`.
    pub time_step: Option<Quantity<Time>>,
    /// `steps = 2000`.
    pub steps: Option<Count>,
    /// `duration = "2 ms"`.
    pub duration: Option<Quantity<Time>>,
    /// `method = "bdf2"`.
    pub method: Option<Choice<Method>>,
    /// `realisation = "auto"`.
    pub realisation: Option<Choice<Realisation>>,
    /// `fields_at = ["0.5 ms", "1 ms"]`.
    pub fields_at: Option<Vec<Quantity<Time>>>,
    /// `fields_every = 100`.
    pub fields_every: Option<Count>,
    /// `initial_velocity = { striker = ["5 m/s", 0] }`.
    pub initial_velocity: Option<BTreeMap<String, [Quantity<Velocity>; 2]>>,
}

/// `[[probe]]` as serde reads it.
#[derive(Debug, Clone, Deserialize, serde::Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawProbe {
    /// `name = "wall"`.
    pub name: String,
    /// `at = ["10 mm", 0]`.
    pub at: [Quantity<Length>; 2],
}

/// The `time` of a `[[bc]]` as written: `"step"`, or a table with one kind key.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum RawTime {
    /// `time = "step"`: the step at t = 0.
    Step,
    /// A table: `{ step = "0.1 ms" }`, `{ ramp = "0.1 ms", start = "0.2 ms" }`,
    /// `{ sine = "5 kHz", phase_deg = 90 }`, `{ csv = "pulse.csv" }`,
    /// `{ points = [[0, 0], ["0.1 ms", 1]] }`.
    Table(RawTimeTable),
}

/// The table form of [`RawTime`], each kind parsed with its unit.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum RawTimeTable {
    /// Step at the time given.
    Step(Quantity<Time>),
    /// Ramp: rise time, start.
    Ramp(Quantity<Time>, Option<Quantity<Time>>),
    /// Sine: frequency, start, phase.
    Sine(
        Quantity<crate::units::Frequency>,
        Option<Quantity<Time>>,
        Option<Quantity<Angle>>,
    ),
    /// A CSV file (time s, factor), relative to the case file's folder.
    Csv(PathBuf),
    /// Inline points (time, factor).
    Points(Vec<(Quantity<Time>, Quantity<Dimensionless>)>),
}

const TIME_RULE: &str = "must be \"step\" or a table with one of step = \"<time>\", ramp = \
    \"<rise time>\", sine = \"<frequency>\", csv = \"<file>\", points = [[t, f], ...] (with \
    start = \"<time>\" for step-free ramp/sine, phase_deg for sine)";

/// Every key a time function's table may hold.
const TIME_KEYS: [&str; 7] = [
    "step",
    "ramp",
    "sine",
    "csv",
    "points",
    "start",
    "phase_deg",
];

fn leaf<T: FromToml>(t: &toml::Table, key: &str) -> Result<Option<T>, Refusal> {
    t.get(key)
        .map(|v| T::from_toml(v).map_err(|r| r.within(format!(".{key}"))))
        .transpose()
}

impl FromToml for RawTime {
    fn from_toml(value: &Value) -> Result<Self, Refusal> {
        let t = match value {
            Value::String(s) if s == "step" => return Ok(RawTime::Step),
            Value::Table(t) => t,
            _ => return Err(Refusal::new(value, TIME_RULE)),
        };
        if let Some(k) = t.keys().find(|k| !TIME_KEYS.contains(&k.as_str())) {
            return Err(Refusal::new(
                &t[k],
                format!(
                    "unknown key ({}): a time function is one kind key, with start for a \
                     ramp or a sine and phase_deg for a sine",
                    TIME_KEYS.join(", ")
                ),
            )
            .within(format!(".{k}")));
        }
        let kinds: Vec<&str> = ["step", "ramp", "sine", "csv", "points"]
            .into_iter()
            .filter(|k| t.contains_key(*k))
            .collect();
        if kinds.len() != 1 {
            return Err(Refusal::new(
                value,
                format!("{TIME_RULE} (found {})", kinds.len()),
            ));
        }
        let allowed: &[&str] = match kinds[0] {
            "ramp" => &["ramp", "start"],
            "sine" => &["sine", "start", "phase_deg"],
            other => std::slice::from_ref(match other {
                "step" => &"step",
                "csv" => &"csv",
                _ => &"points",
            }),
        };
        if let Some(k) = t.keys().find(|k| !allowed.contains(&k.as_str())) {
            return Err(Refusal::new(
                &t[k],
                format!(
                    "unknown key for a {} time function (keys: {})",
                    kinds[0],
                    allowed.join(", ")
                ),
            )
            .within(format!(".{k}")));
        }
        let table = match kinds[0] {
            "step" => {
                RawTimeTable::Step(leaf(t, "step")?.ok_or_else(|| Refusal::new(value, TIME_RULE))?)
            }
            "ramp" => RawTimeTable::Ramp(
                leaf(t, "ramp")?.ok_or_else(|| Refusal::new(value, TIME_RULE))?,
                leaf(t, "start")?,
            ),
            "sine" => RawTimeTable::Sine(
                leaf(t, "sine")?.ok_or_else(|| Refusal::new(value, TIME_RULE))?,
                leaf(t, "start")?,
                leaf(t, "phase_deg")?,
            ),
            "csv" => match &t["csv"] {
                Value::String(s) if !s.trim().is_empty() => RawTimeTable::Csv(PathBuf::from(s)),
                other => {
                    return Err(Refusal::new(
                        other,
                        "must be the name of a CSV file (time s, factor)",
                    )
                    .within(".csv"))
                }
            },
            _ => {
                let rows = match &t["points"] {
                    Value::Array(rows) => rows,
                    other => {
                        return Err(
                            Refusal::new(other, "must be [[time, factor], ...]").within(".points")
                        )
                    }
                };
                let mut points = Vec::with_capacity(rows.len());
                for (k, r) in rows.iter().enumerate() {
                    let at = format!(".points[{k}]");
                    let Value::Array(pair) = r else {
                        return Err(Refusal::new(r, "must be [time, factor]").within(at));
                    };
                    if pair.len() != 2 {
                        return Err(Refusal::new(r, "must be [time, factor]").within(at));
                    }
                    let time = Quantity::<Time>::from_toml(&pair[0])
                        .map_err(|e| e.within(format!("{at}[0]")))?;
                    let factor = Quantity::<Dimensionless>::from_toml(&pair[1])
                        .map_err(|e| e.within(format!("{at}[1]")))?;
                    points.push((time, factor));
                }
                RawTimeTable::Points(points)
            }
        };
        Ok(RawTime::Table(table))
    }
}

impl serde::Serialize for RawTime {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let RawTime::Table(t) = self else {
            return serializer.serialize_str("step");
        };
        let mut m = serializer.serialize_map(None)?;
        match t {
            RawTimeTable::Step(t0) => m.serialize_entry("step", t0)?,
            RawTimeTable::Ramp(rise, start) => {
                m.serialize_entry("ramp", rise)?;
                if let Some(t0) = start {
                    m.serialize_entry("start", t0)?;
                }
            }
            RawTimeTable::Sine(f, start, phase) => {
                m.serialize_entry("sine", f)?;
                if let Some(t0) = start {
                    m.serialize_entry("start", t0)?;
                }
                if let Some(p) = phase {
                    m.serialize_entry("phase_deg", p)?;
                }
            }
            RawTimeTable::Csv(path) => m.serialize_entry("csv", path)?,
            RawTimeTable::Points(points) => m.serialize_entry("points", points)?,
        }
        m.end()
    }
}

impl<'de> Deserialize<'de> for RawTime {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        crate::schema::deserialize_leaf(deserializer)
    }
}

// ---------------------------------------------------------------- validated

/// A probe point, validated: inside a region.
#[derive(Debug, Clone, PartialEq)]
pub struct ProbeSpec {
    /// Name.
    pub name: String,
    /// (x, y), m.
    pub at: [f64; 2],
    /// The region holding it.
    pub region: String,
}

/// The validated dynamic settings of a case, for the solver. Times in s.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicsSpec {
    /// Time step dt, s.
    pub time_step: f64,
    /// Number of steps M (sample times t_n = n dt, n = 0..=M).
    pub steps: usize,
    /// Duration M dt, s.
    pub duration: f64,
    /// The CQ rule.
    pub method: Method,
    /// The realisation, resolved (`Auto` replaced: `AllAtOnce` without contact pairs,
    /// `Marching` with).
    pub realisation: Realisation,
    /// The sample indices n (times n dt) of the field snapshots, increasing.
    pub field_steps: Vec<usize>,
    /// Density of each material of a region, kg/m^3.
    pub densities: BTreeMap<String, f64>,
    /// The time function of each `[[bc]]`, in their order (no `time`: the constant 1 from
    /// t = 0, i.e. a load applied suddenly at t = 0).
    pub bc_time: Vec<TimeFunction>,
    /// The time function of each rigid segment's controls (`steps[0].rigid.<segment>.time`),
    /// in the order of the case's `rigid` (no `time`: the constant 1 from t = 0).
    pub rigid_time: Vec<TimeFunction>,
    /// The probes.
    pub probes: Vec<ProbeSpec>,
    /// Initial rigid-body velocity per region, (v_x, v_y) m/s (regions not listed: at rest).
    pub initial_velocity: BTreeMap<String, [f64; 2]>,
    /// Validation notes the run prints (an initial velocity above 1 % of the shear wave
    /// speed, [`IMPACT_NOTE`]).
    pub notes: Vec<String>,
}

/// The largest |factor| of a tabulated time function (inline points or CSV): the factor
/// scales the condition's value (a load of 10 MPa times 1e308 overflows the convolution);
/// 1e6 leaves any physical load history room (a dynamic amplification is O(1)).
pub const MAX_TIME_FACTOR: f64 = 1e6;

const FACTOR_RULE: &str = "must be at most 1e6 in magnitude (a time function's factor scales \
    the condition's value; give the load's size in the [[bc]] and the shape here)";

/// The fraction of a region's shear wave speed c2 above which an initial velocity gets a
/// validation note: the linear-elastic impact (small strains, no plasticity) needs |v|
/// well below c2 (the impact strain is of the order of v/c); at |v| >= c2 it is refused.
pub const IMPACT_NOTE: f64 = 0.01;

/// What the dynamic rules need from the validated static case.
pub(crate) struct DynamicsContext<'a> {
    /// Each material's `density` as written (None: not given).
    pub densities: BTreeMap<String, Option<Quantity<Density>>>,
    /// The regions: (name, material name).
    pub regions: Vec<(String, String)>,
    /// Each `[[bc]]`'s origin (`bc[2]`) and `time` as written.
    pub bc_times: Vec<(String, Option<RawTime>)>,
    /// Each rigid control's origin (`steps[0].rigid.punch`) and `time` as written.
    pub rigid_times: Vec<(String, Option<RawTime>)>,
    /// The rigid segments (`rigid`), in order.
    pub rigid: Vec<String>,
    /// Whether the case marches: contact pairs or rigid segments.
    pub has_contact: bool,
    /// Number of load steps (`[[steps]]`); a dynamic case has one.
    pub load_steps: usize,
    /// The case file's folder (CSV files are relative to it).
    pub base_dir: &'a Path,
    /// The region holding a point (None: outside every region).
    pub locate: &'a dyn Fn([f64; 2]) -> Option<String>,
    /// The materials by name (the wave speeds of the initial-velocity rule).
    pub materials: &'a BTreeMap<String, ElasticMaterial>,
}

fn bad(
    field: impl Into<String>,
    value: impl std::fmt::Display,
    rule: impl Into<String>,
) -> CaseError {
    CaseError::field(field, value, rule)
}

/// The dynamic settings, or None for a static case. Errors name the item: a `time`,
/// `[[probe]]` or `initial_velocity` without `[dynamics]`; the time step, steps and duration
/// (not positive, fewer than two given, inconsistent, the duration not a whole number of
/// steps, too many steps); `all_at_once` with contact; more than one load step; output times
/// outside [0, duration] or falling on the same step; a region's material without a density
/// (or one outside [`DENSITY_RANGE`]); a time function that breaks its rule (a table not
/// increasing, a rise time not positive, a factor above [`MAX_TIME_FACTOR`]); a probe
/// outside every region or named twice; an initial velocity of no region, not finite or not
/// below the region's shear wave speed (a note above [`IMPACT_NOTE`] of it).
pub(crate) fn validate(
    raw: Option<RawDynamics>,
    probes: Option<Vec<RawProbe>>,
    ctx: &DynamicsContext<'_>,
) -> CaseResult<Option<DynamicsSpec>> {
    let Some(raw) = raw else {
        if let Some((origin, _)) = ctx
            .bc_times
            .iter()
            .chain(&ctx.rigid_times)
            .find(|(_, t)| t.is_some())
        {
            return Err(bad(
                format!("{origin}.time"),
                "(given)",
                "a time function needs a [dynamics] table (time_step or steps, duration)",
            ));
        }
        if probes.as_ref().is_some_and(|p| !p.is_empty()) {
            return Err(bad(
                "probe",
                "(given)",
                "probes record time histories: they need a [dynamics] table",
            ));
        }
        return Ok(None);
    };
    let (time_step, steps, duration) = timing(&raw)?;
    if ctx.load_steps > 1 {
        return Err(bad(
            "steps",
            format!("{} steps", ctx.load_steps),
            "a dynamic case has one load history: the time functions of [[bc]] replace \
             load steps (give at most one [[steps]] entry)",
        ));
    }
    let method = raw.method.as_ref().map_or(Method::Bdf2, |m| m.value);
    let realisation = match raw.realisation.as_ref() {
        None => resolve(Realisation::Auto, ctx.has_contact),
        Some(r) if r.value == Realisation::AllAtOnce && ctx.has_contact => {
            return Err(bad(
                "dynamics.realisation",
                &r.written,
                "all_at_once solves a linear problem without contact pairs or rigid segments \
                 (contact is nonlinear; a rigid segment's translation is an unknown of each \
                 step): use \"marching\" or \"auto\"",
            ))
        }
        Some(r) => resolve(r.value, ctx.has_contact),
    };
    let field_steps = field_steps(&raw, time_step, steps, duration)?;
    let densities = densities(ctx)?;
    let mut bc_time = Vec::with_capacity(ctx.bc_times.len());
    for (origin, t) in &ctx.bc_times {
        bc_time.push(match t {
            None => TimeFunction::constant(1.0).map_err(CaseError::from)?,
            Some(t) => time_function(&format!("{origin}.time"), t, ctx.base_dir)?,
        });
    }
    let mut rigid_time = Vec::with_capacity(ctx.rigid.len());
    for seg in &ctx.rigid {
        let origin = format!("steps[0].rigid.{seg}");
        let written = ctx.rigid_times.iter().find(|(o, _)| *o == origin);
        rigid_time.push(match written.and_then(|(_, t)| t.as_ref()) {
            None => TimeFunction::constant(1.0).map_err(CaseError::from)?,
            Some(t) => time_function(&format!("{origin}.time"), t, ctx.base_dir)?,
        });
    }
    let probes = probe_specs(probes.unwrap_or_default(), ctx)?;
    let mut initial_velocity = BTreeMap::new();
    let mut notes = Vec::new();
    let regions: BTreeSet<&str> = ctx.regions.iter().map(|r| r.0.as_str()).collect();
    for (name, v) in raw.initial_velocity.iter().flatten() {
        let field = format!("dynamics.initial_velocity.{name}");
        if !regions.contains(name.as_str()) {
            return Err(bad(
                field,
                format!("[{}, {}]", v[0], v[1]),
                format!(
                    "names no region (regions: {})",
                    regions.iter().copied().collect::<Vec<_>>().join(", ")
                ),
            ));
        }
        let si = [v[0].si(), v[1].si()];
        if let Some(note) = velocity_rule(&field, si, name, ctx, &densities)? {
            notes.push(note);
        }
        initial_velocity.insert(name.clone(), si);
    }
    Ok(Some(DynamicsSpec {
        time_step,
        steps,
        duration,
        method,
        realisation,
        field_steps,
        densities,
        bc_time,
        rigid_time,
        probes,
        initial_velocity,
        notes,
    }))
}

/// The range rule of `dynamics.initial_velocity.<region>` (`field`), the velocity `v` in
/// m/s: finite components and |v| below the shear wave speed c2 = sqrt(mu / rho) of the
/// region's material (a rigid-body velocity entering a linear-elastic impact as a closing
/// gap: the impact strain is ~ |v| / c, so |v| must be << c2; 1e300 m/s used to reach the
/// convolution as a numerical failure). Returns a note for |v| > [`IMPACT_NOTE`] c2.
fn velocity_rule(
    field: &str,
    v: [f64; 2],
    region: &str,
    ctx: &DynamicsContext<'_>,
    densities: &BTreeMap<String, f64>,
) -> CaseResult<Option<String>> {
    let shown = format!("[{:e}, {:e}] m/s", v[0], v[1]);
    if !(v[0].is_finite() && v[1].is_finite()) {
        return Err(bad(field, shown, "both components must be finite numbers"));
    }
    let material = ctx
        .regions
        .iter()
        .find(|(r, _)| r == region)
        .map(|(_, m)| m.as_str());
    let c2 = material.and_then(|m| {
        let rho = densities.get(m)?;
        let mu = ctx.materials.get(m)?.shear_modulus();
        Some((mu / rho).sqrt())
    });
    let Some(c2) = c2.filter(|c| c.is_finite() && *c > 0.0) else {
        return Ok(None);
    };
    let speed = v[0].hypot(v[1]);
    if speed >= c2 {
        return Err(bad(
            field,
            shown,
            format!(
                "|v| = {speed:e} m/s must be below the shear wave speed c2 = sqrt(mu/rho) = \
                 {c2:.6e} m/s of the region's material {:?} (a linear-elastic impact needs \
                 |v| << c2: the impact strain is about |v|/c)",
                material.unwrap_or_default()
            ),
        ));
    }
    Ok((speed > IMPACT_NOTE * c2).then(|| {
        format!(
            "{field}: |v| = {speed:e} m/s is {:.1} % of the shear wave speed c2 = {c2:.4e} m/s \
             of {:?}: the impact strain (~ |v|/c) may leave the linear-elastic range the \
             dynamic model assumes",
            100.0 * speed / c2,
            material.unwrap_or_default()
        )
    }))
}

fn resolve(r: Realisation, has_contact: bool) -> Realisation {
    match r {
        Realisation::Auto if has_contact => Realisation::Marching,
        Realisation::Auto => Realisation::AllAtOnce,
        other => other,
    }
}

/// (dt, M, duration) from two or three of time_step, steps, duration.
fn timing(raw: &RawDynamics) -> CaseResult<(f64, usize, f64)> {
    if let Some(dt) = &raw.time_step {
        if dt.si() <= 0.0 {
            return Err(bad(
                "dynamics.time_step",
                dt,
                "the time step must be > 0 (s)",
            ));
        }
    }
    if let Some(d) = &raw.duration {
        if d.si() <= 0.0 {
            return Err(bad("dynamics.duration", d, "the duration must be > 0 (s)"));
        }
    }
    if let Some(m) = &raw.steps {
        if m.n == 0 || m.n > MAX_STEPS {
            return Err(bad(
                "dynamics.steps",
                m.n,
                format!(
                    "must be in [1, {MAX_STEPS}] (the 2D convolution history is never \
                     truncated: the cost grows as steps^2)"
                ),
            ));
        }
    }
    let count = |ratio: f64, written: String| -> CaseResult<usize> {
        let m = ratio.round();
        if !(m >= 1.0 && m <= MAX_STEPS as f64) {
            return Err(bad(
                "dynamics.duration",
                written,
                format!(
                    "gives {ratio:.6e} time steps; must be in [1, {MAX_STEPS}] (the 2D \
                     convolution history is never truncated: the cost grows as steps^2)"
                ),
            ));
        }
        if (ratio - m).abs() > MULTIPLE_TOLERANCE * m {
            return Err(bad(
                "dynamics.duration",
                written,
                format!("must be a whole number of time steps (duration / time_step = {ratio})"),
            ));
        }
        Ok(m as usize)
    };
    match (&raw.time_step, &raw.steps, &raw.duration) {
        (Some(dt), None, Some(d)) => {
            let m = count(d.si() / dt.si(), format!("{d} with time_step = {dt}"))?;
            Ok((dt.si(), m, d.si()))
        }
        (None, Some(m), Some(d)) => {
            let dt = d.si() / m.n as f64;
            if dt <= 0.0 {
                return Err(bad(
                    "dynamics.duration",
                    d,
                    format!(
                        "gives a time step of {dt:e} s over {} steps: too small",
                        m.n
                    ),
                ));
            }
            Ok((dt, m.n, d.si()))
        }
        (Some(dt), Some(m), None) => {
            let d = dt.si() * m.n as f64;
            if !d.is_finite() {
                return Err(bad("dynamics.steps", m.n, "time_step x steps overflows"));
            }
            Ok((dt.si(), m.n, d))
        }
        (Some(dt), Some(m), Some(d)) => {
            let n = count(d.si() / dt.si(), format!("{d} with time_step = {dt}"))?;
            if n != m.n {
                return Err(bad(
                    "dynamics.steps",
                    m.n,
                    format!("disagrees with duration / time_step = {n}; give two of the three"),
                ));
            }
            Ok((dt.si(), n, d.si()))
        }
        _ => Err(bad(
            "dynamics",
            "(incomplete)",
            "give two of time_step, steps and duration (e.g. time_step = \"1 us\", duration \
             = \"2 ms\")",
        )),
    }
}

/// The sample indices of the snapshots.
fn field_steps(raw: &RawDynamics, dt: f64, steps: usize, duration: f64) -> CaseResult<Vec<usize>> {
    match (&raw.fields_at, &raw.fields_every) {
        (Some(_), Some(_)) => Err(bad(
            "dynamics.fields_every",
            "(with fields_at)",
            "give either fields_at (times) or fields_every (every N steps), not both",
        )),
        (None, Some(n)) => {
            if n.n == 0 {
                return Err(bad("dynamics.fields_every", 0, "must be >= 1 (steps)"));
            }
            Ok((0..=steps).step_by(n.n).collect())
        }
        (Some(times), None) => {
            let mut out: Vec<usize> = Vec::with_capacity(times.len());
            for (k, t) in times.iter().enumerate() {
                let field = format!("dynamics.fields_at[{k}]");
                if !(0.0..=duration).contains(&t.si()) {
                    return Err(bad(
                        field,
                        t,
                        format!("an output time must be in [0, duration = {duration:e} s]"),
                    ));
                }
                let n = ((t.si() / dt).round() as usize).min(steps);
                if out.last().is_some_and(|&p| n <= p) {
                    return Err(bad(
                        field,
                        t,
                        "output times must increase and fall on different time steps (each \
                         is taken at the nearest step)",
                    ));
                }
                out.push(n);
            }
            Ok(out)
        }
        (None, None) => Ok(Vec::new()),
    }
}

/// The density of each material of a region (every such material needs one).
fn densities(ctx: &DynamicsContext<'_>) -> CaseResult<BTreeMap<String, f64>> {
    let mut out = BTreeMap::new();
    for (k, (region, material)) in ctx.regions.iter().enumerate() {
        let field = format!("materials.{material}.density");
        match ctx.densities.get(material) {
            Some(Some(rho)) => {
                let [lo, hi] = DENSITY_RANGE;
                if !(lo..=hi).contains(&rho.si()) {
                    return Err(bad(
                        field,
                        rho,
                        format!(
                            "a density must be in [{lo:e}, {hi:e}] kg/m^3 (aerogels ~1, \
                             osmium 2.26e4); a value outside is a unit mistake"
                        ),
                    ));
                }
                out.insert(material.clone(), rho.si());
            }
            _ => {
                return Err(bad(
                    field,
                    "(missing)",
                    format!(
                        "region {region:?} (regions[{k}]) is of material {material:?}: a \
                         dynamic case needs its density (e.g. density = \"7850 kg/m^3\")"
                    ),
                ))
            }
        }
    }
    Ok(out)
}

/// A library error of a time function, renamed to the case's field.
fn renamed(field: &str, e: tribo::Error) -> CaseError {
    match e {
        tribo::Error::InvalidParameter {
            field: f,
            value,
            rule,
        } => CaseError::Field {
            field: f.replacen("time_function", field, 1),
            value,
            rule,
        },
        other => CaseError::Library(other),
    }
}

/// The time function of `raw` (errors name `field`, e.g. `bc[2].time`).
pub(crate) fn time_function(
    field: &str,
    raw: &RawTime,
    base_dir: &Path,
) -> CaseResult<TimeFunction> {
    let start = |s: &Option<Quantity<Time>>| s.as_ref().map_or(0.0, |s| s.si());
    let made = match raw {
        RawTime::Step => TimeFunction::step(0.0),
        RawTime::Table(RawTimeTable::Step(t0)) => TimeFunction::step(t0.si()),
        RawTime::Table(RawTimeTable::Ramp(rise, t0)) => {
            if rise.si() <= 0.0 {
                return Err(bad(
                    format!("{field}.ramp"),
                    rise,
                    "the rise time must be > 0 (s)",
                ));
            }
            TimeFunction::ramp(start(t0), rise.si())
        }
        RawTime::Table(RawTimeTable::Sine(f, t0, phase)) => {
            if f.si() <= 0.0 {
                return Err(bad(
                    format!("{field}.sine"),
                    f,
                    "the frequency must be > 0 (Hz)",
                ));
            }
            let phase = phase.as_ref().map_or(0.0, |p| p.si().to_radians());
            TimeFunction::sine(start(t0), f.si(), phase)
        }
        RawTime::Table(RawTimeTable::Points(points)) => {
            for (k, w) in points.windows(2).enumerate() {
                if w[1].0.si() <= w[0].0.si() {
                    return Err(bad(
                        format!("{field}.points[{}][0]", k + 1),
                        &w[1].0,
                        format!(
                            "times must increase strictly (the point before is at {})",
                            w[0].0
                        ),
                    ));
                }
            }
            if let Some((k, (_, f))) = points
                .iter()
                .enumerate()
                .find(|(_, (_, f))| f.si().abs() > MAX_TIME_FACTOR)
            {
                return Err(bad(format!("{field}.points[{k}][1]"), f, FACTOR_RULE));
            }
            TimeFunction::table(points.iter().map(|(t, f)| [t.si(), f.si()]).collect())
        }
        RawTime::Table(RawTimeTable::Csv(path)) => {
            let path = base_dir.join(path);
            return read_time_csv(&format!("{field}.csv"), &path);
        }
    };
    made.map_err(|e| renamed(field, e))
}

/// A tabulated time function from a CSV file: two columns, time (s) and factor, one row
/// per line; an optional header line first (a first line none of whose fields is a number,
/// so that a malformed first data row such as `0.001,abc` is an error, not a skipped header);
/// blank lines and lines starting with `#` skipped. Errors ([`CaseError::DataFile`]) carry
/// the 1-based line number: not two columns, not numbers, not finite, a factor above
/// [`MAX_TIME_FACTOR`] in magnitude, a time not after the one before; fewer than two rows.
pub fn read_time_csv(field: &str, path: &Path) -> CaseResult<TimeFunction> {
    let text = std::fs::read_to_string(path).map_err(|source| CaseError::Unreadable {
        field: field.to_string(),
        path: path.to_path_buf(),
        source,
    })?;
    let data_error = |line: usize, rule: String| CaseError::DataFile {
        field: field.to_string(),
        path: path.to_path_buf(),
        line,
        rule,
    };
    let mut points: Vec<[f64; 2]> = Vec::new();
    let mut seen_first = false;
    let mut last_line = 0;
    for (i, line) in text.lines().enumerate() {
        let n = i + 1;
        last_line = n;
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let first = !seen_first;
        seen_first = true;
        let cols: Vec<&str> = line.split(',').map(str::trim).collect();
        let parsed: Option<Vec<f64>> = cols.iter().map(|c| c.parse::<f64>().ok()).collect();
        let (cols, values) = match parsed {
            Some(v) if v.len() == 2 => (cols, v),
            // The header: no field of it reads as a number.
            _ if first && cols.iter().all(|c| c.parse::<f64>().is_err()) => continue,
            Some(v) => {
                return Err(data_error(
                    n,
                    format!("needs 2 columns (time s, factor), found {}", v.len()),
                ))
            }
            None => {
                return Err(data_error(
                    n,
                    format!("needs two numbers (time s, factor), found {line:?}"),
                ))
            }
        };
        if let Some(k) = values.iter().position(|v| !v.is_finite()) {
            return Err(data_error(n, format!("{} is not a finite number", cols[k])));
        }
        if values[1].abs() > MAX_TIME_FACTOR {
            return Err(data_error(
                n,
                format!("the factor {} {FACTOR_RULE}", cols[1]),
            ));
        }
        if let Some(p) = points.last() {
            if values[0] <= p[0] {
                return Err(data_error(
                    n,
                    format!(
                        "times must increase strictly: {} s follows {} s",
                        values[0], p[0]
                    ),
                ));
            }
        }
        points.push([values[0], values[1]]);
    }
    if points.len() < 2 {
        return Err(data_error(
            last_line,
            format!(
                "a time table needs at least 2 rows (time s, factor), found {}",
                points.len()
            ),
        ));
    }
    TimeFunction::table(points).map_err(|e| renamed(field, e))
}

/// The probes: named (unique, not empty), inside a region.
fn probe_specs(raw: Vec<RawProbe>, ctx: &DynamicsContext<'_>) -> CaseResult<Vec<ProbeSpec>> {
    let mut names = BTreeSet::new();
    let mut out = Vec::with_capacity(raw.len());
    for (k, p) in raw.into_iter().enumerate() {
        let field = format!("probe[{k}]");
        if p.name.trim().is_empty() || !names.insert(p.name.clone()) {
            return Err(bad(
                format!("{field}.name"),
                format!("{:?}", p.name),
                "probe names must be unique and not empty",
            ));
        }
        let at = [p.at[0].si(), p.at[1].si()];
        let region = (ctx.locate)(at).ok_or_else(|| {
            bad(
                format!("{field}.at"),
                format!("[{}, {}]", p.at[0], p.at[1]),
                "lies outside every region of the model (a probe records the field inside \
                 a body)",
            )
        })?;
        out.push(ProbeSpec {
            name: p.name,
            at,
            region,
        });
    }
    Ok(out)
}

// ---------------------------------------------------------------- locators

/// A closed polyline per loop of a region (arcs as 4096 chords, gmsh curves 64 per quadratic piece).
fn polylines<'a>(
    loops: &'a [Vec<LoopItem>],
    owned: &BTreeMap<&str, &'a SegmentShape>,
) -> Vec<Vec<[f64; 2]>> {
    loops
        .iter()
        .map(|l| {
            let mut pts = Vec::new();
            for item in l {
                let (shape, reversed) = match item {
                    LoopItem::Segment(s) => (Some(&s.shape), false),
                    LoopItem::Shared(name) => (owned.get(name.as_str()).copied(), true),
                };
                let Some(shape) = shape else { continue };
                let n = match shape {
                    SegmentShape::Line { .. } => 1,
                    SegmentShape::Arc { .. } => 4096,
                    SegmentShape::Meshed(c) => 64 * c.pieces().max(1),
                };
                for j in 0..n {
                    let t = j as f64 / n as f64;
                    pts.push(shape.point(if reversed { 1.0 - t } else { t }));
                }
            }
            pts
        })
        .collect()
}

/// Whether `p` is inside the loops (even-odd rule) or within `tol` of one of their edges.
fn inside(loops: &[Vec<[f64; 2]>], p: [f64; 2], tol: f64) -> bool {
    let mut crossings = 0usize;
    for l in loops {
        for (k, a) in l.iter().enumerate() {
            let b = l[(k + 1) % l.len()];
            // Distance to the edge: on the boundary counts as inside.
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            let len2 = dx * dx + dy * dy;
            let s = if len2 > 0.0 {
                (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let (fx, fy) = (a[0] + s * dx - p[0], a[1] + s * dy - p[1]);
            if fx.hypot(fy) <= tol {
                return true;
            }
            if (a[1] > p[1]) != (b[1] > p[1]) {
                let x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * dx;
                if x > p[0] {
                    crossings += 1;
                }
            }
        }
    }
    crossings % 2 == 1
}

/// The region holding a point, from (name, loops) of every region; `Shared` items are
/// resolved by name among the regions' own segments.
fn locator_of<'a>(
    regions: impl Iterator<Item = (&'a str, &'a [Vec<LoopItem>])> + Clone,
) -> impl Fn([f64; 2]) -> Option<String> {
    let mut owned: BTreeMap<&str, &SegmentShape> = BTreeMap::new();
    for (_, loops) in regions.clone() {
        for item in loops.iter().flatten() {
            if let LoopItem::Segment(s) = item {
                owned.insert(s.name.as_str(), &s.shape);
            }
        }
    }
    let shapes: Vec<(String, Vec<Vec<[f64; 2]>>)> = regions
        .map(|(name, loops)| (name.to_string(), polylines(loops, &owned)))
        .collect();
    let extent = shapes
        .iter()
        .flat_map(|s| s.1.iter().flatten())
        .fold(0.0_f64, |m, p| m.max(p[0].abs()).max(p[1].abs()));
    let tol = 1e-12 * extent.max(f64::MIN_POSITIVE);
    move |p| {
        if !(p[0].is_finite() && p[1].is_finite()) {
            return None;
        }
        shapes
            .iter()
            .find(|(_, loops)| inside(loops, p, tol))
            .map(|(name, _)| name.clone())
    }
}

/// The region of the case's outlines holding a point (on the boundary counts as inside;
/// arcs are taken as 4096 chords, so a point within 3e-7 of the radius of an arc may be
/// misjudged). Regions from gmsh files are not covered: use [`model_locator`].
pub fn outline_locator(regions: &[RegionSpec]) -> impl Fn([f64; 2]) -> Option<String> + '_ {
    locator_of(
        regions
            .iter()
            .map(|r| (r.name.as_str(), r.loops.as_slice())),
    )
}

/// The region of a built model holding a point (outlines and gmsh regions), as
/// [`outline_locator`].
pub fn model_locator(model: &BemModel) -> impl Fn([f64; 2]) -> Option<String> + '_ {
    locator_of(
        model
            .regions
            .iter()
            .map(|r| (r.name.as_str(), r.loops.as_slice())),
    )
}

#[cfg(test)]
mod tests;
