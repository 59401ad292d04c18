//! The rules of the outlines of `[[regions]]` (closed loops of lines and arcs, shared
//! segments) and of body forces.

use std::collections::BTreeMap;

use tribo::operators::bem2d::{BodyForce, Division, Grading, LoopItem, Segment, SegmentShape};

use super::bad;
use super::schema::{written, Point, RawBodyForce, RawItem, GRADING_RULE};
use crate::error::CaseResult;

fn close_to(a: [f64; 2], b: [f64; 2], scale: f64) -> bool {
    (a[0] - b[0]).hypot(a[1] - b[1]) <= 1e-9 * scale
}

/// Parses one loop: each segment starts where the previous one ends (the first at `start`),
/// a shared item follows another region's segment backwards (that region must come first),
/// and the last item must end at `start` (a closed outline).
pub(super) fn parse_loop(
    region: &str,
    field: &str,
    start: &Point,
    items: &[RawItem],
    owned: &mut BTreeMap<String, SegmentShape>,
) -> CaseResult<Vec<LoopItem>> {
    if items.is_empty() {
        return Err(bad(
            format!("{field}.outline"),
            "[]",
            "an outline needs at least one segment",
        ));
    }
    let first = start.si();
    let mut walk = Walk {
        region,
        current: first,
        scale: first[0].abs().max(first[1].abs()),
    };
    let mut out = Vec::new();
    for (k, t) in items.iter().enumerate() {
        let f = format!("{field}.outline[{k}]");
        let item = match &t.shared {
            Some(name) => walk.shared(&f, t, name, owned)?,
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
        t: &RawItem,
        name: &str,
        owned: &BTreeMap<String, SegmentShape>,
    ) -> CaseResult<LoopItem> {
        let alone = RawItem {
            shared: t.shared.clone(),
            ..RawItem::default()
        };
        if *t != alone {
            let mut other = t.clone();
            other.shared = None;
            let (key, value) = match toml::Value::try_from(&other) {
                Ok(toml::Value::Table(rest)) => rest
                    .into_iter()
                    .next()
                    .map(|(k, v)| (format!(".{k}"), crate::units::show(&v)))
                    .unwrap_or_default(),
                _ => (String::new(), written(&other)),
            };
            return Err(bad(
                format!("{f}{key}"),
                value,
                "a shared item takes only `shared = \"SEGMENT\"`",
            ));
        }
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
        Ok(LoopItem::Shared(name.to_string()))
    }

    /// A named line or arc from the current point to `to`, with its division and grading.
    fn segment(
        &mut self,
        f: &str,
        t: &RawItem,
        owned: &mut BTreeMap<String, SegmentShape>,
    ) -> CaseResult<LoopItem> {
        let name = match &t.name {
            Some(s) if !s.trim().is_empty() => s.clone(),
            Some(other) => {
                return Err(bad(
                    format!("{f}.name"),
                    format!("{other:?}"),
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
        let to =
            t.to.as_ref()
                .ok_or_else(|| {
                    bad(
                        format!("{f}.to"),
                        "(missing)",
                        "the end point [x, y] of the segment",
                    )
                })?
                .si();
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
    t: &RawItem,
    current: [f64; 2],
    to: [f64; 2],
) -> CaseResult<SegmentShape> {
    let Some(c) = &t.center else {
        if let Some(c) = &t.clockwise {
            return Err(bad(
                format!("{f}.clockwise"),
                &c.written,
                "only arcs (with `center`) have a direction",
            ));
        }
        return Ok(SegmentShape::Line {
            start: current,
            end: to,
        });
    };
    let center = c.si();
    let clockwise = t.clockwise.as_ref().is_some_and(|c| c.on);
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
fn division(f: &str, t: &RawItem) -> CaseResult<Division> {
    Ok(match (&t.elements, &t.size) {
        (Some(_), Some(h)) => {
            return Err(bad(
                format!("{f}.size"),
                h,
                "give `elements` or `size`, not both",
            ))
        }
        (Some(n), None) => Division::Count(n.n),
        (None, Some(h)) => Division::Size(h.si()),
        (None, None) => Division::Count(4),
    })
}

/// `grading = { both = R }`, `{ start = R }` or `{ end = R }`; uniform where not given.
fn grading(f: &str, t: &RawItem) -> CaseResult<Grading> {
    let Some(g) = &t.grading else {
        return Ok(Grading::Uniform);
    };
    let q = g.ratio.si();
    match g.at.as_str() {
        "both" => Ok(Grading::BothEnds(q)),
        "start" => Ok(Grading::Start(q)),
        "end" => Ok(Grading::End(q)),
        k => Err(bad(format!("{f}.grading.{k}"), &g.ratio, GRADING_RULE)),
    }
}

/// `body_force = { density = 7850, gravity = [gx, gy], angular_velocity = w, center = [x, y] }`:
/// gravity (m/s^2) and/or rotation (rad/s about the axis through `center`), density in
/// kg/m^3 (required). The library validates the values and names the region.
pub(super) fn body_forces(field: &str, t: &RawBodyForce) -> CaseResult<Vec<BodyForce>> {
    let Some(density) = &t.density else {
        return Err(bad(
            format!("{field}.density"),
            "(missing)",
            "a body force needs the density, kg/m^3",
        ));
    };
    let density = density.si();
    let mut out = Vec::new();
    if let Some(g) = &t.gravity {
        out.push(BodyForce::gravity(density, [g.0[0].si(), g.0[1].si()]));
    }
    match (&t.angular_velocity, &t.center) {
        (Some(w), Some(c)) => out.push(BodyForce::centrifugal(density, w.si(), c.si())),
        (None, None) => {}
        _ => {
            return Err(bad(
                field,
                written(t),
                "a rotation needs both angular_velocity (rad/s) and center [x, y]",
            ))
        }
    }
    if out.is_empty() {
        return Err(bad(
            field,
            written(t),
            "gives no body force: add gravity = [gx, gy] and/or angular_velocity with center",
        ));
    }
    Ok(out)
}
