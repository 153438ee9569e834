//! Gauss–Legendre quadrature.
//!
//! Nodes and weights are computed by Newton's method on the Legendre polynomial
//! P_n with Tricomi's initial guesses (Abramowitz & Stegun 25.4.29; Press et al.,
//! *Numerical Recipes*, 3rd ed., sect. 4.6), accurate to machine precision for n up to
//! several hundred.

/// The 4-point Gauss–Legendre rule on [−1, 1] as (node, weight), to 16 digits (Abramowitz &
/// Stegun, table 25.4): for rules applied millions of times (the drag along a roller).
/// Tested against [`GaussLegendre::new`].
pub const GAUSS_LEGENDRE_4: [(f64, f64); 4] = [
    (-0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
    (-0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
];

/// The 6-point Gauss–Legendre rule on [−1, 1] as (node, weight), to 15 digits (Abramowitz &
/// Stegun, table 25.4): the oil film along a roller. Tested against
/// [`GaussLegendre::new`].
pub const GAUSS_LEGENDRE_6: [(f64, f64); 6] = [
    (-0.932_469_514_203_152, 0.171_324_492_379_170),
    (-0.661_209_386_466_265, 0.360_761_573_048_139),
    (-0.238_619_186_083_197, 0.467_913_934_572_691),
    (0.238_619_186_083_197, 0.467_913_934_572_691),
    (0.661_209_386_466_265, 0.360_761_573_048_139),
    (0.932_469_514_203_152, 0.171_324_492_379_170),
];

/// A tabulated rule on [−1, 1] mapped to [−h, h]: (node, weight) pairs.
pub fn mapped_table(table: &[(f64, f64)], h: f64) -> Vec<(f64, f64)> {
    table.iter().map(|&(x, w)| (h * x, h * w)).collect()
}

/// An n-point Gauss–Legendre rule on [-1, 1].
#[derive(Debug, Clone, PartialEq)]
pub struct GaussLegendre {
    /// Abscissae in ascending order.
    pub nodes: Vec<f64>,
    /// Weights; they add up to 2.
    pub weights: Vec<f64>,
}

impl GaussLegendre {
    /// Builds the n-point rule (n ≥ 1).
    pub fn new(n: usize) -> Self {
        assert!(n >= 1, "a Gauss–Legendre rule needs at least one node");
        let mut nodes = vec![0.0; n];
        let mut weights = vec![0.0; n];
        let nf = n as f64;
        for i in 0..n.div_ceil(2) {
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (p, d) = legendre_with_derivative(n, x);
                dp = d;
                let dx = p / d;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            let (_, d) = legendre_with_derivative(n, x);
            dp = if d != 0.0 { d } else { dp };
            let w = 2.0 / ((1.0 - x * x) * dp * dp);
            nodes[i] = -x;
            nodes[n - 1 - i] = x;
            weights[i] = w;
            weights[n - 1 - i] = w;
        }
        if n % 2 == 1 {
            nodes[n / 2] = 0.0;
        }
        Self { nodes, weights }
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// True for an empty rule (never, by construction).
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Nodes and weights mapped from [-1, 1] to [a, b].
    pub fn mapped(&self, a: f64, b: f64) -> (Vec<f64>, Vec<f64>) {
        let half = 0.5 * (b - a);
        let mid = 0.5 * (b + a);
        let x = self.nodes.iter().map(|t| mid + half * t).collect();
        let w = self.weights.iter().map(|w| half * w).collect();
        (x, w)
    }

    /// ∫_a^b f(x) dx by this rule.
    pub fn integrate(&self, a: f64, b: f64, f: impl Fn(f64) -> f64) -> f64 {
        let half = 0.5 * (b - a);
        let mid = 0.5 * (b + a);
        half * self
            .nodes
            .iter()
            .zip(&self.weights)
            .map(|(t, w)| w * f(mid + half * t))
            .sum::<f64>()
    }
}

/// P_n(x) and P_n'(x) by the three-term recurrence.
fn legendre_with_derivative(n: usize, x: f64) -> (f64, f64) {
    let mut p0 = 1.0;
    let mut p1 = x;
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=n {
        let kf = k as f64;
        let p2 = ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf;
        p0 = p1;
        p1 = p2;
    }
    let d = n as f64 * (x * p1 - p0) / (x * x - 1.0);
    (p1, d)
}

/// ∫_a^b f by composite Gauss–Legendre on `panels` equal panels of 20 nodes each,
/// doubling the panel count until two results agree to `rtol` (relative, with an
/// absolute floor of `rtol·1e-300`). A slow, sure reference integrator for tests and
/// one-off fits, not for the hot path.
pub fn integrate_converged(a: f64, b: f64, rtol: f64, f: impl Fn(f64) -> f64) -> f64 {
    let rule = GaussLegendre::new(20);
    let composite = |panels: usize| -> f64 {
        let h = (b - a) / panels as f64;
        (0..panels)
            .map(|k| {
                let lo = a + k as f64 * h;
                rule.integrate(lo, lo + h, &f)
            })
            .sum()
    };
    let mut panels = 1;
    let mut previous = composite(panels);
    loop {
        panels *= 2;
        let current = composite(panels);
        if (current - previous).abs() <= rtol * current.abs().max(1e-300) || panels >= 1 << 14 {
            return current;
        }
        previous = current;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_add_up_to_two_and_polynomials_are_exact() {
        // An n-point rule integrates polynomials of degree 2n-1 exactly
        // (Abramowitz & Stegun 25.4.29).
        for n in 1..=40 {
            let g = GaussLegendre::new(n);
            let s: f64 = g.weights.iter().sum();
            assert!((s - 2.0).abs() < 1e-13, "n={n}: {s}");
            // ∫_{-1}^{1} x^(2n-2) dx = 2/(2n-1): the highest even degree the rule must get right.
            let power = 2 * n - 2;
            let num = g.integrate(-1.0, 1.0, |x| x.powi(power as i32));
            let exact = 2.0 / (power as f64 + 1.0);
            assert!((num - exact).abs() < 1e-12, "n={n}: {num} vs {exact}");
        }
    }

    #[test]
    fn known_five_point_rule() {
        // A&S table 25.4: n = 5, x = 0.906179845938664, w = 0.236926885056189.
        let g = GaussLegendre::new(5);
        assert!((g.nodes[4] - 0.906_179_845_938_664).abs() < 1e-14);
        assert!((g.weights[4] - 0.236_926_885_056_189).abs() < 1e-14);
        assert!((g.weights[2] - 128.0 / 225.0).abs() < 1e-14);
    }

    #[test]
    fn converged_integral_of_a_sqrt_edge() {
        // ∫_0^1 sqrt(1 - x²) dx = π/4: the Hertzian edge singularity.
        let v = integrate_converged(0.0, 1.0, 1e-10, |x| (1.0 - x * x).max(0.0).sqrt());
        assert!((v - std::f64::consts::FRAC_PI_4).abs() < 1e-8);
    }
}

#[cfg(test)]
mod table_tests {
    use super::*;

    /// The tabulated rules are the computed ones to their printed digits.
    #[test]
    fn tabulated_rules_match_the_computed_ones() {
        for (table, tol) in [
            (&GAUSS_LEGENDRE_4[..], 1e-15),
            (&GAUSS_LEGENDRE_6[..], 1e-14),
        ] {
            let (x, w) = GaussLegendre::new(table.len()).mapped(-1.0, 1.0);
            for (k, &(xt, wt)) in table.iter().enumerate() {
                assert!((x[k] - xt).abs() < tol && (w[k] - wt).abs() < tol, "{k}");
            }
        }
    }
}
