//! The state vector's layout and the bodies' kinematics read from it.
//!
//! Inner ring first: position (3), velocity (3); with tilt free also the axis angles
//! (θ_y, θ_z) and the transverse angular velocity (3). Then per roller: centre (3), axis
//! angles θ_y, θ_z (2), velocity (3), angular velocity ω (3, spin included) — 11 states.
//! The inner ring's spin is prescribed and not a state; the outer ring is centred and
//! aligned, its spin prescribed too (0 unless it turns, [`Kinematics::turning`]).
//! [`BearingKinematics`] gathers the kinematics of all bodies at one state.

use super::topology::Body;
use crate::dynamics::rigid::axis_from_angles;
use crate::geometry::primitives::Vec3;

/// States per roller.
pub const ROLLER_STATES: usize = 11;

/// Where each body's states sit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Layout {
    /// Number of rollers.
    pub rollers: usize,
    /// Inner ring tilt free.
    pub tilt_free: bool,
}

impl Layout {
    /// States of the inner ring.
    pub fn ring_states(&self) -> usize {
        if self.tilt_free {
            11
        } else {
            6
        }
    }

    /// First state of roller `i`.
    pub fn roller(&self, i: usize) -> usize {
        self.ring_states() + ROLLER_STATES * i
    }

    /// Total states.
    pub fn len(&self) -> usize {
        self.roller(self.rollers)
    }

    /// Never empty (a ring and at least three rollers).
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Which body a state belongs to: None for the ring, Some(i) for roller i.
    pub fn body_of(&self, state: usize) -> Option<usize> {
        state
            .checked_sub(self.ring_states())
            .map(|k| k / ROLLER_STATES)
    }
}

/// Position, orientation and velocities of a rigid body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kinematics {
    /// Centre of mass [m].
    pub center: Vec3,
    /// Unit axis.
    pub axis: Vec3,
    /// Velocity of the centre [m/s].
    pub velocity: Vec3,
    /// Angular velocity [rad/s].
    pub omega: Vec3,
}

impl Kinematics {
    /// A body at rest at the origin with axis +x (a fixed outer ring).
    pub fn fixed() -> Self {
        Self::turning(0.0)
    }

    /// The outer ring: centred at the origin with axis +x, turning at `speed` [rad/s]
    /// about +x (0: fixed, B1; a planet gear's bearing turns its outer ring).
    pub fn turning(speed: f64) -> Self {
        Self {
            center: Vec3::zeros(),
            axis: Vec3::x(),
            velocity: Vec3::zeros(),
            omega: Vec3::new(speed, 0.0, 0.0),
        }
    }

    /// Orbital angular velocity of the centre about the bearing axis (x) [rad/s].
    #[inline]
    pub fn orbital_speed(&self) -> f64 {
        let c = &self.center;
        let rho2 = c.y * c.y + c.z * c.z;
        (c.y * self.velocity.z - c.z * self.velocity.y) / rho2.max(1e-300)
    }

    /// Velocity of the frame that carries this roller's contact locations, at `p`: the
    /// centre velocity plus the orbital rotation about the bearing axis.
    #[inline]
    pub fn frame_velocity(&self, p: &Vec3) -> Vec3 {
        self.velocity + Vec3::new(self.orbital_speed(), 0.0, 0.0).cross(&(p - self.center))
    }

    /// Velocity of the material point at `p`: v + ω × (p − c).
    #[inline]
    pub fn point_velocity(&self, p: &Vec3) -> Vec3 {
        self.velocity + self.omega.cross(&(p - self.center))
    }

    /// This body's motion seen from the rigid body `frame` (the outer ring, for the power
    /// losses): the velocity less that of the frame's material point at the centre, and the
    /// angular velocity less the frame's. Positions stay.
    pub fn seen_from(&self, frame: &Kinematics) -> Self {
        Self {
            velocity: self.velocity - frame.point_velocity(&self.center),
            omega: self.omega - frame.omega,
            ..*self
        }
    }
}

/// Reads roller `i` from the state.
#[inline]
pub fn roller_kinematics(layout: &Layout, y: &[f64], i: usize) -> Kinematics {
    let s = &y[layout.roller(i)..layout.roller(i) + ROLLER_STATES];
    Kinematics {
        center: Vec3::new(s[0], s[1], s[2]),
        axis: axis_from_angles(s[3], s[4]),
        velocity: Vec3::new(s[5], s[6], s[7]),
        omega: Vec3::new(s[8], s[9], s[10]),
    }
}

/// Reads the inner ring from the state, with its prescribed spin Ω about its axis;
/// `locked_axis` is the (unit) axis of a ring whose tilt is locked.
#[inline]
pub fn ring_kinematics(layout: &Layout, y: &[f64], spin: f64, locked_axis: &Vec3) -> Kinematics {
    let center = Vec3::new(y[0], y[1], y[2]);
    let velocity = Vec3::new(y[3], y[4], y[5]);
    if layout.tilt_free {
        let axis = axis_from_angles(y[6], y[7]);
        let transverse = Vec3::new(y[8], y[9], y[10]);
        let transverse = transverse - transverse.dot(&axis) * axis;
        Kinematics {
            center,
            axis,
            velocity,
            omega: spin * axis + transverse,
        }
    } else {
        Kinematics {
            center,
            axis: *locked_axis,
            velocity,
            omega: spin * locked_axis,
        }
    }
}

/// The kinematics of every body at one state: the inner ring, the outer ring (centred and
/// aligned, turning at its prescribed speed, [`Kinematics::turning`]) and the rollers.
#[derive(Debug, Clone, PartialEq)]
pub struct BearingKinematics {
    /// The inner ring.
    pub inner_ring: Kinematics,
    /// The outer ring.
    pub outer_ring: Kinematics,
    /// The rollers, in order.
    pub rollers: Vec<Kinematics>,
}

impl BearingKinematics {
    /// The kinematics of `body`.
    pub fn of(&self, body: Body) -> &Kinematics {
        match body {
            Body::InnerRing => &self.inner_ring,
            Body::OuterRing => &self.outer_ring,
            Body::Roller(i) => &self.rollers[i],
        }
    }
}

/// Azimuth ψ of a point about the bearing axis, from +y towards +z, in [0, 2π).
#[inline]
pub fn azimuth(p: &Vec3) -> f64 {
    p.z.atan2(p.y).rem_euclid(2.0 * std::f64::consts::PI)
}

/// Tilt and skew of a roller axis in its azimuth frame: tilt turns the axis about the
/// circumferential direction (towards radial), skew about the radial direction (towards
/// circumferential) (docs/dynamics.md, "Bodies and state").
#[inline]
pub fn tilt_and_skew(center: &Vec3, axis: &Vec3) -> (f64, f64) {
    let psi = azimuth(center);
    let radial = Vec3::new(0.0, psi.cos(), psi.sin());
    let circumferential = Vec3::x().cross(&radial);
    let a = if axis.x < 0.0 { -axis } else { *axis };
    (a.dot(&radial).asin(), a.dot(&circumferential).atan2(a.x))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tilt_and_skew_are_the_axis_components_in_the_azimuth_frame() {
        // Roller at the bottom (ψ = π): radial is −y, circumferential e_x × radial = −z.
        let c = Vec3::new(0.0, -0.01225, 0.0);
        assert!((azimuth(&c) - std::f64::consts::PI).abs() < 1e-12);
        let (tilt, skew) = tilt_and_skew(&c, &Vec3::new(1.0, -0.01, 0.0).normalize());
        assert!((tilt - 0.01f64.atan()).abs() < 1e-9 && skew.abs() < 1e-12);
        let (tilt, skew) = tilt_and_skew(&c, &Vec3::new(1.0, 0.0, -0.02).normalize());
        assert!(tilt.abs() < 1e-12 && (skew - 0.02f64.atan()).abs() < 1e-9);
    }

    /// A locked ring with a prescribed misalignment γ moves as the free ring at the tilt
    /// angles (0, γ) with no transverse rotation: the same axis, turned by γ about z, and
    /// the spin about that axis.
    #[test]
    fn misaligned_locked_ring_is_the_free_ring_held_at_its_tilt() {
        let gamma = 0.05f64.to_radians();
        let spin = 52.36;
        let locked = Layout {
            rollers: 3,
            tilt_free: false,
        };
        let free = Layout {
            rollers: 3,
            tilt_free: true,
        };
        let y_locked = [1e-6, -2e-6, 3e-6, 0.1, 0.2, 0.3];
        let mut y_free = [0.0; 11];
        y_free[..6].copy_from_slice(&y_locked);
        y_free[7] = gamma;
        let a = ring_kinematics(&locked, &y_locked, spin, &axis_from_angles(0.0, gamma));
        let b = ring_kinematics(&free, &y_free, spin, &Vec3::x());
        assert!((a.axis - Vec3::new(gamma.cos(), gamma.sin(), 0.0)).norm() < 1e-15);
        assert!((a.axis - b.axis).norm() < 1e-15);
        assert!((a.omega - b.omega).norm() < 1e-12 * spin);
        assert_eq!((a.center, a.velocity), (b.center, b.velocity));
    }

    #[test]
    fn layout_maps_states_to_bodies() {
        for tilt_free in [false, true] {
            let l = Layout {
                rollers: 17,
                tilt_free,
            };
            assert_eq!(l.len(), l.ring_states() + 17 * ROLLER_STATES);
            assert_eq!(l.body_of(0), None);
            assert_eq!(l.body_of(l.roller(5) + 10), Some(5));
            assert_eq!(l.body_of(l.len() - 1), Some(16));
        }
    }
}
