//! The rules of `[contact]`: the normal load or approach, and friction with its tangential
//! load or sliding.

use super::positive;
use crate::error::{CaseError, CaseResult};
use crate::halfspace::model::{Friction, MAX_LOAD_STEPS};
use crate::halfspace::schema::{Degrees, RawContact, TractionDirection};
use tribo::solvers::tangential::TangentialLoading;
use tribo::solvers::NormalLoading;

/// How the case is loaded: a force or an approach, or a mean pressure (periodic grids only;
/// the force on one period once the period is known).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum LoadSpec {
    /// `contact.load` or `contact.approach`.
    Loading(NormalLoading),
    /// `contact.mean_pressure`, Pa.
    MeanPressure(f64),
}

impl LoadSpec {
    /// The loading where it is known before the grid.
    pub(super) fn loading(self) -> Option<NormalLoading> {
        match self {
            LoadSpec::Loading(l) => Some(l),
            LoadSpec::MeanPressure(_) => None,
        }
    }
}

/// Exactly one of `load` (N), `approach` (m) and `mean_pressure` (Pa, periodic grids only:
/// the force on one period divided by its area), > 0.
pub(super) fn load_spec(c: &RawContact, periodic: bool) -> CaseResult<LoadSpec> {
    let Some(p) = &c.mean_pressure else {
        if periodic && c.load.is_none() && c.approach.is_none() {
            return Err(CaseError::field(
                "contact",
                "(none of load and mean_pressure)",
                "give exactly one of contact.load (N, the force on one period) and \
                 contact.mean_pressure (Pa) on a periodic grid",
            ));
        }
        return loading(c).map(LoadSpec::Loading);
    };
    if let Some(l) = &c.load {
        return Err(CaseError::field(
            "contact.load",
            l,
            "give exactly one of contact.load (N), contact.approach (m) and \
             contact.mean_pressure (Pa), not both",
        ));
    }
    if let Some(a) = &c.approach {
        return Err(CaseError::field(
            "contact.approach",
            a,
            "give exactly one of contact.load (N), contact.approach (m) and \
             contact.mean_pressure (Pa), not both",
        ));
    }
    if !periodic {
        return Err(CaseError::field(
            "contact.mean_pressure",
            p,
            "applies to periodic grids ([grid] periodic = true), where the load is the mean \
             pressure times the period area; give contact.load (N) otherwise",
        ));
    }
    Ok(LoadSpec::MeanPressure(positive(
        "contact.mean_pressure",
        p,
        "the mean pressure (Pa)",
    )?))
}

/// `contact.load_steps`: 1 ... [`MAX_LOAD_STEPS`], default 1.
pub(super) fn load_steps(c: &RawContact) -> CaseResult<usize> {
    match &c.load_steps {
        None => Ok(1),
        Some(n) if (1..=MAX_LOAD_STEPS).contains(&n.n) => Ok(n.n),
        Some(n) => Err(CaseError::field(
            "contact.load_steps",
            n.n,
            format!(
                "must be 1 ... {MAX_LOAD_STEPS} (the number of loads of the sweep, each one \
                 contact solution)"
            ),
        )),
    }
}

/// Exactly one of `load` (N) and `approach` (m), > 0.
pub(super) fn loading(c: &RawContact) -> CaseResult<NormalLoading> {
    match (&c.load, &c.approach) {
        (Some(l), None) => Ok(NormalLoading::Force(positive(
            "contact.load",
            l,
            "the normal load (N)",
        )?)),
        (None, Some(a)) => Ok(NormalLoading::Approach(positive(
            "contact.approach",
            a,
            "the approach (m)",
        )?)),
        (Some(l), Some(_)) => Err(CaseError::field(
            "contact.load",
            l,
            "give exactly one of contact.load (N) and contact.approach (m), not both",
        )),
        (None, None) => Err(CaseError::field(
            "contact",
            "(neither load nor approach)",
            "give exactly one of contact.load (N) and contact.approach (m)",
        )),
    }
}

/// An angle in degrees from the x axis (default 0), in rad.
fn angle_deg(v: Option<&Degrees>) -> f64 {
    v.map_or(0.0, |d| d.si().to_radians())
}

/// The friction keys: none without `friction`; with it, exactly one of a tangential load
/// and sliding, each with its own angle.
pub(super) fn friction(c: &RawContact) -> CaseResult<Option<Friction>> {
    let Some(fv) = &c.friction else {
        no_friction_keys(c)?;
        return Ok(None);
    };
    let f = fv.si();
    if !(f.is_finite() && f > 0.0) {
        return Err(CaseError::field(
            "contact.friction",
            fv,
            "the friction coefficient must be finite and > 0",
        ));
    }
    let sliding = c.sliding.as_ref().map(|s| s.on);
    let loading = match (&c.tangential_load, sliding) {
        (Some(q), None) | (Some(q), Some(false)) => {
            if let Some(v) = &c.sliding_angle_deg {
                return Err(CaseError::field(
                    "contact.sliding_angle_deg",
                    v,
                    "applies to sliding = true; under a tangential load give \
                 contact.tangential_angle_deg",
                ));
            }
            let magnitude = positive("contact.tangential_load", q, "the tangential load |Q| (N)")?;
            TangentialLoading::Force {
                magnitude,
                angle: angle_deg(c.tangential_angle_deg.as_ref()),
            }
        }
        (None, Some(true)) => {
            if let Some(v) = &c.tangential_angle_deg {
                return Err(CaseError::field(
                    "contact.tangential_angle_deg",
                    v,
                    "applies to tangential_load; when sliding give contact.sliding_angle_deg",
                ));
            }
            TangentialLoading::Sliding {
                angle: angle_deg(c.sliding_angle_deg.as_ref()),
            }
        }
        (Some(q), Some(true)) => {
            return Err(CaseError::field(
                "contact.tangential_load",
                q,
                "give exactly one of contact.tangential_load (partial slip) and \
                 contact.sliding = true (full sliding), not both",
            ))
        }
        (None, _) => {
            return Err(CaseError::field(
                "contact.friction",
                fv,
                "needs exactly one of contact.tangential_load (N, partial slip) and \
                 contact.sliding = true (full sliding)",
            ))
        }
    };
    let free_direction = c
        .traction_direction
        .as_ref()
        .is_some_and(|d| d.value == TractionDirection::Free);
    Ok(Some(Friction {
        coefficient: f,
        loading,
        free_direction,
    }))
}

/// Without `contact.friction`, none of the keys that need it.
fn no_friction_keys(c: &RawContact) -> CaseResult<()> {
    if let Some(q) = &c.tangential_load {
        return Err(CaseError::field(
            "contact.tangential_load",
            q,
            "needs contact.friction (the Coulomb coefficient f > 0)",
        ));
    }
    if let Some(s) = &c.sliding {
        return Err(CaseError::field(
            "contact.sliding",
            &s.written,
            "needs contact.friction (the Coulomb coefficient f > 0)",
        ));
    }
    for (name, v) in [
        (
            "contact.tangential_angle_deg",
            c.tangential_angle_deg
                .as_ref()
                .map(|q| q.written().to_string()),
        ),
        (
            "contact.sliding_angle_deg",
            c.sliding_angle_deg
                .as_ref()
                .map(|q| q.written().to_string()),
        ),
        (
            "contact.traction_direction",
            c.traction_direction.as_ref().map(|d| d.written.clone()),
        ),
    ] {
        if let Some(v) = v {
            return Err(CaseError::field(
                name,
                v,
                "needs contact.friction and a tangential load or sliding = true",
            ));
        }
    }
    Ok(())
}
