//! The quasi-static analysis (`rollerdyn.statics`): equilibria of load cases on a built
//! model, each returned as a dict of SI values (flat lists, roller-major), the stiffness
//! at each, and the friction power of steady rolling there (flanges, inner race, outer
//! race, drag).

use crate::convert::core_err;
use crate::simulation::PyModel;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rollerdyn_core::bearing::quasi_static::{RingTilt, StaticCase, StaticSolution};
use rollerdyn_core::bearing::statics::RollingFriction;

/// A load case as Python hands it over: (radial load [N], axial load [N], moment about y
/// [N·m], moment about z [N·m], inner ring speed [rad/s], prescribed tilt (θ_y, θ_z)
/// [rad] or None for a free tilt, the roller set's phase [rad], outer ring speed [rad/s],
/// the planet carrier's speed [rad/s]).
type Case = (f64, f64, f64, f64, f64, Option<(f64, f64)>, f64, f64, f64);

/// The core's case of `c`.
fn case_of(c: &Case) -> StaticCase {
    StaticCase {
        radial_load: c.0,
        axial_load: c.1,
        moment: [c.2, c.3],
        speed: c.4,
        outer_speed: c.7,
        carrier_speed: c.8,
        tilt: match c.5 {
            Some((a, b)) => RingTilt::Prescribed(a, b),
            None => RingTilt::Free,
        },
        roller_set_phase: c.6,
    }
}

/// A float64 array of `values`.
fn array<'py>(py: Python<'py>, values: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_vec(py, values)
}

/// The dict of one solution (and its stiffness, row by row, when asked).
fn solution_dict<'py>(
    py: Python<'py>,
    s: &StaticSolution,
    stiffness: Option<[[f64; 5]; 5]>,
    friction: &RollingFriction,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item(
        "friction_power",
        array(
            py,
            vec![
                friction.flanges,
                friction.inner_race,
                friction.outer_race,
                friction.roller_pairs,
                friction.drag,
            ],
        ),
    )?;
    d.set_item("roller_slip", array(py, friction.roller_slip.clone()))?;
    d.set_item("roller_skew", array(py, friction.roller_skew.clone()))?;
    d.set_item("flange_offsets", array(py, friction.flange_offsets.clone()))?;
    d.set_item(
        "flange_sliding_speeds",
        array(py, friction.flange_sliding_speeds.clone()),
    )?;
    d.set_item("pair_force", array(py, friction.pair_forces.clone()))?;
    let rollers = &s.rollers;
    let per_roller = |f: &dyn Fn(usize) -> f64| array(py, (0..rollers.len()).map(f).collect());
    d.set_item("ring", array(py, s.ring.to_vec()))?;
    d.set_item("roller_azimuth", per_roller(&|i| rollers[i].azimuth))?;
    d.set_item("roller_radial", per_roller(&|i| rollers[i].radial))?;
    d.set_item("roller_axial", per_roller(&|i| rollers[i].axial))?;
    d.set_item("roller_tilt", per_roller(&|i| rollers[i].tilt))?;
    let flat = |f: &dyn Fn(&rollerdyn_core::bearing::quasi_static::RollerForces) -> Vec<f64>| {
        array(py, s.forces.iter().flat_map(f).collect())
    };
    d.set_item("inner_slices", flat(&|f| f.inner_slices.clone()))?;
    d.set_item("outer_slices", flat(&|f| f.outer_slices.clone()))?;
    d.set_item("inner_pressures", flat(&|f| f.inner_pressures.clone()))?;
    d.set_item("outer_pressures", flat(&|f| f.outer_pressures.clone()))?;
    d.set_item(
        "flange_force",
        flat(&|f| f.flanges.iter().map(|x| x.force).collect()),
    )?;
    d.set_item(
        "flange_pressure",
        flat(&|f| f.flanges.iter().map(|x| x.pressure).collect()),
    )?;
    d.set_item(
        "flange_contact_radius",
        flat(&|f| f.flanges.iter().map(|x| x.radius).collect()),
    )?;
    d.set_item(
        "flange_penetration",
        flat(&|f| f.flanges.iter().map(|x| x.penetration).collect()),
    )?;
    d.set_item(
        "flange_pairing",
        flat(&|f| {
            f.flanges
                .iter()
                .map(|x| x.pairing.map_or(-1.0, |p| p as f64))
                .collect()
        }),
    )?;
    let w = &s.ring_load;
    d.set_item(
        "ring_load",
        array(
            py,
            vec![
                w.force.x, w.force.y, w.force.z, w.moment.x, w.moment.y, w.moment.z,
            ],
        ),
    )?;
    d.set_item("residual", s.residual)?;
    d.set_item("iterations", s.iterations)?;
    d.set_item("evaluations", s.evaluations)?;
    if let Some(k) = stiffness {
        d.set_item(
            "stiffness",
            array(py, k.iter().flatten().copied().collect()),
        )?;
    }
    Ok(d)
}

/// The quasi-static equilibria of `cases` on `model`, in order: a dict per case, or the
/// core's message (a str) where no equilibrium was found. With `chain`, each search starts
/// from the last solution found (a sweep); `stiffness` adds the 5×5 stiffness matrix.
#[pyfunction]
#[pyo3(signature = (model, cases, chain=true, stiffness=false))]
pub(crate) fn statics<'py>(
    py: Python<'py>,
    model: &PyModel,
    cases: Vec<Case>,
    chain: bool,
    stiffness: bool,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let model = model.system();
    let mut last: Option<StaticSolution> = None;
    let mut last_friction: Option<RollingFriction> = None;
    let mut out = Vec::with_capacity(cases.len());
    for c in &cases {
        let start = if chain { last.as_ref() } else { None };
        let warm = if chain { last_friction.as_ref() } else { None };
        let found = py.detach(|| {
            model.statics(&case_of(c), start).map(|s| {
                let k = stiffness.then(|| model.stiffness(&s));
                let friction = model.steady_rolling_friction(&s, warm);
                (s, k, friction)
            })
        });
        match found {
            Ok((s, k, friction)) => {
                out.push(solution_dict(py, &s, k, &friction)?.into_any());
                last = Some(s);
                last_friction = Some(friction);
            }
            Err(e) => out.push(core_err(e).value(py).str()?.into_any()),
        }
        py.check_signals()?;
    }
    Ok(out)
}

/// Adds this module's functions to `m`.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(statics, m)?)?;
    Ok(())
}
