//! Gauss-Legendre quadrature nodes and weights (crate-internal helper of the kernels).
//!
//! Nodes are the roots of the Legendre polynomial P_n, found by Newton's method from the
//! Tricomi-type initial guess cos(pi (i - 1/4) / (n + 1/2)); weights
//! w_i = 2 / ((1 - x_i^2) P_n'(x_i)^2) (Abramowitz & Stegun 1964, 25.4.29; Press et al.,
//! *Numerical Recipes*, sec. 4.6). An n-point rule integrates polynomials of degree 2n - 1
//! exactly on [-1, 1].

/// `(nodes, weights)` of the n-point Gauss-Legendre rule on [-1, 1], nodes ascending.
/// `n = 0` gives empty vectors.
pub(crate) fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut nodes = vec![0.0; n];
    let mut weights = vec![0.0; n];
    let nf = n as f64;
    for i in 0..n.div_ceil(2) {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
        let mut derivative = 1.0;
        for _ in 0..100 {
            // Three-term recurrence for P_n(x) and P_{n-1}(x).
            let (mut p_prev, mut p) = (1.0_f64, x);
            for j in 2..=n {
                let jf = j as f64;
                let p_next = ((2.0 * jf - 1.0) * x * p - (jf - 1.0) * p_prev) / jf;
                p_prev = p;
                p = p_next;
            }
            derivative = nf * (x * p - p_prev) / (x * x - 1.0);
            let step = p / derivative;
            x -= step;
            if step.abs() <= 1e-16 {
                break;
            }
        }
        let weight = 2.0 / ((1.0 - x * x) * derivative * derivative);
        nodes[i] = -x;
        nodes[n - 1 - i] = x;
        weights[i] = weight;
        weights[n - 1 - i] = weight;
    }
    (nodes, weights)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integrates_polynomials_exactly() {
        for n in [1, 2, 5, 12, 16, 20] {
            let (x, w) = gauss_legendre(n);
            let total: f64 = w.iter().sum();
            assert!((total - 2.0).abs() < 1e-14, "n = {n}: {total}");
            // int_{-1}^{1} t^(2n-2) dt = 2 / (2n - 1): exact for the rule (degree <= 2n - 1).
            let d = 2 * n as i32 - 2;
            let q: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(d)).sum();
            assert!((q - 2.0 / (d as f64 + 1.0)).abs() < 1e-14, "n = {n}: {q}");
        }
    }
}
