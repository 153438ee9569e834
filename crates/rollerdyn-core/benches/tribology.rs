//! Criterion benchmarks of the hot path: the EHL traction integral of one line slice and
//! one elliptical contact, B1's oil at 80 °C (η₀ = 16.5 mPa·s, z = 0.62), and the
//! Hertz point contact (fit and exact). Run: `cargo bench -p rollerdyn-core`.

use criterion::{criterion_group, criterion_main, Criterion};
use rollerdyn_core::bearing::forces::{line_slice, LineKind, Section, Tribology};
use rollerdyn_core::bearing::state::Kinematics;
use rollerdyn_core::bearing::RollingResistance;
use rollerdyn_core::geometry::primitives::Vec3;
use rollerdyn_core::tribology::film::{thermal_correction, FilmInputs, ThermalCorrection};
use rollerdyn_core::tribology::friction::{BoundaryFriction, LoadSharing};
use rollerdyn_core::tribology::hertz::{EllipticalContact, EllipticalMethod};
use rollerdyn_core::tribology::line_contact::LinePowerLaw;
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
    let table = rollerdyn_core::tribology::film::MoesTable::default();
    c.bench_function("film: Moes line, tabulated", |b| {
        b.iter(|| {
            inputs.moes_line_tabulated(&table, black_box(1.9e-3), black_box(0.13), black_box(1e5))
        })
    });
    c.bench_function("film: ZEV line", |b| {
        b.iter(|| inputs.zev_line(black_box(1.1e-3), black_box(0.13), black_box(1e5)))
    });
    c.bench_function("film: thermal correction", |b| {
        b.iter(|| thermal_correction(-8e-4, 0.134, black_box(0.13), black_box(2e-3)))
    });
}

/// One loaded slice of a roller–inner race contact with all of its tribology (eq. 11
/// with damping, Moes film, thermal correction, EHL traction, boundary and mixed friction,
/// rolling resistance): B1's inner race at full speed (R' = 1.9 mm, u₀ ≈ 0.13 m/s, about
/// 2 % slide-to-roll ratio, 5 µm penetration of a 0.5 mm slice).
fn slice(c: &mut Criterion) {
    let tribology = Tribology {
        traction: b1_traction(12).tabulated(TableGrid::default()),
        boundary: BoundaryFriction {
            mu_b0: 0.1,
            s0: 0.02,
            smoothing_speed: 1e-3,
        },
        eta0: 0.0165,
        alpha_star: 1.4e-8,
        thermal: ThermalCorrection::new(-8e-4, 0.134),
        moes: Default::default(),
        hysteresis_coefficient: 0.007,
        rolling_resistance: RollingResistance::Paper,
        damping_ratio: 0.1,
        friction: true,
        film: rollerdyn_core::tribology::hydrodynamic::RigidFilm::OFF,
    };
    let kind = LineKind {
        law: LinePowerLaw {
            k1: 1.3e-11,
            k2: 0.9,
        },
        e_prime: 2.3e11,
        r_eff: 1.9e-3,
        roughness: 0.2e-6,
        sharing: LoadSharing { b: 1.2, c: 0.9 },
        counter_rotating: false,
        rolling_resistance: true,
        mass_per_length: 1.0,
    };
    // Inner ring (A) turning at 100 rad/s about x; the roller (B) 2.25 mm outside its
    // raceway of 25 mm radius, spinning backwards a little slower than pure rolling.
    let ring = Kinematics {
        center: Vec3::zeros(),
        axis: Vec3::x(),
        velocity: Vec3::zeros(),
        omega: Vec3::new(1.3 / 0.025, 0.0, 0.0),
    };
    let roller = Kinematics {
        center: Vec3::new(0.0, 0.02725, 0.0),
        axis: Vec3::x(),
        velocity: Vec3::new(0.0, 0.0, 0.55),
        omega: Vec3::new(-320.0, 0.0, 0.0),
    };
    let normal = Vec3::y();
    let location = Vec3::new(1e-3, 0.025, 0.0);
    let rolling = Vec3::z();
    let frame = Vec3::new(0.0, 0.0, 0.55 * 0.025 / 0.02725);
    c.bench_function("line slice, loaded race slice with all tribology", |b| {
        b.iter(|| {
            line_slice(
                &tribology,
                &kind,
                &Section {
                    a: &ring,
                    b: black_box(&roller),
                    normal,
                    location,
                    penetration: black_box(5e-6),
                    length: 5e-4,
                    rolling,
                    frame,
                },
            )
        })
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
    targets = traction, film, slice, hertz
}
criterion_main!(benches);
