//! The line contacts of the bearing, roller–inner race, roller–outer race and
//! roller–roller (paper sect. 3.1.1): the roller is cut into slices along its straight
//! length, each slice's penetration and contact location follow from the two bodies'
//! poses (eqs. 2, 3, the cylinders taken parallel), and each slice in contact carries the
//! paper's laws ([`line_slice`]: eq. 11, the EHL film and traction of sect. 3.2, the
//! rolling resistance of sect. 3.3).
//!
//! Beyond the paper, the oil film of the line contacts acts across their gaps
//! ([`film_slice`], [`crate::tribology::hydrodynamic`]), evaluated at 6 Gauss points along
//! the roller rather than at the slices. A contact whose bodies are too far apart for any
//! slice to touch or any film to act is recognised from a bound of its penetration
//! (`BearingSystem::penetration_bound`) without computing its slices.

use super::contacts::ElementResult;
use super::forces::{film_slice, line_slice, ContactForces, LineKind, Section};
use super::params::{BearingParams, SurfacePair};
use super::state::Kinematics;
use super::topology::LineContact;
use crate::bearing::workspace::BearingSystem;
use crate::geometry::primitives::Vec3;
use crate::geometry::roller::MassProperties;
use crate::numerics::quadrature::{mapped_table, GAUSS_LEGENDRE_6};

/// Points along the roller at which the oil film of a line contact is evaluated
/// (Gauss–Legendre). The film is smooth along the roller (its gap varies linearly with tilt
/// and skew): 6 points integrate it as closely as B1's 20 slices would, at a third of the
/// cost (test `six_gauss_points_integrate_the_film`).
const FILM_POINTS: [(f64, f64); 6] = GAUSS_LEGENDRE_6;

/// A place along the roller at which a line contact is evaluated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Station {
    /// Axial position from the roller's centre [m].
    pub(super) s: f64,
    /// The roller's radius there (crowning) [m].
    pub(super) radius: f64,
    /// The length it stands for [m]: the slice length, or a film point's quadrature weight.
    pub(super) length: f64,
}

/// The geometry of one section of a line contact (eqs. 2, 3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct SectionGeometry {
    /// Unit normal from body A towards body B.
    pub(super) normal: Vec3,
    /// Contact location P_m [m].
    pub(super) location: Vec3,
    /// Penetration δ [m] (negative: a gap).
    pub(super) penetration: f64,
}

/// The geometry of a line contact at one pose: per slice (none when no slice can touch)
/// and per film point (none without the film), in one allocation.
pub(super) struct LineGeometry {
    /// The slices' sections, then the film points'.
    sections: Vec<SectionGeometry>,
    /// How many of `sections` are slices.
    slice_count: usize,
}

impl LineGeometry {
    /// At the slice centres ([`LineContacts::slices`]).
    pub(super) fn slices(&self) -> &[SectionGeometry] {
        &self.sections[..self.slice_count]
    }

    /// At the film's quadrature points ([`LineContacts::film_points`]).
    pub(super) fn film(&self) -> &[SectionGeometry] {
        &self.sections[self.slice_count..]
    }
}

/// What the line contacts of a bearing share: the data of each kind and the stations
/// along the roller.
#[derive(Debug, Clone)]
pub(super) struct LineContacts {
    /// The elastic and surface data of each kind, by [`LineContact::index`].
    kinds: [LineKind; 3],
    /// Slice centres along the roller axis and their radii (crowning) [m].
    pub(super) slices: Vec<Station>,
    /// Where the oil film of a line contact is evaluated: 6-point Gauss–Legendre along the
    /// straight length [m].
    pub(super) film_points: Vec<Station>,
    /// The largest |s| of a slice centre or film point [m].
    reach: f64,
    /// The largest radius of a slice centre or film point [m].
    largest_radius: f64,
    /// The length of a slice [m].
    pub(super) slice_length: f64,
}

impl LineContacts {
    /// The line contacts of `params`' bearing, whose rollers have the mass properties
    /// `roller_mass`.
    pub(super) fn new(params: &BearingParams, roller_mass: &MassProperties) -> Self {
        let r = params.roller.radius;
        let straight = params.roller.straight_length();
        let slice_length = straight / params.slices as f64;
        let slices: Vec<Station> = (0..params.slices)
            .map(|j| {
                let s = -0.5 * straight + (j as f64 + 0.5) * slice_length;
                Station {
                    s,
                    radius: r - params.crown_drop(s, straight),
                    length: slice_length,
                }
            })
            .collect();
        let film_points: Vec<Station> = mapped_table(&FILM_POINTS, 0.5 * straight)
            .into_iter()
            .map(|(s, w)| Station {
                s,
                radius: r - params.crown_drop(s, straight),
                length: w,
            })
            .collect();
        let per_length = roller_mass.mass / straight;
        let kind = |line: LineContact, r_other: f64, surface: &SurfacePair| {
            let k = line.index();
            let pair = line == LineContact::RollerRoller;
            LineKind {
                law: params.line_laws[k],
                e_prime: params.e_prime[k],
                r_eff: 1.0 / (1.0 / r + 1.0 / r_other),
                roughness: surface.roughness,
                sharing: surface.sharing,
                counter_rotating: pair,
                rolling_resistance: !pair,
                mass_per_length: if pair { 0.5 * per_length } else { per_length },
            }
        };
        let kinds = [
            kind(
                LineContact::InnerRace,
                params.inner_raceway_radius,
                &params.raceway,
            ),
            kind(
                LineContact::OuterRace,
                -params.outer_raceway_radius,
                &params.raceway,
            ),
            kind(LineContact::RollerRoller, r, &params.roller_roller),
        ];
        // Over the slices and the film points, so that the bound holds for both.
        let (reach, largest_radius) =
            slices
                .iter()
                .chain(&film_points)
                .fold((0.0, 0.0), |(s, r), station| {
                    (
                        f64::max(s, f64::abs(station.s)),
                        f64::max(r, station.radius),
                    )
                });
        Self {
            kinds,
            slices,
            film_points,
            reach,
            largest_radius,
            slice_length,
        }
    }

    /// The data of the line contacts of kind `line`.
    pub(super) fn kind(&self, line: LineContact) -> &LineKind {
        &self.kinds[line.index()]
    }
}

impl BearingSystem<'_> {
    /// The slices' and the film points' geometry of a line contact whose penetration is at
    /// most `bound` (no slice computed where it is negative: none touches).
    pub(super) fn line_geometry(
        &self,
        line: LineContact,
        a: &Kinematics,
        b: &Kinematics,
        bound: f64,
    ) -> LineGeometry {
        let at = |station: &Station| self.slice_geometry(line, a, b, station.s, station.radius);
        let slices: &[Station] = if bound > 0.0 { &self.lines.slices } else { &[] };
        let film: &[Station] = if self.tribology.film.enabled {
            &self.lines.film_points
        } else {
            &[]
        };
        LineGeometry {
            sections: slices.iter().chain(film).map(at).collect(),
            slice_count: slices.len(),
        }
    }

    /// Geometry (eqs. 2, 3) of the section at `s` along roller `b` (radius `radius`, for
    /// two rollers both) against body `a`.
    pub(super) fn slice_geometry(
        &self,
        line: LineContact,
        a: &Kinematics,
        b: &Kinematics,
        s: f64,
        radius: f64,
    ) -> SectionGeometry {
        let cb = b.center + s * b.axis;
        let (normal, location, penetration) = match line {
            LineContact::InnerRace | LineContact::OuterRace => {
                let d = cb - a.center;
                let perp = d - d.dot(&a.axis) * a.axis;
                let dist = perp.norm();
                let out = perp / dist;
                if line == LineContact::InnerRace {
                    let delta = radius + self.params.inner_raceway_radius - dist;
                    (out, cb - out * (radius - 0.5 * delta), delta)
                } else {
                    let delta = dist + radius - self.params.outer_raceway_radius;
                    (-out, cb + out * (radius - 0.5 * delta), delta)
                }
            }
            LineContact::RollerRoller => {
                let ca = a.center + s * a.axis;
                let mean = (a.axis + b.axis).normalize();
                let d = cb - ca;
                let perp = d - d.dot(&mean) * mean;
                let dist = perp.norm();
                let n = perp / dist;
                let delta = 2.0 * radius - dist;
                (n, ca + n * (radius - 0.5 * delta), delta)
            }
        };
        SectionGeometry {
            normal,
            location,
            penetration,
        }
    }

    /// Whether a line contact whose penetration is at most `bound` carries nothing: no
    /// slice touches and every gap is beyond the film's reach.
    pub(super) fn is_apart(&self, bound: f64) -> bool {
        bound < -self.tribology.film.reach()
    }

    /// The result of a line contact whose bodies are apart: no force, and for the
    /// penetration the (negative) `bound`, not the largest slice penetration.
    pub(super) fn apart(bound: f64) -> ElementResult {
        ElementResult {
            penetration: bound,
            ..Default::default()
        }
    }

    /// An upper bound of the penetration of every slice of a line contact of kind `line`
    /// (eqs. 2, 3 without their slices): the distance of slice s is |P + s·Q|, P the part of
    /// the centres' offset across the reference axis and Q that of the roller axis (of the
    /// axes' difference for two rollers), whose least and greatest values over the slice
    /// centres |s| ≤ s_max are those of a point's distance to a segment; the slice radius
    /// is at most the largest one. Negative: no slice touches, and the slices need not be
    /// computed (on B1 many roller–roller pairs and the inner race outside the load zone).
    pub(super) fn penetration_bound(
        &self,
        line: LineContact,
        a: &Kinematics,
        b: &Kinematics,
    ) -> f64 {
        let (s_max, r_max) = (self.lines.reach, self.lines.largest_radius);
        let across = |v: Vec3, axis: &Vec3| v - v.dot(axis) * axis;
        let (axis, sway) = match line {
            LineContact::InnerRace | LineContact::OuterRace => (a.axis, b.axis),
            LineContact::RollerRoller => ((a.axis + b.axis).normalize(), b.axis - a.axis),
        };
        let (least, greatest) = distance_range(
            &across(b.center - a.center, &axis),
            &across(sway, &axis),
            s_max,
        );
        match line {
            LineContact::InnerRace => r_max + self.params.inner_raceway_radius - least,
            LineContact::OuterRace => greatest + r_max - self.params.outer_raceway_radius,
            LineContact::RollerRoller => 2.0 * r_max - least,
        }
    }

    /// The forces of a line contact of kind `line` from its slices' and film points'
    /// `geometry` ([`Self::line_geometry`]): the paper's laws per slice in contact, the oil
    /// film at its quadrature points. Computed along the way by [`Self::evaluate`], or
    /// given (from the same positions) for Jacobian columns of velocities, which leave it
    /// unchanged. The penetration is the slices' largest, or the film points' where no
    /// slice was computed.
    pub(super) fn line_forces(
        &self,
        line: LineContact,
        a: &Kinematics,
        b: &Kinematics,
        geometry: &LineGeometry,
    ) -> ElementResult {
        let start = self.workspace.profiler.stopwatch();
        let mut out = ElementResult::untouched();
        for section in geometry.slices() {
            out.penetration = out.penetration.max(section.penetration);
            if section.penetration > 0.0 {
                self.section_into(&mut out, line, a, b, section, None);
            }
        }
        for (section, point) in geometry.film().iter().zip(&self.lines.film_points) {
            if geometry.slices().is_empty() {
                out.penetration = out.penetration.max(section.penetration);
            }
            // in contact a film point acts up to its fade (RigidFilm::contact_fade), which
            // its own speeds set
            if self.tribology.film.reaches(section.penetration) {
                self.section_into(&mut out, line, a, b, section, Some(point.length));
            }
        }
        self.workspace
            .profiler
            .spend_time(start, |pr, t| pr.line_contacts += t);
        out
    }

    /// Adds the forces of one section of a line contact of kind `line` to `out`: the
    /// paper's slice laws ([`line_slice`]) for a slice, or the oil film ([`film_slice`])
    /// over the length `film` of a film point.
    fn section_into(
        &self,
        out: &mut ElementResult,
        line: LineContact,
        a: &Kinematics,
        b: &Kinematics,
        section: &SectionGeometry,
        film: Option<f64>,
    ) {
        let (n, p) = (&section.normal, &section.location);
        let rolling = n.cross(&b.axis).normalize();
        let frame = if line == LineContact::RollerRoller {
            0.5 * (a.frame_velocity(p) + b.frame_velocity(p))
        } else {
            b.frame_velocity(p)
        };
        let (tri, kind) = (&self.tribology, self.lines.kind(line));
        let geometry = Section {
            a,
            b,
            normal: *n,
            location: *p,
            penetration: section.penetration,
            length: film.unwrap_or(self.lines.slice_length),
            rolling,
            frame,
        };
        let f = match film {
            None => line_slice(tri, kind, &geometry),
            Some(_) => film_slice(tri, kind, &geometry),
        };
        // a film point past its fade carries nothing (adding its zeros would change no sum)
        if film.is_none() || f != ContactForces::default() {
            out.add_forces(&f, n, p, a, b);
        }
    }
}

/// The least and the greatest of |p + s·q| over |s| ≤ s_max: the distance of the origin
/// to the segment p ± s_max·q (its nearest point, or an end), and that of its farther end
/// (|p + s·q| is convex in s).
fn distance_range(p: &Vec3, q: &Vec3, s_max: f64) -> (f64, f64) {
    let qq = q.norm_squared();
    let nearest = if qq > 0.0 {
        (-p.dot(q) / qq).clamp(-s_max, s_max)
    } else {
        0.0
    };
    let least = (p + nearest * q).norm();
    let greatest = (p - s_max * q).norm().max((p + s_max * q).norm());
    (least, greatest)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The range of a slice distance |p + s·q| over the slice centres against a brute
        /// force over 2 001 values of s: it contains every sampled value, and its ends are
        /// met to the sampling's resolution (s_max/1000 times |q|, plus round-off).
        #[test]
        fn distance_range_bounds_every_slice(
            p in prop::array::uniform3(-5e-3..5e-3f64),
            q in prop::array::uniform3(-1e-2..1e-2f64),
            s_max in 1e-4..3e-3f64,
        ) {
            let (p, q) = (Vec3::from(p), Vec3::from(q));
            let (least, greatest) = distance_range(&p, &q, s_max);
            let samples: Vec<f64> = (0..=2000)
                .map(|i| (p + (s_max * (i as f64 / 1000.0 - 1.0)) * q).norm())
                .collect();
            let (lo, hi) = samples.iter().fold((f64::INFINITY, 0.0f64), |(l, h), &d| (l.min(d), h.max(d)));
            let tol = 1e-15 + s_max / 1000.0 * q.norm();
            prop_assert!(least <= lo + 1e-15 && least >= lo - tol, "{least} vs {lo}");
            prop_assert!(greatest >= hi - 1e-15 && greatest <= hi + 1e-15, "{greatest} vs {hi}");
        }
    }

    /// The film's load (Martin and squeeze) over a 4 mm roller whose gap falls linearly
    /// from 5 µm at its centre to `end` at one end (a tilted roller nearing the race), by
    /// the 6 Gauss points against a fine midpoint rule (20 000 sections) and against 20
    /// slices: the Gauss points are within 1.5 % for end gaps ≥ 0.5 µm and at least as
    /// close as the slices.
    #[test]
    fn six_gauss_points_integrate_the_film() {
        use crate::tribology::hydrodynamic::{film_line, RigidFilm};
        let film = RigidFilm {
            enabled: true,
            cutoff: 100e-6,
            suction_limit: 0.0,
        };
        let (length, sigma, eta, r) = (4e-3, 0.16e-6, 0.0165, 1.8e-3);
        for end in [0.5e-6, 1e-6, 2e-6, 0.2e-6] {
            for (u, rate) in [(0.3, 0.0), (1e-3, 1e-3)] {
                let load = |s: f64| {
                    let penetration = -(5e-6 - (5e-6 - end) * s / (0.5 * length));
                    let (h, weight) = film.gap_and_weight(penetration, sigma, sigma).unwrap();
                    weight * film_line(eta, r, h, u, rate, 0.0).load
                };
                let midpoint = |n: usize| -> f64 {
                    let dl = length / n as f64;
                    (0..n)
                        .map(|k| load(-0.5 * length + (k as f64 + 0.5) * dl) * dl)
                        .sum()
                };
                let exact = midpoint(20_000);
                let gauss: f64 = mapped_table(&FILM_POINTS, 0.5 * length)
                    .into_iter()
                    .map(|(s, w)| load(s) * w)
                    .sum();
                let (e_gauss, e_slices) = (
                    (gauss / exact - 1.0).abs(),
                    (midpoint(20) / exact - 1.0).abs(),
                );
                assert!(
                    e_gauss <= e_slices + 1e-3,
                    "{end} {u}: {e_gauss} vs {e_slices}"
                );
                if end >= 0.5e-6 {
                    assert!(e_gauss < 0.015, "{end} {u}: {e_gauss}");
                }
            }
        }
    }
}
