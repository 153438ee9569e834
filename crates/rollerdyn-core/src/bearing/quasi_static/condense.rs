//! The Jacobian of the quasi-static residual and the ring's Newton step with the rollers
//! condensed out (static condensation, e.g. Bathe, "Finite Element Procedures", sect.
//! 8.2.4): the rollers touch only the rings, so each roller's block of the Jacobian is 3×3
//! and the ring's step needs only their inverses.

use super::roller::{RollerForces, ROLLER_UNKNOWNS};
use super::solver::{Problem, RING_UNKNOWNS};
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
    /// ([`Self::floor`]), and each of the ring's moves is limited to [`Self::max_move`].
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
        let mut unheld = vec![false; m];
        for i in 0..m {
            if k[(i, i)].abs() < floor {
                k[(i, i)] -= floor;
                unheld[i] = true;
            }
        }
        let dp = k
            .lu()
            .solve(&rhs)
            .unwrap_or_else(|| rhs.map(|v| -v / floor));
        let dp = limited(dp, &unheld, self.max_move());
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
            let limit = if arcs > self.max_move() {
                self.max_move() / arcs
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

/// The ring's step `dp` (arcs and lengths) limited to `limit`: a direction no contact holds
/// (`unheld`, its step its force over the stiffness floor) on its own, the others scaled
/// together. Scaled with the rest, an unheld direction (the ring's axial move before its
/// flanges touch) shrank the held ones to nothing, and the ring crept along it by
/// line-search fractions of the limit while its radial residual stood (a bearing of B1's
/// proportions on a 65/90 mm raceway, `rollerdyn new`: 30 iterations at 20 kN unbalanced,
/// no equilibrium found from the cold start).
fn limited(mut dp: DVector<f64>, unheld: &[bool], limit: f64) -> DVector<f64> {
    let held_largest = dp
        .iter()
        .zip(unheld)
        .filter(|(_, &u)| !u)
        .fold(0.0f64, |a, (v, _)| a.max(v.abs()));
    let scale = if held_largest > limit {
        limit / held_largest
    } else {
        1.0
    };
    for (v, &u) in dp.iter_mut().zip(unheld) {
        *v = if u {
            v.clamp(-limit, limit)
        } else {
            *v * scale
        };
    }
    dp
}

#[cfg(test)]
mod tests {
    use super::limited;
    use nalgebra::DVector;
    use proptest::prelude::*;

    proptest! {
        /// Every move within the limit; the held directions keep their proportions (the
        /// Newton direction among them), an unheld one is clipped alone, so a huge unheld
        /// step (a force over the stiffness floor) leaves the held ones whole.
        #[test]
        fn each_unheld_move_is_clipped_alone_and_the_held_ones_scaled_together(
            moves in proptest::collection::vec(-1e-3f64..1e-3, 5),
            unheld in proptest::collection::vec(any::<bool>(), 5),
            limit in 1e-7f64..1e-5,
        ) {
            let dp = limited(DVector::from_vec(moves.clone()), &unheld, limit);
            let held: Vec<usize> = (0..5).filter(|&i| !unheld[i]).collect();
            let largest = held.iter().fold(0.0f64, |a, &i| a.max(moves[i].abs()));
            let scale = if largest > limit { limit / largest } else { 1.0 };
            for i in 0..5 {
                prop_assert!(dp[i].abs() <= limit * (1.0 + 1e-12));
                let expected = if unheld[i] { moves[i].clamp(-limit, limit) } else { moves[i] * scale };
                prop_assert!((dp[i] - expected).abs() <= 1e-15 * limit, "{i}: {} {}", dp[i], expected);
            }
        }
    }

    #[test]
    fn a_huge_unheld_step_leaves_the_held_one_whole() {
        // the ring's axial force over the stiffness floor (2 m) beside its radial step of 3 µm
        let dp = limited(DVector::from_vec(vec![2.0, -3e-6]), &[true, false], 4e-6);
        assert_eq!(dp.as_slice(), &[4e-6, -3e-6]);
    }
}
