//! The bearing's stiffness at a quasi-static equilibrium: how the contact forces on the
//! inner ring change with its displacement and tilt when the rollers follow into their
//! own equilibrium.

use super::solver::{unknowns_of, Problem, RING_UNKNOWNS};
use super::StaticSolution;
use crate::bearing::workspace::BearingSystem;
use nalgebra::DVector;

impl BearingSystem<'_> {
    /// The 5×5 stiffness matrix K at `solution`: rows the force (x, y, z) [N] and moment
    /// (about y, z) [N·m] that the ring needs, columns its displacement (x, y, z) [m] and
    /// tilt (θ_y, θ_z) [rad]. With the Jacobian J of the residual forces split into the
    /// ring's unknowns p and the rollers' q, the rollers' equilibrium dq = −J_qq⁻¹ J_qp dp
    /// leaves K = −(J_pp − J_pq J_qq⁻¹ J_qp), the Schur complement (static condensation,
    /// e.g. Bathe, "Finite Element Procedures", sect. 8.2.4). A roller direction that no
    /// contact holds (an unloaded roller's axial position, or a loaded one's without flange
    /// contact) is taken as held, as friction would hold it ([`Problem::roller_block`]).
    pub fn stiffness(&self, solution: &StaticSolution) -> [[f64; RING_UNKNOWNS]; RING_UNKNOWNS] {
        let mut problem = Problem::new(*self, &solution.case);
        // Every column is perturbed, z and the tilt about y too: no mirror.
        problem.mirror = None;
        let u = unknowns_of(solution, &problem);
        let base = problem.evaluate(&u, false);
        let columns: Vec<usize> = (0..RING_UNKNOWNS).collect();
        let jac = problem.jacobian(&u, &base, &columns);
        let blocks: Vec<_> = (0..self.layout.rollers)
            .map(|i| problem.roller_block(&jac, i))
            .collect();
        let zero = DVector::zeros(problem.len());
        let (condensed, _) =
            problem.condensed(&jac, &zero, &columns, &[1.0; RING_UNKNOWNS], &blocks);
        let mut k = [[0.0; RING_UNKNOWNS]; RING_UNKNOWNS];
        for (i, row) in k.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = -condensed[(i, j)];
            }
        }
        k
    }
}
