//! Bindings of roller end–flange contact detection (core `contact`, paper sect. 2): the
//! detection benchmark on a roller's trajectory and Eberly's circle–circle distance.

use crate::convert::{core_err, count, set_fields, MAX_REPETITIONS};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rollerdyn_core::contact::benchmark::{mesh_study, run, Trajectory};
use rollerdyn_core::contact::mesh::MeshResolution;
use rollerdyn_core::geometry::circle::{self as circle, Circle3, ClosestPairs};
use rollerdyn_core::geometry::end_flange::{Flange, FlangePlacement, FlangeShape};
use rollerdyn_core::geometry::primitives::Vec3;
use rollerdyn_core::geometry::roller::RollerShape;

/// Most trajectory steps of the benchmark: it keeps 144 bytes of results per step (a
/// billion, which the repetition bound let through, asked for 144 GB and aborted).
const MAX_TRAJECTORY_STEPS: usize = 1_000_000;

/// Most segments of a mesh along either direction: (4096, 4096) already meshes each figure
/// with 16.8 million vertices (the benchmark's finest is (128, 32)).
const MAX_MESH_SEGMENTS: usize = 4096;

/// Roller end / flange detection benchmark on a roller's trajectory against one inner-ring
/// flange (see core `contact::benchmark`). Lengths in m, angles in rad.
#[pyfunction]
#[pyo3(signature = (*, roller_diameter, roller_length, edge_radius, end_face_radius, opening_angle, flange_height, root_radius, rim_radius, raceway_radius, pitch_radius, axial_play, steps=6283, step=1e-3, push=22e-6, wobble=1e-3, reference_every=100, mesh_every=0, mesh_resolutions=Vec::new()))]
#[allow(clippy::too_many_arguments)]
fn contact_benchmark<'py>(
    py: Python<'py>,
    roller_diameter: f64,
    roller_length: f64,
    edge_radius: f64,
    end_face_radius: f64,
    opening_angle: f64,
    flange_height: f64,
    root_radius: f64,
    rim_radius: f64,
    raceway_radius: f64,
    pitch_radius: f64,
    axial_play: f64,
    steps: i64,
    step: f64,
    push: f64,
    wobble: f64,
    reference_every: i64,
    mesh_every: i64,
    mesh_resolutions: Vec<(i64, i64)>,
) -> PyResult<Bound<'py, PyDict>> {
    let steps = count("steps", steps, 1..=MAX_TRAJECTORY_STEPS)?;
    let reference_every = count("reference_every", reference_every, 0..=MAX_REPETITIONS)?;
    let mesh_every = count("mesh_every", mesh_every, 0..=MAX_REPETITIONS)?;
    let shape = RollerShape::new(
        0.5 * roller_diameter,
        roller_length,
        edge_radius,
        end_face_radius,
    )
    .map_err(core_err)?;
    let flange_shape = FlangeShape::new(opening_angle, flange_height, root_radius, rim_radius)
        .map_err(core_err)?;
    let flange = Flange::new(
        &flange_shape,
        &FlangePlacement {
            origin: Vec3::zeros(),
            axis: Vec3::x(),
            raceway_radius,
            rises: 1.0,
            face_position: 0.5 * roller_length + axial_play,
            facing: -1.0,
        },
    );
    let trajectory = Trajectory {
        pitch_radius,
        step,
        steps,
        push,
        wobble,
    };
    let r = py.detach(|| run(&shape, &flange, &trajectory, reference_every));
    let d = PyDict::new(py);
    set_fields!(
        d,
        r;
        evaluations,
        semi_analytical_ns,
        pruned_ns,
        composite_ns,
        pruned_composite_ns,
        gradient_ns,
        gradient_pruned_ns,
        gradient_mean_iterations,
        gradient_not_converged,
        gradient_wrong_stationary,
        gradient_wrong_composite,
        pruned_pairings,
        pruned_flanges,
        steps_in_contact,
        semi_max_location_error,
        semi_max_penetration_error,
        reference_checks,
    );
    let resolutions = mesh_resolutions
        .iter()
        .enumerate()
        .map(|(k, &(around, along))| {
            let name = |part: &str| format!("mesh_resolutions[{k}].{part}");
            Ok(MeshResolution {
                around: count(&name("around"), around, 3..=MAX_MESH_SEGMENTS)?,
                along: count(&name("along"), along, 1..=MAX_MESH_SEGMENTS)?,
            })
        })
        .collect::<PyResult<Vec<_>>>()?;
    if mesh_every > 0 && !resolutions.is_empty() {
        let points =
            py.detach(|| mesh_study(&shape, &flange, &trajectory, mesh_every, &resolutions));
        let rows: Vec<(usize, usize, f64, f64, usize)> = points
            .iter()
            .map(|p| {
                (
                    p.resolution.around,
                    p.resolution.along,
                    p.ns,
                    p.max_penetration_error,
                    p.samples,
                )
            })
            .collect();
        d.set_item("mesh", rows)?;
    }
    Ok(d)
}

/// Closest points of two circles in 3D (Eberly's method, core `geometry::circle`):
/// returns (squared distance, kind: "unique" | "several" | "infinite", point on circle 1,
/// point on circle 2).
#[pyfunction]
#[allow(clippy::type_complexity)]
fn circle_circle_distance(
    center1: [f64; 3],
    normal1: [f64; 3],
    radius1: f64,
    center2: [f64; 3],
    normal2: [f64; 3],
    radius2: f64,
) -> PyResult<(f64, &'static str, [f64; 3], [f64; 3])> {
    let all = center1
        .iter()
        .chain(&normal1)
        .chain(&center2)
        .chain(&normal2)
        .chain([&radius1, &radius2]);
    if all.clone().any(|v| !v.is_finite()) || radius1 <= 0.0 || radius2 <= 0.0 {
        return Err(PyValueError::new_err(
            "circle centres and normals must be finite and radii finite and positive",
        ));
    }
    for (name, n) in [("normal1", normal1), ("normal2", normal2)] {
        if Vec3::from(n).norm() < 1e-12 {
            return Err(PyValueError::new_err(format!(
                "{name} = {n:?}: must be a direction (a vector of length above 1e-12)"
            )));
        }
    }
    let c1 = Circle3 {
        center: Vec3::from(center1),
        normal: Vec3::from(normal1),
        radius: radius1,
    };
    let c2 = Circle3 {
        center: Vec3::from(center2),
        normal: Vec3::from(normal2),
        radius: radius2,
    };
    let d = circle::circle_circle_distance(&c1, &c2);
    let kind = match d.pairs {
        ClosestPairs::Unique(..) => "unique",
        ClosestPairs::Several(..) => "several",
        ClosestPairs::Infinite(..) => "infinite",
    };
    let (p1, p2) = d.pairs.first();
    Ok((
        d.squared_distance,
        kind,
        [p1.x, p1.y, p1.z],
        [p2.x, p2.y, p2.z],
    ))
}

/// Adds this module's functions to `m`.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(contact_benchmark, m)?)?;
    m.add_function(wrap_pyfunction!(circle_circle_distance, m)?)?;
    Ok(())
}
