//! Roller ends and flanges built from the basic figures (paper fig. 1, sect. 4).
//!
//! * A **roller end** is the edge torus (minor radius r_e, tangent to the cylinder) and the
//!   convex end-face sphere of large radius R_s, both axisymmetric about the roller axis.
//! * A **flange** is a cone (its face, opening angle θ) between a root torus (next to the
//!   raceway) and a rim torus (at the flange's top), both convex roundings tangent to the
//!   face. The face recedes from the roller by θ as it rises from the raceway, so the axial
//!   gap opens away from the raceway (B1.md).
//!
//! Placement (ring frame, axis a): the face meets the raceway radius at the axial
//! coordinate s_f = ±(L/2 + axial play); with the roller centred, the gap between the end
//! face and the flange face at the raceway is the axial play.

use super::primitives::{ConePatch, SpherePatch, TorusPatch, Vec3};
use super::roller::RollerShape;
use crate::error::{require_non_negative, require_positive, Error, Result};
use std::f64::consts::FRAC_PI_2;

/// The two figures of one roller end, in the frame where the detection runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollerEnd {
    /// The edge torus; its axis points out of this end.
    pub torus: TorusPatch,
    /// The end-face sphere; its pole points out of this end.
    pub sphere: SpherePatch,
}

impl RollerEnd {
    /// The end of a roller with centre `center` whose unit axis direction `outward` points
    /// out of this end.
    pub fn new(shape: &RollerShape, center: Vec3, outward: Vec3) -> Self {
        let e = outward.normalize();
        let phi_t = shape.edge_tangent_angle();
        let torus = TorusPatch {
            origin: center + e * shape.edge_torus_center(),
            axis: e,
            major_radius: shape.radius - shape.edge_radius,
            minor_radius: shape.edge_radius,
            phi_mid: 0.5 * phi_t,
            phi_half: 0.5 * phi_t,
        };
        let sphere = SpherePatch {
            center: center + e * shape.end_sphere_center(),
            radius: shape.end_face_radius,
            pole: e,
            cap_angle: FRAC_PI_2 - phi_t,
        };
        Self { torus, sphere }
    }
}

/// The shape of a flange, independent of its ring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlangeShape {
    /// Opening angle θ of the face [rad].
    pub opening_angle: f64,
    /// Height above the raceway [m].
    pub height: f64,
    /// Minor radius of the root torus (next to the raceway) [m].
    pub root_radius: f64,
    /// Minor radius of the rim torus [m].
    pub rim_radius: f64,
}

impl FlangeShape {
    /// A validated flange shape: 0 ≤ θ < 10°, radii positive, root + rim radius below
    /// the height.
    pub fn new(opening_angle: f64, height: f64, root_radius: f64, rim_radius: f64) -> Result<Self> {
        require_non_negative("flange opening angle", opening_angle)?;
        if opening_angle >= 10f64.to_radians() {
            return Err(Error::InvalidParameter {
                name: "flange opening angle",
                value: opening_angle,
                rule: "must be below 10° (0.1745 rad)",
            });
        }
        require_positive("flange height", height)?;
        require_positive("flange root radius", root_radius)?;
        require_positive("flange rim radius", rim_radius)?;
        if root_radius + rim_radius >= height {
            return Err(Error::InvalidParameter {
                name: "flange root radius + rim radius",
                value: root_radius + rim_radius,
                rule: "must be smaller than the flange height",
            });
        }
        Ok(Self {
            opening_angle,
            height,
            root_radius,
            rim_radius,
        })
    }
}

/// Where a flange sits on its ring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlangePlacement {
    /// Ring origin (centre of the raceway) [m].
    pub origin: Vec3,
    /// Unit ring axis.
    pub axis: Vec3,
    /// Raceway radius [m].
    pub raceway_radius: f64,
    /// +1 if the flange rises to larger radii (inner ring), −1 if to smaller (outer ring).
    pub rises: f64,
    /// Axial coordinate of the face at the raceway [m].
    pub face_position: f64,
    /// +1 if the face looks along +axis (towards a roller on that side), −1 otherwise.
    pub facing: f64,
}

/// The three figures of one flange.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Flange {
    /// The face.
    pub cone: ConePatch,
    /// Rounding next to the raceway.
    pub root: TorusPatch,
    /// Rounding at the rim.
    pub rim: TorusPatch,
}

impl Flange {
    /// Builds the flange in the frame of its placement.
    pub fn new(shape: &FlangeShape, at: &FlangePlacement) -> Self {
        let (st, ct) = shape.opening_angle.sin_cos();
        let (f, sigma) = (at.facing, at.rises);
        // Generator: away from the raceway (σ radially), receding from the roller (−f).
        let (ds, drho) = (-f * st, sigma * ct);
        // Outward normal (f cos θ, σ sin θ) = side·(−dρ, ds).
        let side = -f * sigma;
        let (ns, nr) = (f * ct, sigma * st);
        let face_point = |g: f64| (at.face_position + g * ds, at.raceway_radius + g * drho);
        let r1 = shape.root_radius;
        let r2 = shape.rim_radius;
        // Tube centres behind the face, tangent to it; the root tube reaches down to the
        // raceway radius, the rim tube up to the flange's top.
        let g1 = r1 * (1.0 + st) / ct;
        let g2 = (shape.height - r2 + r2 * st) / ct;
        let torus_at = |g: f64, r: f64, towards: f64| {
            let (s, rho) = face_point(g);
            let (cs, crho) = (s - r * ns, rho - r * nr);
            // Arc from the face normal to the radial direction `towards`·σ.
            let phi_face = ns.atan2(nr);
            let phi_end = 0.0f64.atan2(towards * sigma);
            let mut delta = (phi_end - phi_face).rem_euclid(std::f64::consts::TAU);
            if delta > std::f64::consts::PI {
                delta -= std::f64::consts::TAU;
            }
            TorusPatch {
                origin: at.origin + at.axis * cs,
                axis: at.axis,
                major_radius: crho,
                minor_radius: r,
                phi_mid: phi_face + 0.5 * delta,
                phi_half: 0.5 * delta.abs(),
            }
        };
        let cone = ConePatch {
            origin: at.origin,
            axis: at.axis,
            s0: at.face_position,
            rho0: at.raceway_radius,
            ds,
            drho,
            side,
            g_min: g1,
            g_max: g2,
        };
        Self {
            cone,
            root: torus_at(g1, r1, -1.0),
            rim: torus_at(g2, r2, 1.0),
        }
    }
}

/// The area of a roller's end face that lies on a flange's face (cone) when the end lies
/// flat on it, the roller on its raceway: the band of heights above the raceway from the
/// cone's foot to its top (the root and rim tori's tangent points), cut from the end
/// face's disc (radius ρ_j, where the end sphere meets the edge torus, centred one roller
/// radius above the raceway) [m²]. B1: 0.400 mm².
pub fn face_contact_area(roller: &RollerShape, flange: &FlangeShape) -> f64 {
    let st = flange.opening_angle.sin();
    let foot = flange.root_radius * (1.0 + st);
    let top = flange.height - flange.rim_radius * (1.0 - st);
    let rho = roller.end_face_radius * roller.edge_tangent_angle().cos();
    // The disc's area below the height h (measured from its centre, h = u ρ).
    let below = |h: f64| {
        let u = ((h - roller.radius) / rho).clamp(-1.0, 1.0);
        rho * rho * (std::f64::consts::PI - u.acos() + u * (1.0 - u * u).sqrt())
    };
    below(top) - below(foot)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn b1_flange(facing: f64) -> Flange {
        let shape = FlangeShape::new(0.11f64.to_radians(), 1.1e-3, 0.2e-3, 0.3e-3).unwrap();
        Flange::new(
            &shape,
            &FlangePlacement {
                origin: Vec3::zeros(),
                axis: Vec3::x(),
                raceway_radius: 10e-3,
                rises: 1.0,
                face_position: -facing * (2.5e-3 + 20e-6),
                facing,
            },
        )
    }

    #[test]
    fn flange_figures_are_tangent() {
        // The root and rim tori touch the face at the ends of the cone patch: the face
        // points there are at distance r from the tube centres, along the face normal.
        for facing in [-1.0, 1.0] {
            let fl = b1_flange(facing);
            for (torus, g) in [(fl.root, fl.cone.g_min), (fl.rim, fl.cone.g_max)] {
                let (s, rho) = (fl.cone.s0 + g * fl.cone.ds, fl.cone.rho0 + g * fl.cone.drho);
                let p = Vec3::new(s, rho, 0.0);
                let foot = torus.foot(&p);
                assert!(foot.distance.abs() < 1e-15, "{}", foot.distance);
                assert!(foot.on_patch);
                let cone_foot = fl.cone.foot(&p);
                assert!((foot.normal - cone_foot.normal).norm() < 1e-12);
            }
            // The root tube reaches the raceway radius, the rim tube the flange top.
            assert!((fl.root.major_radius - fl.root.minor_radius - 10e-3).abs() < 1e-15);
            assert!((fl.rim.major_radius + fl.rim.minor_radius - 11.1e-3).abs() < 1e-15);
        }
    }

    #[test]
    fn face_recedes_away_from_the_raceway() {
        // Inner-ring flange at +x (facing −x): higher up the face lies further along +x.
        let fl = b1_flange(-1.0);
        let low = fl.cone.s0 + fl.cone.g_min * fl.cone.ds;
        let high = fl.cone.s0 + fl.cone.g_max * fl.cone.ds;
        assert!(high > low);
        let (ns, _) = fl.cone.meridian_normal();
        assert!(ns < 0.0);
    }

    #[test]
    fn b1_face_contact_area_is_a_circular_segment() {
        // B1: the face disc (ρ_j = R_s (R − r_e)/(R_s − r_e) = 1.7477 mm, centre R =
        // 2.2475 mm above the race) below the cone's top, h − r_rim (1 − sin θ) = 0.8006 mm
        // above the race: a segment of chord distance d = R − top from the centre,
        // ρ² acos(d/ρ) − d √(ρ² − d²) = 0.400 mm².
        let roller = RollerShape::new(4.495e-3 / 2.0, 5e-3, 0.5e-3, 5.0).unwrap();
        let theta = 0.11f64.to_radians();
        let flange = FlangeShape::new(theta, 1.1e-3, 0.2e-3, 0.3e-3).unwrap();
        let rho = 5.0 * (2.2475e-3 - 0.5e-3) / (5.0 - 0.5e-3);
        let d = 2.2475e-3 - (1.1e-3 - 0.3e-3 * (1.0 - theta.sin()));
        let segment = rho * rho * (d / rho).acos() - d * (rho * rho - d * d).sqrt();
        let area = face_contact_area(&roller, &flange);
        assert!((area / segment - 1.0).abs() < 1e-9, "{area} vs {segment}");
        assert!((area - 0.400e-6).abs() < 1e-9);
    }

    #[test]
    fn refuses_impossible_flanges() {
        assert!(FlangeShape::new(-0.1, 1e-3, 1e-4, 1e-4).is_err());
        assert!(FlangeShape::new(0.001, 1e-3, 6e-4, 6e-4).is_err());
        assert!(FlangeShape::new(0.001, f64::NAN, 1e-4, 1e-4).is_err());
    }
}
