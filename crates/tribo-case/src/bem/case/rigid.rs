//! Rigid (guided) segments of a dynamic case (issue 13; docs/user/case-bem2d-dynamics.md,
//! docs/theory/DYNAMICS.md sec. 5.4 "Rigid segments"): the controls of the case's one load
//! step (`steps[0].rigid.<segment>`, a force or a translation per direction) with their
//! time function (`time`, as a `[[bc]]`'s), for the march
//! ([`tribo::dynamics::contact::DynamicContact::with_rigid`]), and the march's translation
//! and force history of each segment.

use serde::Serialize;
use tribo::dynamics::contact::{DynamicContactResult, DynamicRigid};

use super::dynamics::DynamicsSpec;
use super::BemCase;
use crate::error::{CaseError, CaseResult};

/// The rigid segments of `case` with the controls of its (one) load step and the time
/// functions of `spec`.
pub fn segments(case: &BemCase, spec: &DynamicsSpec) -> CaseResult<Vec<DynamicRigid>> {
    let Some(step) = case.steps.first() else {
        return Ok(Vec::new());
    };
    let mut out = Vec::with_capacity(case.rigid.len());
    for (k, seg) in case.rigid.iter().enumerate() {
        let (_, x, y) = step
            .rigid
            .iter()
            .find(|(s, _, _)| s == seg)
            .ok_or_else(|| {
                CaseError::field(
                    format!("steps[0].rigid.{seg}"),
                    "(missing)",
                    "every step must control every rigid segment: { fx or ux, fy or uy }",
                )
            })?;
        let time = spec.rigid_time.get(k).cloned().ok_or_else(|| {
            CaseError::field(
                format!("steps[0].rigid.{seg}.time"),
                "(missing)",
                "no time function for the rigid segment",
            )
        })?;
        out.push(DynamicRigid::new(seg, *x, *y)?.with_time(time));
    }
    Ok(out)
}

/// A library error about `rigid_segment[j]` renamed to the case's item
/// `steps[0].rigid.<segment>` (the segment's control) or `rigid` (its name).
pub fn rename_error(e: tribo::Error, case: &BemCase) -> CaseError {
    if let tribo::Error::InvalidParameter { field, value, rule } = &e {
        if let Some((j, rest)) = field
            .strip_prefix("rigid_segment[")
            .and_then(|r| r.split_once(']'))
        {
            if let Some(seg) = j.parse::<usize>().ok().and_then(|j| case.rigid.get(j)) {
                let item = if rest.is_empty() {
                    format!("rigid[{j}]")
                } else {
                    format!("steps[0].rigid.{seg}")
                };
                return CaseError::field(item, value, rule);
            }
        }
    }
    CaseError::from(e)
}

/// One rigid segment over the march.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RigidHistory {
    /// The segment.
    pub segment: String,
    /// Its translation at every step t_n = n dt, m.
    pub translation: Vec<[f64; 2]>,
    /// The resultant of the traction on it (the force it exerts on the body) at every
    /// step, N/m.
    pub force: Vec<[f64; 2]>,
}

/// The histories of the case's rigid segments in the march `result`.
pub fn histories(case: &BemCase, result: &DynamicContactResult) -> Vec<RigidHistory> {
    case.rigid
        .iter()
        .enumerate()
        .map(|(k, seg)| RigidHistory {
            segment: seg.clone(),
            translation: result
                .steps
                .iter()
                .map(|s| s.rigid.get(k).map_or([0.0; 2], |r| r.translation))
                .collect(),
            force: result
                .steps
                .iter()
                .map(|s| s.rigid.get(k).map_or([0.0; 2], |r| r.force))
                .collect(),
        })
        .collect()
}
