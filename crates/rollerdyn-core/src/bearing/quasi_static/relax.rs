//! Each roller's own equilibrium with the inner ring held: the inner loop of the
//! quasi-static solver. A roller touches only the rings, so its three unknowns are solved
//! alone, as the minimum of its potential energy (the contact forces are conservative, the
//! unbalanced force is minus the energy's gradient): Newton with a 3×3 Jacobian by forward
//! differences where the roller's stiffness (the symmetric part of −J) is positive
//! definite, else a step from its eigenvalues floored (saddle-free Newton: along a
//! direction nothing holds, a roller resting on one end slice or pinched between two
//! flanges, it follows the unbalanced force); a backtracking line search that accepts a
//! step on which the residual falls or the unbalanced forces do work. A roller that
//! touches no race is first set onto the race its radial force pushes it to, level with
//! it, at the penetration of that force spread evenly over its slices (eq. 11 inverted),
//! because from an open gap the power law gives Newton no stiffness to go by.
use super::roller::{RollerForces, ROLLER_UNKNOWNS};
use super::solver::{Problem, RING_UNKNOWNS};
use crate::bearing::model::LineContact;
use crate::bearing::state::Kinematics;
use nalgebra::{DVector, Matrix3, Vector3};

/// The largest fall of a roller's residual per chord step (the Jacobian kept from an
/// earlier step) for which the Jacobian is kept for the next step.
const CHORD_CONTRACTION: f64 = 0.1;
/// Newton iterations of one roller before it counts as not in equilibrium.
const MAX_ROLLER_ITERATIONS: usize = 30;
/// Trials of the roller's line search (each halving its step).
const ROLLER_LINE_SEARCH: usize = 10;
/// The largest move of a roller in one iteration [m] (arcs for its tilt).
const MAX_ROLLER_MOVE: f64 = 2e-6;

/// The scale of a roller's own tolerance [N]: the sum of its flange forces and of the
/// magnitude of the net contact force on it (near equilibrium about its weight and
/// centrifugal force, not its race loads: a roller's tolerance grows with the flange
/// forces that pinch it, whose tilting couples converge slowly, not with its race load).
fn contact_sum(f: &RollerForces) -> f64 {
    f.flanges.iter().map(|x| x.force).sum::<f64>() + f.on_roller.force.norm()
}

impl Problem<'_> {
    /// Every roller in its own equilibrium with the ring at `u`'s pose (the rollers'
    /// unknowns in `u` updated; a mirrored roller set from its partner): whether all of
    /// them reached it.
    pub(super) fn relax(&mut self, u: &mut [f64], tolerance: f64) -> bool {
        let ring = self.ring(u);
        let mut all = true;
        for i in 0..self.azimuths.len() {
            if self.computed(i) {
                all &= self.relax_roller(&ring, u, i, tolerance);
            }
        }
        self.symmetrize(u);
        all
    }

    /// Whether every roller is in its own equilibrium by the rule of [`Self::relax`]: its
    /// residual in `r` below `tolerance` or 1e-5 of the sum of its contact forces `forces`.
    pub(super) fn rollers_balanced(
        &self,
        forces: &[RollerForces],
        r: &DVector<f64>,
        tolerance: f64,
    ) -> bool {
        forces.iter().enumerate().all(|(i, f)| {
            self.scaled(i, &self.own_residual(r, i)).amax() < tolerance.max(1e-5 * contact_sum(f))
        })
    }

    /// Roller i's forces and residual (radial, axial force, tilting moment) at `u` with the
    /// ring at `ring`.
    pub(super) fn roller_at(
        &mut self,
        ring: &Kinematics,
        u: &[f64],
        i: usize,
    ) -> (RollerForces, Vector3<f64>) {
        self.evaluations += 1;
        let kin = self.pose(u, i).kinematics(self.pitch);
        let f = self.model.quasi_static_roller(ring, &kin, false);
        let r = self.roller_residual(u, i, &f);
        (f, Vector3::from(r))
    }

    /// Roller i's residual over the weights (moments over the roller radius) [N].
    pub(super) fn scaled(&self, i: usize, r: &Vector3<f64>) -> Vector3<f64> {
        let s = RING_UNKNOWNS + ROLLER_UNKNOWNS * i;
        Vector3::from_fn(|a, _| r[a] / self.weight(s + a))
    }

    /// Roller i in its own equilibrium with the ring at `ring` (module doc), to `tolerance`
    /// or 1e-5 of the sum of its contact forces, whichever is larger (a roller pinched
    /// between two flanges and tilted onto its ends converges slowly below that). A roller
    /// that does not get there while pinched between two flanges and touching no race
    /// (at speed, its centrifugal force unbalanced) is set onto its race, at the tilt the
    /// flanges hold it at, and tried once more.
    pub(super) fn relax_roller(
        &mut self,
        ring: &Kinematics,
        u: &mut [f64],
        i: usize,
        tolerance: f64,
    ) -> bool {
        self.relax_attempt(ring, u, i, tolerance, false)
            || self.relax_attempt(ring, u, i, tolerance, true)
    }

    /// One try of [`Self::relax_roller`]; `land_pinched`: set the roller onto its race
    /// when it touches none, even while two flanges pinch it.
    fn relax_attempt(
        &mut self,
        ring: &Kinematics,
        u: &mut [f64],
        i: usize,
        tolerance: f64,
        land_pinched: bool,
    ) -> bool {
        let s = RING_UNKNOWNS + ROLLER_UNKNOWNS * i;
        let (mut f, mut r) = self.roller_at(ring, u, i);
        let mut tol = tolerance;
        let mut refresh = false;
        for _ in 0..MAX_ROLLER_ITERATIONS {
            tol = tolerance.max(1e-5 * contact_sum(&f));
            let size = self.scaled(i, &r).amax();
            if size < tol {
                return true;
            }
            let pinched = f.flanges.iter().any(|x| x.force > 0.0);
            if (land_pinched || !pinched) && self.set_onto_race(ring, u, i, r[0], pinched) {
                (f, r) = self.roller_at(ring, u, i);
                continue;
            }
            // A step from the roller's last Jacobian (chord Newton: one evaluation when
            // the full step is taken), refreshed when the chord step did not lower the
            // residual (the step is taken again) or lowered it slowly (the next one).
            let chord = !refresh && !self.careful && self.roller_jacobians[i].is_some();
            let start: [f64; ROLLER_UNKNOWNS] = std::array::from_fn(|a| u[s + a]);
            let (mut trial_f, mut trial, full) =
                self.roller_search(ring, u, i, &r, refresh || self.careful);
            refresh = false;
            if chord && !full {
                u[s..s + ROLLER_UNKNOWNS].copy_from_slice(&start);
                (trial_f, trial, _) = self.roller_search(ring, u, i, &r, true);
            } else if chord {
                refresh = self.scaled(i, &trial).amax() > CHORD_CONTRACTION * size;
            }
            (f, r) = (trial_f, trial);
        }
        self.scaled(i, &r).amax() < tol
    }

    /// A backtracking line search of roller i from `u` (its residual `r`) along its Newton
    /// step ([`Self::roller_step`], from a `fresh` Jacobian or its last one): accepts a step
    /// on which the residual falls or the unbalanced forces do work, the last trial
    /// otherwise (with the last Jacobian, the full step is the only trial). Leaves the
    /// roller's unknowns in `u` at the step taken and returns its forces, its residual and
    /// whether the full step was taken with a fall of the residual.
    fn roller_search(
        &mut self,
        ring: &Kinematics,
        u: &mut [f64],
        i: usize,
        r: &Vector3<f64>,
        fresh: bool,
    ) -> (RollerForces, Vector3<f64>, bool) {
        let s = RING_UNKNOWNS + ROLLER_UNKNOWNS * i;
        let attempts = if fresh || self.roller_jacobians[i].is_none() {
            ROLLER_LINE_SEARCH
        } else {
            1
        };
        let step = self.roller_step(ring, u, i, r, fresh);
        let merit = self.scaled(i, r).norm_squared();
        let start: [f64; ROLLER_UNKNOWNS] = std::array::from_fn(|a| u[s + a]);
        let mut alpha = 1.0;
        for attempt in 0..attempts {
            for a in 0..ROLLER_UNKNOWNS {
                u[s + a] = start[a] + alpha * step[a];
            }
            let (trial_f, trial) = self.roller_at(ring, u, i);
            let trial_merit = self.scaled(i, &trial).norm_squared();
            // The work of the unbalanced forces over the step (trapezoid): the fall of
            // the roller's potential energy, positive along a direction in which the
            // residual stays flat (a roller tilting about the one slice it rests on).
            let moved = Vector3::from_fn(|a, _| alpha * step[a] * self.weight(s + a));
            let slope = self.scaled(i, r).dot(&moved);
            let work = 0.5 * (self.scaled(i, r) + self.scaled(i, &trial)).dot(&moved);
            let descends = slope > 0.0 && work > 1e-4 * slope;
            let falls = trial_merit < (1.0 - 1e-4 * alpha) * merit;
            if falls || descends || attempt + 1 == attempts {
                return (trial_f, trial, attempt == 0 && falls);
            }
            alpha *= 0.5;
        }
        unreachable!("the last trial is always taken")
    }

    /// Roller i's stiffness in arcs and forces, −∂r/∂q scaled by the weights, by forward
    /// differences at `u` (its residual `r`), kept for the next step of the roller.
    fn roller_jacobian(
        &mut self,
        ring: &Kinematics,
        u: &mut [f64],
        i: usize,
        r: &Vector3<f64>,
    ) -> Matrix3<f64> {
        let s = RING_UNKNOWNS + ROLLER_UNKNOWNS * i;
        let w = self.roller_weights();
        let shrink = self.light_contact_shrink(ring, u, i);
        let mut jac = Matrix3::zeros();
        for c in 0..ROLLER_UNKNOWNS {
            let h = shrink * self.step(s + c);
            let was = u[s + c];
            u[s + c] = was + h;
            let moved = self.roller_at(ring, u, i).1;
            u[s + c] = was;
            for a in 0..ROLLER_UNKNOWNS {
                jac[(a, c)] = (moved[a] - r[a]) / h / (w[a] * w[c]);
            }
        }
        self.roller_jacobians[i] = Some(jac);
        jac
    }

    /// The factor on the difference steps of roller i's own Jacobian: below 1 where its
    /// deepest race slice lies less deep than 20 difference steps (a roller carrying
    /// little more than its weight: 1.7 mN spread over B1's slices is a penetration of
    /// picometres, which a step of 0.1 nm jumps over, so the difference quotient is the
    /// secant to the open gap and the search cycles between the race and the gap), so
    /// that a step is a twentieth of that depth; 1 otherwise (every loaded roller).
    fn light_contact_shrink(&self, ring: &Kinematics, u: &[f64], i: usize) -> f64 {
        let (inner, outer) = self.race_depths(ring, u, i);
        let depth = inner.max(outer);
        let radial_step = self.step(RING_UNKNOWNS + ROLLER_UNKNOWNS * i);
        if depth > 0.0 {
            (0.05 * depth / radial_step).clamp(1e-4, 1.0)
        } else {
            1.0
        }
    }

    /// Roller i's Newton step from its scaled Jacobian (a `fresh` one by forward
    /// differences, else the last one kept, from its own search or the whole problem's
    /// Jacobian), with the stiffness floor on free directions, limited to
    /// [`MAX_ROLLER_MOVE`].
    fn roller_step(
        &mut self,
        ring: &Kinematics,
        u: &mut [f64],
        i: usize,
        r: &Vector3<f64>,
        fresh: bool,
    ) -> Vector3<f64> {
        let w = self.roller_weights();
        let mut jac = match self.roller_jacobians[i] {
            Some(jac) if !fresh => jac,
            _ => self.roller_jacobian(ring, u, i, r),
        };
        let floor = self.floor();
        for a in 0..ROLLER_UNKNOWNS {
            if jac[(a, a)].abs() < floor {
                jac[(a, a)] -= floor;
            }
        }
        let rhs = -self.scaled(i, r);
        let stiffness = -(jac + jac.transpose()) * 0.5;
        let eigen = stiffness.symmetric_eigen();
        let scaled_step = if eigen.eigenvalues.min() >= floor {
            jac.lu().solve(&rhs).unwrap_or_else(|| -rhs / floor)
        } else {
            let v = eigen.eigenvectors;
            let d = eigen.eigenvalues.map(|l| 1.0 / l.abs().max(floor));
            v * Matrix3::from_diagonal(&d) * v.transpose() * (-rhs)
        };
        let largest = scaled_step.amax();
        let scaled_step = if largest > MAX_ROLLER_MOVE {
            scaled_step * (MAX_ROLLER_MOVE / largest)
        } else {
            scaled_step
        };
        Vector3::from_fn(|a, _| scaled_step[a] / w[a])
    }

    /// Roller i's deepest slice penetration at the inner race (the ring at `ring`) and at
    /// the outer race [m], at the unknowns `u` (negative: the smallest gap).
    fn race_depths(&self, ring: &Kinematics, u: &[f64], i: usize) -> (f64, f64) {
        let kin = self.pose(u, i).kinematics(self.pitch);
        (
            self.model.deepest_slice(LineContact::InnerRace, ring, &kin),
            self.model
                .deepest_slice(LineContact::OuterRace, &Kinematics::fixed(), &kin),
        )
    }

    /// Sets roller i, if it touches neither race and a radial force `radial` [N] pushes
    /// it, onto the race it is pushed to (module doc): whether it moved. `pinched`: two
    /// flanges hold it (the flanges give Newton no radial stiffness to go by either).
    fn set_onto_race(
        &mut self,
        ring: &Kinematics,
        u: &mut [f64],
        i: usize,
        radial: f64,
        pinched: bool,
    ) -> bool {
        if radial == 0.0 {
            return false;
        }
        let (mut inner_depth, mut outer_depth) = self.race_depths(ring, u, i);
        if inner_depth > 0.0 || outer_depth > 0.0 {
            return false;
        }
        let line = if radial < 0.0 {
            LineContact::InnerRace
        } else {
            LineContact::OuterRace
        };
        let lines = &self.model.lines;
        let per_slice = radial.abs() / lines.slices.len() as f64;
        let depth = lines
            .kind(line)
            .law
            .deflection(per_slice, lines.slice_length);
        let s = RING_UNKNOWNS + ROLLER_UNKNOWNS * i;
        // Nothing holds the tilt of a roller that touches nothing: it lands level with
        // the race it falls onto, so that its slices meet the race together (a roller
        // landing on one end would be held there by the slice at that end alone). A
        // roller pinched between two flanges keeps the tilt they hold it at (levelled,
        // it would be pinched harder).
        let pose = self.pose(u, i);
        let level = match line {
            LineContact::InnerRace => ring.axis.dot(&pose.radial_direction()).atan2(ring.axis.x),
            _ => 0.0,
        };
        if !pinched && level != pose.tilt {
            u[s + 2] = level;
            (inner_depth, outer_depth) = self.race_depths(ring, u, i);
        }
        // The inner penetration falls as the roller moves out, the outer one rises.
        u[s] += match line {
            LineContact::InnerRace => inner_depth - depth,
            _ => depth - outer_depth,
        };
        true
    }
}
