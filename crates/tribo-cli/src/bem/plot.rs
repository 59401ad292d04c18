//! PNG plots of 2D boundary element results: colour maps over the triangulated regions
//! (Fig. 7a, 8a), interface tractions along x for each step (Fig. 7b), the damage sweep
//! (Fig. 8b) and the material comparison.

use plotters::prelude::*;
use std::path::Path;

use crate::output::plot::{e, legend_box, register_font, styled_axes, tick, viridis, FAMILY};

/// Blue-white-red for signed values, `t` in [-1, 1].
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
    let root = BitMapBackend::new(path, (plot_w + 150, plot_h)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let (main, bar) = root.split_horizontally(plot_w);
    let mut chart = ChartBuilder::on(&main)
        .caption(title, (FAMILY, 20))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d((lo[0] - pad)..(hi[0] + pad), (lo[1] - pad)..(hi[1] + pad))
        .map_err(e)?;
    styled_axes(&mut chart, "x, mm", "y, mm", 14)?;
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
    const P: [RGBColor; 6] = [
        RGBColor(31, 119, 180),
        RGBColor(214, 39, 40),
        RGBColor(44, 160, 44),
        RGBColor(148, 103, 189),
        RGBColor(255, 127, 14),
        RGBColor(23, 190, 207),
    ];
    P[k % P.len()]
}

/// Panels of curves, one panel per entry of `panels` (title, y label, lines), stacked
/// vertically with a common x label; `log_y` for logarithmic y axes (positive values).
pub fn panels(
    path: &Path,
    panels: &[(String, String, Vec<Line>)],
    x_desc: &str,
    log_y: bool,
) -> Result<(), String> {
    register_font()?;
    let rows = panels.len().max(1);
    let root = BitMapBackend::new(path, (1100, 360 * rows as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let areas = root.split_evenly((rows, 1));
    for (area, (title, y_desc, lines)) in areas.iter().zip(panels) {
        let xs = lines.iter().flat_map(|l| l.points.iter().map(|p| p.0));
        let (x0, x1) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        });
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
            (x0 - 1.0, x0 + 1.0)
        };
        let mut builder = ChartBuilder::on(area);
        builder
            .caption(title, (FAMILY, 18))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(80);
        if log_y {
            let y0 = y0.max(f64::MIN_POSITIVE);
            let (y0, y1) = (y0 / 1.3, (y1.max(y0)) * 1.3);
            let mut chart = builder
                .build_cartesian_2d(x0..x1, (y0..y1).log_scale())
                .map_err(e)?;
            chart
                .configure_mesh()
                .x_desc(x_desc)
                .y_desc(y_desc.as_str())
                .x_label_formatter(&tick)
                .y_label_formatter(&|v| format!("{v:.3e}"))
                .label_style((FAMILY, 13))
                .axis_desc_style((FAMILY, 15))
                .draw()
                .map_err(e)?;
            for l in lines {
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
            legend_box(&mut chart)?;
        } else {
            let pad = 0.08
                * (y1 - y0)
                    .abs()
                    .max(y1.abs().max(y0.abs()) * 1e-3)
                    .max(f64::MIN_POSITIVE);
            let (y0, y1) = (y0.min(0.0) - pad, y1.max(0.0) + pad);
            let mut chart = builder.build_cartesian_2d(x0..x1, y0..y1).map_err(e)?;
            styled_axes(&mut chart, x_desc, y_desc, 13)?;
            chart
                .draw_series(LineSeries::new(
                    [(x0, 0.0), (x1, 0.0)],
                    BLACK.mix(0.3).stroke_width(1),
                ))
                .map_err(e)?;
            for l in lines {
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
            legend_box(&mut chart)?;
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
    let root = BitMapBackend::new(path, (1100, 600)).into_drawing_area();
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
