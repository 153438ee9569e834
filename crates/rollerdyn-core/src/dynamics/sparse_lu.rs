//! The linear solver of the Newton iterations: an LU factorisation with partial pivoting,
//! stored dense but computed and applied on the non-zeros only.
//!
//! The Newton matrix I − hγJ of a multibody model is mostly zeros: a body couples only to
//! the bodies it touches (in a bearing, a roller to its two neighbours and the rings), and
//! only a few bodies (the inner ring) couple to all. On B1 at full speed (193 states) it has
//! about 2 600 non-zeros (7 %), and diffsol's dense LU took 12 % of a run's samples (perf).
//! Here the right-looking elimination of Golub & Van Loan (Matrix Computations, 4th ed.,
//! algorithm 3.4.1, "Gaussian elimination with partial pivoting") updates only the rows with
//! a non-zero multiplier and the columns with a non-zero pivot-row entry, and the states that
//! couple to more than a quarter of all others are eliminated last (an arrow ordering), so
//! that eliminating them first cannot fill the whole matrix: B1's factors have about 6 000
//! non-zeros, and the factorisation took 5 % of the samples, most of it in the passes over
//! the dense storage. The arithmetic on the non-zeros is that of the dense algorithm; the
//! pivots are the largest in their column, so the stability is that of partial pivoting
//! (GVL sect. 3.4.6).

use diffsol_la::error::LinearSolverError;
use diffsol_la::{
    LaError, LinearOp, LinearSolver, Matrix, MatrixCommon, NalgebraContext, NalgebraMat,
    NalgebraVec,
};

/// Fraction of the states a state must couple to (in its row and column together) to be
/// eliminated last.
const GLOBAL_COUPLING: f64 = 0.25;

/// LU factors of P·(Q A Qᵀ) = L·U: Q the arrow ordering, P the row interchanges.
#[derive(Debug, Default)]
struct Factors {
    n: usize,
    /// Elimination order: position k holds state `order[k]`.
    order: Vec<usize>,
    /// Row interchanged with row k at step k.
    pivots: Vec<usize>,
    /// Strictly lower part of L by columns (compressed: start, rows, values).
    l_start: Vec<usize>,
    l_rows: Vec<usize>,
    l_values: Vec<f64>,
    /// Strictly upper part of U by columns.
    u_start: Vec<usize>,
    u_rows: Vec<usize>,
    u_values: Vec<f64>,
    /// Diagonal of U.
    diagonal: Vec<f64>,
    /// False if a pivot was zero (the matrix is singular).
    regular: bool,
}

/// Working storage reused between factorisations.
#[derive(Debug, Default)]
struct Work {
    /// Q A Qᵀ, column-major, overwritten by the factors.
    a: Vec<f64>,
    rows: Vec<usize>,
    columns: Vec<usize>,
    coupling: Vec<usize>,
    /// The structure of the rows: bit j of row i's `words` words is set where column j of
    /// row i may be non-zero (set where it was, and by fill-in), so that the pivot row's
    /// non-zeros are found without a strided pass over the column-major storage.
    row_bits: Vec<u64>,
}

/// Words of a row's bit set for n columns.
fn words(n: usize) -> usize {
    n.div_ceil(64)
}

/// diffsol's [`LinearSolver`] for the dense nalgebra matrix, factorising on the non-zeros.
#[derive(Debug, Default)]
pub struct SparseSkipLu {
    matrix: Option<NalgebraMat<f64>>,
    factors: Factors,
    work: Work,
}

impl SparseSkipLu {
    /// Factorises the square column-major matrix `a` (n × n).
    pub fn factorise(&mut self, a: &[f64], n: usize) {
        assert_eq!(a.len(), n * n, "the matrix must be n × n");
        let order = arrow_order(a, n, &mut self.work.coupling);
        let w = &mut self.work;
        let nw = words(n);
        w.a.clear();
        w.a.resize(n * n, 0.0);
        w.row_bits.clear();
        w.row_bits.resize(n * nw, 0);
        for (jj, &j) in order.iter().enumerate() {
            for (ii, &i) in order.iter().enumerate() {
                let v = a[j * n + i];
                w.a[jj * n + ii] = v;
                if v != 0.0 {
                    w.row_bits[ii * nw + jj / 64] |= 1 << (jj % 64);
                }
            }
        }
        let mut pivots = Vec::with_capacity(n);
        let mut regular = true;
        for k in 0..n {
            let p = pivot_row(&w.a, n, k);
            pivots.push(p);
            let diag = w.a[k * n + p];
            if diag == 0.0 {
                regular = false;
                continue;
            }
            if p != k {
                for j in 0..n {
                    w.a.swap(j * n + k, j * n + p);
                }
                for word in 0..nw {
                    w.row_bits.swap(k * nw + word, p * nw + word);
                }
            }
            eliminate(
                &mut w.a,
                n,
                k,
                diag,
                &mut w.rows,
                &mut w.columns,
                &mut w.row_bits,
            );
        }
        self.factors = compress(&w.a, n, order, pivots, regular);
    }

    /// Solves A x = b in place.
    pub fn solve(&self, b: &mut [f64]) -> Result<(), LaError> {
        let f = self.checked(b.len())?;
        let mut x: Vec<f64> = f.order.iter().map(|&i| b[i]).collect();
        for (k, &p) in f.pivots.iter().enumerate() {
            x.swap(k, p);
        }
        for k in 0..f.n {
            let xk = x[k];
            if xk != 0.0 {
                for e in f.l_start[k]..f.l_start[k + 1] {
                    x[f.l_rows[e]] -= f.l_values[e] * xk;
                }
            }
        }
        for k in (0..f.n).rev() {
            x[k] /= f.diagonal[k];
            let xk = x[k];
            if xk != 0.0 {
                for e in f.u_start[k]..f.u_start[k + 1] {
                    x[f.u_rows[e]] -= f.u_values[e] * xk;
                }
            }
        }
        scatter(&x, &f.order, b)
    }

    /// Solves Aᵀ x = b in place: Uᵀ z = Q b, Lᵀ w = z, x = Qᵀ Pᵀ w.
    pub fn solve_transpose(&self, b: &mut [f64]) -> Result<(), LaError> {
        let f = self.checked(b.len())?;
        let mut x: Vec<f64> = f.order.iter().map(|&i| b[i]).collect();
        for k in 0..f.n {
            let s: f64 = (f.u_start[k]..f.u_start[k + 1])
                .map(|e| f.u_values[e] * x[f.u_rows[e]])
                .sum();
            x[k] = (x[k] - s) / f.diagonal[k];
        }
        for k in (0..f.n).rev() {
            let s: f64 = (f.l_start[k]..f.l_start[k + 1])
                .map(|e| f.l_values[e] * x[f.l_rows[e]])
                .sum();
            x[k] -= s;
        }
        for (k, &p) in f.pivots.iter().enumerate().rev() {
            x.swap(k, p);
        }
        scatter(&x, &f.order, b)
    }

    fn checked(&self, len: usize) -> Result<&Factors, LaError> {
        let f = &self.factors;
        if f.order.is_empty() && len > 0 {
            return Err(LinearSolverError::LuNotInitialized.into());
        }
        if len != f.n {
            return Err(LinearSolverError::LinearSolverMatrixVectorNotCompatible.into());
        }
        if !f.regular {
            return Err(LinearSolverError::LuSolveFailed.into());
        }
        Ok(f)
    }
}

/// The elimination order: the states in their order, those coupled to more than
/// [`GLOBAL_COUPLING`] of all states (non-zeros in their row and column) moved to the end.
fn arrow_order(a: &[f64], n: usize, coupling: &mut Vec<usize>) -> Vec<usize> {
    coupling.clear();
    coupling.resize(n, 0);
    for j in 0..n {
        for (i, &v) in a[j * n..(j + 1) * n].iter().enumerate() {
            if v != 0.0 && i != j {
                coupling[i] += 1;
                coupling[j] += 1;
            }
        }
    }
    let limit = GLOBAL_COUPLING * 2.0 * n as f64;
    let global = |i: &usize| coupling[*i] as f64 > limit;
    let mut order: Vec<usize> = (0..n).filter(|i| !global(i)).collect();
    order.extend((0..n).filter(global));
    order
}

/// The row (k or below) with the largest magnitude in column k (ties to the first).
fn pivot_row(a: &[f64], n: usize, k: usize) -> usize {
    let column = &a[k * n..(k + 1) * n];
    let mut best = k;
    for i in k + 1..n {
        if column[i].abs() > column[best].abs() {
            best = i;
        }
    }
    best
}

/// Step k of the elimination on its non-zeros: the multipliers below the pivot, then the
/// rank-one update of the rows that have one and the columns with a non-zero pivot-row entry.
/// The fill-in goes into `row_bits` (see [`Work::row_bits`]).
fn eliminate(
    a: &mut [f64],
    n: usize,
    k: usize,
    diag: f64,
    rows: &mut Vec<usize>,
    columns: &mut Vec<usize>,
    row_bits: &mut [u64],
) {
    rows.clear();
    for i in k + 1..n {
        let v = &mut a[k * n + i];
        if *v != 0.0 {
            *v /= diag;
            rows.push(i);
        }
    }
    if rows.is_empty() {
        return;
    }
    let nw = words(n);
    columns.clear();
    for word in (k + 1) / 64..nw {
        let mut bits = row_bits[k * nw + word];
        if word == (k + 1) / 64 {
            bits &= u64::MAX << ((k + 1) % 64);
        }
        while bits != 0 {
            let j = word * 64 + bits.trailing_zeros() as usize;
            bits &= bits - 1;
            if a[j * n + k] != 0.0 {
                columns.push(j);
            }
        }
    }
    for &j in columns.iter() {
        let u = a[j * n + k];
        for &i in rows.iter() {
            a[j * n + i] -= a[k * n + i] * u;
        }
    }
    for &i in rows.iter() {
        for word in 0..nw {
            let pivot_row = row_bits[k * nw + word];
            row_bits[i * nw + word] |= pivot_row;
        }
    }
}

/// The factors' non-zeros by columns.
fn compress(a: &[f64], n: usize, order: Vec<usize>, pivots: Vec<usize>, regular: bool) -> Factors {
    let mut f = Factors {
        n,
        order,
        pivots,
        regular,
        ..Default::default()
    };
    f.l_start.push(0);
    f.u_start.push(0);
    for j in 0..n {
        let column = &a[j * n..(j + 1) * n];
        for (i, &v) in column.iter().enumerate() {
            if v == 0.0 {
                continue;
            }
            if i < j {
                f.u_rows.push(i);
                f.u_values.push(v);
            } else if i > j {
                f.l_rows.push(i);
                f.l_values.push(v);
            }
        }
        f.diagonal.push(column[j]);
        f.l_start.push(f.l_rows.len());
        f.u_start.push(f.u_rows.len());
    }
    f
}

/// b[order[k]] = x[k].
fn scatter(x: &[f64], order: &[usize], b: &mut [f64]) -> Result<(), LaError> {
    for (k, &i) in order.iter().enumerate() {
        b[i] = x[k];
    }
    if b.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(LinearSolverError::LuSolveFailed.into())
    }
}

impl LinearSolver<NalgebraMat<f64>> for SparseSkipLu {
    fn set_linearisation<
        C: LinearOp<T = f64, V = NalgebraVec<f64>, M = NalgebraMat<f64>, C = NalgebraContext>,
    >(
        &mut self,
        op: &C,
    ) {
        let mut matrix = self.matrix.take().expect("set_sparsity comes first");
        op.matrix_inplace(&mut matrix);
        let n = matrix.nrows();
        self.factorise(matrix.inner().as_slice(), n);
        self.matrix = Some(matrix);
    }

    fn set_sparsity<
        C: LinearOp<T = f64, V = NalgebraVec<f64>, M = NalgebraMat<f64>, C = NalgebraContext>,
    >(
        &mut self,
        op: &C,
    ) {
        self.matrix = Some(NalgebraMat::new_from_sparsity(
            op.nrows(),
            op.ncols(),
            op.sparsity(),
            *op.context(),
        ));
        self.factors = Factors::default();
    }

    fn solve_in_place(&self, b: &mut NalgebraVec<f64>) -> Result<(), LaError> {
        self.solve(b.batch_as_mut_slice(0))
    }

    fn solve_transpose_in_place(&self, b: &mut NalgebraVec<f64>) -> Result<(), LaError> {
        self.solve_transpose(b.batch_as_mut_slice(0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};
    use proptest::prelude::*;

    /// A random matrix with a bearing's pattern: `blocks` bodies of `size` states coupled
    /// to their neighbours around a ring, and `global` states coupled to all (placed first,
    /// as the inner ring is in the state layout), each non-zero kept with probability
    /// `density`; the diagonal made dominant or not by `shift`.
    fn bearing_like(
        seed: u64,
        blocks: usize,
        size: usize,
        global: usize,
        shift: f64,
    ) -> DMatrix<f64> {
        let n = global + blocks * size;
        let mut s = seed | 1;
        let mut next = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
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

    /// On B1's pattern (17 rollers of 12 states, 6 inner-ring states first) the ring's
    /// states are eliminated last; the others keep their order.
    #[test]
    fn globally_coupled_states_go_last() {
        let a = bearing_like(7, 17, 12, 6, 4.0);
        let mut coupling = Vec::new();
        let order = arrow_order(a.as_slice(), a.nrows(), &mut coupling);
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
}
