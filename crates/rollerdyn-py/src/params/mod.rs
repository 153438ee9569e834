//! The model's parameters and a run's options as they cross from Python: dicts read once
//! into typed, nested structs ([`schema`], declared with [`read::section!`]), which are
//! then turned into the core's `BearingParams` and `RunOptions` here, in one place.
//!
//! Every key is read: a missing key, a key of the wrong type and a key no struct has are
//! `ValueError`s naming its path ("model parameter geometry.roller.radius is missing"), so
//! the dicts of `rollerdyn.simulation` and these structs cannot disagree silently
//! (`tests/test_params_agree.py`).

mod read;
mod schema;

use crate::convert::core_err;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use read::{read_dict, Kind};
use rollerdyn_core::bearing::run::RunOptions;
use rollerdyn_core::bearing::{BearingParams, Carrier, History, ModelOptions, SurfacePair};
use rollerdyn_core::contact::border::BorderBands;
use rollerdyn_core::dynamics::integrate::StepControl;
use rollerdyn_core::geometry::end_flange::FlangeShape;
use rollerdyn_core::geometry::primitives::Vec3;
use rollerdyn_core::geometry::roller::RollerShape;
use rollerdyn_core::tribology::drag::Mixture;
use rollerdyn_core::tribology::friction::{BoundaryFriction, LoadSharing};
use rollerdyn_core::tribology::hydrodynamic::RigidFilm;
use rollerdyn_core::tribology::line_contact::LinePowerLaw;
use rollerdyn_core::tribology::squeeze::SqueezeFilm;
use rollerdyn_core::tribology::traction::EhlTraction;
use schema::{ModelParameters, RunSettings, Shape, Start};

/// The model parameters of the SI dict `d` (`rollerdyn.simulation.model_parameters`) with
/// the EHL traction `traction`.
pub(crate) fn bearing_params(
    d: &Bound<'_, PyDict>,
    traction: &EhlTraction,
) -> PyResult<BearingParams> {
    to_core(read_dict(d, Kind::Parameter)?, traction)
}

/// A run's settings from the SI dict `d` (`rollerdyn.simulation.run_options`), and the
/// threads it asks for (`threads` may be left out: `simulate` builds its model on that
/// many threads, 1 by default; `Model.run` runs on the model's own).
pub(crate) fn run_options(d: &Bound<'_, PyDict>) -> PyResult<(RunOptions, Option<usize>)> {
    let s: RunSettings = read_dict(d, Kind::Option)?;
    let options = RunOptions {
        t_end: s.t_end,
        rtol: s.rtol,
        atol: s.atol,
        atol_time_scale: s.atol_time_scale,
        dt_max: s.dt_max,
        output_interval: s.output_interval,
        method: s.method,
        step_control: StepControl {
            max_growth: s.max_step_growth,
            gain: s.step_gain,
            jacobian_after_newton_failure: s.jacobian_after_newton_failure,
            jacobian_at_latest_iterate: s.jacobian_at_latest_iterate,
            partial_jacobians: s.partial_jacobians,
        },
        checkpoint_interval: s.checkpoint_interval,
        start_from_equilibrium: s.start == Some(Start::Equilibrium),
        min_mean_step: s.min_mean_step,
        check_flange_law: s.check_flange_law,
        roller_records: s.roller_records,
    };
    Ok((options, s.threads.0))
}

/// The core's history of `h`.
fn history(h: schema::History) -> History {
    match h {
        schema::History::Ramp(r) => History::Ramp {
            value: r.value,
            start: r.start,
            end: r.end,
            cosine: r.shape == Shape::Cosine,
        },
        schema::History::Table(t) => History::Table(t.times.into_iter().zip(t.values).collect()),
    }
}

/// The core's flange shape of `f`.
fn flange(f: &schema::Flange) -> PyResult<FlangeShape> {
    FlangeShape::new(f.opening_angle, f.height, f.root_radius, f.rim_radius).map_err(core_err)
}

/// The core's surface pair of `p`.
fn surface(p: &schema::SurfacePair) -> SurfacePair {
    SurfacePair {
        roughness: p.roughness,
        sharing: LoadSharing {
            b: p.zh_b,
            c: p.zh_c,
        },
    }
}

/// The core's parameters of `p` with the EHL traction `traction` (the core checks them
/// when it builds the model).
fn to_core(p: ModelParameters, traction: &EhlTraction) -> PyResult<BearingParams> {
    let ModelParameters {
        geometry: g,
        materials: m,
        inner_ring: ring,
        lubricant: lub,
        surfaces: s,
        operating: op,
        cavity,
        solver,
    } = p;
    let r = &g.roller;
    let contacts = [&m.inner_race, &m.outer_race, &m.roller_roller];
    Ok(BearingParams {
        roller_count: g.roller_count,
        roller: RollerShape::new(r.radius, r.length, r.edge_radius, r.end_face_radius)
            .map_err(core_err)?,
        slices: r.slices,
        crown_drop: r.crown_drop,
        crown_length: r.crown_length,
        log_relief: r.log_relief,
        roller_density: m.roller_density,
        inner_raceway_radius: g.inner_raceway_radius,
        outer_raceway_radius: g.outer_raceway_radius,
        inner_flange: flange(&g.inner_flange)?,
        outer_flange: flange(&g.outer_flange)?,
        flanges: g.flanges,
        inner_axial_play: g.inner_flange.axial_play,
        outer_axial_play: g.outer_flange.axial_play,
        e_prime: contacts.map(|c| c.e_prime),
        line_laws: contacts.map(|c| LinePowerLaw { k1: c.k1, k2: c.k2 }),
        inner_ring_mass: ring.mass,
        inner_ring_axial_inertia: ring.axial_inertia,
        inner_ring_transverse_inertia: ring.transverse_inertia,
        inner_ring_tilt_free: ring.tilt_free,
        inner_ring_misalignment: ring.misalignment,
        traction: traction.clone(),
        eta0: lub.eta0,
        viscosity_slope: lub.viscosity_slope,
        alpha_star: lub.alpha_star,
        thermal_conductivity: lub.thermal_conductivity,
        raceway: surface(&s.raceway),
        flange_surface: surface(&s.flange),
        flange_law: s.flange_law,
        roller_roller: surface(&s.roller_roller),
        boundary: BoundaryFriction {
            mu_b0: s.boundary_friction.mu_b0,
            s0: s.boundary_friction.s0,
            smoothing_speed: s.boundary_friction.smoothing_speed,
        },
        hysteresis_coefficient: s.hysteresis_coefficient,
        rolling_resistance: s.rolling_resistance,
        damping_ratio: s.damping_ratio,
        gravity: Vec3::from(op.gravity),
        race_film: RigidFilm {
            enabled: s.race_film.enabled,
            cutoff: s.race_film.cutoff,
            suction_limit: s.race_film.suction_limit,
        },
        mixture: Mixture::new(
            cavity.oil_fraction,
            lub.density,
            lub.eta0,
            cavity.air_density,
            cavity.air_viscosity,
        ),
        radial_load: history(op.radial_load),
        axial_load: history(op.axial_load),
        inner_ring_speed: history(op.inner_ring_speed),
        outer_ring_speed: history(op.outer_ring_speed),
        carrier: Carrier {
            speed: history(op.carrier_speed),
            offset: Vec3::from(op.carrier_offset),
        },
        squeeze_film: SqueezeFilm {
            enabled: s.squeeze_film.enabled,
            half_width: s.squeeze_film.half_width,
            floor: s.squeeze_film.floor,
            cutoff: s.squeeze_film.cutoff,
        },
        options: ModelOptions {
            detector: solver.detector,
            mesh_resolution: (solver.mesh_around, solver.mesh_along),
            pruning: solver.pruning,
            border_bands: BorderBands {
                roller_angle: solver.border_band_roller,
                flange_length: solver.border_band_flange,
            },
            friction: solver.friction,
        },
    })
}
