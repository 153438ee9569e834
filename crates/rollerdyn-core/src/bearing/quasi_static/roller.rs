//! One roller of the quasi-static analysis: its pose from its unknowns, and the normal
//! forces of its contacts with the two races (slices, eq. 11) and the four flanges
//! (semi-analytical detection, Hertz by Brewe–Hamrock, eqs. 5–8, or the distributed
//! overlap), as a wrench on the roller and a wrench on the inner ring about the ring's
//! centre.

use crate::bearing::contacts::Wrench;
use crate::bearing::model::LineContact;
use crate::bearing::params::FlangeLaw;
use crate::bearing::state::Kinematics;
use crate::bearing::workspace::BearingSystem;
use crate::contact::{border, pruning, Contact, Pairing};
use crate::geometry::end_flange::{Flange, RollerEnd};
use crate::geometry::primitives::Vec3;
use crate::tribology::foundation;
use crate::tribology::hertz::{
    line_half_width, line_max_pressure, EllipticalContact, EllipticalMethod,
};
use std::f64::consts::PI;

/// Unknowns per roller: radial offset, axial position, tilt.
pub const ROLLER_UNKNOWNS: usize = 3;

/// The pose of a roller: its azimuth ψ (given), and its unknowns: the offset ρ of its
/// centre from the pitch circle (outwards), its axial position a and its tilt τ about its
/// tangential axis t = x × e_r (positive: the +x end moves outwards). Its skew stays zero:
/// without friction nothing sets it (as in ISO/TS 16281).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollerPose {
    /// Azimuth ψ [rad], from +y towards +z.
    pub azimuth: f64,
    /// Radial offset ρ from the pitch circle [m].
    pub radial: f64,
    /// Axial position a [m].
    pub axial: f64,
    /// Tilt τ about the tangential axis [rad].
    pub tilt: f64,
}

impl RollerPose {
    /// The pose with unknowns `q` = (ρ, a, τ) at azimuth `azimuth`.
    pub fn new(azimuth: f64, q: &[f64]) -> Self {
        Self {
            azimuth,
            radial: q[0],
            axial: q[1],
            tilt: q[2],
        }
    }

    /// The outward radial unit vector e_r = (0, cos ψ, sin ψ).
    pub fn radial_direction(&self) -> Vec3 {
        Vec3::new(0.0, self.azimuth.cos(), self.azimuth.sin())
    }

    /// The tangential unit vector t = x × e_r.
    pub fn tangential_direction(&self) -> Vec3 {
        Vec3::x().cross(&self.radial_direction())
    }

    /// Position and axis (at rest) on the pitch circle of radius `pitch`: the axis is
    /// cos τ·x + sin τ·e_r, the bearing axis turned by τ about t.
    pub fn kinematics(&self, pitch: f64) -> Kinematics {
        let e_r = self.radial_direction();
        Kinematics {
            center: Vec3::x() * self.axial + e_r * (pitch + self.radial),
            axis: Vec3::x() * self.tilt.cos() + e_r * self.tilt.sin(),
            velocity: Vec3::zeros(),
            omega: Vec3::zeros(),
        }
    }
}

/// The normal force of one flange contact of a roller.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FlangeLoad {
    /// Normal force [N].
    pub force: f64,
    /// Penetration [m] (negative: gap; NaN: no contact found).
    pub penetration: f64,
    /// Index into [`Pairing::ALL`] of the loaded pairing.
    pub pairing: Option<usize>,
    /// Hertz pressure p₀ = 3F/(2πab) [Pa] of the exact ellipse ([`exact_max_pressure`]; with
    /// the distributed law [`peak_pressure`]), what ISO 76's flange limit judges.
    pub pressure: f64,
    /// Distance [m] of the force's point (the detected point; with the distributed law the
    /// overlap's centre) from the flange ring's axis: where on the flange the end presses
    /// (NaN where nothing is carried).
    pub radius: f64,
}

/// What the contacts of one roller do.
#[derive(Debug, Clone, Default)]
pub struct RollerForces {
    /// Wrench on the roller about its centre.
    pub on_roller: Wrench,
    /// Wrench on the inner ring about its centre.
    pub on_ring: Wrench,
    /// Slice loads at the inner race [N], from the −x end (only when asked for details).
    pub inner_slices: Vec<f64>,
    /// Slice loads at the outer race [N] (only when asked for details).
    pub outer_slices: Vec<f64>,
    /// Hertz pressure p₀ of each slice at the inner race [Pa] (with details).
    pub inner_pressures: Vec<f64>,
    /// Hertz pressure p₀ of each slice at the outer race [Pa] (with details).
    pub outer_pressures: Vec<f64>,
    /// Flange contacts 0–3 (inner −x, +x; outer −x, +x).
    pub flanges: [FlangeLoad; 4],
}

/// Every flange contact of `forces` as (roller, flange 0–3, its load).
pub fn flange_loads(forces: &[RollerForces]) -> impl Iterator<Item = (usize, usize, &FlangeLoad)> {
    forces
        .iter()
        .enumerate()
        .flat_map(|(i, f)| f.flanges.iter().enumerate().map(move |(k, x)| (i, k, x)))
}

impl BearingSystem<'_> {
    /// The normal forces of the contacts of a roller at `roller` (at rest) against the
    /// inner ring at `ring` and the outer ring (its position; speeds do not enter); with
    /// `details`, the slice loads too.
    pub(crate) fn quasi_static_roller(
        &self,
        ring: &Kinematics,
        roller: &Kinematics,
        details: bool,
    ) -> RollerForces {
        let mut out = RollerForces::default();
        let outer = Kinematics::fixed();
        for (line, race) in [
            (LineContact::InnerRace, ring),
            (LineContact::OuterRace, &outer),
        ] {
            let slices = self.race_slices(line, race, roller, ring, &mut out);
            if details {
                let kind = self.lines.kind(line);
                let length = self.lines.slice_length;
                let pressures = slices
                    .iter()
                    .map(|&f| {
                        let b = line_half_width(f, length, kind.r_eff, kind.e_prime);
                        if f > 0.0 {
                            line_max_pressure(f, b, length)
                        } else {
                            0.0
                        }
                    })
                    .collect();
                match line {
                    LineContact::InnerRace => {
                        (out.inner_slices, out.inner_pressures) = (slices, pressures)
                    }
                    _ => (out.outer_slices, out.outer_pressures) = (slices, pressures),
                }
            }
        }
        for k in 0..4 {
            let race = if k < 2 { ring } else { &outer };
            out.flanges[k] = self.flange_load(k, race, roller, ring, &mut out);
        }
        out
    }

    /// The largest penetration of roller's slices against `race` in contact `line` [m]
    /// (negative: the narrowest gap).
    pub(crate) fn deepest_slice(
        &self,
        line: LineContact,
        race: &Kinematics,
        roller: &Kinematics,
    ) -> f64 {
        self.lines
            .slices
            .iter()
            .map(|station| {
                self.slice_geometry(line, race, roller, station.s, station.radius)
                    .penetration
            })
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Adds the slices of race contact `line` (race body `race`) to `out` and returns
    /// their loads.
    fn race_slices(
        &self,
        line: LineContact,
        race: &Kinematics,
        roller: &Kinematics,
        ring: &Kinematics,
        out: &mut RollerForces,
    ) -> Vec<f64> {
        if self.penetration_bound(line, race, roller) <= 0.0 {
            return vec![0.0; self.lines.slices.len()];
        }
        let kind = self.lines.kind(line);
        self.lines
            .slices
            .iter()
            .map(|station| {
                let section = self.slice_geometry(line, race, roller, station.s, station.radius);
                let force = kind.law.force(section.penetration, self.lines.slice_length);
                if force > 0.0 {
                    let f = force * section.normal;
                    add_force(
                        out,
                        f,
                        &section.location,
                        roller,
                        ring,
                        line == LineContact::InnerRace,
                    );
                }
                force
            })
            .collect()
    }

    /// The normal force of roller end k against flange k of `race`, added to `out`: the
    /// paper's point contact (Hertz at the detected point), or with
    /// `surfaces.flange_law = "distributed"` the whole overlap on its Winkler foundation at
    /// the load's centre, as in the dynamic model ([`crate::bearing::flange_contacts`]).
    fn flange_load(
        &self,
        k: usize,
        race: &Kinematics,
        roller: &Kinematics,
        ring: &Kinematics,
        out: &mut RollerForces,
    ) -> FlangeLoad {
        let none = FlangeLoad {
            penetration: f64::NAN,
            radius: f64::NAN,
            ..Default::default()
        };
        if !self.params.flanges[k] {
            return none; // a ring without this flange (BearingParams::flanges)
        }
        let end = self.roller_end(k, roller);
        let flange = self.flange(k, race);
        let distributed = self.params.flange_law == FlangeLaw::Distributed;
        // The distributed law carries across gaps within the asperities' reach.
        let reach = if distributed {
            self.asperities().reach()
        } else {
            0.0
        };
        let Some(found) =
            pruning::composite_within_bounds(&end, &flange, &self.flange_bounds[k], reach)
        else {
            return none;
        };
        let c: Contact = border::blend(&found, &end, &flange, &self.params.options.border_bands);
        let load = FlangeLoad {
            penetration: c.penetration,
            pairing: Pairing::ALL.iter().position(|q| *q == c.pairing),
            radius: f64::NAN,
            ..Default::default()
        };
        let placed = if distributed {
            self.distributed_flange_load(k, &end, &flange, &c)
        } else {
            point_flange_load(&c, self.ellipse.e_prime)
        };
        let Some((force, pressure, location, normal)) = placed else {
            return FlangeLoad {
                pairing: None,
                ..load
            };
        };
        add_force(out, force * normal, &location, roller, ring, k < 2);
        FlangeLoad {
            force,
            pressure,
            radius: distance_from_axis(&location, race),
            ..load
        }
    }

    /// The distributed law's load of `end` on flange k (detected contact `c`): (force,
    /// peak pressure ([`peak_pressure`]), centre, normal), None where nothing is carried.
    fn distributed_flange_load(
        &self,
        k: usize,
        end: &RollerEnd,
        flange: &Flange,
        c: &Contact,
    ) -> Option<(f64, f64, Vec3, Vec3)> {
        let overlap = self.overlap(end, flange, c, false)?;
        let force = foundation::foundation_force(
            self.foundation_modulus[usize::from(k >= 2)],
            overlap.volume,
        );
        if force.is_nan() || force <= 0.0 {
            return None;
        }
        Some((
            force,
            peak_pressure(c, force, overlap.semi_axes, self.ellipse.e_prime),
            overlap.centre,
            overlap.normal,
        ))
    }
}

/// The peak pressure of a distributed contact of normal force `force` [Pa], for the flange
/// pressure limit ([`super::FLANGE_PRESSURE_LIMIT`], ISO 76's Hertzian criterion): the
/// larger of p₀ = 3F/(2πab) of the ellipse of the load's second moments (`semi_axes` a, b)
/// and Hertz's p₀ of the detected contact's penetration on its (blended) curvature, what
/// the point law would press there. The Winkler foundation's own pressure is the flat
/// face's (`tribology/foundation.rs`): on the 0.5 mm edge torus or the flange's rim it is
/// a tenth of Hertz's, and B1 at 30 kN axially has an equilibrium with the rollers tipped
/// by 23 mrad into the rims at 3.1 GPa by the ellipse alone. (Hertz's p₀ of the
/// foundation's force on that curvature would overstate it: where the end lies nearly
/// flat, the overlap is far wider than the curvature's quadric at the same depth, B1 at
/// 2000 N: 1.1 × 0.19 mm against 0.10 × 0.03 mm, and carries 94 N where Hertz carries 6.)
fn peak_pressure(c: &Contact, force: f64, (a, b): (f64, f64), e_prime: f64) -> f64 {
    let ellipse = 1.5 * force / (PI * a.max(1e-12) * b.max(1e-12));
    if !(c.penetration > 0.0 && c.rx > 0.0 && c.ry > 0.0 && c.rx.max(c.ry).is_finite()) {
        return ellipse;
    }
    let hertz = EllipticalContact::new(c.rx, c.ry, e_prime, EllipticalMethod::BreweHamrock);
    exact_max_pressure(c, hertz.force(c.penetration), e_prime).max(ellipse)
}

/// Hertz's maximum pressure of a force `force` on the relative radii of the detected
/// contact `c` by the exact solution (elliptic integrals; Hamrock, Schmid & Jacobson 2004,
/// eqs. 3.24–3.27), what the flange pressure limit judges. The force laws keep the paper's
/// Brewe–Hamrock fits (eqs. 6–8), whose p₀ at B1's nearly flat roller ends (radius ratios
/// of thousands) is 9–13 % lower (docs/dynamics.md, "Lubrication at the contacts").
fn exact_max_pressure(c: &Contact, force: f64, e_prime: f64) -> f64 {
    EllipticalContact::new(c.rx, c.ry, e_prime, EllipticalMethod::Exact)
        .at_force(force)
        .max_pressure
}

/// The paper's point law at the detected contact `c`: (Hertz force by Brewe–Hamrock, p₀
/// by the exact solution ([`exact_max_pressure`]), contact point, normal), None where it
/// carries nothing.
fn point_flange_load(c: &Contact, e_prime: f64) -> Option<(f64, f64, Vec3, Vec3)> {
    if !(c.valid && c.penetration > 0.0 && c.rx > 0.0 && c.ry > 0.0 && c.ry.is_finite()) {
        return None;
    }
    let hertz = EllipticalContact::new(c.rx, c.ry, e_prime, EllipticalMethod::BreweHamrock);
    let force = hertz.force(c.penetration);
    Some((
        force,
        exact_max_pressure(c, force, e_prime),
        c.location(),
        c.normal,
    ))
}

/// Adds the force `f` on the roller at `p` (and, when the race is the inner ring's, −f on
/// the ring) to `out`, with its moments about each body's centre.
fn add_force(
    out: &mut RollerForces,
    f: Vec3,
    p: &Vec3,
    roller: &Kinematics,
    ring: &Kinematics,
    on_inner_ring: bool,
) {
    out.on_roller.force += f;
    out.on_roller.moment += (p - roller.center).cross(&f);
    if on_inner_ring {
        out.on_ring.force -= f;
        out.on_ring.moment -= (p - ring.center).cross(&f);
    }
}

/// Distance of `point` from the axis of `body` (through its centre along its unit axis).
fn distance_from_axis(point: &Vec3, body: &Kinematics) -> f64 {
    let d = point - body.center;
    (d - d.dot(&body.axis) * body.axis).norm()
}
