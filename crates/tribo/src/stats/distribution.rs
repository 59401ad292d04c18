//! The distributions of random inputs and the counter-based uniform generator.

use crate::analysis::woehler::stats::{ln_gamma, ln_normal_cdf};
use serde::{Deserialize, Serialize};

/// A parameter of a distribution breaks a rule: which parameter, its value and the rule.
///
/// Converts into [`crate::Error::InvalidParameter`] (the field is the parameter's name; a
/// caller that knows the key path, e.g. `damage.probabilistic.limit`, prefixes it with
/// [`StatsError::into_error`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{parameter} = {value}: {rule}")]
pub struct StatsError {
    /// Name of the parameter (`sd`, `sigma_ln`, `low`, ...).
    pub parameter: &'static str,
    /// Its value.
    pub value: f64,
    /// The rule it breaks.
    pub rule: &'static str,
}

impl StatsError {
    fn new(parameter: &'static str, value: f64, rule: &'static str) -> Self {
        Self {
            parameter,
            value,
            rule,
        }
    }

    /// The library error with the parameter named under `prefix` (`prefix.parameter`; the bare
    /// parameter where `prefix` is empty).
    pub fn into_error(self, prefix: &str) -> crate::Error {
        let field = if prefix.is_empty() {
            self.parameter.to_string()
        } else {
            format!("{prefix}.{}", self.parameter)
        };
        crate::Error::invalid(field, self.value, self.rule)
    }
}

impl From<StatsError> for crate::Error {
    fn from(e: StatsError) -> Self {
        e.into_error("")
    }
}

/// A univariate distribution of a random input (SI units of the quantity it describes).
///
/// In a TOML/JSON file the variant is named by `dist`: `{ dist = "normal", mean = 1.0, sd =
/// 0.1 }`, `{ dist = "lognormal", median = 2e9, sigma_ln = 0.1 }`, `{ dist = "uniform", low =
/// 0.0, high = 1.0 }`, `{ dist = "weibull", shape = 3.0, scale = 1e9, location = 0.0 }`
/// (`location` optional, 0 by default). Unknown keys are refused.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "dist", rename_all = "lowercase", deny_unknown_fields)]
pub enum Distribution {
    /// Normal (Gaussian) with mean `mean` and standard deviation `sd` > 0.
    Normal {
        /// Mean.
        mean: f64,
        /// Standard deviation (> 0).
        sd: f64,
    },
    /// Lognormal: ln X ~ N(ln `median`, `sigma_ln`^2); X > 0.
    Lognormal {
        /// Median (> 0), exp of the mean of ln X.
        median: f64,
        /// Standard deviation of ln X (> 0).
        sigma_ln: f64,
    },
    /// Uniform on [`low`, `high`], low < high.
    Uniform {
        /// Lower end.
        low: f64,
        /// Upper end (> low).
        high: f64,
    },
    /// Three-parameter Weibull: F(x) = 1 - exp(-((x - location) / scale)^shape) for
    /// x > location.
    Weibull {
        /// Shape k (> 0).
        shape: f64,
        /// Scale lambda (> 0).
        scale: f64,
        /// Location (lower end of the support; 0 by default).
        #[serde(default)]
        location: f64,
    },
}

fn finite(parameter: &'static str, v: f64) -> Result<(), StatsError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(StatsError::new(parameter, v, "must be a finite number"))
    }
}

fn positive(parameter: &'static str, v: f64) -> Result<(), StatsError> {
    finite(parameter, v)?;
    if v > 0.0 {
        Ok(())
    } else {
        Err(StatsError::new(parameter, v, "must be > 0"))
    }
}

/// Phi(z) and 1 - Phi(z) = Phi(-z), each accurate in its small tail.
fn phi(z: f64) -> f64 {
    ln_normal_cdf(z).exp()
}

impl Distribution {
    /// Checks the parameters: finite, scales and shapes > 0, `low < high`.
    pub fn validate(&self) -> Result<(), StatsError> {
        match *self {
            Distribution::Normal { mean, sd } => {
                finite("mean", mean)?;
                positive("sd", sd)
            }
            Distribution::Lognormal { median, sigma_ln } => {
                positive("median", median)?;
                positive("sigma_ln", sigma_ln)
            }
            Distribution::Uniform { low, high } => {
                finite("low", low)?;
                finite("high", high)?;
                if high > low {
                    Ok(())
                } else {
                    Err(StatsError::new("high", high, "must be > low"))
                }
            }
            Distribution::Weibull {
                shape,
                scale,
                location,
            } => {
                positive("shape", shape)?;
                positive("scale", scale)?;
                finite("location", location)
            }
        }
    }

    /// The distribution's name as written in `dist`.
    pub fn name(&self) -> &'static str {
        match self {
            Distribution::Normal { .. } => "normal",
            Distribution::Lognormal { .. } => "lognormal",
            Distribution::Uniform { .. } => "uniform",
            Distribution::Weibull { .. } => "weibull",
        }
    }

    /// The cumulative distribution function F(x) = P(X <= x).
    pub fn cdf(&self, x: f64) -> f64 {
        if x.is_nan() {
            return f64::NAN;
        }
        if x == f64::NEG_INFINITY {
            return 0.0;
        }
        if x == f64::INFINITY {
            return 1.0;
        }
        match *self {
            Distribution::Normal { mean, sd } => phi((x - mean) / sd),
            Distribution::Lognormal { median, sigma_ln } => {
                if x <= 0.0 {
                    0.0
                } else {
                    phi((x / median).ln() / sigma_ln)
                }
            }
            Distribution::Uniform { low, high } => ((x - low) / (high - low)).clamp(0.0, 1.0),
            Distribution::Weibull {
                shape,
                scale,
                location,
            } => {
                if x <= location {
                    0.0
                } else {
                    -(-((x - location) / scale).powf(shape)).exp_m1()
                }
            }
        }
    }

    /// The survival function S(x) = P(X > x) = 1 - F(x), computed directly so that it keeps its
    /// relative precision in the upper tail.
    pub fn survival(&self, x: f64) -> f64 {
        if x.is_nan() {
            return f64::NAN;
        }
        if x == f64::NEG_INFINITY {
            return 1.0;
        }
        if x == f64::INFINITY {
            return 0.0;
        }
        match *self {
            Distribution::Normal { mean, sd } => phi(-(x - mean) / sd),
            Distribution::Lognormal { median, sigma_ln } => {
                if x <= 0.0 {
                    1.0
                } else {
                    phi(-(x / median).ln() / sigma_ln)
                }
            }
            Distribution::Uniform { low, high } => ((high - x) / (high - low)).clamp(0.0, 1.0),
            Distribution::Weibull {
                shape,
                scale,
                location,
            } => {
                if x <= location {
                    1.0
                } else {
                    (-((x - location) / scale).powf(shape)).exp()
                }
            }
        }
    }

    /// The quantile (inverse CDF) x with F(x) = p, for p in (0, 1); p = 0 and p = 1 give the
    /// ends of the support (possibly infinite), p outside [0, 1] gives NaN.
    pub fn quantile(&self, p: f64) -> f64 {
        if !(0.0..=1.0).contains(&p) {
            return f64::NAN;
        }
        match *self {
            Distribution::Normal { mean, sd } => mean + sd * normal_quantile(p),
            Distribution::Lognormal { median, sigma_ln } => {
                median * (sigma_ln * normal_quantile(p)).exp()
            }
            Distribution::Uniform { low, high } => {
                if p > 0.5 {
                    high - (1.0 - p) * (high - low)
                } else {
                    low + p * (high - low)
                }
            }
            Distribution::Weibull {
                shape,
                scale,
                location,
            } => location + scale * (-(-p).ln_1p()).powf(1.0 / shape),
        }
    }

    /// The upper quantile x with S(x) = P(X > x) = q, for q in (0, 1): the quantile at 1 - q
    /// without forming 1 - q (precise for small q).
    pub fn quantile_upper(&self, q: f64) -> f64 {
        if !(0.0..=1.0).contains(&q) {
            return f64::NAN;
        }
        match *self {
            Distribution::Normal { mean, sd } => mean - sd * normal_quantile(q),
            Distribution::Lognormal { median, sigma_ln } => {
                median * (-sigma_ln * normal_quantile(q)).exp()
            }
            Distribution::Uniform { low, high } => {
                if q > 0.5 {
                    low + (1.0 - q) * (high - low)
                } else {
                    high - q * (high - low)
                }
            }
            Distribution::Weibull {
                shape,
                scale,
                location,
            } => location + scale * (-q.ln()).powf(1.0 / shape),
        }
    }

    /// The mean E(X). Lognormal: median exp(sigma_ln^2 / 2); Weibull: location + scale
    /// Gamma(1 + 1/k).
    pub fn mean(&self) -> f64 {
        match *self {
            Distribution::Normal { mean, .. } => mean,
            Distribution::Lognormal { median, sigma_ln } => {
                median * (0.5 * sigma_ln * sigma_ln).exp()
            }
            Distribution::Uniform { low, high } => 0.5 * (low + high),
            Distribution::Weibull {
                shape,
                scale,
                location,
            } => location + scale * ln_gamma(1.0 + 1.0 / shape).exp(),
        }
    }

    /// The standard deviation. Lognormal: mean sqrt(exp(sigma_ln^2) - 1); uniform:
    /// (high - low) / sqrt 12; Weibull: scale sqrt(Gamma(1 + 2/k) - Gamma(1 + 1/k)^2).
    pub fn sd(&self) -> f64 {
        match *self {
            Distribution::Normal { sd, .. } => sd,
            Distribution::Lognormal { sigma_ln, .. } => {
                self.mean() * (sigma_ln * sigma_ln).exp_m1().sqrt()
            }
            Distribution::Uniform { low, high } => (high - low) / 12f64.sqrt(),
            Distribution::Weibull { shape, scale, .. } => {
                let g1 = ln_gamma(1.0 + 1.0 / shape).exp();
                let g2 = ln_gamma(1.0 + 2.0 / shape).exp();
                scale * (g2 - g1 * g1).max(0.0).sqrt()
            }
        }
    }

    /// The lower and upper ends of the support (infinite where unbounded).
    pub fn support(&self) -> (f64, f64) {
        match *self {
            Distribution::Normal { .. } => (f64::NEG_INFINITY, f64::INFINITY),
            Distribution::Lognormal { .. } => (0.0, f64::INFINITY),
            Distribution::Uniform { low, high } => (low, high),
            Distribution::Weibull { location, .. } => (location, f64::INFINITY),
        }
    }
}

/// A distribution restricted to [`low`, `high`] (either end optional) and renormalised:
/// F_T(x) = (F(x) - F(low)) / (F(high) - F(low)) on [low, high].
#[derive(Debug, Clone, PartialEq)]
pub struct Truncated {
    /// The untruncated distribution.
    pub dist: Distribution,
    /// Lower truncation point (none: the support's own end).
    pub low: Option<f64>,
    /// Upper truncation point (none: the support's own end).
    pub high: Option<f64>,
}

impl Truncated {
    /// No truncation: the distribution itself.
    pub fn plain(dist: Distribution) -> Self {
        Self {
            dist,
            low: None,
            high: None,
        }
    }

    fn lo(&self) -> f64 {
        self.low.unwrap_or(f64::NEG_INFINITY)
    }

    fn hi(&self) -> f64 {
        self.high.unwrap_or(f64::INFINITY)
    }

    /// The probability mass of the untruncated distribution inside [low, high].
    pub fn mass(&self) -> f64 {
        let (a, b) = (self.lo(), self.hi());
        // Take the difference on the side of the smaller tail probabilities.
        if self.dist.cdf(a) > 0.5 {
            self.dist.survival(a) - self.dist.survival(b)
        } else {
            self.dist.cdf(b) - self.dist.cdf(a)
        }
    }

    /// Checks the distribution, the ends (finite, low < high) and that [low, high] holds
    /// probability (a mass above 1e-300).
    pub fn validate(&self) -> Result<(), StatsError> {
        self.dist.validate()?;
        if let Some(low) = self.low {
            finite("low", low)?;
        }
        if let Some(high) = self.high {
            finite("high", high)?;
            if let Some(low) = self.low {
                if high <= low {
                    return Err(StatsError::new("high", high, "must be > low"));
                }
            }
        }
        let m = self.mass();
        if m.is_nan() || m <= 1e-300 {
            let (p, v) = match (self.low, self.high) {
                (Some(l), _) => ("low", l),
                (None, Some(h)) => ("high", h),
                (None, None) => ("low", f64::NAN),
            };
            return Err(StatsError::new(
                p,
                v,
                "the truncation interval [low, high] holds no probability of the distribution",
            ));
        }
        Ok(())
    }

    /// The CDF of the truncated distribution (0 below low, 1 above high).
    pub fn cdf(&self, x: f64) -> f64 {
        if x.is_nan() {
            return f64::NAN;
        }
        if x == f64::NEG_INFINITY {
            return 0.0;
        }
        if x == f64::INFINITY {
            return 1.0;
        }
        let (a, b) = (self.lo(), self.hi());
        if x <= a {
            return 0.0;
        }
        if x >= b {
            return 1.0;
        }
        let m = self.mass();
        let v = if self.dist.cdf(a) > 0.5 {
            (self.dist.survival(a) - self.dist.survival(x)) / m
        } else {
            (self.dist.cdf(x) - self.dist.cdf(a)) / m
        };
        v.clamp(0.0, 1.0)
    }

    /// The quantile: the untruncated quantile of the rescaled probability F(low) + p (F(high) -
    /// F(low)) (by the survival function where F(low) > 1/2, which keeps the precision in the
    /// upper tail), clamped to [low, high]; p = 0 and 1 give the ends exactly.
    pub fn quantile(&self, p: f64) -> f64 {
        if !(0.0..=1.0).contains(&p) {
            return f64::NAN;
        }
        let (lo, hi) = self.dist.support();
        let (a, b) = (self.lo().max(lo), self.hi().min(hi));
        if p == 0.0 {
            return a;
        }
        if p == 1.0 {
            return b;
        }
        let m = self.mass();
        let x = if self.dist.cdf(a) > 0.5 {
            self.dist.quantile_upper(self.dist.survival(a) - p * m)
        } else {
            self.dist.quantile(self.dist.cdf(a) + p * m)
        };
        x.clamp(a, b)
    }
}

/// The standard normal quantile Phi^-1(p) for p in (0, 1) (-inf at 0, +inf at 1, NaN
/// outside): Wichura's algorithm AS 241 (PPND16), rational approximations in three ranges,
/// relative accuracy about 1e-16 (Wichura 1988, Appl. Statist. 37(3), 477-484).
// The coefficients keep the digits printed in the paper.
#[allow(clippy::excessive_precision)]
pub fn normal_quantile(p: f64) -> f64 {
    if p.is_nan() || !(0.0..=1.0).contains(&p) {
        return f64::NAN;
    }
    if p == 0.0 {
        return f64::NEG_INFINITY;
    }
    if p == 1.0 {
        return f64::INFINITY;
    }
    const A: [f64; 8] = [
        3.387_132_872_796_366_608,
        1.331_416_678_917_843_774_5e2,
        1.971_590_950_306_551_442_7e3,
        1.373_169_376_550_946_112_5e4,
        4.592_195_393_154_987_145_7e4,
        6.726_577_092_700_870_085_3e4,
        3.343_057_558_358_812_810_5e4,
        2.509_080_928_730_122_672_7e3,
    ];
    const B: [f64; 8] = [
        1.0,
        4.231_333_070_160_091_125_2e1,
        6.871_870_074_920_579_083e2,
        5.394_196_021_424_751_107_7e3,
        2.121_379_430_158_659_586_7e4,
        3.930_789_580_009_271_061e4,
        2.872_908_573_572_194_267_4e4,
        5.226_495_278_852_854_561e3,
    ];
    const C: [f64; 8] = [
        1.423_437_110_749_683_577_34,
        4.630_337_846_156_545_295_9,
        5.769_497_221_460_691_405_5,
        3.647_848_324_763_204_605_04,
        1.270_458_252_452_368_382_58,
        2.417_807_251_774_506_117_7e-1,
        2.272_384_498_926_918_458_33e-2,
        7.745_450_142_783_414_076_4e-4,
    ];
    const D: [f64; 8] = [
        1.0,
        2.053_191_626_637_758_821_87,
        1.676_384_830_183_803_849_4,
        6.897_673_349_851_000_045_5e-1,
        1.481_039_764_274_800_745_9e-1,
        1.519_866_656_361_645_719_66e-2,
        5.475_938_084_995_344_946e-4,
        1.050_750_071_644_416_843_24e-9,
    ];
    const E: [f64; 8] = [
        6.657_904_643_501_103_777_2,
        5.463_784_911_164_114_369_9,
        1.784_826_539_917_291_335_8,
        2.965_605_718_285_048_912_3e-1,
        2.653_218_952_657_612_309_3e-2,
        1.242_660_947_388_078_438_6e-3,
        2.711_555_568_743_487_578_15e-5,
        2.010_334_399_292_288_132_65e-7,
    ];
    const F: [f64; 8] = [
        1.0,
        5.998_322_065_558_879_376_9e-1,
        1.369_298_809_227_358_053_1e-1,
        1.487_536_129_085_061_485_25e-2,
        7.868_691_311_456_132_591e-4,
        1.846_318_317_510_054_681_8e-5,
        1.421_511_758_316_445_888_7e-7,
        2.044_263_103_389_939_785_64e-15,
    ];
    fn poly(c: &[f64; 8], x: f64) -> f64 {
        c.iter().rev().fold(0.0, |acc, &ci| acc * x + ci)
    }
    let q = p - 0.5;
    if q.abs() <= 0.425 {
        let r = 0.180_625 - q * q;
        return q * poly(&A, r) / poly(&B, r);
    }
    // 1 - p is exact for p in [0.5, 1] (Sterbenz).
    let r = if q < 0.0 { p } else { 1.0 - p };
    let r = (-r.ln()).sqrt();
    let v = if r <= 5.0 {
        let r = r - 1.6;
        poly(&C, r) / poly(&D, r)
    } else {
        let r = r - 5.0;
        poly(&E, r) / poly(&F, r)
    };
    if q < 0.0 {
        -v
    } else {
        v
    }
}

/// The SplitMix64 finaliser (Steele, Lea & Flood 2014, "Fast splittable pseudorandom number
/// generators", OOPSLA; the constants of its `mix64`): a bijection of u64 with full avalanche.
fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The golden-ratio increment of SplitMix64.
const GAMMA: u64 = 0x9e37_79b9_7f4a_7c15;

/// A uniform number in (0, 1) from (seed, stream, index): counter-based, so the value depends
/// only on the three numbers, never on the order, the chunking or the engine that asks.
///
/// The three are combined by chained SplitMix64 finalisers (each a bijection, so distinct
/// indices of one (seed, stream) give distinct 64-bit states), and the top 52 bits k give
/// (k + 1/2) 2^-52: never 0 or 1, in [2^-53, 1 - 2^-53]. The streams separate the random
/// inputs of one study (stream = the parameter's number), the index the points or samples.
pub fn uniform01(seed: u64, stream: u64, index: u64) -> f64 {
    let h = mix64(seed.wrapping_add(GAMMA));
    let h = mix64(h ^ stream.wrapping_mul(GAMMA).wrapping_add(GAMMA));
    let h = mix64(
        h ^ index
            .wrapping_mul(GAMMA)
            .wrapping_add(GAMMA.rotate_left(17)),
    );
    bits_to_open01(h)
}

/// (k + 1/2) 2^-52 with k the top 52 bits of `h`: in [2^-53, 1 - 2^-53], both ends exactly
/// representable (53 significant bits), so never 0 or 1.
fn bits_to_open01(h: u64) -> f64 {
    ((h >> 12) as f64 + 0.5) * (1.0 / (1u64 << 52) as f64)
}

#[cfg(test)]
mod tests;
