//! `tribo-bench-periodic --surface FILE --n N [--tolerance T] [--repeat R] [--kernel spectral|element] [--no-coarse-start] [--reference FILE] [--pressure-out FILE]`
//!
//! Issue 16's periodic benchmark, tribo's half: periodic normal contact of the rigid rough
//! surface in FILE (N * N little-endian f64, x fastest, apex up: what
//! `bench/tamaas_periodic.py --surface-out STEM` writes to STEM.bin) against a flat elastic
//! half-space, E* = 1, a unit periodic window, mean pressure 0.1 E*, with tribo's
//! Polonsky-Keer solver on the periodic operator (`--kernel spectral`, the default: Tamaas's
//! continuous kernel, like with like; `element`: tribo's element-integrated default). Prints
//! one line of JSON.
//!
//! - `seconds` / `cpu_seconds`: the iteration alone (`solve_normal` on a prebuilt operator),
//!   the median of `--repeat` solves (default 1), wall and CPU (user + system, all threads);
//!   `operator_seconds`: the operator's construction; `apply_seconds`: one operator
//!   application (a forward and an inverse real FFT of N^2 points), mean of 10.
//! - `residuals`: tribo's answer under both stopping measures, `min_map` (tribo's,
//!   `tribo::solvers::normal::complementarity_residual`) and `tamaas` (Tamaas's,
//!   `tribo::validation::tamaas::tamaas_residual`), both computed here with the same operator.
//! - `--reference FILE`: Tamaas's pressure on the same surface (`tamaas_periodic.py
//!   --pressure-out`): its residuals under both measures (`reference_residuals`), and
//!   `max_pressure_difference` = max |p_tribo - p_tamaas| / max p_tamaas, `contact_mismatch`
//!   (elements in contact in one answer only).
//! - `peak_rss_bytes`: `VmHWM` of this process at the end (one process per N).
//!
//! Exit 2 on bad arguments, 3 when the solve fails (a JSON line with `error` is printed).

use std::process::ExitCode;
use std::time::Instant;

use serde_json::{json, Value};
use tribo::kernels::periodic::PeriodicKernel;
use tribo::solvers::normal::normal_compliance_operator_periodic;
use tribo::solvers::{solve_normal, NormalContactParams, NormalContactProblem, NormalLoading};
use tribo::validation::tamaas::{decode_f64_le, residuals_of};
use tribo::SurfaceGrid;

#[path = "../common/procstat.rs"]
mod procstat;
use procstat::{cpu_seconds, median, peak_rss_bytes, rayon_threads};

/// Mean pressure of the case, units of E* (issue 16, "Speed and memory").
const MEAN_PRESSURE: f64 = 0.1;

const USAGE: &str =
    "usage: tribo-bench-periodic --surface FILE --n N [--tolerance T] [--repeat R] \
     [--kernel spectral|element] [--no-coarse-start] [--reference FILE] [--pressure-out FILE]";

struct Args {
    surface: String,
    n: usize,
    tolerance: f64,
    repeat: usize,
    kernel: PeriodicKernel,
    coarse_start: bool,
    reference: Option<String>,
    pressure_out: Option<String>,
}

fn parse_args() -> Result<Args, String> {
    let (mut surface, mut n, mut reference, mut pressure_out) = (None, None, None, None);
    let mut tolerance = NormalContactParams::default().tolerance;
    let mut repeat = 1;
    let mut kernel = PeriodicKernel::Spectral;
    let mut coarse_start = true;
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        let (key, inline) = match arg.split_once('=') {
            Some((k, v)) => (k.to_string(), Some(v.to_string())),
            None => (arg.clone(), None),
        };
        match key.as_str() {
            "-h" | "--help" => return Err(USAGE.to_string()),
            "--no-coarse-start" => {
                coarse_start = false;
                continue;
            }
            _ => {}
        }
        let value = inline
            .or_else(|| it.next())
            .ok_or_else(|| format!("{key} needs a value\n{USAGE}"))?;
        match key.as_str() {
            "--surface" => surface = Some(value),
            "--n" => {
                let v = value.parse::<usize>().map_err(|e| format!("--n: {e}"))?;
                if v < 4 {
                    return Err("--n must be >= 4".into());
                }
                n = Some(v);
            }
            "--tolerance" => {
                tolerance = value
                    .parse::<f64>()
                    .map_err(|e| format!("--tolerance: {e}"))?;
                if !(tolerance.is_finite() && tolerance > 0.0 && tolerance < 1.0) {
                    return Err("--tolerance must be in (0, 1)".into());
                }
            }
            "--repeat" => {
                repeat = value
                    .parse::<usize>()
                    .map_err(|e| format!("--repeat: {e}"))?;
                if repeat == 0 {
                    return Err("--repeat must be >= 1".into());
                }
            }
            "--kernel" => {
                kernel = match value.as_str() {
                    "spectral" => PeriodicKernel::Spectral,
                    "element" => PeriodicKernel::ElementIntegrated,
                    other => {
                        return Err(format!(
                            "--kernel must be spectral or element, got {other:?}"
                        ))
                    }
                }
            }
            "--reference" => reference = Some(value),
            "--pressure-out" => pressure_out = Some(value),
            _ => return Err(format!("unknown argument {arg:?}\n{USAGE}")),
        }
    }
    Ok(Args {
        surface: surface.ok_or_else(|| format!("--surface is required\n{USAGE}"))?,
        n: n.ok_or_else(|| format!("--n is required\n{USAGE}"))?,
        tolerance,
        repeat,
        kernel,
        coarse_start,
        reference,
        pressure_out,
    })
}

/// Read `n * n` little-endian f64 from `path`.
fn read_field(path: &str, n: usize) -> Result<Vec<f64>, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{path}: {e}"))?;
    decode_f64_le(&bytes, n * n, path).map_err(|e| e.to_string())
}

fn run(args: &Args) -> Result<Value, String> {
    let n = args.n;
    let surface = read_field(&args.surface, n)?;
    let grid = SurfaceGrid::centred(n, n, 0.5, 0.5).map_err(|e| e.to_string())?;
    // tribo's initial gap h = z1 - z2: the rigid surface's height with its sign turned.
    let gap: Vec<f64> = surface.iter().map(|z| -z).collect();
    drop(surface);
    let params = NormalContactParams::default()
        .with_tolerance(args.tolerance)
        .map_err(|e| e.to_string())?
        .with_max_iterations(100_000)
        .map_err(|e| e.to_string())?
        .with_coarse_start(args.coarse_start);
    let problem = NormalContactProblem {
        grid: &grid,
        initial_gap: &gap,
        composite_modulus: 1.0,
        loading: NormalLoading::Force(MEAN_PRESSURE),
    };
    let cpu = || cpu_seconds().unwrap_or(f64::NAN);
    let t = Instant::now();
    let operator = normal_compliance_operator_periodic(&grid, 1.0, args.kernel);
    let operator_seconds = t.elapsed().as_secs_f64();
    let (mut walls, mut cpus, mut solved) = (Vec::new(), Vec::new(), None);
    for _ in 0..args.repeat {
        let (t, c) = (Instant::now(), cpu());
        solved = Some(solve_normal(&problem, &params, Some(&operator), None));
        walls.push(t.elapsed().as_secs_f64());
        cpus.push(cpu() - c);
    }
    let seconds = median(&walls);
    let sol = solved
        .ok_or("--repeat must be >= 1")?
        .map_err(|e| format!("solve_normal failed after {seconds:.3} s: {e}"))?;
    let mut workspace = operator.workspace();
    let reps = 10;
    let mut out = vec![0.0; grid.len()];
    let t = Instant::now();
    for _ in 0..reps {
        operator.apply_into(&sol.pressure, &mut out, &mut workspace);
    }
    let apply_seconds = t.elapsed().as_secs_f64() / reps as f64;
    drop(out);
    drop(workspace);

    let (min_map, tamaas) = residuals_of(&operator, &gap, &sol.pressure);
    let mut reference = Value::Null;
    if let Some(path) = &args.reference {
        let p_ref = read_field(path, n)?;
        let (r_min_map, r_tamaas) = residuals_of(&operator, &gap, &p_ref);
        let p_max = p_ref.iter().fold(0.0f64, |m, &p| m.max(p));
        let (mut diff, mut mismatch) = (0.0f64, 0usize);
        for (a, b) in sol.pressure.iter().zip(&p_ref) {
            diff = diff.max((a - b).abs());
            mismatch += usize::from((*a > 0.0) != (*b > 0.0));
        }
        reference = json!({
            "file": path,
            "residuals": {"min_map": r_min_map, "tamaas": r_tamaas},
            "max_pressure_difference": diff / p_max,
            "contact_mismatch": mismatch,
        });
    }
    if let Some(path) = &args.pressure_out {
        let bytes: Vec<u8> = sol.pressure.iter().flat_map(|p| p.to_le_bytes()).collect();
        std::fs::write(path, bytes).map_err(|e| format!("{path}: {e}"))?;
    }
    let iterations = sol.iterations;
    Ok(json!({
        "code": "tribo-periodic",
        "n": n,
        "kernel": match args.kernel {
            PeriodicKernel::Spectral => "spectral",
            PeriodicKernel::ElementIntegrated => "element",
        },
        "tolerance": args.tolerance,
        "coarse_start": args.coarse_start,
        "threads": rayon_threads(),
        "repeat": args.repeat,
        "seconds": seconds,
        "cpu_seconds": median(&cpus),
        "operator_seconds": operator_seconds,
        "apply_seconds": apply_seconds,
        "iterations": iterations,
        "seconds_per_iteration": seconds / iterations.max(1) as f64,
        "residual": sol.residual,
        "residuals": {"min_map": min_map, "tamaas": tamaas},
        "reference": reference,
        "mean_pressure": sol.normal_load,
        "max_pressure": sol.max_pressure(),
        "contact_fraction": sol.contact_elements as f64 / grid.len() as f64,
        "peak_rss_bytes": peak_rss_bytes(),
    }))
}

fn main() -> ExitCode {
    let args = match parse_args() {
        Ok(a) => a,
        Err(msg) => {
            eprintln!("{msg}");
            return ExitCode::from(2);
        }
    };
    match run(&args) {
        Ok(v) => {
            println!("{v}");
            ExitCode::SUCCESS
        }
        Err(msg) => {
            eprintln!("tribo-bench-periodic: {msg}");
            println!(
                "{}",
                json!({"code": "tribo-periodic", "n": args.n, "error": msg, "peak_rss_bytes": peak_rss_bytes()})
            );
            ExitCode::from(3)
        }
    }
}
