//! Least-squares fitting: straight lines, linear models by QR (nalgebra), and a
//! Nelder–Mead simplex for the few nonlinear parameters of a separable model
//! (variable projection: Golub & Pereyra, SIAM J. Numer. Anal. 10 (1973) 413).

use nalgebra::{DMatrix, DVector};

/// Weighted least-squares straight line y ≈ slope·x + intercept.
/// Returns (slope, intercept).
pub fn line_fit(x: &[f64], y: &[f64], w: &[f64]) -> (f64, f64) {
    let sw: f64 = w.iter().sum();
    let mx = x.iter().zip(w).map(|(x, w)| w * x).sum::<f64>() / sw;
    let my = y.iter().zip(w).map(|(y, w)| w * y).sum::<f64>() / sw;
    let sxy: f64 = x
        .iter()
        .zip(y)
        .zip(w)
        .map(|((x, y), w)| w * (x - mx) * (y - my))
        .sum();
    let sxx: f64 = x.iter().zip(w).map(|(x, w)| w * (x - mx) * (x - mx)).sum();
    let slope = sxy / sxx;
    (slope, my - slope * mx)
}

/// Linear least squares: coefficients c minimising ‖Σ_j c_j·basis_j − y‖₂, with the
/// basis functions given as columns sampled at the data points. Solved by SVD so
/// that nearly collinear bases (two similar exponentials) stay well defined.
pub fn linear_least_squares(columns: &[Vec<f64>], y: &[f64]) -> Vec<f64> {
    let a = DMatrix::from_fn(y.len(), columns.len(), |i, j| columns[j][i]);
    let b = DVector::from_column_slice(y);
    let svd = a.svd(true, true);
    let c = svd
        .solve(&b, 1e-14)
        .unwrap_or_else(|_| DVector::zeros(columns.len()));
    c.iter().copied().collect()
}

/// Minimises f by the Nelder–Mead simplex (Lagarias et al., SIAM J. Optim. 9 (1998) 112,
/// standard coefficients 1, 2, ½, ½) from x0 with initial steps `step`.
/// Stops when the simplex's function values agree to `ftol` (absolute) or after
/// `max_evaluations`. Returns (x_best, f_best).
pub fn nelder_mead(
    f: impl Fn(&[f64]) -> f64,
    x0: &[f64],
    step: &[f64],
    ftol: f64,
    max_evaluations: usize,
) -> (Vec<f64>, f64) {
    let n = x0.len();
    let mut simplex: Vec<Vec<f64>> = vec![x0.to_vec()];
    for i in 0..n {
        let mut x = x0.to_vec();
        x[i] += step[i];
        simplex.push(x);
    }
    let mut values: Vec<f64> = simplex.iter().map(|x| f(x)).collect();
    let mut evaluations = n + 1;
    let point = |c: &[f64], w: &[f64], t: f64| -> Vec<f64> {
        c.iter().zip(w).map(|(c, w)| c + t * (w - c)).collect()
    };
    while evaluations < max_evaluations {
        let mut order: Vec<usize> = (0..=n).collect();
        order.sort_by(|&i, &j| values[i].total_cmp(&values[j]));
        simplex = order.iter().map(|&i| simplex[i].clone()).collect();
        values = order.iter().map(|&i| values[i]).collect();
        if (values[n] - values[0]).abs() <= ftol {
            break;
        }
        let centroid: Vec<f64> = (0..n)
            .map(|d| simplex[..n].iter().map(|x| x[d]).sum::<f64>() / n as f64)
            .collect();
        let reflected = point(&centroid, &simplex[n], -1.0);
        let fr = f(&reflected);
        evaluations += 1;
        if fr < values[0] {
            let expanded = point(&centroid, &simplex[n], -2.0);
            let fe = f(&expanded);
            evaluations += 1;
            if fe < fr {
                simplex[n] = expanded;
                values[n] = fe;
            } else {
                simplex[n] = reflected;
                values[n] = fr;
            }
        } else if fr < values[n - 1] {
            simplex[n] = reflected;
            values[n] = fr;
        } else {
            let (contracted, fc) = if fr < values[n] {
                let c = point(&centroid, &reflected, 0.5);
                let fc = f(&c);
                (c, fc)
            } else {
                let c = point(&centroid, &simplex[n], 0.5);
                let fc = f(&c);
                (c, fc)
            };
            evaluations += 1;
            if fc < values[n].min(fr) {
                simplex[n] = contracted;
                values[n] = fc;
            } else {
                for i in 1..=n {
                    simplex[i] = point(&simplex[0], &simplex[i], 0.5);
                    values[i] = f(&simplex[i]);
                }
                evaluations += n;
            }
        }
    }
    let best = (0..=n)
        .min_by(|&i, &j| values[i].total_cmp(&values[j]))
        .unwrap_or(0);
    (simplex[best].clone(), values[best])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_fit_recovers_a_line() {
        let x: Vec<f64> = (0..10).map(|i| i as f64).collect();
        let y: Vec<f64> = x.iter().map(|x| 3.0 * x - 2.0).collect();
        let (s, i) = line_fit(&x, &y, &[1.0; 10]);
        assert!((s - 3.0).abs() < 1e-12 && (i + 2.0).abs() < 1e-12);
    }

    #[test]
    fn linear_least_squares_recovers_coefficients() {
        let x: Vec<f64> = (0..20).map(|i| i as f64 / 10.0).collect();
        let c0: Vec<f64> = x.iter().map(|x| (-x).exp()).collect();
        let c1: Vec<f64> = x.iter().map(|x| (-3.0 * x).exp()).collect();
        let y: Vec<f64> = c0.iter().zip(&c1).map(|(a, b)| 2.0 * a + 0.5 * b).collect();
        let c = linear_least_squares(&[c0, c1], &y);
        assert!((c[0] - 2.0).abs() < 1e-10 && (c[1] - 0.5).abs() < 1e-10);
    }

    #[test]
    fn nelder_mead_finds_the_rosenbrock_minimum() {
        let rosen = |x: &[f64]| (1.0 - x[0]).powi(2) + 100.0 * (x[1] - x[0] * x[0]).powi(2);
        let (x, fx) = nelder_mead(rosen, &[-1.2, 1.0], &[0.1, 0.1], 1e-20, 10_000);
        assert!(fx < 1e-12, "{fx}");
        assert!((x[0] - 1.0).abs() < 1e-5 && (x[1] - 1.0).abs() < 1e-5);
    }
}
