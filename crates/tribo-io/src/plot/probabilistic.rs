//! The plot of a probabilistic damage result: the exceedance curves P(V >= v) and
//! P(psi_max >= x), side by side, one curve per criterion with a random limit, with
//! psi_max = 1 and each P(psi_max >= 1) marked.

use super::bem::palette;
use super::canvas::Canvas;
use super::style::*;
use plotters::prelude::*;
use std::path::Path;
use tribo::analysis::damage::probabilistic::ProbabilisticDamage;

/// Draws `probabilistic.png` of one or more criteria (`entries`: name and result, drawn in
/// the palette's colours with a legend where there are several): left, P(V >= v) against v
/// (the points with V > 0); right, P(psi_max >= x) against x, with the dashed line x = 1 and
/// a circle at each P(psi_max >= 1) (the first criterion's level dashed).
pub fn exceedance(
    path: &Path,
    entries: &[(&str, &ProbabilisticDamage)],
    dimension: usize,
) -> Result<(), String> {
    let Some(&(name, first)) = entries.first() else {
        return Err("no probabilistic result to draw".into());
    };
    register_font()?;
    let root = Canvas::new(path, (1200, 560)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let title = if entries.len() == 1 {
        format!(
            "{name}: random limit, P(psi_max >= 1) = {:.4}",
            first.probability_psi_max_ge_1
        )
    } else {
        let parts: Vec<String> = entries
            .iter()
            .map(|(n, r)| format!("{n} {:.4}", r.probability_psi_max_ge_1))
            .collect();
        format!("random limits, P(psi_max >= 1): {}", parts.join(", "))
    };
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
    let labels: Vec<&str> = entries.iter().map(|(n, _)| *n).collect();

    let vols: Vec<Vec<(f64, f64)>> = entries
        .iter()
        .map(|(_, r)| {
            r.points
                .iter()
                .filter(|p| p.volume > 0.0)
                .map(|p| (p.volume * scale, p.probability))
                .collect()
        })
        .collect();
    let v1 = vols.iter().flatten().map(|p| p.0).fold(0.0f64, f64::max);
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
    for (k, vol) in vols.iter().enumerate() {
        let c = palette(k);
        chart
            .draw_series(LineSeries::new(vol.iter().copied(), c.stroke_width(2)))
            .map_err(e)?
            .label(labels[k])
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
        chart
            .draw_series(vol.iter().map(|&p| Circle::new(p, 3, c.filled())))
            .map_err(e)?;
    }
    if entries.len() > 1 {
        let pts: Vec<(f64, f64)> = vols.iter().flatten().copied().collect();
        legend_avoiding(&mut chart, &pts, &labels)?;
    }

    let psis: Vec<Vec<(f64, f64)>> = entries
        .iter()
        .map(|(_, r)| {
            r.points
                .iter()
                .map(|p| (p.psi_max, p.probability))
                .collect()
        })
        .collect();
    let (x0, x1) = psis
        .iter()
        .flatten()
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
    // The first criterion keeps the single-criterion plot's red.
    let colour = |k: usize| {
        if entries.len() == 1 {
            RGBColor(214, 39, 40)
        } else {
            palette(k)
        }
    };
    for (k, psi) in psis.iter().enumerate() {
        let c = colour(k);
        chart
            .draw_series(LineSeries::new(psi.iter().copied(), c.stroke_width(2)))
            .map_err(e)?
            .label(labels[k])
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
        chart
            .draw_series(psi.iter().map(|&p| Circle::new(p, 3, c.filled())))
            .map_err(e)?;
    }
    let pf = first.probability_psi_max_ge_1;
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
        .draw_series(
            entries.iter().map(|(_, r)| {
                Circle::new((1.0, r.probability_psi_max_ge_1), 6, BLACK.stroke_width(2))
            }),
        )
        .map_err(e)?;
    if entries.len() > 1 {
        let pts: Vec<(f64, f64)> = psis.iter().flatten().copied().collect();
        legend_avoiding(&mut chart, &pts, &labels)?;
    }
    root.present().map_err(e)?;
    Ok(())
}
