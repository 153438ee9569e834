//! The Jacobian of the quasi-static residual and the ring's Newton step with the rollers
//! condensed out (static condensation, e.g. Bathe, "Finite Element Procedures", sect.
//! 8.2.4): the rollers touch only the rings, so each roller's block of the Jacobian is 3×3
//! and the ring's step needs only their inverses.

use super::roller::{RollerForces, ROLLER_UNKNOWNS};
use super::solver::{Problem, MAX_MOVE, RING_UNKNOWNS};
use nalgebra::{DMatrix, DVector, Matrix3};

impl Problem<'_> {
    /// ∂(residual)/∂u by forward differences at `u` (forces `base`): the columns of the
    /// ring's unknowns `ring_columns` one by one, the rollers' in three groups (one
    /// unknown of every roller at once: roller i's forces depend on its own pose and the
    /// ring's only).
    pub(super) fn jacobian(
        &mut self,
        u: &[f64],
        base: &[RollerForces],
        ring_columns: &[usize],
    ) -> DMatrix<f64> {
        let n = self.len();
        let mut jac = DMatrix::zeros(n, n);
        let r0 = self.residual(u, base);
        let mut v = u.to_vec();
        for &k in ring_columns {
            let h = self.step(k);
            v[k] = u[k] + h;
            let f = self.evaluate(&v, false);
            jac.set_column(k, &((self.residual(&v, &f) - &r0) / h));
            v[k] = u[k];
        }
        for j in 0..ROLLER_UNKNOWNS {
            let h = self.step(RING_UNKNOWNS + j);
            let columns: Vec<usize> = (0..self.azimuths.len())
                .map(|i| RING_UNKNOWNS + ROLLER_UNKNOWNS * i + j)
                .collect();
            for &k in &columns {
                v[k] = u[k] + h;
            }
            let f = self.evaluate(&v, false);
            for (i, &k) in columns.iter().enumerate() {
                let s = RING_UNKNOWNS + ROLLER_UNKNOWNS * i;
                let now = self.roller_residual(&v, i, &f[i]);
                let was = self.roller_residual(u, i, &base[i]);
                for (row, (a, b)) in now.iter().zip(was).enumerate() {
                    jac[(s + row, k)] = (a - b) / h;
                }
                let now = Self::ring_rows(&f[i].on_ring);
                let was = Self::ring_rows(&base[i].on_ring);
                for (row, (a, b)) in now.iter().zip(was).enumerate() {
                    jac[(row, k)] = (a - b) / h;
                }
            }
            for &k in &columns {
                v[k] = u[k];
            }
        }
        for i in 0..self.azimuths.len() {
            let s = RING_UNKNOWNS + ROLLER_UNKNOWNS * i;
            let w = self.roller_weights();
            self.roller_jacobians[i] =
                Some(Matrix3::from_fn(|a, c| jac[(s + a, s + c)] / (w[a] * w[c])));
        }
        jac
    }

    /// The Newton step of the ring's unknowns `ring` with the rollers condensed out
    /// (K = J_pp − Σ_i J_pq,i J_qq,i⁻¹ J_qp,i, roller i's block J_qq,i being 3×3 because
    /// the rollers touch only the rings), and the rollers' predicted move with it,
    /// dq_i = −J_qq,i⁻¹ (r_q,i + J_qp,i dp) ([`Self::roller_block`]). Scaled to arcs and
    /// forces; a ring direction no contact holds gets the stiffness floor
    /// ([`Self::floor`]), and the ring's step is limited to [`MAX_MOVE`].
    pub(super) fn condensed_step(
        &self,
        jac: &DMatrix<f64>,
        r: &DVector<f64>,
        ring: &[usize],
    ) -> Vec<f64> {
        let m = ring.len();
        let w: Vec<f64> = ring.iter().map(|&k| self.weight(k)).collect();
        let blocks: Vec<_> = (0..self.azimuths.len())
            .map(|i| self.roller_block(jac, i))
            .collect();
        let (mut k, rhs) = self.condensed(jac, r, ring, &w, &blocks);
        let floor = self.floor();
        for i in 0..m {
            if k[(i, i)].abs() < floor {
                k[(i, i)] -= floor;
            }
        }
        let dp = k
            .lu()
            .solve(&rhs)
            .unwrap_or_else(|| rhs.map(|v| -v / floor));
        let largest = dp.amax();
        let dp = if largest > MAX_MOVE {
            dp * (MAX_MOVE / largest)
        } else {
            dp
        };
        let mut step = vec![0.0; self.len()];
        for (i, &kk) in ring.iter().enumerate() {
            step[kk] = dp[i] / w[i];
        }
        for (i, inverse) in blocks.iter().enumerate() {
            let s = RING_UNKNOWNS + ROLLER_UNKNOWNS * i;
            let jqp = DMatrix::from_fn(ROLLER_UNKNOWNS, m, |a, b| jac[(s + a, ring[b])] / w[b]);
            let rq = DVector::from_fn(ROLLER_UNKNOWNS, |a, _| r[s + a]);
            let dq = -(inverse * (rq + jqp * &dp));
            // The prediction, limited like the ring's step (a nearly free roller's block
            // is nearly singular); the roller's own equilibrium follows in `relax`.
            let arcs =
                (0..ROLLER_UNKNOWNS).fold(0.0f64, |m, a| m.max((dq[a] * self.weight(s + a)).abs()));
            let limit = if arcs > MAX_MOVE {
                MAX_MOVE / arcs
            } else {
                1.0
            };
            for a in 0..ROLLER_UNKNOWNS {
                step[s + a] = limit * dq[a];
            }
        }
        step
    }

    /// The ring's Jacobian over `ring` with the rollers condensed out and the right-hand
    /// side of its Newton step: K = J_pp − Σ_i J_pq,i J_qq,i⁻¹ J_qp,i and
    /// −r_p + Σ_i J_pq,i J_qq,i⁻¹ r_q,i, rows and columns divided by the weights `w`;
    /// `blocks` the inverses of the rollers' blocks ([`Self::roller_block`]).
    pub(super) fn condensed(
        &self,
        jac: &DMatrix<f64>,
        r: &DVector<f64>,
        ring: &[usize],
        w: &[f64],
        blocks: &[DMatrix<f64>],
    ) -> (DMatrix<f64>, DVector<f64>) {
        let m = ring.len();
        let mut k = DMatrix::from_fn(m, m, |i, j| jac[(ring[i], ring[j])] / (w[i] * w[j]));
        let mut rhs = DVector::from_fn(m, |i, _| -r[ring[i]] / w[i]);
        for (i, inverse) in blocks.iter().enumerate() {
            let s = RING_UNKNOWNS + ROLLER_UNKNOWNS * i;
            let jpq = DMatrix::from_fn(m, ROLLER_UNKNOWNS, |a, b| jac[(ring[a], s + b)] / w[a]);
            let jqp = DMatrix::from_fn(ROLLER_UNKNOWNS, m, |a, b| jac[(s + a, ring[b])] / w[b]);
            let rq = DVector::from_fn(ROLLER_UNKNOWNS, |a, _| r[s + a]);
            k -= &jpq * inverse * &jqp;
            rhs += &jpq * inverse * rq;
        }
        (k, rhs)
    }

    /// The inverse of roller i's block J_qq,i of `jac` over the directions a contact
    /// holds, zero along the others (an unloaded roller's, or the axial position of a
    /// roller without flange contact): the roller is taken as not moving along a direction
    /// nothing resists, as friction would hold it, instead of as on a soft spring whose
    /// stiffness would set the result. Held: a diagonal of at least the stiffness floor
    /// ([`Self::floor`]), in arcs and forces.
    pub(super) fn roller_block(&self, jac: &DMatrix<f64>, i: usize) -> DMatrix<f64> {
        let s = RING_UNKNOWNS + ROLLER_UNKNOWNS * i;
        let floor = self.floor();
        let held: Vec<usize> = (0..ROLLER_UNKNOWNS)
            .filter(|&a| {
                let w = self.weight(s + a);
                jac[(s + a, s + a)].abs() / (w * w) >= floor
            })
            .collect();
        let block = DMatrix::from_fn(held.len(), held.len(), |a, c| {
            jac[(s + held[a], s + held[c])]
        });
        let mut inverse = DMatrix::zeros(ROLLER_UNKNOWNS, ROLLER_UNKNOWNS);
        if let Some(b) = block.try_inverse() {
            for (a, &ha) in held.iter().enumerate() {
                for (c, &hc) in held.iter().enumerate() {
                    inverse[(ha, hc)] = b[(a, c)];
                }
            }
        }
        inverse
    }
}
