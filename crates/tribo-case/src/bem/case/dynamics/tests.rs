//! One test per rule of the dynamic keys (each names the item in its error), the CSV time
//! tables, the locators, and hostile documents that never panic.

use super::*;
use crate::schema::from_text;
use crate::units::Density;
use proptest::prelude::*;
use tribo::operators::bem2d::Segment;

/// The keys of a case the dynamic rules read, as a test document.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Doc {
    dynamics: Option<RawDynamics>,
    probe: Option<Vec<RawProbe>>,
    bc: Option<Vec<BcDoc>>,
    materials: Option<BTreeMap<String, MaterialDoc>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BcDoc {
    time: Option<RawTime>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MaterialDoc {
    density: Option<Quantity<Density>>,
}

/// A unit square "block" of steel with a square hole [0.4, 0.6]^2, and a triangle "tip"
/// bonded to its right side (x = 1, y in [0, 1]) reaching x = 2.
fn regions() -> Vec<RegionSpec> {
    let seg =
        |name: &str, a: [f64; 2], b: [f64; 2]| LoopItem::Segment(Segment::line(name, a, b, 2));
    let block = RegionSpec {
        name: "block".into(),
        material: "steel".into(),
        loops: vec![
            vec![
                seg("bottom", [0.0, 0.0], [1.0, 0.0]),
                seg("right", [1.0, 0.0], [1.0, 1.0]),
                seg("top", [1.0, 1.0], [0.0, 1.0]),
                seg("left", [0.0, 1.0], [0.0, 0.0]),
            ],
            vec![
                seg("h1", [0.4, 0.4], [0.4, 0.6]),
                seg("h2", [0.4, 0.6], [0.6, 0.6]),
                seg("h3", [0.6, 0.6], [0.6, 0.4]),
                seg("h4", [0.6, 0.4], [0.4, 0.4]),
            ],
        ],
        body_forces: vec![],
    };
    let tip = RegionSpec {
        name: "tip".into(),
        material: "brass".into(),
        loops: vec![vec![
            seg("t1", [1.0, 0.0], [2.0, 0.5]),
            seg("t2", [2.0, 0.5], [1.0, 1.0]),
            LoopItem::Shared("right".into()),
        ]],
        body_forces: vec![],
    };
    vec![block, tip]
}

const BASE: &str = r#"
[dynamics]
time_step = "1 us"
duration = "2 ms"

[materials.steel]
density = "7850 kg/m^3"

[materials.brass]
density = "8.5 g/cm^3"

[[bc]]
time = "step"

[[bc]]

[[probe]]
name = "p"
at = ["0.2 m", 0.5]
"#;

/// Parses `text` and validates it against [`regions`] (with contact where `contact`).
fn run_with(text: &str, contact: bool, load_steps: usize) -> CaseResult<Option<DynamicsSpec>> {
    let doc: Doc = from_text(text, "t.toml")?;
    let regions = regions();
    let locate = outline_locator(&regions);
    // Steel c2 = sqrt(mu/rho) = 3.2e3 m/s (mu = 80.77 GPa, rho = 7850).
    let materials: BTreeMap<String, ElasticMaterial> =
        [("steel", 210e9, 0.3), ("brass", 100e9, 0.34)]
            .into_iter()
            .map(|(n, e, nu)| (n.to_string(), ElasticMaterial::new(e, nu).unwrap()))
            .collect();
    let ctx = DynamicsContext {
        densities: doc
            .materials
            .unwrap_or_default()
            .into_iter()
            .map(|(k, m)| (k, m.density))
            .collect(),
        regions: regions
            .iter()
            .map(|r| (r.name.clone(), r.material.clone()))
            .collect(),
        bc_times: doc
            .bc
            .unwrap_or_default()
            .into_iter()
            .enumerate()
            .map(|(k, b)| (format!("bc[{k}]"), b.time))
            .collect(),
        rigid_times: Vec::new(),
        rigid: Vec::new(),
        has_contact: contact,
        load_steps,
        base_dir: Path::new(env!("CARGO_MANIFEST_DIR")),
        locate: &locate,
        materials: &materials,
    };
    validate(doc.dynamics, doc.probe, &ctx)
}

fn run(text: &str) -> CaseResult<Option<DynamicsSpec>> {
    run_with(text, false, 1)
}

/// The error of `text`, as text.
fn err(text: &str) -> String {
    run(text).unwrap_err().to_string()
}

/// BASE with `key = value` set in `[dynamics]` (replacing a line of that key).
fn with_dyn(lines: &str) -> String {
    BASE.replace("[dynamics]\n", &format!("[dynamics]\n{lines}\n"))
}

#[test]
fn a_complete_case_gives_the_spec() {
    let text = with_dyn(
        "method = \"radau_iia_2\"\nfields_at = [\"0 ms\", \"0.5 ms\", \"2 ms\"]\n\
         initial_velocity = { tip = [\"-5 m/s\", 0] }",
    )
    .replace(
        "time = \"step\"",
        "time = { ramp = \"0.1 ms\", start = \"10 us\" }",
    );
    let s = run(&text).unwrap().unwrap();
    assert_eq!((s.time_step, s.steps, s.duration), (1e-6, 2000, 2e-3));
    assert_eq!(s.method, Method::RadauIia2);
    assert_eq!(s.realisation, Realisation::AllAtOnce);
    assert_eq!(s.field_steps, vec![0, 500, 2000]);
    assert_eq!(s.densities["steel"], 7850.0);
    assert_eq!(s.densities["brass"], 8500.0);
    assert_eq!(s.bc_time.len(), 2);
    // The ramp: 0 before 10 us, 1/2 at 10 + 50 us, 1 after 110 us; no time: constant 1.
    assert_eq!(s.bc_time[0].value(5e-6), 0.0);
    assert!((s.bc_time[0].value(60e-6) - 0.5).abs() < 1e-12);
    assert_eq!(s.bc_time[0].value(1e-3), 1.0);
    assert_eq!(s.bc_time[1].value(0.0), 1.0);
    assert_eq!(s.probes[0].region, "block");
    assert_eq!(s.initial_velocity["tip"], [-5.0, 0.0]);
    // Contact makes "auto" marching; steps and duration give the step.
    let s = run_with(
        &BASE.replace("time_step = \"1 us\"", "steps = 400"),
        true,
        1,
    )
    .unwrap()
    .unwrap();
    assert_eq!((s.time_step, s.realisation), (5e-6, Realisation::Marching));
    // fields_every: every N steps from t = 0.
    let s = run(&with_dyn("fields_every = 700")).unwrap().unwrap();
    assert_eq!(s.field_steps, vec![0, 700, 1400]);
}

#[test]
fn a_static_case_has_no_spec_and_no_dynamic_keys() {
    let stat = "[[bc]]\n";
    assert!(run(stat).unwrap().is_none());
    let e = err("[[bc]]\n[[bc]]\ntime = \"step\"\n");
    assert!(
        e.starts_with("bc[1].time = (given): a time function needs a [dynamics]"),
        "{e}"
    );
    let e = err("[[probe]]\nname = \"a\"\nat = [0.5, 0.5]\n");
    assert!(e.starts_with("probe = (given)"), "{e}");
}

#[test]
fn rule_time_step_must_be_positive() {
    for bad in ["0", "\"-1 us\"", "-0.0"] {
        let e = err(&BASE.replace("\"1 us\"", bad));
        assert!(
            e.starts_with("dynamics.time_step") && e.contains("> 0"),
            "{e}"
        );
    }
    let e = err(&BASE.replace("\"2 ms\"", "\"0 ms\""));
    assert!(
        e.starts_with("dynamics.duration") && e.contains("> 0"),
        "{e}"
    );
    let e = err(&BASE.replace("time_step = \"1 us\"", "steps = 0"));
    assert!(e.starts_with("dynamics.steps = 0"), "{e}");
    let e = err(&BASE
        .replace("\"1 us\"", "\"1 ns\"")
        .replace("\"2 ms\"", "\"2 s\""));
    assert!(
        e.starts_with("dynamics.duration") && e.contains("1000000"),
        "{e}"
    );
}

#[test]
fn rule_duration_must_be_a_whole_number_of_steps() {
    let e = err(&BASE.replace("\"1 us\"", "\"3 us\""));
    assert!(
        e.starts_with("dynamics.duration = \"2 ms\" with time_step = \"3 us\""),
        "{e}"
    );
    assert!(e.contains("whole number of time steps"), "{e}");
    // Decimal unit strings that are a whole number up to rounding pass.
    assert_eq!(
        run(&BASE
            .replace("\"1 us\"", "\"0.1 us\"")
            .replace("\"2 ms\"", "\"0.3 ms\""))
        .unwrap()
        .unwrap()
        .steps,
        3000
    );
    let e = err(&with_dyn("steps = 7"));
    assert!(e.starts_with("dynamics.steps = 7: disagrees"), "{e}");
    assert!(run(&with_dyn("steps = 2000")).is_ok());
    let e = err(&BASE.replace("duration = \"2 ms\"", ""));
    assert!(e.starts_with("dynamics = (incomplete)"), "{e}");
}

#[test]
fn rule_density_required_for_every_region() {
    let e = err(&BASE.replace("density = \"8.5 g/cm^3\"", ""));
    assert!(e.starts_with("materials.brass.density = (missing)"), "{e}");
    assert!(e.contains("\"tip\" (regions[1])"), "{e}");
    let e = err(&BASE.replace("\"7850 kg/m^3\"", "\"7850 g/cm^3\""));
    assert!(
        e.starts_with("materials.steel.density") && e.contains("unit mistake"),
        "{e}"
    );
    let e = err(&BASE.replace("\"7850 kg/m^3\"", "\"7850 kg/m3\""));
    assert!(
        e.starts_with("materials.steel.density") && e.contains("a density"),
        "{e}"
    );
}

#[test]
fn rule_time_table_must_increase() {
    let t = BASE.replace(
        "time = \"step\"",
        "time = { points = [[0, 0], [\"0.1 ms\", 1], [\"0.1 ms\", 0.5]] }",
    );
    let e = err(&t);
    assert!(e.starts_with("bc[0].time.points[2][0] = \"0.1 ms\""), "{e}");
    assert!(e.contains("increase"), "{e}");
    let e = err(&BASE.replace("time = \"step\"", "time = { points = [[0, 0]] }"));
    assert!(
        e.starts_with("bc[0].time.points") && e.contains("at least 2"),
        "{e}"
    );
    let e = err(&BASE.replace("time = \"step\"", "time = { points = [[0, \"1 ms\"]] }"));
    assert!(e.starts_with("bc[0].time.points[0][1]"), "{e}");
    let s = run(&BASE.replace(
        "time = \"step\"",
        "time = { points = [[0, 0], [\"1 ms\", 2]] }",
    ))
    .unwrap()
    .unwrap();
    assert!((s.bc_time[0].value(0.5e-3) - 1.0).abs() < 1e-15);
}

#[test]
fn rule_time_functions_name_their_parameter() {
    let e = err(&BASE.replace("time = \"step\"", "time = { ramp = \"0 ms\" }"));
    assert!(
        e.starts_with("bc[0].time.ramp = \"0 ms\"") && e.contains("> 0"),
        "{e}"
    );
    let e = err(&BASE.replace("time = \"step\"", "time = { sine = \"-5 kHz\" }"));
    assert!(e.starts_with("bc[0].time.sine") && e.contains("> 0"), "{e}");
    let e = err(&BASE.replace("time = \"step\"", "time = { sine = \"5 ms\" }"));
    assert!(
        e.starts_with("bc[0].time.sine") && e.contains("a frequency"),
        "{e}"
    );
    let e = err(&BASE.replace("time = \"step\"", "time = \"ramp\""));
    assert!(
        e.starts_with("bc[0].time = \"ramp\"") && e.contains("must be \"step\""),
        "{e}"
    );
    let e = err(&BASE.replace(
        "time = \"step\"",
        "time = { ramp = \"1 ms\", phase_deg = 3 }",
    ));
    assert!(
        e.starts_with("bc[0].time.phase_deg") && e.contains("unknown key"),
        "{e}"
    );
    let e = err(&BASE.replace("time = \"step\"", "time = { ramp = \"1 ms\", step = 0 }"));
    assert!(e.starts_with("bc[0].time") && e.contains("found 2"), "{e}");
    let s = run(&BASE.replace(
        "time = \"step\"",
        "time = { sine = \"250 Hz\", phase_deg = 90, start = \"1 ms\" }",
    ))
    .unwrap()
    .unwrap();
    assert!((s.bc_time[0].value(1e-3) - 1.0).abs() < 1e-15);
    let s = run(&BASE.replace("time = \"step\"", "time = { step = \"0.5 ms\" }"))
        .unwrap()
        .unwrap();
    assert_eq!(
        (s.bc_time[0].value(0.4e-3), s.bc_time[0].value(0.5e-3)),
        (0.0, 1.0)
    );
}

#[test]
fn rule_probe_inside_a_body() {
    // In the hole, beyond the tip, and far away.
    for at in ["[0.5, 0.5]", "[1.9, 0.1]", "[\"3 m\", 0]", "[-0.001, 0.5]"] {
        let e = err(&BASE.replace("[\"0.2 m\", 0.5]", at));
        assert!(
            e.starts_with("probe[0].at") && e.contains("outside every region"),
            "{e}"
        );
    }
    // In the tip (bonded through a shared segment), on the outer boundary, on the interface.
    for (at, region) in [
        ("[1.5, 0.5]", "tip"),
        ("[0, 0.3]", "block"),
        ("[1, 0.5]", "block"),
    ] {
        let s = run(&BASE.replace("[\"0.2 m\", 0.5]", at)).unwrap().unwrap();
        assert_eq!(s.probes[0].region, region, "{at}");
    }
    let two = format!("{BASE}\n[[probe]]\nname = \"p\"\nat = [0.1, 0.1]\n");
    assert!(err(&two).starts_with("probe[1].name = \"p\""));
    let e = err(&BASE.replace("[\"0.2 m\", 0.5]", "[\"0.2 s\", 0.5]"));
    assert!(e.starts_with("probe[0].at[0]"), "{e}");
}

#[test]
fn rule_output_times_within_the_run() {
    let e = err(&with_dyn("fields_at = [\"1 ms\", \"3 ms\"]"));
    assert!(
        e.starts_with("dynamics.fields_at[1] = \"3 ms\"") && e.contains("[0, duration"),
        "{e}"
    );
    let e = err(&with_dyn("fields_at = [\"-1 us\"]"));
    assert!(e.starts_with("dynamics.fields_at[0]"), "{e}");
    let e = err(&with_dyn("fields_at = [\"1 ms\", \"1.0001 ms\"]"));
    assert!(
        e.starts_with("dynamics.fields_at[1]") && e.contains("different time steps"),
        "{e}"
    );
    let e = err(&with_dyn("fields_at = [\"1 ms\", \"0.5 ms\"]"));
    assert!(e.starts_with("dynamics.fields_at[1]"), "{e}");
    let e = err(&with_dyn("fields_every = 0"));
    assert!(e.starts_with("dynamics.fields_every = 0"), "{e}");
    let e = err(&with_dyn("fields_every = 3\nfields_at = [0]"));
    assert!(
        e.starts_with("dynamics.fields_every") && e.contains("not both"),
        "{e}"
    );
}

#[test]
fn rule_all_at_once_is_linear_only_and_one_load_step() {
    let text = with_dyn("realisation = \"all_at_once\"");
    assert!(run(&text).is_ok());
    let e = run_with(&text, true, 1).unwrap_err().to_string();
    assert!(
        e.starts_with("dynamics.realisation = \"all_at_once\""),
        "{e}"
    );
    let e = run_with(BASE, false, 2).unwrap_err().to_string();
    assert!(e.starts_with("steps = 2 steps"), "{e}");
    let e = err(&with_dyn("method = \"rk4\""));
    assert!(
        e.starts_with("dynamics.method = \"rk4\": must be \"bdf2\""),
        "{e}"
    );
    let e = err(&with_dyn("initial_velocity = { knife = [1, 0] }"));
    assert!(
        e.starts_with("dynamics.initial_velocity.knife") && e.contains("block, tip"),
        "{e}"
    );
    let e = err(&with_dyn("initial_velocity = { tip = [\"1 m\", 0] }"));
    assert!(e.starts_with("dynamics.initial_velocity.tip[0]"), "{e}");
    let e = err(&with_dyn("dt = 3"));
    assert!(
        e.contains("unknown field `dt`") && e.contains("dynamics.dt"),
        "{e}"
    );
}

/// A temporary CSV file with `text`.
fn csv(text: &str) -> tempfile::NamedTempFile {
    use std::io::Write;
    let mut f = tempfile::NamedTempFile::new().unwrap();
    f.write_all(text.as_bytes()).unwrap();
    f
}

#[test]
fn csv_time_tables() {
    let f = csv("# a pulse\ntime_s, factor\n0, 0\n1e-4, 1\n\n2e-4, 0\n");
    let t = read_time_csv("bc[0].time.csv", f.path()).unwrap();
    // Linear interpolation: 1/2 at the middles (to rounding of (t - t0)/(t1 - t0)).
    assert!((t.value(0.5e-4) - 0.5).abs() < 1e-15);
    assert!((t.value(1.5e-4) - 0.5).abs() < 1e-15);
    assert_eq!(t.value(1.0), 0.0);
    // Without a header.
    assert!(read_time_csv("f", csv("0,0\n1,1\n").path()).is_ok());
    for (text, line, what) in [
        ("t,f\n0,0\n1e-4,1\n1e-4,2\n", 4, "increase"),
        ("t,f\n0,0\n2e-4,1\n1e-4,2\n", 4, "increase"),
        ("t,f\n0,0\n1,2,3\n", 3, "2 columns"),
        ("t,f\n0,0\n1,x\n", 3, "two numbers"),
        ("0,0\nt,f\n", 2, "two numbers"),
        // A malformed first data row is not taken for a header (it has a number in it).
        ("1e-4,x\n2e-4,1\n3e-4,0\n", 1, "two numbers"),
        ("1e-4\n2e-4,1\n3e-4,0\n", 1, "2 columns"),
        ("t,f\n0,0\n1,inf\n", 3, "finite"),
        ("t,f\n0,0\n", 2, "at least 2 rows"),
        ("", 0, "at least 2 rows"),
    ] {
        let f = csv(text);
        match read_time_csv("bc[0].time.csv", f.path()).unwrap_err() {
            CaseError::DataFile {
                field,
                line: l,
                rule,
                ..
            } => {
                assert_eq!(
                    (field.as_str(), l),
                    ("bc[0].time.csv", line),
                    "{text:?}: {rule}"
                );
                assert!(rule.contains(what), "{text:?}: {rule}");
            }
            other => panic!("{text:?}: {other}"),
        }
    }
    let e = read_time_csv("bc[0].time.csv", Path::new("/nonexistent/pulse.csv")).unwrap_err();
    assert!(matches!(e, CaseError::Unreadable { .. }) && e.is_bad_input());
    // Through the case: the file relative to the case's folder.
    let f = csv("0,0\n1e-3,1\n");
    let text = BASE.replace(
        "time = \"step\"",
        &format!("time = {{ csv = {:?} }}", f.path().display().to_string()),
    );
    let s = run(&text).unwrap().unwrap();
    assert!((s.bc_time[0].value(0.5e-3) - 0.5).abs() < 1e-15);
    let e = err(&BASE.replace("time = \"step\"", "time = { csv = \"missing.csv\" }"));
    assert!(e.starts_with("bc[0].time.csv: cannot read"), "{e}");
}

#[test]
fn locators_of_outlines_and_models_agree() {
    let regions = regions();
    let a = outline_locator(&regions);
    // An annulus of arcs: inner radius 1 (a hole), outer 2.
    let arc = |name: &str, r: f64, a0: f64, a1: f64| Segment::arc(name, [0.0, 0.0], r, a0, a1, 8);
    let ring = tribo::operators::bem2d::Region::new(
        "ring",
        tribo::ElasticMaterial::new(2e11, 0.3).unwrap(),
        vec![arc("outer", 2.0, 0.0, 2.0 * std::f64::consts::PI)],
    )
    .with_hole(vec![arc("inner", 1.0, 2.0 * std::f64::consts::PI, 0.0)]);
    let model = BemModel::new(tribo::kernels::kelvin2d::PlaneCondition::Strain, vec![ring]);
    let b = model_locator(&model);
    assert_eq!(a([0.1, 0.9]).as_deref(), Some("block"));
    assert_eq!(a([0.5, 0.45]), None);
    assert_eq!(a([f64::NAN, 0.5]), None);
    assert_eq!(b([1.5, 0.0]).as_deref(), Some("ring"));
    assert_eq!(b([0.0, -1.999]).as_deref(), Some("ring"));
    assert_eq!(b([0.0, 0.5]), None);
    assert_eq!(b([0.0, 2.01]), None);
    // 1e-5 inside the outer arc between two vertices of a 256-chord polygon (whose chords
    // cut 1.5e-4 deep into the ring there): inside with 4096 chords (3e-7 deep).
    let a = 2.0 * std::f64::consts::PI / 256.0 * 10.5;
    let r = 2.0 - 1e-5;
    assert_eq!(b([r * a.cos(), r * a.sin()]).as_deref(), Some("ring"));
}

// ---------------------------------------------------------------- hostile input

/// The dynamic keys with their tables.
const KEYS: &[(&str, &[&str])] = &[
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
    ("materials.steel", &["density"]),
    ("materials.brass", &["density"]),
];

/// Hostile values: wrong types, non-finite, huge, empty, near misses.
fn hostile(k: usize) -> Value {
    let texts = [
        "\"x\"",
        "\"\"",
        "true",
        "0",
        "-1",
        "1",
        "3",
        "0.5",
        "-0.0",
        "1e308",
        "-1e308",
        "5e-324",
        "9223372036854775807",
        "nan",
        "inf",
        "\"nan\"",
        "\"inf s\"",
        "\"1e400 s\"",
        "\"1e-400 s\"",
        "\"1e-300 s\"",
        "\"1 us\"",
        "\"3 us\"",
        "\"2 ms\"",
        "\"1e300 s\"",
        "\"5 kHz\"",
        "\"-5 kHz\"",
        "\"7850 kg/m^3\"",
        "\"0 kg/m^3\"",
        "\"5 m/s\"",
        "\"step\"",
        "\"ramp\"",
        "\"marching\"",
        "\"all_at_once\"",
        "\"radau_iia_3\"",
        "[]",
        "[1]",
        "[1, 2]",
        "[\"1 ms\", \"1 ms\"]",
        "[\"0 s\", \"2 ms\", \"3 ms\"]",
        "[[0, 0], [1, 1]]",
        "[[1, 0], [0, 1]]",
        "[[0, 0], [\"nan\", 1]]",
        "{}",
        "{ a = 1 }",
        "{ block = [1, 2] }",
        "{ tip = [\"1 m/s\", \"inf\"] }",
        "{ step = \"1 ms\" }",
        "{ ramp = \"0 s\" }",
        "{ ramp = \"1e-300 s\", start = \"-1e300 s\" }",
        "{ sine = \"1e300 Hz\", phase_deg = 1e308 }",
        "{ points = [[0, 0]] }",
        "{ points = [[\"1e-320 s\", 1], [\"2e-320 s\", 0]] }",
        "{ points = [[0, 1e308], [1, -1e308]] }",
        "{ csv = \"/nonexistent.csv\" }",
        "{ csv = \"\" }",
        "1979-05-27T07:32:00Z",
    ];
    let text = texts[k % texts.len()];
    toml::from_str::<toml::Table>(&format!("v = {text}")).expect("a TOML value")["v"].clone()
}

fn table_at<'a>(root: &'a mut toml::Table, path: &str) -> &'a mut toml::Table {
    let mut t = root;
    for part in path.split('.').filter(|p| !p.is_empty()) {
        let entry = t
            .entry(part.to_string())
            .or_insert_with(|| Value::Table(toml::Table::new()));
        if !entry.is_table() {
            *entry = Value::Table(toml::Table::new());
        }
        t = entry.as_table_mut().expect("a table");
    }
    t
}

/// One mutation: a dynamic key, a bc's time, a probe's key set to a hostile value, or a
/// key removed.
fn mutate(doc: &mut toml::Table, (op, table, key, value): (usize, usize, usize, usize)) {
    match op % 4 {
        0 => {
            let (path, keys) = KEYS[table % KEYS.len()];
            table_at(doc, path).insert(keys[key % keys.len()].into(), hostile(value));
        }
        1 => {
            let (path, keys) = KEYS[table % KEYS.len()];
            table_at(doc, path).remove(keys[key % keys.len()]);
        }
        2 => {
            if let Some(Value::Array(bcs)) = doc.get_mut("bc") {
                if let Some(Value::Table(b)) = bcs.get_mut(table % 2) {
                    b.insert("time".into(), hostile(value));
                }
            }
        }
        _ => {
            if let Some(Value::Array(p)) = doc.get_mut("probe") {
                if let Some(Value::Table(p)) = p.get_mut(0) {
                    let k = ["name", "at"][key % 2];
                    p.insert(k.into(), hostile(value));
                }
            }
        }
    }
}

fn names_a_key(e: &CaseError) -> bool {
    let roots = ["dynamics", "materials", "bc", "probe", "steps"];
    let starts = |s: &str| {
        roots.iter().any(|r| {
            s.strip_prefix(r)
                .is_some_and(|rest| rest.is_empty() || rest.starts_with(['.', '[', ' ']))
        })
    };
    match e {
        CaseError::Field { field, .. } => starts(field),
        CaseError::Parse { message, .. } => message.contains("in `") || message.contains("field `"),
        CaseError::Unreadable { field, .. } | CaseError::DataFile { field, .. } => starts(field),
        CaseError::Library(_) => false,
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]
    /// Hostile values of every dynamic key never panic, and every error names a key.
    #[test]
    fn hostile_dynamic_keys_never_panic_and_errors_name_a_key(
        ops in proptest::collection::vec((0usize..64, 0usize..64, 0usize..64, 0usize..256), 1..5)
    ) {
        let mut doc: toml::Table = toml::from_str(BASE).unwrap();
        for m in ops {
            mutate(&mut doc, m);
        }
        let text = toml::to_string(&doc).unwrap();
        if let Err(e) = run(&text) {
            prop_assert!(names_a_key(&e), "{e}\n--- case:\n{text}");
        }
    }
}

/// `dynamics.initial_velocity`: finite components below the shear wave speed c2 =
/// sqrt(mu/rho) of the region's material (brass here: mu = 100e9 / 2.68 = 37.3 GPa, rho =
/// 8500 kg/m^3, c2 = 2095 m/s); a note above 1 % of c2 (20.95 m/s), none below.
#[test]
fn initial_velocity_is_finite_and_below_the_shear_wave_speed() {
    for v in [
        "[1e300, 0]",
        "[0, -1e300]",
        "[\"2100 m/s\", 0]",
        "[\"1500 m/s\", \"1500 m/s\"]",
        "[nan, 0]",
        "[0, inf]",
    ] {
        let e = err(&with_dyn(&format!("initial_velocity = {{ tip = {v} }}")));
        assert!(e.starts_with("dynamics.initial_velocity.tip"), "{v}: {e}");
        assert!(
            e.contains("shear wave speed c2") || e.contains("finite"),
            "{v}: {e}"
        );
    }
    let e = err(&with_dyn("initial_velocity = { tip = [1e300, 0] }"));
    assert!(e.contains("2.095189e3"), "c2 of brass named: {e}");
    let s = run(&with_dyn("initial_velocity = { tip = [\"2000 m/s\", 0] }"))
        .unwrap()
        .unwrap();
    assert_eq!(s.notes.len(), 1, "{:?}", s.notes);
    assert!(
        s.notes[0].starts_with("dynamics.initial_velocity.tip") && s.notes[0].contains("95.5 %"),
        "{:?}",
        s.notes
    );
    let s = run(&with_dyn("initial_velocity = { tip = [\"20 m/s\", 0] }"))
        .unwrap()
        .unwrap();
    assert!(s.notes.is_empty(), "{:?}", s.notes);
}

/// The probe of the dynamic inputs at extreme values (issue 13: each a clean error naming
/// the item, or a correct result): (what is set, the field the error must start with).
#[test]
fn extreme_dynamic_inputs_are_refused_naming_the_item() {
    let csv = std::env::temp_dir().join(format!("tribo_dynenergy_nan_{}.csv", std::process::id()));
    std::fs::write(&csv, "t,f\n0,0\n1e-3,NaN\n").unwrap();
    let big = std::env::temp_dir().join(format!("tribo_dynenergy_big_{}.csv", std::process::id()));
    std::fs::write(&big, "t,f\n0,0\n1e-3,1e308\n").unwrap();
    let table: Vec<(String, &str)> = vec![
        // dt = 1e-300 s over 2 ms: 2e297 steps.
        (
            with_dyn("time_step = \"1e-300 s\"").replace("time_step = \"1 us\"\n", ""),
            "dynamics",
        ),
        // 1e12 steps (with the time step: the duration line removed).
        (
            with_dyn("steps = 1000000000000").replace("duration = \"2 ms\"\n", ""),
            "dynamics.steps",
        ),
        // 2 ms / 3 us is not a whole number of steps.
        (
            with_dyn("time_step = \"3 us\"").replace("time_step = \"1 us\"\n", ""),
            "dynamics",
        ),
        // A time table with 1e308 factors (a load times 1e308 overflows).
        (
            BASE.replace(
                "time = \"step\"",
                "time = { points = [[0, 0], [\"1 ms\", 1e308]] }",
            ),
            "bc[0].time.points[1][1]",
        ),
        (
            BASE.replace(
                "time = \"step\"",
                &format!("time = {{ csv = {:?} }}", big.display().to_string()),
            ),
            "bc[0].time.csv",
        ),
        // A NaN factor in a tabulated CSV.
        (
            BASE.replace(
                "time = \"step\"",
                &format!("time = {{ csv = {:?} }}", csv.display().to_string()),
            ),
            "bc[0].time.csv",
        ),
        // A probe at 1e300.
        (
            BASE.replace("at = [\"0.2 m\", 0.5]", "at = [1e300, 0.5]"),
            "probe[0].at",
        ),
        // Densities 1e-300 and 1e300 kg/m^3.
        (
            BASE.replace("\"7850 kg/m^3\"", "\"1e-300 kg/m^3\""),
            "materials.steel.density",
        ),
        (
            BASE.replace("\"8.5 g/cm^3\"", "\"1e300 kg/m^3\""),
            "materials.brass.density",
        ),
    ];
    for (text, field) in &table {
        let e = match run(text) {
            Err(e) => e.to_string(),
            Ok(_) => panic!("accepted: {text}"),
        };
        assert!(
            e.starts_with(field)
                || e.contains(&format!("{field}:"))
                || e.contains(&format!("{field} ")),
            "{field}: {e}"
        );
    }
    let _ = std::fs::remove_file(&csv);
    let _ = std::fs::remove_file(&big);
}
