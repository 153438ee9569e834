//! The linear solver of the Newton iterations: an LU factorisation with partial pivoting,
//! computed and applied on the non-zeros only.
//!
//! The Newton matrix I − hγJ of a multibody model is mostly zeros: a body couples only to
//! the bodies it touches (in a bearing, a roller to its two neighbours and the rings), and
//! only a few bodies (the inner ring) couple to all. On B1 at full speed (193 states) it has
//! about 2 700 non-zeros (7 %), and diffsol's dense LU took 12 % of a run's samples (perf).
//! Here the right-looking elimination of Golub & Van Loan (Matrix Computations, 4th ed.,
//! algorithm 3.4.1, "Gaussian elimination with partial pivoting") updates only the rows with
//! a non-zero multiplier and the columns with a non-zero pivot-row entry, and the states that
//! couple to more than a quarter of all others are eliminated last (an arrow ordering), so
//! that eliminating them first cannot fill the whole matrix: B1's factors have about 6 400
//! non-zeros and take about 28 000 multiply-adds.
//!
//! The elimination works in place, in the matrix diffsol assembles, and never moves a row:
//! the pivot rows are recorded instead of interchanged (B1's columns nearly all pivot off
//! the diagonal: a position's column has its largest entries in the velocity rows), and the
//! structure of the rows and columns is kept in bit sets, so that after the one pass that
//! finds the non-zeros no work is spent on zeros. The arithmetic on the non-zeros is that of
//! the dense algorithm; the pivots are the largest in their column, so the stability is that
//! of partial pivoting (GVL sect. 3.4.6).

use diffsol_la::error::LinearSolverError;
use diffsol_la::{
    LaError, LinearOp, LinearSolver, Matrix, MatrixCommon, NalgebraContext, NalgebraMat,
    NalgebraVec,
};

/// Fraction of the states a state must couple to (in its row and column together) to be
/// eliminated last.
const GLOBAL_COUPLING: f64 = 0.25;

/// LU factors of P·A·Q = L·U: Q the elimination order of the columns (the arrow ordering),
/// P the pivot rows in the order they were chosen.
#[derive(Debug, Default)]
struct Factors {
    n: usize,
    /// Elimination order: step k eliminates the column of state `order[k]`.
    order: Vec<usize>,
    /// The pivot row of step k (a row of A).
    pivot_rows: Vec<usize>,
    /// Strictly lower part of L by columns (compressed: start, rows, values), in the
    /// numbering of the steps.
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
    /// A copy of the matrix for [`SparseSkipLu::factorise`].
    copy: Vec<f64>,
    rows: Vec<usize>,
    columns: Vec<usize>,
    coupling: Vec<usize>,
    /// The step at which each row of A became a pivot row (usize::MAX: not yet).
    step_of_row: Vec<usize>,
    /// The structure of the rows: bit j of row i's `words` words is set where column j of
    /// row i may be non-zero (set where it was, and by fill-in), so that the pivot row's
    /// non-zeros are found without a strided pass over the column-major storage.
    row_bits: Vec<u64>,
    /// The structure of the columns, likewise (bit i of column j: row i may be non-zero).
    column_bits: Vec<u64>,
    /// Rows already chosen as pivots, and columns already eliminated.
    pivoted: Vec<u64>,
    eliminated: Vec<u64>,
    /// The rows updated by one elimination step.
    updated: Vec<u64>,
}

/// Words of a bit set for n indices.
fn words(n: usize) -> usize {
    n.div_ceil(64)
}

/// The indices set in `bits` and clear in `excluded` (bit sets of equal length), ascending.
fn ones_except<'a>(bits: &'a [u64], excluded: &'a [u64]) -> impl Iterator<Item = usize> + 'a {
    bits.iter()
        .zip(excluded)
        .enumerate()
        .flat_map(|(word, (&b, &x))| ones_of_word(word, b & !x))
}

/// The indices set in `bits`, ascending.
fn ones(bits: &[u64]) -> impl Iterator<Item = usize> + '_ {
    bits.iter()
        .enumerate()
        .flat_map(|(word, &b)| ones_of_word(word, b))
}

/// The indices set in word `word` of a bit set, whose value is `bits`.
fn ones_of_word(word: usize, mut bits: u64) -> impl Iterator<Item = usize> {
    std::iter::from_fn(move || {
        (bits != 0).then(|| {
            let j = word * 64 + bits.trailing_zeros() as usize;
            bits &= bits - 1;
            j
        })
    })
}

fn set(bits: &mut [u64], i: usize) {
    bits[i / 64] |= 1 << (i % 64);
}

fn is_set(bits: &[u64], i: usize) -> bool {
    bits[i / 64] >> (i % 64) & 1 == 1
}

/// diffsol's [`LinearSolver`] for the dense nalgebra matrix, factorising on the non-zeros.
#[derive(Debug, Default)]
pub struct SparseSkipLu {
    matrix: Option<NalgebraMat<f64>>,
    factors: Factors,
    work: Work,
}

impl SparseSkipLu {
    /// Factorises the square column-major matrix `a` (n × n), copied.
    pub fn factorise(&mut self, a: &[f64], n: usize) {
        let mut copy = std::mem::take(&mut self.work.copy);
        copy.clear();
        copy.extend_from_slice(a);
        self.factorise_in_place(&mut copy, n);
        self.work.copy = copy;
    }

    /// Factorises the square column-major matrix `a` (n × n), overwriting it.
    ///
    /// One pass over `a` finds its non-zeros; everything after works on the non-zeros and
    /// the fill-in only, through the row and column bit sets.
    pub fn factorise_in_place(&mut self, a: &mut [f64], n: usize) {
        assert_eq!(a.len(), n * n, "the matrix must be n × n");
        let w = &mut self.work;
        let nw = words(n);
        find_structure(a, n, w);
        let order = arrow_order_of(&w.row_bits, &w.column_bits, n, &mut w.coupling);
        for bits in [&mut w.pivoted, &mut w.eliminated, &mut w.updated] {
            bits.clear();
            bits.resize(nw, 0);
        }
        w.step_of_row.clear();
        w.step_of_row.resize(n, usize::MAX);
        let mut pivot_rows = Vec::with_capacity(n);
        for (k, &c) in order.iter().enumerate() {
            let Some(p) = pivot_row(a, n, c, w) else {
                self.factors = Factors {
                    n,
                    order,
                    ..Default::default()
                };
                return;
            };
            pivot_rows.push(p);
            w.step_of_row[p] = k;
            set(&mut w.pivoted, p);
            eliminate(a, n, c, p, w);
            set(&mut w.eliminated, c);
        }
        self.factors = compress(a, n, order, pivot_rows, w);
    }

    /// Solves A x = b in place: L U z = P b, x = Q z.
    pub fn solve(&self, b: &mut [f64]) -> Result<(), LaError> {
        let f = self.checked(b.len())?;
        let mut x: Vec<f64> = f.pivot_rows.iter().map(|&i| b[i]).collect();
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

    /// Solves Aᵀ x = b in place: Uᵀ Lᵀ w = Qᵀ b, x = Pᵀ w.
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
        scatter(&x, &f.pivot_rows, b)
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

/// The row and column bit sets of the non-zeros of `a`, in one pass over it.
fn find_structure(a: &[f64], n: usize, w: &mut Work) {
    let nw = words(n);
    w.row_bits.clear();
    w.row_bits.resize(n * nw, 0);
    w.column_bits.clear();
    w.column_bits.resize(n * nw, 0);
    for j in 0..n {
        let column = &mut w.column_bits[j * nw..(j + 1) * nw];
        for (word, chunk) in a[j * n..(j + 1) * n].chunks(64).enumerate() {
            // Branch-free: a bit per entry.
            let mut bits = 0u64;
            for (b, &v) in chunk.iter().enumerate() {
                bits |= u64::from(v != 0.0) << b;
            }
            column[word] = bits;
        }
        for i in ones(&w.column_bits[j * nw..(j + 1) * nw]) {
            set(&mut w.row_bits[i * nw..(i + 1) * nw], j);
        }
    }
}

/// The elimination order: the states in their order, those coupled to more than
/// [`GLOBAL_COUPLING`] of all states (non-zeros in their row and column, the diagonal
/// aside) moved to the end.
fn arrow_order_of(
    row_bits: &[u64],
    column_bits: &[u64],
    n: usize,
    coupling: &mut Vec<usize>,
) -> Vec<usize> {
    let nw = words(n);
    let count = |bits: &[u64]| bits.iter().map(|b| b.count_ones() as usize).sum::<usize>();
    coupling.clear();
    coupling.extend((0..n).map(|i| {
        let row = &row_bits[i * nw..(i + 1) * nw];
        let diagonal = usize::from(is_set(row, i));
        count(row) + count(&column_bits[i * nw..(i + 1) * nw]) - 2 * diagonal
    }));
    let limit = GLOBAL_COUPLING * 2.0 * n as f64;
    let global = |i: &usize| coupling[*i] as f64 > limit;
    let mut order: Vec<usize> = (0..n).filter(|i| !global(i)).collect();
    order.extend((0..n).filter(global));
    order
}

/// The pivot of column c: the row not yet pivoted with the largest magnitude (ties to
/// row c itself, then to the first); None if all are zero (A is singular).
fn pivot_row(a: &[f64], n: usize, c: usize, w: &Work) -> Option<usize> {
    let nw = words(n);
    let column = &a[c * n..(c + 1) * n];
    let mut best = (!is_set(&w.pivoted, c)).then_some(c);
    for i in ones_except(&w.column_bits[c * nw..(c + 1) * nw], &w.pivoted) {
        if best.is_none_or(|b| column[i].abs() > column[b].abs()) {
            best = Some(i);
        }
    }
    best.filter(|&b| column[b] != 0.0)
}

/// The step that eliminates column c with pivot row p, on the non-zeros: the multipliers
/// in the rows not yet pivoted, then the rank-one update of those rows in the columns not
/// yet eliminated where row p has a non-zero. The fill-in goes into the row and column
/// structure.
fn eliminate(a: &mut [f64], n: usize, c: usize, p: usize, w: &mut Work) {
    let nw = words(n);
    let diag = a[c * n + p];
    w.rows.clear();
    for i in ones_except(&w.column_bits[c * nw..(c + 1) * nw], &w.pivoted) {
        let v = &mut a[c * n + i];
        if *v != 0.0 {
            *v /= diag;
            w.rows.push(i);
        }
    }
    if w.rows.is_empty() {
        return;
    }
    w.columns.clear();
    for j in ones_except(&w.row_bits[p * nw..(p + 1) * nw], &w.eliminated) {
        if j != c && a[j * n + p] != 0.0 {
            w.columns.push(j);
        }
    }
    for &j in w.columns.iter() {
        let u = a[j * n + p];
        for &i in w.rows.iter() {
            a[j * n + i] -= a[c * n + i] * u;
        }
    }
    // The fill-in: the updated rows gain the updated columns, and the transpose.
    w.updated.fill(0);
    for &j in w.columns.iter() {
        set(&mut w.updated, j);
    }
    for &i in w.rows.iter() {
        for (word, &columns) in w.updated.iter().enumerate() {
            w.row_bits[i * nw + word] |= columns;
        }
    }
    w.updated.fill(0);
    for &i in w.rows.iter() {
        set(&mut w.updated, i);
    }
    for &j in w.columns.iter() {
        for (word, &rows) in w.updated.iter().enumerate() {
            w.column_bits[j * nw + word] |= rows;
        }
    }
}

/// The factors' non-zeros by columns, read along the column structure and numbered by
/// the steps.
fn compress(a: &[f64], n: usize, order: Vec<usize>, pivot_rows: Vec<usize>, w: &Work) -> Factors {
    let nw = words(n);
    let mut f = Factors {
        n,
        regular: true,
        ..Default::default()
    };
    f.l_start.push(0);
    f.u_start.push(0);
    for (k, &c) in order.iter().enumerate() {
        let column = &a[c * n..(c + 1) * n];
        f.diagonal.push(column[pivot_rows[k]]);
        for i in ones(&w.column_bits[c * nw..(c + 1) * nw]) {
            let v = column[i];
            let r = w.step_of_row[i];
            if v == 0.0 || r == k {
                continue;
            }
            if r < k {
                f.u_rows.push(r);
                f.u_values.push(v);
            } else {
                f.l_rows.push(r);
                f.l_values.push(v);
            }
        }
        f.l_start.push(f.l_rows.len());
        f.u_start.push(f.u_rows.len());
    }
    f.order = order;
    f.pivot_rows = pivot_rows;
    f
}

/// b[index[k]] = x[k].
fn scatter(x: &[f64], index: &[usize], b: &mut [f64]) -> Result<(), LaError> {
    for (k, &i) in index.iter().enumerate() {
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
        self.factorise_in_place(matrix.inner_mut().as_mut_slice(), n);
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

    /// Textbook dense Gaussian elimination with partial pivoting (GVL algorithm 3.4.1)
    /// of Q A Qᵀ for the order `order`, interchanging rows, every entry updated at every
    /// step. Returns the pivot rows (rows of A, step by step) and the packed factors (L's
    /// multipliers below the diagonal, U on and above).
    fn dense_elimination(a: &DMatrix<f64>, order: &[usize]) -> (Vec<usize>, DMatrix<f64>) {
        let n = a.nrows();
        let mut m = DMatrix::from_fn(n, n, |i, j| a[(order[i], order[j])]);
        let mut rows: Vec<usize> = order.to_vec();
        for k in 0..n {
            let mut p = k;
            for i in k + 1..n {
                if m[(i, k)].abs() > m[(p, k)].abs() {
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
            let f = &lu.factors;
            prop_assume!(f.regular);
            let (rows, m) = dense_elimination(&a, &f.order);
            prop_assert_eq!(&f.pivot_rows, &rows);
            let mut packed = DMatrix::zeros(n, n);
            for j in 0..n {
                packed[(j, j)] = f.diagonal[j];
                for e in f.l_start[j]..f.l_start[j + 1] {
                    packed[(f.l_rows[e], j)] = f.l_values[e];
                }
                for e in f.u_start[j]..f.u_start[j + 1] {
                    packed[(f.u_rows[e], j)] = f.u_values[e];
                }
            }
            for (x, y) in packed.iter().zip(m.iter()) {
                prop_assert!(x.to_bits() == y.to_bits() || (*x == 0.0 && *y == 0.0), "{x} vs {y}");
            }
        }
    }

    /// On B1's pattern (17 rollers of 12 states, 6 inner-ring states first) the ring's
    /// states are eliminated last; the others keep their order.
    #[test]
    fn globally_coupled_states_go_last() {
        let a = bearing_like(7, 17, 12, 6, 4.0);
        let n = a.nrows();
        let mut w = Work::default();
        find_structure(a.as_slice(), n, &mut w);
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
}
