//! The time-integration driver: a stiff, adaptive, error-controlled solver (diffsol's
//! L-stable singly diagonally implicit Runge–Kutta methods TR-BDF2 and ESDIRK34) for
//! any system y' = f(t, y) that supplies its own Jacobian. It knows nothing of bearings.
//!
//! Results are delivered at fixed output times by the solver's dense output
//! (interpolation), not at solver steps (model-notes, "Outputs"), so they do not depend on
//! the step size. Δt_max caps every step.

use diffsol::{NalgebraLU, NalgebraMat, OdeBuilder, OdeSolverMethod, OdeSolverStopReason, Vector};
use nalgebra::DMatrix;
use std::cell::RefCell;
use std::ops::ControlFlow;
use std::time::Instant;

/// Smallest step before the run is declared failed (step-size collapse) [s].
pub const MIN_STEP: f64 = 1e-13;

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
}

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
    jac: DMatrix<f64>,
}

impl<S: OdeSystem> Counters<'_, S> {
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        let start = Instant::now();
        self.system.rhs(t, y, dy);
        self.stats.rhs_evaluations += 1;
        self.stats.rhs_seconds += start.elapsed().as_secs_f64();
    }

    /// J·v. diffsol assembles its Newton matrix column by column from products with unit
    /// vectors; the Jacobian is computed once per (t, y) and the columns are read off.
    fn jac_mul(&mut self, t: f64, y: &[f64], v: &[f64], out: &mut [f64]) {
        if t != self.key_t || self.key.as_slice() != y {
            let start = Instant::now();
            self.system.jacobian(t, y, &mut self.jac);
            self.key.clear();
            self.key.extend_from_slice(y);
            self.key_t = t;
            self.stats.jacobian_evaluations += 1;
            self.stats.jacobian_seconds += start.elapsed().as_secs_f64();
        }
        let mut nonzero = v.iter().enumerate().filter(|(_, x)| **x != 0.0);
        match (nonzero.next(), nonzero.next()) {
            (None, _) => out.fill(0.0),
            (Some((j, &s)), None) => {
                for (o, c) in out.iter_mut().zip(self.jac.column(j).iter()) {
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

/// Integrates from (t0, y0) to t_end. `observe(t, y)` is called at t0 and at every
/// output time t0 + k·Δt_out ≤ t_end (and at t_end), with the interpolated state; it may
/// stop the run by returning `ControlFlow::Break`.
pub fn integrate<S: OdeSystem>(
    system: &S,
    y0: &[f64],
    t0: f64,
    t_end: f64,
    options: &Options,
    mut observe: impl FnMut(f64, &[f64], &Stats) -> ControlFlow<()>,
) -> Result<Stats, Failure> {
    let n = system.len();
    let wall = Instant::now();
    let counters = RefCell::new(Counters {
        system,
        stats: Stats::default(),
        key: Vec::with_capacity(n),
        key_t: f64::NAN,
        jac: DMatrix::zeros(n, n),
    });
    let fail = |time: f64, message: String, state: Vec<f64>, c: &RefCell<Counters<S>>| {
        let mut stats = c.borrow().stats;
        stats.total_seconds = wall.elapsed().as_secs_f64();
        stats.t_reached = time;
        Failure {
            time,
            message,
            stats: Box::new(stats),
            state,
        }
    };
    let y_init = y0.to_vec();
    let mut problem = OdeBuilder::<NalgebraMat<f64>>::new()
        .t0(t0)
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
            n,
        )
        .build()
        .map_err(|e| fail(t0, e.to_string(), y0.to_vec(), &counters))?;
    // diffsol counts Newton failures over the whole run and gives up after 50 by default;
    // a long run with contacts opening and closing has many, each handled by a Jacobian
    // update or a smaller step. The run fails when the step size collapses instead.
    problem.ode_options.max_nonlinear_solver_failures = usize::MAX / 4;
    problem.ode_options.min_timestep = MIN_STEP;
    let solver = match options.method {
        Method::TrBdf2 => problem.tr_bdf2::<NalgebraLU<f64>>().map(Solver::TrBdf2),
        Method::Esdirk34 => problem.esdirk34::<NalgebraLU<f64>>().map(Solver::Esdirk34),
    };
    let mut solver = solver.map_err(|e| fail(t0, e.to_string(), y0.to_vec(), &counters))?;
    let report = |c: &RefCell<Counters<S>>, t: f64, h: f64| {
        let mut s = c.borrow().stats;
        s.total_seconds = wall.elapsed().as_secs_f64();
        s.t_reached = t;
        s.last_step = h;
        s
    };
    if observe(t0, y0, &report(&counters, t0, 0.0)).is_break() {
        return Ok(report(&counters, t0, 0.0));
    }
    let mut k = 1usize;
    let next_output = |k: usize| (t0 + k as f64 * options.output_interval).min(t_end);
    if let Err(e) = on!(&mut solver, s => s.set_stop_time(t_end)) {
        return Err(fail(t0, e.to_string(), y0.to_vec(), &counters));
    }
    loop {
        on!(&mut solver, s => {
            if s.state().h > options.dt_max {
                *s.state_mut().h = options.dt_max;
            }
        });
        let reason = match on!(&mut solver, s => s.step()) {
            Ok(r) => r,
            Err(e) => {
                let (t, y) = on!(&solver, s => (s.state().t, s.state().y.clone_as_vec()));
                return Err(fail(t, e.to_string(), y, &counters));
            }
        };
        {
            let solver_stats = on!(&solver, s => s.get_statistics().clone());
            let stats = &mut counters.borrow_mut().stats;
            stats.steps += 1;
            stats.error_test_failures = solver_stats.number_of_error_test_failures;
            stats.newton_failures = solver_stats.number_of_nonlinear_solver_fails;
            stats.newton_iterations = solver_stats.number_of_nonlinear_solver_iterations;
        }
        let t = on!(&solver, s => s.state().t);
        let h = on!(&solver, s => s.state().h);
        while next_output(k) <= t + 1e-12 * t.abs().max(1.0) && next_output(k - 1) < t_end {
            let to = next_output(k);
            let y = match on!(&solver, s => s.interpolate(to.min(t))) {
                Ok(y) => y.clone_as_vec(),
                Err(e) => {
                    return Err(fail(
                        t,
                        e.to_string(),
                        on!(&solver, s => s.state().y.clone_as_vec()),
                        &counters,
                    ))
                }
            };
            if !y.iter().all(|v| v.is_finite()) {
                return Err(fail(
                    t,
                    "the state is no longer finite (NaN or infinity)".into(),
                    on!(&solver, s => s.state().y.clone_as_vec()),
                    &counters,
                ));
            }
            if observe(to, &y, &report(&counters, t, h)).is_break() {
                return Ok(report(&counters, t, h));
            }
            k += 1;
        }
        if matches!(reason, OdeSolverStopReason::TstopReached) || t >= t_end {
            return Ok(report(&counters, t, h));
        }
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
mod tests {
    use super::*;

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

    fn run(method: Method) -> (Vec<(f64, Vec<f64>)>, Stats) {
        let options = Options {
            rtol: 1e-8,
            atol: vec![1e-10],
            dt_max: 5e-3,
            dt_initial: 1e-6,
            output_interval: 0.1,
            method,
        };
        let mut out = Vec::new();
        let stats = integrate(&Stiff, &[1.0, 0.0, 1.0], 0.0, 2.0, &options, |t, y, _| {
            out.push((t, y.to_vec()));
            ControlFlow::Continue(())
        })
        .unwrap();
        (out, stats)
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
}
