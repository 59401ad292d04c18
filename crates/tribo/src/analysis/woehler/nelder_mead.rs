//! A derivative-free minimiser: the Nelder-Mead simplex method (Nelder & Mead 1965, Computer
//! Journal 7, 308-313) with the standard coefficients reflection 1, expansion 2, contraction
//! 1/2, shrink 1/2 and the ordering rules of Lagarias et al. (1998, SIAM J. Optim. 9, 112-147).
//! After convergence the simplex is rebuilt around the best point and the search restarted,
//! which guards against a collapsed simplex (a known failure of the method, McKinnon 1998);
//! the run is converged when a restart no longer improves the objective by more than the
//! tolerance. Non-finite objective values count as +infinity (points outside the domain).

/// Options of [`minimize`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NelderMeadOptions {
    /// Maximum iterations, all restarts together.
    pub max_iterations: usize,
    /// Tolerance on the spread max |f_i - f_best| over the simplex (objective units).
    pub f_tolerance: f64,
    /// Tolerance on the simplex size max |x_i - x_best| (parameter units, infinity norm).
    pub x_tolerance: f64,
    /// Restarts around the best point after the first convergence.
    pub max_restarts: usize,
}

impl Default for NelderMeadOptions {
    fn default() -> Self {
        Self {
            max_iterations: 20_000,
            f_tolerance: 1e-10,
            x_tolerance: 1e-8,
            max_restarts: 5,
        }
    }
}

/// The outcome of [`minimize`], with its convergence record.
#[derive(Debug, Clone, PartialEq)]
pub struct Minimum {
    /// The best point found.
    pub x: Vec<f64>,
    /// The objective there.
    pub f: f64,
    /// Iterations done (all restarts).
    pub iterations: usize,
    /// Objective evaluations.
    pub evaluations: usize,
    /// Restarts done.
    pub restarts: usize,
    /// Final spread of the objective over the simplex.
    pub f_spread: f64,
    /// Whether the tolerances were met within `max_iterations`.
    pub converged: bool,
}

fn eval(f: &mut impl FnMut(&[f64]) -> f64, x: &[f64], count: &mut usize) -> f64 {
    *count += 1;
    let v = f(x);
    if v.is_finite() {
        v
    } else {
        f64::INFINITY
    }
}

/// Minimise `f` from `x0`; the initial simplex is `x0` and `x0 + steps[i] e_i`.
pub fn minimize(
    mut f: impl FnMut(&[f64]) -> f64,
    x0: &[f64],
    steps: &[f64],
    options: &NelderMeadOptions,
) -> Minimum {
    let n = x0.len();
    let mut evaluations = 0;
    let mut iterations = 0;
    let mut restarts = 0;
    let mut best = x0.to_vec();
    let mut best_f = eval(&mut f, x0, &mut evaluations);
    let mut f_spread = f64::INFINITY;
    let mut converged;
    loop {
        // Build the simplex around `best`.
        let mut simplex: Vec<Vec<f64>> = vec![best.clone()];
        let mut values = vec![best_f];
        for i in 0..n {
            let mut x = best.clone();
            x[i] += steps[i];
            values.push(eval(&mut f, &x, &mut evaluations));
            simplex.push(x);
        }
        let start_f = best_f;
        let mut this_converged = false;
        while iterations < options.max_iterations {
            // Order: best first.
            let mut order: Vec<usize> = (0..=n).collect();
            order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
            simplex = order.iter().map(|&i| simplex[i].clone()).collect();
            values = order.iter().map(|&i| values[i]).collect();
            f_spread = values[1..]
                .iter()
                .map(|v| (v - values[0]).abs())
                .fold(0.0, f64::max);
            let x_size = simplex[1..]
                .iter()
                .flat_map(|x| x.iter().zip(&simplex[0]).map(|(a, b)| (a - b).abs()))
                .fold(0.0, f64::max);
            if f_spread <= options.f_tolerance && x_size <= options.x_tolerance {
                this_converged = true;
                break;
            }
            iterations += 1;
            let centroid: Vec<f64> = (0..n)
                .map(|j| simplex[..n].iter().map(|x| x[j]).sum::<f64>() / n as f64)
                .collect();
            let worst = &simplex[n];
            let along = |t: f64| -> Vec<f64> {
                centroid
                    .iter()
                    .zip(worst)
                    .map(|(c, w)| c + t * (c - w))
                    .collect()
            };
            let xr = along(1.0);
            let fr = eval(&mut f, &xr, &mut evaluations);
            if fr < values[0] {
                let xe = along(2.0);
                let fe = eval(&mut f, &xe, &mut evaluations);
                if fe < fr {
                    simplex[n] = xe;
                    values[n] = fe;
                } else {
                    simplex[n] = xr;
                    values[n] = fr;
                }
                continue;
            }
            if fr < values[n - 1] {
                simplex[n] = xr;
                values[n] = fr;
                continue;
            }
            // Contraction: outside if the reflected point beats the worst, else inside.
            let (xc, fc) = if fr < values[n] {
                let xc = along(0.5);
                let fc = eval(&mut f, &xc, &mut evaluations);
                (xc, fc)
            } else {
                let xc = along(-0.5);
                let fc = eval(&mut f, &xc, &mut evaluations);
                (xc, fc)
            };
            if fc < fr.min(values[n]) {
                simplex[n] = xc;
                values[n] = fc;
                continue;
            }
            // Shrink towards the best point.
            for i in 1..=n {
                let x: Vec<f64> = simplex[i]
                    .iter()
                    .zip(&simplex[0])
                    .map(|(a, b)| b + 0.5 * (a - b))
                    .collect();
                values[i] = eval(&mut f, &x, &mut evaluations);
                simplex[i] = x;
            }
        }
        let k = (0..=n)
            .min_by(|&a, &b| values[a].total_cmp(&values[b]))
            .unwrap_or(0);
        best = simplex[k].clone();
        best_f = values[k];
        converged = this_converged;
        if !this_converged
            || (start_f - best_f).abs() <= options.f_tolerance
            || restarts >= options.max_restarts
        {
            break;
        }
        restarts += 1;
    }
    Minimum {
        x: best,
        f: best_f,
        iterations,
        evaluations,
        restarts,
        f_spread,
        converged,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_rosenbrock_minimum() {
        // Rosenbrock's valley, minimum 0 at (1, 1): a classic hard case for simplex methods.
        let rosen = |x: &[f64]| 100.0 * (x[1] - x[0] * x[0]).powi(2) + (1.0 - x[0]).powi(2);
        let m = minimize(
            rosen,
            &[-1.2, 1.0],
            &[0.1, 0.1],
            &NelderMeadOptions::default(),
        );
        assert!(m.converged);
        // x tolerance 1e-8 on the simplex; the valley is flat along its floor, so the point is
        // known to ~1e-5 (f ~ 1e-10 there): 1e-4 is safely above that, far below a wrong answer.
        assert!(
            (m.x[0] - 1.0).abs() < 1e-4 && (m.x[1] - 1.0).abs() < 1e-4,
            "{m:?}"
        );
    }

    #[test]
    fn reports_non_convergence() {
        let m = minimize(
            |x: &[f64]| x.iter().map(|v| v * v).sum(),
            &[3.0, 4.0, 5.0],
            &[1.0, 1.0, 1.0],
            &NelderMeadOptions {
                max_iterations: 5,
                ..Default::default()
            },
        );
        assert!(!m.converged);
        assert_eq!(m.iterations, 5);
    }
}
