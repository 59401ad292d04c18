//! The rules of a half-space case: ranges, exclusive and dependent keys, defaults. serde has
//! parsed the types ([`super::schema`]); what is checked here is only what a type cannot say.
//! Every error names its key and the rule.

mod body;
mod bulk;
mod contact;
mod damage;
mod field;
mod grid;
mod rough;

pub use body::read_height_csv;
#[cfg(test)]
pub(crate) use bulk::shaft_radius_from;

use super::model::{Body, HalfSpaceCase, Shape, Window};
use super::schema::RawCase;
use super::schema::RawContact;
use crate::error::{CaseError, CaseResult};
use crate::units::{Dim, Dimension, Quantity};
use std::path::Path;
use tribo::solvers::NormalLoading;

/// The validated case from its raw form, in the order of the sections' dependencies: the
/// bodies and the load, the window, the solver, then bulk, friction, field and damage.
pub(super) fn validate(
    raw: RawCase,
    source: &str,
    base_dir: &Path,
    echo: serde_json::Value,
) -> CaseResult<HalfSpaceCase> {
    let m1 = body::material("body1", &raw.body1)?;
    let m2 = body::material("body2", &raw.body2)?;
    let e_star = tribo::composite_modulus(&m1, &m2);

    let raw_grid = raw.grid.unwrap_or_default();
    let periodic = raw_grid.periodic.as_ref().is_some_and(|p| p.on);
    let load_spec = contact::load_spec(&raw.contact, periodic)?;
    let load_steps = contact::load_steps(&raw.contact)?;

    if let Some(a) = &raw.body1.angle_deg {
        return Err(CaseError::field(
            "body1.angle_deg",
            a,
            "not allowed: body 1's first principal direction defines the x axis; \
             give the angle between the bodies as body2.angle_deg",
        ));
    }
    let ctx = body::ShapeContext {
        e_star,
        loading: load_spec.loading(),
        base_dir,
    };
    let (shape1, rough1) = body::shape("body1", raw.body1, &ctx)?;
    let (shape2, rough2) = body::shape("body2", raw.body2, &ctx)?;
    let rough = rough1.is_some() || rough2.is_some();
    let hertzian =
        matches!(shape1, Shape::Radii { .. }) && matches!(shape2, Shape::Radii { .. }) && !rough;
    if let (Shape::Radii { radii: r1, .. }, Shape::Radii { radii: r2, angle }) = (&shape1, &shape2)
    {
        if !periodic {
            body::check_convex(*r1, *r2, *angle)?;
        }
    }
    let body1 = Body {
        material: m1,
        shape: shape1,
        roughness: rough1,
    };
    let body2 = Body {
        material: m2,
        shape: shape2,
        roughness: rough2,
    };

    let n = grid::elements(&raw_grid)?;
    let window = match grid::periodic_window(&raw_grid, rough::default_period([&body1, &body2]))? {
        Some(w) => w,
        None => grid::window(&raw_grid, hertzian, [&body1.shape, &body2.shape])?,
    };
    rough::check_against_grid([("body1", &body1), ("body2", &body2)], n, window, periodic)?;
    let loading = match (load_spec, window) {
        (contact::LoadSpec::Loading(l), _) => l,
        (contact::LoadSpec::MeanPressure(p), Window::HalfWidth(hw)) => {
            // The pipeline's check of the force over the window is the same ratio; checked
            // here so that the refusal names the key the case gives.
            crate::units::check_strain(
                "contact.mean_pressure",
                format!("{p:e} Pa"),
                p / e_star,
                "the mean pressure over E*",
            )?;
            NormalLoading::Force(p * 4.0 * hw[0] * hw[1])
        }
        (contact::LoadSpec::MeanPressure(p), Window::Extent(_)) => {
            // A periodic window is sized by its period (grid::periodic_window).
            return Err(CaseError::field(
                "contact.mean_pressure",
                p,
                "applies to periodic grids only",
            ));
        }
    };
    if periodic {
        if let NormalLoading::Approach(d) = loading {
            return Err(CaseError::field(
                "contact.approach",
                d,
                "approach control is not defined on a periodic grid (the mean displacement of \
                 a periodic half-space is unbounded): give contact.load (N, the force on one \
                 period) or contact.mean_pressure (Pa)",
            ));
        }
        periodic_refusals(&raw.contact, raw.bulk.is_some(), raw.field.is_some())?;
    }
    let (method, params) = grid::solver(raw.solver, n, periodic)?;
    let bulk = match raw.bulk {
        None => None,
        Some(b) => Some(bulk::bulk(b, &body1.shape, &body2.shape)?),
    };

    let friction = contact::friction(&raw.contact)?;
    let field = match raw.field {
        None => None,
        Some(f) => Some(field::field_spec(f, hertzian, n)?),
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
            Some(damage::damage_spec(d, &loading, bulk.as_ref())?)
        }
    };
    let title = raw.title.unwrap_or_else(|| source.to_string());
    Ok(HalfSpaceCase {
        title,
        source: source.to_string(),
        body1,
        body2,
        loading,
        load_steps,
        periodic,
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

/// What a periodic grid does not run yet: friction (the tangential solvers' operators are
/// the non-periodic ones), the back effect of bulk loading (a shaft is not periodic), and
/// the stress field and damage (the case's field paths are the non-periodic ones; the
/// library's `stress_field_periodic_pressure` is not wired to `[field]` yet).
fn periodic_refusals(c: &RawContact, bulk: bool, field: bool) -> CaseResult<()> {
    if let Some(f) = &c.friction {
        return Err(CaseError::field(
            "contact.friction",
            f,
            "friction is not available on a periodic grid yet (the tangential solvers are \
             non-periodic): leave it out, or run on a non-periodic window",
        ));
    }
    if bulk {
        return Err(CaseError::field(
            "bulk",
            "given",
            "the back effect of bulk loading needs a shaft, not a periodic surface: leave \
             [bulk] out on a periodic grid",
        ));
    }
    if field {
        return Err(CaseError::field(
            "field",
            "given",
            "the stress field of a periodic grid is not available from a case file yet: leave \
             [field] (and [damage]) out on a periodic grid",
        ));
    }
    Ok(())
}

/// A quantity that must be > 0 (`what` names it in the rule); a length of the geometry (any
/// length but the approach, which is checked relative to the window in the pipeline) also
/// within [`crate::units::LENGTH_RANGE`].
fn positive<D: Dimension>(field: &str, q: &Quantity<D>, what: &str) -> CaseResult<f64> {
    let x = q.si();
    if x.is_finite() && x > 0.0 {
        if D::DIM == Some(Dim::Length) && field != "contact.approach" {
            crate::units::check_length(field, q.written(), x)?;
        }
        Ok(x)
    } else {
        Err(CaseError::field(
            field,
            q,
            format!("{what} must be finite and > 0"),
        ))
    }
}

/// A plain number that must be > 0.
fn positive_number<D: Dimension>(field: &str, q: &Quantity<D>) -> CaseResult<f64> {
    let x = q.si();
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(CaseError::field(field, q, "must be finite and > 0"))
    }
}

/// The rule part of a library error message "field = value: rule".
fn strip_field(message: &str) -> String {
    message
        .split_once(": ")
        .map_or(message, |(_, rule)| rule)
        .to_string()
}
