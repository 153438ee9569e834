//! The forces of a roller end against a flange, from the contact detected
//! ([`super::detection`], paper sect. 2): Hertz's point contact by the Brewe–Hamrock fits
//! (eqs. 5–8) at the contact location P_m (eq. 1), or, with the distributed flange law (not
//! in the paper), the whole overlap on a Winkler foundation ([`foundation`]) at its centre;
//! Chittenden's film and the traction of sect. 3.2 ([`flange_friction`]); beyond the
//! paper, the squeeze film of the oil in the gap and over the contact
//! ([`crate::tribology::squeeze`]).

use super::contacts::ElementResult;
use super::detection::EndGeometry;
use super::forces::{end_flange, flange_friction, penetration_rate, ContactForces, FlangeLoad};
use super::state::Kinematics;
use crate::bearing::workspace::BearingSystem;
use crate::contact::distributed::DistributedOverlap;
use crate::contact::{relative_radius, Contact, Pairing};
use crate::tribology::foundation;
use std::f64::consts::PI;

impl BearingSystem<'_> {
    /// The forces of a roller end (`roller`) against a flange of `ring` whose contact
    /// `geometry` was detected at the same positions ([`Self::geometry`]; given apart for
    /// Jacobian columns of velocities, which leave it unchanged).
    pub(super) fn flange_element_at(
        &self,
        ring: &Kinematics,
        roller: &Kinematics,
        geometry: &EndGeometry,
    ) -> ElementResult {
        let mut out = ElementResult::untouched();
        let Some(c) = geometry.contact.as_ref() else {
            return out;
        };
        out.penetration = c.penetration;
        let squeeze = &self.params.squeeze_film;
        // The distributed law carries across gaps within the asperities' reach.
        let carries = geometry.overlap.is_some() || (!self.distributed() && c.penetration > 0.0);
        if c.penetration.is_nan()
            || (!carries && (c.penetration <= -squeeze.reach() || !squeeze.enabled))
        {
            return out;
        }
        let start = self.workspace.profiler.stopwatch();
        let p = c.location();
        let approach = penetration_rate(ring, roller, &p, &c.normal);
        let squeeze_force =
            squeeze.damping(self.tribology.eta0, c.rx, c.ry, c.penetration) * approach;
        let (mut f, normal, location) = match &geometry.overlap {
            Some(overlap) => (
                self.distributed_forces(ring, roller, overlap, geometry.foundation_modulus),
                overlap.normal,
                overlap.centre,
            ),
            None if carries => (self.point_forces(ring, roller, c), c.normal, p),
            // A gap (or, with the distributed law, no load): only the squeeze film acts.
            None => (ContactForces::default(), c.normal, p),
        };
        if carries {
            out.location = location;
            out.pairing = Pairing::ALL.iter().position(|q| *q == c.pairing);
        }
        f.normal += squeeze_force;
        // the squeeze film's force acts where the law puts the contact: at the detected
        // point (its approach rate is the film's own), or at the overlap's centre
        let applied = match geometry.overlap {
            Some(_) => penetration_rate(ring, roller, &location, &normal),
            None => approach,
        };
        f.normal_power += squeeze_force * applied;
        out.add_forces(&f, &normal, &location, ring, roller);
        self.workspace
            .profiler
            .spend_time(start, |pr, t| pr.flange_forces += t);
        out
    }

    fn distributed(&self) -> bool {
        self.params.flange_law == super::params::FlangeLaw::Distributed
    }

    /// The paper's point contact: Hertz at P_m with the detected (blended) radii.
    fn point_forces(&self, ring: &Kinematics, roller: &Kinematics, c: &Contact) -> ContactForces {
        let p = c.location();
        end_flange(
            &self.tribology,
            &self.ellipse,
            ring,
            roller,
            &c.normal,
            &p,
            c.penetration,
            (c.rx, c.ry),
            &c.major_axis,
            &roller.frame_velocity(&p),
        )
    }

    /// The distributed overlap on its Winkler foundation of modulus `modulus`
    /// ([`foundation::foundation_force`]), at its centre, with the film and the traction of
    /// the ellipse of equal second moments (semi-axes a, b): p₀ = 1.5 F/(π a b), relative
    /// radii a²/δ and b²/δ (Hertz's a² = R δ), δ the largest local load p/K; the stiffness
    /// dF/dδ = K ∫ dp/dg dA for the damping.
    fn distributed_forces(
        &self,
        ring: &Kinematics,
        roller: &Kinematics,
        overlap: &DistributedOverlap,
        modulus: f64,
    ) -> ContactForces {
        let elastic = foundation::foundation_force(modulus, overlap.volume);
        let depth = overlap.max_depth;
        if !(elastic > 0.0 && depth > 0.0) {
            return ContactForces::default();
        }
        let (a, b) = overlap.semi_axes;
        let radius = |s: f64| relative_radius(depth / (s * s));
        let (r_major, r_minor) = (radius(a), radius(b));
        let load = FlangeLoad {
            elastic,
            stiffness: modulus * overlap.stiffness_area,
            radii: (r_minor.min(r_major), r_major.max(r_minor)),
            major_axis: overlap.major_axis,
        };
        let frame = roller.frame_velocity(&overlap.centre);
        flange_friction(
            &self.tribology,
            &self.ellipse,
            ring,
            roller,
            &overlap.normal,
            &overlap.centre,
            &load,
            &frame,
            |f| (1.5 * f / (PI * a.max(1e-12) * b.max(1e-12)), a, b),
        )
    }
}
