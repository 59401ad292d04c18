//! The rules of `[[bc]]` (boundary conditions and their profiles) and `[[steps]]` (load
//! factors and the controls of the rigid segments).

use std::collections::{BTreeMap, BTreeSet};

use tribo::solvers::bem2d::contact::Control;

use super::schema::{written, Number, Profile, RawBc, RawControl, RawStep};
use super::{bad, BcKind, BcSpec, ComponentSpec, ProfileSpec, StepSpec};
use crate::error::CaseResult;
use crate::units::{Dimension, Quantity};

/// The conditions and the load groups they name.
pub(super) fn bcs(raw: &[RawBc]) -> CaseResult<(Vec<BcSpec>, BTreeSet<String>)> {
    let mut bcs = Vec::new();
    let mut groups = BTreeSet::new();
    for (i, b) in raw.iter().enumerate() {
        let bc = bc_spec(&format!("bc[{i}]"), b)?;
        if let Some(g) = &bc.group {
            groups.insert(g.clone());
        }
        bcs.push(bc);
    }
    Ok((bcs, groups))
}

/// The steps (one with every group at factor 1 where none is given): unique names, factors
/// of known groups, every rigid segment controlled in every step.
pub(super) fn steps(
    raw: Option<Vec<RawStep>>,
    groups: &BTreeSet<String>,
    rigid: &[String],
) -> CaseResult<Vec<StepSpec>> {
    let raw_steps = raw.unwrap_or_else(|| vec![RawStep::default()]);
    if raw_steps.is_empty() {
        return Err(bad("steps", "[]", "at least one step is needed (omit [[steps]] for one step with every group at factor 1)"));
    }
    let mut steps = Vec::new();
    let mut names = BTreeSet::new();
    for (k, s) in raw_steps.iter().enumerate() {
        let field = format!("steps[{k}]");
        let name = s.name.clone().unwrap_or_else(|| format!("step{}", k + 1));
        if name.trim().is_empty() || !names.insert(name.clone()) {
            return Err(bad(
                format!("{field}.name"),
                format!("{name:?}"),
                "step names must be unique and not empty",
            ));
        }
        steps.push(StepSpec {
            name,
            factors: factors(&field, s.factors.as_ref(), groups)?,
            rigid: rigid_controls(&field, s.rigid.as_ref(), rigid)?,
        });
    }
    Ok(steps)
}

/// A step's factor of each load group (finite; groups not listed 0; all 1 where none given).
fn factors(
    field: &str,
    given: Option<&BTreeMap<String, Number>>,
    groups: &BTreeSet<String>,
) -> CaseResult<BTreeMap<String, f64>> {
    let mut factors = BTreeMap::new();
    let Some(t) = given else {
        for g in groups {
            factors.insert(g.clone(), 1.0);
        }
        return Ok(factors);
    };
    for (g, v) in t {
        if !groups.contains(g) {
            return Err(bad(
                format!("{field}.factors.{g}"),
                v,
                format!(
                    "names no load group (groups are named by the `group` of [[bc]] entries: {})",
                    if groups.is_empty() {
                        "none".to_string()
                    } else {
                        groups.iter().cloned().collect::<Vec<_>>().join(", ")
                    }
                ),
            ));
        }
        factors.insert(g.clone(), v.si());
    }
    Ok(factors)
}

/// A step's controls of the rigid segments: each declared one, { fx or ux, fy or uy }.
fn rigid_controls(
    field: &str,
    given: Option<&BTreeMap<String, RawControl>>,
    rigid: &[String],
) -> CaseResult<Vec<(String, Control, Control)>> {
    let empty = BTreeMap::new();
    let given = given.unwrap_or(&empty);
    for (seg, v) in given {
        if !rigid.contains(seg) {
            return Err(bad(
                format!("{field}.rigid.{seg}"),
                written(v),
                "names no rigid segment (declare it in `rigid = [...]`)",
            ));
        }
    }
    let mut controls = Vec::new();
    for seg in rigid {
        let f = format!("{field}.rigid.{seg}");
        let Some(t) = given.get(seg) else {
            return Err(bad(
                f,
                "(missing)",
                "every step must control every rigid segment: { fx or ux, fy or uy }",
            ));
        };
        let x = control(&f, t, (&t.fx, "fx"), (&t.ux, "ux"))?;
        let y = control(&f, t, (&t.fy, "fy"), (&t.uy, "uy"))?;
        controls.push((seg.clone(), x, y));
    }
    Ok(controls)
}

/// A profile's rules: a table's t increases from 0 to 1 (two rows at least).
fn profile<D: Dimension>(field: &str, p: &Profile<D>) -> CaseResult<ProfileSpec> {
    match p {
        Profile::Uniform(q) => Ok(ProfileSpec::Uniform(q.si())),
        Profile::Linear([a, b]) => Ok(ProfileSpec::Linear(a.si(), b.si())),
        Profile::Table(rows) => {
            let mut out: Vec<(f64, f64)> = Vec::new();
            for (i, (t, value)) in rows.iter().enumerate() {
                let t = t.si();
                if !(0.0..=1.0).contains(&t) || out.last().is_some_and(|&(p, _)| t <= p) {
                    return Err(bad(format!("{field}.table[{i}][0]"), t, "t must increase within [0, 1] (the fraction of the segment's length from its start)"));
                }
                out.push((t, value.si()));
            }
            if out.len() < 2 || out[0].0 != 0.0 || out[out.len() - 1].0 != 1.0 {
                return Err(bad(
                    format!("{field}.table"),
                    written(rows),
                    "needs at least two rows, the first at t = 0 and the last at t = 1",
                ));
            }
            Ok(ProfileSpec::Table(out))
        }
    }
}

fn bc_spec(field: &str, b: &RawBc) -> CaseResult<BcSpec> {
    let comp = |name: &str,
                u: &Option<Profile<crate::units::Length>>,
                t: &Option<Profile<crate::units::Pressure>>|
     -> CaseResult<Option<ComponentSpec>> {
        match (u, t) {
            (Some(_), Some(_)) => Err(bad(
                format!("{field}.{name}"),
                "(both displacement and traction)",
                "a direction takes either a displacement (ux/uy) or a traction (tx/ty), not both",
            )),
            (Some(u), None) => Ok(Some(ComponentSpec::Displacement(profile(
                &format!("{field}.u{name}"),
                u,
            )?))),
            (None, Some(t)) => Ok(Some(ComponentSpec::Traction(profile(
                &format!("{field}.t{name}"),
                t,
            )?))),
            (None, None) => Ok(None),
        }
    };
    let x = comp("x", &b.ux, &b.tx)?;
    let y = comp("y", &b.uy, &b.ty)?;
    let kind = match (&b.pressure, x, y) {
        (Some(p), None, None) => BcKind::Pressure(profile(&format!("{field}.pressure"), p)?),
        (Some(_), _, _) => {
            return Err(bad(format!("{field}.pressure"), "(with ux/uy/tx/ty)", "a normal pressure is the whole condition of the segment; do not combine it with components"));
        }
        (None, None, None) => {
            return Err(bad(field, format!("segment {:?}", b.segment), "gives no condition (ux, uy, tx, ty or pressure); a segment without condition is traction-free"));
        }
        (None, x, y) => BcKind::Components(
            x.unwrap_or(ComponentSpec::Traction(ProfileSpec::Uniform(0.0))),
            y.unwrap_or(ComponentSpec::Traction(ProfileSpec::Uniform(0.0))),
        ),
    };
    if let Some(g) = &b.group {
        if g.trim().is_empty() {
            return Err(bad(format!("{field}.group"), "\"\"", "must not be empty"));
        }
    }
    Ok(BcSpec {
        segment: b.segment.clone(),
        kind,
        group: b.group.clone(),
        origin: field.to_string(),
    })
}

fn control<F: Dimension, U: Dimension>(
    field: &str,
    t: &RawControl,
    (force, force_key): (&Option<Quantity<F>>, &str),
    (disp, disp_key): (&Option<Quantity<U>>, &str),
) -> CaseResult<Control> {
    match (force, disp) {
        (Some(f), None) => Ok(Control::Force(f.si())),
        (None, Some(u)) => Ok(Control::Displacement(u.si())),
        _ => Err(bad(field, written(t), format!("needs exactly one of {force_key} (force per unit thickness, N/m) and {disp_key} (translation, m)"))),
    }
}
