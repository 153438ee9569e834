//! What changes while a model is evaluated, kept apart from the model (as MuJoCo keeps
//! `mjData` apart from `mjModel`): the gradient detector's warm starts, the profile and the
//! helper threads. [`BearingModel`] is immutable once built and can be shared between
//! threads and runs; a [`Workspace`] belongs to one run (or one quasi-static analysis) at a
//! time, and [`BearingSystem`] joins the two into the ODE system the integrator drives.
//!
//! Every stage of a right-hand side (`contacts`, `line_contacts`, `detection`,
//! `flange_contacts`, `equations`, `jacobian`) and the quasi-static analysis are methods of
//! [`BearingSystem`]; what only reads the model (its parameters, layout, topology) is
//! reached through it as on the model itself ([`std::ops::Deref`]).

use super::detection::WarmStarts;
use super::model::BearingModel;
use super::params::Detector;
use super::profile::{Profile, Profiler};
use crate::dynamics::integrate::OdeSystem;
use crate::dynamics::team::Team;
use crate::error::{Error, Result};
use nalgebra::DMatrix;
use std::ops::Deref;

/// The data a model's evaluations change: the gradient detector's warm starts (one slot per
/// roller end and flange), the profile (one slot per thread) and the helper threads.
#[derive(Debug)]
pub struct Workspace {
    /// The gradient detector's warm starts, one slot per roller end and flange.
    pub(super) warm_starts: WarmStarts,
    /// The profile, one slot per thread that evaluates the model.
    pub(super) profiler: Profiler,
    /// The helper threads that evaluate contacts and Jacobian columns beside the calling
    /// thread (None: the calling thread only); see [`BearingSystem::map`].
    team: Option<Team>,
}

impl Workspace {
    /// A workspace for evaluating `model` on the calling thread only.
    pub fn single(model: &BearingModel) -> Self {
        Self {
            warm_starts: WarmStarts::new(model.params.roller_count),
            profiler: Profiler::single(),
            team: None,
        }
    }

    /// A workspace for evaluating `model`'s contacts and Jacobian columns on `threads`
    /// threads (a numerical setting: the results do not depend on it, bit for bit, since
    /// every contact and column is computed alone and summed in a fixed order). The
    /// gradient detector keeps one thread: its warm starts carry over from one evaluation
    /// to the next, in an order that threads would change (the race hazard of paper
    /// sect. 5.4). More threads than the cores this process may use are not started: the
    /// helpers spin between jobs, and helpers without a core of their own would wait for
    /// the cores (B1 to 0.05 s with 64 threads on 2 cores: 110 s against 2.4 s on 2).
    pub fn new(model: &BearingModel, threads: usize) -> Result<Self> {
        if threads == 0 {
            return Err(Error::invalid("threads", threads, ">= 1"));
        }
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        let threads = threads.min(cores);
        let team = if threads > 1 && model.params.options.detector != Detector::Gradient {
            // The calling thread works too (BearingSystem::map): threads − 1 helpers.
            let team = Team::new(threads - 1)
                .map_err(|e| Error::invalid("threads", threads, e.to_string()))?;
            Some(team)
        } else {
            None
        };
        Ok(Self {
            warm_starts: WarmStarts::new(model.params.roller_count),
            profiler: Profiler::for_threads(threads),
            team,
        })
    }

    /// Threads that evaluate the model (1: the calling thread only).
    pub fn threads(&self) -> usize {
        self.team.as_ref().map_or(1, |t| t.threads())
    }

    /// Time spent so far, by kind of work.
    pub fn profile(&self) -> Profile {
        self.profiler.total()
    }
}

/// A model with the workspace it is evaluated in: the bearing as an ODE system
/// ([`OdeSystem`]) and the home of every evaluation (right-hand side, Jacobian, energy,
/// statics). Cheap to copy: two references.
#[derive(Clone, Copy)]
pub struct BearingSystem<'a> {
    /// The immutable model.
    pub model: &'a BearingModel,
    /// What its evaluations change.
    pub workspace: &'a Workspace,
}

impl Deref for BearingSystem<'_> {
    type Target = BearingModel;

    fn deref(&self) -> &BearingModel {
        self.model
    }
}

impl BearingModel {
    /// This model evaluated in `workspace` (built for it: [`Workspace::new`]).
    pub fn system<'a>(&'a self, workspace: &'a Workspace) -> BearingSystem<'a> {
        BearingSystem {
            model: self,
            workspace,
        }
    }
}

impl BearingSystem<'_> {
    /// `f(0..n)` in order, on the workspace's threads if it has any ([`Team::map`]: the
    /// calling thread starts at once and the helpers, awake within a run, join it; every
    /// value is computed alone, so the result does not depend on the threads).
    pub(super) fn map<T: Send + Sync>(
        &self,
        n: usize,
        f: impl Fn(usize) -> T + Sync + Send,
    ) -> Vec<T> {
        match &self.workspace.team {
            Some(team) => team.map(n, f),
            None => (0..n).map(f).collect(),
        }
    }

    /// Time spent so far, by kind of work.
    pub fn profile(&self) -> Profile {
        self.workspace.profile()
    }
}

impl OdeSystem for BearingSystem<'_> {
    fn len(&self) -> usize {
        self.layout.len()
    }

    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let kin = self.kinematics(t, y);
        let results = self.evaluate_all(&kin);
        let loads = self.loads(&results);
        self.rates(t, y, &kin, &loads, dy);
    }

    fn jacobian(&self, t: f64, y: &[f64], jac: &mut DMatrix<f64>) {
        self.structured_jacobian(t, y, jac);
    }

    /// Clears the gradient detector's warm starts (checkpoints restart from here).
    fn restart(&self) {
        self.workspace.warm_starts.clear();
    }
}
