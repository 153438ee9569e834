//! The forces of a roller end against a flange, from the contact detected
//! ([`super::detection`], paper sect. 2): Hertz's point contact by the Brewe–Hamrock fits
//! (eqs. 5–8) at the contact location P_m (eq. 1), Chittenden's film and the traction of
//! sect. 3.2 ([`end_flange`]); beyond the paper, the squeeze film of the oil in the gap
//! and over the contact ([`crate::tribology::squeeze`]).

use super::contacts::ElementResult;
use super::forces::{end_flange, penetration_rate, ContactForces};
use super::model::BearingModel;
use super::state::Kinematics;
use crate::contact::{Contact, Pairing};

impl BearingModel {
    /// Evaluates the contact of roller i's end (`roller`) against flange k of `ring`.
    pub(super) fn flange_element(
        &self,
        i: usize,
        k: usize,
        ring: &Kinematics,
        roller: &Kinematics,
    ) -> ElementResult {
        let end = self.roller_end(k, roller);
        let contact = self.end_contact(&end, &self.flange(k, ring), i, k);
        self.flange_element_at(ring, roller, contact.as_ref())
    }

    /// [`Self::flange_element`] with the contact given (`contact`, detected at the same
    /// positions): for Jacobian columns of velocities, which leave it unchanged.
    pub(super) fn flange_element_at(
        &self,
        ring: &Kinematics,
        roller: &Kinematics,
        contact: Option<&Contact>,
    ) -> ElementResult {
        let mut out = ElementResult::untouched();
        let Some(c) = contact else {
            return out;
        };
        out.penetration = c.penetration;
        let squeeze = &self.params.squeeze_film;
        if c.penetration.is_nan()
            || c.penetration <= -squeeze.reach()
            || (c.penetration <= 0.0 && !squeeze.enabled)
        {
            return out;
        }
        let start = self.profiler.stopwatch();
        let p = c.location();
        let frame = roller.frame_velocity(&p);
        let squeeze_force = squeeze.damping(self.tribology.eta0, c.rx, c.ry, c.penetration)
            * penetration_rate(ring, roller, &p, &c.normal);
        if c.penetration <= 0.0 {
            // A gap within the squeeze film's reach: only the film acts.
            let film = ContactForces {
                normal: squeeze_force,
                ..Default::default()
            };
            out.add_forces(&film, &c.normal, &p, ring, roller);
            self.profiler
                .spend_time(start, |pr, t| pr.flange_forces += t);
            return out;
        }
        out.location = p;
        out.pairing = Pairing::ALL.iter().position(|q| *q == c.pairing);
        let mut f = end_flange(
            &self.tribology,
            &self.ellipse,
            ring,
            roller,
            &c.normal,
            &p,
            c.penetration,
            (c.rx, c.ry),
            &c.major_axis,
            &frame,
        );
        f.normal += squeeze_force;
        out.add_forces(&f, &c.normal, &p, ring, roller);
        self.profiler
            .spend_time(start, |pr, t| pr.flange_forces += t);
        out
    }
}
