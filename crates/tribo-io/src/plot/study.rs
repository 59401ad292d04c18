//! The plots of a study's gathered table (`tribo sweep gather`, `plots/` of the study
//! directory; the pages' data are [`crate::study`]'s). The statistics are computed by the
//! caller (`tribo_study::plots` with [`tribo::stats::sample`]); here they are only drawn.
//!
//! - [`random_output`]: for a study with random inputs, one output's histogram (sample size,
//!   mean and quantiles marked), its empirical exceedance curve with the DKW band, the
//!   Spearman rank correlations with the random inputs (a tornado chart) and scatter plots of
//!   the output against the most influential inputs;
//! - [`grid_output`]: for a grid or zip study, one output against each swept parameter, a line
//!   per combination of the other parameters.

use super::canvas::Canvas;
use super::style::*;
use crate::study::{GridOutput, Influence, Quantity, RandomOutput};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// A unit prefix for the plotted values: (factor the SI values are multiplied by, the unit's
/// label), so that the ticks read 3.3 GPa, not 3300000000 Pa.
fn display_unit(unit: &str, max_abs: f64) -> (f64, String) {
    let prefixed = ["Pa", "N", "m", "J", "W", "s", "N/m"];
    let a = if max_abs.is_finite() && max_abs > 0.0 {
        max_abs
    } else {
        1.0
    };
    if prefixed.contains(&unit) {
        let e = ((a.log10() / 3.0).floor() as i32 * 3).clamp(-9, 9);
        let e = if unit == "s" || unit == "N/m" {
            e.min(0)
        } else {
            e
        };
        let p = match e {
            -9 => "n",
            -6 => "u",
            -3 => "m",
            3 => "k",
            6 => "M",
            9 => "G",
            _ => "",
        };
        return (10f64.powi(-e), format!("{p}{unit}"));
    }
    match unit {
        "m^2" if a < 1e-2 => (1e6, "mm^2".into()),
        "m^3" if a < 1e-3 => (1e9, "mm^3".into()),
        "1" | "" if !(1e-3..1e5).contains(&a) => {
            let e = a.log10().floor() as i32;
            (10f64.powi(-e), format!("x 1e{e}"))
        }
        "1" | "" => (1.0, String::new()),
        u => (1.0, u.to_string()),
    }
}

/// An axis description: `name (unit)`, or the name alone for a plain number.
fn describe(q: &Quantity, unit: &str) -> String {
    if unit.is_empty() || unit == "1" {
        q.name.clone()
    } else {
        format!("{} ({unit})", q.name)
    }
}

const BLUE: RGBColor = RGBColor(31, 119, 180);
const RED: RGBColor = RGBColor(214, 39, 40);
const GREY: RGBColor = RGBColor(120, 120, 120);

/// Ten distinct line colours (the tab10 palette).
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// Inputs drawn as scatter plots (the most influential first).
pub const MAX_SCATTER: usize = 4;

/// Draws one output of a random study: top, the histogram, the exceedance curve and the
/// tornado chart of Spearman's rho; bottom, the output against each of the (at most
/// [`MAX_SCATTER`]) most influential inputs.
pub fn random_output(path: &Path, r: &RandomOutput) -> Result<(), String> {
    register_font()?;
    let (w, h) = (1500u32, 1000u32);
    let root = Canvas::new(path, (w, h)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let root = root
        .titled(&r.title, (FAMILY, title_size(&r.title, 20.0, w)))
        .map_err(e)?;
    let (top, bottom) = root.split_vertically(500);
    let cols = top.split_evenly((1, 3));
    let max_abs = r.summary.min.abs().max(r.summary.max.abs());
    let (f, unit) = display_unit(&r.output.unit, max_abs);
    let xdesc = describe(&r.output, &unit);
    histogram_panel(&cols[0], r, f, &xdesc)?;
    exceedance_panel(&cols[1], r, f, &xdesc)?;
    tornado_panel(&cols[2], r)?;
    let shown: Vec<&Influence> = r
        .influences
        .iter()
        .filter(|i| !i.points.is_empty())
        .take(MAX_SCATTER)
        .collect();
    if !shown.is_empty() {
        let panels = bottom.split_evenly((1, shown.len()));
        for (area, inf) in panels.iter().zip(shown) {
            scatter_panel(area, inf, &r.output, f, &unit)?;
        }
    }
    root.present().map_err(e)?;
    Ok(())
}

/// The axes of a panel: descriptions, x ticks by [`sig`] (about `n` of them), y ticks by
/// [`sig`] or, for counts and probabilities, [`tick`]; labels at `size` px, no minor lines.
fn axes(
    chart: &mut MapChart<'_, '_>,
    x_desc: &str,
    y_desc: &str,
    y_sig: bool,
    n: usize,
    size: u32,
) -> Result<(), String> {
    let y_fmt: fn(&f64) -> String = if y_sig { sig } else { tick };
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(&sig)
        .y_label_formatter(&y_fmt)
        .x_labels(n)
        .label_style((FAMILY, size))
        .axis_desc_style((FAMILY, size + 1))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(e)
}

/// The series legend at `pos`, labels at `size` px, on a light box.
fn legend<'a, 'b: 'a>(
    chart: &mut MapChart<'a, 'b>,
    pos: SeriesLabelPosition,
    size: u32,
) -> Result<(), String> {
    chart
        .configure_series_labels()
        .position(pos)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FAMILY, size))
        .draw()
        .map_err(e)
}

/// A dashed vertical line at `x` from `y0` to `y1`.
fn dashed_v(x: f64, y0: f64, y1: f64, c: RGBColor) -> Vec<PathElement<(f64, f64)>> {
    let n = 24;
    (0..n)
        .step_by(2)
        .map(|k| {
            let a = y0 + (y1 - y0) * k as f64 / n as f64;
            let b = y0 + (y1 - y0) * (k + 1) as f64 / n as f64;
            PathElement::new(vec![(x, a), (x, b)], c.stroke_width(2))
        })
        .collect()
}

fn histogram_panel(
    area: &DrawingArea<Canvas<'_>, Shift>,
    r: &RandomOutput,
    f: f64,
    xdesc: &str,
) -> Result<(), String> {
    let hst = &r.histogram;
    let (x0, x1) = (hst.edges[0] * f, hst.edges[hst.edges.len() - 1] * f);
    let (x0, x1) = axis_range(x0, x1, 0.03);
    let top = hst.counts.iter().copied().max().unwrap_or(1).max(1) as f64 * 1.25;
    let s = &r.summary;
    let excluded = if r.excluded > 0 {
        format!(", {} excluded", r.excluded)
    } else {
        String::new()
    };
    let mut chart = ChartBuilder::on(area)
        .caption(format!("histogram: n = {}{excluded}", s.n), (FAMILY, 16))
        .margin(15)
        .x_label_area_size(55)
        .y_label_area_size(60)
        .build_cartesian_2d(x0..x1, 0.0..top)
        .map_err(e)?;
    axes(&mut chart, xdesc, "points per bin", false, 6, 13)?;
    chart
        .draw_series(hst.counts.iter().enumerate().map(|(k, &c)| {
            Rectangle::new(
                [(hst.edges[k] * f, 0.0), (hst.edges[k + 1] * f, c as f64)],
                BLUE.mix(0.55).filled(),
            )
        }))
        .map_err(e)?;
    // Each bar outlined, so that neighbours of equal height read as two bins.
    chart
        .draw_series(hst.counts.iter().enumerate().map(|(k, &c)| {
            Rectangle::new(
                [(hst.edges[k] * f, 0.0), (hst.edges[k + 1] * f, c as f64)],
                WHITE.stroke_width(1),
            )
        }))
        .map_err(e)?;
    chart
        .draw_series([PathElement::new(
            vec![(s.mean * f, 0.0), (s.mean * f, top)],
            RED.stroke_width(2),
        )])
        .map_err(e)?
        .label(format!("mean {}", sig(&(s.mean * f))))
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED.stroke_width(2)));
    let levels: Vec<String> = s
        .quantiles
        .iter()
        .map(|(p, _)| format!("{}", (p * 100.0 * 1e6).round() / 1e6))
        .collect();
    for (_, q) in &s.quantiles {
        chart
            .draw_series(dashed_v(q * f, 0.0, top, BLACK))
            .map_err(e)?;
    }
    let values: Vec<String> = s.quantiles.iter().map(|(_, q)| sig(&(q * f))).collect();
    if !s.quantiles.is_empty() {
        chart
            .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())
            .map_err(e)?
            .label(format!("quantiles {} %:", levels.join(", ")))
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 8, y)], BLACK.stroke_width(2)));
        chart
            .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())
            .map_err(e)?
            .label(values.join(", "))
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x, y)], WHITE));
    }
    legend(&mut chart, SeriesLabelPosition::UpperRight, 13)
}

fn exceedance_panel(
    area: &DrawingArea<Canvas<'_>, Shift>,
    r: &RandomOutput,
    f: f64,
    xdesc: &str,
) -> Result<(), String> {
    let ex = &r.exceedance;
    let (lo, hi) = (ex.x[0] * f, ex.x[ex.x.len() - 1] * f);
    let (x0, x1) = axis_range(lo, hi, 0.05);
    let mut chart = ChartBuilder::on(area)
        .caption("exceedance 1 - F(x)", (FAMILY, 16))
        .margin(15)
        .x_label_area_size(55)
        .y_label_area_size(60)
        .build_cartesian_2d(x0..x1, 0.0..1.0)
        .map_err(e)?;
    axes(&mut chart, xdesc, "P(output > x)", false, 6, 13)?;
    // Steps: S is 1 left of the first value, S_k from x_k to x_k+1.
    let step = |v: &[f64], left: f64| {
        let mut pts = vec![(x0, left), (ex.x[0] * f, left)];
        for (k, (&x, &s)) in ex.x.iter().zip(v).enumerate() {
            pts.push((x * f, s));
            let next = ex.x.get(k + 1).map_or(x1, |x| x * f);
            pts.push((next, s));
        }
        pts
    };
    let upper = step(&ex.upper, 1.0);
    let lower = step(&ex.lower, (1.0 - ex.epsilon).max(0.0));
    let mut band = upper.clone();
    band.extend(lower.iter().rev());
    let conf = (ex.confidence * 100.0 * 1e6).round() / 1e6;
    chart
        .draw_series([Polygon::new(band, BLUE.mix(0.2).filled())])
        .map_err(e)?
        .label(format!("{conf} % DKW band (+-{})", sig(&ex.epsilon)))
        .legend(|(x, y)| Rectangle::new([(x, y - 5), (x + 20, y + 5)], BLUE.mix(0.2).filled()));
    chart
        .draw_series(LineSeries::new(
            step(&ex.survival, 1.0),
            BLUE.stroke_width(2),
        ))
        .map_err(e)?
        .label(format!("empirical, n = {}", r.summary.n))
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE.stroke_width(2)));
    legend(&mut chart, SeriesLabelPosition::UpperRight, 13)
}

fn tornado_panel(area: &DrawingArea<Canvas<'_>, Shift>, r: &RandomOutput) -> Result<(), String> {
    let k = r.influences.len().max(1);
    let mut chart = ChartBuilder::on(area)
        .caption("influence: Spearman rank correlation", (FAMILY, 16))
        .margin(15)
        .x_label_area_size(55)
        .y_label_area_size(20)
        .build_cartesian_2d(-1.0..1.0, -0.6..(k as f64 - 0.4))
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc("rho(input, output)")
        .x_label_formatter(&tick)
        .y_labels(0)
        .label_style((FAMILY, 13))
        .axis_desc_style((FAMILY, 14))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(e)?;
    chart
        .draw_series(dashed_v(-r.rho_null_95, -0.6, k as f64 - 0.4, GREY))
        .map_err(e)?
        .label(format!(
            "|rho| < {} : no influence (95 %)",
            sig(&r.rho_null_95)
        ))
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], GREY.stroke_width(2)));
    chart
        .draw_series(dashed_v(r.rho_null_95, -0.6, k as f64 - 0.4, GREY))
        .map_err(e)?;
    chart
        .draw_series([PathElement::new(
            vec![(0.0, -0.6), (0.0, k as f64 - 0.4)],
            BLACK.stroke_width(1),
        )])
        .map_err(e)?;
    // The most influential at the top.
    for (i, inf) in r.influences.iter().enumerate() {
        let y = (k - 1 - i) as f64;
        let (text, colour) = match inf.rho {
            Some(rho) => {
                chart
                    .draw_series([Rectangle::new(
                        [(0.0, y - 0.22), (rho, y + 0.22)],
                        (if rho >= 0.0 { RED } else { BLUE }).mix(0.8).filled(),
                    )])
                    .map_err(e)?;
                (format!("{}: {}", inf.input.name, sig(&rho)), BLACK)
            }
            None => (format!("{}: undefined", inf.input.name), GREY),
        };
        chart
            .draw_series([Text::new(
                text,
                (-0.97, y + 0.42),
                (FAMILY, 13).into_font().color(&colour),
            )])
            .map_err(e)?;
    }
    legend(&mut chart, SeriesLabelPosition::LowerRight, 12)
}

fn scatter_panel(
    area: &DrawingArea<Canvas<'_>, Shift>,
    inf: &Influence,
    output: &Quantity,
    fy: f64,
    yunit: &str,
) -> Result<(), String> {
    let xs = inf.points.iter().map(|p| p.0);
    let (lo, hi) = xs
        .clone()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    let (fx, xunit) = display_unit(&inf.input.unit, lo.abs().max(hi.abs()));
    let (x0, x1) = axis_range(lo * fx, hi * fx, 0.05);
    let (ylo, yhi) = inf
        .points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.1), b.max(p.1))
        });
    let (y0, y1) = axis_range(ylo * fy, yhi * fy, 0.05);
    let caption = match inf.rho {
        Some(rho) => format!("rho = {}", sig(&rho)),
        None => "rho undefined".into(),
    };
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FAMILY, 15))
        .margin(15)
        .x_label_area_size(55)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(e)?;
    axes(
        &mut chart,
        &describe(&inf.input, &xunit),
        &describe(output, yunit),
        true,
        5,
        12,
    )?;
    chart
        .draw_series(
            inf.points
                .iter()
                .map(|p| Circle::new((p.0 * fx, p.1 * fy), 2, BLUE.mix(0.7).filled())),
        )
        .map_err(e)?;
    Ok(())
}

/// Draws one output of a grid study: a panel per swept parameter, a line per combination of
/// the other parameters (labelled in a legend where there are 2 to 10 lines).
pub fn grid_output(path: &Path, g: &GridOutput) -> Result<(), String> {
    register_font()?;
    let k = g.panels.len().max(1);
    let (w, h) = ((600 * k as u32).max(700), 560u32);
    let root = Canvas::new(path, (w, h)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let title = if g.excluded > 0 {
        format!(
            "{} ({} points excluded: failed or missing)",
            g.title, g.excluded
        )
    } else {
        g.title.clone()
    };
    let root = root
        .titled(&title, (FAMILY, title_size(&title, 20.0, w)))
        .map_err(e)?;
    let max_abs = g
        .panels
        .iter()
        .flat_map(|p| p.lines.iter().flat_map(|l| l.1.iter().map(|q| q.1.abs())))
        .fold(0.0, f64::max);
    let (fy, yunit) = display_unit(&g.output.unit, max_abs);
    let areas = root.split_evenly((1, k));
    for (area, panel) in areas.iter().zip(&g.panels) {
        let pts: Vec<(f64, f64)> = panel.lines.iter().flat_map(|l| l.1.clone()).collect();
        let (xl, xh) = pts
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(p.0), b.max(p.0))
            });
        let (fx, xunit) = display_unit(&panel.parameter.unit, xl.abs().max(xh.abs()));
        let (yl, yh) = pts
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(p.1), b.max(p.1))
            });
        let (x0, x1) = axis_range(xl * fx, xh * fx, 0.05);
        let (y0, y1) = axis_range(yl * fy, yh * fy, 0.08);
        let mut chart = ChartBuilder::on(area)
            .margin(20)
            .x_label_area_size(55)
            .y_label_area_size(75)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(e)?;
        axes(
            &mut chart,
            &describe(&panel.parameter, &xunit),
            &describe(&g.output, &yunit),
            true,
            6,
            13,
        )?;
        let labelled = (2..=PALETTE.len()).contains(&panel.lines.len());
        for (i, (label, line)) in panel.lines.iter().enumerate() {
            let c = PALETTE[i % PALETTE.len()];
            let scaled: Vec<(f64, f64)> = line.iter().map(|p| (p.0 * fx, p.1 * fy)).collect();
            let s = chart
                .draw_series(LineSeries::new(scaled.clone(), c.stroke_width(2)))
                .map_err(e)?;
            if labelled {
                s.label(label.clone()).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                });
            }
            chart
                .draw_series(scaled.iter().map(|&p| Circle::new(p, 3, c.filled())))
                .map_err(e)?;
        }
        if labelled {
            let scaled: Vec<(f64, f64)> = pts.iter().map(|p| (p.0 * fx, p.1 * fy)).collect();
            let labels: Vec<&str> = panel.lines.iter().map(|l| l.0.as_str()).collect();
            let px = chart.plotting_area().dim_in_pixel();
            let frac = legend_frac(&labels, 13.0, px);
            let (pos, _) = emptiest_corner(&densify(&scaled), (x0, x1), (y0, y1), frac);
            legend(&mut chart, pos, 13)?;
        }
    }
    root.present().map_err(e)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_units_read_as_prefixed_si() {
        assert_eq!(display_unit("Pa", 3.3e9), (1e-9, "GPa".into()));
        assert_eq!(display_unit("N", 2000.0), (1e-3, "kN".into()));
        assert_eq!(display_unit("m", 2e-5), (1e6, "um".into()));
        assert_eq!(display_unit("m^3", 2e-10), (1e9, "mm^3".into()));
        assert_eq!(display_unit("1", 0.9), (1.0, String::new()));
        assert_eq!(display_unit("1", 2e-6), (1e6, "x 1e-6".into()));
    }
}
