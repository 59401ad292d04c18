//! Checks of the shared summary layout.

#![allow(dead_code)] // each test crate uses part of it

/// Every numeric leaf of `summary` (outside the case echo), as a dotted path with `[]` for
/// array elements.
pub fn numeric_paths(summary: &serde_json::Value) -> Vec<String> {
    fn walk(v: &serde_json::Value, path: &str, out: &mut Vec<String>) {
        match v {
            serde_json::Value::Object(m) => {
                for (k, x) in m {
                    if path.is_empty() && (k == "case" || k == "units") {
                        continue;
                    }
                    let p = if path.is_empty() {
                        k.clone()
                    } else {
                        format!("{path}.{k}")
                    };
                    walk(x, &p, out);
                }
            }
            serde_json::Value::Array(a) => {
                for x in a {
                    walk(x, &format!("{path}[]"), out);
                }
            }
            serde_json::Value::Number(_) => out.push(path.to_string()),
            _ => {}
        }
    }
    let mut out = Vec::new();
    walk(summary, "", &mut out);
    out.sort();
    out.dedup();
    out
}

/// Does the units key `pattern` (segments split at '.', `*` any one segment) match `path`?
fn matches(pattern: &str, path: &str) -> bool {
    let (p, q): (Vec<&str>, Vec<&str>) = (pattern.split('.').collect(), path.split('.').collect());
    p.len() == q.len() && p.iter().zip(&q).all(|(a, b)| *a == "*" || a == b)
}

/// The shared layout (`kind`, `version`, `title`, `case`, `outputs`, `timings`, `units`) and
/// a unit for every number.
pub fn assert_layout(summary: &serde_json::Value) {
    for key in ["kind", "version", "title"] {
        assert!(summary[key].is_string(), "{key}");
    }
    assert_eq!(summary["version"], env!("CARGO_PKG_VERSION"));
    assert!(summary["case"].is_object(), "case");
    assert!(summary["outputs"].is_array(), "outputs");
    let timings = summary["timings"].as_object().expect("timings");
    assert!(timings
        .iter()
        .all(|(k, v)| k.ends_with("_s") && v.as_f64().is_some_and(|t| t >= 0.0)));
    let units = summary["units"].as_object().expect("units");
    for path in numeric_paths(summary) {
        assert!(
            units.keys().any(|k| matches(k, &path)),
            "no unit for {path}"
        );
    }
}
