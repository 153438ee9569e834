//! The basic figures of the roller end and flange geometry (paper sect. 2, fig. 1):
//! sphere, cone and torus, each as a bounded patch of a surface of revolution.
//!
//! Every figure is described in its *meridian half-plane*: for a point p, the axial
//! coordinate s = a·(p − o) and the radial coordinate ρ = |p − o − s·a| about the figure's
//! axis (origin o, unit direction a). The surface normal always points out of the solid.
//!
//! **Patch rule.** A point belongs to a patch when its parameter lies in the patch's closed
//! range, widened by a relative tolerance of 1e-9 of the range (so that a contact found
//! exactly on the border between two tangent patches, e.g. torus and cone of a flange,
//! counts for both). A contact point found outside its patch does not count.

use nalgebra::Vector3;

/// 3-vector of the geometry (metres).
pub type Vec3 = Vector3<f64>;

/// Relative widening of patch ranges (see the module's patch rule).
pub const PATCH_TOLERANCE: f64 = 1e-9;

/// Meridian coordinates (s, ρ) of p about the axis (o, a), and the unit radial direction
/// e_ρ of p's meridian half-plane (any perpendicular of a if p is on the axis).
///
/// Within round-off of the axis (ρ ≤ 1e-8·|s|) the radial part d − a·s is mostly
/// cancellation noise, whose direction need not be perpendicular to a (a roller end's
/// sphere centre on the ring axis gave an e_ρ almost along a, a tube centre on the axis
/// and an infinite curvature: docs/robustness.md, finding 4); there it is projected on
/// the plane normal to a once more (any perpendicular if nothing is left). Elsewhere the
/// result is unchanged bit for bit.
#[inline]
pub fn meridian(p: &Vec3, origin: &Vec3, axis: &Vec3) -> (f64, f64, Vec3) {
    let d = p - origin;
    let s = axis.dot(&d);
    let radial = d - axis * s;
    let rho = radial.norm();
    let e_rho = if rho > 1e-8 * s.abs() && rho > 1e-300 {
        radial / rho
    } else {
        let again = radial - axis * axis.dot(&radial);
        let norm = again.norm();
        if norm > 1e-8 * rho && norm > 1e-300 {
            again / norm
        } else {
            any_perpendicular(axis)
        }
    };
    (s, rho, e_rho)
}

/// The angle x wrapped into [−π, π): (x + π).rem_euclid(2π) − π, bit for bit, without the
/// floating-point remainder where x + π lies within [−2π, 4π) (one addition or subtraction
/// of 2π there is exact or rounds as `rem_euclid` does).
#[inline]
pub fn wrap_angle(x: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let y = x + PI;
    let r = if (0.0..TAU).contains(&y) {
        y
    } else if (TAU..2.0 * TAU).contains(&y) {
        y - TAU
    } else if (-TAU..0.0).contains(&y) {
        y + TAU
    } else {
        y.rem_euclid(TAU)
    };
    r - PI
}

/// A unit vector perpendicular to the unit vector a.
#[inline]
pub fn any_perpendicular(a: &Vec3) -> Vec3 {
    let helper = if a.x.abs() < 0.9 {
        Vec3::x()
    } else {
        Vec3::y()
    };
    a.cross(&helper).normalize()
}

/// True if x lies in [lo, hi] widened by the patch tolerance.
#[inline]
pub fn in_range(x: f64, lo: f64, hi: f64) -> bool {
    let slack = PATCH_TOLERANCE * (hi - lo).abs().max(1e-300);
    x >= lo - slack && x <= hi + slack
}

/// Principal curvatures of a surface at a point: κ₁ along t₁, κ₂ along t₂ (unit, tangent,
/// orthogonal); positive for a convex surface (centre of curvature inside the solid).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Curvature {
    /// First principal direction.
    pub t1: Vec3,
    /// Curvature along t₁ [1/m].
    pub k1: f64,
    /// Second principal direction.
    pub t2: Vec3,
    /// Curvature along t₂ [1/m].
    pub k2: f64,
}

/// A spherical cap: centre, radius, and the cap of half-angle `cap_angle` about `pole`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpherePatch {
    /// Centre [m].
    pub center: Vec3,
    /// Radius [m].
    pub radius: f64,
    /// Unit direction of the cap's middle.
    pub pole: Vec3,
    /// Half-angle of the cap [rad].
    pub cap_angle: f64,
}

impl SpherePatch {
    /// Signed distance of p from the (whole) sphere, positive outside.
    pub fn signed_distance(&self, p: &Vec3) -> f64 {
        (p - self.center).norm() - self.radius
    }

    /// True if the surface point in direction `n` from the centre lies on the cap.
    pub fn contains_direction(&self, n: &Vec3) -> bool {
        let angle = n.dot(&self.pole).clamp(-1.0, 1.0).acos();
        in_range(angle, 0.0, self.cap_angle)
    }

    /// Curvature (1/R in every direction) with principal directions chosen in the plane
    /// normal to n.
    pub fn curvature(&self, n: &Vec3) -> Curvature {
        let t1 = any_perpendicular(n);
        let t2 = n.cross(&t1);
        let k = 1.0 / self.radius;
        Curvature {
            t1,
            k1: k,
            t2,
            k2: k,
        }
    }
}

/// A conical patch: the surface of revolution about (origin, axis) of the straight
/// generator through the meridian point (s₀, ρ₀) with unit meridian direction
/// (d_s, d_ρ), for generator coordinates g ∈ [g_min, g_max]. `side` = ±1 says on which
/// side of the generator the solid lies: the outward normal in the meridian plane is
/// side·(−d_ρ, d_s) in (s, ρ) components.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConePatch {
    /// Point on the axis [m].
    pub origin: Vec3,
    /// Unit axis.
    pub axis: Vec3,
    /// Meridian point of the generator (s₀, ρ₀) [m].
    pub s0: f64,
    /// Radial coordinate of that point [m].
    pub rho0: f64,
    /// Unit generator direction, axial component.
    pub ds: f64,
    /// Unit generator direction, radial component.
    pub drho: f64,
    /// Side of the solid (±1).
    pub side: f64,
    /// Patch range of the generator coordinate [m].
    pub g_min: f64,
    /// Upper end of the range [m].
    pub g_max: f64,
}

/// The closest point of a figure's (unbounded) surface to a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Foot {
    /// Signed distance of the point from the surface, positive outside the solid [m].
    pub distance: f64,
    /// The closest surface point [m].
    pub point: Vec3,
    /// Outward unit normal there.
    pub normal: Vec3,
    /// True if the surface point lies on the patch.
    pub on_patch: bool,
}

impl ConePatch {
    /// Outward meridian normal (n_s, n_ρ).
    #[inline]
    pub fn meridian_normal(&self) -> (f64, f64) {
        (-self.side * self.drho, self.side * self.ds)
    }

    /// Closest point on the cone (in p's meridian half-plane) and signed distance.
    pub fn foot(&self, p: &Vec3) -> Foot {
        let (s, rho, e_rho) = meridian(p, &self.origin, &self.axis);
        let (ns, nr) = self.meridian_normal();
        let (ws, wr) = (s - self.s0, rho - self.rho0);
        let distance = ws * ns + wr * nr;
        let g = ws * self.ds + wr * self.drho;
        let (fs, fr) = (self.s0 + g * self.ds, self.rho0 + g * self.drho);
        Foot {
            distance,
            point: self.origin + self.axis * fs + e_rho * fr,
            normal: self.axis * ns + e_rho * nr,
            on_patch: in_range(g, self.g_min, self.g_max),
        }
    }

    /// True if the surface point p (in its meridian plane) lies on the patch.
    pub fn contains_point(&self, p: &Vec3) -> bool {
        let (s, rho, _) = meridian(p, &self.origin, &self.axis);
        let g = (s - self.s0) * self.ds + (rho - self.rho0) * self.drho;
        in_range(g, self.g_min, self.g_max)
    }

    /// Principal curvatures at a surface point with outward normal n: zero along the
    /// generator, n_ρ/ρ around the axis (Meusnier's theorem: the parallel circle's
    /// curvature 1/ρ times the cosine between its principal normal −e_ρ and −n).
    pub fn curvature(&self, point: &Vec3, normal: &Vec3) -> Curvature {
        let (_, rho, e_rho) = meridian(point, &self.origin, &self.axis);
        let t_circ = self.axis.cross(&e_rho);
        let t_gen = self.axis * self.ds + e_rho * self.drho;
        let n_rho = normal.dot(&e_rho);
        Curvature {
            t1: t_gen,
            k1: 0.0,
            t2: t_circ,
            k2: n_rho / rho.max(1e-300),
        }
    }
}

/// A toroidal patch: tube of radius r about the circle of radius R (the major radius)
/// around (origin, axis); a surface point is tube-centre + r·m(φ) with the meridian unit
/// vector m(φ) = sin φ·a + cos φ·e_ρ (φ = 0 points radially outward, φ = π/2 along the
/// axis). The patch is the arc |φ − φ_mid| ≤ φ_half (angles compared modulo 2π); the
/// solid is inside the tube (convex torus).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorusPatch {
    /// Centre of the tube-centre circle [m].
    pub origin: Vec3,
    /// Unit axis.
    pub axis: Vec3,
    /// Major radius R (of the tube-centre circle) [m].
    pub major_radius: f64,
    /// Minor (tube) radius r [m].
    pub minor_radius: f64,
    /// Middle of the patch's tube-angle arc [rad].
    pub phi_mid: f64,
    /// Half-width of the arc [rad].
    pub phi_half: f64,
}

impl TorusPatch {
    /// Tube-centre point in the meridian half-plane of p, with that plane's e_ρ.
    #[inline]
    pub fn tube_center_towards(&self, p: &Vec3) -> (Vec3, Vec3) {
        let (_, _, e_rho) = meridian(p, &self.origin, &self.axis);
        (self.origin + e_rho * self.major_radius, e_rho)
    }

    /// Tube angle φ of the outward normal n at a tube point in the meridian plane e_ρ.
    #[inline]
    pub fn tube_angle(&self, n: &Vec3, e_rho: &Vec3) -> f64 {
        n.dot(&self.axis).atan2(n.dot(e_rho))
    }

    /// Closest point on the torus and signed distance (p off the axis).
    pub fn foot(&self, p: &Vec3) -> Foot {
        let (q, e_rho) = self.tube_center_towards(p);
        let w = p - q;
        let d = w.norm();
        let normal = if d > 1e-300 { w / d } else { e_rho };
        Foot {
            distance: d - self.minor_radius,
            point: q + normal * self.minor_radius,
            normal,
            on_patch: self.contains_angle(self.tube_angle(&normal, &e_rho)),
        }
    }

    /// True if the tube angle φ lies on the patch's arc (modulo 2π).
    #[inline]
    pub fn contains_angle(&self, phi: f64) -> bool {
        in_range(
            wrap_angle(phi - self.phi_mid),
            -self.phi_half,
            self.phi_half,
        )
    }

    /// True if the surface point p with outward normal n lies on the patch.
    #[inline]
    pub fn contains_surface_point(&self, p: &Vec3, n: &Vec3) -> bool {
        let (q, _) = self.tube_center_towards(p);
        self.contains_normal(&q, n)
    }

    /// True if the outward normal n at the tube point facing it lies on the patch.
    #[inline]
    pub fn contains_normal(&self, tube_center: &Vec3, n: &Vec3) -> bool {
        let (_, _, e_rho) = meridian(tube_center, &self.origin, &self.axis);
        self.contains_angle(self.tube_angle(n, &e_rho))
    }

    /// Principal curvatures at a surface point with outward normal n (n in the meridian
    /// plane): 1/r along the meridian, n_ρ/ρ around the axis (Meusnier).
    pub fn curvature(&self, point: &Vec3, normal: &Vec3) -> Curvature {
        let (_, rho, e_rho) = meridian(point, &self.origin, &self.axis);
        let t_circ = self.axis.cross(&e_rho);
        let t_mer = normal.cross(&t_circ);
        Curvature {
            t1: t_mer,
            k1: 1.0 / self.minor_radius,
            t2: t_circ,
            k2: normal.dot(&e_rho) / rho.max(1e-300),
        }
    }
}

/// Relative principal curvatures of two surfaces touching with common normal n: the sum
/// of their curvature tensors in the tangent plane, diagonalised (Johnson 1985, sect. 4.1).
/// Returns (1/R_x, 1/R_y, major-axis direction): 1/R_x ≥ 1/R_y, so R_x ≤ R_y, and the
/// contact ellipse's major axis lies along the direction of R_y.
pub fn relative_curvature(n: &Vec3, a: &Curvature, b: &Curvature) -> (f64, f64, Vec3) {
    relative_curvature_of(n, &[(1.0, a), (1.0, b)])
}

/// As [`relative_curvature`], for a weighted sum of curvature tensors Σ wᵢ·Kᵢ (used to
/// blend a body's curvature across a patch border, [`crate::contact::border`]).
pub fn relative_curvature_of(n: &Vec3, weighted: &[(f64, &Curvature)]) -> (f64, f64, Vec3) {
    let e1 = any_perpendicular(n);
    let e2 = n.cross(&e1);
    let mut m = [[0.0; 2]; 2];
    for (w, c) in weighted {
        for (t, k) in [(&c.t1, w * c.k1), (&c.t2, w * c.k2)] {
            let (u, v) = (t.dot(&e1), t.dot(&e2));
            m[0][0] += k * u * u;
            m[0][1] += k * u * v;
            m[1][1] += k * v * v;
        }
    }
    let mean = 0.5 * (m[0][0] + m[1][1]);
    let half_diff = 0.5 * (m[0][0] - m[1][1]);
    let radius = (half_diff * half_diff + m[0][1] * m[0][1]).sqrt();
    let (k_big, k_small) = (mean + radius, mean - radius);
    // Eigenvector of the smaller eigenvalue: the direction of the larger radius R_y.
    let angle = 0.5 * (2.0 * m[0][1]).atan2(2.0 * half_diff) + std::f64::consts::FRAC_PI_2;
    let major = e1 * angle.cos() + e2 * angle.sin();
    (k_big, k_small, major)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn wrap_angle_equals_the_remainder_formula() {
        use std::f64::consts::{PI, TAU};
        let reference = |x: f64| (x + PI).rem_euclid(TAU) - PI;
        let mut x: f64 = -20.0;
        while x < 20.0 {
            for v in [x, x.next_up(), x.next_down()] {
                assert_eq!(wrap_angle(v).to_bits(), reference(v).to_bits(), "{v}");
            }
            x += 1e-3 * PI;
        }
        for v in [
            -PI,
            PI,
            TAU,
            -TAU,
            3.0 * PI,
            -3.0 * PI,
            0.0,
            -0.0,
            1e-300,
            -1e-300,
        ] {
            assert_eq!(wrap_angle(v).to_bits(), reference(v).to_bits(), "{v}");
        }
    }

    #[test]
    fn relative_curvature_of_crossed_cylinders() {
        // Two equal cylinders crossed at right angles: 1/Rx = 1/Ry = 1/R (Johnson 1985,
        // sect. 4.2: a circular contact).
        let n = Vec3::z();
        let a = Curvature {
            t1: Vec3::x(),
            k1: 1.0 / 0.01,
            t2: Vec3::y(),
            k2: 0.0,
        };
        let b = Curvature {
            t1: Vec3::y(),
            k1: 1.0 / 0.01,
            t2: Vec3::x(),
            k2: 0.0,
        };
        let (kx, ky, _) = relative_curvature(&n, &a, &b);
        assert!((kx - 100.0).abs() < 1e-9 && (ky - 100.0).abs() < 1e-9);
        // Parallel cylinders: line contact, 1/Ry = 0 along the axes.
        let (kx, ky, major) = relative_curvature(&n, &a, &a);
        assert!((kx - 200.0).abs() < 1e-9 && ky.abs() < 1e-9);
        assert!(major.dot(&Vec3::y()).abs() > 1.0 - 1e-12);
    }

    proptest! {
        #[test]
        fn torus_foot_is_the_closest_point(
            x in -0.02..0.02f64, y in -0.02..0.02f64, z in -0.02..0.02f64,
            big in 0.002..0.01f64, small in 1e-4..1e-3f64,
        ) {
            // Brute force over the torus surface.
            let t = TorusPatch { origin: Vec3::zeros(), axis: Vec3::x(), major_radius: big,
                minor_radius: small, phi_mid: 0.0, phi_half: 3.2 };
            let p = Vec3::new(x, y, z);
            prop_assume!((y * y + z * z).sqrt() > 1e-3);
            let f = t.foot(&p);
            let mut best = f64::INFINITY;
            for i in 0..360 {
                for j in 0..90 {
                    let beta = i as f64 / 360.0 * std::f64::consts::TAU;
                    let phi = j as f64 / 90.0 * std::f64::consts::TAU;
                    let e = Vec3::new(0.0, beta.cos(), beta.sin());
                    let q = e * (big + small * phi.cos()) + Vec3::x() * small * phi.sin();
                    best = best.min((p - q).norm());
                }
            }
            let d = (p - f.point).norm();
            prop_assert!(d <= best + 1e-12);
            prop_assert!((d - f.distance.abs()).abs() < 1e-12);
        }
    }
}
