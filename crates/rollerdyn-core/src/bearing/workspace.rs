//! What changes while a model is evaluated, kept apart from the model (as MuJoCo keeps
//! `mjData` apart from `mjModel`): the gradient detector's warm starts, the profile, the
//! helper threads and the latest evaluation of every contact. [`BearingModel`] is
//! immutable once built and can be shared between threads and runs; a [`Workspace`]
//! belongs to one run (or one quasi-static analysis) at a time, and [`BearingSystem`]
//! joins the two into the ODE system the integrator drives.
//!
//! Every stage of a right-hand side (`contacts`, `line_contacts`, `detection`,
//! `flange_contacts`, `equations`, `jacobian`) and the quasi-static analysis are methods of
//! [`BearingSystem`]; what only reads the model (its parameters, layout, topology) is
//! reached through it as on the model itself ([`std::ops::Deref`]).

use super::contacts::{ElementResult, Geometry};
use super::detection::{SupportFrames, WarmStarts};
use super::model::BearingModel;
use super::params::{Detector, FlangeLaw};
use super::profile::{Profile, Profiler};
use super::state::BearingKinematics;
use super::topology::Element;
use crate::dynamics::integrate::OdeSystem;
use crate::dynamics::team::Team;
use crate::error::{Error, Result};
use nalgebra::DMatrix;
use std::ops::Deref;
use std::sync::{Mutex, PoisonError};

/// Every contact evaluated at one state: what a Jacobian linearises about
/// ([`BearingSystem::evaluation`]).
pub(super) struct Evaluation {
    /// The model that evaluated it ([`BearingModel::id`]).
    model: u64,
    /// The time and state.
    t: f64,
    y: Vec<f64>,
    /// Each contact's geometry and result, in the order of the model's elements.
    pub(super) geometries: Vec<Geometry>,
    pub(super) results: Vec<ElementResult>,
}

impl std::fmt::Debug for Evaluation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Evaluation")
            .field("model", &self.model)
            .field("t", &self.t)
            .field("contacts", &self.results.len())
            .finish_non_exhaustive()
    }
}

/// The data a model's evaluations change: the gradient detector's warm starts (one slot per
/// roller end and flange), the profile (one slot per thread), the helper threads and the
/// latest right-hand side's evaluation.
#[derive(Debug)]
pub struct Workspace {
    /// The gradient detector's warm starts, one slot per roller end and flange.
    pub(super) warm_starts: WarmStarts,
    /// The distributed flange law's support frames of the step, one slot per roller end
    /// and flange.
    pub(super) support_frames: SupportFrames,
    /// The profile, one slot per thread that evaluates the model.
    pub(super) profiler: Profiler,
    /// The helper threads that evaluate contacts and Jacobian columns beside the calling
    /// thread (None: the calling thread only); see [`BearingSystem::map`].
    team: Option<Team>,
    /// What it was built for: the roller count and whether the model's detector is the
    /// gradient method (which must keep one thread); checked by [`BearingModel::system`].
    built_for: (usize, bool),
    /// The latest right-hand side's evaluation of every contact, which a Jacobian at the
    /// same time and state takes as its base instead of evaluating it again
    /// ([`BearingSystem::evaluation`]).
    latest: Mutex<Option<Evaluation>>,
}

/// The roller count and whether the detector is the gradient method: what a workspace
/// must match.
fn fingerprint(model: &BearingModel) -> (usize, bool) {
    (
        model.params.roller_count,
        model.params.options.detector == Detector::Gradient,
    )
}

impl Workspace {
    /// A workspace for evaluating `model` on the calling thread only.
    pub fn single(model: &BearingModel) -> Self {
        Self {
            warm_starts: WarmStarts::new(model.params.roller_count),
            support_frames: SupportFrames::new(model.params.roller_count),
            profiler: Profiler::single(),
            team: None,
            built_for: fingerprint(model),
            latest: Mutex::new(None),
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
            support_frames: SupportFrames::new(model.params.roller_count),
            profiler: Profiler::for_threads(threads),
            team,
            built_for: fingerprint(model),
            latest: Mutex::new(None),
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

    /// The remembered evaluation.
    fn latest(&self) -> std::sync::MutexGuard<'_, Option<Evaluation>> {
        self.latest.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

/// A model with the workspace it is evaluated in: the bearing as an ODE system
/// ([`OdeSystem`]) and the home of every evaluation (right-hand side, Jacobian, energy,
/// statics). Cheap to copy: two references. Made only by [`BearingModel::system`].
#[derive(Clone, Copy)]
pub struct BearingSystem<'a> {
    /// The immutable model.
    pub(crate) model: &'a BearingModel,
    /// What its evaluations change.
    pub(crate) workspace: &'a Workspace,
}

impl Deref for BearingSystem<'_> {
    type Target = BearingModel;

    fn deref(&self) -> &BearingModel {
        self.model
    }
}

impl BearingModel {
    /// This model evaluated in `workspace`. Panics if the workspace was built for a model
    /// with another roller count (its warm starts would not fit) or another kind of
    /// detector (a gradient model must not run on helper threads): a programming error,
    /// not a user's.
    pub fn system<'a>(&'a self, workspace: &'a Workspace) -> BearingSystem<'a> {
        assert_eq!(
            workspace.built_for,
            fingerprint(self),
            "a workspace built for another model (roller count, gradient detector)"
        );
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

    /// [`Self::map`] with each pair's halves in two lists ([`Team::map_pairs`]: written
    /// straight into their places, without a list of pairs to split).
    pub(super) fn map_pairs<A: Send, B: Send>(
        &self,
        n: usize,
        f: impl Fn(usize) -> (A, B) + Sync + Send,
    ) -> (Vec<A>, Vec<B>) {
        match &self.workspace.team {
            Some(team) => team.map_pairs(n, f),
            None => (0..n).map(f).unzip(),
        }
    }

    /// Time spent so far, by kind of work.
    pub fn profile(&self) -> Profile {
        self.workspace.profile()
    }

    /// Every contact's geometry and result at (t, y) (kinematics `kin`): the remembered
    /// evaluation if it is this model's at the same t and y (taken out of the workspace:
    /// give it back with [`Self::remember`]), else evaluated. A Jacobian is taken at the
    /// latest right-hand side's state (`StepControl::jacobian_at_latest_iterate`), so its
    /// base is that right-hand side's, one evaluation of every contact saved per Jacobian;
    /// a right-hand side at the state of the one before takes it too.
    /// The same numbers either way: an evaluation depends on t and y only (the gradient
    /// detector's, on its warm starts too: its base then keeps those of the right-hand
    /// side's detections).
    pub(super) fn evaluation(&self, t: f64, y: &[f64], kin: &BearingKinematics) -> Evaluation {
        let remembered = self.workspace.latest().take();
        // The same bits (−0.0 is not 0.0 to every function of the state).
        let same = |a: f64, b: f64| a.to_bits() == b.to_bits();
        if let Some(e) = remembered {
            if e.model == self.id
                && same(e.t, t)
                && e.y.len() == y.len()
                && e.y.iter().zip(y).all(|(a, b)| same(*a, *b))
            {
                return e;
            }
        }
        let elements = &self.topology.elements;
        let evaluate = |e: usize| {
            let geometry = self.geometry(&elements[e], kin);
            let result = self.evaluate_at(&elements[e], kin, &geometry);
            (geometry, result)
        };
        let (geometries, results) = self.map_pairs(elements.len(), evaluate);
        Evaluation {
            model: self.id,
            t,
            y: y.to_vec(),
            geometries,
            results,
        }
    }

    /// Keeps `evaluation` for a Jacobian at its state ([`Self::evaluation`]).
    pub(super) fn remember(&self, evaluation: Evaluation) {
        *self.workspace.latest() = Some(evaluation);
    }

    /// With the distributed flange law, takes the support frames of the latest evaluation
    /// (the step's last Newton iterate) as those of the next step's evaluations
    /// ([`super::detection::SupportFrames`]; none where it found no overlap), and forgets
    /// that evaluation: taken from the frames before, it is not the base of a Jacobian
    /// taken from these.
    fn take_support_frames(&self) {
        if self.params.flange_law != FlangeLaw::Distributed {
            return;
        }
        let latest = self.workspace.latest().take();
        self.workspace.support_frames.clear();
        let Some(evaluation) = latest else {
            return;
        };
        for (element, geometry) in self.topology.elements.iter().zip(&evaluation.geometries) {
            if let (Element::End(i, k), Geometry::End(end)) = (element, geometry) {
                self.workspace.support_frames.set(*i, *k, end.support_frame);
            }
        }
    }

    /// Forgets the remembered evaluation, so that the next right-hand side or Jacobian
    /// evaluates every contact (`rollerdyn bench model` times right-hand sides at one
    /// state this way).
    pub fn forget_evaluation(&self) {
        *self.workspace.latest() = None;
    }
}

impl OdeSystem for BearingSystem<'_> {
    fn len(&self) -> usize {
        self.layout.len()
    }

    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let kin = self.kinematics(t, y);
        let evaluation = self.evaluation(t, y, &kin);
        let loads = self.loads(&evaluation.results);
        self.rates(t, y, &kin, &loads, dy);
        self.remember(evaluation);
    }

    fn jacobian(&self, t: f64, y: &[f64], jac: &mut DMatrix<f64>) {
        self.structured_jacobian(t, y, jac);
    }

    fn partial_jacobian(
        &self,
        t: f64,
        y: &[f64],
        states: &[usize],
        jac: &mut DMatrix<f64>,
    ) -> bool {
        self.partial_structured_jacobian(t, y, states, jac)
    }

    /// Clears the gradient detector's warm starts, the distributed law's support frames and
    /// the remembered evaluation (checkpoints restart from here).
    fn restart(&self) {
        self.workspace.warm_starts.clear();
        self.workspace.support_frames.clear();
        self.forget_evaluation();
    }

    fn step_accepted(&self) {
        self.take_support_frames();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bearing::test_b1::{params, B1};
    use crate::bearing::BearingParams;

    /// B1 with `detector`, and its quasi-static equilibrium state at full load and speed
    /// (t = 0 of a run that starts from equilibrium: loaded, rolling, the rollers pressed
    /// against their flanges).
    fn b1_in_motion(detector: Detector) -> (BearingModel, Vec<f64>) {
        let mut p: BearingParams = params(&B1);
        p.options.detector = detector;
        let model = BearingModel::new(p).unwrap();
        let workspace = Workspace::single(&model);
        let y = model.system(&workspace).equilibrium_state(0.0).unwrap();
        (model, y)
    }

    /// f(t, y) on `model` in `workspace`, three times in a row (the gradient detector's
    /// warm starts carry over from one to the next).
    fn rates(model: &BearingModel, workspace: &Workspace, y: &[f64]) -> Vec<Vec<f64>> {
        let system = model.system(workspace);
        (0..3)
            .map(|_| {
                let mut dy = vec![0.0; y.len()];
                system.rhs(0.0, y, &mut dy);
                dy
            })
            .collect()
    }

    /// The model is shared, the workspaces are not: one model evaluated on two threads at
    /// once, at two states, each thread in its own workspace, gives bit for bit what each
    /// state gives alone, for the semi-analytical detector and for the gradient detector
    /// whose warm starts live in the workspace. (With one workspace shared by the two
    /// threads, a thread's next evaluation would start from the other state's solutions:
    /// the gradient detector's rates then differ in their last digits, checked below.)
    #[test]
    fn one_model_serves_two_threads_each_with_its_workspace() {
        fn shared(_: &(impl Send + Sync)) {}
        for detector in [Detector::SemiAnalytical, Detector::Gradient] {
            let (model, y) = b1_in_motion(detector);
            shared(&model);
            // The second state: every roller 0.3 µm further out and 20 µrad more skewed.
            let mut z = y.clone();
            for i in 0..model.layout.rollers {
                let s = model.layout.roller(i);
                let r = (z[s + 1] * z[s + 1] + z[s + 2] * z[s + 2]).sqrt();
                z[s + 1] *= 1.0 + 0.3e-6 / r;
                z[s + 2] *= 1.0 + 0.3e-6 / r;
                z[s + 4] += 20e-6;
            }
            let alone = |y: &[f64]| rates(&model, &Workspace::single(&model), y);
            let (y_alone, z_alone) = (alone(&y), alone(&z));
            let (a, b) = std::thread::scope(|s| {
                let a = s.spawn(|| rates(&model, &Workspace::single(&model), &y));
                let b = s.spawn(|| rates(&model, &Workspace::single(&model), &z));
                (a.join().unwrap(), b.join().unwrap())
            });
            assert!(y_alone
                .iter()
                .chain(&z_alone)
                .flatten()
                .all(|v| v.is_finite()));
            assert_eq!(a, y_alone, "{detector:?}");
            assert_eq!(b, z_alone, "{detector:?}");
            if detector == Detector::Gradient {
                // The same evaluations in one shared workspace, interleaved: they differ.
                let workspace = Workspace::single(&model);
                let system = model.system(&workspace);
                let mut interleaved = Vec::new();
                for _ in 0..3 {
                    for state in [&y, &z] {
                        let mut dy = vec![0.0; y.len()];
                        system.rhs(0.0, state, &mut dy);
                        interleaved.push(dy);
                    }
                }
                let ys: Vec<_> = interleaved.iter().step_by(2).cloned().collect();
                assert_ne!(
                    ys, y_alone,
                    "the warm starts must matter to the last digits"
                );
            }
        }
    }
    /// A partial renewal (`StepControl::partial_jacobians`) takes the columns of the
    /// failing roller and its two neighbours as the whole Jacobian at the same state takes
    /// them, bit for bit, and keeps every other column of the Jacobian it renews; a
    /// failing inner-ring state is declined (the caller renews the whole).
    #[test]
    fn a_partial_renewal_takes_three_rollers_columns_as_the_whole_jacobian_does() {
        let (model, y) = b1_in_motion(Detector::SemiAnalytical);
        let workspace = Workspace::single(&model);
        let system = model.system(&workspace);
        let n = y.len();
        // The state the failed iteration reached: roller 0 0.3 µm further out and
        // 20 µrad more skewed, its skew rate 1 rad/s higher.
        let mut z = y.clone();
        let s = model.layout.roller(0);
        z[s + 1] += 0.3e-6;
        z[s + 4] += 20e-6;
        z[s + 10] += 1.0;
        let whole = |state: &[f64]| {
            let mut jac = DMatrix::zeros(n, n);
            system.jacobian(0.0, state, &mut jac);
            jac
        };
        let (at_y, at_z) = (whole(&y), whole(&z));
        let mut renewed = at_y.clone();
        assert!(system.partial_jacobian(0.0, &z, &[s + 10, s + 4], &mut renewed));
        let z_count = model.layout.rollers;
        let renewed_rollers = [z_count - 1, 0, 1];
        for k in 0..n {
            let expected = match model.layout.body_of(k) {
                Some(i) if renewed_rollers.contains(&i) => &at_z,
                _ => &at_y,
            };
            assert_eq!(renewed.column(k), expected.column(k), "column {k}");
        }
        assert_ne!(
            at_y.column(s + 4),
            at_z.column(s + 4),
            "the states differ there"
        );
        let mut declined = at_y.clone();
        assert!(!system.partial_jacobian(0.0, &z, &[s + 4, 0], &mut declined));
        assert_eq!(declined, at_y);
    }

    /// A Jacobian at the latest right-hand side's time and state takes that right-hand
    /// side's evaluation of every contact as its base: it equals the Jacobian computed
    /// afresh bit for bit, with one right-hand side's detections fewer. At another state,
    /// for another model in the same workspace (B1 without friction: other forces at the
    /// same state) and after a checkpoint's restart it is not taken. A right-hand side at
    /// the state of the one before takes it as well, unless it was forgotten.
    #[test]
    fn a_jacobian_takes_the_latest_right_hand_sides_evaluation() {
        let (model, y) = b1_in_motion(Detector::SemiAnalytical);
        let n = y.len();
        let jacobian = |system: &BearingSystem| {
            let mut jac = DMatrix::zeros(n, n);
            system.jacobian(0.0, &y, &mut jac);
            jac
        };
        let afresh = |m: &BearingModel| {
            let workspace = Workspace::single(m);
            let jac = jacobian(&m.system(&workspace));
            (jac, workspace.profile().detections)
        };
        let (expected, detections_afresh) = afresh(&model);
        let workspace = Workspace::single(&model);
        let system = model.system(&workspace);
        let detections = || workspace.profile().detections;
        let rhs = |system: &BearingSystem| system.rhs(0.0, &y, &mut vec![0.0; n]);
        rhs(&system);
        let per_rhs = detections();
        assert!(per_rhs > 0);
        assert_eq!(jacobian(&system), expected);
        assert_eq!(detections() - per_rhs, detections_afresh - per_rhs);
        // Another state, 1 nm away: evaluated afresh.
        let mut z = y.clone();
        z[model.layout.roller(0) + 1] += 1e-9;
        rhs(&system);
        let before = detections();
        let mut at_z = DMatrix::zeros(n, n);
        system.jacobian(0.0, &z, &mut at_z);
        assert_eq!(detections() - before, detections_afresh);
        let fresh_workspace = Workspace::single(&model);
        let mut fresh_z = DMatrix::zeros(n, n);
        model
            .system(&fresh_workspace)
            .jacobian(0.0, &z, &mut fresh_z);
        assert_eq!(at_z, fresh_z);
        assert_ne!(at_z, expected);
        // Another model, the same workspace and state: its own evaluation.
        let mut p = params(&B1);
        p.options.friction = false;
        let other = BearingModel::new(p).unwrap();
        rhs(&system);
        let frictionless = jacobian(&other.system(&workspace));
        assert_eq!(frictionless, afresh(&other).0);
        assert_ne!(frictionless, expected);
        // A restart forgets it.
        rhs(&system);
        system.restart();
        let before = detections();
        assert_eq!(jacobian(&system), expected);
        assert_eq!(detections() - before, detections_afresh);
        // A right-hand side at the same state takes it too, unless it was forgotten.
        let (mut first, mut again) = (vec![0.0; n], vec![0.0; n]);
        system.rhs(0.0, &y, &mut first);
        let before = detections();
        system.rhs(0.0, &y, &mut again);
        assert_eq!((again.clone(), detections()), (first.clone(), before));
        system.forget_evaluation();
        system.rhs(0.0, &y, &mut again);
        assert_eq!((again, detections()), (first, before + per_rhs));
    }

    /// A workspace goes with the model it was built for: one built for the
    /// semi-analytical detector (which may have helper threads) is refused by a model with
    /// the gradient detector, whose warm starts must not be shared by threads.
    #[test]
    #[should_panic(expected = "a workspace built for another model")]
    fn a_workspace_is_refused_by_another_kind_of_model() {
        let semi = BearingModel::new(params(&B1)).unwrap();
        let mut p = params(&B1);
        p.options.detector = Detector::Gradient;
        let gradient = BearingModel::new(p).unwrap();
        let workspace = Workspace::new(&semi, 2).unwrap();
        let _ = gradient.system(&workspace);
    }

    /// A workspace with two threads (on a machine with two cores or more) gives what one
    /// thread gives, bit for bit: the contacts and Jacobian columns are computed apart and
    /// summed in a fixed order.
    #[test]
    fn the_threads_of_a_workspace_change_no_bit() {
        let (model, y) = b1_in_motion(Detector::SemiAnalytical);
        let n = y.len();
        let evaluate = |threads: usize| {
            let workspace = Workspace::new(&model, threads).unwrap();
            let system = model.system(&workspace);
            let mut dy = vec![0.0; n];
            system.rhs(0.0, &y, &mut dy);
            let mut jac = DMatrix::zeros(n, n);
            system.jacobian(0.0, &y, &mut jac);
            (dy, jac)
        };
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        assert_eq!(
            Workspace::new(&model, 2).unwrap().threads(),
            cores.min(2),
            "two threads where the machine has two cores"
        );
        assert_eq!(evaluate(1), evaluate(2));
        assert!(Workspace::new(&model, 0).is_err());
    }
}
