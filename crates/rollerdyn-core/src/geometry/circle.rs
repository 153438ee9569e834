//! Minimum distance between two circles in 3D, after D. Eberly, *Distance to Circles in
//! 3D*, Geometric Tools (2015, rev. 2021),
//! <https://www.geometrictools.com/Documentation/DistanceToCircle3.pdf> ("Eberly" below;
//! section numbers refer to it). The code is written from the mathematics, not from
//! Geometric Tools' sources.
//!
//! A circle is C = {centre c, unit normal n, radius r}. Circle 1 is parameterised as
//!
//! (E1) P(s) = c₁ + r₁ (cos s · u₁ + sin s · v₁),  (u₁, v₁, n₁) orthonormal,
//!
//! and the closest point of circle 2 to a point P is, with D = P − c₂ and Π the projection
//! onto the plane of circle 2, Πx = x − (n₂·x) n₂ (Eberly sect. 2, eq. 1–2),
//!
//! (E2) K(P) = c₂ + r₂ ΠD / |ΠD|,   F(s) = |P − K|² = |D|² + r₂² − 2 r₂ ρ,  ρ = |ΠD|.
//!
//! The closest pair minimises F over s (Eberly sect. 5.4). With W = cos s u₁ + sin s v₁,
//! W' = −sin s u₁ + cos s v₁, Δ = c₁ − c₂, δ = ΠΔ, ũ = Πu₁, ṽ = Πv₁ (and W·W' = 0):
//!
//! (E3) F'(s)/(2 r₁) = A − r₂ B / ρ,  with
//!      A = Δ·W' = −sin s (Δ·u₁) + cos s (Δ·v₁),
//!      B = ΠW'·(δ + r₁ ΠW) = −sin s (δ·ũ) + cos s (δ·ṽ)
//!          + r₁ [cos s sin s (|ṽ|² − |ũ|²) + (cos²s − sin²s) ũ·ṽ],
//! (E4) ρ² = |δ|² + 2 r₁ (cos s δ·ũ + sin s δ·ṽ) + r₁² |cos s ũ + sin s ṽ|².
//!
//! Setting F' = 0 and squaring away the root ρ gives G = A² ρ² − r₂² B² = 0, a
//! trigonometric polynomial of degree 4. With c = cos s, σ = sin s and σ² = 1 − c² it is
//! G = g₀(c) + σ g₁(c) (deg g₀ ≤ 4, deg g₁ ≤ 3), and eliminating σ,
//!
//! (E5) p(c) = g₀(c)² − (1 − c²) g₁(c)² = 0,  deg p ≤ 8,
//!
//! Eberly's degree-8 polynomial. Every stationary point of F has its cosine among the real
//! roots of p in [−1, 1]; the sign of σ is the one that zeroes G (both when both do, the
//! mirror-symmetric case). The search, without heap allocation:
//!
//! 1. F is sampled at the ends of eight pieces of [−1, 1] (the cosines of kπ/8) on both
//!    half circles, and the best sample is polished: an upper bound d̄ on the distance.
//! 2. Pieces whose arcs cannot come closer than d̄ are skipped: |P'(s)| = r₁ and a distance
//!    to a set is 1-Lipschitz, so d(s) = √F(s) is r₁-Lipschitz and, on an arc of length ℓ
//!    between samples d_a and d_b, d ≥ (d_a + d_b − r₁ ℓ)/2.
//! 3. On the other pieces the real roots of p are isolated by subdividing its Bernstein
//!    form (Descartes' rule of signs: no sign change among the coefficients, no root; one,
//!    exactly one root, then solved by bracketed Newton). Where p stays within rounding of
//!    zero (double roots from mirror-symmetric pairs ±s, with no sign change) the interval
//!    is narrowed to 2·10⁻⁵ in c and its midpoint taken as a candidate, with both signs.
//! 4. Every candidate is evaluated with the exact F of (E2); the best are polished by
//!    safeguarded Newton on F'(s) itself (E3 differentiated once more), and the global
//!    minimum is kept.
//!
//! Special cases (Eberly sect. 5.1–5.3):
//! * parallel normals (same plane, sect. 5.1, or parallel planes, sect. 5.2): the problem
//!   is planar after removing the plane offset h = n₂·Δ; closed form for separated,
//!   nested and crossing projections (two closest pairs at distance |h| when the projected
//!   circles cross), and a continuum when the projections are concentric (coaxial circles,
//!   including equal circles);
//! * centre of circle 2 on the axis of circle 1 (Δ ∥ n₁, sect. 5.3): A ≡ 0, so F' = 0
//!   reduces to B = 0 and the quartic B₀² − (1 − c²) B₁² replaces (E5);
//! * a continuum of closest pairs with non-parallel normals: F constant (circle 2 has a
//!   point on the axis of circle 1 that is closest to all of circle 1, e.g. circle 2 passes
//!   through c₁ tangent to n₁ with r₂ > r₁), or the closest point P lies on the axis of
//!   circle 2 (then all of circle 2 is equidistant from P). Both are detected numerically
//!   and reported as [`ClosestPairs::Infinite`];
//! * G ≡ 0 to rounding (F constant, or its stationary points undetermined by G): 48
//!   equally spaced samples, polished, replace the roots.
//!
//! Distances that differ by less than `EQ_TOL` = 1e-10 times the problem scale
//! max(r₁, r₂, |c₁ − c₂|) count as equal when deciding between unique, several and
//! infinitely many closest pairs; the pairs reported are always the best found, so
//! [`ClosestPairs::first`] is the minimiser whatever the classification.

use nalgebra::Vector3;
use std::f64::consts::FRAC_1_SQRT_2;

type V3 = Vector3<f64>;

/// Normals closer to parallel than this (|n₁ × n₂|) use the planar closed form.
const PARALLEL_TOL: f64 = 1e-14;
/// Relative tolerance (to the problem scale) under which two distances are equal.
const EQ_TOL: f64 = 1e-10;
/// Capacity of the candidate list: 16 samples, 1 polished sample, 2 × 12 root candidates.
const MAX_CANDIDATES: usize = 41;
/// Samples used when the stationarity polynomial degenerates.
const DENSE_SAMPLES: usize = 48;
/// Room for either list of candidates.
const CANDIDATE_CAPACITY: usize = if MAX_CANDIDATES > DENSE_SAMPLES {
    MAX_CANDIDATES
} else {
    DENSE_SAMPLES
};

/// A circle in 3D: centre, normal of its plane and radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Circle3 {
    /// Centre [m].
    pub center: Vector3<f64>,
    /// Normal of the circle's plane; normalised by [`circle_circle_distance`].
    pub normal: Vector3<f64>,
    /// Radius [m], positive.
    pub radius: f64,
}

/// The closest pairs of points between two circles.
#[derive(Debug, Clone, PartialEq)]
pub enum ClosestPairs {
    /// One closest pair (p1 on circle 1, p2 on circle 2).
    Unique(Vector3<f64>, Vector3<f64>),
    /// Two or more isolated closest pairs (e.g. symmetric configurations); all listed,
    /// the closest (to rounding) first.
    Several(Vec<(Vector3<f64>, Vector3<f64>)>),
    /// A continuum of closest pairs (coaxial circles, equal circles); one representative
    /// pair given.
    Infinite(Vector3<f64>, Vector3<f64>),
}

impl ClosestPairs {
    /// The (first) closest pair: point on circle 1, point on circle 2.
    pub fn first(&self) -> (Vector3<f64>, Vector3<f64>) {
        match self {
            ClosestPairs::Unique(p, q) | ClosestPairs::Infinite(p, q) => (*p, *q),
            ClosestPairs::Several(pairs) => pairs
                .first()
                .copied()
                .unwrap_or((V3::repeat(f64::NAN), V3::repeat(f64::NAN))),
        }
    }
}

/// Squared minimum distance between two circles and the pair(s) attaining it.
#[derive(Debug, Clone, PartialEq)]
pub struct CircleDistance {
    /// Squared distance |p1 − p2|² of the closest pair [m²].
    pub squared_distance: f64,
    /// The closest pair(s).
    pub pairs: ClosestPairs,
}

/// Minimum distance between two circles in 3D (Eberly sect. 5; see the module docs for
/// the equations). Normals need not be unit length (they are normalised here); radii
/// must be positive. Never panics; finite inputs give finite outputs.
pub fn circle_circle_distance(c1: &Circle3, c2: &Circle3) -> CircleDistance {
    let n1 = unit_or_z(&c1.normal);
    let n2 = unit_or_z(&c2.normal);
    let (r1, r2) = (c1.radius.abs(), c2.radius.abs());
    let delta = c1.center - c2.center;
    let scale = r1.max(r2).max(delta.norm());
    let finite = [r1, r2]
        .iter()
        .chain(c1.center.iter())
        .chain(c2.center.iter())
        .all(|x| x.is_finite());
    if !finite || !scale.is_finite() {
        let nan = V3::repeat(f64::NAN);
        return CircleDistance {
            squared_distance: f64::NAN,
            pairs: ClosestPairs::Unique(nan, nan),
        };
    }
    if scale == 0.0 {
        // Two points at the same place.
        return CircleDistance {
            squared_distance: 0.0,
            pairs: ClosestPairs::Unique(c1.center, c2.center),
        };
    }
    let (u1, v1) = orthonormal_basis(&n1);
    if n1.cross(&n2).norm() <= PARALLEL_TOL {
        parallel_planes(c1.center, n1, r1, u1, c2.center, n2, r2, scale)
    } else {
        general(c1.center, r1, u1, v1, c2.center, n2, r2, scale)
    }
}

/// `n / |n|`, or +z for a zero or non-finite vector (so that nothing panics).
fn unit_or_z(n: &V3) -> V3 {
    let m = n.norm();
    if m > 0.0 && m.is_finite() {
        n / m
    } else {
        V3::z()
    }
}

/// Two unit vectors completing the unit `n` to a right-handed orthonormal frame.
pub(crate) fn orthonormal_basis(n: &V3) -> (V3, V3) {
    let a = n.abs();
    let axis = if a.x <= a.y && a.x <= a.z {
        V3::x()
    } else if a.y <= a.z {
        V3::y()
    } else {
        V3::z()
    };
    let u = (axis - n * n.dot(&axis)).normalize();
    (u, n.cross(&u))
}

/// The point of the circle {center, unit normal, radius} in the direction of `dir`
/// projected onto its plane (Eberly eq. 2); `fallback` (in the plane) if that projection
/// vanishes.
fn point_on_circle(center: &V3, normal: &V3, radius: f64, dir: &V3, fallback: &V3) -> V3 {
    let w = dir - normal * normal.dot(dir);
    let m = w.norm();
    if m > 1e-300 && m.is_finite() {
        center + w * (radius / m)
    } else {
        center + fallback * radius
    }
}

/// Circles in the same or in parallel planes (Eberly sect. 5.1, 5.2): with h the plane
/// offset and d the distance between the projected centres, the squared distance is h²
/// plus the squared distance of two coplanar circles (0 if they cross, d − r₁ − r₂ if
/// separated, |r₁ − r₂| − d if nested).
#[allow(clippy::too_many_arguments)]
fn parallel_planes(
    c1: V3,
    n1: V3,
    r1: f64,
    u1: V3,
    c2: V3,
    n2: V3,
    r2: f64,
    scale: f64,
) -> CircleDistance {
    let delta = c1 - c2;
    let h = n2.dot(&delta);
    let dperp = delta - n2 * h;
    let d = dperp.norm();
    let (u2, _) = orthonormal_basis(&n2);
    // Concentric projections (coaxial circles): the distance is the same for every
    // aligned pair; within EQ_TOL the pair below is still the best one when d > 0.
    let coaxial = d <= EQ_TOL * scale;
    let result = |pairs: &[(V3, V3)]| {
        let (p, q) = pairs[0];
        CircleDistance {
            squared_distance: (p - q).norm_squared(),
            pairs: if coaxial {
                ClosestPairs::Infinite(p, q)
            } else if pairs.len() == 1 {
                ClosestPairs::Unique(p, q)
            } else {
                ClosestPairs::Several(pairs.to_vec())
            },
        }
    };
    if d.is_nan() || d == 0.0 {
        let p = c1 + u1 * r1;
        let q = point_on_circle(&c2, &n2, r2, &u1, &u2);
        return result(&[(p, q)]);
    }
    let e = dperp / d; // in-plane direction from c2 towards c1
    if d >= r1 + r2 {
        // Separated: the closest points face each other along the centre line.
        let p = point_on_circle(&c1, &n1, r1, &-e, &u1);
        let q = point_on_circle(&c2, &n2, r2, &e, &u2);
        return result(&[(p, q)]);
    }
    if d <= (r1 - r2).abs() {
        // Nested: both points on the far side from the outer circle's centre.
        let dir = if r1 >= r2 { -e } else { e };
        let p = point_on_circle(&c1, &n1, r1, &dir, &u1);
        let q = point_on_circle(&c2, &n2, r2, &dir, &u2);
        return result(&[(p, q)]);
    }
    // Crossing projections: x along e from c2, ±y across.
    let x = (d * d + (r2 - r1) * (r2 + r1)) / (2.0 * d);
    let y = ((r2 - x) * (r2 + x)).max(0.0).sqrt();
    let f = n2.cross(&e);
    let pair = |w: V3| {
        let q = point_on_circle(&c2, &n2, r2, &w, &u2);
        let p = point_on_circle(&c1, &n1, r1, &(q + n2 * h - c1), &u1);
        (p, q)
    };
    if y <= 1e-8 * scale {
        return result(&[pair(e * x)]);
    }
    let a = pair(e * x + f * y);
    let b = pair(e * x - f * y);
    if (a.0 - a.1).norm_squared() <= (b.0 - b.1).norm_squared() {
        result(&[a, b])
    } else {
        result(&[b, a])
    }
}

/// A polynomial of degree ≤ 8, ascending coefficients.
#[derive(Debug, Clone, Copy)]
struct Poly {
    c: [f64; 9],
    deg: usize,
}

impl Poly {
    fn new(coefs: &[f64]) -> Self {
        let mut c = [0.0; 9];
        let n = coefs.len().min(9);
        c[..n].copy_from_slice(&coefs[..n]);
        Poly {
            c,
            deg: n.saturating_sub(1),
        }
    }

    fn mul(&self, o: &Poly) -> Poly {
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

    fn lin(&self, a: f64, o: &Poly, b: f64) -> Poly {
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
    fn one_minus_sq(&self) -> Poly {
        let mut c = [0.0; 9];
        let deg = (self.deg + 2).min(8);
        for (k, ck) in c.iter_mut().enumerate().take(deg + 1) {
            let lo = if k <= self.deg { self.c[k] } else { 0.0 };
            let hi = if k >= 2 { self.c[k - 2] } else { 0.0 };
            *ck = lo - hi;
        }
        Poly { c, deg }
    }

    fn eval(&self, x: f64) -> f64 {
        let mut v = self.c[self.deg];
        for k in (0..self.deg).rev() {
            v = v * x + self.c[k];
        }
        v
    }

    fn eval_d(&self, x: f64) -> (f64, f64) {
        let mut v = self.c[self.deg];
        let mut d = 0.0;
        for k in (0..self.deg).rev() {
            d = d * x + v;
            v = v * x + self.c[k];
        }
        (v, d)
    }

    /// Σ |cₖ xᵏ|, the magnitude against which a value of the polynomial is rounding.
    fn abs_eval(&self, x: f64) -> f64 {
        let ax = x.abs();
        let mut v = self.c[self.deg].abs();
        for k in (0..self.deg).rev() {
            v = v * ax + self.c[k].abs();
        }
        v
    }

    fn abs_sum(&self) -> f64 {
        self.c[..=self.deg].iter().map(|x| x.abs()).sum()
    }
}

/// A trigonometric polynomial reduced with σ² = 1 − c²: value e(c) + σ o(c).
#[derive(Debug, Clone, Copy)]
struct TrigPoly {
    e: Poly,
    o: Poly,
}

impl TrigPoly {
    fn mul(&self, b: &TrigPoly) -> TrigPoly {
        TrigPoly {
            e: self
                .e
                .mul(&b.e)
                .lin(1.0, &self.o.mul(&b.o).one_minus_sq(), 1.0),
            o: self.e.mul(&b.o).lin(1.0, &self.o.mul(&b.e), 1.0),
        }
    }

    fn lin(&self, a: f64, b: &TrigPoly, bb: f64) -> TrigPoly {
        TrigPoly {
            e: self.e.lin(a, &b.e, bb),
            o: self.o.lin(a, &b.o, bb),
        }
    }

    fn abs_sum(&self) -> f64 {
        self.e.abs_sum() + self.o.abs_sum()
    }

    /// The σ-free product (e + σo)(e − σo) = e² − (1 − c²) o² (E5).
    fn eliminate(&self) -> Poly {
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
const PIECES: usize = 8;
/// The ends cₖ = −cos(kπ/8) of the pieces and sin sₖ = √(1 − cₖ²).
const PIECE_ENDS: [(f64, f64); PIECES + 1] = [
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
const PIECE_ARC: f64 = std::f64::consts::PI / PIECES as f64 * (1.0 + 1e-12);

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
fn roots_on_pieces(
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

/// Rotates the unit vector (c, s) = (cos t, sin t) by the angle h.
fn rotate(c: f64, s: f64, h: f64) -> (f64, f64) {
    let (sh, ch) = if h.abs() < 1e-3 {
        let h2 = h * h;
        (
            h * (1.0 - h2 / 6.0 * (1.0 - h2 / 20.0)),
            1.0 - h2 / 2.0 * (1.0 - h2 / 12.0),
        )
    } else {
        h.sin_cos()
    };
    let (c2, s2) = (c * ch - s * sh, s * ch + c * sh);
    let m = (c2 * c2 + s2 * s2).sqrt();
    (c2 / m, s2 / m)
}

/// The general configuration in units of the problem scale: Δ, the frame of circle 1 and
/// their projections onto the plane of circle 2.
struct Setup {
    delta: V3,
    u: V3,
    v: V3,
    r1: f64,
    r2: f64,
    pd: V3,
    pu: V3,
    pv: V3,
}

/// Value and derivatives of F (E2, E3) at one point of circle 1.
struct Eval {
    f: f64,
    f1: f64,
    f2: f64,
}

impl Setup {
    /// F(s) = |P − K(P)|² (E2), as a vector difference (accurate near zero).
    fn f(&self, c: f64, s: f64) -> f64 {
        let d = self.delta + (self.u * c + self.v * s) * self.r1;
        let pdv = self.pd + (self.pu * c + self.pv * s) * self.r1;
        let rho = pdv.norm();
        if rho > 1e-200 {
            (d - pdv * (self.r2 / rho)).norm_squared()
        } else {
            d.norm_squared() + self.r2 * self.r2
        }
    }

    /// ρ = |ΠD| and |D|² at a point of circle 1.
    fn rho_d2(&self, c: f64, s: f64) -> (f64, f64) {
        let d = self.delta + (self.u * c + self.v * s) * self.r1;
        let pdv = self.pd + (self.pu * c + self.pv * s) * self.r1;
        (pdv.norm(), d.norm_squared())
    }

    /// F, F' and F'' (E3 differentiated once more): with a = D·D', b = ΠD·ΠD',
    /// F' = 2(a − r₂ b/ρ), F'' = 2(a' − r₂ (b'/ρ − b²/ρ³)).
    fn derivs(&self, c: f64, s: f64) -> Eval {
        let r1 = self.r1;
        let w = self.u * c + self.v * s;
        let wp = self.v * c - self.u * s;
        let d = self.delta + w * r1;
        let dp = wp * r1;
        let pw = self.pu * c + self.pv * s;
        let pdv = self.pd + pw * r1;
        let pdp = (self.pv * c - self.pu * s) * r1;
        let rho = pdv.norm();
        let a = d.dot(&dp);
        let ap = r1 * r1 - r1 * d.dot(&w);
        if rho > 1e-200 {
            let b = pdv.dot(&pdp);
            let bp = pdp.norm_squared() - r1 * pdv.dot(&pw);
            let f = (d - pdv * (self.r2 / rho)).norm_squared();
            let f1 = 2.0 * (a - self.r2 * b / rho);
            let f2 = 2.0 * (ap - self.r2 * (bp / rho - b * b / (rho * rho * rho)));
            Eval { f, f1, f2 }
        } else {
            // On the axis of circle 2: a concave kink of F, never a minimum.
            Eval {
                f: d.norm_squared() + self.r2 * self.r2,
                f1: 2.0 * a,
                f2: -1.0,
            }
        }
    }

    /// Local minimisation of F from (c, s): Newton on F' with a descent safeguard.
    fn polish(&self, mut c: f64, mut s: f64) -> (f64, f64, f64) {
        let mut e = self.derivs(c, s);
        for _ in 0..60 {
            if e.f1 == 0.0 || !e.f1.is_finite() {
                break;
            }
            let newton = e.f2 > 0.0 && e.f2.is_finite();
            let mut h = if newton {
                -e.f1 / e.f2
            } else {
                -0.1 * e.f1.signum()
            };
            h = h.clamp(-0.5, 0.5);
            if newton && h.abs() < 1e-7 {
                // Quadratic convergence regime: no line search (F is at rounding level).
                (c, s) = rotate(c, s, h);
                if h.abs() < 1e-8 {
                    // The error after this step is O(h²): done.
                    return (c, s, self.f(c, s));
                }
                e = self.derivs(c, s);
                continue;
            }
            let mut accepted = false;
            for _ in 0..60 {
                let (c2, s2) = rotate(c, s, h);
                if self.f(c2, s2) < e.f {
                    (c, s) = (c2, s2);
                    accepted = true;
                    break;
                }
                h *= 0.5;
                if h.abs() < 1e-15 {
                    break;
                }
            }
            if !accepted {
                break;
            }
            e = self.derivs(c, s);
        }
        (c, s, e.f)
    }

    /// True if F has a barrier above `level` on the shorter arc between two points.
    fn barrier_between(&self, a: (f64, f64), b: (f64, f64), level: f64) -> bool {
        let ang = (a.0 * b.1 - a.1 * b.0).atan2(a.0 * b.0 + a.1 * b.1);
        if ang.abs() < 1e-9 {
            return false;
        }
        [0.25, 0.5, 0.75].iter().any(|t| {
            let (c, s) = rotate(a.0, a.1, t * ang);
            self.f(c, s).sqrt() > level
        })
    }
}

/// Non-parallel normals (Eberly sect. 5.3, 5.4): roots of the degree-8 polynomial (E5).
#[allow(clippy::too_many_arguments)]
fn general(c1: V3, r1: f64, u1: V3, v1: V3, c2: V3, n2: V3, r2: f64, scale: f64) -> CircleDistance {
    let inv = 1.0 / scale;
    let delta = (c1 - c2) * inv;
    let proj = |x: &V3| x - n2 * n2.dot(x);
    let st = Setup {
        delta,
        u: u1,
        v: v1,
        r1: r1 * inv,
        r2: r2 * inv,
        pd: proj(&delta),
        pu: proj(&u1),
        pv: proj(&v1),
    };
    let (r1s, r2s) = (st.r1, st.r2);
    let (du, dv) = (delta.dot(&u1), delta.dot(&v1));
    let (pdu, pdv) = (st.pd.dot(&st.pu), st.pd.dot(&st.pv));
    let (puu, pvv, puv) = (
        st.pu.norm_squared(),
        st.pv.norm_squared(),
        st.pu.dot(&st.pv),
    );
    let pdd = st.pd.norm_squared();

    // (E3), (E4) as trigonometric polynomials e(c) + σ o(c).
    let tp = |e: &[f64], o: &[f64]| TrigPoly {
        e: Poly::new(e),
        o: Poly::new(o),
    };
    let b_poly = tp(
        &[-r1s * puv, pdv, 2.0 * r1s * puv],
        &[-pdu, r1s * (pvv - puu)],
    );
    let a_is_zero = du.abs() + dv.abs() <= 1e-14;
    let (g, g_size) = if a_is_zero {
        // Centre of circle 2 on the axis of circle 1 (sect. 5.3): F' = 0 ⇔ B = 0.
        (b_poly, pdd.sqrt() + r1s)
    } else {
        let a_poly = tp(&[0.0, dv], &[-du]);
        let rho2 = tp(
            &[
                pdd + r1s * r1s * pvv,
                2.0 * r1s * pdu,
                r1s * r1s * (puu - pvv),
            ],
            &[2.0 * r1s * pdv, 2.0 * r1s * r1s * puv],
        );
        let t1 = a_poly.mul(&a_poly).mul(&rho2);
        let t2 = b_poly.mul(&b_poly);
        let g = t1.lin(1.0, &t2, -r2s * r2s);
        (g, t1.abs_sum() + r2s * r2s * t2.abs_sum())
    };
    let g_sum = g.abs_sum();
    let degenerate = g_sum.is_nan() || g_sum <= 1e-12 * g_size;

    // Candidate points (cos s, sin s).
    let mut cand = [(0.0f64, 0.0f64, 0.0f64); CANDIDATE_CAPACITY];
    let mut nc = 0;
    let push = |c: f64, s: f64, f: f64, list: &mut [(f64, f64, f64)], n: &mut usize| {
        if *n < list.len() {
            list[*n] = (c, s, f);
            *n += 1;
        }
    };
    let p = g.eliminate();
    let norm = p.c[..=p.deg].iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let mut seed = None;
    if degenerate || !(norm > 0.0 && norm.is_finite()) {
        for k in 0..DENSE_SAMPLES {
            let (s, c) = (std::f64::consts::TAU * k as f64 / DENSE_SAMPLES as f64).sin_cos();
            push(c, s, st.f(c, s), &mut cand, &mut nc);
        }
    } else {
        let p = p.lin(1.0 / norm, &p, 0.0);
        // Samples at the ends of the pieces, on both half circles (σ ≥ 0 and σ ≤ 0).
        let mut d_up = [0.0; PIECES + 1];
        let mut d_down = [0.0; PIECES + 1];
        let mut p_size = 0.0f64;
        for (k, &(c, s)) in PIECE_ENDS.iter().enumerate() {
            let f = st.f(c, s);
            push(c, s, f, &mut cand, &mut nc);
            d_up[k] = f.sqrt();
            d_down[k] = d_up[k];
            if s > 0.0 {
                let f = st.f(c, -s);
                push(c, -s, f, &mut cand, &mut nc);
                d_down[k] = f.sqrt();
            }
            p_size = p_size.max(p.eval(c).abs());
        }
        // An upper bound on the minimum: the best sample, polished.
        let best =
            cand[..nc].iter().fold(
                (0.0, 0.0, f64::INFINITY),
                |b, x| if x.2 < b.2 { *x } else { b },
            );
        let (c, s, f) = st.polish(best.0, best.1);
        push(c, s, f, &mut cand, &mut nc);
        seed = Some((c, s, f));
        let bound = f.sqrt() + 2.0 * EQ_TOL;
        // Only pieces whose arcs may come closer than that need their roots: |P'(s)| = r₁
        // and the distance to a set is 1-Lipschitz, so d(s) is r₁-Lipschitz and on an arc
        // of length ℓ between samples d_a, d_b, d ≥ (d_a + d_b − r₁ ℓ)/2.
        let mut active = [false; PIECES];
        for (j, flag) in active.iter_mut().enumerate() {
            let slack = r1s * PIECE_ARC;
            *flag = d_up[j] + d_up[j + 1] - slack <= 2.0 * bound
                || d_down[j] + d_down[j + 1] - slack <= 2.0 * bound;
        }
        let mut roots = [(0.0, false); 12];
        let nroots = roots_on_pieces(&p, &active, p_size, &mut roots);
        for &(c, cluster) in &roots[..nroots] {
            let s = (1.0 - c * c).max(0.0).sqrt();
            if s == 0.0 {
                push(c, 0.0, st.f(c, 0.0), &mut cand, &mut nc);
                continue;
            }
            // The sign of sin s zeroing G = g₀ + σ g₁ (both if both nearly do, and for an
            // unresolved cluster, as at a double root of p from a mirror pair ±s).
            let (e, o) = (g.e.eval(c), g.o.eval(c) * s);
            let size = g.e.abs_eval(c) + g.o.abs_eval(c) * s;
            let (gp, gm) = ((e + o).abs(), (e - o).abs());
            if cluster || gp <= gm || gp <= 1e-6 * size {
                push(c, s, st.f(c, s), &mut cand, &mut nc);
            }
            if cluster || gm < gp || gm <= 1e-6 * size {
                push(c, -s, st.f(c, -s), &mut cand, &mut nc);
            }
        }
    }
    let cand = &cand[..nc];
    let (f_best, f_worst) = cand
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            (lo.min(x.2), hi.max(x.2))
        });

    // Polish the promising candidates, best first, skipping those next to an already
    // polished one (the polished best sample is one).
    let mut promising = [(0.0f64, 0.0f64, 0.0f64); CANDIDATE_CAPACITY];
    let mut np = 0;
    for x in cand.iter().filter(|x| x.2 <= f_best + 1e-6) {
        promising[np] = *x;
        np += 1;
    }
    let promising = &mut promising[..np];
    promising.sort_unstable_by(|a, b| a.2.total_cmp(&b.2));
    let mut minima = [(0.0f64, 0.0f64, 0.0f64); 8];
    let mut nm = 0;
    if let Some(seed) = seed {
        minima[0] = seed;
        nm = 1;
    }
    for &(c, s, _) in promising.iter() {
        if nm == minima.len() {
            break;
        }
        let near = minima[..nm]
            .iter()
            .any(|m| (m.0 * s - m.1 * c).abs() < 1e-4 && m.0 * c + m.1 * s > 0.0);
        if near {
            continue;
        }
        minima[nm] = st.polish(c, s);
        nm += 1;
    }
    if nm == 0 {
        // Only reachable with non-finite values inside; nothing sensible to return.
        let nan = V3::repeat(f64::NAN);
        return CircleDistance {
            squared_distance: f64::NAN,
            pairs: ClosestPairs::Unique(nan, nan),
        };
    }
    let minima = &mut minima[..nm];
    minima.sort_unstable_by(|a, b| a.2.total_cmp(&b.2));
    let d_min = minima[0].2.sqrt();
    let level = d_min + EQ_TOL;

    // Output in the original units.
    let (u2, _) = orthonormal_basis(&n2);
    let to_pair = |c: f64, s: f64| {
        let p = c1 + (u1 * c + v1 * s) * r1;
        let q = point_on_circle(&c2, &n2, r2, &(p - c2), &u2);
        (p, q)
    };
    let (p, q) = to_pair(minima[0].0, minima[0].1);
    let sq = (p - q).norm_squared();

    // A continuum: F constant over circle 1, or P on the axis of circle 2 (all of
    // circle 2 equidistant from it: the spread of |P − K| over K is ≈ 2 r₂ ρ / d).
    let (rho, d2) = st.rho_d2(minima[0].0, minima[0].1);
    let far = (d2 + r2s * r2s + 2.0 * r2s * rho).sqrt();
    let near = minima[0].2.sqrt();
    let axis_spread = 4.0 * r2s * rho / (far + near).max(1e-300);
    if f_worst.sqrt() <= level || axis_spread <= EQ_TOL {
        return CircleDistance {
            squared_distance: sq,
            pairs: ClosestPairs::Infinite(p, q),
        };
    }

    // Isolated minima at equal distance, one per basin.
    let mut kept = [0usize; 8];
    let mut nk = 0;
    for i in 0..minima.len() {
        if minima[i].2.sqrt() > level {
            break;
        }
        let a = (minima[i].0, minima[i].1);
        let distinct = kept[..nk].iter().all(|&j| {
            let b = (minima[j].0, minima[j].1);
            st.barrier_between(a, b, level)
        });
        if distinct {
            kept[nk] = i;
            nk += 1;
        }
    }
    if nk <= 1 {
        return CircleDistance {
            squared_distance: sq,
            pairs: ClosestPairs::Unique(p, q),
        };
    }
    let pairs = kept[..nk]
        .iter()
        .map(|&i| to_pair(minima[i].0, minima[i].1))
        .collect();
    CircleDistance {
        squared_distance: sq,
        pairs: ClosestPairs::Several(pairs),
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::f64::consts::{PI, TAU};

    pub(crate) fn circle(center: [f64; 3], normal: [f64; 3], radius: f64) -> Circle3 {
        Circle3 {
            center: V3::from(center),
            normal: V3::from(normal),
            radius,
        }
    }

    pub(crate) fn scale(c1: &Circle3, c2: &Circle3) -> f64 {
        c1.radius.max(c2.radius).max((c1.center - c2.center).norm())
    }

    /// Squared distance from a point to a circle in the closed form of Eberly sect. 2:
    /// h² + (ρ − r)², h the height over the plane and ρ the in-plane distance to the
    /// centre (written differently from the code under test).
    fn point_circle_sq(p: &V3, c: &Circle3) -> f64 {
        let n = c.normal.normalize();
        let d = p - c.center;
        let h = n.dot(&d);
        let rho = (d - n * h).norm();
        h * h + (rho - c.radius) * (rho - c.radius)
    }

    /// An in-plane frame built independently of the code under test (Gram–Schmidt
    /// against the coordinate axis least aligned with the normal, other order).
    pub(crate) fn frame(c: &Circle3) -> (V3, V3) {
        let n = c.normal.normalize();
        let k = (0..3)
            .min_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
            .unwrap();
        let mut a = V3::zeros();
        a[k] = 1.0;
        let v = n.cross(&a).normalize();
        (v.cross(&n), v)
    }

    pub(crate) fn point(c: &Circle3, frame: &(V3, V3), t: f64) -> V3 {
        c.center + (frame.0 * t.cos() + frame.1 * t.sin()) * c.radius
    }

    /// Brute-force reference: circle 1 sampled at `n` points with the exact point-circle
    /// distance, then every sampled local minimum refined by golden-section search over
    /// its two neighbouring intervals.
    pub(crate) fn brute_force(c1: &Circle3, c2: &Circle3, n: usize) -> f64 {
        let fr = frame(c1);
        let f = |t: f64| point_circle_sq(&point(c1, &fr, t), c2);
        let h = TAU / n as f64;
        let vals: Vec<f64> = (0..n).map(|k| f(k as f64 * h)).collect();
        let mut best = f64::INFINITY;
        for k in 0..n {
            let (prev, next) = (vals[(k + n - 1) % n], vals[(k + 1) % n]);
            if vals[k] > prev || vals[k] > next {
                continue;
            }
            let (mut a, mut b) = ((k as f64 - 1.0) * h, (k as f64 + 1.0) * h);
            let g = 0.5 * (5f64.sqrt() - 1.0);
            for _ in 0..120 {
                let (x1, x2) = (b - g * (b - a), a + g * (b - a));
                if f(x1) < f(x2) {
                    b = x2;
                } else {
                    a = x1;
                }
            }
            best = best.min(f(0.5 * (a + b))).min(vals[k]);
        }
        best
    }

    /// Raw sampling of both circles, n × n points (an upper bound on the minimum).
    fn grid_min(c1: &Circle3, c2: &Circle3, n: usize) -> f64 {
        let (f1, f2) = (frame(c1), frame(c2));
        let p2: Vec<V3> = (0..n)
            .map(|k| point(c2, &f2, TAU * k as f64 / n as f64))
            .collect();
        let mut best = f64::INFINITY;
        for i in 0..n {
            let p = point(c1, &f1, TAU * i as f64 / n as f64);
            for q in &p2 {
                best = best.min((p - q).norm_squared());
            }
        }
        best
    }

    fn pairs_of(r: &CircleDistance) -> Vec<(V3, V3)> {
        match &r.pairs {
            ClosestPairs::Unique(p, q) | ClosestPairs::Infinite(p, q) => vec![(*p, *q)],
            ClosestPairs::Several(v) => v.clone(),
        }
    }

    /// The returned points lie on their circles and realise the squared distance.
    fn check_points(c1: &Circle3, c2: &Circle3, r: &CircleDistance) {
        let s = scale(c1, c2);
        let on = |p: &V3, c: &Circle3| {
            let n = c.normal.normalize();
            let d = p - c.center;
            assert!((d.norm() - c.radius).abs() <= 1e-12 * s, "off radius: {d}");
            assert!(n.dot(&d).abs() <= 1e-12 * s, "off plane: {d}");
        };
        let pairs = pairs_of(r);
        assert!(!pairs.is_empty());
        let (p0, q0) = r.pairs.first();
        assert_eq!((p0 - q0).norm_squared(), r.squared_distance);
        for (p, q) in &pairs {
            on(p, c1);
            on(q, c2);
            let d = (p - q).norm();
            assert!(d - r.squared_distance.sqrt() <= 1e-10 * s);
        }
    }

    fn assert_close(a: f64, b: f64, tol: f64) {
        assert!((a - b).abs() <= tol, "{a} vs {b} (tol {tol})");
    }

    // ---- 1. Eberly's published cases -------------------------------------------------
    //
    // Source: Geometric Tools unit test of the circle-circle query,
    // github.com/davideberly/GeometricToolsUnitTests,
    // UnitTests/Mathematics/Distance/3D/TestDistCircle3Circle3.cpp (commit 76cae295):
    // circle 0 = unit circle in z = 0 at the origin. Its expected values are single
    // precision checked to maxError = 1e-6 there, and are checked to that tolerance
    // here; tighter checks use closed forms derived below.

    fn unit_xy() -> Circle3 {
        circle([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 1.0)
    }

    #[test]
    fn eberly_nonparallel_concentric_axes() {
        // "Circles in nonparallel planes (concentric)": centre (0,0,1), r = 1.25,
        // normal ∝ (0.0625, 0, 1). Published: 0.911423385 (float, tol 1e-6), closest
        // points (1,0,0) and (1.24756575, 0, 0.922027528).
        let c2 = circle([0.0, 0.0, 1.0], [0.0625, 0.0, 1.0], 1.25);
        let c1 = unit_xy();
        // Double-precision reference, closed form: by the mirror symmetry y → −y and the
        // brute force below, the minimum is at P = (1,0,0): with n the unit normal,
        // h = n·(P − c₂), ρ² = |P − c₂|² − h², F = h² + (ρ − 1.25)² (Eberly sect. 2).
        let n = V3::new(0.0625, 0.0, 1.0).normalize();
        let dvec = V3::new(1.0, 0.0, -1.0);
        let h = n.dot(&dvec);
        let rho = (dvec.norm_squared() - h * h).sqrt();
        let exact = h * h + (rho - 1.25) * (rho - 1.25);
        assert_close(exact, 0.911_422_838_404_8, 1e-12);
        for (a, b, swapped) in [(&c1, &c2, false), (&c2, &c1, true)] {
            let r = circle_circle_distance(a, b);
            check_points(a, b, &r);
            assert!(matches!(r.pairs, ClosestPairs::Unique(..)), "{r:?}");
            assert_close(r.squared_distance, 0.911423385, 1e-6);
            assert_close(r.squared_distance, exact, 1e-13);
            assert_close(r.squared_distance, brute_force(a, b, 4096), 1e-13);
            let (mut p, mut q) = r.pairs.first();
            if swapped {
                std::mem::swap(&mut p, &mut q);
            }
            assert!((p - V3::new(1.0, 0.0, 0.0)).norm() <= 1e-9);
            assert!((q - V3::new(1.24756575, 0.0, 0.922027528)).norm() <= 1e-6);
        }
    }

    #[test]
    fn eberly_same_plane_separated() {
        let c2 = circle([4.0, 0.0, 0.0], [0.0, 0.0, 1.0], 2.0);
        for (a, b) in [(unit_xy(), c2), (c2, unit_xy())] {
            let r = circle_circle_distance(&a, &b);
            check_points(&a, &b, &r);
            assert_eq!(r.squared_distance, 1.0);
            let (p, q) = r.pairs.first();
            let (p1, p2) = if a.radius == 1.0 { (p, q) } else { (q, p) };
            assert_eq!(p1, V3::new(1.0, 0.0, 0.0));
            assert_eq!(p2, V3::new(2.0, 0.0, 0.0));
            assert!(matches!(r.pairs, ClosestPairs::Unique(..)));
        }
    }

    #[test]
    fn eberly_parallel_planes_containment() {
        // Projection of circle 2 (r 0.125 at (0.25, 0)) inside the unit circle: in-plane
        // gap 1 − 0.375, height 1: 1 + 0.625² = 1.390625 exactly.
        let c2 = circle([0.25, 0.0, 1.0], [0.0, 0.0, 1.0], 0.125);
        for (a, b) in [(unit_xy(), c2), (c2, unit_xy())] {
            let r = circle_circle_distance(&a, &b);
            check_points(&a, &b, &r);
            assert_close(r.squared_distance, 1.390625, 1e-15);
            assert!(matches!(r.pairs, ClosestPairs::Unique(..)));
            let (p, q) = r.pairs.first();
            let (p1, p2) = if a.radius == 1.0 { (p, q) } else { (q, p) };
            assert!((p1 - V3::new(1.0, 0.0, 0.0)).norm() < 1e-15);
            assert!((p2 - V3::new(0.375, 0.0, 1.0)).norm() < 1e-15);
        }
    }

    #[test]
    fn eberly_parallel_planes_overlap_two_pairs() {
        // Projections cross at x = 0.21875, y = ±0.975780964: two pairs at distance 1.
        let c2 = circle([1.0, 0.0, 1.0], [0.0, 0.0, 1.0], 1.25);
        for (a, b) in [(unit_xy(), c2), (c2, unit_xy())] {
            let r = circle_circle_distance(&a, &b);
            check_points(&a, &b, &r);
            assert_close(r.squared_distance, 1.0, 1e-15);
            let ClosestPairs::Several(pairs) = &r.pairs else {
                panic!("expected two pairs: {r:?}");
            };
            assert_eq!(pairs.len(), 2);
            let y = (1.0f64 - 0.21875 * 0.21875).sqrt();
            assert_close(y, 0.975780964, 1e-6);
            let mut ys: Vec<f64> = pairs.iter().map(|(p, _)| p.y).collect();
            ys.sort_by(f64::total_cmp);
            assert_close(ys[0], -y, 1e-15);
            assert_close(ys[1], y, 1e-15);
            for (p, q) in pairs {
                assert_close(p.x, 0.21875, 1e-15);
                assert_close(q.x, 0.21875, 1e-15);
                assert_close((p - q).norm_squared(), 1.0, 1e-15);
            }
        }
    }

    #[test]
    fn eberly_equal_and_concentric_are_infinite() {
        // Equal circles: distance 0, a continuum of pairs.
        let r = circle_circle_distance(&unit_xy(), &unit_xy());
        check_points(&unit_xy(), &unit_xy(), &r);
        assert!(matches!(r.pairs, ClosestPairs::Infinite(..)), "{r:?}");
        assert_eq!(r.squared_distance, 0.0);
        // Concentric coplanar, radii 1 and 2: squared distance 1 for every aligned pair.
        let c2 = circle([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 2.0);
        for (a, b) in [(unit_xy(), c2), (c2, unit_xy())] {
            let r = circle_circle_distance(&a, &b);
            check_points(&a, &b, &r);
            assert!(matches!(r.pairs, ClosestPairs::Infinite(..)), "{r:?}");
            assert_close(r.squared_distance, 1.0, 1e-15);
        }
        // Coaxial in parallel planes (Eberly sect. 5.2), opposite normals.
        let c3 = circle([0.0, 0.0, 0.5], [0.0, 0.0, -1.0], 1.5);
        let r = circle_circle_distance(&unit_xy(), &c3);
        check_points(&unit_xy(), &c3, &r);
        assert!(matches!(r.pairs, ClosestPairs::Infinite(..)), "{r:?}");
        assert_close(r.squared_distance, 0.5, 1e-15);
    }

    #[test]
    fn eberly_general_case() {
        // "General case" of the same unit test (float inputs, tolerance 1e-6): squared
        // distance 0.245732963, closest points (0.424922794, 0.938110709, −1.26392782)
        // and (0.227285862, 1.05095041, −0.823541999) (Mathematica agrees to 6 digits).
        let c1 = circle(
            [0.629447341, -0.729045987, 0.811583877],
            [-0.512442946, 0.644127250, 0.567892849],
            2.67001724,
        );
        let c2 = circle(
            [-0.557931900, 0.264718533, -0.383665919],
            [0.122579113, -0.574992657, -0.808923900],
            1.19508076,
        );
        let r = circle_circle_distance(&c1, &c2);
        check_points(&c1, &c2, &r);
        assert!(matches!(r.pairs, ClosestPairs::Unique(..)), "{r:?}");
        assert_close(r.squared_distance, 0.245732963, 1e-6);
        assert_close(r.squared_distance, brute_force(&c1, &c2, 4096), 1e-13);
        let (p, q) = r.pairs.first();
        assert!((p - V3::new(0.424922794, 0.938110709, -1.26392782)).norm() < 1e-5);
        assert!((q - V3::new(0.227285862, 1.05095041, -0.823541999)).norm() < 1e-5);
        let s = circle_circle_distance(&c2, &c1);
        assert_close(s.squared_distance, r.squared_distance, 1e-14);
    }

    // ---- special configurations (derived here) ----------------------------------------

    #[test]
    fn point_on_axis_gives_continuum() {
        // Circle A (normal y, centre (2,0,0), radius 2) passes through the centre of the
        // unit circle B in z = 0, tangent to B's axis there. Points of A are
        // (2 − 2cos θ, 0, 2 sin θ), at squared distance 4 sin²θ + (1 − 2cos θ)² =
        // 5 − 4 cos θ from B: minimum 1 at the origin, equidistant from all of B.
        let a = circle([2.0, 0.0, 0.0], [0.0, 1.0, 0.0], 2.0);
        for (c1, c2) in [(a, unit_xy()), (unit_xy(), a)] {
            let r = circle_circle_distance(&c1, &c2);
            check_points(&c1, &c2, &r);
            assert!(matches!(r.pairs, ClosestPairs::Infinite(..)), "{r:?}");
            assert_close(r.squared_distance, 1.0, 1e-12);
        }
    }

    #[test]
    fn linked_great_circles_meet_twice() {
        // Two unit circles centred at the origin in z = 0 and y = 0 meet at (±1, 0, 0)
        // (centres on each other's axes: Eberly sect. 5.3).
        let c2 = circle([0.0, 0.0, 0.0], [0.0, 1.0, 0.0], 1.0);
        let r = circle_circle_distance(&unit_xy(), &c2);
        check_points(&unit_xy(), &c2, &r);
        let ClosestPairs::Several(pairs) = &r.pairs else {
            panic!("expected two pairs: {r:?}");
        };
        assert_eq!(pairs.len(), 2);
        assert!(r.squared_distance < 1e-28);
        let mut xs: Vec<f64> = pairs.iter().map(|(p, _)| p.x).collect();
        xs.sort_by(f64::total_cmp);
        assert_close(xs[0], -1.0, 1e-14);
        assert_close(xs[1], 1.0, 1e-14);
    }

    #[test]
    fn mirror_symmetric_minima_are_both_reported() {
        // Circle 2 in the plane x = 0.5 (normal x), centre (0.5, 0, 2), radius 2:
        // symmetric under y → −y with its minima off the mirror plane.
        let c2 = circle([0.5, 0.0, 2.0], [1.0, 0.0, 0.0], 2.0);
        let r = circle_circle_distance(&unit_xy(), &c2);
        check_points(&unit_xy(), &c2, &r);
        let ClosestPairs::Several(pairs) = &r.pairs else {
            panic!("expected two pairs: {r:?}");
        };
        assert_eq!(pairs.len(), 2);
        let (a, b) = (pairs[0].0, pairs[1].0);
        assert!((a - V3::new(b.x, -b.y, b.z)).norm() < 1e-9);
        assert!(a.y.abs() > 0.1);
        assert_close(
            r.squared_distance,
            brute_force(&unit_xy(), &c2, 4096),
            1e-13,
        );
    }

    #[test]
    fn grid_sampling_bounds() {
        // An independent 2000 × 2000 sampling of both circles bounds the minimum from
        // above; with spacing h the sampling error is at most ~ (r₁² + r₂²)(π/2000)²/2.
        let cases = [
            (unit_xy(), circle([0.3, -0.2, 0.4], [0.3, 0.8, 0.2], 0.7)),
            (
                circle([0.1, 0.2, 0.3], [1.0, -0.5, 0.2], 1.5),
                circle([-0.4, 0.1, 0.0], [0.2, 0.3, -1.0], 0.4),
            ),
        ];
        for (c1, c2) in cases {
            let r = circle_circle_distance(&c1, &c2);
            check_points(&c1, &c2, &r);
            let g = grid_min(&c1, &c2, 2000);
            let tol = (c1.radius.powi(2) + c2.radius.powi(2)) * (PI / 2000.0).powi(2);
            assert!(
                r.squared_distance <= g + 1e-12,
                "{} > {g}",
                r.squared_distance
            );
            assert!(
                r.squared_distance >= g - tol,
                "{} < {g} - {tol}",
                r.squared_distance
            );
        }
    }

    // ---- 2. brute-force reference over random circles ---------------------------------

    pub(crate) fn unit_vector() -> impl Strategy<Value = V3> {
        (-1.0f64..1.0, 0.0..TAU).prop_map(|(z, phi)| {
            let s = (1.0 - z * z).sqrt();
            V3::new(s * phi.cos(), s * phi.sin(), z)
        })
    }

    pub(crate) fn any_circle() -> impl Strategy<Value = Circle3> {
        (
            prop::array::uniform3(-0.5f64..0.5),
            unit_vector(),
            0.1f64..2.0,
        )
            .prop_map(|(c, n, r)| Circle3 {
                center: V3::from(c),
                normal: n,
                radius: r,
            })
    }

    fn check_against_brute_force(c1: &Circle3, c2: &Circle3) {
        let r = circle_circle_distance(c1, c2);
        check_points(c1, c2, &r);
        let s = scale(c1, c2);
        // Both parameterisations (each gives attained values, i.e. upper bounds).
        let b = brute_force(c1, c2, 2048).min(brute_force(c2, c1, 2048));
        // The brief's bounds, then the much tighter agreement actually reached.
        assert!(
            r.squared_distance <= b + 1e-9,
            "{} > {b}",
            r.squared_distance
        );
        assert!(r.squared_distance >= b - 1e-6 * s * s);
        assert!(
            (r.squared_distance - b).abs() <= 1e-12 * s * s,
            "{} vs brute force {b}",
            r.squared_distance
        );
        // Symmetric in the two circles.
        let t = circle_circle_distance(c2, c1);
        assert!((t.squared_distance - r.squared_distance).abs() <= 1e-12 * s * s);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(1000))]

        #[test]
        fn random_circles_match_brute_force(c1 in any_circle(), c2 in any_circle()) {
            check_against_brute_force(&c1, &c2);
        }

        #[test]
        fn parallel_and_nearly_parallel_match_brute_force(
            c1 in any_circle(),
            mut c2 in any_circle(),
            flip in any::<bool>(),
            tilt in prop::sample::select(vec![0.0, 1e-15, 1e-14, 3e-14, 1e-13, 1e-12, 1e-10, 1e-7, 1e-4, 1e-2]),
            axis in unit_vector(),
        ) {
            let n = if flip { -c1.normal } else { c1.normal };
            c2.normal = (n + axis.cross(&n) * tilt).normalize();
            check_against_brute_force(&c1, &c2);
        }

        #[test]
        fn nearly_coaxial_matches_brute_force(
            c1 in any_circle(),
            mut c2 in any_circle(),
            h in -1.0f64..1.0,
            offset in prop::sample::select(vec![0.0, 1e-15, 1e-13, 1e-11, 1e-9, 1e-7, 1e-5, 1e-3]),
            tilt in prop::sample::select(vec![0.0, 1e-15, 1e-14, 1e-13, 1e-11, 1e-9, 1e-7, 1e-5, 1e-3]),
            dir in unit_vector(),
            axis in unit_vector(),
        ) {
            c2.center = c1.center + c1.normal * h + dir * offset;
            c2.normal = (c1.normal + axis.cross(&c1.normal) * tilt).normalize();
            check_against_brute_force(&c1, &c2);
        }

        #[test]
        fn disparate_scales_match_brute_force(
            mut c1 in any_circle(),
            mut c2 in any_circle(),
            log_r1 in -3.0f64..1.0,
            log_r2 in -3.0f64..1.0,
            log_offset in -3.0f64..1.0,
        ) {
            // Radii and centre distance from 1e-3 to 10 (ratios up to 1e4).
            c1.radius = 10f64.powf(log_r1);
            c2.radius = 10f64.powf(log_r2);
            let dir = c2.center - c1.center;
            let dir = if dir.norm() > 0.0 { dir.normalize() } else { V3::x() };
            c2.center = c1.center + dir * 10f64.powf(log_offset);
            check_against_brute_force(&c1, &c2);
        }

        #[test]
        fn crossing_and_nearly_crossing_circles(
            c1 in any_circle(),
            mut c2 in any_circle(),
            t in 0.0..TAU,
            phi in 0.0..TAU,
            gap in prop::sample::select(vec![0.0, 1e-12, 1e-9, 1e-6, 1e-3]),
            dir in unit_vector(),
        ) {
            // Circle 2 passes through the point X(t) of circle 1, then is moved by `gap`.
            let (u, v) = frame(&c1);
            let x = point(&c1, &(u, v), t);
            let (u2, v2) = frame(&c2);
            c2.center = x - (u2 * phi.cos() + v2 * phi.sin()) * c2.radius + dir * gap;
            let r = circle_circle_distance(&c1, &c2);
            check_points(&c1, &c2, &r);
            let s = scale(&c1, &c2);
            prop_assert!(r.squared_distance <= gap * gap + 1e-24 * s * s, "{}", r.squared_distance);
            check_against_brute_force(&c1, &c2);
        }

        #[test]
        fn centre_on_axis_matches_brute_force(
            c1 in any_circle(),
            mut c2 in any_circle(),
            h in -1.0f64..1.0,
        ) {
            c2.center = c1.center + c1.normal * h;
            check_against_brute_force(&c1, &c2);
            check_against_brute_force(&c2, &c1);
        }
    }

    // ---- 3. roller edge vs flange rim -------------------------------------------------
    //
    // Tube-centre circles of the roller edge torus (radius R − r_e = 1.7475 mm) and of a
    // flange rim torus (radius 10 mm, axis z), millimetre offsets, tilts of ±1° about x
    // and y (0 included), in two arrangements: the edge axis nearly perpendicular to the
    // rim axis (edge normal ≈ x), and nearly parallel to it (edge normal ≈ z, as for a
    // roller whose axis follows the ring axis; zero tilt takes the parallel-plane branch).
    // Reference: the brute force of both parameterisations, to 1e-15 m².

    pub(crate) fn rotation(axis: V3, angle: f64) -> nalgebra::Rotation3<f64> {
        nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle)
    }

    pub(crate) fn roller_cases(perpendicular: bool) -> Vec<(Circle3, Circle3)> {
        let deg = PI / 180.0;
        let mut cases = Vec::new();
        for &tx in &[-1.0, -0.37, 0.0, 0.5, 1.0] {
            for &ty in &[-1.0, 0.0, 0.81, 1.0] {
                for &(dx, dy, dz) in &[
                    (8.5e-3, 0.0, 1.2e-3),
                    (9.1e-3, 0.4e-3, 0.8e-3),
                    (10.3e-3, -0.7e-3, 2.5e-3),
                    (11.9e-3, 0.2e-3, -1.5e-3),
                ] {
                    let rim = circle([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 10e-3);
                    let base = if perpendicular { V3::x() } else { V3::z() };
                    let n = rotation(V3::x(), tx * deg) * (rotation(V3::y(), ty * deg) * base);
                    let edge = Circle3 {
                        center: V3::new(dx, dy, dz),
                        normal: n,
                        radius: 1.7475e-3,
                    };
                    cases.push((edge, rim));
                }
            }
        }
        cases
    }

    #[test]
    fn roller_edge_flange_rim_match_brute_force() {
        for perpendicular in [true, false] {
            for (edge, rim) in roller_cases(perpendicular) {
                for (a, b) in [(edge, rim), (rim, edge)] {
                    let r = circle_circle_distance(&a, &b);
                    check_points(&a, &b, &r);
                    let bf = brute_force(&a, &b, 8192).min(brute_force(&b, &a, 8192));
                    assert!(
                        (r.squared_distance - bf).abs() <= 1e-15,
                        "{} vs {bf} for {a:?} {b:?}",
                        r.squared_distance
                    );
                }
            }
        }
    }

    #[test]
    fn degenerate_inputs_do_not_panic() {
        let zero_normal = circle([0.1, 0.0, 0.0], [0.0, 0.0, 0.0], 1.0);
        let r = circle_circle_distance(&zero_normal, &unit_xy());
        assert!(r.squared_distance.is_finite());
        let point = circle([0.3, 0.2, 0.1], [0.0, 0.0, 1.0], 0.0);
        let r = circle_circle_distance(&point, &unit_xy());
        assert!(r.squared_distance.is_finite());
        for bad in [
            circle([f64::NAN, 0.0, 0.0], [0.0, 0.0, 1.0], 1.0),
            circle([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], f64::NAN),
            circle([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], f64::INFINITY),
            circle([0.0, f64::INFINITY, 0.0], [0.0, 0.0, 1.0], 1.0),
        ] {
            for (a, b) in [(bad, unit_xy()), (unit_xy(), bad)] {
                let r = circle_circle_distance(&a, &b);
                assert!(r.squared_distance.is_nan());
                let _ = r.pairs.first();
            }
        }
        // Non-finite normals fall back to +z.
        let odd = circle([0.5, 0.0, 0.3], [f64::NAN, 0.0, 1.0], 1.0);
        let r = circle_circle_distance(&odd, &unit_xy());
        assert!(r.squared_distance.is_finite());
        // Huge and tiny magnitudes.
        let big = circle([1e150, 0.0, 0.0], [0.3, 0.1, 1.0], 1e149);
        let r = circle_circle_distance(&big, &circle([0.0; 3], [1.0, 0.0, 0.0], 1e150));
        assert!(r.squared_distance.is_finite());
        let tiny = circle([1e-150, 0.0, 0.0], [0.3, 0.1, 1.0], 1e-151);
        let r = circle_circle_distance(&tiny, &circle([0.0; 3], [1.0, 0.0, 0.0], 1e-150));
        assert!(r.squared_distance.is_finite());
    }
}
