//! PNG plots with plotters, rendered with the DejaVu Sans font shipped in `assets/` (no
//! system fonts needed).

use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::FontStyle;
use std::path::Path;
use std::sync::OnceLock;
use tribo::kernels::hertz::HertzContact;
use tribo::SurfaceGrid;

/// DejaVu Sans (Bitstream Vera licence, see `assets/LICENSE-DejaVu.txt`).
static FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// The font family name the plots use.
pub(crate) const FAMILY: &str = "sans-serif";

/// Register the shipped font as `sans-serif` (once per process).
pub fn register_font() -> Result<(), String> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    DONE.get_or_init(|| {
        plotters::style::register_font(FAMILY, FontStyle::Normal, FONT)
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
    let root = BitMapBackend::new(path, (1040, 800)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let (main, bar) = root.split_horizontally(860);
    let (hx, hy) = grid.half_widths();
    let (hx, hy) = (1e3 * hx, 1e3 * hy);
    let pmax = pressure.iter().cloned().fold(0.0, f64::max);
    let pmax_gpa = if pmax > 0.0 { pmax / 1e9 } else { 1.0 };
    let mut chart = surface_chart(&main, hx, hy, &format!("Contact pressure: {title}"))?;
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
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font((FAMILY, 15))
            .draw()
            .map_err(e)?;
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

/// Axes in mm over the surface window |x| <= `hx`, |y| <= `hy` (mm) for the surface maps.
fn surface_chart<'a, 'b>(
    area: &'a DrawingArea<BitMapBackend<'b>, plotters::coord::Shift>,
    hx: f64,
    hy: f64,
    caption: &str,
) -> Result<
    ChartContext<
        'a,
        BitMapBackend<'b>,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    String,
> {
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FAMILY, 20))
        .margin(15)
        .x_label_area_size(50)
        .y_label_area_size(70)
        .build_cartesian_2d(-hx..hx, -hy..hy)
        .map_err(e)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("x, mm")
        .y_desc("y, mm")
        .x_label_formatter(&tick)
        .y_label_formatter(&tick)
        .label_style((FAMILY, 15))
        .axis_desc_style((FAMILY, 17))
        .draw()
        .map_err(e)?;
    Ok(chart)
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
    let top = 1.1 * pmax.max(p0).max(f64::MIN_POSITIVE) / 1e9;
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
    let root = BitMapBackend::new(path, (1200, 560)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let root = root.titled(title, (FAMILY, 20)).map_err(e)?;
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
        if let Some((f, label)) = reference {
            let samples = 600;
            let curve = (0..=samples).map(|s| {
                let t = -half + 2.0 * half * s as f64 / samples as f64;
                let v = if along_x { f(t, fixed) } else { f(fixed, t) };
                (1e3 * t, v / 1e9)
            });
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
        legend_box(&mut chart)?;
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
    let root = BitMapBackend::new(path, (960, 720)).into_drawing_area();
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
            (FAMILY, 20),
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
    let root = BitMapBackend::new(path, (960, 720)).into_drawing_area();
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
    let mut chart = ChartBuilder::on(&root)
        .caption(title, (FAMILY, 20))
        .margin(20)
        .x_label_area_size(55)
        .y_label_area_size(75)
        .build_cartesian_2d(x0..x1, (y0 - pad)..(y1 + pad))
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
    legend_box(&mut chart)?;
    root.present().map_err(e)?;
    Ok(())
}

/// A reference curve q(x, y) (Pa) and its legend label.
pub type Reference<'a> = (&'a dyn Fn(f64, f64) -> f64, &'a str);

pub(crate) fn legend_box<'a, DB: DrawingBackend + 'a, CT: plotters::coord::CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FAMILY, 14))
        .draw()
        .map_err(e)
}

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
    let root = BitMapBackend::new(path, (900, 800)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let (hx, hy) = grid.half_widths();
    let (hx, hy) = (1e3 * hx, 1e3 * hy);
    let mut chart = surface_chart(&root, hx, hy, &format!("Stick and slip: {title}"))?;
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
    legend_box(&mut chart)?;
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
    let top = 1.15 * qmax.max(f64::MIN_POSITIVE) / 1e9;
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
/// (m), axes in mm; with `depth_down` the vertical axis is the depth z, drawn downward.
/// `quantity` = (name, divisor, unit): values are shown divided by the divisor, e.g.
/// ("sigma_xx", 1e9, "GPa"), or ("psi", 1.0, "1") for a dimensionless field.
pub fn section(
    path: &Path,
    h: (&[f64], &str),
    v: (&[f64], &str),
    values: &[f64],
    depth_down: bool,
    quantity: (&str, f64, &str),
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
    let root = BitMapBackend::new(path, (1040, 800)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let (main, bar) = root.split_horizontally(860);
    let sgn = if depth_down { -1.0 } else { 1.0 };
    let (h0, h1) = (1e3 * hs[0], 1e3 * hs[nh - 1]);
    let (va, vb) = (sgn * 1e3 * vs[0], sgn * 1e3 * vs[nv - 1]);
    let (v0, v1) = (va.min(vb), va.max(vb));
    let lo = values.iter().cloned().fold(f64::INFINITY, f64::min) / divisor;
    let hi = values.iter().cloned().fold(f64::NEG_INFINITY, f64::max) / divisor;
    let (lo, hi) = if hi > lo {
        (lo, hi)
    } else {
        (lo - 1.0, lo + 1.0)
    };
    let vlabel = move |x: &f64| tick(&(sgn * x));
    let mut chart = ChartBuilder::on(&main)
        .caption(format!("{quantity}: {title}"), (FAMILY, 20))
        .margin(15)
        .x_label_area_size(50)
        .y_label_area_size(70)
        .build_cartesian_2d(h0..h1, v0..v1)
        .map_err(e)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(format!("{hname}, mm"))
        .y_desc(if depth_down {
            format!("{vname} (depth, downward), mm")
        } else {
            format!("{vname}, mm")
        })
        .x_label_formatter(&tick)
        .y_label_formatter(&vlabel)
        .label_style((FAMILY, 15))
        .axis_desc_style((FAMILY, 17))
        .draw()
        .map_err(e)?;
    let dh = 1e3 * (hs[nh - 1] - hs[0]) / (nh - 1) as f64;
    let dv = 1e3 * (vs[nv - 1] - vs[0]) / (nv - 1) as f64;
    chart
        .draw_series((0..nv).flat_map(|iv| {
            (0..nh).map(move |ih| {
                let (x, y) = (1e3 * hs[ih], sgn * 1e3 * vs[iv]);
                let t = (values[iv * nh + ih] / divisor - lo) / (hi - lo);
                Rectangle::new(
                    [(x - 0.5 * dh, y - 0.5 * dv), (x + 0.5 * dh, y + 0.5 * dv)],
                    viridis(t).filled(),
                )
            })
        }))
        .map_err(e)?;
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
        .y_desc(format!("{quantity}, {unit_name}"))
        .y_label_formatter(&tick)
        .label_style((FAMILY, 15))
        .axis_desc_style((FAMILY, 17))
        .draw()
        .map_err(e)?;
    let levels = 256;
    cb.draw_series((0..levels).map(|k| {
        let (t0, t1) = (k as f64 / levels as f64, (k + 1) as f64 / levels as f64);
        Rectangle::new(
            [(0.0, lo + t0 * (hi - lo)), (1.0, lo + t1 * (hi - lo))],
            viridis(0.5 * (t0 + t1)).filled(),
        )
    }))
    .map_err(e)?;
    root.present().map_err(e)?;
    Ok(())
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
