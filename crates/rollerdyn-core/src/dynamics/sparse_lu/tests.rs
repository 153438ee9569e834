//! Tests of the sparse LU factorisation ([`super`]).

use super::*;
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;

/// A fixed pseudo-random sequence on [0, 1) from a non-zero `seed` (xorshift64).
fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A random matrix with a bearing's pattern: `blocks` bodies of `size` states coupled
/// to their neighbours around a ring, and `global` states coupled to all (placed first,
/// as the inner ring is in the state layout), each non-zero kept with probability
/// `density`; the diagonal made dominant or not by `shift`.
fn bearing_like(seed: u64, blocks: usize, size: usize, global: usize, shift: f64) -> DMatrix<f64> {
    let n = global + blocks * size;
    let mut next = uniform(seed | 1);
    DMatrix::from_fn(n, n, |i, j| {
        let body = |k: usize| (k >= global).then(|| (k - global) / size);
        let coupled = match (body(i), body(j)) {
            (Some(a), Some(b)) => a == b || (a + 1) % blocks == b || (b + 1) % blocks == a,
            _ => true,
        };
        let v = if coupled && next() < 0.7 {
            next() - 0.5
        } else {
            0.0
        };
        v + if i == j { shift } else { 0.0 }
    })
}

/// Relative residual |A x − b| / (|A| |x| + |b|) (max norms): backward stability of
/// partial pivoting (GVL sect. 3.4.6: growth-bounded; a small multiple of n·ε here).
fn residual(a: &DMatrix<f64>, x: &DVector<f64>, b: &DVector<f64>) -> f64 {
    (a * x - b).amax() / (a.amax() * x.amax() * a.nrows() as f64 + b.amax())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, .. ProptestConfig::default() })]

    /// Against nalgebra's dense LU on random bearing-like matrices (up to 212 states,
    /// beyond the 64 columns of one word of the row structure), diagonally dominant
    /// or not (shift 0: pivoting needed): the same solution to 1e-9 relative to its size
    /// (both backward stable; the matrices are far from singular), and a residual at
    /// round-off (1e-13 relative), for A x = b and Aᵀ x = b.
    #[test]
    fn solves_as_the_dense_lu(
        seed in any::<u64>(),
        blocks in 3usize..20,
        size in 1usize..12,
        global in 0usize..4,
        shift in prop::sample::select(vec![0.0, 1.0, 4.0]),
    ) {
        let a = bearing_like(seed, blocks, size, global, shift);
        let n = a.nrows();
        let dense = a.clone().lu();
        prop_assume!(dense.u().diagonal().iter().all(|d| d.abs() > 1e-6));
        let cond = a.clone().svd(false, false).singular_values;
        prop_assume!(cond.max() / cond.min() < 1e6);
        let b = DVector::from_fn(n, |i, _| (i as f64 + 1.0).sin());
        let mut lu = SparseSkipLu::default();
        lu.factorise(a.as_slice(), n);
        let mut x = b.clone();
        lu.solve(x.as_mut_slice()).unwrap();
        let expected = dense.solve(&b).unwrap();
        prop_assert!((&x - &expected).amax() <= 1e-9 * expected.amax(), "{x} vs {expected}");
        prop_assert!(residual(&a, &x, &b) < 1e-13);
        let mut y = b.clone();
        lu.solve_transpose(y.as_mut_slice()).unwrap();
        prop_assert!(residual(&a.transpose(), &y, &b) < 1e-13);
    }
}

/// The factors as a dense packed matrix (L's multipliers below the diagonal, U on and
/// above), with the pivot rows.
fn packed(lu: &SparseSkipLu) -> (Vec<usize>, DMatrix<f64>) {
    let f = &lu.factors;
    let mut m = DMatrix::zeros(f.n, f.n);
    for j in 0..f.n {
        m[(j, j)] = f.diagonal[j];
        for e in f.l_start[j]..f.l_start[j + 1] {
            m[(f.l_rows[e], j)] = f.l_values[e];
        }
        for e in f.u_start[j]..f.u_start[j + 1] {
            m[(f.u_rows[e], j)] = f.u_values[e];
        }
    }
    (f.pivot_rows.clone(), m)
}

/// Textbook dense Gaussian elimination with partial pivoting (GVL algorithm 3.4.1)
/// of Q A Qᵀ for the order `order`, interchanging rows, every entry updated at every
/// step; at the steps marked in `diagonal` the pivot is the diagonal (as the condensed
/// states take it). Returns the pivot rows (rows of A, step by step) and the packed
/// factors (L's multipliers below the diagonal, U on and above).
fn dense_elimination(
    a: &DMatrix<f64>,
    order: &[usize],
    diagonal: &[bool],
) -> (Vec<usize>, DMatrix<f64>) {
    let n = a.nrows();
    let mut m = DMatrix::from_fn(n, n, |i, j| a[(order[i], order[j])]);
    let mut rows: Vec<usize> = order.to_vec();
    for k in 0..n {
        let mut p = k;
        for i in k + 1..n {
            if !diagonal[k] && m[(i, k)].abs() > m[(p, k)].abs() {
                p = i;
            }
        }
        if m[(p, k)] == 0.0 {
            continue;
        }
        m.swap_rows(k, p);
        rows.swap(k, p);
        for i in k + 1..n {
            m[(i, k)] /= m[(k, k)];
        }
        for j in k + 1..n {
            for i in k + 1..n {
                m[(i, j)] -= m[(i, k)] * m[(k, j)];
            }
        }
    }
    (rows, m)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 100, .. ProptestConfig::default() })]

    /// Working on the non-zeros, in place and without moving rows, changes no
    /// arithmetic: the factors equal those of the dense elimination to the last bit
    /// (zeros aside: their sign may differ, and the factors do not store them), with
    /// the same pivot rows. (The random entries never tie for a pivot.)
    #[test]
    fn factors_are_those_of_dense_elimination(
        seed in any::<u64>(),
        blocks in 3usize..20,
        size in 1usize..12,
        global in 0usize..4,
        shift in prop::sample::select(vec![0.0, 1.0, 4.0]),
    ) {
        let a = bearing_like(seed, blocks, size, global, shift);
        let n = a.nrows();
        let mut lu = SparseSkipLu::default();
        // Twice: the second factorisation reuses the first one's storage.
        lu.factorise(bearing_like(seed ^ 1, blocks, size, global, shift).as_slice(), n);
        lu.factorise(a.as_slice(), n);
        prop_assume!(lu.factors.regular);
        let (rows, m) = dense_elimination(&a, &lu.factors.order, &lu.schedule.row_pivot);
        let (pivot_rows, factors) = packed(&lu);
        prop_assert_eq!(&pivot_rows, &rows);
        for (x, y) in factors.iter().zip(m.iter()) {
            prop_assert!(x.to_bits() == y.to_bits() || (*x == 0.0 && *y == 0.0), "{x} vs {y}");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 100, .. ProptestConfig::default() })]

    /// Newton matrices I − hγJ of one Jacobian for step sizes in a row (as diffsol
    /// assembles them), each factorised by replaying the last full elimination where
    /// its pivots pass the threshold, else in full: every factorisation solves as a
    /// fresh full one does (to 1e-9 relative to the solution, the matrices being far
    /// from singular), with a residual at round-off (1e-12: threshold pivoting may grow
    /// the entries by up to 1 + 1/τ = 11 per step instead of 2).
    #[test]
    fn replays_solve_as_full_factorisations(
        seed in any::<u64>(),
        blocks in 3usize..20,
        size in 1usize..12,
        global in 0usize..4,
        steps in prop::collection::vec(1e-3..1e1f64, 2..8),
    ) {
        let jacobian = bearing_like(seed, blocks, size, global, 0.0);
        let n = jacobian.nrows();
        let b = DVector::from_fn(n, |i, _| (i as f64 + 1.0).sin());
        let mut lu = SparseSkipLu::default();
        for h in &steps {
            let m = DMatrix::identity(n, n) - &jacobian * *h;
            let cond = m.clone().svd(false, false).singular_values;
            prop_assume!(cond.max() / cond.min() < 1e6);
            lu.factorise(m.as_slice(), n);
            let mut fresh = SparseSkipLu::default();
            fresh.factorise(m.as_slice(), n);
            let (mut x, mut expected) = (b.clone(), b.clone());
            lu.solve(x.as_mut_slice()).unwrap();
            fresh.solve(expected.as_mut_slice()).unwrap();
            prop_assert!((&x - &expected).amax() <= 1e-9 * expected.amax());
            prop_assert!(residual(&m, &x, &b) < 1e-12);
        }
        let (replays, full) = lu.counts();
        prop_assert_eq!(replays + full, steps.len());
    }
}

/// The same matrix again is always a replay, and one with its largest entries moved
/// to other rows (other pivots) is factorised in full, correctly.
#[test]
fn replay_only_with_the_same_pivots() {
    let a = bearing_like(11, 9, 5, 2, 0.0);
    let n = a.nrows();
    let mut lu = SparseSkipLu::default();
    lu.factorise(a.as_slice(), n);
    let full = packed(&lu);
    lu.factorise(a.as_slice(), n);
    assert_eq!(lu.counts(), (1, 1));
    // The same pivots, the same arithmetic: the same factors to the last bit.
    let replayed = packed(&lu);
    assert_eq!(full.0, replayed.0);
    assert!(full
        .1
        .iter()
        .zip(replayed.1.iter())
        .all(|(x, y)| x.to_bits() == y.to_bits()));
    // Same non-zeros, rows reversed in magnitude order: the pivots change.
    let b = a.map(|v| if v == 0.0 { 0.0 } else { 1.0 / v });
    lu.factorise(b.as_slice(), n);
    assert_eq!(lu.counts(), (1, 2));
    let rhs = DVector::from_fn(n, |i, _| (i as f64).cos());
    let mut x = rhs.clone();
    lu.solve(x.as_mut_slice()).unwrap();
    assert!(residual(&b, &x, &rhs) < 1e-13);
}

/// On B1's pattern (17 rollers of 12 states, 6 inner-ring states first) the ring's
/// states are eliminated last; the others keep their order.
#[test]
fn globally_coupled_states_go_last() {
    let a = bearing_like(7, 17, 12, 6, 4.0);
    let n = a.nrows();
    let mut w = Work::default();
    find_pattern(a.as_slice(), n, &mut w.pattern);
    structure_of(n, &mut w);
    let order = arrow_order_of(&w.row_bits, &w.column_bits, n, &mut Vec::new());
    let expected: Vec<usize> = (6..a.nrows()).chain(0..6).collect();
    assert_eq!(order, expected);
}

/// A singular matrix is reported, not solved into NaN.
#[test]
fn singular_matrix_is_an_error() {
    let a = DMatrix::from_row_slice(3, 3, &[1.0, 2.0, 0.0, 2.0, 4.0, 0.0, 0.0, 0.0, 1.0]);
    let mut lu = SparseSkipLu::default();
    lu.factorise(a.as_slice(), 3);
    assert!(lu.solve(&mut [1.0, 1.0, 1.0]).is_err());
}

/// A mechanical system's Newton matrix I − hγJ, J = [[0, I], [K, C]] (positions q' = v,
/// velocities v' = K q + C v): `blocks` bodies of 3 positions and 3 velocities coupled
/// to their neighbours around a ring, and one global body of 3 + 3 states (the inner
/// ring) coupled to all; stiffnesses K/m of order `stiffness` [1/s²], dampings C/m of
/// order 1e3 1/s (B1's orders: 1e9 … 1e12 and 1e2 … 1e4), the step hγ = 1e-5 s.
fn mechanical(seed: u64, blocks: usize, stiffness: f64) -> DMatrix<f64> {
    let body_count = blocks + 1;
    let n = 6 * body_count;
    let mut next = uniform(seed | 1);
    // Body 0 is the global one; bodies 1..=blocks the ring of neighbours.
    let coupled = |a: usize, b: usize| {
        a == 0 || b == 0 || a == b || a % blocks + 1 == b || b % blocks + 1 == a
    };
    let h_gamma = 1e-5;
    DMatrix::from_fn(n, n, |i, j| {
        let (bi, bj) = (i / 6, j / 6);
        let (li, lj) = (i % 6, j % 6);
        let jac = if li < 3 {
            f64::from(u8::from(bi == bj && lj == li + 3))
        } else if coupled(bi, bj) && next() < 0.8 {
            let scale = if lj < 3 { stiffness } else { 1e3 };
            scale * (next() - 0.5)
        } else {
            0.0
        };
        f64::from(u8::from(i == j)) - h_gamma * jac
    })
}

/// Static condensation ([`condensed_first`]): on mechanical Newton matrices the
/// positions are eliminated first on their diagonals, and the factorisation costs a
/// fraction of partial pivoting's (which picks the stiffness entries of the velocity
/// rows and fills the matrix: on B1's real matrices 280 000–740 000 multiply-adds,
/// measured) while solving as the dense LU does: the solution to 1e-9 of its size and
/// a residual at round-off (the pivot rows are dominant: growth bounded as for partial
/// pivoting).
#[test]
fn positions_are_condensed_first_at_a_fraction_of_the_cost() {
    for (seed, stiffness) in [(3, 1e9), (5, 1e11), (8, 1e12), (13, 1e7)] {
        let a = mechanical(seed, 17, stiffness);
        let n = a.nrows();
        let mut lu = SparseSkipLu::default();
        lu.factorise(a.as_slice(), n);
        let condensed = lu.schedule.row_pivot.iter().filter(|&&r| r).count();
        assert_eq!(
            condensed,
            3 * 18,
            "every position (17 bodies and the global one)"
        );
        let mut partial = SparseSkipLu {
            partial_pivoting_only: true,
            ..Default::default()
        };
        partial.factorise(a.as_slice(), n);
        let (cost, full_cost) = (lu.elimination_cost(), partial.elimination_cost());
        assert!(
            4 * cost < full_cost,
            "K/m = {stiffness}: {cost} against {full_cost} multiply-adds"
        );
        let b = DVector::from_fn(n, |i, _| (i as f64 + 1.0).sin());
        let expected = a.clone().lu().solve(&b).unwrap();
        for solver in [&lu, &partial] {
            let mut x = b.clone();
            solver.solve(x.as_mut_slice()).unwrap();
            assert!(
                (&x - &expected).amax() <= 1e-9 * expected.amax(),
                "K/m = {stiffness}"
            );
            assert!(residual(&a, &x, &b) < 1e-13, "K/m = {stiffness}");
        }
        // A replay of the next step size keeps the condensation and solves as well.
        let next_step = DMatrix::identity(n, n) + (&a - DMatrix::identity(n, n)) * 1.3;
        lu.factorise(next_step.as_slice(), n);
        assert_eq!(lu.counts(), (1, 1));
        let mut x = b.clone();
        lu.solve(x.as_mut_slice()).unwrap();
        assert!(residual(&next_step, &x, &b) < 1e-13, "K/m = {stiffness}");
    }
}
