//! Quick timing of the paper's case: `cargo run --release -p tribo --example smoke -- N`.
use tribo::solvers::normal::*;
use tribo::SurfaceGrid;
fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(21);
    let a = 5.2964e-4;
    let grid = SurfaceGrid::centred(n, n, 1.5 * a, 1.5 * a).expect("grid");
    let h = grid.sample(|x, y| 50.0 * x * x + 60.0 * y * y);
    let t = std::time::Instant::now();
    let op = normal_compliance_operator(&grid, 1.10440e11);
    let mut ws = op.workspace();
    let build = t.elapsed().as_secs_f64();
    let mut applies = 0usize;
    let s = solve_normal_cg_with(
        &op,
        &mut ws,
        &h,
        NormalLoading::Force(2000.0),
        &NormalContactParams::default(),
        &mut |_, _| applies += 1,
    )
    .expect("solve");
    println!(
        "n={n} build={build:.3}s total={:.3}s it={} res={:.2e} delta={:.6e} pmax={:.6e}",
        t.elapsed().as_secs_f64(),
        s.iterations,
        s.residual,
        s.approach,
        s.max_pressure()
    );
}
