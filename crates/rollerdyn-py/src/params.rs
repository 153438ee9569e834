//! The parameter dicts of the Python front end (SI floats, validated by
//! `rollerdyn.config`) marshalled into the core's `BearingParams` and `RunOptions`.
//! Missing keys, wrong types and keys the core does not read become `ValueError`s naming
//! the parameter: the dict and the struct cannot disagree silently.

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
use std::cell::RefCell;
use std::collections::BTreeSet;

/// What a dict holds, for messages: the model's parameters or a run's options.
#[derive(Clone, Copy)]
enum Kind {
    Parameter,
    Option,
}

impl Kind {
    /// "model parameter" or "run option", before a key.
    fn noun(self) -> &'static str {
        match self {
            Kind::Parameter => "model parameter",
            Kind::Option => "run option",
        }
    }

    /// "a parameter" or "an option", after "is not".
    fn short(self) -> &'static str {
        match self {
            Kind::Parameter => "a parameter",
            Kind::Option => "an option",
        }
    }
}

/// A parameter dict and the keys read from it. Every value is taken through it; once the
/// struct is built, [`Dict::done`] refuses any key that was never read, as [`Dict::get`]
/// refuses a missing one.
struct Dict<'py> {
    dict: Bound<'py, PyDict>,
    kind: Kind,
    /// Prefix of the keys in messages: "" at the top, "radial_load." in a nested dict.
    prefix: String,
    read: RefCell<BTreeSet<String>>,
}

impl<'py> Dict<'py> {
    fn new(dict: &Bound<'py, PyDict>, kind: Kind) -> Self {
        Dict {
            dict: dict.clone(),
            kind,
            prefix: String::new(),
            read: RefCell::new(BTreeSet::new()),
        }
    }

    /// `key` as messages name it.
    fn name(&self, key: &str) -> String {
        format!("{} {}{key}", self.kind.noun(), self.prefix)
    }

    /// The value under `key` (None when absent), recorded as read.
    fn item(&self, key: &str) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.read.borrow_mut().insert(key.to_owned());
        self.dict.get_item(key)
    }

    /// `v`, the value of `key`, as a `T`, or ValueError naming the key.
    fn extract<T: pyo3::conversion::FromPyObjectOwned<'py>>(
        &self,
        key: &str,
        v: Bound<'py, PyAny>,
    ) -> PyResult<T> {
        v.extract::<T>()
            .map_err(|_| PyValueError::new_err(format!("{} = {v}: wrong type", self.name(key))))
    }

    /// The value of `key`, or ValueError when it is missing or of the wrong type.
    fn get<T: pyo3::conversion::FromPyObjectOwned<'py>>(&self, key: &str) -> PyResult<T> {
        match self.item(key)? {
            Some(v) => self.extract(key, v),
            None => Err(PyValueError::new_err(format!(
                "{} is missing",
                self.name(key)
            ))),
        }
    }

    /// The value of `key`, None when it is None, or ValueError when it is missing or of
    /// the wrong type.
    fn nullable<T: pyo3::conversion::FromPyObjectOwned<'py>>(
        &self,
        key: &str,
    ) -> PyResult<Option<T>> {
        let v: Bound<'py, PyAny> = self.get(key)?;
        if v.is_none() {
            Ok(None)
        } else {
            self.extract(key, v).map(Some)
        }
    }

    /// The dict under `key`, with its own record of the keys read.
    fn nested(&self, key: &str) -> PyResult<Dict<'py>> {
        let d: Bound<'py, PyDict> = self.get(key)?;
        Ok(Dict {
            prefix: format!("{}{key}.", self.prefix),
            ..Dict::new(&d, self.kind)
        })
    }

    /// Ok when every key of the dict was read; else ValueError naming the first one that
    /// was not (in the dict's order).
    fn done(&self) -> PyResult<()> {
        let read = self.read.borrow();
        for key in self.dict.keys() {
            let unread = match key.extract::<String>() {
                Ok(k) if read.contains(&k) => continue,
                Ok(k) => k,
                Err(_) => key.repr()?.to_string(),
            };
            return Err(PyValueError::new_err(format!(
                "{} is not {} of the core",
                self.name(&unread),
                self.kind.short()
            )));
        }
        Ok(())
    }
}

/// The time history (ramp or table) under `key`.
fn history(d: &Dict<'_>, key: &str) -> PyResult<History> {
    let h = d.nested(key)?;
    let kind: String = h.get("kind")?;
    let history = match kind.as_str() {
        "ramp" => History::Ramp {
            value: h.get("value")?,
            start: h.get("start")?,
            end: h.get("end")?,
            cosine: h.get::<String>("shape")? == "cosine",
        },
        "table" => {
            let t: Vec<f64> = h.get("times")?;
            let v: Vec<f64> = h.get("values")?;
            History::Table(t.into_iter().zip(v).collect())
        }
        other => {
            return Err(PyValueError::new_err(format!(
                "{key}.kind = {other}: must be 'ramp' or 'table'"
            )))
        }
    };
    h.done()?;
    Ok(history)
}

/// The flange shape of `ring` ("inner" or "outer").
fn flange(d: &Dict<'_>, ring: &str) -> PyResult<FlangeShape> {
    let g = |k: &str| d.get::<f64>(&format!("{ring}_flange_{k}"));
    FlangeShape::new(
        g("opening_angle")?,
        g("height")?,
        g("root_radius")?,
        g("rim_radius")?,
    )
    .map_err(core_err)
}

/// The friction data of the surface pair `name`.
fn surface(d: &Dict<'_>, name: &str) -> PyResult<SurfacePair> {
    Ok(SurfacePair {
        roughness: d.get(&format!("{name}_roughness"))?,
        sharing: LoadSharing {
            b: d.get(&format!("{name}_zh_b"))?,
            c: d.get(&format!("{name}_zh_c"))?,
        },
    })
}

/// The model parameters of the SI dict `d` (`rollerdyn.simulation.model_parameters`) with the
/// EHL traction `traction`. Every key of `d` must be one the core reads.
pub(crate) fn bearing_params(
    d: &Bound<'_, PyDict>,
    traction: &EhlTraction,
) -> PyResult<BearingParams> {
    let d = Dict::new(d, Kind::Parameter);
    let params = build_params(&d, traction)?;
    d.done()?;
    Ok(params)
}

/// The parameters of `d`, read key by key (see [`bearing_params`]).
fn build_params(d: &Dict<'_>, traction: &EhlTraction) -> PyResult<BearingParams> {
    let roller = RollerShape::new(
        d.get("roller_radius")?,
        d.get("roller_length")?,
        d.get("edge_radius")?,
        d.get("end_face_radius")?,
    )
    .map_err(core_err)?;
    let law = |k: &str| -> PyResult<LinePowerLaw> {
        Ok(LinePowerLaw {
            k1: d.get(&format!("k1_{k}"))?,
            k2: d.get(&format!("k2_{k}"))?,
        })
    };
    let detector = choose(
        &d.get::<String>("detector")?,
        &Detector::ALL.map(|detector| (detector.name(), detector)),
        |other| format!("detector = {other}: must be semi-analytical, gradient or mesh"),
    )?;
    Ok(BearingParams {
        roller_count: d.get("roller_count")?,
        roller,
        slices: d.get("slices")?,
        crown_drop: d.get("crown_drop")?,
        crown_length: d.get("crown_length")?,
        roller_density: d.get("roller_density")?,
        inner_raceway_radius: d.get("inner_raceway_radius")?,
        outer_raceway_radius: d.get("outer_raceway_radius")?,
        inner_flange: flange(d, "inner")?,
        outer_flange: flange(d, "outer")?,
        inner_axial_play: d.get("inner_axial_play")?,
        outer_axial_play: d.get("outer_axial_play")?,
        e_prime: [
            d.get("e_prime_inner")?,
            d.get("e_prime_outer")?,
            d.get("e_prime_roller")?,
        ],
        line_laws: [law("inner")?, law("outer")?, law("roller")?],
        inner_ring_mass: d.get("inner_ring_mass")?,
        inner_ring_axial_inertia: d.get("inner_ring_axial_inertia")?,
        inner_ring_transverse_inertia: d.get("inner_ring_transverse_inertia")?,
        inner_ring_tilt_free: d.get("inner_ring_tilt_free")?,
        inner_ring_misalignment: d.get("inner_ring_misalignment")?,
        traction: traction.clone(),
        eta0: d.get("eta0")?,
        viscosity_slope: d.get("viscosity_slope")?,
        alpha_star: d.get("alpha_star")?,
        thermal_conductivity: d.get("thermal_conductivity")?,
        raceway: surface(d, "raceway")?,
        flange_surface: surface(d, "flange")?,
        roller_roller: surface(d, "roller_roller")?,
        boundary: BoundaryFriction {
            mu_b0: d.get("mu_b0")?,
            s0: d.get("s0")?,
            smoothing_speed: d.get("smoothing_speed")?,
        },
        hysteresis_coefficient: d.get("hysteresis_coefficient")?,
        damping_ratio: d.get("damping_ratio")?,
        gravity: {
            let g: [f64; 3] = d.get("gravity")?;
            Vec3::new(g[0], g[1], g[2])
        },
        race_film: RigidFilm {
            enabled: d.get("race_film")?,
            cutoff: d.get("race_film_cutoff")?,
        },
        mixture: Mixture::new(
            d.get("oil_fraction")?,
            d.get("oil_density")?,
            d.get("eta0")?,
            d.get("air_density")?,
            d.get("air_viscosity")?,
        ),
        radial_load: history(d, "radial_load")?,
        axial_load: history(d, "axial_load")?,
        inner_ring_speed: history(d, "inner_ring_speed")?,
        squeeze_film: SqueezeFilm {
            enabled: d.get("squeeze_film")?,
            half_width: d.get("squeeze_film_half_width")?,
            floor: d.get("squeeze_film_floor")?,
            cutoff: d.get("squeeze_film_cutoff")?,
        },
        options: ModelOptions {
            detector,
            mesh_resolution: (d.get("mesh_around")?, d.get("mesh_along")?),
            pruning: d.get("pruning")?,
            border_bands: BorderBands {
                roller_angle: d.get("border_band_roller")?,
                flange_length: d.get("border_band_flange")?,
            },
            friction: d.get("friction")?,
        },
    })
}

/// The run's settings from the SI dict `d` (`rollerdyn.simulation.run_options`).
/// Every key of `d` must be one the core reads; `checkpoint_interval` and `start` may be
/// None (no checkpoints; from rest). `threads` may be given: `simulate` builds its model
/// on that many threads (`Model.run` runs on the model's own).
pub(crate) fn run_options(d: &Bound<'_, PyDict>) -> PyResult<RunOptions> {
    let d = Dict::new(d, Kind::Option);
    if let Some(v) = d.item("threads")? {
        d.extract::<usize>("threads", v)?;
    }
    let method = choose(
        &d.get::<String>("method")?,
        &[("tr-bdf2", Method::TrBdf2), ("esdirk34", Method::Esdirk34)],
        |other| format!("method = {other}: must be tr-bdf2 or esdirk34"),
    )?;
    let options = RunOptions {
        t_end: d.get("t_end")?,
        rtol: d.get("rtol")?,
        atol: d.get("atol")?,
        atol_time_scale: d.get("atol_time_scale")?,
        dt_max: d.get("dt_max")?,
        output_interval: d.get("output_interval")?,
        method,
        step_control: StepControl {
            max_growth: d.get("max_step_growth")?,
            gain: d.get("step_gain")?,
            jacobian_after_newton_failure: d.get("jacobian_after_newton_failure")?,
        },
        checkpoint_interval: d.nullable("checkpoint_interval")?,
        start_from_equilibrium: match d.nullable::<String>("start")? {
            Some(start) => choose(&start, &[("rest", false), ("equilibrium", true)], |other| {
                format!("start = {other}: must be rest or equilibrium")
            })?,
            None => false,
        },
    };
    d.done()?;
    Ok(options)
}
