//! Criterion benchmark of the Newton iterations' linear solver on a matrix with B1's
//! shape: 17 rollers of 11 states, each coupled to itself and its two neighbours around
//! the ring, and 6 inner-ring states coupled to all (193 states, ~7 000 non-zeros before
//! dropping; B1's own Newton matrix has ~2 700). Pivoting is needed: the diagonal is not
//! dominant. Run: `cargo bench -p rollerdyn-core --bench linear`.

use criterion::{criterion_group, criterion_main, Criterion};
use rollerdyn_core::dynamics::sparse_lu::SparseSkipLu;
use std::hint::black_box;

/// The B1-shaped matrix, column-major; entries from a fixed pseudo-random sequence,
/// 70 % of the coupled entries kept.
fn b1_shaped() -> (Vec<f64>, usize) {
    let (rollers, size, ring) = (17, 11, 6);
    let n = ring + rollers * size;
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
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

fn lu(c: &mut Criterion) {
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
