//! The documentation cannot drift from the program.
//!
//! * The case references (docs/user/case-halfspace.md, case-bem2d.md) and the fatigue diagram's
//!   input table (docs/user/fatigue.md) document exactly the keys the parser accepts: each
//!   table of the schema is probed through the binary with an unknown key, and the keys the
//!   error message lists must equal the documented ones; every key of every embedded example
//!   (and of the references' own examples) must be documented, and those examples must be
//!   valid. Only the binary's behaviour is used (`tribo run - --dry-run`,
//!   `tribo fatigue diagram -`, `tribo example NAME`), never private items.
//! * docs/verification.md holds the rows of `tribo validate --json`: the test regenerates the
//!   table and compares everything but the computed values and errors (machine-dependent in
//!   the last digits). Regenerate it with `bench/verification_page.sh` (which runs this test
//!   with `TRIBO_REGENERATE_DOCS=1`).
// Tests may unwrap: a panic here is a failed test (workspace lints deny it in library code).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use toml::{Table, Value};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("the workspace root exists")
}

fn read(rel: &str) -> String {
    std::fs::read_to_string(root().join(rel)).unwrap_or_else(|e| panic!("{rel}: {e}"))
}

/// Run the `tribo` binary with `args`, feeding `stdin`.
fn tribo(args: &[&str], stdin: &str) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_tribo"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn tribo");
    {
        use std::io::Write;
        let mut input = child.stdin.take().expect("stdin");
        // A command that fails before reading all of stdin closes the pipe: not an error here.
        let _ = input.write_all(stdin.as_bytes());
    }
    child.wait_with_output().expect("wait for tribo")
}

fn example(name: &str) -> String {
    let out = tribo(&["example", name], "");
    assert!(out.status.success(), "tribo example {name}");
    String::from_utf8(out.stdout).expect("UTF-8 example")
}

/// The names of the embedded examples, from `tribo example`.
fn example_names() -> Vec<String> {
    let out = tribo(&["example"], "");
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).expect("UTF-8");
    text.lines()
        .filter(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next().map(str::to_string))
        .collect()
}

// ------------------------------------------------------------------ the documented keys

/// The key rows of a reference page: `| `key` | type | ...` -> (key, type cell).
struct Doc {
    page: &'static str,
    rows: BTreeMap<String, String>,
}

impl Doc {
    fn load(page: &'static str) -> Doc {
        let text = read(page);
        let mut rows = BTreeMap::new();
        for line in text.lines() {
            let Some(rest) = line.strip_prefix("| `") else {
                continue;
            };
            let Some(end) = rest.find('`') else { continue };
            let key = rest[..end].to_string();
            let cells: Vec<&str> = line.split(" | ").collect();
            let ty = cells.get(1).copied().unwrap_or("").to_string();
            assert!(
                rows.insert(key.clone(), ty).is_none(),
                "{page}: `{key}` documented twice"
            );
        }
        assert!(rows.len() > 5, "{page}: found only {} key rows", rows.len());
        Doc { page, rows }
    }

    /// The 2D reference with its dynamic keys (docs/user/case-bem2d-dynamics.md): one
    /// schema over two pages.
    fn bem() -> Doc {
        let mut doc = Doc::load("docs/user/case-bem2d.md");
        let dynamic = Doc::load("docs/user/case-bem2d-dynamics.md");
        for (k, ty) in dynamic.rows {
            assert!(
                doc.rows.insert(k.clone(), ty).is_none(),
                "`{k}` documented on both 2D pages"
            );
        }
        doc.page = "docs/user/case-bem2d.md and case-bem2d-dynamics.md";
        doc
    }

    /// A documented key, or a table holding documented keys.
    fn documents(&self, key: &str) -> bool {
        self.rows.contains_key(key)
            || self.rows.keys().any(|k| {
                k.strip_prefix(key)
                    .is_some_and(|r| r.starts_with('.') || r.starts_with("[]."))
            })
    }

    /// A table whose keys are names the user chooses (`materials.*`).
    fn is_map(&self, table: &str) -> bool {
        let star = join(table, "*");
        self.documents(&star)
    }

    /// The form (`<segment>`) a key's values take, from its type cell.
    fn form_of(&self, key: &str) -> Option<String> {
        let ty = self.rows.get(key)?;
        let start = ty.find("`<")?;
        let end = ty[start + 1..].find(">`")?;
        Some(ty[start + 1..start + 2 + end].to_string())
    }

    /// The documented keys directly in `table` (`""`: the top level), `[]` stripped.
    fn children(&self, table: &str) -> BTreeSet<String> {
        let mut out = BTreeSet::new();
        for k in self.rows.keys() {
            let rest = if table.is_empty() {
                Some(k.as_str())
            } else {
                k.strip_prefix(table)
                    .and_then(|r| r.strip_prefix('.').or_else(|| r.strip_prefix("[].")))
            };
            let Some(rest) = rest else { continue };
            let first = rest.split('.').next().unwrap_or(rest);
            let first = first.trim_end_matches("[]");
            if first != "*" && !first.starts_with('<') {
                out.insert(first.to_string());
            }
        }
        out
    }

    /// The tables of the schema: the parents of the documented keys, less the maps.
    fn tables(&self) -> BTreeSet<String> {
        let mut out = BTreeSet::new();
        for k in self.rows.keys() {
            let parent = match k.rfind('.') {
                Some(i) => k[..i].trim_end_matches("[]").to_string(),
                None => String::new(),
            };
            if !self.is_map(&parent) {
                out.insert(parent);
            }
        }
        out
    }

    /// Every key of a case, each checked against the rows; returns the undocumented ones.
    fn undocumented(&self, case: &Table) -> Vec<String> {
        let mut missing = Vec::new();
        self.walk(case, "", "", &mut missing);
        missing
    }

    fn walk(&self, table: &Table, prefix: &str, at: &str, missing: &mut Vec<String>) {
        for (k, v) in table {
            let here = join(at, k);
            let key = if self.is_map(prefix) {
                join(prefix, "*")
            } else {
                join(prefix, k)
            };
            if !self.documents(&key) {
                missing.push(format!("{here} (as `{key}`)"));
                continue;
            }
            let form = self.form_of(&key);
            match v {
                Value::Table(t) => self.walk(t, form.as_deref().unwrap_or(&key), &here, missing),
                Value::Array(items) => {
                    let inner = form.unwrap_or_else(|| format!("{key}[]"));
                    for (i, item) in items.iter().enumerate() {
                        if let Value::Table(t) = item {
                            self.walk(t, &inner, &format!("{here}[{i}]"), missing);
                        }
                    }
                }
                _ => {}
            }
        }
    }
}

fn join(prefix: &str, key: &str) -> String {
    if prefix.is_empty() {
        key.to_string()
    } else {
        format!("{prefix}.{key}")
    }
}

/// The ```toml blocks of a page.
fn toml_blocks(page: &str) -> Vec<String> {
    let text = read(page);
    text.split("```toml\n")
        .skip(1)
        .map(|b| b[..b.find("```").expect("closed block")].to_string())
        .collect()
}

/// The first ```toml block of a page.
fn first_toml_block(page: &str) -> String {
    toml_blocks(page)
        .into_iter()
        .next()
        .expect("a ```toml block")
}

fn parse(text: &str) -> Table {
    text.parse::<Table>().expect("a TOML case")
}

/// The value at a dotted path of table keys and array indices (`regions.0.outline.2`),
/// creating missing tables.
fn at<'a>(table: &'a mut Table, path: &str) -> &'a mut Value {
    let mut parts = path.split('.');
    let first = parts.next().expect("a path");
    let mut v = table
        .entry(first.to_string())
        .or_insert_with(|| Value::Table(Table::new()));
    for p in parts {
        v = match (v, p.parse::<usize>()) {
            (Value::Array(a), Ok(i)) => &mut a[i],
            (Value::Table(t), _) => t
                .entry(p.to_string())
                .or_insert_with(|| Value::Table(Table::new())),
            (other, _) => panic!("no table at {p} in {path}: {other:?}"),
        };
    }
    v
}

const PROBE: &str = "zz_probe";

/// How a probe reaches a table of the schema in a base case.
enum Probe {
    /// Insert the unknown key into the table at this path (`""`: the top level).
    Insert(&'static str),
    /// Replace the value at this path by this TOML value (holding the unknown key).
    Replace(&'static str, &'static str),
    /// Edit the case (and put the unknown key in).
    Edit(fn(&mut Table)),
}

/// A TOML value from its text.
fn value(text: &str) -> Value {
    format!("v = {text}")
        .parse::<Table>()
        .expect("a TOML value")["v"]
        .clone()
}

/// The keys a table accepts, read off the error the binary gives for an unknown key.
fn accepted_keys(args: &[&str], base: &str, probe: &Probe) -> BTreeSet<String> {
    let mut case = parse(base);
    match probe {
        Probe::Insert("") => {
            case.insert(PROBE.into(), Value::Integer(1));
        }
        Probe::Insert(path) => match at(&mut case, path) {
            Value::Table(t) => {
                t.insert(PROBE.into(), Value::Integer(1));
            }
            other => panic!("{path} is not a table: {other:?}"),
        },
        Probe::Replace(path, v) => *at(&mut case, path) = value(v),
        Probe::Edit(edit) => edit(&mut case),
    }
    let text = toml::to_string(&case).expect("serialize the probe");
    let out = tribo(args, &text);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(
        out.status.code(),
        Some(2),
        "the unknown key must be refused: {err}"
    );
    if matches!(probe, Probe::Insert(_)) {
        assert!(err.contains(PROBE), "the error must name the key: {err}");
    }
    let mut keys = keys_in_message(&err);
    keys.remove(PROBE);
    keys
}

fn keys_in_message(err: &str) -> BTreeSet<String> {
    let words = |s: &str| -> BTreeSet<String> {
        s.split([',', ';'])
            .map(|w| w.trim().trim_start_matches("or ").trim().trim_matches('`'))
            .filter(|w| !w.is_empty())
            .map(str::to_string)
            .collect()
    };
    // serde: "unknown field `k`, expected one of `a`, `b`" (or "expected `a`").
    if let Some(i) = err
        .find("expected one of `")
        .or_else(|| err.find("expected `"))
    {
        let line = err[i..].lines().next().unwrap_or("");
        return line
            .split('`')
            .skip(1)
            .step_by(2)
            .map(str::to_string)
            .collect();
    }
    // Hand-parsed tables: "unknown key (a, b; or c)", "unknown parameter (a, b)".
    for marker in ["unknown key (", "unknown parameter ("] {
        if let Some(i) = err.find(marker) {
            let rest = &err[i + marker.len()..];
            return words(&rest[..rest.find(')').unwrap_or(rest.len())]);
        }
    }
    // "unknown key; expected one of a, b, c".
    if let Some(i) = err.find("unknown key; expected one of ") {
        let rest = &err[i + "unknown key; expected one of ".len()..];
        return words(rest.lines().next().unwrap_or(""));
    }
    // Value forms: "must be a value, { linear = [...] } or { table = [...] }".
    let mut out = BTreeSet::new();
    let mut rest = err;
    while let Some(i) = rest.find("{ ") {
        rest = &rest[i + 2..];
        if let Some(w) = rest.split(" =").next() {
            if !w.is_empty() && w.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
                out.insert(w.to_string());
            }
        }
    }
    assert!(!out.is_empty(), "no key list in the error: {err}");
    out
}

/// Probes every table of a page's schema; each documented table must have a probe.
fn check_schema(doc: &Doc, args: &[&str], probes: &[(&str, &str, Probe)]) {
    let mut problems = Vec::new();
    let mut accepted: BTreeMap<&str, BTreeSet<String>> = BTreeMap::new();
    for (table, base, probe) in probes {
        accepted
            .entry(table)
            .or_default()
            .extend(accepted_keys(args, base, probe));
    }
    for table in doc.tables() {
        let Some(keys) = accepted.get(table.as_str()) else {
            problems.push(format!("table `{table}` has no probe in tests/docs.rs"));
            continue;
        };
        let mut keys = keys.clone();
        if table.starts_with('<') && doc.children(&table).contains("kind") {
            // Internally tagged (`kind` selects the variant; serde lists the variant's keys).
            keys.insert("kind".into());
        }
        let documented = doc.children(&table);
        for k in keys.difference(&documented) {
            problems.push(format!(
                "`{}` is accepted but not documented",
                join(&table, k)
            ));
        }
        for k in documented.difference(&keys) {
            problems.push(format!(
                "`{}` is documented but not accepted",
                join(&table, k)
            ));
        }
    }
    for (table, _, _) in probes {
        if !doc.tables().contains(*table) {
            problems.push(format!(
                "probe for `{table}`, which the page does not document"
            ));
        }
    }
    assert!(
        problems.is_empty(),
        "{} and the parser disagree:\n{}",
        doc.page,
        problems.join("\n")
    );
}

#[test]
fn halfspace_reference_documents_exactly_the_accepted_keys() {
    let doc = Doc::load("docs/user/case-halfspace.md");
    let roller = example("roller-shaft");
    let sec6 = example("roller-shaft-sec6");
    let crowned = example("crowned-roller");
    let map = example("height-map");
    let rough_roller = example("rough-roller");
    let prob = example("roller-shaft-probabilistic");
    let run = ["run", "-", "--dry-run", "--quiet"];
    check_schema(
        &doc,
        &run,
        &[
            ("", &roller, Probe::Insert("")),
            ("<body>", &roller, Probe::Insert("body1")),
            ("<surface>", &crowned, Probe::Insert("body1.surface")),
            ("<surface>", &map, Probe::Insert("body1.surface")),
            // A roller's roughness table is a `<surface>` (`<surface>.roughness`).
            (
                "<surface>",
                &rough_roller,
                Probe::Insert("body1.surface.roughness"),
            ),
            ("contact", &roller, Probe::Insert("contact")),
            ("grid", &roller, Probe::Insert("grid")),
            ("solver", &roller, Probe::Insert("solver")),
            ("bulk", &roller, Probe::Insert("bulk")),
            ("field", &roller, Probe::Insert("field")),
            ("damage", &roller, Probe::Insert("damage")),
            ("damage.cycle", &sec6, Probe::Insert("damage.cycle")),
            ("damage.study", &sec6, Probe::Insert("damage.study")),
            ("damage.energy", &roller, Probe::Insert("damage.energy")),
            (
                "damage.probabilistic",
                &prob,
                Probe::Insert("damage.probabilistic"),
            ),
            (
                "<distribution>",
                &prob,
                Probe::Insert("damage.probabilistic.limits.sigma_int"),
            ),
            (
                "<distribution>.truncate",
                &prob,
                Probe::Replace(
                    "damage.probabilistic.limits.sigma_int.truncate",
                    "{ low = 1e9, zz_probe = 1 }",
                ),
            ),
        ],
    );
}

/// The reference's block on a base with its top face rigid (guided), the step's motion of it
/// carrying the unknown key.
fn rigid_top(case: &mut Table) {
    case.insert("rigid".into(), value(r#"["block_top"]"#));
    if let Some(Value::Array(bcs)) = case.get_mut("bc") {
        bcs.retain(|b| b.get("segment").and_then(Value::as_str) != Some("block_top"));
    }
    if let Value::Table(step) = at(case, "steps.0") {
        step.remove("factors");
        step.insert(
            "rigid".into(),
            value("{ block_top = { ux = 0, fy = -1e6, zz_probe = 1 } }"),
        );
    }
}

#[test]
fn bem2d_reference_documents_exactly_the_accepted_keys() {
    let doc = Doc::bem();
    let base = first_toml_block("docs/user/case-bem2d.md");
    let knife = example("clamp-knife-base");
    let column = example("column");
    let run = ["run", "-", "--dry-run", "--quiet"];
    let mesh = "kind = \"bem2d\"\n[[mesh]]\nfile = \"part.msh\"\n";
    check_schema(
        &doc,
        &run,
        &[
            ("", &base, Probe::Insert("")),
            ("materials.*", &base, Probe::Insert("materials.steel")),
            ("regions", &base, Probe::Insert("regions.0")),
            (
                "regions[].holes",
                &base,
                Probe::Replace("regions.0.holes", "[{ zz_probe = 1 }]"),
            ),
            ("<segment>", &base, Probe::Insert("regions.0.outline.0")),
            (
                "<grading>",
                &base,
                Probe::Replace("regions.0.outline.2.grading", "{ zz_probe = 1 }"),
            ),
            (
                "<body-force>",
                &base,
                Probe::Replace("regions.0.body_force", "{ density = 7850, zz_probe = 1 }"),
            ),
            ("mesh", mesh, Probe::Insert("mesh.0")),
            ("bc", &base, Probe::Insert("bc.0")),
            (
                "<profile>",
                &base,
                Probe::Replace("bc.0.uy", "{ zz_probe = 1 }"),
            ),
            ("contact", &base, Probe::Insert("contact.0")),
            ("steps", &base, Probe::Insert("steps.0")),
            ("<rigid-motion>", &base, Probe::Edit(rigid_top)),
            ("solver", &base, Probe::Insert("solver")),
            ("field", &base, Probe::Insert("field")),
            ("damage", &base, Probe::Insert("damage")),
            ("damage.sweep", &base, Probe::Insert("damage.sweep")),
            ("compare", &base, Probe::Insert("compare")),
            (
                "clamp_knife_base",
                &knife,
                Probe::Insert("clamp_knife_base"),
            ),
            ("dynamics", &column, Probe::Insert("dynamics")),
            (
                "<time>",
                &column,
                Probe::Replace("bc.0.time", "{ zz_probe = 1 }"),
            ),
            ("probe", &column, Probe::Insert("probe.0")),
        ],
    );
}

#[test]
fn fatigue_diagram_table_documents_exactly_the_accepted_keys() {
    let doc = Doc::load("docs/user/fatigue.md");
    let base = example("fatigue-diagram");
    let out = tempfile::tempdir().expect("tempdir");
    let dir = out.path().to_str().expect("UTF-8 path");
    let args = ["fatigue", "diagram", "-", "-o", dir];
    check_schema(
        &doc,
        &args,
        &[
            ("", &base, Probe::Insert("")),
            ("limits", &base, Probe::Insert("limits")),
            (
                "<fitted-limit>",
                &base,
                Probe::Replace("limits.sigma_1", "{ zz_probe = 1 }"),
            ),
            ("state", &base, Probe::Insert("state")),
        ],
    );
}

#[test]
fn every_example_and_every_key_of_it_is_documented_and_the_references_examples_run() {
    let halfspace = Doc::load("docs/user/case-halfspace.md");
    let bem = Doc::bem();
    let fatigue = Doc::load("docs/user/fatigue.md");
    let names = example_names();
    assert!(names.len() >= 10, "only {} examples listed", names.len());
    let mut missing = Vec::new();
    let examples_page = read("docs/user/examples.md");
    for n in &names {
        if !examples_page.contains(&format!("| `{n}` |")) {
            missing.push(format!("example {n} is not in docs/user/examples.md"));
        }
    }
    let mut cases: Vec<(String, String)> = names
        .iter()
        .map(|n| (format!("example {n}"), example(n)))
        .collect();
    for page in ["docs/user/case-halfspace.md", "docs/user/case-bem2d.md"] {
        for (k, text) in toml_blocks(page).into_iter().enumerate() {
            // A whole case (not a section shown alone) must be valid as written.
            if text.contains("[body1]") || text.contains("kind = \"bem2d\"") {
                let out = tribo(&["run", "-", "--dry-run", "--quiet"], &text);
                assert!(
                    out.status.success(),
                    "example {k} of {page} must be a valid case: {}",
                    String::from_utf8_lossy(&out.stderr)
                );
            }
            cases.push((format!("{page}, example {k}"), text));
        }
    }
    for (name, text) in &cases {
        let case = parse(text);
        let doc = if name.ends_with("fatigue-diagram") {
            &fatigue
        } else if case.get("kind").and_then(Value::as_str) == Some("bem2d") {
            &bem
        } else {
            &halfspace
        };
        for key in doc.undocumented(&case) {
            missing.push(format!("{name}: {key} is not in {}", doc.page));
        }
    }
    assert!(
        missing.is_empty(),
        "undocumented keys:\n{}",
        missing.join("\n")
    );
}

// ------------------------------------------------------------------ the verification page

const BEGIN: &str = "<!-- BEGIN GENERATED: the rows of `tribo validate --json` -->";
const END: &str = "<!-- END GENERATED -->";

fn cell(text: &str) -> String {
    text.replace('\\', "\\\\")
        .replace('|', "\\|")
        .replace('*', "\\*")
        .replace('<', "&lt;")
}

/// A number in its shortest exact form, with an exponent when it is very small or large.
fn shortest(x: f64) -> String {
    if x == 0.0 || (1e-3..1e4).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// The generated part of docs/verification.md, from the JSON rows.
fn verification_table(rows: &[serde_json::Value]) -> String {
    let mut out = format!(
        "{BEGIN}\n\n{} rows. Generated from `tribo validate --json` by \
         `bench/verification_page.sh`; the test suite regenerates the table and compares every \
         column but the computed value and the error, which are this machine's.\n\n\
         | # | case | quantity | reference | computed | error | tolerance | measure | source | pass |\n\
         |---:|---|---|---:|---:|---:|---:|---|---|---|\n",
        rows.len()
    );
    for (i, r) in rows.iter().enumerate() {
        let s = |k: &str| r[k].as_str().map(cell).unwrap_or_default();
        let num = |k: &str| r[k].as_f64().map(shortest).unwrap_or_default();
        let approx = |k: &str, digits: usize| {
            r[k].as_f64()
                .map(|x| format!("{x:.digits$e}"))
                .unwrap_or_default()
        };
        out.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
            i + 1,
            s("case"),
            s("quantity"),
            num("reference"),
            approx("computed", 6),
            approx("error", 2),
            num("tolerance"),
            s("measure"),
            s("source"),
            if r["passed"].as_bool() == Some(true) {
                "yes"
            } else {
                "**no**"
            }
        ));
    }
    out.push('\n');
    out.push_str(END);
    out
}

/// A table line without its computed value and error (columns 5 and 6).
fn masked(line: &str) -> String {
    if !line.starts_with("| ") || line.starts_with("|---") {
        return line.to_string();
    }
    // Split on unescaped bars.
    let mut cells = Vec::new();
    let mut cur = String::new();
    let mut escaped = false;
    for c in line.chars() {
        if c == '|' && !escaped {
            cells.push(std::mem::take(&mut cur));
        } else {
            cur.push(c);
        }
        escaped = c == '\\' && !escaped;
    }
    cells.push(cur);
    if cells.len() > 7 && cells[1].trim().parse::<usize>().is_ok() {
        cells[5] = " ~ ".into();
        cells[6] = " ~ ".into();
    }
    cells.join("|")
}

#[test]
fn verification_page_has_every_row_of_tribo_validate() {
    let out = Command::new(env!("CARGO_BIN_EXE_tribo"))
        .args(["validate", "--json"])
        .output()
        .expect("run tribo validate");
    let rows: Vec<serde_json::Value> =
        serde_json::from_slice(&out.stdout).expect("tribo validate --json prints a JSON array");
    assert!(rows.len() > 50, "only {} rows", rows.len());
    let table = verification_table(&rows);
    let path = root().join("docs/verification.md");
    let page = std::fs::read_to_string(&path).expect("docs/verification.md");
    let (Some(b), Some(e)) = (page.find(BEGIN), page.find(END)) else {
        panic!("docs/verification.md lacks the generated block markers");
    };
    let current = &page[b..e + END.len()];
    if std::env::var_os("TRIBO_REGENERATE_DOCS").is_some() {
        let new = format!("{}{table}{}", &page[..b], &page[e + END.len()..]);
        std::fs::write(&path, new).expect("write docs/verification.md");
        return;
    }
    let want: Vec<String> = table.lines().map(masked).collect();
    let have: Vec<String> = current.lines().map(masked).collect();
    if want != have {
        let first = want
            .iter()
            .zip(&have)
            .position(|(a, b)| a != b)
            .unwrap_or(want.len().min(have.len()));
        panic!(
            "docs/verification.md is out of date ({} rows generated, {} lines on the page); \
             first difference at line {first} of the block:\n  page: {:?}\n  now:  {:?}\n\
             regenerate it with bench/verification_page.sh",
            rows.len(),
            have.len(),
            have.get(first),
            want.get(first)
        );
    }
}

// ------------------------------------------------------------------ the outputs reference

/// docs/user/outputs.md names every file the default case and the 2D reference case write,
/// every CSV header (as written), and every key of their `units` tables.
#[test]
fn outputs_reference_lists_every_file_column_and_unit() {
    let page = read("docs/user/outputs.md");
    let bem = first_toml_block("docs/user/case-bem2d.md");
    let mut missing = Vec::new();
    for (name, case) in [
        ("roller-shaft", example("roller-shaft")),
        ("bem2d", bem),
        ("column", example("column")),
        ("rod-impact", example("rod-impact")),
    ] {
        let dir = tempfile::tempdir().expect("tempdir");
        let out = dir.path().to_str().expect("UTF-8 path");
        let o = tribo(&["run", "-", "-q", "-o", out], &case);
        assert!(
            o.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let text = std::fs::read_to_string(dir.path().join("summary.json")).expect("summary");
        let summary: serde_json::Value = serde_json::from_str(&text).expect("summary JSON");
        let units = summary["units"].as_object().expect("units");
        assert!(units.len() > 20, "{name}: only {} units", units.len());
        for key in units.keys() {
            if !page.contains(&format!("| `{key}` |")) {
                missing.push(format!("{name}: units key `{key}`"));
            }
        }
        // File names, with the names a case chooses in their documented placeholders.
        let mut names: Vec<String> = summary["steps"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(|s| s["name"].as_str().map(str::to_string))
            .collect();
        names.push("sigma_int".into());
        for file in summary["outputs"].as_array().expect("outputs") {
            let file = file.as_str().expect("a file name");
            let forms: Vec<String> = std::iter::once(file.to_string())
                .chain(names.iter().flat_map(|n| {
                    ["<step>", "<name>", "<quantity>"].map(|p| file.replacen(n.as_str(), p, 1))
                }))
                .chain(snapshot_form(file))
                .collect();
            if !forms.iter().any(|f| page.contains(&format!("`{f}`"))) {
                missing.push(format!("{name}: file `{file}`"));
            }
            if file.ends_with(".csv") {
                let csv = std::fs::read_to_string(dir.path().join(file)).expect("CSV");
                let header = csv.lines().next().unwrap_or("");
                if !page.contains(&format!("`{header}`")) {
                    missing.push(format!("{name}: {file} header `{header}`"));
                }
            }
        }
    }
    assert!(
        missing.is_empty(),
        "not in docs/user/outputs.md:\n{}",
        missing.join("\n")
    );
}

/// `fields_0003.vtu` -> `fields_<NNNN>.vtu` (the dynamic snapshots' numbered files).
fn snapshot_form(file: &str) -> Option<String> {
    let digits = file.strip_prefix("fields_")?.strip_suffix(".vtu")?;
    (digits.len() >= 4 && digits.bytes().all(|b| b.is_ascii_digit()))
        .then(|| "fields_<NNNN>.vtu".to_string())
}

// ------------------------------------------------------------------ the CLI reference

/// docs/user/cli.md names every command and every flag the binary's `--help` lists.
#[test]
fn cli_reference_lists_every_command_and_flag() {
    let page = read("docs/user/cli.md");
    let help = |args: &[&str]| {
        let mut all = args.to_vec();
        all.push("--help");
        let o = tribo(&all, "");
        assert!(o.status.success(), "tribo {args:?} --help");
        String::from_utf8(o.stdout).expect("UTF-8 help")
    };
    let mut missing = Vec::new();
    let mut flags = 0;
    for command in [
        &["run"][..],
        &["example"],
        &["validate"],
        &["fatigue", "fit"],
        &["fatigue", "diagram"],
    ] {
        let name = format!("tribo {}", command.join(" "));
        if !page.contains(&format!("`{name}")) {
            missing.push(format!("command `{name}`"));
        }
        let text = help(command);
        let options = &text[text.find("Options:").expect("an Options section")..];
        for line in options.lines() {
            let Some(i) = line.find("--") else { continue };
            let flag: String = line[i..]
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '-')
                .collect();
            if flag == "--help" || !line.trim_start().starts_with('-') {
                continue;
            }
            flags += 1;
            if !page.contains(&format!("`{flag}")) && !page.contains(&format!(", {flag}")) {
                missing.push(format!("{name} {flag}"));
            }
        }
    }
    // Every command of `tribo --help`.
    let top = help(&[]);
    let commands = &top[top.find("Commands:").expect("a Commands section")..];
    for line in commands.lines().skip(1).take_while(|l| l.starts_with("  ")) {
        let word = line.split_whitespace().next().unwrap_or("");
        if word != "help" && !page.contains(&format!("`tribo {word}")) {
            missing.push(format!("command `tribo {word}`"));
        }
    }
    assert!(flags >= 10, "found only {flags} flags");
    assert!(
        missing.is_empty(),
        "not in docs/user/cli.md:\n{}",
        missing.join("\n")
    );
}
