//! `tribo`: the command line of the tribo suite. Case files in; summaries, fields and plots
//! out. See docs/user/cli.md and `tribo --help`.

mod cmd;
mod exit;
mod human;
mod memory;
mod progress;
mod sweep;
mod term;

use clap::{Args, Parser, Subcommand};
use exit::{EXIT_OK, EXIT_OTHER};
use std::path::PathBuf;
use std::process::ExitCode;

const ABOUT: &str =
    "Contact mechanics of tribo-fatigue systems: normal contact of two elastic bodies \
with unknown contact area, compared with Hertz theory.";

const LONG_ABOUT: &str = "\
Contact mechanics of tribo-fatigue systems: normal contact of two elastic bodies with unknown
contact area (the half-space model), compared with Hertz theory where the gap is Hertzian.

Conventions:
  * SI units everywhere (Pa, m, N). HalfSpaceCase files may also write quantities as strings with a
    unit: \"201 GPa\", \"48.4 MPa\", \"10 mm\", \"5 um\", \"2 kN\".
  * Frame: x = body 1's first principal direction (for a roller: its axis), y the second,
    z normal to the common tangent plane. Compressive pressure p > 0.
  * Radii of curvature are signed: positive convex, negative concave, \"inf\" flat.
  * Each body's surface z_k(x, y) is measured from the tangent plane away from the other
    body; the initial gap is h = z1 + z2.
  * The composite modulus is 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2.
  * Unit strings are read as one decimal (\"9 mm\" is exactly 9e-3). TOML inf/nan are
    refused, except a radius of inf (flat).
  * Ranges (exit 2 naming the field): E in [1e2, 1e13] Pa; lengths of the geometry in
    [1e-9, 1e6] m; the load as a strain (Hertz p0/E*, or mean window pressure / E*, or
    approach / window half width) in [1e-15, 0.1], the small-strain range of the theory.
  * Memory: a case whose estimated peak memory exceeds --max-memory (default: what the
    machine has) is refused with exit 2 before solving; --dry-run prints the estimate.
    HalfSpaceCase files over 16 MiB are refused.

A case file is TOML; `tribo example` lists ready-made ones and `tribo example NAME` prints
one. A case with `kind = \"bem2d\"` is a 2D boundary element model of n bodies (regions from
outlines, conditions per named segment, frictional contact pairs, load steps): see
`tribo example clamp-knife-base` and docs/user/case-bem2d.md. Exit codes: 0 ok, 2 bad input, 3 solver did not converge, 1 anything else.";

const AFTER_HELP: &str = "\
Examples:
  tribo run                             the paper's roller/shaft case with friction, the stress
                                        field and the back-effect curve; writes tribo-out/
  tribo example                         list the example cases
  tribo example sphere-on-flat > s.toml
  tribo run s.toml -o out               run a case file, write out/
  tribo example crowned-roller | tribo run - -o roller --json
  tribo example roller-shaft-bending | tribo run - -o fig2a   the back effect (Fig. 2a)
  tribo example roller-shaft-normal | tribo run - -o normal   normal contact only
  tribo example clamp-knife-base | tribo run - -o knife   2D BEM, the paper's Sec. 7
  tribo validate                        the verification table
  tribo fatigue fit data.csv -o fit     Woehler curve fits (E739, max. likelihood), Fig. 3
  tribo example fatigue-diagram | tribo fatigue diagram -   limiting states, Fig. 4";

/// Where a command writes (`-o DIR`) and whether it prints its JSON (`--json`): the options
/// of every command that writes results.
#[derive(Debug, Args)]
pub struct OutputArgs {
    /// Output directory (created if needed).
    #[arg(
        short = 'o',
        long = "out",
        value_name = "DIR",
        default_value = "tribo-out"
    )]
    pub out: PathBuf,
    /// Print the summary as JSON on stdout instead of the human summary.
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, Parser)]
#[command(name = "tribo", version, about = ABOUT, long_about = LONG_ABOUT, after_help = AFTER_HELP)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Solve a case and write summary.json, fields (CSV, VTK) and plots (PNG).
    #[command(long_about = "\
Solve the normal contact of a case file (or of the embedded default case, the paper's Sec. 3
roller on shaft, when CASE is not given; `-` reads the case from stdin) and write into DIR:

  summary.json           loads, approach, max pressure, contact area, iterations, residual,
                         and (Hertzian gaps) the Hertz solution and the errors (17)
  pressure.csv, gap.csv  x_m, y_m, value at element centres (pressure_Pa, gap_m)
  fields.vti             VTK image data for ParaView: cell data pressure_Pa, gap_m,
                         initial_gap_m (and hertz_pressure_Pa)
  pressure_map.png       the pressure over the window with the Hertz ellipse
  pressure_profiles.png  p along x and along y through the centre, against Hertz

With a [bulk] section (the back effect of bulk loading of the shaft, the paper's (18) and
Fig. 2a) also:

  back_effect.csv        kind, sigma_Pa, sigma_over_sigma_max, approach_change_m,
                         normal_load_N, force_ratio, force_ratio_hertz
  back_effect.png        F_N / F_N(0) against sigma / sigma_max at the fixed rigid approach,
                         numerical points and the Hertz estimate, for each load kind

With contact.friction (tangential_load: partial slip, or sliding = true; q acts on body 1,
angles in degrees from x) also:

  traction.csv           x_m, y_m, q_x_Pa, q_y_Pa, stick (1/0); fields.vti gains
                         traction_x_Pa, traction_y_Pa, stick
  stick_slip.png         stick / slip / no contact, with the Cattaneo-Mindlin stick ellipse
  traction_profiles.png  q along the load direction against Cattaneo-Mindlin

With a [field] section (the subsurface stress field, direct sum; z the depth, downward):

  stress.vti             VTK image data, point arrays: stress components, von Mises,
                         max shear, principal stresses, hydrostatic, octahedral shear,
                         strain energy density (and parts), strains
  sigma_xx_y0.png, sigma_xx_z05a.png, von_mises_y0.png   sections (equal scale; signed
                         components blue-white-red about 0)
  sigma_yy_x0.png, von_mises_x0.png   with friction mainly along y: the plane x = 0

A 2D boundary element case (kind = \"bem2d\") writes instead: summary.json, interfaces.csv
and interfaces.png (contact pressure and shear along every pair, each step),
fields_<step>.vtu (VTK unstructured grid: displacement, stresses, sigma_int, strains, psi),
sigma_xx_<step>.png, sigma_int_<step>.png, and with [damage] psi_<quantity>.png,
damage_sweep.csv/png, with [compare] compare.csv/png. Its regions come from outlines of
lines and arcs ([[regions]], see `tribo example clamp-knife-base`) or from gmsh meshes
([[mesh]] file = \"part.msh\", materials = { SURFACE = \"MATERIAL\" }: ASCII .msh 2.2 or
4.1, physical surfaces are regions, physical curves name the segments; `--dry-run` lists
the names). Example with a mesh: crates/tribo-cli/examples/gmsh/hertz-cylinder.toml.

A short summary goes to stdout (--json: the summary JSON instead); progress to stderr.
Nothing is written when the case is invalid (exit 2) or the solver fails (exit 3).")]
    Run {
        /// Case file (TOML); `-` reads stdin; default: the embedded `roller-shaft` case.
        case: Option<PathBuf>,
        #[command(flatten)]
        output: OutputArgs,
        /// No progress on stderr.
        #[arg(short, long)]
        quiet: bool,
        /// Validate the case and print the grid it would use and its memory estimate; solve
        /// nothing, write nothing.
        #[arg(long)]
        dry_run: bool,
        /// Refuse (exit 2, nothing written) a case whose estimated peak memory exceeds SIZE
        /// ("4 GiB", "100MiB", "512 MB"); default: what the machine has (MemAvailable, or the
        /// cgroup's memory.max where smaller).
        #[arg(long, value_name = "SIZE", value_parser = memory::parse_size)]
        max_memory: Option<u64>,
    },
    /// List the example cases, or print one (`tribo example NAME > case.toml`); with `-o DIR`
    /// write it as DIR/NAME.toml with the data files it reads (the measured-x3p example's
    /// .x3p).
    Example {
        /// Example name; omit to list them.
        name: Option<String>,
        /// Write the case and its data files into this directory (created if needed) instead
        /// of printing it.
        #[arg(short = 'o', long = "out", value_name = "DIR")]
        out: Option<PathBuf>,
    },
    /// Fatigue curves from test data and the limiting-state diagram (paper Figs. 3, 4).
    #[command(subcommand)]
    Fatigue(cmd::fatigue::FatigueCommand),
    /// Studies over many cases: plan, run (locally or on SLURM), status, gather.
    #[command(subcommand)]
    Sweep(sweep::SweepCommand),
    /// Run the verification suite and print its table (exit 1 if a row fails).
    Validate {
        /// Print the rows as JSON.
        #[arg(long)]
        json: bool,
    },
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        // Help, version and usage errors, printed fallibly (`Cli::parse` ignores a failed
        // write): a closed stdout pipe ends quietly, any other write error exits 1.
        Err(e) => {
            use std::io::Write;
            let printed = e.print().and_then(|()| {
                if e.use_stderr() {
                    std::io::stderr().flush()
                } else {
                    std::io::stdout().flush()
                }
            });
            return match printed {
                Ok(()) => ExitCode::from(u8::try_from(e.exit_code()).unwrap_or(EXIT_OTHER)),
                Err(w) if w.kind() == std::io::ErrorKind::BrokenPipe && !e.use_stderr() => {
                    ExitCode::from(EXIT_OK)
                }
                Err(w) => {
                    if !e.use_stderr() {
                        term::note(&format!("error: cannot write to standard output: {w}"));
                    }
                    ExitCode::from(EXIT_OTHER)
                }
            };
        }
    };
    let result = match cli.command {
        Command::Run {
            case,
            output: OutputArgs { out, json },
            quiet,
            dry_run,
            max_memory,
        } => cmd::run::run(&cmd::run::RunArgs {
            case,
            out,
            json,
            quiet,
            dry_run,
            max_memory,
        }),
        Command::Example { name, out } => cmd::example::run(name.as_deref(), out.as_deref()),
        Command::Validate { json } => cmd::validate::run(json),
        Command::Fatigue(c) => cmd::fatigue::run(c),
        Command::Sweep(c) => sweep::run(c),
    };
    match result {
        Ok(code) => ExitCode::from(code),
        Err(e) => ExitCode::from(term::report(&e)),
    }
}

/// How the command line writes its files: plots on, and the temporary being written
/// removed on SIGINT/SIGTERM/SIGHUP.
pub fn write_options() -> tribo_io::WriteOptions {
    tribo_io::WriteOptions {
        plots: true,
        remove_temporary_on_signal: true,
    }
}
