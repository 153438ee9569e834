//! The model parameters the Python bindings build (`BearingParams`) and their validation
//! (`BearingParams::check`, run by `BearingModel::new`). Every field the check covers is
//! drawn (roller count and slices, shapes through their validated constructors, raceway
//! radii, plays, densities, ring mass and inertias, η₀, bands, damping, the load and speed
//! histories, a planet carrier's speed and offset) plus the detector, pruning, mesh
//! resolution, crowning, gravity, the flange law, the flanges present, the rolling
//! resistance's form and the race film's suction limit;
//! the tribology data are B1's (the Python config validates those). No panic anywhere; a
//! model that builds and finds a start state must give finite rates f(t, y) at the start
//! and at a perturbed state (rollers pushed into their contacts).
#![no_main]

use libfuzzer_sys::fuzz_target;
use rollerdyn_core::bearing::{
    BearingModel, BearingParams, Carrier, Detector, FlangeLaw, History, ModelOptions,
    RollingResistance, SurfacePair, Workspace,
};
use rollerdyn_core::contact::border::BorderBands;
use rollerdyn_core::dynamics::integrate::OdeSystem;
use rollerdyn_core::geometry::end_flange::FlangeShape;
use rollerdyn_core::geometry::roller::RollerShape;
use rollerdyn_core::tribology::friction::{BoundaryFriction, LoadSharing};
use rollerdyn_core::tribology::line_contact::LinePowerLaw;
use rollerdyn_core::tribology::lubricant::{Carreau, Roelands};
use rollerdyn_core::tribology::squeeze::SqueezeFilm;
use rollerdyn_core::tribology::traction::{EhlTraction, LimitingShearStress};
use rollerdyn_fuzz::Reader;

fn history(r: &mut Reader, scale: f64) -> History {
    if r.flag() {
        let start = r.range(0.0, 1.0);
        History::Ramp {
            value: r.range(-scale, scale),
            start,
            end: start + r.range(0.0, 1.0),
            cosine: r.flag(),
        }
    } else {
        let rows = 1 + (r.byte() % 5) as usize;
        let mut t = r.range(-0.5, 0.5);
        let mut table = Vec::with_capacity(rows);
        for _ in 0..rows {
            table.push((t, r.range(-scale, scale)));
            // Times strictly increasing, steps down to 1 ns.
            t += r.log_range(1e-9, 1.0);
        }
        History::Table(table)
    }
}

fn surface() -> SurfacePair {
    SurfacePair {
        roughness: 0.1e-6,
        sharing: LoadSharing { b: 1.5, c: 1.2 },
    }
}

/// A flange of height 0.1–0.9 roller radii, so that the inner and outer flanges fit in the
/// annulus between the raceways (`check` does not ask for it: docs/robustness.md, finding
/// 3), roundings 5–45 % of it.
fn flange(r: &mut Reader, roller_radius: f64) -> Option<FlangeShape> {
    let height = roller_radius * r.range(0.1, 0.9);
    FlangeShape::new(
        r.range(0.0, 0.2),
        height,
        height * r.range(0.05, 0.45),
        height * r.range(0.05, 0.45),
    )
    .ok()
}

fn params(r: &mut Reader) -> Option<BearingParams> {
    let radius = r.log_range(0.5e-3, 20e-3);
    // Shapes of real rollers (a first version drew edge radii down to 1e-13 m and end
    // spheres as small as the roller: docs/robustness.md, finding 3).
    let roller = RollerShape::new(
        radius,
        radius * r.log_range(1.0, 8.0),
        radius * r.range(0.02, 0.5),
        radius * r.log_range(2.0, 1e4),
    )
    .ok()?;
    let inner_raceway_radius = r.log_range(1e-3, 0.5);
    // A prescribed misalignment only with the tilt locked (else `check` refuses it).
    let inner_ring_tilt_free = r.flag();
    let inner_ring_misalignment = if inner_ring_tilt_free {
        0.0
    } else {
        r.range(-0.02, 0.02)
    };
    let outer_raceway_radius = inner_raceway_radius + 2.0 * radius * r.range(0.98, 1.05);
    let detector = match r.byte() % 3 {
        0 => Detector::SemiAnalytical,
        1 => Detector::Gradient,
        _ => Detector::Mesh,
    };
    let eta0 = r.log_range(1e-4, 10.0);
    Some(BearingParams {
        roller_count: (r.byte() % 64) as usize,
        roller,
        slices: (r.byte() % 40) as usize,
        crown_drop: r.range(0.0, 0.1) * radius,
        crown_length: r.range(0.0, 0.5) * roller.length,
        log_relief: if r.flag() {
            r.range(0.0, 0.02) * radius
        } else {
            0.0
        },
        roller_density: r.log_range(1e2, 2e4),
        inner_raceway_radius,
        outer_raceway_radius,
        inner_flange: flange(r, radius)?,
        outer_flange: flange(r, radius)?,
        flanges: std::array::from_fn(|_| r.flag()),
        inner_axial_play: r.range(0.0, 100e-6),
        outer_axial_play: r.range(0.0, 100e-6),
        e_prime: [2.3e11; 3],
        line_laws: [LinePowerLaw {
            k1: 8.6e-12,
            k2: 0.9,
        }; 3],
        inner_ring_mass: r.log_range(1e-3, 100.0),
        inner_ring_axial_inertia: r.log_range(1e-9, 1.0),
        inner_ring_transverse_inertia: r.log_range(1e-9, 1.0),
        inner_ring_tilt_free,
        inner_ring_misalignment,
        traction: EhlTraction::new(
            Roelands {
                eta_p: 0.0631e-3,
                p_p: -196e6,
                z: 0.62,
            },
            Carreau { tau0: 5e6, n: 0.5 },
            LimitingShearStress {
                chi: 0.0,
                p_star: 1.0,
                tau_l0: 3e7,
                smoothing: 20e6,
            },
            eta0,
            12,
        ),
        eta0,
        viscosity_slope: -1e-3 * eta0,
        alpha_star: 2e-8,
        thermal_conductivity: 0.134,
        raceway: surface(),
        flange_surface: surface(),
        roller_roller: surface(),
        boundary: BoundaryFriction {
            mu_b0: 0.1,
            s0: 0.1,
            smoothing_speed: 1e-3,
        },
        hysteresis_coefficient: 0.01,
        flange_law: if r.flag() {
            FlangeLaw::Point
        } else {
            FlangeLaw::Distributed
        },
        rolling_resistance: if r.flag() {
            RollingResistance::Paper
        } else {
            RollingResistance::Balanced
        },
        damping_ratio: r.range(0.0, 2.0),
        gravity: rollerdyn_core::geometry::primitives::Vec3::new(
            r.range(-100.0, 100.0),
            r.range(-100.0, 100.0),
            r.range(-100.0, 100.0),
        ),
        race_film: rollerdyn_core::tribology::hydrodynamic::RigidFilm {
            enabled: r.flag(),
            cutoff: r.log_range(1e-9, 1e-3),
            // The configuration's range (surfaces.race_film.suction_limit).
            suction_limit: r.range(0.0, 10e6),
        },
        mixture: rollerdyn_core::tribology::drag::Mixture::new(
            r.range(0.0, 1.0),
            860.0,
            0.0165,
            1.2,
            1.8e-5,
        ),
        radial_load: history(r, 1e4),
        axial_load: history(r, 1e3),
        inner_ring_speed: history(r, 1e3),
        outer_ring_speed: history(r, 1e3),
        // A planet carrier half the time; its offset across the axis, up to 1 m.
        carrier: if r.flag() {
            Carrier {
                speed: history(r, 1e3),
                offset: rollerdyn_core::geometry::primitives::Vec3::new(
                    0.0,
                    r.range(-1.0, 1.0),
                    r.range(-1.0, 1.0),
                ),
            }
        } else {
            Carrier::at_rest()
        },
        // The configuration's ranges (surfaces.squeeze_film).
        squeeze_film: SqueezeFilm {
            enabled: r.flag(),
            half_width: r.log_range(1e-6, 10e-3),
            floor: r.log_range(1e-9, 100e-6),
            cutoff: r.log_range(1e-9, 1e-3),
        },
        options: ModelOptions {
            detector,
            // Not the coarsest meshes: (3, 1) gave NaN rates at the start (finding 6).
            mesh_resolution: (8 + (r.byte() % 16) as usize, 2 + (r.byte() % 4) as usize),
            pruning: r.flag(),
            border_bands: BorderBands {
                roller_angle: r.range(0.0, 1e-3),
                flange_length: r.range(0.0, 1e-4),
            },
            friction: r.flag(),
        },
    })
}

fuzz_target!(|data: &[u8]| {
    let mut r = Reader::new(data);
    let Some(params) = params(&mut r) else {
        return;
    };
    let checked = params.check();
    let model = match BearingModel::new(params.clone()) {
        Ok(model) => model,
        Err(e) => {
            // The model refuses exactly what the check refuses.
            assert!(
                checked.is_err(),
                "check passed but the model refused: {e}\n{params:?}"
            );
            return;
        }
    };
    assert!(checked.is_ok(), "model built despite {checked:?}");
    let workspace = Workspace::single(&model);
    let model = model.system(&workspace);
    let Ok(y0) = model.initial_state() else {
        return;
    };
    assert!(
        y0.iter().all(|v| v.is_finite()),
        "start state {y0:?}\n{params:?}"
    );
    let t = r.range(-0.5, 3.0);
    let mut dy = vec![0.0; y0.len()];
    model.rhs(t, &y0, &mut dy);
    assert!(
        dy.iter().all(|v| v.is_finite()),
        "rates at the start, t = {t}: {dy:?}\n{params:?}"
    );
    // Push every state by up to its tolerance scale for 20 µm (velocities: 20 µm in 1 ms),
    // times roller radius over pitch radius so that a ring tilt moves the flanges by micrometres too (unscaled,
    // a 0.5 m ring tilted 2° overlapped 20 mm: finding 5): contacts close and overlap.
    let scale =
        model.absolute_tolerances(20e-6 * params.roller.radius / model.pitch_radius(), 1e-3);
    let y: Vec<f64> = y0
        .iter()
        .zip(&scale)
        .map(|(v, s)| v + s * r.range(-1.0, 1.0))
        .collect();
    model.rhs(t, &y, &mut dy);
    if !dy.iter().all(|v| v.is_finite()) {
        // Name the contacts whose forces are not finite, for the report.
        let kin = model.kinematics(t, &y);
        let results = model.evaluate_all(&kin);
        let bad: Vec<_> = model
            .elements()
            .iter()
            .zip(&results)
            .filter(|(_, e)| {
                let w = [e.on_a.force, e.on_a.moment, e.on_b.force, e.on_b.moment];
                !(w.iter().all(|v| v.iter().all(|x| x.is_finite())) && e.normal.is_finite())
            })
            .map(|(element, e)| format!("{element:?}: {e:?}"))
            .collect();
        panic!("rates at a perturbed state, t = {t}: {dy:?}\nnot finite: {bad:#?}\ny = {y:?}\n{params:?}");
    }
});
