//! The validated half-space case: what [`super::parse_case`] returns and the pipeline runs.

use serde::Deserialize;
use tribo::analysis::damage::{DamageQuantity, TensorKind};
use tribo::geometry::{QuadraticProfile, SurfaceProfile};
use tribo::solvers::{NormalContactParams, NormalLoading, NormalMethod};
use tribo::surface::generate::Method as RoughMethod;
use tribo::surface::{Normalization, PowerSpectrum, Topography};
use tribo::ElasticMaterial;

/// Most load steps of `contact.load_steps` (each is one contact solution).
pub const MAX_LOAD_STEPS: usize = 1000;

/// Largest grid (elements) accepted for the dense active-set solver: its influence matrix
/// needs (nx ny)^2 doubles, 128 MiB at this size.
pub const MAX_ACTIVE_SET_ELEMENTS: usize = 64 * 64;

/// Default number of elements per side when `[grid] n` is not given.
pub const DEFAULT_N: usize = 64;
/// Default window half width in units of the Hertz long semi-axis.
pub const DEFAULT_EXTENT: f64 = 1.5;

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

/// A generated rough surface (`[bodyN.surface] kind = "rough"`): drawn on the contact grid
/// by [`tribo::surface::generate()`] in [`crate::pipeline::prepare`], one height per element,
/// the window (a periodic grid's period) as its period.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GeneratedRoughness {
    /// The spectrum's shape, wavenumbers in rad/m (2 pi / the case's wavelengths).
    pub spectrum: PowerSpectrum,
    /// The target rms height (m) or rms slope.
    pub normalization: Normalization,
    /// Filtered noise (default) or random phase.
    pub method: RoughMethod,
    /// The seed of the random numbers.
    pub seed: u64,
}

/// A measured topography (`[bodyN.surface] kind = "measured"`), read, detrended and scaled.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredRoughness {
    /// The heights (m, positive outward from the body), detrended and scaled.
    pub topography: Topography,
    /// The file as written in the case.
    pub file: String,
    /// The degree of the polynomial removed (`None`: none).
    pub detrend: Option<usize>,
    /// Taken as one period of a periodic surface (`periodic = true`): its size is the period.
    pub periodic: bool,
}

/// The roughness of a body, superposed on its smooth shape.
#[derive(Debug, Clone, PartialEq)]
pub enum Roughness {
    /// Generated from a power spectrum.
    Generated(GeneratedRoughness),
    /// Read from a file.
    Measured(MeasuredRoughness),
}

impl Roughness {
    /// "rough" or "measured", the case file's `kind`.
    pub fn kind(&self) -> &'static str {
        match self {
            Roughness::Generated(_) => "rough",
            Roughness::Measured(_) => "measured",
        }
    }
}

/// One validated body.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// Elastic constants.
    pub material: ElasticMaterial,
    /// Shape of the surface (the smooth part where the body is rough: its radii, or a flat).
    pub shape: Shape,
    /// A rough or measured surface superposed on the shape (`[bodyN.surface] kind = "rough"`
    /// or `"measured"` on radii or a flat; `[bodyN.surface.roughness]` on a roller).
    pub roughness: Option<Roughness>,
}

impl Body {
    /// The table of the case file that holds the body's roughness, for the errors that name
    /// its keys: `"{name}.surface"` on radii or a flat (the surface is the roughness),
    /// `"{name}.surface.roughness"` on a roller (the roughness is a table of its surface).
    pub fn roughness_table(&self, name: &str) -> String {
        match self.shape {
            Shape::Radii { .. } => format!("{name}.surface"),
            Shape::Surface(_) => format!("{name}.surface.roughness"),
        }
    }

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
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
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
/// `[field] edge_refinement = "band"`, stored as 0: the element tractions with the edge band
/// (`tribo::analysis::edge_refinement::EdgeBand`, docs/theory/HALFSPACE.md 2.5): the
/// edge-aware tractions near the contact edges at the surface and shallow depths.
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
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FieldPoints {
    /// `n` points evenly spaced over the field's half width, end points included; the
    /// stresses by the direct sum over the loaded elements (exact at any point).
    Uniform,
    /// The element centres of the contact grid; the stresses by FFT convolution per depth
    /// (the same kernels; cost O(layers N log N), for large contact grids).
    #[serde(alias = "centers")]
    Centres,
}

/// How the stresses at uniform field points are computed (`[field] method`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
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
    /// `edge_refinement`: [`EDGE_REFINEMENT_BAND`] (`"band"`, the default) the element
    /// tractions with the edge band (the edge-aware tractions in the cells along the contact
    /// edges, at the surface and shallow depths); 1 (`"none"`) the element tractions
    /// interpolated bilinearly; N > 1 the edge-aware reconstruction of the tractions (a
    /// square-root contact edge at a sub-element position) sampled on a grid N times finer per
    /// side, [`tribo::analysis::edge_refinement::refine_tractions`] (docs/theory/HALFSPACE.md
    /// 2.5). In 1 ..= [`MAX_EDGE_REFINEMENT`], with N times the contact grid's elements per
    /// side within [`tribo::grid::MAX_ELEMENTS_PER_SIDE`].
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
    /// Random limits and the distributions of V, Psi and psi_max (`[damage.probabilistic]`).
    pub probabilistic: Option<crate::probabilistic::ProbabilisticSpec>,
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
    /// Force or approach control (under `contact.mean_pressure`, the force on one period).
    pub loading: NormalLoading,
    /// Load steps of the sweep (`contact.load_steps`, default 1): loads (or approaches)
    /// `k / load_steps` of the case's, k = 1 ... load_steps, each solved from the previous
    /// pressure; the last is the case's load, at which the other stages run.
    pub load_steps: usize,
    /// The window is one period of a periodic contact (`[grid] periodic = true`); its size
    /// is the period (the window's half widths are half the period).
    pub periodic: bool,
    /// Elements along x and y.
    pub n: [usize; 2],
    /// Window size.
    pub window: Window,
    /// Solver (the case's `solver.method`; [`HalfSpaceCase::params`] keeps the default
    /// method, which the other solves of the pipeline use).
    pub method: NormalMethod,
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
            && !self.is_rough()
            && !self.periodic
    }

    /// Whether a body has a rough or measured surface.
    pub fn is_rough(&self) -> bool {
        self.body1.roughness.is_some() || self.body2.roughness.is_some()
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

/// The damage quantities a case file may name (`damage.criteria`): every stress and strain
/// quantity of (19)-(20) by its [`DamageQuantity::name`].
pub fn damage_vocabulary() -> Vec<DamageQuantity> {
    let mut v = DamageQuantity::standard_set(TensorKind::Stress);
    v.extend(DamageQuantity::standard_set(TensorKind::Strain));
    v
}
