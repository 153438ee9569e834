//! The bearing model: bodies, the contacts between them, and the equations of motion
//! y' = f(t, y) with a Jacobian built from the problem's structure (paper sect. 3, 4).
//!
//! Contacts ("elements"), for every roller i: the inner race and the outer race (line
//! contacts by slices, eqs. 2, 3, 11), the neighbour i+1 (slices, eq. 11), and its two
//! ends against the two inner-ring and the two outer-ring flanges (the detector of the
//! configuration, Hertz eqs. 5–8). Every force acts at its own contact location; the
//! moment on each body is (P_m − c) × F (docs/dynamics.md, "Contacts"). Beyond the
//! paper: the oil film of the line contacts across their gaps (at 6 Gauss points along the
//! roller, [`crate::tribology::hydrodynamic`]), the squeeze film at the flanges, the drag of
//! the oil–air mixture on every roller ([`crate::tribology::drag`]) and gravity.
//!
//! This module holds the model itself ([`BearingModel`]: construction and what is fixed
//! with it); [`super::workspace`] what its evaluations change and the
//! [`OdeSystem`](crate::dynamics::integrate::OdeSystem)
//! ([`BearingSystem`]) that joins the two for the integrator. A right-hand side passes
//! through stages, each in a module of its own:
//!
//! 1. [`super::state`]: the bodies' kinematics read from the state vector;
//! 2. [`super::topology`]: the contacts and the two bodies each one joins;
//! 3. [`super::contacts`]: each contact evaluated, as a line contact
//!    ([`super::line_contacts`]: slices, eqs. 2, 3, 11, and the film) or a roller end
//!    against a flange ([`super::detection`]: detection, sect. 2;
//!    [`super::flange_contacts`]: Hertz, eqs. 5–8);
//! 4. [`super::equations`]: the wrenches summed per body and the Newton–Euler rates;
//!
//! and [`super::jacobian`] builds the Jacobian from the same stages, by finite differences
//! per body. [`super::profile`] samples where the time goes.
//!
//! The contacts of a right-hand side and the columns of a Jacobian are computed apart, on
//! the workspace's threads if it has any ([`Workspace::new`]), and summed in a fixed order:
//! the numbers do not depend on the thread count.

use super::detection::flange_of;
use super::forces::{EllipseKind, Tribology};
use super::line_contacts::LineContacts;
use super::params::BearingParams;
use super::state::{Kinematics, Layout};
use super::topology::Topology;
use crate::contact::pruning::FlangeBounds;
use crate::dynamics::rigid::axis_from_angles;
use crate::error::{Error, Result};
use crate::geometry::end_flange::face_contact_area;
use crate::geometry::primitives::Vec3;
use crate::geometry::roller::MassProperties;
use crate::numerics::quadrature::{mapped_table, GAUSS_LEGENDRE_4};
use crate::tribology::film::ThermalCorrection;
use crate::tribology::foundation::foundation_modulus;

pub use super::contacts::{ElementResult, Wrench};
pub use super::equations::Loads;
pub use super::profile::Profile;
pub use super::state::BearingKinematics;
pub use super::topology::{Body, Element, LineContact, FLANGE_NAMES};
pub use super::workspace::{BearingSystem, Workspace};

/// Points along the roller at which the drag of the oil–air mixture is evaluated
/// (Gauss–Legendre; [`crate::tribology::drag`]).
const DRAG_POINTS: [(f64, f64); 4] = GAUSS_LEGENDRE_4;

/// The bearing model: its parameters and what is derived from them once, immutable after
/// [`BearingModel::new`] (what evaluations change lives in a [`Workspace`]).
pub struct BearingModel {
    /// The parameters.
    pub params: BearingParams,
    /// The state layout.
    pub layout: Layout,
    /// Roller mass properties.
    pub roller_mass: MassProperties,
    pub(super) tribology: Tribology,
    /// The line contacts' data and the stations along the roller.
    pub(super) lines: LineContacts,
    pub(super) ellipse: EllipseKind,
    /// The Winkler modulus of the distributed flange law, inner and outer ring's flanges
    /// ([`crate::tribology::foundation::foundation_modulus`]) [Pa/m].
    pub(super) foundation_modulus: [f64; 2],
    /// Where the drag acts along the roller: (s, weight as a length) [m].
    pub(super) drag_stations: Vec<(f64, f64)>,
    pitch_radius: f64,
    /// The contacts and the contacts of each body.
    pub(super) topology: Topology,
    /// Axis of the inner ring when its tilt is locked: +x turned by the prescribed
    /// misalignment about z.
    pub(super) locked_axis: Vec3,
    /// Pruning bounds of the four flanges (intrinsic, so computed once; [`FlangeBounds`]).
    pub(super) flange_bounds: [FlangeBounds; 4],
    /// A number no other model built in this process has: a workspace's remembered
    /// evaluation ([`Workspace`]) is reused only by the model that made it.
    pub(super) id: u64,
}

/// The next [`BearingModel::id`].
static NEXT_MODEL_ID: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

impl BearingModel {
    /// Builds the model, refusing parameters that cannot be simulated.
    pub fn new(params: BearingParams) -> Result<Self> {
        params.check()?;
        let layout = Layout {
            rollers: params.roller_count,
            tilt_free: params.inner_ring_tilt_free,
        };
        let roller_mass = params.roller.mass_properties(params.roller_density)?;
        let lines = LineContacts::new(&params, &roller_mass);
        let drag_stations = mapped_table(&DRAG_POINTS, 0.5 * params.roller.length);
        let ellipse = EllipseKind {
            e_prime: params.e_prime[0].min(params.e_prime[1]),
            roughness: params.flange_surface.roughness,
            sharing: params.flange_surface.sharing,
            mass: roller_mass.mass,
        };
        let foundation_modulus = [&params.inner_flange, &params.outer_flange]
            .map(|f| foundation_modulus(ellipse.e_prime, face_contact_area(&params.roller, f)));
        let tribology = Tribology {
            traction: params.traction.clone(),
            boundary: params.boundary,
            eta0: params.eta0,
            alpha_star: params.alpha_star,
            thermal: ThermalCorrection::new(params.viscosity_slope, params.thermal_conductivity),
            moes: Default::default(),
            hysteresis_coefficient: params.hysteresis_coefficient,
            rolling_resistance: params.rolling_resistance,
            damping_ratio: params.damping_ratio,
            friction: params.options.friction,
            film: params.race_film,
        };
        let z = params.roller_count;
        let pitch_radius = 0.5 * (params.inner_raceway_radius + params.outer_raceway_radius);
        let at_rest = Kinematics::fixed();
        let flange_bounds =
            std::array::from_fn(|k| FlangeBounds::new(&flange_of(&params, k, &at_rest)));
        Ok(Self {
            layout,
            roller_mass,
            tribology,
            lines,
            ellipse,
            foundation_modulus,
            drag_stations,
            pitch_radius,
            topology: Topology::new(z),
            flange_bounds,
            locked_axis: axis_from_angles(0.0, params.inner_ring_misalignment),
            params,
            id: NEXT_MODEL_ID.fetch_add(1, std::sync::atomic::Ordering::Relaxed),
        })
    }

    /// All contacts, in the order of [`BearingSystem::evaluate_all`].
    pub fn elements(&self) -> &[Element] {
        &self.topology.elements
    }

    /// Pitch radius [m].
    pub fn pitch_radius(&self) -> f64 {
        self.pitch_radius
    }

    /// The rollers' azimuths at the start [rad], from +y towards +z: roller 0 at the
    /// bottom (ψ = π, the centre of the load zone of the radial load along −y), the others
    /// evenly spaced.
    pub fn roller_azimuths(&self) -> Vec<f64> {
        let z = self.params.roller_count;
        (0..z)
            .map(|i| std::f64::consts::PI + 2.0 * std::f64::consts::PI * i as f64 / z as f64)
            .collect()
    }
}

/// The penetration [m] up to which bodies at the start at rest touch rather than overlap
/// ([`BearingSystem::initial_state`]): the round-off of positions of a metre's scale, a
/// thousand times over (a bearing without clearance puts its rollers on both races).
const START_TOUCH: f64 = 1e-12;

impl BearingSystem<'_> {
    /// The consistent start: rollers on the pitch circle, roller 0 at the bottom (−y, ψ = π, the
    /// centre of the load zone), axes along x, at rest; the inner ring centred. Nothing
    /// overlaps (checked).
    pub fn initial_state(&self) -> Result<Vec<f64>> {
        let mut y = vec![0.0; self.layout.len()];
        for (i, psi) in self.roller_azimuths().into_iter().enumerate() {
            let s = self.layout.roller(i);
            y[s + 1] = self.pitch_radius * psi.cos();
            y[s + 2] = self.pitch_radius * psi.sin();
        }
        let kin = self.kinematics(0.0, &y);
        for element in self.elements() {
            let r = self.evaluate(element, &kin);
            // NaN counts as overlap: a start whose forces are not defined is refused. (The
            // oil films act across gaps, so a force alone is no overlap.) Touching is not
            // overlapping: with no clearance the rollers touch both races, to round-off.
            let overlaps = r.penetration > START_TOUCH;
            if overlaps || r.penetration.is_nan() || r.normal.is_nan() {
                return Err(self.overlap_at_rest(element, r.penetration));
            }
        }
        Ok(y)
    }

    /// The error of a start at rest whose bodies overlap: the contact in words and, with a
    /// misaligned ring (B1 above about 0.07°, whose tilted raceway meets the untilted
    /// rollers), that setting and the start from equilibrium, which tilts the rollers with
    /// the ring (B1 at 0.15° starts so).
    fn overlap_at_rest(&self, element: &Element, penetration: f64) -> Error {
        let contact = match *element {
            Element::Inner(i) => format!("roller {i} and the inner race"),
            Element::Outer(i) => format!("roller {i} and the outer race"),
            Element::Pair(i) => format!("rollers {i} and {}", (i + 1) % self.layout.rollers),
            Element::End(i, k) => format!("roller {i}'s end and the {} flange", FLANGE_NAMES[k]),
        };
        let overlap = format!(
            "at solver.start = \"rest\" (rollers on the pitch circle, untilted, rings centred) \
             {contact} overlap by {:.3} um; bodies must not overlap at the start",
            penetration * 1e6
        );
        let misalignment = self.params.inner_ring_misalignment;
        if misalignment != 0.0 {
            Error::invalid(
                "inner_ring.misalignment",
                format!("{:.4} deg", misalignment.to_degrees()),
                format!(
                    "{overlap}; start from the quasi-static equilibrium instead \
                     (solver.start = \"equilibrium\"), whose rollers follow the tilted ring"
                ),
            )
        } else {
            Error::invalid("solver.start", "\"rest\"", overlap)
        }
    }
}
