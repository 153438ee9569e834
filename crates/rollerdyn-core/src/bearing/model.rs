//! The bearing model: bodies, the contacts between them, and the equations of motion
//! y' = f(t, y) with a Jacobian built from the problem's structure.
//!
//! Contacts ("elements"), for every roller i: the inner race and the outer race (line
//! contacts by slices, eqs. 2, 3, 11), the neighbour i+1 (slices, eq. 11), and its two
//! ends against the two inner-ring and the two outer-ring flanges (the detector of the
//! configuration, Hertz eqs. 5–8). Every force acts at its own contact location; the
//! moment on each body is (P_m − c) × F (model-notes, "Forces and moments"). Beyond the
//! paper: the oil film of the line contacts across their gaps (at 6 Gauss points along the
//! roller, [`crate::tribology::hydrodynamic`]), the squeeze film at the flanges, the drag of
//! the oil–air mixture on every roller ([`crate::tribology::drag`]) and gravity.
//!
//! The contacts of a right-hand side and the columns of a Jacobian are computed apart, on
//! the model's threads if it has any ([`BearingModel::with_threads`]), and summed in a fixed
//! order: the numbers do not depend on the thread count.
//!
//! The Jacobian is built by finite differences per body: perturbing one state of
//! roller i re-evaluates only roller i's eight contacts, and changes only the rows of
//! roller i, its two neighbours and the inner ring (issue 4: "a roller couples only to
//! its neighbours and the rings"). A velocity moves no contact, so its columns reuse the
//! slice geometry and the detected flange contacts of the unperturbed state.

use super::forces::{
    end_flange, film_slice, line_slice, penetration_rate, ContactForces, EllipseKind, LineKind,
    Section, Tribology,
};
use super::params::{BearingParams, Detector};
use super::state::{ring_kinematics, roller_kinematics, Kinematics, Layout, ROLLER_STATES};
use crate::contact::gradient::{self, Unknowns};
use crate::contact::mesh::{MeshDetector, MeshResolution};
use crate::contact::pruning::{self, FlangeBounds};
use crate::contact::{border, deepest, semi_analytical, Contact, Pairing};
use crate::dynamics::integrate::OdeSystem;
use crate::dynamics::rigid::{
    angle_rates, angular_acceleration, axis_from_angles, driven_transverse_acceleration,
};
use crate::error::{Error, Result};
use crate::geometry::end_flange::{Flange, FlangePlacement, RollerEnd};
use crate::geometry::primitives::Vec3;
use crate::geometry::roller::MassProperties;
use crate::numerics::quadrature::{mapped_table, GAUSS_LEGENDRE_4, GAUSS_LEGENDRE_6};
use crate::tribology::drag::roller_drag;
use crate::tribology::film::ThermalCorrection;
use nalgebra::DMatrix;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Instant;

/// A force and a moment about the body's centre.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Wrench {
    /// Force [N].
    pub force: Vec3,
    /// Moment about the body's centre of mass [N m].
    pub moment: Vec3,
}

impl Wrench {
    fn add(&mut self, other: &Wrench) {
        self.force += other.force;
        self.moment += other.moment;
    }
    fn sub(&mut self, other: &Wrench) {
        self.force -= other.force;
        self.moment -= other.moment;
    }
    /// Force `f` at point `p` on a body centred at `c`, plus a pure moment.
    fn at(f: Vec3, p: &Vec3, c: &Vec3, pure: Vec3) -> Self {
        Self {
            force: f,
            moment: (p - c).cross(&f) + pure,
        }
    }
}

/// A body of the bearing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Body {
    /// The inner ring (with its shaft).
    InnerRing,
    /// The fixed outer ring.
    OuterRing,
    /// Roller i.
    Roller(usize),
}

/// A contact of the bearing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Element {
    /// Roller i on the inner race.
    Inner(usize),
    /// Roller i on the outer race.
    Outer(usize),
    /// Roller i against roller i+1 (mod Z).
    Pair(usize),
    /// Roller i's end against a flange: 0 inner ring −x, 1 inner ring +x, 2 outer ring −x,
    /// 3 outer ring +x.
    End(usize, usize),
}

impl Element {
    /// The line-contact kind (0 inner race, 1 outer race, 2 roller–roller; the index of
    /// `BearingModel::kinds`), None for a roller end–flange contact.
    fn line_kind(&self) -> Option<usize> {
        match self {
            Element::Inner(_) => Some(0),
            Element::Outer(_) => Some(1),
            Element::Pair(_) => Some(2),
            Element::End(..) => None,
        }
    }
}

/// The side of flange k along the ring axis: −1 for the −x flanges (k = 0, 2), +1 else.
fn flange_side(k: usize) -> f64 {
    if k % 2 == 1 {
        1.0
    } else {
        -1.0
    }
}

/// Names of the four roller end / flange contacts of a roller.
pub const FLANGE_NAMES: [&str; 4] = ["inner-x", "inner+x", "outer-x", "outer+x"];

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
    /// are apart, an upper bound of it, below 0: see `penetration_bound`).
    pub penetration: f64,
    /// Roller end / flange: the active pairing (index in [`Pairing::ALL`]), if any overlaps.
    pub pairing: Option<usize>,
    /// Contact location (roller end / flange) [m].
    pub location: Vec3,
}

/// Where the time of a right-hand side goes.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Profile {
    /// Roller end–flange detection [s].
    pub detection: f64,
    /// Line contacts (slices: geometry, films, traction) [s].
    pub line_contacts: f64,
    /// Roller end–flange forces (Hertz, film, traction) [s].
    pub flange_forces: f64,
    /// Detections made.
    pub detections: usize,
    /// Gradient method: pairings that converged from neither the warm nor the cold start,
    /// or only off their patch, and took the valid semi-analytical solution instead.
    pub gradient_fallbacks: usize,
}

/// One thread's share of the [`Profile`], on a cache line of its own.
#[derive(Debug, Default)]
#[repr(align(128))]
struct ProfileSlot {
    profile: Mutex<Profile>,
    /// Sections entered so far (one in [`PROFILE_EVERY`] is timed, see [`sampled`]).
    sections: AtomicU32,
}

impl Profile {
    /// The sum of two profiles.
    fn plus(&self, other: &Profile) -> Profile {
        Profile {
            detection: self.detection + other.detection,
            line_contacts: self.line_contacts + other.line_contacts,
            flange_forces: self.flange_forces + other.flange_forces,
            detections: self.detections + other.detections,
            gradient_fallbacks: self.gradient_fallbacks + other.gradient_fallbacks,
        }
    }
}

/// What of a contact element depends on positions only.
enum Geometry {
    /// A line contact: per slice (normal A→B, location P_m, penetration δ), none when no
    /// slice can touch; and the same at the film's quadrature points
    /// ([`BearingModel::film_points`]), none without the film.
    Line {
        slices: Vec<(Vec3, Vec3, f64)>,
        film: Vec<(Vec3, Vec3, f64)>,
    },
    /// A line contact whose bodies are apart: the (negative) bound of its penetration,
    /// [`BearingModel::penetration_bound`]; no slice computed.
    Apart(f64),
    /// The detected roller end–flange contact (None: no valid pairing).
    End(Option<Contact>),
}

/// Points along the roller at which the oil film of a line contact is evaluated
/// (Gauss–Legendre). The film is smooth along the roller (its gap varies linearly with tilt
/// and skew): 6 points integrate it as closely as B1's 20 slices would, at a third of the
/// cost (test `six_gauss_points_integrate_the_film`).
const FILM_POINTS: [(f64, f64); 6] = GAUSS_LEGENDRE_6;

/// Points along the roller at which the drag of the oil–air mixture is evaluated
/// (Gauss–Legendre; [`crate::tribology::drag`]).
const DRAG_POINTS: [(f64, f64); 4] = GAUSS_LEGENDRE_4;

/// One in how many contact evaluations the [`Profile`] times (a power of 2): a clock read
/// costs about 25 ns, and timing every one of B1's 187 sections per right-hand side cost
/// 5 % of it. Over the millions of sections of a run the sample's error is far below a
/// percent.
const PROFILE_EVERY: u32 = 8;

/// Whether the n-th section is timed: the top bits of n's Fibonacci hash are zero.
fn sampled(n: u32) -> bool {
    n.wrapping_mul(0x9E37_79B9) >> (32 - PROFILE_EVERY.trailing_zeros()) == 0
}

/// The time since `start` scaled to all the sections it samples [s] (0 if not timed).
fn elapsed(start: Option<Instant>) -> f64 {
    start.map_or(0.0, |s| {
        s.elapsed().as_secs_f64() * f64::from(PROFILE_EVERY)
    })
}

/// The bearing model (immutable parameters plus the gradient method's warm starts).
pub struct BearingModel {
    /// The parameters.
    pub params: BearingParams,
    /// The state layout.
    pub layout: Layout,
    /// Roller mass properties.
    pub roller_mass: MassProperties,
    tribology: Tribology,
    kinds: [LineKind; 3],
    ellipse: EllipseKind,
    /// Slice centres along the roller axis and their radii (crowning) [m].
    slices: Vec<(f64, f64)>,
    /// The largest |s| of a slice centre or film point and the largest radius there [m].
    slice_reach: (f64, f64),
    /// Where the oil film of a line contact is evaluated: 6-point Gauss–Legendre along the
    /// straight length, (s, radius, weight as a length) [m].
    film_points: Vec<(f64, f64, f64)>,
    /// Where the drag acts along the roller: (s, weight as a length) [m].
    drag_stations: Vec<(f64, f64)>,
    slice_length: f64,
    pitch_radius: f64,
    elements: Vec<Element>,
    /// Elements of each roller, and of the inner ring.
    roller_elements: Vec<Vec<usize>>,
    ring_elements: Vec<usize>,
    /// Axis of the inner ring when its tilt is locked: +x turned by the prescribed
    /// misalignment about z.
    locked_axis: Vec3,
    /// Pruning bounds of the four flanges (intrinsic, so computed once; [`FlangeBounds`]).
    flange_bounds: [FlangeBounds; 4],
    /// The gradient detector's warm starts, one slot per roller end and flange.
    warm_starts: Vec<Mutex<[Option<Unknowns>; 6]>>,
    /// The profile, one slot per thread that evaluates the model ([`ProfileSlot`]).
    profiles: Vec<ProfileSlot>,
    /// The threads that evaluate contacts and Jacobian columns (None: this thread only);
    /// see [`Self::with_threads`].
    pool: Option<Arc<rayon::ThreadPool>>,
}

/// Per-state scale for the Jacobian's difference steps: lengths are measured in metres,
/// angles by the roller radius, velocities over a 1 ms time scale.
const TIME_SCALE: f64 = 1e-3;

impl BearingModel {
    /// Builds the model, refusing parameters that cannot be simulated.
    pub fn new(params: BearingParams) -> Result<Self> {
        params.check()?;
        let layout = Layout {
            rollers: params.roller_count,
            tilt_free: params.inner_ring_tilt_free,
        };
        let roller_mass = params.roller.mass_properties(params.roller_density)?;
        let r = params.roller.radius;
        let straight = params.roller.straight_length();
        let slice_length = straight / params.slices as f64;
        let slices: Vec<(f64, f64)> = (0..params.slices)
            .map(|j| {
                let s = -0.5 * straight + (j as f64 + 0.5) * slice_length;
                (s, r - params.crown_drop(s, straight))
            })
            .collect();
        let film_points: Vec<(f64, f64, f64)> = mapped_table(&FILM_POINTS, 0.5 * straight)
            .into_iter()
            .map(|(s, w)| (s, r - params.crown_drop(s, straight), w))
            .collect();
        let drag_stations = mapped_table(&DRAG_POINTS, 0.5 * params.roller.length);
        let per_length = roller_mass.mass / straight;
        let line = |k: usize, r_other: f64, surface: &super::params::SurfacePair| LineKind {
            law: params.line_laws[k],
            e_prime: params.e_prime[k],
            r_eff: 1.0 / (1.0 / r + 1.0 / r_other),
            roughness: surface.roughness,
            sharing: surface.sharing,
            counter_rotating: k == 2,
            rolling_resistance: k < 2,
            mass_per_length: if k == 2 { 0.5 * per_length } else { per_length },
        };
        let kinds = [
            line(0, params.inner_raceway_radius, &params.raceway),
            line(1, -params.outer_raceway_radius, &params.raceway),
            line(2, r, &params.roller_roller),
        ];
        let ellipse = EllipseKind {
            e_prime: params.e_prime[0].min(params.e_prime[1]),
            roughness: params.flange_surface.roughness,
            sharing: params.flange_surface.sharing,
            mass: roller_mass.mass,
        };
        let tribology = Tribology {
            traction: params.traction.clone(),
            boundary: params.boundary,
            eta0: params.eta0,
            alpha_star: params.alpha_star,
            thermal: ThermalCorrection::new(params.viscosity_slope, params.thermal_conductivity),
            moes: Default::default(),
            hysteresis_coefficient: params.hysteresis_coefficient,
            damping_ratio: params.damping_ratio,
            friction: params.friction,
            film: params.race_film,
        };
        let z = params.roller_count;
        let mut elements = Vec::with_capacity(7 * z);
        for i in 0..z {
            elements.extend([Element::Inner(i), Element::Outer(i), Element::Pair(i)]);
            elements.extend((0..4).map(|k| Element::End(i, k)));
        }
        let mut roller_elements = vec![Vec::new(); z];
        let mut ring_elements = Vec::new();
        for (e, element) in elements.iter().enumerate() {
            for body in Self::bodies_of(element, z) {
                match body {
                    Body::Roller(i) => roller_elements[i].push(e),
                    Body::InnerRing => ring_elements.push(e),
                    Body::OuterRing => {}
                }
            }
        }
        let pitch_radius = 0.5 * (params.inner_raceway_radius + params.outer_raceway_radius);
        let at_rest = Kinematics::fixed();
        let flange_bounds =
            std::array::from_fn(|k| FlangeBounds::new(&flange_of(&params, k, &at_rest)));
        Ok(Self {
            layout,
            roller_mass,
            tribology,
            kinds,
            ellipse,
            // Over the slices and the film points, so that the bound holds for both.
            slice_reach: (slices.iter().copied())
                .chain(film_points.iter().map(|&(s, r, _)| (s, r)))
                .fold((0.0, 0.0), |(s, r), (sj, rj)| {
                    (f64::max(s, f64::abs(sj)), f64::max(r, rj))
                }),
            slices,
            film_points,
            drag_stations,
            slice_length,
            pitch_radius,
            elements,
            roller_elements,
            ring_elements,
            flange_bounds,
            locked_axis: axis_from_angles(0.0, params.inner_ring_misalignment),
            warm_starts: (0..4 * z).map(|_| Mutex::new([None; 6])).collect(),
            profiles: vec![ProfileSlot::default()],
            pool: None,
            params,
        })
    }

    /// The model evaluating its contacts and Jacobian columns on `threads` threads (a
    /// numerical setting: the results do not depend on it, bit for bit, since every
    /// contact and column is computed alone and summed in a fixed order). The gradient
    /// detector keeps one thread: its warm starts carry over from one evaluation to the
    /// next, in an order that threads would change (the race hazard of paper sect. 5.4).
    pub fn with_threads(mut self, threads: usize) -> Result<Self> {
        if threads == 0 {
            return Err(Error::invalid("threads", threads, ">= 1"));
        }
        self.profiles = (0..=threads).map(|_| ProfileSlot::default()).collect();
        self.pool = if threads > 1 && self.params.detector != Detector::Gradient {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .map_err(|e| Error::invalid("threads", threads, e.to_string()))?;
            Some(Arc::new(pool))
        } else {
            None
        };
        Ok(self)
    }

    /// Threads that evaluate the model (1: this thread only).
    pub fn threads(&self) -> usize {
        self.pool.as_ref().map_or(1, |p| p.current_num_threads())
    }

    /// Bodies (A, B) of an element.
    fn bodies_of(element: &Element, z: usize) -> [Body; 2] {
        match *element {
            Element::Inner(i) => [Body::InnerRing, Body::Roller(i)],
            Element::Outer(i) => [Body::OuterRing, Body::Roller(i)],
            Element::Pair(i) => [Body::Roller(i), Body::Roller((i + 1) % z)],
            Element::End(i, k) if k < 2 => [Body::InnerRing, Body::Roller(i)],
            Element::End(i, _) => [Body::OuterRing, Body::Roller(i)],
        }
    }

    /// All contacts, in the order of [`Self::evaluate_all`].
    pub fn elements(&self) -> &[Element] {
        &self.elements
    }

    /// Time spent so far, by kind of work.
    pub fn profile(&self) -> Profile {
        self.profiles.iter().fold(Profile::default(), |sum, slot| {
            sum.plus(&slot.profile.lock().unwrap_or_else(PoisonError::into_inner))
        })
    }

    /// Pitch radius [m].
    pub fn pitch_radius(&self) -> f64 {
        self.pitch_radius
    }

    /// The consistent start: rollers on the pitch circle, roller 0 at the bottom (−y, ψ = π, the
    /// centre of the load zone), axes along x, at rest; the inner ring centred. Nothing
    /// overlaps (checked).
    pub fn initial_state(&self) -> Result<Vec<f64>> {
        let mut y = vec![0.0; self.layout.len()];
        let z = self.params.roller_count;
        for i in 0..z {
            let psi = std::f64::consts::PI + 2.0 * std::f64::consts::PI * i as f64 / z as f64;
            let s = self.layout.roller(i);
            y[s + 1] = self.pitch_radius * psi.cos();
            y[s + 2] = self.pitch_radius * psi.sin();
        }
        let kin = self.kinematics(0.0, &y);
        for (e, element) in self.elements.iter().enumerate() {
            let r = self.evaluate(element, &kin, e);
            // NaN counts as overlap: a start whose forces are not defined is refused. (The
            // oil films act across gaps, so a force alone is no overlap.)
            if r.penetration > 0.0 || r.penetration.is_nan() || r.normal.is_nan() {
                return Err(Error::invalid(
                    format!("{element:?}"),
                    format!("penetration {:.3e} m at the start", r.penetration),
                    "bodies must not overlap at the start (rollers on the pitch circle, rings centred)",
                ));
            }
        }
        Ok(y)
    }

    /// Absolute tolerances per state for a length tolerance `atol` [m]: lengths in m,
    /// angles by the roller radius, velocities as the speed that moves a body by `atol`
    /// within `time_scale` [s] (config `solver.atol_time_scale`).
    pub fn absolute_tolerances(&self, atol: f64, time_scale: f64) -> Vec<f64> {
        let r = self.params.roller.radius;
        (0..self.layout.len())
            .map(|k| atol * self.scale_over(k, time_scale) / r)
            .collect()
    }

    /// Typical magnitude of state k relative to a length of one roller radius, with
    /// velocities over [`TIME_SCALE`] (the finite-difference steps of the Jacobian).
    fn scale(&self, k: usize) -> f64 {
        self.scale_over(k, TIME_SCALE)
    }

    /// Whether state k is a velocity or an angular velocity (it moves no contact).
    fn is_velocity(&self, k: usize) -> bool {
        match self.layout.body_of(k) {
            None => matches!(k, 3..=5) || k >= 8,
            Some(i) => k - self.layout.roller(i) >= 5,
        }
    }

    /// [`Self::scale`] with velocities over `time_scale` [s].
    fn scale_over(&self, k: usize, time_scale: f64) -> f64 {
        let r = self.params.roller.radius;
        let local = match self.layout.body_of(k) {
            None => k,
            Some(i) => k - self.layout.roller(i),
        };
        let ring = self.layout.body_of(k).is_none();
        match (ring, local) {
            (_, 0..=2) => r,
            (true, 3..=5) | (false, 5..=7) => r / time_scale,
            (true, 6..=7) | (false, 3..=4) => 1.0,
            _ => 1.0 / time_scale,
        }
    }

    /// Kinematics of all bodies: inner ring, then the rollers.
    pub fn kinematics(&self, t: f64, y: &[f64]) -> (Kinematics, Vec<Kinematics>) {
        let spin = self.params.inner_ring_speed.at(t).0;
        let ring = ring_kinematics(&self.layout, y, spin, &self.locked_axis);
        let rollers = (0..self.layout.rollers)
            .map(|i| roller_kinematics(&self.layout, y, i))
            .collect();
        (ring, rollers)
    }

    fn body<'a>(
        &self,
        b: Body,
        kin: &'a (Kinematics, Vec<Kinematics>),
        fixed: &'a Kinematics,
    ) -> &'a Kinematics {
        match b {
            Body::InnerRing => &kin.0,
            Body::OuterRing => fixed,
            Body::Roller(i) => &kin.1[i],
        }
    }

    /// The bodies A and B of `element` at `kin` (`fixed`: the outer ring).
    fn bodies<'a>(
        &self,
        element: &Element,
        kin: &'a (Kinematics, Vec<Kinematics>),
        fixed: &'a Kinematics,
    ) -> (&'a Kinematics, &'a Kinematics) {
        let [a, b] = Self::bodies_of(element, self.layout.rollers);
        (self.body(a, kin, fixed), self.body(b, kin, fixed))
    }

    /// The end of `roller` that faces flange k.
    fn roller_end(&self, k: usize, roller: &Kinematics) -> RollerEnd {
        RollerEnd::new(
            &self.params.roller,
            roller.center,
            flange_side(k) * roller.axis,
        )
    }

    /// Evaluates one contact.
    pub fn evaluate(
        &self,
        element: &Element,
        kin: &(Kinematics, Vec<Kinematics>),
        index: usize,
    ) -> ElementResult {
        let fixed = Kinematics::fixed();
        let (a, b) = self.bodies(element, kin, &fixed);
        match (*element, element.line_kind()) {
            (_, Some(kind)) => self.line_element(kind, a, b),
            (Element::End(_, k), None) => self.flange_element(k, a, b, index),
            _ => unreachable!("an element is a line contact or a roller end"),
        }
    }

    /// The part of `element` that depends on positions only (slice geometry, detected
    /// flange contact), for [`Self::evaluate_at`].
    fn geometry(
        &self,
        element: &Element,
        kin: &(Kinematics, Vec<Kinematics>),
        index: usize,
    ) -> Geometry {
        let fixed = Kinematics::fixed();
        let (a, b) = self.bodies(element, kin, &fixed);
        let Some(kind) = element.line_kind() else {
            let Element::End(_, k) = *element else {
                unreachable!("an element is a line contact or a roller end")
            };
            let end = self.roller_end(k, b);
            return Geometry::End(self.end_contact(&end, &self.flange(k, a), index));
        };
        let start = self.stopwatch();
        let bound = self.penetration_bound(kind, a, b);
        let geometry = if self.is_apart(bound) {
            Geometry::Apart(bound)
        } else {
            let (slices, film) = self.line_geometry(kind, a, b, bound);
            Geometry::Line { slices, film }
        };
        self.spend_time(start, |pr, t| pr.line_contacts += t);
        geometry
    }

    /// [`Self::evaluate`] with the element's `geometry` taken at the same positions.
    fn evaluate_at(
        &self,
        element: &Element,
        kin: &(Kinematics, Vec<Kinematics>),
        geometry: &Geometry,
    ) -> ElementResult {
        let fixed = Kinematics::fixed();
        let (a, b) = self.bodies(element, kin, &fixed);
        match (element.line_kind(), geometry) {
            (Some(kind), Geometry::Line { slices, film }) => {
                self.line_forces(kind, a, b, slices, film)
            }
            (Some(_), Geometry::Apart(bound)) => Self::apart(*bound),
            (None, Geometry::End(c)) => self.flange_element_at(a, b, c.as_ref()),
            _ => unreachable!("geometry of another kind of element"),
        }
    }

    /// The slices' and the film points' geometry of a line contact whose penetration is at
    /// most `bound` (no slice computed where it is negative: none touches).
    #[allow(clippy::type_complexity)]
    fn line_geometry(
        &self,
        kind: usize,
        a: &Kinematics,
        b: &Kinematics,
        bound: f64,
    ) -> (Vec<(Vec3, Vec3, f64)>, Vec<(Vec3, Vec3, f64)>) {
        let slices = if bound > 0.0 {
            let at = |&(s, radius): &(f64, f64)| self.slice_geometry(kind, a, b, s, radius);
            self.slices.iter().map(at).collect()
        } else {
            Vec::new()
        };
        let film = if self.tribology.film.enabled {
            let at = |&(s, radius, _): &(f64, f64, f64)| self.slice_geometry(kind, a, b, s, radius);
            self.film_points.iter().map(at).collect()
        } else {
            Vec::new()
        };
        (slices, film)
    }

    /// Geometry (eqs. 2, 3) of the section at `s` along roller `b` (radius `radius`, for
    /// two rollers both) against body `a`: (normal A→B, location P_m, penetration δ).
    fn slice_geometry(
        &self,
        kind: usize,
        a: &Kinematics,
        b: &Kinematics,
        s: f64,
        radius: f64,
    ) -> (Vec3, Vec3, f64) {
        let cb = b.center + s * b.axis;
        match kind {
            0 | 1 => {
                let d = cb - a.center;
                let perp = d - d.dot(&a.axis) * a.axis;
                let dist = perp.norm();
                let out = perp / dist;
                if kind == 0 {
                    let delta = radius + self.params.inner_raceway_radius - dist;
                    (out, cb - out * (radius - 0.5 * delta), delta)
                } else {
                    let delta = dist + radius - self.params.outer_raceway_radius;
                    (-out, cb + out * (radius - 0.5 * delta), delta)
                }
            }
            _ => {
                let ca = a.center + s * a.axis;
                let mean = (a.axis + b.axis).normalize();
                let d = cb - ca;
                let perp = d - d.dot(&mean) * mean;
                let dist = perp.norm();
                let n = perp / dist;
                let delta = 2.0 * radius - dist;
                (n, ca + n * (radius - 0.5 * delta), delta)
            }
        }
    }

    fn line_element(&self, kind: usize, a: &Kinematics, b: &Kinematics) -> ElementResult {
        let bound = self.penetration_bound(kind, a, b);
        if self.is_apart(bound) {
            return Self::apart(bound);
        }
        let (slices, film) = self.line_geometry(kind, a, b, bound);
        self.line_forces(kind, a, b, &slices, &film)
    }

    /// Whether a line contact whose penetration is at most `bound` carries nothing: no
    /// slice touches and every gap is beyond the film's reach.
    fn is_apart(&self, bound: f64) -> bool {
        bound < -self.tribology.film.reach()
    }

    /// The result of a line contact whose bodies are apart: no force, and for the
    /// penetration the (negative) `bound`, not the largest slice penetration.
    fn apart(bound: f64) -> ElementResult {
        ElementResult {
            penetration: bound,
            ..Default::default()
        }
    }

    /// An upper bound of the penetration of every slice of a line contact of `kind` (eqs. 2,
    /// 3 without their slices): the distance of slice s is |P + s·Q|, P the part of the
    /// centres' offset across the reference axis and Q that of the roller axis (of the
    /// axes' difference for two rollers), whose least and greatest values over the slice
    /// centres |s| ≤ s_max are those of a point's distance to a segment; the slice radius
    /// is at most the largest one. Negative: no slice touches, and the slices need not be
    /// computed (on B1 many roller–roller pairs and the inner race outside the load zone).
    fn penetration_bound(&self, kind: usize, a: &Kinematics, b: &Kinematics) -> f64 {
        let (s_max, r_max) = self.slice_reach;
        let across = |v: Vec3, axis: &Vec3| v - v.dot(axis) * axis;
        let (axis, sway) = match kind {
            0 | 1 => (a.axis, b.axis),
            _ => ((a.axis + b.axis).normalize(), b.axis - a.axis),
        };
        let (least, greatest) = distance_range(
            &across(b.center - a.center, &axis),
            &across(sway, &axis),
            s_max,
        );
        match kind {
            0 => r_max + self.params.inner_raceway_radius - least,
            1 => greatest + r_max - self.params.outer_raceway_radius,
            _ => 2.0 * r_max - least,
        }
    }

    /// The forces of a line contact of `kind` from its slices' and film points' geometry
    /// (normal, location, penetration; [`Self::line_geometry`]): the paper's laws per
    /// slice in contact, the oil film at its quadrature points. Computed along the way by
    /// [`Self::line_element`], or given (from the same positions) for Jacobian columns of
    /// velocities, which leave it unchanged. The penetration is the slices' largest, or
    /// the film points' where no slice was computed.
    fn line_forces(
        &self,
        kind: usize,
        a: &Kinematics,
        b: &Kinematics,
        slices: &[(Vec3, Vec3, f64)],
        film: &[(Vec3, Vec3, f64)],
    ) -> ElementResult {
        let start = self.stopwatch();
        let mut out = ElementResult {
            penetration: f64::NEG_INFINITY,
            ..Default::default()
        };
        for (n, p, delta) in slices {
            out.penetration = out.penetration.max(*delta);
            if *delta > 0.0 {
                self.section_into(&mut out, kind, a, b, (n, p, *delta), None);
            }
        }
        let roughness = self.kinds[kind].roughness;
        for ((n, p, delta), &(_, _, weight)) in film.iter().zip(&self.film_points) {
            if slices.is_empty() {
                out.penetration = out.penetration.max(*delta);
            }
            if self.tribology.film.acts(*delta, roughness) {
                self.section_into(&mut out, kind, a, b, (n, p, *delta), Some(weight));
            }
        }
        self.spend_time(start, |pr, t| pr.line_contacts += t);
        out
    }

    /// Adds the forces of one section (normal `n`, location `p`, penetration `delta`) of a
    /// line contact of `kind` to `out`: the paper's slice laws ([`line_slice`]) for a slice,
    /// or the oil film ([`film_slice`]) over the length `film` of a film point.
    fn section_into(
        &self,
        out: &mut ElementResult,
        kind: usize,
        a: &Kinematics,
        b: &Kinematics,
        (n, p, delta): (&Vec3, &Vec3, f64),
        film: Option<f64>,
    ) {
        let rolling = n.cross(&b.axis).normalize();
        let frame = if kind == 2 {
            0.5 * (a.frame_velocity(p) + b.frame_velocity(p))
        } else {
            b.frame_velocity(p)
        };
        let (tri, line) = (&self.tribology, &self.kinds[kind]);
        let section = Section {
            a,
            b,
            normal: *n,
            location: *p,
            penetration: delta,
            length: film.unwrap_or(self.slice_length),
            rolling,
            frame,
        };
        let f = match film {
            None => line_slice(tri, line, &section),
            Some(_) => film_slice(tri, line, &section),
        };
        self.accumulate(out, &f, n, p, a, b);
    }

    fn accumulate(
        &self,
        out: &mut ElementResult,
        f: &ContactForces,
        n: &Vec3,
        p: &Vec3,
        a: &Kinematics,
        b: &Kinematics,
    ) {
        let on_b = f.force_on_b(n);
        out.on_b.add(&Wrench::at(on_b, p, &b.center, f.moment_b));
        out.on_a.add(&Wrench::at(-on_b, p, &a.center, f.moment_a));
        out.normal += f.normal;
        out.tangential += f.tangential;
    }

    /// Starts timing one in [`PROFILE_EVERY`] sections, chosen by the top bits of the
    /// section count's Fibonacci hash (Knuth, TAOCP vol. 3, 6.4): spread evenly but not
    /// periodically, so that a fixed order of contacts cannot time the same ones always.
    fn stopwatch(&self) -> Option<Instant> {
        let n = self
            .slot()
            .sections
            .fetch_add(1, Ordering::Relaxed)
            .wrapping_add(1);
        sampled(n).then(Instant::now)
    }

    /// Adds the time of a section begun by [`Self::stopwatch`] (nothing to do when it was
    /// not timed).
    fn spend_time(&self, start: Option<Instant>, f: impl FnOnce(&mut Profile, f64)) {
        if start.is_some() {
            self.spend(|p| f(p, elapsed(start)));
        }
    }

    fn spend(&self, f: impl FnOnce(&mut Profile)) {
        f(&mut self
            .slot()
            .profile
            .lock()
            .unwrap_or_else(PoisonError::into_inner));
    }

    /// This thread's profile slot: the pool's threads have one each, other threads share
    /// the first (so that the threads never contend for one lock or cache line).
    fn slot(&self) -> &ProfileSlot {
        let index = rayon::current_thread_index().map_or(0, |i| i + 1);
        &self.profiles[index % self.profiles.len()]
    }

    /// The flange k of a ring body at its current pose.
    fn flange(&self, k: usize, ring: &Kinematics) -> Flange {
        flange_of(&self.params, k, ring)
    }

    /// The composite contact of a roller end against a flange by the configured detector.
    fn detect(&self, end: &RollerEnd, flange: &Flange, index: usize) -> Option<Contact> {
        let start = self.stopwatch();
        let found = match self.params.detector {
            Detector::SemiAnalytical if self.params.pruning => pruning::composite_within_bounds(
                end,
                flange,
                &self.flange_bounds[index_to_flange(index)],
                self.params.squeeze_film.reach(),
            ),
            Detector::SemiAnalytical => semi_analytical::composite(end, flange),
            Detector::Gradient => {
                let mut memory = self.warm_starts[index_to_slot(index)]
                    .lock()
                    .unwrap_or_else(PoisonError::into_inner);
                let mut outcomes = gradient::detect(end, flange, &memory);
                // A pairing whose warm start failed is tried once more from the cold start.
                let failed: [Option<Unknowns>; 6] = std::array::from_fn(|k| {
                    let o = &outcomes[k];
                    (memory[k].is_some() && !(o.converged && o.opposite_normals))
                        .then_some(None)
                        .flatten()
                });
                if outcomes
                    .iter()
                    .zip(memory.iter())
                    .any(|(o, m)| m.is_some() && !(o.converged && o.opposite_normals))
                {
                    let cold = gradient::detect(end, flange, &failed);
                    for k in 0..6 {
                        let o = &outcomes[k];
                        if memory[k].is_some() && !(o.converged && o.opposite_normals) {
                            outcomes[k] = cold[k];
                        }
                    }
                }
                let mut contacts = Vec::with_capacity(6);
                // Only converged solutions with opposite outward normals count and become
                // the next warm start; after a failure (no convergence, or a wrong stationary
                // point, paper fig. 2) the last good solution stays the warm start.
                // In runs, Newton also lands on stationary points off the patch where the
                // true contact is on it (torus–torus has several), and the lost contact
                // lets the roller pass through the flange. So a pairing that converged from
                // neither start, or only off its patch, takes the semi-analytical solution
                // of that pairing when that one counts; each is counted in
                // `Profile::gradient_fallbacks` and reported with the run.
                let mut semi: Option<[Contact; 6]> = None;
                for (k, o) in outcomes.iter().enumerate() {
                    let converged = o.converged && o.opposite_normals;
                    if converged {
                        memory[k] = Some(o.unknowns);
                        if o.contact.valid {
                            contacts.push(o.contact);
                            continue;
                        }
                    }
                    let all = semi.get_or_insert_with(|| semi_analytical::detect(end, flange));
                    if all[k].valid {
                        contacts.push(all[k]);
                        self.spend(|p| p.gradient_fallbacks += 1);
                    }
                }
                deepest(&contacts)
            }
            Detector::Mesh => {
                let (around, along) = self.params.mesh_resolution;
                let mesh = MeshDetector::new(end, flange, MeshResolution { around, along });
                deepest(&mesh.detect())
            }
        };
        self.spend(|p| {
            p.detection += elapsed(start);
            p.detections += 1;
        });
        found
    }

    /// The detected roller end–flange contact with its curvature blended across patch
    /// borders ([`border::blend`]), so that the force is continuous in the pose.
    fn end_contact(&self, end: &RollerEnd, flange: &Flange, index: usize) -> Option<Contact> {
        self.detect(end, flange, index)
            .map(|c| border::blend(&c, end, flange, &self.params.border_bands))
    }

    fn flange_element(
        &self,
        k: usize,
        ring: &Kinematics,
        roller: &Kinematics,
        index: usize,
    ) -> ElementResult {
        let end = self.roller_end(k, roller);
        let contact = self.end_contact(&end, &self.flange(k, ring), index);
        self.flange_element_at(ring, roller, contact.as_ref())
    }

    /// [`Self::flange_element`] with the contact given (`contact`, detected at the same
    /// positions): for Jacobian columns of velocities, which leave it unchanged.
    fn flange_element_at(
        &self,
        ring: &Kinematics,
        roller: &Kinematics,
        contact: Option<&Contact>,
    ) -> ElementResult {
        let mut out = ElementResult {
            penetration: f64::NEG_INFINITY,
            ..Default::default()
        };
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
        let start = self.stopwatch();
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
            self.accumulate(&mut out, &film, &c.normal, &p, ring, roller);
            self.spend_time(start, |pr, t| pr.flange_forces += t);
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
        self.accumulate(&mut out, &f, &c.normal, &p, ring, roller);
        self.spend_time(start, |pr, t| pr.flange_forces += t);
        out
    }

    /// Elastic energy stored in all contacts [J]: ∫F dδ of eq. 11 per slice,
    /// (l/k₁)·δ^(1/k₂+1)/(1/k₂+1), and 2/5·F·δ for a Hertz contact (F ∝ δ^1.5).
    pub fn contact_energy(&self, kin: &(Kinematics, Vec<Kinematics>)) -> f64 {
        let mut energy = 0.0;
        for (index, element) in self.elements.iter().enumerate() {
            match (self.geometry(element, kin, index), element.line_kind()) {
                (Geometry::End(Some(c)), _) if c.penetration > 0.0 => {
                    let hertz = crate::tribology::hertz::EllipticalContact::new(
                        c.rx,
                        c.ry,
                        self.ellipse.e_prime,
                        crate::tribology::hertz::EllipticalMethod::BreweHamrock,
                    );
                    energy += 0.4 * hertz.force(c.penetration) * c.penetration;
                }
                (Geometry::Line { slices, .. }, Some(kind)) => {
                    let law = &self.kinds[kind].law;
                    let e = 1.0 / law.k2 + 1.0;
                    for (_, _, delta) in slices {
                        if delta > 0.0 {
                            energy += self.slice_length / law.k1 * delta.powf(e) / e;
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
    /// external load at time t (conserved for constant loads without friction and damping).
    pub fn energy(&self, t: f64, y: &[f64]) -> f64 {
        let kin = self.kinematics(t, y);
        let m = &self.roller_mass;
        let g = self.params.gravity;
        let mut energy = self.contact_energy(&kin);
        for k in &kin.1 {
            let h = crate::dynamics::rigid::angular_momentum(
                &k.axis,
                &k.omega,
                m.axial_inertia,
                m.transverse_inertia,
            );
            energy += 0.5 * m.mass * k.velocity.norm_squared() + 0.5 * k.omega.dot(&h)
                - m.mass * g.dot(&k.center);
        }
        let ring = &kin.0;
        let mr = self.params.inner_ring_mass;
        energy += 0.5 * mr * ring.velocity.norm_squared() - mr * g.dot(&ring.center);
        if self.layout.tilt_free {
            let transverse = ring.omega - ring.omega.dot(&ring.axis) * ring.axis;
            energy += 0.5 * self.params.inner_ring_transverse_inertia * transverse.norm_squared();
        }
        energy - self.external_load(t).dot(&ring.center)
    }

    /// Evaluates every contact.
    pub fn evaluate_all(&self, kin: &(Kinematics, Vec<Kinematics>)) -> Vec<ElementResult> {
        self.map(self.elements.len(), |e| {
            self.evaluate(&self.elements[e], kin, e)
        })
    }

    /// Sums contact wrenches per body: (inner ring, outer ring, rollers).
    pub fn loads(&self, results: &[ElementResult]) -> (Wrench, Wrench, Vec<Wrench>) {
        let mut ring = Wrench::default();
        let mut outer = Wrench::default();
        let mut rollers = vec![Wrench::default(); self.layout.rollers];
        for (element, r) in self.elements.iter().zip(results) {
            let [a, b] = Self::bodies_of(element, self.layout.rollers);
            for (body, w) in [(a, &r.on_a), (b, &r.on_b)] {
                match body {
                    Body::InnerRing => ring.add(w),
                    Body::OuterRing => outer.add(w),
                    Body::Roller(i) => rollers[i].add(w),
                }
            }
        }
        (ring, outer, rollers)
    }

    /// Rates of roller i's states.
    fn roller_rates(&self, kin: &Kinematics, y: &[f64], w: &Wrench, dy: &mut [f64]) {
        let m = &self.roller_mass;
        let (drag, drag_moment) = roller_drag(
            &self.params.mixture,
            self.params.roller.radius,
            self.params.roller.length,
            &self.drag_stations,
            &kin.axis,
            &kin.velocity,
            &kin.omega,
        );
        let acc = (w.force + drag) / m.mass + self.params.gravity;
        let alpha = angular_acceleration(
            &kin.axis,
            &kin.omega,
            &(w.moment + drag_moment),
            m.axial_inertia,
            m.transverse_inertia,
        );
        let (dty, dtz) = angle_rates(y[3], y[4], &kin.omega);
        dy[..3].copy_from_slice(kin.velocity.as_slice());
        dy[3] = dty;
        dy[4] = dtz;
        dy[5..8].copy_from_slice(acc.as_slice());
        dy[8..11].copy_from_slice(alpha.as_slice());
    }

    /// The external load on the inner ring at time t: axial +x, radial −y.
    pub fn external_load(&self, t: f64) -> Vec3 {
        Vec3::new(
            self.params.axial_load.at(t).0,
            -self.params.radial_load.at(t).0,
            0.0,
        )
    }

    /// Rates of the inner ring's states.
    fn ring_rates(&self, t: f64, kin: &Kinematics, y: &[f64], w: &Wrench, dy: &mut [f64]) {
        let p = &self.params;
        let acc = (w.force + self.external_load(t)) / p.inner_ring_mass + p.gravity;
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
    fn rates(
        &self,
        t: f64,
        y: &[f64],
        kin: &(Kinematics, Vec<Kinematics>),
        loads: &(Wrench, Wrench, Vec<Wrench>),
        dy: &mut [f64],
    ) {
        let n = self.layout.ring_states();
        self.ring_rates(t, &kin.0, &y[..n], &loads.0, &mut dy[..n]);
        for i in 0..self.layout.rollers {
            let s = self.layout.roller(i);
            let r = s..s + ROLLER_STATES;
            self.roller_rates(&kin.1[i], &y[r.clone()], &loads.2[i], &mut dy[r]);
        }
    }

    /// `f(0..n)` in order, on the model's threads if it has any.
    fn map<T: Send>(&self, n: usize, f: impl Fn(usize) -> T + Sync + Send) -> Vec<T> {
        match &self.pool {
            Some(pool) => pool.install(|| (0..n).into_par_iter().map(&f).collect()),
            None => (0..n).map(f).collect(),
        }
    }

    /// The Jacobian by per-body finite differences (see the module doc), its columns
    /// computed apart (on the model's threads) and written in order.
    fn structured_jacobian(&self, t: f64, y: &[f64], jac: &mut DMatrix<f64>) {
        let kin = self.kinematics(t, y);
        let elements = &self.elements;
        let geometries = self.map(elements.len(), |e| self.geometry(&elements[e], &kin, e));
        let results = self.map(elements.len(), |e| {
            self.evaluate_at(&elements[e], &kin, &geometries[e])
        });
        let base = Linearisation {
            t,
            y,
            kin: &kin,
            geometries: &geometries,
            loads: self.loads(&results),
            results: &results,
        };
        let mut f0 = vec![0.0; self.layout.len()];
        self.rates(t, y, &kin, &base.loads, &mut f0);
        let columns = self.map(y.len(), |k| self.jacobian_column(&base, &f0, k));
        jac.fill(0.0);
        for (k, column) in columns.iter().enumerate() {
            for &(row, value) in column {
                jac[(row, k)] = value;
            }
        }
    }

    /// Column k of the Jacobian as (row, value) pairs: state k perturbed, only its body's
    /// contacts evaluated again, only the rows of the bodies they touch.
    fn jacobian_column(&self, base: &Linearisation, f0: &[f64], k: usize) -> Vec<(usize, f64)> {
        let (t, y, kin) = (base.t, base.y, base.kin);
        let mut yp = y.to_vec();
        let h = 1.5e-8 * y[k].abs().max(self.scale(k));
        yp[k] = y[k] + h;
        let h = yp[k] - y[k];
        let body = self.layout.body_of(k);
        let mut kin_p = kin.clone();
        let elements = match body {
            None => {
                kin_p.0 = ring_kinematics(
                    &self.layout,
                    &yp,
                    self.params.inner_ring_speed.at(t).0,
                    &self.locked_axis,
                );
                &self.ring_elements
            }
            Some(i) => {
                kin_p.1[i] = roller_kinematics(&self.layout, &yp, i);
                &self.roller_elements[i]
            }
        };
        let z = self.layout.rollers;
        let mut loads_p = base.loads.clone();
        let mut touched_ring = body.is_none();
        let mut touched = vec![false; z];
        if let Some(i) = body {
            touched[i] = true;
        }
        let moves = !self.is_velocity(k);
        for &e in elements {
            let element = &self.elements[e];
            let new = if moves {
                self.evaluate(element, &kin_p, e)
            } else {
                self.evaluate_at(element, &kin_p, &base.geometries[e])
            };
            let old = &base.results[e];
            let [body_a, body_b] = Self::bodies_of(element, z);
            for (bd, wn, wo) in [
                (body_a, &new.on_a, &old.on_a),
                (body_b, &new.on_b, &old.on_b),
            ] {
                match bd {
                    Body::InnerRing => {
                        loads_p.0.sub(wo);
                        loads_p.0.add(wn);
                        touched_ring = true;
                    }
                    Body::Roller(r) => {
                        loads_p.2[r].sub(wo);
                        loads_p.2[r].add(wn);
                        touched[r] = true;
                    }
                    Body::OuterRing => {}
                }
            }
        }
        let mut column = Vec::new();
        let mut fp = vec![0.0; f0.len()];
        if touched_ring {
            let m = self.layout.ring_states();
            self.ring_rates(t, &kin_p.0, &yp[..m], &loads_p.0, &mut fp[..m]);
            column.extend((0..m).map(|row| (row, (fp[row] - f0[row]) / h)));
        }
        for (r, _) in touched.iter().enumerate().filter(|(_, t)| **t) {
            let s = self.layout.roller(r);
            let range = s..s + ROLLER_STATES;
            self.roller_rates(
                &kin_p.1[r],
                &yp[range.clone()],
                &loads_p.2[r],
                &mut fp[range.clone()],
            );
            column.extend(range.map(|row| (row, (fp[row] - f0[row]) / h)));
        }
        column
    }
}

/// What every column of a Jacobian shares: the state, its kinematics, the contacts'
/// geometry and results, and the summed loads.
struct Linearisation<'a> {
    t: f64,
    y: &'a [f64],
    kin: &'a (Kinematics, Vec<Kinematics>),
    geometries: &'a [Geometry],
    results: &'a [ElementResult],
    loads: (Wrench, Wrench, Vec<Wrench>),
}

/// The least and the greatest of |p + s·q| over |s| ≤ s_max: the distance of the origin
/// to the segment p ± s_max·q (its nearest point, or an end), and that of its farther end
/// (|p + s·q| is convex in s).
fn distance_range(p: &Vec3, q: &Vec3, s_max: f64) -> (f64, f64) {
    let qq = q.norm_squared();
    let nearest = if qq > 0.0 {
        (-p.dot(q) / qq).clamp(-s_max, s_max)
    } else {
        0.0
    };
    let least = (p + nearest * q).norm();
    let greatest = (p - s_max * q).norm().max((p + s_max * q).norm());
    (least, greatest)
}

/// The flange k (0, 1: inner ring at −x, +x; 2, 3: outer ring) of a ring body at its pose.
fn flange_of(params: &BearingParams, k: usize, ring: &Kinematics) -> Flange {
    let inner = k < 2;
    let side = flange_side(k);
    let (shape, play, radius) = if inner {
        (
            &params.inner_flange,
            params.inner_axial_play,
            params.inner_raceway_radius,
        )
    } else {
        (
            &params.outer_flange,
            params.outer_axial_play,
            params.outer_raceway_radius,
        )
    };
    Flange::new(
        shape,
        &FlangePlacement {
            origin: ring.center,
            axis: ring.axis,
            raceway_radius: radius,
            rises: if inner { 1.0 } else { -1.0 },
            face_position: side * (0.5 * params.roller.length + play),
            facing: -side,
        },
    )
}

/// Flange (0…3) of an element index (elements are ordered Inner, Outer, Pair, End×4 per
/// roller).
fn index_to_flange(index: usize) -> usize {
    index % 7 - 3
}

/// Warm-start slot of an element index (4 flange contacts per roller, after 3 line
/// contacts: elements are ordered Inner, Outer, Pair, End×4 per roller).
fn index_to_slot(index: usize) -> usize {
    4 * (index / 7) + index_to_flange(index)
}

impl OdeSystem for BearingModel {
    fn len(&self) -> usize {
        self.layout.len()
    }

    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let kin = self.kinematics(t, y);
        let results = self.evaluate_all(&kin);
        let loads = self.loads(&results);
        self.rates(t, y, &kin, &loads, dy);
    }

    fn jacobian(&self, t: f64, y: &[f64], jac: &mut DMatrix<f64>) {
        self.structured_jacobian(t, y, jac);
    }

    /// Clears the gradient detector's warm starts (checkpoints restart from here).
    fn restart(&self) {
        for slot in &self.warm_starts {
            *slot.lock().unwrap_or_else(PoisonError::into_inner) = [None; 6];
        }
    }
}

impl BearingParams {
    /// Crown drop of the roller profile at axial position s (0 for a straight roller):
    /// a circular-arc-like quadratic drop over `crown_length` at each end.
    pub fn crown_drop(&self, s: f64, straight: f64) -> f64 {
        if self.crown_drop <= 0.0 || self.crown_length <= 0.0 {
            return 0.0;
        }
        let x = s.abs() - (0.5 * straight - self.crown_length);
        if x <= 0.0 {
            0.0
        } else {
            self.crown_drop * (x / self.crown_length).powi(2)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The range of a slice distance |p + s·q| over the slice centres against a brute
        /// force over 2 001 values of s: it contains every sampled value, and its ends are
        /// met to the sampling's resolution (s_max/1000 times |q|, plus round-off).
        #[test]
        fn distance_range_bounds_every_slice(
            p in prop::array::uniform3(-5e-3..5e-3f64),
            q in prop::array::uniform3(-1e-2..1e-2f64),
            s_max in 1e-4..3e-3f64,
        ) {
            let (p, q) = (Vec3::from(p), Vec3::from(q));
            let (least, greatest) = distance_range(&p, &q, s_max);
            let samples: Vec<f64> = (0..=2000)
                .map(|i| (p + (s_max * (i as f64 / 1000.0 - 1.0)) * q).norm())
                .collect();
            let (lo, hi) = samples.iter().fold((f64::INFINITY, 0.0f64), |(l, h), &d| (l.min(d), h.max(d)));
            let tol = 1e-15 + s_max / 1000.0 * q.norm();
            prop_assert!(least <= lo + 1e-15 && least >= lo - tol, "{least} vs {lo}");
            prop_assert!(greatest >= hi - 1e-15 && greatest <= hi + 1e-15, "{greatest} vs {hi}");
        }
    }

    /// The profile's sample takes one section in PROFILE_EVERY, and does so within every
    /// residue class of the periods a fixed contact order could have (B1 enters 100 to 200
    /// sections per right-hand side), so no contact is always or never timed.
    #[test]
    fn the_profile_samples_evenly_without_aliasing() {
        let count = 1_000_000u32;
        let taken = (1..=count).filter(|&n| sampled(n)).count() as f64;
        let share = taken / f64::from(count);
        assert!(
            (share * f64::from(PROFILE_EVERY) - 1.0).abs() < 0.01,
            "{share}"
        );
        for period in 2..=256u32 {
            for residue in 0..period {
                let members = (0..count / period / 4).map(|k| k * period + residue + 1);
                let (n, hits) = members.fold((0.0, 0.0), |(n, h), m| {
                    (n + 1.0, h + f64::from(u8::from(sampled(m))))
                });
                let class_share = hits / n * f64::from(PROFILE_EVERY);
                assert!(
                    (0.5..1.5).contains(&class_share),
                    "period {period}, residue {residue}: {class_share}"
                );
            }
        }
    }

    /// The film's load (Martin and squeeze) over a 4 mm roller whose gap falls linearly
    /// from 5 µm at its centre to `end` at one end (a tilted roller nearing the race), by
    /// the 6 Gauss points against a fine midpoint rule (20 000 sections) and against 20
    /// slices: the Gauss points are within 1.5 % for end gaps ≥ 0.5 µm and at least as
    /// close as the slices.
    #[test]
    fn six_gauss_points_integrate_the_film() {
        use crate::tribology::hydrodynamic::{film_line, RigidFilm};
        let film = RigidFilm {
            enabled: true,
            cutoff: 100e-6,
        };
        let (length, sigma, eta, r) = (4e-3, 0.16e-6, 0.0165, 1.8e-3);
        for end in [0.5e-6, 1e-6, 2e-6, 0.2e-6] {
            for (u, rate) in [(0.3, 0.0), (1e-3, 1e-3)] {
                let load = |s: f64| {
                    let penetration = -(5e-6 - (5e-6 - end) * s / (0.5 * length));
                    let (h, weight) = film.gap_and_weight(penetration, sigma).unwrap();
                    weight * film_line(eta, r, h, u, rate).load
                };
                let midpoint = |n: usize| -> f64 {
                    let dl = length / n as f64;
                    (0..n)
                        .map(|k| load(-0.5 * length + (k as f64 + 0.5) * dl) * dl)
                        .sum()
                };
                let exact = midpoint(20_000);
                let gauss: f64 = mapped_table(&FILM_POINTS, 0.5 * length)
                    .into_iter()
                    .map(|(s, w)| load(s) * w)
                    .sum();
                let (e_gauss, e_slices) = (
                    (gauss / exact - 1.0).abs(),
                    (midpoint(20) / exact - 1.0).abs(),
                );
                assert!(
                    e_gauss <= e_slices + 1e-3,
                    "{end} {u}: {e_gauss} vs {e_slices}"
                );
                if end >= 0.5e-6 {
                    assert!(e_gauss < 0.015, "{end} {u}: {e_gauss}");
                }
            }
        }
    }
}
