//! `damage.png` of a dynamic run with `[damage]`: the dangerous area A_q(t) and the largest
//! psi_q(t) of each assessed region over time, with the limit psi = 1 dashed.

use std::path::Path;

use tribo::dynamics::history::DynamicHistory;

use super::bem::{palette, panels_plot, Line, Panel};
use super::dynamics::unit_for;
use crate::atomic::draw_atomic;
use crate::error::IoResult;

/// Times.
const TIME: &[(&str, f64)] = &[("s", 1.0), ("ms", 1e-3), ("µs", 1e-6), ("ns", 1e-9)];
/// Areas per unit thickness.
const AREA: &[(&str, f64)] = &[("m²", 1.0), ("cm²", 1e-4), ("mm²", 1e-6), ("µm²", 1e-12)];

/// The two panels: areas and psi_max.
fn panels(h: &DynamicHistory, t: &[f64]) -> Vec<Panel> {
    let a = unit_for(
        h.damage
            .iter()
            .flat_map(|d| d.damage.states.iter().map(|s| s.volume)),
        AREA,
    );
    let areas = h
        .damage
        .iter()
        .enumerate()
        .map(|(k, d)| Line {
            label: format!("{} ({})", d.region, d.quantity),
            points: t
                .iter()
                .zip(&d.damage.states)
                .map(|(&x, s)| (x, s.volume / a.1))
                .collect(),
            colour: palette(k),
            dashed: false,
        })
        .collect();
    let mut psi: Vec<Line> = h
        .damage
        .iter()
        .enumerate()
        .map(|(k, d)| Line {
            label: format!("{} ({})", d.region, d.quantity),
            points: t
                .iter()
                .zip(&d.damage.states)
                .map(|(&x, s)| (x, s.psi_max))
                .collect(),
            colour: palette(k),
            dashed: false,
        })
        .collect();
    if let (Some(&t0), Some(&t1)) = (t.first(), t.last()) {
        psi.push(Line {
            label: "limit ψ = 1".into(),
            points: vec![(t0, 1.0), (t1, 1.0)],
            colour: plotters::style::RGBColor(0, 0, 0),
            dashed: true,
        });
    }
    vec![
        (
            "Dangerous area {ψ ≥ 1} per unit thickness".into(),
            format!("area, {}", a.0),
            areas,
            None,
        ),
        ("Largest ψ = φ / φ_lim".into(), "ψ_max".into(), psi, None),
    ]
}

/// Draws `damage.png` into `dir` (with damage histories).
pub(crate) fn write_plot(dir: &Path, h: &DynamicHistory) -> IoResult<()> {
    if h.damage.is_empty() {
        return Ok(());
    }
    let tu = unit_for(h.times.iter().copied(), TIME);
    let t: Vec<f64> = h.times.iter().map(|x| x / tu.1).collect();
    let x_desc = format!("t, {}", tu.0);
    let p = panels(h, &t);
    draw_atomic(dir, "damage.png", |path| {
        panels_plot(path, &p, &x_desc, false)
    })
}
