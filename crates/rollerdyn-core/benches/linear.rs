//! Criterion benchmark of the Newton iterations' linear solver on a matrix with B1's
//! shape: 17 rollers of 11 states, each coupled to itself and its two neighbours around
//! the ring, and 6 inner-ring states coupled to all (193 states, ~7 000 non-zeros before
//! dropping; B1's own Newton matrix has ~2 700). Pivoting is needed: the diagonal is not
//! dominant. Run: `cargo bench -p rollerdyn-core --bench linear`.

use criterion::{criterion_group, criterion_main, Criterion};
use rollerdyn_core::dynamics::sparse_lu::SparseSkipLu;
use std::hint::black_box;

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

/// The B1-shaped matrix, column-major; entries from a fixed pseudo-random sequence,
/// 70 % of the coupled entries kept.
fn b1_shaped() -> (Vec<f64>, usize) {
    let (rollers, size, ring) = (17, 11, 6);
    let n = ring + rollers * size;
    let mut next = uniform(0x2545_f491_4f6c_dd1d_u64);
    let body = |k: usize| (k >= ring).then(|| (k - ring) / size);
    let mut a = vec![0.0; n * n];
    for j in 0..n {
        for i in 0..n {
            let coupled = match (body(i), body(j)) {
                (Some(p), Some(q)) => p == q || (p + 1) % rollers == q || (q + 1) % rollers == p,
                _ => true,
            };
            if coupled && next() < 0.7 {
                a[j * n + i] = next() - 0.5;
            }
        }
    }
    (a, n)
}

/// A mechanical Newton matrix I − hγJ of B1's shape, J = [[0, I], [K, C]]: 17 rollers
/// and the inner ring, 3 positions and 3 velocities each (q' = v), the velocities coupled
/// to the neighbours' and the ring's states (K/m about 1e11 1/s², C/m 1e3 1/s, hγ = 1e-5 s).
fn mechanical() -> (Vec<f64>, usize) {
    let (rollers, bodies) = (17, 18);
    let n = 6 * bodies;
    let mut next = uniform(0x9e37_79b9_7f4a_7c15_u64);
    let coupled = |a: usize, b: usize| {
        a == 0 || b == 0 || a == b || a % rollers + 1 == b || b % rollers + 1 == a
    };
    let mut a = vec![0.0; n * n];
    for j in 0..n {
        for i in 0..n {
            let (bi, bj, li, lj) = (i / 6, j / 6, i % 6, j % 6);
            let jac = if li < 3 {
                f64::from(u8::from(bi == bj && lj == li + 3))
            } else if coupled(bi, bj) && next() < 0.8 {
                (if lj < 3 { 1e11 } else { 1e3 }) * (next() - 0.5)
            } else {
                0.0
            };
            a[j * n + i] = f64::from(u8::from(i == j)) - 1e-5 * jac;
        }
    }
    (a, n)
}

fn lu(c: &mut Criterion) {
    let (m, n_m) = mechanical();
    c.bench_function(
        "sparse LU: mechanical 108 states, positions condensed",
        |b| b.iter(|| SparseSkipLu::default().factorise(black_box(&m), n_m)),
    );
    c.bench_function(
        "sparse LU: mechanical 108 states, partial pivoting only",
        |b| {
            b.iter(|| {
                let mut lu = SparseSkipLu::default();
                lu.partial_pivoting_only = true;
                lu.factorise(black_box(&m), n_m)
            })
        },
    );
    let (a, n) = b1_shaped();
    c.bench_function("sparse LU: factorise in full, B1-shaped 193 states", |b| {
        b.iter(|| SparseSkipLu::default().factorise(black_box(&a), n))
    });
    let mut lu = SparseSkipLu::default();
    c.bench_function(
        "sparse LU: factorise by replay, B1-shaped 193 states",
        |b| b.iter(|| lu.factorise(black_box(&a), n)),
    );
    let rhs: Vec<f64> = (0..n).map(|i| (i as f64 + 1.0).sin()).collect();
    c.bench_function("sparse LU: solve, B1-shaped 193 states", |b| {
        b.iter(|| {
            let mut x = rhs.clone();
            lu.solve(black_box(&mut x)).unwrap();
            x
        })
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(30).measurement_time(std::time::Duration::from_secs(2));
    targets = lu
}
criterion_main!(benches);
