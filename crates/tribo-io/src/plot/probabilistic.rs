//! The plot of a probabilistic damage result: the exceedance curves P(V >= v) and
//! P(psi_max >= x), side by side, with psi_max = 1 and P(psi_max >= 1) marked.

use super::canvas::Canvas;
use super::style::*;
use plotters::prelude::*;
use std::path::Path;
use tribo::analysis::damage::probabilistic::ProbabilisticDamage;

/// Draws `probabilistic.png`: left, P(V >= v) against v (the points with V > 0); right,
/// P(psi_max >= x) against x, with the dashed line x = 1 and the level P(psi_max >= 1).
pub fn exceedance(
    path: &Path,
    name: &str,
    r: &ProbabilisticDamage,
    dimension: usize,
) -> Result<(), String> {
    register_font()?;
    let root = Canvas::new(path, (1200, 560)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let title = format!(
        "{name}: random limit, P(psi_max >= 1) = {:.4}",
        r.probability_psi_max_ge_1
    );
    let root = root
        .titled(&title, (FAMILY, title_size(&title, 20.0, 1200)))
        .map_err(e)?;
    let (left, right) = root.split_horizontally(600);
    // Plotted in mm^3 (mm^2 in 2D): dangerous volumes are small fractions of a mm^3, whose
    // ticks in m^3 would all read 0.
    let (unit, scale) = if dimension == 2 {
        ("mm^2", 1e6)
    } else {
        ("mm^3", 1e9)
    };

    let vol: Vec<(f64, f64)> = r
        .points
        .iter()
        .filter(|p| p.volume > 0.0)
        .map(|p| (p.volume * scale, p.probability))
        .collect();
    let v1 = vol.iter().map(|p| p.0).fold(0.0f64, f64::max);
    let v1 = if v1 > 0.0 { v1 * 1.05 } else { 1.0 };
    let mut chart = ChartBuilder::on(&left)
        .margin(20)
        .x_label_area_size(55)
        .y_label_area_size(70)
        .build_cartesian_2d(0.0..v1, 0.0..1.0)
        .map_err(e)?;
    styled_axes(
        &mut chart,
        &format!("dangerous volume v ({unit})"),
        "P(V >= v)",
        15,
    )?;
    let blue = RGBColor(31, 119, 180);
    chart
        .draw_series(LineSeries::new(vol.iter().copied(), blue.stroke_width(2)))
        .map_err(e)?;
    chart
        .draw_series(vol.iter().map(|&p| Circle::new(p, 3, blue.filled())))
        .map_err(e)?;

    let psi: Vec<(f64, f64)> = r
        .points
        .iter()
        .map(|p| (p.psi_max, p.probability))
        .collect();
    let (x0, x1) = psi
        .iter()
        .fold((1.0f64, 1.0f64), |(a, b), p| (a.min(p.0), b.max(p.0)));
    let pad = 0.05 * (x1 - x0).max(1e-3);
    let (x0, x1) = (x0 - pad, x1 + pad);
    let mut chart = ChartBuilder::on(&right)
        .margin(20)
        .x_label_area_size(55)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, 0.0..1.0)
        .map_err(e)?;
    styled_axes(
        &mut chart,
        "psi_max = phi_max / phi_lim",
        "P(psi_max >= x)",
        15,
    )?;
    let red = RGBColor(214, 39, 40);
    chart
        .draw_series(LineSeries::new(psi.iter().copied(), red.stroke_width(2)))
        .map_err(e)?;
    chart
        .draw_series(psi.iter().map(|&p| Circle::new(p, 3, red.filled())))
        .map_err(e)?;
    let pf = r.probability_psi_max_ge_1;
    let n = 30;
    chart
        .draw_series((0..n).step_by(2).map(|k| {
            let a = k as f64 / n as f64;
            let b = (k + 1) as f64 / n as f64;
            PathElement::new(vec![(1.0, a), (1.0, b)], BLACK.mix(0.6).stroke_width(1))
        }))
        .map_err(e)?;
    chart
        .draw_series((0..n).step_by(2).map(|k| {
            let a = x0 + (x1 - x0) * k as f64 / n as f64;
            let b = x0 + (x1 - x0) * (k + 1) as f64 / n as f64;
            PathElement::new(vec![(a, pf), (b, pf)], BLACK.mix(0.6).stroke_width(1))
        }))
        .map_err(e)?;
    chart
        .draw_series([Circle::new((1.0, pf), 6, BLACK.stroke_width(2))])
        .map_err(e)?;
    root.present().map_err(e)?;
    Ok(())
}
