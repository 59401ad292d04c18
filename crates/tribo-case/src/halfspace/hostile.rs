//! Hostile input: random TOML documents built from the schema's keys, with wrong types,
//! out-of-range and non-finite values, huge numbers, empty tables and removed keys, over
//! every embedded half-space example and the 2D BEM bases (the clamp-knife-base template, the
//! outline case of docs/user/case-bem2d.md, the dynamic cavity example with `[dynamics]`,
//! `[[probe]]`, `density` and a `time` function). Parsing never panics, and every error names a key.

use crate::error::CaseError;
use crate::examples::EXAMPLES;
use proptest::prelude::*;
use std::path::Path;
use toml::{Table, Value};

/// A schema: every table with its keys.
type Schema = &'static [(&'static str, &'static [&'static str])];

/// Every table of the half-space schema with its keys.
const SCHEMA: Schema = &[
    ("", &["title"]),
    ("body1", &["E", "nu", "radii", "angle_deg"]),
    ("body2", &["E", "nu", "radii", "angle_deg"]),
    (
        "body1.surface",
        &[
            "kind",
            "radius",
            "length",
            "crown",
            "crown_radius",
            "flat_length",
            "design_load",
            "crown_drop",
            "heights",
            "spacing",
            "scale",
            "hurst",
            "rolloff_wavelength",
            "long_wavelength",
            "short_wavelength",
            "rms_height",
            "rms_slope",
            "anisotropy",
            "seed",
            "method",
            "format",
            "detrend",
            "periodic",
        ],
    ),
    (
        "contact",
        &[
            "load",
            "approach",
            "friction",
            "tangential_load",
            "tangential_angle_deg",
            "sliding",
            "sliding_angle_deg",
            "traction_direction",
            "mean_pressure",
            "load_steps",
        ],
    ),
    ("grid", &["n", "extent", "half_width", "periodic", "period"]),
    ("solver", &["method", "tolerance", "max_iterations"]),
    (
        "bulk",
        &[
            "shaft",
            "shaft_radius",
            "kind",
            "stress_max",
            "points",
            "stress",
            "bending_force",
            "span",
            "support",
            "bending_side",
        ],
    ),
    (
        "field",
        &[
            "points",
            "method",
            "layers",
            "n",
            "extent",
            "half_width",
            "depth",
            "depth_m",
            "body",
            "edge_refinement",
        ],
    ),
    (
        "damage",
        &["criteria", "limit_over_p0", "limit_load", "limits"],
    ),
    ("damage.limits", &["sigma_int", "u", "tau_oct"]),
    (
        "damage.cycle",
        &[
            "kind",
            "amplitude",
            "amplitude_over_p0",
            "speed",
            "period",
            "steps",
            "cycles",
        ],
    ),
    ("damage.study", &["bending_over_p0", "limit_over_p0"]),
    (
        "damage.energy",
        &[
            "a_n",
            "a_tau",
            "a_t",
            "a_tau_n",
            "a_m_t",
            "temperature",
            "u0",
        ],
    ),
];

/// The 2D BEM schema's tables with their keys (the arrays of tables are replaced whole).
const BEM_SCHEMA: Schema = &[
    (
        "",
        &[
            "kind", "title", "plane", "rigid", "regions", "bc", "steps", "contact", "mesh", "probe",
        ],
    ),
    ("materials.steel", &["E", "nu", "source", "density"]),
    (
        "dynamics",
        &[
            "time_step",
            "steps",
            "duration",
            "method",
            "realisation",
            "fields_at",
            "fields_every",
            "initial_velocity",
        ],
    ),
    ("dynamics.initial_velocity", &["ring"]),
    (
        "clamp_knife_base",
        &[
            "knife_length",
            "knife_thickness",
            "bevel_length",
            "edge_thickness",
            "cutting_length",
            "base_left",
            "base_thickness",
            "clamp_left",
            "clamp_thickness",
            "bolt_center",
            "bolt_width",
            "bolt_pressure",
            "cutting_load",
            "friction",
            "contact_element_size",
            "element_size",
            "knife_material",
            "clamp_material",
            "base_material",
        ],
    ),
    ("solver", &["max_iterations", "tolerance"]),
    ("field", &["size", "regions"]),
    ("damage", &["region", "quantity", "limit", "step"]),
    ("damage.sweep", &["from", "to", "points"]),
    ("compare", &["region", "materials"]),
];

/// Values a key may be given: wrong types, out of range, non-finite, huge, empty.
fn hostile(k: usize) -> Value {
    let texts = [
        "\"x\"",
        "\"\"",
        "true",
        "false",
        "0",
        "-1",
        "1",
        "2",
        "3",
        "0.5",
        "-0.0",
        "1e308",
        "-1e308",
        "5e-324",
        "9223372036854775807",
        "-9223372036854775808",
        "nan",
        "inf",
        "-inf",
        "\"nan\"",
        "\"inf\"",
        "\"-inf\"",
        "\"NaN Pa\"",
        "\"inf mm\"",
        "\"1e400 m\"",
        "\"1e308 GPa\"",
        "\"201 GPa\"",
        "\"9 mm\"",
        "\"2 kN\"",
        "\"3 N/mm\"",
        "\"10 parsecs\"",
        "[]",
        "[1]",
        "[1, 2]",
        "[1, 2, 3]",
        "[\"inf\", 0.01]",
        "[0.005, -0.005]",
        "[[1, 2], [3]]",
        "[[1, 2], [3, 4]]",
        "[\"sigma_int\", \"sigma_int\"]",
        "[\"bogus\"]",
        "{}",
        "{ a = 1 }",
        "1979-05-27T07:32:00Z",
        "\"cg\"",
        "\"active_set\"",
        "\"roller\"",
        "\"height_map\"",
        "\"rough\"",
        "\"measured\"",
        "\"plane\"",
        "\"none\"",
        "\"x3p\"",
        "\"random_phase\"",
        "\"25 um\"",
        "[\"100 um\", \"100 um\"]",
        "\"logarithmic\"",
        "\"circular\"",
        "\"body1\"",
        "\"centres\"",
        "\"direct\"",
        "\"bending\"",
        "\"cantilever\"",
        "\"compression\"",
        "\"rotating-bending\"",
        "\"rolling\"",
        "\"free\"",
        "\"1 us\"",
        "\"-1 us\"",
        "\"7850 kg/m^3\"",
        "\"bdf2\"",
        "\"marching\"",
        "[\"1 us\", \"2 us\"]",
        "[\"5 m/s\", 0]",
    ];
    let text = texts[k % texts.len()];
    toml::from_str::<Table>(&format!("v = {text}")).expect("a TOML value")["v"].clone()
}

/// The table at a dotted path, created where missing (or replacing a non-table).
fn table_at<'a>(root: &'a mut Table, path: &str) -> &'a mut Table {
    let mut t = root;
    for part in path.split('.').filter(|p| !p.is_empty()) {
        let entry = t
            .entry(part.to_string())
            .or_insert_with(|| Value::Table(Table::new()));
        if !entry.is_table() {
            *entry = Value::Table(Table::new());
        }
        t = entry.as_table_mut().expect("a table");
    }
    t
}

/// Which mutation, of which table, key and value.
type Mutation = (usize, usize, usize, usize);

/// Mutation `op` of the document: set a key to a hostile value, remove it, or empty or
/// replace its table.
fn mutate(doc: &mut Table, schema: Schema, (op, table, key, value): Mutation) {
    let (path, keys) = schema[table % schema.len()];
    let key = keys[key % keys.len()];
    match op % 6 {
        0..=2 => {
            table_at(doc, path).insert(key.to_string(), hostile(value));
        }
        3 => {
            table_at(doc, path).remove(key);
        }
        4 => *table_at(doc, path) = Table::new(),
        _ => {
            if let Some((parent, last)) = path.rsplit_once('.') {
                table_at(doc, parent).insert(last.to_string(), hostile(value));
            } else if !path.is_empty() {
                doc.insert(path.to_string(), hostile(value));
            }
        }
    }
}

/// The top-level tables and keys an error may start with.
const ROOTS: &[&str] = &[
    "title",
    "body1",
    "body2",
    "contact",
    "grid",
    "solver",
    "bulk",
    "field",
    "damage",
    // 2D BEM
    "kind",
    "plane",
    "materials",
    "clamp_knife_base",
    "regions",
    "mesh",
    "bc",
    "rigid",
    "steps",
    "compare",
    "dynamics",
    "probe",
];

fn names_a_key(e: &CaseError) -> bool {
    let text = e.to_string();
    let starts_with_key = |s: &str| {
        ROOTS.iter().any(|r| {
            s.strip_prefix(r)
                .is_some_and(|rest| rest.is_empty() || rest.starts_with(['.', '[', ' ', ',', ':']))
        })
    };
    match e {
        CaseError::Field { field, .. } => starts_with_key(field),
        // serde's own: an unknown, missing or mistyped key, with the path.
        CaseError::Parse { message, .. } => message.contains("in `") || message.contains("field `"),
        CaseError::Unreadable { field, .. } | CaseError::DataFile { field, .. } => {
            starts_with_key(field)
        }
        CaseError::Library(_) => starts_with_key(&text),
    }
}

/// The half-space examples that need no data file (the measured-x3p example reads its
/// .x3p, which `tribo example -o` writes; its keys are mutated through the rough-flat base).
fn half_space_examples() -> Vec<Table> {
    EXAMPLES
        .iter()
        .filter(|e| {
            crate::examples::data_files(e.name)
                .map(|f| f.is_empty())
                .unwrap_or(false)
        })
        .filter_map(|e| toml::from_str::<Table>(e.text).ok())
        .filter(|t| t.contains_key("body1"))
        .collect()
}

fn bem_bases() -> Vec<Table> {
    let doc = include_str!("../../../../docs/user/case-bem2d.md");
    let outline = doc
        .split("```toml\n")
        .nth(1)
        .and_then(|b| b.split("```").next())
        .expect("a TOML block in case-bem2d.md");
    let knife = EXAMPLES
        .iter()
        .find(|e| e.name == "clamp-knife-base")
        .expect("the clamp-knife-base example");
    let cavity = EXAMPLES
        .iter()
        .find(|e| e.name == "cavity")
        .expect("the cavity example");
    [outline, knife.text, cavity.text]
        .iter()
        .map(|t| toml::from_str::<Table>(t).expect("a BEM base"))
        .collect()
}

/// Parses the mutated document: no panic, and an error names a key.
fn check(
    bases: &[Table],
    schema: Schema,
    base: usize,
    ops: Vec<Mutation>,
) -> Result<(), TestCaseError> {
    let mut doc = bases[base % bases.len()].clone();
    for m in ops {
        mutate(&mut doc, schema, m);
    }
    let text = toml::to_string(&doc).expect("serialize");
    if let Err(e) = crate::Case::from_toml(&text, "hostile.toml", Path::new("/nonexistent")) {
        prop_assert!(names_a_key(&e), "{e}\n--- case:\n{text}");
    }
    Ok(())
}

fn mutations() -> impl Strategy<Value = Vec<Mutation>> {
    proptest::collection::vec((0usize..64, 0usize..64, 0usize..64, 0usize..256), 1..5)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]
    #[test]
    fn hostile_documents_never_panic_and_errors_name_a_key(base in 0usize..64, ops in mutations()) {
        check(&half_space_examples(), SCHEMA, base, ops)?;
    }

    #[test]
    fn hostile_bem_documents_never_panic_and_errors_name_a_key(base in 0usize..64, ops in mutations()) {
        check(&bem_bases(), BEM_SCHEMA, base, ops)?;
    }
}

#[test]
fn the_bases_are_valid_cases() {
    let bases = half_space_examples();
    assert!(bases.len() >= 4, "{}", bases.len());
    for b in bases.iter().chain(&bem_bases()) {
        let text = toml::to_string(b).unwrap();
        assert!(
            crate::Case::from_toml(&text, "t", Path::new(".")).is_ok(),
            "{text}"
        );
    }
}
