//! Mirror symmetry of a load case about the plane of the radial load (z = 0): with the
//! radial load, gravity, a planet carrier's field and any tilting moment or misalignment
//! in that plane, and the rollers placed symmetrically about it (roller 0 at the bottom,
//! ψ = π), roller i and roller Z − i are mirror images and the inner ring neither moves
//! along z nor tilts about y. The quasi-static solver then computes the rollers of one half and mirrors
//! the other's (a standard reduction of the classical analysis; Harris & Kotzalas,
//! "Rolling Bearing Analysis", 5th ed., ch. 7, sum over ψ = 0 … π). Friction, which
//! alone would tell the two halves apart, is not in the quasi-static model; centrifugal
//! forces and the gyroscopic moment are even in the direction of rotation.

use super::roller::RollerForces;
use super::{RingTilt, StaticCase};
use crate::bearing::contacts::Wrench;
use crate::bearing::model::BearingModel;
use crate::geometry::primitives::Vec3;

/// Which roller mirrors which.
#[derive(Debug, Clone)]
pub(super) struct Mirror {
    /// partner[i]: the roller at azimuth −ψ_i (i itself on the plane).
    partner: Vec<usize>,
}

impl Mirror {
    /// The mirror of `case` on `model` with the rollers at `azimuths`, or None when the
    /// case is not symmetric about z = 0.
    pub(super) fn of(model: &BearingModel, case: &StaticCase, azimuths: &[f64]) -> Option<Self> {
        let in_plane_tilt = match case.tilt {
            RingTilt::Free => true,
            RingTilt::Prescribed(about_y, _) => about_y == 0.0,
        };
        if case.moment[0] != 0.0 || case.roller_field(&model.params).z != 0.0 || !in_plane_tilt {
            return None;
        }
        let partner = azimuths
            .iter()
            .map(|psi| {
                azimuths.iter().position(|other| {
                    let d = (psi + other).rem_euclid(std::f64::consts::TAU);
                    d.min(std::f64::consts::TAU - d) < 1e-12
                })
            })
            .collect::<Option<Vec<usize>>>()?;
        Some(Self { partner })
    }

    /// Whether roller i is computed (the other of its pair is mirrored from it).
    pub(super) fn computed(&self, i: usize) -> bool {
        self.partner[i] >= i
    }

    /// The mirror image of roller `i`'s unknowns in `u` set on its partner: radial offset,
    /// axial position and tilt are the same in each roller's own directions.
    pub(super) fn copy_unknowns(&self, u: &mut [f64], first: usize, per_roller: usize) {
        for (i, &j) in self.partner.iter().enumerate() {
            if j > i {
                let (s, t) = (first + per_roller * i, first + per_roller * j);
                u.copy_within(s..s + per_roller, t);
            }
        }
    }

    /// Fills the forces of every mirrored roller from its partner's.
    pub(super) fn copy_forces(&self, forces: &mut [RollerForces]) {
        for (i, &j) in self.partner.iter().enumerate() {
            if j > i {
                forces[j] = mirrored(&forces[i]);
            }
        }
    }

    /// Rollers computed per evaluation of all of them.
    pub(super) fn computed_count(&self) -> usize {
        (0..self.partner.len())
            .filter(|&i| self.computed(i))
            .count()
    }
}

/// A force (polar vector) reflected in the plane z = 0.
fn reflect_force(v: &Vec3) -> Vec3 {
    Vec3::new(v.x, v.y, -v.z)
}

/// A moment (axial vector) reflected in the plane z = 0: det(R)·R·M.
fn reflect_moment(m: &Vec3) -> Vec3 {
    Vec3::new(-m.x, -m.y, m.z)
}

/// The wrench `w` reflected in z = 0.
fn reflect(w: &Wrench) -> Wrench {
    Wrench {
        force: reflect_force(&w.force),
        moment: reflect_moment(&w.moment),
    }
}

/// The forces of a roller's mirror image: its wrenches reflected, its slice and flange
/// loads the same.
fn mirrored(f: &RollerForces) -> RollerForces {
    RollerForces {
        on_roller: reflect(&f.on_roller),
        on_ring: reflect(&f.on_ring),
        ..f.clone()
    }
}
