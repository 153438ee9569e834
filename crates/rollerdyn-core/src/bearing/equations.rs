//! The equations of motion y' = f(t, y) of the bearing (paper sect. 3, 4; docs/dynamics.md,
//! "Bodies and state"): the bodies' kinematics read from the state, the contacts' wrenches
//! summed per body ([`Loads`]), and the Newton–Euler rates of the rollers (contacts, the
//! drag of the oil–air mixture, [`crate::tribology::drag`], and gravity) and of the inner
//! ring (contacts, the external load, gravity; its spin prescribed). Also the mechanical
//! energy, for conservation checks.

use super::contacts::{ElementResult, Geometry, Wrench};
use super::detection::EndGeometry;
use super::params::FlangeLaw;
use super::state::ROLLER_STATES;
use super::state::{ring_kinematics, roller_kinematics, BearingKinematics, Kinematics};
use super::topology::{Body, Element};
use crate::bearing::workspace::BearingSystem;
use crate::dynamics::rigid::{
    angle_rates, angular_acceleration, angular_momentum, driven_transverse_acceleration,
    TurningFrame,
};
use crate::geometry::primitives::Vec3;
use crate::tribology::drag::roller_drag;
use crate::tribology::hertz::{EllipticalContact, EllipticalMethod};

/// The contacts' wrenches summed per body.
#[derive(Debug, Clone, PartialEq)]
pub struct Loads {
    /// On the inner ring.
    pub inner_ring: Wrench,
    /// On the outer ring.
    pub outer_ring: Wrench,
    /// On each roller.
    pub rollers: Vec<Wrench>,
}

impl Loads {
    /// The wrench on `body`.
    pub(super) fn on(&mut self, body: Body) -> &mut Wrench {
        match body {
            Body::InnerRing => &mut self.inner_ring,
            Body::OuterRing => &mut self.outer_ring,
            Body::Roller(i) => &mut self.rollers[i],
        }
    }
}

/// What acts on every body alike at one time: gravity, and the planet carrier's frame
/// with its inertial forces on the rollers (`BearingParams::carrier`).
#[derive(Debug, Clone, Copy)]
pub(super) struct BodyField {
    /// Gravity in the bearing's frame [m/s²] (turned against a turning carrier).
    gravity: Vec3,
    /// The carrier's frame, where it turns.
    carrier: Option<TurningFrame>,
}

impl BearingSystem<'_> {
    /// Gravity and the carrier's frame at time t.
    pub(super) fn body_field(&self, t: f64) -> BodyField {
        let carrier = &self.params.carrier;
        BodyField {
            gravity: carrier.gravity_at(&self.params.gravity, t),
            carrier: carrier.turns().then(|| carrier.frame(t)),
        }
    }

    /// Kinematics of all bodies: the rings, then the rollers.
    pub fn kinematics(&self, t: f64, y: &[f64]) -> BearingKinematics {
        let spin = self.params.inner_ring_speed.at(t).0;
        BearingKinematics {
            inner_ring: ring_kinematics(&self.layout, y, spin, &self.locked_axis),
            outer_ring: Kinematics::turning(self.params.outer_ring_speed.at(t).0),
            rollers: (0..self.layout.rollers)
                .map(|i| roller_kinematics(&self.layout, y, i))
                .collect(),
        }
    }

    /// Sums contact wrenches per body.
    pub fn loads(&self, results: &[ElementResult]) -> Loads {
        let mut loads = Loads {
            inner_ring: Wrench::default(),
            outer_ring: Wrench::default(),
            rollers: vec![Wrench::default(); self.layout.rollers],
        };
        for (element, r) in self.topology.elements.iter().zip(results) {
            let [a, b] = element.bodies(self.layout.rollers);
            loads.on(a).add(&r.on_a);
            loads.on(b).add(&r.on_b);
        }
        loads
    }

    /// The external load on the inner ring at time t: axial +x, radial −y.
    pub fn external_load(&self, t: f64) -> Vec3 {
        Vec3::new(
            self.params.axial_load.at(t).0,
            -self.params.radial_load.at(t).0,
            0.0,
        )
    }

    /// The drag of the oil–air mixture on a roller of kinematics `kin`: force and moment
    /// about its centre ([`roller_drag`]).
    pub(super) fn roller_drag(&self, kin: &Kinematics) -> Wrench {
        let (force, moment) = roller_drag(
            &self.params.mixture,
            self.params.roller.radius,
            self.params.roller.length,
            &self.drag_stations,
            &kin.axis,
            &kin.velocity,
            &kin.omega,
        );
        Wrench { force, moment }
    }

    /// Rates of roller i's states under the contact load `w` and its drag `drag` (the
    /// Jacobian's columns of another body reuse the drag: it depends on the roller's own
    /// kinematics only, [`Self::roller_drag`]), in the field `field` (gravity, and in a
    /// turning carrier its inertial forces: [`TurningFrame`]).
    pub(super) fn roller_rates_with(
        &self,
        field: &BodyField,
        kin: &Kinematics,
        y: &[f64],
        w: &Wrench,
        drag: &Wrench,
        dy: &mut [f64],
    ) {
        let m = &self.roller_mass;
        let (drag, drag_moment) = (drag.force, drag.moment);
        let moment = w.moment + drag_moment;
        let mut acc = (w.force + drag) / m.mass + field.gravity;
        let (ia, it) = (m.axial_inertia, m.transverse_inertia);
        let alpha = match &field.carrier {
            None => angular_acceleration(&kin.axis, &kin.omega, &moment, ia, it),
            Some(frame) => {
                acc += frame.inertial_acceleration(&kin.center, &kin.velocity);
                frame.angular_acceleration(&kin.axis, &kin.omega, &moment, ia, it)
            }
        };
        let (dty, dtz) = angle_rates(y[3], y[4], &kin.omega);
        dy[..3].copy_from_slice(kin.velocity.as_slice());
        dy[3] = dty;
        dy[4] = dtz;
        dy[5..8].copy_from_slice(acc.as_slice());
        dy[8..11].copy_from_slice(alpha.as_slice());
    }

    /// Rates of the inner ring's states.
    pub(super) fn ring_rates(
        &self,
        t: f64,
        field: &BodyField,
        kin: &Kinematics,
        y: &[f64],
        w: &Wrench,
        dy: &mut [f64],
    ) {
        let p = &self.params;
        let mut acc = (w.force + self.external_load(t)) / p.inner_ring_mass + field.gravity;
        if let Some(frame) = &field.carrier {
            // the ring's displacement from the bearing's axis and its velocity feel the
            // carrier; its centrifugal force there is the load's (`Carrier`)
            let about_axis = TurningFrame {
                axis_point: Vec3::zeros(),
                ..*frame
            };
            acc += about_axis.inertial_acceleration(&kin.center, &kin.velocity);
        }
        dy[..3].copy_from_slice(kin.velocity.as_slice());
        dy[3..6].copy_from_slice(acc.as_slice());
        if self.layout.tilt_free {
            let (dty, dtz) = angle_rates(y[6], y[7], &kin.omega);
            let alpha = driven_transverse_acceleration(
                &kin.axis,
                &kin.omega,
                &w.moment,
                p.inner_ring_axial_inertia,
                p.inner_ring_transverse_inertia,
            );
            dy[6] = dty;
            dy[7] = dtz;
            dy[8..11].copy_from_slice(alpha.as_slice());
        }
    }

    /// f(t, y) from already summed loads.
    pub(super) fn rates(
        &self,
        t: f64,
        y: &[f64],
        kin: &BearingKinematics,
        loads: &Loads,
        dy: &mut [f64],
    ) {
        self.rates_with(t, y, kin, loads, |i| self.roller_drag(&kin.rollers[i]), dy);
    }

    /// [`Self::rates`] with roller i's drag given by `drag(i)` (a Jacobian column reuses
    /// the drags of the unperturbed state for the rollers it does not move).
    pub(super) fn rates_with(
        &self,
        t: f64,
        y: &[f64],
        kin: &BearingKinematics,
        loads: &Loads,
        drag: impl Fn(usize) -> Wrench,
        dy: &mut [f64],
    ) {
        let n = self.layout.ring_states();
        let field = self.body_field(t);
        let ring = &loads.inner_ring;
        self.ring_rates(t, &field, &kin.inner_ring, &y[..n], ring, &mut dy[..n]);
        for i in 0..self.layout.rollers {
            let s = self.layout.roller(i);
            let r = s..s + ROLLER_STATES;
            self.roller_rates_with(
                &field,
                &kin.rollers[i],
                &y[r.clone()],
                &loads.rollers[i],
                &drag(i),
                &mut dy[r],
            );
        }
    }

    /// Elastic energy stored in all contacts [J]: ∫F dδ of eq. 11 per slice,
    /// (l/k₁)·δ^(1/k₂+1)/(1/k₂+1), 2/5·F·δ for a Hertz contact (F ∝ δ^1.5), and
    /// K ∫ Φ dA for the distributed flange law's Winkler foundation.
    pub fn contact_energy(&self, kin: &BearingKinematics) -> f64 {
        let mut energy = 0.0;
        for element in &self.topology.elements {
            if let (Element::End(i, k), FlangeLaw::Distributed) = (*element, self.params.flange_law)
            {
                let [a, b] = element.bodies(self.layout.rollers);
                energy += self.end_energy(i, k, kin.of(a), kin.of(b));
                continue;
            }
            match (self.geometry(element, kin), element.line()) {
                (
                    Geometry::End(EndGeometry {
                        contact: Some(c), ..
                    }),
                    _,
                ) if c.penetration > 0.0 && self.params.flange_law == FlangeLaw::Point => {
                    let hertz = EllipticalContact::new(
                        c.rx,
                        c.ry,
                        self.ellipse.e_prime,
                        EllipticalMethod::BreweHamrock,
                    );
                    energy += 0.4 * hertz.force(c.penetration) * c.penetration;
                }
                (Geometry::Line(geometry), Some(line)) => {
                    let law = &self.lines.kind(line).law;
                    let e = 1.0 / law.k2 + 1.0;
                    for section in geometry.slices() {
                        let delta = section.penetration;
                        if delta > 0.0 {
                            energy += self.lines.slice_length / law.k1 * delta.powf(e) / e;
                        }
                    }
                }
                _ => {}
            }
        }
        energy
    }

    /// Total mechanical energy [J]: kinetic energy of rollers and inner ring (its prescribed
    /// spin excluded), gravity, the contacts' elastic energy, and the potential −F·x of the
    /// external load at time t (conserved for constant loads without friction and damping,
    /// in a carrier at rest).
    pub fn energy(&self, t: f64, y: &[f64]) -> f64 {
        let kin = self.kinematics(t, y);
        let m = &self.roller_mass;
        let g = self.params.gravity;
        let mut energy = self.contact_energy(&kin);
        for k in &kin.rollers {
            let h = angular_momentum(&k.axis, &k.omega, m.axial_inertia, m.transverse_inertia);
            energy += 0.5 * m.mass * k.velocity.norm_squared() + 0.5 * k.omega.dot(&h)
                - m.mass * g.dot(&k.center);
        }
        let ring = &kin.inner_ring;
        let mr = self.params.inner_ring_mass;
        energy += 0.5 * mr * ring.velocity.norm_squared() - mr * g.dot(&ring.center);
        if self.layout.tilt_free {
            let transverse = ring.omega - ring.omega.dot(&ring.axis) * ring.axis;
            energy += 0.5 * self.params.inner_ring_transverse_inertia * transverse.norm_squared();
        }
        energy - self.external_load(t).dot(&ring.center)
    }
}
