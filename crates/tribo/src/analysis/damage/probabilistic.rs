//! Probabilistic damage: the distributions of the dangerous volume V_q, the damageability
//! Psi_q and psi_max when the limiting value phi_q^lim is random (seed paper, after (21):
//! "psi_ij, psi_i, psi_int, psi_u are generally speaking probabilistic in nature since ...
//! the limiting values ... are the random values with the corresponding distribution
//! functions"). docs/theory/FATIGUE.md, section "Probabilistic damage", derives what follows.
//!
//! # Change of variables
//!
//! For one field phi (nodal values, computed once) and a limit L > 0 (phi oriented so that
//! psi = phi / L >= 1 is dangerous), V(L) = measure of {phi >= L}, Psi(L) = integral of phi / L
//! over it and psi_max(L) = phi_max / L are non-increasing functions of L (the region shrinks
//! and the integrand falls as L grows). Hence, with F the CDF of L and Q its quantile:
//!
//! - P(V >= V(l)) = P(L <= l) = F(l) wherever V(l) > 0 (V strictly decreasing there for a
//!   field linear on non-degenerate cells; at a jump of V the same holds with l its position);
//!   the same for Psi and for psi_max (strictly decreasing everywhere);
//! - the q-quantile of V is V(Q(1 - q)), of Psi Psi(Q(1 - q)), of psi_max phi_max / Q(1 - q);
//! - P(psi_max >= 1) = P(L <= phi_max) = F(phi_max).
//!
//! V and Psi at a limit are the deterministic routine's own numbers ([`dangerous_region`] of
//! psi = phi / L): no resampling and no second field. Several random limits (one per quantity)
//! give each quantity's marginal in the same way; the joint probability that any psi_max
//! reaches 1 needs a dependence assumption, and [`probability_any`] takes the limits as
//! independent. Random loads, geometry or materials change the field itself: that is the study
//! engine's job (`tribo sweep`), not this module's.

use super::{dangerous_region, DamageMesh, Execution};
use crate::error::{Error, Result};
use crate::stats::Truncated;
use serde::Serialize;

/// One point of the distribution: the limit at the probability `probability` = F(limit), and
/// V, Psi and psi_max there.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ProbabilisticPoint {
    /// F(limit) = P(L <= limit): the exceedance probability P(V >= volume) (where volume > 0),
    /// P(Psi >= damageability) and P(psi_max >= psi_max); 1 - probability is the quantile level
    /// of the three values.
    pub probability: f64,
    /// The limit phi_lim = Q(probability), in the quantity's unit.
    pub limit: f64,
    /// V at that limit (22): m^3 (3D) or m^2 per unit thickness (2D).
    pub volume: f64,
    /// Psi at that limit (24, numerator): m^3 (3D) or m^2 (2D).
    pub damageability: f64,
    /// psi_max = phi_max / limit, dimensionless.
    pub psi_max: f64,
}

/// The distribution of V, Psi and psi_max of one quantity with a random limit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ProbabilisticDamage {
    /// The largest nodal phi (the quantity's unit).
    pub phi_max: f64,
    /// P(psi_max >= 1) = F(phi_max): the probability that the limiting state is reached
    /// somewhere.
    pub probability_psi_max_ge_1: f64,
    /// Points at the probabilities asked for, in increasing order of probability (increasing
    /// limit, decreasing V, Psi, psi_max).
    pub points: Vec<ProbabilisticPoint>,
}

impl ProbabilisticDamage {
    /// The point whose probability is closest to `p` (exceedance probability p; quantile level
    /// 1 - p), or `None` for an empty table.
    pub fn at(&self, p: f64) -> Option<&ProbabilisticPoint> {
        self.points.iter().min_by(|a, b| {
            (a.probability - p)
                .abs()
                .total_cmp(&(b.probability - p).abs())
        })
    }
}

/// Probabilities for an exceedance curve: `n` equally spaced points k / (n + 1), k = 1..n,
/// and the tails 1e-4, 1e-3, 0.01, 0.99, 0.999, 0.9999, sorted, duplicates removed.
pub fn curve_probabilities(n: usize) -> Vec<f64> {
    let mut p: Vec<f64> = (1..=n).map(|k| k as f64 / (n + 1) as f64).collect();
    p.extend([1e-4, 1e-3, 0.01, 0.99, 0.999, 0.9999]);
    p.sort_by(f64::total_cmp);
    p.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    p
}

/// The limit distribution must live on L > 0: P(L <= 0) at most this (else truncate it).
const MAX_MASS_AT_OR_BELOW_ZERO: f64 = 1e-12;

/// V, Psi and psi_max of the nodal field `phi` on `mesh` at the limit `limit` > 0: the
/// deterministic routine [`dangerous_region`] of psi = phi / limit.
pub fn at_limit(
    mesh: &DamageMesh,
    phi: &[f64],
    limit: f64,
    execution: Execution,
) -> Result<(f64, f64, f64)> {
    if !(limit.is_finite() && limit > 0.0) {
        return Err(Error::invalid(
            "limit",
            limit,
            "the limit must be finite and > 0 (orient phi so that psi = phi / limit)",
        ));
    }
    let psi: Vec<f64> = phi.iter().map(|v| v / limit).collect();
    let r = dangerous_region(mesh, &psi, execution)?;
    Ok((r.volume, r.damageability, r.psi_max))
}

/// The distribution of V, Psi and psi_max for the nodal field `phi` (the quantity's unit,
/// oriented so that psi = phi / L; for a compressive quantity pass -phi and the distribution
/// of -phi_lim) on `mesh`, when the limit L has the distribution `limit`, at the
/// probabilities `probabilities` (each in (0, 1); see [`curve_probabilities`]). `field` names
/// the limit in errors (e.g. `damage.probabilistic.sigma_int`).
///
/// Errors: an invalid distribution; a distribution with P(L <= 0) > 1e-12 (truncate it, e.g.
/// `low = 0`); probabilities outside (0, 1); the field errors of [`dangerous_region`].
pub fn probabilistic_damage(
    mesh: &DamageMesh,
    phi: &[f64],
    limit: &Truncated,
    probabilities: &[f64],
    field: &str,
    execution: Execution,
) -> Result<ProbabilisticDamage> {
    limit.validate().map_err(|e| e.into_error(field))?;
    let below = limit.cdf(0.0);
    if below > MAX_MASS_AT_OR_BELOW_ZERO {
        return Err(Error::invalid(
            field,
            format!("P(limit <= 0) = {below:.3e}"),
            "the limit must be > 0 with probability 1: truncate the distribution (low = 0) \
             or choose one on positive values (lognormal, Weibull)",
        ));
    }
    if let Some(k) = probabilities
        .iter()
        .position(|p| !(p.is_finite() && *p > 0.0 && *p < 1.0))
    {
        return Err(Error::invalid(
            format!("probabilities[{k}]"),
            probabilities[k],
            "a probability must be in (0, 1)",
        ));
    }
    let phi_max = phi.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let mut ps = probabilities.to_vec();
    ps.sort_by(f64::total_cmp);
    let mut points = Vec::with_capacity(ps.len());
    for p in ps {
        let l = limit.quantile(p);
        let (volume, damageability, psi_max) = at_limit(mesh, phi, l, execution)?;
        points.push(ProbabilisticPoint {
            probability: p,
            limit: l,
            volume,
            damageability,
            psi_max,
        });
    }
    Ok(ProbabilisticDamage {
        phi_max,
        probability_psi_max_ge_1: if phi_max > 0.0 {
            limit.cdf(phi_max)
        } else {
            0.0
        },
        points,
    })
}

/// P(any psi_max >= 1) of several quantities with independent limits: 1 - prod(1 - P_q).
/// (Dependent limits, e.g. two strengths of one material, need their joint distribution; with
/// fully dependent ones the answer is max P_q, a lower bound of this.)
pub fn probability_any(probabilities: &[f64]) -> f64 {
    1.0 - probabilities.iter().map(|p| 1.0 - p).product::<f64>()
}

#[cfg(test)]
mod tests;
