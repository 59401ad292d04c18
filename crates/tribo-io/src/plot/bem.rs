//! PNG plots of 2D boundary element results: colour maps over the triangulated regions
//! (Fig. 7a, 8a), interface tractions along x for each step (Fig. 7b), the damage sweep
//! (Fig. 8b) and the material comparison.

use super::canvas::Canvas;
use crate::atomic::draw_atomic;
use crate::bem::{file_name, psi_file};
use crate::error::{IoError, IoResult};
use plotters::prelude::*;
use std::path::Path;
use tribo::solvers::bem2d::contact::{ContactNode, ContactState};
use tribo_case::bem::case::BemCase;
use tribo_case::bem::pipeline::{BemOutcome, DamageOutcome, DamageUnit, Variant};
use tribo_case::bem::summary::{stress_intensity, BemSummary, DamageSummary, Dangerous};

use super::style::{
    axis_range, densify, e, legend_avoiding, log_ticks, map_chart, register_font, sig, styled_axes,
    tick, viridis, FAMILY,
};

pub use super::style::diverging;

/// One triangulated region with nodal values.
pub struct MapPart<'a> {
    /// Vertices, m.
    pub nodes: &'a [[f64; 2]],
    /// Triangles.
    pub triangles: &'a [[usize; 3]],
    /// Nodal values (plot units).
    pub values: &'a [f64],
}

/// How values are coloured.
#[derive(Debug, Clone, Copy)]
pub enum Scale {
    /// Sequential (viridis) from 0 to the largest value.
    Sequential,
    /// Diverging about 0 (symmetric range).
    Diverging,
    /// psi: grey below 1, viridis from 1 to the largest value (the dangerous part stands out).
    Damage,
}

/// A colour map of nodal values over triangulated regions (axes in mm), with a colour bar.
pub fn field_map(
    path: &Path,
    parts: &[MapPart<'_>],
    scale: Scale,
    title: &str,
    unit: &str,
) -> Result<(), String> {
    register_font()?;
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    let (mut vmin, mut vmax) = (f64::INFINITY, f64::NEG_INFINITY);
    for p in parts {
        for n in p.nodes {
            for d in 0..2 {
                lo[d] = lo[d].min(1e3 * n[d]);
                hi[d] = hi[d].max(1e3 * n[d]);
            }
        }
        for &v in p.values {
            vmin = vmin.min(v);
            vmax = vmax.max(v);
        }
    }
    if !(lo[0].is_finite() && vmin.is_finite()) {
        return Err("field map: nothing to draw".into());
    }
    let (w, h) = (hi[0] - lo[0], hi[1] - lo[1]);
    let pad = 0.03 * w.max(h);
    let plot_w = 1300u32;
    let plot_h = ((plot_w as f64 - 140.0) * (h + 2.0 * pad) / (w + 2.0 * pad) + 130.0)
        .clamp(320.0, 1100.0) as u32;
    let root = Canvas::new(path, (plot_w + 150, plot_h)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let (main, bar) = root.split_horizontally(plot_w);
    let mut chart = map_chart(
        &main,
        (lo[0] - pad, hi[0] + pad),
        (lo[1] - pad, hi[1] + pad),
        title,
        ("x, mm", "y, mm"),
        &tick,
    )?;
    let (c0, c1) = match scale {
        Scale::Sequential => (vmin.min(0.0), vmax.max(f64::MIN_POSITIVE)),
        Scale::Diverging => {
            let m = vmin.abs().max(vmax.abs()).max(f64::MIN_POSITIVE);
            (-m, m)
        }
        Scale::Damage => (1.0, vmax.max(1.0 + 1e-12)),
    };
    let colour = |v: f64| -> RGBColor {
        match scale {
            Scale::Sequential => viridis((v - c0) / (c1 - c0)),
            Scale::Diverging => diverging(v / c1),
            Scale::Damage => {
                if v < 1.0 {
                    RGBColor(215, 215, 215)
                } else {
                    viridis((v - c0) / (c1 - c0))
                }
            }
        }
    };
    for p in parts {
        chart
            .draw_series(p.triangles.iter().map(|t| {
                let v = (p.values[t[0]] + p.values[t[1]] + p.values[t[2]]) / 3.0;
                let pts: Vec<(f64, f64)> = t
                    .iter()
                    .map(|&k| (1e3 * p.nodes[k][0], 1e3 * p.nodes[k][1]))
                    .collect();
                Polygon::new(pts, colour(v).filled())
            }))
            .map_err(e)?;
    }
    // Outlines of the regions (the triangulation's edges that one triangle holds), so that
    // bodies at near-zero values (white on the diverging scale) stay visible.
    let outline = RGBColor(60, 60, 60);
    for p in parts {
        chart
            .draw_series(boundary_edges(p.triangles).into_iter().map(|(a, b)| {
                PathElement::new(
                    vec![
                        (1e3 * p.nodes[a][0], 1e3 * p.nodes[a][1]),
                        (1e3 * p.nodes[b][0], 1e3 * p.nodes[b][1]),
                    ],
                    outline.stroke_width(1),
                )
            }))
            .map_err(e)?;
    }
    if let Scale::Damage = scale {
        // The edge of the dangerous region: psi = 1 on the linear interpolant of each
        // triangle.
        let line = RED.stroke_width(2);
        let mut any = false;
        for p in parts {
            let segs = isoline_triangles(p.nodes, p.triangles, p.values, 1.0);
            any |= !segs.is_empty();
            chart
                .draw_series(segs.into_iter().map(|(a, b)| {
                    PathElement::new(vec![(1e3 * a.0, 1e3 * a.1), (1e3 * b.0, 1e3 * b.1)], line)
                }))
                .map_err(e)?;
        }
        if any {
            chart
                .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())
                .map_err(e)?
                .label("psi = 1 (edge of the dangerous region)")
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], line));
            let hot: Vec<(f64, f64)> = parts
                .iter()
                .flat_map(|p| {
                    p.nodes
                        .iter()
                        .zip(p.values)
                        .filter(|(_, &v)| v >= 1.0)
                        .map(|(n, _)| (1e3 * n[0], 1e3 * n[1]))
                })
                .collect();
            legend_avoiding(
                &mut chart,
                &hot,
                &["psi = 1 (edge of the dangerous region)"],
            )?;
        }
    }
    colour_bar(&bar, c0, c1, &colour, unit)?;
    root.present().map_err(e)?;
    Ok(())
}

/// The edges of a triangulation that only one triangle holds (its boundary).
fn boundary_edges(triangles: &[[usize; 3]]) -> Vec<(usize, usize)> {
    let mut count: std::collections::HashMap<(usize, usize), usize> =
        std::collections::HashMap::new();
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *count.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let mut edges: Vec<(usize, usize)> = count
        .into_iter()
        .filter(|&(_, n)| n == 1)
        .map(|(k, _)| k)
        .collect();
    edges.sort_unstable();
    edges
}

/// The isoline `values = level` of nodal values interpolated linearly on each triangle, as
/// segments (m): on each triangle whose vertices lie on both sides (>= level counts as
/// above), the two edge points where the linear interpolant equals `level`.
pub fn isoline_triangles(
    nodes: &[[f64; 2]],
    triangles: &[[usize; 3]],
    values: &[f64],
    level: f64,
) -> Vec<((f64, f64), (f64, f64))> {
    let mut out = Vec::new();
    for t in triangles {
        if t.iter().any(|&k| k >= nodes.len() || k >= values.len()) {
            continue;
        }
        let mut cross = Vec::with_capacity(2);
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let (va, vb) = (values[a], values[b]);
            if (va >= level) != (vb >= level) {
                let s = (level - va) / (vb - va);
                cross.push((
                    nodes[a][0] + s * (nodes[b][0] - nodes[a][0]),
                    nodes[a][1] + s * (nodes[b][1] - nodes[a][1]),
                ));
            }
        }
        if cross.len() == 2 {
            out.push((cross[0], cross[1]));
        }
    }
    out
}

fn colour_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    c0: f64,
    c1: f64,
    colour: &dyn Fn(f64) -> RGBColor,
    unit: &str,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let mut chart = ChartBuilder::on(area)
        .margin_top(40)
        .margin_bottom(50)
        .margin_right(10)
        .y_label_area_size(80)
        .caption(unit, (FAMILY, 15))
        .build_cartesian_2d(0.0..1.0, c0..c1)
        .map_err(e)?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .disable_x_axis()
        .y_label_formatter(&tick)
        .label_style((FAMILY, 13))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(e)?;
    let n = 200;
    chart
        .draw_series((0..n).map(|k| {
            let a = c0 + (c1 - c0) * k as f64 / n as f64;
            let b = c0 + (c1 - c0) * (k + 1) as f64 / n as f64;
            Rectangle::new([(0.0, a), (1.0, b)], colour(0.5 * (a + b)).filled())
        }))
        .map_err(e)?;
    Ok(())
}

/// One curve: label, (x, y) points, colour, dashed.
pub struct Line {
    /// Legend label.
    pub label: String,
    /// Points.
    pub points: Vec<(f64, f64)>,
    /// Colour.
    pub colour: RGBColor,
    /// Dashed (drawn as short pieces).
    pub dashed: bool,
}

/// The default palette.
pub fn palette(k: usize) -> RGBColor {
    // Ten distinct colours (matplotlib's tab10 order, grey last): a plot of up to ten lines
    // repeats none (energy.png of a contact run has eight).
    const P: [RGBColor; 10] = [
        RGBColor(31, 119, 180),
        RGBColor(214, 39, 40),
        RGBColor(44, 160, 44),
        RGBColor(148, 103, 189),
        RGBColor(255, 127, 14),
        RGBColor(23, 190, 207),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(188, 189, 34),
        RGBColor(127, 127, 127),
    ];
    P[k % P.len()]
}

/// One panel of [`panels`]: title, y label, lines, and the x range shown (None: all the
/// data; e.g. the contact zone of a long interface, [`contact_view`]).
pub type Panel = (String, String, Vec<Line>, Option<(f64, f64)>);

/// The x range that shows a contact zone with context: the points of `lines` with y > 0
/// (the pressure) span the zone; the view adds half its width on each side (at least 2 % of
/// the data's range), within the data's range. None when there is no zone or the view would
/// cover most (80 %) of the data anyway.
pub fn contact_view(lines: &[Line]) -> Option<(f64, f64)> {
    let all = lines.iter().flat_map(|l| l.points.iter());
    let (f0, f1) = all
        .clone()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.0), b.max(p.0))
        });
    let (z0, z1) = all
        .filter(|p| p.1 > 0.0)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.0), b.max(p.0))
        });
    if !(f1 > f0 && z1 >= z0) {
        return None;
    }
    let context = (0.5 * (z1 - z0)).max(0.02 * (f1 - f0));
    let view = ((z0 - context).max(f0), (z1 + context).min(f1));
    (view.1 - view.0 < 0.8 * (f1 - f0)).then_some(view)
}

/// Panels of curves, one panel per entry of `panels` (title, y label, lines, x view),
/// stacked vertically with a common x label; `log_y` for logarithmic y axes (positive values,
/// ticks from [`log_ticks`] so that a range of less than a decade is labelled too). Constant
/// data (the shear of a frictionless contact) gets a valid axis ([`axis_range`]); legends go
/// to the corner with the least data.
pub fn panels_plot(path: &Path, panels: &[Panel], x_desc: &str, log_y: bool) -> Result<(), String> {
    // One function, ~150 lines (moved whole from the command line): plotters' chart type
    // differs between the linear and the logarithmic y axis, so the two branches draw the
    // same panel twice over; splitting them apart would pass the shared layout (ranges,
    // tick labels, legend placement) through a dozen arguments.
    register_font()?;
    let rows = panels.len().max(1);
    let root = Canvas::new(path, (1100, 360 * rows as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let areas = root.split_evenly((rows, 1));
    for (area, (title, y_desc, lines, view)) in areas.iter().zip(panels) {
        // The lines within the view (all of them without one).
        let lines: Vec<Line> = lines
            .iter()
            .map(|l| Line {
                label: l.label.clone(),
                points: l
                    .points
                    .iter()
                    .copied()
                    .filter(|p| view.is_none_or(|v| p.0 >= v.0 && p.0 <= v.1))
                    .collect(),
                colour: l.colour,
                dashed: l.dashed,
            })
            .collect();
        let xs = lines.iter().flat_map(|l| l.points.iter().map(|p| p.0));
        let (x0, x1) = match view {
            Some(v) => *v,
            None => xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(x), b.max(x))
            }),
        };
        let ys = lines.iter().flat_map(|l| l.points.iter().map(|p| p.1));
        let (y0, y1) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| {
            (a.min(y), b.max(y))
        });
        if !(x0.is_finite() && y0.is_finite()) {
            continue;
        }
        let (x0, x1) = if x1 > x0 {
            (x0, x1)
        } else {
            axis_range(x0, x1, 0.0)
        };
        let mut builder = ChartBuilder::on(area);
        builder
            .caption(title, (FAMILY, super::style::title_size(title, 18.0, 1100)))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(80);
        // A line without a label only widens the y range (room for the legend: the
        // dynamic energy plot); it is neither drawn nor listed.
        let lines: Vec<Line> = lines.into_iter().filter(|l| !l.label.is_empty()).collect();
        let mut occupied = Vec::new();
        for l in &lines {
            occupied.extend(densify(&l.points));
        }
        let labels: Vec<&str> = lines.iter().map(|l| l.label.as_str()).collect();
        if log_y {
            let pos: Vec<f64> = lines
                .iter()
                .flat_map(|l| l.points.iter().map(|p| p.1))
                .filter(|&v| v > 0.0 && v.is_finite())
                .collect();
            let lo = pos.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = pos.iter().copied().fold(0.0, f64::max);
            let (lo, hi) = if lo.is_finite() && hi > 0.0 {
                (lo, hi)
            } else {
                (1.0, 1.0)
            };
            let (y0, y1) = (lo / 1.3, hi * 1.3);
            let mut chart = builder
                .build_cartesian_2d(
                    x0..x1,
                    (y0..y1).log_scale().with_key_points(log_ticks(y0, y1)),
                )
                .map_err(e)?;
            chart
                .configure_mesh()
                .x_desc(x_desc)
                .y_desc(y_desc.as_str())
                .x_label_formatter(&tick)
                .y_label_formatter(&sig)
                .label_style((FAMILY, 13))
                .axis_desc_style((FAMILY, 15))
                .light_line_style(WHITE.mix(0.0))
                .draw()
                .map_err(e)?;
            for l in &lines {
                let c = l.colour;
                let pts: Vec<(f64, f64)> = l.points.iter().copied().filter(|p| p.1 > 0.0).collect();
                chart
                    .draw_series(LineSeries::new(pts.clone(), c.stroke_width(2)))
                    .map_err(e)?
                    .label(l.label.clone())
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                    });
                chart
                    .draw_series(pts.iter().map(|&p| Circle::new(p, 4, c.filled())))
                    .map_err(e)?;
            }
            // The legend's corner, on the log axis's fractions (log y).
            let lin: Vec<(f64, f64)> = occupied
                .iter()
                .filter(|p| p.1 > 0.0)
                .map(|p| (p.0, p.1.ln()))
                .collect();
            let px = chart.plotting_area().dim_in_pixel();
            let frac = super::style::legend_frac(&labels, 14.0, px);
            let (corner, _) =
                super::style::emptiest_corner(&lin, (x0, x1), (y0.ln(), y1.ln()), frac);
            chart
                .configure_series_labels()
                .position(corner)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .label_font((FAMILY, 14))
                .draw()
                .map_err(e)?;
        } else {
            let (lo, hi) = (y0.min(0.0), y1.max(0.0));
            let (y0, y1) = axis_range(lo, hi, 0.08);
            let mut chart = builder.build_cartesian_2d(x0..x1, y0..y1).map_err(e)?;
            styled_axes(&mut chart, x_desc, y_desc, 13)?;
            chart
                .draw_series(LineSeries::new(
                    [(x0, 0.0), (x1, 0.0)],
                    BLACK.mix(0.3).stroke_width(1),
                ))
                .map_err(e)?;
            for l in &lines {
                let c = l.colour;
                if l.dashed {
                    let pts = l.points.clone();
                    chart
                        .draw_series(
                            pts.windows(2)
                                .step_by(2)
                                .map(|w| PathElement::new(vec![w[0], w[1]], c.stroke_width(2))),
                        )
                        .map_err(e)?
                        .label(l.label.clone())
                        .legend(move |(x, y)| {
                            PathElement::new(vec![(x, y), (x + 8, y)], c.stroke_width(2))
                        });
                } else {
                    chart
                        .draw_series(LineSeries::new(l.points.clone(), c.stroke_width(2)))
                        .map_err(e)?
                        .label(l.label.clone())
                        .legend(move |(x, y)| {
                            PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                        });
                }
            }
            legend_avoiding(&mut chart, &occupied, &labels)?;
        }
    }
    root.present().map_err(e)?;
    Ok(())
}

/// Grouped bars of relative changes (%) per metric, one bar per series, with the paper's
/// values as black markers where given.
pub fn change_bars(
    path: &Path,
    metrics: &[String],
    series: &[(String, Vec<f64>)],
    paper: Option<&[Option<f64>]>,
    title: &str,
) -> Result<(), String> {
    register_font()?;
    let root = Canvas::new(path, (1100, 600)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let mut vals: Vec<f64> = series.iter().flat_map(|s| s.1.iter().copied()).collect();
    if let Some(p) = paper {
        vals.extend(p.iter().flatten());
    }
    let lo = vals.iter().copied().fold(0.0f64, f64::min);
    let hi = vals.iter().copied().fold(0.0f64, f64::max);
    let pad = 0.1 * (hi - lo).max(1.0);
    let n = metrics.len();
    let mut chart = ChartBuilder::on(&root)
        .caption(title, (FAMILY, 20))
        .margin(20)
        .x_label_area_size(50)
        .y_label_area_size(70)
        .build_cartesian_2d(-0.5..(n as f64 - 0.5), (lo - pad)..(hi + pad))
        .map_err(e)?;
    let names = metrics.to_vec();
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_labels(n.max(1))
        .x_label_formatter(&move |v| {
            let k = v.round();
            if (v - k).abs() < 1e-6 && k >= 0.0 && (k as usize) < names.len() {
                names[k as usize].clone()
            } else {
                String::new()
            }
        })
        .y_desc("change against the first material, %")
        .y_label_formatter(&tick)
        .label_style((FAMILY, 14))
        .axis_desc_style((FAMILY, 15))
        .draw()
        .map_err(e)?;
    let m = series.len().max(1) as f64;
    let width = 0.7 / m;
    for (k, (label, values)) in series.iter().enumerate() {
        let c = palette(k + 1);
        chart
            .draw_series(values.iter().enumerate().map(|(i, &v)| {
                let x0 = i as f64 - 0.35 + k as f64 * width;
                Rectangle::new([(x0, 0.0), (x0 + width * 0.9, v)], c.filled())
            }))
            .map_err(e)?
            .label(label.clone())
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 15, y + 5)], c.filled()));
    }
    if let Some(p) = paper {
        chart
            .draw_series(p.iter().enumerate().filter_map(|(i, v)| {
                v.map(|v| Cross::new((i as f64, v), 8, BLACK.stroke_width(3)))
            }))
            .map_err(e)?
            .label("paper")
            .legend(|(x, y)| Cross::new((x + 7, y), 6, BLACK.stroke_width(3)));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerLeft)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FAMILY, 13))
        .draw()
        .map_err(e)?;
    root.present().map_err(e)?;
    Ok(())
}

/// Draws every plot of a 2D run into `dir` (the data files and checks are
/// [`crate::bem::write_bem`]'s).
pub(crate) fn write_plots(
    dir: &Path,
    case: &BemCase,
    out: &BemOutcome,
    summary: &BemSummary,
) -> IoResult<()> {
    let v = &out.main;
    if v.steps.iter().any(|s| !s.pairs.is_empty()) {
        let panels = interface_panels(v);
        draw_atomic(dir, "interfaces.png", |p| {
            panels_plot(p, &panels, "x, mm", false)
        })?;
    }
    if !v.fields.is_empty() {
        for (k, st) in v.steps.iter().enumerate() {
            field_maps(dir, case, v, k, &st.name)?;
        }
    }
    if let (Some(d), Some(ds)) = (&v.damage, &summary.damage) {
        damage_plots(dir, v, d, ds)?;
    }
    if let Some(c) = &summary.compare {
        let series: Vec<(String, Vec<f64>)> = c
            .rows
            .iter()
            .skip(1)
            .map(|r| {
                (
                    format!("{} vs {}", r.material, c.rows[0].material),
                    r.change_percent.clone(),
                )
            })
            .collect();
        draw_atomic(dir, "compare.png", |p| {
            change_bars(
                p,
                &c.metrics,
                &series,
                c.paper_change_percent.as_deref(),
                &format!(
                    "{}: {} against {} (step {})",
                    c.region,
                    c.rows
                        .iter()
                        .skip(1)
                        .map(|r| r.material.as_str())
                        .collect::<Vec<_>>()
                        .join(", "),
                    c.rows[0].material,
                    c.step
                ),
            )
        })?;
    }
    Ok(())
}

/// The panels of `interfaces.png`: per pair the contact pressure and the tangential
/// traction along x, one line per step.
fn interface_panels(v: &Variant) -> Vec<Panel> {
    let mut panels = Vec::new();
    let npairs = v.steps[0].pairs.len();
    for p in 0..npairs {
        let pair = &v.steps[0].pairs[p];
        let mut pl = Vec::new();
        let mut ql = Vec::new();
        for (k, st) in v.steps.iter().enumerate() {
            let nodes = &st.pairs[p].nodes;
            let pts = |g: &dyn Fn(&ContactNode) -> f64| -> Vec<(f64, f64)> {
                let mut v: Vec<(f64, f64)> = nodes
                    .iter()
                    .filter(|n| n.state != ContactState::Outside)
                    .map(|n| (1e3 * n.position[0], g(n)))
                    .collect();
                v.sort_by(|a, b| a.0.total_cmp(&b.0));
                v
            };
            pl.push(Line {
                label: st.name.clone(),
                points: pts(&|n| n.pressure / 1e6),
                colour: palette(k),
                dashed: false,
            });
            ql.push(Line {
                label: st.name.clone(),
                points: pts(&|n| n.shear / 1e6),
                colour: palette(k),
                dashed: false,
            });
        }
        // Both panels of a pair show its contact zone (with context) where that is a
        // small part of the interface (the gmsh Hertz example: 0.2 mm of 20 mm).
        let view = contact_view(&pl);
        panels.push((
            format!("contact pressure, {} on {}", pair.slave, pair.master),
            "p, MPa".to_string(),
            pl,
            view,
        ));
        panels.push((
            format!("tangential traction, {} on {}", pair.slave, pair.master),
            "q, MPa".to_string(),
            ql,
            view,
        ));
    }
    panels
}

/// The maps of sigma_xx and sigma_int over every sampled region in step `k`.
fn field_maps(dir: &Path, case: &BemCase, v: &Variant, k: usize, step: &str) -> IoResult<()> {
    let name = file_name(step);
    let sxx: Vec<Vec<f64>> = v
        .fields
        .iter()
        .map(|f| f.samples[k].iter().map(|x| x.stress.xx / 1e6).collect())
        .collect();
    let sint: Vec<Vec<f64>> = v
        .fields
        .iter()
        .map(|f| {
            f.samples[k]
                .iter()
                .map(|x| stress_intensity(f, x) / 1e6)
                .collect()
        })
        .collect();
    for (values, key, title, scale) in [
        (&sxx, "sigma_xx", "sigma_xx", Scale::Diverging),
        (
            &sint,
            "sigma_int",
            "stress intensity sigma_int",
            Scale::Sequential,
        ),
    ] {
        let parts: Vec<MapPart> = v
            .fields
            .iter()
            .zip(values)
            .map(|(f, vals)| MapPart {
                nodes: &f.nodes,
                triangles: &f.triangles,
                values: vals,
            })
            .collect();
        draw_atomic(dir, &format!("{key}_{name}.png"), |p| {
            field_map(
                p,
                &parts,
                scale,
                &format!("{title}, step {step}: {}", case.title),
                "MPa",
            )
        })?;
    }
    Ok(())
}

/// The psi map of the damaged region and the sweep's three panels.
fn damage_plots(dir: &Path, v: &Variant, d: &DamageOutcome, ds: &DamageSummary) -> IoResult<()> {
    let f = v
        .fields
        .iter()
        .find(|f| f.region == d.region)
        .ok_or_else(|| IoError::Shape {
            what: "damage".into(),
            detail: "no field of the region".into(),
        })?;
    let parts = [MapPart {
        nodes: &f.nodes,
        triangles: &f.triangles,
        values: &d.psi,
    }];
    let limit_text = if d.unit == DamageUnit::Pascal {
        format!("{:.4} MPa", d.limit / 1e6)
    } else {
        format!("{:.4e} {}", d.limit, d.unit)
    };
    draw_atomic(dir, &psi_file(&d.quantity), |p| {
        field_map(
            p,
            &parts,
            Scale::Damage,
            &format!(
                "psi = {} / {limit_text} over {} (grey: psi < 1), step {}",
                d.quantity, d.region, d.step
            ),
            "psi",
        )
    })?;
    let sweep = &ds.sweep;
    if sweep.is_empty() {
        return Ok(());
    }
    let scale = if d.unit == DamageUnit::Pascal {
        1e-6
    } else {
        1.0
    };
    let unit = if d.unit == DamageUnit::Pascal {
        "MPa"
    } else {
        d.unit.symbol()
    };
    let series = |g: &dyn Fn(&Dangerous) -> f64| -> Vec<(f64, f64)> {
        sweep.iter().map(|s| (s.limit * scale, g(s))).collect()
    };
    let panels = vec![
        (
            format!("dangerous area V ({}), {}", d.quantity, d.region),
            "V, mm^2".to_string(),
            vec![Line {
                label: "V".into(),
                points: series(&|s| s.dangerous_area_m2 * 1e6),
                colour: palette(0),
                dashed: false,
            }],
            None,
        ),
        (
            format!("damageability Psi ({}), {}", d.quantity, d.region),
            "Psi, mm^2".to_string(),
            vec![Line {
                label: "Psi".into(),
                points: series(&|s| s.damageability_m2 * 1e6),
                colour: palette(1),
                dashed: false,
            }],
            None,
        ),
        (
            "largest damage psi_max".to_string(),
            "psi_max".to_string(),
            vec![Line {
                label: "psi_max".into(),
                points: series(&|s| s.psi_max),
                colour: palette(2),
                dashed: false,
            }],
            None,
        ),
    ];
    draw_atomic(dir, "damage_sweep.png", |p| {
        panels_plot(p, &panels, &format!("limit, {unit}"), true)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_contact_view_zooms_to_a_small_zone_with_context() {
        // The gmsh Hertz example: a 20 mm interface, contact over |x| <= 0.105 mm.
        let points: Vec<(f64, f64)> = (0..=2000)
            .map(|k| {
                let x = -10.0 + 20.0 * k as f64 / 2000.0;
                (x, (1.0 - (x / 0.105).powi(2)).max(0.0).sqrt())
            })
            .collect();
        let line = |pts: Vec<(f64, f64)>| Line {
            label: "press".into(),
            points: pts,
            colour: palette(0),
            dashed: false,
        };
        let v = contact_view(&[line(points.clone())]).unwrap();
        // Zone [-0.1, 0.1] (the nodes inside), 2 % of 20 mm = 0.4 mm context each side.
        assert!(v.0 < -0.1 && v.1 > 0.1 && v.1 - v.0 < 1.2, "{v:?}");
        // A zone over most of the interface: no zoom.
        let wide: Vec<(f64, f64)> = points.iter().map(|p| (p.0, 1.0 + p.1)).collect();
        assert!(contact_view(&[line(wide)]).is_none());
        // No contact: no zoom.
        let none: Vec<(f64, f64)> = points.iter().map(|p| (p.0, 0.0)).collect();
        assert!(contact_view(&[line(none)]).is_none());
    }

    /// psi = 2 - r on a fan of triangles around the origin: the isoline psi = 1 crosses each
    /// triangle's two radial edges at r = 1 exactly (psi linear along them).
    #[test]
    fn the_triangle_isoline_is_where_psi_is_one() {
        let k = 12;
        let mut nodes = vec![[0.0, 0.0]];
        for i in 0..k {
            let t = 2.0 * std::f64::consts::PI * i as f64 / k as f64;
            nodes.push([2.0 * t.cos(), 2.0 * t.sin()]);
        }
        let tris: Vec<[usize; 3]> = (0..k).map(|i| [0, 1 + i, 1 + (i + 1) % k]).collect();
        let psi: Vec<f64> = nodes
            .iter()
            .map(|n| 2.0 - (n[0] * n[0] + n[1] * n[1]).sqrt())
            .collect();
        let segs = isoline_triangles(&nodes, &tris, &psi, 1.0);
        assert_eq!(segs.len(), k);
        for (a, b) in segs {
            for p in [a, b] {
                assert!(((p.0 * p.0 + p.1 * p.1).sqrt() - 1.0).abs() < 1e-12);
            }
        }
    }
}
