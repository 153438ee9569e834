//! Interpolation on equally spaced nodes.

/// Cubic Lagrange weights on the nodes −1, 0, 1, 2 at t (t in [0, 1] between the middle
/// two): exact for cubics, error O(h⁴) for smooth functions.
#[inline]
pub fn lagrange_weights(t: f64) -> [f64; 4] {
    let (tm1, tp1, tm2) = (t - 1.0, t + 1.0, t - 2.0);
    [
        -t * tm1 * tm2 / 6.0,
        tp1 * tm1 * tm2 / 2.0,
        -tp1 * t * tm2 / 2.0,
        tp1 * t * tm1 / 6.0,
    ]
}

/// Tensor-product cubic Lagrange interpolation in a table of n_x × n_y values (value
/// (i, j) at index i·n_y + j) at grid coordinates (x, y), counted in steps from the first
/// node. The 4 × 4 stencil is the one around (x, y), moved inwards at the table's edges
/// (n_x, n_y ≥ 4); the caller decides where the table holds.
#[inline]
pub fn bicubic(values: &[f64], n_x: usize, n_y: usize, x: f64, y: f64) -> f64 {
    let i = (x.max(0.0) as usize).clamp(1, n_x - 3);
    let j = (y.max(0.0) as usize).clamp(1, n_y - 3);
    let (wx, wy) = (
        lagrange_weights(x - i as f64),
        lagrange_weights(y - j as f64),
    );
    let mut sum = 0.0;
    for (a, wa) in wx.iter().enumerate() {
        let start = (i - 1 + a) * n_y + j - 1;
        let r = &values[start..start + 4];
        sum += wa * (wy[0] * r[0] + wy[1] * r[1] + wy[2] * r[2] + wy[3] * r[3]);
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// A cubic is reproduced exactly (to round-off), anywhere between the middle nodes.
        #[test]
        fn cubics_are_exact(t in 0.0..1.0f64, c in prop::array::uniform4(-10.0..10.0f64)) {
            let f = |x: f64| c[0] + x * (c[1] + x * (c[2] + x * c[3]));
            let w = lagrange_weights(t);
            let v: f64 = (0..4).map(|k| w[k] * f(k as f64 - 1.0)).sum();
            prop_assert!((v - f(t)).abs() < 1e-11, "{v} vs {}", f(t));
        }

        /// A product of cubics in x and y is reproduced exactly anywhere in a 6 × 7 table,
        /// its edge cells included, where the stencil moves inwards (x < 1 or ≥ 3,
        /// y < 1 or ≥ 4): a cubic's Lagrange interpolation is the cubic itself.
        #[test]
        fn bicubic_reproduces_bicubics(
            x in 0.0..5.0f64,
            y in 0.0..6.0f64,
            c in prop::array::uniform4(-3.0..3.0f64),
            d in prop::array::uniform4(-3.0..3.0f64),
        ) {
            let f = |x: f64, y: f64| {
                (c[0] + x * (c[1] + x * (c[2] + x * c[3])))
                    * (d[0] + y * (d[1] + y * (d[2] + y * d[3])))
            };
            let values: Vec<f64> =
                (0..6).flat_map(|i| (0..7).map(move |j| f(i as f64, j as f64))).collect();
            let v = bicubic(&values, 6, 7, x, y);
            prop_assert!((v - f(x, y)).abs() < 1e-9 * (1.0 + f(x, y).abs()), "{v} vs {}", f(x, y));
        }
    }
}
