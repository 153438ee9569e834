//! Contact detection between a roller end and a flange (paper sect. 2).
//!
//! Each pairing of a roller figure (edge torus, end sphere) with a flange figure (cone,
//! root torus, rim torus) yields a [`Contact`]: the contact points P₁ (roller) and P₂
//! (flange), the contact location P_m = (P₁ + P₂)/2 (eq. 1), the signed penetration δ
//! (positive = overlap, negative = gap), the unit contact normal n (from the flange towards
//! the roller), and the relative principal radii R_x ≤ R_y with the direction of the
//! ellipse's major axis (along R_y), as Hertz (eqs. 5–8) and Chittenden's ξ (eq. 46) need.
//!
//! * [`benchmark`]: time and accuracy of the methods on a roller's trajectory.
//! * [`border`]: the roller's curvature blended across its torus/sphere border.
//! * [`semi_analytical`]: the method of Wolf, Sanner & Fatemi (2020) used by the paper.
//! * [`gradient`]: Koch's gradient method (8 × 8 Newton, warm-started).
//! * [`pruning`]: conservative bounds that skip pairings and flanges that cannot touch.
//! * [`reference`]: brute force plus local refinement, slow and sure, to check the others.

pub mod benchmark;
pub mod border;
pub mod distributed;
pub mod gradient;
pub mod mesh;
pub mod pruning;
pub mod reference;
pub mod semi_analytical;
#[cfg(test)]
pub(crate) mod tests;

use crate::geometry::primitives::{relative_curvature, Curvature, Vec3};

/// The six pairings of roller figure × flange figure (paper fig. 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Pairing {
    /// Roller edge torus – flange face cone (Gupta's pairing).
    TorusCone,
    /// Roller edge torus – flange root torus.
    TorusRoot,
    /// Roller edge torus – flange rim torus.
    TorusRim,
    /// Roller end sphere – flange face cone.
    SphereCone,
    /// Roller end sphere – flange root torus.
    SphereRoot,
    /// Roller end sphere – flange rim torus.
    SphereRim,
}

impl Pairing {
    /// All six, in a fixed order (the composite's tie-break order).
    pub const ALL: [Pairing; 6] = [
        Pairing::TorusCone,
        Pairing::TorusRoot,
        Pairing::TorusRim,
        Pairing::SphereCone,
        Pairing::SphereRoot,
        Pairing::SphereRim,
    ];

    /// The figures paired: (roller figure: 0 edge torus, 1 end sphere; flange figure:
    /// 0 cone, 1 root torus, 2 rim torus). In [`Pairing::ALL`] order the index is
    /// 3·roller + flange.
    pub fn figures(&self) -> (usize, usize) {
        match self {
            Pairing::TorusCone => (0, 0),
            Pairing::TorusRoot => (0, 1),
            Pairing::TorusRim => (0, 2),
            Pairing::SphereCone => (1, 0),
            Pairing::SphereRoot => (1, 1),
            Pairing::SphereRim => (1, 2),
        }
    }

    /// Short label as in the paper's figs. 8, 9 (TO-CO, ...).
    pub fn label(&self) -> &'static str {
        match self {
            Pairing::TorusCone => "TO-CO",
            Pairing::TorusRoot => "TO-TO(root)",
            Pairing::TorusRim => "TO-TO(rim)",
            Pairing::SphereCone => "SP-CO",
            Pairing::SphereRoot => "SP-TO(root)",
            Pairing::SphereRim => "SP-TO(rim)",
        }
    }
}

/// The result of one pairing's detection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// Which figures.
    pub pairing: Pairing,
    /// Contact point on the roller [m].
    pub p1: Vec3,
    /// Contact point on the flange [m].
    pub p2: Vec3,
    /// Signed penetration δ: positive overlap, negative gap [m].
    pub penetration: f64,
    /// Unit contact normal, from the flange towards the roller.
    pub normal: Vec3,
    /// Smaller relative principal radius R_x [m]. Like `ry` and `major_axis`, computed
    /// for valid contacts, overlaps (which carry load by them) and gaps (across which the
    /// squeeze film of [`crate::tribology::squeeze`] acts by them); NaN for invalid ones
    /// (and for the mesh baseline, which has no curvature). For a valid overlapping
    /// contact of the analytical detectors it is finite and within
    /// [[`RADIUS_MIN`], [`RADIUS_MAX`]] ([`relative_radius`]).
    pub rx: f64,
    /// Larger relative principal radius R_y [m].
    pub ry: f64,
    /// Unit direction of the contact ellipse's major axis (along R_y).
    pub major_axis: Vec3,
    /// True if both points lie on their patches (otherwise the contact does not count).
    pub valid: bool,
    /// True if the extremum is not unique (symmetric poses: two mirror-image closest
    /// pairs of two circles, or a circle parallel to a plane); the points are then one
    /// representative of several with the same penetration.
    pub multiple: bool,
}

impl Contact {
    /// Contact location P_m = (P₁ + P₂)/2, paper eq. 1.
    pub fn location(&self) -> Vec3 {
        0.5 * (self.p1 + self.p2)
    }

    /// Assembles a contact from its points, normal and the two surfaces' curvatures.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn from_parts(
        pairing: Pairing,
        p1: Vec3,
        p2: Vec3,
        normal: Vec3,
        penetration: f64,
        roller: &Curvature,
        flange: &Curvature,
        valid: bool,
    ) -> Self {
        Self::assemble(
            pairing,
            p1,
            p2,
            normal,
            penetration,
            || (*roller, *flange),
            valid,
        )
    }

    /// As [`Contact::from_parts`], with the curvatures evaluated only where they are used
    /// (valid contacts: an overlap's load and a gap's squeeze film).
    pub(crate) fn assemble(
        pairing: Pairing,
        p1: Vec3,
        p2: Vec3,
        normal: Vec3,
        penetration: f64,
        curvatures: impl FnOnce() -> (Curvature, Curvature),
        valid: bool,
    ) -> Self {
        let (rx, ry, major_axis) = if valid {
            let (roller, flange) = curvatures();
            let (kx, ky, major) = relative_curvature(&normal, &roller, &flange);
            (relative_radius(kx), relative_radius(ky), major)
        } else {
            (f64::NAN, f64::NAN, Vec3::repeat(f64::NAN))
        };
        Self {
            pairing,
            p1,
            p2,
            penetration,
            normal,
            rx,
            ry,
            major_axis,
            valid,
            multiple: false,
        }
    }
}

/// Smallest relative principal radius a loaded contact reports [m]: 1 nm, below the
/// roughness of any bearing surface.
pub const RADIUS_MIN: f64 = 1e-9;

/// Largest relative principal radius a loaded contact reports [m]: 1000 km, flatter than
/// the form tolerance of any bearing surface.
pub const RADIUS_MAX: f64 = 1e6;

/// The relative principal radius 1/k of a relative principal curvature k, clamped to
/// [[`RADIUS_MIN`], [`RADIUS_MAX`]]: the contract of every valid overlapping contact
/// (the only kind that carries load) is finite R_x, R_y > 0, as Hertz (paper eqs. 5–8)
/// needs them (R = ∞ or 0 made the force NaN: docs/robustness.md, findings 4 and 6).
///
/// Why a clamp (and not an invalid contact): the relative curvature leaves (0, ∞) only
/// where the local quadratic shape behind Hertz no longer describes the bodies — a
/// non-positive k where the surfaces conform or form a saddle (an end sphere in an outer
/// ring's concave bore, points deep inside the other body), an infinite k where a figure's
/// curvature is singular (a parallel circle shrinking to a point on a ring or roller axis)
/// or its square overflows. Such contacts are still overlaps that must push the bodies
/// apart; the clamp keeps a repelling force that is finite and continuous in the pose
/// (an invalid contact would drop it to zero with a jump, letting a roller end pass
/// through a flange). The bounds are far outside any real contact (B1's radii lie
/// between 0.2 mm and about 15 m), so those are unchanged bit for bit. An undefined
/// curvature (NaN) stays NaN: it carries no load ([`crate::bearing::forces::end_flange`]
/// checks R > 0).
#[inline]
pub fn relative_radius(k: f64) -> f64 {
    if k.is_nan() {
        return f64::NAN;
    }
    1.0 / k.clamp(1.0 / RADIUS_MAX, 1.0 / RADIUS_MIN)
}

/// The composite result of one roller end against one flange: the valid pairing with
/// the largest penetration (ties: the first in [`Pairing::ALL`]), or None if no pairing
/// is valid.
pub fn deepest(contacts: &[Contact]) -> Option<Contact> {
    contacts
        .iter()
        .filter(|c| c.valid && c.penetration.is_finite())
        .fold(None, |best: Option<Contact>, c| match best {
            Some(b) if b.penetration >= c.penetration => Some(b),
            _ => Some(*c),
        })
}
