//! Fatigue (Woehler, S-N) curves of a tribo-fatigue system, part J of docs/theory/DESIGN.md: the paper's
//! Fig. 3, four curves from the SI wear-fatigue machines: mechanical fatigue (sigma, bending
//! with rotation of the shaft), rolling fatigue (p, contact pressure of the roller), and
//! mechano-rolling fatigue (sigma_p: the shaft's bending fatigue while it is rolled on;
//! p_sigma: the rolling fatigue under cyclic bending). Each curve has a fatigue limit
//! (sigma_-1, p_f, sigma_-1p, p_f_sigma), the slope m of its left branch and the abscissa N_G
//! of its knee ("inflection point" in the paper's Sec. 3).
//!
//! Amplitude or range is never implicit: a curve carries its [`LoadMeasure`] and every query
//! takes a [`Load`], which carries its own; a stress range is converted to an amplitude by
//! S_a = Delta S / 2 (a stress cycle between S_m - S_a and S_m + S_a has the range 2 S_a),
//! a contact pressure (the maximum Hertz pressure p0 of each pass) is never converted. The
//! convention difference between libraries (pyLife: amplitudes; fatpack and py-fatigue:
//! ranges) is a known source of error (pyLife issue #202, `docs/theory/FATIGUE.md`).
//!
//! Submodules: [`fit`] fits curves to test data (ASTM E739 regression, maximum likelihood);
//! [`stats`] the special functions; [`nelder_mead`] the minimiser of the likelihood.

pub mod fit;
pub mod nelder_mead;
pub mod stats;

pub use fit::{
    fit_max_likelihood, fit_regression, BasquinRegression, ConfidenceBand, FatigueData,
    FatigueTest, FiniteSet, MaxLikelihoodFit, MaxLikelihoodParams, MaxLikelihoodStdErrors,
    RegressionFit, RegressionParams,
};

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// What a load value measures. Values are in Pa.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LoadMeasure {
    /// Stress amplitude S_a = (S_max - S_min) / 2, Pa.
    Amplitude,
    /// Stress range Delta S = S_max - S_min = 2 S_a, Pa.
    Range,
    /// Maximum contact pressure p0 of each rolling pass, Pa (not a cyclic amplitude; never
    /// converted to one).
    ContactPressure,
}

impl LoadMeasure {
    /// The name used in files and messages.
    pub fn name(self) -> &'static str {
        match self {
            LoadMeasure::Amplitude => "amplitude",
            LoadMeasure::Range => "range",
            LoadMeasure::ContactPressure => "contact_pressure",
        }
    }

    /// Factor from this measure to the stress amplitude (1 or 1/2); None for pressure.
    fn to_amplitude(self) -> Option<f64> {
        match self {
            LoadMeasure::Amplitude => Some(1.0),
            LoadMeasure::Range => Some(0.5),
            LoadMeasure::ContactPressure => None,
        }
    }

    /// Convert `value` (Pa) given in this measure into `to`: range = 2 amplitude; a contact
    /// pressure converts only to itself, and a stress never to a pressure.
    pub fn convert(self, value: f64, to: LoadMeasure) -> Result<f64> {
        if self == to {
            return Ok(value);
        }
        match (self.to_amplitude(), to.to_amplitude()) {
            (Some(a), Some(b)) => Ok(value * a / b),
            _ => Err(Error::invalid(
                "load.measure",
                format!("{} -> {}", self.name(), to.name()),
                "a contact pressure and a stress amplitude or range measure different things \
                 and cannot be converted",
            )),
        }
    }
}

/// A stress amplitude S_a, Pa.
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Serialize, Deserialize)]
pub struct StressAmplitude(pub f64);

/// A stress range Delta S = 2 S_a, Pa.
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Serialize, Deserialize)]
pub struct StressRange(pub f64);

/// A maximum contact pressure p0, Pa.
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Serialize, Deserialize)]
pub struct ContactPressure(pub f64);

impl From<StressRange> for StressAmplitude {
    /// S_a = Delta S / 2.
    fn from(r: StressRange) -> Self {
        StressAmplitude(0.5 * r.0)
    }
}

impl From<StressAmplitude> for StressRange {
    /// Delta S = 2 S_a.
    fn from(a: StressAmplitude) -> Self {
        StressRange(2.0 * a.0)
    }
}

/// A load level with its measure: the only way to ask a curve about a load.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Load {
    value: f64,
    measure: LoadMeasure,
}

impl Load {
    /// A load of `value` Pa in `measure`; it must be finite and > 0.
    pub fn new(value: f64, measure: LoadMeasure) -> Result<Self> {
        if !(value.is_finite() && value > 0.0) {
            return Err(Error::invalid(
                "load",
                value,
                "a load level must be finite and > 0 (Pa)",
            ));
        }
        Ok(Self { value, measure })
    }

    /// The value, Pa, in this load's own measure.
    pub fn value(&self) -> f64 {
        self.value
    }

    /// This load's measure.
    pub fn measure(&self) -> LoadMeasure {
        self.measure
    }

    /// The value, Pa, expressed in `measure`.
    pub fn value_in(&self, measure: LoadMeasure) -> Result<f64> {
        self.measure.convert(self.value, measure)
    }
}

impl TryFrom<StressAmplitude> for Load {
    type Error = Error;
    fn try_from(a: StressAmplitude) -> Result<Self> {
        Load::new(a.0, LoadMeasure::Amplitude)
    }
}

impl TryFrom<StressRange> for Load {
    type Error = Error;
    fn try_from(r: StressRange) -> Result<Self> {
        Load::new(r.0, LoadMeasure::Range)
    }
}

impl TryFrom<ContactPressure> for Load {
    type Error = Error;
    fn try_from(p: ContactPressure) -> Result<Self> {
        Load::new(p.0, LoadMeasure::ContactPressure)
    }
}

/// The four test kinds of the paper's Fig. 3 (Sec. 3: "Four fatigue curves are plotted").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum TestKind {
    /// Mechanical fatigue: the shaft in bending with rotation; limit sigma_-1; stress.
    #[serde(rename = "sigma")]
    MechanicalFatigue,
    /// Rolling fatigue of the friction pair; limit p_f; contact pressure.
    #[serde(rename = "p")]
    RollingFatigue,
    /// Mechano-rolling fatigue, bending limit of the shaft while rolled on at a contact
    /// pressure p0; limit sigma_-1p; stress.
    #[serde(rename = "sigma_p")]
    MechanoRollingStress,
    /// Mechano-rolling fatigue, rolling limit under a cyclic bending stress sigma_a; limit
    /// p_f_sigma; contact pressure.
    #[serde(rename = "p_sigma")]
    MechanoRollingPressure,
}

impl TestKind {
    /// Every kind, in the paper's order.
    pub const ALL: [TestKind; 4] = [
        TestKind::MechanicalFatigue,
        TestKind::RollingFatigue,
        TestKind::MechanoRollingStress,
        TestKind::MechanoRollingPressure,
    ];

    /// The curve's symbol in the paper (sigma, p, sigma_p, p_sigma).
    pub fn symbol(self) -> &'static str {
        match self {
            TestKind::MechanicalFatigue => "sigma",
            TestKind::RollingFatigue => "p",
            TestKind::MechanoRollingStress => "sigma_p",
            TestKind::MechanoRollingPressure => "p_sigma",
        }
    }

    /// The limit's symbol (sigma_-1, p_f, sigma_-1p, p_f_sigma).
    pub fn limit_symbol(self) -> &'static str {
        match self {
            TestKind::MechanicalFatigue => "sigma_-1",
            TestKind::RollingFatigue => "p_f",
            TestKind::MechanoRollingStress => "sigma_-1p",
            TestKind::MechanoRollingPressure => "p_f_sigma",
        }
    }

    /// Whether the load is a contact pressure (p, p_sigma) rather than a stress.
    pub fn is_pressure(self) -> bool {
        matches!(
            self,
            TestKind::RollingFatigue | TestKind::MechanoRollingPressure
        )
    }

    /// The measure a test of this kind is naturally reported in.
    pub fn default_measure(self) -> LoadMeasure {
        if self.is_pressure() {
            LoadMeasure::ContactPressure
        } else {
            LoadMeasure::Amplitude
        }
    }

    /// Check that `measure` fits this kind (stress kinds: amplitude or range; pressure kinds:
    /// contact pressure).
    pub fn check_measure(self, measure: LoadMeasure) -> Result<()> {
        let ok = self.is_pressure() == (measure == LoadMeasure::ContactPressure);
        if ok {
            Ok(())
        } else {
            Err(Error::invalid(
                "measure",
                measure.name(),
                format!(
                    "the {} curve is measured in {}",
                    self.symbol(),
                    if self.is_pressure() {
                        "contact_pressure"
                    } else {
                        "stress amplitude or range"
                    }
                ),
            ))
        }
    }
}

/// A predicted life.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Life {
    /// Cycles to failure (median).
    Finite(f64),
    /// Below the fatigue limit (no second slope): no failure.
    Infinite,
}

/// A Woehler curve with a knee: Basquin's law above the fatigue limit,
/// N = N_G (S / S_D)^(-m) for S > S_D (Basquin 1910; the form of pyLife's `WoehlerCurve`
/// with SD, ND, k_1), and below it infinite life, or N = N_G (S / S_D)^(-m2) with an
/// optional second slope m2 (Haibach's extension, m2 = 2m - 1 in his rule). S in the curve's
/// measure, Pa; N in cycles. This is the 50 % (median) curve.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WoehlerCurve {
    kind: TestKind,
    measure: LoadMeasure,
    fatigue_limit: f64,
    slope: f64,
    knee_cycles: f64,
    slope_beyond_knee: Option<f64>,
}

fn positive(field: &str, v: f64, what: &str) -> Result<f64> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(Error::invalid(
            field,
            v,
            format!("{what} must be finite and > 0"),
        ))
    }
}

impl WoehlerCurve {
    /// A curve of `kind` in `measure` with fatigue limit S_D (Pa), slope m of the left branch
    /// (> 0) and knee N_G (cycles, > 0).
    pub fn new(
        kind: TestKind,
        measure: LoadMeasure,
        fatigue_limit: f64,
        slope: f64,
        knee_cycles: f64,
    ) -> Result<Self> {
        kind.check_measure(measure)?;
        Ok(Self {
            kind,
            measure,
            fatigue_limit: positive("fatigue_limit", fatigue_limit, "the fatigue limit (Pa)")?,
            slope: positive("slope", slope, "the slope m")?,
            knee_cycles: positive("knee_cycles", knee_cycles, "the knee N_G (cycles)")?,
            slope_beyond_knee: None,
        })
    }

    /// The same curve with a finite second slope m2 > m below the fatigue limit.
    pub fn with_slope_beyond_knee(mut self, m2: f64) -> Result<Self> {
        positive("slope_beyond_knee", m2, "the second slope m2")?;
        if m2 <= self.slope {
            return Err(Error::invalid(
                "slope_beyond_knee",
                m2,
                format!(
                    "the second slope must be steeper in N than m = {}",
                    self.slope
                ),
            ));
        }
        self.slope_beyond_knee = Some(m2);
        Ok(self)
    }

    /// Test kind.
    pub fn kind(&self) -> TestKind {
        self.kind
    }
    /// The measure of S.
    pub fn measure(&self) -> LoadMeasure {
        self.measure
    }
    /// Fatigue limit S_D, Pa, in [`Self::measure`].
    pub fn fatigue_limit(&self) -> f64 {
        self.fatigue_limit
    }
    /// The fatigue limit as a [`Load`].
    pub fn fatigue_limit_load(&self) -> Load {
        Load {
            value: self.fatigue_limit,
            measure: self.measure,
        }
    }
    /// Slope m of the left branch (pyLife's k_1).
    pub fn slope(&self) -> f64 {
        self.slope
    }
    /// Knee N_G, cycles.
    pub fn knee_cycles(&self) -> f64 {
        self.knee_cycles
    }
    /// Second slope m2, if any.
    pub fn slope_beyond_knee(&self) -> Option<f64> {
        self.slope_beyond_knee
    }

    /// The same curve in another measure (amplitude <-> range: S_D scales by 2, m and N_G
    /// stay).
    pub fn in_measure(&self, measure: LoadMeasure) -> Result<Self> {
        self.kind.check_measure(measure)?;
        Ok(Self {
            fatigue_limit: self.measure.convert(self.fatigue_limit, measure)?,
            measure,
            ..*self
        })
    }

    /// Median cycles to failure at `load` (converted to the curve's measure first).
    pub fn cycles_to_failure(&self, load: Load) -> Result<Life> {
        let s = load.value_in(self.measure)?;
        let r = s / self.fatigue_limit;
        if r > 1.0 {
            Ok(Life::Finite(self.knee_cycles * r.powf(-self.slope)))
        } else {
            Ok(match self.slope_beyond_knee {
                Some(m2) => Life::Finite(self.knee_cycles * r.powf(-m2)),
                None => Life::Infinite,
            })
        }
    }

    /// The load (in the curve's measure) whose median life is `cycles`: the inverse of
    /// Basquin's law, S = S_D (N / N_G)^(-1/m) for N < N_G, S_D beyond (or the second slope).
    pub fn strength_at(&self, cycles: f64) -> Result<Load> {
        positive("cycles", cycles, "a number of cycles")?;
        let r = cycles / self.knee_cycles;
        let value = if r < 1.0 {
            self.fatigue_limit * r.powf(-1.0 / self.slope)
        } else {
            match self.slope_beyond_knee {
                Some(m2) => self.fatigue_limit * r.powf(-1.0 / m2),
                None => self.fatigue_limit,
            }
        };
        Load::new(value, self.measure)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn curve() -> WoehlerCurve {
        WoehlerCurve::new(
            TestKind::MechanicalFatigue,
            LoadMeasure::Amplitude,
            250e6,
            6.0,
            1e6,
        )
        .unwrap()
    }

    #[test]
    fn basquin_and_its_inverse() {
        let c = curve();
        // 500 MPa = 2 S_D: N = 1e6 * 2^-6 = 15625 exactly (powers of two are exact in f64).
        let n = c
            .cycles_to_failure(Load::new(500e6, LoadMeasure::Amplitude).unwrap())
            .unwrap();
        assert_eq!(n, Life::Finite(15_625.0));
        let s = c.strength_at(15_625.0).unwrap();
        assert!((s.value() - 500e6).abs() < 1e-3);
        assert_eq!(
            c.cycles_to_failure(Load::new(200e6, LoadMeasure::Amplitude).unwrap())
                .unwrap(),
            Life::Infinite
        );
        assert_eq!(c.strength_at(1e9).unwrap().value(), 250e6);
        let c2 = c.with_slope_beyond_knee(11.0).unwrap();
        // Haibach m2 = 2m - 1 = 11: at S_D/2, N = 1e6 * 2^11.
        assert_eq!(
            c2.cycles_to_failure(Load::new(125e6, LoadMeasure::Amplitude).unwrap())
                .unwrap(),
            Life::Finite(2048e6)
        );
        assert!(c.with_slope_beyond_knee(5.0).is_err());
    }

    #[test]
    fn range_and_amplitude_are_never_confused() {
        let c = curve();
        // A range of 500 MPa is an amplitude of 250 MPa: the fatigue limit, infinite life.
        let range = Load::try_from(StressRange(500e6)).unwrap();
        assert_eq!(c.cycles_to_failure(range).unwrap(), Life::Infinite);
        let amp = Load::try_from(StressAmplitude(500e6)).unwrap();
        assert_eq!(c.cycles_to_failure(amp).unwrap(), Life::Finite(15_625.0));
        // The same curve in ranges: S_D doubles, the life at a given physical load is equal.
        let cr = c.in_measure(LoadMeasure::Range).unwrap();
        assert_eq!(cr.fatigue_limit(), 500e6);
        assert_eq!(cr.cycles_to_failure(amp).unwrap(), Life::Finite(15_625.0));
        assert_eq!(
            StressAmplitude::from(StressRange(3.0)),
            StressAmplitude(1.5)
        );
        // A pressure is not a stress.
        let p = Load::try_from(ContactPressure(1e9)).unwrap();
        assert!(c.cycles_to_failure(p).is_err());
        assert!(WoehlerCurve::new(
            TestKind::RollingFatigue,
            LoadMeasure::Amplitude,
            1e9,
            6.0,
            1e6
        )
        .is_err());
    }

    #[test]
    fn bad_curve_parameters_are_errors() {
        for (s, m, n) in [
            (0.0, 6.0, 1e6),
            (f64::NAN, 6.0, 1e6),
            (1e8, -1.0, 1e6),
            (1e8, 6.0, 0.0),
            (1e8, 6.0, f64::INFINITY),
        ] {
            let e = WoehlerCurve::new(TestKind::MechanicalFatigue, LoadMeasure::Amplitude, s, m, n);
            assert!(
                matches!(e, Err(Error::InvalidParameter { .. })),
                "{s} {m} {n}"
            );
        }
        assert!(Load::new(-1.0, LoadMeasure::Amplitude).is_err());
        assert!(curve().strength_at(0.0).is_err());
    }
}
