//! `tribo fatigue fit` and `tribo fatigue diagram`: Woehler curves from test data (the paper's
//! Fig. 3) and the multicriterial limiting-state diagram (Fig. 4). See docs/user/fatigue.md.
//! The fit and the diagram are [`tribo_case::fatigue`]'s, the files [`tribo_io::fatigue`]'s.

use crate::exit::{CliError, CliResult, EXIT_OK};
use crate::OutputArgs;
use clap::{Subcommand, ValueEnum};
use serde::Serialize;
use std::io::Read;
use std::path::{Path, PathBuf};
use tribo::analysis::woehler::{LoadMeasure, TestKind};
use tribo_case::fatigue::{diagram, fit, parse_csv, parse_limits};

/// The test kind on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum KindArg {
    /// Mechanical fatigue (bending of the shaft), limit sigma_-1.
    Sigma,
    /// Rolling fatigue, limit p_f (contact pressure).
    P,
    /// Mechano-rolling fatigue, bending under rolling, limit sigma_-1p.
    SigmaP,
    /// Mechano-rolling fatigue, rolling under bending, limit p_f_sigma (contact pressure).
    PSigma,
}

impl From<KindArg> for TestKind {
    fn from(k: KindArg) -> Self {
        match k {
            KindArg::Sigma => TestKind::MechanicalFatigue,
            KindArg::P => TestKind::RollingFatigue,
            KindArg::SigmaP => TestKind::MechanoRollingStress,
            KindArg::PSigma => TestKind::MechanoRollingPressure,
        }
    }
}

/// The load measure on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MeasureArg {
    /// Stress amplitude S_a.
    Amplitude,
    /// Stress range 2 S_a.
    Range,
    /// Maximum contact pressure p0 (the p and p-sigma kinds).
    ContactPressure,
}

impl From<MeasureArg> for LoadMeasure {
    fn from(m: MeasureArg) -> Self {
        match m {
            MeasureArg::Amplitude => LoadMeasure::Amplitude,
            MeasureArg::Range => LoadMeasure::Range,
            MeasureArg::ContactPressure => LoadMeasure::ContactPressure,
        }
    }
}

/// `tribo fatigue ...`.
#[derive(Debug, Subcommand)]
pub enum FatigueCommand {
    /// Fit a Woehler curve to test data (CSV); write woehler.json and woehler.png.
    #[command(long_about = "\
Fit a Woehler (S-N) curve to fatigue test data and write into DIR:

  woehler.json  the ASTM E739 regression of log10 N on log10 S over the finite-zone
                fractures (slope m, intercept, standard error, confidence band factors,
                the curve with the fatigue limit at the run-out/fracture transition), and
                the maximum-likelihood fit of the full model (fatigue limit S_D, slope m,
                knee N_G, scatters T_N, T_S, standard errors, convergence record)
  woehler.png   log-log S-N plot: fractures, run-outs, both curves, the confidence band

DATA.csv: lines starting with '#' are comments; a header names the columns: the load
(`load_Pa` or `load` in Pa, or `load_MPa`), `cycles`, and `runout` (true: no failure) or
`fracture` (true: failed); flags are true/false, 1/0 or yes/no. The load measure (stress
amplitude, range, or contact pressure for the p and p-sigma kinds) is given by --measure;
it is stated in every output. `-` reads the data from stdin.")]
    Fit {
        /// The data file (CSV), or `-` for stdin.
        data: PathBuf,
        #[command(flatten)]
        output: OutputArgs,
        /// The test kind (paper Fig. 3).
        #[arg(long, value_enum, default_value = "sigma")]
        kind: KindArg,
        /// What the load column measures (default: amplitude for sigma kinds, contact
        /// pressure for p kinds).
        #[arg(long, value_enum)]
        measure: Option<MeasureArg>,
        /// Confidence level of the E739 bands, in (0, 1).
        #[arg(long, default_value_t = 0.95)]
        confidence: f64,
    },
    /// The limiting-state diagram of mechano-rolling fatigue (Fig. 4) from a TOML file;
    /// write limit_diagram.json and limit_diagram.png.
    #[command(long_about = "\
Build the multicriterial limiting-state diagram ABCD (the paper's Fig. 4) in the
normalized coordinates p0/p_f (x) and sigma_a/sigma_-1 (y) from the four fatigue limits and
the two loads held in the mechano-rolling test series, and check a load state against it.
`tribo example fatigue-diagram` prints a commented input; `-` reads it from stdin.

Writes limit_diagram.json (points, direct and back effects, the state check: load factor to
the boundary along the ray from the origin, margin = factor - 1, inside or not) and
limit_diagram.png.")]
    Diagram {
        /// The limits file (TOML), or `-` for stdin.
        limits: PathBuf,
        #[command(flatten)]
        output: OutputArgs,
    },
}

/// Run a `tribo fatigue` subcommand.
pub fn run(cmd: FatigueCommand) -> CliResult<u8> {
    match cmd {
        FatigueCommand::Fit {
            data,
            output: OutputArgs { out, json },
            kind,
            measure,
            confidence,
        } => {
            let kind = TestKind::from(kind);
            let measure = measure.map_or(kind.default_measure(), LoadMeasure::from);
            let (text, _) = read_input(&data, "data")?;
            let tests = parse_csv(&text, &data)?;
            let report = fit(
                kind,
                measure,
                tests,
                confidence,
                &data.display().to_string(),
            )?;
            tribo_io::write_fit(&out, &report, &crate::write_options())?;
            emit(json, &report, || crate::human::fit(&report, &out))
        }
        FatigueCommand::Diagram {
            limits,
            output: OutputArgs { out, json },
        } => {
            let (text, base) = read_input(&limits, "limits")?;
            let name = if limits.as_os_str() == "-" {
                "<stdin>".to_string()
            } else {
                limits.display().to_string()
            };
            let input = parse_limits(&text, &name, &base)?;
            let report = diagram(input)?;
            tribo_io::write_diagram(&out, &report, &crate::write_options())?;
            emit(json, &report, || crate::human::diagram(&report, &out))
        }
    }
}

fn emit<T: Serialize>(json: bool, value: &T, human: impl FnOnce() -> String) -> CliResult<u8> {
    if json {
        crate::term::outln(&to_json(value, "fatigue JSON")?)?;
    } else {
        crate::term::out(&human())?;
    }
    Ok(EXIT_OK)
}

fn to_json<T: Serialize>(value: &T, what: &str) -> CliResult<String> {
    let text = serde_json::to_string_pretty(value).map_err(|e| CliError::Output {
        what: what.into(),
        detail: e.to_string(),
    })?;
    Ok(text)
}

/// Read a file (or stdin for `-`); also return the directory relative paths resolve from.
fn read_input(path: &Path, field: &str) -> CliResult<(String, PathBuf)> {
    let unreadable = |source| tribo_case::CaseError::Unreadable {
        field: field.into(),
        path: path.to_path_buf(),
        source,
    };
    if path.as_os_str() == "-" {
        let mut text = String::new();
        std::io::stdin()
            .read_to_string(&mut text)
            .map_err(unreadable)?;
        Ok((text, PathBuf::from(".")))
    } else {
        let text = std::fs::read_to_string(path).map_err(unreadable)?;
        let base = path
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_else(|| PathBuf::from("."));
        Ok((text, base))
    }
}
