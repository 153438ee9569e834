//! A certified fast path for the closest pair of two circles in 3D, falling back to
//! Eberly's polynomial solver ([`circle_circle_distance`]) whenever its certificate fails.
//!
//! One circle (the smaller, P) is parameterised by its angle t; the distance from a point
//! of P to the other circle K is closed form in K's cylindrical coordinates (Eberly
//! sect. 2): with X, Y the in-plane and z the axial coordinates of the point about K's
//! centre and axis, ρ = √(X² + Y²),
//!
//! (C1) F(t) = d(t)² = (ρ − r_K)² + z²,
//!
//! and X, Y, z are sinusoids in t: X = X₀ + X_c cos t + X_s sin t, etc. The first two
//! derivatives are exact: with b = XX' + YY' (= ρρ'), g = X'² + Y'² + XX'' + YY'',
//!
//! (C2) F'/2 = (ρ − r_K) b/ρ + z z',
//!      F''/2 = r_K b²/ρ³ + (ρ − r_K) g/ρ + z'² + z z''   (X'' = −(X − X₀), ...).
//!
//! **Search and certificate** (all without heap allocation):
//!
//! 1. F is sampled at 16 equally spaced angles; the best sample is polished by bracketed
//!    Newton, which gives an upper bound d_U on the minimum distance.
//! 2. Every arc between samples gets interval bounds. A sinusoid g = g₀ + α cos τ + β sin τ
//!    on an arc of half-width w about its middle (τ ∈ [−w, w]) lies between its end values
//!    widened by the bulge of the cosine: with e_a, e_b the end values of g − g₀ and
//!    m = (e_a + e_b)/2 = α cos w, g − g₀ lies in [min(e_a, e_b) + min(0, m ε),
//!    max(e_a, e_b) + max(0, m ε)], ε = 1/cos w − 1 (because α cos τ lies between α cos w
//!    and α, and the magnitude of β sin τ is at most that of β sin w = (e_b − e_a)/2).
//!    From the boxes of X, Y, z follow a lower bound on F (C1) and a lower bound on F''
//!    (C2, interval arithmetic); d = √F is also r_P-Lipschitz in t, so on an arc of
//!    length ℓ, d ≥ (d_a + d_b − r_P ℓ)/2 (the cheap test, tried first).
//! 3. An arc is *excluded* when its lower bound on d exceeds d_U + 4·10⁻¹⁰ (in units of
//!    the problem scale max(r₁, r₂, |c₁ − c₂|)); otherwise it must be *convex*, F'' > 0 on
//!    it (with a relative rounding margin), else it is halved (down to 1/16 of the
//!    first arcs) and both halves are examined. If an arc is neither excluded nor convex
//!    at the finest level, or no arc is excluded, the certificate fails.
//! 4. The non-excluded arcs form runs of adjacent arcs. On a run F'' > 0, so F has at
//!    most one stationary point there, a minimum, and the run's ends (shared with
//!    excluded arcs) lie above d_U + margin; bracketed Newton on F' (increasing on the
//!    run) finds the run's minimum.
//!
//! **Why the global minimum is never missed.** Every point of P lies on an excluded arc
//! or on a run. On an excluded arc d > d_U + margin ≥ d_min + margin, so the global
//! minimiser lies on a run, where it is the run's only local minimum and is found by that
//! run's Newton search. The answer is the best run minimum; it is certified *unique* when
//! every other run's minimum exceeds it by the margin (which is 4 times Eberly's
//! `EQ_TOL`, under which his solver reports several or infinitely many closest pairs),
//! and when the closest point is not near K's axis (where Eberly reports a continuum).
//! Otherwise the fast path declines, and Eberly's solver gives the answer (and its
//! classification: several pairs, continuum). Parallel or nearly parallel normals
//! (|n₁ × n₂| ≤ 1e-14) go straight to Eberly's closed form; so do non-finite or zero
//! radii. The interval bounds are evaluated in floating point with absolute slack
//! (4e-15 of the unit scale, against rounding of at most a few ulp of quantities ≤ 3)
//! and relative margins far above rounding.
//!
//! The result, where certified, is the same closest pair as Eberly's (to rounding: the
//! property tests, `circle_fast/tests.rs`, check the distance to 1e-12 of the scale and
//! the points), at a fraction of the cost: for the nearly parallel circles of a roller's
//! edge torus and a flange torus, typically 16 samples, one or two Newton runs of a few
//! steps and 16 interval bounds, instead of the degree-8 polynomial's roots. The interval
//! bounds of step 2 are in `circle_fast/interval.rs`.

use super::circle::{
    circle_circle_distance, orthonormal_basis, Circle3, CircleDistance, ClosestPairs,
};
use interval::{Iv, Sinusoid};
use nalgebra::Vector3;
use std::f64::consts::{FRAC_1_SQRT_2, TAU};

mod interval;

type V3 = Vector3<f64>;

/// Normals closer to parallel than this go to Eberly's closed form (as there).
const PARALLEL_TOL: f64 = 1e-14;
/// Eberly's tolerance for equal distances (relative to the scale), see [`super::circle`].
const EQ_TOL: f64 = 1e-10;
/// Separation (in units of the scale) required between the minimum and any other
/// candidate, and by which excluded arcs must lie above the upper bound.
const MARGIN: f64 = 4.0 * EQ_TOL;
/// Number of initial samples (arcs) around the circle.
const N: usize = 16;
/// Length of an initial arc.
const ARC: f64 = TAU / N as f64;
/// cos(2πk/16) and sin(2πk/16).
const COS: [f64; N] = [
    1.0,
    0.9238795325112867,
    FRAC_1_SQRT_2,
    0.3826834323650898,
    0.0,
    -0.3826834323650898,
    -FRAC_1_SQRT_2,
    -0.9238795325112867,
    -1.0,
    -0.9238795325112867,
    -FRAC_1_SQRT_2,
    -0.3826834323650898,
    0.0,
    0.3826834323650898,
    FRAC_1_SQRT_2,
    0.9238795325112867,
];
const SIN: [f64; N] = [
    0.0,
    0.3826834323650898,
    FRAC_1_SQRT_2,
    0.9238795325112867,
    1.0,
    0.9238795325112867,
    FRAC_1_SQRT_2,
    0.3826834323650898,
    0.0,
    -0.3826834323650898,
    -FRAC_1_SQRT_2,
    -0.9238795325112867,
    -1.0,
    -0.9238795325112867,
    -FRAC_1_SQRT_2,
    -0.3826834323650898,
];
/// Subdivision levels below the initial arcs.
const LEVELS: usize = 4;
/// ε = 1/cos(w) − 1 for the half-width w = ARC/2^(level+1) of an arc at each level,
/// rounded up.
const BULGE: [f64; LEVELS + 1] = [
    0.019591158208319,
    0.004838572376312,
    0.001205996470393,
    0.000301272041303,
    0.000075303831096,
];
/// Absolute slack of the interval bounds (quantities are ≤ 3 in units of the scale).
const SLACK: f64 = 4e-15;

/// Closest pair of two circles: the certified fast path where it applies (see the module
/// docs), else Eberly's solver. Same contract as [`circle_circle_distance`].
pub fn circle_circle_distance_fast(c1: &Circle3, c2: &Circle3) -> CircleDistance {
    certified_closest_pair(c1, c2).unwrap_or_else(|| circle_circle_distance(c1, c2))
}

/// The unique closest pair of two circles with its certificate (module docs), or None
/// where the certificate fails (then use [`circle_circle_distance`]). Some(..) always
/// holds [`ClosestPairs::Unique`].
pub fn certified_closest_pair(c1: &Circle3, c2: &Circle3) -> Option<CircleDistance> {
    let n1 = unit(&c1.normal)?;
    let n2 = unit(&c2.normal)?;
    let (r1, r2) = (c1.radius, c2.radius);
    if !(r1 > 0.0 && r2 > 0.0 && r1.is_finite() && r2.is_finite()) {
        return None;
    }
    if n1.cross(&n2).norm() <= PARALLEL_TOL {
        return None;
    }
    // Parameterise the smaller circle.
    let swapped = r1 > r2;
    let ((cp, np, rp), (ck, nk, rk)) = if swapped {
        ((c2.center, n2, r2), (c1.center, n1, r1))
    } else {
        ((c1.center, n1, r1), (c2.center, n2, r2))
    };
    let delta = cp - ck;
    let scale = r1.max(r2).max(delta.norm());
    if !(scale > 0.0 && scale.is_finite()) {
        return None;
    }
    let inv = 1.0 / scale;
    let (u, v) = orthonormal_basis(&np);
    let (e1, e2) = orthonormal_basis(&nk);
    let d = delta * inv;
    let rps = rp * inv;
    let sin = |e: &V3| Sinusoid {
        offset: e.dot(&d),
        cos: rps * e.dot(&u),
        sin: rps * e.dot(&v),
    };
    let pb = Problem {
        x: sin(&e1),
        y: sin(&e2),
        z: sin(&nk),
        rp: rps,
        rk: rk * inv,
    };
    let (_, c, s, _) = pb.minimise()?;
    // Output in the original units, as Eberly's solver writes it.
    let p = cp + (u * c + v * s) * rp;
    let w = p - ck;
    let w = w - nk * nk.dot(&w);
    let m = w.norm();
    if !(m > 0.0 && m.is_finite()) {
        return None;
    }
    let q = ck + w * (rk / m);
    let (a, b) = if swapped { (q, p) } else { (p, q) };
    Some(CircleDistance {
        squared_distance: (a - b).norm_squared(),
        pairs: ClosestPairs::Unique(a, b),
    })
}

/// `n / |n|`, None for a zero or non-finite vector.
fn unit(n: &V3) -> Option<V3> {
    let m = n.norm();
    (m > 0.0 && m.is_finite()).then(|| n / m)
}

/// (cos h, sin h) by Taylor series of a degree chosen by |h| (truncation error below
/// 1e-18 in each branch), libm beyond |h| = 0.4. Newton steps are mostly small, and the
/// short series has a short dependency chain.
#[inline]
pub(crate) fn cos_sin(h: f64) -> (f64, f64) {
    let q = h * h;
    let a = h.abs();
    if a <= 1e-4 {
        // Next terms h⁴/24 ≤ 4e-18, h⁵/120 ≤ 1e-22.
        (1.0 - 0.5 * q, h - h * q * (1.0 / 6.0))
    } else if a <= 0.01 {
        // Next terms h⁸/8! ≤ 3e-21, h⁷/7! ≤ 2e-18.
        let c = 1.0 - q * (0.5 - q * (1.0 / 24.0 - q * (1.0 / 720.0)));
        let s = h - h * q * (1.0 / 6.0 - q * (1.0 / 120.0));
        (c, s)
    } else if a <= 0.4 {
        // Horner in h² with the coefficients ±1/n!; next terms h¹⁶/16!, h¹⁵/15! ≤ 1e-18.
        let s = 1.0 / 6_227_020_800.0;
        let s = s * q - 1.0 / 39_916_800.0;
        let s = s * q + 1.0 / 362_880.0;
        let s = s * q - 1.0 / 5_040.0;
        let s = s * q + 1.0 / 120.0;
        let s = s * q - 1.0 / 6.0;
        let s = h + h * q * s;
        let c = 1.0 / 87_178_291_200.0;
        let c = c * q - 1.0 / 479_001_600.0;
        let c = c * q + 1.0 / 3_628_800.0;
        let c = c * q - 1.0 / 40_320.0;
        let c = c * q + 1.0 / 720.0;
        let c = c * q - 1.0 / 24.0;
        let c = c * q + 0.5;
        (1.0 - q * c, s)
    } else {
        let (s, c) = h.sin_cos();
        (c, s)
    }
}

/// Rotates (c, s) = (cos t, sin t) by the angle h (not renormalised: each rotation
/// changes the norm by rounding only).
#[inline]
pub(crate) fn rotate(c: f64, s: f64, h: f64) -> (f64, f64) {
    let (ch, sh) = cos_sin(h);
    (c * ch - s * sh, s * ch + c * sh)
}

/// True if, after a Newton step of size `a` following one of size `previous`, the error
/// K·a² (K ≈ a/previous², quadratic convergence) is below `tol`; only trusted in the
/// asymptotic regime (previous ≤ 1e-2 and a contraction a/previous ≤ 1e-3).
#[inline]
pub(crate) fn converged(a: f64, previous: f64, tol: f64) -> bool {
    previous <= 1e-2 && a <= 1e-3 * previous && a * a * a <= tol * previous * previous
}

/// One sample of circle P: its angle, (cos, sin), X, Y, z, F and d = √F.
#[derive(Debug, Clone, Copy)]
struct Sample {
    t: f64,
    c: f64,
    s: f64,
    x: f64,
    y: f64,
    z: f64,
    f: f64,
    d: f64,
}

/// The problem in units of the scale: the coordinates of P(t) about K, and the radii.
struct Problem {
    x: Sinusoid,
    y: Sinusoid,
    z: Sinusoid,
    rp: f64,
    rk: f64,
}

/// A run of adjacent convex arcs: its angular range and its best sample.
#[derive(Debug, Clone, Copy)]
struct Run {
    lo: f64,
    hi: f64,
    start: Sample,
}

/// State of the scan over the arcs.
struct Runs {
    /// Arcs on which d provably exceeds this are excluded ...
    bound: f64,
    /// ... and F its square.
    threshold: f64,
    /// The polished best sample (an upper bound on the minimum).
    estimate: Sample,
    /// The run before the first excluded arc (joined with the last one).
    head: Option<Run>,
    /// The run being built.
    current: Option<Run>,
    seen_excluded: bool,
    /// Best minimum so far (t, cos, sin, F) and the second best F.
    best: Option<(f64, f64, f64, f64)>,
    second: f64,
}

impl Problem {
    #[inline]
    fn sample(&self, t: f64, c: f64, s: f64) -> Sample {
        let (x, y, z) = (self.x.at(c, s), self.y.at(c, s), self.z.at(c, s));
        let dr = (x * x + y * y).sqrt() - self.rk;
        let f = dr * dr + z * z;
        Sample {
            t,
            c,
            s,
            x,
            y,
            z,
            f,
            d: f.sqrt(),
        }
    }

    /// F, F'/2 and F''/2 (C1, C2).
    #[inline]
    fn derivs(&self, c: f64, s: f64) -> (f64, f64, f64) {
        let (x, y, z) = (self.x.at(c, s), self.y.at(c, s), self.z.at(c, s));
        let (xp, yp, zp) = (self.x.slope(c, s), self.y.slope(c, s), self.z.slope(c, s));
        let (xpp, ypp, zpp) = (self.x.offset - x, self.y.offset - y, self.z.offset - z);
        let rho = (x * x + y * y).sqrt();
        let inv = 1.0 / rho;
        let b = x * xp + y * yp;
        let g = xp * xp + yp * yp + x * xpp + y * ypp;
        let dr = rho - self.rk;
        (
            dr * dr + z * z,
            dr * b * inv + z * zp,
            (self.rk * b * b * inv * inv + dr * g) * inv + zp * zp + z * zpp,
        )
    }

    /// True if d provably exceeds `bound` on the arc between two samples (of length
    /// `len`): first the Lipschitz bound (d is r_P-Lipschitz in t, so on the arc
    /// d ≥ (d_a + d_b − r_P·len)/2), then the interval bound on F.
    #[inline]
    fn excluded(&self, a: &Sample, b: &Sample, len: f64, bulge: f64, state: &Runs) -> bool {
        if a.d <= state.bound || b.d <= state.bound {
            return false;
        }
        if 0.5 * (a.d + b.d - self.rp * len) - SLACK > state.bound {
            return true;
        }
        let x = Iv::sinusoid(a.x, b.x, self.x.offset, bulge).sq();
        let y = Iv::sinusoid(a.y, b.y, self.y.offset, bulge).sq();
        let z = Iv::sinusoid(a.z, b.z, self.z.offset, bulge).sq();
        let rho_lo = (x.lo + y.lo).sqrt();
        let rho_hi = (x.hi + y.hi).sqrt();
        let gap = (rho_lo - self.rk).max(self.rk - rho_hi).max(0.0);
        gap * gap + z.lo > state.threshold
    }

    /// True if F'' > 0 on the whole arc, by interval arithmetic on (C2).
    fn convex(&self, a: &Sample, b: &Sample, bulge: f64) -> bool {
        let iv = |s: &Sinusoid, ga: f64, gb: f64| Iv::sinusoid(ga, gb, s.offset, bulge);
        let x = iv(&self.x, a.x, b.x);
        let y = iv(&self.y, a.y, b.y);
        let z = iv(&self.z, a.z, b.z);
        let slope = |s: &Sinusoid| Iv::sinusoid(s.slope(a.c, a.s), s.slope(b.c, b.s), 0.0, bulge);
        let (xp, yp, zp) = (slope(&self.x), slope(&self.y), slope(&self.z));
        let (xpp, ypp, zpp) = (
            x.reflect(self.x.offset),
            y.reflect(self.y.offset),
            z.reflect(self.z.offset),
        );
        let (xs, ys) = (x.sq(), y.sq());
        let rho_lo = (xs.lo + ys.lo).sqrt();
        let rho_hi = (xs.hi + ys.hi).sqrt();
        if rho_lo.is_nan() || rho_lo <= 1e-6 * self.rk || !rho_hi.is_finite() {
            return false;
        }
        let bb = x.mul(xp).add(y.mul(yp)).sq();
        let g = xp.sq().add(yp.sq()).add(x.mul(xpp)).add(y.mul(ypp));
        // r_K b²/ρ³ ≥ r_K·min b²/ρ_hi³; (ρ − r_K)/ρ = 1 − r_K/ρ is increasing in ρ.
        let t1 = self.rk * bb.lo / (rho_hi * rho_hi * rho_hi);
        let t1_hi = self.rk * bb.hi / (rho_lo * rho_lo * rho_lo);
        let ratio = Iv {
            lo: 1.0 - self.rk / rho_lo,
            hi: 1.0 - self.rk / rho_hi,
        };
        let t2 = ratio.mul(g);
        let t3 = zp.sq().add(z.mul(zpp));
        let lo = t1 + t2.lo + t3.lo;
        let size = t1_hi + t2.magnitude() + t3.magnitude();
        lo > 1e-10 * size && size.is_finite()
    }

    /// The minimum of F on [lo, hi] from the start (F' increasing there, or at least
    /// F'(lo) < 0 < F'(hi) for the bracket logic), by Newton's method safeguarded by
    /// bisection (`rtsafe`). Returns (t, cos t, sin t, F).
    fn bracketed_min(&self, start: &Sample, mut lo: f64, mut hi: f64) -> (f64, f64, f64, f64) {
        let (mut t, mut c, mut s) = (start.t, start.c, start.s);
        let mut previous = f64::INFINITY;
        for _ in 0..80 {
            let (_, f1, f2) = self.derivs(c, s);
            if f1 == 0.0 || !f1.is_finite() {
                break;
            }
            if f1 < 0.0 {
                lo = t;
            } else {
                hi = t;
            }
            let newton = t - f1 / f2;
            let (target, is_newton) = if f2 > 0.0 && newton >= lo && newton <= hi {
                (newton, true)
            } else {
                (0.5 * (lo + hi), false)
            };
            let step = target - t;
            (c, s) = rotate(c, s, step);
            t = target;
            // After a Newton step h the error is about K·h², K ≈ |h|/|previous h|²: done
            // when that is below 1e-16 (or h below 1e-8, as Eberly's polish); bisection
            // stops on a bracket at rounding level.
            let a = step.abs();
            if (is_newton && (a < 1e-8 || converged(a, previous, 1e-16))) || hi - lo <= 1e-15 {
                break;
            }
            previous = if is_newton { a } else { f64::INFINITY };
        }
        let m = (c * c + s * s).sqrt();
        let p = self.sample(t, c / m, s / m);
        (t, p.c, p.s, p.f)
    }

    /// The certified global minimum (module docs): (t, cos t, sin t, F), or None.
    fn minimise(&self) -> Option<(f64, f64, f64, f64)> {
        // 1. Samples (vectorisable) and an upper bound at the vertex of the parabola
        // through the best sample and its neighbours.
        let mut xs = [0.0; N];
        let mut ys = [0.0; N];
        let mut zs = [0.0; N];
        let mut fs = [0.0; N];
        for k in 0..N {
            let (c, s) = (COS[k], SIN[k]);
            xs[k] = self.x.offset + self.x.cos * c + self.x.sin * s;
            ys[k] = self.y.offset + self.y.cos * c + self.y.sin * s;
            zs[k] = self.z.offset + self.z.cos * c + self.z.sin * s;
            let dr = (xs[k] * xs[k] + ys[k] * ys[k]).sqrt() - self.rk;
            fs[k] = dr * dr + zs[k] * zs[k];
        }
        let ds = fs.map(f64::sqrt);
        let at = |k: usize| {
            let j = k % N;
            Sample {
                t: k as f64 * ARC,
                c: COS[j],
                s: SIN[j],
                x: xs[j],
                y: ys[j],
                z: zs[j],
                f: fs[j],
                d: ds[j],
            }
        };
        let best = (1..N).fold(0, |b, k| if fs[k] < fs[b] { k } else { b });
        if !fs[best].is_finite() {
            return None;
        }
        let (fm, f0, fp) = (fs[(best + N - 1) % N], fs[best], fs[(best + 1) % N]);
        let curvature = fm - 2.0 * f0 + fp;
        let offset = if curvature > 0.0 {
            (0.5 * ARC * (fm - fp) / curvature).clamp(-0.5 * ARC, 0.5 * ARC)
        } else {
            0.0
        };
        let (c, s) = rotate(COS[best], SIN[best], offset);
        let vertex = self.sample(best as f64 * ARC + offset, c, s);
        let start = if vertex.f < f0 { vertex } else { at(best) };
        let t0 = best as f64 * ARC;
        let (t, c, s, f) = self.bracketed_min(&start, t0 - ARC, t0 + ARC);
        let estimate = if f < start.f {
            Sample {
                t,
                c,
                s,
                f,
                d: f.sqrt(),
                ..start
            }
        } else {
            start
        };
        let bound = estimate.d + MARGIN;
        let mut state = Runs {
            bound,
            threshold: bound * bound,
            estimate,
            head: None,
            current: None,
            seen_excluded: false,
            best: None,
            second: f64::INFINITY,
        };
        // 2., 3. Arcs in order: excluded or convex, halved where neither.
        for k in 0..N {
            self.examine(&at(k), &at(k + 1), 0, &mut state)?;
        }
        // 4. The run that wraps around 2π joins the first one.
        if !state.seen_excluded {
            return None;
        }
        let last = match (state.current.take(), state.head.take()) {
            (Some(mut tail), Some(head)) => {
                tail.hi = head.hi + TAU;
                if head.start.f < tail.start.f {
                    tail.start = Sample {
                        t: head.start.t + TAU,
                        ..head.start
                    };
                }
                Some(tail)
            }
            (tail, head) => tail.or(head),
        };
        if let Some(run) = last {
            self.finish(run, &mut state)?;
        }
        let best_min = state.best?;
        let d = best_min.3.sqrt();
        if state.second.sqrt() <= d + MARGIN {
            return None;
        }
        // Near K's axis all of K is (nearly) equidistant from the point: Eberly reports a
        // continuum when 4 r_K ρ / (far + near) ≤ EQ_TOL; stay well clear of that.
        let (x, y, z) = (
            self.x.at(best_min.1, best_min.2),
            self.y.at(best_min.1, best_min.2),
            self.z.at(best_min.1, best_min.2),
        );
        let rho = (x * x + y * y).sqrt();
        let far = ((rho + self.rk) * (rho + self.rk) + z * z).sqrt();
        let spread = 4.0 * self.rk * rho;
        if spread.is_nan() || spread <= 100.0 * EQ_TOL * (far + d) {
            return None;
        }
        Some(best_min)
    }

    /// Examines the arc between two samples at a subdivision level, in order: excluded,
    /// convex (added to the current run) or halved. None if the certificate fails.
    fn examine(&self, a: &Sample, b: &Sample, level: usize, state: &mut Runs) -> Option<()> {
        let len = ARC / (1 << level) as f64;
        if self.excluded(a, b, len, BULGE[level], state) {
            if let Some(run) = state.current.take() {
                if state.seen_excluded {
                    self.finish(run, state)?;
                } else {
                    state.head = Some(run);
                }
            }
            state.seen_excluded = true;
            return Some(());
        }
        if self.convex(a, b, BULGE[level]) {
            let better = |p: &Sample, q: &Sample| if q.f < p.f { *q } else { *p };
            state.current = Some(match state.current {
                None => Run {
                    lo: a.t,
                    hi: b.t,
                    start: better(a, b),
                },
                Some(run) => Run {
                    lo: run.lo,
                    hi: b.t,
                    start: better(&better(&run.start, a), b),
                },
            });
            return Some(());
        }
        if level == LEVELS {
            return None;
        }
        let (c, s) = (a.c + b.c, a.s + b.s);
        let m = (c * c + s * s).sqrt();
        let mid = self.sample(0.5 * (a.t + b.t), c / m, s / m);
        self.examine(a, &mid, level + 1, state)?;
        self.examine(&mid, b, level + 1, state)
    }

    /// The minimum of a finished run (F convex on it), recorded as best or second best.
    fn finish(&self, run: Run, state: &mut Runs) -> Option<()> {
        let mut start = run.start;
        let e = state.estimate;
        let te = e.t.rem_euclid(TAU);
        for t in [te, te + TAU] {
            if t > run.lo && t < run.hi && e.f < start.f {
                start = Sample { t, ..e };
            }
        }
        let m = self.bracketed_min(&start, run.lo, run.hi);
        if !m.3.is_finite() {
            return None;
        }
        match state.best {
            Some(b) if b.3 <= m.3 => state.second = state.second.min(m.3),
            previous => {
                if let Some(b) = previous {
                    state.second = state.second.min(b.3);
                }
                state.best = Some(m);
            }
        }
        Some(())
    }
}

#[cfg(test)]
mod tests;
