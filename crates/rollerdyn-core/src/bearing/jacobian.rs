//! The Jacobian ∂f/∂y of the equations of motion, by finite differences per body (a
//! roller couples only to its neighbours and the rings): perturbing one state of
//! roller i re-evaluates only roller i's eight contacts, and changes only the rows of
//! roller i, its two neighbours and the inner ring. A velocity moves no contact, so its
//! columns reuse the slice geometry and the detected flange contacts of the unperturbed
//! state (`Geometry`). A contact's forces depend on the two bodies' relative pose and
//! velocity, so moving the inner ring by δ does to each of its contacts about what moving
//! the roller by −δ does (not exactly: the entrainment speeds are taken in the roller's
//! frame, which orbits with the roller's own position and velocity, so the ring's columns
//! leave out about a fifth, |P − c|/ρ, of the entrainment's change; only the Newton
//! matrix sees it, docs/performance-log.md, "The inner ring's Jacobian columns from the
//! rollers'"): the ring's translation and velocity columns are assembled from
//! the rollers' corresponding columns (their ring contacts' changes, negated) instead of
//! evaluating every ring contact again; its tilt columns are differenced. After a failed
//! Newton iteration the integrator may ask for the columns of a few rollers only
//! (`partial_structured_jacobian`), computed as here. The columns are
//! computed apart, on the workspace's threads if it has any, and written in order: the
//! numbers do not depend on the thread count.
//!
//! Also the per-state scales of the difference steps and of the integrator's absolute
//! tolerances.

use super::contacts::{ElementResult, Geometry, Wrench};
use super::equations::{BodyField, Loads};
use super::state::{ring_kinematics, roller_kinematics, BearingKinematics, ROLLER_STATES};
use super::topology::Body;
use crate::bearing::workspace::BearingSystem;
use nalgebra::DMatrix;

/// Per-state scale for the Jacobian's difference steps: lengths are measured in metres,
/// angles by the roller radius, velocities over a 1 ms time scale.
const TIME_SCALE: f64 = 1e-3;

/// What every column of a Jacobian shares: the state, its kinematics, the contacts'
/// geometry and results, and the summed loads.
struct Linearisation<'a> {
    t: f64,
    y: &'a [f64],
    kin: &'a BearingKinematics,
    geometries: &'a [Geometry],
    results: &'a [ElementResult],
    loads: Loads,
    /// Each roller's drag at the state.
    drags: Vec<Wrench>,
    /// Gravity and the carrier's frame at t.
    field: BodyField,
}

/// One column of the Jacobian: (row, value) pairs and, for a roller's translation or
/// velocity column, what it changed in the roller's inner-ring contacts.
struct Column {
    entries: Vec<(usize, f64)>,
    /// The difference step.
    step: f64,
    /// For each of the roller's inner-ring contacts: (new − old) wrench on the ring and on
    /// the roller (only for a roller's translation and velocity columns).
    ring_changes: Vec<(Wrench, Wrench)>,
}

/// State k moved by its difference step ([`BearingSystem::jacobian_column`]).
struct Perturbation {
    /// The moved state vector.
    state: Vec<f64>,
    /// The step taken (after round-off).
    step: f64,
    /// The kinematics at the moved state.
    kin: BearingKinematics,
    /// The roller moved (None: the inner ring).
    body: Option<usize>,
}

/// The loads after a [`Perturbation`]: the summed loads, which bodies the evaluated
/// contacts touch, and what the moved roller's inner-ring contacts changed.
struct ChangedLoads {
    loads: Loads,
    touched_ring: bool,
    touched: Vec<bool>,
    ring_changes: Vec<(Wrench, Wrench)>,
}

/// The roller state (local index) that moves a roller as inner-ring state `k` moves the
/// ring, for the ring's translations (0–2) and velocities (3–5); `None` for its tilt.
fn roller_twin(k: usize) -> Option<usize> {
    match k {
        0..=2 => Some(k),
        3..=5 => Some(k + 2),
        _ => None,
    }
}

/// Writes column k of `jac`: the (row, value) pairs, zero elsewhere.
fn set_column(jac: &mut DMatrix<f64>, k: usize, entries: &[(usize, f64)]) {
    jac.column_mut(k).fill(0.0);
    for &(row, value) in entries {
        jac[(row, k)] = value;
    }
}

/// Whether a roller's state (local index) is the twin of an inner-ring state.
fn has_ring_twin(local: usize) -> bool {
    (0..6).any(|k| roller_twin(k) == Some(local))
}

impl BearingSystem<'_> {
    /// Absolute tolerances per state for a length tolerance `atol` [m]: lengths in m,
    /// angles by the roller radius, velocities as the speed that moves a body by `atol`
    /// within `time_scale` [s] (config `solver.atol_time_scale`).
    pub fn absolute_tolerances(&self, atol: f64, time_scale: f64) -> Vec<f64> {
        let r = self.params.roller.radius;
        (0..self.layout.len())
            .map(|k| atol * self.scale_over(k, time_scale) / r)
            .collect()
    }

    /// Typical magnitude of state k relative to a length of one roller radius, with
    /// velocities over [`TIME_SCALE`] (the finite-difference steps of the Jacobian).
    fn scale(&self, k: usize) -> f64 {
        self.scale_over(k, TIME_SCALE)
    }

    /// Whether state k is a velocity or an angular velocity (it moves no contact).
    fn is_velocity(&self, k: usize) -> bool {
        match self.layout.body_of(k) {
            None => matches!(k, 3..=5) || k >= 8,
            Some(i) => k - self.layout.roller(i) >= 5,
        }
    }

    /// [`Self::scale`] with velocities over `time_scale` [s].
    fn scale_over(&self, k: usize, time_scale: f64) -> f64 {
        let r = self.params.roller.radius;
        let local = match self.layout.body_of(k) {
            None => k,
            Some(i) => k - self.layout.roller(i),
        };
        let ring = self.layout.body_of(k).is_none();
        match (ring, local) {
            (_, 0..=2) => r,
            (true, 3..=5) | (false, 5..=7) => r / time_scale,
            (true, 6..=7) | (false, 3..=4) => 1.0,
            _ => 1.0 / time_scale,
        }
    }

    /// Evaluates every contact at (t, y) (or takes the latest right-hand side's
    /// evaluation there, [`Self::evaluation`]) and hands `f` the linearisation point and
    /// the rates there.
    fn with_linearisation<R>(
        &self,
        t: f64,
        y: &[f64],
        f: impl FnOnce(&Linearisation, &[f64]) -> R,
    ) -> R {
        let kin = self.kinematics(t, y);
        let evaluation = self.evaluation(t, y, &kin);
        let base = Linearisation {
            t,
            y,
            kin: &kin,
            geometries: &evaluation.geometries,
            loads: self.loads(&evaluation.results),
            results: &evaluation.results,
            drags: kin.rollers.iter().map(|r| self.roller_drag(r)).collect(),
            field: self.body_field(t),
        };
        let mut f0 = vec![0.0; self.layout.len()];
        self.rates_with(t, y, &kin, &base.loads, |i| base.drags[i], &mut f0);
        let jacobian = f(&base, &f0);
        self.remember(evaluation);
        jacobian
    }

    /// The Jacobian by per-body finite differences (see the module doc), its columns
    /// computed apart (on the workspace's threads) and written in order.
    pub(super) fn structured_jacobian(&self, t: f64, y: &[f64], jac: &mut DMatrix<f64>) {
        self.with_linearisation(t, y, |base, f0| {
            let m = self.layout.ring_states();
            let rollers = self.map(y.len() - m, |j| self.jacobian_column(base, f0, m + j));
            let ring = self.map(m, |k| match roller_twin(k) {
                Some(local) => self.ring_column_from_rollers(base, f0, k, local, &rollers),
                None => self.jacobian_column(base, f0, k).entries,
            });
            let entries = ring.iter().chain(rollers.iter().map(|c| &c.entries));
            for (k, column) in entries.enumerate() {
                set_column(jac, k, column);
            }
        });
    }

    /// The rollers whose columns a partial renewal takes anew for a failed Newton
    /// iteration whose largest updates were in `states`: their owners and the owners'
    /// neighbours (a roller's rates depend on its neighbours' states through the
    /// roller–roller contacts); `None` if one of the states is the inner ring's (its
    /// contacts reach every roller: the whole Jacobian is renewed then).
    fn rollers_to_renew(&self, states: &[usize]) -> Option<Vec<usize>> {
        let z = self.layout.rollers;
        let mut chosen = vec![false; z];
        for &k in states {
            let i = self.layout.body_of(k)?;
            for j in [i + z - 1, i, i + 1] {
                chosen[j % z] = true;
            }
        }
        Some((0..z).filter(|&i| chosen[i]).collect())
    }

    /// Renews, at (t, y), the columns of the rollers that own `states` and of their
    /// neighbours ([`Self::rollers_to_renew`]), and keeps the other columns of `jac` (a
    /// Jacobian of a nearby state); `false` (and `jac` untouched) if a state is the inner
    /// ring's. The columns renewed are computed as [`Self::structured_jacobian`] computes
    /// them, so a column is the same whichever way it was renewed (for the gradient
    /// detector, whose warm starts remember earlier evaluations, up to those). Used after a
    /// failed Newton iteration (`StepControl::partial_jacobians`): the failures at B1's
    /// full speed come from a few rollers; a partial renewal there takes 6.5 of the 17
    /// rollers on average and about half a whole Jacobian's time. The inner ring's
    /// columns are kept too, with their entries in the renewed rollers' rows.
    pub(super) fn partial_structured_jacobian(
        &self,
        t: f64,
        y: &[f64],
        states: &[usize],
        jac: &mut DMatrix<f64>,
    ) -> bool {
        let Some(rollers) = self.rollers_to_renew(states) else {
            return false;
        };
        let columns: Vec<usize> = rollers
            .iter()
            .flat_map(|&i| (0..ROLLER_STATES).map(move |l| (i, l)))
            .map(|(i, l)| self.layout.roller(i) + l)
            .collect();
        let computed = self.with_linearisation(t, y, |base, f0| {
            self.map(columns.len(), |c| {
                self.jacobian_column(base, f0, columns[c])
            })
        });
        for (&k, column) in columns.iter().zip(&computed) {
            set_column(jac, k, &column.entries);
        }
        true
    }

    /// Column k of the inner ring (a translation or a velocity, `local` the roller state
    /// that moves a roller alike) from the rollers' columns: moving the ring by h changes
    /// each inner-ring contact as moving its roller by −h does, i.e. by −h/h_r times the
    /// change that roller's column of step h_r made. The ring's and every roller's rates
    /// are then evaluated with the loads so changed (and the ring's state moved by h, for
    /// its kinematic rows).
    fn ring_column_from_rollers(
        &self,
        base: &Linearisation,
        f0: &[f64],
        k: usize,
        local: usize,
        rollers: &[Column],
    ) -> Vec<(usize, f64)> {
        let (t, y, kin) = (base.t, base.y, base.kin);
        let m = self.layout.ring_states();
        let mut yp = y.to_vec();
        let h = 1.5e-8 * y[k].abs().max(self.scale(k));
        yp[k] = y[k] + h;
        let h = yp[k] - y[k];
        let mut loads_p = base.loads.clone();
        for i in 0..self.layout.rollers {
            let column = &rollers[self.layout.roller(i) + local - m];
            let ratio = -h / column.step;
            for (on_ring, on_roller) in &column.ring_changes {
                loads_p.inner_ring.add_scaled(on_ring, ratio);
                loads_p.rollers[i].add_scaled(on_roller, ratio);
            }
        }
        let mut kin_p = kin.clone();
        kin_p.inner_ring = ring_kinematics(
            &self.layout,
            &yp,
            self.params.inner_ring_speed.at(t).0,
            &self.locked_axis,
        );
        let mut fp = vec![0.0; f0.len()];
        self.rates_with(t, &yp, &kin_p, &loads_p, |i| base.drags[i], &mut fp);
        (0..fp.len())
            .map(|row| (row, (fp[row] - f0[row]) / h))
            .collect()
    }

    /// Column k of the Jacobian as (row, value) pairs: state k perturbed, only its body's
    /// contacts evaluated again, only the rows of the bodies they touch.
    fn jacobian_column(&self, base: &Linearisation, f0: &[f64], k: usize) -> Column {
        let moved = self.perturbed(base, k);
        let changed = self.changed_loads(base, &moved, k);
        let entries = self.changed_rows(base, f0, &moved, &changed);
        Column {
            entries,
            step: moved.step,
            ring_changes: changed.ring_changes,
        }
    }

    /// State k of the linearisation moved by its difference step, and the kinematics
    /// that follow.
    fn perturbed(&self, base: &Linearisation, k: usize) -> Perturbation {
        let (t, y) = (base.t, base.y);
        let mut yp = y.to_vec();
        let h = 1.5e-8 * y[k].abs().max(self.scale(k));
        yp[k] = y[k] + h;
        let step = yp[k] - y[k];
        let body = self.layout.body_of(k);
        let mut kin = base.kin.clone();
        match body {
            None => {
                kin.inner_ring = ring_kinematics(
                    &self.layout,
                    &yp,
                    self.params.inner_ring_speed.at(t).0,
                    &self.locked_axis,
                );
            }
            Some(i) => kin.rollers[i] = roller_kinematics(&self.layout, &yp, i),
        }
        Perturbation {
            state: yp,
            step,
            kin,
            body,
        }
    }

    /// The summed loads with the moved body's contacts evaluated again (a velocity moves
    /// no contact: their geometry is the linearisation's), the bodies they touch, and for
    /// a roller state with a ring twin the changes of its inner-ring contacts.
    fn changed_loads(&self, base: &Linearisation, moved: &Perturbation, k: usize) -> ChangedLoads {
        let z = self.layout.rollers;
        let elements = match moved.body {
            None => &self.topology.ring_elements,
            Some(i) => &self.topology.roller_elements[i],
        };
        let mut out = ChangedLoads {
            loads: base.loads.clone(),
            touched_ring: moved.body.is_none(),
            touched: vec![false; z],
            ring_changes: Vec::new(),
        };
        if let Some(i) = moved.body {
            out.touched[i] = true;
        }
        let moves = !self.is_velocity(k);
        let twin = moved
            .body
            .is_some_and(|i| has_ring_twin(k - self.layout.roller(i)));
        for &e in elements {
            let element = &self.topology.elements[e];
            let new = if moves {
                self.evaluate(element, &moved.kin)
            } else {
                self.evaluate_at(element, &moved.kin, &base.geometries[e])
            };
            let old = &base.results[e];
            let [body_a, body_b] = element.bodies(z);
            if twin && body_a == Body::InnerRing {
                let mut on_ring = new.on_a;
                on_ring.sub(&old.on_a);
                let mut on_roller = new.on_b;
                on_roller.sub(&old.on_b);
                out.ring_changes.push((on_ring, on_roller));
            }
            for (bd, wn, wo) in [
                (body_a, &new.on_a, &old.on_a),
                (body_b, &new.on_b, &old.on_b),
            ] {
                match bd {
                    Body::InnerRing => out.touched_ring = true,
                    Body::Roller(r) => out.touched[r] = true,
                    Body::OuterRing => continue,
                }
                let w = out.loads.on(bd);
                w.sub(wo);
                w.add(wn);
            }
        }
        out
    }

    /// The differences (f(y + h e_k) − f(y))/h in the rows of the bodies the changed
    /// contacts touch (the moved roller's drag evaluated again).
    fn changed_rows(
        &self,
        base: &Linearisation,
        f0: &[f64],
        moved: &Perturbation,
        changed: &ChangedLoads,
    ) -> Vec<(usize, f64)> {
        let (t, yp, kin_p, h) = (base.t, &moved.state, &moved.kin, moved.step);
        let mut column = Vec::new();
        let mut fp = vec![0.0; f0.len()];
        if changed.touched_ring {
            let m = self.layout.ring_states();
            self.ring_rates(
                t,
                &base.field,
                &kin_p.inner_ring,
                &yp[..m],
                &changed.loads.inner_ring,
                &mut fp[..m],
            );
            column.extend((0..m).map(|row| (row, (fp[row] - f0[row]) / h)));
        }
        for (r, _) in changed.touched.iter().enumerate().filter(|(_, t)| **t) {
            let s = self.layout.roller(r);
            let range = s..s + ROLLER_STATES;
            let moved_drag;
            let drag = if moved.body == Some(r) {
                moved_drag = self.roller_drag(&kin_p.rollers[r]);
                &moved_drag
            } else {
                &base.drags[r]
            };
            self.roller_rates_with(
                &base.field,
                &kin_p.rollers[r],
                &yp[range.clone()],
                &changed.loads.rollers[r],
                drag,
                &mut fp[range.clone()],
            );
            column.extend(range.map(|row| (row, (fp[row] - f0[row]) / h)));
        }
        column
    }
}
