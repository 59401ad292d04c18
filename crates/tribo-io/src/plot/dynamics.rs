//! The plots of a dynamic run: `probes.png` (displacement, velocity and stress histories at
//! the probes), `contacts.png` (forces and extents of each contact pair) and `energy.png`
//! (the energies and their balance), drawn with [`super::bem::panels_plot`]: one panel per
//! quantity over time, in units chosen from the data's magnitude (ms or us, mm or um, MPa).

use std::path::Path;

use tribo::dynamics::history::{DynamicHistory, ProbeHistory};

use super::bem::{palette, panels_plot, Line, Panel};
use crate::atomic::draw_atomic;
use crate::error::IoResult;

/// Times.
const TIME: &[(&str, f64)] = &[("s", 1.0), ("ms", 1e-3), ("µs", 1e-6), ("ns", 1e-9)];
/// Lengths (displacements, extents).
const LENGTH: &[(&str, f64)] = &[("m", 1.0), ("mm", 1e-3), ("µm", 1e-6), ("nm", 1e-9)];
/// Velocities.
const VELOCITY: &[(&str, f64)] = &[("m/s", 1.0), ("mm/s", 1e-3), ("µm/s", 1e-6)];
/// Stresses.
const STRESS: &[(&str, f64)] = &[("GPa", 1e9), ("MPa", 1e6), ("kPa", 1e3), ("Pa", 1.0)];
/// Forces per unit thickness.
const LINE_FORCE: &[(&str, f64)] = &[("MN/m", 1e6), ("kN/m", 1e3), ("N/m", 1.0)];
/// Energies per unit thickness.
const ENERGY: &[(&str, f64)] = &[("kJ/m", 1e3), ("J/m", 1.0), ("mJ/m", 1e-3), ("µJ/m", 1e-6)];

/// The unit of `units` (largest first) in which the largest magnitude of `values` is at
/// least 1 (the smallest unit where all are below its factor; the SI unit for zeros).
pub fn unit_for(
    values: impl Iterator<Item = f64>,
    units: &'static [(&'static str, f64)],
) -> (&'static str, f64) {
    let max = values.fold(0.0_f64, |m, v| m.max(v.abs()));
    if max == 0.0 {
        return units
            .iter()
            .copied()
            .find(|u| u.1 == 1.0)
            .unwrap_or(units[0]);
    }
    units
        .iter()
        .copied()
        .find(|u| max >= u.1)
        .unwrap_or(units[units.len() - 1])
}

/// A line of `values` against the scaled times.
fn line(label: String, t: &[f64], values: impl Iterator<Item = f64>, scale: f64, k: usize) -> Line {
    Line {
        label,
        points: t.iter().copied().zip(values.map(|v| v / scale)).collect(),
        colour: palette(k),
        dashed: false,
    }
}

/// The panels of `probes.png`: one per component (u_x, u_y, v_x, v_y, sigma_xx, sigma_yy,
/// sigma_xy), the probes as lines in the same colour in every panel (sigma_zz, which follows
/// from the plane condition, is in `probes.csv`).
fn probe_panels(h: &DynamicHistory, t: &[f64]) -> Vec<Panel> {
    let u = unit_for(
        h.probes
            .iter()
            .flat_map(|p| p.displacement.iter().flatten().copied()),
        LENGTH,
    );
    let v = unit_for(
        h.probes
            .iter()
            .flat_map(|p| p.velocity.iter().flatten().copied()),
        VELOCITY,
    );
    let s = unit_for(
        h.probes
            .iter()
            .flat_map(|p| p.stress.iter().flat_map(|s| [s.xx, s.yy, s.xy])),
        STRESS,
    );
    type Get = fn(&ProbeHistory, usize) -> f64;
    let parts: [(&str, String, (&str, f64), Get); 7] = [
        ("Displacement u_x at the probes", "u_x".into(), u, |p, k| {
            p.displacement[k][0]
        }),
        ("Displacement u_y at the probes", "u_y".into(), u, |p, k| {
            p.displacement[k][1]
        }),
        ("Velocity v_x at the probes", "v_x".into(), v, |p, k| {
            p.velocity[k][0]
        }),
        ("Velocity v_y at the probes", "v_y".into(), v, |p, k| {
            p.velocity[k][1]
        }),
        (
            "Stress σ_xx at the probes (tension positive)",
            "σ_xx".into(),
            s,
            |p, k| p.stress[k].xx,
        ),
        (
            "Stress σ_yy at the probes (tension positive)",
            "σ_yy".into(),
            s,
            |p, k| p.stress[k].yy,
        ),
        ("Stress σ_xy at the probes", "σ_xy".into(), s, |p, k| {
            p.stress[k].xy
        }),
    ];
    let panels = if h.stresses { parts.len() } else { 4 };
    parts
        .into_iter()
        .take(panels)
        .map(|(title, symbol, (unit, scale), get)| {
            let lines = h
                .probes
                .iter()
                .enumerate()
                .map(|(i, p)| line(p.name.clone(), t, (0..t.len()).map(|k| get(p, k)), scale, i))
                .collect();
            (title.to_string(), format!("{symbol}, {unit}"), lines, None)
        })
        .collect()
}

/// Two panels per contact pair: forces and extents.
fn contact_panels(h: &DynamicHistory, t: &[f64]) -> Vec<Panel> {
    let mut panels = Vec::new();
    for c in &h.contacts {
        let f = unit_for(
            c.normal_force.iter().chain(&c.tangential_force).copied(),
            LINE_FORCE,
        );
        let l = unit_for(
            c.length
                .iter()
                .chain(&c.stick_length)
                .chain(&c.slip_length)
                .copied(),
            LENGTH,
        );
        let pair = format!("{} on {}", c.slave, c.master);
        panels.push((
            format!("Contact forces, {pair}"),
            format!("force per thickness, {}", f.0),
            vec![
                line("normal".into(), t, c.normal_force.iter().copied(), f.1, 0),
                line(
                    "tangential".into(),
                    t,
                    c.tangential_force.iter().copied(),
                    f.1,
                    1,
                ),
            ],
            None,
        ));
        panels.push((
            format!("Contact extent, {pair}"),
            format!("length, {}", l.0),
            vec![
                line("in contact".into(), t, c.length.iter().copied(), l.1, 2),
                line("stick".into(), t, c.stick_length.iter().copied(), l.1, 3),
                line("slip".into(), t, c.slip_length.iter().copied(), l.1, 4),
            ],
            None,
        ));
    }
    panels
}

/// The legend label of an energy series or `energy.csv` column (name with its unit).
fn energy_label(name: &str) -> String {
    match name {
        "input_work_J_per_m" => "input work W".into(),
        "strain_energy_J_per_m" => "strain energy U".into(),
        "kinetic_energy_J_per_m" => "kinetic energy K".into(),
        "dissipation_J_per_m" => "friction dissipation D".into(),
        "mechanical_energy_J_per_m" => "mechanical energy U + K".into(),
        "translational_kinetic_J_per_m" => "translational kinetic energy".into(),
        "normal_contact_work_J_per_m" => "normal contact work".into(),
        other => other.trim_end_matches("_J_per_m").replace('_', " "),
    }
}

/// A line without a label at (t_0, `top`): it widens the panel's y range so that the
/// upper corners hold no data and the legend covers no line ([`super::bem::panels_plot`]
/// neither draws nor lists it).
fn headroom(t: &[f64], top: f64) -> Line {
    Line {
        label: String::new(),
        points: t.first().map(|&t0| (t0, top)).into_iter().collect(),
        colour: palette(0),
        dashed: false,
    }
}

/// The y value above which a legend of `n` lines fits in a panel of `energy.png` whose data
/// span `lo..hi` (a 360 px panel has ~270 px of axis; a legend row takes 22 px, its frame
/// 16 px, [`super::style::legend_frac`]; 10 % more as a margin).
fn legend_top(lo: f64, hi: f64, n: usize) -> f64 {
    let frac = ((n as f64 * 22.0 + 16.0) / 270.0 + 0.1).min(0.8);
    let (lo, hi) = (lo.min(0.0), hi.max(0.0));
    lo + (hi - lo) / (1.0 - frac)
}

/// The panels of `energy.png`: the computed energies (the history's series, U + K where
/// both are computed, and the `columns` of `energy.csv` beyond the history's: a contact
/// run's mechanical and translational kinetic energy and contact work), then the balance
/// on its own scale (the history's W - U - K - D, [`crate::dynamics::energy_balance`], or
/// a `balance_J_per_m` column).
fn energy_panels(h: &DynamicHistory, t: &[f64], columns: &[(&str, &[f64])]) -> Vec<Panel> {
    let mut series: Vec<(String, Vec<f64>)> = h
        .energy
        .series()
        .into_iter()
        .map(|(name, v)| (energy_label(name), v.to_vec()))
        .collect();
    if let (Some(u), Some(k)) = (&h.energy.strain_energy, &h.energy.kinetic_energy) {
        series.push((
            "U + K".into(),
            u.iter().zip(k).map(|(u, k)| u + k).collect(),
        ));
    }
    let mut balance = crate::dynamics::energy_balance(h).map(|b| ("W - U - K".to_string(), b));
    if h.energy.dissipation.is_some() {
        if let Some(b) = &mut balance {
            b.0 = "W - U - K - D".into();
        }
    }
    let mut domain_balance: Vec<(String, Vec<f64>)> = Vec::new();
    for (name, v) in columns {
        if v.len() != t.len() {
            continue;
        }
        if name.starts_with("balance") {
            balance.get_or_insert(("W - (U + K) - D".into(), v.to_vec()));
        } else if name.starts_with("domain_balance") {
            // A balance: drawn in the balance panel on its own scale, not among the energies.
            domain_balance.push((energy_label(name), v.to_vec()));
        } else {
            series.push((energy_label(name), v.to_vec()));
        }
    }
    let e = unit_for(
        series
            .iter()
            .flat_map(|s| s.1.iter().copied())
            .chain(balance.iter().flat_map(|b| b.1.iter().copied())),
        ENERGY,
    );
    let mut lines: Vec<Line> = series
        .iter()
        .enumerate()
        .map(|(k, (name, v))| line(name.clone(), t, v.iter().copied(), e.1, k))
        .collect();
    let (lo, hi) = lines
        .iter()
        .flat_map(|l| l.points.iter().map(|p| p.1))
        .fold((0.0_f64, 0.0_f64), |(a, b), y| (a.min(y), b.max(y)));
    lines.push(headroom(t, legend_top(lo, hi, series.len())));
    let mut panels = vec![(
        "Energy per unit thickness".into(),
        format!("energy, {}", e.0),
        lines,
        None,
    )];
    // The balance on its own scale: a drift small against W (spurious contact
    // oscillation, a scheme's numerical damping) shows here.
    if let Some((label, b)) = balance {
        // Below 1e-12 of the largest energy the balance is rounding (1e-16 relative), which
        // an axis fitted to it would blow up into a plot of noise: shown as 0 (energy.csv
        // keeps the values).
        let largest = series
            .iter()
            .flat_map(|s| s.1.iter())
            .fold(0.0_f64, |m, v| m.max(v.abs()));
        let shown = b
            .into_iter()
            .map(|v| if v.abs() < 1e-12 * largest { 0.0 } else { v });
        let mut l = line(label.clone(), t, shown, e.1, 0);
        l.colour = plotters::style::RGBColor(0, 0, 0);
        let mut balance_lines = vec![l];
        // The contact run's balance over the domain's U and K (energy.csv
        // domain_balance_J_per_m) beside the march's.
        for (k, (name, v)) in domain_balance.iter().enumerate() {
            balance_lines.push(line(name.clone(), t, v.iter().copied(), e.1, k + 1));
        }
        let (lo, hi) = balance_lines
            .iter()
            .flat_map(|l| l.points.iter().map(|p| p.1))
            .fold((0.0_f64, 0.0_f64), |(a, b), y| (a.min(y), b.max(y)));
        let n = balance_lines.len();
        balance_lines.push(headroom(t, legend_top(lo, hi, n)));
        panels.push((
            format!("Energy balance {label} (0 for an exact solution)"),
            format!("energy, {}", e.0),
            balance_lines,
            None,
        ));
    }
    panels
}

/// Draws `probes.png`, `contacts.png` and `energy.png` (those with data) into `dir`;
/// `columns` are `energy.csv`'s columns beyond the history's ([`energy_panels`]).
pub(crate) fn write_plots(
    dir: &Path,
    h: &DynamicHistory,
    columns: &[(&str, &[f64])],
) -> IoResult<()> {
    let tu = unit_for(h.times.iter().copied(), TIME);
    let t: Vec<f64> = h.times.iter().map(|x| x / tu.1).collect();
    let x_desc = format!("t, {}", tu.0);
    if !h.probes.is_empty() {
        let panels = probe_panels(h, &t);
        draw_atomic(dir, "probes.png", |p| {
            panels_plot(p, &panels, &x_desc, false)
        })?;
    }
    if !h.contacts.is_empty() {
        let panels = contact_panels(h, &t);
        draw_atomic(dir, "contacts.png", |p| {
            panels_plot(p, &panels, &x_desc, false)
        })?;
    }
    if !h.energy.series().is_empty() {
        let panels = energy_panels(h, &t, columns);
        draw_atomic(dir, "energy.png", |p| {
            panels_plot(p, &panels, &x_desc, false)
        })?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_follow_the_magnitude() {
        let u = |v: &[f64], units| unit_for(v.iter().copied(), units).0;
        assert_eq!(u(&[2e-3, -1e-3], TIME), "ms");
        assert_eq!(u(&[5e-7], TIME), "ns");
        assert_eq!(u(&[1.5e-6], LENGTH), "µm");
        assert_eq!(u(&[-3e8], STRESS), "MPa");
        assert_eq!(u(&[0.0], STRESS), "Pa");
        assert_eq!(u(&[1e-12], LENGTH), "nm");
        assert_eq!(u(&[7.0], ENERGY), "J/m");
    }
}
