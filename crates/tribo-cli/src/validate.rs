//! `tribo validate`: the verification suite's table.

use crate::error::CliResult;
pub use tribo::validation::ValidationRow;

/// Run the library's verification suite (`tribo::validation::run_all`).
pub fn run_suite() -> CliResult<Vec<ValidationRow>> {
    Ok(tribo::validation::run_all()?)
}

fn num(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if (1e-3..1e5).contains(&x.abs()) {
        format!("{x:.6}")
    } else {
        format!("{x:.5e}")
    }
}

/// The table as text: case, quantity, reference, computed, error, tolerance, pass.
pub fn table(rows: &[ValidationRow]) -> String {
    let header = [
        "case",
        "quantity",
        "reference",
        "computed",
        "error",
        "tolerance",
        "pass",
    ];
    let cells: Vec<[String; 7]> = rows
        .iter()
        .map(|r| {
            [
                r.case.clone(),
                r.quantity.clone(),
                num(r.reference),
                num(r.computed),
                format!("{:.3e}", r.error),
                format!("{:.1e}", r.tolerance),
                if r.passed { "yes".into() } else { "NO".into() },
            ]
        })
        .collect();
    let mut width = header.map(str::len);
    for row in &cells {
        for (w, c) in width.iter_mut().zip(row) {
            *w = (*w).max(c.chars().count());
        }
    }
    let line = |row: &[String]| {
        row.iter()
            .enumerate()
            .map(|(k, c)| {
                if k < 2 {
                    format!("{c:<w$}", w = width[k])
                } else {
                    format!("{c:>w$}", w = width[k])
                }
            })
            .collect::<Vec<_>>()
            .join("  ")
            .trim_end()
            .to_string()
    };
    let mut out = line(&header.map(String::from));
    out.push('\n');
    out.push_str(
        &width
            .iter()
            .map(|w| "-".repeat(*w))
            .collect::<Vec<_>>()
            .join("  "),
    );
    out.push('\n');
    for row in &cells {
        out.push_str(&line(row));
        out.push('\n');
    }
    let failed = rows.iter().filter(|r| !r.passed).count();
    out.push_str(&format!(
        "{} rows, {} passed, {} failed\n",
        rows.len(),
        rows.len() - failed,
        failed
    ));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_layout() {
        let rows = vec![
            ValidationRow {
                case: "hertz paper".into(),
                quantity: "a".into(),
                reference: 5.2964e-4,
                computed: 5.2964e-4,
                error: 1e-9,
                tolerance: 1e-6,
                measure: tribo::validation::ErrorMeasure::Relative,
                source: "test".into(),
                passed: true,
            },
            ValidationRow {
                case: "x".into(),
                quantity: "eps_avg".into(),
                reference: 0.004,
                computed: 0.0037,
                error: 0.3,
                tolerance: 0.1,
                measure: tribo::validation::ErrorMeasure::Relative,
                source: "test".into(),
                passed: false,
            },
        ];
        let t = table(&rows);
        let lines: Vec<&str> = t.lines().collect();
        assert!(lines[0].starts_with("case") && lines[0].ends_with("pass"));
        assert!(lines[2].contains("5.29640e-4") && lines[2].ends_with("yes"));
        assert!(lines[3].ends_with("NO"));
        assert_eq!(lines[4], "2 rows, 1 passed, 1 failed");
    }
}
