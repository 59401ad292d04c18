//! Key paths: the addresses of a study's parameters in the case TOML and of its collected
//! numbers in the run's summary JSON.
//!
//! A key path is dot-separated names, each optionally followed by indices in brackets:
//! `contact.load`, `body1.radii[0]`, `steps[-1].pairs[0].max_pressure.value` (a negative index
//! counts from the end). Where a name leads to an array of tables (a 2D case's `[[bc]]`,
//! `[[regions]]`, `[[contact]]`), the next name picks the entry whose `name` (or, failing
//! that, `segment`) equals it: `bc.wall.pressure` is the `pressure` of the `[[bc]]` entry
//! with `segment = "wall"`.

/// One segment of a key path: a name and the indices after it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Segment {
    /// The name.
    pub name: String,
    /// The indices (`[2]`, `[-1]`) after it, in order.
    pub index: Vec<i64>,
}

/// A parsed key path.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct KeyPath {
    /// As written.
    pub text: String,
    /// Its segments.
    pub segments: Vec<Segment>,
}

impl std::fmt::Display for KeyPath {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text)
    }
}

impl KeyPath {
    /// Parses `text`; the error says what is malformed.
    pub fn parse(text: &str) -> Result<KeyPath, String> {
        if text.is_empty() {
            return Err("a key path is names separated by dots, e.g. contact.load".into());
        }
        let mut segments = Vec::new();
        for part in text.split('.') {
            let (name, mut rest) = match part.find('[') {
                Some(i) => (&part[..i], &part[i..]),
                None => (part, ""),
            };
            if name.is_empty()
                || !name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
            {
                return Err(format!(
                    "{part:?} is not a key: names of letters, digits, '_' and '-', each \
                     optionally followed by [index]"
                ));
            }
            let mut index = Vec::new();
            while !rest.is_empty() {
                let close = rest
                    .find(']')
                    .filter(|_| rest.starts_with('['))
                    .ok_or_else(|| format!("{part:?}: an index is written [N]"))?;
                let n: i64 = rest[1..close]
                    .parse()
                    .map_err(|_| format!("{part:?}: an index is an integer, [0] or [-1]"))?;
                index.push(n);
                rest = &rest[close + 1..];
            }
            segments.push(Segment {
                name: name.to_string(),
                index,
            });
        }
        Ok(KeyPath {
            text: text.to_string(),
            segments,
        })
    }

    /// The path with every index written `[]`: the form of the summaries' unit tables.
    pub fn pattern_form(&self) -> Vec<String> {
        self.segments
            .iter()
            .map(|s| format!("{}{}", s.name, "[]".repeat(s.index.len())))
            .collect()
    }
}

/// Resolves a possibly negative index into an array of `len`.
fn resolve(i: i64, len: usize) -> Option<usize> {
    let n = i64::try_from(len).ok()?;
    let j = if i < 0 { n + i } else { i };
    usize::try_from(j).ok().filter(|&j| j < len)
}

/// The entry of an array of tables whose `name` (or else `segment`) is `id`.
fn pick<'a>(items: &'a mut [toml::Value], id: &str) -> Result<&'a mut toml::Value, String> {
    for field in ["name", "segment"] {
        let hits: Vec<usize> = items
            .iter()
            .enumerate()
            .filter(|(_, v)| v.get(field).and_then(toml::Value::as_str) == Some(id))
            .map(|(i, _)| i)
            .collect();
        match hits.as_slice() {
            [] => continue,
            [i] => return Ok(&mut items[*i]),
            _ => {
                return Err(format!(
                    "{} entries have {field} = {id:?}: address one by its index, [N]",
                    hits.len()
                ))
            }
        }
    }
    Err(format!("no entry has name or segment = {id:?}"))
}

/// Sets `value` at `path` in a case's TOML table. Missing tables on the way are created (the
/// case schema decides whether the result is a case); arrays must exist, and a name after an
/// array of tables picks an entry by its `name` or `segment`. The error says which part of
/// the path does not resolve.
pub fn set(root: &mut toml::Table, path: &KeyPath, value: toml::Value) -> Result<(), String> {
    let mut cur: &mut toml::Table = root;
    let segs = &path.segments;
    let mut k = 0;
    while k < segs.len() {
        let seg = &segs[k];
        let last = k + 1 == segs.len();
        if last && seg.index.is_empty() {
            cur.insert(seg.name.clone(), value);
            return Ok(());
        }
        let mut v: &mut toml::Value = cur
            .entry(seg.name.clone())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        for (j, &i) in seg.index.iter().enumerate() {
            let toml::Value::Array(items) = v else {
                return Err(format!("{} is not an array", seg.name));
            };
            let len = items.len();
            let at = resolve(i, len)
                .ok_or_else(|| format!("{}: index {i} out of range (length {len})", seg.name))?;
            if last && j + 1 == seg.index.len() {
                items[at] = value;
                return Ok(());
            }
            v = &mut items[at];
        }
        if let toml::Value::Array(items) = v {
            // A name after an array of tables picks an entry.
            let Some(next) = segs.get(k + 1) else {
                return Err(format!(
                    "{} is an array: give an index or an entry's name",
                    seg.name
                ));
            };
            let entry = pick(items, &next.name).map_err(|e| format!("{}: {e}", seg.name))?;
            if !next.index.is_empty() {
                return Err(format!(
                    "{}.{}: no index after an entry's name",
                    seg.name, next.name
                ));
            }
            k += 1;
            if k + 1 == segs.len() {
                return Err(format!(
                    "{}.{}: a value goes into a key of the entry",
                    seg.name, next.name
                ));
            }
            v = entry;
        }
        match v {
            toml::Value::Table(t) => cur = t,
            _ => return Err(format!("{} is a value, not a table", seg.name)),
        }
        k += 1;
    }
    Err("empty key path".into())
}

/// The number at `path` in a JSON document (a run's summary): booleans as 0/1; `None` where
/// the path does not resolve or holds no number.
pub fn get_number(root: &serde_json::Value, path: &KeyPath) -> Option<f64> {
    get_typed_number(root, path).map(|(x, _)| x)
}

/// [`get_number`] with whether the value is an integer in `summary.json` (a count: iterations,
/// elements, passes; a boolean counts as one).
pub fn get_typed_number(root: &serde_json::Value, path: &KeyPath) -> Option<(f64, bool)> {
    let mut v = root;
    for seg in &path.segments {
        v = v.get(&seg.name)?;
        for &i in &seg.index {
            let items = v.as_array()?;
            v = items.get(resolve(i, items.len())?)?;
        }
    }
    match v {
        serde_json::Value::Number(n) => Some((n.as_f64()?, n.is_i64() || n.is_u64())),
        serde_json::Value::Bool(b) => Some((f64::from(u8::from(*b)), true)),
        _ => None,
    }
}

/// The string at `path` in a JSON document, if there is one.
pub fn get_str<'a>(root: &'a serde_json::Value, path: &str) -> Option<&'a str> {
    let mut v = root;
    for name in path.split('.') {
        v = v.get(name)?;
    }
    v.as_str()
}

/// Whether a path (in [`KeyPath::pattern_form`]) matches a unit table's pattern, in which
/// `*` stands for one or more segments.
pub fn matches(pattern: &[&str], path: &[String]) -> bool {
    match (pattern.first(), path.first()) {
        (None, None) => true,
        (Some(&"*"), Some(_)) => (1..=path.len()).any(|n| matches(&pattern[1..], &path[n..])),
        (Some(p), Some(s)) => *p == s && matches(&pattern[1..], &path[1..]),
        _ => false,
    }
}

/// The unit of a summary number at `path` from a unit table (`(pattern, unit)` pairs), if
/// the table has it.
pub fn unit_of(table: &[(&'static str, &'static str)], path: &KeyPath) -> Option<&'static str> {
    let form = path.pattern_form();
    table.iter().find_map(|(pattern, unit)| {
        let p: Vec<&str> = pattern.split('.').collect();
        matches(&p, &form).then_some(*unit)
    })
}

/// A unit as a column-name suffix: `Pa` -> `_Pa`, `m^2` -> `_m2`, `N/m` -> `_N_per_m`,
/// `%` -> `_pct`, `1` (dimensionless) -> nothing.
pub fn unit_suffix(unit: &str) -> String {
    if unit == "1" || unit.is_empty() {
        return String::new();
    }
    let s = unit
        .replace('^', "")
        .replace('/', "_per_")
        .replace('%', "pct")
        .replace(' ', "_");
    format!("_{s}")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(s: &str) -> KeyPath {
        KeyPath::parse(s).unwrap()
    }

    #[test]
    fn parse_and_pattern() {
        let k = p("steps[-1].pairs[0].max_pressure.value");
        assert_eq!(k.segments[0].index, vec![-1]);
        assert_eq!(
            k.pattern_form(),
            vec!["steps[]", "pairs[]", "max_pressure", "value"]
        );
        for bad in ["", "a..b", "a[x]", "a[1", "a b", "a]"] {
            assert!(KeyPath::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn set_creates_tables_and_picks_entries() {
        let mut t: toml::Table = toml::from_str(
            "[contact]\nload = 1.0\n[[bc]]\nsegment = \"a\"\nux = 0\n[[bc]]\nsegment = \"wall\"\npressure = \"1 MPa\"\n[body1]\nradii = [1.0, 2.0]\n",
        )
        .unwrap();
        set(&mut t, &p("contact.load"), toml::Value::Float(2.0)).unwrap();
        set(
            &mut t,
            &p("damage.limits.sigma_int"),
            toml::Value::Float(3.0),
        )
        .unwrap();
        set(&mut t, &p("bc.wall.pressure"), "2 MPa".into()).unwrap();
        set(&mut t, &p("body1.radii[-1]"), toml::Value::Float(5.0)).unwrap();
        set(&mut t, &p("bc[0].ux"), toml::Value::Integer(1)).unwrap();
        assert_eq!(t["contact"]["load"].as_float(), Some(2.0));
        assert_eq!(t["damage"]["limits"]["sigma_int"].as_float(), Some(3.0));
        assert_eq!(t["bc"][1]["pressure"].as_str(), Some("2 MPa"));
        assert_eq!(t["body1"]["radii"][1].as_float(), Some(5.0));
        assert_eq!(t["bc"][0]["ux"].as_integer(), Some(1));
        let e = set(&mut t, &p("bc.nowhere.ux"), 1.into()).unwrap_err();
        assert!(e.contains("nowhere"), "{e}");
        assert!(set(&mut t, &p("body1.radii[2]"), 1.into()).is_err());
        assert!(set(&mut t, &p("contact.load.x"), 1.into()).is_err());
    }

    #[test]
    fn numbers_and_units() {
        let j: serde_json::Value =
            serde_json::from_str(r#"{"a": {"b": [1.5, 2.5]}, "c": true, "d": "x"}"#).unwrap();
        assert_eq!(get_number(&j, &p("a.b[-1]")), Some(2.5));
        assert_eq!(get_number(&j, &p("c")), Some(1.0));
        assert_eq!(get_number(&j, &p("d")), None);
        assert_eq!(get_number(&j, &p("a.b[2]")), None);
        let table = [
            ("back_effect.*.normal_load", "N"),
            ("damage.criteria[].volume", "m^3"),
            ("timings.*", "s"),
        ];
        assert_eq!(
            unit_of(&table, &p("back_effect.operating.bending.normal_load")),
            Some("N")
        );
        assert_eq!(
            unit_of(&table, &p("damage.criteria[0].volume")),
            Some("m^3")
        );
        assert_eq!(unit_of(&table, &p("timings.solve_s")), Some("s"));
        assert_eq!(unit_of(&table, &p("back_effect.normal_load")), None);
        assert_eq!(unit_suffix("m^3 s"), "_m3_s");
        assert_eq!(unit_suffix("N/m"), "_N_per_m");
        assert_eq!(unit_suffix("1"), "");
    }
}
