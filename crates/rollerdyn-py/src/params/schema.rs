//! The parameters as they cross from Python: typed, nested structs whose fields are the
//! dicts' keys, grouped as the configuration's sections (all SI, derived and validated by
//! `rollerdyn.config`; built by `rollerdyn.simulation.model_parameters` and
//! `run_options`). `ModelParameters` holds the physical sections and, apart, the numerical
//! ones (`solver`); `RunSettings` a run's options. Adding a parameter means a field here,
//! its key in `rollerdyn.simulation` and its use in `params::to_core`; `tests/
//! test_params_agree.py` fails while they disagree.

use super::read::{choice, nested_with, section, Fields, Omittable, Param, Section};
use pyo3::prelude::*;
use rollerdyn_core::bearing::{Detector, FlangeLaw, RollingResistance};
use rollerdyn_core::dynamics::integrate::Method;

section! {
    /// The model's parameters (`_core.Model(params, traction)`).
    struct ModelParameters {
        geometry: Geometry,
        materials: Materials,
        inner_ring: InnerRing,
        lubricant: Lubricant,
        surfaces: Surfaces,
        operating: Operating,
        cavity: Cavity,
        /// The numerical settings (the core's `ModelOptions`).
        solver: Solver,
    }

    /// Bearing geometry [m].
    struct Geometry {
        /// Number of rollers Z.
        roller_count: usize,
        roller: Roller,
        inner_raceway_radius: f64,
        outer_raceway_radius: f64,
        inner_flange: Flange,
        outer_flange: Flange,
        /// Which flanges the rings have: inner ring −x, +x, outer ring −x, +x
        /// (`_core.FLANGES`).
        flanges: [bool; 4],
    }

    /// The roller's shape [m] and slicing.
    struct Roller {
        radius: f64,
        length: f64,
        edge_radius: f64,
        end_face_radius: f64,
        /// Slices of the line contacts.
        slices: usize,
        /// Crown drop at the ends of the straight part (0: straight profile).
        crown_drop: f64,
        /// Length of the crowned zone at each end (0: straight profile).
        crown_length: f64,
        /// Relief k·D of the logarithmic profile (0: none).
        log_relief: f64,
    }

    /// One ring's flanges (both sides) [m, rad].
    struct Flange {
        opening_angle: f64,
        height: f64,
        root_radius: f64,
        rim_radius: f64,
        /// Axial play per roller end and flange at the raceway, roller centred.
        axial_play: f64,
    }

    /// Elastic data of the contacts (from the materials and the geometry).
    struct Materials {
        /// [kg/m³].
        roller_density: f64,
        inner_race: LineContact,
        outer_race: LineContact,
        roller_roller: LineContact,
    }

    /// One kind of line contact: E' [Pa] and the power law of eq. 11 (k1, k2).
    struct LineContact {
        e_prime: f64,
        k1: f64,
        k2: f64,
    }

    /// The inner ring's body [kg, kg m², rad].
    struct InnerRing {
        mass: f64,
        axial_inertia: f64,
        transverse_inertia: f64,
        /// Tilt free (else locked).
        tilt_free: bool,
        /// Prescribed tilt of a locked ring about z.
        misalignment: f64,
    }

    /// The lubricant at the operating temperature.
    struct Lubricant {
        /// Ambient viscosity η₀ [Pa s].
        eta0: f64,
        /// dη₀/dT [Pa s/K].
        viscosity_slope: f64,
        /// α* [1/Pa].
        alpha_star: f64,
        /// [W/(m K)].
        thermal_conductivity: f64,
        /// [kg/m³].
        density: f64,
    }

    /// Friction and damping of the surfaces, and the oil films between them.
    struct Surfaces {
        raceway: SurfacePair,
        flange: SurfacePair,
        /// How the roller end–flange contacts carry their load.
        flange_law: FlangeLaw,
        roller_roller: SurfacePair,
        boundary_friction: BoundaryFriction,
        /// α_v (eq. 55).
        hysteresis_coefficient: f64,
        /// How the rolling resistance acts on the two bodies of a contact.
        rolling_resistance: RollingResistance,
        /// ζ of the normal contact damping.
        damping_ratio: f64,
        squeeze_film: SqueezeFilm,
        race_film: RaceFilm,
    }

    /// One kind of surface pair: composite roughness σ [m], Zhou–Hoeprich b and c.
    struct SurfacePair {
        roughness: f64,
        zh_b: f64,
        zh_c: f64,
    }

    /// Boundary friction (eqs. 51, 52).
    struct BoundaryFriction {
        mu_b0: f64,
        s0: f64,
        /// [m/s].
        smoothing_speed: f64,
    }

    /// Squeeze film of the roller end–flange gaps [m].
    struct SqueezeFilm {
        enabled: bool,
        half_width: f64,
        floor: f64,
        cutoff: f64,
    }

    /// Oil film across the roller–race and roller–roller gaps [m].
    struct RaceFilm {
        enabled: bool,
        cutoff: f64,
        suction_limit: f64,
    }

    /// Loads [N] and the rings' speeds [rad/s] over time, gravity [m/s²], the planet
    /// carrier's speed [rad/s] over time and the bearing's offset from its axis [m].
    struct Operating {
        radial_load: History,
        axial_load: History,
        inner_ring_speed: History,
        outer_ring_speed: History,
        gravity: [f64; 3],
        carrier_speed: History,
        carrier_offset: [f64; 3],
    }

    /// The oil–air mixture in the cavity.
    struct Cavity {
        oil_fraction: f64,
        /// [kg/m³].
        air_density: f64,
        /// [Pa s].
        air_viscosity: f64,
    }

    /// The model's numerical settings.
    struct Solver {
        detector: Detector,
        mesh_around: usize,
        mesh_along: usize,
        pruning: bool,
        /// Border band half-widths [rad] and [m].
        border_band_roller: f64,
        border_band_flange: f64,
        friction: bool,
    }

    /// A ramp to a constant value [s], after `kind = "ramp"`.
    struct Ramp {
        value: f64,
        start: f64,
        end: f64,
        shape: Shape,
    }

    /// A table of values over time [s], after `kind = "table"`.
    struct Table {
        times: Vec<f64>,
        values: Vec<f64>,
    }

    /// A run's options (`Model.run(options)`, `_core.simulate`).
    struct RunSettings {
        t_end: f64,
        rtol: f64,
        atol: f64,
        atol_time_scale: f64,
        dt_max: f64,
        output_interval: f64,
        method: Method,
        max_step_growth: f64,
        step_gain: f64,
        jacobian_after_newton_failure: bool,
        jacobian_at_latest_iterate: bool,
        partial_jacobians: usize,
        /// None: no checkpoints.
        checkpoint_interval: Option<f64>,
        /// None: from rest.
        start: Option<Start>,
        /// The least mean step over 10 000 steps [s] (0: never stop a run as stalled).
        min_mean_step: f64,
        /// `simulate` builds its model on that many threads (`Model.run`: the model's own).
        threads: Omittable<usize>,
        /// Refuse a point-law run whose loads press a roller end onto its end face
        /// (`simulate(force=True)` sends false).
        check_flange_law: bool,
        /// Keep the per-roller records of every output (`solver.outputs` not empty).
        roller_records: bool,
    }
}

/// A quantity over time: a dict whose `kind` says which of the others it holds.
pub(crate) enum History {
    Ramp(Ramp),
    Table(Table),
}

/// The shape of a ramp.
#[derive(Clone, Copy, PartialEq)]
pub(crate) enum Shape {
    Linear,
    Cosine,
}

/// Where a run starts.
#[derive(Clone, Copy, PartialEq)]
pub(crate) enum Start {
    Rest,
    Equilibrium,
}

/// A name in the dict, read as one of its choices.
macro_rules! named {
    ($($t:ty => $choices:expr;)+) => {$(
        impl Param for $t {
            fn from_value<'py>(s: &Section<'py>, key: &str, v: &Bound<'py, PyAny>) -> PyResult<Self> {
                choice(s, key, v, &$choices)
            }
        }
    )+};
}

named! {
    Detector => Detector::ALL.map(|d| (d.name(), d));
    FlangeLaw => FlangeLaw::ALL.map(|l| (l.name(), l));
    RollingResistance => RollingResistance::ALL.map(|r| (r.name(), r));
    Method => [("tr-bdf2", Method::TrBdf2), ("esdirk34", Method::Esdirk34)];
    Shape => [("linear", Shape::Linear), ("cosine", Shape::Cosine)];
    Start => [("rest", Start::Rest), ("equilibrium", Start::Equilibrium)];
}

/// What a history's dict holds (its key `kind`).
#[derive(Clone, Copy)]
enum HistoryKind {
    Ramp,
    Table,
}

named! {
    HistoryKind => [("ramp", HistoryKind::Ramp), ("table", HistoryKind::Table)];
}

impl Param for History {
    fn from_value<'py>(s: &Section<'py>, key: &str, v: &Bound<'py, PyAny>) -> PyResult<Self> {
        nested_with(s, key, v, |h| {
            Ok(match HistoryKind::from_key(h, "kind")? {
                HistoryKind::Ramp => History::Ramp(Ramp::read_fields(h)?),
                HistoryKind::Table => History::Table(Table::read_fields(h)?),
            })
        })
    }
}
