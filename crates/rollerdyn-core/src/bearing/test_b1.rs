//! B1 (`examples/b1.toml`) for the core's own tests: its geometry, materials, line-contact
//! laws and loads built as the Python front end builds them
//! (`rollerdyn.simulation.model_parameters` with `rollerdyn.model.Model`), by the same core
//! functions; its lubricant and traction simplified (the quasi-static model uses neither),
//! and the films, drag and squeeze film off (a test turns them on).

use crate::bearing::{
    BearingModel, BearingParams, BearingSystem, Carrier, Detector, FlangeLaw, History,
    ModelOptions, RollingResistance, SurfacePair, Workspace,
};
use crate::contact::border::BorderBands;
use crate::geometry::end_flange::FlangeShape;
use crate::geometry::primitives::Vec3;
use crate::geometry::roller::RollerShape;
use crate::tribology::drag::Mixture;
use crate::tribology::friction::{BoundaryFriction, LoadSharing};
use crate::tribology::hydrodynamic::RigidFilm;
use crate::tribology::line_contact::{Counterface, LinePowerLaw, TrippContact};
use crate::tribology::lubricant::{Carreau, Roelands, Vogel, ZERO_CELSIUS};
use crate::tribology::squeeze::SqueezeFilm;
use crate::tribology::traction::{EhlTraction, LimitingShearStress};
use crate::tribology::Elastic;

/// What the tests vary of B1: roller count, raceway diameters [m], diametral clearance
/// [m], gravity along −y [m/s²].
pub(crate) struct Bearing {
    pub(crate) z: usize,
    pub(crate) inner: f64,
    pub(crate) outer: f64,
    pub(crate) clearance: f64,
    pub(crate) gravity: f64,
}

/// B1 (paper tab. 3; `examples/b1.toml`).
pub(crate) const B1: Bearing = Bearing {
    z: 17,
    inner: 20e-3,
    outer: 29e-3,
    clearance: 10e-6,
    gravity: 9.81,
};

/// The parameters of `b` with the rest of B1's data, derived as the front end derives them.
pub(crate) fn params(b: &Bearing) -> BearingParams {
    let steel = Elastic {
        youngs_modulus: 210e9,
        poisson_ratio: 0.3,
    };
    // roller diameter (D_o − D_i)/2 − clearance/2 (config/derived.py)
    let radius = 0.5 * (0.5 * (b.outer - b.inner) - 0.5 * b.clearance);
    let roller = RollerShape::new(radius, 5e-3, 0.5e-3, 5.0).unwrap();
    // Eq. 11 fitted to Tripp over model.py's line_fit_range: q_ref = 4.08 F_r/(Z l) at
    // B1's 5 kN, race contacts over [0.1, 2] q_ref, roller-roller over [0.01, 0.2] q_ref.
    let q_ref = (4.08 * 5000.0 / (b.z as f64 * roller.straight_length())).max(1e3);
    let contact = |counterface, (lo, hi): (f64, f64)| {
        let c = TrippContact::new(radius, steel, counterface, steel).unwrap();
        let (law, _) = LinePowerLaw::fit(&c, lo * q_ref, hi * q_ref, 64).unwrap();
        (c.e_prime(), law)
    };
    let races = [
        contact(
            Counterface::Convex {
                radius: b.inner / 2.0,
            },
            (0.1, 2.0),
        ),
        contact(
            Counterface::OuterRing {
                raceway_radius: b.outer / 2.0,
                wall_thickness: 2.5e-3,
            },
            (0.1, 2.0),
        ),
        contact(Counterface::Convex { radius }, (0.01, 0.2)),
    ];
    let flange = FlangeShape::new(0.11f64.to_radians(), 1.1e-3, 0.2e-3, 0.3e-3).unwrap();
    // The lubricant, traction, films, drag and friction do not enter the quasi-static
    // model (normal forces only, roller.rs): B1's η₀ at 80 °C (Vogel scaled to 81 mPa s at
    // 40 °C), the rest as simple as their constructors allow.
    let vogel = Vogel {
        k: 0.062e-3,
        b: 1021.7,
        c: 101.5517,
    }
    .scaled_to(ZERO_CELSIUS + 40.0, 81e-3);
    let eta0 = vogel.viscosity(ZERO_CELSIUS + 80.0);
    let traction = EhlTraction::new(
        Roelands::default(),
        Carreau { tau0: 5e6, n: 0.5 },
        LimitingShearStress {
            chi: 0.08,
            p_star: 1.5e9,
            tau_l0: 0.12e9,
            smoothing: 20e6,
        },
        eta0,
        1,
    );
    let surface = |roughness, b, c| SurfacePair {
        roughness,
        sharing: LoadSharing { b, c },
    };
    BearingParams {
        roller_count: b.z,
        roller,
        slices: 20,
        crown_drop: 0.0,
        crown_length: 0.0,
        log_relief: 0.0,
        roller_density: 7850.0,
        inner_raceway_radius: b.inner / 2.0,
        outer_raceway_radius: b.outer / 2.0,
        inner_flange: flange,
        outer_flange: flange,
        flanges: [true; 4],
        inner_axial_play: 20e-6,
        outer_axial_play: 20e-6,
        e_prime: races.map(|(e, _)| e),
        line_laws: races.map(|(_, law)| law),
        inner_ring_mass: 1.0,
        // m r²/2 of the solid cylinder of radius D_i/2 (config/derived.py)
        inner_ring_axial_inertia: 0.5 * (b.inner / 2.0).powi(2),
        inner_ring_transverse_inertia: 5e-4,
        inner_ring_tilt_free: false,
        inner_ring_misalignment: 0.0,
        traction,
        eta0,
        viscosity_slope: vogel.viscosity_slope(ZERO_CELSIUS + 80.0),
        alpha_star: 1e-8,
        thermal_conductivity: 0.134,
        raceway: surface(0.16e-6, 2.32, 0.97),
        flange_surface: surface(0.24e-6, 1.90, 0.99),
        flange_law: FlangeLaw::Point,
        roller_roller: surface(0.16e-6, 2.32, 0.97),
        boundary: BoundaryFriction {
            mu_b0: 0.1,
            s0: 0.02,
            smoothing_speed: 1e-3,
        },
        hysteresis_coefficient: 0.007,
        rolling_resistance: RollingResistance::Paper,
        damping_ratio: 0.1,
        gravity: Vec3::new(0.0, -b.gravity, 0.0),
        race_film: RigidFilm::OFF,
        mixture: Mixture::NONE,
        radial_load: History::constant(5000.0),
        axial_load: History::constant(1000.0),
        inner_ring_speed: History::constant(500.0 * std::f64::consts::PI / 30.0),
        outer_ring_speed: History::constant(0.0),
        carrier: Carrier::at_rest(),
        squeeze_film: SqueezeFilm::OFF,
        options: ModelOptions {
            detector: Detector::SemiAnalytical,
            mesh_resolution: (64, 16),
            pruning: true,
            border_bands: BorderBands {
                roller_angle: 1.5e-4,
                flange_length: 50e-6,
            },
            friction: true,
        },
    }
}

pub(crate) fn model(b: &Bearing) -> BearingModel {
    BearingModel::new(params(b)).unwrap()
}

/// `f` of `model` evaluated in a workspace of its own (one thread).
pub(crate) fn in_workspace<R>(model: &BearingModel, f: impl FnOnce(BearingSystem<'_>) -> R) -> R {
    let workspace = Workspace::single(model);
    f(model.system(&workspace))
}

/// B1's quasi-static equilibrium with `axial` [N] axially and the other loads and speed of
/// t = 1.288 s, beside the rollers that carry at least a tenth of the heaviest roller's
/// load at the inner race.
pub(crate) fn loaded_equilibrium(
    s: &BearingSystem<'_>,
    axial: f64,
) -> (crate::bearing::quasi_static::StaticSolution, Vec<usize>) {
    let case = crate::bearing::quasi_static::StaticCase {
        axial_load: axial,
        ..crate::bearing::quasi_static::StaticCase::at_time(&s.params, 1.288)
    };
    let solution = s.statics(&case, None).expect("an equilibrium");
    let load: Vec<f64> = solution
        .forces
        .iter()
        .map(|f| f.inner_slices.iter().sum::<f64>())
        .collect();
    let heaviest = load.iter().copied().fold(0.0, f64::max);
    let loaded = (0..load.len())
        .filter(|&i| load[i] >= 0.1 * heaviest)
        .collect();
    (solution, loaded)
}
