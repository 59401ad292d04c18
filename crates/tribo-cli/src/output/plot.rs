//! PNG plots with plotters, rendered with the DejaVu Sans font shipped in `assets/` (no
//! system fonts needed).

use super::canvas::Canvas;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::FontStyle;
use std::path::Path;
use std::sync::OnceLock;
use tribo::kernels::hertz::HertzContact;
use tribo::SurfaceGrid;

/// DejaVu Sans (Bitstream Vera licence, see `assets/LICENSE-DejaVu.txt`).
pub(crate) static FONT_BYTES: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// The font family name the plots use.
pub(crate) const FAMILY: &str = "sans-serif";

/// Register the shipped font as `sans-serif` (once per process).
pub fn register_font() -> Result<(), String> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    DONE.get_or_init(|| {
        plotters::style::register_font(FAMILY, FontStyle::Normal, FONT_BYTES)
            .map_err(|_| "the shipped font DejaVuSans.ttf could not be loaded".to_string())
    })
    .clone()
}

pub(crate) fn e<E: std::fmt::Display>(err: E) -> String {
    err.to_string()
}

/// Axis tick labels: rounded to 1e-6 of the unit, without a "-0".
pub(crate) fn tick(v: &f64) -> String {
    let r = (v * 1e6).round() / 1e6;
    if r == 0.0 {
        "0".into()
    } else {
        format!("{r}")
    }
}

/// Draws the axes of a line chart: descriptions, plain tick labels ([`tick`]), labels at
/// font size `size` and descriptions at `size + 2`, no minor grid lines.
pub(crate) fn styled_axes<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    x_desc: &str,
    y_desc: &str,
    size: u32,
) -> Result<(), String> {
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(&tick)
        .y_label_formatter(&tick)
        .label_style((FAMILY, size))
        .axis_desc_style((FAMILY, size + 2))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(e)
}

/// A valid axis range around data in [`lo`, `hi`], padded by `pad` times the span: a
/// degenerate range (all values equal, e.g. the shear of a frictionless contact, all 0) gets
/// +-1 about 0, or +-10 % about a non-zero value, so that the axis has ticks; non-finite
/// bounds give [-1, 1].
pub(crate) fn axis_range(lo: f64, hi: f64, pad: f64) -> (f64, f64) {
    if !(lo.is_finite() && hi.is_finite()) || hi < lo {
        return (-1.0, 1.0);
    }
    let scale = lo.abs().max(hi.abs());
    let span = hi - lo;
    if scale < 1e-300 {
        (-1.0, 1.0)
    } else if span <= 1e-9 * scale {
        (lo - 0.1 * scale, hi + 0.1 * scale)
    } else {
        (lo - pad * span, hi + pad * span)
    }
}

/// Tick values for a logarithmic axis over [`lo`, `hi`] (> 0): powers of ten, or, where
/// those give fewer than 3 ticks, 1-2-5, then 1, 1.5, 2, 2.5, 3, 4, 5, 6, 8 times powers of
/// ten, and for a narrower range evenly spaced round values (1, 2, 2.5 or 5 times a power
/// of ten apart): a range of less than a decade still has 3 or more labelled ticks.
pub(crate) fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    if !(lo > 0.0 && hi > lo && lo.is_finite() && hi.is_finite()) {
        return Vec::new();
    }
    let sets: [&[f64]; 3] = [
        &[1.0],
        &[1.0, 2.0, 5.0],
        &[1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0],
    ];
    for m in sets {
        let mut t = Vec::new();
        let mut p = 10f64.powf(lo.log10().floor());
        while p <= hi {
            for &k in m {
                let v = k * p;
                if v >= lo * (1.0 - 1e-12) && v <= hi * (1.0 + 1e-12) {
                    t.push(v);
                }
            }
            p *= 10.0;
        }
        if t.len() >= 3 {
            if t.len() > 14 {
                // Many decades: every decade, or every k-th.
                let k = t.len().div_ceil(10);
                return t.into_iter().step_by(k).collect();
            }
            return t;
        }
    }
    linear_ticks(lo, hi)
}

/// 3 to 11 evenly spaced round values in [`lo`, `hi`] (`hi` > `lo`): 1, 2, 2.5 or 5 times a
/// power of ten apart.
pub(crate) fn linear_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let span = hi - lo;
    let p = 10f64.powf((span / 4.0).log10().floor());
    for m in [5.0, 2.5, 2.0, 1.0, 0.5] {
        let step = m * p;
        let first = (lo / step).ceil();
        let last = (hi / step).floor();
        if last - first >= 2.0 {
            return (first as i64..=last as i64)
                .map(|k| {
                    // Rounded to the step's digits, so that labels read 0.8, not 0.8000000001.
                    let v = k as f64 * step;
                    let d = 10f64.powi(-(step.log10().floor() as i32) + 3);
                    (v * d).round() / d
                })
                .collect();
        }
    }
    vec![lo, 0.5 * (lo + hi), hi]
}

/// A tick label with 4 significant digits: plain between 1e-3 and 1e5, else 1.234e-7.
pub(crate) fn sig(v: &f64) -> String {
    let a = v.abs();
    if a == 0.0 || !a.is_finite() {
        return tick(v);
    }
    if (1e-3..1e5).contains(&a) {
        let digits = (3 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{v:.digits$}");
        let s = if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        };
        if s == "-0" {
            "0".into()
        } else {
            s
        }
    } else {
        format!("{v:.3e}")
    }
}

/// The font size (px) at which `text` fits in `width` px (less 20 px of border), at most
/// `nominal` and at least 9: long titles (a case title is the user's) shrink instead of
/// running off both sides of the image.
pub(crate) fn title_size(text: &str, nominal: f64, width: u32) -> f64 {
    let avail = (width as f64 - 20.0).max(1.0);
    match super::canvas::layout(text, nominal) {
        Some(l) if l.width as f64 > avail => (nominal * avail / l.width as f64).max(9.0),
        _ => nominal,
    }
}

/// Ranges for a map of physical space with the same metres per pixel along both axes: the
/// data ranges `x` and `y` (m or mm) drawn on a plotting area of `px` = (width, height)
/// pixels. The range that is short for its side is widened about its centre; the other is
/// kept, so all the data stays in view and a circle is drawn as a circle.
pub fn equal_aspect(x: (f64, f64), y: (f64, f64), px: (u32, u32)) -> ((f64, f64), (f64, f64)) {
    let (w, h) = (px.0.max(1) as f64, px.1.max(1) as f64);
    let (sx, sy) = ((x.1 - x.0).abs(), (y.1 - y.0).abs());
    if !(sx > 0.0 && sy > 0.0 && sx.is_finite() && sy.is_finite()) {
        return (x, y);
    }
    let per_px = (sx / w).max(sy / h);
    let widen = |r: (f64, f64), n: f64| {
        let c = 0.5 * (r.0 + r.1);
        (c - 0.5 * per_px * n, c + 0.5 * per_px * n)
    };
    (widen(x, w), widen(y, h))
}

/// Height (px) of an image whose map of `x` by `y` (data ranges) fills a plotting area
/// `plot_w` px wide at equal scale, with `extra` px of caption, labels and margins; clamped to
/// [`min`, `max`] (the ranges are then widened by [`equal_aspect`]).
pub(crate) fn map_height(
    x: (f64, f64),
    y: (f64, f64),
    plot_w: u32,
    extra: u32,
    (min, max): (u32, u32),
) -> u32 {
    let r = ((y.1 - y.0) / (x.1 - x.0)).abs();
    let h = if r.is_finite() {
        plot_w as f64 * r + extra as f64
    } else {
        max as f64
    };
    h.clamp(min as f64, max as f64).round() as u32
}

/// A chart with f64 axes on the [`Canvas`] (maps and line plots).
pub(crate) type MapChart<'a, 'b> =
    ChartContext<'a, Canvas<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Axes for a map of physical space on `area` at equal scale ([`equal_aspect`]): the caption
/// (shrunk to fit, [`title_size`]), x and y labels (`y_label` formats the y ticks, e.g. the
/// depth drawn downward), ranges `x` and `y` (widened where needed).
pub(crate) fn map_chart<'a, 'b>(
    area: &'a DrawingArea<Canvas<'b>, plotters::coord::Shift>,
    x: (f64, f64),
    y: (f64, f64),
    caption: &str,
    (x_desc, y_desc): (&str, &str),
    y_label: &dyn Fn(&f64) -> String,
) -> Result<MapChart<'a, 'b>, String> {
    let (w, _) = area.dim_in_pixel();
    let size = title_size(caption, 20.0, w);
    let inner = area
        .margin(8, 15, 15, 15)
        .titled(caption, (FAMILY, size))
        .map_err(e)?;
    let (iw, ih) = inner.dim_in_pixel();
    let (xl, yl) = (50u32, 70u32);
    let (xr, yr) = equal_aspect(x, y, (iw.saturating_sub(yl), ih.saturating_sub(xl)));
    let mut chart = ChartBuilder::on(&inner)
        .x_label_area_size(xl)
        .y_label_area_size(yl)
        .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
        .map_err(e)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(&tick)
        .y_label_formatter(y_label)
        .label_style((FAMILY, 15))
        .axis_desc_style((FAMILY, 17))
        .draw()
        .map_err(e)?;
    Ok(chart)
}

/// The corner of a plot whose legend box, `frac` = (width, height) as fractions of the
/// plotting area, covers the fewest of `points` (data coordinates, ranges `x`, `y`); ties in
/// the order upper right, upper left, lower right, lower left. With `frac` from the legend's
/// size in pixels this puts the legend over the emptiest part of the plot.
pub(crate) fn emptiest_corner(
    points: &[(f64, f64)],
    x: (f64, f64),
    y: (f64, f64),
    frac: (f64, f64),
) -> (SeriesLabelPosition, usize) {
    let (fw, fh) = (frac.0.clamp(0.0, 1.0), frac.1.clamp(0.0, 1.0));
    let count = |right: bool, upper: bool| {
        points
            .iter()
            .filter(|p| {
                let u = (p.0 - x.0) / (x.1 - x.0);
                let v = (p.1 - y.0) / (y.1 - y.0);
                let inx = if right { u >= 1.0 - fw } else { u <= fw };
                let iny = if upper { v >= 1.0 - fh } else { v <= fh };
                inx && iny && (0.0..=1.0).contains(&u) && (0.0..=1.0).contains(&v)
            })
            .count()
    };
    [
        (SeriesLabelPosition::UpperRight, count(true, true)),
        (SeriesLabelPosition::UpperLeft, count(false, true)),
        (SeriesLabelPosition::LowerRight, count(true, false)),
        (SeriesLabelPosition::LowerLeft, count(false, false)),
    ]
    .into_iter()
    .enumerate()
    .min_by_key(|(k, (_, n))| (*n, *k))
    .map(|(_, c)| c)
    .unwrap_or((SeriesLabelPosition::UpperRight, 0))
}

/// The legend's box as fractions of a plotting area of `px` pixels: labels at `size` px, one
/// row each, a 20 px sample and margins (plotters' legend layout).
pub(crate) fn legend_frac(labels: &[&str], size: f64, px: (u32, u32)) -> (f64, f64) {
    let wmax = labels
        .iter()
        .filter_map(|l| super::canvas::layout(l, size))
        .map(|l| l.width as f64)
        .fold(0.0, f64::max);
    let w = wmax + 50.0;
    let h = labels.len() as f64 * (size + 8.0) + 16.0;
    (w / px.0.max(1) as f64, h / px.1.max(1) as f64)
}

/// Points along `f` sampled densely enough to stand for a curve in [`emptiest_corner`].
pub(crate) fn densify(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(points.len() * 8);
    for w in points.windows(2) {
        for k in 0..8 {
            let t = k as f64 / 8.0;
            out.push((
                w[0].0 + t * (w[1].0 - w[0].0),
                w[0].1 + t * (w[1].1 - w[0].1),
            ));
        }
    }
    out.extend(points.last());
    out
}

/// Blue-white-red for signed values, `t` in [-1, 1] (white at 0, the neutral colour).
pub fn diverging(t: f64) -> RGBColor {
    let t = if t.is_finite() {
        t.clamp(-1.0, 1.0)
    } else {
        0.0
    };
    let lerp = |a: f64, b: f64, s: f64| (a + s * (b - a)).round() as u8;
    if t < 0.0 {
        let s = -t;
        RGBColor(
            lerp(255.0, 33.0, s),
            lerp(255.0, 102.0, s),
            lerp(255.0, 172.0, s),
        )
    } else {
        RGBColor(
            lerp(255.0, 178.0, t),
            lerp(255.0, 24.0, t),
            lerp(255.0, 43.0, t),
        )
    }
}

/// How a section colours its values.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SectionScale {
    /// Viridis from the smallest to the largest value (von Mises, >= 0).
    Sequential,
    /// Signed values (stress components): blue-white-red symmetric about 0, so that 0 is
    /// white wherever it lies in the data's range.
    Signed,
    /// psi: viridis, with the isoline psi = 1 (the edge of the dangerous region) drawn.
    Damage,
}

/// The colour range of a section's values in [`lo`, `hi`] on `scale`: symmetric about 0 for
/// [`SectionScale::Signed`], a valid range where all values are equal.
pub(crate) fn colour_range(lo: f64, hi: f64, scale: SectionScale) -> (f64, f64) {
    match scale {
        SectionScale::Signed => {
            let m = lo.abs().max(hi.abs());
            if m.is_finite() && m > 0.0 {
                (-m, m)
            } else {
                (-1.0, 1.0)
            }
        }
        _ => {
            if hi > lo {
                (lo, hi)
            } else {
                axis_range(lo, hi, 0.0)
            }
        }
    }
}

/// The colour of `v` on `scale` over the colour range (`c0`, `c1`) of [`colour_range`].
pub(crate) fn section_colour(v: f64, (c0, c1): (f64, f64), scale: SectionScale) -> RGBColor {
    match scale {
        SectionScale::Signed => diverging(v / c1),
        _ => viridis((v - c0) / (c1 - c0)),
    }
}

/// The isoline `values = level` of values on a regular grid (`values[iv * nh + ih]` at
/// (`h[ih]`, `v[iv]`)), as segments, by marching squares on the bilinear cells (linear along
/// the edges; a saddle cell pairs its crossings by the value at the centre).
pub fn isoline_grid(
    h: &[f64],
    v: &[f64],
    values: &[f64],
    level: f64,
) -> Vec<((f64, f64), (f64, f64))> {
    let (nh, nv) = (h.len(), v.len());
    let mut out = Vec::new();
    if nh < 2 || nv < 2 || values.len() != nh * nv {
        return out;
    }
    for iv in 0..nv - 1 {
        for ih in 0..nh - 1 {
            // Corners counter-clockwise: (ih, iv), (ih+1, iv), (ih+1, iv+1), (ih, iv+1).
            let c = [
                (h[ih], v[iv], values[iv * nh + ih]),
                (h[ih + 1], v[iv], values[iv * nh + ih + 1]),
                (h[ih + 1], v[iv + 1], values[(iv + 1) * nh + ih + 1]),
                (h[ih], v[iv + 1], values[(iv + 1) * nh + ih]),
            ];
            if c.iter().any(|p| !p.2.is_finite()) {
                continue;
            }
            let mut cross = Vec::with_capacity(4);
            for k in 0..4 {
                let (a, b) = (c[k], c[(k + 1) % 4]);
                if (a.2 >= level) != (b.2 >= level) {
                    let t = (level - a.2) / (b.2 - a.2);
                    cross.push((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
                }
            }
            match cross.len() {
                2 => out.push((cross[0], cross[1])),
                4 => {
                    let centre = 0.25 * c.iter().map(|p| p.2).sum::<f64>();
                    // Corner 0 inside with the centre: join across corners 1 and 3.
                    if (centre >= level) == (c[0].2 >= level) {
                        out.push((cross[0], cross[1]));
                        out.push((cross[2], cross[3]));
                    } else {
                        out.push((cross[3], cross[0]));
                        out.push((cross[1], cross[2]));
                    }
                }
                _ => {}
            }
        }
    }
    out
}

/// Viridis colour map (matplotlib's, 9 anchors, linear in between), `t` in [0, 1].
pub fn viridis(t: f64) -> RGBColor {
    const C: [(u8, u8, u8); 9] = [
        (68, 1, 84),
        (71, 44, 122),
        (59, 81, 139),
        (44, 113, 142),
        (33, 144, 141),
        (39, 173, 129),
        (92, 200, 99),
        (170, 220, 50),
        (253, 231, 37),
    ];
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let f = t * (C.len() - 1) as f64;
    let i = (f.floor() as usize).min(C.len() - 2);
    let s = f - i as f64;
    let lerp = |a: u8, b: u8| (a as f64 + s * (b as f64 - a as f64)).round() as u8;
    RGBColor(
        lerp(C[i].0, C[i + 1].0),
        lerp(C[i].1, C[i + 1].1),
        lerp(C[i].2, C[i + 1].2),
    )
}

fn ellipse_mm(h: &HertzContact) -> Vec<(f64, f64)> {
    let (s, c) = h.angle.sin_cos();
    (0..=360)
        .map(|k| {
            let t = (k as f64).to_radians();
            let (xp, yp) = (h.semi_major * t.cos(), h.semi_minor * t.sin());
            (1e3 * (c * xp - s * yp), 1e3 * (s * xp + c * yp))
        })
        .collect()
}

/// Colour map of the pressure over the window (axes in mm, colour bar in GPa), with the Hertz
/// contact ellipse drawn over it where given.
pub fn pressure_map(
    path: &Path,
    grid: &SurfaceGrid,
    pressure: &[f64],
    hertz: Option<&HertzContact>,
    title: &str,
) -> Result<(), String> {
    register_font()?;
    let (hx, hy) = grid.half_widths();
    let (hx, hy) = (1e3 * hx, 1e3 * hy);
    let height = map_height((-hx, hx), (-hy, hy), 760, 115, (300, 1000));
    let root = Canvas::new(path, (1040, height)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let (main, bar) = root.split_horizontally(860);
    let pmax = pressure.iter().cloned().fold(0.0, f64::max);
    let pmax_gpa = if pmax > 0.0 { pmax / 1e9 } else { 1.0 };
    let mut chart = map_chart(
        &main,
        (-hx, hx),
        (-hy, hy),
        &format!("Contact pressure: {title}"),
        ("x, mm", "y, mm"),
        &tick,
    )?;
    let (dx, dy) = (1e3 * grid.dx(), 1e3 * grid.dy());
    chart
        .draw_series((0..grid.ny()).flat_map(|iy| {
            (0..grid.nx()).map(move |ix| {
                let (x, y) = (1e3 * grid.x(ix), 1e3 * grid.y(iy));
                let p = pressure[grid.index(ix, iy)] / 1e9;
                Rectangle::new(
                    [(x - 0.5 * dx, y - 0.5 * dy), (x + 0.5 * dx, y + 0.5 * dy)],
                    viridis(p / pmax_gpa).filled(),
                )
            })
        }))
        .map_err(e)?;
    if let Some(h) = hertz {
        chart
            .draw_series(LineSeries::new(ellipse_mm(h), RED.stroke_width(2)))
            .map_err(e)?
            .label("Hertz contact ellipse")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED.stroke_width(2)));
        let ellipse = ellipse_mm(h);
        legend_avoiding(&mut chart, &ellipse, &["Hertz contact ellipse"])?;
    }
    let mut cb = ChartBuilder::on(&bar)
        .margin_top(50)
        .margin_bottom(65)
        .margin_left(10)
        .margin_right(25)
        .right_y_label_area_size(80)
        .build_cartesian_2d(0.0..1.0, 0.0..pmax_gpa)
        .map_err(e)?;
    cb.configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_desc("p, GPa")
        .y_label_formatter(&tick)
        .label_style((FAMILY, 15))
        .axis_desc_style((FAMILY, 17))
        .draw()
        .map_err(e)?;
    let levels = 256;
    cb.draw_series((0..levels).map(|k| {
        let (v0, v1) = (k as f64 / levels as f64, (k + 1) as f64 / levels as f64);
        Rectangle::new(
            [(0.0, v0 * pmax_gpa), (1.0, v1 * pmax_gpa)],
            viridis(0.5 * (v0 + v1)).filled(),
        )
    }))
    .map_err(e)?;
    root.present().map_err(e)?;
    Ok(())
}

/// Pressure along x through the row nearest y = 0 and along y through the column nearest
/// x = 0: numerical values at element centres (markers) against Hertz on the same line
/// (curve), where given.
pub fn pressure_profiles(
    path: &Path,
    grid: &SurfaceGrid,
    pressure: &[f64],
    hertz: Option<&HertzContact>,
    title: &str,
) -> Result<(), String> {
    let pmax = pressure.iter().cloned().fold(0.0, f64::max);
    let p0 = hertz.map_or(0.0, |h| h.max_pressure);
    let top = pmax.max(p0);
    let top = if top > 0.0 { 1.1 * top / 1e9 } else { 1.0 };
    let hertz_pressure = hertz.map(|h| move |x: f64, y: f64| h.pressure(x, y));
    let reference: Option<Reference<'_>> = hertz_pressure
        .as_ref()
        .map(|f| (f as &dyn Fn(f64, f64) -> f64, "Hertz"));
    profiles(
        path,
        grid,
        pressure,
        reference,
        &format!("Pressure profiles: {title}"),
        "p, GPa",
        (0.0, top),
    )
}

/// A field along x through the row nearest y = 0 and along y through the column nearest
/// x = 0 (two panels): element-centre values (markers, GPa) against a reference curve.
fn profiles(
    path: &Path,
    grid: &SurfaceGrid,
    field: &[f64],
    reference: Option<Reference<'_>>,
    title: &str,
    y_desc: &str,
    y_range: (f64, f64),
) -> Result<(), String> {
    register_font()?;
    let root = Canvas::new(path, (1200, 560)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let root = root
        .titled(title, (FAMILY, title_size(title, 20.0, 1200)))
        .map_err(e)?;
    let panels = root.split_evenly((1, 2));
    let nearest = |n: usize, c: &dyn Fn(usize) -> f64| {
        (0..n)
            .min_by(|&a, &b| c(a).abs().total_cmp(&c(b).abs()))
            .unwrap_or(0)
    };
    let iy0 = nearest(grid.ny(), &|i| grid.y(i));
    let ix0 = nearest(grid.nx(), &|i| grid.x(i));
    for (k, panel) in panels.iter().enumerate() {
        let along_x = k == 0;
        let (n, half, fixed) = if along_x {
            (grid.nx(), grid.half_widths().0, grid.y(iy0))
        } else {
            (grid.ny(), grid.half_widths().1, grid.x(ix0))
        };
        let half_mm = 1e3 * half;
        let (axis, other) = if along_x { ("x", "y") } else { ("y", "x") };
        let mut chart = ChartBuilder::on(panel)
            .caption(
                format!("along {axis} at {other} = {:.4} mm", 1e3 * fixed),
                (FAMILY, 17),
            )
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(60)
            .build_cartesian_2d(-half_mm..half_mm, y_range.0..y_range.1)
            .map_err(e)?;
        styled_axes(&mut chart, &format!("{axis}, mm"), y_desc, 14)?;
        let mut occupied = Vec::new();
        let mut labels = Vec::new();
        if let Some((f, label)) = reference {
            let samples = 600;
            let curve: Vec<(f64, f64)> = (0..=samples)
                .map(|s| {
                    let t = -half + 2.0 * half * s as f64 / samples as f64;
                    let v = if along_x { f(t, fixed) } else { f(fixed, t) };
                    (1e3 * t, v / 1e9)
                })
                .collect();
            occupied.extend(curve.iter().copied());
            labels.push(label);
            chart
                .draw_series(LineSeries::new(curve, BLUE.stroke_width(2)))
                .map_err(e)?
                .label(label.to_string())
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE.stroke_width(2)));
        }
        let points: Vec<(f64, f64)> = (0..n)
            .map(|i| {
                let (t, idx) = if along_x {
                    (grid.x(i), grid.index(i, iy0))
                } else {
                    (grid.y(i), grid.index(ix0, i))
                };
                (1e3 * t, field[idx] / 1e9)
            })
            .collect();
        chart
            .draw_series(
                points
                    .iter()
                    .map(|&(x, v)| Circle::new((x, v), 4, RED.filled())),
            )
            .map_err(e)?
            .label("tribo (element centres)")
            .legend(|(x, y)| Circle::new((x + 10, y), 4, RED.filled()));
        occupied.extend(densify(&points));
        labels.push("tribo (element centres)");
        legend_avoiding(&mut chart, &occupied, &labels)?;
    }
    root.present().map_err(e)?;
    Ok(())
}

/// The back effect of bulk loading, like the paper's Fig. 2a: F_N / F_N(0) against
/// sigma_a / sigma_a,max, numerical points (markers) and the Hertz estimate (curves) for each
/// load kind.
pub fn back_effect(
    path: &Path,
    series: &[super::back_effect::Series],
    title: &str,
) -> Result<(), String> {
    register_font()?;
    let root = Canvas::new(path, (960, 720)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let all = series
        .iter()
        .flat_map(|s| s.points.iter().chain(&s.hertz))
        .map(|p| p.1)
        .filter(|v| v.is_finite());
    let (lo, hi) = all.fold((1.0f64, 1.0f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
    let pad = 0.06 * (hi - lo).max(0.1);
    let (lo, hi) = ((lo - pad).max(0.0), hi + pad);
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!("Contact force vs bulk stress: {title}"),
            (
                FAMILY,
                title_size(&format!("Contact force vs bulk stress: {title}"), 20.0, 960),
            ),
        )
        .margin(20)
        .x_label_area_size(55)
        .y_label_area_size(75)
        .build_cartesian_2d(-1.08..1.08, lo..hi)
        .map_err(e)?;
    styled_axes(
        &mut chart,
        "bulk stress at the contact, sigma_a / sigma_a,max (tension > 0)",
        "contact force at fixed approach, F_N / F_N(0)",
        15,
    )?;
    chart
        .draw_series(LineSeries::new(
            [(-1.08, 1.0), (1.08, 1.0)],
            BLACK.mix(0.3).stroke_width(1),
        ))
        .map_err(e)?;
    for s in series {
        let colour = if s.name == "bending" {
            RGBColor(31, 119, 180)
        } else {
            RGBColor(214, 39, 40)
        };
        chart
            .draw_series(LineSeries::new(
                s.hertz.iter().copied(),
                colour.stroke_width(2),
            ))
            .map_err(e)?
            .label(format!("{}, Hertz (1 + u_z/delta_0)^1.5", s.name))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
            });
        if s.name == "bending" {
            chart
                .draw_series(
                    s.points
                        .iter()
                        .map(|&p| TriangleMarker::new(p, 7, colour.filled())),
                )
                .map_err(e)?
                .label(format!("{}, tribo", s.name))
                .legend(move |(x, y)| TriangleMarker::new((x + 10, y), 7, colour.filled()));
        } else {
            chart
                .draw_series(s.points.iter().map(|&p| Circle::new(p, 5, colour.filled())))
                .map_err(e)?
                .label(format!("{}, tribo", s.name))
                .legend(move |(x, y)| Circle::new((x + 10, y), 5, colour.filled()));
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FAMILY, 15))
        .draw()
        .map_err(e)?;
    root.present().map_err(e)?;
    Ok(())
}

/// One curve of [`lines`]: name, points, colour, and a dashed horizontal reference level.
pub struct Curve {
    /// Legend label.
    pub name: String,
    /// (x, y) points (markers joined by a line).
    pub points: Vec<(f64, f64)>,
    /// Colour.
    pub colour: RGBColor,
    /// A reference value drawn as a dashed horizontal line in the same colour (the paper's).
    pub reference: Option<f64>,
}

/// Curves y(x) with markers, and dashed horizontal reference levels (the paper's values):
/// the Sec. 6 changes of V_int and Psi_int against sigma_b / p0.
pub fn lines(
    path: &Path,
    curves: &[Curve],
    x_desc: &str,
    y_desc: &str,
    title: &str,
) -> Result<(), String> {
    register_font()?;
    let root = Canvas::new(path, (960, 720)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let xs = curves.iter().flat_map(|c| c.points.iter().map(|p| p.0));
    let (x0, x1) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
        (a.min(x), b.max(x))
    });
    let ys = curves
        .iter()
        .flat_map(|c| c.points.iter().map(|p| p.1).chain(c.reference));
    let (y0, y1) = ys.fold((0.0f64, 0.0f64), |(a, b), y| (a.min(y), b.max(y)));
    if !(x0.is_finite() && x1.is_finite()) {
        return Err("lines: no points".into());
    }
    let (x0, x1) = if x1 > x0 {
        (x0, x1)
    } else {
        (x0 - 1.0, x0 + 1.0)
    };
    let pad = 0.08 * (y1 - y0).max(1.0);
    // Room above the data for the legend (its height as a fraction of the ~590 px tall
    // plotting area, plus a margin), so that it covers no curve.
    let names: Vec<&str> = curves.iter().map(|c| c.name.as_str()).collect();
    let f = (legend_frac(&names, 14.0, (800, 590)).1 + 0.04).min(0.6);
    let (bottom, top) = (y0 - pad, y1 + pad);
    let top = (top - f * bottom) / (1.0 - f);
    let mut chart = ChartBuilder::on(&root)
        .caption(title, (FAMILY, title_size(title, 20.0, 960)))
        .margin(20)
        .x_label_area_size(55)
        .y_label_area_size(75)
        .build_cartesian_2d(x0..x1, bottom..top)
        .map_err(e)?;
    styled_axes(&mut chart, x_desc, y_desc, 15)?;
    chart
        .draw_series(LineSeries::new(
            [(x0, 0.0), (x1, 0.0)],
            BLACK.mix(0.3).stroke_width(1),
        ))
        .map_err(e)?;
    for c in curves {
        let colour = c.colour;
        chart
            .draw_series(LineSeries::new(
                c.points.iter().copied(),
                colour.stroke_width(2),
            ))
            .map_err(e)?
            .label(c.name.clone())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
            });
        chart
            .draw_series(c.points.iter().map(|&p| Circle::new(p, 4, colour.filled())))
            .map_err(e)?;
        if let Some(r) = c.reference {
            // Dashed: short segments.
            let n = 40;
            chart
                .draw_series((0..n).step_by(2).map(|k| {
                    let a = x0 + (x1 - x0) * k as f64 / n as f64;
                    let b = x0 + (x1 - x0) * (k + 1) as f64 / n as f64;
                    PathElement::new(vec![(a, r), (b, r)], colour.mix(0.7).stroke_width(1))
                }))
                .map_err(e)?;
        }
    }
    let mut occupied = Vec::new();
    for c in curves {
        occupied.extend(densify(&c.points));
        if let Some(r) = c.reference {
            occupied.extend((0..=40).map(|k| (x0 + (x1 - x0) * k as f64 / 40.0, r)));
        }
    }
    legend_avoiding(&mut chart, &occupied, &names)?;
    root.present().map_err(e)?;
    Ok(())
}

/// A reference curve q(x, y) (Pa) and its legend label.
pub type Reference<'a> = (&'a dyn Fn(f64, f64) -> f64, &'a str);

/// Map of the stick zone, the slip zone and the elements out of contact, with the
/// Cattaneo-Mindlin stick ellipse (the Hertz ellipse scaled by `stick_ratio` = c/a) drawn over
/// it where given.
pub fn stick_slip_map(
    path: &Path,
    grid: &SurfaceGrid,
    pressure: &[f64],
    stick: &[bool],
    hertz: Option<(&HertzContact, f64)>,
    title: &str,
) -> Result<(), String> {
    register_font()?;
    let (hx, hy) = grid.half_widths();
    let (hx, hy) = (1e3 * hx, 1e3 * hy);
    let height = map_height((-hx, hx), (-hy, hy), 815, 115, (300, 1000));
    let root = Canvas::new(path, (900, height)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let mut chart = map_chart(
        &root,
        (-hx, hx),
        (-hy, hy),
        &format!("Stick and slip: {title}"),
        ("x, mm", "y, mm"),
        &tick,
    )?;
    let (dx, dy) = (1e3 * grid.dx(), 1e3 * grid.dy());
    let stick_c = RGBColor(33, 144, 141);
    let slip_c = RGBColor(253, 174, 97);
    let none_c = RGBColor(235, 235, 235);
    chart
        .draw_series((0..grid.ny()).flat_map(|iy| {
            (0..grid.nx()).map(move |ix| {
                let (x, y) = (1e3 * grid.x(ix), 1e3 * grid.y(iy));
                let k = grid.index(ix, iy);
                let c = if stick[k] {
                    stick_c
                } else if pressure[k] > 0.0 {
                    slip_c
                } else {
                    none_c
                };
                Rectangle::new(
                    [(x - 0.5 * dx, y - 0.5 * dy), (x + 0.5 * dx, y + 0.5 * dy)],
                    c.filled(),
                )
            })
        }))
        .map_err(e)?;
    for (label, c) in [("stick", stick_c), ("slip", slip_c), ("no contact", none_c)] {
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
            .map_err(e)?
            .label(label)
            .legend(move |(x, y)| Rectangle::new([(x, y - 6), (x + 14, y + 6)], c.filled()));
    }
    if let Some((h, k)) = hertz {
        chart
            .draw_series(LineSeries::new(
                ellipse_mm(h).into_iter().map(|(x, y)| (k * x, k * y)),
                RED.stroke_width(2),
            ))
            .map_err(e)?
            .label(format!("Cattaneo-Mindlin stick ellipse, c/a = {k:.4}"))
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED.stroke_width(2)));
        chart
            .draw_series(LineSeries::new(ellipse_mm(h), BLACK.stroke_width(1)))
            .map_err(e)?
            .label("Hertz contact ellipse")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(1)));
    }
    let inside: Vec<(f64, f64)> = (0..grid.ny())
        .flat_map(|iy| (0..grid.nx()).map(move |ix| (ix, iy)))
        .filter(|&(ix, iy)| pressure[grid.index(ix, iy)] > 0.0)
        .map(|(ix, iy)| (1e3 * grid.x(ix), 1e3 * grid.y(iy)))
        .collect();
    let mut labels = vec!["stick", "slip", "no contact"];
    let cm = hertz.map(|(_, k)| format!("Cattaneo-Mindlin stick ellipse, c/a = {k:.4}"));
    if let Some(l) = &cm {
        labels.push(l);
        labels.push("Hertz contact ellipse");
    }
    legend_avoiding(&mut chart, &inside, &labels)?;
    root.present().map_err(e)?;
    Ok(())
}

/// The tangential traction along the load direction (q . e) along x through the row nearest
/// y = 0 and along y through the column nearest x = 0, against a closed form where given.
pub fn traction_profiles(
    path: &Path,
    grid: &SurfaceGrid,
    traction: &[f64],
    reference: Option<Reference<'_>>,
    title: &str,
) -> Result<(), String> {
    let qmax = traction.iter().fold(0.0f64, |m, q| m.max(q.abs()));
    // All zero (no friction): +-1 GPa rather than a range of 1e-308 without ticks.
    let top = if qmax > 0.0 { 1.15 * qmax / 1e9 } else { 1.0 };
    profiles(
        path,
        grid,
        traction,
        reference,
        &format!("Tangential traction profiles: {title}"),
        "q along the load direction, GPa",
        (-top, top),
    )
}

/// A colour map of a scalar on a plane section: `values[iv * nh + ih]` at (`h[ih]`, `v[iv]`)
/// (m), axes in mm at equal scale ([`equal_aspect`]); with `depth_down` the vertical axis is
/// the depth z, drawn downward. `quantity` = (name, divisor, unit): values are shown divided
/// by the divisor, e.g. ("sigma_xx", 1e9, "GPa"), or ("psi", 1.0, "1") for a dimensionless
/// field. `scale`: [`SectionScale::Signed`] for stress components (0 is white),
/// [`SectionScale::Damage`] for psi (the isoline psi = 1 drawn in red).
#[allow(clippy::too_many_arguments)]
pub fn section(
    path: &Path,
    h: (&[f64], &str),
    v: (&[f64], &str),
    values: &[f64],
    depth_down: bool,
    quantity: (&str, f64, &str),
    scale: SectionScale,
    title: &str,
) -> Result<(), String> {
    let (quantity, divisor, unit_name) = quantity;
    register_font()?;
    let (hs, hname) = h;
    let (vs, vname) = v;
    let (nh, nv) = (hs.len(), vs.len());
    if nh < 2 || nv < 2 || values.len() != nh * nv {
        return Err(format!(
            "section: {} values for {nh} x {nv} points",
            values.len()
        ));
    }
    let sgn = if depth_down { -1.0 } else { 1.0 };
    let (h0, h1) = (1e3 * hs[0], 1e3 * hs[nh - 1]);
    let (va, vb) = (sgn * 1e3 * vs[0], sgn * 1e3 * vs[nv - 1]);
    let (v0, v1) = (va.min(vb), va.max(vb));
    let height = map_height((h0, h1), (v0, v1), 760, 115, (300, 1000));
    let root = Canvas::new(path, (1040, height)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let (main, bar) = root.split_horizontally(860);
    let lo = values.iter().cloned().fold(f64::INFINITY, f64::min) / divisor;
    let hi = values.iter().cloned().fold(f64::NEG_INFINITY, f64::max) / divisor;
    let (lo, hi) = colour_range(lo, hi, scale);
    let vlabel = move |x: &f64| tick(&(sgn * x));
    let y_desc = if depth_down {
        format!("{vname} (depth, downward), mm")
    } else {
        format!("{vname}, mm")
    };
    let mut chart = map_chart(
        &main,
        (h0, h1),
        (v0, v1),
        &format!("{quantity}: {title}"),
        (&format!("{hname}, mm"), &y_desc),
        &vlabel,
    )?;
    // Cells between the points' midpoints (the first and last halved), so that the map
    // covers exactly the field's box.
    let mid = |c: &[f64], i: usize| -> (f64, f64) {
        let a = if i == 0 {
            c[0]
        } else {
            0.5 * (c[i - 1] + c[i])
        };
        let b = if i + 1 == c.len() {
            c[i]
        } else {
            0.5 * (c[i] + c[i + 1])
        };
        (a, b)
    };
    chart
        .draw_series((0..nv).flat_map(|iv| {
            (0..nh).map(move |ih| {
                let (xa, xb) = mid(hs, ih);
                let (ya, yb) = mid(vs, iv);
                let c = section_colour(values[iv * nh + ih] / divisor, (lo, hi), scale);
                Rectangle::new(
                    [(1e3 * xa, sgn * 1e3 * ya), (1e3 * xb, sgn * 1e3 * yb)],
                    c.filled(),
                )
            })
        }))
        .map_err(e)?;
    if scale == SectionScale::Damage {
        let scaled: Vec<f64> = values.iter().map(|x| x / divisor).collect();
        let segments = isoline_grid(hs, vs, &scaled, 1.0);
        let line = RED.stroke_width(2);
        chart
            .draw_series(segments.iter().map(|&(a, b)| {
                PathElement::new(
                    vec![(1e3 * a.0, sgn * 1e3 * a.1), (1e3 * b.0, sgn * 1e3 * b.1)],
                    line,
                )
            }))
            .map_err(e)?;
    }
    let mut cb = ChartBuilder::on(&bar)
        .margin_top(50)
        .margin_bottom(65)
        .margin_left(10)
        .margin_right(25)
        .right_y_label_area_size(80)
        .build_cartesian_2d(0.0..1.0, lo..hi)
        .map_err(e)?;
    cb.configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_desc(if scale == SectionScale::Damage {
            format!("{quantity}, dangerous >= 1 (red line)")
        } else {
            format!("{quantity}, {unit_name}")
        })
        .y_label_formatter(&tick)
        .label_style((FAMILY, 15))
        .axis_desc_style((FAMILY, 17))
        .draw()
        .map_err(e)?;
    let levels = 256;
    cb.draw_series((0..levels).map(|k| {
        let (t0, t1) = (k as f64 / levels as f64, (k + 1) as f64 / levels as f64);
        let (a, b) = (lo + t0 * (hi - lo), lo + t1 * (hi - lo));
        Rectangle::new(
            [(0.0, a), (1.0, b)],
            section_colour(0.5 * (a + b), (lo, hi), scale).filled(),
        )
    }))
    .map_err(e)?;
    if scale == SectionScale::Damage && lo < 1.0 && hi > 1.0 {
        cb.draw_series(std::iter::once(PathElement::new(
            vec![(0.0, 1.0), (1.0, 1.0)],
            RED.stroke_width(2),
        )))
        .map_err(e)?;
    }
    root.present().map_err(e)?;
    Ok(())
}

/// Draws the legend of `chart` in the corner that covers the fewest of `points` (data
/// coordinates; [`emptiest_corner`]), its size estimated from `labels`.
pub(crate) fn legend_avoiding<'a, 'b: 'a>(
    chart: &mut MapChart<'a, 'b>,
    points: &[(f64, f64)],
    labels: &[&str],
) -> Result<(), String> {
    let (xr, yr) = (chart.x_range(), chart.y_range());
    let px = chart.plotting_area().dim_in_pixel();
    let frac = legend_frac(labels, 14.0, px);
    let (pos, _) = emptiest_corner(points, (xr.start, xr.end), (yr.start, yr.end), frac);
    chart
        .configure_series_labels()
        .position(pos)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FAMILY, 14))
        .draw()
        .map_err(e)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn font_registers_and_colours_are_bounded() {
        register_font().unwrap();
        assert_eq!(viridis(0.0), RGBColor(68, 1, 84));
        assert_eq!(viridis(1.0), RGBColor(253, 231, 37));
        assert_eq!(viridis(f64::NAN), RGBColor(68, 1, 84));
        assert_eq!(viridis(7.0), RGBColor(253, 231, 37));
    }

    #[test]
    fn equal_aspect_gives_equal_metres_per_pixel_and_keeps_the_data() {
        for (x, y, px) in [
            ((-2.0, 2.0), (-0.5, 0.5), (760u32, 300u32)),
            ((-0.1, 0.1), (-3.0, 3.0), (760, 600)),
            ((0.0, 1.0), (-1.5, 0.0), (500, 500)),
        ] {
            let (xr, yr) = equal_aspect(x, y, px);
            let mx = (xr.1 - xr.0) / px.0 as f64;
            let my = (yr.1 - yr.0) / px.1 as f64;
            assert!((mx - my).abs() <= 1e-12 * mx, "{mx} vs {my}");
            assert!(xr.0 <= x.0 && xr.1 >= x.1 && yr.0 <= y.0 && yr.1 >= y.1);
        }
    }

    /// The map axes as drawn: a 4 x 1 mm window in a 1040 x 420 px image has the same mm per
    /// pixel along x and y in plotters' own plotting area (to the rounding of 1 px), where the
    /// old layout (fixed 860 x 800 px axes over the data ranges) drew 4 mm over 760 px and
    /// 1 mm over 685 px.
    #[test]
    fn maps_are_drawn_at_equal_scale() {
        register_font().unwrap();
        let (w, h) = (860u32, 420u32);
        let mut buf = vec![255u8; (w * h * 3) as usize];
        let root = Canvas::with_buffer(&mut buf, (w, h)).into_drawing_area();
        let chart = map_chart(
            &root,
            (-2.0, 2.0),
            (-0.5, 0.5),
            "a long title that has to fit",
            ("x, mm", "y, mm"),
            &tick,
        )
        .unwrap();
        let (xr, yr) = (chart.x_range(), chart.y_range());
        let (pw, ph) = chart.plotting_area().dim_in_pixel();
        let mx = (xr.end - xr.start) / pw as f64;
        let my = (yr.end - yr.start) / ph as f64;
        assert!(
            (mx - my).abs() <= mx / ph.min(pw) as f64,
            "{mx} vs {my} mm/px"
        );
    }

    #[test]
    fn signed_fields_put_zero_at_white() {
        assert_eq!(diverging(0.0), RGBColor(255, 255, 255));
        // A mostly tensile field (-0.2 .. 2 GPa): 0 is still white, -0.2 light blue, 2 red.
        let range = colour_range(-0.2, 2.0, SectionScale::Signed);
        assert_eq!(range, (-2.0, 2.0));
        assert_eq!(
            section_colour(0.0, range, SectionScale::Signed),
            RGBColor(255, 255, 255)
        );
        let neg = section_colour(-0.2, range, SectionScale::Signed);
        assert!(neg.2 > neg.0, "{neg:?}");
        assert_eq!(
            section_colour(2.0, range, SectionScale::Signed),
            RGBColor(178, 24, 43)
        );
        // The sequential scale of the old sections put 0 at a mid colour of viridis.
        assert_ne!(
            section_colour(
                0.0,
                colour_range(-0.2, 2.0, SectionScale::Sequential),
                SectionScale::Sequential
            ),
            RGBColor(255, 255, 255)
        );
    }

    /// A constant field (the shear of a frictionless contact, all 0) gets an axis with
    /// distinct tick labels; the old padding (0.08 f64::MIN_POSITIVE) gave a range of 1e-309
    /// whose labels all read "0".
    #[test]
    fn a_degenerate_range_gives_a_valid_axis() {
        use plotters::coord::ranged1d::Ranged;
        for (lo, hi) in [(0.0, 0.0), (5.0, 5.0), (-3e-7, -3e-7), (f64::NAN, 1.0)] {
            let (a, b) = axis_range(lo, hi, 0.08);
            assert!(
                a.is_finite() && b.is_finite() && b > a,
                "{lo} {hi}: {a} {b}"
            );
            if lo.is_finite() {
                assert!(a < lo && b > hi);
            }
            let r: RangedCoordf64 = (a..b).into();
            let labels: Vec<String> = r.key_points(6).iter().map(sig).collect();
            assert!(labels.len() >= 3, "{labels:?}");
            let mut d = labels.clone();
            d.dedup();
            assert_eq!(d.len(), labels.len(), "{labels:?}");
        }
        assert_eq!(axis_range(1.0, 3.0, 0.1), (0.8, 3.2));
    }

    /// A log axis over less than a decade still has labelled ticks (the V and Psi panels of
    /// the damage sweep had none): 3 to 14 ticks inside the range for any range.
    #[test]
    fn log_axes_have_ticks_for_any_range() {
        for (lo, hi) in [
            (0.423, 0.806),
            (1.0 / 1.3, 1.3),
            (0.1386 / 1.3, 0.1466 * 1.3),
            (1e-3, 1e3),
            (2e-9, 5e-5),
            (87.0, 160.0),
        ] {
            let t = log_ticks(lo, hi);
            assert!((3..=14).contains(&t.len()), "{lo}..{hi}: {t:?}");
            assert!(t.iter().all(|&v| v >= lo * 0.999 && v <= hi * 1.001));
            let labels: Vec<String> = t.iter().map(sig).collect();
            let mut d = labels.clone();
            d.dedup();
            assert_eq!(d.len(), labels.len(), "{labels:?}");
        }
        assert_eq!(log_ticks(1e-3, 1e3).len(), 7);
        assert_eq!(sig(&0.5), "0.5");
        assert_eq!(sig(&1.25e-7), "1.250e-7");
        assert_eq!(sig(&123.456), "123.5");
    }

    #[test]
    fn long_titles_shrink_to_fit() {
        register_font().unwrap();
        let t = "Sec. 6: dangerous volume of the intensity, limit 1.2 p0 (dashed: the paper)";
        let size = title_size(t, 20.0, 960);
        let w = crate::output::canvas::layout(t, size).unwrap().width;
        assert!(w <= 940.0, "{w} px at {size}");
        assert_eq!(title_size("short", 20.0, 960), 20.0);
    }

    #[test]
    fn the_legend_goes_to_the_emptiest_corner() {
        // A curve rising to the upper right: the upper left is free.
        let pts: Vec<(f64, f64)> = (0..=100)
            .map(|k| (k as f64 / 100.0, (k as f64 / 100.0).powi(2)))
            .collect();
        let (c, n) = emptiest_corner(&pts, (0.0, 1.0), (0.0, 1.0), (0.4, 0.3));
        assert!(matches!(c, SeriesLabelPosition::UpperLeft), "{n}");
        assert_eq!(n, 0);
        // Traction q >= 0 over the middle of a symmetric axis (the traction profiles): the
        // bump reaches both upper corners' boxes, the lower ones are free.
        let bump: Vec<(f64, f64)> = (0..=100)
            .map(|k| {
                let x = -1.0 + 2.0 * k as f64 / 100.0;
                (x, (1.0 - x * x).max(0.0))
            })
            .collect();
        let (c, n) = emptiest_corner(&bump, (-1.0, 1.0), (-1.2, 1.2), (0.3, 0.25));
        assert!(matches!(c, SeriesLabelPosition::LowerRight), "{n}");
        assert_eq!(n, 0);
    }

    /// psi = 2 - r / R on a grid: the isoline psi = 1 is the circle r = R; the marching
    /// squares points lie on it to the error of linear interpolation along a cell edge
    /// (r is convex: below h^2 / (8 R) ~ 0.002 R for h = 0.125 R), and it closes (each point is
    /// the end of two segments).
    #[test]
    fn the_psi_isoline_is_where_psi_is_one() {
        let n = 33;
        let c: Vec<f64> = (0..n)
            .map(|i| -2.0 + 4.0 * i as f64 / (n - 1) as f64)
            .collect();
        let r0 = 1.0;
        let psi: Vec<f64> = (0..n * n)
            .map(|k| 2.0 - (c[k % n].powi(2) + c[k / n].powi(2)).sqrt() / r0)
            .collect();
        let segs = isoline_grid(&c, &c, &psi, 1.0);
        assert!(segs.len() > 40, "{}", segs.len());
        for (a, b) in &segs {
            for p in [a, b] {
                let r = (p.0 * p.0 + p.1 * p.1).sqrt();
                assert!((r - r0).abs() < 2e-3 * r0 + 1e-12, "{r}");
            }
        }
        assert!(isoline_grid(&c, &c, &vec![0.5; n * n], 1.0).is_empty());
    }

    #[test]
    fn plots_render_without_system_fonts() {
        let dir = tempfile::tempdir().unwrap();
        let g = SurfaceGrid::centred(16, 12, 1e-3, 8e-4).unwrap();
        let p = g.sample(|x, y| (1e9 * (1.0 - (x / 8e-4).powi(2) - (y / 6e-4).powi(2))).max(0.0));
        let map = dir.path().join("m.png");
        pressure_map(&map, &g, &p, None, "test").unwrap();
        let prof = dir.path().join("p.png");
        pressure_profiles(&prof, &g, &p, None, "test").unwrap();
        for f in [map, prof] {
            let bytes = std::fs::read(f).unwrap();
            assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
        }
    }
}
