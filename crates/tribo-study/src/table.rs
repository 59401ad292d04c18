//! The results table of a study: one row per point, in point order: `index`, `seed`, the
//! parameters (as `points.csv` has them), the collected numbers (named by their key path and
//! unit: `contact.max_pressure_Pa`) and `status` (`ok`, `failed: <reason>`, `missing`).
//! Written as `results.csv` and `results.nc` (NetCDF-3, [`crate::netcdf`]); both hold the
//! same columns under the same names. The table is a function of the point directories
//! only: the same whatever the jobs, chunks or machines that computed them.

use crate::error::{StudyError, StudyResult};
use crate::netcdf::{self, Attr, Column, Variable};
use crate::plan::{cell, point_seed, quote, value, StudyDir};
use crate::run::{point_dir, states, PointState};

/// The results table.
#[derive(Debug, Clone)]
pub struct Table {
    /// The column names: index, seed, the parameters, the collected numbers, status.
    pub columns: Vec<String>,
    /// Per point: the parameters' values.
    pub parameters: Vec<Vec<toml::Value>>,
    /// Per point: the collected numbers (NaN where the point has none).
    pub collected: Vec<Vec<f64>>,
    /// Per collected column: every value present is an integer in the points' `summary.json`
    /// (a count: iterations, elements), written as an integer in `results.csv`.
    pub integer: Vec<bool>,
    /// Per point: `ok`, `failed: <reason>` or `missing`.
    pub status: Vec<String>,
}

impl Table {
    /// The number of points done, failed and missing.
    pub fn counts(&self) -> (usize, usize, usize) {
        let done = self.status.iter().filter(|s| *s == "ok").count();
        let failed = self
            .status
            .iter()
            .filter(|s| s.starts_with("failed"))
            .count();
        (done, failed, self.status.len() - done - failed)
    }
}

/// Reads every point's state and collected numbers.
pub fn gather(sd: &StudyDir) -> StudyResult<Table> {
    let study = &sd.study;
    let n = study.len();
    let st = states(sd)?;
    let mut columns = vec!["index".to_string(), "seed".to_string()];
    columns.extend(study.parameters.iter().map(|p| p.key.text.clone()));
    columns.extend(study.collect.iter().map(|c| c.column.clone()));
    columns.push("status".into());
    let mut parameters = Vec::with_capacity(n);
    let mut collected = Vec::with_capacity(n);
    let mut status = Vec::with_capacity(n);
    let mut integer = vec![true; study.collect.len()];
    for (i, s) in st.iter().enumerate() {
        parameters.push(
            (0..study.parameters.len())
                .map(|j| value(study, j, i))
                .collect(),
        );
        let mut row = vec![f64::NAN; study.collect.len()];
        match s {
            PointState::Done => {
                let path = point_dir(sd, i).join("summary.json");
                let text =
                    std::fs::read_to_string(&path).map_err(|e| StudyError::file(&path, e))?;
                let json: serde_json::Value =
                    serde_json::from_str(&text).map_err(|e| StudyError::Dir {
                        dir: sd.dir.clone(),
                        detail: format!("{}: {e}", path.display()),
                    })?;
                for (j, (c, x)) in study.collect.iter().zip(row.iter_mut()).enumerate() {
                    if let Some((v, is_integer)) = crate::path::get_typed_number(&json, &c.key) {
                        *x = v;
                        integer[j] &= is_integer;
                    }
                }
                status.push("ok".to_string());
            }
            PointState::Failed(r) => status.push(r.clone()),
            PointState::Missing => status.push("missing".into()),
        }
        collected.push(row);
    }
    Ok(Table {
        columns,
        parameters,
        collected,
        integer,
        status,
    })
}

/// The text of `results.csv`: numbers in Rust's shortest round-trip form, counts (a column
/// whose values are all integers in `summary.json`) as integers (`21`, not `2.1e1`), an empty
/// cell where a point has no number.
pub fn csv(sd: &StudyDir, t: &Table) -> String {
    let mut s = t
        .columns
        .iter()
        .map(|c| quote(c))
        .collect::<Vec<_>>()
        .join(",");
    s.push('\n');
    for i in 0..t.status.len() {
        s.push_str(&format!("{i},{}", point_seed(sd.study.seed, i)));
        for v in &t.parameters[i] {
            s.push(',');
            s.push_str(&cell(v));
        }
        for (j, x) in t.collected[i].iter().enumerate() {
            s.push(',');
            if x.is_nan() {
            } else if t.integer.get(j).copied().unwrap_or(false) && x.abs() < 9.0e15 {
                // An integer of summary.json, exact in f64 below 2^53.
                s.push_str(&format!("{}", *x as i64));
            } else {
                s.push_str(&format!("{:e}", x + 0.0));
            }
        }
        s.push(',');
        s.push_str(&quote(&t.status[i]));
        s.push('\n');
    }
    s
}

/// A parameter's column for NetCDF: doubles where every value is a number, else text.
fn parameter_column(t: &Table, j: usize) -> Column {
    let numbers: Option<Vec<f64>> = t
        .parameters
        .iter()
        .map(|row| match &row[j] {
            toml::Value::Float(x) => Some(*x),
            toml::Value::Integer(k) => Some(*k as f64),
            _ => None,
        })
        .collect();
    match numbers {
        Some(x) => Column::Double(x),
        None => Column::Text(
            t.parameters
                .iter()
                .map(|row| match &row[j] {
                    toml::Value::String(s) => s.clone(),
                    v => v.to_string(),
                })
                .collect(),
        ),
    }
}

/// The bytes of `results.nc`: the columns of `results.csv` as variables over the dimension
/// `point` (`index` NC_INT, `seed` and the numbers NC_DOUBLE, text NC_CHAR), each collected
/// number with its `units` and `key` attributes, each parameter with `key`.
pub fn netcdf_bytes(sd: &StudyDir, t: &Table) -> StudyResult<Vec<u8>> {
    let study = &sd.study;
    let n = t.status.len();
    let text = |s: &str| Attr::Text(s.to_string());
    let mut vars = vec![
        Variable {
            name: "index".into(),
            attrs: vec![("long_name".into(), text("point index"))],
            data: Column::Int(
                (0..n)
                    .map(|i| i32::try_from(i).unwrap_or(i32::MAX))
                    .collect(),
            ),
        },
        Variable {
            name: "seed".into(),
            attrs: vec![(
                "long_name".into(),
                text("the point's seed (integer below 2^53)"),
            )],
            data: Column::Double((0..n).map(|i| point_seed(study.seed, i) as f64).collect()),
        },
    ];
    for (j, p) in study.parameters.iter().enumerate() {
        vars.push(Variable {
            name: p.key.text.clone(),
            attrs: vec![
                ("key".into(), text(&p.key.text)),
                ("long_name".into(), text(&format!("parameter {}", p.item))),
            ],
            data: parameter_column(t, j),
        });
    }
    for (k, c) in study.collect.iter().enumerate() {
        vars.push(Variable {
            name: c.column.clone(),
            attrs: vec![
                ("units".into(), text(&c.unit)),
                ("key".into(), text(&c.key.text)),
            ],
            data: Column::Double(t.collected.iter().map(|r| r[k]).collect()),
        });
    }
    vars.push(Variable {
        name: "status".into(),
        attrs: vec![],
        data: Column::Text(t.status.clone()),
    });
    let globals = vec![
        ("title".into(), text(&study.name)),
        (
            "source".into(),
            text(&format!("tribo {} sweep gather", env!("CARGO_PKG_VERSION"))),
        ),
        ("base_case".into(), text(&study.base.source)),
        ("study_seed".into(), Attr::Double(study.seed as f64)),
    ];
    netcdf::write(n, &globals, &vars).map_err(|detail| StudyError::Dir {
        dir: sd.dir.clone(),
        detail: format!("results.nc: {detail}"),
    })
}

/// Gathers the table and writes `results.csv` and `results.nc` into the study directory
/// (each atomically).
pub fn write(sd: &StudyDir) -> StudyResult<Table> {
    let t = gather(sd)?;
    tribo_io::atomic::write_atomic(&sd.dir, "results.csv", csv(sd, &t).as_bytes())?;
    tribo_io::atomic::write_atomic(&sd.dir, "results.nc", &netcdf_bytes(sd, &t)?)?;
    Ok(t)
}
