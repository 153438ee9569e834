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
//!
//! The polynomials (E5) and the isolation of their real roots (step 3) are in
//! `circle/polynomial.rs`.

use nalgebra::Vector3;
use polynomial::{roots_on_pieces, Poly, TrigPoly, PIECES, PIECE_ARC, PIECE_ENDS};

mod polynomial;

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
    let (g, degenerate) = st.stationarity();
    let mut cand = Candidates::default();
    let seed = cand.collect(&st, &g, degenerate);
    let cand = cand.as_slice();
    let f_worst = cand.iter().fold(f64::NEG_INFINITY, |hi, x| hi.max(x.2));
    let mut minima = [(0.0f64, 0.0f64, 0.0f64); 8];
    let nm = st.polished_minima(cand, seed, &mut minima);
    if nm == 0 {
        // Only reachable with non-finite values inside; nothing sensible to return.
        let nan = V3::repeat(f64::NAN);
        return CircleDistance {
            squared_distance: f64::NAN,
            pairs: ClosestPairs::Unique(nan, nan),
        };
    }
    // Output in the original units.
    let (u2, _) = orthonormal_basis(&n2);
    let to_pair = |c: f64, s: f64| {
        let p = c1 + (u1 * c + v1 * s) * r1;
        let q = point_on_circle(&c2, &n2, r2, &(p - c2), &u2);
        (p, q)
    };
    st.closest_pairs(&minima[..nm], f_worst, to_pair)
}

/// Candidate points (cos s, sin s, F) of circle 1 for the minimum of F.
struct Candidates {
    list: [(f64, f64, f64); CANDIDATE_CAPACITY],
    n: usize,
}

impl Default for Candidates {
    fn default() -> Self {
        Self {
            list: [(0.0, 0.0, 0.0); CANDIDATE_CAPACITY],
            n: 0,
        }
    }
}

impl Candidates {
    fn push(&mut self, c: f64, s: f64, f: f64) {
        if self.n < self.list.len() {
            self.list[self.n] = (c, s, f);
            self.n += 1;
        }
    }

    fn as_slice(&self) -> &[(f64, f64, f64)] {
        &self.list[..self.n]
    }

    /// The candidates of F's minimum: dense samples where the polynomial `g` of F' = 0
    /// is `degenerate`; else the ends of the pieces, the best of them polished (returned
    /// as the seed), and the roots of the polynomial on the pieces whose arcs may come
    /// closer than that.
    fn collect(&mut self, st: &Setup, g: &TrigPoly, degenerate: bool) -> Option<(f64, f64, f64)> {
        let p = g.eliminate();
        let norm = p.c[..=p.deg].iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if degenerate || !(norm > 0.0 && norm.is_finite()) {
            for k in 0..DENSE_SAMPLES {
                let (s, c) = (std::f64::consts::TAU * k as f64 / DENSE_SAMPLES as f64).sin_cos();
                self.push(c, s, st.f(c, s));
            }
            return None;
        }
        let p = p.lin(1.0 / norm, &p, 0.0);
        // Samples at the ends of the pieces, on both half circles (σ ≥ 0 and σ ≤ 0).
        let mut d_up = [0.0; PIECES + 1];
        let mut d_down = [0.0; PIECES + 1];
        let mut p_size = 0.0f64;
        for (k, &(c, s)) in PIECE_ENDS.iter().enumerate() {
            let f = st.f(c, s);
            self.push(c, s, f);
            d_up[k] = f.sqrt();
            d_down[k] = d_up[k];
            if s > 0.0 {
                let f = st.f(c, -s);
                self.push(c, -s, f);
                d_down[k] = f.sqrt();
            }
            p_size = p_size.max(p.eval(c).abs());
        }
        // An upper bound on the minimum: the best sample, polished.
        let best =
            self.as_slice().iter().fold(
                (0.0, 0.0, f64::INFINITY),
                |b, x| if x.2 < b.2 { *x } else { b },
            );
        let (c, s, f) = st.polish(best.0, best.1);
        self.push(c, s, f);
        let bound = f.sqrt() + 2.0 * EQ_TOL;
        // Only pieces whose arcs may come closer than that need their roots: |P'(s)| = r₁
        // and the distance to a set is 1-Lipschitz, so d(s) is r₁-Lipschitz and on an arc
        // of length ℓ between samples d_a, d_b, d ≥ (d_a + d_b − r₁ ℓ)/2.
        let mut active = [false; PIECES];
        for (j, flag) in active.iter_mut().enumerate() {
            let slack = st.r1 * PIECE_ARC;
            *flag = d_up[j] + d_up[j + 1] - slack <= 2.0 * bound
                || d_down[j] + d_down[j + 1] - slack <= 2.0 * bound;
        }
        let mut roots = [(0.0, false); 12];
        let nroots = roots_on_pieces(&p, &active, p_size, &mut roots);
        for &(c, cluster) in &roots[..nroots] {
            self.push_root(st, g, c, cluster);
        }
        Some((c, s, f))
    }

    /// The points of circle 1 at cos s = `c`, a root of the eliminated polynomial: the
    /// sign of sin s zeroing G = g₀ + σ g₁ (both if both nearly do, and for an unresolved
    /// `cluster`, as at a double root from a mirror pair ±s).
    fn push_root(&mut self, st: &Setup, g: &TrigPoly, c: f64, cluster: bool) {
        let s = (1.0 - c * c).max(0.0).sqrt();
        if s == 0.0 {
            self.push(c, 0.0, st.f(c, 0.0));
            return;
        }
        let (e, o) = (g.e.eval(c), g.o.eval(c) * s);
        let size = g.e.abs_eval(c) + g.o.abs_eval(c) * s;
        let (gp, gm) = ((e + o).abs(), (e - o).abs());
        if cluster || gp <= gm || gp <= 1e-6 * size {
            self.push(c, s, st.f(c, s));
        }
        if cluster || gm < gp || gm <= 1e-6 * size {
            self.push(c, -s, st.f(c, -s));
        }
    }
}

impl Setup {
    /// The polynomial G of F' = 0 ((E3), (E4) as trigonometric polynomials e(c) + σ o(c))
    /// and whether it is degenerate (nil against the size of its terms).
    fn stationarity(&self) -> (TrigPoly, bool) {
        let (r1s, r2s) = (self.r1, self.r2);
        let (du, dv) = (self.delta.dot(&self.u), self.delta.dot(&self.v));
        let (pdu, pdv) = (self.pd.dot(&self.pu), self.pd.dot(&self.pv));
        let (puu, pvv, puv) = (
            self.pu.norm_squared(),
            self.pv.norm_squared(),
            self.pu.dot(&self.pv),
        );
        let pdd = self.pd.norm_squared();
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
        (g, degenerate)
    }

    /// Polishes the promising candidates `cand` (within 1e-6 of the best), best first,
    /// skipping those next to an already polished one (the polished `seed` is one), into
    /// `minima`, sorted; returns how many.
    fn polished_minima(
        &self,
        cand: &[(f64, f64, f64)],
        seed: Option<(f64, f64, f64)>,
        minima: &mut [(f64, f64, f64); 8],
    ) -> usize {
        let f_best = cand.iter().fold(f64::INFINITY, |lo, x| lo.min(x.2));
        let mut promising = [(0.0f64, 0.0f64, 0.0f64); CANDIDATE_CAPACITY];
        let mut np = 0;
        for x in cand.iter().filter(|x| x.2 <= f_best + 1e-6) {
            promising[np] = *x;
            np += 1;
        }
        let promising = &mut promising[..np];
        promising.sort_unstable_by(|a, b| a.2.total_cmp(&b.2));
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
            minima[nm] = self.polish(c, s);
            nm += 1;
        }
        minima[..nm].sort_unstable_by(|a, b| a.2.total_cmp(&b.2));
        nm
    }

    /// The distance and closest pairs (by `to_pair`, in the original units) from the
    /// sorted `minima` of F, whose candidates reached up to `f_worst`: a continuum where F
    /// is constant over circle 1 or the point lies on circle 2's axis; else the isolated
    /// minima at equal distance, one per basin.
    fn closest_pairs(
        &self,
        minima: &[(f64, f64, f64)],
        f_worst: f64,
        to_pair: impl Fn(f64, f64) -> (V3, V3),
    ) -> CircleDistance {
        let level = minima[0].2.sqrt() + EQ_TOL;
        let (p, q) = to_pair(minima[0].0, minima[0].1);
        let sq = (p - q).norm_squared();
        // A continuum: F constant over circle 1, or P on the axis of circle 2 (all of
        // circle 2 equidistant from it: the spread of |P − K| over K is ≈ 2 r₂ ρ / d).
        let (rho, d2) = self.rho_d2(minima[0].0, minima[0].1);
        let far = (d2 + self.r2 * self.r2 + 2.0 * self.r2 * rho).sqrt();
        let near = minima[0].2.sqrt();
        let axis_spread = 4.0 * self.r2 * rho / (far + near).max(1e-300);
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
                self.barrier_between(a, b, level)
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
}

#[cfg(test)]
pub(crate) mod tests;
