//! The relative curvature of a roller end / flange contact blended across the borders
//! between patches, so that the contact force is a continuous function of the pose.
//!
//! Both bodies are tangent-continuous (G1) but not curvature-continuous. On the roller the
//! meridian radius jumps at the border between the edge torus (r_e, 0.5 mm for B1) and the
//! end-face sphere (R_s, 5 m); on the flange between the face cone (∞) and the root and rim
//! tori (0.2 and 0.3 mm). The two pairings that meet at a border find the same contact point
//! and penetration there (the rule of `docs/contact.md`), but their Hertz forces (paper
//! eqs. 5–8) at equal penetration differ, by orders of magnitude at the roller's border, so
//! a contact sitting on a border makes the force jump and the integrator's step collapses
//! (a stiff system with a discontinuous right-hand side). A real contact patch there covers
//! both patches anyway, so its effective curvature lies between the two.
//!
//! The rule (each body separately, C¹ smoothsteps, see [`blend`]):
//! * roller: K = w·K_torus + (1 − w)·K_sphere, both at P₁, w = smoothstep(θ − θ_b) over
//!   ±Δθ, θ the angle of the roller's outward normal −n from its axis and θ_b the sphere's
//!   cap angle. The angle is the natural coordinate because the contact normal follows the
//!   roller's tilt one to one; the contact point moves by r_e·Δθ on the torus and R_s·Δθ on
//!   the sphere.
//! * flange: K = w_root·K_root + w_rim·K_rim + (1 − w_root − w_rim)·K_cone, both at P₂,
//!   each w a smoothstep of the signed arc length of P₂ past that cone/torus border over
//!   ±Δσ.
//!
//! Δθ and Δσ are numerical settings of the model (`solver.border_band_roller`,
//! `solver.border_band_flange`). Outside the bands the pairing's own curvature is used
//! unchanged (B1's usual TO-CO contact, 0.11° from the roller axis, is far outside).

use super::{relative_radius, Contact, Pairing};
use crate::geometry::end_flange::{Flange, RollerEnd};
use crate::geometry::primitives::{meridian, relative_curvature_of, Curvature, Vec3};
use crate::numerics::smooth::smoothstep;

/// The half-widths of the blending bands.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BorderBands {
    /// Roller end, torus/sphere border: Δθ in the angle of the roller's surface normal
    /// from its axis [rad].
    pub roller_angle: f64,
    /// Flange, cone/root-torus and cone/rim-torus borders: Δσ in arc length along the
    /// flange's meridian [m].
    pub flange_length: f64,
}

impl BorderBands {
    /// rollerdyn's defaults: 1.5e-4 rad (75 nm of the 0.5 mm edge torus, 0.75 mm of the
    /// 5 m end sphere, about the Hertz radius of the end face on the flange face at 10 N)
    /// and 50 µm (a few semi-minor axes of a loaded contact).
    pub const DEFAULT: Self = Self {
        roller_angle: 1.5e-4,
        flange_length: 50e-6,
    };
}

/// Angle between two unit vectors, accurate also for tiny angles [rad].
fn angle_between(a: &Vec3, b: &Vec3) -> f64 {
    a.cross(b).norm().atan2(a.dot(b))
}

/// Weight of the roller's edge torus (1 − w: its end sphere) at a contact with normal n
/// (from the flange towards the roller): smoothstep of θ − θ_b, θ the angle of the
/// roller's outward normal −n from its axis, θ_b the sphere's cap angle.
pub fn torus_weight(end: &RollerEnd, contact: &Contact, band: f64) -> f64 {
    let theta = angle_between(&(-contact.normal), &end.sphere.pole);
    smoothstep(theta - end.sphere.cap_angle, band)
}

/// Weights (cone, root torus, rim torus) of the flange's figures at the contact: the
/// signed arc length σ of P₂ past each cone/torus border (positive on the torus),
/// r_T·(angle of n from the cone's normal) on a torus, the generator distance beyond the
/// cone's end on the cone, each through [`smoothstep`].
pub fn flange_weights(flange: &Flange, contact: &Contact, band: f64) -> [f64; 3] {
    let cone = &flange.cone;
    let (sigma_root, sigma_rim) = match contact.pairing {
        Pairing::TorusCone | Pairing::SphereCone => {
            let foot = cone.foot(&contact.p2);
            let (s, rho, _) = meridian(&foot.point, &cone.origin, &cone.axis);
            let g = (s - cone.s0) * cone.ds + (rho - cone.rho0) * cone.drho;
            (cone.g_min - g, g - cone.g_max)
        }
        Pairing::TorusRoot | Pairing::SphereRoot => {
            let past = flange.root.minor_radius
                * angle_between(&contact.normal, &cone.foot(&contact.p2).normal);
            (past, f64::NEG_INFINITY)
        }
        Pairing::TorusRim | Pairing::SphereRim => {
            let past = flange.rim.minor_radius
                * angle_between(&contact.normal, &cone.foot(&contact.p2).normal);
            (f64::NEG_INFINITY, past)
        }
    };
    let root = smoothstep(sigma_root, band);
    let rim = smoothstep(sigma_rim, band);
    [(1.0 - root - rim).max(0.0), root, rim]
}

/// The contact with its relative radii R_x, R_y and major axis recomputed from the blended
/// curvatures of both bodies (module doc), for overlaps (their load) and gaps alike (their
/// squeeze film, which scales with R_x·R_y). Invalid contacts, and contacts outside every
/// band, are returned unchanged, except contacts without curvature (the
/// mesh baseline's, R_x = R_y = NaN): those get the curvatures of the figures at their
/// points, weighted alike (outside the bands: their own pairing's), so that the mesh
/// detector's overlaps carry a Hertz force in the model too.
///
/// The radii follow the contract of [`super::relative_radius`]: finite and positive
/// (docs/robustness.md, findings 4 and 6: a non-positive blended curvature was R = ∞,
/// and Hertz made a NaN force of it).
pub fn blend(contact: &Contact, end: &RollerEnd, flange: &Flange, bands: &BorderBands) -> Contact {
    if !contact.valid {
        return *contact;
    }
    let w_torus = torus_weight(end, contact, bands.roller_angle);
    let roller_w = [w_torus, 1.0 - w_torus];
    let flange_w = flange_weights(flange, contact, bands.flange_length);
    let (roller_own, flange_own) = contact.pairing.figures();
    let has_curvature = !(contact.rx.is_nan() || contact.ry.is_nan());
    if has_curvature && roller_w[roller_own] >= 1.0 && flange_w[flange_own] >= 1.0 {
        return *contact;
    }
    let n = contact.normal;
    let (p1, p2) = (contact.p1, contact.p2);
    let roller: [Curvature; 2] = [end.torus.curvature(&p1, &(-n)), end.sphere.curvature(&(-n))];
    let flange_k: [Curvature; 3] = [
        flange.cone.curvature(&p2, &n),
        flange.root.curvature(&p2, &n),
        flange.rim.curvature(&p2, &n),
    ];
    let weighted: Vec<(f64, &Curvature)> = roller_w
        .iter()
        .zip(&roller)
        .chain(flange_w.iter().zip(&flange_k))
        .filter(|(w, _)| **w > 0.0)
        .map(|(w, k)| (*w, k))
        .collect();
    let (kx, ky, major) = relative_curvature_of(&n, &weighted);
    Contact {
        rx: relative_radius(kx),
        ry: relative_radius(ky),
        major_axis: major,
        ..*contact
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::semi_analytical;
    use crate::contact::tests::{b1_end, b1_flange};
    use proptest::prelude::*;

    const BANDS: BorderBands = BorderBands::DEFAULT;

    /// B1's roller end against the inner ring's +x flange (paper tab. 3 and B1.md), pushed
    /// axially by `push` into it and tilted by `tilt` about the circumferential direction:
    /// the contact normal leans 0.11° (the opening angle) from the roller axis untilted, so
    /// tilts between about 1.2e-3 and 2.7e-3 rad bring it onto the end sphere.
    fn pose(tilt: f64, push: f64) -> (RollerEnd, Flange) {
        (
            b1_end(true, 0.0, push, 0.0, tilt, 0.0),
            b1_flange(true, true),
        )
    }

    /// Relative curvatures (1/R_x, 1/R_y) of the composite contact, blended by `bands`.
    fn curvatures(tilt: f64, push: f64, bands: &BorderBands) -> Option<(f64, f64, Pairing)> {
        let (end, flange) = pose(tilt, push);
        let c = semi_analytical::composite(&end, &flange)?;
        if c.penetration <= 0.0 {
            return None;
        }
        let b = blend(&c, &end, &flange, bands);
        Some((1.0 / b.rx, 1.0 / b.ry, c.pairing))
    }

    /// Largest change of 1/R_x or 1/R_y between neighbouring tilts of a scan over
    /// [lo, hi] in n steps, and the pairings met on the way.
    fn largest_step(lo: f64, hi: f64, n: usize, bands: &BorderBands) -> (f64, Vec<Pairing>) {
        let mut previous: Option<(f64, f64)> = None;
        let mut pairings = Vec::new();
        let mut largest: f64 = 0.0;
        for i in 0..=n {
            let tilt = lo + (hi - lo) * i as f64 / n as f64;
            let Some((kx, ky, pairing)) = curvatures(tilt, 35e-6, bands) else {
                previous = None;
                continue;
            };
            if !pairings.contains(&pairing) {
                pairings.push(pairing);
            }
            if let Some((kx0, ky0)) = previous {
                largest = largest.max((kx - kx0).abs()).max((ky - ky0).abs());
            }
            previous = Some((kx, ky));
        }
        (largest, pairings)
    }

    /// Continuity across the borders (the scan crosses SP-TO(rim) -> SP-CO on the flange
    /// and SP-CO -> TO-CO on the roller): refining the scan ten times shrinks the largest
    /// step between neighbours about ten times (a Lipschitz function), where without the
    /// bands it stays (a jump). Reference: the definition of continuity.
    #[test]
    fn curvature_is_continuous_across_the_patch_borders() {
        let (lo, hi) = (-1.8e-3, -1.2e-3);
        let sharp = BorderBands {
            roller_angle: 0.0,
            flange_length: 0.0,
        };
        let (coarse, pairings) = largest_step(lo, hi, 2_000, &BANDS);
        for p in [Pairing::SphereRim, Pairing::SphereCone, Pairing::TorusCone] {
            assert!(
                pairings.contains(&p),
                "the scan must cross {p:?}: {pairings:?}"
            );
        }
        let (fine, _) = largest_step(lo, hi, 20_000, &BANDS);
        assert!(fine < 0.2 * coarse, "blended: {coarse} -> {fine}");
        let (coarse, _) = largest_step(lo, hi, 2_000, &sharp);
        let (fine, _) = largest_step(lo, hi, 20_000, &sharp);
        assert!(
            fine > 0.5 * coarse,
            "unblended jumps must stay: {coarse} -> {fine}"
        );
    }

    /// B1's usual flange contact (TO-CO, normal 0.11° from the roller axis, far outside the
    /// band, which ends 5e-4 rad from the axis) keeps the paper's Hertz radii exactly.
    #[test]
    fn outside_the_bands_the_pairing_keeps_its_own_curvature() {
        for tilt in [-1e-3, 0.0, 1e-3] {
            let (end, flange) = pose(tilt, 35e-6);
            let c = semi_analytical::composite(&end, &flange).unwrap();
            assert_eq!(c.pairing, Pairing::TorusCone);
            assert!(c.penetration > 0.0);
            assert_eq!(blend(&c, &end, &flange, &BANDS), c);
        }
    }

    #[test]
    fn the_weights_sum_to_one_and_switch_sides_at_the_borders() {
        let (end, flange) = pose(-1.5e-3, 35e-6);
        let c = semi_analytical::composite(&end, &flange).unwrap();
        let w = flange_weights(&flange, &c, 10e-6);
        assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        assert_eq!(smoothstep(0.0, 1.0), 0.5);
        assert_eq!(smoothstep(-1.0, 1.0), 0.0);
        assert_eq!(smoothstep(1.0, 1.0), 1.0);
        assert_eq!(smoothstep(-1e-30, 0.0), 0.0);
    }

    proptest! {
        /// The weight is in [0, 1] and the blended radii are finite and ordered for any
        /// loaded pose near the border.
        #[test]
        fn blended_radii_are_finite_and_ordered(tilt in -3e-3f64..3e-3, push in 25e-6f64..60e-6) {
            if let Some((kx, ky, _)) = curvatures(tilt, push, &BANDS) {
                prop_assert!(kx.is_finite() && kx > 0.0 && ky <= kx && ky >= 0.0);
            }
        }
    }
}
