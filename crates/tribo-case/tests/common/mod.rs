//! Helpers shared by the library tests: cases from the embedded examples (with sections
//! added or replaced in their text), runs with the silent progress, the typed summary.
#![allow(dead_code)] // each test file uses its own subset

use std::path::Path;
use tribo_case::case::{parse_case, HalfSpaceCase};
use tribo_case::examples;
use tribo_case::pipeline::{self, Outcome};
use tribo_case::summary::Summary;
use tribo_case::{CaseError, Silent};

/// The text of the embedded example `name`.
pub fn example(name: &str) -> &'static str {
    examples::find(name)
        .unwrap_or_else(|| panic!("no example {name}"))
        .text
}

/// The paper's roller on the shaft (Sec. 3: steel, R = 5 mm / 50 mm on a shaft of 10 mm,
/// 2000 N, 21 x 21 elements over 1.5 a): the example `roller-shaft-normal`, with `contact`
/// added to its `[contact]` section and the sections `sections` appended.
pub fn paper(contact: &str, sections: &str) -> String {
    with_contact(example("roller-shaft-normal"), contact) + sections
}

/// A steel ball (R = 10 mm, E = 210 GPa) on a steel flat under 100 N: the example
/// `sphere-on-flat` on `n` x `n` elements, with `contact` added to its `[contact]` section
/// and the sections `sections` appended.
pub fn sphere(n: usize, contact: &str, sections: &str) -> String {
    with_contact(example("sphere-on-flat"), contact).replace("n = 64", &format!("n = {n}"))
        + sections
}

/// Sliding friction f = 0.2 across the roller (along y, the rolling direction).
pub const DAMAGE_BASE: &str = "friction = 0.2\nsliding = true\nsliding_angle_deg = 90\n";

/// The paper's roller sliding across ([`DAMAGE_BASE`]) with the generalized energy criterion
/// (25)-(36) at u0 = `u0` (J/m^3) next to the strain energy u with the limit u0, at 300 K,
/// on a 9 x 9 x 5 field.
pub fn energy_case(u0: f64) -> String {
    paper(
        DAMAGE_BASE,
        &format!(
            "[field]\nn = [9, 9, 5]\n[damage]\ncriteria = [\"u\"]\n[damage.limits]\nu = {u0}\n\
             [damage.energy]\nu0 = {u0}\ntemperature = 300.0\n"
        ),
    )
}

/// `text` with the lines `contact` at the end of its `[contact]` section (the examples
/// write `[grid]` right after it).
pub fn with_contact(text: &str, contact: &str) -> String {
    assert_eq!(text.matches("[grid]").count(), 1);
    text.replace("[grid]", &format!("{contact}[grid]"))
}

/// A height map on a flat (both steel, 10 N, 8 x 8 elements over +-0.1 mm), the map's nodes
/// 0.1 mm apart in micrometres: `source` is its `heights = [...]` or `file = "..."`.
pub fn height_map(source: &str) -> String {
    format!(
        "[body1]\nE = 2.01e11\nnu = 0.3\nsurface = {{ kind = \"height_map\", {source}, \
         spacing = [1e-4, 1e-4], scale = 1e-6 }}\n[body2]\nE = 2.01e11\nnu = 0.3\n\
         radii = [\"inf\", \"inf\"]\n[contact]\nload = 10.0\n[grid]\nn = 8\nhalf_width = 1e-4\n"
    )
}

/// Parses and validates a half-space case.
pub fn parse(text: &str) -> Result<HalfSpaceCase, CaseError> {
    parse_case(text, "case.toml", Path::new("."))
}

/// A solved case and its summary (`summary.json` as typed data).
pub struct Solved {
    /// The case.
    pub case: HalfSpaceCase,
    /// The pipeline's results.
    pub out: Outcome,
    /// The summary of case and results.
    pub summary: Summary,
}

/// Parses, validates and runs a half-space case that must solve.
pub fn solve(text: &str) -> Solved {
    let case = parse(text).unwrap_or_else(|e| panic!("invalid case: {e}\n{text}"));
    let out = pipeline::run(&case, &mut Silent).unwrap_or_else(|e| panic!("run failed: {e}"));
    let summary = Summary::new(&case, &out, Vec::new());
    Solved { case, out, summary }
}

/// The case `text` is refused (by validation, or by the run where the rule needs the
/// solution), as bad input, with a message that contains `field`.
pub fn assert_refused(text: &str, field: &str) {
    let err = match parse(text) {
        Err(e) => e,
        Ok(case) => match pipeline::run(&case, &mut Silent) {
            Err(e) => e,
            Ok(_) => panic!("accepted, expected an error naming {field:?}:\n{text}"),
        },
    };
    assert!(err.is_bad_input(), "{field}: not bad input: {err}");
    assert!(
        err.to_string().contains(field),
        "the error does not name {field:?}: {err}"
    );
}

/// Relative difference |a / b - 1|.
pub fn rel(a: f64, b: f64) -> f64 {
    (a / b - 1.0).abs()
}
