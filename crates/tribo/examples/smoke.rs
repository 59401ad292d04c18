//! Quick timing of the paper's case: `cargo run --release -p tribo --example smoke -- N`.
use tribo::solvers::normal::*;
use tribo::SurfaceGrid;
fn main() -> Result<(), tribo::Error> {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(21);
    let a = 5.2964e-4;
    let grid = SurfaceGrid::centred(n, n, 1.5 * a, 1.5 * a)?;
    let h = grid.sample(|x, y| 50.0 * x * x + 60.0 * y * y);
    let t = std::time::Instant::now();
    let op = normal_compliance_operator(&grid, 1.10440e11);
    let build = t.elapsed().as_secs_f64();
    let problem = NormalContactProblem {
        grid: &grid,
        initial_gap: &h,
        composite_modulus: 1.10440e11,
        loading: NormalLoading::Force(2000.0),
    };
    let s = solve_normal(&problem, &NormalContactParams::default(), Some(&op), None)?;
    println!(
        "n={n} build={build:.3}s total={:.3}s it={} res={:.2e} delta={:.6e} pmax={:.6e}",
        t.elapsed().as_secs_f64(),
        s.iterations,
        s.residual,
        s.approach,
        s.max_pressure()
    );
    Ok(())
}
