//! The roller end–flange overlap as a field over the roller end (not in the paper).
//!
//! The paper's detectors (sect. 2) reduce the end–flange contact to the deepest point of
//! one pairing of figures. Where the nearly flat end face (B1: a 5 m sphere) lies almost
//! parallel to the nearly flat flange face (0.11° opening), that point jumps between the
//! edge torus, the face and the rim within microradians of tilt while the overlap spreads
//! over the whole face (`docs/dynamics.md`, "Why the steps collapse at 2000 N"). This
//! module measures the whole overlap instead, as a field g over the end:
//!
//! * the end surface is written as a graph over its end plane, h(ρ) along the roller axis
//!   (end sphere for ρ ≤ ρ_j, edge torus out to the roller radius), exactly;
//! * g at a point of the end surface is its depth inside the flange, from the flange's
//!   meridian profile (root torus, cone, rim torus), exactly; the load p(g) of the
//!   surfaces' asperities ([`Asperities`]) reaches across gaps of a few σ;
//! * points of the end plane are addressed in coordinates (u, v) that follow the ring's
//!   circles ([`Field`]), in which the support {p > 0} is nearly convex (both solids are
//!   convex but for the flange's bend around the ring axis, which the coordinates undo);
//! * the support's centre and principal axes are found from chords through the detected
//!   deepest point and two passes of rays over the area; from that centroid, rays in the
//!   frame stretched along the axes find the boundary (one bracketed root each), and Gauss
//!   points along each ray integrate the load, its moments and the flange normal.
//!
//! The integration nodes move with the support's boundary, so every integral is a smooth
//! function of the pose as the overlap moves from the edge across the face to the rim; the
//! integrand vanishes at the boundary, so the roots' tolerance enters the load and its
//! centre only at second order.
//!
//! A run integrates the same end and flange at nearby poses step after step:
//! [`integrate_near`] starts from the frame the last integration left ([`SupportFrame`]:
//! the centroid and axes of the area its final rays bounded, and their reaches) instead of
//! the chords and passes, at about half the cost.

use crate::geometry::end_flange::{Flange, RollerEnd};
use crate::geometry::primitives::Vec3;
use std::f64::consts::TAU;
use std::sync::LazyLock;

/// Rays from the support's centre (uniform in angle: the periodic trapezoidal rule).
const RAYS: usize = 24;
/// Rays that find the support's centroid and principal axes first.
const COARSE_RAYS: usize = 12;

/// (sin θₖ, cos θₖ) of the N rays θₖ = (k + ½)·2π/N, computed once.
fn ray_angles<const N: usize>() -> [(f64, f64); N] {
    let step = TAU / N as f64;
    std::array::from_fn(|k| ((k as f64 + 0.5) * step).sin_cos())
}

/// The angles of the final rays.
static RAY_ANGLES: LazyLock<[(f64, f64); RAYS]> = LazyLock::new(ray_angles::<RAYS>);
/// The angles of the coarse rays.
static COARSE_RAY_ANGLES: LazyLock<[(f64, f64); COARSE_RAYS]> =
    LazyLock::new(ray_angles::<COARSE_RAYS>);
/// Gauss–Legendre nodes and weights on [0, 1], five points (exact to degree 9).
const GAUSS_NODES: [f64; 5] = [
    0.046_910_077_030_668_,
    0.230_765_344_947_158_5,
    0.5,
    0.769_234_655_052_841_5,
    0.953_089_922_969_332,
];
const GAUSS_WEIGHTS: [f64; 5] = [
    0.118_463_442_528_094_5,
    0.239_314_335_249_683_2,
    0.284_444_444_444_444_4,
    0.239_314_335_249_683_2,
    0.118_463_442_528_094_5,
];
/// Slope of the end surface continued past the roller radius (a steep fall, so that the
/// support's boundary lies on the end; any value ≫ 1 does).
const PAST_THE_EDGE_SLOPE: f64 = 10.0;
/// A boundary root is accepted when |g| falls below this fraction of the overlap at the
/// ray's start (the root's error enters the load and its centre at second order).
const ROOT_FTOL: f64 = 1e-6;
/// A Newton step is taken as the root without checking when |g| before it is below this
/// fraction of the overlap at the ray's start: for a parabolic overlap g₀(1 − ρ²) the
/// step's error is then at most (g/g₀)²/8 = 1.25e-5 of the reach. The integrand vanishes on
/// the boundary, so that error enters the load, its moments and its centre at second order
/// (1e-10); only the support's area (an output) and, for smooth surfaces, the stiffness
/// integral carry it at first order (2.5e-5; with roughness the boundary lies at g = −4σ,
/// where dp/dg is 1.8 %, so 5e-7). One evaluation per boundary fewer than at 1e-3.
const NEWTON_FTOL: f64 = 1e-2;

/// The roller end as a graph over its end plane: the height h(ρ) along the outward axis
/// of the surface point at distance ρ from the axis, measured from the edge torus's centre.
#[derive(Debug, Clone, Copy)]
struct EndGraph {
    origin: Vec3,
    axis: Vec3,
    sphere_offset: f64,
    sphere_radius: f64,
    junction: f64,
    tube_center: f64,
    tube_radius: f64,
}

impl EndGraph {
    fn new(end: &RollerEnd) -> Self {
        let (t, s) = (&end.torus, &end.sphere);
        Self {
            origin: t.origin,
            axis: t.axis,
            sphere_offset: (s.center - t.origin).dot(&t.axis),
            sphere_radius: s.radius,
            junction: s.radius * s.cap_angle.sin(),
            tube_center: t.major_radius,
            tube_radius: t.minor_radius,
        }
    }

    /// dh/dρ, bounded by the slope past the edge (the torus's is vertical at the edge).
    fn slope(&self, rho: f64) -> f64 {
        let s = if rho <= self.junction {
            -rho / ((self.sphere_radius - rho) * (self.sphere_radius + rho)).sqrt()
        } else {
            let x = rho - self.tube_center;
            if x < self.tube_radius {
                -x / ((self.tube_radius - x) * (self.tube_radius + x)).sqrt()
            } else {
                -PAST_THE_EDGE_SLOPE
            }
        };
        s.max(-PAST_THE_EDGE_SLOPE)
    }

    /// h(ρ) at K radii at once: the end sphere inside the junction radius, the edge torus
    /// outside it, and a steep fall past the roller radius (no surface there). Without
    /// branches (the pieces chosen by selection), so that the points' square roots overlap.
    fn heights<const K: usize>(&self, rho: &[f64; K]) -> [f64; K] {
        std::array::from_fn(|k| {
            let rho = rho[k];
            let on_sphere = rho <= self.junction;
            let x = rho - self.tube_center;
            let (reach, offset, base) = if on_sphere {
                (self.sphere_radius, rho, self.sphere_offset)
            } else {
                (self.tube_radius, x, 0.0)
            };
            let root = ((reach - offset) * (reach + offset)).max(0.0).sqrt();
            if on_sphere || x < self.tube_radius {
                base + root
            } else {
                -PAST_THE_EDGE_SLOPE * (x - self.tube_radius)
            }
        })
    }
}

/// A flange as its meridian profile about the ring axis: root torus, cone, rim torus.
#[derive(Debug, Clone, Copy)]
struct FlangeProfile {
    origin: Vec3,
    axis: Vec3,
    s0: f64,
    rho0: f64,
    ds: f64,
    drho: f64,
    normal: (f64, f64),
    g_min: f64,
    g_max: f64,
    root: (f64, f64, f64),
    rim: (f64, f64, f64),
}

impl FlangeProfile {
    fn new(flange: &Flange) -> Self {
        let c = &flange.cone;
        let tube = |t: &crate::geometry::primitives::TorusPatch| {
            (
                (t.origin - c.origin).dot(&c.axis),
                t.major_radius,
                t.minor_radius,
            )
        };
        Self {
            origin: c.origin,
            axis: c.axis,
            s0: c.s0,
            rho0: c.rho0,
            ds: c.ds,
            drho: c.drho,
            // Outward meridian normal side·(−dρ, ds) (geometry::end_flange).
            normal: (-c.side * c.drho, c.side * c.ds),
            g_min: c.g_min,
            g_max: c.g_max,
            root: tube(&flange.root),
            rim: tube(&flange.rim),
        }
    }

    /// The depth of each of K points `p` (components by array) inside the flange (positive
    /// inside, negative outside) and the flange's outward unit normal at its foot: the cone
    /// between the root and rim tori's tangent circles, the nearer torus beyond them.
    /// Without branches: the torus's distance is computed for every point and selected.
    fn depths<const K: usize>(&self, p: &[[f64; K]; 3]) -> ([f64; K], [[f64; K]; 3]) {
        let (o, ax) = (&self.origin, &self.axis);
        let mut depth = [0.0; K];
        let mut normal = [[0.0; K]; 3];
        for k in 0..K {
            let d = [p[0][k] - o[0], p[1][k] - o[1], p[2][k] - o[2]];
            let s = d[0] * ax[0] + d[1] * ax[1] + d[2] * ax[2];
            let radial = [d[0] - ax[0] * s, d[1] - ax[1] * s, d[2] - ax[2] * s];
            let rho =
                (radial[0] * radial[0] + radial[1] * radial[1] + radial[2] * radial[2]).sqrt();
            let inv_rho = if rho > 0.0 { 1.0 / rho } else { 0.0 };
            let g = (s - self.s0) * self.ds + (rho - self.rho0) * self.drho;
            let on_root = g < self.g_min;
            let on_cone = !on_root && g <= self.g_max;
            let (cs, crho, r) = if on_root { self.root } else { self.rim };
            let (vs, vr) = (s - cs, rho - crho);
            let length = (vs * vs + vr * vr).sqrt();
            let (ns, nr) = self.normal;
            let cone_distance = (s - self.s0) * ns + (rho - self.rho0) * nr;
            let (depth_k, along, across) = if on_cone {
                (-cone_distance, ns, nr)
            } else {
                (r - length, vs / length, vr / length)
            };
            depth[k] = depth_k;
            for i in 0..3 {
                normal[i][k] = ax[i] * along + radial[i] * (inv_rho * across);
            }
        }
        (depth, normal)
    }
}

/// The overlap field g over the end plane. Its points are addressed in coordinates that
/// follow the ring's circles: (a, b) = (v, u − v²/2ρ₀) in the end's frame, ρ₀ the roller
/// axis's distance from the ring axis, so that u is (to v⁴/8ρ₀³, 1 µm over B1's end) the
/// radial distance from the ring's circle of radius ρ₀ and v the distance along it. The
/// flange's figures lie at constant distance from the ring axis, so its rim and root are
/// lines of nearly constant u, and an overlap along the rim (a sliver bent with the rim's
/// circle, whose sagitta over a 2 mm face exceeds its width) is straight in (u, v). The
/// map is a shear: it keeps areas (dA = du dv). The end's frame: w from the ring axis
/// towards the roller axis in the end plane, t = axis × w.
struct Field {
    end: EndGraph,
    flange: FlangeProfile,
    t: Vec3,
    w: Vec3,
    /// The roller axis's distance from the ring axis in the end plane, ρ₀ [m].
    rho0: f64,
    /// The surfaces' roughness law ([`Asperities`]).
    asperities: Asperities,
    /// Whether to integrate the energy density too.
    energy: bool,
}

/// The load of the surfaces' asperities at a local overlap g (negative: a gap), per unit
/// of the foundation's modulus: σ ln(1 + e^{g/σ}), less its value at the support's edge
/// g = −CUT·σ so that it vanishes there. For g ≫ σ it is the overlap g of smooth surfaces;
/// across a gap it falls as σ e^{−h/σ}, the load of Greenwood & Williamson's asperities
/// with an exponential distribution of heights of scale σ (Proc. R. Soc. A 295, 1966), the
/// composite roughness. With σ = 0 it is max(g, 0).
#[derive(Debug, Clone, Copy)]
pub struct Asperities {
    /// σ [m].
    pub sigma: f64,
}

/// Where the asperities' load is cut off: at a gap of CUT·σ (e^{−4} = 1.8 % of σ's load).
const CUT: f64 = 4.0;

impl Asperities {
    /// The gap beyond which nothing is carried [m].
    pub fn reach(&self) -> f64 {
        CUT * self.sigma
    }

    /// The load per unit modulus p(g) [m].
    fn load(&self, g: f64) -> f64 {
        self.load_and_stiffness(g).0
    }

    /// dp/dg [-]: the share of the area that carries.
    #[cfg(test)]
    fn stiffness(&self, g: f64) -> f64 {
        self.load_and_stiffness(g).1
    }

    /// The load p(g) [m] and its slope dp/dg [-] together, from one exponential:
    /// with e = exp(−|x|), x = g/σ, ln(1 + eˣ) = max(x, 0) + ln(1 + e) and the logistic
    /// slope 1/(1 + e^{−x}) is 1/(1 + e) for x ≥ 0 and e/(1 + e) below. Nothing beyond
    /// the reach −CUT·σ (load and slope 0).
    fn load_and_stiffness(&self, g: f64) -> (f64, f64) {
        if self.sigma > 0.0 {
            if g <= -self.reach() {
                return (0.0, 0.0);
            }
            let x = g / self.sigma;
            let e = (-x.abs()).exp();
            let softplus = x.max(0.0) + e.ln_1p();
            let slope = if x >= 0.0 { 1.0 } else { e } / (1.0 + e);
            ((self.sigma * (softplus - SOFTPLUS_AT_CUT)).max(0.0), slope)
        } else if g > 0.0 {
            (g, 1.0)
        } else {
            (0.0, 0.0)
        }
    }

    /// ∫ p dg from the edge of the support to g [m²]: the energy density per unit modulus
    /// (five-point Gauss on the smooth load; exact, g²/2, without roughness).
    fn energy(&self, g: f64) -> f64 {
        let edge = -self.reach();
        if g <= edge {
            return 0.0;
        }
        if self.sigma == 0.0 {
            return 0.5 * g * g;
        }
        let width = g - edge;
        GAUSS_NODES
            .iter()
            .zip(GAUSS_WEIGHTS)
            .map(|(x, w)| w * width * self.load(edge + x * width))
            .sum()
    }
}

/// ln(1 + e^{−CUT}), the asperities' load at the support's edge (per σ).
const SOFTPLUS_AT_CUT: f64 = 0.018_149_927_917_809_738;

impl Field {
    /// The field of `end` against `flange`; None if the ring axis does not cross the end
    /// plane at a useful angle (never in a bearing: the axes are within degrees).
    fn new(end: EndGraph, flange: FlangeProfile) -> Option<Self> {
        let e = end.axis;
        let cos = flange.axis.dot(&e);
        if cos.abs() < 0.5 {
            return None;
        }
        // The ring axis O + s A meets the end plane (P − O_t)·e = 0 at s.
        let s = (end.origin - flange.origin).dot(&e) / cos;
        let crossing = flange.origin + flange.axis * s;
        let outward = end.origin - crossing;
        let rho0 = outward.norm();
        let w = outward.try_normalize(1e-12)?;
        Some(Self {
            end,
            flange,
            t: e.cross(&w),
            w,
            rho0,
            asperities: Asperities { sigma: 0.0 },
            energy: false,
        })
    }

    /// The (u, v) of the end-plane projection of `p`.
    fn coordinates(&self, p: &Vec3) -> (f64, f64) {
        let rel = p - self.end.origin;
        let (a, b) = (rel.dot(&self.t), rel.dot(&self.w));
        (b + 0.5 * a * a / self.rho0, a)
    }
}

/// The field at K points at once ([`Field::samples`]), as arrays: depth, surface point on
/// the roller and flange normal of each, by component.
struct Samples<const K: usize> {
    depth: [f64; K],
    point: [[f64; K]; 3],
    normal: [[f64; K]; 3],
}

impl Field {
    /// The field at K points (u, v) at once ([`Field::samples_plane`]).
    fn samples<const K: usize>(&self, u: &[f64; K], v: &[f64; K]) -> Samples<K> {
        let plane: [(f64, f64); K] = std::array::from_fn(|k| self.plane(u[k], v[k]));
        self.samples_plane(&plane.map(|p| p.0), &plane.map(|p| p.1))
    }

    /// The field at K end-plane points (a, b) at once: the end's surface point over each
    /// and its depth in the flange with the flange's normal. The points' chains of square
    /// roots and divisions (the end's radius and height, the flange's radius, the tube's
    /// distance) are independent and taken without branches, so the processor overlaps
    /// them.
    fn samples_plane<const K: usize>(&self, a: &[f64; K], b: &[f64; K]) -> Samples<K> {
        let rho: [f64; K] = std::array::from_fn(|k| (a[k] * a[k] + b[k] * b[k]).sqrt());
        let h = self.end.heights(&rho);
        let (o, t, w, e) = (&self.end.origin, &self.t, &self.w, &self.end.axis);
        let point: [[f64; K]; 3] = std::array::from_fn(|i| {
            std::array::from_fn(|k| o[i] + t[i] * a[k] + w[i] * b[k] + e[i] * h[k])
        });
        let (depth, normal) = self.flange.depths(&point);
        Samples {
            depth,
            point,
            normal,
        }
    }
}

/// One sample of the field: depth and flange normal.
struct Sample {
    depth: f64,
    normal: Vec3,
}

impl Field {
    /// The end-plane coordinates (a, b) of (u, v).
    fn plane(&self, u: f64, v: f64) -> (f64, f64) {
        (v, u - 0.5 * v * v / self.rho0)
    }

    fn sample(&self, u: f64, v: f64) -> Sample {
        let (a, b) = self.plane(u, v);
        self.sample_plane(a, b)
    }

    /// The sample at the end-plane point (a, b) ([`Field::samples_plane`] at one point).
    fn sample_plane(&self, a: f64, b: f64) -> Sample {
        let s = self.samples_plane(&[a], &[b]);
        Sample {
            depth: s.depth[0],
            normal: Vec3::new(s.normal[0][0], s.normal[1][0], s.normal[2][0]),
        }
    }

    /// The local overlap g at (a, b) shifted by the asperities' reach: positive on the
    /// support.
    fn depth(&self, a: f64, b: f64) -> f64 {
        self.sample(a, b).depth + self.asperities.reach()
    }

    /// g at (u, v) + r (du, dv) (shifted by the asperities' reach) and its derivative in
    /// r: the end-plane point moves by (da, db) = (dv, du − v dv/ρ₀), the end point by that
    /// plus e h'(ρ_e) dρ_e/dr, and g = −distance falls along the flange normal.
    fn depth_along(&self, (u, v): (f64, f64), (du, dv): (f64, f64), r: f64) -> (f64, f64) {
        let (u, v) = (u + r * du, v + r * dv);
        let (a, b) = self.plane(u, v);
        let (da, db) = (dv, du - v * dv / self.rho0);
        let rho = (a * a + b * b).sqrt();
        let s = self.sample_plane(a, b);
        let drho = if rho > 0.0 {
            (a * da + b * db) / rho
        } else {
            0.0
        };
        let dp = self.t * da + self.w * db + self.end.axis * (self.end.slope(rho) * drho);
        (s.depth + self.asperities.reach(), -s.normal.dot(&dp))
    }

    /// The distance r > 0 from (u, v), where g = `inside` > 0, along `dir` to the support's
    /// boundary, from the guess `start` ([`BoundarySearch`]).
    fn boundary(&self, p: (f64, f64), dir: (f64, f64), inside: f64, start: f64) -> f64 {
        self.boundaries(p, &[dir], inside, &[start])[0]
    }

    /// The boundary along each of the N rays `dirs` from (u, v), where g = `inside` > 0,
    /// each from its guess in `starts`: every ray's search takes the same evaluations as
    /// it would alone ([`BoundarySearch`]), but the rays' Newton steps are taken in turn,
    /// one ray's after another's, so that the processor overlaps their independent chains
    /// of square roots and divisions instead of waiting for each.
    fn boundaries<const N: usize>(
        &self,
        p: (f64, f64),
        dirs: &[(f64, f64); N],
        inside: f64,
        starts: &[f64; N],
    ) -> [f64; N] {
        let reach = 2.5 * (self.end.tube_center + self.end.tube_radius);
        let mut searches: [BoundarySearch; N] = std::array::from_fn(|k| {
            BoundarySearch::new(reach / dirs[k].0.hypot(dirs[k].1), inside, starts[k])
        });
        let mut roots: [Option<f64>; N] = [None; N];
        while roots.iter().any(Option::is_none) {
            for (root, (search, dir)) in roots.iter_mut().zip(searches.iter_mut().zip(dirs)) {
                if root.is_none() {
                    let (g, slope) = self.depth_along(p, *dir, search.r);
                    *root = search.take(g, slope);
                }
            }
        }
        roots.map(|root| root.unwrap_or(f64::NAN))
    }

    /// The midpoint of the chord through `p` along `u`, and the chord's half-length.
    fn chord_midpoint(&self, p: (f64, f64), u: (f64, f64), scale: f64) -> ((f64, f64), f64) {
        let inside = self.depth(p.0, p.1);
        let [forward, backward] = self.boundaries(p, &[u, (-u.0, -u.1)], inside, &[scale; 2]);
        let shift = 0.5 * (forward - backward);
        (
            (p.0 + shift * u.0, p.1 + shift * u.1),
            0.5 * (forward + backward),
        )
    }
}

/// One search for the support's boundary along a ray: Newton's method kept within the
/// bracket found so far (bisection when it leaves it). g is concave along the ray, so
/// Newton's steps from outside approach the root monotonically. The bracket starts at the
/// ray's `limit`, 2.5 roller radii, where every point is off the end (g falls steeply past
/// its edge), and short of the ring's circle's other side. At most 100 evaluations.
struct BoundarySearch {
    lo: f64,
    hi: f64,
    /// Where g is to be evaluated next.
    r: f64,
    /// g at the ray's start.
    inside: f64,
    evaluations: usize,
}

impl BoundarySearch {
    fn new(limit: f64, inside: f64, start: f64) -> Self {
        Self {
            lo: 0.0,
            hi: limit,
            r: start.clamp(1e-12, limit),
            inside,
            evaluations: 0,
        }
    }

    /// Takes g and dg/dr at `self.r`: the root, once found, or None with the next `r` set.
    fn take(&mut self, g: f64, slope: f64) -> Option<f64> {
        let r = self.r;
        if g.abs() <= ROOT_FTOL * self.inside {
            return Some(r);
        }
        if g > 0.0 {
            self.lo = r;
        } else {
            self.hi = r;
        }
        let (lo, hi) = (self.lo, self.hi);
        if hi - lo <= 1e-12 * hi {
            return Some(0.5 * (lo + hi));
        }
        let newton = r - g / slope;
        let in_bracket = slope < 0.0 && newton > lo && newton < hi;
        if in_bracket && g.abs() <= NEWTON_FTOL * self.inside {
            return Some(newton);
        }
        self.r = if in_bracket { newton } else { 0.5 * (lo + hi) };
        self.evaluations += 1;
        (self.evaluations == 100).then_some(0.5 * (lo + hi))
    }
}

/// The overlap of a roller end with a flange, integrated over its whole support.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DistributedOverlap {
    /// The load integral V = ∫ p(g) dA [m³] (without roughness, the overlap volume ∫ g dA;
    /// [`Asperities`]).
    pub volume: f64,
    /// ∫ g_p dA, the stiffness integral, g_p = dp/dg the carrying share [m²].
    pub stiffness_area: f64,
    /// ∫ ∫p dg dA [m⁴], the energy integral (only if asked for; else 0).
    pub energy: f64,
    /// Support area A = ∫ dA [m²] (on the end plane).
    pub area: f64,
    /// Largest load p(g) found [m].
    pub max_depth: f64,
    /// Centre of the load, ∫ p P_m dA / V, with P_m midway between the surfaces [m].
    pub centre: Vec3,
    /// Overlap-weighted flange normal, unit, from the flange towards the roller.
    pub normal: Vec3,
    /// Semi-axes (larger first) of the ellipse whose Hertzian pressure has the overlap's
    /// second moments about its centre: a = √(5 λ) for each principal moment λ [m].
    pub semi_axes: (f64, f64),
    /// Unit direction of the larger semi-axis.
    pub major_axis: Vec3,
}

/// Integrates the load of `end` on `flange` with the roughness `asperities` from `deepest`,
/// the roller end's point nearest to or deepest in the flange (the detected contact's P₁);
/// with `energy` also the energy integral. None if the load there is nil.
pub fn integrate(
    end: &RollerEnd,
    flange: &Flange,
    deepest: &Vec3,
    asperities: Asperities,
    energy: bool,
) -> Option<DistributedOverlap> {
    integrate_from(end, flange, deepest, asperities, energy, None).map(|(overlap, ..)| overlap)
}

/// The frame of the final rays that one integration leaves for the next at a nearby pose
/// ([`integrate_near`]): the support's centroid and principal axes from the reach of its
/// final rays (exact moments of the area the rays bound), and guesses of each ray's reach.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SupportFrame {
    stretch: Stretch,
    starts: [f64; RAYS],
}

/// [`integrate`], and the support's frame for the next integration at a nearby pose. With
/// `near`, the frame an integration at a nearby pose left: its rays are used as they are
/// when its centre lies inside the support here, and the chords and both passes of
/// [`Field::support_frame`] (two fifths of the field's samples) are not taken. The
/// integrals then differ from [`integrate`]'s by the quadrature's dependence on its frame
/// only (the integrand vanishes on the boundary the rays find, wherever they start), and
/// for a fixed `near` they are as smooth in the pose as [`integrate`]'s.
pub fn integrate_near(
    end: &RollerEnd,
    flange: &Flange,
    deepest: &Vec3,
    asperities: Asperities,
    energy: bool,
    near: Option<&SupportFrame>,
) -> Option<(DistributedOverlap, SupportFrame)> {
    let (overlap, frame, reaches) = integrate_from(end, flange, deepest, asperities, energy, near)?;
    let (stretch, points) = shape_of_support(&frame, &RAY_ANGLES, &reaches);
    let next = SupportFrame {
        stretch,
        starts: predicted_reaches(&stretch, &RAY_ANGLES, &points),
    };
    Some((overlap, next))
}

/// The overlap integrated from the frame `near` if it serves here, else from a fresh one
/// ([`Field::support_frame`]), with the frame of its final rays and their reaches.
fn integrate_from(
    end: &RollerEnd,
    flange: &Flange,
    deepest: &Vec3,
    asperities: Asperities,
    energy: bool,
    near: Option<&SupportFrame>,
) -> Option<(DistributedOverlap, Stretch, [f64; RAYS])> {
    let graph = EndGraph::new(end);
    let profile = FlangeProfile::new(flange);
    let field = Field {
        asperities,
        energy,
        ..Field::new(graph, profile)?
    };
    let anchor = field.coordinates(deepest);
    let depth0 = field.depth(anchor.0, anchor.1);
    if !(depth0 > 0.0 && depth0.is_finite()) {
        return None;
    }
    let (frame, depth_c, starts) = match near.and_then(|near| field.reuse(near)) {
        Some(reused) => reused,
        None => field.support_frame(anchor, depth0)?,
    };
    let depth0 = asperities.load(depth0 - asperities.reach());
    let (overlap, reaches) = field.sum_over_rays(&frame, depth_c, depth0, &starts);
    Some((overlap, frame, reaches))
}

impl Field {
    /// The frame `near` of an integration at a nearby pose, with g at its centre, if its
    /// centre lies inside the support here (else None: a fresh frame is needed).
    fn reuse(&self, near: &SupportFrame) -> Option<(Stretch, f64, [f64; RAYS])> {
        let (u, v) = near.stretch.centre;
        let depth_c = self.depth(u, v);
        (depth_c > 0.0 && depth_c.is_finite()).then_some((near.stretch, depth_c, near.starts))
    }

    /// The frame of the final rays and g at its centre, from `anchor` (g = `depth0` > 0):
    /// a first centre mid-way along chords through the anchor along u, v and u again, then
    /// twice the support's own centroid and principal axes from the reach of rays (the
    /// area's moments are exact in the reach; the second pass mends a frame stretched
    /// badly by a wedge-shaped support), so that the final rays do not depend on where the
    /// deepest point lies. None if the first centre is outside the support.
    fn support_frame(
        &self,
        anchor: (f64, f64),
        depth0: f64,
    ) -> Option<(Stretch, f64, [f64; RAYS])> {
        // Each chord's search starts from the last chord's half-length: the first from the
        // half-width of an edge torus's overlap, the one along v from half the end's
        // radius (an overlap that spans the face).
        let scale = (2.0 * self.end.tube_radius * depth0).sqrt();
        let (mid_u, half_u) = self.chord_midpoint(anchor, (1.0, 0.0), scale);
        let reach_v = 0.5 * (self.end.tube_center + self.end.tube_radius);
        let (mid_v, half_v) = self.chord_midpoint(mid_u, (0.0, 1.0), reach_v.max(half_u));
        let (first, half_u) = self.chord_midpoint(mid_v, (1.0, 0.0), half_u);
        let depth_first = self.depth(first.0, first.1);
        if depth_first.is_nan() || depth_first <= 0.0 {
            return None;
        }
        let mut frame = Stretch {
            centre: first,
            axes: [(1.0, 0.0), (0.0, 1.0)],
            half: (half_u, half_v),
        };
        let mut depth_c = depth_first;
        let mut found: Option<[(f64, f64); COARSE_RAYS]> = None;
        for _ in 0..2 {
            let starts = found.map(|points| predicted_reaches(&frame, &COARSE_RAY_ANGLES, &points));
            let (shape, points) = self.area_moments(&frame, depth_c, starts.as_ref());
            found = Some(points);
            let centroid = self.depth(shape.centre.0, shape.centre.1);
            if centroid > 0.0 {
                (frame, depth_c) = (shape, centroid);
            }
        }
        let starts = found.map(|points| predicted_reaches(&frame, &RAY_ANGLES, &points))?;
        Some((frame, depth_c, starts))
    }
}

/// Guesses of the reach of each ray of `frame` at `angles` from points on the support's
/// boundary found by an earlier pass: the points' stretched polar radius ρ, interpolated
/// linearly in their polar angle ([`pseudo_angle`]) about the frame's centre
/// (periodically). Only the
/// boundary searches' starts, which a better guess shortens: on B1's flange through the
/// flat tilt the 24 final rays took 75–97 evaluations with these guesses against 95–101
/// from the previous ray's reach (the corners where the rim cuts the end's edge keep the
/// guesses a few per cent off). A guess that is not a positive number is replaced by 1.
fn predicted_reaches<const N: usize, const M: usize>(
    frame: &Stretch,
    angles: &[(f64, f64); N],
    points: &[(f64, f64); M],
) -> [f64; N] {
    let [e1, e2] = frame.axes;
    let mut polar = points.map(|p| {
        let d = (p.0 - frame.centre.0, p.1 - frame.centre.1);
        let x = (d.0 * e1.0 + d.1 * e1.1) / frame.half.0;
        let y = (d.0 * e2.0 + d.1 * e2.1) / frame.half.1;
        (pseudo_angle(x, y), (x * x + y * y).sqrt())
    });
    polar.sort_by(|a, b| a.0.total_cmp(&b.0));
    let n = M;
    std::array::from_fn(|k| {
        let (sin, cos) = angles[k];
        let theta = pseudo_angle(cos, sin);
        let j = polar.partition_point(|p| p.0 <= theta);
        let (lo, hi) = match j {
            0 => ((polar[n - 1].0 - PSEUDO_TURN, polar[n - 1].1), polar[0]),
            j if j == n => (polar[n - 1], (polar[0].0 + PSEUDO_TURN, polar[0].1)),
            j => (polar[j - 1], polar[j]),
        };
        let span = hi.0 - lo.0;
        let w = if span > 0.0 {
            (theta - lo.0) / span
        } else {
            0.5
        };
        let guess = lo.1 + w * (hi.1 - lo.1);
        if guess > 0.0 && guess.is_finite() {
            guess
        } else {
            1.0
        }
    })
}

/// A full turn of [`pseudo_angle`].
const PSEUDO_TURN: f64 = 4.0;

/// A stand-in for the polar angle of (x, y) in [0, 4) that rises with it (0 along +x, 1
/// along +y, 2 along −x, 3 along −y), without a trigonometric function: enough to order
/// points around a centre and to interpolate between neighbours.
fn pseudo_angle(x: f64, y: f64) -> f64 {
    let r = x / (x.abs() + y.abs());
    if y >= 0.0 {
        1.0 - r
    } else {
        3.0 + r
    }
}

/// Polar coordinates stretched along two orthonormal axes of the end plane: the point
/// centre + ρ (half.0 cos θ axes[0] + half.1 sin θ axes[1]); the support is about the
/// unit disc in ρ, θ, so the rays' reach varies slowly with θ.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Stretch {
    centre: (f64, f64),
    axes: [(f64, f64); 2],
    half: (f64, f64),
}

impl Stretch {
    /// The direction of the ray at the angle whose (sin θ, cos θ) is given (not unit:
    /// ρ = 1 is the stretched unit circle).
    fn ray(&self, (sin, cos): (f64, f64)) -> (f64, f64) {
        let [e1, e2] = self.axes;
        let (x, y) = (self.half.0 * cos, self.half.1 * sin);
        (x * e1.0 + y * e2.0, x * e1.1 + y * e2.1)
    }

    /// The Jacobian of (ρ, θ) to the end plane, divided by ρ.
    fn jacobian(&self) -> f64 {
        self.half.0 * self.half.1
    }
}

/// Running sums of the integrals.
#[derive(Default)]
struct Sums {
    volume: f64,
    stiffness_area: f64,
    energy: f64,
    area: f64,
    max_depth: f64,
    a: f64,
    b: f64,
    aa: f64,
    bb: f64,
    ab: f64,
    centre: Vec3,
    normal: Vec3,
}

impl Field {
    /// The support's centroid and principal axes ([`shape_of_support`]) from
    /// `COARSE_RAYS` rays of `frame` (starting at its centre, where g = `inside`), and the
    /// boundary points the rays found.
    fn area_moments(
        &self,
        frame: &Stretch,
        inside: f64,
        starts: Option<&[f64; COARSE_RAYS]>,
    ) -> (Stretch, [(f64, f64); COARSE_RAYS]) {
        let dirs = COARSE_RAY_ANGLES.map(|angle| frame.ray(angle));
        let reaches = match starts {
            Some(starts) => self.boundaries(frame.centre, &dirs, inside, starts),
            // Without guesses each ray starts from the reach of the one before.
            None => {
                let mut reach = 1.0;
                dirs.map(|dir| {
                    reach = self.boundary(frame.centre, dir, inside, reach);
                    reach
                })
            }
        };
        shape_of_support(frame, &COARSE_RAY_ANGLES, &reaches)
    }

    /// Sums the integrals over `RAYS` rays of `frame` (g = `depth_c` at its centre), with
    /// `depth0` the deepest overlap known; each ray's boundary searched from its guess in
    /// `starts` ([`predicted_reaches`]). Also the rays' reaches.
    fn sum_over_rays(
        &self,
        frame: &Stretch,
        depth_c: f64,
        depth0: f64,
        starts: &[f64; RAYS],
    ) -> (DistributedOverlap, [f64; RAYS]) {
        let step = TAU / RAYS as f64;
        let jacobian = frame.jacobian() * step;
        let c = frame.centre;
        let mut s = Sums {
            max_depth: depth0,
            ..Default::default()
        };
        let dirs = RAY_ANGLES.map(|angle| frame.ray(angle));
        let reaches = self.boundaries(c, &dirs, depth_c, starts);
        s.area = reaches
            .iter()
            .map(|reach| 0.5 * reach * reach * jacobian)
            .sum();
        // Node by node, every ray's point at once ([`Field::samples`]).
        for (xi, wi) in GAUSS_NODES.iter().zip(GAUSS_WEIGHTS) {
            let r = reaches.map(|reach| reach * xi);
            let u: [f64; RAYS] = std::array::from_fn(|k| c.0 + r[k] * dirs[k].0);
            let v: [f64; RAYS] = std::array::from_fn(|k| c.1 + r[k] * dirs[k].1);
            let p = self.samples(&u, &v);
            for k in 0..RAYS {
                let depth = p.depth[k];
                let (a, b) = (u[k], v[k]);
                let (load, stiffness) = self.asperities.load_and_stiffness(depth);
                let area = wi * reaches[k] * r[k] * jacobian;
                let weight = area * load;
                s.volume += weight;
                s.stiffness_area += area * stiffness;
                if self.energy {
                    s.energy += area * self.asperities.energy(depth);
                }
                s.max_depth = s.max_depth.max(load);
                let g = depth.max(0.0);
                s.a += weight * a;
                s.b += weight * b;
                s.aa += weight * a * a;
                s.bb += weight * b * b;
                s.ab += weight * a * b;
                let point = Vec3::new(p.point[0][k], p.point[1][k], p.point[2][k]);
                let normal = Vec3::new(p.normal[0][k], p.normal[1][k], p.normal[2][k]);
                s.centre += (point + normal * (0.5 * g)) * weight;
                s.normal += normal * weight;
            }
        }
        (self.finish(&s), reaches)
    }

    fn finish(&self, s: &Sums) -> DistributedOverlap {
        let v = s.volume;
        let (ma, mb) = (s.a / v, s.b / v);
        let caa = (s.aa / v - ma * ma).max(0.0);
        let cbb = (s.bb / v - mb * mb).max(0.0);
        let cab = s.ab / v - ma * mb;
        let (l1, l2, (eu, ev)) = principal(caa, cbb, cab);
        // (u, v) directions at the centroid in the end plane: ∂(a, b)/∂u = (0, 1),
        // ∂(a, b)/∂v = (1, −v/ρ₀).
        let (ea, eb) = (ev, eu - ev * mb / self.rho0);
        let major = (self.t * ea + self.w * eb)
            .try_normalize(1e-300)
            .unwrap_or(self.t);
        DistributedOverlap {
            volume: v,
            stiffness_area: s.stiffness_area,
            energy: s.energy,
            area: s.area,
            max_depth: s.max_depth,
            centre: s.centre / v,
            normal: s.normal.normalize(),
            semi_axes: ((5.0 * l1).sqrt(), (5.0 * l2).sqrt()),
            major_axis: major,
        }
    }
}

/// The support's centroid and principal axes (half-lengths 2√λ, an ellipse's semi-axes)
/// from the reach R of each of the N rays of `frame` at `angles` (uniform in angle): the
/// area's moments are exact integrals of polynomials in ρ over the region the rays bound.
/// Also the boundary points the rays found.
fn shape_of_support<const N: usize>(
    frame: &Stretch,
    angles: &[(f64, f64); N],
    reaches: &[f64; N],
) -> (Stretch, [(f64, f64); N]) {
    let step = TAU / N as f64;
    let jacobian = frame.jacobian() * step;
    let (mut area, mut m1, mut m2) = (0.0, (0.0, 0.0), (0.0, 0.0, 0.0));
    let (ca, cb) = frame.centre;
    let dirs = angles.map(|angle| frame.ray(angle));
    let mut points = [(0.0, 0.0); N];
    for (k, (&(ua, ub), &reach)) in dirs.iter().zip(reaches).enumerate() {
        points[k] = (ca + reach * ua, cb + reach * ub);
        // ∫₀ᴿ ρ dρ, ∫₀ᴿ ρ² dρ, ∫₀ᴿ ρ³ dρ.
        let (r2, r3, r4) = (
            reach.powi(2) / 2.0,
            reach.powi(3) / 3.0,
            reach.powi(4) / 4.0,
        );
        area += r2 * jacobian;
        m1.0 += (ca * r2 + ua * r3) * jacobian;
        m1.1 += (cb * r2 + ub * r3) * jacobian;
        m2.0 += (ca * ca * r2 + 2.0 * ca * ua * r3 + ua * ua * r4) * jacobian;
        m2.1 += (cb * cb * r2 + 2.0 * cb * ub * r3 + ub * ub * r4) * jacobian;
        m2.2 += (ca * cb * r2 + (ca * ub + cb * ua) * r3 + ua * ub * r4) * jacobian;
    }
    let centre = (m1.0 / area, m1.1 / area);
    let caa = (m2.0 / area - centre.0 * centre.0).max(0.0);
    let cbb = (m2.1 / area - centre.1 * centre.1).max(0.0);
    let cab = m2.2 / area - centre.0 * centre.1;
    let (l1, l2, (e1a, e1b)) = principal(caa, cbb, cab);
    let floor = 1e-3 * frame.half.0.max(frame.half.1);
    let shape = Stretch {
        centre,
        axes: [(e1a, e1b), (-e1b, e1a)],
        half: ((2.0 * l1.sqrt()).max(floor), (2.0 * l2.sqrt()).max(floor)),
    };
    (shape, points)
}

/// The principal moments λ₁ ≥ λ₂ of the covariance [[caa, cab], [cab, cbb]] and the unit
/// eigenvector of λ₁, its sign fixed (first non-zero component positive).
fn principal(caa: f64, cbb: f64, cab: f64) -> (f64, f64, (f64, f64)) {
    let mean = 0.5 * (caa + cbb);
    let spread = (0.25 * (caa - cbb).powi(2) + cab * cab).sqrt();
    let (l1, l2) = (mean + spread, (mean - spread).max(0.0));
    // From whichever row is better conditioned.
    let (x, y) = if caa >= cbb {
        (l1 - cbb, cab)
    } else {
        (cab, l1 - caa)
    };
    let norm = x.hypot(y);
    let (x, y) = if norm > 0.0 {
        (x / norm, y / norm)
    } else {
        (1.0, 0.0)
    };
    let sign = if x > 0.0 || (x == 0.0 && y >= 0.0) {
        1.0
    } else {
        -1.0
    };
    (l1, l2, (sign * x, sign * y))
}

#[cfg(test)]
mod tests;
