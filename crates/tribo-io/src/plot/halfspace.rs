//! The plots of a half-space run: the pressure map and profiles, the back effect, the
//! stick/slip map and traction profiles, the stress and damage sections, the Sec. 6 study;
//! and [`write_plots`], which draws every plot of a run into its directory.

use super::canvas::Canvas;
use super::style::*;
use crate::atomic::draw_atomic;
use crate::error::{IoError, IoResult};
use crate::halfspace::{
    damage_plot_name, damage_plot_name_x0, DataFiles, BACK_EFFECT_FILES, FILES, ROUGH_FILES,
    STRESS_FILES, STRESS_X0_FILES, STUDY_FILES, SWEEP_FILES, TANGENTIAL_FILES,
};
use plotters::prelude::*;
use std::path::Path;
use tribo::kernels::hertz::HertzContact;
use tribo::SurfaceGrid;
use tribo_case::case::HalfSpaceCase;
use tribo_case::derived::{
    cattaneo_mindlin_traction, loading_angle, traction_along, traction_along_y, BackEffectSeries,
};
use tribo_case::pipeline::{Outcome, Stress};
use tribo_case::summary::{StudyRow, Summary};

/// Index of the value of `v` nearest `t`.
pub fn nearest(v: &[f64], t: f64) -> usize {
    (0..v.len())
        .min_by(|&a, &b| (v[a] - t).abs().total_cmp(&(v[b] - t).abs()))
        .unwrap_or(0)
}

/// The plane `y = y[iy]` of `values`: (x fastest, z rows).
pub fn plane_y(st: &Stress, values: &[f64], iy: usize) -> Vec<f64> {
    let g = &st.field.grid;
    let mut out = Vec::with_capacity(g.x.len() * g.z.len());
    for iz in 0..g.z.len() {
        for ix in 0..g.x.len() {
            out.push(values[g.index(ix, iy, iz)]);
        }
    }
    out
}

/// The plane `x = x[ix]` of `values`: (y fastest, z rows).
pub fn plane_x(st: &Stress, values: &[f64], ix: usize) -> Vec<f64> {
    let g = &st.field.grid;
    let mut out = Vec::with_capacity(g.y.len() * g.z.len());
    for iz in 0..g.z.len() {
        for iy in 0..g.y.len() {
            out.push(values[g.index(ix, iy, iz)]);
        }
    }
    out
}

/// The plane `z = z[iz]` of `values`: (x fastest, y rows).
pub fn plane_z(st: &Stress, values: &[f64], iz: usize) -> Vec<f64> {
    let g = &st.field.grid;
    let n = g.x.len() * g.y.len();
    values[iz * n..(iz + 1) * n].to_vec()
}

/// Draws every plot of a half-space run into `dir` (the data files and checks are
/// [`crate::halfspace::write_halfspace`]'s).
pub(crate) fn write_plots(
    dir: &Path,
    case: &HalfSpaceCase,
    out: &Outcome,
    summary: &Summary,
    data: &DataFiles,
) -> IoResult<()> {
    let grid = &out.prepared.grid;
    let sol = &out.solution;
    let hertz = out.prepared.hertz.as_ref().map(|h| &h.contact);
    draw_atomic(dir, FILES[4], |p| {
        pressure_map(p, grid, &sol.pressure, hertz, &case.title)
    })?;
    draw_atomic(dir, FILES[5], |p| {
        pressure_profiles(p, grid, &sol.pressure, hertz, &case.title)
    })?;
    if out.back_effect.is_some() {
        draw_atomic(dir, BACK_EFFECT_FILES[1], |p| {
            back_effect(p, &data.back_effect_series, &case.title)
        })?;
    }
    tangential_plots(dir, case, out)?;
    rough_plots(dir, case, out)?;
    if let (Some(arrays), Some(st)) = (&data.stress_arrays, &out.stress) {
        stress_sections(dir, case, out, st, arrays)?;
    }
    if let (Some(_), Some(st)) = (&out.damage, &out.stress) {
        damage_sections(dir, out, st)?;
    }
    if let Some(study) = summary.damage.as_ref().and_then(|d| d.study.as_ref()) {
        let pick = |f: &dyn Fn(&StudyRow) -> f64| -> Vec<(f64, f64)> {
            study
                .rows
                .iter()
                .map(|r| (r.bending_over_p0, f(r)))
                .collect()
        };
        let paper = study.paper;
        let curves = vec![
            Curve {
                name: "n+tau+b, tension zone: V_int".into(),
                points: pick(&|r| r.tension[0]),
                colour: RGBColor(214, 39, 40),
                reference: Some(paper[2]),
            },
            Curve {
                name: "n+tau+b, tension zone: Psi_int".into(),
                points: pick(&|r| r.tension[1]),
                colour: RGBColor(255, 127, 14),
                reference: Some(paper[3]),
            },
            Curve {
                name: "n+tau+b, compression zone: V_int".into(),
                points: pick(&|r| r.compression[0]),
                colour: RGBColor(31, 119, 180),
                reference: Some(paper[4]),
            },
            Curve {
                name: "n+tau+b, compression zone: Psi_int".into(),
                points: pick(&|r| r.compression[1]),
                colour: RGBColor(44, 160, 44),
                reference: Some(paper[5]),
            },
        ];
        draw_atomic(dir, STUDY_FILES[1], |p| {
            lines(
                p,
                &curves,
                "bending stress at the contact, sigma_b / p0",
                "change against the loading n (normal only), %",
                &format!(
                    "Sec. 6: dangerous volume of the intensity, limit {} p0 (dashed: the paper)",
                    study.limit_over_p0
                ),
            )
        })?;
    }
    Ok(())
}

/// The contact patches map, the area against the load (cases with a sweep) and the PSD of
/// the surface (rough cases).
fn rough_plots(dir: &Path, case: &HalfSpaceCase, out: &Outcome) -> IoResult<()> {
    use super::rough;
    let grid = &out.prepared.grid;
    let r = out.prepared.rough.as_ref();
    if let Some(w) = &out.sweep {
        draw_atomic(dir, SWEEP_FILES[2], |p| {
            rough::patches_map(p, grid, &w.labels, w.patches.len(), &case.title)
        })?;
        let slope = r.map(|r| r.composite.rms_slope).filter(|_| case.periodic);
        draw_atomic(dir, SWEEP_FILES[3], |p| {
            rough::area_vs_load(
                p,
                &w.steps,
                out.prepared.composite_modulus,
                slope,
                &format!("Contact area against load: {}", case.title),
            )
        })?;
    }
    if let Some(r) = r {
        let input: Option<Vec<(f64, f64)>> = r.input_psd(1.0).map(|_| {
            // The input spectrum on a log-spaced set of wavenumbers over the bins' range,
            // with its corners (roll-off, start of the power law, cutoff) exact.
            let (q0, q1) = (
                r.psd.first().map_or(1.0, |b| b.q),
                r.psd.last().map_or(1.0, |b| b.q),
            );
            let mut qs: Vec<f64> = (0..=400)
                .map(|k| q0 * (q1 / q0).powf(k as f64 / 400.0))
                .collect();
            for b in &r.bodies {
                if let Some(g) = &b.generated {
                    let s = g.spectrum;
                    for q in [s.rolloff, s.powerlaw_start, s.cutoff] {
                        qs.extend([q * (1.0 - 1e-9), q * (1.0 + 1e-9)]);
                    }
                }
            }
            qs.retain(|q| *q >= q0 && *q <= q1);
            qs.sort_by(f64::total_cmp);
            qs.into_iter()
                .filter_map(|q| r.input_psd(q).map(|c| (q, c)))
                .collect()
        });
        draw_atomic(dir, ROUGH_FILES[1], |p| {
            rough::psd(
                p,
                &r.psd,
                input.as_deref(),
                &format!("PSD of the surface: {}", case.title),
            )
        })?;
    }
    Ok(())
}

/// The stick/slip map and the traction profiles (cases with friction).
fn tangential_plots(dir: &Path, case: &HalfSpaceCase, out: &Outcome) -> IoResult<()> {
    let Some(t) = &out.tangential else {
        return Ok(());
    };
    let grid = &out.prepared.grid;
    let sol = &out.solution;
    let hertz = out.prepared.hertz.as_ref().map(|h| &h.contact);
    let s = &t.solution;
    let f = case.friction.as_ref().map_or(0.0, |f| f.coefficient);
    // Cattaneo-Mindlin c/a (partial slip; None when sliding: no stick zone).
    let ratio = t.stick_ratio_cattaneo_mindlin;
    draw_atomic(dir, TANGENTIAL_FILES[1], |p| {
        stick_slip_map(
            p,
            grid,
            &sol.pressure,
            &s.stick,
            hertz.zip(ratio),
            &case.title,
        )
    })?;
    let along = traction_along(s, loading_angle(case));
    let closed = |x: f64, y: f64| match hertz {
        Some(h) => cattaneo_mindlin_traction(h, f, ratio, x, y),
        None => 0.0,
    };
    let label = if ratio.is_some() {
        "Cattaneo-Mindlin"
    } else {
        "f p (Hertz)"
    };
    let reference: Option<Reference<'_>> =
        hertz.map(|_| (&closed as &dyn Fn(f64, f64) -> f64, label));
    draw_atomic(dir, TANGENTIAL_FILES[2], |p| {
        traction_profiles(p, grid, &along, reference, &case.title)
    })
}

/// The stress sections: sigma_xx and von Mises in y = 0, sigma_xx in the layer nearest
/// z = a/2; with friction mainly along y also sigma_yy and von Mises in x = 0.
fn stress_sections(
    dir: &Path,
    case: &HalfSpaceCase,
    out: &Outcome,
    st: &Stress,
    arrays: &[(String, Vec<f64>)],
) -> IoResult<()> {
    let g = &st.field.grid;
    let get = |name: &str| arrays.iter().find(|a| a.0 == name).map(|a| &a.1[..]);
    let (Some(sxx), Some(vm)) = (get("sigma_xx"), get("von_mises")) else {
        return Err(IoError::Shape {
            what: "stress sections".into(),
            detail: "missing arrays".into(),
        });
    };
    let iy0 = nearest(&g.y, 0.0);
    let a = out.prepared.hertz.as_ref().map(|h| h.contact.semi_major);
    let z_target = 0.5 * a.unwrap_or(g.z.last().copied().unwrap_or(0.0) / 3.0);
    let iz = nearest(&g.z, z_target);
    let y0 = format!("plane y = {:.4} mm", 1e3 * g.y[iy0]);
    draw_atomic(dir, STRESS_FILES[1], |p| {
        section(
            p,
            (&g.x, "x"),
            (&g.z, "z"),
            &plane_y(st, sxx, iy0),
            true,
            ("sigma_xx", 1e9, "GPa"),
            SectionScale::Signed,
            &format!("{y0}, {}", case.title),
        )
    })?;
    draw_atomic(dir, STRESS_FILES[2], |p| {
        section(
            p,
            (&g.x, "x"),
            (&g.y, "y"),
            &plane_z(st, sxx, iz),
            false,
            ("sigma_xx", 1e9, "GPa"),
            SectionScale::Signed,
            &format!(
                "layer z = {:.4} mm nearest {}, {}",
                1e3 * g.z[iz],
                if a.is_some() { "0.5a" } else { "depth/6" },
                case.title
            ),
        )
    })?;
    draw_atomic(dir, STRESS_FILES[3], |p| {
        section(
            p,
            (&g.x, "x"),
            (&g.z, "z"),
            &plane_y(st, vm, iy0),
            true,
            ("von Mises", 1e9, "GPa"),
            SectionScale::Sequential,
            &format!("{y0}, {}", case.title),
        )
    })?;
    if !traction_along_y(out) {
        return Ok(());
    }
    let Some(syy) = get("sigma_yy") else {
        return Err(IoError::Shape {
            what: "stress sections".into(),
            detail: "missing sigma_yy".into(),
        });
    };
    let ix0 = nearest(&g.x, 0.0);
    let x0 = format!("plane x = {:.4} mm (friction along y)", 1e3 * g.x[ix0]);
    for (file, values, quantity, scale) in [
        (STRESS_X0_FILES[0], syy, "sigma_yy", SectionScale::Signed),
        (
            STRESS_X0_FILES[1],
            vm,
            "von Mises",
            SectionScale::Sequential,
        ),
    ] {
        draw_atomic(dir, file, |p| {
            section(
                p,
                (&g.y, "y"),
                (&g.z, "z"),
                &plane_x(st, values, ix0),
                true,
                (quantity, 1e9, "GPa"),
                scale,
                &format!("{x0}, {}", case.title),
            )
        })?;
    }
    Ok(())
}

/// The psi section of every damage criterion in y = 0 (and x = 0 with friction mainly
/// along y), like the paper's Fig. 6.
fn damage_sections(dir: &Path, out: &Outcome, st: &Stress) -> IoResult<()> {
    let Some(d) = &out.damage else {
        return Ok(());
    };
    let g = &st.field.grid;
    let iy0 = nearest(&g.y, 0.0);
    for c in &d.criteria {
        let r = &c.assessment.region;
        let name = &c.assessment.name;
        draw_atomic(dir, &damage_plot_name(name), |p| {
            section(
                p,
                (&g.x, "x"),
                (&g.z, "z"),
                &plane_y(st, &c.psi, iy0),
                true,
                (&format!("psi_{name}"), 1.0, "1 (dangerous where >= 1)"),
                SectionScale::Damage,
                &format!(
                    "y = {:.3} mm, V = {:.3e} m^3, Psi = {:.3e} m^3, max {:.3}",
                    1e3 * g.y[iy0],
                    r.volume,
                    r.damageability,
                    r.psi_max
                ),
            )
        })?;
        if traction_along_y(out) {
            let ix0 = nearest(&g.x, 0.0);
            draw_atomic(dir, &damage_plot_name_x0(name), |p| {
                section(
                    p,
                    (&g.y, "y"),
                    (&g.z, "z"),
                    &plane_x(st, &c.psi, ix0),
                    true,
                    (&format!("psi_{name}"), 1.0, "1 (dangerous where >= 1)"),
                    SectionScale::Damage,
                    &format!(
                        "x = {:.3} mm (friction along y), V = {:.3e} m^3, Psi = {:.3e} m^3, \
                         max {:.3}",
                        1e3 * g.x[ix0],
                        r.volume,
                        r.damageability,
                        r.psi_max
                    ),
                )
            })?;
        }
    }
    Ok(())
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
pub fn back_effect(path: &Path, series: &[BackEffectSeries], title: &str) -> Result<(), String> {
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
#[cfg(test)]
mod tests {
    use super::*;

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
