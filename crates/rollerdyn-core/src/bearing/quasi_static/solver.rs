//! The Newton solver of the quasi-static equilibrium (module doc of [`super`]): the
//! residual forces of the unknowns and the iteration (fast and careful paths, line search,
//! step limit, load continuation); the Jacobian and the condensed step are in
//! [`super::condense`].

use super::mirror::Mirror;
use super::roller::{RollerForces, RollerPose, ROLLER_UNKNOWNS};
use super::{RingTilt, StaticCase, StaticSolution};
use crate::bearing::contacts::Wrench;
use crate::bearing::model::LineContact;
use crate::bearing::params::FlangeLaw;
use crate::bearing::state::Kinematics;
use crate::bearing::topology::FLANGE_NAMES;
use crate::bearing::workspace::BearingSystem;
use crate::dynamics::rigid::axis_from_angles;
use crate::error::{Error, Result};
use crate::geometry::primitives::Vec3;
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};

/// Unknowns of the inner ring: centre (x, y, z) and tilt (θ_y, θ_z).
pub const RING_UNKNOWNS: usize = 5;
/// Newton iterations per load level before the level counts as failed.
const MAX_ITERATIONS: usize = 30;
/// Trials of the line search (each halving the step) before the last is taken anyway.
const LINE_SEARCH_STEPS: usize = 6;
/// Halvings of the load step before the continuation gives up.
const MAX_BISECTIONS: usize = 4;
/// Newton iterations of a whole solve, over every load level, before it gives up: a load
/// the bearing can carry takes 5–12 from the cold start (B1 up to 2 kN axially), while a
/// load it cannot (rollers tipped onto the flange rims, 30 kN axially on B1) would creep
/// on through ever smaller load steps for seconds.
const MAX_TOTAL_ITERATIONS: usize = 60;
/// The largest move of a position (or arc: angle times the roller radius) in one
/// iteration [m] at B1's size: a fifth of B1's axial play, well inside the region where
/// the contacts' linearisation holds ([`Problem::max_move`] scales it with the roller).
const MAX_MOVE: f64 = 4e-6;
/// [`MAX_MOVE`] over B1's roller radius (2.2475 mm; B1 keeps [`MAX_MOVE`]): a larger
/// bearing's contacts deflect in proportion to its size at the same stress (a bearing of
/// B1's proportions on a 80/110 mm raceway, `rollerdyn new`, moves its ring 74 µm
/// radially under its loads against B1's 21 µm, which steps of 4 µm took more than a load
/// level's iterations to reach).
const MAX_MOVE_PER_ROLLER_RADIUS: f64 = 1.77e-3;
/// The rollers' own equilibrium is sought to this share of the ring's unbalanced force
/// while the ring is far from its own (inexact Newton).
const FORCING: f64 = 0.01;
/// Evaluations of one roller's contacts after which the fast path gives way to the
/// careful one: three times what B1's cold start takes on it (1 159), a third of what the
/// careful path takes.
const FAST_PATH_EVALUATIONS: usize = 3500;
/// The largest fall of the ring's residual per step for which the Jacobian is kept for
/// the next step.
const CHORD_CONTRACTION: f64 = 0.3;
/// Forward-difference steps: positions [m] and angles [rad] (an arc of 0.2 nm on B1).
const POSITION_STEP: f64 = 1e-10;
const ANGLE_STEP: f64 = 1e-7;

/// What stays fixed while the equilibrium of one case is sought.
pub(super) struct Problem<'a> {
    pub(super) model: BearingSystem<'a>,
    pub(super) case: StaticCase,
    /// Roller azimuths [rad].
    pub(super) azimuths: Vec<f64>,
    /// Pitch radius [m].
    pub(super) pitch: f64,
    /// Roller spin relative to the set ω_s [rad/s].
    spin: f64,
    /// The roller set's speed in space, ω_c + Ω_c: its speed ω_c relative to the rings'
    /// frame and a planet carrier's speed Ω_c [rad/s]:
    /// what the centrifugal force and the gyroscopic moment of the orbit follow (the
    /// carrier's centrifugal field about the bearing's axis and the Coriolis force of the
    /// orbit together with the orbit's own centrifugal force make (ω_c + Ω_c)² r).
    inertial_orbit: f64,
    /// Gravity and the carrier's centrifugal field at the bearing's axis [m/s²]
    /// ([`StaticCase::roller_field`]).
    roller_field: Vec3,
    /// The share of the external loads applied (continuation).
    load_factor: f64,
    /// Roller radius: the length that turns angles into arcs and moments into forces.
    scale: f64,
    /// Evaluations of one roller's contact forces so far.
    pub(super) evaluations: usize,
    /// A whole roller's stiffness against the inner race at 1 µm [N/m]: the scale of the
    /// stiffness floor.
    reference_stiffness: f64,
    /// Each roller's last Jacobian of its own residual, scaled to arcs and forces (the
    /// chord of its search in [`Self::relax`]).
    pub(super) roller_jacobians: Vec<Option<Matrix3<f64>>>,
    /// The case's mirror symmetry, when it has one and it is used ([`Mirror`]).
    pub(super) mirror: Option<Mirror>,
    /// The careful path: every roller searched at every trial, no kept Jacobians
    /// ([`Self::newton`]).
    pub(super) careful: bool,
    /// The ring's axial position [m] while it is held there and searched apart
    /// ([`super::axial`]); `None`: an unknown like the others.
    pub(super) axial_position: Option<f64>,
}

impl<'a> Problem<'a> {
    pub(super) fn new(model: BearingSystem<'a>, case: &StaticCase) -> Self {
        let p = &model.model.params;
        let pitch = model.pitch_radius();
        let r = p.roller.radius;
        let (orbit, spin) = model.rolling_speeds(case.speed, case.outer_speed);
        let azimuths: Vec<f64> = model
            .roller_azimuths()
            .into_iter()
            .map(|psi| psi + case.roller_set_phase)
            .collect();
        Self {
            model,
            case: *case,
            mirror: Mirror::of(model.model, case, &azimuths),
            azimuths,
            pitch,
            spin,
            inertial_orbit: orbit + case.carrier_speed,
            roller_field: case.roller_field(p),
            load_factor: 1.0,
            scale: r,
            evaluations: 0,
            roller_jacobians: vec![None; model.layout.rollers],
            careful: false,
            axial_position: None,
            reference_stiffness: {
                let lines = &model.model.lines;
                let law = lines.kind(LineContact::InnerRace).law;
                let force = lines.slices.len() as f64 * law.force(1e-6, lines.slice_length);
                force / (law.k2 * 1e-6)
            },
        }
    }

    /// Number of unknowns (ring and rollers, the ring's prescribed tilt included).
    pub(super) fn len(&self) -> usize {
        RING_UNKNOWNS + ROLLER_UNKNOWNS * self.azimuths.len()
    }

    /// Whether unknown k is an angle (its residual a moment).
    pub(super) fn is_angle(&self, k: usize) -> bool {
        if k < RING_UNKNOWNS {
            k >= 3
        } else {
            (k - RING_UNKNOWNS) % ROLLER_UNKNOWNS == 2
        }
    }

    /// The weight of unknown k and of its residual: the roller radius for angles (arcs,
    /// moments over the radius), 1 otherwise.
    pub(super) fn weight(&self, k: usize) -> f64 {
        if self.is_angle(k) {
            self.scale
        } else {
            1.0
        }
    }

    /// The weights of one roller's three unknowns ([`Self::weight`]), the same for every
    /// roller.
    pub(super) fn roller_weights(&self) -> [f64; ROLLER_UNKNOWNS] {
        std::array::from_fn(|a| self.weight(RING_UNKNOWNS + a))
    }

    /// Roller i's three rows of the residual `r`.
    pub(super) fn own_residual(&self, r: &DVector<f64>, i: usize) -> Vector3<f64> {
        let s = RING_UNKNOWNS + ROLLER_UNKNOWNS * i;
        Vector3::new(r[s], r[s + 1], r[s + 2])
    }

    /// The unknowns Newton moves: the ring's centre, its tilt when free, every roller's;
    /// with a mirror symmetry, not the ring's move along z nor its tilt about y; while the
    /// ring's axial position is searched apart, not that.
    pub(super) fn active(&self) -> Vec<usize> {
        let free_tilt = self.case.tilt == RingTilt::Free;
        let mirrored = self.mirror.is_some();
        let axial_held = self.axial_position.is_some();
        (0..self.len())
            .filter(|&k| !(3..RING_UNKNOWNS).contains(&k) || free_tilt)
            .filter(|&k| !(mirrored && (k == 2 || k == 3)))
            .filter(|&k| !(axial_held && k == 0))
            .collect()
    }

    /// Whether roller i is computed rather than mirrored from its partner.
    pub(super) fn computed(&self, i: usize) -> bool {
        self.mirror.as_ref().is_none_or(|m| m.computed(i))
    }

    /// A start for a case with a mirror symmetry taken from one without (a neighbouring
    /// case of a sweep over the roller set's phase): the ring's move along z and tilt about
    /// y, which the symmetric case does not solve for, set to their value 0, and each
    /// mirrored roller set from its partner. Without the symmetry `u` is kept.
    fn symmetric_start(&self, mut u: Vec<f64>) -> Vec<f64> {
        if self.mirror.is_some() {
            (u[2], u[3]) = (0.0, 0.0);
            self.symmetrize(&mut u);
        }
        u
    }

    /// Sets each mirrored roller's unknowns in `u` from its partner's.
    pub(super) fn symmetrize(&self, u: &mut [f64]) {
        if let Some(m) = &self.mirror {
            m.copy_unknowns(u, RING_UNKNOWNS, ROLLER_UNKNOWNS);
        }
    }

    /// The inner ring at rest at the unknowns `u`.
    pub(super) fn ring(&self, u: &[f64]) -> Kinematics {
        Kinematics {
            center: Vec3::new(u[0], u[1], u[2]),
            axis: axis_from_angles(u[3], u[4]),
            velocity: Vec3::zeros(),
            omega: Vec3::zeros(),
        }
    }

    /// Roller i's pose at the unknowns `u`.
    pub(super) fn pose(&self, u: &[f64], i: usize) -> RollerPose {
        let s = RING_UNKNOWNS + ROLLER_UNKNOWNS * i;
        RollerPose::new(self.azimuths[i], &u[s..s + ROLLER_UNKNOWNS])
    }

    /// The contact forces of every roller at the unknowns `u`.
    pub(super) fn evaluate(&mut self, u: &[f64], details: bool) -> Vec<RollerForces> {
        let ring = self.ring(u);
        let mut forces: Vec<RollerForces> = (0..self.azimuths.len())
            .map(|i| {
                if !self.computed(i) {
                    return RollerForces::default();
                }
                let kin = self.pose(u, i).kinematics(self.pitch);
                self.model.quasi_static_roller(&ring, &kin, details)
            })
            .collect();
        match &self.mirror {
            Some(m) => {
                m.copy_forces(&mut forces);
                self.evaluations += m.computed_count();
            }
            None => self.evaluations += self.azimuths.len(),
        }
        forces
    }

    /// Roller i's unbalanced radial force, axial force and tilting moment [N, N, N·m]:
    /// its contact forces, gravity and the centrifugal force, less the moment its steady
    /// precession needs (dH/dt = ω_c x × H with H = J_a(ω·a)a + J_t(ω − (ω·a)a),
    /// ω = ω_c x + ω_s a).
    pub(super) fn roller_residual(&self, u: &[f64], i: usize, f: &RollerForces) -> [f64; 3] {
        let pose = self.pose(u, i);
        let kin = pose.kinematics(self.pitch);
        let m = &self.model.roller_mass;
        let e_r = pose.radial_direction();
        let orbit = self.inertial_orbit;
        let centrifugal = m.mass * orbit * orbit * (self.pitch + pose.radial) * e_r;
        let force = f.on_roller.force + m.mass * self.roller_field + centrifugal;
        let x = Vec3::x();
        let omega = orbit * x + self.spin * kin.axis;
        let along = omega.dot(&kin.axis);
        let momentum =
            m.axial_inertia * along * kin.axis + m.transverse_inertia * (omega - along * kin.axis);
        let needed = orbit * x.cross(&momentum);
        [
            force.dot(&e_r),
            force.x,
            (f.on_roller.moment - needed).dot(&pose.tangential_direction()),
        ]
    }

    /// The external load on the ring at the current load factor: (force, moment).
    fn external(&self) -> (Vec3, Vec3) {
        let c = &self.case;
        let force = self.load_factor * Vec3::new(c.axial_load, -c.radial_load, 0.0)
            + self.model.params.inner_ring_mass * self.model.params.gravity;
        let moment = self.load_factor * Vec3::new(0.0, c.moment[0], c.moment[1]);
        (force, moment)
    }

    /// The rows of the ring's residual from a wrench: Fx, Fy, Fz, My, Mz.
    pub(super) fn ring_rows(w: &Wrench) -> [f64; RING_UNKNOWNS] {
        [w.force.x, w.force.y, w.force.z, w.moment.y, w.moment.z]
    }

    /// The unbalanced forces and moments of every unknown's equation.
    pub(super) fn residual(&self, u: &[f64], forces: &[RollerForces]) -> DVector<f64> {
        let mut r = DVector::zeros(self.len());
        let (force, moment) = self.external();
        let mut ring = Wrench { force, moment };
        for (i, f) in forces.iter().enumerate() {
            ring.add(&f.on_ring);
            let s = RING_UNKNOWNS + ROLLER_UNKNOWNS * i;
            r.as_mut_slice()[s..s + ROLLER_UNKNOWNS]
                .copy_from_slice(&self.roller_residual(u, i, f));
        }
        r.as_mut_slice()[..RING_UNKNOWNS].copy_from_slice(&Self::ring_rows(&ring));
        r
    }

    /// The stiffness given to a direction no contact holds [N/m]: 1e-6 of a roller's
    /// against a race at 1 µm, so that an unbalanced force (a roller's weight) moves it by
    /// at most about a micrometre per step and a balanced one not at all.
    pub(super) fn floor(&self) -> f64 {
        1e-6 * self.reference_stiffness
    }

    /// The largest move of a position (or arc) in one iteration [m]: [`MAX_MOVE`], or in
    /// proportion to the roller where it is larger than B1's.
    pub(super) fn max_move(&self) -> f64 {
        MAX_MOVE.max(MAX_MOVE_PER_ROLLER_RADIUS * self.scale)
    }

    /// The difference step of unknown k.
    pub(super) fn step(&self, k: usize) -> f64 {
        if self.is_angle(k) {
            ANGLE_STEP
        } else {
            POSITION_STEP
        }
    }

    /// The largest unbalanced force of `r` over the active unknowns (moments over the
    /// roller radius) [N].
    fn largest(&self, r: &DVector<f64>, active: &[usize]) -> f64 {
        active
            .iter()
            .map(|&k| (r[k] / self.weight(k)).abs())
            .fold(0.0, f64::max)
    }

    /// The tolerance on the unbalanced forces [N]: 1e-7 of the largest load on the
    /// bearing (external, weights, centrifugal), at least 1 µN (B1 at 5 kN: 0.5 mN, a
    /// tenth of a roller's weight).
    pub(super) fn tolerance(&self) -> f64 {
        let c = &self.case;
        let p = &self.model.params;
        let m = &self.model.roller_mass;
        let z = self.azimuths.len() as f64;
        let body = p.inner_ring_mass * p.gravity.norm()
            + z * m.mass * self.roller_field.norm()
            + z * m.mass * self.inertial_orbit * self.inertial_orbit * self.pitch;
        let external = c.radial_load.abs()
            + c.axial_load.abs()
            + (c.moment[0].abs() + c.moment[1].abs()) / self.scale;
        (1e-7 * (external + body)).max(1e-6)
    }

    /// Newton's method from `u` at the current load factor: the rollers first set into
    /// their own equilibrium ([`Self::relax`]), then coupled Newton steps of the ring and
    /// the rollers together ([`Self::coupled_trial`]), taken when they lower the ring's
    /// residual, with the Jacobian kept while the residual falls fast and a roller searched
    /// alone only to a share ([`FORCING`]) of the ring's residual; where a coupled step
    /// does not help, and on the careful path ([`Self::careful`]) always, the ring's step
    /// is searched with every roller in its own equilibrium at each trial. Returns the
    /// unknowns reached, their residual, whether it converged and the iterations taken.
    fn newton(&mut self, mut u: Vec<f64>) -> (Vec<f64>, DVector<f64>, bool, usize) {
        let all = self.active();
        let ring: Vec<usize> = all.iter().copied().filter(|&k| k < RING_UNKNOWNS).collect();
        let tolerance = self.tolerance();
        let mut rollers_held = self.relax(&mut u, tolerance);
        let mut forces = self.evaluate(&u, false);
        let mut r = self.residual(&u, &forces);
        let mut kept: Option<DMatrix<f64>> = None;
        let mut contraction = 1.0;
        for iteration in 0..MAX_ITERATIONS {
            if !self.careful && self.evaluations > FAST_PATH_EVALUATIONS {
                break;
            }
            if self.largest(&r, &ring) < tolerance {
                if rollers_held {
                    return (u, r, true, iteration);
                }
                // The ring is balanced and some roller is not: its own search sets it.
                rollers_held = self.relax(&mut u, tolerance);
                forces = self.evaluate(&u, false);
                r = self.residual(&u, &forces);
                if rollers_held && self.largest(&r, &ring) < tolerance {
                    return (u, r, true, iteration);
                }
            }
            // The Jacobian is kept for the next iteration while the residual falls fast
            // (chord Newton: a Jacobian costs six evaluations of every roller).
            if contraction > CHORD_CONTRACTION || self.careful {
                kept = None;
            }
            let jac = kept.get_or_insert_with(|| self.jacobian(&u, &forces, &ring));
            let step = self.condensed_step(jac, &r, &ring);
            let merit = self.merit(&r, &ring);
            // Inexact Newton: a roller searched alone is balanced to a share (FORCING) of
            // the ring's unbalanced force.
            let loose = if self.careful {
                tolerance
            } else {
                tolerance.max(FORCING * self.largest(&r, &ring))
            };
            if !self.careful {
                let (trial, trial_forces, trial_r, held) = self.coupled_trial(&u, &r, &step, loose);
                if self.merit(&trial_r, &ring) < (1.0 - 1e-4) * merit {
                    contraction = (self.merit(&trial_r, &ring) / merit).sqrt();
                    (u, forces, r) = (trial, trial_forces, trial_r);
                    rollers_held = held && self.rollers_balanced(&forces, &r, tolerance);
                    continue;
                }
            }
            let mut alpha = 1.0;
            for attempt in 0..LINE_SEARCH_STEPS {
                let mut trial: Vec<f64> = u.iter().zip(&step).map(|(a, d)| a + alpha * d).collect();
                let held = self.relax(&mut trial, loose);
                let trial_forces = self.evaluate(&trial, false);
                let trial_r = self.residual(&trial, &trial_forces);
                let trial_merit = self.merit(&trial_r, &ring);
                let last = attempt + 1 == LINE_SEARCH_STEPS;
                if (trial_merit.is_finite() && trial_merit < (1.0 - 1e-4 * alpha) * merit) || last {
                    (u, forces, r) = (trial, trial_forces, trial_r);
                    rollers_held = held && self.rollers_balanced(&forces, &r, tolerance);
                    contraction = 1.0;
                    break;
                }
                alpha *= 0.5;
            }
        }
        let converged = rollers_held && self.largest(&r, &ring) < tolerance;
        (u, r, converged, MAX_ITERATIONS)
    }

    /// The coupled Newton step `step` from `u` (residual `r`): the ring's move and each
    /// roller's predicted move whole, except for a roller whose own residual the
    /// prediction leaves larger than it was (one that a contact holds only weakly, or
    /// that a contact meets or leaves within the step): that one is searched alone from
    /// there ([`Self::relax_roller`], to `loose`). The unknowns, forces and residual
    /// reached, and whether every roller searched alone reached its equilibrium.
    fn coupled_trial(
        &mut self,
        u: &[f64],
        r: &DVector<f64>,
        step: &[f64],
        loose: f64,
    ) -> (Vec<f64>, Vec<RollerForces>, DVector<f64>, bool) {
        let mut trial: Vec<f64> = u.iter().zip(step).map(|(a, d)| a + d).collect();
        let mut trial_forces = self.evaluate(&trial, false);
        let ring = self.ring(&trial);
        let mut held = true;
        for (i, forces) in trial_forces.iter_mut().enumerate() {
            if !self.computed(i) {
                continue;
            }
            let before = self.scaled(i, &self.own_residual(r, i)).amax();
            let after = self.roller_residual(&trial, i, forces);
            if self.scaled(i, &Vector3::from(after)).amax() > before.max(loose) {
                held &= self.relax_roller(&ring, &mut trial, i, loose);
                *forces = self.roller_at(&ring, &trial, i).0;
            }
        }
        self.symmetrize(&mut trial);
        if let Some(m) = &self.mirror {
            m.copy_forces(&mut trial_forces);
        }
        let trial_r = self.residual(&trial, &trial_forces);
        (trial, trial_forces, trial_r, held)
    }

    /// Σ (r_k / w_k)² over the unknowns `which`.
    fn merit(&self, r: &DVector<f64>, which: &[usize]) -> f64 {
        which.iter().map(|&k| (r[k] / self.weight(k)).powi(2)).sum()
    }

    /// The start of the search: the ring moved along its load by the radial clearance
    /// and 1 µm, the rollers it faces (or whose body forces push them out) on the outer
    /// race, the others on the inner; along an axial load the rollers against the outer
    /// ring's loaded flange and the ring by both axial plays and 3 µm more.
    fn guess(&self) -> Vec<f64> {
        let mut u = vec![0.0; self.len()];
        let p = &self.model.params;
        if let RingTilt::Prescribed(a, b) = self.case.tilt {
            u[3] = a;
            u[4] = b;
        }
        let (force, _) = self.external();
        let across = Vec3::new(0.0, force.y, force.z);
        let clearance = p.outer_raceway_radius - p.inner_raceway_radius - 2.0 * p.roller.radius;
        let down = if across.norm() > 0.0 {
            across.normalize()
        } else {
            Vec3::zeros()
        };
        u[1] = (clearance + 1e-6) * down.y;
        u[2] = (clearance + 1e-6) * down.z;
        let m = &self.model.roller_mass;
        for i in 0..self.azimuths.len() {
            let pose = self.pose(&u, i);
            let e_r = pose.radial_direction();
            let outward = m.mass
                * (self.roller_field.dot(&e_r)
                    + self.inertial_orbit * self.inertial_orbit * self.pitch);
            let s = RING_UNKNOWNS + ROLLER_UNKNOWNS * i;
            u[s] = if e_r.dot(&down) > 0.0 || outward > 0.0 {
                0.5 * clearance
            } else {
                -0.5 * clearance + Vec3::new(0.0, u[1], u[2]).dot(&e_r)
            };
            if force.x != 0.0 {
                u[s + 1] = force.x.signum() * p.outer_axial_play;
            }
        }
        if force.x != 0.0 {
            u[0] = force.x.signum() * (p.inner_axial_play + p.outer_axial_play + 3e-6);
        }
        if let Some(x) = self.axial_position {
            u[0] = x;
        }
        u
    }

    /// The equilibrium from `start` (or from [`Self::guess`]): by the fast path
    /// ([`Self::newton`]), and where that fails, by the careful one. A `start` (another
    /// case's solution, e.g. a sweep's neighbour) that leads to none is dropped for the
    /// guess: the continuation from it runs in this case's load from zero, far from the
    /// neighbour's state (B1 swept from 0 to 1000 N axially found no equilibrium at 1000 N
    /// from the 0 N solution, and one from the guess).
    pub(super) fn solve(
        &mut self,
        start: Option<Vec<f64>>,
    ) -> Result<(Vec<f64>, DVector<f64>, usize)> {
        let found = self.solve_coupled(start);
        match found {
            // The axial position of a lightly loaded ring searched apart ([`super::axial`]);
            // where that finds none either, the coupled solver's error stands.
            Err(e) if self.axial_load_is_light() => self.axial_search().map_err(|_| e),
            found => found,
        }
    }

    /// [`Self::solve`] with every unknown solved together: from `start`, and where that
    /// fails, cold.
    fn solve_coupled(
        &mut self,
        start: Option<Vec<f64>>,
    ) -> Result<(Vec<f64>, DVector<f64>, usize)> {
        if start.is_none() {
            return self.solve_by_both_paths(None);
        }
        self.solve_by_both_paths(start).or_else(|_| {
            // a cold search exactly as without a start: a warm start must never decide
            // whether an equilibrium is found (the evaluations spent from the start would
            // otherwise cut the cold fast path short; B1 at 0.03° misalignment and 0 N
            // after 0° and 500 N was refused so, 2026-12-01)
            self.careful = false;
            self.evaluations = 0;
            self.roller_jacobians.iter_mut().for_each(|j| *j = None);
            self.solve_by_both_paths(None)
        })
    }

    /// [`Self::solve`] from `start` by the fast path, then the careful one.
    pub(super) fn solve_by_both_paths(
        &mut self,
        start: Option<Vec<f64>>,
    ) -> Result<(Vec<f64>, DVector<f64>, usize)> {
        match self.continuation(start.clone()) {
            Ok(found) => Ok(found),
            Err(_) => {
                // The fast path's shortcuts (coupled steps, loose rollers, kept Jacobians)
                // can stall where a roller's contacts jump (a roller end lying flat on a
                // flange); the careful path searches every roller at every trial.
                self.careful = true;
                self.roller_jacobians.iter_mut().for_each(|j| *j = None);
                self.continuation(start)
            }
        }
    }

    /// [`Self::solve`] by the current path: Newton at the full load, and where it fails,
    /// continuation from the last load level reached in steps halved up to
    /// [`MAX_BISECTIONS`] times.
    fn continuation(&mut self, start: Option<Vec<f64>>) -> Result<(Vec<f64>, DVector<f64>, usize)> {
        let mut u = start.unwrap_or_else(|| {
            self.load_factor = 1.0;
            self.guess()
        });
        let (mut reached, mut step, mut iterations): (f64, f64, usize) = (0.0, 1.0, 0);
        let mut halvings = 0;
        // The unknowns of the last load level reached, if any.
        let mut held: Option<Vec<f64>> = None;
        loop {
            self.load_factor = (reached + step).min(1.0);
            let (found, r, converged, taken) = self.newton(u.clone());
            iterations += taken;
            if converged {
                u = found;
                reached = self.load_factor;
                if reached >= 1.0 {
                    return Ok((u, r, iterations));
                }
                if iterations > MAX_TOTAL_ITERATIONS {
                    return Err(self.failure(reached, &r, Some(&u)));
                }
                held = Some(u.clone());
                // A halving of a doubled step past the whole load must change the level.
                step = (2.0 * step).min(1.0 - reached);
                continue;
            }
            halvings += 1;
            let spent = !self.careful && self.evaluations > FAST_PATH_EVALUATIONS;
            if halvings > MAX_BISECTIONS || iterations > MAX_TOTAL_ITERATIONS || spent {
                return Err(self.failure(reached, &r, held.as_deref()));
            }
            step *= 0.5;
        }
    }

    /// The error of a case whose equilibrium was not found, `reached` the share of the
    /// load carried at the unknowns `held`. Where the flanges at that level are already
    /// pressed past ISO 76's limit, that is the reason given (the load is past what the
    /// flanges carry whether or not its equilibrium could be found); where the residual
    /// left is within the tolerance, the iteration budget ran out in ever smaller load
    /// steps. With the ring's tilt free and the point law, the message names the
    /// distributed law, whose contact does not jump along the rims.
    fn failure(&mut self, reached: f64, r: &DVector<f64>, held: Option<&[f64]>) -> Error {
        if let Some(u) = held {
            let forces = self.evaluate(u, true);
            if let Err(e) = check_flange_pressures(&self.case, &forces, reached) {
                return e;
            }
        }
        let hint = if self.case.tilt == RingTilt::Free
            && self.model.model.params.flange_law == FlangeLaw::Point
        {
            "; with the ring's tilt free, the point law's flange contact jumps along the rims \
             (docs/dynamics.md, \"Free inner ring tilt\"): try surfaces.flange_law = \
             \"distributed\""
        } else {
            ""
        };
        self.no_equilibrium(reached, r, hint)
    }

    /// The "no quasi-static equilibrium" error: the load level reached, and the largest
    /// residual left with its body, or the iteration budget where that residual is within
    /// the tolerance.
    pub(super) fn no_equilibrium(&self, reached: f64, r: &DVector<f64>, hint: &str) -> Error {
        let active = self.active();
        let worst = active
            .iter()
            .copied()
            .max_by(|&a, &b| {
                (r[a] / self.weight(a))
                    .abs()
                    .total_cmp(&(r[b] / self.weight(b)).abs())
            })
            .unwrap_or(0);
        let tolerance = self.tolerance() * self.weight(worst);
        let unit = if self.is_angle(worst) { "N m" } else { "N" };
        let why = if r[worst].abs() < tolerance {
            format!(
                "no quasi-static equilibrium within {MAX_TOTAL_ITERATIONS} Newton iterations: \
                 reached {:.0} % of the load in ever smaller load steps (each level balanced \
                 to the tolerance, {tolerance:.1e} {unit}); the bearing may not carry this load",
                100.0 * reached,
            )
        } else {
            format!(
                "no quasi-static equilibrium: reached {:.0} % of the load; at the next level the \
                 residual is {:.3e} on {} (tolerance {tolerance:.1e} {unit}); the bearing may not \
                 carry this load",
                100.0 * reached,
                r[worst],
                self.unknown_name(worst),
            )
        };
        // The continuation scales the loads, not a misalignment: where not even a sixteenth
        // of the load is carried, the tilt itself may be too much (B1 at 0.3° without axial
        // load presses its flanges at 6.3 GPa; at 1° no equilibrium is found).
        let misalignment = if self.case.misalignment().is_some() && reached == 0.0 {
            "; the misalignment is applied whole at every load level, so it may itself be more \
             than the rollers take (inner_ring.misalignment)"
        } else {
            ""
        };
        Error::invalid(
            "load",
            self.case.describe(),
            format!("{why}{misalignment}{hint}"),
        )
    }

    /// Which body and direction unknown k belongs to.
    fn unknown_name(&self, k: usize) -> String {
        if k < RING_UNKNOWNS {
            return format!(
                "the inner ring ({})",
                [
                    "force x [N]",
                    "force y [N]",
                    "force z [N]",
                    "moment y [N m]",
                    "moment z [N m]"
                ][k]
            );
        }
        let (i, j) = (
            (k - RING_UNKNOWNS) / ROLLER_UNKNOWNS,
            (k - RING_UNKNOWNS) % ROLLER_UNKNOWNS,
        );
        let what = [
            "radial force [N]",
            "axial force [N]",
            "tilting moment [N m]",
        ][j];
        format!("roller {i} ({what})")
    }
}

impl BearingSystem<'_> {
    /// The quasi-static equilibrium of `case` (module doc of [`super`]), from the unknowns
    /// of `start` (a neighbouring case's solution) or from the loads' contacts.
    pub fn statics(
        &self,
        case: &StaticCase,
        start: Option<&StaticSolution>,
    ) -> Result<StaticSolution> {
        let solution = self
            .elastic_equilibrium(case, start)
            .map_err(|e| self.with_point_law_hint(case, e))?;
        check_flange_pressures(case, &solution.forces, 1.0)?;
        Ok(solution)
    }

    /// A point-law case's "no quasi-static equilibrium" (the ring locked) with the
    /// distributed law named: B1 with the point law finds none at 2000 N axially under
    /// 5 kN radially, at 1000 N without radial load, at 1000 N under 1000 N and at 500 N
    /// under 100 N with 0.01° misalignment, where the rollers tip
    /// onto their end faces and the point contact jumps across them, while the
    /// distributed law finds every such case up to ISO 76's flange limit (docs/statics.md).
    /// (With the tilt free the solver names it already; the point law's load check before
    /// a run, which calls [`Self::elastic_equilibrium`], names it in its own words.)
    fn with_point_law_hint(&self, case: &StaticCase, e: Error) -> Error {
        match e {
            Error::Invalid { name, value, rule }
                if self.params.flange_law == FlangeLaw::Point
                    && case.tilt != RingTilt::Free
                    && rule.starts_with("no quasi-static equilibrium") =>
            {
                Error::Invalid {
                    name,
                    value,
                    rule: format!(
                        "{rule}; where the axial load tips the rollers onto their end faces \
                         (B1 from about 2 kN under 5 kN radially, from 0.5-1 kN under light \
                         radial loads or with a misalignment), the \
                         point law's flange contact jumps across the face (docs/statics.md): \
                         try surfaces.flange_law = \"distributed\""
                    ),
                }
            }
            e => e,
        }
    }

    /// [`Self::statics`] without ISO 76's flange limit: the elastic equilibrium, however
    /// hard its roller ends press the flanges (B1 at 10 kN axially: 15.6 GPa, the most
    /// loaded end's edge torus on a flange rim), for a judgement of where the rollers lie
    /// ([`BearingSystem::check_point_law`]).
    pub(crate) fn elastic_equilibrium(
        &self,
        case: &StaticCase,
        start: Option<&StaticSolution>,
    ) -> Result<StaticSolution> {
        case.check()?;
        self.params
            .check_axial_load_path("axial_load", case.axial_load)?;
        let mut problem = Problem::new(*self, case);
        let from = start.map(|s| problem.symmetric_start(unknowns_of(s, &problem)));
        let (u, r, iterations) = problem.solve(from)?;
        let forces = problem.evaluate(&u, true);
        let mut ring_load = Wrench::default();
        for f in &forces {
            ring_load.add(&f.on_ring);
        }
        let active = problem.active();
        Ok(StaticSolution {
            case: *case,
            ring: [u[0], u[1], u[2], u[3], u[4]],
            rollers: (0..self.layout.rollers)
                .map(|i| problem.pose(&u, i))
                .collect(),
            forces,
            ring_load,
            residual: problem.largest(&r, &active),
            iterations,
            evaluations: problem.evaluations,
        })
    }
}

/// The largest Hertz pressure at a roller end–flange contact that a solution may have
/// [Pa]: ISO 76's limit of the static load rating of roller bearings (4 000 MPa at the
/// centre of the most heavily loaded contact). Beyond it the axial load is more than the
/// flanges carry: B1 at 10 and 20 kN axially has elastic "equilibria" at 16 and 19 GPa,
/// with the rollers tipped by about 20 mrad and their ends tens of µm deep in the flange
/// rims, states of a bearing that has failed.
pub const FLANGE_PRESSURE_LIMIT: f64 = 4.0e9;

/// Refuses an equilibrium whose flange contacts exceed [`FLANGE_PRESSURE_LIMIT`], found at
/// the share `reached` of the case's load (1: the whole load).
fn check_flange_pressures(case: &StaticCase, forces: &[RollerForces], reached: f64) -> Result<()> {
    let worst = super::flange_loads(forces)
        .map(|(i, k, x)| (i, k, x.pressure))
        .max_by(|a, b| a.2.total_cmp(&b.2));
    match worst {
        Some((i, k, pressure)) if pressure > FLANGE_PRESSURE_LIMIT => Err(Error::invalid(
            "load",
            case.describe(),
            format!(
                "the flanges cannot carry it: at equilibrium{} roller {i} presses the {} flange \
                 at {:.1} GPa, above the {:.0} GPa of ISO 76's static limit",
                if reached < 1.0 {
                    format!(" under {:.0} % of the load", 100.0 * reached)
                } else {
                    String::new()
                },
                FLANGE_NAMES[k],
                pressure / 1e9,
                FLANGE_PRESSURE_LIMIT / 1e9
            ),
        )),
        _ => Ok(()),
    }
}

/// The unknowns of a solution, with the ring's tilt set to `problem`'s when prescribed.
pub(super) fn unknowns_of(s: &StaticSolution, problem: &Problem) -> Vec<f64> {
    let mut u = s.ring.to_vec();
    if let RingTilt::Prescribed(a, b) = problem.case.tilt {
        u[3] = a;
        u[4] = b;
    }
    for pose in &s.rollers {
        u.extend([pose.radial, pose.axial, pose.tilt]);
    }
    u
}
