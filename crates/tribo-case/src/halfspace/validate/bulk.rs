//! The rules of `[bulk]`: the shaft, the back-effect curve and the operating bulk stress.

use super::positive;
use crate::error::{CaseError, CaseResult};
use crate::halfspace::model::{Bulk, LoadKind, Shape, DEFAULT_BULK_POINTS, MAX_BULK_POINTS};
use crate::halfspace::schema::{BendingSide, BodyId, BulkKind, RawBulk, Support};
use tribo::kernels::bulk::{bending_moment, bending_stress, BeamSupport};

/// The default shaft radius from a body's radii: their common magnitude where both are
/// finite and equal up to the sign (the paper's shaft, radii [-0.01, 0.01]), or the one
/// finite convex radius of a cylinder ([inf, R]).
pub(crate) fn shaft_radius_from(shape: &Shape) -> Option<f64> {
    let Shape::Radii {
        radii: [r0, r1], ..
    } = *shape
    else {
        return None;
    };
    match (r0.is_finite(), r1.is_finite()) {
        (true, true) if (r0.abs() - r1.abs()).abs() <= 1e-12 * r0.abs().max(r1.abs()) => {
            Some(r0.abs())
        }
        (true, false) if r0 > 0.0 => Some(r0),
        (false, true) if r1 > 0.0 => Some(r1),
        _ => None,
    }
}

pub(super) fn bulk(b: RawBulk, shape1: &Shape, shape2: &Shape) -> CaseResult<Bulk> {
    let shaft = b.shaft.as_ref().map_or(BodyId::Body2, |s| s.value.0);
    let shaft_shape = if shaft == BodyId::Body1 {
        shape1
    } else {
        shape2
    };
    let shaft = shaft.name();
    let shaft_radius = match &b.shaft_radius {
        Some(v) => positive("bulk.shaft_radius", v, "the shaft radius (m)")?,
        None => shaft_radius_from(shaft_shape).ok_or_else(|| {
            CaseError::field(
                "bulk.shaft_radius",
                "(missing)",
                format!(
                    "required: {shaft} has no single radius to take it from (its radii differ, \
                     or it is a surface); give the shaft radius R2 in m"
                ),
            )
        })?,
    };
    let kinds = match b.kind.as_ref().map_or(BulkKind::Both, |k| k.value) {
        BulkKind::Both => vec![LoadKind::TensionCompression, LoadKind::Bending],
        BulkKind::TensionCompression => vec![LoadKind::TensionCompression],
        BulkKind::Bending => vec![LoadKind::Bending],
    };
    let stress_max = match &b.stress_max {
        Some(v) => positive(
            "bulk.stress_max",
            v,
            "the largest bulk stress sigma_a,max (Pa)",
        )?,
        None => {
            return Err(CaseError::field(
                "bulk.stress_max",
                "(missing)",
                "required: the largest bulk stress sigma_a,max in Pa (the curve spans \
                 sigma/sigma_max in [-1, 1])",
            ))
        }
    };
    let points = match &b.points {
        None => DEFAULT_BULK_POINTS,
        Some(c) => {
            let k = c.n;
            if !(3..=MAX_BULK_POINTS).contains(&k) || k % 2 == 0 {
                return Err(CaseError::field(
                    "bulk.points",
                    k,
                    format!(
                        "must be odd and in 3 ... {MAX_BULK_POINTS} (odd, so that sigma = 0 \
                         is a point of the curve)"
                    ),
                ));
            }
            k
        }
    };
    let stress = operating_stress(&b, &kinds, shaft_radius)?;
    Ok(Bulk {
        shaft,
        shaft_radius,
        kinds,
        stress_max,
        points,
        stress,
    })
}

/// The operating bulk stress, Pa: `stress`, or the bending stress 4 M/(pi R^3) from a force,
/// a span and the support (beam theory), or none.
fn operating_stress(b: &RawBulk, kinds: &[LoadKind], shaft_radius: f64) -> CaseResult<Option<f64>> {
    let from_force = b.bending_force.is_some()
        || b.span.is_some()
        || b.support.is_some()
        || b.bending_side.is_some();
    if !from_force {
        return Ok(b.stress.as_ref().map(|s| s.si()));
    }
    if let Some(v) = &b.stress {
        return Err(CaseError::field(
            "bulk.stress",
            v,
            "give either bulk.stress or bulk.bending_force with bulk.span, not both",
        ));
    }
    if kinds != [LoadKind::Bending] {
        return Err(CaseError::field(
            "bulk.bending_force",
            "given",
            "needs kind = \"bending\" (the force bends the shaft)",
        ));
    }
    let required = |key: &str| {
        CaseError::field(
            format!("bulk.{key}"),
            "(missing)",
            "required with a bending force: bending_force (N), span (m), and \
             optionally support and bending_side",
        )
    };
    let force = b
        .bending_force
        .as_ref()
        .ok_or_else(|| required("bending_force"))?
        .si();
    let span = b.span.as_ref().ok_or_else(|| required("span"))?.si();
    let support = match b
        .support
        .as_ref()
        .map_or(Support::SimplySupported, |s| s.value)
    {
        Support::SimplySupported => BeamSupport::SimplySupported,
        Support::Cantilever => BeamSupport::Cantilever,
    };
    let sign = match b
        .bending_side
        .as_ref()
        .map_or(BendingSide::Tension, |s| s.value)
    {
        BendingSide::Tension => 1.0,
        BendingSide::Compression => -1.0,
    };
    let moment = bending_moment(force, span, support, "bulk.")?;
    Ok(Some(sign * bending_stress(moment, shaft_radius)))
}
