//! The typed leaves of the case schemas and the serde entry points that name the field in
//! every error.
//!
//! serde parses a case's structure (tables, keys, unknown keys, enums) into the raw structs of
//! [`crate::halfspace::schema`] and [`crate::bem::case`]; their leaves are the types here and
//! [`crate::units::Quantity`], each with a `Deserialize` that refuses a value with the value as
//! written and the rule it breaks. [`from_text`] and [`from_value`] track the key path with
//! `serde_path_to_error`, so that a refused leaf becomes a [`CaseError::Field`] named by its
//! full path (`body1.radii[0] = "big": a radius must be ...`), and any other schema error (an
//! unknown key, a missing table, a table where a value belongs) a [`CaseError::Parse`] with
//! the parser's line and column and the path.

use crate::error::{CaseError, CaseResult};
use crate::units::show;
use serde::de::{DeserializeOwned, Error as _};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt;
use toml::Value;

/// Marks a refusal's message among serde's own (which never start with a NUL).
const MARK: char = '\u{0}';

/// A value refused by a leaf of the schema: where below the leaf's key (`""`, or `[1]` for
/// an array item), the value as written, and the rule.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Refusal {
    at: String,
    value: String,
    rule: String,
}

impl Refusal {
    /// `value` breaks `rule`.
    pub(crate) fn new(value: &Value, rule: impl Into<String>) -> Self {
        Refusal {
            at: String::new(),
            value: show(value),
            rule: rule.into(),
        }
    }

    /// The refusal of an item `item` (e.g. `[1]`) of the value.
    pub(crate) fn within(mut self, item: impl fmt::Display) -> Self {
        self.at = format!("{item}{}", self.at);
        self
    }

    /// The refusal as a serde error message (decoded by [`Refusal::decode`]).
    fn encode(&self) -> String {
        format!("{MARK}{}{MARK}{}{MARK}{}", self.at, self.value, self.rule)
    }

    fn decode(message: &str) -> Option<Refusal> {
        let mut parts = message.strip_prefix(MARK)?.splitn(3, MARK);
        Some(Refusal {
            at: parts.next()?.to_string(),
            value: parts.next()?.to_string(),
            rule: parts.next()?.to_string(),
        })
    }
}

/// A leaf of the schema: converted from the TOML value at its key, or refused.
pub(crate) trait FromToml: Sized {
    /// The leaf `value` gives, or why not.
    fn from_toml(value: &Value) -> Result<Self, Refusal>;
}

/// `Deserialize` of a leaf: the TOML value, then [`FromToml`], a refusal carried through serde
/// as its error message.
pub(crate) fn deserialize_leaf<'de, T: FromToml, D: Deserializer<'de>>(
    deserializer: D,
) -> Result<T, D::Error> {
    let value = Value::deserialize(deserializer)?;
    T::from_toml(&value).map_err(|r| D::Error::custom(r.encode()))
}

macro_rules! leaf_deserialize {
    ($($t:ident),*) => {$(
        impl<'de> serde::Deserialize<'de> for $t {
            fn deserialize<D: serde::Deserializer<'de>>(
                deserializer: D,
            ) -> Result<Self, D::Error> {
                $crate::schema::deserialize_leaf(deserializer)
            }
        }
    )*};
}
pub(crate) use leaf_deserialize;

/// The case text parsed into the raw schema `T`. Errors name `source`; a refused leaf names
/// its full key path, other schema errors carry the parser's line and column and the path.
pub(crate) fn from_text<T: DeserializeOwned>(text: &str, source: &str) -> CaseResult<T> {
    let deserializer = toml::Deserializer::parse(text).map_err(|e| CaseError::Parse {
        path: source.to_string(),
        message: e.to_string().trim_end().to_string(),
    })?;
    serde_path_to_error::deserialize(deserializer).map_err(|e| schema_error(source, e))
}

/// A TOML value (a case built in code) parsed into the raw schema `T`, errors as
/// [`from_text`]'s (without line numbers).
pub(crate) fn from_value<T: DeserializeOwned>(value: Value, source: &str) -> CaseResult<T> {
    serde_path_to_error::deserialize(value).map_err(|e| schema_error(source, e))
}

fn schema_error(source: &str, e: serde_path_to_error::Error<toml::de::Error>) -> CaseError {
    let path = e.path().to_string();
    let inner = e.into_inner();
    match Refusal::decode(inner.message()) {
        Some(r) => CaseError::Field {
            field: format!("{path}{}", r.at),
            value: r.value,
            rule: r.rule,
        },
        None => {
            let mut message = inner.to_string().trim_end().to_string();
            if path != "." {
                // The first line names the key and the rule (the CLI prints it as the
                // error's line): "in `body1.nuu`: unknown field `nuu`, expected one of ...
                // (line 8, column 1)", then toml's snippet of the file. The full path in place
                // of toml's own (the table's, where it gives one).
                let rule = inner.message().trim().replace('\n', " ");
                let location = message
                    .lines()
                    .next()
                    .and_then(|l| l.strip_prefix("TOML parse error at "))
                    .map(|at| format!(" ({at})"))
                    .unwrap_or_default();
                let snippet: Vec<&str> = message
                    .lines()
                    .skip(1)
                    .filter(|l| l.trim_start().starts_with('|') || is_snippet_line(l))
                    .collect();
                let mut first = format!("in `{path}`: {rule}{location}");
                if !snippet.is_empty() {
                    first = format!("{first}\n{}", snippet.join("\n"));
                }
                message = first;
            }
            CaseError::Parse {
                path: source.to_string(),
                message,
            }
        }
    }
}

/// A line of toml's snippet: `8 | nuu = 1` (a line number, then the bar).
fn is_snippet_line(line: &str) -> bool {
    let t = line.trim_start();
    let digits = t.bytes().take_while(u8::is_ascii_digit).count();
    digits > 0 && t[digits..].trim_start().starts_with('|')
}

/// The items of a TOML array, each a leaf `T`; a refusal names the item (`[k]`).
pub(crate) fn items<T: FromToml>(values: &[Value]) -> Result<Vec<T>, Refusal> {
    values
        .iter()
        .enumerate()
        .map(|(k, v)| T::from_toml(v).map_err(|r| r.within(format!("[{k}]"))))
        .collect()
}

/// A non-negative integer (a number of elements, points, steps).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Count {
    /// The value.
    pub n: usize,
}

impl FromToml for Count {
    fn from_toml(value: &Value) -> Result<Self, Refusal> {
        crate::units::count_of(value)
            .map(|n| Count { n })
            .map_err(|rule| Refusal::new(value, rule))
    }
}

/// `true` or `false`, with the value as written.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Flag {
    /// The value.
    pub on: bool,
    /// As written.
    pub written: String,
}

impl FromToml for Flag {
    fn from_toml(value: &Value) -> Result<Self, Refusal> {
        match value {
            Value::Boolean(on) => Ok(Flag {
                on: *on,
                written: show(value),
            }),
            _ => Err(Refusal::new(value, "must be true or false")),
        }
    }
}

leaf_deserialize!(Count, Flag);

impl Serialize for Count {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_u64(self.n as u64)
    }
}

impl Serialize for Flag {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_bool(self.on)
    }
}

impl<E: Serialize> Serialize for Choice<E> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.value.serialize(serializer)
    }
}

/// An enum of a case file's choices (serde parses the strings: `rename_all`, `alias`), with
/// the rule naming them for a string that is none of them.
pub(crate) trait Choices: DeserializeOwned {
    /// "must be \"a\" (what it is) or \"b\" (...)".
    const RULE: &'static str;
}

/// A choice among the strings of `E`, with the value as written.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Choice<E> {
    /// The choice.
    pub value: E,
    /// As written.
    pub written: String,
}

impl<E: Choices> FromToml for Choice<E> {
    fn from_toml(value: &Value) -> Result<Self, Refusal> {
        match value {
            Value::String(_) => E::deserialize(value.clone())
                .map(|v| Choice {
                    value: v,
                    written: show(value),
                })
                .map_err(|_| Refusal::new(value, E::RULE)),
            _ => Err(Refusal::new(value, E::RULE)),
        }
    }
}

impl<'de, E: Choices> Deserialize<'de> for Choice<E> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserialize_leaf(deserializer)
    }
}

/// One value for both x and y, or an array of two `[x, y]`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Pair<T> {
    /// The x and y values.
    pub items: [T; 2],
    /// Whether it was written as an array (errors then name `[0]`, `[1]`).
    pub array: bool,
    /// As written.
    pub written: String,
}

impl<T> Pair<T> {
    /// The key of item `k` under `field`: `field[k]` where written as an array.
    pub fn item_key(&self, field: &str, k: usize) -> String {
        if self.array {
            format!("{field}[{k}]")
        } else {
            field.to_string()
        }
    }
}

impl<T: FromToml + Clone> FromToml for Pair<T> {
    fn from_toml(value: &Value) -> Result<Self, Refusal> {
        let written = show(value);
        match value {
            Value::Array(a) if a.len() == 2 => {
                let [x, y]: [T; 2] = items(a)?
                    .try_into()
                    .map_err(|_| Refusal::new(value, "must be an array of two [x, y]"))?;
                Ok(Pair {
                    items: [x, y],
                    array: true,
                    written,
                })
            }
            Value::Array(a) => Err(Refusal::new(
                value,
                format!(
                    "must be one value or an array of two [x, y] (got {} values)",
                    a.len()
                ),
            )),
            single => {
                let v = T::from_toml(single)?;
                Ok(Pair {
                    items: [v.clone(), v],
                    array: false,
                    written,
                })
            }
        }
    }
}

impl<'de, T: FromToml + Clone> Deserialize<'de> for Pair<T> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserialize_leaf(deserializer)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::units::{Length, Quantity};

    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Outer {
        inner: Inner,
    }

    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Inner {
        size: Option<Pair<Quantity<Length>>>,
        n: Option<Count>,
        rows: Option<Vec<Vec<Quantity<Length>>>>,
    }

    fn err(text: &str) -> String {
        from_text::<Outer>(text, "t.toml").unwrap_err().to_string()
    }

    #[test]
    fn refusals_name_the_full_key_path() {
        assert_eq!(
            err("[inner]\nsize = [1, \"x\"]"),
            "inner.size[1] = \"x\": must be a length: a number in m or a string \
             \"<number> <unit>\" with unit one of mm, cm, um, µm, nm, m"
        );
        assert!(err("[inner]\nsize = [1, 2, 3]").starts_with("inner.size = [1, 2, 3]: "));
        assert!(err("[inner]\nn = -1").starts_with("inner.n = -1: must be a non-negative"));
        assert!(err("[inner]\nrows = [[1], [2, nan]]").starts_with("inner.rows[1][1] = nan:"));
        let ok = from_text::<Outer>("[inner]\nsize = \"2 mm\"\nn = 3", "t.toml").unwrap();
        let size = ok.inner.size.unwrap();
        assert_eq!((size.items[1].si(), size.array), (2e-3, false));
        assert_eq!((ok.inner.n.map(|c| c.n), ok.inner.rows), (Some(3), None));
    }

    #[test]
    fn other_schema_errors_carry_line_and_path() {
        // The first line names the key, the rule and where (the CLI's error line).
        let e = err("[inner]\nn = 3\nsise = 1");
        let first = e.lines().next().unwrap();
        assert!(
            first.starts_with("t.toml: in `inner.sise`: unknown field `sise`"),
            "{e}"
        );
        assert!(first.ends_with("(line 3, column 1)"), "{e}");
        assert!(e.contains("3 | sise = 1"), "{e}");
        let e = err("inner = 3");
        assert!(e.starts_with("t.toml: in `inner`: "), "{e}");
        let table: toml::Table = toml::from_str("[inner]\nsise = 1").unwrap();
        let e = from_value::<Outer>(Value::Table(table), "code")
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("code: in `inner.sise`: unknown field `sise`"),
            "{e}"
        );
        assert_eq!(e.matches("in `").count(), 1, "{e}");
    }
}
