//! `[damage.probabilistic]` of a half-space case: random limiting values phi_q^lim, and the
//! distributions of V_q, Psi_q and psi_max that follow from the one computed field (seed paper,
//! after (21): "psi_ij, psi_i, psi_int, psi_u are generally speaking probabilistic in nature").
//!
//! ```toml
//! [damage.probabilistic]
//! probabilities = [0.05, 0.5, 0.95]     # exceedance probabilities reported in summary.json
//! points = 49                           # points of the exceedance curves (probabilistic.csv)
//! [damage.probabilistic.limits.sigma_int]   # one per criterion, the spelling of [[random]]
//! dist = "lognormal"
//! median = "3.3 GPa"                    # in the criterion's unit (a unit string for stresses)
//! sigma_ln = 0.08
//! truncate = { low = "2 GPa" }          # optional
//! ```
//!
//! Only the limit is random: the field is computed once and
//! [`tribo::analysis::damage::probabilistic::probabilistic_damage`] gives the distributions by
//! change of variables (docs/theory/FATIGUE.md, "Probabilistic damage"). For a compressive
//! criterion (a name ending in `-`) the distribution is that of the magnitude |phi_lim|. The
//! criterion's deterministic result uses `damage.limits.NAME` where given, else the
//! distribution's median, else the case's default limit.

use crate::error::{CaseError, CaseResult};
use crate::units::{number, quantity, show, Dim};
use serde::Serialize;
use toml::Value;
use tribo::analysis::damage::probabilistic::{
    curve_probabilities, probabilistic_damage, ProbabilisticDamage,
};
use tribo::analysis::damage::{
    relative_damage, DamageMesh, DamageQuantity, Execution, Limit, Sense,
};
use tribo::kernels::subsurface::StressTensor;
use tribo::stats::{Distribution, Truncated};
use tribo::ElasticMaterial;

/// The keys of `[damage.probabilistic]`.
pub const KEYS: [&str; 3] = ["limits", "probabilities", "points"];

/// The keys of a distribution (`damage.probabilistic.limits.NAME`), as in a study's
/// `[[random]]` (less its `key`).
pub const DISTRIBUTION_KEYS: [&str; 11] = [
    "dist", "mean", "sd", "median", "sigma_ln", "low", "high", "shape", "scale", "location",
    "truncate",
];

/// The default exceedance probabilities reported in `summary.json`.
pub const DEFAULT_PROBABILITIES: [f64; 3] = [0.05, 0.5, 0.95];

/// The default number of equally spaced points of the exceedance curves.
pub const DEFAULT_POINTS: usize = 49;

/// The most curve points (each is one pass of the dangerous-region routine over the field).
pub const MAX_POINTS: usize = 999;

/// The largest ratio between a random limit's quantiles over the probabilities evaluated
/// (the curve's 1e-4 ... 0.9999 and the reported ones): six decades. A material's limit
/// scatters by tens of percent (the examples: sigma_ln = 0.08); a distribution wider than
/// this (a lognormal with sigma_ln above ~1.8, a Weibull shape below ~0.8) puts its tails at
/// limits no material has, and its far quantiles overflow or vanish.
pub const MAX_LIMIT_SPREAD: f64 = 1e6;

/// The range of a random limit's quantiles by the criterion's unit: stresses within the range
/// of the elastic moduli a case takes ([1e2, 1e13] Pa), energy densities within
/// [1e-6, 1e13] J/m^3, strains within [1e-12, 1].
pub fn limit_range(unit: &str) -> [f64; 2] {
    match unit {
        "Pa" => [1e2, 1e13],
        "J/m^3" => [1e-6, 1e13],
        _ => [1e-12, 1.0],
    }
}

/// A random limit's quantiles at `probabilities` (and their complements) are finite, within
/// [`limit_range`] and within [`MAX_LIMIT_SPREAD`] of each other, and not all equal (to
/// 1e-9: a degenerate distribution, sigma_ln = 1e-300, made NaN of the summary).
fn check_quantiles(
    field: &str,
    limit: &Truncated,
    unit: &str,
    probabilities: &[f64],
) -> CaseResult<()> {
    let (mut lo, mut hi, mut finite) = (f64::INFINITY, 0.0_f64, true);
    for &p in probabilities {
        for q in [limit.quantile(p), limit.quantile(1.0 - p)] {
            finite &= q.is_finite() && q > 0.0;
            lo = lo.min(q);
            hi = hi.max(q);
        }
    }
    let [a, b] = limit_range(unit);
    if finite && lo >= a && hi <= b && hi <= MAX_LIMIT_SPREAD * lo && hi > lo * (1.0 + 1e-9) {
        return Ok(());
    }
    Err(CaseError::field(
        field,
        format!("quantiles from {lo:e} to {hi:e} {unit}"),
        format!(
            "a random limit must stay finite, within [{a:e}, {b:e}] {unit}, and within a \
             factor {MAX_LIMIT_SPREAD:e} between its quantiles at the probabilities evaluated \
             (1e-4 ... 0.9999 and the reported ones), and scatter (a limit whose quantiles \
             agree to 1e-9 is a fixed one: give it as damage.limits.NAME)"
        ),
    ))
}

/// The validated `[damage.probabilistic]` table.
#[derive(Debug, Clone, PartialEq)]
pub struct ProbabilisticSpec {
    /// The random limits by criterion name, in the order of `damage.criteria`; each the
    /// distribution of phi_lim (tensile and unsigned criteria) or of |phi_lim| (compressive).
    pub limits: Vec<(String, Truncated)>,
    /// Exceedance probabilities reported in `summary.json`, each in (0, 1), increasing.
    pub probabilities: Vec<f64>,
    /// Equally spaced points of the exceedance curves ([`curve_probabilities`]).
    pub points: usize,
}

impl ProbabilisticSpec {
    /// The distribution of criterion `name`'s limit, if it is random.
    pub fn limit(&self, name: &str) -> Option<&Truncated> {
        self.limits.iter().find(|(n, _)| n == name).map(|(_, t)| t)
    }

    /// Every probability evaluated: the curve's and the reported ones, sorted, distinct.
    pub fn all_probabilities(&self) -> Vec<f64> {
        let mut p = curve_probabilities(self.points);
        p.extend(&self.probabilities);
        p.sort_by(f64::total_cmp);
        p.dedup();
        p
    }

    /// The deterministic limit a criterion without `damage.limits.NAME` takes: the median of
    /// its distribution, signed as the quantity (negative for a compressive one).
    pub fn median_limit(&self, name: &str, quantity: DamageQuantity) -> Option<f64> {
        let m = self.limit(name)?.quantile(0.5);
        Some(if quantity.sense() == Some(Sense::Compression) {
            -m
        } else {
            m
        })
    }
}

/// Parses `[damage.probabilistic]`: `criteria` are the names of `damage.criteria` (a random
/// limit must belong to one of them), `unit_of` gives a criterion's unit ("Pa" reads unit
/// strings). Every error names its key.
pub fn parse(
    table: &toml::Table,
    criteria: &[(String, DamageQuantity)],
) -> CaseResult<ProbabilisticSpec> {
    for key in table.keys() {
        if !KEYS.contains(&key.as_str()) {
            return Err(CaseError::field(
                format!("damage.probabilistic.{key}"),
                show(&table[key]),
                format!("unknown key; expected one of {}", KEYS.join(", ")),
            ));
        }
    }
    let probabilities = match table.get("probabilities") {
        None => DEFAULT_PROBABILITIES.to_vec(),
        Some(v) => probabilities(v)?,
    };
    let points = match table.get("points") {
        None => DEFAULT_POINTS,
        Some(v) => {
            let field = "damage.probabilistic.points";
            let n = crate::units::count(field, v)?;
            if !(1..=MAX_POINTS).contains(&n) {
                return Err(CaseError::field(
                    field,
                    n,
                    format!("must be 1 ... {MAX_POINTS} (points of the exceedance curves)"),
                ));
            }
            n
        }
    };
    let Some(limits) = table.get("limits") else {
        return Err(CaseError::field(
            "damage.probabilistic.limits",
            "(missing)",
            "required: a distribution per criterion, e.g. [damage.probabilistic.limits.sigma_int] \
             dist = \"lognormal\", median = \"3.3 GPa\", sigma_ln = 0.08",
        ));
    };
    let Value::Table(limits) = limits else {
        return Err(CaseError::field(
            "damage.probabilistic.limits",
            show(limits),
            "must be a table of distributions by criterion name",
        ));
    };
    if limits.is_empty() {
        return Err(CaseError::field(
            "damage.probabilistic.limits",
            "{}",
            "needs at least one criterion's distribution",
        ));
    }
    for name in limits.keys() {
        if !criteria.iter().any(|(n, _)| n == name) {
            return Err(CaseError::field(
                format!("damage.probabilistic.limits.{name}"),
                "given",
                "is not one of damage.criteria",
            ));
        }
    }
    let mut evaluated = curve_probabilities(points);
    evaluated.extend(&probabilities);
    evaluated.push(0.5);
    let mut out = Vec::new();
    let mut first_unit: Option<(&str, &str)> = None;
    for (name, quantity) in criteria {
        if let Some(v) = limits.get(name) {
            let field = format!("damage.probabilistic.limits.{name}");
            match first_unit {
                None => first_unit = Some((name, quantity.unit())),
                Some((n, u)) if u != quantity.unit() => {
                    return Err(CaseError::field(
                        &field,
                        "given",
                        format!(
                            "the random limits share one unit (the limit column of \
                             probabilistic.csv): {n} is in {u}, {name} in {}",
                            quantity.unit()
                        ),
                    ))
                }
                Some(_) => {}
            }
            let limit = distribution(&field, v, quantity.unit())?;
            check_quantiles(&field, &limit, quantity.unit(), &evaluated)?;
            out.push((name.clone(), limit));
        }
    }
    Ok(ProbabilisticSpec {
        limits: out,
        probabilities,
        points,
    })
}

fn probabilities(v: &Value) -> CaseResult<Vec<f64>> {
    let field = "damage.probabilistic.probabilities";
    let Value::Array(items) = v else {
        return Err(CaseError::field(
            field,
            show(v),
            "must be a list of exceedance probabilities in (0, 1)",
        ));
    };
    if items.is_empty() || items.len() > 99 {
        return Err(CaseError::field(
            field,
            show(v),
            "must hold 1 ... 99 probabilities",
        ));
    }
    let mut out: Vec<f64> = Vec::with_capacity(items.len());
    for (k, item) in items.iter().enumerate() {
        let f = format!("{field}[{k}]");
        let p = number(&f, item)?;
        if !(p > 0.0 && p < 1.0) {
            return Err(CaseError::field(
                &f,
                show(item),
                "an exceedance probability must be in (0, 1)",
            ));
        }
        if out.last().is_some_and(|q| p <= *q) {
            return Err(CaseError::field(&f, show(item), "must be increasing"));
        }
        out.push(p);
    }
    Ok(out)
}

/// The distribution at `field`: `dist` and its parameters (those with the quantity's
/// dimension read in `unit`, a stress's as a unit string), optional `truncate = { low, high }`.
fn distribution(field: &str, v: &Value, unit: &str) -> CaseResult<Truncated> {
    let Value::Table(t) = v else {
        return Err(CaseError::field(
            field,
            show(v),
            "must be a distribution table, e.g. { dist = \"lognormal\", median = \"3.3 GPa\", \
             sigma_ln = 0.08 }",
        ));
    };
    for key in t.keys() {
        if !DISTRIBUTION_KEYS.contains(&key.as_str()) {
            return Err(CaseError::field(
                format!("{field}.{key}"),
                show(&t[key]),
                format!(
                    "unknown key; expected one of {}",
                    DISTRIBUTION_KEYS.join(", ")
                ),
            ));
        }
    }
    let dimensioned = |key: &str, v: &Value| -> CaseResult<f64> {
        let f = format!("{field}.{key}");
        if unit == "Pa" {
            quantity(&f, v, Dim::Pressure)
        } else {
            number(&f, v)
        }
    };
    let kinds = "\"normal\" (mean, sd), \"lognormal\" (median, sigma_ln), \"uniform\" (low, \
                 high) or \"weibull\" (shape, scale, location)";
    let dist = match t.get("dist") {
        Some(Value::String(s)) => s.as_str(),
        Some(other) => {
            return Err(CaseError::field(
                format!("{field}.dist"),
                show(other),
                format!("must be {kinds}"),
            ))
        }
        None => {
            return Err(CaseError::field(
                format!("{field}.dist"),
                "(missing)",
                format!("required: {kinds}"),
            ))
        }
    };
    let (params, optional): (&[&str], &[&str]) = match dist {
        "normal" => (&["mean", "sd"], &[]),
        "lognormal" => (&["median", "sigma_ln"], &[]),
        "uniform" => (&["low", "high"], &[]),
        "weibull" => (&["shape", "scale"], &["location"]),
        other => {
            return Err(CaseError::field(
                format!("{field}.dist"),
                format!("{other:?}"),
                format!("must be {kinds}"),
            ))
        }
    };
    for key in t.keys() {
        let k = key.as_str();
        if k != "dist" && k != "truncate" && !params.contains(&k) && !optional.contains(&k) {
            return Err(CaseError::field(
                format!("{field}.{key}"),
                show(&t[key]),
                format!(
                    "not a parameter of dist = {dist:?}, whose parameters are {}",
                    params
                        .iter()
                        .chain(optional)
                        .copied()
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            ));
        }
    }
    let get = |key: &str, dimensionless: bool| -> CaseResult<Option<f64>> {
        match t.get(key) {
            None => Ok(None),
            Some(v) if dimensionless => number(&format!("{field}.{key}"), v).map(Some),
            Some(v) => dimensioned(key, v).map(Some),
        }
    };
    let need = |key: &str, dimensionless: bool| -> CaseResult<f64> {
        get(key, dimensionless)?.ok_or_else(|| {
            CaseError::field(
                format!("{field}.{key}"),
                "(missing)",
                format!("required by dist = {dist:?}"),
            )
        })
    };
    let d = match dist {
        "normal" => Distribution::Normal {
            mean: need("mean", false)?,
            sd: need("sd", false)?,
        },
        "lognormal" => Distribution::Lognormal {
            median: need("median", false)?,
            sigma_ln: need("sigma_ln", true)?,
        },
        "uniform" => Distribution::Uniform {
            low: need("low", false)?,
            high: need("high", false)?,
        },
        _ => Distribution::Weibull {
            shape: need("shape", true)?,
            scale: need("scale", false)?,
            location: get("location", false)?.unwrap_or(0.0),
        },
    };
    let (mut low, mut high) = (None, None);
    match t.get("truncate") {
        None => {}
        Some(Value::Table(b)) => {
            for (key, v) in b {
                let f = format!("{field}.truncate.{key}");
                match key.as_str() {
                    "low" => low = Some(dimensioned("truncate.low", v)?),
                    "high" => high = Some(dimensioned("truncate.high", v)?),
                    _ => {
                        return Err(CaseError::field(
                            f,
                            show(v),
                            "unknown key; expected one of low, high",
                        ))
                    }
                }
            }
        }
        Some(v) => {
            return Err(CaseError::field(
                format!("{field}.truncate"),
                show(v),
                "must be a table { low = .., high = .. } (either optional)",
            ))
        }
    }
    let truncated = Truncated { dist: d, low, high };
    truncated.validate().map_err(|e| {
        CaseError::field(
            format!("{field}.{}", e.parameter),
            e.value,
            e.rule.to_string(),
        )
    })?;
    if truncated.cdf(0.0) > 1e-12 {
        return Err(CaseError::field(
            field,
            format!("P(limit <= 0) = {:.3e}", truncated.cdf(0.0)),
            "the limit (its magnitude for a compressive criterion) must be > 0 with \
             probability 1: truncate the distribution (truncate = { low = 0 }) or choose one \
             on positive values (lognormal, Weibull)",
        ));
    }
    Ok(truncated)
}

/// The distributions of one criterion with a random limit on the field `stress`: phi is the
/// quantity at a unit limit (psi at phi_lim = 1, or -1 for a compressive quantity, so that
/// psi = phi / L with L the limit's magnitude), then
/// [`probabilistic_damage`] at every probability of `spec`.
pub fn evaluate(
    spec: &ProbabilisticSpec,
    name: &str,
    quantity: DamageQuantity,
    mesh: &DamageMesh,
    stress: &[StressTensor],
    material: &ElasticMaterial,
) -> CaseResult<Option<CriterionDistribution>> {
    let Some(limit) = spec.limit(name) else {
        return Ok(None);
    };
    let unit = if quantity.sense() == Some(Sense::Compression) {
        -1.0
    } else {
        1.0
    };
    let phi = relative_damage(&Limit::new(quantity, unit)?, stress, material)?;
    let field = format!("damage.probabilistic.limits.{name}");
    let result = probabilistic_damage(
        mesh,
        &phi,
        limit,
        &spec.all_probabilities(),
        &field,
        Execution::Parallel,
    )?;
    Ok(Some(CriterionDistribution {
        result,
        reported: spec.probabilities.clone(),
    }))
}

/// The distributions of one criterion with a random limit, as the run found them.
#[derive(Debug, Clone, Serialize)]
pub struct CriterionDistribution {
    /// The curve and the reported points, in increasing probability.
    pub result: ProbabilisticDamage,
    /// The probabilities reported in `summary.json`.
    pub reported: Vec<f64>,
}

/// One reported probability in `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct ProbabilisticPointSummary {
    /// p = P(V >= volume) = P(Psi >= damageability) = P(psi_max >= psi_max); the three
    /// values are the (1 - p)-quantiles.
    pub exceedance_probability: f64,
    /// The limit Q(p), in the criterion's unit (its magnitude for a compressive criterion).
    pub limit: f64,
    /// V_q (22) at that limit, m^3.
    pub volume: f64,
    /// Psi_q (24) at that limit, m^3.
    pub damageability: f64,
    /// psi_max at that limit.
    pub psi_max: f64,
}

/// The probabilistic result of one criterion in `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct ProbabilisticSummary {
    /// The largest phi (at a unit limit), in the criterion's unit.
    pub phi_max: f64,
    /// P(psi_max >= 1) = F(phi_max): the probability that the limiting state is reached.
    pub probability_psi_max_ge_1: f64,
    /// The reported probabilities (`damage.probabilistic.probabilities`).
    pub points: Vec<ProbabilisticPointSummary>,
}

impl ProbabilisticSummary {
    /// The summary of a criterion's distributions at its reported probabilities.
    pub fn new(d: &CriterionDistribution) -> Self {
        let r = &d.result;
        let points = d
            .reported
            .iter()
            .filter_map(|p| {
                let q = r.points.iter().find(|q| q.probability == *p)?;
                Some(ProbabilisticPointSummary {
                    exceedance_probability: q.probability,
                    limit: q.limit,
                    volume: q.volume + 0.0,
                    damageability: q.damageability + 0.0,
                    psi_max: q.psi_max,
                })
            })
            .collect();
        Self {
            phi_max: r.phi_max,
            probability_psi_max_ge_1: r.probability_psi_max_ge_1,
            points,
        }
    }

    /// Every number, for the finiteness check.
    pub fn scalars(&self) -> Vec<f64> {
        let mut v = vec![self.phi_max, self.probability_psi_max_ge_1];
        for p in &self.points {
            v.extend([
                p.exceedance_probability,
                p.limit,
                p.volume,
                p.damageability,
                p.psi_max,
            ]);
        }
        v
    }
}
