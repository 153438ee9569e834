//! Bindings of the dynamic model (core `bearing`, paper sect. 3, 4): a whole run
//! (`simulate`, with progress and checkpoint callbacks), the start states
//! (`initial_state`, `equilibrium_state`) and the model's right-hand side, Jacobian,
//! timing and energy at one state (for tests and `rollerdyn bench model`). The results of
//! a run come back as a dict of flat arrays (`rollerdyn.simulation` shapes them).

use crate::convert::{core_err, count, set_fields, MAX_REPETITIONS};
use crate::params::{bearing_params, run_options};
use crate::traction::PyEhlTraction;
use numpy::PyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use rollerdyn_core::bearing::profile::Profile;
use rollerdyn_core::bearing::run::{
    run, ContactLubrication, Progress, Record, RollerRecord, RunCheckpoint, RunOptions, RunOutput,
};
use rollerdyn_core::bearing::{BearingModel, BearingSystem, Workspace};
use rollerdyn_core::dynamics::integrate::{OdeSystem, Start, Stats};
use std::ops::ControlFlow;
use std::time::Instant;

/// The quasi-static equilibrium state at time t (`solver.start = "equilibrium"`), or
/// ValueError with the residual and the body where there is none.
#[pyfunction]
fn equilibrium_state(
    params: &Bound<'_, PyDict>,
    traction: &PyEhlTraction,
    t: f64,
) -> PyResult<Vec<f64>> {
    let model = BearingModel::new(bearing_params(params, &traction.inner)?).map_err(core_err)?;
    let workspace = Workspace::single(&model);
    model
        .system(&workspace)
        .equilibrium_state(t)
        .map_err(core_err)
}

/// Checks a parameter set and returns the initial state (or raises ValueError).
#[pyfunction]
fn initial_state(params: &Bound<'_, PyDict>, traction: &PyEhlTraction) -> PyResult<Vec<f64>> {
    let model = BearingModel::new(bearing_params(params, &traction.inner)?).map_err(core_err)?;
    let workspace = Workspace::single(&model);
    model.system(&workspace).initial_state().map_err(core_err)
}

/// The model of `params`, checked to have as many states as `y`.
fn model_for(
    params: &Bound<'_, PyDict>,
    traction: &PyEhlTraction,
    y: &[f64],
) -> PyResult<BearingModel> {
    let model = BearingModel::new(bearing_params(params, &traction.inner)?).map_err(core_err)?;
    if y.len() != model.layout.len() {
        return Err(PyValueError::new_err(format!(
            "y has {} states: the model has {}",
            y.len(),
            model.layout.len()
        )));
    }
    Ok(model)
}

/// f(t, y) and the structured Jacobian of the model at (t, y) (for tests).
#[pyfunction]
fn model_rhs(
    params: &Bound<'_, PyDict>,
    traction: &PyEhlTraction,
    t: f64,
    y: Vec<f64>,
) -> PyResult<(Vec<f64>, Vec<f64>)> {
    let model = model_for(params, traction, &y)?;
    let workspace = Workspace::single(&model);
    let model = model.system(&workspace);
    let n = model.len();
    let mut dy = vec![0.0; n];
    model.rhs(t, &y, &mut dy);
    let mut jac = nalgebra::DMatrix::zeros(n, n);
    model.jacobian(t, &y, &mut jac);
    Ok((dy, jac.transpose().as_slice().to_vec()))
}

/// Times the model at (t, y) on this thread: `rhs_repetitions` right-hand sides, each
/// evaluating every contact, then `jacobian_repetitions` Jacobians, each taking its base
/// from the evaluation before at the same state as in a run (`rollerdyn bench model`).
/// Returns the mean wall time of each [s] and the profile of the right-hand sides
/// (detection, line contacts, flange forces [s per right-hand side]; sampled as in a run).
#[pyfunction]
fn model_timing<'py>(
    py: Python<'py>,
    params: &Bound<'py, PyDict>,
    traction: &PyEhlTraction,
    t: f64,
    y: Vec<f64>,
    rhs_repetitions: i64,
    jacobian_repetitions: i64,
) -> PyResult<Bound<'py, PyDict>> {
    let model = model_for(params, traction, &y)?;
    let workspace = Workspace::single(&model);
    timing(
        py,
        &model.system(&workspace),
        t,
        &y,
        rhs_repetitions,
        jacobian_repetitions,
    )
}

/// Most threads a model may be asked for (the workspace takes at most the cores; a count
/// above this is a mistake).
const MAX_THREADS: usize = 1 << 20;

/// [`model_timing`] of a built model: at least one right-hand side, any number of
/// Jacobians.
fn timing<'py>(
    py: Python<'py>,
    model: &BearingSystem<'_>,
    t: f64,
    y: &[f64],
    rhs_repetitions: i64,
    jacobian_repetitions: i64,
) -> PyResult<Bound<'py, PyDict>> {
    let rhs_n = count("rhs_repetitions", rhs_repetitions, 1..=MAX_REPETITIONS)?;
    let jac_n = count(
        "jacobian_repetitions",
        jacobian_repetitions,
        0..=MAX_REPETITIONS,
    )?;
    let y = y.to_vec();
    let n = model.len();
    let mut dy = vec![0.0; n];
    let mut jac = nalgebra::DMatrix::zeros(n, n);
    // Warm-up (and the gradient detector's warm starts), then as after a run's accepted
    // step: the distributed law's overlaps start from the support frames the warm-up found
    // (`OdeSystem::step_accepted`), as a run's do.
    model.rhs(t, &y, &mut dy);
    model.step_accepted();
    let before = model.profile();
    let start = Instant::now();
    for _ in 0..rhs_n {
        // each evaluated afresh, not taken from the one before at the same state
        model.forget_evaluation();
        model.rhs(t, std::hint::black_box(&y), &mut dy);
    }
    let rhs = start.elapsed().as_secs_f64() / rhs_n as f64;
    let after = model.profile();
    let start = Instant::now();
    for _ in 0..jac_n {
        model.jacobian(t, std::hint::black_box(&y), &mut jac);
    }
    let jacobian = start.elapsed().as_secs_f64() / jac_n.max(1) as f64;
    let per = |a: f64, b: f64| (a - b) / rhs_n as f64;
    let d = PyDict::new(py);
    d.set_item("states", n)?;
    d.set_item("rhs_seconds", rhs)?;
    d.set_item(
        "jacobian_seconds",
        if jac_n > 0 { jacobian } else { f64::NAN },
    )?;
    d.set_item("detection_seconds", per(after.detection, before.detection))?;
    d.set_item(
        "line_contact_seconds",
        per(after.line_contacts, before.line_contacts),
    )?;
    d.set_item(
        "flange_force_seconds",
        per(after.flange_forces, before.flange_forces),
    )?;
    d.set_item(
        "detections",
        (after.detections - before.detections) as f64 / rhs_n as f64,
    )?;
    Ok(d)
}

/// Total mechanical energy of the model at (t, y) [J] (for conservation checks).
#[pyfunction]
fn model_energy(
    params: &Bound<'_, PyDict>,
    traction: &PyEhlTraction,
    t: f64,
    y: Vec<f64>,
) -> PyResult<f64> {
    let model = model_for(params, traction, &y)?;
    let workspace = Workspace::single(&model);
    Ok(model.system(&workspace).energy(t, &y))
}

/// Runs the dynamic model. `progress(time, t_end, steps, rhs, jac, step, at_output)` is
/// called at every output time and every 0.2 s of wall time between them (`at_output`
/// False), where signals are read too; returning True stops the run. `checkpoint(dict)` is called at every
/// checkpoint with the results so far (the dict `simulate` returns, cut at the
/// checkpoint); returning True stops the run. `start = (t, y, h)` starts from a state,
/// `h` None for a fresh start, a checkpoint's step to continue from it bit for bit.
/// Returns a dict of flat arrays (see `rollerdyn.simulation`), the solver counters, the
/// profile, the final state, the last checkpoint (or the start) and the error (None if
/// the run completed).
#[pyfunction]
#[pyo3(signature = (params, traction, options, progress=None, start=None, checkpoint=None))]
fn simulate<'py>(
    py: Python<'py>,
    params: &Bound<'py, PyDict>,
    traction: &PyEhlTraction,
    options: &Bound<'py, PyDict>,
    progress: Option<Bound<'py, PyAny>>,
    start: Option<(f64, Vec<f64>, Option<f64>)>,
    checkpoint: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (opts, threads) = run_options(options)?;
    let model = BearingModel::new(bearing_params(params, &traction.inner)?).map_err(core_err)?;
    let workspace = Workspace::new(&model, threads.unwrap_or(1)).map_err(core_err)?;
    run_model(
        py,
        &model.system(&workspace),
        &opts,
        progress,
        start,
        checkpoint,
    )
}

/// [`simulate`] with a built model in its workspace (the workspace's threads;
/// `options["threads"]` unused).
fn run_model<'py>(
    py: Python<'py>,
    model: &BearingSystem<'_>,
    opts: &RunOptions,
    progress: Option<Bound<'py, PyAny>>,
    start: Option<(f64, Vec<f64>, Option<f64>)>,
    checkpoint: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let start = start.map(|(time, state, step)| Start { time, state, step });
    let z = model.layout.rollers;
    let callback_error = std::cell::RefCell::new(None::<PyErr>);
    let stop = |r: PyResult<Bound<'py, PyAny>>| match r {
        Ok(r) if r.is_truthy().unwrap_or(false) => ControlFlow::Break(()),
        Ok(_) => ControlFlow::Continue(()),
        Err(e) => {
            *callback_error.borrow_mut() = Some(e);
            ControlFlow::Break(())
        }
    };
    let output = run(
        model,
        start,
        opts,
        |p: &Progress| {
            if let Err(e) = py.check_signals() {
                *callback_error.borrow_mut() = Some(e);
                return ControlFlow::Break(());
            }
            let Some(cb) = &progress else {
                return ControlFlow::Continue(());
            };
            let s = &p.stats;
            stop(cb.call1((
                p.time,
                p.t_end,
                s.steps,
                s.rhs_evaluations,
                s.jacobian_evaluations,
                s.last_step,
                p.at_output,
            )))
        },
        |c: &RunCheckpoint, records: &[Record]| {
            let Some(cb) = &checkpoint else {
                return ControlFlow::Continue(());
            };
            let d = match partial_dict(py, c, records, z) {
                Ok(d) => d,
                Err(e) => return stop(Err(e)),
            };
            stop(cb.call1((d,)))
        },
    )
    .map_err(core_err)?;
    let out = to_dict(py, &output, z)?;
    put_checkpoint(py, &out, &output.checkpoint)?;
    if let Some(e) = callback_error.into_inner() {
        out.set_item("interruption", e.to_string())?;
    }
    Ok(out)
}

/// The results up to a checkpoint, as `simulate` returns them (not completed).
fn partial_dict<'py>(
    py: Python<'py>,
    c: &RunCheckpoint,
    records: &[Record],
    z: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let k = &c.checkpoint;
    let partial = RunOutput {
        records: records[..c.records].to_vec(),
        stats: k.stats,
        profile: c.profile,
        final_state: k.state.clone(),
        final_time: k.time,
        error: None,
        interrupted: true,
        checkpoint: c.clone(),
    };
    let d = to_dict(py, &partial, z)?;
    put_checkpoint(py, &d, c)?;
    Ok(d)
}

/// The checkpoint entries: time, state, step (NaN: a fresh start) and counters.
fn put_checkpoint(py: Python<'_>, d: &Bound<'_, PyDict>, c: &RunCheckpoint) -> PyResult<()> {
    let k = &c.checkpoint;
    d.set_item("checkpoint_time", k.time)?;
    d.set_item("checkpoint_step", k.step)?;
    d.set_item("checkpoint_state", PyList::new(py, &k.state)?)?;
    d.set_item("checkpoint_stats", stats_dict(py, &k.stats, &c.profile)?)?;
    Ok(())
}

fn stats_dict<'py>(py: Python<'py>, s: &Stats, p: &Profile) -> PyResult<Bound<'py, PyDict>> {
    let stats = PyDict::new(py);
    set_fields!(
        stats,
        s;
        steps,
        rhs_evaluations,
        jacobian_evaluations,
        rhs_seconds,
        jacobian_seconds,
        total_seconds,
        t_reached,
        error_test_failures,
        newton_failures,
        newton_iterations,
        linear_solver_setups,
        partial_jacobians,
    );
    stats.set_item("detection_seconds", p.detection)?;
    stats.set_item("line_contact_seconds", p.line_contacts)?;
    stats.set_item("flange_force_seconds", p.flange_forces)?;
    set_fields!(stats, p; detections, gradient_fallbacks);
    Ok(stats)
}

/// One value of a contact's lubrication.
type LubricationValue = fn(&ContactLubrication) -> f64;

/// The lubrication outputs of every contact, by the name's suffix (the group "lubrication"
/// of `solver.outputs`).
const LUBRICATION: [(&str, LubricationValue); 4] = [
    ("max_pressure", |l| l.max_pressure),
    ("film_thickness", |l| l.film),
    ("specific_film_thickness", |l| l.specific_film),
    ("sliding_speed", |l| l.sliding_speed),
];

fn to_dict<'py>(py: Python<'py>, o: &RunOutput, z: usize) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let recs = &o.records;
    let put = |name: &str, v: Vec<f64>| d.set_item(name, PyArray1::from_vec(py, v));
    macro_rules! per_record {
        ($name:literal, $f:expr) => {
            put($name, recs.iter().map($f).collect())?
        };
    }
    per_record!("time", |r| r.time);
    put(
        "ring_position",
        recs.iter()
            .flat_map(|r| r.ring_position.iter().copied().collect::<Vec<_>>())
            .collect(),
    )?;
    put(
        "ring_tilt",
        recs.iter()
            .flat_map(|r| [r.ring_tilt.0, r.ring_tilt.1])
            .collect(),
    )?;
    per_record!("ring_speed", |r| r.ring_speed);
    per_record!("outer_ring_speed", |r| r.outer_ring_speed);
    per_record!("carrier_speed", |r| r.carrier_speed);
    per_record!("radial_load", |r| r.loads.0);
    per_record!("axial_load", |r| r.loads.1);
    per_record!("frictional_torque", |r| r.frictional_torque);
    per_record!("outer_ring_torque", |r| r.outer_ring_torque);
    per_record!("power_loss", |r| r.power_loss);
    per_record!("sliding_power_loss", |r| r.power_by_mechanism.sliding);
    per_record!("normal_power_loss", |r| r.power_by_mechanism.normal);
    per_record!("rolling_power_loss", |r| r.power_by_mechanism.rolling);
    macro_rules! per_roller {
        ($name:literal, $f:expr) => {
            put(
                $name,
                recs.iter().flat_map(|r| r.rollers.iter().map($f)).collect(),
            )?
        };
    }
    per_roller!("azimuth", |x| x.azimuth);
    per_roller!("tilt", |x| x.tilt);
    per_roller!("skew", |x| x.skew);
    per_roller!("spin_speed", |x| x.spin_speed);
    per_roller!("orbital_speed", |x| x.orbital_speed);
    per_roller!("srr_inner", |x| x.srr_inner);
    per_roller!("srr_outer", |x| x.srr_outer);
    per_roller!("inner_normal_force", |x| x.inner_normal);
    per_roller!("outer_normal_force", |x| x.outer_normal);
    per_roller!("inner_tangential_force", |x| x.inner_tangential);
    per_roller!("outer_tangential_force", |x| x.outer_tangential);
    per_roller!("roller_roller_normal_force", |x| x.pair_normal);
    per_roller!("roller_roller_tangential_force", |x| x.pair_tangential);
    per_roller!("inner_power_loss", |x| x.inner_power.loss);
    per_roller!("outer_power_loss", |x| x.outer_power.loss);
    per_roller!("roller_roller_power_loss", |x| x.pair_power.loss);
    per_roller!("inner_sliding_power_loss", |x| x.inner_power.sliding);
    per_roller!("outer_sliding_power_loss", |x| x.outer_power.sliding);
    per_roller!("roller_roller_sliding_power_loss", |x| x.pair_power.sliding);
    per_roller!("inner_rolling_power_loss", |x| x.inner_power.rolling);
    per_roller!("outer_rolling_power_loss", |x| x.outer_power.rolling);
    per_roller!("roller_roller_rolling_power_loss", |x| x.pair_power.rolling);
    per_roller!("drag_power_loss", |x| x.drag_power_loss);
    for (contact, of) in [
        (
            "inner",
            (|x| &x.inner_lubrication) as fn(&RollerRecord) -> &ContactLubrication,
        ),
        ("outer", |x| &x.outer_lubrication),
        ("roller_roller", |x| &x.pair_lubrication),
    ] {
        for (quantity, value) in LUBRICATION {
            let v = recs
                .iter()
                .flat_map(|r| r.rollers.iter().map(|x| value(of(x))))
                .collect();
            put(&format!("{contact}_{quantity}"), v)?;
        }
    }
    put(
        "position",
        recs.iter()
            .flat_map(|r| {
                r.rollers
                    .iter()
                    .flat_map(|x| x.position.iter().copied().collect::<Vec<_>>())
            })
            .collect(),
    )?;
    macro_rules! per_flange {
        ($name:literal, $f:expr) => {
            put(
                $name,
                recs.iter()
                    .flat_map(|r| r.rollers.iter().flat_map(|x| x.flanges.iter().map($f)))
                    .collect(),
            )?
        };
    }
    per_flange!("flange_pairing", |f| f.pairing as f64);
    per_flange!("flange_penetration", |f| if f.penetration.is_finite() {
        f.penetration
    } else {
        f64::NAN
    });
    per_flange!("flange_normal_force", |f| f.normal_force);
    per_flange!("flange_friction_force", |f| f.friction_force);
    per_flange!("flange_axial_force", |f| f.axial_force);
    per_flange!("flange_power_loss", |f| f.power.loss);
    per_flange!("flange_sliding_power_loss", |f| f.power.sliding);
    for (quantity, value) in LUBRICATION {
        let v = recs
            .iter()
            .flat_map(|r| {
                r.rollers
                    .iter()
                    .flat_map(|x| x.flanges.iter().map(|f| value(&f.lubrication)))
            })
            .collect();
        put(&format!("flange_{quantity}"), v)?;
    }
    put(
        "flange_location",
        recs.iter()
            .flat_map(|r| {
                r.rollers.iter().flat_map(|x| {
                    x.flanges
                        .iter()
                        .flat_map(|f| f.location.iter().copied().collect::<Vec<_>>())
                })
            })
            .collect(),
    )?;
    d.set_item("rollers", z)?;
    let stats = stats_dict(py, &o.stats, &o.profile)?;
    d.set_item("stats", stats)?;
    d.set_item("final_state", PyList::new(py, &o.final_state)?)?;
    d.set_item("final_time", o.final_time)?;
    d.set_item("error", o.error.clone())?;
    d.set_item("interrupted", o.interrupted)?;
    Ok(d)
}

/// The bearing model, built once from its parameters and shared by every call: the
/// states at the start, the right-hand side, Jacobian and energy at a state, their
/// timing, and whole runs. `threads` evaluate the contacts and the Jacobian's columns
/// (the result does not depend on them, bit for bit).
#[pyclass(name = "Model", module = "rollerdyn._core", frozen)]
pub struct PyModel {
    pub(crate) model: BearingModel,
    /// What the model's evaluations change (warm starts, profile) and its threads.
    pub(crate) workspace: Workspace,
}

impl PyModel {
    /// The model in its workspace.
    pub(crate) fn system(&self) -> BearingSystem<'_> {
        self.model.system(&self.workspace)
    }

    /// `y` checked to be a state of this model.
    fn state<'a>(&self, y: &'a [f64]) -> PyResult<&'a [f64]> {
        if y.len() != self.model.layout.len() {
            return Err(PyValueError::new_err(format!(
                "y has {} states: the model has {}",
                y.len(),
                self.model.layout.len()
            )));
        }
        Ok(y)
    }
}

#[pymethods]
impl PyModel {
    #[new]
    #[pyo3(signature = (params, traction, threads=1))]
    fn new(params: &Bound<'_, PyDict>, traction: &PyEhlTraction, threads: i64) -> PyResult<Self> {
        let threads = count("threads", threads, 1..=MAX_THREADS)?;
        let model =
            BearingModel::new(bearing_params(params, &traction.inner)?).map_err(core_err)?;
        let workspace = Workspace::new(&model, threads).map_err(core_err)?;
        Ok(PyModel { model, workspace })
    }

    /// Number of states.
    #[getter]
    fn states(&self) -> usize {
        self.model.layout.len()
    }

    /// Number of rollers.
    #[getter]
    fn rollers(&self) -> usize {
        self.model.layout.rollers
    }

    /// The state at rest on the pitch circle (`solver.start = "rest"`).
    fn initial_state(&self) -> PyResult<Vec<f64>> {
        self.system().initial_state().map_err(core_err)
    }

    /// The quasi-static equilibrium state at time t (`solver.start = "equilibrium"`).
    fn equilibrium_state(&self, t: f64) -> PyResult<Vec<f64>> {
        self.system().equilibrium_state(t).map_err(core_err)
    }

    /// The point end–flange law's load check of a run to time t, as a run makes it before
    /// its first step: a ValueError with the refusal, or None (`rollerdyn check` prints it).
    fn check_point_law(&self, t: f64) -> PyResult<()> {
        self.system().check_point_law(t).map_err(core_err)
    }

    /// f(t, y).
    fn rhs(&self, t: f64, y: Vec<f64>) -> PyResult<Vec<f64>> {
        let y = self.state(&y)?;
        let mut dy = vec![0.0; y.len()];
        self.system().rhs(t, y, &mut dy);
        Ok(dy)
    }

    /// ∂f/∂y at (t, y), row by row (n·n values).
    fn jacobian(&self, t: f64, y: Vec<f64>) -> PyResult<Vec<f64>> {
        let y = self.state(&y)?;
        let n = y.len();
        let mut jac = nalgebra::DMatrix::zeros(n, n);
        self.system().jacobian(t, y, &mut jac);
        Ok(jac.transpose().as_slice().to_vec())
    }

    /// Total mechanical energy at (t, y) [J].
    fn energy(&self, t: f64, y: Vec<f64>) -> PyResult<f64> {
        Ok(self.system().energy(t, self.state(&y)?))
    }

    /// Mean wall time of a right-hand side and a Jacobian at (t, y) (see `model_timing`).
    fn timing<'py>(
        &self,
        py: Python<'py>,
        t: f64,
        y: Vec<f64>,
        rhs_repetitions: i64,
        jacobian_repetitions: i64,
    ) -> PyResult<Bound<'py, PyDict>> {
        let y = self.state(&y)?;
        timing(
            py,
            &self.system(),
            t,
            y,
            rhs_repetitions,
            jacobian_repetitions,
        )
    }

    /// A whole run, as `simulate` (on the threads of the model's workspace).
    #[pyo3(signature = (options, progress=None, start=None, checkpoint=None))]
    fn run<'py>(
        &self,
        py: Python<'py>,
        options: &Bound<'py, PyDict>,
        progress: Option<Bound<'py, PyAny>>,
        start: Option<(f64, Vec<f64>, Option<f64>)>,
        checkpoint: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let (opts, _threads) = run_options(options)?;
        run_model(py, &self.system(), &opts, progress, start, checkpoint)
    }
}

/// Adds this module's functions to `m`.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyModel>()?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(initial_state, m)?)?;
    m.add_function(wrap_pyfunction!(equilibrium_state, m)?)?;
    m.add_function(wrap_pyfunction!(model_rhs, m)?)?;
    m.add_function(wrap_pyfunction!(model_timing, m)?)?;
    m.add_function(wrap_pyfunction!(model_energy, m)?)?;
    Ok(())
}
