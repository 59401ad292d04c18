//! PNG plots with plotters, rendered with the DejaVu Sans font shipped in `assets/` (no
//! system fonts needed).

use super::canvas::Canvas;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::FontStyle;
use std::sync::OnceLock;

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

/// Tick labels in one notation per axis `[lo, hi]` (`log`: a logarithmic axis): [`sig`]'s
/// fixed notation where all of the axis's ticks have it (the largest magnitude in
/// [1e-2, 1e5) and, on a log axis, the smallest at least 1e-3), scientific with the mantissa
/// trimmed ("5e-4", "1.5e-3") for every tick otherwise, so that one axis never mixes
/// "5.000e-4" and "0.001". Zero is "0" in either.
pub(crate) fn axis_labels(lo: f64, hi: f64, log: bool) -> impl Fn(&f64) -> String {
    let top = lo.abs().max(hi.abs());
    let bottom = lo.abs().min(hi.abs());
    let fixed = (1e-2..1e5).contains(&top) && (!log || bottom >= 1e-3);
    move |v: &f64| {
        if fixed || *v == 0.0 || !v.is_finite() {
            sig(v)
        } else {
            scientific(*v)
        }
    }
}

/// `v` in scientific notation with at most four significant digits, trailing zeros of the
/// mantissa removed: 5e-4, 1.5e-3, -2.25e6.
fn scientific(v: f64) -> String {
    let s = format!("{v:.3e}");
    match s.split_once('e') {
        Some((mantissa, exponent)) => {
            let mantissa = if mantissa.contains('.') {
                mantissa.trim_end_matches('0').trim_end_matches('.')
            } else {
                mantissa
            };
            format!("{mantissa}e{exponent}")
        }
        None => s,
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
    fn one_axis_uses_one_notation() {
        // p / E* from 0 to 1.2e-3: every tick scientific (it mixed "5.000e-4" and "0.001").
        let small = axis_labels(0.0, 1.2e-3, false);
        assert_eq!(
            [0.0, 5e-4, 1e-3, 1.5e-3].map(|v| small(&v)),
            ["0", "5e-4", "1e-3", "1.5e-3"]
        );
        // An axis within [1e-2, 1e5): fixed notation throughout.
        let plain = axis_labels(0.0, 0.6, false);
        assert_eq!([0.0, 0.25, 0.5].map(|v| plain(&v)), ["0", "0.25", "0.5"]);
        // A log axis over decades (a PSD's wavenumbers): scientific throughout.
        let log = axis_labels(1e2, 1e6, true);
        assert_eq!([1e2, 1e4, 1e6].map(|v| log(&v)), ["1e2", "1e4", "1e6"]);
        assert_eq!(scientific(-2.25e6), "-2.25e6");
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
        let w = super::super::canvas::layout(t, size).unwrap().width;
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
}
