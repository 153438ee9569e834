//! The parameter dicts of the Python front end (SI floats, validated by
//! `rollerdyn.config`) marshalled into the core's `BearingParams` and `RunOptions`.
//! Missing keys and wrong types become `ValueError`s naming the parameter.

use crate::convert::{choose, core_err};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rollerdyn_core::bearing::run::RunOptions;
use rollerdyn_core::bearing::{BearingParams, Detector, History, ModelOptions, SurfacePair};
use rollerdyn_core::contact::border::BorderBands;
use rollerdyn_core::dynamics::integrate::{Method, StepControl};
use rollerdyn_core::geometry::end_flange::FlangeShape;
use rollerdyn_core::geometry::primitives::Vec3;
use rollerdyn_core::geometry::roller::RollerShape;
use rollerdyn_core::tribology::drag::Mixture;
use rollerdyn_core::tribology::friction::{BoundaryFriction, LoadSharing};
use rollerdyn_core::tribology::hydrodynamic::RigidFilm;
use rollerdyn_core::tribology::line_contact::LinePowerLaw;
use rollerdyn_core::tribology::squeeze::SqueezeFilm;
use rollerdyn_core::tribology::traction::EhlTraction;

/// The value of `key` in `d`, or ValueError when it is missing or of the wrong type.
fn get<'py, T: pyo3::conversion::FromPyObjectOwned<'py>>(
    d: &Bound<'py, PyDict>,
    key: &str,
) -> PyResult<T> {
    match d.get_item(key)? {
        Some(v) => v
            .extract::<T>()
            .map_err(|_| PyValueError::new_err(format!("model parameter {key} = {v}: wrong type"))),
        None => Err(PyValueError::new_err(format!(
            "model parameter {key} is missing"
        ))),
    }
}

/// The time history (ramp or table) under `key`.
fn history(d: &Bound<'_, PyDict>, key: &str) -> PyResult<History> {
    let h: Bound<'_, PyDict> = get(d, key)?;
    let kind: String = get(&h, "kind")?;
    match kind.as_str() {
        "ramp" => Ok(History::Ramp {
            value: get(&h, "value")?,
            start: get(&h, "start")?,
            end: get(&h, "end")?,
            cosine: get::<String>(&h, "shape")? == "cosine",
        }),
        "table" => {
            let t: Vec<f64> = get(&h, "times")?;
            let v: Vec<f64> = get(&h, "values")?;
            Ok(History::Table(t.into_iter().zip(v).collect()))
        }
        other => Err(PyValueError::new_err(format!(
            "{key}.kind = {other}: must be 'ramp' or 'table'"
        ))),
    }
}

/// The flange shape of `ring` ("inner" or "outer").
fn flange(d: &Bound<'_, PyDict>, ring: &str) -> PyResult<FlangeShape> {
    let g = |k: &str| get::<f64>(d, &format!("{ring}_flange_{k}"));
    FlangeShape::new(
        g("opening_angle")?,
        g("height")?,
        g("root_radius")?,
        g("rim_radius")?,
    )
    .map_err(core_err)
}

/// The friction data of the surface pair `name`.
fn surface(d: &Bound<'_, PyDict>, name: &str) -> PyResult<SurfacePair> {
    Ok(SurfacePair {
        roughness: get(d, &format!("{name}_roughness"))?,
        sharing: LoadSharing {
            b: get(d, &format!("{name}_zh_b"))?,
            c: get(d, &format!("{name}_zh_c"))?,
        },
    })
}

/// The model parameters of the SI dict `d` (`rollerdyn.simulation.model_parameters`) with the
/// EHL traction `traction`.
pub(crate) fn bearing_params(
    d: &Bound<'_, PyDict>,
    traction: &EhlTraction,
) -> PyResult<BearingParams> {
    let roller = RollerShape::new(
        get(d, "roller_radius")?,
        get(d, "roller_length")?,
        get(d, "edge_radius")?,
        get(d, "end_face_radius")?,
    )
    .map_err(core_err)?;
    let law = |k: &str| -> PyResult<LinePowerLaw> {
        Ok(LinePowerLaw {
            k1: get(d, &format!("k1_{k}"))?,
            k2: get(d, &format!("k2_{k}"))?,
        })
    };
    let detector = choose(
        &get::<String>(d, "detector")?,
        &Detector::ALL.map(|detector| (detector.name(), detector)),
        |other| format!("detector = {other}: must be semi-analytical, gradient or mesh"),
    )?;
    Ok(BearingParams {
        roller_count: get(d, "roller_count")?,
        roller,
        slices: get(d, "slices")?,
        crown_drop: get(d, "crown_drop")?,
        crown_length: get(d, "crown_length")?,
        roller_density: get(d, "roller_density")?,
        inner_raceway_radius: get(d, "inner_raceway_radius")?,
        outer_raceway_radius: get(d, "outer_raceway_radius")?,
        inner_flange: flange(d, "inner")?,
        outer_flange: flange(d, "outer")?,
        inner_axial_play: get(d, "inner_axial_play")?,
        outer_axial_play: get(d, "outer_axial_play")?,
        e_prime: [
            get(d, "e_prime_inner")?,
            get(d, "e_prime_outer")?,
            get(d, "e_prime_roller")?,
        ],
        line_laws: [law("inner")?, law("outer")?, law("roller")?],
        inner_ring_mass: get(d, "inner_ring_mass")?,
        inner_ring_axial_inertia: get(d, "inner_ring_axial_inertia")?,
        inner_ring_transverse_inertia: get(d, "inner_ring_transverse_inertia")?,
        inner_ring_tilt_free: get(d, "inner_ring_tilt_free")?,
        inner_ring_misalignment: get(d, "inner_ring_misalignment")?,
        traction: traction.clone(),
        eta0: get(d, "eta0")?,
        viscosity_slope: get(d, "viscosity_slope")?,
        alpha_star: get(d, "alpha_star")?,
        thermal_conductivity: get(d, "thermal_conductivity")?,
        raceway: surface(d, "raceway")?,
        flange_surface: surface(d, "flange")?,
        roller_roller: surface(d, "roller_roller")?,
        boundary: BoundaryFriction {
            mu_b0: get(d, "mu_b0")?,
            s0: get(d, "s0")?,
            smoothing_speed: get(d, "smoothing_speed")?,
        },
        hysteresis_coefficient: get(d, "hysteresis_coefficient")?,
        damping_ratio: get(d, "damping_ratio")?,
        gravity: {
            let g: [f64; 3] = get(d, "gravity")?;
            Vec3::new(g[0], g[1], g[2])
        },
        race_film: RigidFilm {
            enabled: get(d, "race_film")?,
            cutoff: get(d, "race_film_cutoff")?,
        },
        mixture: Mixture::new(
            get(d, "oil_fraction")?,
            get(d, "oil_density")?,
            get(d, "eta0")?,
            get(d, "air_density")?,
            get(d, "air_viscosity")?,
        ),
        radial_load: history(d, "radial_load")?,
        axial_load: history(d, "axial_load")?,
        inner_ring_speed: history(d, "inner_ring_speed")?,
        squeeze_film: SqueezeFilm {
            enabled: get(d, "squeeze_film")?,
            half_width: get(d, "squeeze_film_half_width")?,
            floor: get(d, "squeeze_film_floor")?,
            cutoff: get(d, "squeeze_film_cutoff")?,
        },
        options: ModelOptions {
            detector,
            mesh_resolution: (get(d, "mesh_around")?, get(d, "mesh_along")?),
            pruning: get(d, "pruning")?,
            border_bands: BorderBands {
                roller_angle: get(d, "border_band_roller")?,
                flange_length: get(d, "border_band_flange")?,
            },
            friction: get(d, "friction")?,
        },
    })
}

/// The run's settings from the SI dict `d` (built by `rollerdyn.simulation.simulate`).
pub(crate) fn run_options(d: &Bound<'_, PyDict>) -> PyResult<RunOptions> {
    let method = choose(
        &get::<String>(d, "method")?,
        &[("tr-bdf2", Method::TrBdf2), ("esdirk34", Method::Esdirk34)],
        |other| format!("method = {other}: must be tr-bdf2 or esdirk34"),
    )?;
    Ok(RunOptions {
        t_end: get(d, "t_end")?,
        rtol: get(d, "rtol")?,
        atol: get(d, "atol")?,
        atol_time_scale: get(d, "atol_time_scale")?,
        dt_max: get(d, "dt_max")?,
        output_interval: get(d, "output_interval")?,
        method,
        step_control: StepControl {
            max_growth: get(d, "max_step_growth")?,
            gain: get(d, "step_gain")?,
            jacobian_after_newton_failure: get(d, "jacobian_after_newton_failure")?,
        },
        checkpoint_interval: match d.get_item("checkpoint_interval")? {
            Some(v) if !v.is_none() => Some(v.extract().map_err(|_| {
                PyValueError::new_err(format!("checkpoint_interval = {v}: wrong type"))
            })?),
            _ => None,
        },
        start_from_equilibrium: match d.get_item("start")? {
            Some(v) if !v.is_none() => choose(
                &v.extract::<String>()?,
                &[("rest", false), ("equilibrium", true)],
                |other| format!("start = {other}: must be rest or equilibrium"),
            )?,
            _ => false,
        },
    })
}
