//! The time-integration driver: a stiff, adaptive, error-controlled solver (diffsol's
//! L-stable singly diagonally implicit Runge–Kutta methods TR-BDF2 and ESDIRK34) for
//! any system y' = f(t, y) that supplies its own Jacobian. It knows nothing of bearings.
//!
//! Results are delivered at fixed output times by the solver's dense output
//! (interpolation), not at solver steps (docs/dynamics.md, "Outputs"), so they do not depend on
//! the step size. Δt_max caps every step.
//!
//! Checkpoints: with a checkpoint interval the integration restarts its
//! solver from (t, y, h) at fixed times, in every run; a run resumed from a checkpoint
//! takes the same path from there and so equals the uninterrupted run bit for bit.

use super::sparse_lu::SparseSkipLu;
use diffsol::ode_solver::OdeSolverStatistics;
use diffsol::{NalgebraMat, OdeBuilder, OdeSolverMethod, OdeSolverStopReason, Vector};
use nalgebra::DMatrix;
use std::cell::RefCell;
use std::ops::ControlFlow;
use std::time::Instant;

/// Smallest step before the run is declared failed (step-size collapse) [s].
pub const MIN_STEP: f64 = 1e-13;
/// A step this short that ends a segment is round-off, not the solver's choice: the next
/// segment does not start from it ([`integrate`]) [s].
const STEP_SLIVER: f64 = 1e3 * MIN_STEP;

/// A first-order system y' = f(t, y) with an analytic or structured Jacobian.
pub trait OdeSystem {
    /// Number of states.
    fn len(&self) -> usize;
    /// True if there are no states.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// f(t, y) into `dy`.
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]);
    /// ∂f/∂y at (t, y) into `jac` (n × n, every entry written).
    fn jacobian(&self, t: f64, y: &[f64], jac: &mut DMatrix<f64>);
    /// Forgets whatever the system remembers between calls (warm starts of inner
    /// iterations), as if newly built. [`integrate`] calls it at every (re)start, so that a
    /// run resumed from a checkpoint computes what the uninterrupted run computed.
    fn restart(&self) {}
    /// Told after every accepted step, when the solver has evaluated all it will of it: a
    /// system may take what its latest evaluation found as the start of the next step's
    /// evaluations (inner iterations' starting points), which every evaluation of that
    /// step then shares, so that within a step f stays one function of (t, y).
    fn step_accepted(&self) {}
    /// Renews in `jac` (∂f/∂y at an earlier state) only the columns of the states coupled
    /// to `states`, at (t, y), and keeps the others; returns `false`, leaving `jac` as it
    /// is, if the system cannot (the caller then computes the whole Jacobian). Used after
    /// a failed Newton iteration whose updates were largest in `states`
    /// ([`StepControl::partial_jacobians`]).
    fn partial_jacobian(
        &self,
        _t: f64,
        _y: &[f64],
        _states: &[usize],
        _jac: &mut DMatrix<f64>,
    ) -> bool {
        false
    }
}

/// The implicit method.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// TR-BDF2 (Bank et al. 1985; Hosea & Shampine 1996): L-stable, order 2, embedded
    /// order-3 error estimate.
    TrBdf2,
    /// ESDIRK34 (Jørgensen, Kristensen, Thomsen 2018): L-stable, order 3.
    Esdirk34,
}

/// How the step size follows the error estimate, and when the Newton iteration's Jacobian
/// is renewed (diffsol's solver options; see docs/dynamics.md, "Step-size control").
///
/// The step-size factor is diffsol's: h_new = h · 0.9·s · err^(−k/(q+1)), with err the
/// error estimate (1 at the tolerance), q its order, k the `gain` and s ≤ 1 a safety factor
/// that falls with the Newton iterations the step took; a proposed growth below 2 is not
/// taken (the Newton matrix is kept), and no step grows by more than `max_growth`.
/// diffsol's PI variant (a proportional gain on the previous error) is not offered: in
/// diffsol 0.18 it computes ∞·0 = NaN when two error estimates in a row are exactly zero
/// (a body in free flight is integrated exactly), and the run then never ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepControl {
    /// Largest factor by which a step may exceed the one before (diffsol's default: 2).
    pub max_growth: f64,
    /// Gain k of the step-size controller (diffsol's default: 0.5).
    pub gain: f64,
    /// After a first Newton failure at an unchanged step size, evaluate the Jacobian anew
    /// before the retry (diffsol's default). `false`: retry with the Newton matrix as it is
    /// and cut the step if that fails too, keeping Jacobians for when the step changed.
    pub jacobian_after_newton_failure: bool,
    /// Take each Jacobian at the state of the latest right-hand side (the last Newton
    /// iterate) instead of at the state diffsol names (the step's start). After a first
    /// Newton failure diffsol renews the Jacobian at the start of the failed step, which,
    /// when the step crossed a change of the dynamics (a contact that closed, a pairing
    /// that changed), linearises the same side of it as the Jacobian that failed; the last
    /// iterate lies beyond it. A scheduled renewal after an accepted step names the new
    /// state, which the last iterate of its last stage approaches. The Newton matrix is
    /// only the iteration's; the residuals, and so the solution, are unchanged. `false`:
    /// diffsol's own.
    pub jacobian_at_latest_iterate: bool,
    /// After a failed Newton iteration, renew only the Jacobian's columns of the states
    /// that its last update moved most ([`OdeSystem::partial_jacobian`]), at most this
    /// many times in a row before the whole Jacobian is renewed again; 0: always the
    /// whole. Needs `jacobian_at_latest_iterate` (the failed iterate is where the columns
    /// are taken). The failures at B1's full speed come from a few rollers (their tilt,
    /// skew and spin rates), whose columns cost a part of the whole Jacobian.
    pub partial_jacobians: usize,
}

impl StepControl {
    /// diffsol's own settings.
    pub const DIFFSOL: StepControl = StepControl {
        max_growth: 2.0,
        gain: 0.5,
        jacobian_after_newton_failure: true,
        jacobian_at_latest_iterate: false,
        partial_jacobians: 0,
    };
}

impl Default for StepControl {
    /// rollerdyn's settings, chosen by measurement on the whole B1 run (docs/performance-log.md,
    /// "Step-size control: the tuning"): the growth cap and gain before the oil film (74 s
    /// against 152 s with [`StepControl::DIFFSOL`]); the Jacobian renewed after a first
    /// Newton failure since the film's suction limit (30 812 steps against 36 380 kept);
    /// at most two partial renewals in a row (the whole run's work in right-hand sides,
    /// Jacobians counted as what they took, 11 % lower).
    fn default() -> Self {
        StepControl {
            max_growth: 1.3,
            gain: 0.3,
            jacobian_after_newton_failure: true,
            jacobian_at_latest_iterate: true,
            partial_jacobians: 2,
        }
    }
}

/// Settings of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance per state (or one value for all).
    pub atol: Vec<f64>,
    /// Largest step Δt_max [s].
    pub dt_max: f64,
    /// First step [s].
    pub dt_initial: f64,
    /// Output interval [s].
    pub output_interval: f64,
    /// Method.
    pub method: Method,
    /// Time origin of the output and checkpoint grids [s] (outputs at origin + k·Δt_out).
    pub origin: f64,
    /// Checkpoint interval Δt_c [s]: the solver restarts at origin + j·Δt_c (see
    /// [`integrate`]); `None`: one segment, no checkpoints.
    pub checkpoint_interval: Option<f64>,
    /// Step-size control and Jacobian renewal.
    pub step_control: StepControl,
    /// The run fails when [`STALL_WINDOW`] steps in a row advance the time by less than
    /// this mean step [s] (0: never): a run whose steps have collapsed to nanoseconds
    /// would otherwise go on for days.
    pub min_mean_step: f64,
}

/// Steps over which the mean step is compared with [`Options::min_mean_step`].
pub const STALL_WINDOW: usize = 10_000;

/// What the solver did.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Stats {
    /// Accepted steps.
    pub steps: usize,
    /// Right-hand-side evaluations (outside the Jacobian).
    pub rhs_evaluations: usize,
    /// Jacobian evaluations.
    pub jacobian_evaluations: usize,
    /// Wall time in right-hand sides [s].
    pub rhs_seconds: f64,
    /// Wall time in Jacobians [s].
    pub jacobian_seconds: f64,
    /// Wall time of the whole integration [s].
    pub total_seconds: f64,
    /// Time reached [s].
    pub t_reached: f64,
    /// The last step size [s].
    pub last_step: f64,
    /// Steps rejected by the local error test (diffsol's statistics).
    pub error_test_failures: usize,
    /// Newton convergence failures (each followed by a Jacobian update or a smaller step).
    pub newton_failures: usize,
    /// Newton iterations over all stages and steps.
    pub newton_iterations: usize,
    /// Newton matrices I − hγJ assembled and factorised (diffsol's linear solver setups:
    /// after a new Jacobian, a change of step size beyond diffsol's threshold, or a failure).
    pub linear_solver_setups: usize,
    /// Jacobians renewed only in part ([`StepControl::partial_jacobians`]; also counted
    /// in `jacobian_evaluations`).
    pub partial_jacobians: usize,
}

/// Why an integration stopped early.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    /// Time reached [s].
    pub time: f64,
    /// The solver's message.
    pub message: String,
    /// Counters until the failure (boxed: keeps the error small).
    pub stats: Box<Stats>,
    /// The last accepted state.
    pub state: Vec<f64>,
}

struct Counters<'s, S: OdeSystem> {
    system: &'s S,
    stats: Stats,
    key: Vec<f64>,
    key_t: f64,
    /// Right-hand sides evaluated when the Jacobian of the key was computed.
    key_rhs: usize,
    jac: DMatrix<f64>,
    /// Take the Jacobian at the latest right-hand side's state ([`StepControl`]).
    at_latest_iterate: bool,
    /// The state of the latest right-hand side (empty: none since the segment began, or
    /// not finite) and its time.
    latest: Vec<f64>,
    latest_t: f64,
    /// The state of the right-hand side before the latest (empty: none).
    previous: Vec<f64>,
    /// The error weights: absolute tolerance per state and the relative tolerance.
    atol: Vec<f64>,
    rtol: f64,
    /// Partial renewals allowed in a row ([`StepControl::partial_jacobians`]).
    partial_limit: usize,
    /// Partial renewals since the last whole Jacobian.
    partial_streak: usize,
    /// `jac` holds a Jacobian of this segment (a partial renewal builds on it).
    jac_valid: bool,
}

/// A Jacobian is asked for after a failed Newton iteration when the latest iterate lies
/// this far (RMS, in error weights) from the state named: a renewal after an accepted
/// step names the step's end, which its last iterate approaches to within the Newton
/// tolerance (0.2); a failed step's iterate lies a step's change away (B1 at full speed,
/// all renewals over 0–60 ms: a median of 10, more than 1 for 528 of 552).
const FAILED_ITERATE_DISTANCE: f64 = 1.0;

/// The states whose share of the failed iteration's last update, in error weights, is at
/// least this fraction of the largest are the ones renewed.
const CULPRIT_FRACTION: f64 = 0.1;

impl<'s, S: OdeSystem> Counters<'s, S> {
    /// The counters of a run of `system` with `options`, nothing counted yet.
    fn new(system: &'s S, options: &Options) -> Self {
        let n = system.len();
        let control = &options.step_control;
        Self {
            system,
            stats: Stats::default(),
            key: Vec::with_capacity(n),
            key_t: f64::NAN,
            key_rhs: 0,
            jac: DMatrix::zeros(n, n),
            at_latest_iterate: control.jacobian_at_latest_iterate,
            latest: Vec::with_capacity(n),
            latest_t: f64::NAN,
            previous: Vec::with_capacity(n),
            atol: if options.atol.len() == n {
                options.atol.clone()
            } else {
                vec![options.atol.first().copied().unwrap_or(0.0); n]
            },
            rtol: options.rtol,
            partial_limit: if control.jacobian_at_latest_iterate {
                control.partial_jacobians
            } else {
                0
            },
            partial_streak: 0,
            jac_valid: false,
        }
    }

    /// Forgets the Jacobian and the iterates (a segment starts with a fresh solver, as a
    /// run resumed there does); keeps the counts.
    fn start_segment(&mut self) {
        self.key.clear();
        self.key_t = f64::NAN;
        self.latest.clear();
        self.previous.clear();
        self.partial_streak = 0;
        self.jac_valid = false;
    }

    /// Counts an accepted step and takes diffsol's counters of this segment, `solver`, on
    /// top of those of the earlier segments, `before`.
    fn record_solver(&mut self, before: &Stats, solver: &OdeSolverStatistics) {
        let stats = &mut self.stats;
        stats.steps += 1;
        stats.error_test_failures =
            before.error_test_failures + solver.number_of_error_test_failures;
        stats.newton_failures = before.newton_failures + solver.number_of_nonlinear_solver_fails;
        stats.newton_iterations =
            before.newton_iterations + solver.number_of_nonlinear_solver_iterations;
        stats.linear_solver_setups =
            before.linear_solver_setups + solver.number_of_linear_solver_setups;
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.latest_t = t;
        std::mem::swap(&mut self.previous, &mut self.latest);
        self.latest.clear();
        if y.iter().all(|v| v.is_finite()) {
            self.latest.extend_from_slice(y);
        }
        let start = Instant::now();
        self.system.rhs(t, y, dy);
        self.stats.rhs_evaluations += 1;
        self.stats.rhs_seconds += start.elapsed().as_secs_f64();
    }

    /// After a failed Newton iteration (the latest iterate more than
    /// [`FAILED_ITERATE_DISTANCE`] from the `named` state), the states whose last update
    /// evaluated (latest − previous iterate: the iteration diverges from its second update
    /// on, and the update that failed the test is not evaluated) is at least
    /// [`CULPRIT_FRACTION`] of the largest, in error weights atol + rtol·|y|; otherwise
    /// none.
    fn failed_iteration_culprits(&self, latest: &[f64], named: &[f64]) -> Vec<usize> {
        let n = latest.len();
        if self.previous.len() != n || named.len() != n {
            return Vec::new();
        }
        let weight = |k: usize| self.atol[k] + self.rtol * latest[k].abs();
        let distance = (0..n)
            .map(|k| ((latest[k] - named[k]) / weight(k)).powi(2))
            .sum::<f64>();
        // NaN (0/0 where a weight is zero) counts as near: the whole Jacobian is renewed.
        let far = (distance / n as f64).sqrt() > FAILED_ITERATE_DISTANCE;
        if !far {
            return Vec::new();
        }
        let update: Vec<f64> = (0..n)
            .map(|k| ((latest[k] - self.previous[k]) / weight(k)).abs())
            .collect();
        let largest = update.iter().copied().fold(0.0, f64::max);
        if !(largest > 0.0 && largest.is_finite()) {
            return Vec::new();
        }
        (0..n)
            .filter(|&k| update[k] >= CULPRIT_FRACTION * largest)
            .collect()
    }

    /// Computes the Jacobian named by diffsol at (t, y): at the latest iterate instead with
    /// [`StepControl::jacobian_at_latest_iterate`] (unless that gives a non-finite one),
    /// and there only in the failing states' columns where
    /// [`StepControl::partial_jacobians`] allows ([`Self::failed_iteration_culprits`]).
    fn renew_jacobian(&mut self, t: f64, y: &[f64]) {
        let start = Instant::now();
        let mut done = false;
        if self.at_latest_iterate && self.latest.len() == y.len() {
            let latest = std::mem::take(&mut self.latest);
            let may_be_partial = self.partial_streak < self.partial_limit && self.jac_valid;
            let culprits = if may_be_partial {
                self.failed_iteration_culprits(&latest, y)
            } else {
                Vec::new()
            };
            let partial = !culprits.is_empty()
                && self
                    .system
                    .partial_jacobian(self.latest_t, &latest, &culprits, &mut self.jac);
            if !partial {
                self.system.jacobian(self.latest_t, &latest, &mut self.jac);
            }
            self.latest = latest;
            // An iterate far enough off to give a non-finite Jacobian: the named state's.
            done = self.jac.iter().all(|v| v.is_finite());
            if done && partial {
                self.partial_streak += 1;
                self.stats.partial_jacobians += 1;
            } else {
                self.partial_streak = 0;
            }
        }
        if !done {
            self.partial_streak = 0;
            self.system.jacobian(t, y, &mut self.jac);
        }
        self.jac_valid = true;
        self.key.clear();
        self.key.extend_from_slice(y);
        self.key_t = t;
        self.key_rhs = self.stats.rhs_evaluations;
        self.stats.jacobian_evaluations += 1;
        self.stats.jacobian_seconds += start.elapsed().as_secs_f64();
    }

    /// J·v. diffsol assembles its Newton matrix column by column from products with unit
    /// vectors (and asks for them only when it renews the Jacobian); the Jacobian is
    /// computed once per (t, y) and the columns are read off. With
    /// [`StepControl::jacobian_at_latest_iterate`] it is taken at the state of the latest
    /// right-hand side instead of (t, y), and computed again for the same (t, y) once a
    /// right-hand side has been evaluated since (a renewal after a failed iteration); such a
    /// renewal may take only the failing states' columns
    /// ([`StepControl::partial_jacobians`]).
    fn jac_mul(&mut self, t: f64, y: &[f64], v: &[f64], out: &mut [f64]) {
        let moved = self.at_latest_iterate && self.stats.rhs_evaluations != self.key_rhs;
        if moved || t != self.key_t || self.key.as_slice() != y {
            self.renew_jacobian(t, y);
        }
        // diffsol assembles its Newton matrix column by column from unit vectors: the
        // column is read from the contiguous column-major storage.
        let mut nonzero = v.iter().enumerate().filter(|(_, x)| **x != 0.0);
        match (nonzero.next(), nonzero.next()) {
            (None, _) => out.fill(0.0),
            (Some((j, &s)), None) => {
                let n = out.len();
                let column = &self.jac.as_slice()[j * n..(j + 1) * n];
                for (o, c) in out.iter_mut().zip(column) {
                    *o = s * c;
                }
            }
            _ => {
                let r = &self.jac * nalgebra::DVector::from_column_slice(v);
                out.copy_from_slice(r.as_slice());
            }
        }
    }
}

/// Where an integration starts.
#[derive(Debug, Clone, PartialEq)]
pub struct Start {
    /// Time [s].
    pub time: f64,
    /// State.
    pub state: Vec<f64>,
    /// `None`: a fresh start; the state at `time` is the first output and the first step is
    /// diffsol's estimate. `Some(h)`: a [`Checkpoint`]'s step; the run continues exactly as
    /// the run that reached the checkpoint did, whose output at `time` was already
    /// delivered (it is not repeated).
    pub step: Option<f64>,
}

/// A point where the solver restarts: its time, state and next step, and the counters of
/// the integration until then. A run started from it (see [`Start`]) takes the same code
/// path as the run that reached it, so it continues bit for bit.
#[derive(Debug, Clone, PartialEq)]
pub struct Checkpoint {
    /// Time [s] (the checkpoint time, within diffsol's stop-time round-off).
    pub time: f64,
    /// State at `time`.
    pub state: Vec<f64>,
    /// The step size the solver proposed for the next step [s].
    pub step: f64,
    /// Counters of this integration until `time`.
    pub stats: Stats,
}

/// What [`integrate`] reports while it runs.
#[derive(Debug, Clone, Copy)]
pub enum Event<'a> {
    /// The (interpolated) state at an output time.
    Output {
        /// Output time [s].
        time: f64,
        /// State at `time`.
        state: &'a [f64],
        /// Counters so far.
        stats: &'a Stats,
    },
    /// A checkpoint was reached; the solver restarts from it.
    Checkpoint(&'a Checkpoint),
    /// A solver step was taken (before the outputs it passed are reported): for progress
    /// displays and interruption checks between outputs.
    Step {
        /// Time reached [s].
        time: f64,
        /// Counters so far.
        stats: &'a Stats,
    },
}

/// Times closer than this count as equal when output and checkpoint times are compared
/// with the solver's time [s] (relative 1e-12, absolute below 1 s).
pub fn slack(t: f64) -> f64 {
    1e-12 * t.abs().max(1.0)
}

/// The first index k of the grid origin + k·interval whose time lies after t (by more than
/// [`slack`]). Both the run that reaches t and a run started at t compute it alike.
fn first_after(origin: f64, interval: f64, t: f64) -> usize {
    let limit = t + slack(t);
    let mut k = ((limit - origin) / interval).floor().max(0.0) as usize;
    while k > 0 && origin + (k - 1) as f64 * interval > limit {
        k -= 1;
    }
    while origin + k as f64 * interval <= limit {
        k += 1;
    }
    k
}

/// Integrates from `start` to t_end, reporting to `events`, which may stop the run by
/// returning `ControlFlow::Break`.
///
/// Outputs ([`Event::Output`]) come at the output times origin + k·Δt_out ≤ t_end (and at
/// t_end), interpolated, and at a fresh start's time. With a checkpoint interval, the
/// integration runs in segments ending exactly at the checkpoint times origin + j·Δt_c
/// (diffsol's stop time); at each it reports an [`Event::Checkpoint`] (after the outputs
/// up to that time), then calls [`OdeSystem::restart`] and builds a fresh solver from
/// (t, y, h), as every run does at its start. A run resumed from a checkpoint does exactly
/// the same from there, so it equals the uninterrupted run bit for bit. The restarts
/// cost a Newton matrix and a step-size history per segment, and make the result differ
/// (within the tolerances) from a run with another checkpoint interval.
pub fn integrate<S: OdeSystem>(
    system: &S,
    start: &Start,
    t_end: f64,
    options: &Options,
    mut events: impl FnMut(Event) -> ControlFlow<()>,
) -> Result<Stats, Failure> {
    let counters = RefCell::new(Counters::new(system, options));
    let run = Run {
        counters: &counters,
        wall: Instant::now(),
    };
    let (mut t, mut y, mut h) = (start.time, start.state.clone(), start.step);
    if h.is_none() {
        let stats = run.stats(t, 0.0);
        let event = Event::Output {
            time: t,
            state: &y,
            stats: &stats,
        };
        if events(event).is_break() {
            return Ok(stats);
        }
    }
    let mut outputs = OutputGrid::new(options, t_end, t);
    // A run resumed from a checkpoint starts a window of the stall check there.
    let mut stall = StallWatch {
        steps: counters.borrow().stats.steps,
        time: t,
    };
    loop {
        // One segment: from (t, y, h) with a fresh solver to the next checkpoint or t_end.
        let checkpoint = options
            .checkpoint_interval
            .map(|dt| options.origin + first_after(options.origin, dt, t) as f64 * dt)
            .filter(|&tc| tc <= t_end + slack(t_end));
        system.restart();
        // The Jacobian cache must not carry over: the run resumed here has none.
        counters.borrow_mut().start_segment();
        let segment = Segment {
            run: &run,
            options,
            stop: checkpoint.unwrap_or(t_end),
        };
        let step = match segment.integrate((t, &y, h), &mut outputs, &mut stall, &mut events)? {
            SegmentEnd::Stopped(stats) => return Ok(stats),
            SegmentEnd::Reached { time, state, step } => {
                (t, y, h) = (time, state, Some(step));
                step
            }
        };
        let stats = run.stats(t, step);
        if checkpoint.is_none() {
            return Ok(stats);
        }
        let reached = Checkpoint {
            time: t,
            state: y.clone(),
            step,
            stats,
        };
        if events(Event::Checkpoint(&reached)).is_break() || t >= t_end - slack(t_end) {
            return Ok(stats);
        }
    }
}

/// The counters of one integration and its wall clock: what it reports, and how it fails.
struct Run<'c, 's, S: OdeSystem> {
    counters: &'c RefCell<Counters<'s, S>>,
    wall: Instant,
}

impl<S: OdeSystem> Run<'_, '_, S> {
    /// The counters so far, at time `t` with the last step `h`.
    fn stats(&self, t: f64, h: f64) -> Stats {
        let mut s = self.counters.borrow().stats;
        s.total_seconds = self.wall.elapsed().as_secs_f64();
        s.t_reached = t;
        s.last_step = h;
        s
    }

    /// The run's failure at time `t`, with the last accepted `state`.
    fn failure(&self, time: f64, message: String, state: Vec<f64>) -> Failure {
        let mut stats = self.counters.borrow().stats;
        stats.total_seconds = self.wall.elapsed().as_secs_f64();
        stats.t_reached = time;
        Failure {
            time,
            message,
            stats: Box::new(stats),
            state,
        }
    }

    /// Fails the run at `t` (with the accepted `state()`) if the step proposed next,
    /// `step`, is not finite: the solver would loop for ever (its Newton failures are not
    /// limited); or if the steps collapsed ([`StallWatch`]).
    fn check_step(
        &self,
        stall: &mut StallWatch,
        (t, step): (f64, f64),
        min_mean_step: f64,
        state: &dyn Fn() -> Vec<f64>,
    ) -> Result<(), Failure> {
        if !step.is_finite() {
            let message = format!("the step size became {step}");
            return Err(self.failure(t, message, state()));
        }
        let taken = self.counters.borrow().stats.steps;
        let checked = stall.check(taken, t, min_mean_step);
        checked.map_err(|message| self.failure(t, message, state()))
    }

    /// Delivers to `events` the outputs that the step to `t` (of size `step`) passed,
    /// each state from `interpolate`; the counters if the events stopped the run. A state
    /// that is not finite fails the run (with the accepted `state()`).
    fn deliver_outputs(
        &self,
        outputs: &mut OutputGrid,
        (t, step): (f64, f64),
        interpolate: impl Fn(f64) -> Result<Vec<f64>, String>,
        state: &dyn Fn() -> Vec<f64>,
        events: &mut impl FnMut(Event) -> ControlFlow<()>,
    ) -> Result<Option<Stats>, Failure> {
        while let Some(to) = outputs.due(t) {
            let y = interpolate(to).map_err(|message| self.failure(t, message, state()))?;
            if !y.iter().all(|v| v.is_finite()) {
                let message = "the state is no longer finite (NaN or infinity)".into();
                return Err(self.failure(t, message, state()));
            }
            let stats = self.stats(t, step);
            let event = Event::Output {
                time: to,
                state: &y,
                stats: &stats,
            };
            if events(event).is_break() {
                return Ok(Some(stats));
            }
            outputs.delivered(to);
        }
        Ok(None)
    }
}

/// The output times origin + k·Δt_out (the last one t_end) and how far they were
/// delivered.
struct OutputGrid {
    origin: f64,
    interval: f64,
    t_end: f64,
    /// The index k of the next output.
    next: usize,
    /// The output at t_end was delivered.
    ended: bool,
}

impl OutputGrid {
    /// The grid of `options` for a run to `t_end` that has reached `t` (its outputs up to
    /// `t` delivered).
    fn new(options: &Options, t_end: f64, t: f64) -> Self {
        Self {
            origin: options.origin,
            interval: options.output_interval,
            t_end,
            next: first_after(options.origin, options.output_interval, t),
            ended: t >= t_end,
        }
    }

    /// The next output time, if the solver's time `t` has passed it.
    fn due(&self, t: f64) -> Option<f64> {
        let next = (self.origin + self.next as f64 * self.interval).min(self.t_end);
        (!self.ended && next <= t + slack(t)).then_some(next)
    }

    /// The output at `time` ([`Self::due`]) was delivered.
    fn delivered(&mut self, time: f64) {
        self.ended = time >= self.t_end;
        self.next += 1;
    }
}

/// The start of the current window of [`STALL_WINDOW`] steps: steps taken and time.
struct StallWatch {
    steps: usize,
    time: f64,
}

impl StallWatch {
    /// After `steps` steps at time `t`: the error message if the last [`STALL_WINDOW`]
    /// steps advanced the time by less than `min_mean_step` each on average; a new window
    /// starts at the end of each.
    fn check(&mut self, steps: usize, t: f64, min_mean_step: f64) -> Result<(), String> {
        if steps < self.steps + STALL_WINDOW {
            return Ok(());
        }
        let mean = (t - self.time) / (steps - self.steps) as f64;
        if mean < min_mean_step {
            return Err(format!(
                "the steps collapsed: the last {} steps advanced the time by {:.3e} s \
                 (a mean step of {mean:.3e} s, below min_mean_step = {:.3e} s; 0 turns \
                 this stop off)",
                steps - self.steps,
                t - self.time,
                min_mean_step
            ));
        }
        *self = StallWatch { steps, time: t };
        Ok(())
    }
}

/// One segment of an integration: a fresh solver from (t, y, h) to `stop` (a checkpoint
/// or t_end).
struct Segment<'r, 'c, 's, S: OdeSystem> {
    run: &'r Run<'c, 's, S>,
    options: &'r Options,
    stop: f64,
}

/// How a segment ended.
enum SegmentEnd {
    /// The events stopped the run.
    Stopped(Stats),
    /// It reached its stop: the time, state and next step there.
    Reached {
        time: f64,
        state: Vec<f64>,
        step: f64,
    },
}

impl<S: OdeSystem> Segment<'_, '_, '_, S> {
    /// Integrates from `(t, y, h)` (`h` None: diffsol's first step) to the stop, delivering
    /// the outputs it passes and reporting every step to `events`.
    fn integrate(
        &self,
        (t, y, h): (f64, &[f64], Option<f64>),
        outputs: &mut OutputGrid,
        stall: &mut StallWatch,
        events: &mut impl FnMut(Event) -> ControlFlow<()>,
    ) -> Result<SegmentEnd, Failure> {
        let (run, options) = (self.run, self.options);
        let counters = run.counters;
        let fail = |time: f64, e: &dyn std::fmt::Display, state: Vec<f64>| {
            run.failure(time, e.to_string(), state)
        };
        let y_init = y.to_vec();
        let mut problem = OdeBuilder::<NalgebraMat<f64>>::new()
            .t0(t)
            .h0(options.dt_initial.min(options.dt_max))
            .rtol(options.rtol)
            .atol(options.atol.clone())
            .rhs_implicit(
                |x: &[f64], _p: &[f64], t: f64, y: &mut [f64]| counters.borrow_mut().rhs(t, x, y),
                |x: &[f64], _p: &[f64], t: f64, v: &[f64], y: &mut [f64]| {
                    counters.borrow_mut().jac_mul(t, x, v, y)
                },
            )
            .init(
                move |_p: &[f64], _t: f64, y: &mut [f64]| y.copy_from_slice(&y_init),
                y.len(),
            )
            .build()
            .map_err(|e| fail(t, &e, y.to_vec()))?;
        // diffsol counts Newton failures over the whole run and gives up after 50 by
        // default; a long run with contacts opening and closing has many, each handled by a
        // Jacobian update or a smaller step. The run fails when the step size collapses.
        problem.ode_options.max_nonlinear_solver_failures = usize::MAX / 4;
        problem.ode_options.min_timestep = MIN_STEP;
        apply_step_control(&mut problem.ode_options, &options.step_control);
        let solver = match options.method {
            Method::TrBdf2 => problem.tr_bdf2::<SparseSkipLu>().map(Solver::TrBdf2),
            Method::Esdirk34 => problem.esdirk34::<SparseSkipLu>().map(Solver::Esdirk34),
        };
        let mut solver = solver.map_err(|e| fail(t, &e, y.to_vec()))?;
        if let Some(h) = h {
            on!(&mut solver, s => *s.state_mut().h = h);
        }
        if let Err(e) = on!(&mut solver, s => s.set_stop_time(self.stop)) {
            return Err(fail(t, &e, y.to_vec()));
        }
        // diffsol's counters of the earlier segments.
        let before = counters.borrow().stats;
        let mut last_step = h.unwrap_or(options.dt_max);
        loop {
            on!(&mut solver, s => {
                if s.state().h > options.dt_max {
                    *s.state_mut().h = options.dt_max;
                }
            });
            let reason = on!(&mut solver, s => s.step());
            let state = || on!(&solver, s => s.state().y.clone_as_vec());
            let t = on!(&solver, s => s.state().t);
            let reason = reason.map_err(|e| fail(t, &e, state()))?;
            counters
                .borrow_mut()
                .record_solver(&before, on!(&solver, s => s.get_statistics()));
            counters.borrow().system.step_accepted();
            let step = on!(&solver, s => s.state().h);
            run.check_step(stall, (t, step), options.min_mean_step, &state)?;
            let stats = run.stats(t, step);
            if events(Event::Step {
                time: t,
                stats: &stats,
            })
            .is_break()
            {
                return Ok(SegmentEnd::Stopped(stats));
            }
            let interpolate = |to: f64| {
                on!(&solver, s => s.interpolate(to.min(t)))
                    .map(|y| y.clone_as_vec())
                    .map_err(|e| e.to_string())
            };
            let delivered = run.deliver_outputs(outputs, (t, step), interpolate, &state, events)?;
            if let Some(stats) = delivered {
                return Ok(SegmentEnd::Stopped(stats));
            }
            // A step cut to land on the stop can fall short of it by round-off (B1 with the
            // free tilt: at 0.2 s − 7.5e-15 s, after a step of 7.6e-15 s); the rest would
            // be a step below MIN_STEP, so the stop counts as reached, and the next segment
            // starts from the step before the sliver.
            let stop = self.stop;
            if matches!(reason, OdeSolverStopReason::TstopReached) || t >= stop - slack(stop) {
                return Ok(SegmentEnd::Reached {
                    time: t,
                    state: state(),
                    step: if step < STEP_SLIVER { last_step } else { step },
                });
            }
            last_step = step;
        }
    }
}

/// Sets diffsol's step-size and Jacobian options from `control`.
fn apply_step_control(o: &mut diffsol::OdeSolverOptions<f64>, control: &StepControl) {
    o.max_timestep_growth = Some(control.max_growth);
    o.pi_control_proportional = 0.0;
    o.pi_control_integral = control.gain;
    if !control.jacobian_after_newton_failure {
        // diffsol renews the Jacobian after a first failure when the step size is within
        // this relative threshold of the one the Jacobian was taken at: never.
        o.threshold_to_update_rhs_jacobian = 0.0;
    }
}

/// The two SDIRK solvers behind one face.
enum Solver<A, B> {
    TrBdf2(A),
    Esdirk34(B),
}

/// Runs `$e` on whichever solver `$solver` holds, bound to `$s`.
macro_rules! on {
    ($solver:expr, $s:ident => $e:expr) => {
        match $solver {
            Solver::TrBdf2($s) => $e,
            Solver::Esdirk34($s) => $e,
        }
    };
}
use on;

#[cfg(test)]
mod tests;
