//! The rules of rough (generated) and measured surfaces (`[bodyN.surface] kind = "rough"`
//! or `"measured"`), and of periodic grids (`[grid] periodic = true`).
//!
//! Spelling: the spectrum's bounds are given as wavelengths in m (`rolloff_wavelength`,
//! `long_wavelength`, `short_wavelength`), as every length of a case file (with unit strings
//! such as "20 um") and as the cutoffs of surface filters are given (ISO 25178-3's nesting
//! indices are wavelengths); the library's wavenumbers are `q = 2 pi / wavelength` (rad/m).

use super::positive;
use crate::error::{CaseError, CaseResult};
use crate::halfspace::model::{
    Body, GeneratedRoughness, MeasuredRoughness, Roughness, Shape, Window,
};
use crate::halfspace::schema::{RawSurface, RoughMethod, TopographyFormat};
use crate::topography::{self, ReadOptions};
use std::f64::consts::PI;
use std::path::Path;
use tribo::surface::generate::{plateau, GenerateParams, Method};
use tribo::surface::{Normalization, PowerSpectrum};

/// A generated rough surface's keys: the spectrum (Hurst exponent, the three wavelengths,
/// anisotropy), the level (exactly one of `rms_height` and `rms_slope`), the method, the seed.
/// The checks against the grid (Nyquist, period) are in [`check_against_grid`].
pub(super) fn generated(field: &str, s: &RawSurface) -> CaseResult<GeneratedRoughness> {
    let key = |k: &str| format!("{field}.{k}");
    let hurst = s.hurst.as_ref().ok_or_else(|| {
        CaseError::field(
            key("hurst"),
            "(missing)",
            "required: the Hurst exponent H in (0, 1]",
        )
    })?;
    let h = hurst.si();
    if !(h > 0.0 && h <= 1.0) {
        return Err(CaseError::field(
            key("hurst"),
            hurst,
            "the Hurst exponent must be in (0, 1]",
        ));
    }
    let wavelength = |k: &str, v: &Option<super::super::schema::Metres>, what: &str| {
        let q = v.as_ref().ok_or_else(|| {
            CaseError::field(key(k), "(missing)", format!("required: {what} (m)"))
        })?;
        positive(&key(k), q, what)
    };
    let short = wavelength(
        "short_wavelength",
        &s.short_wavelength,
        "the short cutoff wavelength lambda_s",
    )?;
    let long = wavelength(
        "long_wavelength",
        &s.long_wavelength,
        "the longest wavelength of the power law lambda_r",
    )?;
    if long <= short {
        return Err(CaseError::field(
            key("long_wavelength"),
            long,
            format!("must be longer than short_wavelength ({short:e} m)"),
        ));
    }
    let rolloff = match &s.rolloff_wavelength {
        None => long,
        Some(v) => {
            let l = positive(&key("rolloff_wavelength"), v, "the roll-off wavelength")?;
            if l < long {
                return Err(CaseError::field(
                    key("rolloff_wavelength"),
                    v,
                    format!(
                        "must be at least long_wavelength ({long:e} m): the plateau lies at \
                         wavelengths longer than the power law"
                    ),
                ));
            }
            l
        }
    };
    let anisotropy = match &s.anisotropy {
        None => [1.0, 1.0],
        Some(p) => {
            let a = [p.items[0].si(), p.items[1].si()];
            for (k, v) in a.iter().enumerate() {
                if !(v.is_finite() && *v > 0.0) {
                    return Err(CaseError::field(
                        p.item_key(&key("anisotropy"), k),
                        v,
                        "the wavevector scale factors must be finite and > 0",
                    ));
                }
            }
            a
        }
    };
    let normalization = match (&s.rms_height, &s.rms_slope) {
        (Some(r), None) => {
            Normalization::RmsHeight(positive(&key("rms_height"), r, "the rms height (m)")?)
        }
        (None, Some(r)) => {
            let x = r.si();
            if !(x.is_finite() && x > 0.0) {
                return Err(CaseError::field(
                    key("rms_slope"),
                    r,
                    "the rms slope must be finite and > 0",
                ));
            }
            if x > crate::rough::MAX_RMS_SLOPE {
                return Err(CaseError::field(
                    key("rms_slope"),
                    r,
                    format!(
                        "the rms slope must be at most {} (45 degrees): the half-space theory \
                         assumes small slopes",
                        crate::rough::MAX_RMS_SLOPE
                    ),
                ));
            }
            Normalization::RmsSlope(x)
        }
        (Some(r), Some(_)) => {
            return Err(CaseError::field(
                key("rms_height"),
                r,
                "give exactly one of rms_height (m) and rms_slope, not both",
            ))
        }
        (None, None) => {
            return Err(CaseError::field(
                key("rms_height"),
                "(missing)",
                "give the level: exactly one of rms_height (m) and rms_slope",
            ))
        }
    };
    let spectrum = PowerSpectrum {
        rolloff: 2.0 * PI / rolloff,
        powerlaw_start: 2.0 * PI / long,
        cutoff: 2.0 * PI / short,
        hurst: h,
        anisotropy,
    }
    .validated()
    .map_err(|e| CaseError::field(key("hurst"), h, super::strip_field(&e.to_string())))?;
    let method = match s.method.as_ref().map(|m| m.value) {
        None | Some(RoughMethod::FilteredNoise) => Method::FilteredNoise,
        Some(RoughMethod::RandomPhase) => Method::RandomPhase,
    };
    Ok(GeneratedRoughness {
        spectrum,
        normalization,
        method,
        seed: s.seed.as_ref().map_or(0, |c| c.n as u64),
    })
}

/// A measured surface's keys: the file (its format by the extension or `format`), the
/// spacing for formats without one, the scale on the heights, the detrending, and whether
/// the map is one period of a periodic surface.
pub(super) fn measured(
    field: &str,
    s: RawSurface,
    base_dir: &Path,
) -> CaseResult<MeasuredRoughness> {
    let key = |k: &str| format!("{field}.{k}");
    let file = s.file.clone().ok_or_else(|| {
        CaseError::field(
            key("file"),
            "(missing)",
            "required: the measured topography (.x3p, .npy, or an ASCII grid .csv/.txt/.asc/.dat)",
        )
    })?;
    let spacing = match &s.spacing {
        None => None,
        Some(p) => {
            let sp = [p.items[0].si(), p.items[1].si()];
            for (k, d) in sp.iter().enumerate() {
                if !(d.is_finite() && *d > 0.0) {
                    return Err(CaseError::field(
                        p.item_key(&key("spacing"), k),
                        d,
                        "the spacing must be finite and > 0 (m)",
                    ));
                }
                crate::units::check_length(
                    &p.item_key(&key("spacing"), k),
                    p.items[k].written(),
                    *d,
                )?;
            }
            Some((sp[0], sp[1]))
        }
    };
    let scale = match &s.scale {
        None => 1.0,
        Some(v) => {
            let x = v.si();
            if !(x.is_finite() && x > 0.0) {
                return Err(CaseError::field(key("scale"), v, "must be finite and > 0"));
            }
            x
        }
    };
    let options = ReadOptions {
        spacing,
        ..ReadOptions::default()
    };
    let path = base_dir.join(&file);
    let read = match s.format.as_ref().map(|f| f.value) {
        None => topography::read(&path, &options),
        Some(TopographyFormat::X3p) => topography::x3p::read(&path, &options),
        Some(TopographyFormat::Ascii) => topography::ascii::read(&path, &options),
        Some(TopographyFormat::Npy) => topography::npy::read(&path, &options),
    };
    let t = read
        .and_then(topography::Measured::into_topography)
        .map_err(|e| e.into_case_error(&key("file")))?;
    // The file's own spacing (a header, X3P's increments) and the map's size are lengths of
    // the geometry too.
    let (dx, dy) = t.spacing();
    let size = [t.nx() as f64 * dx, t.ny() as f64 * dy];
    let [lo, hi] = crate::units::LENGTH_RANGE;
    if !((lo..=hi).contains(&dx) && (lo..=hi).contains(&dy) && size[0] <= hi && size[1] <= hi) {
        let (k, v) = match &s.spacing {
            Some(_) => (key("spacing"), format!("[{dx:e}, {dy:e}]")),
            None => (key("file"), path.display().to_string()),
        };
        return Err(CaseError::field(
            k,
            v,
            format!(
                "the map's spacing ({dx:e}, {dy:e}) m and size ({:e} x {:e}) m must lie within \
                 [{lo:e}, {hi:e}] m, the range of the lengths of the geometry",
                size[0], size[1]
            ),
        ));
    }
    let detrend = match &s.detrend {
        None => Some(1),
        Some(d) => d.degree,
    };
    let t = match detrend {
        None => t,
        Some(degree) => {
            tribo::surface::detrend::detrend_polynomial(&t, degree)
                .map_err(|e| {
                    let written = s
                        .detrend
                        .as_ref()
                        .map_or("\"plane\"".to_string(), |d| d.written.clone());
                    CaseError::field(key("detrend"), written, super::strip_field(&e.to_string()))
                })?
                .residual
        }
    };
    Ok(MeasuredRoughness {
        topography: t.scaled(scale),
        file,
        detrend,
        periodic: s.periodic.as_ref().is_some_and(|p| p.on),
    })
}

/// The window's size (m) of a validated grid: the period of a periodic grid.
fn window_size(window: Window) -> Option<[f64; 2]> {
    match window {
        Window::HalfWidth(hw) => Some([2.0 * hw[0], 2.0 * hw[1]]),
        Window::Extent(_) => None,
    }
}

/// The rules between the surfaces and the grid: a generated surface's band must lie on the
/// grid (short wavelength at least two elements, the Nyquist wavelength; roll-off no longer
/// than the window); a measured map must cover a non-periodic window, and on a periodic grid
/// be declared periodic with its size the period; a periodic grid takes flat bodies only.
pub(super) fn check_against_grid(
    bodies: [(&str, &Body); 2],
    n: [usize; 2],
    window: Window,
    periodic: bool,
) -> CaseResult<()> {
    let Some(size) = window_size(window) else {
        return Ok(());
    };
    let element = [size[0] / n[0] as f64, size[1] / n[1] as f64];
    for (name, body) in bodies {
        let field = body.roughness_table(name);
        if periodic {
            let flat = match &body.shape {
                Shape::Radii { radii, .. } => radii.iter().all(|r| r.is_infinite()),
                Shape::Surface(_) => false,
            };
            if !flat {
                let key = match body.shape {
                    Shape::Radii { .. } => format!("{name}.radii"),
                    Shape::Surface(_) => format!("{name}.surface.kind"),
                };
                return Err(CaseError::field(
                    key,
                    "(a curved body)",
                    "a periodic grid repeats the window: both bodies must be flat (radii = \
                     [\"inf\", \"inf\"], or a rough or measured surface without radii)",
                ));
            }
        }
        match &body.roughness {
            None => {}
            Some(Roughness::Generated(g)) => {
                let short = 2.0 * PI / g.spectrum.cutoff;
                let nyquist = 2.0 * element[0].max(element[1]);
                if short < nyquist * (1.0 - 1e-9) {
                    return Err(CaseError::field(
                        format!("{field}.short_wavelength"),
                        short,
                        format!(
                            "must be at least two elements of the grid (its Nyquist wavelength \
                             {nyquist:e} m): shorter wavelengths cannot be drawn on it; refine \
                             grid.n or lengthen the cutoff"
                        ),
                    ));
                }
                let rolloff = 2.0 * PI / g.spectrum.rolloff;
                let shortest_side = size[0].min(size[1]);
                if rolloff > shortest_side * (1.0 + 1e-9) {
                    let k = if g.spectrum.rolloff == g.spectrum.powerlaw_start {
                        "long_wavelength"
                    } else {
                        "rolloff_wavelength"
                    };
                    return Err(CaseError::field(
                        format!("{field}.{k}"),
                        rolloff,
                        format!(
                            "must not exceed the window {} ({shortest_side:e} m): the surface \
                             is drawn with the window as its period",
                            if periodic { "period" } else { "size" }
                        ),
                    ));
                }
                let params = GenerateParams {
                    nx: n[0],
                    ny: n[1],
                    periods: (size[0], size[1]),
                    spectrum: g.spectrum,
                    normalization: g.normalization,
                    method: g.method,
                    seed: g.seed,
                };
                plateau(&params).map_err(|e| {
                    // The anisotropy scales the band's wavevectors: where it is given, it is
                    // what moved the band off the grid.
                    let a = g.spectrum.anisotropy;
                    let (k, v) = if a == [1.0, 1.0] {
                        ("short_wavelength", short.to_string())
                    } else {
                        ("anisotropy", format!("[{}, {}]", a[0], a[1]))
                    };
                    CaseError::field(
                        format!("{field}.{k}"),
                        v,
                        super::strip_field(&e.to_string()),
                    )
                })?;
            }
            Some(Roughness::Measured(m)) => {
                let t = &m.topography;
                if periodic {
                    if !m.periodic {
                        return Err(CaseError::field(
                            "grid.periodic",
                            "true",
                            format!(
                                "a measured map is not periodic: set {field}.periodic = true to \
                                 take it as one period (its size becomes the period), or run \
                                 it on a non-periodic window (grid.half_width)"
                            ),
                        ));
                    }
                    let (px, py) = t.periods();
                    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs());
                    if !(close(px, size[0]) && close(py, size[1])) {
                        return Err(CaseError::field(
                            "grid.period",
                            format!("[{}, {}]", size[0], size[1]),
                            format!(
                                "must be the size of the measured map of {name}, \
                                 [{px:e}, {py:e}] m (points times spacing): the map is one \
                                 period; leave grid.period out to take it"
                            ),
                        ));
                    }
                } else {
                    if m.periodic {
                        return Err(CaseError::field(
                            format!("{field}.periodic"),
                            "true",
                            "applies to periodic grids ([grid] periodic = true) only",
                        ));
                    }
                    let (dx, dy) = t.spacing();
                    let (mx, my) = (
                        0.5 * (t.nx() - 1) as f64 * dx,
                        0.5 * (t.ny() - 1) as f64 * dy,
                    );
                    let hw = [0.5 * size[0], 0.5 * size[1]];
                    if hw[0] > mx * (1.0 + 1e-12) || hw[1] > my * (1.0 + 1e-12) {
                        return Err(CaseError::field(
                            "grid.half_width",
                            format!("[{}, {}]", hw[0], hw[1]),
                            format!(
                                "the window must lie within the measured map of {name}, which \
                                 covers |x| <= {mx:e} m, |y| <= {my:e} m about its centre"
                            ),
                        ));
                    }
                }
            }
        }
    }
    Ok(())
}

/// The period of a periodic grid when `grid.period` is not given: the size of a measured map
/// (body 1's first; one not declared periodic is then refused by [`check_against_grid`],
/// naming the key that declares it), m.
pub(super) fn default_period(bodies: [&Body; 2]) -> Option<[f64; 2]> {
    bodies.iter().find_map(|b| match &b.roughness {
        Some(Roughness::Measured(m)) => {
            let (px, py) = m.topography.periods();
            Some([px, py])
        }
        _ => None,
    })
}
