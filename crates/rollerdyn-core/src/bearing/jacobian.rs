//! The Jacobian ∂f/∂y of the equations of motion, by finite differences per body (a
//! roller couples only to its neighbours and the rings): perturbing one state of
//! roller i re-evaluates only roller i's eight contacts, and changes only the rows of
//! roller i, its two neighbours and the inner ring. A velocity moves no contact, so its
//! columns reuse the slice geometry and the detected flange contacts of the unperturbed
//! state (`Geometry`). The columns are computed apart, on the model's threads if it has
//! any, and written in order: the numbers do not depend on the thread count.
//!
//! Also the per-state scales of the difference steps and of the integrator's absolute
//! tolerances.

use super::contacts::{ElementResult, Geometry, Wrench};
use super::equations::Loads;
use super::model::BearingModel;
use super::state::{ring_kinematics, roller_kinematics, BearingKinematics, ROLLER_STATES};
use super::topology::Body;
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
}

impl BearingModel {
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

    /// The Jacobian by per-body finite differences (see the module doc), its columns
    /// computed apart (on the model's threads) and written in order.
    pub(super) fn structured_jacobian(&self, t: f64, y: &[f64], jac: &mut DMatrix<f64>) {
        let kin = self.kinematics(t, y);
        let elements = &self.topology.elements;
        let geometries = self.map(elements.len(), |e| self.geometry(&elements[e], &kin));
        let results = self.map(elements.len(), |e| {
            self.evaluate_at(&elements[e], &kin, &geometries[e])
        });
        let base = Linearisation {
            t,
            y,
            kin: &kin,
            geometries: &geometries,
            loads: self.loads(&results),
            results: &results,
            drags: kin.rollers.iter().map(|r| self.roller_drag(r)).collect(),
        };
        let mut f0 = vec![0.0; self.layout.len()];
        self.rates(t, y, &kin, &base.loads, &mut f0);
        let columns = self.map(y.len(), |k| self.jacobian_column(&base, &f0, k));
        jac.fill(0.0);
        for (k, column) in columns.iter().enumerate() {
            for &(row, value) in column {
                jac[(row, k)] = value;
            }
        }
    }

    /// Column k of the Jacobian as (row, value) pairs: state k perturbed, only its body's
    /// contacts evaluated again, only the rows of the bodies they touch.
    fn jacobian_column(&self, base: &Linearisation, f0: &[f64], k: usize) -> Vec<(usize, f64)> {
        let (t, y, kin) = (base.t, base.y, base.kin);
        let mut yp = y.to_vec();
        let h = 1.5e-8 * y[k].abs().max(self.scale(k));
        yp[k] = y[k] + h;
        let h = yp[k] - y[k];
        let body = self.layout.body_of(k);
        let mut kin_p = kin.clone();
        let elements = match body {
            None => {
                kin_p.inner_ring = ring_kinematics(
                    &self.layout,
                    &yp,
                    self.params.inner_ring_speed.at(t).0,
                    &self.locked_axis,
                );
                &self.topology.ring_elements
            }
            Some(i) => {
                kin_p.rollers[i] = roller_kinematics(&self.layout, &yp, i);
                &self.topology.roller_elements[i]
            }
        };
        let z = self.layout.rollers;
        let mut loads_p = base.loads.clone();
        let mut touched_ring = body.is_none();
        let mut touched = vec![false; z];
        if let Some(i) = body {
            touched[i] = true;
        }
        let moves = !self.is_velocity(k);
        for &e in elements {
            let element = &self.topology.elements[e];
            let new = if moves {
                self.evaluate(element, &kin_p)
            } else {
                self.evaluate_at(element, &kin_p, &base.geometries[e])
            };
            let old = &base.results[e];
            let [body_a, body_b] = element.bodies(z);
            for (bd, wn, wo) in [
                (body_a, &new.on_a, &old.on_a),
                (body_b, &new.on_b, &old.on_b),
            ] {
                match bd {
                    Body::InnerRing => touched_ring = true,
                    Body::Roller(r) => touched[r] = true,
                    Body::OuterRing => continue,
                }
                let w = loads_p.on(bd);
                w.sub(wo);
                w.add(wn);
            }
        }
        let mut column = Vec::new();
        let mut fp = vec![0.0; f0.len()];
        if touched_ring {
            let m = self.layout.ring_states();
            self.ring_rates(
                t,
                &kin_p.inner_ring,
                &yp[..m],
                &loads_p.inner_ring,
                &mut fp[..m],
            );
            column.extend((0..m).map(|row| (row, (fp[row] - f0[row]) / h)));
        }
        for (r, _) in touched.iter().enumerate().filter(|(_, t)| **t) {
            let s = self.layout.roller(r);
            let range = s..s + ROLLER_STATES;
            let moved_drag;
            let drag = if body == Some(r) {
                moved_drag = self.roller_drag(&kin_p.rollers[r]);
                &moved_drag
            } else {
                &base.drags[r]
            };
            self.roller_rates_with(
                &kin_p.rollers[r],
                &yp[range.clone()],
                &loads_p.rollers[r],
                drag,
                &mut fp[range.clone()],
            );
            column.extend(range.map(|row| (row, (fp[row] - f0[row]) / h)));
        }
        column
    }
}
