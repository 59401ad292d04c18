//! Exactly rounded summation, so that integrals over a mesh do not depend on the order of
//! the cells nor on how rayon splits the work.

/// A running sum kept exactly as a list of non-overlapping partials (Shewchuk 1997,
/// "Adaptive precision floating-point arithmetic", Discrete Comput. Geom. 18:305; the
/// algorithm of Python's `math.fsum`). [`ExactSum::value`] is the correctly rounded value of
/// the exact sum of the finite terms added, so the result is the same bit for bit whatever
/// the order of the terms and however partial sums are merged.
#[derive(Debug, Clone, Default)]
pub(crate) struct ExactSum {
    partials: Vec<f64>,
}

impl ExactSum {
    /// Add one finite term.
    pub(crate) fn add(&mut self, term: f64) {
        let mut x = term;
        let mut kept = 0;
        for j in 0..self.partials.len() {
            let mut y = self.partials[j];
            if x.abs() < y.abs() {
                std::mem::swap(&mut x, &mut y);
            }
            let hi = x + y;
            let lo = y - (hi - x);
            if lo != 0.0 {
                self.partials[kept] = lo;
                kept += 1;
            }
            x = hi;
        }
        self.partials.truncate(kept);
        self.partials.push(x);
    }

    /// Add every term of another exact sum (exactly).
    pub(crate) fn merge(&mut self, other: &ExactSum) {
        for &p in &other.partials {
            self.add(p);
        }
    }

    /// The correctly rounded (round half to even) value of the sum.
    pub(crate) fn value(&self) -> f64 {
        let p = &self.partials;
        let mut n = p.len();
        if n == 0 {
            return 0.0;
        }
        n -= 1;
        let mut hi = p[n];
        let mut lo = 0.0;
        while n > 0 {
            let x = hi;
            n -= 1;
            let y = p[n];
            hi = x + y;
            let yr = hi - x;
            lo = y - yr;
            if lo != 0.0 {
                break;
            }
        }
        // Half-way case: make the rounding of hi + lo + (the rest) correct.
        if n > 0 && ((lo < 0.0 && p[n - 1] < 0.0) || (lo > 0.0 && p[n - 1] > 0.0)) {
            let y = lo * 2.0;
            let x = hi + y;
            let yr = x - hi;
            if y == yr {
                hi = x;
            }
        }
        hi
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_sum_is_exact_and_order_free() {
        // 1e16 + 1 - 1e16 is 0 in naive summation and 1 exactly.
        let mut s = ExactSum::default();
        for t in [1e16, 1.0, -1e16] {
            s.add(t);
        }
        assert_eq!(s.value(), 1.0);
        // Many terms of mixed magnitude: any order and any split give the same bits.
        let terms: Vec<f64> = (0..2000)
            .map(|i| ((i * 7919 % 1000) as f64 - 500.0) * 10f64.powi((i % 17) - 8) / 3.0)
            .collect();
        let mut forward = ExactSum::default();
        terms.iter().for_each(|&t| forward.add(t));
        let mut backward = ExactSum::default();
        terms.iter().rev().for_each(|&t| backward.add(t));
        let (mut a, mut b) = (ExactSum::default(), ExactSum::default());
        terms[..777].iter().for_each(|&t| a.add(t));
        terms[777..].iter().for_each(|&t| b.add(t));
        b.merge(&a);
        assert_eq!(forward.value().to_bits(), backward.value().to_bits());
        assert_eq!(forward.value().to_bits(), b.value().to_bits());
    }
}
