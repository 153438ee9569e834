//! Pruning, which the paper only proposes (sect. 5.3): skip pairings that cannot touch and
//! flanges that cannot be reached, by conservative bounds that provably miss no contact.
//!
//! Both bounds work in the flange's meridian plane (axial coordinate s and radius ρ about
//! the ring axis). For any two points p, q: |p − q| ≥ |(s_p − s_q, ρ_p − ρ_q)|, since the
//! azimuthal separation only adds to the distance. So if the meridian boxes that contain
//! a roller figure and a flange figure are apart, the figures cannot overlap.
//!
//! * A roller figure's box: s from its support function along ±a (exact for the torus of
//!   which the patch is a part, and for the spherical cap), ρ within ρ(centre) ± (extent)
//!   by the triangle inequality.
//! * A flange figure's box: exact s and ρ ranges of the patch (cone ends; torus arcs with
//!   their interior extrema).
//!
//! A pairing whose boxes are apart is skipped; a flange whose box (the union of its
//! three) is apart from the roller end's box is skipped whole.

use super::{semi_analytical, Contact};
use crate::geometry::end_flange::{Flange, RollerEnd};
use crate::geometry::primitives::{meridian, wrap_angle, ConePatch, SpherePatch, TorusPatch, Vec3};
use std::f64::consts::{FRAC_PI_2, PI};

/// A box [s_lo, s_hi] × [ρ_lo, ρ_hi] in a flange's meridian plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeridianBox {
    /// Axial range.
    pub s: (f64, f64),
    /// Radial range.
    pub rho: (f64, f64),
}

impl MeridianBox {
    /// The smallest box containing both.
    pub fn union(&self, other: &Self) -> Self {
        Self {
            s: (self.s.0.min(other.s.0), self.s.1.max(other.s.1)),
            rho: (self.rho.0.min(other.rho.0), self.rho.1.max(other.rho.1)),
        }
    }

    /// True if the two boxes are apart by more than `margin` (so that their contents
    /// cannot come closer than `margin`).
    pub fn apart(&self, other: &Self, margin: f64) -> bool {
        let gap = |a: (f64, f64), b: (f64, f64)| (a.0 - b.1).max(b.0 - a.1).max(0.0);
        let (ds, dr) = (gap(self.s, other.s), gap(self.rho, other.rho));
        ds * ds + dr * dr > margin * margin
    }
}

/// The unit meridian directions m(φ) = (sin φ, cos φ) in (s, ρ) at which the components of
/// c + r·m(φ) over an arc of tube angles take their extremes: the arc's two ends, and the
/// axis directions (±1, 0), (0, ±1) that lie inside it.
fn arc_extreme_directions(mid: f64, half: f64) -> ([(f64, f64); 6], usize) {
    let mut out = [(0.0, 0.0); 6];
    out[0] = (mid - half).sin_cos();
    out[1] = (mid + half).sin_cos();
    let mut n = 2;
    for (phi, dir) in [
        (FRAC_PI_2, (1.0, 0.0)),
        (-FRAC_PI_2, (-1.0, 0.0)),
        (0.0, (0.0, 1.0)),
        (PI, (0.0, -1.0)),
    ] {
        if wrap_angle(phi - mid).abs() <= half {
            out[n] = dir;
            n += 1;
        }
    }
    (out, n)
}

/// Meridian box of the points c + ρ·m(φ) of a flange torus patch (its axis is the ring
/// axis) for every tube radius ρ in `radii` and φ on the arc. Each coordinate is linear in
/// ρ, so for a range of radii its two ends suffice.
fn torus_box_radii(
    t: &TorusPatch,
    radii: &[f64],
    ring_origin: &Vec3,
    ring_axis: &Vec3,
) -> MeridianBox {
    let s_c = ring_axis.dot(&(t.origin - ring_origin));
    let (dirs, n) = arc_extreme_directions(t.phi_mid, t.phi_half);
    let mut b = MeridianBox {
        s: (f64::INFINITY, f64::NEG_INFINITY),
        rho: (f64::INFINITY, f64::NEG_INFINITY),
    };
    for &r in radii {
        for &(sin, cos) in &dirs[..n] {
            let (ps, pr) = (s_c + r * sin, t.major_radius + r * cos);
            b.s = (b.s.0.min(ps), b.s.1.max(ps));
            b.rho = (b.rho.0.min(pr), b.rho.1.max(pr));
        }
    }
    b
}

/// Meridian box of a flange torus patch (its axis is the ring axis).
pub fn torus_box(t: &TorusPatch, ring_origin: &Vec3, ring_axis: &Vec3) -> MeridianBox {
    torus_box_radii(t, &[t.minor_radius], ring_origin, ring_axis)
}

/// Meridian box of a cone patch about its own axis.
pub fn cone_box(c: &ConePatch) -> MeridianBox {
    let ends = [c.g_min, c.g_max].map(|g| (c.s0 + g * c.ds, c.rho0 + g * c.drho));
    MeridianBox {
        s: (ends[0].0.min(ends[1].0), ends[0].0.max(ends[1].0)),
        rho: (ends[0].1.min(ends[1].1), ends[0].1.max(ends[1].1)),
    }
}

/// Meridian box of a flange: the union of its three patches.
pub fn flange_box(f: &Flange) -> MeridianBox {
    FlangeBounds::new(f).whole
}

/// Deepest penetration for which pruning is guaranteed to miss no contact [m].
///
/// The boxes of the flange's patches enclose surfaces, but an overlapping roller point lies
/// inside the flange's solid, at the penetration δ below the patch along its normal. B1's
/// face box is only about 1 µm deep (opening angle 0.11°), so without this margin a roller
/// end pushed 30 µm through the face was skipped (a proptest case). The flange boxes are
/// therefore extended by this depth into the solid (not towards the roller, so flanges in
/// front of a roller are still skipped). 100 µm (less than B1's 0.2 mm root radius) is far
/// beyond any penetration of a run (at most 12 µm seen in B1's rattling impacts).
pub const PENETRATION_BOUND: f64 = 100e-6;

impl MeridianBox {
    /// The union of the box and its copy shifted by `d`·(n_s, n_ρ) (the region swept).
    fn swept(&self, (ns, nr): (f64, f64), d: f64) -> Self {
        let (ds, dr) = (ns * d, nr * d);
        self.union(&Self {
            s: (self.s.0 + ds, self.s.1 + ds),
            rho: (self.rho.0 + dr, self.rho.1 + dr),
        })
    }
}

/// Meridian box of a flange torus patch with the tube's solid down to depth `d` (< r)
/// beneath it: the points c + ρ·m(φ), ρ ∈ [r − d, r], φ on the arc.
fn torus_solid_box(t: &TorusPatch, d: f64, o: &Vec3, a: &Vec3) -> MeridianBox {
    let r = t.minor_radius;
    torus_box_radii(t, &[r, (r - d).max(0.0)], o, a)
}

/// Meridian boxes of the flange's cone, root torus and rim torus, each with the solid
/// beneath it down to [`PENETRATION_BOUND`] (only into the solid, so the boxes do not grow
/// towards a roller in front of the flange): the cone's box swept along its inward normal,
/// the tori's boxes with their tubes shrunk by that depth.
fn figure_boxes(f: &Flange) -> [MeridianBox; 3] {
    let (o, a) = (f.cone.origin, f.cone.axis);
    let (ns, nr) = f.cone.meridian_normal();
    [
        cone_box(&f.cone).swept((-ns, -nr), PENETRATION_BOUND),
        torus_solid_box(&f.root, PENETRATION_BOUND, &o, &a),
        torus_solid_box(&f.rim, PENETRATION_BOUND, &o, &a),
    ]
}

/// The meridian boxes of a flange's cone, root torus and rim torus, each with the solid
/// beneath it (see [`PENETRATION_BOUND`]), and their union.
///
/// They are intrinsic to the flange: s is measured from the flange's origin along its axis
/// and ρ about that axis, so a flange keeps its bounds however its ring moves or tilts. A
/// model therefore computes them once per flange: on B1 they cost about 75 ns, a third of a
/// pruned composite when recomputed at every call.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlangeBounds {
    /// Cone, root torus, rim torus.
    pub figures: [MeridianBox; 3],
    /// The union of the three.
    pub whole: MeridianBox,
}

impl FlangeBounds {
    /// The bounds of `flange`.
    pub fn new(flange: &Flange) -> Self {
        let figures = figure_boxes(flange);
        let whole = figures[0].union(&figures[1]).union(&figures[2]);
        Self { figures, whole }
    }
}

/// Support h(d) = max p·d over the whole torus of which the roller's edge patch is part.
fn torus_support(t: &TorusPatch, d: &Vec3) -> f64 {
    let along = t.axis.dot(d);
    t.origin.dot(d) + t.major_radius * (d - t.axis * along).norm() + t.minor_radius * d.norm()
}

/// Support of a spherical cap: the full sphere's if d lies within the cap's cone of
/// directions, else the cap's boundary circle's. `(sin, cos)` of the cap angle.
fn cap_support(s: &SpherePatch, (sin, cos): (f64, f64), d: &Vec3) -> f64 {
    let dn = d.norm();
    let along = s.pole.dot(d);
    if along >= dn * cos {
        return s.center.dot(d) + s.radius * dn;
    }
    let base = s.center + s.pole * (s.radius * cos);
    base.dot(d) + s.radius * sin * (d - s.pole * along).norm()
}

/// Meridian box of a roller figure with the given supports and extent about `center`.
fn roller_box(
    support: impl Fn(&Vec3) -> f64,
    center: &Vec3,
    extent: f64,
    ring_origin: &Vec3,
    ring_axis: &Vec3,
) -> MeridianBox {
    let o_dot = ring_origin.dot(ring_axis);
    let (_, rho, _) = meridian(center, ring_origin, ring_axis);
    MeridianBox {
        s: (-support(&(-ring_axis)) - o_dot, support(ring_axis) - o_dot),
        rho: ((rho - extent).max(0.0), rho + extent),
    }
}

/// Meridian boxes of the roller end's torus and sphere cap in the flange's frame.
pub fn end_boxes(end: &RollerEnd, flange: &Flange) -> [MeridianBox; 2] {
    let (o, a) = (flange.cone.origin, flange.cone.axis);
    let t = &end.torus;
    let s = &end.sphere;
    let cap = s.cap_angle.sin_cos();
    let cap_center = s.center + s.pole * (s.radius * cap.1);
    [
        roller_box(
            |d| torus_support(t, d),
            &t.origin,
            t.major_radius + t.minor_radius,
            &o,
            &a,
        ),
        roller_box(
            |d| cap_support(s, cap, d),
            &cap_center,
            s.radius * cap.0,
            &o,
            &a,
        ),
    ]
}

/// The six pairings with those that provably cannot overlap skipped (None), in
/// [`super::Pairing::ALL`] order, and whether the whole flange was skipped.
pub fn detect(end: &RollerEnd, flange: &Flange) -> ([Option<Contact>; 6], bool) {
    let ends = end_boxes(end, flange);
    let bounds = FlangeBounds::new(flange);
    if ends[0].union(&ends[1]).apart(&bounds.whole, 0.0) {
        return ([None; 6], true);
    }
    let skip: [bool; 6] = std::array::from_fn(|k| ends[k / 3].apart(&bounds.figures[k % 3], 0.0));
    let contacts = [
        (!skip[0]).then(|| semi_analytical::torus_cone(&end.torus, &flange.cone)),
        (!skip[1]).then(|| {
            semi_analytical::torus_torus(&end.torus, &flange.root, super::Pairing::TorusRoot)
        }),
        (!skip[2]).then(|| {
            semi_analytical::torus_torus(&end.torus, &flange.rim, super::Pairing::TorusRim)
        }),
        (!skip[3]).then(|| semi_analytical::sphere_cone(&end.sphere, &flange.cone)),
        (!skip[4]).then(|| {
            semi_analytical::sphere_torus(&end.sphere, &flange.root, super::Pairing::SphereRoot)
        }),
        (!skip[5]).then(|| {
            semi_analytical::sphere_torus(&end.sphere, &flange.rim, super::Pairing::SphereRim)
        }),
    ];
    (contacts, false)
}

/// The composite with both shortcuts: flanges and pairings that provably cannot overlap
/// are skipped, and the torus–torus pairings are solved only when no other pairing is valid
/// (see [`semi_analytical::composite`]). Returns the deepest valid *overlapping* contact,
/// None when nothing overlaps.
pub fn composite(end: &RollerEnd, flange: &Flange) -> Option<Contact> {
    composite_within(end, flange, 0.0)
}

/// [`composite`] that also reports gaps narrower than `reach` [m] (for forces that act
/// across a gap, the squeeze film): the deepest valid contact with penetration > −reach,
/// None when everything is farther apart. The boxes are tested with `reach` as margin,
/// so a skipped pairing is provably farther than `reach`.
pub fn composite_within(end: &RollerEnd, flange: &Flange, reach: f64) -> Option<Contact> {
    composite_within_bounds(end, flange, &FlangeBounds::new(flange), reach)
}

/// [`composite_within`] with the flange's bounds computed beforehand (once per flange, see
/// [`FlangeBounds`]); `bounds` must be those of `flange` or of the same flange in another
/// pose.
pub fn composite_within_bounds(
    end: &RollerEnd,
    flange: &Flange,
    bounds: &FlangeBounds,
    reach: f64,
) -> Option<Contact> {
    let ends = end_boxes(end, flange);
    if ends[0].union(&ends[1]).apart(&bounds.whole, reach) {
        return None;
    }
    let keep = |k: usize| !ends[k / 3].apart(&bounds.figures[k % 3], reach);
    let cheap = [
        keep(3).then(|| semi_analytical::sphere_cone(&end.sphere, &flange.cone)),
        keep(4).then(|| {
            semi_analytical::sphere_torus(&end.sphere, &flange.root, super::Pairing::SphereRoot)
        }),
        keep(5).then(|| {
            semi_analytical::sphere_torus(&end.sphere, &flange.rim, super::Pairing::SphereRim)
        }),
        keep(0).then(|| semi_analytical::torus_cone(&end.torus, &flange.cone)),
    ];
    let best = deepest_of(&cheap).or_else(|| {
        deepest_of(&[
            keep(1).then(|| {
                semi_analytical::torus_torus(&end.torus, &flange.root, super::Pairing::TorusRoot)
            }),
            keep(2).then(|| {
                semi_analytical::torus_torus(&end.torus, &flange.rim, super::Pairing::TorusRim)
            }),
        ])
    });
    best.filter(|c| c.penetration > -reach)
}

/// [`super::deepest`] of the computed (Some) contacts, without collecting them: the valid
/// one with the largest finite penetration, ties to the first.
fn deepest_of(contacts: &[Option<Contact>]) -> Option<Contact> {
    contacts
        .iter()
        .flatten()
        .filter(|c| c.valid && c.penetration.is_finite())
        .fold(None, |best: Option<Contact>, c| match best {
            Some(b) if b.penetration >= c.penetration => Some(b),
            _ => Some(*c),
        })
}
