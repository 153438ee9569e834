//! One contact of the bearing evaluated: what it does to its two bodies ([`ElementResult`],
//! [`Wrench`]), dispatched to the line contacts ([`super::line_contacts`]: slices, eqs. 2,
//! 3, 11, and the oil film) or the roller end–flange contacts ([`super::detection`],
//! [`super::flange_contacts`]: sect. 2, Hertz eqs. 5–8).
//!
//! A contact can also be evaluated in two parts: its geometry, which depends on positions
//! only (`Geometry`: slice geometry, detected flange contact), and its forces at that
//! geometry. The Jacobian's columns of velocities, which move no contact, reuse the
//! geometry of the unperturbed state ([`super::jacobian`]).
//!
//! Every force acts at its own contact location; the moment on each body is (P_m − c) × F
//! (docs/dynamics.md, "Contacts").

use super::detection::EndGeometry;
use super::forces::ContactForces;
use super::line_contacts::LineGeometry;
use super::state::{BearingKinematics, Kinematics};
use super::topology::Element;
use crate::bearing::workspace::BearingSystem;
use crate::geometry::primitives::Vec3;

/// A force and a moment about the body's centre.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Wrench {
    /// Force [N].
    pub force: Vec3,
    /// Moment about the body's centre of mass [N m].
    pub moment: Vec3,
}

impl Wrench {
    pub(super) fn add(&mut self, other: &Wrench) {
        self.force += other.force;
        self.moment += other.moment;
    }
    pub(super) fn sub(&mut self, other: &Wrench) {
        self.force -= other.force;
        self.moment -= other.moment;
    }
    /// Adds `scale` times `other`.
    pub(super) fn add_scaled(&mut self, other: &Wrench, scale: f64) {
        self.force += scale * other.force;
        self.moment += scale * other.moment;
    }

    /// The power this wrench delivers to a body moving with `k` [W]: F·v + M·ω (about
    /// the body's centre, where the wrench is taken).
    pub fn power(&self, k: &Kinematics) -> f64 {
        self.force.dot(&k.velocity) + self.moment.dot(&k.omega)
    }

    /// Force `f` at point `p` on a body centred at `c`, plus a pure moment.
    fn at(f: Vec3, p: &Vec3, c: &Vec3, pure: Vec3) -> Self {
        Self {
            force: f,
            moment: (p - c).cross(&f) + pure,
        }
    }
}

/// What one contact did.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ElementResult {
    /// Wrench on body A (ring, or roller i for a pair).
    pub on_a: Wrench,
    /// Wrench on body B (roller i, or roller i+1 for a pair).
    pub on_b: Wrench,
    /// Sum of the normal forces [N].
    pub normal: f64,
    /// Sum of the tangential forces on B [N].
    pub tangential: Vec3,
    /// Largest penetration [m] (−∞ if no pairing was valid; for a line contact whose bodies
    /// are apart, an upper bound of it, below 0: see `BearingSystem::penetration_bound`).
    pub penetration: f64,
    /// Roller end / flange: the active pairing (index in [`crate::contact::Pairing::ALL`]),
    /// if any overlaps.
    pub pairing: Option<usize>,
    /// Contact location (roller end / flange) [m].
    pub location: Vec3,
    /// Of [`Self::power_loss`], the sliding's part [W] ([`ContactForces::sliding_power`]).
    pub sliding_power: f64,
    /// Of [`Self::power_loss`], the normal forces' part [W]
    /// ([`ContactForces::normal_power`]); the rest is the rolling resistance's.
    pub normal_power: f64,
    /// The lubrication at the contact's most loaded section (not in the paper's outputs).
    pub lubrication: Lubrication,
}

/// The lubrication of a contact where its pressure is highest: the section (slice, or the
/// one flange ellipse) of the largest maximum pressure p₀, its central film and sliding
/// speed. All 0 where no section is in contact.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Lubrication {
    /// Largest maximum pressure p₀ over the sections [Pa] ([`ContactForces::max_pressure`]).
    pub max_pressure: f64,
    /// Central film thickness h_c at that section [m] ([`ContactForces::film`]).
    pub film: f64,
    /// Sliding speed at that section [m/s] ([`ContactForces::sliding_speed`]).
    pub sliding_speed: f64,
}

impl ElementResult {
    /// Nothing yet: no force, and a penetration of −∞ (the start of a maximum).
    pub(super) fn untouched() -> Self {
        ElementResult {
            penetration: f64::NEG_INFINITY,
            ..Default::default()
        }
    }

    /// The power this contact takes from the motion of its bodies `a` and `b` [W]: minus
    /// what its wrenches deliver to them (not in the paper). It is what the contact
    /// dissipates (friction, traction, rolling resistance, damping, the oil films) plus
    /// the rate at which it stores elastic energy; the latter averages out over steady
    /// running, so the time mean is the contact's power loss. Since every force acts on
    /// both bodies at one point, only the relative motion there does work: F·(v_B − v_A)
    /// at the contact, plus the couples' work on each body.
    ///
    /// The motion is taken relative to the outer ring `outer` (fixed in B1, turning in a
    /// planet gear). Where the contact's wrenches balance (every law but the paper's
    /// rolling resistance) the frame does not matter; the paper's law puts a couple against
    /// each body's rolling without a reaction, whose work would otherwise depend on the
    /// frame: relative to the outer ring a turning-ring bearing's contacts take what a fixed
    /// ring's at the same relative speeds take, and the power over that relative speed is
    /// the frictional torque on the inner ring, as with a fixed outer ring
    /// (docs/dynamics.md, "A turning outer ring").
    pub fn power_loss(&self, a: &Kinematics, b: &Kinematics, outer: &Kinematics) -> f64 {
        -(self.on_a.power(&a.seen_from(outer)) + self.on_b.power(&b.seen_from(outer)))
    }

    /// Adds the forces `f` of one section (normal `n` from A to B, location `p`) between
    /// bodies `a` and `b`.
    pub(super) fn add_forces(
        &mut self,
        f: &ContactForces,
        n: &Vec3,
        p: &Vec3,
        a: &Kinematics,
        b: &Kinematics,
    ) {
        let on_b = f.force_on_b(n);
        self.on_b.add(&Wrench::at(on_b, p, &b.center, f.moment_b));
        self.on_a.add(&Wrench::at(-on_b, p, &a.center, f.moment_a));
        self.normal += f.normal;
        self.tangential += f.tangential;
        self.sliding_power += f.sliding_power;
        self.normal_power += f.normal_power;
        if f.max_pressure > self.lubrication.max_pressure {
            self.lubrication = Lubrication {
                max_pressure: f.max_pressure,
                film: f.film,
                sliding_speed: f.sliding_speed,
            };
        }
    }
}

/// What of a contact element depends on positions only.
// Roller ends are four of a roller's seven contacts, so most values are `End` anyway;
// boxing it would allocate in every evaluation.
#[allow(clippy::large_enum_variant)]
pub(super) enum Geometry {
    /// A line contact: its slices' and film points' geometry.
    Line(LineGeometry),
    /// A line contact whose bodies are apart: the (negative) bound of its penetration,
    /// [`BearingSystem::penetration_bound`]; no slice computed.
    Apart(f64),
    /// The detected roller end–flange contact, with its distributed overlap when the
    /// flange law is [`super::params::FlangeLaw::Distributed`].
    End(EndGeometry),
}

impl BearingSystem<'_> {
    /// The bodies A and B of `element` at `kin`.
    fn bodies<'a>(
        &self,
        element: &Element,
        kin: &'a BearingKinematics,
    ) -> (&'a Kinematics, &'a Kinematics) {
        let [a, b] = element.bodies(self.layout.rollers);
        (kin.of(a), kin.of(b))
    }

    /// Evaluates one contact: its geometry ([`Self::geometry`]), then its forces
    /// ([`Self::evaluate_at`]).
    pub fn evaluate(&self, element: &Element, kin: &BearingKinematics) -> ElementResult {
        self.evaluate_at(element, kin, &self.geometry(element, kin))
    }

    /// Evaluates every contact, in the order of
    /// [`BearingModel::elements`](super::BearingModel::elements).
    pub fn evaluate_all(&self, kin: &BearingKinematics) -> Vec<ElementResult> {
        let elements = &self.topology.elements;
        self.map(elements.len(), |e| self.evaluate(&elements[e], kin))
    }

    /// The part of `element` that depends on positions only (slice geometry, detected
    /// flange contact), for [`Self::evaluate_at`].
    pub(super) fn geometry(&self, element: &Element, kin: &BearingKinematics) -> Geometry {
        let (a, b) = self.bodies(element, kin);
        let Some(line) = element.line() else {
            let Element::End(i, k) = *element else {
                unreachable!("an element is a line contact or a roller end")
            };
            let end = self.roller_end(k, b);
            return Geometry::End(self.end_geometry(&end, &self.flange(k, a), i, k));
        };
        let start = self.workspace.profiler.stopwatch();
        let bound = self.penetration_bound(line, a, b);
        let geometry = if self.is_apart(bound) {
            Geometry::Apart(bound)
        } else {
            Geometry::Line(self.line_geometry(line, a, b, bound))
        };
        self.workspace
            .profiler
            .spend_time(start, |pr, t| pr.line_contacts += t);
        geometry
    }

    /// [`Self::evaluate`] with the element's `geometry` taken at the same positions.
    pub(super) fn evaluate_at(
        &self,
        element: &Element,
        kin: &BearingKinematics,
        geometry: &Geometry,
    ) -> ElementResult {
        let (a, b) = self.bodies(element, kin);
        match (element.line(), geometry) {
            (Some(line), Geometry::Line(sections)) => self.line_forces(line, a, b, sections),
            (Some(_), Geometry::Apart(bound)) => Self::apart(*bound),
            (None, Geometry::End(g)) => self.flange_element_at(a, b, g),
            _ => unreachable!("geometry of another kind of element"),
        }
    }
}
