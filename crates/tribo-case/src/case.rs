//! Case files: TOML in, a validated [`HalfSpaceCase`] out, before any computation.
//!
//! The schema (every key; docs/user/case-halfspace.md is the user's reference):
//!
//! ```toml
//! title = "..."                    # optional
//! [body1]                          # body 1 defines the frame: x = its first principal direction
//! E = 2.01e11                      # Young's modulus, Pa (or "201 GPa")
//! nu = 0.3                         # Poisson's ratio, in (-1, 0.5)
//! radii = [0.005, 0.05]            # principal radii along x and y, m; < 0 concave; "inf" flat
//! # or, instead of radii, a surface: [body1.surface] kind = "roller" | "height_map"
//! [body2]
//! E = 2.01e11
//! nu = 0.3
//! radii = [-0.01, 0.01]
//! angle_deg = 0.0                  # angle from body 1's first principal plane to body 2's, deg
//! [contact]
//! load = 2000.0                    # N; or approach = 2.723e-5 (m); exactly one
//! # friction = 0.2                 # optional Coulomb f > 0, then exactly one of:
//! # tangential_load = 300.0        #   partial slip, |Q| on body 1, N (tangential_angle_deg, from x)
//! # sliding = true                 #   full sliding q = f p (sliding_angle_deg, from x)
//! [grid]                           # optional
//! n = 21                           # elements per side, or [nx, ny]; default 64
//! extent = 1.5                     # window half width / Hertz long semi-axis (radii only; default 1.5)
//! # half_width = 8e-4              # or the window half width in m, scalar or [x, y]
//! [solver]                         # optional
//! method = "cg"                    # "cg" (Polonsky-Keer) or "active_set" (dense, small grids)
//! tolerance = 1e-10
//! max_iterations = 10000
//! [bulk]                           # optional: the back effect of bulk loading, (18), Fig. 2a
//! shaft = "body2"                  # which body is the shaft: "body1" or "body2" (default body2)
//! shaft_radius = 0.01              # R2, m (default: the body's radius where it has one)
//! kind = "both"                    # "tension-compression", "bending" or "both" (default)
//! stress_max = 6.4e8               # sigma_a,max, Pa: the curve spans sigma/sigma_max in [-1, 1]
//! points = 21                      # points per curve, odd, 3 ... 1001 (default 21)
//! # stress = 3.2e8                 # optional operating bulk stress, Pa: F_N reported there
//! # bending_force = 5e3            # or, with kind = "bending": the operating bending stress
//! # span = 0.2                     #   4 M/(pi R^3) from a force (N), a span (m) and the
//! # support = "simply-supported"   #   support (M = F L/4; "cantilever": M = F L), with
//! # bending_side = "tension"       #   the contact on the tension or compression side
//! [field]                          # optional: the subsurface stress field
//! n = [39, 39, 20]                 # points along x, y, z (default the paper's)
//! extent = 1.5                     # x, y half width / Hertz a (or half_width, m)
//! depth = 1.5                      # depth / Hertz a (or depth_m, m); z down into the body
//! body = "body2"                   # the body the field is in (default body2)
//! # method = "direct"              # uniform points: "fft" (default, FFT + cubic interpolation)
//!                                  #   or "direct" (the exact direct sum, slow)
//! # points = "centres"             # instead of n and extent: x, y at the contact grid's
//! # layers = 20                    # element centres (FFT, for large grids), `layers` depths
//! # edge_refinement = "band"       # 1 (default, off: bilinear); "band": the edge-aware
//!                                  #   tractions near the contact edges at shallow depths;
//!                                  #   2 ... 16: the edge-aware tractions everywhere, on a
//!                                  #   grid this many times finer (slow)
//! ```

use crate::error::{CaseError, CaseResult};
use crate::units::{count, number, pair, quantity, show, Dim};
use serde::Deserialize;
use std::path::{Path, PathBuf};
use toml::Value;
use tribo::analysis::damage::{DamageQuantity, TensorKind};
use tribo::geometry::{
    Crown, HeightMap, LogarithmicCrown, QuadraticProfile, Roller, SurfaceProfile,
};
use tribo::grid::MAX_ELEMENTS_PER_SIDE;
use tribo::kernels::bulk::{bending_moment, bending_stress, BeamSupport};
use tribo::solvers::{NormalContactParams, NormalLoading};
use tribo::ElasticMaterial;

/// Largest grid (elements) accepted for the dense active-set solver: its influence matrix
/// needs (nx ny)^2 doubles, 128 MiB at this size.
pub const MAX_ACTIVE_SET_ELEMENTS: usize = 64 * 64;

/// Default number of elements per side when `[grid] n` is not given.
pub const DEFAULT_N: usize = 64;
/// Default window half width in units of the Hertz long semi-axis.
pub const DEFAULT_EXTENT: f64 = 1.5;

// ---------------------------------------------------------------- raw (serde) layer

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCase {
    title: Option<String>,
    body1: RawBody,
    body2: RawBody,
    contact: RawContact,
    grid: Option<RawGrid>,
    solver: Option<RawSolver>,
    bulk: Option<RawBulk>,
    field: Option<RawField>,
    damage: Option<RawDamage>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDamage {
    criteria: Option<Value>,
    limit_over_p0: Option<Value>,
    limit_load: Option<Value>,
    limits: Option<toml::Table>,
    study: Option<RawStudy>,
    cycle: Option<RawCycle>,
    energy: Option<RawEnergy>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawEnergy {
    a_n: Option<Value>,
    a_tau: Option<Value>,
    a_t: Option<Value>,
    a_tau_n: Option<Value>,
    a_m_t: Option<Value>,
    temperature: Option<Value>,
    u0: Option<Value>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCycle {
    kind: Option<Value>,
    amplitude: Option<Value>,
    amplitude_over_p0: Option<Value>,
    speed: Option<Value>,
    period: Option<Value>,
    steps: Option<Value>,
    cycles: Option<Value>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawStudy {
    bending_over_p0: Option<Value>,
    limit_over_p0: Option<Value>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBody {
    #[serde(rename = "E")]
    e: Value,
    nu: Value,
    radii: Option<Value>,
    angle_deg: Option<Value>,
    surface: Option<RawSurface>,
}

#[derive(Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
enum RawSurface {
    Roller {
        radius: Value,
        length: Value,
        crown: Option<String>,
        crown_radius: Option<Value>,
        flat_length: Option<Value>,
        design_load: Option<Value>,
        crown_drop: Option<Value>,
    },
    HeightMap {
        file: Option<String>,
        heights: Option<Vec<Vec<Value>>>,
        spacing: Value,
        scale: Option<Value>,
    },
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawContact {
    load: Option<Value>,
    approach: Option<Value>,
    friction: Option<Value>,
    tangential_load: Option<Value>,
    tangential_angle_deg: Option<Value>,
    sliding: Option<Value>,
    sliding_angle_deg: Option<Value>,
    traction_direction: Option<Value>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawField {
    points: Option<Value>,
    method: Option<Value>,
    layers: Option<Value>,
    n: Option<Value>,
    extent: Option<Value>,
    half_width: Option<Value>,
    depth: Option<Value>,
    depth_m: Option<Value>,
    body: Option<Value>,
    edge_refinement: Option<Value>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGrid {
    n: Option<Value>,
    extent: Option<Value>,
    half_width: Option<Value>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSolver {
    method: Option<Method>,
    tolerance: Option<Value>,
    max_iterations: Option<Value>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBulk {
    shaft: Option<Value>,
    shaft_radius: Option<Value>,
    kind: Option<Value>,
    stress_max: Option<Value>,
    points: Option<Value>,
    stress: Option<Value>,
    bending_force: Option<Value>,
    span: Option<Value>,
    support: Option<Value>,
    bending_side: Option<Value>,
}

// ---------------------------------------------------------------- validated layer

/// The normal contact solver to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// Constrained conjugate gradients (Polonsky & Keer 1999) with FFT convolution.
    Cg,
    /// The paper's "matrix inversion": active set with a dense factorization (small grids).
    ActiveSet,
}

impl Method {
    /// The name used in case files and summaries.
    pub fn name(self) -> &'static str {
        match self {
            Method::Cg => "cg",
            Method::ActiveSet => "active_set",
        }
    }
}

/// One body's shape.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// Principal radii (m, signed; infinite = flat) and the angle (rad) of the first principal
    /// direction from the x axis.
    Radii {
        /// R along x' and y', m.
        radii: [f64; 2],
        /// Angle of x' from x, rad.
        angle: f64,
    },
    /// A general surface (roller, height map).
    Surface(SurfaceProfile),
}

/// One validated body.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// Elastic constants.
    pub material: ElasticMaterial,
    /// Shape of the surface.
    pub shape: Shape,
}

impl Body {
    /// The body's surface profile in the common frame (see [`tribo::geometry`]).
    pub fn profile(&self, field: &str) -> tribo::Result<SurfaceProfile> {
        match &self.shape {
            Shape::Radii { radii, angle } => Ok(SurfaceProfile::Quadratic(
                QuadraticProfile::from_radii(&format!("{field}.radii"), *radii, *angle)?,
            )),
            Shape::Surface(s) => Ok(s.clone()),
        }
    }
}

/// How the computational window is sized.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Window {
    /// Half width = extent * (Hertz long semi-axis), square; Hertzian gaps only.
    Extent(f64),
    /// Half widths (x, y), m.
    HalfWidth([f64; 2]),
}

/// Default number of points per back-effect curve.
pub const DEFAULT_BULK_POINTS: usize = 21;
/// Most points per back-effect curve (each is one contact solution).
pub const MAX_BULK_POINTS: usize = 1001;

/// A kind of bulk load of the shaft, as the back effect (18) distinguishes them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LoadKind {
    /// Tension-compression: u_z = -(nu/E) sigma R2.
    TensionCompression,
    /// Bending: u_z = -(nu/(2E)) sigma R2.
    Bending,
}

impl LoadKind {
    /// The name used in case files and outputs.
    pub fn name(self) -> &'static str {
        match self {
            LoadKind::TensionCompression => "tension-compression",
            LoadKind::Bending => "bending",
        }
    }

    /// The bulk load of this kind with axial stress `sigma` (Pa) at the contact.
    pub fn load(self, sigma: f64) -> tribo::kernels::bulk::BulkLoad {
        use tribo::kernels::bulk::BulkLoad;
        match self {
            LoadKind::TensionCompression => BulkLoad::TensionCompression { stress: sigma },
            LoadKind::Bending => BulkLoad::Bending {
                surface_stress: sigma,
            },
        }
    }
}

/// The validated `[bulk]` section: the back effect of bulk loading of the shaft.
#[derive(Debug, Clone, PartialEq)]
pub struct Bulk {
    /// Which body is the shaft: "body1" or "body2".
    pub shaft: &'static str,
    /// Shaft radius R2, m.
    pub shaft_radius: f64,
    /// The load kinds, tension-compression first.
    pub kinds: Vec<LoadKind>,
    /// sigma_a,max, Pa.
    pub stress_max: f64,
    /// Points per curve (odd, so that sigma = 0 is one of them).
    pub points: usize,
    /// An operating bulk stress, Pa, at which F_N is reported.
    pub stress: Option<f64>,
}

impl Bulk {
    /// The stress ratios sigma/sigma_max of the curve: `points` values evenly over [-1, 1].
    pub fn ratios(&self) -> Vec<f64> {
        // (2k - m) / m: one correctly rounded division, so 0.1 is 0.1 and the middle is 0.
        let m = self.points as f64 - 1.0;
        (0..self.points).map(|k| (2.0 * k as f64 - m) / m).collect()
    }
}

/// The validated friction keys of `[contact]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Friction {
    /// Coulomb friction coefficient f.
    pub coefficient: f64,
    /// Partial slip under a force, or full sliding (angles in rad from x).
    pub loading: tribo::solvers::tangential::TangentialLoading,
    /// Partial slip with the traction direction free (`traction_direction = "free"`, the
    /// full 2D problem) instead of parallel to the load (Cattaneo-Mindlin's assumption).
    pub free_direction: bool,
}

impl Friction {
    /// "partial_slip" or "sliding".
    pub fn mode(&self) -> &'static str {
        match self.loading {
            tribo::solvers::tangential::TangentialLoading::Force { .. } => "partial_slip",
            tribo::solvers::tangential::TangentialLoading::Sliding { .. } => "sliding",
        }
    }
}

/// Default field points [nx, ny, nz] (the paper's Sec. 6 grid).
pub const DEFAULT_FIELD_N: [usize; 3] = [39, 39, 20];
/// Most field points per direction.
pub const MAX_FIELD_N: usize = 512;
/// Most field points in all (nx ny nz).
pub const MAX_FIELD_POINTS: usize = 2_000_000;
/// Default field half width and depth in units of the Hertz long semi-axis.
pub const DEFAULT_FIELD_EXTENT: f64 = 1.5;
/// Largest `[field] edge_refinement`: the limit of
/// `tribo::analysis::edge_refinement::refine_tractions` (the refined grid has factor^2 times
/// the elements).
pub const MAX_EDGE_REFINEMENT: usize = 16;
/// `[field] edge_refinement = "band"`, stored as 0: the element tractions with the edge band (`tribo::analysis::edge_refinement::EdgeBand`, docs/theory/HALFSPACE.md
/// 2.5), the edge-aware tractions near the contact edges at the surface and shallow depths.
pub const EDGE_REFINEMENT_BAND: usize = 0;

/// A length given in units of the Hertz long semi-axis a, or in m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Length {
    /// Multiple of a (Hertzian gaps only).
    Semi(f64),
    /// Metres.
    Metres(f64),
}

/// Where the field points lie in x and y.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FieldPoints {
    /// `n` points evenly spaced over the field's half width, end points included; the
    /// stresses by the direct sum over the loaded elements (exact at any point).
    Uniform,
    /// The element centres of the contact grid; the stresses by FFT convolution per depth
    /// (the same kernels; cost O(layers N log N), for large contact grids).
    Centres,
}

/// How the stresses at uniform field points are computed (`[field] method`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FieldMethod {
    /// "fft" (default): FFT on the contact grid's element centres, extended with zero
    /// tractions over the field box, at the field depths, then cubic interpolation in x and y
    /// (`tribo::analysis::stress_field::stress_field_interpolated`).
    Fft,
    /// "direct": the direct sum over the loaded elements, exact at any point (slow: points x
    /// loaded elements).
    Direct,
}

/// The validated `[field]` section: the subsurface stress field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FieldSpec {
    /// Where the points lie in x and y.
    pub points: FieldPoints,
    /// How uniform points are computed.
    pub method: FieldMethod,
    /// Points along x, y, z (for [`FieldPoints::Centres`], the contact grid's nx, ny).
    pub n: [usize; 3],
    /// Half width of the field in x and y (unused, zero, for [`FieldPoints::Centres`]).
    pub half_width: Length,
    /// Depth of the field.
    pub depth: Length,
    /// The body the field is computed in ("body1" or "body2").
    pub body: &'static str,
    /// `edge_refinement`: 1 (the default) the element tractions interpolated bilinearly;
    /// [`EDGE_REFINEMENT_BAND`] ("band") with the edge band (the edge-aware tractions near
    /// the contact edges, at the surface and shallow depths); N > 1 of the edge-aware reconstruction of the tractions (a
    /// square-root contact edge at a sub-element position) sampled on a grid N times finer per
    /// side, [`tribo::analysis::edge_refinement::refine_tractions`] (docs/theory/HALFSPACE.md
    /// 2.5). In 1 ..= [`MAX_EDGE_REFINEMENT`], with N times the contact grid's elements per
    /// side within [`MAX_ELEMENTS_PER_SIDE`].
    pub edge_refinement: usize,
}

/// Where a damage criterion's limit phi_q^lim comes from ((19)-(20)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LimitSource {
    /// Given in `[damage.limits]` (material data), in the quantity's unit.
    Given(f64),
    /// A multiple of p0, the largest contact pressure of the run (stress quantities).
    OverP0(f64),
    /// The extreme of the field under the limiting load `damage.limit_load` (N).
    LimitingLoad(f64),
}

/// The validated `[damage]` section: volume damageability (19)-(24).
#[derive(Debug, Clone, PartialEq)]
pub struct DamageSpec {
    /// The criteria with the source of each limit.
    pub criteria: Vec<(DamageQuantity, LimitSource)>,
    /// The limiting load F_lim, N, where some limit comes from it.
    pub limit_load: Option<f64>,
    /// The paper's Sec. 6 study (`[damage.study]`).
    pub study: Option<StudySpec>,
    /// Accumulation over a load cycle (`[damage.cycle]`), (23), (24), (36).
    pub cycle: Option<CycleSpec>,
}

/// The load history of one cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CycleKind {
    /// A rotating bent shaft under the fixed roller: sigma_b(t) = sigma_a cos(2 pi t / T)
    /// superposed on the contact field; the amplitude in Pa.
    RotatingBending {
        /// sigma_a, Pa (> 0 starts in the tension zone).
        amplitude: CycleAmplitude,
    },
    /// Rolling: the contact field moves along y at `speed` (m/s).
    Rolling {
        /// v, m/s.
        speed: f64,
    },
}

/// A bending amplitude in Pa or as a multiple of p0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CycleAmplitude {
    /// Pa.
    Pascal(f64),
    /// sigma_a / p0.
    OverP0(f64),
}

/// The validated `[damage.cycle]` table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CycleSpec {
    /// The history.
    pub kind: CycleKind,
    /// Duration of one cycle (one revolution), s.
    pub period: f64,
    /// Time steps per cycle.
    pub steps: usize,
    /// Number of cycles N for the totals.
    pub cycles: f64,
}

/// The validated `[damage.study]` table: the paper's Sec. 6 loadings n, n + tau, n + tau + b
/// over a range of bending stresses.
#[derive(Debug, Clone, PartialEq)]
pub struct StudySpec {
    /// sigma_b / p0 values (>= 0, increasing).
    pub bending_over_p0: Vec<f64>,
    /// The intensity limit over p0 (the paper: 0.186).
    pub limit_over_p0: f64,
}

/// A validated case, ready to run.
#[derive(Debug, Clone, PartialEq)]
pub struct HalfSpaceCase {
    /// Title (the file name where none is given).
    pub title: String,
    /// Where the case came from (a path, or `<embedded NAME>`).
    pub source: String,
    /// Body 1 (defines the frame).
    pub body1: Body,
    /// Body 2.
    pub body2: Body,
    /// Force or approach control.
    pub loading: NormalLoading,
    /// Elements along x and y.
    pub n: [usize; 2],
    /// Window size.
    pub window: Window,
    /// Solver.
    pub method: Method,
    /// Solver parameters.
    pub params: NormalContactParams,
    /// The back effect of bulk loading, where asked for.
    pub bulk: Option<Bulk>,
    /// Friction: the tangential problem, where `contact.friction` is given.
    pub friction: Option<Friction>,
    /// The subsurface stress field, where `[field]` is given.
    pub field: Option<FieldSpec>,
    /// Volume damageability, where `[damage]` is given.
    pub damage: Option<DamageSpec>,
    /// The case as written (TOML converted to JSON), echoed in `summary.json`.
    pub echo: serde_json::Value,
}

impl HalfSpaceCase {
    /// Whether both bodies are given by radii, so that the gap is Hertzian.
    pub fn is_hertzian(&self) -> bool {
        matches!(self.body1.shape, Shape::Radii { .. })
            && matches!(self.body2.shape, Shape::Radii { .. })
    }

    /// Composite modulus E*, Pa.
    pub fn composite_modulus(&self) -> f64 {
        tribo::composite_modulus(&self.body1.material, &self.body2.material)
    }

    /// The body named `name` ("body1" or "body2").
    pub fn body(&self, name: &str) -> &Body {
        if name == "body1" {
            &self.body1
        } else {
            &self.body2
        }
    }
}

/// Parse and validate a case file's text. `source` names it in errors; `base_dir` resolves
/// relative file paths (height maps).
pub fn parse_case(text: &str, source: &str, base_dir: &Path) -> CaseResult<HalfSpaceCase> {
    let (raw, echo) = parse_raw::<RawCase>(text, source)?;
    validate(raw, source, base_dir, echo)
}

/// Validate a case given as a TOML table (the same schema and rules as a case file; see
/// [`crate::builder::CaseBuilder`] for building one in code). `source` names it in errors;
/// `base_dir` resolves relative file paths (height maps).
pub fn from_table(table: toml::Table, source: &str, base_dir: &Path) -> CaseResult<HalfSpaceCase> {
    let value = Value::Table(table);
    let echo = echo_json(&value);
    let raw = RawCase::deserialize(value).map_err(|e| CaseError::Parse {
        path: source.to_string(),
        message: e.to_string().trim_end().to_string(),
    })?;
    validate(raw, source, base_dir, echo)
}

/// The case text parsed into the raw (serde) schema `T`, and the case as JSON (echoed in
/// the summary). Errors name `source` and carry the parser's line and column.
pub fn parse_raw<T: serde::de::DeserializeOwned>(
    text: &str,
    source: &str,
) -> CaseResult<(T, serde_json::Value)> {
    let parse_error = |message: String| CaseError::Parse {
        path: source.to_string(),
        message,
    };
    let raw: T =
        toml::from_str(text).map_err(|e| parse_error(e.to_string().trim_end().to_string()))?;
    let table: toml::Table = toml::from_str(text).map_err(|e| parse_error(e.to_string()))?;
    let echo = echo_json(&Value::Table(table));
    Ok((raw, echo))
}

/// The case as JSON for the summary's echo. JSON has no infinity: TOML's `inf`, `-inf` and
/// `nan` floats are echoed as the strings "inf", "-inf" and "nan" (serde_json would write
/// null, which reads back as a different case); dates as their TOML text.
fn echo_json(v: &Value) -> serde_json::Value {
    use serde_json::Value as J;
    match v {
        Value::String(s) => J::String(s.clone()),
        Value::Integer(i) => J::from(*i),
        Value::Float(x) if x.is_nan() => J::String("nan".into()),
        Value::Float(x) if x.is_infinite() => {
            J::String(if *x > 0.0 { "inf" } else { "-inf" }.into())
        }
        Value::Float(x) => J::from(*x),
        Value::Boolean(b) => J::Bool(*b),
        Value::Datetime(d) => J::String(d.to_string()),
        Value::Array(a) => J::Array(a.iter().map(echo_json).collect()),
        Value::Table(t) => J::Object(t.iter().map(|(k, v)| (k.clone(), echo_json(v))).collect()),
    }
}

fn validate(
    raw: RawCase,
    source: &str,
    base_dir: &Path,
    echo: serde_json::Value,
) -> CaseResult<HalfSpaceCase> {
    let m1 = material("body1", &raw.body1)?;
    let m2 = material("body2", &raw.body2)?;
    let e_star = tribo::composite_modulus(&m1, &m2);

    let loading = loading(&raw.contact)?;

    if let Some(a) = &raw.body1.angle_deg {
        return Err(CaseError::field(
            "body1.angle_deg",
            show(a),
            "not allowed: body 1's first principal direction defines the x axis; \
             give the angle between the bodies as body2.angle_deg",
        ));
    }
    let ctx = ShapeContext {
        e_star,
        loading,
        base_dir,
    };
    let shape1 = shape("body1", raw.body1, &ctx)?;
    let shape2 = shape("body2", raw.body2, &ctx)?;
    let hertzian = matches!(shape1, Shape::Radii { .. }) && matches!(shape2, Shape::Radii { .. });
    if let (Shape::Radii { radii: r1, .. }, Shape::Radii { radii: r2, angle }) = (&shape1, &shape2)
    {
        check_convex(*r1, *r2, *angle)?;
    }

    let grid = raw.grid.unwrap_or(RawGrid {
        n: None,
        extent: None,
        half_width: None,
    });
    let n = match &grid.n {
        None => [DEFAULT_N; 2],
        Some(v) => pair("grid.n", v, count)?,
    };
    for (k, nk) in n.iter().enumerate() {
        let f = if matches!(grid.n, Some(Value::Array(_))) {
            format!("grid.n[{k}]")
        } else {
            "grid.n".to_string()
        };
        if *nk < 4 {
            return Err(CaseError::field(
                f,
                nk,
                "at least 4 elements per side are needed",
            ));
        }
        if *nk > MAX_ELEMENTS_PER_SIDE {
            return Err(CaseError::field(
                f,
                nk,
                format!("at most {MAX_ELEMENTS_PER_SIDE} elements per side (memory)"),
            ));
        }
    }
    let window = match (&grid.extent, &grid.half_width) {
        (Some(e), Some(_)) => {
            return Err(CaseError::field(
                "grid.extent",
                show(e),
                "give either grid.extent or grid.half_width, not both",
            ))
        }
        (Some(e), None) => {
            let x = number("grid.extent", e)?;
            if !hertzian {
                return Err(CaseError::field(
                    "grid.extent",
                    show(e),
                    "extent is in units of the Hertz semi-axis, defined only where both bodies \
                     are given by radii; give grid.half_width (m) for a surface",
                ));
            }
            if !(x.is_finite() && x > 1.0) {
                return Err(CaseError::field(
                    "grid.extent",
                    show(e),
                    "must be a finite number > 1 (the window must contain the Hertz contact)",
                ));
            }
            Window::Extent(x)
        }
        (None, Some(h)) => {
            let hw = pair("grid.half_width", h, |f, v| quantity(f, v, Dim::Length))?;
            for (k, w) in hw.iter().enumerate() {
                if !(w.is_finite() && *w > 0.0) {
                    return Err(CaseError::field(
                        format!("grid.half_width[{k}]"),
                        w,
                        "the window half width must be finite and > 0 (m)",
                    ));
                }
                crate::units::check_length(&format!("grid.half_width[{k}]"), h, *w)?;
            }
            Window::HalfWidth(hw)
        }
        (None, None) => {
            if !hertzian {
                return Err(CaseError::field(
                    "grid.half_width",
                    "(missing)",
                    "required where a body is given by a surface (the window cannot be sized \
                     from Hertz theory): give the window half width in m, scalar or [x, y]",
                ));
            }
            Window::Extent(DEFAULT_EXTENT)
        }
    };
    if let Window::HalfWidth(hw) = window {
        for (name, s) in [("body1", &shape1), ("body2", &shape2)] {
            if let Shape::Surface(SurfaceProfile::HeightMap(m)) = s {
                let (mx, my) = m.half_extents();
                if hw[0] > mx * (1.0 + 1e-12) || hw[1] > my * (1.0 + 1e-12) {
                    return Err(CaseError::field(
                        "grid.half_width",
                        format!("[{}, {}]", hw[0], hw[1]),
                        format!(
                            "the window must lie within the height map of {name}, which covers \
                             |x| <= {mx:e} m, |y| <= {my:e} m"
                        ),
                    ));
                }
            }
        }
    }

    let (method, params) = solver(raw.solver, n)?;
    let bulk = match raw.bulk {
        None => None,
        Some(b) => Some(bulk(b, &shape1, &shape2)?),
    };

    let friction = friction(&raw.contact)?;
    let field = match raw.field {
        None => None,
        Some(f) => Some(field_spec(f, hertzian, n)?),
    };
    let damage = match raw.damage {
        None => None,
        Some(d) => {
            if field.is_none() {
                return Err(CaseError::field(
                    "damage",
                    "given",
                    "needs a [field] section: the damage measures are integrals over the \
                     stress field's points",
                ));
            }
            Some(damage_spec(d, &loading, bulk.as_ref())?)
        }
    };
    let title = raw.title.unwrap_or_else(|| source.to_string());
    Ok(HalfSpaceCase {
        title,
        source: source.to_string(),
        body1: Body {
            material: m1,
            shape: shape1,
        },
        body2: Body {
            material: m2,
            shape: shape2,
        },
        loading,
        n,
        window,
        method,
        params,
        bulk,
        friction,
        field,
        damage,
        echo,
    })
}

/// The damage quantities a case file may name (`damage.criteria`): every stress and strain
/// quantity of (19)-(20) by its [`DamageQuantity::name`].
pub fn damage_vocabulary() -> Vec<DamageQuantity> {
    let mut v = DamageQuantity::standard_set(TensorKind::Stress);
    v.extend(DamageQuantity::standard_set(TensorKind::Strain));
    v
}

fn damage_spec(
    d: RawDamage,
    loading: &NormalLoading,
    bulk: Option<&Bulk>,
) -> CaseResult<DamageSpec> {
    let vocabulary = damage_vocabulary();
    let known = || {
        vocabulary
            .iter()
            .map(|q| q.name())
            .collect::<Vec<_>>()
            .join(", ")
    };
    let names: Vec<String> = match &d.criteria {
        // With [damage.energy] alone: only the effective energy.
        None if d.energy.is_some() => Vec::new(),
        None => vec!["sigma_int".into()],
        Some(Value::Array(a)) if !a.is_empty() => {
            let mut names = Vec::new();
            for (k, v) in a.iter().enumerate() {
                match v {
                    Value::String(s) => names.push(s.clone()),
                    _ => {
                        return Err(CaseError::field(
                            format!("damage.criteria[{k}]"),
                            show(v),
                            "must be the name of a quantity, e.g. \"sigma_int\"",
                        ))
                    }
                }
            }
            names
        }
        Some(v) => {
            return Err(CaseError::field(
                "damage.criteria",
                show(v),
                "must be a non-empty list of quantity names, e.g. [\"sigma_int\", \"u\"]",
            ))
        }
    };
    // Two default limits for the criteria without their own: the second would be silently
    // ignored (limit_load took precedence), so exactly one may be given.
    if let (Some(l), Some(_)) = (&d.limit_load, &d.limit_over_p0) {
        return Err(CaseError::field(
            "damage.limit_load",
            format!("{} (and damage.limit_over_p0)", show(l)),
            "give at most one of damage.limit_load (N) and damage.limit_over_p0 (the default \
             limit of the criteria without their own in damage.limits), not both",
        ));
    }
    let over_p0 = match &d.limit_over_p0 {
        None => None,
        Some(v) => Some(positive_number("damage.limit_over_p0", v)?),
    };
    let limit_load = match &d.limit_load {
        None => None,
        Some(v) => {
            if !matches!(loading, NormalLoading::Force(_)) {
                return Err(CaseError::field(
                    "damage.limit_load",
                    show(v),
                    "needs force control (contact.load): the limiting state is the same case \
                     at the load F_lim",
                ));
            }
            Some(positive(
                "damage.limit_load",
                v,
                Dim::Force,
                "the limiting load F_lim (N)",
            )?)
        }
    };
    let limits = d.limits.unwrap_or_default();
    for key in limits.keys() {
        if !names.iter().any(|n| n == key) {
            return Err(CaseError::field(
                format!("damage.limits.{key}"),
                "given",
                "is not one of damage.criteria",
            ));
        }
    }
    let mut criteria = Vec::new();
    for (k, name) in names.iter().enumerate() {
        let Some(quantity) = vocabulary.iter().find(|q| &q.name() == name).copied() else {
            return Err(CaseError::field(
                format!("damage.criteria[{k}]"),
                name,
                format!("unknown quantity; known: {}", known()),
            ));
        };
        if criteria.iter().any(|(q, _)| *q == quantity) {
            return Err(CaseError::field(
                format!("damage.criteria[{k}]"),
                name,
                "is named twice",
            ));
        }
        let field = format!("damage.limits.{name}");
        let source = if let Some(v) = limits.get(name) {
            let dim = match quantity.unit() {
                "Pa" => Some(Dim::Pressure),
                _ => None,
            };
            let x = match dim {
                Some(dim) => crate::units::quantity(&field, v, dim)?,
                None => number(&field, v)?,
            };
            tribo::analysis::damage::Limit::new(quantity, x)
                .map_err(|e| CaseError::field(&field, show(v), strip_field(&e.to_string())))?;
            LimitSource::Given(x)
        } else if limit_load.is_some() {
            LimitSource::LimitingLoad(limit_load.unwrap_or(0.0))
        } else if let Some(r) = over_p0 {
            if quantity.unit() != "Pa" {
                return Err(CaseError::field(
                    &field,
                    "(missing)",
                    format!(
                        "damage.limit_over_p0 applies to stresses only; give the limit of \
                         {name} ({}) here, or damage.limit_load",
                        quantity.unit()
                    ),
                ));
            }
            if quantity.sense() == Some(tribo::analysis::damage::Sense::Compression) {
                LimitSource::OverP0(-r)
            } else {
                LimitSource::OverP0(r)
            }
        } else {
            return Err(CaseError::field(
                &field,
                "(missing)",
                "required: give the limit here (material data), or damage.limit_over_p0 \
                 (stresses, a multiple of p0), or damage.limit_load (the field's extremes at \
                 the limiting load, (19))",
            ));
        };
        criteria.push((quantity, source));
    }
    if let Some(e) = &d.energy {
        // The generalized energy criterion (25)-(36): u_eff with the limit u0 (34).
        let coefficient = |key: &str, v: &Option<Value>, default: f64| -> CaseResult<f64> {
            match v {
                None => Ok(default),
                Some(v) => number(&format!("damage.energy.{key}"), v),
            }
        };
        let m = tribo::analysis::energy_criterion::EnergyCoefficients::MECHANICAL;
        let coefficients = tribo::analysis::energy_criterion::EnergyCoefficients {
            a_n: coefficient("a_n", &e.a_n, m.a_n)?,
            a_tau: coefficient("a_tau", &e.a_tau, m.a_tau)?,
            a_t: coefficient("a_t", &e.a_t, m.a_t)?,
            a_tau_n: coefficient("a_tau_n", &e.a_tau_n, m.a_tau_n)?,
            a_m_t: coefficient("a_m_t", &e.a_m_t, m.a_m_t)?,
        };
        coefficients
            .validate("damage.energy")
            .map_err(CaseError::from)?;
        let temperature = coefficient("temperature", &e.temperature, 293.15)?;
        if !(temperature.is_finite() && temperature >= 0.0) {
            return Err(CaseError::field(
                "damage.energy.temperature",
                temperature,
                "must be finite and >= 0 K (absolute temperature)",
            ));
        }
        let u0 = match &e.u0 {
            Some(v) => number("damage.energy.u0", v)?,
            None => {
                return Err(CaseError::field(
                    "damage.energy.u0",
                    "(missing)",
                    "required: the activation energy per unit volume u0, J/m^3",
                ))
            }
        };
        if !(u0.is_finite() && u0 > 0.0) {
            return Err(CaseError::field(
                "damage.energy.u0",
                u0,
                "must be finite and > 0 (J/m^3)",
            ));
        }
        criteria.push((
            DamageQuantity::EffectiveEnergy {
                coefficients,
                temperature,
            },
            LimitSource::Given(u0),
        ));
    }
    let study = match d.study {
        None => None,
        Some(st) => {
            let Some(b) = bulk else {
                return Err(CaseError::field(
                    "damage.study",
                    "given",
                    "needs a [bulk] section for the shaft (bulk.shaft, bulk.shaft_radius)",
                ));
            };
            let _ = b;
            let values = match &st.bending_over_p0 {
                Some(Value::Array(a)) if !a.is_empty() && a.len() <= 101 => {
                    let mut out = Vec::new();
                    for (k, v) in a.iter().enumerate() {
                        let f = format!("damage.study.bending_over_p0[{k}]");
                        let x = number(&f, v)?;
                        if !(x.is_finite() && x >= 0.0) || out.last().is_some_and(|&l| x <= l) {
                            return Err(CaseError::field(
                                f,
                                show(v),
                                "must be finite, >= 0 and increasing (sigma_b / p0; the zone \
                                 gives the sign)",
                            ));
                        }
                        out.push(x);
                    }
                    out
                }
                Some(v) => {
                    return Err(CaseError::field(
                        "damage.study.bending_over_p0",
                        show(v),
                        "must be a list of 1 ... 101 values sigma_b / p0",
                    ))
                }
                None => (0..=12).map(|k| 0.025 * k as f64).collect(),
            };
            let limit_over_p0 = match &st.limit_over_p0 {
                None => 0.186,
                Some(v) => positive_number("damage.study.limit_over_p0", v)?,
            };
            Some(StudySpec {
                bending_over_p0: values,
                limit_over_p0,
            })
        }
    };
    let cycle = match d.cycle {
        None => None,
        Some(c) => Some(cycle_spec(c, bulk)?),
    };
    Ok(DamageSpec {
        criteria,
        limit_load,
        study,
        cycle,
    })
}

fn cycle_spec(c: RawCycle, bulk: Option<&Bulk>) -> CaseResult<CycleSpec> {
    let kind = match &c.kind {
        Some(Value::String(k)) if k == "rotating-bending" => {
            if bulk.is_none() {
                return Err(CaseError::field(
                    "damage.cycle.kind",
                    k,
                    "rotating bending needs a [bulk] section (the shaft and its radius)",
                ));
            }
            let amplitude = match (&c.amplitude, &c.amplitude_over_p0) {
                (Some(v), None) => {
                    let x = crate::units::quantity("damage.cycle.amplitude", v, Dim::Pressure)?;
                    if !(x.is_finite() && x != 0.0) {
                        return Err(CaseError::field(
                            "damage.cycle.amplitude",
                            show(v),
                            "must be finite and non-zero (Pa; > 0 starts in the tension zone)",
                        ));
                    }
                    CycleAmplitude::Pascal(x)
                }
                (None, Some(v)) => {
                    let x = number("damage.cycle.amplitude_over_p0", v)?;
                    if !(x.is_finite() && x != 0.0) {
                        return Err(CaseError::field(
                            "damage.cycle.amplitude_over_p0",
                            show(v),
                            "must be finite and non-zero (sigma_a / p0)",
                        ));
                    }
                    CycleAmplitude::OverP0(x)
                }
                _ => {
                    return Err(CaseError::field(
                        "damage.cycle.amplitude",
                        "(missing or doubled)",
                        "give exactly one of amplitude (Pa) and amplitude_over_p0",
                    ))
                }
            };
            if c.speed.is_some() {
                return Err(CaseError::field(
                    "damage.cycle.speed",
                    "given",
                    "only for kind = \"rolling\"",
                ));
            }
            CycleKind::RotatingBending { amplitude }
        }
        Some(Value::String(k)) if k == "rolling" => {
            if c.amplitude.is_some() || c.amplitude_over_p0.is_some() {
                return Err(CaseError::field(
                    "damage.cycle.amplitude",
                    "given",
                    "only for kind = \"rotating-bending\"",
                ));
            }
            let speed = match &c.speed {
                Some(v) => number("damage.cycle.speed", v)?,
                None => {
                    return Err(CaseError::field(
                        "damage.cycle.speed",
                        "(missing)",
                        "required for rolling: the speed of the contact along y, m/s",
                    ))
                }
            };
            if !(speed.is_finite() && speed != 0.0) {
                return Err(CaseError::field(
                    "damage.cycle.speed",
                    speed,
                    "must be finite and non-zero (m/s)",
                ));
            }
            CycleKind::Rolling { speed }
        }
        other => {
            return Err(CaseError::field(
                "damage.cycle.kind",
                other.as_ref().map_or("(missing)".to_string(), show),
                "must be \"rotating-bending\" (a bent shaft turning under the roller) or \
                 \"rolling\" (the contact moving along y)",
            ))
        }
    };
    let period = match &c.period {
        Some(v) => positive_number("damage.cycle.period", v)?,
        None => {
            return Err(CaseError::field(
                "damage.cycle.period",
                "(missing)",
                "required: the duration of one cycle (one revolution), s",
            ))
        }
    };
    let steps = match &c.steps {
        None => 36,
        Some(v) => {
            let k = count("damage.cycle.steps", v)?;
            if !(2..=3600).contains(&k) {
                return Err(CaseError::field(
                    "damage.cycle.steps",
                    k,
                    "must be in 2 ... 3600 time steps per cycle",
                ));
            }
            k
        }
    };
    let cycles = match &c.cycles {
        None => 1.0,
        Some(v) => positive_number("damage.cycles", v).map_err(|_| {
            CaseError::field(
                "damage.cycle.cycles",
                show(v),
                "must be finite and > 0 (the number of cycles N)",
            )
        })?,
    };
    Ok(CycleSpec {
        kind,
        period,
        steps,
        cycles,
    })
}

fn positive_number(field: &str, v: &Value) -> CaseResult<f64> {
    let x = number(field, v)?;
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(CaseError::field(field, show(v), "must be finite and > 0"))
    }
}

/// The rule part of a library error message "field = value: rule".
fn strip_field(message: &str) -> String {
    message
        .split_once(": ")
        .map_or(message, |(_, rule)| rule)
        .to_string()
}

/// The default shaft radius from a body's radii: their common magnitude where both are
/// finite and equal up to the sign (the paper's shaft, radii [-0.01, 0.01]), or the one
/// finite convex radius of a cylinder ([inf, R]).
fn shaft_radius_from(shape: &Shape) -> Option<f64> {
    let Shape::Radii {
        radii: [r0, r1], ..
    } = *shape
    else {
        return None;
    };
    match (r0.is_finite(), r1.is_finite()) {
        (true, true) if (r0.abs() - r1.abs()).abs() <= 1e-12 * r0.abs().max(r1.abs()) => {
            Some(r0.abs())
        }
        (true, false) if r0 > 0.0 => Some(r0),
        (false, true) if r1 > 0.0 => Some(r1),
        _ => None,
    }
}

fn bulk(b: RawBulk, shape1: &Shape, shape2: &Shape) -> CaseResult<Bulk> {
    let shaft = match &b.shaft {
        None => "body2",
        Some(Value::String(s)) if s == "body1" => "body1",
        Some(Value::String(s)) if s == "body2" => "body2",
        Some(v) => {
            return Err(CaseError::field(
                "bulk.shaft",
                show(v),
                "must be \"body1\" or \"body2\" (the body that is the shaft)",
            ))
        }
    };
    let shaft_shape = if shaft == "body1" { shape1 } else { shape2 };
    let shaft_radius = match &b.shaft_radius {
        Some(v) => positive("bulk.shaft_radius", v, Dim::Length, "the shaft radius (m)")?,
        None => shaft_radius_from(shaft_shape).ok_or_else(|| {
            CaseError::field(
                "bulk.shaft_radius",
                "(missing)",
                format!(
                    "required: {shaft} has no single radius to take it from (its radii differ, \
                     or it is a surface); give the shaft radius R2 in m"
                ),
            )
        })?,
    };
    let kinds = match &b.kind {
        None => vec![LoadKind::TensionCompression, LoadKind::Bending],
        Some(Value::String(s)) if s == "both" => {
            vec![LoadKind::TensionCompression, LoadKind::Bending]
        }
        Some(Value::String(s)) if s == "tension-compression" => {
            vec![LoadKind::TensionCompression]
        }
        Some(Value::String(s)) if s == "bending" => vec![LoadKind::Bending],
        Some(v) => {
            return Err(CaseError::field(
                "bulk.kind",
                show(v),
                "must be \"tension-compression\", \"bending\" or \"both\"",
            ))
        }
    };
    let stress_max = match &b.stress_max {
        Some(v) => positive(
            "bulk.stress_max",
            v,
            Dim::Pressure,
            "the largest bulk stress sigma_a,max (Pa)",
        )?,
        None => {
            return Err(CaseError::field(
                "bulk.stress_max",
                "(missing)",
                "required: the largest bulk stress sigma_a,max in Pa (the curve spans \
                 sigma/sigma_max in [-1, 1])",
            ))
        }
    };
    let points = match &b.points {
        None => DEFAULT_BULK_POINTS,
        Some(v) => {
            let k = count("bulk.points", v)?;
            if !(3..=MAX_BULK_POINTS).contains(&k) || k % 2 == 0 {
                return Err(CaseError::field(
                    "bulk.points",
                    k,
                    format!(
                        "must be odd and in 3 ... {MAX_BULK_POINTS} (odd, so that sigma = 0 \
                         is a point of the curve)"
                    ),
                ));
            }
            k
        }
    };
    let stress = match &b.stress {
        None => None,
        Some(v) => {
            let x = quantity("bulk.stress", v, Dim::Pressure)?;
            if !x.is_finite() {
                return Err(CaseError::field(
                    "bulk.stress",
                    show(v),
                    "the operating bulk stress must be finite (Pa, tension > 0)",
                ));
            }
            Some(x)
        }
    };
    // The operating bending stress from a force, a span and the shaft section (beam theory).
    let from_force = b.bending_force.is_some()
        || b.span.is_some()
        || b.support.is_some()
        || b.bending_side.is_some();
    let stress = if from_force {
        if let Some(v) = &b.stress {
            return Err(CaseError::field(
                "bulk.stress",
                show(v),
                "give either bulk.stress or bulk.bending_force with bulk.span, not both",
            ));
        }
        if kinds != [LoadKind::Bending] {
            return Err(CaseError::field(
                "bulk.bending_force",
                "given",
                "needs kind = \"bending\" (the force bends the shaft)",
            ));
        }
        let required = |key: &str, v: &Option<Value>| {
            v.clone().ok_or_else(|| {
                CaseError::field(
                    format!("bulk.{key}"),
                    "(missing)",
                    "required with a bending force: bending_force (N), span (m), and \
                     optionally support and bending_side",
                )
            })
        };
        let force = quantity(
            "bulk.bending_force",
            &required("bending_force", &b.bending_force)?,
            Dim::Force,
        )?;
        let span = quantity("bulk.span", &required("span", &b.span)?, Dim::Length)?;
        let support = match &b.support {
            None => BeamSupport::SimplySupported,
            Some(Value::String(s)) if s == "simply-supported" => BeamSupport::SimplySupported,
            Some(Value::String(s)) if s == "cantilever" => BeamSupport::Cantilever,
            Some(v) => {
                return Err(CaseError::field(
                    "bulk.support",
                    show(v),
                    "must be \"simply-supported\" (force at mid-span, M = F L/4) or \
                     \"cantilever\" (force at the free end, M = F L)",
                ))
            }
        };
        let sign = match &b.bending_side {
            None => 1.0,
            Some(Value::String(s)) if s == "tension" => 1.0,
            Some(Value::String(s)) if s == "compression" => -1.0,
            Some(v) => {
                return Err(CaseError::field(
                    "bulk.bending_side",
                    show(v),
                    "must be \"tension\" or \"compression\" (the side of the shaft the \
                     contact is on)",
                ))
            }
        };
        let moment = bending_moment(force, span, support, "bulk.")?;
        Some(sign * bending_stress(moment, shaft_radius))
    } else {
        stress
    };
    Ok(Bulk {
        shaft,
        shaft_radius,
        kinds,
        stress_max,
        points,
        stress,
    })
}

fn boolean(field: &str, v: &Value) -> CaseResult<bool> {
    match v {
        Value::Boolean(b) => Ok(*b),
        _ => Err(CaseError::field(field, show(v), "must be true or false")),
    }
}

fn angle_deg(field: &str, v: Option<&Value>) -> CaseResult<f64> {
    match v {
        None => Ok(0.0),
        Some(v) => {
            let x = number(field, v)?;
            if x.is_finite() {
                Ok(x.to_radians())
            } else {
                Err(CaseError::field(
                    field,
                    show(v),
                    "the angle must be a finite number of degrees from the x axis",
                ))
            }
        }
    }
}

fn friction(c: &RawContact) -> CaseResult<Option<Friction>> {
    use tribo::solvers::tangential::TangentialLoading;
    let sliding = match &c.sliding {
        None => None,
        Some(v) => Some((boolean("contact.sliding", v)?, v)),
    };
    let Some(fv) = &c.friction else {
        if let Some(q) = &c.tangential_load {
            return Err(CaseError::field(
                "contact.tangential_load",
                show(q),
                "needs contact.friction (the Coulomb coefficient f > 0)",
            ));
        }
        if let Some((_, v)) = sliding {
            return Err(CaseError::field(
                "contact.sliding",
                show(v),
                "needs contact.friction (the Coulomb coefficient f > 0)",
            ));
        }
        for (name, v) in [
            ("contact.tangential_angle_deg", &c.tangential_angle_deg),
            ("contact.sliding_angle_deg", &c.sliding_angle_deg),
            ("contact.traction_direction", &c.traction_direction),
        ] {
            if let Some(v) = v {
                return Err(CaseError::field(
                    name,
                    show(v),
                    "needs contact.friction and a tangential load or sliding = true",
                ));
            }
        }
        return Ok(None);
    };
    let f = number("contact.friction", fv)?;
    if !(f.is_finite() && f > 0.0) {
        return Err(CaseError::field(
            "contact.friction",
            show(fv),
            "the friction coefficient must be finite and > 0",
        ));
    }
    let loading = match (&c.tangential_load, sliding) {
        (Some(q), None) | (Some(q), Some((false, _))) => {
            if let Some(v) = &c.sliding_angle_deg {
                return Err(CaseError::field(
                    "contact.sliding_angle_deg",
                    show(v),
                    "applies to sliding = true; under a tangential load give \
                 contact.tangential_angle_deg",
                ));
            }
            let magnitude = positive(
                "contact.tangential_load",
                q,
                Dim::Force,
                "the tangential load |Q| (N)",
            )?;
            TangentialLoading::Force {
                magnitude,
                angle: angle_deg(
                    "contact.tangential_angle_deg",
                    c.tangential_angle_deg.as_ref(),
                )?,
            }
        }
        (None, Some((true, _))) => {
            if let Some(v) = &c.tangential_angle_deg {
                return Err(CaseError::field(
                    "contact.tangential_angle_deg",
                    show(v),
                    "applies to tangential_load; when sliding give contact.sliding_angle_deg",
                ));
            }
            TangentialLoading::Sliding {
                angle: angle_deg("contact.sliding_angle_deg", c.sliding_angle_deg.as_ref())?,
            }
        }
        (Some(q), Some((true, _))) => {
            return Err(CaseError::field(
                "contact.tangential_load",
                show(q),
                "give exactly one of contact.tangential_load (partial slip) and \
                 contact.sliding = true (full sliding), not both",
            ))
        }
        (None, _) => {
            return Err(CaseError::field(
                "contact.friction",
                show(fv),
                "needs exactly one of contact.tangential_load (N, partial slip) and \
                 contact.sliding = true (full sliding)",
            ))
        }
    };
    let free_direction = match &c.traction_direction {
        None => false,
        Some(Value::String(v)) if v == "parallel" => false,
        Some(Value::String(v)) if v == "free" => true,
        Some(v) => {
            return Err(CaseError::field(
                "contact.traction_direction",
                show(v),
                "must be \"parallel\" (q along the load, Cattaneo-Mindlin's assumption) or \
                 \"free\" (the full 2D partial-slip problem)",
            ))
        }
    };
    Ok(Some(Friction {
        coefficient: f,
        loading,
        free_direction,
    }))
}

fn field_length(
    semi_key: &str,
    semi: Option<&Value>,
    metres_key: &str,
    metres: Option<&Value>,
    hertzian: bool,
) -> CaseResult<Length> {
    match (semi, metres) {
        (Some(v), Some(_)) => Err(CaseError::field(
            semi_key,
            show(v),
            format!("give either {semi_key} or {metres_key}, not both"),
        )),
        (Some(v), None) => {
            let x = number(semi_key, v)?;
            if !hertzian {
                return Err(CaseError::field(
                    semi_key,
                    show(v),
                    format!(
                        "is in units of the Hertz semi-axis, defined only where both bodies are \
                         given by radii; give {metres_key} (m)"
                    ),
                ));
            }
            if !(x.is_finite() && x > 0.0) {
                return Err(CaseError::field(
                    semi_key,
                    show(v),
                    "must be finite and > 0 (units of the Hertz long semi-axis a)",
                ));
            }
            Ok(Length::Semi(x))
        }
        (None, Some(v)) => Ok(Length::Metres(positive(
            metres_key,
            v,
            Dim::Length,
            "the field size (m)",
        )?)),
        (None, None) => {
            if hertzian {
                Ok(Length::Semi(DEFAULT_FIELD_EXTENT))
            } else {
                Err(CaseError::field(
                    metres_key,
                    "(missing)",
                    "required where a body is given by a surface (no Hertz semi-axis to scale \
                 by): give it in m",
                ))
            }
        }
    }
}

fn field_spec(f: RawField, hertzian: bool, contact_n: [usize; 2]) -> CaseResult<FieldSpec> {
    let points = match &f.points {
        None => FieldPoints::Uniform,
        Some(Value::String(s)) if s == "uniform" => FieldPoints::Uniform,
        Some(Value::String(s)) if s == "centres" || s == "centers" => FieldPoints::Centres,
        Some(v) => {
            return Err(CaseError::field(
                "field.points",
                show(v),
                "must be \"uniform\" (n points over the extent, direct sum) or \"centres\" \
                 (the contact grid's element centres, FFT)",
            ))
        }
    };
    let method = match &f.method {
        None => FieldMethod::Fft,
        Some(Value::String(s)) if s == "fft" => FieldMethod::Fft,
        Some(Value::String(s)) if s == "direct" => FieldMethod::Direct,
        Some(v) => {
            return Err(CaseError::field(
                "field.method",
                show(v),
                "must be \"fft\" (FFT on the extended contact grid + cubic interpolation, \
                 the default) or \"direct\" (the exact direct sum, slow)",
            ))
        }
    };
    if points == FieldPoints::Centres {
        for (name, given) in [
            ("field.n", f.n.is_some()),
            ("field.extent", f.extent.is_some()),
            ("field.half_width", f.half_width.is_some()),
        ] {
            if given {
                return Err(CaseError::field(
                    name,
                    "given",
                    "with points = \"centres\" the x, y points are the contact grid's element \
                     centres; give only field.layers and field.depth (or depth_m)",
                ));
            }
        }
    } else if f.layers.is_some() {
        return Err(CaseError::field(
            "field.layers",
            "given",
            "only with points = \"centres\"; with uniform points give n = [nx, ny, nz]",
        ));
    }
    let n = match &f.n {
        None if points == FieldPoints::Centres => {
            let layers = match &f.layers {
                None => DEFAULT_FIELD_N[2],
                Some(v) => count("field.layers", v)?,
            };
            if !(2..=MAX_FIELD_N).contains(&layers) {
                return Err(CaseError::field(
                    "field.layers",
                    layers,
                    format!("must be in 2 ... {MAX_FIELD_N} depths"),
                ));
            }
            [contact_n[0], contact_n[1], layers]
        }
        None => DEFAULT_FIELD_N,
        Some(Value::Array(a)) if a.len() == 3 => {
            let mut n = [0usize; 3];
            for (k, v) in a.iter().enumerate() {
                let name = format!("field.n[{k}]");
                let c = count(&name, v)?;
                if !(2..=MAX_FIELD_N).contains(&c) {
                    return Err(CaseError::field(
                        name,
                        c,
                        format!("must be in 2 ... {MAX_FIELD_N} points"),
                    ));
                }
                n[k] = c;
            }
            n
        }
        Some(v) => {
            return Err(CaseError::field(
                "field.n",
                show(v),
                "must be [nx, ny, nz], three point counts",
            ))
        }
    };
    let total = n[0] * n[1] * n[2];
    if total > MAX_FIELD_POINTS {
        return Err(CaseError::field(
            "field.n",
            format!("[{}, {}, {}]", n[0], n[1], n[2]),
            format!(
                "{total} points; at most {MAX_FIELD_POINTS} (the ASCII stress.vti holds 22 \
                 arrays over every point)"
            ),
        ));
    }
    // With points at the element centres the contact grid sets x and y (no half width).
    let half_width = match points {
        FieldPoints::Centres => Length::Metres(0.0),
        FieldPoints::Uniform => field_length(
            "field.extent",
            f.extent.as_ref(),
            "field.half_width",
            f.half_width.as_ref(),
            hertzian,
        )?,
    };
    let depth = field_length(
        "field.depth",
        f.depth.as_ref(),
        "field.depth_m",
        f.depth_m.as_ref(),
        hertzian,
    )?;
    let body = match &f.body {
        None => "body2",
        Some(Value::String(s)) if s == "body1" => "body1",
        Some(Value::String(s)) if s == "body2" => "body2",
        Some(v) => {
            return Err(CaseError::field(
                "field.body",
                show(v),
                "must be \"body1\" or \"body2\" (the body the field is computed in)",
            ))
        }
    };
    let edge_refinement = match &f.edge_refinement {
        None => 1,
        Some(Value::String(s)) if s == "band" => EDGE_REFINEMENT_BAND,
        Some(v) => {
            let factor = count("field.edge_refinement", v)?;
            let finest = contact_n[0].max(contact_n[1]);
            if !(1..=MAX_EDGE_REFINEMENT).contains(&factor) {
                return Err(CaseError::field(
                    "field.edge_refinement",
                    factor,
                    format!(
                        "must be \"band\" or an integer in 1 ... {MAX_EDGE_REFINEMENT} (1: the bilinear \
                         element tractions; N: the edge-aware tractions on a grid N times finer)"
                    ),
                ));
            }
            if finest * factor > MAX_ELEMENTS_PER_SIDE {
                return Err(CaseError::field(
                    "field.edge_refinement",
                    factor,
                    format!(
                        "the refined grid would have {} elements per side ({finest} x {factor}); \
                         at most {MAX_ELEMENTS_PER_SIDE}",
                        finest * factor
                    ),
                ));
            }
            factor
        }
    };
    Ok(FieldSpec {
        points,
        method,
        n,
        half_width,
        depth,
        body,
        edge_refinement,
    })
}

fn material(name: &str, b: &RawBody) -> CaseResult<ElasticMaterial> {
    let e = quantity(&format!("{name}.E"), &b.e, Dim::Pressure)?;
    let nu = number(&format!("{name}.nu"), &b.nu)?;
    let m = ElasticMaterial::named(name, e, nu)?;
    crate::units::check_modulus(&format!("{name}.E"), &b.e, e)?;
    Ok(m)
}

/// A quantity that must be finite and > 0; a length of the geometry (any `Dim::Length` but
/// the approach, which is checked relative to the window in `run::prepare`) also within
/// [`crate::units::LENGTH_RANGE`].
fn positive(field: &str, value: &Value, dim: Dim, what: &str) -> CaseResult<f64> {
    let x = quantity(field, value, dim)?;
    if x.is_finite() && x > 0.0 {
        if dim == Dim::Length && field != "contact.approach" {
            crate::units::check_length(field, value, x)?;
        }
        Ok(x)
    } else {
        Err(CaseError::field(
            field,
            show(value),
            format!("{what} must be finite and > 0"),
        ))
    }
}

fn loading(c: &RawContact) -> CaseResult<NormalLoading> {
    match (&c.load, &c.approach) {
        (Some(l), None) => Ok(NormalLoading::Force(positive(
            "contact.load",
            l,
            Dim::Force,
            "the normal load (N)",
        )?)),
        (None, Some(a)) => Ok(NormalLoading::Approach(positive(
            "contact.approach",
            a,
            Dim::Length,
            "the approach (m)",
        )?)),
        (Some(l), Some(_)) => Err(CaseError::field(
            "contact.load",
            show(l),
            "give exactly one of contact.load (N) and contact.approach (m), not both",
        )),
        (None, None) => Err(CaseError::field(
            "contact",
            "(neither load nor approach)",
            "give exactly one of contact.load (N) and contact.approach (m)",
        )),
    }
}

struct ShapeContext<'a> {
    e_star: f64,
    loading: NormalLoading,
    base_dir: &'a Path,
}

/// A principal radius of curvature, m: a number, a unit string, or infinite (flat) written
/// as the string "inf" or the TOML float `inf` (both echoed as "inf" in summary.json). A
/// negative infinity or a NaN is refused: a concave flat direction is not a different shape,
/// and the sign convention asks for an explicit "inf".
fn radius(field: &str, v: &Value) -> CaseResult<f64> {
    if let Value::String(s) = v {
        let t = s.trim();
        if t.eq_ignore_ascii_case("inf") || t.eq_ignore_ascii_case("infinity") {
            return Ok(f64::INFINITY);
        }
    }
    if let Value::Float(x) = v {
        if *x == f64::INFINITY {
            return Ok(f64::INFINITY);
        }
        if !x.is_finite() {
            return Err(CaseError::field(
                field,
                show(v),
                "a radius must be a finite number in m, or inf / \"inf\" (flat); -inf and \
                 nan are refused",
            ));
        }
    }
    let r = quantity(field, v, Dim::Length).map_err(|_| {
        CaseError::field(
            field,
            show(v),
            "a radius must be a number in m (< 0 concave), a string like \"10 mm\", or \"inf\" (flat)",
        )
    })?;
    if r == 0.0 {
        return Err(CaseError::field(
            field,
            show(v),
            "a radius of curvature must be non-zero (use \"inf\" for a flat direction)",
        ));
    }
    if r.is_nan() {
        return Err(CaseError::field(
            field,
            show(v),
            "a radius must be a number",
        ));
    }
    crate::units::check_length(field, v, r)?;
    Ok(r)
}

fn shape(name: &str, b: RawBody, ctx: &ShapeContext<'_>) -> CaseResult<Shape> {
    match (b.radii, b.surface) {
        (Some(_), Some(_)) => Err(CaseError::field(
            format!("{name}.radii"),
            "(and a surface)",
            format!("give exactly one of {name}.radii and [{name}.surface]"),
        )),
        (None, None) => Err(CaseError::field(
            format!("{name}.radii"),
            "(missing)",
            format!("give the body's shape: {name}.radii = [Rx, Ry] or a [{name}.surface] table"),
        )),
        (Some(r), None) => {
            let radii = match &r {
                Value::Array(a) if a.len() == 2 => [
                    radius(&format!("{name}.radii[0]"), &a[0])?,
                    radius(&format!("{name}.radii[1]"), &a[1])?,
                ],
                other => {
                    return Err(CaseError::field(
                        format!("{name}.radii"),
                        show(other),
                        "must be an array of two principal radii [Rx, Ry] (m, or \"inf\")",
                    ))
                }
            };
            let angle = match &b.angle_deg {
                None => 0.0,
                Some(v) => {
                    let deg = number(&format!("{name}.angle_deg"), v)?;
                    if !deg.is_finite() {
                        return Err(CaseError::field(
                            format!("{name}.angle_deg"),
                            show(v),
                            "must be finite",
                        ));
                    }
                    deg.to_radians()
                }
            };
            Ok(Shape::Radii { radii, angle })
        }
        (None, Some(s)) => {
            if let Some(a) = &b.angle_deg {
                return Err(CaseError::field(
                    format!("{name}.angle_deg"),
                    show(a),
                    "applies to radii only; a surface is given in the common frame",
                ));
            }
            Ok(Shape::Surface(surface(&format!("{name}.surface"), s, ctx)?))
        }
    }
}

fn surface(field: &str, s: RawSurface, ctx: &ShapeContext<'_>) -> CaseResult<SurfaceProfile> {
    match s {
        RawSurface::Roller {
            radius,
            length,
            crown,
            crown_radius,
            flat_length,
            design_load,
            crown_drop,
        } => {
            let r = positive(
                &format!("{field}.radius"),
                &radius,
                Dim::Length,
                "the roller radius (m)",
            )?;
            let l = positive(
                &format!("{field}.length"),
                &length,
                Dim::Length,
                "the roller length (m)",
            )?;
            let kind = crown.as_deref().unwrap_or("none");
            let unused = |key: &str, v: &Option<Value>| -> CaseResult<()> {
                match v {
                    Some(v) => Err(CaseError::field(
                        format!("{field}.{key}"),
                        show(v),
                        format!("does not apply to crown = {kind:?}"),
                    )),
                    None => Ok(()),
                }
            };
            let c = match kind {
                "none" => {
                    unused("crown_radius", &crown_radius)?;
                    unused("flat_length", &flat_length)?;
                    unused("design_load", &design_load)?;
                    unused("crown_drop", &crown_drop)?;
                    Crown::None
                }
                "circular" => {
                    unused("design_load", &design_load)?;
                    unused("crown_drop", &crown_drop)?;
                    let cr = crown_radius.as_ref().ok_or_else(|| {
                        CaseError::field(
                            format!("{field}.crown_radius"),
                            "(missing)",
                            "a circular crown needs its radius (m)",
                        )
                    })?;
                    let crown_radius = positive(
                        &format!("{field}.crown_radius"),
                        cr,
                        Dim::Length,
                        "the crown radius (m)",
                    )?;
                    let flat_length = match &flat_length {
                        None => 0.0,
                        Some(v) => quantity(&format!("{field}.flat_length"), v, Dim::Length)?,
                    };
                    Crown::Circular {
                        crown_radius,
                        flat_length,
                    }
                }
                "logarithmic" => {
                    unused("crown_radius", &crown_radius)?;
                    unused("flat_length", &flat_length)?;
                    let q = match (&design_load, ctx.loading) {
                        (Some(v), _) => positive(
                            &format!("{field}.design_load"),
                            v,
                            Dim::Force,
                            "the design load (N)",
                        )?,
                        (None, NormalLoading::Force(f)) => f,
                        (None, NormalLoading::Approach(_)) => return Err(CaseError::field(
                            format!("{field}.design_load"),
                            "(missing)",
                            "a logarithmic crown under approach control needs its design load (N)",
                        )),
                    };
                    let zm = match &crown_drop {
                        None => None,
                        Some(v) => Some(positive(
                            &format!("{field}.crown_drop"),
                            v,
                            Dim::Length,
                            "the crown drop at the roller ends (m)",
                        )?),
                    };
                    Crown::Logarithmic(LogarithmicCrown::new(field, q, l, ctx.e_star, zm)?)
                }
                other => {
                    return Err(CaseError::field(
                        format!("{field}.crown"),
                        format!("{other:?}"),
                        "must be \"none\", \"circular\" or \"logarithmic\"",
                    ))
                }
            };
            Ok(SurfaceProfile::Roller(Roller::new(field, r, l, c)?))
        }
        RawSurface::HeightMap {
            file,
            heights,
            spacing,
            scale,
        } => {
            let sp = pair(&format!("{field}.spacing"), &spacing, |f, v| {
                quantity(f, v, Dim::Length)
            })?;
            let scale = match &scale {
                None => 1.0,
                Some(v) => {
                    let s = number(&format!("{field}.scale"), v)?;
                    if !(s.is_finite() && s > 0.0) {
                        return Err(CaseError::field(
                            format!("{field}.scale"),
                            show(v),
                            "must be finite and > 0",
                        ));
                    }
                    s
                }
            };
            let (nx, ny, mut values) = match (file, heights) {
                (Some(f), None) => {
                    let path = ctx.base_dir.join(&f);
                    read_height_csv(&format!("{field}.file"), &path)?
                }
                (None, Some(rows)) => inline_heights(&format!("{field}.heights"), &rows)?,
                (Some(f), Some(_)) => {
                    return Err(CaseError::field(
                        format!("{field}.file"),
                        format!("{f:?}"),
                        "give either file or heights, not both",
                    ))
                }
                (None, None) => {
                    return Err(CaseError::field(
                        format!("{field}.file"),
                        "(missing)",
                        "a height map needs file = \"map.csv\" or heights = [[...], ...]",
                    ))
                }
            };
            values.iter_mut().for_each(|h| *h *= scale);
            Ok(SurfaceProfile::HeightMap(HeightMap::new(
                field, nx, ny, sp, values,
            )?))
        }
    }
}

fn inline_heights(field: &str, rows: &[Vec<Value>]) -> CaseResult<(usize, usize, Vec<f64>)> {
    let ny = rows.len();
    let nx = rows.first().map_or(0, Vec::len);
    let mut out = Vec::with_capacity(nx * ny);
    for (j, row) in rows.iter().enumerate() {
        if row.len() != nx {
            return Err(CaseError::field(
                format!("{field}[{j}]"),
                format!("{} values", row.len()),
                format!("ragged: every row must have as many values as the first ({nx})"),
            ));
        }
        for (i, v) in row.iter().enumerate() {
            let h = number(&format!("{field}[{j}][{i}]"), v)?;
            if !h.is_finite() {
                return Err(CaseError::field(
                    format!("{field}[{j}][{i}]"),
                    h,
                    "heights must be finite",
                ));
            }
            out.push(h);
        }
    }
    if nx < 2 || ny < 2 {
        return Err(CaseError::field(
            field,
            format!("{ny} x {nx}"),
            "a height map needs at least 2 x 2 values",
        ));
    }
    Ok((nx, ny, out))
}

/// Read a height map CSV: one row of the grid per line, values separated by commas, row `j`
/// (the j-th data line) at `y_j`, column `i` at `x_i` (both increasing; see
/// [`tribo::geometry::HeightMap`]); blank lines and lines starting with `#` are skipped.
pub fn read_height_csv(field: &str, path: &Path) -> CaseResult<(usize, usize, Vec<f64>)> {
    let text = std::fs::read_to_string(path).map_err(|source| CaseError::Unreadable {
        field: field.to_string(),
        path: path.to_path_buf(),
        source,
    })?;
    let bad = |line: usize, rule: String| CaseError::DataFile {
        field: field.to_string(),
        path: PathBuf::from(path),
        line,
        rule,
    };
    let mut nx = 0;
    let mut ny = 0;
    let mut values = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let t = line.trim();
        if t.is_empty() || t.starts_with('#') {
            continue;
        }
        let mut count = 0;
        for (i, cell) in t.split(',').enumerate() {
            let c = cell.trim();
            let v: f64 = c
                .parse()
                .map_err(|_| bad(k + 1, format!("column {}: {c:?} is not a number", i + 1)))?;
            if !v.is_finite() {
                return Err(bad(
                    k + 1,
                    format!("column {}: {c:?} is not a finite number", i + 1),
                ));
            }
            values.push(v);
            count += 1;
        }
        if ny == 0 {
            nx = count;
        } else if count != nx {
            return Err(bad(
                k + 1,
                format!("ragged: {count} values where the first row has {nx}"),
            ));
        }
        ny += 1;
    }
    if nx < 2 || ny < 2 {
        return Err(bad(
            text.lines().count().max(1),
            format!("a height map needs at least 2 rows of 2 values (found {ny} rows of {nx})"),
        ));
    }
    Ok((nx, ny, values))
}

/// Refuse radii whose gap h = A x'^2 + B y'^2 is not positive definite (docs/theory/HALFSPACE.md 3.1,
/// Johnson 1985 section 4.2): no bounded contact (both flat, or too conforming).
fn check_convex(r1: [f64; 2], r2: [f64; 2], angle: f64) -> CaseResult<()> {
    let k = |r: f64| if r.is_infinite() { 0.0 } else { 1.0 / r };
    let (k11, k12, k21, k22) = (k(r1[0]), k(r1[1]), k(r2[0]), k(r2[1]));
    let sum = 0.5 * (k11 + k12 + k21 + k22);
    let (d1, d2) = (k11 - k12, k21 - k22);
    let diff = 0.5
        * (d1 * d1 + d2 * d2 + 2.0 * d1 * d2 * (2.0 * angle).cos())
            .max(0.0)
            .sqrt();
    let (a, b) = (sum - diff, sum + diff);
    // Relative threshold: a curvature below 1e-9 of the largest is zero up to round-off.
    let scale = [k11, k12, k21, k22]
        .iter()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    if !(a > 1e-9 * scale && b > 0.0) {
        return Err(CaseError::field(
            "body1.radii, body2.radii",
            format!("[{}, {}], [{}, {}]", r1[0], r1[1], r2[0], r2[1]),
            format!(
                "the gap h = A x'^2 + B y'^2 must be convex (A, B > 0) for a bounded contact, \
                 here A = {a:.4e}, B = {b:.4e} 1/m (both bodies flat, or a concave body tighter \
                 than the convex one); use a [bodyN.surface] for line contacts"
            ),
        ));
    }
    Ok(())
}

fn solver(raw: Option<RawSolver>, n: [usize; 2]) -> CaseResult<(Method, NormalContactParams)> {
    let mut params = NormalContactParams::default();
    let Some(s) = raw else {
        return Ok((Method::Cg, params));
    };
    let method = s.method.unwrap_or(Method::Cg);
    if let Some(t) = &s.tolerance {
        let x = number("solver.tolerance", t)?;
        if !(x.is_finite() && x > 0.0 && x < 1.0) {
            return Err(CaseError::field(
                "solver.tolerance",
                show(t),
                "must be in (0, 1)",
            ));
        }
        params.tolerance = x;
    }
    if let Some(m) = &s.max_iterations {
        let x = count("solver.max_iterations", m)?;
        if x == 0 {
            return Err(CaseError::field(
                "solver.max_iterations",
                x,
                "must be at least 1",
            ));
        }
        params.max_iterations = x;
    }
    if method == Method::ActiveSet && n[0] * n[1] > MAX_ACTIVE_SET_ELEMENTS {
        return Err(CaseError::field(
            "solver.method",
            "\"active_set\"",
            format!(
                "the dense active-set solver is for small grids (nx * ny <= {MAX_ACTIVE_SET_ELEMENTS}, \
                 here {}); use method = \"cg\"",
                n[0] * n[1]
            ),
        ));
    }
    Ok((method, params))
}

#[cfg(test)]
mod tests {
    use super::*;

    const PAPER: &str = r#"
title = "Roller on shaft, paper Sec. 3"
[body1]
E = 2.01e11
nu = 0.3
radii = [0.005, 0.05]
[body2]
E = 2.01e11
nu = 0.3
radii = [-0.01, 0.01]
[contact]
load = 2000.0
[grid]
n = 21
extent = 1.5
"#;

    fn parse(text: &str) -> CaseResult<HalfSpaceCase> {
        parse_case(text, "test.toml", Path::new("."))
    }

    fn err(text: &str) -> String {
        parse(text).unwrap_err().to_string()
    }

    #[test]
    fn the_papers_case_parses() {
        let c = parse(PAPER).unwrap();
        assert_eq!(c.title, "Roller on shaft, paper Sec. 3");
        assert_eq!(c.n, [21, 21]);
        assert_eq!(c.window, Window::Extent(1.5));
        assert_eq!(c.loading, NormalLoading::Force(2000.0));
        assert!(c.is_hertzian());
        assert_eq!(
            c.body2.shape,
            Shape::Radii {
                radii: [-0.01, 0.01],
                angle: 0.0
            }
        );
        assert!((c.composite_modulus() / 1.10440e11 - 1.0).abs() < 5e-6);
        assert_eq!(c.echo["body1"]["radii"][1], serde_json::json!(0.05));
        assert_eq!(c.method, Method::Cg);
    }

    #[test]
    fn units_inf_and_pairs() {
        let t = PAPER
            .replace(
                "E = 2.01e11\nnu = 0.3\nradii = [0.005, 0.05]",
                "E = \"201 GPa\"\nnu = 0.3\nradii = [\"5 mm\", \"inf\"]",
            )
            .replace(
                "n = 21\nextent = 1.5",
                "n = [32, 16]\nhalf_width = [\"1 mm\", 5e-4]",
            )
            .replace("load = 2000.0", "approach = \"27.23 um\"");
        let c = parse(&t).unwrap();
        assert_eq!(c.body1.material.youngs_modulus(), 201e9);
        assert!(
            matches!(c.body1.shape, Shape::Radii { radii, .. } if radii[0] == 0.005 && radii[1].is_infinite())
        );
        assert_eq!(c.n, [32, 16]);
        assert_eq!(c.window, Window::HalfWidth([0.001, 5e-4]));
        assert!(matches!(c.loading, NormalLoading::Approach(a) if (a - 2.723e-5).abs() < 1e-15));
    }

    #[test]
    fn bad_materials() {
        let e = err(&PAPER.replacen("nu = 0.3", "nu = 0.55", 1));
        assert_eq!(e, "body1.nu = 0.55: Poisson's ratio must be in (-1, 0.5)");
        assert!(err(&PAPER.replacen("E = 2.01e11", "E = -1.0", 2)).starts_with("body1.E"));
        let t = PAPER.replacen("[body2]\nE = 2.01e11", "[body2]\nE = nan", 1);
        assert!(err(&t).starts_with("body2.E = nan"), "{}", err(&t));
        assert!(err(&PAPER.replacen("nu = 0.3", "nu = -1.0", 1)).starts_with("body1.nu"));
    }

    #[test]
    fn bad_radii() {
        assert!(
            err(&PAPER.replace("[0.005, 0.05]", "[0.0, 0.05]")).starts_with("body1.radii[0] = 0")
        );
        assert!(err(&PAPER.replace("[0.005, 0.05]", "[0.005]")).starts_with("body1.radii"));
        let flat = PAPER
            .replace("[0.005, 0.05]", "[\"inf\", \"inf\"]")
            .replace("[-0.01, 0.01]", "[\"inf\", \"inf\"]");
        let e = err(&flat);
        assert!(e.contains("radii") && e.contains("convex"), "{e}");
        // A concave body tighter than the convex one.
        let e = err(&PAPER.replace("[-0.01, 0.01]", "[-0.004, 0.01]"));
        assert!(e.contains("convex"), "{e}");
        let e = err(&PAPER.replace("[0.005, 0.05]", "[\"big\", 0.05]"));
        assert!(e.starts_with("body1.radii[0] = \"big\""), "{e}");
    }

    #[test]
    fn load_and_approach() {
        let both = PAPER.replace("load = 2000.0", "load = 2000.0\napproach = 1e-5");
        assert!(err(&both).contains("exactly one"));
        let neither = PAPER.replace("load = 2000.0", "");
        assert!(err(&neither).starts_with("contact"));
        assert!(err(&PAPER.replace("load = 2000.0", "load = 0")).starts_with("contact.load = 0"));
        assert!(err(&PAPER.replace("load = 2000.0", "load = -5.0")).starts_with("contact.load"));
        assert!(err(&PAPER.replace("load = 2000.0", "approach = -1e-6"))
            .starts_with("contact.approach"));
        assert!(
            err(&PAPER.replace("load = 2000.0", "approach = 0.0")).starts_with("contact.approach")
        );
    }

    #[test]
    fn bad_grids() {
        assert!(err(&PAPER.replace("n = 21", "n = 3")).starts_with("grid.n = 3"));
        assert!(err(&PAPER.replace("n = 21", "n = 100000000")).starts_with("grid.n = 100000000"));
        assert!(err(&PAPER.replace("n = 21", "n = [21, 2]")).starts_with("grid.n[1] = 2"));
        assert!(err(&PAPER.replace("n = 21", "n = -4")).starts_with("grid.n"));
        assert!(err(&PAPER.replace("extent = 1.5", "extent = 0.9")).starts_with("grid.extent"));
        assert!(
            err(&PAPER.replace("extent = 1.5", "extent = 1.5\nhalf_width = 1e-3"))
                .contains("not both")
        );
        assert!(err(&PAPER.replace("extent = 1.5", "half_width = -1e-3"))
            .starts_with("grid.half_width"));
        // No [grid] at all: defaults.
        let c = parse(&PAPER.replace("[grid]\nn = 21\nextent = 1.5", "")).unwrap();
        assert_eq!(
            (c.n, c.window),
            ([DEFAULT_N; 2], Window::Extent(DEFAULT_EXTENT))
        );
    }

    #[test]
    fn unknown_keys_are_errors() {
        let e = err(&PAPER.replace("nu = 0.3", "nu = 0.3\nnuu = 0.3"));
        assert!(e.contains("nuu"), "{e}");
        let e = err(&PAPER.replace("[grid]", "[gird]"));
        assert!(e.contains("gird"), "{e}");
        let e = err(&PAPER.replace("load = 2000.0", "lod = 2000.0"));
        assert!(e.contains("lod"), "{e}");
        let e = err(&(PAPER.to_string() + "[solver]\nmethod = \"newton\"\n"));
        assert!(e.contains("newton"), "{e}");
        assert!(err("title = ").starts_with("test.toml"));
    }

    #[test]
    fn angle_and_solver() {
        let t = PAPER.replace(
            "radii = [-0.01, 0.01]",
            "radii = [-0.01, 0.01]\nangle_deg = 30",
        );
        let c = parse(
            &(t + "[solver]\nmethod = \"active_set\"\ntolerance = 1e-8\nmax_iterations = 50\n"),
        )
        .unwrap();
        assert!(
            matches!(c.body2.shape, Shape::Radii { angle, .. } if (angle - 30f64.to_radians()).abs() < 1e-15)
        );
        assert_eq!(c.method, Method::ActiveSet);
        assert_eq!((c.params.tolerance, c.params.max_iterations), (1e-8, 50));
        let t = PAPER.replace(
            "radii = [0.005, 0.05]",
            "radii = [0.005, 0.05]\nangle_deg = 30",
        );
        assert!(err(&t).starts_with("body1.angle_deg"));
        let big = PAPER.replace("n = 21", "n = 128") + "[solver]\nmethod = \"active_set\"\n";
        assert!(err(&big).starts_with("solver.method"));
        assert!(
            err(&(PAPER.to_string() + "[solver]\ntolerance = 0\n")).starts_with("solver.tolerance")
        );
    }

    #[test]
    fn bulk_section() {
        assert_eq!(parse(PAPER).unwrap().bulk, None);
        let c = parse(&(PAPER.to_string() + "[bulk]\nstress_max = \"640 MPa\"\n")).unwrap();
        let b = c.bulk.unwrap();
        assert_eq!((b.shaft, b.shaft_radius), ("body2", 0.01));
        assert_eq!(b.kinds, [LoadKind::TensionCompression, LoadKind::Bending]);
        assert_eq!((b.stress_max, b.points, b.stress), (6.4e8, 21, None));
        let r = b.ratios();
        assert_eq!((r.len(), r[0], r[10], r[20]), (21, -1.0, 0.0, 1.0));
        let t = PAPER.to_string()
            + "[bulk]\nshaft = \"body2\"\nshaft_radius = \"10.5 mm\"\nkind = \"bending\"\n\
               stress_max = 6.4e8\npoints = 5\nstress = -3.2e8\n";
        let b = parse(&t).unwrap().bulk.unwrap();
        assert!((b.shaft_radius - 0.0105).abs() < 1e-15);
        assert_eq!(
            (b.kinds.as_slice(), b.points),
            ([LoadKind::Bending].as_slice(), 5)
        );
        assert_eq!(b.stress, Some(-3.2e8));
        // Body 1's radii differ: the radius is required.
        let e = err(&(PAPER.to_string() + "[bulk]\nshaft = \"body1\"\nstress_max = 1e8\n"));
        assert!(
            e.starts_with("bulk.shaft_radius") && e.contains("required"),
            "{e}"
        );
        let bad = |extra: &str| err(&format!("{PAPER}[bulk]\nstress_max = 6.4e8\n{extra}\n"));
        for (extra, field) in [
            ("shaft = \"body3\"", "bulk.shaft = \"body3\""),
            ("shaft_radius = -0.01", "bulk.shaft_radius = -0.01"),
            ("shaft_radius = 0", "bulk.shaft_radius = 0"),
            ("kind = \"torsion\"", "bulk.kind = \"torsion\""),
            ("points = 2", "bulk.points = 2"),
            ("points = 20", "bulk.points = 20"),
            ("points = 1", "bulk.points = 1"),
            ("points = 100001", "bulk.points = 100001"),
            ("points = 2.5", "bulk.points = 2.5"),
            ("stress = nan", "bulk.stress = nan"),
            ("stress = \"3 mm\"", "bulk.stress"),
        ] {
            let e = bad(extra);
            assert!(e.starts_with(field), "{extra}: {e}");
        }
        let e = err(&(PAPER.to_string() + "[bulk]\nstress_max = -1\n"));
        assert!(e.starts_with("bulk.stress_max = -1"), "{e}");
        let e = err(&(PAPER.to_string() + "[bulk]\nkind = \"bending\"\n"));
        assert!(
            e.starts_with("bulk.stress_max") && e.contains("required"),
            "{e}"
        );
        let e = bad("stres = 1e8");
        assert!(e.contains("stres"), "{e}");
    }

    #[test]
    fn default_shaft_radius() {
        let r = |radii: [f64; 2]| shaft_radius_from(&Shape::Radii { radii, angle: 0.0 });
        assert_eq!(r([-0.01, 0.01]), Some(0.01));
        assert_eq!(r([0.02, 0.02]), Some(0.02));
        assert_eq!(r([f64::INFINITY, 0.01]), Some(0.01));
        assert_eq!(r([0.01, f64::INFINITY]), Some(0.01));
        assert_eq!(r([-0.01, f64::INFINITY]), None);
        assert_eq!(r([0.005, 0.05]), None);
        assert_eq!(r([f64::INFINITY; 2]), None);
    }

    const ROLLER: &str = r#"
[body1]
E = 2.01e11
nu = 0.3
[body1.surface]
kind = "roller"
radius = 0.005
length = 0.01
crown = "logarithmic"
crown_drop = 1e-5
[body2]
E = 2.01e11
nu = 0.3
radii = ["inf", 0.02]
[contact]
load = 2000.0
[grid]
n = [64, 16]
half_width = [0.0056, 0.0003]
"#;

    #[test]
    fn roller_surfaces() {
        let c = parse(ROLLER).unwrap();
        assert!(!c.is_hertzian());
        match &c.body1.shape {
            Shape::Surface(SurfaceProfile::Roller(r)) => match r.crown {
                Crown::Logarithmic(l) => {
                    assert_eq!((l.design_load, l.end_drop), (2000.0, Some(1e-5)));
                }
                _ => panic!(),
            },
            _ => panic!(),
        }
        // extent is not defined for surfaces; half_width is required.
        let e = err(&ROLLER.replace("half_width = [0.0056, 0.0003]", "extent = 1.5"));
        assert!(e.starts_with("grid.extent"), "{e}");
        let e = err(&ROLLER.replace("half_width = [0.0056, 0.0003]", ""));
        assert!(
            e.starts_with("grid.half_width") && e.contains("required"),
            "{e}"
        );
        let e = err(&ROLLER.replace("crown = \"logarithmic\"", "crown = \"parabolic\""));
        assert!(e.starts_with("body1.surface.crown"), "{e}");
        let e = err(&ROLLER.replace("crown = \"logarithmic\"", "crown = \"circular\""));
        assert!(e.starts_with("body1.surface.crown_drop"), "{e}");
        let circ = ROLLER.replace(
            "crown = \"logarithmic\"\ncrown_drop = 1e-5",
            "crown = \"circular\"\ncrown_radius = 0.5",
        );
        assert!(parse(&circ).is_ok());
        let e = err(&ROLLER.replace("kind = \"roller\"", "kind = \"roller\"\ncolour = 1"));
        assert!(e.contains("colour"), "{e}");
        let e = err(&ROLLER.replace("kind = \"roller\"", "kind = \"cone\""));
        assert!(e.contains("cone"), "{e}");
        let e = err(&ROLLER.replace(
            "radii = [\"inf\", 0.02]",
            "radii = [\"inf\", 0.02]\n[body2.surface]\nkind = \"roller\"\nradius = 1\nlength = 1",
        ));
        assert!(e.contains("exactly one of body2.radii"), "{e}");
        let e = err(&ROLLER.replace("radius = 0.005", "radius = 0"));
        assert!(e.starts_with("body1.surface.radius"), "{e}");
        let approach = ROLLER.replace("load = 2000.0", "approach = 1e-5");
        assert!(err(&approach).starts_with("body1.surface.design_load"));
    }

    const MAP: &str = r#"
[body1]
E = 2.01e11
nu = 0.3
[body1.surface]
kind = "height_map"
spacing = [1e-4, 1e-4]
heights = [[2, 1, 2], [1, 0, 1], [2, 1, 2]]
scale = 1e-6
[body2]
E = 2.01e11
nu = 0.3
radii = ["inf", "inf"]
[contact]
load = 10.0
[grid]
n = 8
half_width = 1e-4
"#;

    #[test]
    fn inline_height_maps() {
        let c = parse(MAP).unwrap();
        match &c.body1.shape {
            Shape::Surface(SurfaceProfile::HeightMap(m)) => {
                assert_eq!((m.nx(), m.ny()), (3, 3));
                assert!((m.height(0.0, 0.0).unwrap()).abs() < 1e-20);
                assert!((m.height(1e-4, 0.0).unwrap() - 1e-6).abs() < 1e-18);
            }
            _ => panic!(),
        }
        let e = err(&MAP.replace("[1, 0, 1]", "[1, 0]"));
        assert!(
            e.starts_with("body1.surface.heights[1]") && e.contains("ragged"),
            "{e}"
        );
        let e = err(&MAP.replace("[1, 0, 1]", "[1, \"x\", 1]"));
        assert!(e.starts_with("body1.surface.heights[1][1]"), "{e}");
        let e = err(&MAP.replace("[1, 0, 1]", "[1, nan, 1]"));
        assert!(e.starts_with("body1.surface.heights[1][1]"), "{e}");
        let e = err(&MAP.replace("half_width = 1e-4", "half_width = 2e-4"));
        assert!(
            e.starts_with("grid.half_width") && e.contains("height map"),
            "{e}"
        );
    }

    #[test]
    fn csv_height_maps() {
        let dir = tempfile::tempdir().unwrap();
        let write = |name: &str, text: &str| std::fs::write(dir.path().join(name), text).unwrap();
        write("ok.csv", "# heights in um\n2, 1, 2\n1,0,1\n\n2,1,2\n");
        write("ragged.csv", "2,1,2\n1,0\n2,1,2\n");
        write("text.csv", "2,1,2\n1,zero,1\n2,1,2\n");
        write("nan.csv", "2,1,2\n1,NaN,1\n2,1,2\n");
        let case = |file: &str| {
            let t = MAP.replace(
                "heights = [[2, 1, 2], [1, 0, 1], [2, 1, 2]]",
                &format!("file = \"{file}\""),
            );
            parse_case(&t, "t.toml", dir.path())
        };
        let c = case("ok.csv").unwrap();
        assert!(
            matches!(&c.body1.shape, Shape::Surface(SurfaceProfile::HeightMap(m)) if m.nx() == 3 && m.ny() == 3)
        );
        let e = case("ragged.csv").unwrap_err().to_string();
        assert!(
            e.contains("ragged.csv, line 2") && e.contains("ragged"),
            "{e}"
        );
        let e = case("text.csv").unwrap_err().to_string();
        assert!(
            e.contains("text.csv, line 2") && e.contains("not a number"),
            "{e}"
        );
        let e = case("nan.csv").unwrap_err().to_string();
        assert!(e.contains("nan.csv, line 2") && e.contains("finite"), "{e}");
        let e = case("missing.csv").unwrap_err();
        assert!(
            e.to_string().starts_with("body1.surface.file: cannot read"),
            "{e}"
        );
        assert!(e.is_bad_input());
    }
}
