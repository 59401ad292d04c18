//! The plots of rough, measured and periodic contacts: the contact patches map, the contact
//! area fraction against the load with the small-load linear law, and the PSD of the surface
//! with its input spectrum.

use super::canvas::Canvas;
use super::style::*;
use plotters::prelude::*;
use std::path::Path;
use tribo::surface::statistics::PsdBin;
use tribo::SurfaceGrid;
use tribo_case::rough::{LoadStep, KAPPA_BGT, KAPPA_PERSSON, KAPPA_SIMULATIONS};

/// Ten distinct colours (Tableau 10) for the patches.
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

/// A reference law drawn on the area plot: label, colour, dashed, points.
type LawLine = (String, RGBColor, bool, Vec<(f64, f64)>);

/// The length unit of a map of half widths `h` (m): um below 0.5 mm, else mm; (factor, name).
fn map_unit(h: f64) -> (f64, &'static str) {
    if h < 5e-4 {
        (1e6, "um")
    } else {
        (1e3, "mm")
    }
}

/// Map of the contact patches (`labels`: 0 out of contact, k > 0 patch k): each patch in one
/// of ten distinct colours (patch k in colour (7 k) mod 10, so that neighbouring labels
/// differ), out of contact white; equal aspect.
pub fn patches_map(
    path: &Path,
    grid: &SurfaceGrid,
    labels: &[u32],
    count: usize,
    title: &str,
) -> Result<(), String> {
    register_font()?;
    let (hx, hy) = grid.half_widths();
    let (f, unit) = map_unit(hx.max(hy));
    let (hx, hy) = (f * hx, f * hy);
    let height = map_height((-hx, hx), (-hy, hy), 860, 115, (300, 1000));
    let root = Canvas::new(path, (960, height)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let mut chart = map_chart(
        &root,
        (-hx, hx),
        (-hy, hy),
        &format!("Contact patches ({count}, 4-connected): {title}"),
        (&format!("x, {unit}"), &format!("y, {unit}")),
        &tick,
    )?;
    let (dx, dy) = (f * grid.dx(), f * grid.dy());
    chart
        .draw_series(
            (0..grid.ny())
                .flat_map(|iy| (0..grid.nx()).map(move |ix| (ix, iy)))
                .filter(|&(ix, iy)| labels[grid.index(ix, iy)] > 0)
                .map(|(ix, iy)| {
                    let (x, y) = (f * grid.x(ix), f * grid.y(iy));
                    let l = labels[grid.index(ix, iy)] as usize;
                    Rectangle::new(
                        [(x - 0.5 * dx, y - 0.5 * dy), (x + 0.5 * dx, y + 0.5 * dy)],
                        PALETTE[(7 * l) % PALETTE.len()].filled(),
                    )
                }),
        )
        .map_err(e)?;
    // The window's outline (the period on a periodic grid).
    chart
        .draw_series(LineSeries::new(
            [(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy), (-hx, -hy)],
            BLACK.stroke_width(1),
        ))
        .map_err(e)?;
    root.present().map_err(e)?;
    Ok(())
}

/// The contact area fraction A/A0 against the nominal mean pressure over E*, p/E* (the
/// sweep's loads, markers), with the small-load linear law `A/A0 = kappa p/(E* h'_rms)`
/// (`rms_slope` = h'_rms of the composite surface) drawn for kappa = 2 (the simulations of
/// Hyun et al. 2004) and dashed for the theories' bounds sqrt(8/pi) (Persson) and sqrt(2 pi)
/// (Bush, Gibson & Thomas).
pub fn area_vs_load(
    path: &Path,
    steps: &[LoadStep],
    composite_modulus: f64,
    rms_slope: Option<f64>,
    title: &str,
) -> Result<(), String> {
    register_font()?;
    let root = Canvas::new(path, (960, 720)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let pts: Vec<(f64, f64)> = steps
        .iter()
        .map(|s| (s.mean_pressure / composite_modulus, s.area_fraction))
        .collect();
    let x1 = pts.iter().map(|p| p.0).fold(0.0, f64::max);
    let y1 = pts.iter().map(|p| p.1).fold(0.0, f64::max);
    let x1 = if x1 > 0.0 { 1.05 * x1 } else { 1.0 };
    let law = |kappa: f64| -> Option<Vec<(f64, f64)>> {
        let s = rms_slope.filter(|s| *s > 0.0)?;
        // Up to the largest load, or where the law reaches full contact.
        let x_end = x1.min(s / kappa);
        Some(vec![(0.0, 0.0), (x_end, kappa * x_end / s)])
    };
    let lines: Vec<LawLine> = [
        // One colour per law (red, orange, green): the two dashed bounds were both red and
        // the legend could not tell them apart.
        (
            KAPPA_SIMULATIONS,
            "kappa = 2 (Hyun et al. 2004)",
            false,
            RGBColor(214, 39, 40),
        ),
        (
            KAPPA_PERSSON,
            "kappa = sqrt(8/pi) (Persson)",
            true,
            RGBColor(255, 127, 14),
        ),
        (
            KAPPA_BGT,
            "kappa = sqrt(2 pi) (Bush et al.)",
            true,
            RGBColor(44, 160, 44),
        ),
    ]
    .into_iter()
    .filter_map(|(k, name, dashed, colour)| law(k).map(|p| (name.to_string(), colour, dashed, p)))
    .collect();
    let y_top = lines
        .iter()
        .flat_map(|l| l.3.iter().map(|p| p.1))
        .fold(y1, f64::max);
    let y_top = if y_top > 0.0 { 1.25 * y_top } else { 1.0 };
    let mut chart = ChartBuilder::on(&root)
        .caption(title, (FAMILY, title_size(title, 20.0, 960)))
        .margin(20)
        .x_label_area_size(55)
        .y_label_area_size(80)
        .build_cartesian_2d(0.0..x1, 0.0..y_top.min(1.05))
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc("nominal mean pressure over E*, p / E*")
        .y_desc("contact area fraction A / A0")
        .x_label_formatter(&axis_labels(0.0, x1, false))
        .y_label_formatter(&axis_labels(0.0, y_top.min(1.05), false))
        .label_style((FAMILY, 15))
        .axis_desc_style((FAMILY, 17))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(e)?;
    let mut names: Vec<String> = Vec::new();
    let mut occupied = densify(&pts);
    for (name, colour, dashed, p) in &lines {
        let c = *colour;
        occupied.extend(densify(p));
        let style = c.stroke_width(2);
        if *dashed {
            let n = 40;
            let (a, b) = (p[0], p[1]);
            chart
                .draw_series((0..n).step_by(2).map(move |k| {
                    let t0 = k as f64 / n as f64;
                    let t1 = (k + 1) as f64 / n as f64;
                    PathElement::new(
                        vec![
                            (a.0 + t0 * (b.0 - a.0), a.1 + t0 * (b.1 - a.1)),
                            (a.0 + t1 * (b.0 - a.0), a.1 + t1 * (b.1 - a.1)),
                        ],
                        style,
                    )
                }))
                .map_err(e)?
                .label(name.clone())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
        } else {
            chart
                .draw_series(LineSeries::new(p.clone(), style))
                .map_err(e)?
                .label(name.clone())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
        }
        names.push(name.clone());
    }
    let blue = RGBColor(31, 119, 180);
    chart
        .draw_series(LineSeries::new(pts.clone(), blue.stroke_width(2)))
        .map_err(e)?
        .label("tribo (each load warm-started from the previous)")
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], blue.stroke_width(2)));
    chart
        .draw_series(pts.iter().map(|&p| Circle::new(p, 4, blue.filled())))
        .map_err(e)?;
    names.push("tribo (each load warm-started from the previous)".into());
    let labels: Vec<&str> = names.iter().map(String::as_str).collect();
    legend_avoiding(&mut chart, &occupied, &labels)?;
    root.present().map_err(e)?;
    Ok(())
}

/// The radially averaged PSD of the surface (markers, log-log; bins below 1e-12 of the
/// largest, round-off, left out), with the input spectrum `input` (q, C) overlaid where given.
pub fn psd(
    path: &Path,
    bins: &[PsdBin],
    input: Option<&[(f64, f64)]>,
    title: &str,
) -> Result<(), String> {
    register_font()?;
    let root = Canvas::new(path, (960, 720)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    // Bins below 1e-12 of the largest are the transform's round-off (outside a generated
    // surface's band): not drawn, so that the axis shows the spectrum.
    let top = bins.iter().map(|b| b.psd).fold(0.0, f64::max);
    let pts: Vec<(f64, f64)> = bins
        .iter()
        .filter(|b| b.q > 0.0 && b.psd > 1e-12 * top)
        .map(|b| (b.q, b.psd))
        .collect();
    let input: Vec<(f64, f64)> = input
        .unwrap_or(&[])
        .iter()
        .copied()
        .filter(|p| p.0 > 0.0 && p.1 > 0.0)
        .collect();
    let all = pts.iter().chain(&input);
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
    for p in all {
        x0 = x0.min(p.0);
        x1 = x1.max(p.0);
        y0 = y0.min(p.1);
        y1 = y1.max(p.1);
    }
    if !(x0.is_finite() && x1 > x0 && y0.is_finite() && y1 > y0) {
        return Err("psd: no positive values".into());
    }
    let (x0, x1) = (x0 / 1.3, x1 * 1.3);
    let (y0, y1) = (y0 / 3.0, y1 * 30.0);
    let mut chart = ChartBuilder::on(&root)
        .caption(title, (FAMILY, title_size(title, 20.0, 960)))
        .margin(20)
        .x_label_area_size(55)
        .y_label_area_size(90)
        .build_cartesian_2d(
            (x0..x1).log_scale().with_key_points(log_ticks(x0, x1)),
            (y0..y1).log_scale().with_key_points(log_ticks(y0, y1)),
        )
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc("wavenumber q, rad/m")
        .y_desc("PSD C(q), m^4")
        .x_label_formatter(&axis_labels(x0, x1, true))
        .y_label_formatter(&axis_labels(y0, y1, true))
        .label_style((FAMILY, 15))
        .axis_desc_style((FAMILY, 17))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(e)?;
    let blue = RGBColor(31, 119, 180);
    chart
        .draw_series(pts.iter().map(|&p| Circle::new(p, 3, blue.filled())))
        .map_err(e)?
        .label("radially averaged PSD of the surface on the grid")
        .legend(move |(x, y)| Circle::new((x + 10, y), 3, blue.filled()));
    if !input.is_empty() {
        let red = RGBColor(214, 39, 40);
        chart
            .draw_series(LineSeries::new(input.clone(), red.stroke_width(2)))
            .map_err(e)?
            .label("input spectrum (C_r times the shape)")
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], red.stroke_width(2)));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FAMILY, 14))
        .draw()
        .map_err(e)?;
    root.present().map_err(e)?;
    Ok(())
}
