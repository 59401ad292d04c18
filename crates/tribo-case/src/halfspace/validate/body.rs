//! The rules of `[body1]`, `[body2]` and their `[bodyN.surface]`: materials, radii, rollers,
//! height maps.

use super::positive;
use crate::error::{CaseError, CaseResult};
use crate::halfspace::model::{Roughness, Shape};
use crate::halfspace::schema::{CrownKind, Metres, Radii, RawBody, RawSurface, SurfaceKind};
use std::path::{Path, PathBuf};
use tribo::geometry::{Crown, HeightMap, LogarithmicCrown, Roller, SurfaceProfile};
use tribo::solvers::NormalLoading;
use tribo::ElasticMaterial;

pub(super) fn material(name: &str, b: &RawBody) -> CaseResult<ElasticMaterial> {
    let m = ElasticMaterial::named(name, b.e.si(), b.nu.si())?;
    crate::units::check_modulus(&format!("{name}.E"), b.e.written(), b.e.si())?;
    Ok(m)
}

/// What a body's surface needs from the rest of the case.
pub(super) struct ShapeContext<'a> {
    pub e_star: f64,
    /// The load, `None` under `contact.mean_pressure` (the force needs the period).
    pub loading: Option<NormalLoading>,
    pub base_dir: &'a Path,
}

/// A body's smooth shape and its roughness. `radii` and a `[bodyN.surface]` of kind
/// "rough" or "measured" combine: the roughness superposed on the body of those radii (a
/// rough ball); such a surface alone is a rough flat. A roller or a height map is the
/// whole shape: not with `radii`; a roller takes a roughness as its table
/// `[bodyN.surface.roughness]` (a rough crowned roller), with the keys and rules of a
/// surface of kind "rough" or "measured".
pub(super) fn shape(
    name: &str,
    b: RawBody,
    ctx: &ShapeContext<'_>,
) -> CaseResult<(Shape, Option<Roughness>)> {
    let field = format!("{name}.surface");
    let rough_kind =
        |s: &RawSurface| matches!(s.kind.value, SurfaceKind::Rough | SurfaceKind::Measured);
    match (b.radii, b.surface) {
        (Some(r), Some(s)) if rough_kind(&s) => {
            let roughness = roughness(&field, s, ctx)?;
            let radii = radii(name, &r)?;
            let angle = b.angle_deg.as_ref().map_or(0.0, |d| d.si().to_radians());
            Ok((Shape::Radii { radii, angle }, Some(roughness)))
        }
        (Some(_), Some(s)) => Err(CaseError::field(
            format!("{name}.radii"),
            format!("(and a surface of kind = {})", s.kind.written),
            format!(
                "give exactly one of {name}.radii and a [{name}.surface] of kind \"roller\" or \
                 \"height_map\" (radii combine only with a \"rough\" or \"measured\" surface)"
            ),
        )),
        (None, None) => Err(CaseError::field(
            format!("{name}.radii"),
            "(missing)",
            format!("give the body's shape: {name}.radii = [Rx, Ry] or a [{name}.surface] table"),
        )),
        (Some(r), None) => {
            let radii = radii(name, &r)?;
            let angle = match &b.angle_deg {
                None => 0.0,
                Some(deg) => deg.si().to_radians(),
            };
            Ok((Shape::Radii { radii, angle }, None))
        }
        (None, Some(mut s)) => {
            if let Some(a) = &b.angle_deg {
                return Err(CaseError::field(
                    format!("{name}.angle_deg"),
                    a,
                    "applies to radii only; a surface is given in the common frame",
                ));
            }
            if rough_kind(&s) {
                // A rough flat: the roughness on a plane.
                let roughness = roughness(&field, s, ctx)?;
                return Ok((
                    Shape::Radii {
                        radii: [f64::INFINITY; 2],
                        angle: 0.0,
                    },
                    Some(roughness),
                ));
            }
            // A roller's roughness table; on any other surface `surface` refuses it.
            let nested = match s.kind.value {
                SurfaceKind::Roller => s.roughness.take(),
                _ => None,
            };
            let shape = Shape::Surface(surface(&field, s, ctx)?);
            let roughness = match nested {
                Some(r) => Some(roughness(&format!("{field}.roughness"), *r, ctx)?),
                None => None,
            };
            Ok((shape, roughness))
        }
    }
}

/// The principal radii, m: non-zero, within [`crate::units::LENGTH_RANGE`] (or infinite).
fn radii(name: &str, r: &Radii) -> CaseResult<[f64; 2]> {
    let mut out = [0.0; 2];
    for (k, radius) in r.0.iter().enumerate() {
        let field = format!("{name}.radii[{k}]");
        if radius.metres == 0.0 {
            return Err(CaseError::field(
                field,
                &radius.written,
                "a radius of curvature must be non-zero (use \"inf\" for a flat direction)",
            ));
        }
        if radius.metres.is_finite() {
            crate::units::check_length(&field, &radius.written, radius.metres)?;
        }
        out[k] = radius.metres;
    }
    Ok(out)
}

/// Refuses the keys that do not apply to the surface's kind; a roughness table
/// (`roughness`) applies to a roller only.
fn check_keys(field: &str, s: &RawSurface) -> CaseResult<()> {
    if s.roughness.is_some() && s.kind.value != SurfaceKind::Roller {
        return Err(CaseError::field(
            format!("{field}.roughness"),
            "(a table)",
            format!(
                "a roughness table belongs to a roller surface (kind = \"roller\"), not to \
                 kind = {}; for a rough ball or a rough flat give kind = \"rough\" or \
                 \"measured\" in the surface itself (with {body}.radii for the ball)",
                s.kind.written,
                body = field.split('.').next().unwrap_or(field)
            ),
        ));
    }
    match foreign_key(s) {
        Some((key, value)) => Err(CaseError::field(
            format!("{field}.{key}"),
            value,
            format!("does not apply to kind = {}", s.kind.written),
        )),
        None => Ok(()),
    }
}

fn surface(field: &str, s: RawSurface, ctx: &ShapeContext<'_>) -> CaseResult<SurfaceProfile> {
    check_keys(field, &s)?;
    match s.kind.value {
        SurfaceKind::Roller => roller(field, s, ctx),
        SurfaceKind::HeightMap => height_map(field, s, ctx),
        // `shape` takes these to `roughness`.
        SurfaceKind::Rough | SurfaceKind::Measured => Err(CaseError::field(
            format!("{field}.kind"),
            &s.kind.written,
            "a rough or measured surface is a roughness, not a shape",
        )),
    }
}

/// A roughness: a surface of kind "rough" or "measured" (`field` names its table, a
/// `[bodyN.surface]` or a roller's `[bodyN.surface.roughness]`).
fn roughness(field: &str, s: RawSurface, ctx: &ShapeContext<'_>) -> CaseResult<Roughness> {
    if matches!(s.kind.value, SurfaceKind::Roller | SurfaceKind::HeightMap) {
        return Err(CaseError::field(
            format!("{field}.kind"),
            &s.kind.written,
            "a roughness must be kind = \"rough\" (generated) or \"measured\" (a file)",
        ));
    }
    check_keys(field, &s)?;
    match s.kind.value {
        SurfaceKind::Rough => super::rough::generated(field, &s).map(Roughness::Generated),
        _ => super::rough::measured(field, s, ctx.base_dir).map(Roughness::Measured),
    }
}

/// The first key given that does not apply to the surface's kind, with its value as written.
fn foreign_key(s: &RawSurface) -> Option<(&'static str, String)> {
    use SurfaceKind::{HeightMap, Measured, Roller, Rough};
    let q = |q: Option<&Metres>| q.map(|q| q.written().to_string());
    let n = |q: Option<&crate::halfspace::schema::Number>| q.map(|q| q.written().to_string());
    let keys: Vec<(&'static str, Option<String>, &[SurfaceKind])> = vec![
        ("radius", q(s.radius.as_ref()), &[Roller]),
        ("length", q(s.length.as_ref()), &[Roller]),
        (
            "crown",
            s.crown.as_ref().map(|c| c.written.clone()),
            &[Roller],
        ),
        ("crown_radius", q(s.crown_radius.as_ref()), &[Roller]),
        ("flat_length", q(s.flat_length.as_ref()), &[Roller]),
        (
            "design_load",
            s.design_load.as_ref().map(|x| x.written().to_string()),
            &[Roller],
        ),
        ("crown_drop", q(s.crown_drop.as_ref()), &[Roller]),
        (
            "file",
            s.file.as_ref().map(|f| format!("{f:?}")),
            &[HeightMap, Measured],
        ),
        (
            "heights",
            s.heights.as_ref().map(|_| "given".to_string()),
            &[HeightMap],
        ),
        (
            "spacing",
            s.spacing.as_ref().map(|p| p.written.clone()),
            &[HeightMap, Measured],
        ),
        ("scale", n(s.scale.as_ref()), &[HeightMap, Measured]),
        ("hurst", n(s.hurst.as_ref()), &[Rough]),
        (
            "rolloff_wavelength",
            q(s.rolloff_wavelength.as_ref()),
            &[Rough],
        ),
        ("long_wavelength", q(s.long_wavelength.as_ref()), &[Rough]),
        ("short_wavelength", q(s.short_wavelength.as_ref()), &[Rough]),
        ("rms_height", q(s.rms_height.as_ref()), &[Rough]),
        ("rms_slope", n(s.rms_slope.as_ref()), &[Rough]),
        (
            "anisotropy",
            s.anisotropy.as_ref().map(|p| p.written.clone()),
            &[Rough],
        ),
        ("seed", s.seed.as_ref().map(|c| c.n.to_string()), &[Rough]),
        (
            "method",
            s.method.as_ref().map(|m| m.written.clone()),
            &[Rough],
        ),
        (
            "format",
            s.format.as_ref().map(|f| f.written.clone()),
            &[Measured],
        ),
        (
            "detrend",
            s.detrend.as_ref().map(|d| d.written.clone()),
            &[Measured],
        ),
        (
            "periodic",
            s.periodic.as_ref().map(|p| p.written.clone()),
            &[Measured],
        ),
    ];
    keys.into_iter()
        .filter(|(_, _, kinds)| !kinds.contains(&s.kind.value))
        .find_map(|(k, v, _)| Some((k, v?)))
}

fn required<'a>(
    field: &str,
    key: &str,
    v: &'a Option<Metres>,
    what: &str,
) -> CaseResult<&'a Metres> {
    v.as_ref().ok_or_else(|| {
        CaseError::field(
            format!("{field}.{key}"),
            "(missing)",
            format!("required: {what}"),
        )
    })
}

fn roller(field: &str, s: RawSurface, ctx: &ShapeContext<'_>) -> CaseResult<SurfaceProfile> {
    let r = positive(
        &format!("{field}.radius"),
        required(field, "radius", &s.radius, "the roller radius (m)")?,
        "the roller radius (m)",
    )?;
    let l = positive(
        &format!("{field}.length"),
        required(field, "length", &s.length, "the roller length (m)")?,
        "the roller length (m)",
    )?;
    let kind = s.crown.as_ref().map_or(CrownKind::None, |c| c.value);
    let kind_name = s
        .crown
        .as_ref()
        .map_or("\"none\"".to_string(), |c| c.written.clone());
    let unused = |key: &str, v: Option<String>| -> CaseResult<()> {
        match v {
            Some(v) => Err(CaseError::field(
                format!("{field}.{key}"),
                v,
                format!("does not apply to crown = {kind_name}"),
            )),
            None => Ok(()),
        }
    };
    let written = |q: &Option<Metres>| q.as_ref().map(|q| q.written().to_string());
    let c = match kind {
        CrownKind::None => {
            unused("crown_radius", written(&s.crown_radius))?;
            unused("flat_length", written(&s.flat_length))?;
            unused(
                "design_load",
                s.design_load.as_ref().map(|q| q.written().to_string()),
            )?;
            unused("crown_drop", written(&s.crown_drop))?;
            Crown::None
        }
        CrownKind::Circular => {
            unused(
                "design_load",
                s.design_load.as_ref().map(|q| q.written().to_string()),
            )?;
            unused("crown_drop", written(&s.crown_drop))?;
            let cr = s.crown_radius.as_ref().ok_or_else(|| {
                CaseError::field(
                    format!("{field}.crown_radius"),
                    "(missing)",
                    "a circular crown needs its radius (m)",
                )
            })?;
            let crown_radius =
                positive(&format!("{field}.crown_radius"), cr, "the crown radius (m)")?;
            let flat_length = s.flat_length.as_ref().map_or(0.0, Metres::si);
            Crown::Circular {
                crown_radius,
                flat_length,
            }
        }
        CrownKind::Logarithmic => {
            unused("crown_radius", written(&s.crown_radius))?;
            unused("flat_length", written(&s.flat_length))?;
            let q =
                match (&s.design_load, ctx.loading) {
                    (Some(v), _) => {
                        positive(&format!("{field}.design_load"), v, "the design load (N)")?
                    }
                    (None, Some(NormalLoading::Force(f))) => f,
                    (None, None) => return Err(CaseError::field(
                        format!("{field}.design_load"),
                        "(missing)",
                        "a logarithmic crown under contact.mean_pressure needs its design load (N)",
                    )),
                    (None, Some(NormalLoading::Approach(_))) => {
                        return Err(CaseError::field(
                            format!("{field}.design_load"),
                            "(missing)",
                            "a logarithmic crown under approach control needs its design load (N)",
                        ))
                    }
                };
            let zm = match &s.crown_drop {
                None => None,
                Some(v) => Some(positive(
                    &format!("{field}.crown_drop"),
                    v,
                    "the crown drop at the roller ends (m)",
                )?),
            };
            Crown::Logarithmic(LogarithmicCrown::new(field, q, l, ctx.e_star, zm)?)
        }
    };
    Ok(SurfaceProfile::Roller(Roller::new(field, r, l, c)?))
}

fn height_map(field: &str, s: RawSurface, ctx: &ShapeContext<'_>) -> CaseResult<SurfaceProfile> {
    let spacing = s.spacing.as_ref().ok_or_else(|| {
        CaseError::field(
            format!("{field}.spacing"),
            "(missing)",
            "required: the spacing of the height map's points, m, scalar or [dx, dy]",
        )
    })?;
    let sp = [spacing.items[0].si(), spacing.items[1].si()];
    let scale = match &s.scale {
        None => 1.0,
        Some(v) => {
            let x = v.si();
            if !(x.is_finite() && x > 0.0) {
                return Err(CaseError::field(
                    format!("{field}.scale"),
                    v,
                    "must be finite and > 0",
                ));
            }
            x
        }
    };
    let (nx, ny, mut values) = match (s.file, s.heights) {
        (Some(f), None) => {
            let path = ctx.base_dir.join(&f);
            read_height_csv(&format!("{field}.file"), &path)?
        }
        (None, Some(rows)) => inline_heights(&format!("{field}.heights"), &rows)?,
        (Some(f), Some(_)) => {
            return Err(CaseError::field(
                format!("{field}.file"),
                format!("{f:?}"),
                "give either file or heights, not both",
            ))
        }
        (None, None) => {
            return Err(CaseError::field(
                format!("{field}.file"),
                "(missing)",
                "a height map needs file = \"map.csv\" or heights = [[...], ...]",
            ))
        }
    };
    values.iter_mut().for_each(|h| *h *= scale);
    Ok(SurfaceProfile::HeightMap(HeightMap::new(
        field, nx, ny, sp, values,
    )?))
}

fn inline_heights(
    field: &str,
    rows: &[Vec<crate::halfspace::schema::Number>],
) -> CaseResult<(usize, usize, Vec<f64>)> {
    let ny = rows.len();
    let nx = rows.first().map_or(0, Vec::len);
    let mut out = Vec::with_capacity(nx * ny);
    for (j, row) in rows.iter().enumerate() {
        if row.len() != nx {
            return Err(CaseError::field(
                format!("{field}[{j}]"),
                format!("{} values", row.len()),
                format!("ragged: every row must have as many values as the first ({nx})"),
            ));
        }
        out.extend(row.iter().map(|h| h.si()));
    }
    if nx < 2 || ny < 2 {
        return Err(CaseError::field(
            field,
            format!("{ny} x {nx}"),
            "a height map needs at least 2 x 2 values",
        ));
    }
    Ok((nx, ny, out))
}

/// Read a height map CSV: one row of the grid per line, values separated by commas, row `j`
/// (the j-th data line) at `y_j`, column `i` at `x_i` (both increasing; see
/// [`tribo::geometry::HeightMap`]); blank lines and lines starting with `#` are skipped.
pub fn read_height_csv(field: &str, path: &Path) -> CaseResult<(usize, usize, Vec<f64>)> {
    let unreadable = |source: std::io::Error| CaseError::Unreadable {
        field: field.to_string(),
        path: path.to_path_buf(),
        source,
    };
    // A regular file only: a device (/dev/zero never ends) or a pipe (the open blocks) is
    // refused before it is opened; its size is bounded like a topography's text.
    use crate::topography::{read_regular, BoundedReadError};
    let limit = crate::topography::ReadOptions::default()
        .max_bytes
        .saturating_mul(8) as u64;
    let bytes = read_regular(path, limit).map_err(|e| {
        unreadable(match e {
            BoundedReadError::Io(e) => e,
            BoundedReadError::Directory | BoundedReadError::NotRegular => std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "not a regular file (a directory, a device, a pipe or a socket)",
            ),
            BoundedReadError::TooLarge(len) => std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!("the file has {len} bytes, above the limit of {limit} bytes"),
            ),
        })
    })?;
    let text = String::from_utf8(bytes)
        .map_err(|e| unreadable(std::io::Error::new(std::io::ErrorKind::InvalidData, e)))?;
    let bad = |line: usize, rule: String| CaseError::DataFile {
        field: field.to_string(),
        path: PathBuf::from(path),
        line,
        rule,
    };
    let mut nx = 0;
    let mut ny = 0;
    let mut values = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let t = line.trim();
        if t.is_empty() || t.starts_with('#') {
            continue;
        }
        let mut count = 0;
        for (i, cell) in t.split(',').enumerate() {
            let c = cell.trim();
            let v: f64 = c
                .parse()
                .map_err(|_| bad(k + 1, format!("column {}: {c:?} is not a number", i + 1)))?;
            if !v.is_finite() {
                return Err(bad(
                    k + 1,
                    format!("column {}: {c:?} is not a finite number", i + 1),
                ));
            }
            values.push(v);
            count += 1;
        }
        if ny == 0 {
            nx = count;
        } else if count != nx {
            return Err(bad(
                k + 1,
                format!("ragged: {count} values where the first row has {nx}"),
            ));
        }
        ny += 1;
    }
    if nx < 2 || ny < 2 {
        return Err(bad(
            text.lines().count().max(1),
            format!("a height map needs at least 2 rows of 2 values (found {ny} rows of {nx})"),
        ));
    }
    Ok((nx, ny, values))
}

/// Refuse radii whose gap h = A x'^2 + B y'^2 is not positive definite (docs/theory/HALFSPACE.md 3.1,
/// Johnson 1985 section 4.2): no bounded contact (both flat, or too conforming).
pub(super) fn check_convex(r1: [f64; 2], r2: [f64; 2], angle: f64) -> CaseResult<()> {
    let k = |r: f64| if r.is_infinite() { 0.0 } else { 1.0 / r };
    let (k11, k12, k21, k22) = (k(r1[0]), k(r1[1]), k(r2[0]), k(r2[1]));
    let sum = 0.5 * (k11 + k12 + k21 + k22);
    let (d1, d2) = (k11 - k12, k21 - k22);
    let diff = 0.5
        * (d1 * d1 + d2 * d2 + 2.0 * d1 * d2 * (2.0 * angle).cos())
            .max(0.0)
            .sqrt();
    let (a, b) = (sum - diff, sum + diff);
    // Relative threshold: a curvature below 1e-9 of the largest is zero up to round-off.
    let scale = [k11, k12, k21, k22]
        .iter()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    if !(a > 1e-9 * scale && b > 0.0) {
        return Err(CaseError::field(
            "body1.radii, body2.radii",
            format!("[{}, {}], [{}, {}]", r1[0], r1[1], r2[0], r2[1]),
            format!(
                "the gap h = A x'^2 + B y'^2 must be convex (A, B > 0) for a bounded contact, \
                 here A = {a:.4e}, B = {b:.4e} 1/m (both bodies flat, or a concave body tighter \
                 than the convex one); use a [bodyN.surface] for line contacts, and \
                 [grid] periodic = true for a rough flat on a flat"
            ),
        ));
    }
    Ok(())
}
