//! The detection benchmark (paper sect. 5.3, Wolf et al. 2020): time per roller end /
//! flange evaluation of each method on a realistic trajectory, with each method's
//! accuracy against the reference solver.
//!
//! The trajectory: one roller end passing once around the bearing against one flange,
//! in steps of Δψ of roller-set azimuth (default 1e-3 rad, the roller-set motion of a
//! 50 µs step at B1's 21 rad/s), with an axial position that pushes the end into the flange
//! in the load zone (around ψ = 0) and lets it go outside, and small periodic tilt and
//! skew. The gradient method is cold-started once and then warm-started from the previous
//! step, as in a real run (paper sect. 4).

use super::mesh::{MeshDetector, MeshResolution};
use super::{deepest, gradient, pruning, reference, semi_analytical, Contact};
use crate::geometry::end_flange::{Flange, RollerEnd};
use crate::geometry::primitives::Vec3;
use crate::geometry::roller::RollerShape;
use std::hint::black_box;
use std::time::Instant;

/// A roller's pose on the trajectory at step k: azimuth ψ, axial shift, tilt, skew.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Trajectory {
    /// Pitch radius [m].
    pub pitch_radius: f64,
    /// Azimuth step Δψ [rad].
    pub step: f64,
    /// Number of steps.
    pub steps: usize,
    /// Axial shift in the load zone (towards the flange) [m].
    pub push: f64,
    /// Amplitude of tilt and skew [rad].
    pub wobble: f64,
}

impl Trajectory {
    /// The end facing +x of a roller at step k.
    pub fn end(&self, shape: &RollerShape, k: usize) -> RollerEnd {
        let psi = -std::f64::consts::PI + self.step * k as f64;
        let radial = Vec3::new(0.0, psi.cos(), psi.sin());
        let circumferential = Vec3::x().cross(&radial);
        // Pushed towards +x in the load zone (cos ψ > 0), pulled back outside it.
        let dx = self.push * psi.cos();
        let (tilt, skew) = (self.wobble * (2.0 * psi).sin(), self.wobble * psi.cos());
        let axis = (Vec3::x() + radial * tilt + circumferential * skew).normalize();
        RollerEnd::new(shape, Vec3::x() * dx + radial * self.pitch_radius, axis)
    }
}

/// The benchmark's results.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactBenchmark {
    /// Evaluations per method (trajectory steps).
    pub evaluations: usize,
    /// Semi-analytical, all six pairings [ns per roller end / flange].
    pub semi_analytical_ns: f64,
    /// Semi-analytical with pruning [ns].
    pub pruned_ns: f64,
    /// Pruned composite, overlapping contacts only ([`pruning::composite_within_bounds`]:
    /// pruning and the torus–torus shortcut, the flange's bounds computed once as in the
    /// dynamic model) [ns].
    pub pruned_composite_ns: f64,
    /// Semi-analytical composite only ([`semi_analytical::composite`]: torus–torus solved
    /// only when no other pairing is valid) [ns].
    pub composite_ns: f64,
    /// Gradient method, warm-started, all six pairings [ns].
    pub gradient_ns: f64,
    /// Gradient method, warm-started, with the same pruning as the semi-analytical method
    /// (pairings and flanges whose boxes are apart are not solved; a skipped pairing keeps
    /// its warm start) [ns].
    pub gradient_pruned_ns: f64,
    /// Mean Newton iterations per pairing solve (warm-started).
    pub gradient_mean_iterations: f64,
    /// Pairing solves that did not converge.
    pub gradient_not_converged: usize,
    /// Pairing solves that converged to a wrong stationary point (outward normals not
    /// opposite, e.g. the far side of a sphere: paper fig. 2).
    pub gradient_wrong_stationary: usize,
    /// Composite results of the gradient method that differ from the semi-analytical one
    /// (wrong stationary point, or a pairing lost), out of `evaluations`.
    pub gradient_wrong_composite: usize,
    /// Pairings skipped by pruning, out of 6·evaluations.
    pub pruned_pairings: usize,
    /// Whole flanges skipped by pruning, out of `evaluations`.
    pub pruned_flanges: usize,
    /// Steps with an overlapping composite contact.
    pub steps_in_contact: usize,
    /// Largest |ΔP_m| of the semi-analytical composite against the reference [m], over
    /// the checked steps.
    pub semi_max_location_error: f64,
    /// Largest |Δδ| of the same [m].
    pub semi_max_penetration_error: f64,
    /// Steps checked against the reference.
    pub reference_checks: usize,
}

fn time_ns(evaluations: usize, mut f: impl FnMut(usize)) -> f64 {
    let start = Instant::now();
    for k in 0..evaluations {
        f(k);
    }
    start.elapsed().as_secs_f64() * 1e9 / evaluations as f64
}

/// Runs the benchmark on the trajectory against `flange`; every `reference_every`-th step
/// is checked against the reference solver (0: never).
pub fn run(
    shape: &RollerShape,
    flange: &Flange,
    trajectory: &Trajectory,
    reference_every: usize,
) -> ContactBenchmark {
    let n = trajectory.steps;
    let ends: Vec<RollerEnd> = (0..n).map(|k| trajectory.end(shape, k)).collect();
    let semi_analytical_ns = time_ns(n, |k| {
        black_box(semi_analytical::detect(black_box(&ends[k]), flange));
    });
    let pruned_ns = time_ns(n, |k| {
        black_box(pruning::detect(black_box(&ends[k]), flange));
    });
    let bounds = pruning::FlangeBounds::new(flange);
    let pruned_composite_ns = time_ns(n, |k| {
        black_box(pruning::composite_within_bounds(
            black_box(&ends[k]),
            flange,
            &bounds,
            0.0,
        ));
    });
    let composite_ns = time_ns(n, |k| {
        black_box(semi_analytical::composite(black_box(&ends[k]), flange));
    });
    let mut previous = [None; 6];
    let mut outcomes = Vec::with_capacity(n);
    let gradient_ns = time_ns(n, |k| {
        let o = gradient::detect(black_box(&ends[k]), flange, &previous);
        previous = std::array::from_fn(|i| Some(o[i].unknowns));
        outcomes.push(o);
    });
    let mut memory = [None; 6];
    let gradient_pruned_ns = time_ns(n, |k| {
        let end = black_box(&ends[k]);
        let boxes = pruning::end_boxes(end, flange);
        if boxes[0].union(&boxes[1]).apart(&bounds.whole, 0.0) {
            return;
        }
        for (p, slot) in memory.iter_mut().enumerate() {
            if !boxes[p / 3].apart(&bounds.figures[p % 3], 0.0) {
                let o = gradient::detect_pairing(end, flange, p, *slot);
                *slot = Some(black_box(o).unknowns);
            }
        }
    });
    let mut result = ContactBenchmark {
        evaluations: n,
        semi_analytical_ns,
        pruned_ns,
        composite_ns,
        pruned_composite_ns,
        gradient_ns,
        gradient_pruned_ns,
        gradient_mean_iterations: 0.0,
        gradient_not_converged: 0,
        gradient_wrong_stationary: 0,
        gradient_wrong_composite: 0,
        pruned_pairings: 0,
        pruned_flanges: 0,
        steps_in_contact: 0,
        semi_max_location_error: 0.0,
        semi_max_penetration_error: 0.0,
        reference_checks: 0,
    };
    let mut iterations = 0;
    for (k, end) in ends.iter().enumerate() {
        let semi = semi_analytical::detect(end, flange);
        let best = deepest(&semi);
        let outcome = &outcomes[k];
        iterations += outcome.iter().map(|o| o.iterations).sum::<usize>();
        result.gradient_not_converged += outcome.iter().filter(|o| !o.converged).count();
        result.gradient_wrong_stationary += outcome
            .iter()
            .filter(|o| o.converged && !o.opposite_normals)
            .count();
        let koch: Vec<Contact> = outcome.iter().map(|o| o.contact).collect();
        if !same_composite(best, deepest(&koch)) {
            result.gradient_wrong_composite += 1;
        }
        let (pruned, whole) = pruning::detect(end, flange);
        result.pruned_pairings += pruned.iter().filter(|p| p.is_none()).count();
        result.pruned_flanges += usize::from(whole);
        if best.is_some_and(|c| c.penetration > 0.0) {
            result.steps_in_contact += 1;
        }
        if reference_every > 0 && k % reference_every == 0 {
            let slow = deepest(&reference::detect(end, flange));
            if let (Some(a), Some(b)) = (best, slow) {
                result.reference_checks += 1;
                result.semi_max_location_error = result
                    .semi_max_location_error
                    .max((a.location() - b.location()).norm());
                result.semi_max_penetration_error = result
                    .semi_max_penetration_error
                    .max((a.penetration - b.penetration).abs());
            }
        }
    }
    result.gradient_mean_iterations = iterations as f64 / (6 * n) as f64;
    result
}

fn same_composite(a: Option<Contact>, b: Option<Contact>) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => {
            a.pairing == b.pairing
                && (a.penetration - b.penetration).abs() < 1e-10
                && ((a.location() - b.location()).norm() < 1e-9 || a.multiple)
        }
        _ => false,
    }
}

/// The mesh baseline at one resolution: time per roller end / flange evaluation
/// (meshing included, as the flange window follows the roller) and the largest error of
/// its composite penetration against the semi-analytical one over the sampled steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshPoint {
    /// Segments around and along.
    pub resolution: MeshResolution,
    /// Mean time per evaluation, meshing included [ns].
    pub ns: f64,
    /// Largest |δ_mesh − δ_exact| of the composite over the samples [m].
    pub max_penetration_error: f64,
    /// Sampled steps that had a composite contact in both.
    pub samples: usize,
}

/// The mesh baseline on every `every`-th step of the trajectory, at each resolution.
pub fn mesh_study(
    shape: &RollerShape,
    flange: &Flange,
    trajectory: &Trajectory,
    every: usize,
    resolutions: &[MeshResolution],
) -> Vec<MeshPoint> {
    let ends: Vec<RollerEnd> = (0..trajectory.steps)
        .step_by(every.max(1))
        .map(|k| trajectory.end(shape, k))
        .collect();
    resolutions
        .iter()
        .map(|&resolution| {
            let mut errors = Vec::new();
            let ns = time_ns(ends.len(), |k| {
                let mesh = deepest(&MeshDetector::new(&ends[k], flange, resolution).detect());
                if let (Some(m), Some(e)) =
                    (mesh, deepest(&semi_analytical::detect(&ends[k], flange)))
                {
                    errors.push((m.penetration - e.penetration).abs());
                }
            });
            MeshPoint {
                resolution,
                ns,
                max_penetration_error: errors.iter().cloned().fold(0.0, f64::max),
                samples: errors.len(),
            }
        })
        .collect()
}
