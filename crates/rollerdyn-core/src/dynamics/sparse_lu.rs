//! The linear solver of the Newton iterations: an LU factorisation with partial pivoting,
//! computed and applied on the non-zeros only.
//!
//! The Newton matrix I − hγJ of a multibody model is mostly zeros: a body couples only to
//! the bodies it touches (in a bearing, a roller to its two neighbours and the rings), and
//! only a few bodies (the inner ring) couple to all. On B1 at full speed (193 states) it has
//! about 2 700 non-zeros (7 %), and diffsol's dense LU took 12 % of a run's samples (perf).
//! Here the right-looking elimination of Golub & Van Loan (Matrix Computations, 4th ed.,
//! algorithm 3.4.1, "Gaussian elimination with partial pivoting") updates only the rows with
//! a non-zero multiplier and the columns with a non-zero pivot-row entry. The positions of
//! the mechanical system (rows with a few non-zeros, dominated by their diagonal) are
//! eliminated first, on their diagonals ([`condensed_first`]: static condensation); the
//! states that couple to more than a quarter of all others are eliminated last (an arrow
//! ordering), so that eliminating them early cannot fill the whole matrix. Partial
//! pivoting alone picked the velocity rows as the positions' pivots and took 280 000 to
//! 740 000 multiply-adds on B1's Newton matrices at full speed; with the condensation the
//! whole B1 run spends about 2.6 s instead of 7.4 s outside its right-hand sides and
//! Jacobians (docs/performance-log.md, "Static condensation in the sparse LU").
//!
//! The elimination works in place, in the matrix diffsol assembles, and never moves a row:
//! the pivot rows are recorded instead of interchanged, and the
//! structure of the rows and columns is kept in bit sets, so that after the one pass that
//! finds the non-zeros no work is spent on zeros. The arithmetic on the non-zeros is that of
//! the dense algorithm; the pivots are the largest in their column, or for a condensed
//! position the largest in its row, so the stability is that of partial pivoting (GVL
//! sect. 3.4.6, by columns or by rows).
//!
//! Most Newton matrices differ from the one before only by the step size h (diffsol
//! assembles a new one whenever h changes by 30 %, and keeps J for up to 50 steps). They have
//! the same non-zeros, so the last elimination is replayed: the same pivot rows, the same
//! structure and fill-in, with only the arithmetic done again, as long as each pivot stays
//! within [`REPLAY_PIVOT_THRESHOLD`] of the largest entry of its column (of its row, for a
//! condensed position: threshold partial pivoting); else the matrix is factorised in full.

use diffsol_la::error::LinearSolverError;
use diffsol_la::{
    LaError, LinearOp, LinearSolver, Matrix, MatrixCommon, NalgebraContext, NalgebraMat,
    NalgebraVec,
};

/// Fraction of the states a state must couple to (in its row and column together) to be
/// eliminated last.
const GLOBAL_COUPLING: f64 = 0.25;

/// A state whose row has at most this many non-zeros besides the diagonal, and whose
/// diagonal is at least the sum of their magnitudes, is eliminated first, on its diagonal
/// ([`condensed_first`]).
const CONDENSED_ROW: usize = 8;

/// A replayed elimination keeps its pivot where it is at least this fraction of the
/// largest candidate in its column: threshold partial pivoting (Duff, Erisman & Reid,
/// Direct Methods for Sparse Matrices, 2nd ed., sect. 6.3; 0.1 is UMFPACK's default),
/// which bounds the growth of the entries per step by 1 + 1/τ = 11 instead of 2. A
/// full factorisation pivots on the largest.
const REPLAY_PIVOT_THRESHOLD: f64 = 0.1;

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
    /// Where in the factorised matrix each value of L, U and the diagonal stands (the
    /// layout is that of the elimination, so a replay only gathers the values anew).
    l_source: Vec<usize>,
    u_source: Vec<usize>,
    diagonal_source: Vec<usize>,
    /// False if a pivot was zero (the matrix is singular).
    regular: bool,
}

impl Factors {
    /// The values of L, U and the diagonal from the factorised matrix `a`.
    fn gather(&mut self, a: &[f64]) {
        for (values, source) in [
            (&mut self.l_values, &self.l_source),
            (&mut self.u_values, &self.u_source),
            (&mut self.diagonal, &self.diagonal_source),
        ] {
            values.clear();
            values.extend(source.iter().map(|&e| a[e]));
        }
    }
}

/// The last full elimination, kept to be replayed on the next matrix if that has the same
/// non-zeros (on B1 most often: the same Jacobian with a new step size) and the same
/// pivot rows pass [`REPLAY_PIVOT_THRESHOLD`]: the search for the pivots, the structure and
/// the fill-in is not repeated.
#[derive(Debug, Default)]
struct Schedule {
    /// The non-zeros of the matrix it was made for (column bit sets); empty: none yet.
    pattern: Vec<u64>,
    /// The structure of the factors (column bit sets).
    structure: Vec<u64>,
    /// The elimination order and the pivot rows of the steps.
    order: Vec<usize>,
    pivot_rows: Vec<usize>,
    /// Whether step k took its diagonal as pivot by the row test of [`condensed_first`]
    /// (else: the largest of its column).
    row_pivot: Vec<bool>,
    /// The step at which each row became a pivot row.
    step_of_row: Vec<usize>,
    /// Step k: the rows of the pivot column not pivoted before it, ascending (the pivot
    /// row among them): `candidates[candidate_start[k]..candidate_start[k + 1]]`.
    candidates: Vec<usize>,
    candidate_start: Vec<usize>,
    /// Step k: the columns it updates.
    columns: Vec<usize>,
    column_start: Vec<usize>,
}

/// What a replay of the [`Schedule`] did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Replay {
    /// The matrix is factorised.
    Done,
    /// The matrix has other non-zeros: untouched.
    OtherPattern,
    /// A pivot fell below the threshold (or was zero) part-way: the matrix is overwritten.
    OtherPivot,
}

/// Working storage reused between factorisations.
#[derive(Debug, Default)]
struct Work {
    /// A copy of the matrix for [`SparseSkipLu::factorise`].
    copy: Vec<f64>,
    /// The non-zeros of the matrix being factorised (column bit sets).
    pattern: Vec<u64>,
    coupling: Vec<usize>,
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
    schedule: Schedule,
    /// Factorisations done by replaying the schedule, and in full.
    replays: usize,
    full: usize,
    /// Partial pivoting throughout, no state eliminated first on its diagonal
    /// ([`condensed_first`]): for comparison only (tests, `benches/linear.rs`).
    pub partial_pivoting_only: bool,
}

impl SparseSkipLu {
    /// Factorises the square column-major matrix `a` (n × n), copied.
    pub fn factorise(&mut self, a: &[f64], n: usize) {
        let mut copy = std::mem::take(&mut self.work.copy);
        copy.clear();
        copy.extend_from_slice(a);
        match self.replay(&mut copy, n) {
            Replay::Done => {}
            Replay::OtherPattern => self.factorise_in_place(&mut copy, n),
            Replay::OtherPivot => {
                copy.copy_from_slice(a);
                self.factorise_in_place(&mut copy, n);
            }
        }
        self.work.copy = copy;
    }

    /// Factorisations so far: (by replaying the last elimination, in full).
    pub fn counts(&self) -> (usize, usize) {
        (self.replays, self.full)
    }

    /// Multiply-adds of the last elimination's updates (what a replay costs).
    pub fn elimination_cost(&self) -> usize {
        let sc = &self.schedule;
        (0..sc.pivot_rows.len())
            .map(|k| {
                let rows = sc.candidate_start[k + 1] - sc.candidate_start[k];
                let columns = sc.column_start[k + 1] - sc.column_start[k];
                rows.saturating_sub(1) * columns
            })
            .sum()
    }

    /// Factorises `a` (n × n, column-major) by replaying the last full elimination if `a`
    /// has its non-zeros and its pivot rows pass the threshold; see [`Replay`] for what is
    /// left in `a`.
    fn replay(&mut self, a: &mut [f64], n: usize) -> Replay {
        assert_eq!(a.len(), n * n, "the matrix must be n × n");
        find_pattern(a, n, &mut self.work.pattern);
        if self.schedule.pattern != self.work.pattern {
            return Replay::OtherPattern;
        }
        if !replay_elimination(a, n, &self.schedule) {
            return Replay::OtherPivot;
        }
        self.factors.gather(a);
        self.replays += 1;
        Replay::Done
    }

    /// Factorises the square column-major matrix `a` (n × n) in full, overwriting it, and
    /// keeps the elimination as the schedule to replay.
    ///
    /// One pass over `a` finds its non-zeros; everything after works on the non-zeros and
    /// the fill-in only, through the row and column bit sets.
    pub fn factorise_in_place(&mut self, a: &mut [f64], n: usize) {
        assert_eq!(a.len(), n * n, "the matrix must be n × n");
        self.full += 1;
        let w = &mut self.work;
        let sc = &mut self.schedule;
        let nw = words(n);
        find_pattern(a, n, &mut w.pattern);
        structure_of(n, w);
        let arrow = arrow_order_of(&w.row_bits, &w.column_bits, n, &mut w.coupling);
        let condensed = if self.partial_pivoting_only {
            sc.order = arrow;
            0
        } else {
            condensed_first(a, n, &w.row_bits, arrow, &mut sc.order)
        };
        for bits in [&mut w.pivoted, &mut w.eliminated, &mut w.updated] {
            bits.clear();
            bits.resize(nw, 0);
        }
        sc.step_of_row.clear();
        sc.step_of_row.resize(n, usize::MAX);
        sc.pivot_rows.clear();
        sc.row_pivot.clear();
        for list in [&mut sc.candidates, &mut sc.columns] {
            list.clear();
        }
        for start in [&mut sc.candidate_start, &mut sc.column_start] {
            start.clear();
            start.push(0);
        }
        for k in 0..n {
            let c = sc.order[k];
            let from = sc.candidates.len();
            sc.candidates.extend(ones_except(
                &w.column_bits[c * nw..(c + 1) * nw],
                &w.pivoted,
            ));
            let row_pivot = k < condensed
                && !is_set(&w.pivoted, c)
                && dominates_its_row(a, n, c, &w.row_bits[c * nw..(c + 1) * nw], &w.eliminated);
            let pivot = if row_pivot {
                Some(c)
            } else {
                pivot_row(a, n, c, &sc.candidates[from..], !is_set(&w.pivoted, c))
            };
            let Some(p) = pivot else {
                sc.pattern.clear();
                self.factors = Factors {
                    n,
                    order: sc.order.clone(),
                    ..Default::default()
                };
                return;
            };
            sc.candidate_start.push(sc.candidates.len());
            sc.pivot_rows.push(p);
            sc.row_pivot.push(row_pivot);
            sc.step_of_row[p] = k;
            set(&mut w.pivoted, p);
            eliminate(a, n, c, p, w, sc);
            sc.column_start.push(sc.columns.len());
            set(&mut w.eliminated, c);
        }
        sc.structure.clone_from(&w.column_bits);
        sc.pattern.clone_from(&w.pattern);
        self.factors = compress(a, n, sc);
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

/// The column bit sets of the non-zeros of `a`, in one pass over it.
fn find_pattern(a: &[f64], n: usize, pattern: &mut Vec<u64>) {
    let nw = words(n);
    pattern.clear();
    pattern.resize(n * nw, 0);
    for j in 0..n {
        let column = &mut pattern[j * nw..(j + 1) * nw];
        for (word, chunk) in a[j * n..(j + 1) * n].chunks(64).enumerate() {
            // Branch-free: a bit per entry.
            let mut bits = 0u64;
            for (b, &v) in chunk.iter().enumerate() {
                bits |= u64::from(v != 0.0) << b;
            }
            column[word] = bits;
        }
    }
}

/// The working row and column bit sets of the matrix with the non-zeros `w.pattern`.
fn structure_of(n: usize, w: &mut Work) {
    let nw = words(n);
    w.column_bits.clone_from(&w.pattern);
    w.row_bits.clear();
    w.row_bits.resize(n * nw, 0);
    for j in 0..n {
        for i in ones(&w.pattern[j * nw..(j + 1) * nw]) {
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

/// Puts first, into `order`, the states of `arrow` whose rows have at most
/// [`CONDENSED_ROW`] non-zeros besides the diagonal and are diagonally dominant
/// (|a_ii| ≥ Σ_{j≠i} |a_ij|), the rest after them as `arrow` has them; returns how many
/// were put first.
///
/// Such rows are those of the positions of a mechanical system, q' = v: in the Newton
/// matrix I − hγJ a position's row holds 1 and the −hγ of its velocities, while its
/// column holds the stiffness hγ·∂a/∂q of every body it touches, which partial pivoting
/// would pick as pivots (and fill the matrix with). Eliminated first on their diagonals,
/// the positions leave the velocities' system I − hγJ_vv − (hγ)²J_vq, which has the
/// sparsity of the velocities (static condensation, as in the Newmark-type solvers of
/// structural dynamics; Géradin & Rixen, *Mechanical Vibrations*, 3rd ed., 2015, ch. 7).
/// With a dominant pivot row every |u_kj/u_kk| ≤ 1, so each such step at most doubles an
/// entry: the bound of partial pivoting, by rows (Golub & Van Loan, 4th ed., sect. 3.4.6,
/// applied to Aᵀ). On B1 the elimination takes 4–10 times fewer multiply-adds than with
/// partial pivoting throughout (`benches/linear.rs`, docs/performance-log.md).
fn condensed_first(
    a: &[f64],
    n: usize,
    row_bits: &[u64],
    arrow: Vec<usize>,
    order: &mut Vec<usize>,
) -> usize {
    let nw = words(n);
    let light = |i: usize| {
        let row = &row_bits[i * nw..(i + 1) * nw];
        let (count, sum) = ones(row)
            .filter(|&j| j != i)
            .fold((0, 0.0), |(c, s), j| (c + 1, s + a[j * n + i].abs()));
        count <= CONDENSED_ROW && sum <= a[i * n + i].abs() && a[i * n + i] != 0.0
    };
    order.clear();
    order.extend(arrow.iter().copied().filter(|&i| light(i)));
    let condensed = order.len();
    order.extend(arrow.iter().copied().filter(|&i| !light(i)));
    condensed
}

/// Whether row c of `a` (its structure `row`) is still dominated by its diagonal over the
/// columns not yet eliminated, as when [`condensed_first`] chose it.
fn dominates_its_row(a: &[f64], n: usize, c: usize, row: &[u64], eliminated: &[u64]) -> bool {
    let off: f64 = ones_except(row, eliminated)
        .filter(|&j| j != c)
        .map(|j| a[j * n + c].abs())
        .sum();
    a[c * n + c] != 0.0 && off <= a[c * n + c].abs()
}

/// The pivot of column c among its `candidates` (the rows not yet pivoted where it may be
/// non-zero, ascending): the largest in magnitude, ties to row c itself (if it is not yet
/// pivoted: `c_free`), then to the first; None if all are zero (A is singular).
fn pivot_row(a: &[f64], n: usize, c: usize, candidates: &[usize], c_free: bool) -> Option<usize> {
    let column = &a[c * n..(c + 1) * n];
    let mut best = c_free.then_some(c);
    for &i in candidates {
        if best.is_none_or(|b| column[i].abs() > column[b].abs()) {
            best = Some(i);
        }
    }
    best.filter(|&b| column[b] != 0.0)
}

/// The step that eliminates column c with pivot row p: the multipliers in the candidate
/// rows of step k (the last of `schedule.candidate_start`), then the rank-one update of
/// those rows in the columns not yet eliminated where row p may be non-zero, which are
/// added to the schedule. The fill-in goes into the row and column structure.
fn eliminate(a: &mut [f64], n: usize, c: usize, p: usize, w: &mut Work, sc: &mut Schedule) {
    let nw = words(n);
    let k = sc.candidate_start.len() - 2;
    let rows = &sc.candidates[sc.candidate_start[k]..sc.candidate_start[k + 1]];
    let from = sc.columns.len();
    sc.columns
        .extend(ones_except(&w.row_bits[p * nw..(p + 1) * nw], &w.eliminated).filter(|&j| j != c));
    let columns = &sc.columns[from..];
    update(a, n, c, p, rows, columns);
    // The fill-in: the updated rows gain the updated columns, and the transpose.
    w.updated.fill(0);
    for &j in columns {
        set(&mut w.updated, j);
    }
    for &i in rows.iter().filter(|&&i| i != p) {
        for (word, &columns) in w.updated.iter().enumerate() {
            w.row_bits[i * nw + word] |= columns;
        }
    }
    w.updated.fill(0);
    for &i in rows.iter().filter(|&&i| i != p) {
        set(&mut w.updated, i);
    }
    for &j in columns {
        for (word, &rows) in w.updated.iter().enumerate() {
            w.column_bits[j * nw + word] |= rows;
        }
    }
}

/// The arithmetic of one step: the multipliers a(i, c) / a(p, c) of the `rows` (p
/// skipped), and a(i, j) −= multiplier·a(p, j) in the `columns`. Entries that are zero
/// change nothing (x − 0·y = x), so the structure may hold more than the non-zeros.
fn update(a: &mut [f64], n: usize, c: usize, p: usize, rows: &[usize], columns: &[usize]) {
    let diag = a[c * n + p];
    for &i in rows {
        if i != p {
            a[c * n + i] /= diag;
        }
    }
    for &j in columns {
        let u = a[j * n + p];
        if u == 0.0 {
            continue;
        }
        for &i in rows {
            if i != p {
                a[j * n + i] -= a[c * n + i] * u;
            }
        }
    }
}

/// Replays `schedule` on `a`, each recorded pivot checked to be non-zero and within
/// [`REPLAY_PIVOT_THRESHOLD`] of the largest candidate of its column; false (with `a`
/// overwritten part-way) at the first that is not.
fn replay_elimination(a: &mut [f64], n: usize, sc: &Schedule) -> bool {
    for (k, &c) in sc.order.iter().enumerate() {
        let rows = &sc.candidates[sc.candidate_start[k]..sc.candidate_start[k + 1]];
        let p = sc.pivot_rows[k];
        let columns = &sc.columns[sc.column_start[k]..sc.column_start[k + 1]];
        let pivot = a[c * n + p];
        let largest = if sc.row_pivot[k] {
            columns
                .iter()
                .fold(0.0f64, |m, &j| m.max(a[j * n + p].abs()))
        } else {
            rows.iter().fold(0.0f64, |m, &i| m.max(a[c * n + i].abs()))
        };
        if !(pivot.abs() >= REPLAY_PIVOT_THRESHOLD * largest && pivot != 0.0) {
            return false;
        }
        update(a, n, c, p, rows, columns);
    }
    true
}

/// The factors by columns, laid out along the structure of the schedule's elimination
/// (its non-zeros and the entries that cancelled to zero) and numbered by its steps.
fn compress(a: &[f64], n: usize, sc: &Schedule) -> Factors {
    let nw = words(n);
    let mut f = Factors {
        n,
        regular: true,
        ..Default::default()
    };
    f.l_start.push(0);
    f.u_start.push(0);
    for (k, &c) in sc.order.iter().enumerate() {
        f.diagonal_source.push(c * n + sc.pivot_rows[k]);
        for i in ones(&sc.structure[c * nw..(c + 1) * nw]) {
            let r = sc.step_of_row[i];
            if r < k {
                f.u_rows.push(r);
                f.u_source.push(c * n + i);
            } else if r > k {
                f.l_rows.push(r);
                f.l_source.push(c * n + i);
            }
        }
        f.l_start.push(f.l_rows.len());
        f.u_start.push(f.u_rows.len());
    }
    f.order.clone_from(&sc.order);
    f.pivot_rows.clone_from(&sc.pivot_rows);
    f.gather(a);
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
        match self.replay(matrix.inner_mut().as_mut_slice(), n) {
            Replay::Done => {}
            Replay::OtherPattern => self.factorise_in_place(matrix.inner_mut().as_mut_slice(), n),
            Replay::OtherPivot => {
                op.matrix_inplace(&mut matrix);
                self.factorise_in_place(matrix.inner_mut().as_mut_slice(), n);
            }
        }
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
mod tests;
