//! Tests of the integrator ([`super`]).

use super::*;
use std::cell::Cell;

/// A stiff linear oscillator with a fast decaying mode: y1' = y2, y2' = −ω²y1 − 2ζω y2,
/// plus y3' = −λ (y3 − cos t) with λ = 1e7 (a mode far faster than any step).
struct Stiff;
const OMEGA: f64 = 20.0;
const ZETA: f64 = 0.05;
const LAMBDA: f64 = 1e7;
impl OdeSystem for Stiff {
    fn len(&self) -> usize {
        3
    }
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = -OMEGA * OMEGA * y[0] - 2.0 * ZETA * OMEGA * y[1];
        dy[2] = -LAMBDA * (y[2] - t.cos());
    }
    fn jacobian(&self, _t: f64, _y: &[f64], jac: &mut DMatrix<f64>) {
        jac.fill(0.0);
        jac[(0, 1)] = 1.0;
        jac[(1, 0)] = -OMEGA * OMEGA;
        jac[(1, 1)] = -2.0 * ZETA * OMEGA;
        jac[(2, 2)] = -LAMBDA;
    }
}

fn exact(t: f64) -> (f64, f64) {
    let wd = OMEGA * (1.0 - ZETA * ZETA).sqrt();
    let decay = (-ZETA * OMEGA * t).exp();
    let y1 = decay * ((wd * t).cos() + ZETA * OMEGA / wd * (wd * t).sin());
    (y1, t.cos())
}

fn options(method: Method, checkpoint_interval: Option<f64>) -> Options {
    Options {
        rtol: 1e-8,
        atol: vec![1e-10],
        dt_max: 5e-3,
        dt_initial: 1e-6,
        output_interval: 0.1,
        method,
        origin: 0.0,
        checkpoint_interval,
        step_control: StepControl::default(),
        min_mean_step: 0.0,
    }
}

type Outputs = Vec<(f64, Vec<f64>)>;

/// Runs `Stiff` from `start` to 2 s; returns the outputs, the checkpoints and the
/// counters.
fn run_from(start: &Start, options: &Options) -> (Outputs, Vec<Checkpoint>, Stats) {
    let mut out = Vec::new();
    let mut checkpoints = Vec::new();
    let stats = integrate(&Stiff, start, 2.0, options, |event| {
        match event {
            Event::Output { time, state, .. } => out.push((time, state.to_vec())),
            Event::Checkpoint(c) => checkpoints.push(c.clone()),
            Event::Step { .. } => {}
        }
        ControlFlow::Continue(())
    })
    .unwrap();
    (out, checkpoints, stats)
}

fn fresh() -> Start {
    Start {
        time: 0.0,
        state: vec![1.0, 0.0, 1.0],
        step: None,
    }
}

fn run(method: Method) -> (Outputs, Stats) {
    let (out, checkpoints, stats) = run_from(&fresh(), &options(method, None));
    assert!(checkpoints.is_empty());
    (out, stats)
}

/// Counters that do not depend on the wall clock.
fn counts(s: &Stats) -> [usize; 6] {
    [
        s.steps,
        s.rhs_evaluations,
        s.jacobian_evaluations,
        s.error_test_failures,
        s.newton_failures,
        s.newton_iterations,
    ]
}

#[test]
fn a_run_resumed_from_a_checkpoint_equals_the_uninterrupted_run_bit_for_bit() {
    for method in [Method::TrBdf2, Method::Esdirk34] {
        // Checkpoints every 0.25 s: on the output grid at 0.5, 1, 1.5 s, off it between.
        let opts = options(method, Some(0.25));
        let (whole, checkpoints, stats) = run_from(&fresh(), &opts);
        assert_eq!(whole.len(), 21);
        assert_eq!(checkpoints.len(), 8, "0.25, 0.5, ..., 2.0 s");
        for (j, c) in checkpoints.iter().enumerate() {
            let nominal = (j + 1) as f64 * 0.25;
            assert!((c.time - nominal).abs() < 1e-12, "{} vs {nominal}", c.time);
        }
        for c in [&checkpoints[2], &checkpoints[3]] {
            let start = Start {
                time: c.time,
                state: c.state.clone(),
                step: Some(c.step),
            };
            let (rest, later, rest_stats) = run_from(&start, &opts);
            // The outputs after the checkpoint, bit for bit (== on f64), none repeated.
            let head = whole.iter().take_while(|(t, _)| *t <= c.time).count();
            assert_eq!(rest, whole[head..], "{method:?} from t = {}", c.time);
            let key = |c: &Checkpoint| (c.time, c.state.clone(), c.step);
            let tail = &checkpoints[checkpoints.len() - later.len()..];
            assert_eq!(
                later.iter().map(key).collect::<Vec<_>>(),
                tail.iter().map(key).collect::<Vec<_>>()
            );
            // The counters add up exactly too.
            let sum: Vec<usize> = counts(&c.stats)
                .iter()
                .zip(counts(&rest_stats))
                .map(|(a, b)| a + b)
                .collect();
            assert_eq!(sum, counts(&stats));
        }
        // The restarts change the trajectory only within the tolerances.
        let (plain, _) = run(method);
        for ((t, a), (_, b)) in whole.iter().zip(&plain) {
            assert!((a[0] - b[0]).abs() < 1e-5, "{method:?} t={t}");
        }
    }
}

/// A damped hardening oscillator whose spring force g(y) = y + y³/2 is linearised
/// about an anchor that is moved to y only when y has left it by 0.05: a memory of
/// earlier calls that, like the gradient detector's warm starts, changes the results.
/// `forget` selects whether [`OdeSystem::restart`] clears it.
struct Memo {
    anchor: std::cell::Cell<Option<f64>>,
    forget: bool,
}
impl Memo {
    fn new(forget: bool) -> Self {
        Self {
            anchor: std::cell::Cell::new(None),
            forget,
        }
    }
    /// The linearised spring force at y and its slope.
    fn spring(&self, y: f64) -> (f64, f64) {
        let a = match self.anchor.get() {
            Some(a) if (y - a).abs() < 0.05 => a,
            _ => y,
        };
        self.anchor.set(Some(a));
        let slope = 1.0 + 1.5 * a * a;
        (a + 0.5 * a * a * a + slope * (y - a), slope)
    }
}
impl OdeSystem for Memo {
    fn len(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = -400.0 * self.spring(y[0]).0 - 2.0 * y[1];
    }
    fn jacobian(&self, _t: f64, y: &[f64], jac: &mut DMatrix<f64>) {
        jac.fill(0.0);
        jac[(0, 1)] = 1.0;
        jac[(1, 0)] = -400.0 * self.spring(y[0]).1;
        jac[(1, 1)] = -2.0;
    }
    fn restart(&self) {
        if self.forget {
            self.anchor.set(None);
        }
    }
}

#[test]
fn restarts_clear_the_systems_memory_so_resumed_runs_match() {
    let run = |system: &Memo, start: &Start| {
        let mut out = Vec::new();
        let mut checkpoints = Vec::new();
        let opts = options(Method::TrBdf2, Some(0.25));
        integrate(system, start, 1.0, &opts, |event| {
            match event {
                Event::Output { time, state, .. } => out.push((time, state.to_vec())),
                Event::Checkpoint(c) => checkpoints.push(c.clone()),
                Event::Step { .. } => {}
            }
            ControlFlow::Continue(())
        })
        .unwrap();
        (out, checkpoints)
    };
    let start = Start {
        time: 0.0,
        state: vec![2.0, 0.0],
        step: None,
    };
    for forget in [true, false] {
        let (whole, checkpoints) = run(&Memo::new(forget), &start);
        let c = &checkpoints[1];
        let resumed = Start {
            time: c.time,
            state: c.state.clone(),
            step: Some(c.step),
        };
        // The process that resumes builds its system anew (empty memory).
        let (rest, _) = run(&Memo::new(forget), &resumed);
        let head = whole.iter().take_while(|(t, _)| *t <= c.time).count();
        if forget {
            assert_eq!(rest, whole[head..]);
        } else {
            // Without the reset the warm starts differ and so do the last bits: the
            // comparison above is able to fail.
            assert_ne!(rest, whole[head..]);
        }
    }
}

/// y' = −λ(y − cos t) − sin t from y(0) = 1 (solution cos t), whose right-hand side
/// is NaN wherever |y − cos t| exceeds `band`: Newton's iterates (from the step's
/// predictor) land there while the solution never does, as a bearing's iterate may
/// try an overlap that gives NaN forces.
struct NanAway {
    band: f64,
    nans: Cell<usize>,
}
impl OdeSystem for NanAway {
    fn len(&self) -> usize {
        1
    }
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = if (y[0] - t.cos()).abs() > self.band {
            self.nans.set(self.nans.get() + 1);
            f64::NAN
        } else {
            -1e3 * (y[0] - t.cos()) - t.sin()
        };
    }
    fn jacobian(&self, _t: f64, _y: &[f64], jac: &mut DMatrix<f64>) {
        jac[(0, 0)] = -1e3;
    }
}

/// A non-finite right-hand side at a Newton iterate makes the solver reject the step
/// and retry smaller (diffsol counts a Newton failure), never a NaN output or a
/// crash; the run ends on the solution.
#[test]
fn a_nan_right_hand_side_in_newton_is_a_rejected_step() {
    for method in [Method::TrBdf2, Method::Esdirk34] {
        let system = NanAway {
            band: 1e-7,
            nans: Cell::new(0),
        };
        let mut opts = options(method, None);
        opts.dt_max = 0.05;
        let mut out = Vec::new();
        let stats = integrate(&system, &fresh_1d(), 2.0, &opts, |event| {
            if let Event::Output { time, state, .. } = event {
                out.push((time, state[0]));
            }
            ControlFlow::Continue(())
        })
        .unwrap_or_else(|f| panic!("{method:?}: {f:?}"));
        assert!(
            system.nans.get() > 0,
            "{method:?}: no iterate reached the NaN"
        );
        assert!(stats.newton_failures > 0, "{method:?}: {stats:?}");
        assert_eq!(out.len(), 21);
        for (t, y) in &out {
            assert!((y - t.cos()).abs() < 1e-7, "{method:?} t = {t}: {y}");
        }
    }
}

/// The step sizes of a run of `Stiff` to 0.05 s from a first step of 1e-6 s, read from
/// outputs every 1e-6 s (no step is shorter, so every step shows).
fn step_sizes(control: StepControl) -> Vec<f64> {
    let mut opts = options(Method::TrBdf2, None);
    opts.output_interval = 1e-6;
    opts.step_control = control;
    let mut steps: Vec<f64> = Vec::new();
    integrate(&Stiff, &fresh(), 0.05, &opts, |event| {
        if let Event::Output { stats, .. } = event {
            if stats.last_step > 0.0 && steps.last() != Some(&stats.last_step) {
                steps.push(stats.last_step);
            }
        }
        ControlFlow::Continue(())
    })
    .unwrap();
    steps
}

/// `StepControl::max_growth` caps the growth from one step to the next (diffsol's own
/// cap is 2, which the same run reaches: the check can fail).
#[test]
fn no_step_grows_by_more_than_the_maximum_growth() {
    let largest = |h: &[f64]| h.windows(2).map(|w| w[1] / w[0]).fold(0.0, f64::max);
    let capped = step_sizes(StepControl::default());
    let growth = StepControl::default().max_growth;
    assert!(capped.len() > 5, "{capped:?}");
    assert!(largest(&capped) <= growth * (1.0 + 1e-12), "{capped:?}");
    assert!(
        largest(&capped) > 0.99 * growth,
        "never grew as far: {capped:?}"
    );
    let free = step_sizes(StepControl::DIFFSOL);
    assert!(largest(&free) > 1.9, "{free:?}");
}

/// y' = −λ(t)·(y − cos t) − sin t with λ = 1e4 for t < 1 and 1e6 after (solution
/// cos t from y(0) = 1): a stiffness that jumps, so that the Jacobian taken before the
/// jump makes Newton fail after it.
struct Jump;
impl Jump {
    fn lambda(t: f64) -> f64 {
        if t < 1.0 {
            1e4
        } else {
            1e6
        }
    }
}
impl OdeSystem for Jump {
    fn len(&self) -> usize {
        1
    }
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = -Self::lambda(t) * (y[0] - t.cos()) - t.sin();
    }
    fn jacobian(&self, t: f64, _y: &[f64], jac: &mut DMatrix<f64>) {
        jac[(0, 0)] = -Self::lambda(t);
    }
}

/// Both Jacobian policies after a Newton failure end on the solution, and the setting
/// reaches the solver (the runs differ). That keeping the Jacobian saves Jacobians is
/// measured on B1 (docs/performance-log.md, "Step-size control: the tuning": 8 524
/// against 9 955 Jacobians in the whole run).
#[test]
fn both_jacobian_policies_after_a_newton_failure_end_on_the_solution() {
    let run = |renew: bool| {
        let mut opts = options(Method::TrBdf2, None);
        opts.step_control.jacobian_after_newton_failure = renew;
        let start = Start {
            time: 0.0,
            state: vec![1.0],
            step: None,
        };
        let mut last = f64::NAN;
        let stats = integrate(&Jump, &start, 2.0, &opts, |event| {
            if let Event::Output { state, .. } = event {
                last = state[0];
            }
            ControlFlow::Continue(())
        })
        .unwrap();
        assert!((last - 2.0f64.cos()).abs() < 1e-7, "renew {renew}: {last}");
        stats
    };
    let (kept, renewed) = (run(false), run(true));
    assert!(kept.newton_failures > 0 && renewed.newton_failures > 0);
    assert_ne!(counts(&kept), counts(&renewed));
}

/// The Jacobian at the latest iterate: on `Jump`, a step that crosses t = 1 fails its
/// Newton iteration with the Jacobian of λ = 1e4; diffsol's renewal at the step's start
/// (t < 1) gives that Jacobian again and the step must be cut, while the renewal at the
/// last iterate (t > 1) gives λ = 1e6 and the retry converges. Both end on the solution
/// (the Newton matrix is only the iteration's), and the one at the latest iterate fails
/// fewer Newton iterations.
#[test]
fn the_jacobian_at_the_latest_iterate_sees_beyond_the_jump() {
    let run = |latest: bool| {
        let mut opts = options(Method::TrBdf2, None);
        opts.step_control.jacobian_at_latest_iterate = latest;
        let mut last = f64::NAN;
        let stats = integrate(&Jump, &fresh_1d(), 2.0, &opts, |event| {
            if let Event::Output { state, .. } = event {
                last = state[0];
            }
            ControlFlow::Continue(())
        })
        .unwrap();
        assert!(
            (last - 2.0f64.cos()).abs() < 1e-7,
            "latest {latest}: {last}"
        );
        stats
    };
    let (start, latest) = (run(false), run(true));
    assert!(start.newton_failures > 0);
    assert!(
        latest.newton_failures < start.newton_failures,
        "{} against {}",
        latest.newton_failures,
        start.newton_failures
    );
}

fn fresh_1d() -> Start {
    Start {
        time: 0.0,
        state: vec![1.0],
        step: None,
    }
}

#[test]
fn stiff_oscillator_matches_closed_form_at_every_output_time() {
    for method in [Method::TrBdf2, Method::Esdirk34] {
        let (out, stats) = run(method);
        assert_eq!(out.len(), 21, "outputs at 0, 0.1, ..., 2.0");
        for (t, y) in &out {
            let (y1, y3) = exact(*t);
            // Tolerance 1e-8 relative per step over ~400 steps, plus interpolation
            // error of the dense output: 2e-5 is 100x the expected global error.
            assert!(
                (y[0] - y1).abs() < 2e-5,
                "{method:?} t={t}: {} vs {y1}",
                y[0]
            );
            // The fast mode follows cos t with lag sin(t)/λ ~ 1e-7.
            assert!(
                (y[2] - y3).abs() < 1e-5,
                "{method:?} t={t}: {} vs {y3}",
                y[2]
            );
        }
        assert!(
            stats.steps >= 400,
            "Δt_max = 5 ms caps the steps: {}",
            stats.steps
        );
        assert!(stats.jacobian_evaluations >= 1);
    }
}

/// y' = cos(Ωt) with Ω = 1e8 rad/s: the tolerance holds the steps to a small fraction of
/// the period 2π/Ω ≈ 63 ns, the way a bearing run's steps collapse where a contact
/// chatters.
struct Chattering;
const CHATTER: f64 = 1e8;
impl OdeSystem for Chattering {
    fn len(&self) -> usize {
        1
    }
    fn rhs(&self, t: f64, _y: &[f64], dy: &mut [f64]) {
        dy[0] = (CHATTER * t).cos();
    }
    fn jacobian(&self, _t: f64, _y: &[f64], jac: &mut DMatrix<f64>) {
        jac.fill(0.0);
    }
}

/// A run whose mean step over `STALL_WINDOW` steps falls below `min_mean_step` fails at
/// the end of that window with a message saying so and its state there; with the check
/// off (0) the same run goes on past the window.
#[test]
fn a_run_whose_steps_collapse_fails_after_one_window() {
    let mut opts = options(Method::TrBdf2, None);
    opts.rtol = 1e-8;
    opts.atol = vec![1e-16];
    opts.dt_max = 1e-6;
    opts.output_interval = 1e-6;
    opts.min_mean_step = 1e-7;
    let start = Start {
        time: 0.0,
        state: vec![0.0],
        step: None,
    };
    let continue_ = |_: Event| ControlFlow::Continue(());
    let err = integrate(&Chattering, &start, 1.0, &opts, continue_).unwrap_err();
    assert!(
        err.message.contains("the steps collapsed"),
        "{}",
        err.message
    );
    assert_eq!(err.stats.steps, STALL_WINDOW);
    assert!(
        err.time < STALL_WINDOW as f64 * opts.min_mean_step,
        "{}",
        err.time
    );
    assert_eq!(err.state.len(), 1);
    // y = sin(Ωt)/Ω where it stopped, to the tolerance's order.
    let exact = (CHATTER * err.time).sin() / CHATTER;
    assert!(
        (err.state[0] - exact).abs() < 1e-12,
        "{} vs {exact}",
        err.state[0]
    );
    opts.min_mean_step = 0.0;
    let t_end = 1.5 * err.time;
    let stats = integrate(&Chattering, &start, t_end, &opts, continue_).unwrap();
    assert!(stats.steps > STALL_WINDOW, "{}", stats.steps);
}

/// Two decoupled components: y₀ as [`Jump`]'s (its stiffness jumps at t = 1), y₁' =
/// −1e4·(y₁ − cos t) − sin t (solution cos t for both). The system renews single columns
/// when asked (`offer`) and records the states it was asked for.
struct TwoParts {
    offer: bool,
    asked: std::cell::RefCell<Vec<Vec<usize>>>,
}
impl TwoParts {
    fn column(t: f64, k: usize) -> f64 {
        if k == 0 {
            -Jump::lambda(t)
        } else {
            -1e4
        }
    }
}
impl OdeSystem for TwoParts {
    fn len(&self) -> usize {
        2
    }
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        for k in 0..2 {
            dy[k] = Self::column(t, k) * (y[k] - t.cos()) - t.sin();
        }
    }
    fn jacobian(&self, t: f64, _y: &[f64], jac: &mut DMatrix<f64>) {
        jac.fill(0.0);
        for k in 0..2 {
            jac[(k, k)] = Self::column(t, k);
        }
    }
    fn partial_jacobian(
        &self,
        t: f64,
        _y: &[f64],
        states: &[usize],
        jac: &mut DMatrix<f64>,
    ) -> bool {
        if !self.offer {
            return false;
        }
        self.asked.borrow_mut().push(states.to_vec());
        for &k in states {
            jac[(k, k)] = Self::column(t, k);
        }
        true
    }
}

/// Partial renewals after a Newton failure: on [`TwoParts`] the step across t = 1 fails
/// in y₀, the system is asked for y₀'s column (first alone), and the run ends on the
/// solution as with whole renewals; a system that declines gets whole Jacobians, and
/// `partial_jacobians = 0` asks for none.
#[test]
fn partial_jacobians_renew_the_columns_of_the_failing_states() {
    let run = |offer: bool, limit: usize| {
        let system = TwoParts {
            offer,
            asked: Default::default(),
        };
        let mut opts = options(Method::TrBdf2, None);
        opts.step_control.partial_jacobians = limit;
        let start = Start {
            time: 0.0,
            state: vec![1.0, 1.0],
            step: None,
        };
        let mut last = vec![];
        let stats = integrate(&system, &start, 2.0, &opts, |event| {
            if let Event::Output { state, .. } = event {
                last = state.to_vec();
            }
            ControlFlow::Continue(())
        })
        .unwrap();
        for value in &last {
            assert!(
                (value - 2.0f64.cos()).abs() < 1e-7,
                "{offer} {limit}: {last:?}"
            );
        }
        (stats, system.asked.into_inner())
    };
    let (partial, asked) = run(true, 2);
    assert!(partial.newton_failures > 0);
    assert!(partial.partial_jacobians > 0 && partial.partial_jacobians == asked.len());
    assert!(partial.partial_jacobians < partial.jacobian_evaluations);
    // The first failure, at the jump, is y₀'s alone; the retries' updates of y₁ (whose
    // columns never change) may reach a tenth of y₀'s and be renewed with it.
    assert_eq!(asked[0], vec![0]);
    assert!(asked.iter().all(|states| states.contains(&0)), "{asked:?}");
    let (declined, asked) = run(false, 2);
    assert_eq!((declined.partial_jacobians, asked.len()), (0, 0));
    let (off, asked) = run(true, 0);
    assert_eq!((off.partial_jacobians, asked.len()), (0, 0));
}
