//! Case files: TOML in, a validated [`HalfSpaceCase`] out, before any computation.
//!
//! serde parses the schema into typed raw structs (`halfspace/schema.rs`: [`crate::units::Quantity`]
//! for numbers with units, enums for choices, unknown keys refused); `halfspace/validate/`
//! checks only the rules between values; the validated model (`halfspace/model.rs`) is what
//! the pipeline runs. Every error names the key and the rule.
//!
//! The schema (every key; docs/user/case-halfspace.md is the user's reference):
//!
//! ```toml
//! title = "..."                    # optional
//! [body1]                          # body 1 defines the frame: x = its first principal direction
//! E = 2.01e11                      # Young's modulus, Pa (or "201 GPa")
//! nu = 0.3                         # Poisson's ratio, in (-1, 0.5)
//! radii = [0.005, 0.05]            # principal radii along x and y, m; < 0 concave; "inf" flat
//! # or, instead of radii, a surface: [body1.surface] kind = "roller" | "height_map"
//! # (a roughness: kind = "rough" | "measured", with or without radii; on a roller its
//! # table [body1.surface.roughness] of kind "rough" | "measured")
//! [body2]
//! E = 2.01e11
//! nu = 0.3
//! radii = [-0.01, 0.01]
//! angle_deg = 0.0                  # angle from body 1's first principal plane to body 2's, deg
//! [contact]
//! load = 2000.0                    # N; or approach = 2.723e-5 (m); exactly one
//! # friction = 0.2                 # optional Coulomb f > 0, then exactly one of:
//! # tangential_load = 300.0        #   partial slip, |Q| on body 1, N (tangential_angle_deg, from x)
//! # sliding = true                 #   full sliding q = f p (sliding_angle_deg, from x)
//! [grid]                           # optional
//! n = 21                           # elements per side, or [nx, ny]; default 64
//! extent = 1.5                     # window half width / Hertz long semi-axis (radii only; default 1.5)
//! # half_width = 8e-4              # or the window half width in m, scalar or [x, y]
//! [solver]                         # optional
//! method = "cg"                    # "cg" (Polonsky-Keer) or "active_set" (dense, small grids)
//! tolerance = 1e-10
//! max_iterations = 10000
//! [bulk]                           # optional: the back effect of bulk loading, (18), Fig. 2a
//! shaft = "body2"                  # which body is the shaft: "body1" or "body2" (default body2)
//! shaft_radius = 0.01              # R2, m (default: the body's radius where it has one)
//! kind = "both"                    # "tension-compression", "bending" or "both" (default)
//! stress_max = 6.4e8               # sigma_a,max, Pa: the curve spans sigma/sigma_max in [-1, 1]
//! points = 21                      # points per curve, odd, 3 ... 1001 (default 21)
//! # stress = 3.2e8                 # optional operating bulk stress, Pa: F_N reported there
//! # bending_force = 5e3            # or, with kind = "bending": the operating bending stress
//! # span = 0.2                     #   4 M/(pi R^3) from a force (N), a span (m) and the
//! # support = "simply-supported"   #   support (M = F L/4; "cantilever": M = F L), with
//! # bending_side = "tension"       #   the contact on the tension or compression side
//! [field]                          # optional: the subsurface stress field
//! n = [39, 39, 20]                 # points along x, y, z (default the paper's)
//! extent = 1.5                     # x, y half width / Hertz a (or half_width, m)
//! depth = 1.5                      # depth / Hertz a (or depth_m, m); z down into the body
//! body = "body2"                   # the body the field is in (default body2)
//! # method = "direct"              # uniform points: "fft" (default, FFT + cubic interpolation)
//!                                  #   or "direct" (the exact direct sum, slow)
//! # points = "centres"             # instead of n and extent: x, y at the contact grid's
//! # layers = 20                    # element centres (FFT, for large grids), `layers` depths
//! # edge_refinement = "none"       # "band" (default): the edge-aware tractions near the
//!                                  #   contact edges at shallow depths; "none" (or 1): the
//!                                  #   bilinear element tractions; 2 ... 16: the edge-aware
//!                                  #   tractions everywhere, on a grid this many times finer
//! ```

mod model;
mod schema;
mod validate;

#[cfg(test)]
mod hostile;

pub use model::*;
pub use validate::read_height_csv;

use crate::error::{CaseError, CaseResult};
use schema::RawCase;
use std::path::Path;
use toml::Value;

/// Parse and validate a case file's text. `source` names it in errors; `base_dir` resolves
/// relative file paths (height maps).
pub fn parse_case(text: &str, source: &str, base_dir: &Path) -> CaseResult<HalfSpaceCase> {
    let (raw, echo) = parse_raw::<RawCase>(text, source)?;
    validate::validate(raw, source, base_dir, echo)
}

/// Validate a case given as a TOML table (the same schema and rules as a case file; see
/// [`crate::builder::CaseBuilder`] for building one in code). `source` names it in errors;
/// `base_dir` resolves relative file paths (height maps).
pub fn from_table(table: toml::Table, source: &str, base_dir: &Path) -> CaseResult<HalfSpaceCase> {
    let value = Value::Table(table);
    let echo = echo_json(&value);
    let raw = crate::schema::from_value::<RawCase>(value, source)?;
    validate::validate(raw, source, base_dir, echo)
}

/// The case text parsed into the raw (serde) schema `T`, and the case as JSON (echoed in
/// the summary). Errors name `source`; a value refused by the schema names its full key path
/// (`body1.radii[0] = "big": ...`), other schema errors carry the parser's line and column.
pub fn parse_raw<T: serde::de::DeserializeOwned>(
    text: &str,
    source: &str,
) -> CaseResult<(T, serde_json::Value)> {
    let raw: T = crate::schema::from_text(text, source)?;
    let table: toml::Table = toml::from_str(text).map_err(|e| CaseError::Parse {
        path: source.to_string(),
        message: e.to_string(),
    })?;
    let echo = echo_json(&Value::Table(table));
    Ok((raw, echo))
}

/// The case as JSON for the summary's echo. JSON has no infinity: TOML's `inf`, `-inf` and
/// `nan` floats are echoed as the strings "inf", "-inf" and "nan" (serde_json would write
/// null, which reads back as a different case); dates as their TOML text.
pub(crate) fn echo_json(v: &Value) -> serde_json::Value {
    use serde_json::Value as J;
    match v {
        Value::String(s) => J::String(s.clone()),
        Value::Integer(i) => J::from(*i),
        Value::Float(x) if x.is_nan() => J::String("nan".into()),
        Value::Float(x) if x.is_infinite() => {
            J::String(if *x > 0.0 { "inf" } else { "-inf" }.into())
        }
        Value::Float(x) => J::from(*x),
        Value::Boolean(b) => J::Bool(*b),
        Value::Datetime(d) => J::String(d.to_string()),
        Value::Array(a) => J::Array(a.iter().map(echo_json).collect()),
        Value::Table(t) => J::Object(t.iter().map(|(k, v)| (k.clone(), echo_json(v))).collect()),
    }
}

#[cfg(test)]
mod tests {
    use super::validate::shaft_radius_from;
    use super::*;
    use tribo::solvers::NormalMethod;

    /// The case's `solver.method` is the library's [`NormalMethod`]: its name in summaries is
    /// the string serde reads and writes, so the two cannot drift.
    #[test]
    fn solver_method_names_are_the_library_methods_serde_names() {
        for m in [NormalMethod::ConjugateGradient, NormalMethod::ActiveSet] {
            let json = serde_json::to_value(m).unwrap();
            assert_eq!(json, serde_json::Value::String(m.name().into()));
            let back: NormalMethod = serde_json::from_value(json).unwrap();
            assert_eq!(back, m);
        }
    }
    use tribo::geometry::{Crown, SurfaceProfile};
    use tribo::solvers::NormalLoading;

    const PAPER: &str = r#"
title = "Roller on shaft, paper Sec. 3"
[body1]
E = 2.01e11
nu = 0.3
radii = [0.005, 0.05]
[body2]
E = 2.01e11
nu = 0.3
radii = [-0.01, 0.01]
[contact]
load = 2000.0
[grid]
n = 21
extent = 1.5
"#;

    fn parse(text: &str) -> CaseResult<HalfSpaceCase> {
        parse_case(text, "test.toml", Path::new("."))
    }

    fn err(text: &str) -> String {
        parse(text).unwrap_err().to_string()
    }

    #[test]
    fn the_papers_case_parses() {
        let c = parse(PAPER).unwrap();
        assert_eq!(c.title, "Roller on shaft, paper Sec. 3");
        assert_eq!(c.n, [21, 21]);
        assert_eq!(c.window, Window::Extent(1.5));
        assert_eq!(c.loading, NormalLoading::Force(2000.0));
        assert!(c.is_hertzian());
        assert_eq!(
            c.body2.shape,
            Shape::Radii {
                radii: [-0.01, 0.01],
                angle: 0.0
            }
        );
        assert!((c.composite_modulus() / 1.10440e11 - 1.0).abs() < 5e-6);
        assert_eq!(c.echo["body1"]["radii"][1], serde_json::json!(0.05));
        assert_eq!(c.method, NormalMethod::ConjugateGradient);
    }

    #[test]
    fn units_inf_and_pairs() {
        let t = PAPER
            .replace(
                "E = 2.01e11\nnu = 0.3\nradii = [0.005, 0.05]",
                "E = \"201 GPa\"\nnu = 0.3\nradii = [\"5 mm\", \"inf\"]",
            )
            .replace(
                "n = 21\nextent = 1.5",
                "n = [32, 16]\nhalf_width = [\"1 mm\", 5e-4]",
            )
            .replace("load = 2000.0", "approach = \"27.23 um\"");
        let c = parse(&t).unwrap();
        assert_eq!(c.body1.material.youngs_modulus(), 201e9);
        assert!(
            matches!(c.body1.shape, Shape::Radii { radii, .. } if radii[0] == 0.005 && radii[1].is_infinite())
        );
        assert_eq!(c.n, [32, 16]);
        assert_eq!(c.window, Window::HalfWidth([0.001, 5e-4]));
        assert!(matches!(c.loading, NormalLoading::Approach(a) if (a - 2.723e-5).abs() < 1e-15));
    }

    #[test]
    fn bad_materials() {
        let e = err(&PAPER.replacen("nu = 0.3", "nu = 0.55", 1));
        assert_eq!(e, "body1.nu = 0.55: Poisson's ratio must be in (-1, 0.5)");
        assert!(err(&PAPER.replacen("E = 2.01e11", "E = -1.0", 2)).starts_with("body1.E"));
        let t = PAPER.replacen("[body2]\nE = 2.01e11", "[body2]\nE = nan", 1);
        assert!(err(&t).starts_with("body2.E = nan"), "{}", err(&t));
        assert!(err(&PAPER.replacen("nu = 0.3", "nu = -1.0", 1)).starts_with("body1.nu"));
    }

    #[test]
    fn bad_radii() {
        assert!(
            err(&PAPER.replace("[0.005, 0.05]", "[0.0, 0.05]")).starts_with("body1.radii[0] = 0")
        );
        assert!(err(&PAPER.replace("[0.005, 0.05]", "[0.005]")).starts_with("body1.radii"));
        let flat = PAPER
            .replace("[0.005, 0.05]", "[\"inf\", \"inf\"]")
            .replace("[-0.01, 0.01]", "[\"inf\", \"inf\"]");
        let e = err(&flat);
        assert!(e.contains("radii") && e.contains("convex"), "{e}");
        // A concave body tighter than the convex one.
        let e = err(&PAPER.replace("[-0.01, 0.01]", "[-0.004, 0.01]"));
        assert!(e.contains("convex"), "{e}");
        let e = err(&PAPER.replace("[0.005, 0.05]", "[\"big\", 0.05]"));
        assert!(e.starts_with("body1.radii[0] = \"big\""), "{e}");
    }

    #[test]
    fn load_and_approach() {
        let both = PAPER.replace("load = 2000.0", "load = 2000.0\napproach = 1e-5");
        assert!(err(&both).contains("exactly one"));
        let neither = PAPER.replace("load = 2000.0", "");
        assert!(err(&neither).starts_with("contact"));
        assert!(err(&PAPER.replace("load = 2000.0", "load = 0")).starts_with("contact.load = 0"));
        assert!(err(&PAPER.replace("load = 2000.0", "load = -5.0")).starts_with("contact.load"));
        assert!(err(&PAPER.replace("load = 2000.0", "approach = -1e-6"))
            .starts_with("contact.approach"));
        assert!(
            err(&PAPER.replace("load = 2000.0", "approach = 0.0")).starts_with("contact.approach")
        );
    }

    #[test]
    fn bad_grids() {
        assert!(err(&PAPER.replace("n = 21", "n = 3")).starts_with("grid.n = 3"));
        assert!(err(&PAPER.replace("n = 21", "n = 100000000")).starts_with("grid.n = 100000000"));
        assert!(err(&PAPER.replace("n = 21", "n = [21, 2]")).starts_with("grid.n[1] = 2"));
        assert!(err(&PAPER.replace("n = 21", "n = -4")).starts_with("grid.n"));
        assert!(err(&PAPER.replace("extent = 1.5", "extent = 0.9")).starts_with("grid.extent"));
        assert!(
            err(&PAPER.replace("extent = 1.5", "extent = 1.5\nhalf_width = 1e-3"))
                .contains("not both")
        );
        assert!(err(&PAPER.replace("extent = 1.5", "half_width = -1e-3"))
            .starts_with("grid.half_width"));
        // No [grid] at all: defaults.
        let c = parse(&PAPER.replace("[grid]\nn = 21\nextent = 1.5", "")).unwrap();
        assert_eq!(
            (c.n, c.window),
            ([DEFAULT_N; 2], Window::Extent(DEFAULT_EXTENT))
        );
    }

    #[test]
    fn unknown_keys_are_errors() {
        let e = err(&PAPER.replace("nu = 0.3", "nu = 0.3\nnuu = 0.3"));
        assert!(e.contains("nuu"), "{e}");
        let e = err(&PAPER.replace("[grid]", "[gird]"));
        assert!(e.contains("gird"), "{e}");
        let e = err(&PAPER.replace("load = 2000.0", "lod = 2000.0"));
        assert!(e.contains("lod"), "{e}");
        let e = err(&(PAPER.to_string() + "[solver]\nmethod = \"newton\"\n"));
        assert!(e.contains("newton"), "{e}");
        assert!(err("title = ").starts_with("test.toml"));
    }

    #[test]
    fn angle_and_solver() {
        let t = PAPER.replace(
            "radii = [-0.01, 0.01]",
            "radii = [-0.01, 0.01]\nangle_deg = 30",
        );
        let c = parse(
            &(t + "[solver]\nmethod = \"active_set\"\ntolerance = 1e-8\nmax_iterations = 50\n"),
        )
        .unwrap();
        assert!(
            matches!(c.body2.shape, Shape::Radii { angle, .. } if (angle - 30f64.to_radians()).abs() < 1e-15)
        );
        assert_eq!(c.method, NormalMethod::ActiveSet);
        assert_eq!((c.params.tolerance, c.params.max_iterations), (1e-8, 50));
        let t = PAPER.replace(
            "radii = [0.005, 0.05]",
            "radii = [0.005, 0.05]\nangle_deg = 30",
        );
        assert!(err(&t).starts_with("body1.angle_deg"));
        // An angle with its unit is the same f64 as the plain number of degrees.
        let deg = PAPER.replace(
            "radii = [-0.01, 0.01]",
            "radii = [-0.01, 0.01]\nangle_deg = \"30 deg\"",
        );
        assert!(
            matches!(parse(&deg).unwrap().body2.shape, Shape::Radii { angle, .. } if angle == 30f64.to_radians())
        );
        let e = err(&deg.replace("30 deg", "30 grad"));
        assert!(
            e.starts_with("body2.angle_deg = \"30 grad\": must be an angle"),
            "{e}"
        );
        // Radians are accepted (to_degrees, then to_radians: within 2 ulp of the radians).
        let rad = deg.replace("30 deg", "0.5235987755982988 rad");
        assert!(
            matches!(parse(&rad).unwrap().body2.shape, Shape::Radii { angle, .. } if (angle - 30f64.to_radians()).abs() < 1e-15)
        );
        let big = PAPER.replace("n = 21", "n = 128") + "[solver]\nmethod = \"active_set\"\n";
        assert!(err(&big).starts_with("solver.method"));
        assert!(
            err(&(PAPER.to_string() + "[solver]\ntolerance = 0\n")).starts_with("solver.tolerance")
        );
    }

    #[test]
    fn bulk_section() {
        assert_eq!(parse(PAPER).unwrap().bulk, None);
        let c = parse(&(PAPER.to_string() + "[bulk]\nstress_max = \"640 MPa\"\n")).unwrap();
        let b = c.bulk.unwrap();
        assert_eq!((b.shaft, b.shaft_radius), ("body2", 0.01));
        assert_eq!(b.kinds, [LoadKind::TensionCompression, LoadKind::Bending]);
        assert_eq!((b.stress_max, b.points, b.stress), (6.4e8, 21, None));
        let r = b.ratios();
        assert_eq!((r.len(), r[0], r[10], r[20]), (21, -1.0, 0.0, 1.0));
        let t = PAPER.to_string()
            + "[bulk]\nshaft = \"body2\"\nshaft_radius = \"10.5 mm\"\nkind = \"bending\"\n\
               stress_max = 6.4e8\npoints = 5\nstress = -3.2e8\n";
        let b = parse(&t).unwrap().bulk.unwrap();
        assert!((b.shaft_radius - 0.0105).abs() < 1e-15);
        assert_eq!(
            (b.kinds.as_slice(), b.points),
            ([LoadKind::Bending].as_slice(), 5)
        );
        assert_eq!(b.stress, Some(-3.2e8));
        // Body 1's radii differ: the radius is required.
        let e = err(&(PAPER.to_string() + "[bulk]\nshaft = \"body1\"\nstress_max = 1e8\n"));
        assert!(
            e.starts_with("bulk.shaft_radius") && e.contains("required"),
            "{e}"
        );
        let bad = |extra: &str| err(&format!("{PAPER}[bulk]\nstress_max = 6.4e8\n{extra}\n"));
        for (extra, field) in [
            ("shaft = \"body3\"", "bulk.shaft = \"body3\""),
            ("shaft_radius = -0.01", "bulk.shaft_radius = -0.01"),
            ("shaft_radius = 0", "bulk.shaft_radius = 0"),
            ("kind = \"torsion\"", "bulk.kind = \"torsion\""),
            ("points = 2", "bulk.points = 2"),
            ("points = 20", "bulk.points = 20"),
            ("points = 1", "bulk.points = 1"),
            ("points = 100001", "bulk.points = 100001"),
            ("points = 2.5", "bulk.points = 2.5"),
            ("stress = nan", "bulk.stress = nan"),
            ("stress = \"3 mm\"", "bulk.stress"),
        ] {
            let e = bad(extra);
            assert!(e.starts_with(field), "{extra}: {e}");
        }
        let e = err(&(PAPER.to_string() + "[bulk]\nstress_max = -1\n"));
        assert!(e.starts_with("bulk.stress_max = -1"), "{e}");
        let e = err(&(PAPER.to_string() + "[bulk]\nkind = \"bending\"\n"));
        assert!(
            e.starts_with("bulk.stress_max") && e.contains("required"),
            "{e}"
        );
        let e = bad("stres = 1e8");
        assert!(e.contains("stres"), "{e}");
    }

    #[test]
    fn default_shaft_radius() {
        let r = |radii: [f64; 2]| shaft_radius_from(&Shape::Radii { radii, angle: 0.0 });
        assert_eq!(r([-0.01, 0.01]), Some(0.01));
        assert_eq!(r([0.02, 0.02]), Some(0.02));
        assert_eq!(r([f64::INFINITY, 0.01]), Some(0.01));
        assert_eq!(r([0.01, f64::INFINITY]), Some(0.01));
        assert_eq!(r([-0.01, f64::INFINITY]), None);
        assert_eq!(r([0.005, 0.05]), None);
        assert_eq!(r([f64::INFINITY; 2]), None);
    }

    const ROLLER: &str = r#"
[body1]
E = 2.01e11
nu = 0.3
[body1.surface]
kind = "roller"
radius = 0.005
length = 0.01
crown = "logarithmic"
crown_drop = 1e-5
[body2]
E = 2.01e11
nu = 0.3
radii = ["inf", 0.02]
[contact]
load = 2000.0
[grid]
n = [64, 16]
half_width = [0.0056, 0.0003]
"#;

    #[test]
    fn roller_surfaces() {
        let c = parse(ROLLER).unwrap();
        assert!(!c.is_hertzian());
        match &c.body1.shape {
            Shape::Surface(SurfaceProfile::Roller(r)) => match r.crown {
                Crown::Logarithmic(l) => {
                    assert_eq!((l.design_load, l.end_drop), (2000.0, Some(1e-5)));
                }
                _ => panic!(),
            },
            _ => panic!(),
        }
        // extent is not defined for surfaces; half_width is required.
        let e = err(&ROLLER.replace("half_width = [0.0056, 0.0003]", "extent = 1.5"));
        assert!(e.starts_with("grid.extent"), "{e}");
        let e = err(&ROLLER.replace("half_width = [0.0056, 0.0003]", ""));
        assert!(
            e.starts_with("grid.half_width") && e.contains("required"),
            "{e}"
        );
        let e = err(&ROLLER.replace("crown = \"logarithmic\"", "crown = \"parabolic\""));
        assert!(e.starts_with("body1.surface.crown"), "{e}");
        let e = err(&ROLLER.replace("crown = \"logarithmic\"", "crown = \"circular\""));
        assert!(e.starts_with("body1.surface.crown_drop"), "{e}");
        let circ = ROLLER.replace(
            "crown = \"logarithmic\"\ncrown_drop = 1e-5",
            "crown = \"circular\"\ncrown_radius = 0.5",
        );
        assert!(parse(&circ).is_ok());
        let e = err(&ROLLER.replace("kind = \"roller\"", "kind = \"roller\"\ncolour = 1"));
        assert!(e.contains("colour"), "{e}");
        let e = err(&ROLLER.replace("kind = \"roller\"", "kind = \"cone\""));
        assert!(
            e.starts_with("body1.surface.kind = \"cone\": must be"),
            "{e}"
        );
        // The keys of the other kind of surface, and a roller's required keys.
        let e = err(&ROLLER.replace("radius = 0.005", "radius = 0.005\nscale = 2"));
        assert_eq!(
            e,
            "body1.surface.scale = 2: does not apply to kind = \"roller\""
        );
        let e = err(&ROLLER.replace("radius = 0.005", ""));
        assert!(
            e.starts_with("body1.surface.radius = (missing): required"),
            "{e}"
        );
        // A type error deep in the schema names the full path.
        let e = err(&ROLLER.replace("crown_drop = 1e-5", "crown_drop = \"10 GPa\""));
        assert!(
            e.starts_with("body1.surface.crown_drop = \"10 GPa\": must be a length"),
            "{e}"
        );
        let e = err(&ROLLER.replace(
            "radii = [\"inf\", 0.02]",
            "radii = [\"inf\", 0.02]\n[body2.surface]\nkind = \"roller\"\nradius = 1\nlength = 1",
        ));
        assert!(e.contains("exactly one of body2.radii"), "{e}");
        let e = err(&ROLLER.replace("radius = 0.005", "radius = 0"));
        assert!(e.starts_with("body1.surface.radius"), "{e}");
        let approach = ROLLER.replace("load = 2000.0", "approach = 1e-5");
        assert!(err(&approach).starts_with("body1.surface.design_load"));
    }

    const MAP: &str = r#"
[body1]
E = 2.01e11
nu = 0.3
[body1.surface]
kind = "height_map"
spacing = [1e-4, 1e-4]
heights = [[2, 1, 2], [1, 0, 1], [2, 1, 2]]
scale = 1e-6
[body2]
E = 2.01e11
nu = 0.3
radii = ["inf", "inf"]
[contact]
load = 10.0
[grid]
n = 8
half_width = 1e-4
"#;

    #[test]
    fn inline_height_maps() {
        let c = parse(MAP).unwrap();
        match &c.body1.shape {
            Shape::Surface(SurfaceProfile::HeightMap(m)) => {
                assert_eq!((m.nx(), m.ny()), (3, 3));
                assert!((m.height(0.0, 0.0).unwrap()).abs() < 1e-20);
                assert!((m.height(1e-4, 0.0).unwrap() - 1e-6).abs() < 1e-18);
            }
            _ => panic!(),
        }
        let e = err(&MAP.replace("[1, 0, 1]", "[1, 0]"));
        assert!(
            e.starts_with("body1.surface.heights[1]") && e.contains("ragged"),
            "{e}"
        );
        let e = err(&MAP.replace("[1, 0, 1]", "[1, \"x\", 1]"));
        assert!(e.starts_with("body1.surface.heights[1][1]"), "{e}");
        let e = err(&MAP.replace("[1, 0, 1]", "[1, nan, 1]"));
        assert!(e.starts_with("body1.surface.heights[1][1]"), "{e}");
        let e = err(&MAP.replace("half_width = 1e-4", "half_width = 2e-4"));
        assert!(
            e.starts_with("grid.half_width") && e.contains("height map"),
            "{e}"
        );
    }

    #[test]
    fn csv_height_maps() {
        let dir = tempfile::tempdir().unwrap();
        let write = |name: &str, text: &str| std::fs::write(dir.path().join(name), text).unwrap();
        write("ok.csv", "# heights in um\n2, 1, 2\n1,0,1\n\n2,1,2\n");
        write("ragged.csv", "2,1,2\n1,0\n2,1,2\n");
        write("text.csv", "2,1,2\n1,zero,1\n2,1,2\n");
        write("nan.csv", "2,1,2\n1,NaN,1\n2,1,2\n");
        let case = |file: &str| {
            let t = MAP.replace(
                "heights = [[2, 1, 2], [1, 0, 1], [2, 1, 2]]",
                &format!("file = \"{file}\""),
            );
            parse_case(&t, "t.toml", dir.path())
        };
        let c = case("ok.csv").unwrap();
        assert!(
            matches!(&c.body1.shape, Shape::Surface(SurfaceProfile::HeightMap(m)) if m.nx() == 3 && m.ny() == 3)
        );
        let e = case("ragged.csv").unwrap_err().to_string();
        assert!(
            e.contains("ragged.csv, line 2") && e.contains("ragged"),
            "{e}"
        );
        let e = case("text.csv").unwrap_err().to_string();
        assert!(
            e.contains("text.csv, line 2") && e.contains("not a number"),
            "{e}"
        );
        let e = case("nan.csv").unwrap_err().to_string();
        assert!(e.contains("nan.csv, line 2") && e.contains("finite"), "{e}");
        let e = case("missing.csv").unwrap_err();
        assert!(
            e.to_string().starts_with("body1.surface.file: cannot read"),
            "{e}"
        );
        assert!(e.is_bad_input());
    }
}
