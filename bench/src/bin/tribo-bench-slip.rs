//! `tribo-bench-slip --n N [--ratio R]`
//!
//! The partial-slip solve of a sphere on a flat (R = 10 mm, steel on steel E = 2.1e11 Pa,
//! nu = 0.3, F_N = 2000 N, f = 0.3) under a tangential force Q = R f F_N along x (default
//! R = 0.5), on N x N elements over |x|, |y| <= 1.2a, with the element-averaged Hertz
//! pressure as the normal solution. Prints one line of JSON: the times of the operator
//! construction and of the constrained-CG iteration, the iterations, the residual, and the
//! stick radius sqrt(A_stick/pi) against Cattaneo-Mindlin c = a (1 - Q/(f P))^(1/3)
//! (Johnson 1985 eq. (7.39)).

use std::process::ExitCode;
use std::time::Instant;

use serde_json::json;
use tribo::kernels::hertz::HertzContact;
use tribo::solvers::tangential::{
    solve_tangential, tangential_compliance_operator, TangentialLoading, TangentialParams,
    TangentialProblem,
};
use tribo::{composite_modulus, ElasticMaterial, SurfaceGrid};

const USAGE: &str = "usage: tribo-bench-slip --n N [--ratio R]";

fn run() -> Result<serde_json::Value, String> {
    let (mut n, mut ratio) = (None, 0.5f64);
    let mut it = std::env::args().skip(1);
    while let Some(key) = it.next() {
        let mut value = || {
            it.next()
                .ok_or_else(|| format!("{key} needs a value\n{USAGE}"))
        };
        match key.as_str() {
            "--n" => n = Some(value()?.parse::<usize>().map_err(|e| format!("--n: {e}"))?),
            "--ratio" => ratio = value()?.parse().map_err(|e| format!("--ratio: {e}"))?,
            _ => return Err(format!("unknown argument {key:?}\n{USAGE}")),
        }
    }
    let n = n.ok_or_else(|| format!("--n is required\n{USAGE}"))?;
    if !(ratio > 0.0 && ratio < 1.0) {
        return Err(format!("--ratio must be in (0, 1)\n{USAGE}"));
    }
    let steel = ElasticMaterial::new(2.1e11, 0.3).map_err(|e| e.to_string())?;
    let e_star = composite_modulus(&steel, &steel);
    let (load, friction) = (2000.0, 0.3);
    let hertz = HertzContact::circle(0.01, e_star, load).map_err(|e| e.to_string())?;
    let a = hertz.semi_major;
    let grid = SurfaceGrid::centred(n, n, 1.2 * a, 1.2 * a).map_err(|e| e.to_string())?;
    let (hx, hy) = (0.5 * grid.dx(), 0.5 * grid.dy());
    let pressure = grid.sample(|x, y| hertz.mean_pressure_over_rectangle(x, y, hx, hy));
    let total: f64 = pressure.iter().sum::<f64>() * grid.dx() * grid.dy();
    let q = ratio * friction * total;
    let problem = TangentialProblem {
        grid: &grid,
        pressure: &pressure,
        friction,
        body1: steel,
        body2: steel,
        loading: TangentialLoading::Force {
            magnitude: q,
            angle: 0.0,
        },
        offset: None,
    };
    let start = Instant::now();
    let operator = tangential_compliance_operator(&grid, &steel, &steel, 0.0);
    let operator_seconds = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let solution = solve_tangential(
        &problem,
        &TangentialParams::default(),
        Some(&operator),
        None,
    )
    .map_err(|e| e.to_string())?;
    let seconds = start.elapsed().as_secs_f64();
    let stick_radius = (solution.stick_area / std::f64::consts::PI).sqrt();
    let expected = a * (1.0 - ratio).cbrt();
    Ok(json!({
        "code": "tribo",
        "n": n,
        "ratio": ratio,
        "operator_seconds": operator_seconds,
        "seconds": seconds,
        "iterations": solution.iterations,
        "residual": solution.residual,
        "stick_radius_over_a": stick_radius / a,
        "cattaneo_mindlin_over_a": expected / a,
        "stick_radius_error_in_elements": (stick_radius - expected) / grid.dx(),
    }))
}

fn main() -> ExitCode {
    match run() {
        Ok(v) => {
            println!("{v}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("{e}");
            ExitCode::from(2)
        }
    }
}
