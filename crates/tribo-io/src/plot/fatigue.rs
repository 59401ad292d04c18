//! The plots of `tribo fatigue`: the S-N diagram (log-log) and the limiting-state diagram.

use super::canvas::Canvas;
use super::style::{register_font, title_size};
use plotters::prelude::*;
use std::path::Path;
use tribo::analysis::woehler::{Life, Load};
use tribo_case::fatigue::{DiagramReport, FitReport};

const FAMILY: &str = "sans-serif";
const BLUE: RGBColor = RGBColor(31, 119, 180);
const RED_: RGBColor = RGBColor(214, 39, 40);
const GREEN_: RGBColor = RGBColor(44, 160, 44);

fn e<E: std::fmt::Display>(err: E) -> String {
    err.to_string()
}

/// Round load values (MPa) for a log axis spanning less than a decade: 1, 1.5, 2, 2.5, 3,
/// 4, 5, 6, 8 times powers of ten inside [lo, hi].
fn nice_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let mut t = Vec::new();
    let mut p = 10f64.powf(lo.log10().floor());
    while p <= hi {
        for m in [1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0] {
            let v = m * p;
            if v >= lo && v <= hi {
                t.push(v);
            }
        }
        p *= 10.0;
    }
    t
}

fn measure_label(r: &FitReport) -> &'static str {
    match r.measure {
        tribo::analysis::woehler::LoadMeasure::Amplitude => "stress amplitude S_a",
        tribo::analysis::woehler::LoadMeasure::Range => "stress range 2 S_a",
        tribo::analysis::woehler::LoadMeasure::ContactPressure => "max. contact pressure p0",
    }
}

/// Log-log S-N plot: cycles (x) against load in MPa (y); fractures (dots), run-outs
/// (open triangles), the E739 median line with its confidence band over the regression's
/// range, and the maximum-likelihood curve with its fatigue limit.
pub fn woehler(path: &Path, r: &FitReport) -> Result<(), String> {
    register_font()?;
    let root = Canvas::new(path, (960, 720)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let (mut smin, mut smax) = (f64::INFINITY, 0.0f64);
    let (mut nmin, mut nmax) = (f64::INFINITY, 0.0f64);
    for t in &r.points {
        smin = smin.min(t.load);
        smax = smax.max(t.load);
        nmin = nmin.min(t.cycles);
        nmax = nmax.max(t.cycles);
    }
    let (nlo, nhi) = (
        10f64.powf(nmin.log10().floor()),
        10f64.powf((nmax.log10() + 0.3).ceil()),
    );
    let (slo, shi) = (smin / 1e6 * 0.85, smax / 1e6 * 1.15);
    let caption = format!(
        "Woehler curve {} ({}): {}",
        r.kind.symbol(),
        r.limit_symbol,
        r.data
    );
    let mut chart = ChartBuilder::on(&root)
        .caption(&caption, (FAMILY, title_size(&caption, 18.0, 960)))
        .margin(20)
        .x_label_area_size(55)
        .y_label_area_size(75)
        .build_cartesian_2d(
            (nlo..nhi).log_scale(),
            (slo..shi).log_scale().with_key_points(nice_ticks(slo, shi)),
        )
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc("cycles N")
        .y_desc(format!("{}, MPa", measure_label(r)))
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .y_label_formatter(&|v| format!("{v:.0}"))
        .label_style((FAMILY, 15))
        .axis_desc_style((FAMILY, 17))
        .draw()
        .map_err(e)?;
    let fr: Vec<(f64, f64)> = r
        .points
        .iter()
        .filter(|t| !t.runout)
        .map(|t| (t.cycles, t.load / 1e6))
        .collect();
    let ro: Vec<(f64, f64)> = r
        .points
        .iter()
        .filter(|t| t.runout)
        .map(|t| (t.cycles, t.load / 1e6))
        .collect();
    chart
        .draw_series(fr.iter().map(|&p| Circle::new(p, 5, BLACK.filled())))
        .map_err(e)?
        .label("fracture")
        .legend(|(x, y)| Circle::new((x + 10, y), 5, BLACK.filled()));
    let grey = RGBColor(140, 140, 140);
    chart
        .draw_series(ro.iter().map(|&p| TriangleMarker::new(p, 7, grey.filled())))
        .map_err(e)?
        .label("run-out (no failure)")
        .legend(move |(x, y)| TriangleMarker::new((x + 10, y), 7, grey.filled()));
    if let Some(reg) = &r.regression {
        let k = 40;
        let mut median = Vec::new();
        let mut lower = Vec::new();
        let mut upper = Vec::new();
        for i in 0..=k {
            let s = reg.min_load * (reg.max_load / reg.min_load).powf(i as f64 / k as f64);
            let load = Load::new(s, r.measure).map_err(e)?;
            let (lo, med, hi) = reg.band_at(load, false).map_err(e)?;
            median.push((med, s / 1e6));
            lower.push((lo, s / 1e6));
            upper.push((hi, s / 1e6));
        }
        chart
            .draw_series(LineSeries::new(median, BLUE.stroke_width(2)))
            .map_err(e)?
            .label("E739 regression, median")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE.stroke_width(2)));
        let style = BLUE.mix(0.8).stroke_width(1);
        chart
            .draw_series(DashedLineSeries::new(lower, 6, 4, style))
            .map_err(e)?
            .label(format!(
                "{:.0} % confidence band of the median (t)",
                100.0 * reg.band.level
            ))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
        chart
            .draw_series(DashedLineSeries::new(upper, 6, 4, style))
            .map_err(e)?;
    }
    if let Some(m) = &r.max_likelihood {
        let c = &m.curve;
        let mut pts = Vec::new();
        let top = shi * 1e6;
        let k = 40;
        let sd = c.fatigue_limit();
        for i in 0..=k {
            let s = top * (sd / top).powf(i as f64 / k as f64);
            if s <= sd {
                break;
            }
            let load = Load::new(s, r.measure).map_err(e)?;
            if let Life::Finite(n) = c.cycles_to_failure(load).map_err(e)? {
                pts.push((n, s / 1e6));
            }
        }
        pts.push((c.knee_cycles(), sd / 1e6));
        pts.push((nhi, sd / 1e6));
        chart
            .draw_series(LineSeries::new(pts, RED_.stroke_width(2)))
            .map_err(e)?
            .label(format!(
                "max. likelihood: {} = {:.1} MPa, m = {:.2}, N_G = {:.2e}",
                r.limit_symbol,
                sd / 1e6,
                c.slope(),
                c.knee_cycles()
            ))
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED_.stroke_width(2)));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FAMILY, 14))
        .draw()
        .map_err(e)?;
    root.present().map_err(e)
}

/// The diagram ABCD in p0/p_f (x) and sigma_a/sigma_-1 (y): the safe region shaded, the
/// single-criterion limits (x = 1, y = 1) dashed, the points labelled, and the load state
/// with its ray to the boundary.
pub fn limit_diagram(path: &Path, r: &DiagramReport) -> Result<(), String> {
    register_font()?;
    let root = Canvas::new(path, (900, 760)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let d = &r.diagram;
    let pts: Vec<(f64, f64)> = d
        .points
        .iter()
        .map(|p| (p.pressure_ratio, p.stress_ratio))
        .collect();
    let mut xmax = pts.iter().map(|p| p.0).fold(1.0, f64::max);
    let mut ymax = pts.iter().map(|p| p.1).fold(1.0, f64::max);
    if let Some(c) = &r.state {
        xmax = xmax.max(c.pressure_ratio).max(c.boundary_pressure_ratio);
        ymax = ymax.max(c.stress_ratio).max(c.boundary_stress_ratio);
    }
    let (xmax, ymax) = (xmax * 1.15, ymax * 1.4);
    let caption = format!("Limiting states, mechano-rolling fatigue: {}", r.title);
    let mut chart = ChartBuilder::on(&root)
        .caption(&caption, (FAMILY, title_size(&caption, 18.0, 900)))
        .margin(20)
        .x_label_area_size(55)
        .y_label_area_size(75)
        .build_cartesian_2d(0.0..xmax, 0.0..ymax)
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc("contact pressure p0 / p_f")
        .y_desc("bending stress amplitude sigma_a / sigma_-1")
        .label_style((FAMILY, 15))
        .axis_desc_style((FAMILY, 17))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(e)?;
    let mut region = vec![(0.0, 0.0)];
    region.extend(&pts);
    chart
        .draw_series(std::iter::once(Polygon::new(
            region,
            GREEN_.mix(0.18).filled(),
        )))
        .map_err(e)?
        .label("safe region")
        .legend(|(x, y)| Rectangle::new([(x, y - 6), (x + 20, y + 6)], GREEN_.mix(0.3).filled()));
    let grey = BLACK.mix(0.4).stroke_width(1);
    chart
        .draw_series(DashedLineSeries::new([(1.0, 0.0), (1.0, ymax)], 6, 4, grey))
        .map_err(e)?
        .label("single-criterion limits p_f, sigma_-1")
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], grey));
    chart
        .draw_series(DashedLineSeries::new([(0.0, 1.0), (xmax, 1.0)], 6, 4, grey))
        .map_err(e)?;
    chart
        .draw_series(LineSeries::new(pts.clone(), BLACK.stroke_width(3)))
        .map_err(e)?
        .label(format!(
            "ABCD: direct effect {:.2}, back effect {:.2}",
            d.direct_effect, d.back_effect
        ))
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(3)));
    for p in &d.points {
        let at = (p.pressure_ratio, p.stress_ratio);
        chart
            .draw_series(std::iter::once(Circle::new(at, 5, BLACK.filled())))
            .map_err(e)?;
        chart
            .draw_series(std::iter::once(Text::new(
                p.name.to_string(),
                (at.0 + 0.015 * xmax, at.1 + 0.02 * ymax),
                (FAMILY, 22),
            )))
            .map_err(e)?;
    }
    if let Some(c) = &r.state {
        let colour = if c.inside { BLUE } else { RED_ };
        let s = (c.pressure_ratio, c.stress_ratio);
        let b = (c.boundary_pressure_ratio, c.boundary_stress_ratio);
        chart
            .draw_series(DashedLineSeries::new(
                [(0.0, 0.0), s, b],
                5,
                4,
                colour.stroke_width(1),
            ))
            .map_err(e)?;
        chart
            .draw_series(std::iter::once(TriangleMarker::new(s, 8, colour.filled())))
            .map_err(e)?
            .label(format!(
                "state sigma_a = {:.0} MPa, p0 = {:.0} MPa: load factor {:.2} ({})",
                c.stress_amplitude / 1e6,
                c.contact_pressure / 1e6,
                c.load_factor,
                if c.inside { "inside" } else { "outside" }
            ))
            .legend(move |(x, y)| TriangleMarker::new((x + 10, y), 8, colour.filled()));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FAMILY, 14))
        .draw()
        .map_err(e)?;
    root.present().map_err(e)
}
