//! A whole simulation: integrate the model and record what the figures need at every
//! output time; on a failure keep everything recorded so far and
//! say when and where it happened.

use super::contacts::ElementResult;
use super::params::FlangeLaw;
use super::profile::Profile;
use super::state::{azimuth, tilt_and_skew, Kinematics};
use super::topology::{Element, FLANGE_NAMES};
use super::workspace::BearingSystem;
use crate::contact::Pairing;
use crate::dynamics::integrate::{
    integrate, Checkpoint, Event, Method, Options, Start, Stats, StepControl,
};
use crate::geometry::primitives::Vec3;
use std::ops::ControlFlow;

/// Settings of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct RunOptions {
    /// End time [s].
    pub t_end: f64,
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance for lengths [m] (other states scaled, see
    /// [`BearingSystem::absolute_tolerances`]).
    pub atol: f64,
    /// Time over which a velocity error moves a body by `atol` [s]: velocities are held to
    /// atol / atol_time_scale (see [`BearingSystem::absolute_tolerances`]).
    pub atol_time_scale: f64,
    /// Δt_max [s].
    pub dt_max: f64,
    /// Output interval [s].
    pub output_interval: f64,
    /// Method.
    pub method: Method,
    /// Checkpoint interval [s]: the solver restarts every this much simulated time from
    /// t = 0, and a run resumed from a checkpoint equals the uninterrupted run bit for bit
    /// (see [`integrate`]); `None`: no checkpoints.
    pub checkpoint_interval: Option<f64>,
    /// Step-size control and Jacobian renewal of the solver.
    pub step_control: StepControl,
    /// Start (without a checkpoint) from the quasi-static equilibrium of the loads and speed
    /// at t = 0 ([`BearingSystem::equilibrium_state`]) instead of at rest on the pitch circle.
    pub start_from_equilibrium: bool,
    /// The least mean step over [`crate::dynamics::integrate::STALL_WINDOW`] steps [s]
    /// before the run fails as stalled (0: never; see the integrator's `Options`).
    pub min_mean_step: f64,
    /// Refuse, before the first step, a run with the point end–flange law whose loads
    /// press the most loaded roller end onto its end face
    /// ([`BearingSystem::check_point_law`]); `false` runs it anyway (the front end's
    /// `--force`), to creep or to stop as stalled.
    pub check_flange_law: bool,
    /// Keep each output's per-roller records ([`Record::rollers`]: the rollers', their
    /// contacts' and the flanges' outputs); `false` keeps only the bearing's own, so that
    /// a run of fine outputs holds a fraction of the memory ([`record_bytes`]).
    pub roller_records: bool,
}

/// Largest memory the records of one run may take [bytes]: a run that would record more
/// is refused before it starts (the front end refuses far less without `--force`).
pub const MAX_RECORD_BYTES: f64 = 8e9;

/// Wall time between progress reports between output times [s]: a slow run still shows
/// progress, and the front end reads signals at least this often between outputs.
pub const PROGRESS_EVERY: f64 = 0.2;

/// The shortest end time, maximum step, output and checkpoint interval a run takes [s]
/// (the configuration's floor of `dt_max` and `output_interval`).
pub const SHORTEST_INTERVAL: f64 = 1e-9;

impl RunOptions {
    /// Checks the settings before any work (the core never runs on a NaN tolerance or an
    /// output grid it cannot hold); `rollers` sizes the records, `t0` is the start time.
    pub fn validate(&self, rollers: usize, t0: f64) -> crate::Result<()> {
        let positive = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(crate::Error::invalid(
                    name,
                    v,
                    "must be a positive, finite number",
                ))
            }
        };
        // Times below 1 ns would not move the run's clock past its start (t + 1e-40 = t):
        // the run would loop without end.
        let interval = |name: &str, v: f64| {
            if v.is_finite() && v >= SHORTEST_INTERVAL {
                Ok(())
            } else {
                Err(crate::Error::invalid(name, v, "must be at least 1e-9 s"))
            }
        };
        interval("t_end", self.t_end)?;
        positive("atol", self.atol)?;
        positive("atol_time_scale", self.atol_time_scale)?;
        interval("dt_max", self.dt_max)?;
        interval("output_interval", self.output_interval)?;
        if !(self.rtol > 0.0 && self.rtol < 1.0) {
            return Err(crate::Error::invalid(
                "rtol",
                self.rtol,
                "must lie in (0, 1)",
            ));
        }
        if let Some(c) = self.checkpoint_interval {
            interval("checkpoint_interval", c)?;
        }
        if !(self.min_mean_step >= 0.0 && self.min_mean_step < self.dt_max) {
            return Err(crate::Error::invalid(
                "min_mean_step",
                self.min_mean_step,
                "must be >= 0 and below dt_max",
            ));
        }
        let control = &self.step_control;
        if !(control.max_growth > 1.0 && control.max_growth.is_finite()) {
            return Err(crate::Error::invalid(
                "max_step_growth",
                control.max_growth,
                "must be a finite number > 1",
            ));
        }
        if !(control.gain > 0.0 && control.gain <= 1.0) {
            return Err(crate::Error::invalid(
                "step_gain",
                control.gain,
                "must lie in (0, 1]",
            ));
        }
        let outputs = ((self.t_end - t0).max(0.0) / self.output_interval).ceil() + 2.0;
        let bytes = outputs * record_bytes(if self.roller_records { rollers } else { 0 });
        if bytes > MAX_RECORD_BYTES {
            return Err(crate::Error::invalid(
                "output_interval",
                format!("{} s", self.output_interval),
                format!(
                    "{outputs:.3e} outputs to t_end = {} s would take {:.3e} bytes; at most {MAX_RECORD_BYTES:.0e}",
                    self.t_end, bytes
                ),
            ));
        }
        Ok(())
    }
}

/// Memory of one output of a bearing with `rollers` rollers [bytes] (0: an output without
/// per-roller records, [`RunOptions::roller_records`]).
pub fn record_bytes(rollers: usize) -> f64 {
    (std::mem::size_of::<Record>() + rollers * std::mem::size_of::<RollerRecord>()) as f64
}

/// A checkpoint of a bearing run.
#[derive(Debug, Clone, PartialEq)]
pub struct RunCheckpoint {
    /// The integrator's checkpoint (time, state, next step, counters of this run).
    pub checkpoint: Checkpoint,
    /// The profile of the model's workspace until the checkpoint.
    pub profile: Profile,
    /// Number of records up to and including the checkpoint time.
    pub records: usize,
}

/// Outputs of one roller end / flange contact at one time.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct FlangeRecord {
    /// Active pairing (index in [`crate::contact::Pairing::ALL`]), −1 if none overlaps.
    pub pairing: i32,
    /// Penetration of the composite contact [m] (−∞ if no pairing is valid).
    pub penetration: f64,
    /// Contact location P_m [m] (zero without contact).
    pub location: Vec3,
    /// Normal force [N].
    pub normal_force: f64,
    /// Friction (tangential) force magnitude [N].
    pub friction_force: f64,
    /// Axial force on the roller (x) [N].
    pub axial_force: f64,
    /// Power the contact takes from the bodies' motion, and its parts [W].
    pub power: ContactPower,
    /// Pressure, film and sliding in the contact.
    pub lubrication: ContactLubrication,
}

/// The lubrication of one contact at one time, where its pressure is highest (the slice,
/// or the flange ellipse, of the largest maximum pressure;
/// [`super::contacts::Lubrication`]). Not among the
/// paper's outputs; all 0 where no section of the contact is in contact.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactLubrication {
    /// Maximum pressure p₀ [Pa] (eq. 17 of the slice; Hertz's 3F/(2πab) of the flange
    /// ellipse, with the distributed law that of the ellipse of equal second moments).
    pub max_pressure: f64,
    /// Central film thickness h_c there [m] (Moes, or the greater of Moes and ZEV between
    /// rollers, eqs. 33–44; Chittenden at a flange, eqs. 45, 46; thermally corrected, eq. 47).
    pub film: f64,
    /// Specific film thickness Λ = h_c/σ there, σ the contact's composite roughness (the
    /// ratio eq. 53 shares the load by).
    pub specific_film: f64,
    /// Sliding speed |u_B − u_A| there [m/s].
    pub sliding_speed: f64,
}

impl ContactLubrication {
    /// The lubrication of the result `r` of a contact of composite roughness `roughness`.
    fn of(r: &ElementResult, roughness: f64) -> Self {
        let l = r.lubrication;
        Self {
            max_pressure: l.max_pressure,
            film: l.film,
            specific_film: l.film / roughness,
            sliding_speed: l.sliding_speed,
        }
    }
}

/// The power one contact takes from the motion of its two bodies [W]
/// ([`ElementResult::power_loss`]; its time mean is the contact's power loss), and its
/// parts by mechanism; the normal forces' part is the rest, `loss − sliding − rolling`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactPower {
    /// All of it.
    pub loss: f64,
    /// Sliding: traction, boundary friction and the films' shear
    /// ([`ElementResult::sliding_power`]).
    pub sliding: f64,
    /// Rolling resistance: what the sliding and the normal forces
    /// ([`ElementResult::normal_power`]) leave (round-off where the contact has none, as at
    /// the flanges).
    pub rolling: f64,
}

impl ContactPower {
    /// The power the contact with result `r` takes from bodies `a` and `b`, relative to the
    /// outer ring `outer`, split.
    fn of(r: &ElementResult, a: &Kinematics, b: &Kinematics, outer: &Kinematics) -> Self {
        let loss = r.power_loss(a, b, outer);
        Self {
            loss,
            sliding: r.sliding_power,
            rolling: loss - r.sliding_power - r.normal_power,
        }
    }
}

/// Outputs of one roller at one time.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct RollerRecord {
    /// Azimuth ψ from +y towards +z [rad].
    pub azimuth: f64,
    /// Centre [m].
    pub position: Vec3,
    /// Tilt [rad] (axis towards radial).
    pub tilt: f64,
    /// Skew [rad] (axis towards circumferential).
    pub skew: f64,
    /// Spin speed ω·a [rad/s].
    pub spin_speed: f64,
    /// Orbital speed about the bearing axis [rad/s].
    pub orbital_speed: f64,
    /// Slide-to-roll ratio at the inner race (eq. 49, 1 = race, 2 = roller, mid-roller).
    pub srr_inner: f64,
    /// Slide-to-roll ratio at the outer race.
    pub srr_outer: f64,
    /// Inner race normal force (sum over slices) [N].
    pub inner_normal: f64,
    /// Outer race normal force [N].
    pub outer_normal: f64,
    /// Inner race tangential force on the roller, magnitude of the slice sum [N].
    pub inner_tangential: f64,
    /// Outer race tangential force [N].
    pub outer_tangential: f64,
    /// Normal force between this roller and the next [N].
    pub pair_normal: f64,
    /// Tangential force between this roller and the next [N].
    pub pair_tangential: f64,
    /// Power the inner race contact takes from the motion, and its parts [W].
    pub inner_power: ContactPower,
    /// The same of the outer race contact [W].
    pub outer_power: ContactPower,
    /// The same of the contact between this roller and the next [W].
    pub pair_power: ContactPower,
    /// Power the drag of the oil–air mixture takes from this roller's motion [W].
    pub drag_power_loss: f64,
    /// Pressure, film and sliding at the inner race.
    pub inner_lubrication: ContactLubrication,
    /// The same at the outer race.
    pub outer_lubrication: ContactLubrication,
    /// The same between this roller and the next.
    pub pair_lubrication: ContactLubrication,
    /// The four roller end / flange contacts (see [`FLANGE_NAMES`]).
    pub flanges: [FlangeRecord; 4],
}

/// Outputs of the bearing at one time.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    /// Time [s].
    pub time: f64,
    /// Inner ring centre [m].
    pub ring_position: Vec3,
    /// Inner ring axis angles (θ_y, θ_z) [rad] (zero when tilt is locked).
    pub ring_tilt: (f64, f64),
    /// Inner ring speed [rad/s].
    pub ring_speed: f64,
    /// Outer ring speed [rad/s] about +x.
    pub outer_ring_speed: f64,
    /// The planet carrier's speed Ω_c [rad/s] about +x ([`crate::bearing::params::Carrier`]):
    /// every other output is seen from the carrier; 0 where it stands.
    pub carrier_speed: f64,
    /// Radial and axial load applied [N].
    pub loads: (f64, f64),
    /// Bearing frictional torque: the moment of all contact forces on the inner ring about
    /// its axis, positive when it resists the inner ring's rotation relative to the outer
    /// ring (a positive one where the two stand or turn alike) [N m].
    pub frictional_torque: f64,
    /// The moment of all contact forces on the outer ring about +x, as it comes [N m]: the
    /// reaction to the frictional torque, less what the drag and the rollers' inertia take.
    pub outer_ring_torque: f64,
    /// Power taken from the bodies' motion by every contact and the drag [W]: in steady
    /// running its mean is the friction power, the frictional torque times the ring speed.
    pub power_loss: f64,
    /// Of it, by mechanism over every contact [W]: sliding (traction, boundary friction,
    /// film shear), the normal forces (elastic storage, damping, the films' normal load)
    /// and the rest, the rolling resistance's couples and forces; the drag is the remainder.
    pub power_by_mechanism: PowerByMechanism,
    /// Per roller.
    pub rollers: Vec<RollerRecord>,
}

/// What the contacts take from the motion, by mechanism [W] ([`Record::power_loss`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PowerByMechanism {
    /// Sliding: traction, boundary friction and the films' shear ([`ElementResult::sliding_power`]).
    pub sliding: f64,
    /// The normal forces ([`ElementResult::normal_power`]).
    pub normal: f64,
    /// Rolling resistance: what remains of the contacts' power.
    pub rolling: f64,
}

/// The result of a run, complete or not.
#[derive(Debug, Clone)]
pub struct RunOutput {
    /// Records at the output times.
    pub records: Vec<Record>,
    /// Solver counters.
    pub stats: Stats,
    /// Where the right-hand-side time went.
    pub profile: Profile,
    /// The last state (for a restart).
    pub final_state: Vec<f64>,
    /// Time of the last state [s].
    pub final_time: f64,
    /// Why the run stopped early, if it did (says when and where).
    pub error: Option<String>,
    /// True if the progress callback stopped the run.
    pub interrupted: bool,
    /// The last checkpoint reached, or the start (step NaN if fresh, zero counters, the
    /// profile of the consistent initial state's evaluation): where a resumed run begins.
    pub checkpoint: RunCheckpoint,
}

/// What the progress callback sees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// Simulated time reached [s].
    pub time: f64,
    /// End time [s].
    pub t_end: f64,
    /// Counters.
    pub stats: Stats,
    /// At an output time (false: a report between outputs, see [`PROGRESS_EVERY`]).
    pub at_output: bool,
}

/// Runs the bearing (a model in its workspace) from `start` (or its consistent initial
/// state at t = 0) to `options.t_end`. `progress` is called at every output time (and
/// every [`PROGRESS_EVERY`] of wall time between them) and `checkpoint` at every
/// checkpoint (with the records so far); either may stop the run. A start with a step
/// continues from a checkpoint: its output at the start time is not repeated.
pub fn run(
    system: &BearingSystem<'_>,
    start: Option<Start>,
    options: &RunOptions,
    mut progress: impl FnMut(&Progress) -> ControlFlow<()>,
    mut checkpoint: impl FnMut(&RunCheckpoint, &[Record]) -> ControlFlow<()>,
) -> crate::Result<RunOutput> {
    options.validate(
        system.layout.rollers,
        start.as_ref().map_or(0.0, |s| s.time),
    )?;
    let start = checked_start(system, start, options)?;
    let (t0, y0) = (start.time, &start.state);
    let settings = Options {
        rtol: options.rtol,
        atol: system.absolute_tolerances(options.atol, options.atol_time_scale),
        dt_max: options.dt_max,
        dt_initial: options.dt_max.min(1e-6),
        output_interval: options.output_interval,
        method: options.method,
        origin: 0.0,
        checkpoint_interval: options.checkpoint_interval,
        step_control: options.step_control,
        min_mean_step: options.min_mean_step,
    };
    let mut records = Vec::new();
    let mut last = (t0, y0.clone());
    let mut interrupted = false;
    let mut reported = std::time::Instant::now();
    let mut reached = RunCheckpoint {
        checkpoint: Checkpoint {
            time: t0,
            state: y0.clone(),
            step: start.step.unwrap_or(f64::NAN),
            stats: Stats::default(),
        },
        profile: system.profile(),
        records: 0,
    };
    let outcome = integrate(system, &start, options.t_end, &settings, |event| {
        let flow = match event {
            Event::Output { time, state, stats } => {
                let mut output = record(system, time, state);
                if !options.roller_records {
                    output.rollers = Vec::new();
                }
                records.push(output);
                last = (time, state.to_vec());
                reported = std::time::Instant::now();
                progress(&Progress {
                    time,
                    t_end: options.t_end,
                    stats: *stats,
                    at_output: true,
                })
            }
            Event::Step { time, stats } => {
                if reported.elapsed().as_secs_f64() < PROGRESS_EVERY {
                    return ControlFlow::Continue(());
                }
                reported = std::time::Instant::now();
                progress(&Progress {
                    time,
                    t_end: options.t_end,
                    stats: *stats,
                    at_output: false,
                })
            }
            Event::Checkpoint(c) => {
                let r = RunCheckpoint {
                    checkpoint: c.clone(),
                    profile: system.profile(),
                    records: records.len(),
                };
                let flow = checkpoint(&r, &records);
                reached = r;
                flow
            }
        };
        interrupted = flow.is_break();
        flow
    });
    Ok(match outcome {
        Ok(stats) => RunOutput {
            records,
            stats,
            profile: system.profile(),
            final_state: last.1,
            final_time: last.0,
            error: None,
            interrupted,
            checkpoint: reached,
        },
        Err(failure) => RunOutput {
            error: Some(format!(
                "the integration failed at t = {} s: {}; {}",
                super::statics::shown(failure.time),
                failure.message,
                diagnose(system, failure.time, &failure.state)
            )),
            records,
            stats: *failure.stats,
            profile: system.profile(),
            final_state: last.1,
            final_time: last.0,
            interrupted,
            checkpoint: reached,
        },
    })
}

/// The run's start: `start` (a checkpoint's) or the consistent initial state at t = 0
/// (from rest, or from the quasi-static equilibrium with
/// [`RunOptions::start_from_equilibrium`]), checked: the model's number of finite states,
/// every body inside the bearing, a positive step. A point-law run the flanges cannot
/// carry at its end time is refused first ([`BearingSystem::check_point_law`]), a resumed
/// one too: continued to a later end time, it reaches loads its first part did not.
fn checked_start(
    system: &BearingSystem<'_>,
    start: Option<Start>,
    options: &RunOptions,
) -> crate::Result<Start> {
    if options.check_flange_law {
        system.check_point_law(options.t_end)?;
    }
    let start = match start {
        Some(s) => s,
        None => Start {
            time: 0.0,
            state: if options.start_from_equilibrium {
                system.equilibrium_state(0.0)?
            } else {
                system.initial_state()?
            },
            step: None,
        },
    };
    let (t0, y0) = (start.time, &start.state);
    let n = system.layout.len();
    if y0.len() != n || !y0.iter().all(|v| v.is_finite()) || !t0.is_finite() {
        return Err(crate::Error::invalid(
            "start state",
            format!("{} values at t = {t0}", y0.len()),
            format!("must be {n} finite values, the state of this model (same rollers and ring tilt mode)"),
        ));
    }
    if let Some(outside) = left_the_bearing(system, t0, y0) {
        // A start outside the bearing (a tampered checkpoint) has no step the solver could
        // take: it would shrink its steps for ever inside one attempt.
        return Err(crate::Error::invalid(
            "start state",
            format!("t = {t0}"),
            format!("must place every body inside the bearing: {outside}"),
        ));
    }
    if let Some(h) = start.step.filter(|h| !(h.is_finite() && *h > 0.0)) {
        return Err(crate::Error::invalid(
            "start step",
            format!("{h} s"),
            "must be a positive step size (a checkpoint's)",
        ));
    }
    Ok(start)
}

/// Evaluates the outputs at (t, y).
pub fn record(system: &BearingSystem<'_>, t: f64, y: &[f64]) -> Record {
    let kin = system.kinematics(t, y);
    let results = system.evaluate_all(&kin);
    let loads = system.loads(&results);
    let ring = kin.inner_ring;
    let layout = system.layout;
    let ring_tilt = if layout.tilt_free {
        (y[6], y[7])
    } else {
        (0.0, system.params.inner_ring_misalignment)
    };
    let mut rollers = vec![RollerRecord::default(); layout.rollers];
    let mut power_loss = 0.0;
    let mut by_mechanism = PowerByMechanism::default();
    for (element, r) in system.elements().iter().zip(&results) {
        let [a, b] = element.bodies(layout.rollers);
        let power = ContactPower::of(r, kin.of(a), kin.of(b), &kin.outer_ring);
        power_loss += power.loss;
        by_mechanism.sliding += power.sliding;
        by_mechanism.normal += r.normal_power;
        by_mechanism.rolling += power.rolling;
        let roughness = match element.line() {
            Some(line) => system.lines.kind(line).roughness,
            None => system.ellipse.roughness,
        };
        let lubrication = ContactLubrication::of(r, roughness);
        fill(&mut rollers, element, r, power, lubrication);
    }
    for (i, rec) in rollers.iter_mut().enumerate() {
        let k = &kin.rollers[i];
        rec.drag_power_loss = -system.roller_drag(k).power(k);
        power_loss += rec.drag_power_loss;
        rec.azimuth = azimuth(&k.center);
        rec.position = k.center;
        (rec.tilt, rec.skew) = tilt_and_skew(&k.center, &k.axis);
        rec.spin_speed = k.omega.dot(&k.axis);
        rec.orbital_speed = k.orbital_speed();
        rec.srr_inner = slide_to_roll(system, &ring, k, true);
        rec.srr_outer = slide_to_roll(system, &kin.outer_ring, k, false);
    }
    Record {
        time: t,
        ring_position: ring.center,
        ring_tilt,
        ring_speed: system.params.inner_ring_speed.at(t).0,
        outer_ring_speed: kin.outer_ring.omega.x,
        carrier_speed: system.params.carrier.speed.at(t).0,
        loads: (
            system.params.radial_load.at(t).0,
            system.params.axial_load.at(t).0,
        ),
        frictional_torque: -relative_sense(ring.omega.dot(&ring.axis), kin.outer_ring.omega.x)
            * loads.inner_ring.moment.dot(&ring.axis),
        outer_ring_torque: loads.outer_ring.moment.x,
        power_loss,
        power_by_mechanism: by_mechanism,
        rollers,
    }
}

/// The sense of the inner ring's rotation relative to the outer ring: −1 where it turns
/// backwards relative to it (an outer ring turning faster, as in a planet gear), else 1.
fn relative_sense(inner_speed: f64, outer_speed: f64) -> f64 {
    if inner_speed < outer_speed {
        -1.0
    } else {
        1.0
    }
}

/// Roller records from the result `r` of `element`, which takes `power` [W] and has
/// `lubrication`.
fn fill(
    rollers: &mut [RollerRecord],
    element: &Element,
    r: &ElementResult,
    power: ContactPower,
    lubrication: ContactLubrication,
) {
    match *element {
        Element::Inner(i) => {
            rollers[i].inner_normal = r.normal;
            rollers[i].inner_tangential = r.tangential.norm();
            rollers[i].inner_power = power;
            rollers[i].inner_lubrication = lubrication;
        }
        Element::Outer(i) => {
            rollers[i].outer_normal = r.normal;
            rollers[i].outer_tangential = r.tangential.norm();
            rollers[i].outer_power = power;
            rollers[i].outer_lubrication = lubrication;
        }
        Element::Pair(i) => {
            rollers[i].pair_normal = r.normal;
            rollers[i].pair_tangential = r.tangential.norm();
            rollers[i].pair_power = power;
            rollers[i].pair_lubrication = lubrication;
        }
        Element::End(i, k) => {
            rollers[i].flanges[k] = FlangeRecord {
                pairing: r.pairing.map_or(-1, |p| p as i32),
                penetration: r.penetration,
                location: r.location,
                normal_force: r.normal,
                friction_force: r.tangential.norm(),
                axial_force: r.on_b.force.x,
                power,
                lubrication,
            };
        }
    }
}

/// Kinematic slide-to-roll ratio (eq. 49) at the middle of a roller against a race:
/// S = 2(u_roller − u_race)/(u_race + u_roller), rolling components relative to the
/// contact frame; 0 where both surfaces stand still.
fn slide_to_roll(
    system: &BearingSystem<'_>,
    race: &Kinematics,
    roller: &Kinematics,
    inner: bool,
) -> f64 {
    let d = roller.center - race.center;
    let out = (d - d.dot(&race.axis) * race.axis).normalize();
    let r = system.params.roller.radius;
    let (n, p) = if inner {
        (out, roller.center - out * r)
    } else {
        (-out, roller.center + out * r)
    };
    let rolling = n.cross(&roller.axis).normalize();
    let frame = roller.frame_velocity(&p);
    let u1 = (race.point_velocity(&p) - frame).dot(&rolling);
    let u2 = (roller.point_velocity(&p) - frame).dot(&rolling);
    let sum = u1 + u2;
    if sum.abs() < 1e-9 {
        0.0
    } else {
        2.0 * (u2 - u1) / sum
    }
}

/// Says where a failed run went wrong: non-finite states, a roller that left the
/// bearing, or the deepest contact and the body with the largest acceleration.
pub fn diagnose(system: &BearingSystem<'_>, t: f64, y: &[f64]) -> String {
    let layout = system.layout;
    if let Some(k) = y.iter().position(|v| !v.is_finite()) {
        return match layout.body_of(k) {
            None => format!("inner ring state {k} is not finite"),
            Some(i) => format!("roller {i} state {} is not finite", k - layout.roller(i)),
        };
    }
    if let Some(outside) = left_the_bearing(system, t, y) {
        return outside;
    }
    let kin = system.kinematics(t, y);
    let results = system.evaluate_all(&kin);
    let (deepest, result) = system
        .elements()
        .iter()
        .zip(&results)
        .max_by(|a, b| a.1.penetration.total_cmp(&b.1.penetration))
        .expect("a bearing has contacts");
    let name = match *deepest {
        Element::End(i, k) => format!("roller {i} end / flange {}", FLANGE_NAMES[k]),
        other => format!("{other:?}"),
    };
    format!(
        "deepest contact: {name}, penetration {:.3e} m, normal force {:.3e} N{}",
        result.penetration,
        result.normal,
        flat_end_hint(system, &results)
    )
}

/// Which body, if any, lies outside the bearing in state `y` at `t`: a roller whose centre
/// is not between the raceways or is an axial roller length off the middle, or whose axis
/// leans by more than 25° from the bearing's; the inner ring displaced by more than a
/// roller radius.
fn left_the_bearing(system: &BearingSystem<'_>, t: f64, y: &[f64]) -> Option<String> {
    let kin = system.kinematics(t, y);
    let p = &system.params;
    let ring = kin.inner_ring.center;
    if ring.norm() > p.roller.radius {
        return Some(format!(
            "the inner ring left the bearing (centre displaced by {:.3e} m, more than the \
             roller radius {:.3e} m)",
            ring.norm(),
            p.roller.radius
        ));
    }
    for (i, k) in kin.rollers.iter().enumerate() {
        let rho = (k.center.y.powi(2) + k.center.z.powi(2)).sqrt();
        let radial_ok = rho > p.inner_raceway_radius && rho < p.outer_raceway_radius;
        let axial_ok = k.center.x.abs() < p.roller.length;
        if !(radial_ok && axial_ok) || k.axis.x.abs() < 0.9 {
            return Some(format!(
                "roller {i} left the bearing (centre at x = {:.3e} m, radius {:.3e} m; raceways {:.3e}..{:.3e} m; axis {:?})",
                k.center.x, rho, p.inner_raceway_radius, p.outer_raceway_radius, k.axis.as_slice()
            ));
        }
    }
    None
}

/// With the point law, a note on the roller ends that press a flange with their end
/// sphere (SP-CO, SP-TO): there the nearly flat face lies almost parallel to the flange
/// and the point contact jumps across it, which collapses the steps (docs/dynamics.md,
/// "Why the steps collapse at 2000 N"). Empty otherwise.
fn flat_end_hint(system: &BearingSystem<'_>, results: &[ElementResult]) -> String {
    if system.params.flange_law != FlangeLaw::Point {
        return String::new();
    }
    let on_sphere = |pairing: usize| {
        matches!(
            Pairing::ALL[pairing],
            Pairing::SphereCone | Pairing::SphereRoot | Pairing::SphereRim
        )
    };
    let mut ends: Vec<(f64, String)> = system
        .elements()
        .iter()
        .zip(results)
        .filter_map(|(element, r)| match (*element, r.pairing) {
            (Element::End(i, k), Some(p)) if on_sphere(p) && r.normal > 0.0 => Some((
                r.normal,
                format!(
                    "roller {i} on flange {}, {}, {:.3} N",
                    FLANGE_NAMES[k],
                    Pairing::ALL[p].label(),
                    r.normal
                ),
            )),
            _ => None,
        })
        .collect();
    if ends.is_empty() {
        return String::new();
    }
    ends.sort_by(|a, b| b.0.total_cmp(&a.0));
    let named: Vec<&str> = ends.iter().take(3).map(|(_, e)| e.as_str()).collect();
    format!(
        "; {} roller end(s) press a flange with the end sphere (the most loaded: {}): the \
         point law's contact jumps across the nearly flat end face there (docs/dynamics.md, \
         \"Why the steps collapse at 2000 N\"); surfaces.flange_law = \"distributed\" \
         spreads it over the face",
        ends.len(),
        named.join("; ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn options() -> RunOptions {
        RunOptions {
            t_end: 1.288,
            rtol: 1e-5,
            atol: 1e-9,
            atol_time_scale: 1e-5,
            dt_max: 1e-4,
            output_interval: 1e-3,
            method: Method::TrBdf2,
            checkpoint_interval: Some(0.1),
            step_control: StepControl::default(),
            start_from_equilibrium: false,
            min_mean_step: 2e-8,
            check_flange_law: true,
            roller_records: true,
        }
    }

    #[test]
    fn the_b1_settings_pass() {
        assert!(options().validate(17, 0.0).is_ok());
    }

    /// The core never runs on a NaN tolerance or a step it cannot take: each
    /// bad setting is refused with its name.
    #[test]
    fn nan_negative_and_infinite_settings_are_refused_by_name() {
        type Change = fn(&mut RunOptions);
        let cases: [(&str, Change); 11] = [
            ("rtol", |o| o.rtol = f64::NAN),
            ("rtol", |o| o.rtol = -1.0),
            ("atol", |o| o.atol = 0.0),
            ("dt_max", |o| o.dt_max = f64::NAN),
            ("output_interval", |o| o.output_interval = -1.0),
            ("t_end", |o| o.t_end = f64::INFINITY),
            ("checkpoint_interval", |o| {
                o.checkpoint_interval = Some(f64::NAN)
            }),
            ("max_step_growth", |o| o.step_control.max_growth = 1.0),
            // below 1 ns a checkpoint or the end would not move the clock: a run without end
            ("checkpoint_interval", |o| {
                o.checkpoint_interval = Some(1e-30)
            }),
            ("t_end", |o| o.t_end = 1e-40),
            ("output_interval", |o| o.output_interval = 1e-12),
        ];
        for (name, change) in cases {
            let mut o = options();
            change(&mut o);
            let message = o.validate(17, 0.0).unwrap_err().to_string();
            assert!(message.contains(name), "{name}: {message}");
        }
    }

    /// An output grid whose records would not fit in memory is refused before the run
    /// allocates them: 1 ns over B1's 1.288 s is 1.3e9 outputs of 17 rollers.
    #[test]
    fn an_output_grid_beyond_memory_is_refused() {
        let mut o = options();
        o.output_interval = 1e-9;
        let message = o.validate(17, 0.0).unwrap_err().to_string();
        assert!(message.contains("output_interval") && message.contains("bytes"));
        // the same interval over a short span is fine: the limit is the records' memory
        o.t_end = 1e-6;
        assert!(o.validate(17, 0.0).is_ok());
    }

    /// Without per-roller records an output holds the bearing's own outputs only, so the
    /// bound admits a grid that the full records would not: 1 µs over 13 s is 1.3e7
    /// outputs, above 8 GB with 17 rollers' records and a few GB without.
    #[test]
    fn an_output_grid_without_roller_records_is_bounded_by_what_it_keeps() {
        let mut o = options();
        (o.output_interval, o.t_end) = (1e-6, 13.0);
        assert!(o.validate(17, 0.0).is_err());
        o.roller_records = false;
        assert!(o.validate(17, 0.0).is_ok());
    }
}
