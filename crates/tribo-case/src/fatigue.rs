//! Fatigue from test data and limits: the fatigue CSV parser, the Woehler fits (the paper's
//! Fig. 3) and the multicriterial limiting-state diagram (Fig. 4), as reports (plain data).
//! See docs/user/fatigue.md.

use crate::error::{CaseError, CaseResult};
use crate::units::{self, Dim};
use serde::Serialize;
use std::path::Path;
use toml::Value;
use tribo::analysis::limit_diagram::{LimitDiagram, MechanoRollingLimits, StateCheck};
use tribo::analysis::woehler::{
    fit_max_likelihood, fit_regression, FatigueData, FatigueTest, LoadMeasure, MaxLikelihoodFit,
    MaxLikelihoodParams, RegressionFit, RegressionParams, TestKind, WoehlerCurve,
};

/// Files `tribo fatigue fit` writes.
pub const FIT_FILES: [&str; 2] = ["woehler.json", "woehler.png"];
/// Files `tribo fatigue diagram` writes.
pub const DIAGRAM_FILES: [&str; 2] = ["limit_diagram.json", "limit_diagram.png"];

fn flag(s: &str) -> Option<bool> {
    match s.trim().to_ascii_lowercase().as_str() {
        "true" | "1" | "yes" | "y" => Some(true),
        "false" | "0" | "no" | "n" => Some(false),
        _ => None,
    }
}

/// Parse the fatigue CSV (see `tribo fatigue fit --help`). Loads returned in Pa.
pub fn parse_csv(text: &str, path: &Path) -> CaseResult<Vec<FatigueTest>> {
    let bad = |line: usize, rule: String| CaseError::DataFile {
        field: "data".into(),
        path: path.to_path_buf(),
        line,
        rule,
    };
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let (hline, header) = lines
        .next()
        .ok_or_else(|| bad(0, "no header line (load_Pa, cycles, runout)".into()))?;
    let cols: Vec<String> = header.split(',').map(|c| c.trim().to_string()).collect();
    // Each quantity in exactly one column: a repeated column, or two spellings of one
    // quantity (load and load_MPa; runout and fracture, which are each other's negation),
    // would silently take the first and drop the other.
    for (i, c) in cols.iter().enumerate() {
        if !c.is_empty() && cols[..i].contains(c) {
            return Err(bad(
                hline,
                format!("header {header:?} names the column {c:?} twice; give each column once"),
            ));
        }
    }
    let find_one = |what: &str, names: &[&str]| -> CaseResult<Option<usize>> {
        let found: Vec<usize> = (0..cols.len())
            .filter(|&i| names.contains(&cols[i].as_str()))
            .collect();
        match found.as_slice() {
            [] => Ok(None),
            [i] => Ok(Some(*i)),
            _ => Err(bad(
                hline,
                format!(
                    "header {header:?} has {} {what} columns ({}): give exactly one",
                    found.len(),
                    found
                        .iter()
                        .map(|&i| cols[i].as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )),
        }
    };
    let (load_col, unit_power) = match find_one("load", &["load", "load_Pa", "load_MPa"])? {
        Some(i) if cols[i] == "load_MPa" => (i, 6),
        Some(i) => (i, 0),
        None => {
            return Err(bad(
                hline,
                format!("header {header:?} has no load column (load_Pa, load or load_MPa)"),
            ))
        }
    };
    let cycles_col = find_one("cycles", &["cycles", "N"])?
        .ok_or_else(|| bad(hline, format!("header {header:?} has no cycles column")))?;
    let (flag_col, is_runout) = match find_one("flag", &["runout", "fracture"])? {
        Some(i) => (i, cols[i] == "runout"),
        None => {
            return Err(bad(
                hline,
                format!("header {header:?} has no runout (or fracture) column"),
            ))
        }
    };
    let mut tests = Vec::new();
    for (ln, l) in lines {
        let cells: Vec<&str> = l.split(',').map(str::trim).collect();
        if cells.len() != cols.len() {
            return Err(bad(
                ln,
                format!("{} columns, the header has {}", cells.len(), cols.len()),
            ));
        }
        // Loads in MPa: the decimal exponent is shifted, so "300" MPa is exactly 3e8 Pa.
        let num = |i: usize, what: &str, power: i32| {
            crate::units::shifted_decimal(cells[i], power)
                .ok_or_else(|| bad(ln, format!("{what} {:?} is not a finite number", cells[i])))
        };
        let load = num(load_col, "load", unit_power)?;
        let cycles = num(cycles_col, "cycles", 0)?;
        let f = flag(cells[flag_col]).ok_or_else(|| {
            bad(
                ln,
                format!(
                    "flag {:?} must be true/false, 1/0 or yes/no",
                    cells[flag_col]
                ),
            )
        })?;
        tests.push(FatigueTest {
            load,
            cycles,
            runout: if is_runout { f } else { !f },
        });
    }
    Ok(tests)
}

/// The report of `tribo fatigue fit` (woehler.json).
#[derive(Debug, Clone, Serialize)]
pub struct FitReport {
    /// The tribo version.
    pub version: &'static str,
    /// Files written (names within the output directory).
    pub outputs: [&'static str; 2],
    /// The data file.
    pub data: String,
    /// The test kind (sigma, p, sigma_p, p_sigma).
    pub kind: TestKind,
    /// Symbol of its limit.
    pub limit_symbol: &'static str,
    /// What the loads measure.
    pub measure: LoadMeasure,
    /// Unit of the loads.
    pub unit: &'static str,
    /// Number of tests, fractures, run-outs.
    pub tests: usize,
    /// Fractures.
    pub fractures: usize,
    /// Run-outs.
    pub runouts: usize,
    /// Mixed levels, Pa.
    pub mixed_levels: Vec<f64>,
    /// The E739 regression (null when not possible; see notes).
    pub regression: Option<RegressionFit>,
    /// The maximum-likelihood fit (null when not possible; see notes).
    pub max_likelihood: Option<MaxLikelihoodFit>,
    /// Why a method was skipped.
    pub notes: Vec<String>,
    /// The tests (for the plot).
    #[serde(skip)]
    pub points: Vec<FatigueTest>,
}

/// Fit both ways. A method that cannot run on these data is skipped with a note; when
/// neither can, the regression's error is returned.
pub fn fit(
    kind: TestKind,
    measure: LoadMeasure,
    tests: Vec<FatigueTest>,
    confidence: f64,
    source: &str,
) -> CaseResult<FitReport> {
    let data = FatigueData::new(kind, measure, tests)?;
    let mut notes = Vec::new();
    let regression = match fit_regression(&data, &RegressionParams { confidence }) {
        Ok(r) => Some(r),
        Err(e @ tribo::Error::InvalidParameter { .. }) if e.to_string().starts_with("data") => {
            notes.push(format!("regression skipped: {e}"));
            None
        }
        Err(e) => return Err(e.into()),
    };
    let max_likelihood = match fit_max_likelihood(&data, &MaxLikelihoodParams::default()) {
        Ok(m) => Some(m),
        Err(e @ tribo::Error::InvalidParameter { .. }) => {
            notes.push(format!("maximum likelihood skipped: {e}"));
            None
        }
        Err(e) => return Err(e.into()),
    };
    if regression.is_none() && max_likelihood.is_none() {
        fit_regression(&data, &RegressionParams { confidence })?;
    }
    if let Some(m) = &max_likelihood {
        if m.load_scatter_fixed {
            notes.push(
                "fewer than two mixed levels: the load scatter T_S is held at T_N^(1/m) of \
                 the regression (as pyLife does)"
                    .into(),
            );
        }
    }
    Ok(FitReport {
        version: env!("CARGO_PKG_VERSION"),
        outputs: FIT_FILES,
        data: source.to_string(),
        kind,
        limit_symbol: kind.limit_symbol(),
        measure,
        unit: "Pa",
        tests: data.tests().len(),
        fractures: data.fractures().count(),
        runouts: data.runouts().count(),
        mixed_levels: data.mixed_levels(),
        regression,
        max_likelihood,
        notes,
        points: data.tests().to_vec(),
    })
}

impl FitReport {
    /// The finite numbers of the report (all must be finite for it to be written).
    pub fn scalars(&self) -> Vec<f64> {
        let mut v = self.mixed_levels.clone();
        if let Some(r) = &self.regression {
            let g = &r.regression;
            v.extend([
                g.intercept,
                g.slope_b,
                g.std_error,
                g.std_error_slope,
                g.std_error_intercept,
                g.r_squared,
                r.band.t_quantile,
                r.band.e739_factor,
            ]);
            v.extend(r.curve.iter().flat_map(curve_scalars));
        }
        if let Some(m) = &self.max_likelihood {
            v.extend(curve_scalars(&m.curve));
            v.extend([
                m.scatter_cycles,
                m.scatter_load,
                m.log_likelihood,
                m.f_spread,
            ]);
        }
        v
    }
}

fn curve_scalars(c: &WoehlerCurve) -> [f64; 3] {
    [c.fatigue_limit(), c.slope(), c.knee_cycles()]
}

/// Where a limit came from.
#[derive(Debug, Clone, Serialize)]
pub struct LimitSource {
    /// The limit's key (sigma_1, p_f, sigma_1p, p_f_sigma).
    pub key: &'static str,
    /// Value, Pa.
    pub value: f64,
    /// "given", or the data file it was fitted from.
    pub source: String,
    /// The fitting method, when fitted.
    pub method: Option<&'static str>,
}

/// The parsed diagram input.
#[derive(Debug, Clone)]
pub struct DiagramInput {
    /// Title.
    pub title: String,
    /// The limits.
    pub limits: MechanoRollingLimits,
    /// Where each came from.
    pub sources: Vec<LimitSource>,
    /// Optional load state (sigma_a, p0), Pa.
    pub state: Option<(f64, f64)>,
}

const LIMIT_KEYS: [(&str, TestKind); 4] = [
    ("sigma_1", TestKind::MechanicalFatigue),
    ("p_f", TestKind::RollingFatigue),
    ("sigma_1p", TestKind::MechanoRollingStress),
    ("p_f_sigma", TestKind::MechanoRollingPressure),
];

fn table<'a>(
    v: &'a Value,
    field: &str,
    allowed: &[&str],
) -> CaseResult<&'a toml::map::Map<String, Value>> {
    let t = v
        .as_table()
        .ok_or_else(|| CaseError::field(field, units::show(v), "must be a table"))?;
    if let Some(k) = t.keys().find(|k| !allowed.contains(&k.as_str())) {
        let name = if field.is_empty() {
            k.clone()
        } else {
            format!("{field}.{k}")
        };
        return Err(CaseError::field(
            name,
            "...",
            format!("unknown key; expected one of {}", allowed.join(", ")),
        ));
    }
    Ok(t)
}

fn required<'a>(
    t: &'a toml::map::Map<String, Value>,
    field: &str,
    key: &str,
) -> CaseResult<&'a Value> {
    t.get(key)
        .ok_or_else(|| CaseError::field(format!("{field}.{key}"), "missing", "is required"))
}

/// A limit: a quantity, or `{ data = "file.csv", measure = "...", method = "..." }`.
fn limit(v: &Value, key: &'static str, kind: TestKind, base: &Path) -> CaseResult<LimitSource> {
    let field = format!("limits.{key}");
    if !v.is_table() {
        return Ok(LimitSource {
            key,
            value: units::quantity(&field, v, Dim::Pressure)?,
            source: "given".into(),
            method: None,
        });
    }
    let t = table(v, &field, &["data", "measure", "method"])?;
    let file = required(t, &field, "data")?
        .as_str()
        .ok_or_else(|| CaseError::field(format!("{field}.data"), "...", "must be a file name"))?;
    let measure = match t.get("measure").map(|m| m.as_str()) {
        None => kind.default_measure(),
        Some(Some("amplitude")) => LoadMeasure::Amplitude,
        Some(Some("range")) => LoadMeasure::Range,
        Some(Some("contact_pressure")) => LoadMeasure::ContactPressure,
        Some(_) => {
            return Err(CaseError::field(
                format!("{field}.measure"),
                units::show(&t["measure"]),
                "must be \"amplitude\", \"range\" or \"contact_pressure\"",
            ))
        }
    };
    let method = match t.get("method").map(|m| m.as_str()) {
        None | Some(Some("max-likelihood")) => "max-likelihood",
        Some(Some("regression")) => "regression",
        Some(_) => {
            return Err(CaseError::field(
                format!("{field}.method"),
                units::show(&t["method"]),
                "must be \"max-likelihood\" or \"regression\"",
            ))
        }
    };
    let path = base.join(file);
    let text = std::fs::read_to_string(&path).map_err(|source| CaseError::Unreadable {
        field: format!("{field}.data"),
        path: path.clone(),
        source,
    })?;
    let tests = parse_csv(&text, &path)?;
    let data = FatigueData::new(kind, measure, tests)?;
    let curve = if method == "regression" {
        fit_regression(&data, &RegressionParams::default())?
            .curve
            .ok_or_else(|| {
                CaseError::field(
                    format!("{field}.data"),
                    file,
                    "no run-outs: the regression gives no fatigue limit",
                )
            })?
    } else {
        fit_max_likelihood(&data, &MaxLikelihoodParams::default())?.curve
    };
    let target = kind.default_measure();
    Ok(LimitSource {
        key,
        value: curve.fatigue_limit_load().value_in(target)?,
        source: path.display().to_string(),
        method: Some(method),
    })
}

/// Parse the diagram TOML (`tribo example fatigue-diagram`).
pub fn parse_limits(text: &str, name: &str, base: &Path) -> CaseResult<DiagramInput> {
    let doc: Value =
        text.parse::<toml::Table>()
            .map(Value::Table)
            .map_err(|e| CaseError::Parse {
                path: name.into(),
                message: e.to_string(),
            })?;
    let top = table(&doc, "", &["title", "limits", "state"])?;
    let title = match top.get("title") {
        None => "limiting-state diagram".to_string(),
        Some(Value::String(s)) => s.clone(),
        Some(v) => {
            return Err(CaseError::field(
                "title",
                units::show(v),
                "must be a string",
            ))
        }
    };
    let lim = required(top, "", "limits")
        .map_err(|_| CaseError::field("limits", "missing", "the [limits] table is required"))?;
    let mut keys: Vec<&str> = LIMIT_KEYS.iter().map(|k| k.0).collect();
    keys.extend(["sigma_p_contact_pressure", "p_sigma_stress_amplitude"]);
    let lt = table(lim, "limits", &keys)?;
    let mut sources = Vec::new();
    for (key, kind) in LIMIT_KEYS {
        sources.push(limit(required(lt, "limits", key)?, key, kind, base)?);
    }
    let held = |key: &str| -> CaseResult<f64> {
        units::quantity(
            &format!("limits.{key}"),
            required(lt, "limits", key)?,
            Dim::Pressure,
        )
    };
    let limits = MechanoRollingLimits {
        sigma_1: sources[0].value,
        p_f: sources[1].value,
        sigma_1p: sources[2].value,
        p_f_sigma: sources[3].value,
        sigma_p_contact_pressure: held("sigma_p_contact_pressure")?,
        p_sigma_stress_amplitude: held("p_sigma_stress_amplitude")?,
    };
    let state = match top.get("state") {
        None => None,
        Some(v) => {
            let st = table(v, "state", &["stress_amplitude", "contact_pressure"])?;
            let q = |k: &str| -> CaseResult<f64> {
                units::quantity(
                    &format!("state.{k}"),
                    required(st, "state", k)?,
                    Dim::Pressure,
                )
            };
            Some((q("stress_amplitude")?, q("contact_pressure")?))
        }
    };
    Ok(DiagramInput {
        title,
        limits,
        sources,
        state,
    })
}

/// The report of `tribo fatigue diagram` (limit_diagram.json).
#[derive(Debug, Clone, Serialize)]
pub struct DiagramReport {
    /// The tribo version.
    pub version: &'static str,
    /// Files written (names within the output directory).
    pub outputs: [&'static str; 2],
    /// Title.
    pub title: String,
    /// Coordinates: x = p0 / p_f, y = sigma_a / sigma_-1.
    pub axes: &'static str,
    /// The diagram.
    pub diagram: LimitDiagram,
    /// Where the limits came from.
    pub sources: Vec<LimitSource>,
    /// The load state check.
    pub state: Option<StateCheck>,
    /// Definition of the margin.
    pub margin_definition: &'static str,
}

/// Build the diagram and check the state.
pub fn diagram(input: DiagramInput) -> CaseResult<DiagramReport> {
    let d = LimitDiagram::new(input.limits)?;
    let state = match input.state {
        Some((s, p)) => Some(d.check(s, p)?),
        None => None,
    };
    Ok(DiagramReport {
        version: env!("CARGO_PKG_VERSION"),
        outputs: DIAGRAM_FILES,
        title: input.title,
        axes: "x = p0 / p_f (contact pressure), y = sigma_a / sigma_-1 (bending stress amplitude)",
        diagram: d,
        sources: input.sources,
        state,
        margin_definition: "load_factor: the factor on both sigma_a and p0 (proportional \
                            loading) that reaches the boundary ABCD; inside when > 1; margin = \
                            load_factor - 1",
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_headers_units_and_flags() {
        let t = parse_csv(
            "# c\nload_MPa, cycles, fracture\n300,1e5,yes\n250,1e7,0\n",
            Path::new("x.csv"),
        )
        .unwrap();
        assert_eq!(t[0].load, 300e6);
        assert!(!t[0].runout && t[1].runout);
        let e = parse_csv("load,cycles\n1,2\n", Path::new("x.csv")).unwrap_err();
        assert!(e.to_string().contains("runout"), "{e}");
        let e = parse_csv("load,cycles,runout\n1,x,true\n", Path::new("x.csv")).unwrap_err();
        assert!(e.to_string().contains("line 2"), "{e}");
        let t = parse_csv("load_MPa,cycles,runout\n0.3,1e5,0\n", Path::new("x.csv")).unwrap();
        assert_eq!(t[0].load.to_bits(), 3e5f64.to_bits());
    }

    /// A duplicated column, or two columns for one quantity, was silently resolved by taking
    /// the first (issue 11 item 10): now refused, naming the columns and the rule.
    #[test]
    fn csv_with_conflicting_columns_is_refused() {
        for (text, names) in [
            ("load,cycles,runout,runout\n1,2,1,0\n", "\"runout\" twice"),
            ("load,cycles,cycles,runout\n1,2,3,1\n", "\"cycles\" twice"),
            (
                "load,cycles,runout,fracture\n1,2,1,1\n",
                "2 flag columns (runout, fracture)",
            ),
            (
                "load_Pa,load_MPa,cycles,runout\n1,2,3,1\n",
                "2 load columns (load_Pa, load_MPa)",
            ),
            (
                "load,N,cycles,runout\n1,2,3,1\n",
                "2 cycles columns (N, cycles)",
            ),
        ] {
            let e = parse_csv(text, Path::new("x.csv")).unwrap_err().to_string();
            assert!(e.contains(names), "{text:?}: {e}");
            assert!(e.contains("line 1"), "{e}");
        }
        for cell in ["inf", "NaN", "-inf"] {
            let text = format!("load,cycles,runout\n{cell},1e5,0\n");
            let e = parse_csv(&text, Path::new("x.csv"))
                .unwrap_err()
                .to_string();
            assert!(e.contains("finite"), "{e}");
        }
    }
}
