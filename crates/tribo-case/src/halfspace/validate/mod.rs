//! The rules of a half-space case: ranges, exclusive and dependent keys, defaults. serde has
//! parsed the types ([`super::schema`]); what is checked here is only what a type cannot say.
//! Every error names its key and the rule.

mod body;
mod bulk;
mod contact;
mod damage;
mod field;
mod grid;

pub use body::read_height_csv;
#[cfg(test)]
pub(crate) use bulk::shaft_radius_from;

use super::model::{Body, HalfSpaceCase, Shape};
use super::schema::RawCase;
use crate::error::{CaseError, CaseResult};
use crate::units::{Dim, Dimension, Quantity};
use std::path::Path;

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

    let loading = contact::loading(&raw.contact)?;

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
        loading,
        base_dir,
    };
    let shape1 = body::shape("body1", raw.body1, &ctx)?;
    let shape2 = body::shape("body2", raw.body2, &ctx)?;
    let hertzian = matches!(shape1, Shape::Radii { .. }) && matches!(shape2, Shape::Radii { .. });
    if let (Shape::Radii { radii: r1, .. }, Shape::Radii { radii: r2, angle }) = (&shape1, &shape2)
    {
        body::check_convex(*r1, *r2, *angle)?;
    }

    let raw_grid = raw.grid.unwrap_or_default();
    let n = grid::elements(&raw_grid)?;
    let window = grid::window(&raw_grid, hertzian, [&shape1, &shape2])?;
    let (method, params) = grid::solver(raw.solver, n)?;
    let bulk = match raw.bulk {
        None => None,
        Some(b) => Some(bulk::bulk(b, &shape1, &shape2)?),
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
