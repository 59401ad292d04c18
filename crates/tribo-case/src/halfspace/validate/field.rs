//! The rules of `[field]`: where the points lie, how many, and the edge refinement.

use super::positive;
use crate::error::{CaseError, CaseResult};
use crate::halfspace::model::{
    FieldMethod, FieldPoints, FieldSpec, Length, DEFAULT_FIELD_EXTENT, DEFAULT_FIELD_N,
    EDGE_REFINEMENT_BAND, MAX_EDGE_REFINEMENT, MAX_FIELD_N, MAX_FIELD_POINTS,
};
use crate::halfspace::schema::{BodyId, Metres, Number, RawField};
use tribo::grid::MAX_ELEMENTS_PER_SIDE;

/// A field size in units of the Hertz semi-axis (`semi_key`, Hertzian gaps only) or in m
/// (`metres_key`), at most one of them; the default 1.5 a.
fn field_length(
    semi_key: &str,
    semi: Option<&Number>,
    metres_key: &str,
    metres: Option<&Metres>,
    hertzian: bool,
) -> CaseResult<Length> {
    match (semi, metres) {
        (Some(v), Some(_)) => Err(CaseError::field(
            semi_key,
            v,
            format!("give either {semi_key} or {metres_key}, not both"),
        )),
        (Some(v), None) => {
            if !hertzian {
                return Err(CaseError::field(
                    semi_key,
                    v,
                    format!(
                        "is in units of the Hertz semi-axis, defined only where both bodies are \
                         given by radii; give {metres_key} (m)"
                    ),
                ));
            }
            let x = v.si();
            if !(x.is_finite() && x > 0.0) {
                return Err(CaseError::field(
                    semi_key,
                    v,
                    "must be finite and > 0 (units of the Hertz long semi-axis a)",
                ));
            }
            Ok(Length::Semi(x))
        }
        (None, Some(v)) => Ok(Length::Metres(positive(
            metres_key,
            v,
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

pub(super) fn field_spec(
    f: RawField,
    hertzian: bool,
    contact_n: [usize; 2],
) -> CaseResult<FieldSpec> {
    let points = f.points.as_ref().map_or(FieldPoints::Uniform, |p| p.value);
    let method = f.method.as_ref().map_or(FieldMethod::Fft, |m| m.value);
    let n = points_n(&f, points, contact_n)?;
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
    let body = f.body.as_ref().map_or(BodyId::Body2, |b| b.value.0).name();
    // The band is the default (issue 11 item 1: the surface stresses within 2 % p0 of the
    // closed forms wherever the points sit); "none" (or 1) the bilinear element tractions.
    let edge_refinement = match &f.edge_refinement {
        None => EDGE_REFINEMENT_BAND,
        Some(c) => match c.n {
            None => EDGE_REFINEMENT_BAND,
            Some(n) => edge_refinement(n, contact_n)?,
        },
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

/// The points along x, y, z: `n` for uniform points, the contact grid and `layers` for
/// centres; at most [`MAX_FIELD_POINTS`] in all.
fn points_n(f: &RawField, points: FieldPoints, contact_n: [usize; 2]) -> CaseResult<[usize; 3]> {
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
            let layers = f.layers.as_ref().map_or(DEFAULT_FIELD_N[2], |c| c.n);
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
        Some(n) => {
            for (k, c) in n.0.iter().enumerate() {
                if !(2..=MAX_FIELD_N).contains(c) {
                    return Err(CaseError::field(
                        format!("field.n[{k}]"),
                        c,
                        format!("must be in 2 ... {MAX_FIELD_N} points"),
                    ));
                }
            }
            n.0
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
    Ok(n)
}

/// `edge_refinement` in 1 ... [`MAX_EDGE_REFINEMENT`], the refined grid within
/// [`MAX_ELEMENTS_PER_SIDE`].
fn edge_refinement(factor: usize, contact_n: [usize; 2]) -> CaseResult<usize> {
    let finest = contact_n[0].max(contact_n[1]);
    if !(1..=MAX_EDGE_REFINEMENT).contains(&factor) {
        return Err(CaseError::field(
            "field.edge_refinement",
            factor,
            format!(
                "must be \"band\" (the default), \"none\" or an integer in 1 ... \
                 {MAX_EDGE_REFINEMENT} (\"none\" or 1: the bilinear element tractions; N: the \
                 edge-aware tractions on a grid N times finer)"
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
    Ok(factor)
}
