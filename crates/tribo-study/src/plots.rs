//! The plots of a gathered study (`tribo sweep gather`), written into `DIR/plots/`, one PNG
//! per collected number (`plots/<column>.png`):
//!
//! - a study with random parameters: the output's histogram (its size, mean and the 5, 50 and
//!   95 % quantiles marked), its empirical exceedance curve 1 - F_n with the 95 %
//!   Dvoretzky-Kiefer-Wolfowitz band, the Spearman rank correlation with each random input (a
//!   tornado chart; the dashed lines at +-1.96 / sqrt(n - 1) bound what is indistinguishable
//!   from no influence) and scatter plots against the most influential inputs;
//! - a grid or zip study without random parameters: the output against each swept numeric
//!   parameter, one line per combination of the other axes' values.
//!
//! Points that failed, are missing, or lack the number are excluded and counted. Why Spearman
//! for the influence: it measures a monotone dependence, whatever its shape (psi_max goes as
//! 1 / limit, V falls steeply with the limit), uses every sample rather than two tails, and
//! needs no fitted model; a low/high-quantile swing would need a surrogate model or split the
//! sample into thin tails. The statistics are [`tribo::stats::sample`]'s; the drawing is
//! [`tribo_io::study`]'s.

use crate::plan::{cell, StudyDir};
use crate::spec::{Study, Variation};
use crate::table::Table;
use crate::StudyResult;
use std::path::PathBuf;
use tribo::stats::sample::{spearman, spearman_null_95, Exceedance, Sample, Summary};
use tribo_io::study::{GridOutput, GridPanel, Influence, Quantity, RandomOutput};

/// The quantile levels marked on the histograms.
pub const QUANTILE_LEVELS: [f64; 3] = [0.05, 0.5, 0.95];

/// The DKW band's alpha (a 95 % band).
pub const DKW_ALPHA: f64 = 0.05;

/// The statistics of one collected number over the points that have it.
#[derive(Debug, Clone, PartialEq)]
pub struct OutputStatistics {
    /// The column (`damage.criteria[0].psi_max`, `contact.max_pressure_Pa`).
    pub column: String,
    /// Its summary at [`QUANTILE_LEVELS`].
    pub summary: Summary,
    /// Its exceedance curve with the DKW band at 1 - [`DKW_ALPHA`].
    pub exceedance: Exceedance,
    /// Points without the number: failed, missing, or none in their summary.
    pub excluded: usize,
    /// Spearman's rho with each random parameter (in parameter order; None where undefined).
    pub spearman: Vec<(String, Option<f64>)>,
}

/// A parameter's value as a number (None for text, booleans).
fn number(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Float(x) => Some(*x),
        toml::Value::Integer(k) => Some(*k as f64),
        _ => None,
    }
}

/// The SI unit of a case input by its key path's last name (the case pages of docs/user list
/// them); "" where the name is not one of these (the axis then shows the key path alone).
pub fn input_unit(key: &str) -> &'static str {
    let last = key
        .rsplit('.')
        .next()
        .unwrap_or(key)
        .split('[')
        .next()
        .unwrap_or("");
    let stress = key.contains(".limits.")
        || matches!(last, "E" | "stress" | "pressure" | "tx" | "ty" | "p0")
        || last.starts_with("sigma")
        || last.starts_with("tau");
    if stress {
        "Pa"
    } else if matches!(last, "load" | "normal_load" | "force") {
        "N"
    } else if matches!(last, "friction" | "nu" | "mu" | "ratio") {
        "1"
    } else if matches!(
        last,
        "radius" | "radii" | "R" | "length" | "width" | "ux" | "uy" | "size" | "depth"
    ) {
        "m"
    } else if last == "density" {
        "kg/m^3"
    } else {
        ""
    }
}

/// Per point: whether it is done and has the collected number `k` finite.
fn present(t: &Table, k: usize) -> Vec<bool> {
    t.status
        .iter()
        .zip(&t.collected)
        .map(|(s, row)| s == "ok" && row[k].is_finite())
        .collect()
}

/// The values of collected number `k` at the points where `ok`.
fn collected(t: &Table, ok: &[bool], k: usize) -> Vec<f64> {
    (0..t.status.len())
        .filter(|&i| ok[i])
        .map(|i| t.collected[i][k])
        .collect()
}

/// The statistics of every collected number that at least one point has (others skipped).
pub fn statistics(study: &Study, t: &Table) -> Vec<OutputStatistics> {
    let random: Vec<usize> = (0..study.parameters.len())
        .filter(|&j| matches!(study.parameters[j].variation, Variation::Random(_)))
        .collect();
    let mut out = Vec::new();
    for (k, c) in study.collect.iter().enumerate() {
        let ok = present(t, k);
        let values = collected(t, &ok, k);
        let Ok(sample) = Sample::new(&values) else {
            continue;
        };
        let Ok(exceedance) = sample.exceedance(DKW_ALPHA) else {
            continue;
        };
        let spearman = random
            .iter()
            .map(|&j| {
                let x: Vec<f64> = (0..t.status.len())
                    .filter(|&i| ok[i])
                    .map(|i| number(&t.parameters[i][j]).unwrap_or(f64::NAN))
                    .collect();
                (study.parameters[j].key.text.clone(), spearman(&x, &values))
            })
            .collect();
        out.push(OutputStatistics {
            column: c.column.clone(),
            summary: sample.summary(&QUANTILE_LEVELS),
            exceedance,
            excluded: t.status.len() - values.len(),
            spearman,
        });
    }
    out
}

/// A file name from a column name: letters, digits, `.`, `_` and `-` kept, others `_`.
pub fn file_name(column: &str) -> String {
    let s: String = column
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "._-".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect();
    format!("{s}.png")
}

/// The lines of a grid panel: collected number `k` against parameter `j` (indices into the
/// study's `collect` and `parameters`), one line per combination of the values of the
/// parameters on the other axes (labelled `key = value unit, ...`), each sorted by parameter `j`;
/// points without the number left out.
pub fn grid_lines(study: &Study, t: &Table, k: usize, j: usize) -> Vec<(String, Vec<(f64, f64)>)> {
    let own_axis = study.axes.iter().position(|(_, m)| m.contains(&j));
    let others: Vec<usize> = study
        .axes
        .iter()
        .enumerate()
        .filter(|(a, _)| Some(*a) != own_axis)
        .flat_map(|(_, (_, m))| m.iter().copied())
        .collect();
    let ok = present(t, k);
    let mut lines: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for i in (0..t.status.len()).filter(|&i| ok[i]) {
        let Some(x) = number(&t.parameters[i][j]) else {
            continue;
        };
        let label = others
            .iter()
            .map(|&o| {
                let key = &study.parameters[o].key.text;
                let unit = match input_unit(key) {
                    "" | "1" => String::new(),
                    u => format!(" {u}"),
                };
                format!("{key} = {}{unit}", cell(&t.parameters[i][o]))
            })
            .collect::<Vec<_>>()
            .join(", ");
        let y = t.collected[i][k];
        match lines.iter_mut().find(|l| l.0 == label) {
            Some(l) => l.1.push((x, y)),
            None => lines.push((label, vec![(x, y)])),
        }
    }
    for l in &mut lines {
        l.1.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    lines
}

/// Writes `DIR/plots/<column>.png` for each collected number (each file atomically) and
/// returns their paths. A study with random parameters gets [`RandomOutput`] pages, a grid
/// or zip study [`GridOutput`] pages (over its numeric parameters; none where all are text);
/// a number no point has is skipped.
pub fn write(sd: &StudyDir, t: &Table) -> StudyResult<Vec<PathBuf>> {
    let study = &sd.study;
    let dir = sd.dir.join("plots");
    std::fs::create_dir_all(&dir).map_err(|e| crate::StudyError::file(&dir, e))?;
    let stats = statistics(study, t);
    let random = study
        .parameters
        .iter()
        .any(|p| matches!(p.variation, Variation::Random(_)));
    let mut written = Vec::new();
    for s in &stats {
        let Some(k) = study.collect.iter().position(|c| c.column == s.column) else {
            continue;
        };
        let c = &study.collect[k];
        let output = Quantity {
            name: c.key.text.clone(),
            unit: c.unit.clone(),
        };
        let name = file_name(&c.column);
        if random {
            let ok = present(t, k);
            let Ok(sample) = Sample::new(&collected(t, &ok, k)) else {
                continue;
            };
            let mut influences: Vec<Influence> = s
                .spearman
                .iter()
                .map(|(key, rho)| {
                    let j = study
                        .parameters
                        .iter()
                        .position(|p| &p.key.text == key)
                        .unwrap_or(0);
                    Influence {
                        input: Quantity {
                            name: key.clone(),
                            unit: input_unit(key).into(),
                        },
                        rho: *rho,
                        points: (0..t.status.len())
                            .filter(|&i| ok[i])
                            .filter_map(|i| {
                                number(&t.parameters[i][j]).map(|x| (x, t.collected[i][k]))
                            })
                            .collect(),
                    }
                })
                .collect();
            influences.sort_by(|a, b| {
                let m = |r: Option<f64>| r.map_or(-1.0, f64::abs);
                m(b.rho).total_cmp(&m(a.rho))
            });
            let page = RandomOutput {
                title: format!("{}: {} over the random inputs", study.name, c.key.text),
                output,
                summary: s.summary.clone(),
                histogram: sample.histogram(0),
                exceedance: s.exceedance.clone(),
                excluded: s.excluded,
                influences,
                rho_null_95: spearman_null_95(s.summary.n),
            };
            if !tribo_io::study::write_random_output(&dir, &name, &page)? {
                continue;
            }
        } else {
            let panels: Vec<GridPanel> = (0..study.parameters.len())
                .filter(|&j| t.parameters.iter().all(|row| number(&row[j]).is_some()))
                .map(|j| GridPanel {
                    parameter: Quantity {
                        name: study.parameters[j].key.text.clone(),
                        unit: input_unit(&study.parameters[j].key.text).into(),
                    },
                    lines: grid_lines(study, t, k, j),
                })
                .filter(|p| !p.lines.is_empty())
                .collect();
            if panels.is_empty() {
                continue;
            }
            let page = GridOutput {
                title: format!("{}: {}", study.name, c.key.text),
                output,
                excluded: s.excluded,
                panels,
            };
            if !tribo_io::study::write_grid_output(&dir, &name, &page)? {
                continue;
            }
        }
        written.push(dir.join(&name));
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn input_units_and_file_names() {
        assert_eq!(input_unit("contact.load"), "N");
        assert_eq!(input_unit("damage.limits.sigma_int"), "Pa");
        assert_eq!(input_unit("body2.E"), "Pa");
        assert_eq!(input_unit("contact.friction"), "1");
        assert_eq!(input_unit("field.n"), "");
        assert_eq!(input_unit("body1.radii[0]"), "m");
        assert_eq!(
            file_name("damage.criteria[0].psi_max"),
            "damage.criteria_0_.psi_max.png"
        );
    }
}
