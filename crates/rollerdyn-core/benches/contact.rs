//! Criterion benchmarks of roller end / flange detection on B1's geometry: one composite
//! evaluation (six pairings of one roller end against one flange) per method, over a
//! roller's trajectory through the load zone (the gradient method warm-started from the
//! previous step, as in a run); and the distributed law's overlap integral over the
//! trajectory's poses where the end presses the flange, from a fresh support frame and from
//! the one the pose before left, as in a run. Run:
//! `cargo bench -p rollerdyn-core --bench contact`.

use criterion::{criterion_group, criterion_main, Criterion};
use rollerdyn_core::contact::benchmark::Trajectory;
use rollerdyn_core::contact::distributed::{self, Asperities};
use rollerdyn_core::contact::{deepest, gradient, pruning, semi_analytical, Pairing};
use rollerdyn_core::geometry::circle::{circle_circle_distance, Circle3};
use rollerdyn_core::geometry::end_flange::{Flange, FlangePlacement, FlangeShape, RollerEnd};
use rollerdyn_core::geometry::primitives::Vec3;
use rollerdyn_core::geometry::roller::RollerShape;
use std::hint::black_box;

fn b1() -> (RollerShape, Flange, Vec<RollerEnd>) {
    let shape = RollerShape::new(4.495e-3 / 2.0, 5e-3, 0.5e-3, 5.0).unwrap();
    let flange_shape = FlangeShape::new(0.11f64.to_radians(), 1.1e-3, 0.2e-3, 0.3e-3).unwrap();
    let flange = Flange::new(
        &flange_shape,
        &FlangePlacement {
            origin: Vec3::zeros(),
            axis: Vec3::x(),
            raceway_radius: 10e-3,
            rises: 1.0,
            face_position: 2.52e-3,
            facing: -1.0,
        },
    );
    let trajectory = Trajectory {
        pitch_radius: 12.25e-3,
        step: 1e-3,
        steps: 6283,
        push: 22e-6,
        wobble: 1e-3,
    };
    let ends = (0..trajectory.steps)
        .map(|k| trajectory.end(&shape, k))
        .collect();
    (shape, flange, ends)
}

fn detection(c: &mut Criterion) {
    let (_, flange, ends) = b1();
    let n = ends.len();
    let mut k = 0;
    c.bench_function("semi-analytical composite (6 pairings)", |b| {
        b.iter(|| {
            k = (k + 1) % n;
            semi_analytical::detect(black_box(&ends[k]), &flange)
        })
    });
    c.bench_function("semi-analytical composite, pruned", |b| {
        b.iter(|| {
            k = (k + 1) % n;
            pruning::detect(black_box(&ends[k]), &flange)
        })
    });
    c.bench_function(
        "semi-analytical composite only (torus-torus when needed)",
        |b| {
            b.iter(|| {
                k = (k + 1) % n;
                semi_analytical::composite(black_box(&ends[k]), &flange)
            })
        },
    );
    // The flange's bounds are intrinsic, so the dynamic model computes them once per flange.
    let bounds = pruning::FlangeBounds::new(&flange);
    c.bench_function("semi-analytical composite, pruned (overlap only)", |b| {
        b.iter(|| {
            k = (k + 1) % n;
            pruning::composite_within_bounds(black_box(&ends[k]), &flange, &bounds, 0.0)
        })
    });
    c.bench_function("semi-analytical composite, pruned, within 20 um", |b| {
        b.iter(|| {
            k = (k + 1) % n;
            pruning::composite_within_bounds(black_box(&ends[k]), &flange, &bounds, 20e-6)
        })
    });
    c.bench_function("flange bounds (once per flange)", |b| {
        b.iter(|| pruning::FlangeBounds::new(black_box(&flange)))
    });
    let mut previous = [None; 6];
    c.bench_function("gradient composite (6 pairings), warm-started", |b| {
        b.iter(|| {
            k = (k + 1) % n;
            let o = gradient::detect(black_box(&ends[k]), &flange, &previous);
            previous = std::array::from_fn(|i| Some(o[i].unknowns));
            o
        })
    });
    let end = &ends[n / 2];
    c.bench_function("torus-cone", |b| {
        b.iter(|| semi_analytical::torus_cone(black_box(&end.torus), &flange.cone))
    });
    c.bench_function("torus-torus (rim)", |b| {
        b.iter(|| {
            semi_analytical::torus_torus(black_box(&end.torus), &flange.rim, Pairing::TorusRim)
        })
    });
    c.bench_function("torus-torus (root)", |b| {
        b.iter(|| {
            semi_analytical::torus_torus(black_box(&end.torus), &flange.root, Pairing::TorusRoot)
        })
    });
    c.bench_function("sphere-cone", |b| {
        b.iter(|| semi_analytical::sphere_cone(black_box(&end.sphere), &flange.cone))
    });
    c.bench_function("sphere-torus (root)", |b| {
        b.iter(|| {
            semi_analytical::sphere_torus(black_box(&end.sphere), &flange.root, Pairing::SphereRoot)
        })
    });
    // Per pairing along the whole trajectory (the single poses above are one point of it).
    c.bench_function("torus-cone, trajectory", |b| {
        b.iter(|| {
            k = (k + 1) % n;
            semi_analytical::torus_cone(black_box(&ends[k].torus), &flange.cone)
        })
    });
    c.bench_function("torus-torus (root + rim), trajectory", |b| {
        b.iter(|| {
            k = (k + 1) % n;
            let t = black_box(&ends[k].torus);
            (
                semi_analytical::torus_torus(t, &flange.root, Pairing::TorusRoot),
                semi_analytical::torus_torus(t, &flange.rim, Pairing::TorusRim),
            )
        })
    });
    c.bench_function("Eberly circle-circle (root + rim), trajectory", |b| {
        b.iter(|| {
            k = (k + 1) % n;
            let t = black_box(&ends[k].torus);
            let edge = Circle3 {
                center: t.origin,
                normal: t.axis,
                radius: t.major_radius,
            };
            [flange.root, flange.rim].map(|f| {
                circle_circle_distance(
                    &edge,
                    &Circle3 {
                        center: f.origin,
                        normal: f.axis,
                        radius: f.major_radius,
                    },
                )
            })
        })
    });
}

/// The distributed end–flange law's overlap integral (`contact::distributed::integrate`)
/// with B1's roughness, at each pose of the trajectory whose detected contact lies within
/// the asperities' reach, from the detected deepest point as in a run.
fn distributed_overlap(c: &mut Criterion) {
    let (_, flange, ends) = b1();
    let asperities = Asperities { sigma: 0.24e-6 };
    let pressed: Vec<(RollerEnd, Vec3)> = ends
        .iter()
        .filter_map(|end| {
            let contact = deepest(&semi_analytical::detect(end, &flange))?;
            (contact.penetration > -asperities.reach()).then_some((*end, contact.p1))
        })
        .collect();
    assert!(
        !pressed.is_empty(),
        "no pose of the trajectory presses the flange"
    );
    let n = pressed.len();
    let mut k = 0;
    c.bench_function("distributed overlap (B1 roughness)", |b| {
        b.iter(|| {
            k = (k + 1) % n;
            let (end, p1) = black_box(&pressed[k]);
            distributed::integrate(end, &flange, p1, asperities, false)
        })
    });
    // As a run integrates it: from the support frame the pose before left
    // (`distributed::integrate_near`), carried along the trajectory.
    let mut frame = None;
    let frames: Vec<_> = pressed
        .iter()
        .map(|(end, p1)| {
            let before = frame;
            frame =
                distributed::integrate_near(end, &flange, p1, asperities, false, before.as_ref())
                    .map(|(_, next)| next);
            before
        })
        .collect();
    c.bench_function(
        "distributed overlap from the pose before's frame (B1 roughness)",
        |b| {
            b.iter(|| {
                k = (k + 1) % n;
                let (end, p1) = black_box(&pressed[k]);
                distributed::integrate_near(end, &flange, p1, asperities, false, frames[k].as_ref())
            })
        },
    );
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).measurement_time(std::time::Duration::from_secs(2));
    targets = detection, distributed_overlap
}
criterion_main!(benches);
