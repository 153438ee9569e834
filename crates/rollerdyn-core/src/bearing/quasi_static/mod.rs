//! Quasi-static analysis of the bearing (beyond the paper; the classical analysis of
//! Harris & Kotzalas, "Rolling Bearing Analysis", 5th ed., ch. 7, and ISO/TS 16281:2008):
//! the equilibrium of the inner ring and the rollers under a radial load, an axial load, a
//! tilting moment or a prescribed misalignment, at rest or at a speed, with the contact
//! laws of the dynamic model:
//!
//! * race contacts by slices (eq. 11 per slice, the roller's crowning in the slice radii,
//!   the roller's tilt in the slice penetrations);
//! * roller end–flange contacts by the semi-analytical detector with pruning (sect. 2.1,
//!   5.3) and the curvature blended across patch borders, Hertz by Brewe–Hamrock (eqs. 5–8),
//!   or with the distributed flange law (not in the paper) the whole overlap on its
//!   Winkler foundation ([`crate::contact::distributed`], [`crate::tribology::foundation`]);
//! * centrifugal force and the gyroscopic moment of the roller's steady motion (the roller
//!   set orbits at the epicyclic speed ω_c = Ω(1 − D/d_m)/2 and each roller spins relative
//!   to it at ω_s = −(Ω − ω_c) r_i/r, Harris & Kotzalas sect. 8.2), and gravity.
//!
//! Unknowns: the ring's centre (3) and tilt (2; prescribed unless free), and per roller
//! its radial offset, axial position and tilt about its tangential axis ([`RollerPose`]).
//! Each roller's azimuth stays where it is and its skew zero; roller–roller contacts and
//! friction are left out (they act along the circumference, which nothing here resolves),
//! as in ISO/TS 16281. Solved by Newton's method with a Jacobian by forward differences
//! whose roller columns are grouped (the rollers touch only the rings, so one evaluation
//! perturbs the same unknown of every roller): coupled steps of the ring and the rollers
//! with the rollers condensed out, a chord (kept) Jacobian while the residual falls fast,
//! each roller's own search where its predicted move fails, a step limit and, where
//! Newton stalls, continuation in the load; where that fast path fails, a careful one
//! that searches every roller's equilibrium at every trial ([`solver`]). A case symmetric
//! about the load plane is solved on half the rollers ([`mirror`]). An equilibrium whose
//! flange contacts exceed 4 GPa is refused ([`FLANGE_PRESSURE_LIMIT`]). The bearing's 5×5
//! stiffness is the Schur complement of the rollers in the Jacobian at the equilibrium
//! ([`stiffness`]).

mod axial;
mod condense;
mod mirror;
mod relax;
mod roller;
mod solver;
mod stiffness;
#[cfg(test)]
mod tests;

pub use roller::{flange_loads, FlangeLoad, RollerForces, RollerPose, ROLLER_UNKNOWNS};
pub use solver::{FLANGE_PRESSURE_LIMIT, RING_UNKNOWNS};

use super::contacts::Wrench;
use super::params::BearingParams;
use crate::error::{Error, Result};
use crate::geometry::primitives::Vec3;

/// The inner ring's tilt in a quasi-static case.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RingTilt {
    /// Solved from the tilting moment.
    Free,
    /// Prescribed angles (θ_y, θ_z) [rad], a misalignment; the moment that holds them is
    /// a reaction ([`StaticSolution::ring_load`]).
    Prescribed(f64, f64),
}

/// A load case of the quasi-static analysis (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticCase {
    /// Radial load on the inner ring along −y [N].
    pub radial_load: f64,
    /// Axial load on the inner ring along +x [N].
    pub axial_load: f64,
    /// Tilting moment on the inner ring about y and z [N·m].
    pub moment: [f64; 2],
    /// Inner ring speed Ω [rad/s] (0: at rest).
    pub speed: f64,
    /// Outer ring speed Ω_o [rad/s] (0: fixed).
    pub outer_speed: f64,
    /// The planet carrier's speed Ω_c [rad/s] about +x (`BearingParams::carrier`; 0: the
    /// bearing's frame at rest). The speeds above are relative to the carrier.
    pub carrier_speed: f64,
    /// The ring's tilt.
    pub tilt: RingTilt,
    /// The roller set's turn from its reference place [rad]: roller i at azimuth
    /// π + 2πi/Z + φ ([`super::model::BearingModel::roller_azimuths`]), roller 0 under the
    /// load at φ = 0. Over one roller pitch, 2π/Z, the ring's equilibrium passes through
    /// every place it takes as the roller set turns: the varying compliance of a bearing
    /// whose rollers pass the load zone one by one (Sunnersjö, J. Sound Vib. 58 (1978)
    /// 363).
    pub roller_set_phase: f64,
}

impl StaticCase {
    /// The case of `params` at time `t`: its loads and speed then, the ring's tilt free
    /// when the configuration frees it, else its misalignment about z.
    pub fn at_time(params: &BearingParams, t: f64) -> Self {
        Self {
            radial_load: params.radial_load.at(t).0,
            axial_load: params.axial_load.at(t).0,
            moment: [0.0, 0.0],
            speed: params.inner_ring_speed.at(t).0,
            outer_speed: params.outer_ring_speed.at(t).0,
            carrier_speed: params.carrier.speed.at(t).0,
            tilt: if params.inner_ring_tilt_free {
                RingTilt::Free
            } else {
                RingTilt::Prescribed(0.0, params.inner_ring_misalignment)
            },
            roller_set_phase: 0.0,
        }
    }

    /// The prescribed tilt (θ_y, θ_z) [rad] where it is not zero: a misalignment.
    pub fn misalignment(&self) -> Option<(f64, f64)> {
        match self.tilt {
            RingTilt::Prescribed(a, b) if a != 0.0 || b != 0.0 => Some((a, b)),
            _ => None,
        }
    }

    /// The case as an error names it: its loads, and its misalignment or moments where it
    /// has them (the misalignment is applied whole at every load level of the solver's
    /// continuation, so an error at "0 % of the load" may be the misalignment's).
    pub fn describe(&self) -> String {
        let mut text = format!("radial {} N, axial {} N", self.radial_load, self.axial_load);
        if let Some((a, b)) = self.misalignment() {
            let angle = if a == 0.0 {
                format!("{:.4} deg", b.to_degrees())
            } else {
                format!("({:.4}, {:.4}) deg", a.to_degrees(), b.to_degrees())
            };
            text.push_str(&format!(", misalignment {angle}"));
        }
        if self.moment != [0.0, 0.0] {
            text.push_str(&format!(
                ", moment ({}, {}) N m",
                self.moment[0], self.moment[1]
            ));
        }
        text
    }

    /// The acceleration of the field every roller stands in, beyond its orbit's
    /// centrifugal force: gravity (as the carrier stands at t = 0) and the carrier's
    /// centrifugal field at the bearing's axis, Ω_c²·offset [m/s²].
    pub fn roller_field(&self, params: &BearingParams) -> Vec3 {
        params.gravity + self.carrier_speed * self.carrier_speed * params.carrier.offset
    }

    /// Refuses values that are not finite.
    pub fn check(&self) -> Result<()> {
        let named = [
            ("radial_load", self.radial_load),
            ("axial_load", self.axial_load),
            ("moment about y", self.moment[0]),
            ("moment about z", self.moment[1]),
            ("speed", self.speed),
            ("outer_speed", self.outer_speed),
            ("carrier_speed", self.carrier_speed),
            ("roller_set_phase", self.roller_set_phase),
        ];
        for (name, value) in named {
            if !value.is_finite() {
                return Err(Error::invalid(name, value, "must be finite"));
            }
        }
        if self.roller_set_phase.abs() > std::f64::consts::TAU {
            // far beyond a turn the azimuths' sines lose their digits
            return Err(Error::invalid(
                "roller_set_phase",
                format!("{} rad", self.roller_set_phase),
                "must lie within one turn, |phase| <= 2 pi",
            ));
        }
        if let RingTilt::Prescribed(a, b) = self.tilt {
            if !(a.is_finite() && b.is_finite() && a.abs() < 0.1 && b.abs() < 0.1) {
                return Err(Error::invalid(
                    "misalignment",
                    format!("({a}, {b}) rad"),
                    "must be finite and below 0.1 rad",
                ));
            }
        }
        Ok(())
    }
}

/// The equilibrium of a [`StaticCase`].
#[derive(Debug, Clone)]
pub struct StaticSolution {
    /// The case solved.
    pub case: StaticCase,
    /// The inner ring's displacement (x, y, z) [m] and tilt (θ_y, θ_z) [rad].
    pub ring: [f64; RING_UNKNOWNS],
    /// The rollers' poses.
    pub rollers: Vec<RollerPose>,
    /// Each roller's contact forces, with its slice loads.
    pub forces: Vec<RollerForces>,
    /// The sum of the contact forces on the inner ring (about its centre): minus the
    /// external load, and with a prescribed tilt the moment that holds it.
    pub ring_load: Wrench,
    /// The largest unbalanced force left (moments over the roller radius) [N].
    pub residual: f64,
    /// Newton iterations taken.
    pub iterations: usize,
    /// Evaluations of the rollers' contact forces (each for every roller).
    pub evaluations: usize,
}
