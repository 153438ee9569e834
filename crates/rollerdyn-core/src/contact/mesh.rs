//! The mesh baseline: the approach of general multibody tools (paper sect. 2). The same
//! patches the other detectors use are tessellated into triangle meshes, and penetration
//! and contact points come from a general collision library (parry3d-f64).
//!
//! **Meshes.** Every patch becomes an oriented [`TriMesh`] (outward normals, so that
//! parry's pseudo-normals say inside from outside) on a grid of `around` × `along`
//! segments: the roller's edge torus over 2π × its tube-angle arc, its end sphere as
//! `along` rings of `around` points about the pole, and each flange figure over an azimuth
//! window × its meridian range (tube-angle arc, or generator length for the cone, which
//! the cone's mesh follows exactly). All vertices lie on the true surfaces.
//!
//! **Detection (node to surface).** For a pairing, every vertex of the roller figure's
//! mesh is projected onto the flange figure's mesh, and every vertex of the flange figure's
//! mesh onto the roller figure's (parry's exact point–trimesh projection, with the
//! prediction distance as the search radius). The signed distance of the vertex from the
//! other surface (negative inside, by the pseudo-normal of the closest feature) gives a
//! candidate penetration −d with the vertex and its projection as P₁ and P₂; the deepest
//! candidate is the pairing's contact. A projection on the border of the other mesh does
//! not count: the vertex lies beyond that patch (this is the mesh's version of the patch
//! rule; borders shared by two tangent patches are covered by the neighbouring patch).
//! The normal (from the flange towards the roller) is the direction between the two
//! points, or the triangle's normal where they coincide. The mesh gives no curvature:
//! R_x = R_y = NaN and the major axis is set to the normal.
//!
//! The sampled penetration converges quadratically in the segment size: the deepest
//! point lies between vertices (roller chord sag R·(Δβ)²/8 around the axis, r·(Δφ)²/8
//! along the tube, 0.13 µm + 0.04 µm for B1 at (256, 64)), and the secant mesh it is
//! projected on deviates from the surface by the same order.
//!
//! **Why not GJK/EPA on convex pieces.** The first version built convex hulls (roller
//! figures whole, flange figures as compounds of one hull per azimuth segment) and used
//! `parry3d_f64::query::contact` with a prediction distance. On these shapes (thousands of
//! vertices on nearly flat or nearly coplanar rings: B1's end face is a lens 0.3 µm thick
//! over 3.5 mm) GJK and EPA often did not converge (on many segments their own lower and
//! upper bounds disagreed by tens of µm) and sometimes failed outright (126.8 µm with a
//! wrong normal for a 47.9 µm overlap at (256, 64)); the point projections used here are
//! exact per triangle.
//!
//! **Flange window.** Only an azimuth window of the flange is tessellated, β_c ± α with
//! sin α = (r_b + d_p)/ρ_min: β_c the azimuth (about the flange axis) of the edge torus'
//! centre c, r_b the radius of a sphere about c that holds the roller end, d_p the
//! prediction distance [`PREDICTION`] and ρ_min the flange's smallest radius; the whole
//! ring if that sine reaches 1. Every flange point within d_p of the roller end lies within
//! r_b + d_p of c, so in the plane normal to the axis its azimuth differs from β_c by at
//! most α. For B1 the window is about 0.67 rad wide (38°, against the roller end's own 21°
//! as seen from the axis). `around` is the number of segments over the window, not over
//! 2π. The window does not depend on the resolution, so that doubling `around` and
//! `along` keeps every vertex (nested meshes).
//!
//! **Poses.** The meshes are kept in frames translated to one of their vertices, so that
//! coordinates stay small; but the detector is built for one pose of the roller end
//! against the flange (the window depends on it), i.e. [`MeshDetector::new`] runs per
//! pose. A multibody code would keep the meshes in body frames and only pass the bodies'
//! poses to the queries each step (with a flange window wide enough for the roller's
//! travel, or the whole ring).

use super::{Contact, Pairing};
use crate::geometry::end_flange::{Flange, RollerEnd};
use crate::geometry::primitives::{any_perpendicular, ConePatch, SpherePatch, TorusPatch, Vec3};
use parry3d_f64::math::Vector;
use parry3d_f64::query::PointQueryWithLocation;
use parry3d_f64::shape::{TriMesh, TriMeshFlags, TrianglePointLocation};
use std::collections::{HashMap, HashSet};
use std::f64::consts::TAU;

/// Prediction distance [m]: the search radius of the projections. A pairing with no
/// vertex within this distance of the other patch is reported invalid (no contact found);
/// within it, the gap is reported.
pub const PREDICTION: f64 = 1e-3;

/// Tessellation resolution: segments around the axis over the patch's azimuth span, and along the meridian.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshResolution {
    /// Segments around the axis (over 2π for the roller, over the window for the flange);
    /// at least 3 are used.
    pub around: usize,
    /// Segments along the meridian (tube arc of a torus, polar angle of the sphere cap,
    /// generator of the cone); at least 1 is used.
    pub along: usize,
}

/// Triangle meshes of one roller end's figures and one flange's figures.
pub struct MeshDetector {
    /// Edge torus, end sphere.
    roller: [Option<PatchMesh>; 2],
    /// Face cone, root torus, rim torus.
    flange: [Option<PatchMesh>; 3],
    /// Azimuth window of the flange meshes about the flange axis [rad], (start, end).
    window: (f64, f64),
}

/// One patch's oriented triangle mesh, in a frame translated to `origin`.
struct PatchMesh {
    origin: Vec3,
    mesh: TriMesh,
    /// Vertices in the ring frame.
    vertices: Vec<Vec3>,
    /// Vertices on the mesh's border.
    border_vertex: Vec<bool>,
    /// Edges (sorted vertex pairs) on the mesh's border: those of one triangle only.
    border_edges: HashSet<(u32, u32)>,
    /// Bounding box in the ring frame, widened by the prediction distance.
    reach: (Vec3, Vec3),
}

/// The closest point of a patch mesh to a point.
struct Projection {
    /// Signed distance of the point from the mesh, negative inside [m].
    distance: f64,
    /// The closest point on the mesh (ring frame).
    point: Vec3,
    /// Outward unit normal of the mesh there (towards the point if it is outside).
    normal: Vec3,
}

impl PatchMesh {
    /// Mesh of `points` (ring frame) with the given triangles, each turned so that its
    /// normal agrees with `outward` at its centroid.
    fn new(
        points: Vec<Vec3>,
        mut triangles: Vec<[u32; 3]>,
        outward: impl Fn(&Vec3) -> Vec3,
    ) -> Option<Self> {
        let origin = *points.first()?;
        for t in &mut triangles {
            let [a, b, c] = t.map(|i| points[i as usize]);
            if (b - a).cross(&(c - a)).dot(&outward(&((a + b + c) / 3.0))) < 0.0 {
                t.swap(1, 2);
            }
        }
        let mut edges = HashMap::<(u32, u32), u32>::new();
        for t in &triangles {
            for (i, j) in [(t[0], t[1]), (t[1], t[2]), (t[0], t[2])] {
                *edges.entry((i.min(j), i.max(j))).or_default() += 1;
            }
        }
        let mut border_vertex = vec![false; points.len()];
        let border_edges: HashSet<(u32, u32)> = edges
            .into_iter()
            .filter(|&(_, n)| n == 1)
            .map(|(e, _)| e)
            .collect();
        for &(a, b) in &border_edges {
            border_vertex[a as usize] = true;
            border_vertex[b as usize] = true;
        }
        let local: Vec<Vector> = points.iter().map(|p| to_parry(&(p - origin))).collect();
        let mesh = TriMesh::with_flags(local, triangles, TriMeshFlags::ORIENTED).ok()?;
        let aabb = mesh.local_aabb();
        let slack = Vec3::repeat(PREDICTION);
        let reach = (
            to_vec3(aabb.mins) + origin - slack,
            to_vec3(aabb.maxs) + origin + slack,
        );
        Some(Self {
            origin,
            mesh,
            vertices: points,
            border_vertex,
            border_edges,
            reach,
        })
    }

    /// The closest point of the mesh to p, if within the prediction distance and not on
    /// the mesh's border.
    fn project(&self, p: &Vec3) -> Option<Projection> {
        let (lo, hi) = &self.reach;
        if (0..3).any(|k| p[k] < lo[k] || p[k] > hi[k]) {
            return None;
        }
        let (proj, (tri, location)) = self
            .mesh
            .project_local_point_and_get_location_with_max_dist(
                to_parry(&(p - self.origin)),
                false,
                PREDICTION,
            )?;
        let idx = self.mesh.indices()[tri as usize];
        let on_border = match location {
            TrianglePointLocation::OnVertex(i) => self.border_vertex[idx[i as usize] as usize],
            TrianglePointLocation::OnEdge(i, _) => {
                let (a, b) = match i {
                    0 => (idx[0], idx[1]),
                    1 => (idx[1], idx[2]),
                    _ => (idx[0], idx[2]),
                };
                self.border_edges.contains(&(a.min(b), a.max(b)))
            }
            TrianglePointLocation::OnFace(..) | TrianglePointLocation::OnSolid => false,
        };
        if on_border {
            return None;
        }
        let point = to_vec3(proj.point) + self.origin;
        let sign = if proj.is_inside { -1.0 } else { 1.0 };
        let d = p - point;
        let length = d.norm();
        let normal = if length > 1e-15 {
            d * (sign / length)
        } else {
            to_vec3(self.mesh.triangle(tri).normal()?)
        };
        Some(Projection {
            distance: sign * length,
            point,
            normal,
        })
    }
}

/// An axis with a fixed reference direction for azimuths.
struct Ring {
    origin: Vec3,
    u: Vec3,
    v: Vec3,
}

impl Ring {
    fn new(origin: Vec3, axis: Vec3) -> Self {
        let u = any_perpendicular(&axis);
        let v = axis.cross(&u);
        Self { origin, u, v }
    }

    /// Unit radial direction at azimuth β.
    fn radial(&self, beta: f64) -> Vec3 {
        let (s, c) = beta.sin_cos();
        self.u * c + self.v * s
    }

    /// Azimuth of p.
    fn azimuth(&self, p: &Vec3) -> f64 {
        let d = p - self.origin;
        d.dot(&self.v).atan2(d.dot(&self.u))
    }
}

fn to_parry(p: &Vec3) -> Vector {
    Vector::new(p.x, p.y, p.z)
}

fn to_vec3(p: Vector) -> Vec3 {
    Vec3::new(p.x, p.y, p.z)
}

/// lo + (hi − lo)·k/n, k = 0..=n.
fn steps(lo: f64, hi: f64, n: usize) -> impl Iterator<Item = f64> + Clone {
    (0..=n).map(move |k| lo + (hi - lo) * k as f64 / n as f64)
}

/// Triangles of a grid of `columns` meridians (azimuths) of `rows` points each, vertex
/// index column·rows + row; `closed` joins the last column to the first.
fn grid(columns: usize, rows: usize, closed: bool) -> Vec<[u32; 3]> {
    let spans = if closed { columns } else { columns - 1 };
    let at = |c: usize, r: usize| ((c % columns) * rows + r) as u32;
    (0..spans)
        .flat_map(|c| {
            (0..rows - 1).flat_map(move |r| {
                [
                    [at(c, r), at(c + 1, r), at(c + 1, r + 1)],
                    [at(c, r), at(c + 1, r + 1), at(c, r + 1)],
                ]
            })
        })
        .collect()
}

/// Mesh of a torus patch over the azimuths `betas` about its axis (`closed`: the whole
/// ring, the last azimuth joined to the first).
fn torus_mesh(t: &TorusPatch, betas: &[f64], closed: bool, along: usize) -> Option<PatchMesh> {
    let ring = Ring::new(t.origin, t.axis);
    let phis = steps(t.phi_mid - t.phi_half, t.phi_mid + t.phi_half, along);
    let points = betas
        .iter()
        .flat_map(|&beta| {
            let e = ring.radial(beta);
            phis.clone().map(move |phi| {
                let (s, c) = phi.sin_cos();
                t.origin + e * t.major_radius + (t.axis * s + e * c) * t.minor_radius
            })
        })
        .collect();
    PatchMesh::new(points, grid(betas.len(), along + 1, closed), |p| {
        t.foot(p).normal
    })
}

/// Mesh of the end sphere's cap: the pole and `along` rings of `around` points.
fn sphere_mesh(s: &SpherePatch, res: MeshResolution) -> Option<PatchMesh> {
    let ring = Ring::new(s.center, s.pole);
    let mut points = vec![s.center + s.pole * s.radius];
    for i in 0..res.around {
        let e = ring.radial(TAU * i as f64 / res.around as f64);
        for alpha in steps(0.0, s.cap_angle, res.along).skip(1) {
            let (sa, ca) = alpha.sin_cos();
            points.push(s.center + (s.pole * ca + e * sa) * s.radius);
        }
    }
    // Rings about the pole (vertex 0): the grid of the rings, shifted by one, and a fan.
    let mut triangles: Vec<[u32; 3]> = grid(res.around, res.along, true)
        .into_iter()
        .map(|t| t.map(|i| i + 1))
        .collect();
    triangles.extend((0..res.around).map(|i| {
        let next = (i + 1) % res.around;
        [0, (i * res.along + 1) as u32, (next * res.along + 1) as u32]
    }));
    PatchMesh::new(points, triangles, |p| (p - s.center).normalize())
}

/// Mesh of the flange face over the azimuths `betas` (`closed`: the whole ring).
fn cone_mesh(c: &ConePatch, betas: &[f64], closed: bool, along: usize) -> Option<PatchMesh> {
    let ring = Ring::new(c.origin, c.axis);
    let points = betas
        .iter()
        .flat_map(|&beta| {
            let e = ring.radial(beta);
            steps(c.g_min, c.g_max, along)
                .map(move |g| c.origin + c.axis * (c.s0 + g * c.ds) + e * (c.rho0 + g * c.drho))
        })
        .collect();
    PatchMesh::new(points, grid(betas.len(), along + 1, closed), |p| {
        c.foot(p).normal
    })
}

impl MeshDetector {
    /// Builds the meshes (in the frame of the given RollerEnd and Flange).
    pub fn new(end: &RollerEnd, flange: &Flange, resolution: MeshResolution) -> Self {
        let res = MeshResolution {
            around: resolution.around.max(3),
            along: resolution.along.max(1),
        };
        let full: Vec<f64> = (0..res.around)
            .map(|i| TAU * i as f64 / res.around as f64)
            .collect();
        let roller = [
            torus_mesh(&end.torus, &full, true, res.along),
            sphere_mesh(&end.sphere, res),
        ];
        // The flange figures share the flange axis, so one window serves all three.
        let ring = Ring::new(flange.cone.origin, flange.cone.axis);
        let (window, betas, closed) = match flange_window(&ring, flange, end) {
            Some((start, stop)) => (
                (start, stop),
                steps(start, stop, res.around).collect(),
                false,
            ),
            None => ((0.0, TAU), full.clone(), true),
        };
        let flange_meshes = [
            cone_mesh(&flange.cone, &betas, closed, res.along),
            torus_mesh(&flange.root, &betas, closed, res.along),
            torus_mesh(&flange.rim, &betas, closed, res.along),
        ];
        Self {
            roller,
            flange: flange_meshes,
            window,
        }
    }

    /// The flange's azimuth window [rad] about its axis, as (start, end), measured from the
    /// flange's reference direction (`any_perpendicular` of the axis); (0, 2π) when the
    /// whole ring is meshed.
    pub fn window(&self) -> (f64, f64) {
        self.window
    }

    /// Detection per pairing, same order as Pairing::ALL; rx, ry, major_axis may be NaN/unknown (the mesh gives no curvature): set rx = ry = f64::NAN and major_axis = normal.
    pub fn detect(&self) -> [Contact; 6] {
        std::array::from_fn(|k| {
            let pairing = Pairing::ALL[k];
            let (r, f) = pairing.figures();
            match (&self.roller[r], &self.flange[f]) {
                (Some(roller), Some(flange)) => pair(pairing, roller, flange),
                _ => not_found(pairing),
            }
        })
    }
}

/// The deepest vertex of either mesh relative to the other.
fn pair(pairing: Pairing, roller: &PatchMesh, flange: &PatchMesh) -> Contact {
    // (penetration, P₁, P₂, normal from the flange towards the roller)
    let mut best: Option<(f64, Vec3, Vec3, Vec3)> = None;
    let mut offer = |candidate: (f64, Vec3, Vec3, Vec3)| {
        if best.is_none_or(|b| candidate.0 > b.0) {
            best = Some(candidate);
        }
    };
    for v in &roller.vertices {
        if let Some(q) = flange.project(v) {
            offer((-q.distance, *v, q.point, q.normal));
        }
    }
    for w in &flange.vertices {
        if let Some(q) = roller.project(w) {
            offer((-q.distance, q.point, *w, -q.normal));
        }
    }
    match best {
        Some((penetration, p1, p2, normal)) => Contact {
            pairing,
            p1,
            p2,
            penetration,
            normal,
            rx: f64::NAN,
            ry: f64::NAN,
            major_axis: normal,
            valid: true,
            multiple: false,
        },
        None => not_found(pairing),
    }
}

/// No vertex within the prediction distance: an invalid contact (NaN points, δ = −∞).
fn not_found(pairing: Pairing) -> Contact {
    let nan = Vec3::repeat(f64::NAN);
    Contact {
        pairing,
        p1: nan,
        p2: nan,
        penetration: f64::NEG_INFINITY,
        normal: nan,
        rx: f64::NAN,
        ry: f64::NAN,
        major_axis: nan,
        valid: false,
        multiple: false,
    }
}

/// Azimuth window of the flange, (start, end), over the roller end (see the module
/// documentation), or None for the whole ring.
fn flange_window(ring: &Ring, flange: &Flange, end: &RollerEnd) -> Option<(f64, f64)> {
    let rho_min = [
        flange.cone.rho0 + flange.cone.g_min * flange.cone.drho,
        flange.cone.rho0 + flange.cone.g_max * flange.cone.drho,
        flange.root.major_radius - flange.root.minor_radius,
        flange.rim.major_radius - flange.rim.minor_radius,
    ]
    .into_iter()
    .fold(f64::INFINITY, f64::min);
    // Bounding sphere of the roller end about the edge torus' centre: the torus lies
    // within R + r of it; on the sphere cap, whose axis passes through that centre, the
    // distance is monotone in the polar angle, so largest at the pole or at the rim
    // (which is on the torus).
    let centre = end.torus.origin;
    let apex = end.sphere.center + end.sphere.pole * end.sphere.radius;
    let bound = (end.torus.major_radius + end.torus.minor_radius).max((apex - centre).norm());
    let beta = ring.azimuth(&centre);
    let sine = (bound + PREDICTION) / rho_min;
    // A flange reaching the ring axis (rho_min <= 0: degenerate, found by fuzzing,
    // docs/robustness.md) has no window: the whole ring.
    (rho_min > 0.0 && sine < 1.0).then(|| {
        let half = sine.asin();
        (beta - half, beta + half)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::tests::{b1_end, b1_flange};
    use crate::contact::{deepest, semi_analytical};
    use crate::geometry::end_flange::{FlangePlacement, FlangeShape};
    use std::time::Instant;

    const RESOLUTIONS: [MeshResolution; 4] = [
        MeshResolution {
            around: 32,
            along: 8,
        },
        MeshResolution {
            around: 64,
            along: 16,
        },
        MeshResolution {
            around: 128,
            along: 32,
        },
        MeshResolution {
            around: 256,
            along: 64,
        },
    ];

    /// B1 poses over the ranges of the property tests (gap to overlap, tilt and skew up to
    /// ±1°), from a fixed pseudo-random sequence.
    fn poses(n: usize) -> Vec<(bool, bool, [f64; 5])> {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        (0..n)
            .map(|k| {
                let (inner, plus_end) = (k % 2 == 0, k % 4 < 2);
                let psi = -3.2 + 6.4 * next();
                let dx = (-60.0 + 120.0 * next()) * 1e-6;
                let dr = (-20.0 + 40.0 * next()) * 1e-6;
                let tilt = (-1.0 + 2.0 * next()).to_radians();
                let skew = (-1.0 + 2.0 * next()).to_radians();
                (inner, plus_end, [psi, dx, dr, tilt, skew])
            })
            .collect()
    }

    #[test]
    fn composite_converges_to_the_semi_analytical_penetration() {
        let mut worst = [0.0f64; 4];
        let mut seconds = [0.0f64; 4];
        let mut build = [0.0f64; 4];
        let mut detections = 0;
        for (inner, plus_end, [psi, dx, dr, tilt, skew]) in poses(8) {
            let end = b1_end(plus_end, psi, dx, dr, tilt, skew);
            let flange = b1_flange(inner, plus_end);
            let exact = deepest(&semi_analytical::detect(&end, &flange))
                .expect("a valid semi-analytical pairing");
            let mut errors = [0.0; 4];
            for (k, res) in RESOLUTIONS.iter().enumerate() {
                let start = Instant::now();
                let mesh = MeshDetector::new(&end, &flange, *res);
                build[k] += start.elapsed().as_secs_f64();
                let start = Instant::now();
                let contacts = mesh.detect();
                seconds[k] += start.elapsed().as_secs_f64();
                let best = deepest(&contacts).expect("a mesh contact");
                errors[k] = (best.penetration - exact.penetration).abs();
                worst[k] = worst[k].max(errors[k]);
                // Sampled vertices find the deepest point from below; only the secant
                // mesh of a patch concave around the axis (outer-ring face, inner-ring
                // root) lies outside the solid, by a chord sag well below 1 µm.
                assert!(
                    best.penetration <= exact.penetration + 1e-6,
                    "{res:?}: mesh {} deeper than exact {}",
                    best.penetration,
                    exact.penetration
                );
            }
            detections += 1;
            println!(
                "inner {inner} plus {plus_end}: δ = {:+.3} µm ({}), errors [µm] {:?}",
                exact.penetration * 1e6,
                exact.pairing.label(),
                errors.map(|e| (e * 1e9).round() / 1e3)
            );
            assert!(errors[3] < errors[0], "{errors:?}");
        }
        for (k, res) in RESOLUTIONS.iter().enumerate() {
            println!(
                "({}, {}): max error {:.4} µm, {:.3} ms per new(), {:.3} ms per detect()",
                res.around,
                res.along,
                worst[k] * 1e6,
                build[k] / detections as f64 * 1e3,
                seconds[k] / detections as f64 * 1e3
            );
        }
        // For scale: the exact detector, on the first pose.
        let (inner, plus_end, [psi, dx, dr, tilt, skew]) = poses(1)[0];
        let (end, flange) = (
            b1_end(plus_end, psi, dx, dr, tilt, skew),
            b1_flange(inner, plus_end),
        );
        let start = Instant::now();
        for _ in 0..1000 {
            std::hint::black_box(semi_analytical::detect(std::hint::black_box(&end), &flange));
        }
        println!(
            "semi-analytical: {:.3} µs per detect()",
            start.elapsed().as_secs_f64() * 1e3
        );
        for k in 1..4 {
            assert!(worst[k] < worst[k - 1], "{worst:?}");
        }
        assert!(worst[3] < 1e-6, "{worst:?}");
    }

    #[test]
    fn contacts_follow_the_conventions() {
        // P₁ − P₂ = −δ·n with a unit normal from the flange towards the roller, no
        // curvature, on every valid pairing of a few poses.
        for (inner, plus_end, [psi, dx, dr, tilt, skew]) in poses(4) {
            let end = b1_end(plus_end, psi, dx, dr, tilt, skew);
            let flange = b1_flange(inner, plus_end);
            let mesh = MeshDetector::new(&end, &flange, RESOLUTIONS[1]);
            let contacts = mesh.detect();
            for (c, pairing) in contacts.iter().zip(Pairing::ALL) {
                assert_eq!(c.pairing, pairing);
                if !c.valid {
                    continue;
                }
                assert!((c.normal.norm() - 1.0).abs() < 1e-12);
                let residual = (c.p1 - c.p2) + c.normal * c.penetration;
                assert!(residual.norm() < 1e-12, "{pairing:?}: {residual:?}");
                assert!(c.rx.is_nan() && c.ry.is_nan());
                assert_eq!(c.major_axis, c.normal);
            }
        }
    }

    #[test]
    fn centred_roller_gap_at_the_bottom_of_the_edge() {
        // The exact answer: the edge torus faces the inner flange's face across the play
        // at the roller's bottom (contact::tests). The mesh finds the same gap within
        // 0.2 µm, the same normal, and a point within a segment of the exact one.
        let end = b1_end(true, 0.3, 0.0, 0.0, 0.0, 0.0);
        let flange = b1_flange(true, true);
        let exact = deepest(&semi_analytical::detect(&end, &flange)).unwrap();
        let mesh = MeshDetector::new(&end, &flange, RESOLUTIONS[3]);
        let contacts = mesh.detect();
        let best = deepest(&contacts).unwrap();
        assert!(best.penetration < 0.0);
        assert!(
            (best.penetration - exact.penetration).abs() < 0.2e-6,
            "{} vs {}",
            best.penetration,
            exact.penetration
        );
        assert!(best.normal.dot(&exact.normal) > 1.0 - 1e-6);
        // One segment around the edge circle: 2π·1.75 mm/256 ≈ 43 µm.
        let segment = TAU * end.torus.major_radius / 256.0;
        assert!((best.location() - exact.location()).norm() < segment);
        // The flange window covers the roller end with the margin: about 0.67 rad.
        let (start, stop) = mesh.window();
        assert!((stop - start - 0.67).abs() < 0.01, "{}", stop - start);
    }

    #[test]
    fn nothing_beyond_the_prediction_distance() {
        // Roller pulled 1.5 mm away from the flange: no pairing within 1 mm.
        let end = b1_end(true, 0.3, -1.5e-3, 0.0, 0.0, 0.0);
        let flange = b1_flange(true, true);
        let contacts = MeshDetector::new(&end, &flange, RESOLUTIONS[0]).detect();
        assert!(contacts.iter().all(|c| !c.valid));
        assert!(deepest(&contacts).is_none());
    }

    #[test]
    fn small_ring_is_meshed_whole() {
        // A flange on a 3 mm raceway is smaller than the roller end's reach (2.3 mm +
        // prediction): the window is the whole ring, closed, and the mesh still agrees.
        let shape = FlangeShape::new(0.11f64.to_radians(), 1.1e-3, 0.2e-3, 0.3e-3).unwrap();
        let flange = Flange::new(
            &shape,
            &FlangePlacement {
                origin: Vec3::zeros(),
                axis: Vec3::x(),
                raceway_radius: 3e-3,
                rises: 1.0,
                face_position: 2.5e-3 + 20e-6,
                facing: -1.0,
            },
        );
        let end = b1_end(true, 0.3, 30e-6, -7.0025e-3, 0.2f64.to_radians(), 0.0);
        let exact = deepest(&semi_analytical::detect(&end, &flange)).unwrap();
        let mesh = MeshDetector::new(&end, &flange, RESOLUTIONS[3]);
        assert_eq!(mesh.window(), (0.0, TAU));
        let best = deepest(&mesh.detect()).unwrap();
        assert!(
            (best.penetration - exact.penetration).abs() < 1e-6,
            "{} vs {}",
            best.penetration,
            exact.penetration
        );
    }
}
