//! Bracketed scalar root finding (Brent's method; Brent, *Algorithms for Minimization
//! without Derivatives*, 1973, ch. 4). Used where a model must be inverted, e.g. Tripp's
//! load–deflection law (eq. 9, 10) or the exact Hertz ellipticity.

use crate::error::{Error, Result};

/// Finds x in [a, b] with f(x) = 0 to an absolute tolerance `xtol`.
/// f(a) and f(b) must have opposite signs (or one be zero).
pub fn brent(mut a: f64, mut b: f64, xtol: f64, f: impl Fn(f64) -> f64) -> Result<f64> {
    let mut fa = f(a);
    let mut fb = f(b);
    if fa == 0.0 {
        return Ok(a);
    }
    if fb == 0.0 {
        return Ok(b);
    }
    if !(fa.is_finite() && fb.is_finite()) || fa.signum() == fb.signum() {
        return Err(Error::NoConvergence {
            what: "bracketed root search",
            detail: format!("no sign change on [{a}, {b}]: f = {fa}, {fb}"),
        });
    }
    let (mut c, mut fc) = (a, fa);
    let mut d = b - a;
    let mut e = d;
    for _ in 0..200 {
        if fb.signum() == fc.signum() {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol = 2.0 * f64::EPSILON * b.abs() + 0.5 * xtol;
        let m = 0.5 * (c - b);
        if m.abs() <= tol || fb == 0.0 {
            return Ok(b);
        }
        if e.abs() >= tol && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q) = if a == c {
                (2.0 * m * s, 1.0 - s)
            } else {
                let q = fa / fc;
                let r = fb / fc;
                (
                    s * (2.0 * m * q * (q - r) - (b - a) * (r - 1.0)),
                    (q - 1.0) * (r - 1.0) * (s - 1.0),
                )
            };
            if p > 0.0 {
                q = -q;
            } else {
                p = -p;
            }
            if 2.0 * p < (3.0 * m * q - (tol * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = m;
                e = m;
            }
        } else {
            d = m;
            e = m;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol { d } else { tol.copysign(m) };
        fb = f(b);
    }
    Err(Error::NoConvergence {
        what: "Brent root search",
        detail: "200 iterations".into(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_roots_of_known_functions() {
        let r = brent(0.0, 2.0, 1e-14, |x| x * x - 2.0).unwrap();
        assert!((r - std::f64::consts::SQRT_2).abs() < 1e-13);
        let r = brent(0.0, 1.0, 1e-14, |x| x.cos() - x).unwrap();
        assert!((r - 0.739_085_133_215_160_6).abs() < 1e-13);
    }

    #[test]
    fn refuses_a_bracket_without_sign_change() {
        assert!(brent(0.0, 1.0, 1e-12, |x| x * x + 1.0).is_err());
    }
}
