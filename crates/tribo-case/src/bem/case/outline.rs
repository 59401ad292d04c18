//! The rules of the outlines of `[[regions]]` (closed loops of lines and arcs, shared
//! segments) and of body forces.

use std::collections::BTreeMap;

use toml::Value;
use tribo::operators::bem2d::{BodyForce, Division, Grading, LoopItem, Segment, SegmentShape};

use super::bad;
use crate::error::CaseResult;
use crate::units::{count, number, quantity, show, Dim};

fn point(field: &str, v: &Value) -> CaseResult<[f64; 2]> {
    match v {
        Value::Array(a) if a.len() == 2 => Ok([
            quantity(&format!("{field}[0]"), &a[0], Dim::Length)?,
            quantity(&format!("{field}[1]"), &a[1], Dim::Length)?,
        ]),
        other => Err(bad(field, show(other), "must be a point [x, y] (lengths)")),
    }
}

fn close_to(a: [f64; 2], b: [f64; 2], scale: f64) -> bool {
    (a[0] - b[0]).hypot(a[1] - b[1]) <= 1e-9 * scale
}

/// Parses one loop: each segment starts where the previous one ends (the first at `start`),
/// a shared item follows another region's segment backwards (that region must come first),
/// and the last item must end at `start` (a closed outline).
pub(super) fn parse_loop(
    region: &str,
    field: &str,
    start: &Value,
    items: &[toml::Table],
    owned: &mut BTreeMap<String, SegmentShape>,
) -> CaseResult<Vec<LoopItem>> {
    if items.is_empty() {
        return Err(bad(
            format!("{field}.outline"),
            "[]",
            "an outline needs at least one segment",
        ));
    }
    let first = point(&format!("{field}.start"), start)?;
    let mut walk = Walk {
        region,
        current: first,
        scale: first[0].abs().max(first[1].abs()),
    };
    let mut out = Vec::new();
    for (k, t) in items.iter().enumerate() {
        let f = format!("{field}.outline[{k}]");
        let item = match t.get("shared") {
            Some(v) => walk.shared(&f, t, v, owned)?,
            None => walk.segment(&f, t, owned)?,
        };
        out.push(item);
    }
    if !close_to(walk.current, first, walk.scale) {
        return Err(bad(
            format!("{field}.outline"),
            format!("ends at ({:e}, {:e}) m", walk.current[0], walk.current[1]),
            format!("region '{region}': the outline is open; its last segment must end at start = ({:e}, {:e}) m", first[0], first[1]),
        ));
    }
    Ok(out)
}

/// Where a loop has got to: the end of its last item, and the length scale of the
/// closure tolerance.
struct Walk<'a> {
    region: &'a str,
    current: [f64; 2],
    scale: f64,
}

impl Walk<'_> {
    /// `{ shared = "SEGMENT" }`: an earlier region's segment, traversed backwards.
    fn shared(
        &mut self,
        f: &str,
        t: &toml::Table,
        v: &Value,
        owned: &BTreeMap<String, SegmentShape>,
    ) -> CaseResult<LoopItem> {
        for key in t.keys() {
            if key != "shared" {
                return Err(bad(
                    format!("{f}.{key}"),
                    show(&t[key]),
                    "a shared item takes only `shared = \"SEGMENT\"`",
                ));
            }
        }
        let Value::String(name) = v else {
            return Err(bad(
                format!("{f}.shared"),
                show(v),
                "must be the name of an earlier region's segment",
            ));
        };
        let shape = owned.get(name).ok_or_else(|| {
            bad(format!("{f}.shared"), format!("{name:?}"), "names no segment of an earlier region (the region owning a bonded interface must come first)")
        })?;
        let (a, b) = (shape.point(0.0), shape.point(1.0));
        self.scale = self
            .scale
            .max(shape.length())
            .max(a[0].abs())
            .max(a[1].abs());
        // Traversed backwards: from the segment's end to its start.
        if !close_to(b, self.current, self.scale) {
            return Err(bad(
                f,
                format!("shared {name:?} runs from ({:e}, {:e}) back to ({:e}, {:e}) m", b[0], b[1], a[0], a[1]),
                format!("region '{}': a shared segment is followed backwards and must start where the previous item ends, at ({:e}, {:e}) m", self.region, self.current[0], self.current[1]),
            ));
        }
        self.current = a;
        Ok(LoopItem::Shared(name.clone()))
    }

    /// A named line or arc from the current point to `to`, with its division and grading.
    fn segment(
        &mut self,
        f: &str,
        t: &toml::Table,
        owned: &mut BTreeMap<String, SegmentShape>,
    ) -> CaseResult<LoopItem> {
        for key in t.keys() {
            if ![
                "name",
                "to",
                "center",
                "clockwise",
                "elements",
                "size",
                "grading",
            ]
            .contains(&key.as_str())
            {
                return Err(bad(
                    format!("{f}.{key}"),
                    show(&t[key]),
                    "unknown key (name, to, center, clockwise, elements, size, grading; or shared)",
                ));
            }
        }
        let name = match t.get("name") {
            Some(Value::String(s)) if !s.trim().is_empty() => s.clone(),
            Some(other) => {
                return Err(bad(
                    format!("{f}.name"),
                    show(other),
                    "must be a non-empty string",
                ))
            }
            None => {
                return Err(bad(
                    format!("{f}.name"),
                    "(missing)",
                    "every segment needs a unique name",
                ))
            }
        };
        let to_value = t.get("to").ok_or_else(|| {
            bad(
                format!("{f}.to"),
                "(missing)",
                "the end point [x, y] of the segment",
            )
        })?;
        let to = point(&format!("{f}.to"), to_value)?;
        self.scale = self.scale.max(to[0].abs()).max(to[1].abs());
        let shape = segment_shape(f, t, self.current, to)?;
        let division = division(f, t)?;
        let grading = grading(f, t)?;
        if owned.insert(name.clone(), shape.clone()).is_some() {
            return Err(bad(
                format!("{f}.name"),
                format!("{name:?}"),
                "a segment is named twice (names must be unique in the model)",
            ));
        }
        self.current = to;
        Ok(LoopItem::Segment(Segment {
            name,
            shape,
            division,
            grading,
        }))
    }
}

/// A line from `current` to `to`, or an arc about `center` (both ends equally far from it),
/// counter-clockwise unless `clockwise = true`.
fn segment_shape(
    f: &str,
    t: &toml::Table,
    current: [f64; 2],
    to: [f64; 2],
) -> CaseResult<SegmentShape> {
    let Some(c) = t.get("center") else {
        if let Some(c) = t.get("clockwise") {
            return Err(bad(
                format!("{f}.clockwise"),
                show(c),
                "only arcs (with `center`) have a direction",
            ));
        }
        return Ok(SegmentShape::Line {
            start: current,
            end: to,
        });
    };
    let center = point(&format!("{f}.center"), c)?;
    let clockwise = match t.get("clockwise") {
        None => false,
        Some(Value::Boolean(b)) => *b,
        Some(o) => {
            return Err(bad(
                format!("{f}.clockwise"),
                show(o),
                "must be true or false",
            ))
        }
    };
    let r0 = (current[0] - center[0]).hypot(current[1] - center[1]);
    let r1 = (to[0] - center[0]).hypot(to[1] - center[1]);
    if !(r0 > 0.0 && (r0 - r1).abs() <= 1e-9 * r0.max(r1)) {
        return Err(bad(
            format!("{f}.center"),
            format!("[{:e}, {:e}]", center[0], center[1]),
            format!("an arc's start and end must be equally far from its centre (radii {r0:e} and {r1:e} m)"),
        ));
    }
    let a0 = (current[1] - center[1]).atan2(current[0] - center[0]);
    let mut a1 = (to[1] - center[1]).atan2(to[0] - center[0]);
    let tau = std::f64::consts::TAU;
    if clockwise {
        while a1 >= a0 - 1e-12 {
            a1 -= tau;
        }
    } else {
        while a1 <= a0 + 1e-12 {
            a1 += tau;
        }
    }
    Ok(SegmentShape::Arc {
        center,
        radius: r0,
        start_angle: a0,
        end_angle: a1,
    })
}

/// `elements = N` or `size = h` (not both; default 4 elements).
fn division(f: &str, t: &toml::Table) -> CaseResult<Division> {
    Ok(match (t.get("elements"), t.get("size")) {
        (Some(_), Some(_)) => {
            return Err(bad(
                format!("{f}.size"),
                show(&t["size"]),
                "give `elements` or `size`, not both",
            ))
        }
        (Some(n), None) => Division::Count(count(&format!("{f}.elements"), n)?),
        (None, Some(h)) => Division::Size(quantity(&format!("{f}.size"), h, Dim::Length)?),
        (None, None) => Division::Count(4),
    })
}

/// `grading = { both = R }`, `{ start = R }` or `{ end = R }`; uniform where not given.
fn grading(f: &str, t: &toml::Table) -> CaseResult<Grading> {
    let grading_rule =
        "grading is { both = R }, { start = R } or { end = R } (R = largest / smallest element)";
    match t.get("grading") {
        None => Ok(Grading::Uniform),
        Some(Value::Table(g)) if g.len() == 1 => {
            let (k, v) = g
                .iter()
                .next()
                .ok_or_else(|| bad(format!("{f}.grading"), "{}", grading_rule))?;
            let q = number(&format!("{f}.grading.{k}"), v)?;
            match k.as_str() {
                "both" => Ok(Grading::BothEnds(q)),
                "start" => Ok(Grading::Start(q)),
                "end" => Ok(Grading::End(q)),
                _ => Err(bad(format!("{f}.grading.{k}"), show(v), grading_rule)),
            }
        }
        Some(other) => Err(bad(format!("{f}.grading"), show(other), grading_rule)),
    }
}

/// `body_force = { density = 7850, gravity = [gx, gy], angular_velocity = w, center = [x, y] }`:
/// gravity (m/s^2) and/or rotation (rad/s about the axis through `center`), density in
/// kg/m^3 (required). The library validates the values and names the region.
pub(super) fn body_forces(field: &str, t: &toml::Table) -> CaseResult<Vec<BodyForce>> {
    for key in t.keys() {
        if !["density", "gravity", "angular_velocity", "center"].contains(&key.as_str()) {
            return Err(bad(
                format!("{field}.{key}"),
                show(&t[key]),
                "unknown key (density, gravity, angular_velocity, center)",
            ));
        }
    }
    let density = match t.get("density") {
        Some(v) => number(&format!("{field}.density"), v)?,
        None => {
            return Err(bad(
                format!("{field}.density"),
                "(missing)",
                "a body force needs the density, kg/m^3",
            ))
        }
    };
    let mut out = Vec::new();
    if let Some(g) = t.get("gravity") {
        let pair = match g {
            Value::Array(a) if a.len() == 2 => [
                number(&format!("{field}.gravity[0]"), &a[0])?,
                number(&format!("{field}.gravity[1]"), &a[1])?,
            ],
            other => {
                return Err(bad(
                    format!("{field}.gravity"),
                    show(other),
                    "must be [gx, gy] in m/s^2",
                ))
            }
        };
        out.push(BodyForce::gravity(density, pair));
    }
    match (t.get("angular_velocity"), t.get("center")) {
        (Some(w), Some(c)) => {
            let w = number(&format!("{field}.angular_velocity"), w)?;
            out.push(BodyForce::centrifugal(
                density,
                w,
                point(&format!("{field}.center"), c)?,
            ));
        }
        (None, None) => {}
        _ => {
            return Err(bad(
                field,
                show(&Value::Table(t.clone())),
                "a rotation needs both angular_velocity (rad/s) and center [x, y]",
            ))
        }
    }
    if out.is_empty() {
        return Err(bad(
            field,
            show(&Value::Table(t.clone())),
            "gives no body force: add gravity = [gx, gy] and/or angular_velocity with center",
        ));
    }
    Ok(out)
}
