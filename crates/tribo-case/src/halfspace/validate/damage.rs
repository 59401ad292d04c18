//! The rules of `[damage]`: the criteria and the sources of their limits ((19)-(20)), the
//! energy criterion ((25)-(36)), the Sec. 6 study and the load cycle ((23), (24), (36)).

use super::{positive, positive_number, strip_field};
use crate::error::{CaseError, CaseResult};
use crate::halfspace::model::{
    damage_vocabulary, Bulk, CycleAmplitude, CycleKind, CycleSpec, DamageSpec, LimitSource,
    StudySpec,
};
use crate::halfspace::schema::{CycleKindName, RawCycle, RawDamage, RawEnergy, RawStudy};
use crate::units::{number, show, Dim};
use tribo::analysis::damage::{DamageQuantity, Limit, Sense};
use tribo::analysis::energy_criterion::EnergyCoefficients;
use tribo::solvers::NormalLoading;

pub(super) fn damage_spec(
    d: RawDamage,
    loading: &NormalLoading,
    bulk: Option<&Bulk>,
) -> CaseResult<DamageSpec> {
    let names: Vec<String> = match &d.criteria {
        // With [damage.energy] alone: only the effective energy.
        None if d.energy.is_some() => Vec::new(),
        None => vec!["sigma_int".into()],
        Some(c) => c.0.clone(),
    };
    let defaults = default_limits(&d, loading)?;
    let probabilistic = match &d.probabilistic {
        None => None,
        Some(t) => Some(crate::probabilistic::parse(t, &named_quantities(&names))?),
    };
    let mut criteria = criteria(&names, &d, &defaults, probabilistic.as_ref())?;
    if let Some(e) = &d.energy {
        criteria.push(energy(e)?);
    }
    let study = match d.study {
        None => None,
        Some(st) => Some(study(&st, bulk)?),
    };
    let cycle = match d.cycle {
        None => None,
        Some(c) => Some(cycle_spec(c, bulk)?),
    };
    Ok(DamageSpec {
        criteria,
        limit_load: defaults.limit_load,
        study,
        cycle,
        probabilistic,
    })
}

/// The criteria's names with their quantities (an unknown name is refused by [`criteria`]
/// with the list of known ones; here it is skipped).
fn named_quantities(names: &[String]) -> Vec<(String, DamageQuantity)> {
    let vocabulary = damage_vocabulary();
    names
        .iter()
        .filter_map(|n| {
            let q = vocabulary.iter().find(|q| &q.name() == n)?;
            Some((n.clone(), *q))
        })
        .collect()
}

/// The default limits of the criteria without their own: at most one of `limit_load`
/// (force control only) and `limit_over_p0`.
struct Defaults {
    limit_load: Option<f64>,
    over_p0: Option<f64>,
}

fn default_limits(d: &RawDamage, loading: &NormalLoading) -> CaseResult<Defaults> {
    // Two default limits for the criteria without their own: the second would be silently
    // ignored (limit_load took precedence), so exactly one may be given.
    if let (Some(l), Some(_)) = (&d.limit_load, &d.limit_over_p0) {
        return Err(CaseError::field(
            "damage.limit_load",
            format!("{l} (and damage.limit_over_p0)"),
            "give at most one of damage.limit_load (N) and damage.limit_over_p0 (the default \
             limit of the criteria without their own in damage.limits), not both",
        ));
    }
    let over_p0 = match &d.limit_over_p0 {
        None => None,
        Some(v) => {
            let r = positive_number("damage.limit_over_p0", v)?;
            // 1e300 p0 overflowed to an infinite limit; 1e-300 p0 makes psi overflow.
            if !(1e-9..=1e9).contains(&r) {
                return Err(CaseError::field(
                    "damage.limit_over_p0",
                    v,
                    "must be in [1e-9, 1e9] (a limit as a multiple of the largest contact \
                     pressure)",
                ));
            }
            Some(r)
        }
    };
    let limit_load = match &d.limit_load {
        None => None,
        Some(v) => {
            if !matches!(loading, NormalLoading::Force(_)) {
                return Err(CaseError::field(
                    "damage.limit_load",
                    v,
                    "needs force control (contact.load): the limiting state is the same case \
                     at the load F_lim",
                ));
            }
            Some(positive(
                "damage.limit_load",
                v,
                "the limiting load F_lim (N)",
            )?)
        }
    };
    Ok(Defaults {
        limit_load,
        over_p0,
    })
}

/// The named criteria, each with the source of its limit: `damage.limits.NAME`, else the
/// default limit.
fn criteria(
    names: &[String],
    d: &RawDamage,
    defaults: &Defaults,
    probabilistic: Option<&crate::probabilistic::ProbabilisticSpec>,
) -> CaseResult<Vec<(DamageQuantity, LimitSource)>> {
    let vocabulary = damage_vocabulary();
    let empty = toml::Table::new();
    let limits = d.limits.as_ref().unwrap_or(&empty);
    for key in limits.keys() {
        if !names.iter().any(|n| n == key) {
            return Err(CaseError::field(
                format!("damage.limits.{key}"),
                "given",
                "is not one of damage.criteria",
            ));
        }
    }
    let mut criteria: Vec<(DamageQuantity, LimitSource)> = Vec::new();
    for (k, name) in names.iter().enumerate() {
        let Some(quantity) = vocabulary.iter().find(|q| &q.name() == name).copied() else {
            let known: Vec<_> = vocabulary.iter().map(|q| q.name()).collect();
            return Err(CaseError::field(
                format!("damage.criteria[{k}]"),
                name,
                format!("unknown quantity; known: {}", known.join(", ")),
            ));
        };
        if criteria.iter().any(|(q, _)| *q == quantity) {
            return Err(CaseError::field(
                format!("damage.criteria[{k}]"),
                name,
                "is named twice",
            ));
        }
        let median = probabilistic.and_then(|p| p.median_limit(name, quantity));
        let source = match (limits.get(name), median) {
            // A random limit without a given one: the deterministic result at its median.
            (None, Some(m)) => LimitSource::Given(m),
            (given, _) => limit_source(name, quantity, given, defaults)?,
        };
        criteria.push((quantity, source));
    }
    Ok(criteria)
}

fn limit_source(
    name: &str,
    quantity: DamageQuantity,
    given: Option<&toml::Value>,
    defaults: &Defaults,
) -> CaseResult<LimitSource> {
    let field = format!("damage.limits.{name}");
    if let Some(v) = given {
        // The unit is the quantity's: a stress in Pa (or a unit string), others plain.
        let x = match quantity.unit() {
            "Pa" => crate::units::quantity(&field, v, Dim::Pressure)?,
            _ => number(&field, v)?,
        };
        Limit::new(quantity, x)
            .map_err(|e| CaseError::field(&field, show(v), strip_field(&e.to_string())))?;
        // The range of the random limits' quantiles (1e-300 Pa made psi infinite).
        let [lo, hi] = crate::probabilistic::limit_range(quantity.unit());
        if !(lo..=hi).contains(&x.abs()) {
            return Err(CaseError::field(
                &field,
                show(v),
                format!(
                    "a limit must lie within [{lo:e}, {hi:e}] {} in magnitude",
                    quantity.unit()
                ),
            ));
        }
        return Ok(LimitSource::Given(x));
    }
    if let Some(f) = defaults.limit_load {
        return Ok(LimitSource::LimitingLoad(f));
    }
    let Some(r) = defaults.over_p0 else {
        return Err(CaseError::field(
            &field,
            "(missing)",
            "required: give the limit here (material data), or damage.limit_over_p0 \
             (stresses, a multiple of p0), or damage.limit_load (the field's extremes at \
             the limiting load, (19))",
        ));
    };
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
    if quantity.sense() == Some(Sense::Compression) {
        Ok(LimitSource::OverP0(-r))
    } else {
        Ok(LimitSource::OverP0(r))
    }
}

/// The generalized energy criterion (25)-(36): u_eff with the limit u0 (34).
fn energy(e: &RawEnergy) -> CaseResult<(DamageQuantity, LimitSource)> {
    let m = EnergyCoefficients::MECHANICAL;
    let or = |v: &Option<crate::halfspace::schema::Number>, default: f64| {
        v.as_ref().map_or(default, |x| x.si())
    };
    let coefficients = EnergyCoefficients {
        a_n: or(&e.a_n, m.a_n),
        a_tau: or(&e.a_tau, m.a_tau),
        a_t: or(&e.a_t, m.a_t),
        a_tau_n: or(&e.a_tau_n, m.a_tau_n),
        a_m_t: or(&e.a_m_t, m.a_m_t),
    };
    coefficients
        .validate("damage.energy")
        .map_err(CaseError::from)?;
    let temperature = or(&e.temperature, 293.15);
    if !(temperature.is_finite() && temperature >= 0.0) {
        return Err(CaseError::field(
            "damage.energy.temperature",
            temperature,
            "must be finite and >= 0 K (absolute temperature)",
        ));
    }
    let Some(u0) = e.u0.as_ref().map(|u| u.si()) else {
        return Err(CaseError::field(
            "damage.energy.u0",
            "(missing)",
            "required: the activation energy per unit volume u0, J/m^3",
        ));
    };
    if !(u0.is_finite() && u0 > 0.0) {
        return Err(CaseError::field(
            "damage.energy.u0",
            u0,
            "must be finite and > 0 (J/m^3)",
        ));
    }
    Ok((
        DamageQuantity::EffectiveEnergy {
            coefficients,
            temperature,
        },
        LimitSource::Given(u0),
    ))
}

/// The paper's Sec. 6 study: needs `[bulk]`; bending ratios >= 0 and increasing.
fn study(st: &RawStudy, bulk: Option<&Bulk>) -> CaseResult<StudySpec> {
    if bulk.is_none() {
        return Err(CaseError::field(
            "damage.study",
            "given",
            "needs a [bulk] section for the shaft (bulk.shaft, bulk.shaft_radius)",
        ));
    }
    let values = match &st.bending_over_p0 {
        Some(list) => {
            let mut out: Vec<f64> = Vec::new();
            for (k, v) in list.0.iter().enumerate() {
                let x = v.si();
                if !(x.is_finite() && x >= 0.0) || out.last().is_some_and(|&l| x <= l) {
                    return Err(CaseError::field(
                        format!("damage.study.bending_over_p0[{k}]"),
                        v,
                        "must be finite, >= 0 and increasing (sigma_b / p0; the zone \
                         gives the sign)",
                    ));
                }
                out.push(x);
            }
            out
        }
        None => (0..=12).map(|k| 0.025 * k as f64).collect(),
    };
    let limit_over_p0 = match &st.limit_over_p0 {
        None => 0.186,
        Some(v) => positive_number("damage.study.limit_over_p0", v)?,
    };
    Ok(StudySpec {
        bending_over_p0: values,
        limit_over_p0,
    })
}

fn cycle_spec(c: RawCycle, bulk: Option<&Bulk>) -> CaseResult<CycleSpec> {
    let kind = match c.kind.as_ref().map(|k| k.value) {
        Some(CycleKindName::RotatingBending) => rotating_bending(&c, bulk)?,
        Some(CycleKindName::Rolling) => rolling(&c)?,
        None => {
            return Err(CaseError::field(
                "damage.cycle.kind",
                "(missing)",
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
        Some(s) => {
            if !(2..=3600).contains(&s.n) {
                return Err(CaseError::field(
                    "damage.cycle.steps",
                    s.n,
                    "must be in 2 ... 3600 time steps per cycle",
                ));
            }
            s.n
        }
    };
    let cycles = match &c.cycles {
        None => 1.0,
        Some(v) => positive_number("damage.cycle.cycles", v).map_err(|_| {
            CaseError::field(
                "damage.cycle.cycles",
                v,
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

/// A bent shaft turning under the roller: needs `[bulk]` and exactly one amplitude.
fn rotating_bending(c: &RawCycle, bulk: Option<&Bulk>) -> CaseResult<CycleKind> {
    if bulk.is_none() {
        return Err(CaseError::field(
            "damage.cycle.kind",
            "rotating-bending",
            "rotating bending needs a [bulk] section (the shaft and its radius)",
        ));
    }
    let amplitude = match (&c.amplitude, &c.amplitude_over_p0) {
        (Some(v), None) => {
            let x = v.si();
            if !(x.is_finite() && x != 0.0) {
                return Err(CaseError::field(
                    "damage.cycle.amplitude",
                    v,
                    "must be finite and non-zero (Pa; > 0 starts in the tension zone)",
                ));
            }
            CycleAmplitude::Pascal(x)
        }
        (None, Some(v)) => {
            let x = v.si();
            if !(x.is_finite() && x != 0.0) {
                return Err(CaseError::field(
                    "damage.cycle.amplitude_over_p0",
                    v,
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
    Ok(CycleKind::RotatingBending { amplitude })
}

/// The contact moving along y at a non-zero speed.
fn rolling(c: &RawCycle) -> CaseResult<CycleKind> {
    if c.amplitude.is_some() || c.amplitude_over_p0.is_some() {
        return Err(CaseError::field(
            "damage.cycle.amplitude",
            "given",
            "only for kind = \"rotating-bending\"",
        ));
    }
    let Some(speed) = c.speed.as_ref().map(|s| s.si()) else {
        return Err(CaseError::field(
            "damage.cycle.speed",
            "(missing)",
            "required for rolling: the speed of the contact along y, m/s",
        ));
    };
    if !(speed.is_finite() && speed != 0.0) {
        return Err(CaseError::field(
            "damage.cycle.speed",
            speed,
            "must be finite and non-zero (m/s)",
        ));
    }
    Ok(CycleKind::Rolling { speed })
}
