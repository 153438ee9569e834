//! The polynomial machinery of the circle–circle distance ([`super`], Eberly sect. 5.4):
//! polynomials of degree ≤ 8 in c = cos s and trigonometric polynomials reduced with
//! σ² = 1 − c² (for G and its σ-free product p of (E5)), and the real roots of p on the
//! pieces of [−1, 1] by subdivision of its Bernstein form, each polished by bracketed
//! Newton (steps 2 and 3 of the search in the parent module's doc).

use std::f64::consts::FRAC_1_SQRT_2;

/// A polynomial of degree ≤ 8, ascending coefficients.
#[derive(Debug, Clone, Copy)]
pub(super) struct Poly {
    pub(super) c: [f64; 9],
    pub(super) deg: usize,
}

impl Poly {
    pub(super) fn new(coefs: &[f64]) -> Self {
        let mut c = [0.0; 9];
        let n = coefs.len().min(9);
        c[..n].copy_from_slice(&coefs[..n]);
        Poly {
            c,
            deg: n.saturating_sub(1),
        }
    }

    pub(super) fn mul(&self, o: &Poly) -> Poly {
        let mut c = [0.0; 9];
        for i in 0..=self.deg {
            for j in 0..=o.deg {
                if i + j < 9 {
                    c[i + j] += self.c[i] * o.c[j];
                }
            }
        }
        Poly {
            c,
            deg: (self.deg + o.deg).min(8),
        }
    }

    pub(super) fn lin(&self, a: f64, o: &Poly, b: f64) -> Poly {
        let mut c = [0.0; 9];
        for (k, ck) in c.iter_mut().enumerate() {
            *ck = a * self.c[k] + b * o.c[k];
        }
        Poly {
            c,
            deg: self.deg.max(o.deg),
        }
    }

    /// (1 − c²) · self.
    pub(super) fn one_minus_sq(&self) -> Poly {
        let mut c = [0.0; 9];
        let deg = (self.deg + 2).min(8);
        for (k, ck) in c.iter_mut().enumerate().take(deg + 1) {
            let lo = if k <= self.deg { self.c[k] } else { 0.0 };
            let hi = if k >= 2 { self.c[k - 2] } else { 0.0 };
            *ck = lo - hi;
        }
        Poly { c, deg }
    }

    pub(super) fn eval(&self, x: f64) -> f64 {
        let mut v = self.c[self.deg];
        for k in (0..self.deg).rev() {
            v = v * x + self.c[k];
        }
        v
    }

    pub(super) fn eval_d(&self, x: f64) -> (f64, f64) {
        let mut v = self.c[self.deg];
        let mut d = 0.0;
        for k in (0..self.deg).rev() {
            d = d * x + v;
            v = v * x + self.c[k];
        }
        (v, d)
    }

    /// Σ |cₖ xᵏ|, the magnitude against which a value of the polynomial is rounding.
    pub(super) fn abs_eval(&self, x: f64) -> f64 {
        let ax = x.abs();
        let mut v = self.c[self.deg].abs();
        for k in (0..self.deg).rev() {
            v = v * ax + self.c[k].abs();
        }
        v
    }

    pub(super) fn abs_sum(&self) -> f64 {
        self.c[..=self.deg].iter().map(|x| x.abs()).sum()
    }
}

/// A trigonometric polynomial reduced with σ² = 1 − c²: value e(c) + σ o(c).
#[derive(Debug, Clone, Copy)]
pub(super) struct TrigPoly {
    pub(super) e: Poly,
    pub(super) o: Poly,
}

impl TrigPoly {
    pub(super) fn mul(&self, b: &TrigPoly) -> TrigPoly {
        TrigPoly {
            e: self
                .e
                .mul(&b.e)
                .lin(1.0, &self.o.mul(&b.o).one_minus_sq(), 1.0),
            o: self.e.mul(&b.o).lin(1.0, &self.o.mul(&b.e), 1.0),
        }
    }

    pub(super) fn lin(&self, a: f64, b: &TrigPoly, bb: f64) -> TrigPoly {
        TrigPoly {
            e: self.e.lin(a, &b.e, bb),
            o: self.o.lin(a, &b.o, bb),
        }
    }

    pub(super) fn abs_sum(&self) -> f64 {
        self.e.abs_sum() + self.o.abs_sum()
    }

    /// The σ-free product (e + σo)(e − σo) = e² − (1 − c²) o² (E5).
    pub(super) fn eliminate(&self) -> Poly {
        self.e
            .mul(&self.e)
            .lin(1.0, &self.o.mul(&self.o).one_minus_sq(), -1.0)
    }
}

/// The root of `q` in [a, b], the only one there, q(a) and q(b) of opposite signs, from
/// the first guess `x`: Newton's method safeguarded by bisection whenever a Newton step
/// would leave the bracket or fails to halve the step before last (`rtsafe` of Press et
/// al., *Numerical Recipes*, sect. 9.4).
fn bracketed_root(q: &Poly, mut a: f64, mut b: f64, a_negative: bool, mut x: f64) -> f64 {
    // Absolute tolerance on [−1, 1]; with quadratic convergence the point returned after
    // such a step is far more accurate, and candidates are polished on F afterwards.
    const TOL: f64 = 1e-10;
    if !(x > a && x < b) {
        x = 0.5 * (a + b);
    }
    let mut dx_old = b - a;
    let mut dx = dx_old;
    for _ in 0..100 {
        let (f, df) = q.eval_d(x);
        if f == 0.0 {
            return x;
        }
        if (f < 0.0) == a_negative {
            a = x;
        } else {
            b = x;
        }
        let newton = x - f / df;
        dx_old = std::mem::replace(&mut dx, f / df);
        if newton > a && newton < b && (2.0 * f).abs() <= (dx_old * df).abs() {
            x = newton;
        } else {
            dx = 0.5 * (b - a);
            x = a + dx;
        }
        if dx.abs() <= TOL {
            return x;
        }
    }
    x
}

/// Number of pieces of [−1, 1] (in c = cos s) on which the Bernstein forms start: the
/// cosines of equally spaced angles, so that each piece is an arc of π/8 on either half
/// of the circle.
pub(super) const PIECES: usize = 8;
/// The ends cₖ = −cos(kπ/8) of the pieces and sin sₖ = √(1 − cₖ²).
pub(super) const PIECE_ENDS: [(f64, f64); PIECES + 1] = [
    (-1.0, 0.0),
    (-0.9238795325112867, 0.3826834323650898),
    (-FRAC_1_SQRT_2, FRAC_1_SQRT_2),
    (-0.3826834323650898, 0.9238795325112867),
    (0.0, 1.0),
    (0.3826834323650898, 0.9238795325112867),
    (FRAC_1_SQRT_2, FRAC_1_SQRT_2),
    (0.9238795325112867, 0.3826834323650898),
    (1.0, 0.0),
];
/// Length of the arc of each piece (an upper bound).
pub(super) const PIECE_ARC: f64 = std::f64::consts::PI / PIECES as f64 * (1.0 + 1e-12);

/// For each piece [l, h] of [−1, 1], the matrix (indexed [k][i]) taking the monomial
/// coefficients of a polynomial of degree ≤ 8 to its Bernstein coefficients on [l, h]:
/// the coefficient of B₈,ᵢ in cᵏ is the blossom of cᵏ at (l⁸⁻ⁱ, hⁱ), i.e.
/// Σⱼ C(i, j) C(8 − i, k − j) hʲ lᵏ⁻ʲ / C(8, k).
static BERNSTEIN: [[[f64; 9]; 9]; PIECES] = bernstein_matrices();

const fn binomial(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    let mut r = 1.0;
    let mut j = 0;
    while j < k {
        r = r * (n - j) as f64 / (j + 1) as f64;
        j += 1;
    }
    r
}

const fn powi(x: f64, n: usize) -> f64 {
    let mut r = 1.0;
    let mut j = 0;
    while j < n {
        r *= x;
        j += 1;
    }
    r
}

const fn bernstein_matrices() -> [[[f64; 9]; 9]; PIECES] {
    let mut m = [[[0.0; 9]; 9]; PIECES];
    let mut piece = 0;
    while piece < PIECES {
        let lo = PIECE_ENDS[piece].0;
        let hi = PIECE_ENDS[piece + 1].0;
        let mut i = 0;
        while i <= 8 {
            let mut k = 0;
            while k <= 8 {
                let mut sum = 0.0;
                let mut j = 0;
                while j <= k {
                    sum += binomial(i, j) * binomial(8 - i, k - j) * powi(hi, j) * powi(lo, k - j);
                    j += 1;
                }
                m[piece][k][i] = sum / binomial(8, k);
                k += 1;
            }
            i += 1;
        }
        piece += 1;
    }
    m
}

/// Real roots of `p` (degree ≤ 8) on the pieces of [−1, 1] flagged in `active`, by
/// subdivision of its Bernstein form (Descartes' rule of signs for the Bernstein basis:
/// no sign change in the coefficients means no root, exactly one means exactly one root,
/// bracketed for [`bracketed_root`]). Coefficients within rounding of zero (relative to
/// `size`, the magnitude of p) count as possible roots, so a double or nearly double root
/// (no sign change, e.g. from mirror-symmetric pairs ±s) ends in an interval narrower
/// than `MIN_WIDTH`, whose midpoint is reported as a root candidate too (flagged `true`).
/// Returns the number of values written to `out`, ascending.
pub(super) fn roots_on_pieces(
    p: &Poly,
    active: &[bool; PIECES],
    size: f64,
    out: &mut [(f64, bool); 12],
) -> usize {
    const MIN_WIDTH: f64 = 2e-5; // in c; candidates are polished on F afterwards
    const STACK: usize = 24;
    // Depth-first over intervals: Bernstein coefficients and (start, width) in c.
    let mut coef = [[0.0f64; 9]; STACK];
    let mut span = [(0.0f64, 0.0f64); STACK];
    let mut size = size;
    let mut depth = 0;
    // Pushed in reverse so that the pieces are processed in ascending order.
    for piece in (0..PIECES).rev() {
        if !active[piece] {
            continue;
        }
        let b = &mut coef[depth];
        for (column, &a) in BERNSTEIN[piece].iter().zip(&p.c) {
            for (bi, m) in b.iter_mut().zip(column) {
                *bi += m * a;
            }
        }
        size = b.iter().fold(size, |m, x| m.max(x.abs()));
        let (lo, hi) = (PIECE_ENDS[piece].0, PIECE_ENDS[piece + 1].0);
        span[depth] = (lo, hi - lo);
        depth += 1;
    }
    if !size.is_finite() || size <= 0.0 {
        return 0;
    }
    let tau = 1e-13 * size;
    let mut n = 0;
    // A run of adjacent unresolved intervals (p at rounding level) gives one candidate.
    let mut run = (f64::NAN, f64::NAN);
    while depth > 0 {
        depth -= 1;
        let b = coef[depth];
        let (t0, w) = span[depth];
        // Signs of the coefficients, those within rounding of zero counted apart.
        let (mut changes, mut small, mut prev) = (0, 0, 0i32);
        for &x in &b {
            let sign = (x > tau) as i32 - (x < -tau) as i32;
            small += (sign == 0) as i32;
            changes += (sign * prev < 0) as i32;
            if sign != 0 {
                prev = sign;
            }
        }
        if small == 0 && changes == 0 {
            continue;
        }
        if small == 0 && changes == 1 {
            if n == out.len() {
                break;
            }
            // One root: start from the zero of the control polygon.
            let i = (0..8)
                .find(|&i| (b[i] < 0.0) != (b[i + 1] < 0.0))
                .unwrap_or(0);
            let t = (i as f64 + b[i] / (b[i] - b[i + 1])) / 8.0;
            out[n] = (bracketed_root(p, t0, t0 + w, b[0] < 0.0, t0 + w * t), false);
            n += 1;
            continue;
        }
        if small == 9 || w < MIN_WIDTH || depth + 2 > STACK {
            if n > 0 && (t0 - run.1).abs() <= 1e-15 {
                run.1 = t0 + w;
                out[n - 1] = (0.5 * (run.0 + run.1), true);
            } else {
                if n == out.len() {
                    break;
                }
                run = (t0, t0 + w);
                out[n] = (t0 + 0.5 * w, true);
                n += 1;
            }
            continue;
        }
        // de Casteljau at the midpoint: the right half replaces this interval, the left
        // half goes on top (processed first).
        let mut work = b;
        let mut left = [0.0; 9];
        left[0] = work[0];
        for (r, slot) in left.iter_mut().enumerate().skip(1) {
            for i in 0..=8 - r {
                work[i] = 0.5 * (work[i] + work[i + 1]);
            }
            *slot = work[0];
        }
        coef[depth] = work; // work[i] now holds the right half's coefficient i
        coef[depth + 1] = left;
        span[depth] = (t0 + 0.5 * w, 0.5 * w);
        span[depth + 1] = (t0, 0.5 * w);
        depth += 2;
    }
    n
}
