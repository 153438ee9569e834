//! Criterion benchmarks of the hot path: the EHL traction integral of one line slice and
//! one elliptical contact, B1's oil at 80 °C (η₀ = 16.5 mPa·s, z = 0.62), and the
//! Hertz point contact (fit and exact). Run: `cargo bench -p rollerdyn-core`.

use criterion::{criterion_group, criterion_main, Criterion};
use rollerdyn_core::tribology::film::{thermal_correction, FilmInputs};
use rollerdyn_core::tribology::hertz::{EllipticalContact, EllipticalMethod};
use rollerdyn_core::tribology::lubricant::{Carreau, Roelands};
use rollerdyn_core::tribology::traction::{EhlTraction, LimitingShearStress, TableGrid};
use std::hint::black_box;

fn b1_traction(nodes: usize) -> EhlTraction {
    EhlTraction::new(
        Roelands {
            z: 0.62,
            ..Roelands::default()
        },
        Carreau { tau0: 5e6, n: 0.5 },
        LimitingShearStress {
            chi: 0.08,
            p_star: 1.5e9,
            tau_l0: 0.12e9,
            smoothing: 20e6,
        },
        0.0165,
        nodes,
    )
}

fn traction(c: &mut Criterion) {
    let variants = [
        ("tabulated", b1_traction(12).tabulated(TableGrid::default())),
        ("direct 12 nodes", b1_traction(12)),
        ("direct 24 nodes", b1_traction(24)),
    ];
    for (name, t) in &variants {
        c.bench_function(&format!("traction line slice, {name}"), |b| {
            b.iter(|| {
                t.line_force(
                    black_box(1.8e9),
                    black_box(1.2e-4),
                    2.5e-4,
                    black_box(0.02),
                    2e-7,
                )
            })
        });
        c.bench_function(&format!("traction ellipse, {name}"), |b| {
            b.iter(|| {
                t.ellipse_force(
                    black_box(1.2e9),
                    black_box(3e-4),
                    1e-4,
                    black_box(0.05),
                    2e-7,
                )
            })
        });
    }
}

/// The film formulas of one line slice (B1's inner race at full speed: R' = 1.9 mm,
/// u₀ = 0.13 m/s, q = 100 kN/m) and the thermal correction.
fn film(c: &mut Criterion) {
    let inputs = FilmInputs {
        e_prime: 2.3e11,
        alpha_star: 1.4e-8,
        eta0: 0.0165,
    };
    c.bench_function("film: Moes line", |b| {
        b.iter(|| inputs.moes_line(black_box(1.9e-3), black_box(0.13), black_box(1e5)))
    });
    c.bench_function("film: ZEV line", |b| {
        b.iter(|| inputs.zev_line(black_box(1.1e-3), black_box(0.13), black_box(1e5)))
    });
    c.bench_function("film: thermal correction", |b| {
        b.iter(|| thermal_correction(-8e-4, 0.134, black_box(0.13), black_box(2e-3)))
    });
}

fn hertz(c: &mut Criterion) {
    for (name, method) in [
        ("Brewe-Hamrock", EllipticalMethod::BreweHamrock),
        ("exact", EllipticalMethod::Exact),
    ] {
        c.bench_function(&format!("Hertz point contact setup + force, {name}"), |b| {
            b.iter(|| {
                let contact =
                    EllipticalContact::new(black_box(5e-4), black_box(3.2e-3), 2.3e11, method);
                contact.at_penetration(black_box(1e-6))
            })
        });
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(30).measurement_time(std::time::Duration::from_secs(2));
    targets = traction, film, hertz
}
criterion_main!(benches);
