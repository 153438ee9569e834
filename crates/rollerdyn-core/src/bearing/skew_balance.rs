//! The rollers' skew in steady rolling (not in the paper): the angle about its radial
//! direction at which the moments on a roller about that direction balance.
//!
//! The quasi-static equilibrium ([`super::quasi_static`]) balances each roller's forces and
//! its moment about the tangential direction (its tilt), not its moment about the radial
//! direction: the friction of the flanges makes one. Under an axial load a loaded roller is
//! pressed by an inner flange at one end and an outer flange at the other, each of whose
//! rims slides past the end faster than the end turns ([`super::statics`], the spin's
//! balance), so their friction forces point along the orbit at opposite ends of the roller
//! and turn it about its radial direction; how the end–flange contacts move as the roller
//! skews (their points and penetrations, with the ends' spheres and tori) changes that
//! moment, while the races' sideways traction hardly does (B1 at 1 kN, 500 rpm: a loaded
//! roller's flanges 0.035 N·m each at zero skew, the races 0.004 N·m, flat within ±1 mrad:
//! at that skew they slide sideways at a millimetre per second). The skew where the moment
//! vanishes is what the dynamic model's loaded rollers settle at (B1: −0.12 against the
//! run's −0.13 mrad at the bottom of the load zone; docs/statics.md, "The rollers' skew").
//!
//! As a root of one roller's moment it need not be stable alone: on B1 the moment grows
//! with the skew through the root (a roller turned further is turned further still), and
//! in the run the root is held by the roller's other motions (its axial position and tilt
//! against the flanges), which the statics keep at their equilibrium. So the root nearest
//! zero skew is taken, whatever its slope ([`skew_root`]).

use super::contacts::ElementResult;
use super::state::BearingKinematics;
use super::statics::SpinMoment;
use super::topology::{Body, Element};
use super::workspace::BearingSystem;
use crate::geometry::primitives::Vec3;
use nalgebra::{Rotation3, Unit};

/// The first step [rad] of [`skew_root`]'s search outwards from zero skew, each next one
/// twice the last.
const FIRST_SKEW_STEP: f64 = 1e-5;
/// The first step [rad] from a skew of the round before (the rounds of
/// [`super::statics`]' spin and skew balance move B1's skews by 1e-6 … 1e-8).
const WARM_SKEW_STEP: f64 = 1e-6;
/// The skew step [rad] over which a roller's race contacts' moment is differenced for its
/// line in [`BearingSystem::balanced_skews`].
const RACE_SKEW_STEP: f64 = 1e-6;
/// The widest skew [rad] [`skew_root`] searches (5 mrad: five times the largest skew of
/// B1's loaded rollers in its runs, −1.03 mrad with the distributed law).
pub(crate) const SKEW_LIMIT: f64 = 5e-3;
/// Width [rad] of the bracket at which [`skew_root`] stops (10 nrad: 1e-4 of B1's
/// skews in the load zone).
const SKEW_TOLERANCE: f64 = 1e-8;
/// The share of the moments that meet on a roller about its radial direction (the sum of
/// their magnitudes) below which [`skew_root`] takes their sum for balanced.
const SKEW_BALANCE: f64 = 1e-4;
/// The share of the heaviest roller's race load that a roller's largest flange force must
/// reach for its skew to be balanced ([`BearingSystem::pressed_by_flanges`]): the flanges'
/// friction is what skews a roller; one that they touch with less (an unloaded roller on
/// its films, every roller without axial load: B1's at 0 N carry millinewtons at the
/// flanges against 1 288 N at the races) is held by nothing but its films and the drag,
/// whose moments hardly change until its end meets a flange, so its skew is free within its
/// play between the flanges and no balance sets it: it keeps zero skew (B1 at 1 kN: the
/// loaded rollers' flanges 26–141 N, the threshold 1.3 N, the free rollers' millinewtons).
const SKEW_FLANGE_SHARE: f64 = 1e-3;
/// The most evaluations of [`skew_root`]'s narrowing.
const SKEW_NARROWING: usize = 40;

/// The skew β [rad] nearest `start` within ±[`SKEW_LIMIT`] at which `moment(β)` (a
/// roller's moment about its radial direction, with the sum of its parts' magnitudes)
/// changes sign, or where it is balanced to [`SKEW_BALANCE`] of its parts. The search
/// steps outwards from `start` on both sides at once, ±`first_step`·2ᵏ, to the first sign
/// change (on both sides at one step: the one whose secant's root is nearer `start`), then
/// narrows it by the Illinois variant of regula falsi (Dowell & Jarratt 1971) to
/// [`SKEW_TOLERANCE`]. Without a sign change within the limit, the skew of the least
/// |moment| met is kept.
pub(crate) fn skew_root(
    start: f64,
    first_step: f64,
    mut moment: impl FnMut(f64) -> SpinMoment,
) -> f64 {
    let balanced = |m: &SpinMoment| m.net.abs() <= SKEW_BALANCE * m.gross;
    let m0 = moment(start);
    if balanced(&m0) {
        return start;
    }
    let mut best = (start, m0.net.abs());
    let mut inner = [(start, m0.net), (start, m0.net)];
    let mut step = first_step;
    loop {
        let mut brackets = Vec::new();
        for (side, sign) in [1.0, -1.0].into_iter().enumerate() {
            let beta = (start + sign * step).clamp(-SKEW_LIMIT, SKEW_LIMIT);
            if beta == inner[side].0 {
                continue;
            }
            let m = moment(beta);
            if balanced(&m) {
                return beta;
            }
            if m.net.abs() < best.1 {
                best = (beta, m.net.abs());
            }
            let point = (beta, m.net);
            if point.1 * inner[side].1 < 0.0 {
                brackets.push((inner[side], point));
            }
            inner[side] = point;
        }
        if let Some(&(a, b)) = brackets.iter().min_by(|x, y| {
            (secant_root(x.0, x.1) - start)
                .abs()
                .total_cmp(&(secant_root(y.0, y.1) - start).abs())
        }) {
            return narrowed(&mut moment, a, b, balanced);
        }
        if inner.iter().all(|p| p.0.abs() >= SKEW_LIMIT) {
            return best.0;
        }
        step *= 2.0;
    }
}

/// The root of the line through the points a and b.
fn secant_root(a: (f64, f64), b: (f64, f64)) -> f64 {
    b.0 - b.1 * (b.0 - a.0) / (b.1 - a.1)
}

/// The Illinois regula falsi on the sign change between the points `a` and `b` of `moment`.
fn narrowed(
    moment: &mut impl FnMut(f64) -> SpinMoment,
    a: (f64, f64),
    b: (f64, f64),
    balanced: impl Fn(&SpinMoment) -> bool,
) -> f64 {
    let (mut kept, mut latest) = (a, b);
    for _ in 0..SKEW_NARROWING {
        if (latest.0 - kept.0).abs() <= SKEW_TOLERANCE {
            break;
        }
        let x = secant_root(kept, latest);
        let m = moment(x);
        if balanced(&m) || m.net == 0.0 {
            return x;
        }
        let point = (x, m.net);
        kept = if point.1 * latest.1 < 0.0 {
            latest
        } else {
            (kept.0, 0.5 * kept.1)
        };
        latest = point;
    }
    if latest.1.abs() <= kept.1.abs() {
        latest.0
    } else {
        kept.0
    }
}

impl BearingSystem<'_> {
    /// The contacts of roller `i` a skew acts in: its races and flanges (its neighbours are
    /// the roller train's, [`super::roller_train`]).
    fn skew_elements(&self, i: usize) -> Vec<Element> {
        let z = self.layout.rollers;
        self.elements()
            .iter()
            .filter(|e| !matches!(e, Element::Pair(_)) && e.bodies(z)[1] == Body::Roller(i))
            .copied()
            .collect()
    }

    /// [`Self::skew_elements`] of roller `i` split into its race contacts and the rest (its
    /// flanges).
    fn skew_parts(&self, i: usize) -> (Vec<Element>, Vec<Element>) {
        self.skew_elements(i)
            .into_iter()
            .partition(|e| matches!(e, Element::Inner(_) | Element::Outer(_)))
    }

    /// Which rollers the flanges press hard enough to skew them: a roller's largest flange
    /// force at least [`SKEW_FLANGE_SHARE`] of the heaviest roller's race load, both from
    /// `results` (every contact at the equilibrium's positions, in the order of the model's
    /// elements).
    pub(super) fn pressed_by_flanges(&self, results: &[ElementResult]) -> Vec<bool> {
        let z = self.layout.rollers;
        let mut flange = vec![0.0f64; z];
        let mut heaviest = 0.0f64;
        for (e, r) in self.elements().iter().zip(results) {
            match *e {
                Element::End(i, _) => flange[i] = flange[i].max(r.normal),
                Element::Inner(_) | Element::Outer(_) => heaviest = heaviest.max(r.normal),
                Element::Pair(_) => {}
            }
        }
        flange
            .iter()
            .map(|f| *f > 0.0 && *f >= SKEW_FLANGE_SHARE * heaviest)
            .collect()
    }

    /// Roller i's moment [N m] about its radial direction `radial` from its `elements` and,
    /// with `drag`, the drag at `kin`, beside the sum of those parts' magnitudes.
    fn skew_moment(
        &self,
        kin: &BearingKinematics,
        i: usize,
        elements: &[Element],
        radial: &Vec3,
        drag: bool,
    ) -> SpinMoment {
        let mut moment = SpinMoment::default();
        if drag {
            moment.add(self.roller_drag(&kin.rollers[i]).moment.dot(radial));
        }
        for e in elements {
            let r: ElementResult = self.evaluate(e, kin);
            moment.add(r.on_b.moment.dot(radial));
        }
        moment
    }

    /// Each roller's skew [rad] ([`skew_root`] from `start`, one skew per roller, with the
    /// first step of a cold or a `warm` start; module doc), the rollers orbiting at `orbit`
    /// [rad/s] and spinning at `spins` [rad/s] about their axes at `kin`'s unskewed axes;
    /// `kin`'s rollers are left skewed by them (each axis turned about its radial
    /// direction), spinning about their new axes. Only the rollers marked in `pressed`
    /// ([`Self::pressed_by_flanges`]) are balanced; the others keep zero skew, the
    /// equilibrium's. In the search the roller's race contacts, whose moment hardly changes
    /// with skew (module doc), are taken on their line through the start (differenced over
    /// [`RACE_SKEW_STEP`]), its flanges and drag evaluated at every skew: the roots are
    /// exact where the skews have settled, as the rounds of [`super::statics`]' balance
    /// start each from the last. The rollers are searched apart (on the workspace's
    /// threads), each with the others at `kin`'s positions: a skew moves none of the other
    /// rollers' contacts.
    pub(super) fn balanced_skews(
        &self,
        kin: &mut BearingKinematics,
        orbit: f64,
        spins: &[f64],
        start: &[f64],
        warm: bool,
        pressed: &[bool],
    ) -> Vec<f64> {
        let frozen: &BearingKinematics = kin;
        let z = frozen.rollers.len();
        // roller i's moment at skew beta from `parts` (and the drag: `drag`)
        let moment_at = |trial: &mut BearingKinematics, i, beta, parts: &[Element], drag| {
            skew_roller(trial, frozen, i, beta, orbit, spins[i]);
            let radial = radial_direction(&frozen.rollers[i].center);
            self.skew_moment(trial, i, parts, &radial, drag)
        };
        let step = if warm {
            WARM_SKEW_STEP
        } else {
            FIRST_SKEW_STEP
        };
        let skews = self.map(z, |i| {
            if !pressed[i] {
                return 0.0;
            }
            let (races, rest) = self.skew_parts(i);
            let mut trial = frozen.clone();
            // the races on their line through the start
            let race = moment_at(&mut trial, i, start[i], &races, false).net;
            let shifted = moment_at(&mut trial, i, start[i] + RACE_SKEW_STEP, &races, false).net;
            let slope = (shifted - race) / RACE_SKEW_STEP;
            skew_root(start[i], step, |beta| {
                let mut m = moment_at(&mut trial, i, beta, &rest, true);
                m.add(race + slope * (beta - start[i]));
                m
            })
        });
        let unskewed = kin.clone();
        set_skews(kin, &unskewed, &skews, orbit, spins);
        skews
    }
}

/// The rollers of `kin` at the axes of `from` skewed by `skews` [rad] ([`skew_roller`]),
/// orbiting at `orbit` [rad/s] and spinning at `spins` [rad/s].
pub(super) fn set_skews(
    kin: &mut BearingKinematics,
    from: &BearingKinematics,
    skews: &[f64],
    orbit: f64,
    spins: &[f64],
) {
    for (i, beta) in skews.iter().enumerate() {
        skew_roller(kin, from, i, *beta, orbit, spins[i]);
    }
}

/// The unit vector from the bearing axis (x) towards `center`, across the axis.
pub(super) fn radial_direction(center: &Vec3) -> Vec3 {
    Vec3::new(0.0, center.y, center.z).normalize()
}

/// Sets roller i of `kin` to its axis in `from` turned by `beta` [rad] about its radial
/// direction, orbiting at `orbit` [rad/s] about x and spinning at `spin` [rad/s] about the
/// turned axis (skew as [`super::state::tilt_and_skew`] measures it: towards x × e_r).
pub(super) fn skew_roller(
    kin: &mut BearingKinematics,
    from: &BearingKinematics,
    i: usize,
    beta: f64,
    orbit: f64,
    spin: f64,
) {
    let k = &from.rollers[i];
    let radial = radial_direction(&k.center);
    // turning about e_r by −β takes x towards x × e_r by β (Rodrigues)
    let axis = Rotation3::from_axis_angle(&Unit::new_normalize(radial), -beta) * k.axis;
    kin.rollers[i].axis = axis;
    kin.rollers[i].omega = Vec3::new(orbit, 0.0, 0.0) + spin * axis;
}

#[cfg(test)]
mod tests {
    use super::*;

    fn moment(net: f64) -> SpinMoment {
        SpinMoment {
            net,
            gross: net.abs() + 1e-12,
        }
    }

    /// A linear moment with its root at 0.3 mrad, either slope: found to the tolerance.
    #[test]
    fn a_root_of_either_slope_is_found() {
        for slope in [-50.0, 50.0] {
            let beta = skew_root(0.0, FIRST_SKEW_STEP, |b| moment(slope * (b - 3e-4) * 1e-2));
            assert!((beta - 3e-4).abs() < 1e-8, "{beta}");
        }
    }

    /// Two roots, at −0.12 and +2 mrad: the one nearer zero.
    #[test]
    fn the_root_nearest_zero_is_taken() {
        let beta = skew_root(0.0, FIRST_SKEW_STEP, |b| {
            moment((b + 1.2e-4) * (b - 2e-3) * 1e3)
        });
        assert!((beta + 1.2e-4).abs() < 1e-8, "{beta}");
    }

    /// No root within the limit: the least |moment| met.
    #[test]
    fn without_a_root_the_least_moment_is_kept() {
        let beta = skew_root(0.0, FIRST_SKEW_STEP, |b| moment(1.0 + (b - 1e-3).powi(2)));
        assert!((beta - 1.28e-3).abs() < 1e-15, "{beta}");
    }

    /// B1 at 1000 N axially, 500 rpm (the quasi-static equilibrium, the spins balanced):
    /// every loaded roller's moment about its radial direction vanishes at the skew found
    /// (to [`SKEW_BALANCE`] of the moments that meet on it, or the skew known to twice
    /// [`SKEW_TOLERANCE`] by the moment's slope there), where at zero skew it was 0.07 N·m
    /// (measured on roller 0); the loaded rollers skew by −0.05 … −0.2 mrad, the dynamic
    /// model's range in B1's load zone (−0.08 … −0.13 mrad, docs/statics.md, "The rollers'
    /// skew"; the run itself is compared in the Python tests). Without axial load no
    /// flange presses a roller: no skew.
    #[test]
    fn the_flanges_friction_skews_the_loaded_rollers_and_the_moments_balance() {
        use crate::bearing::test_b1::{in_workspace, loaded_equilibrium, params, B1};
        use crate::bearing::BearingModel;
        let model = BearingModel::new(params(&B1)).unwrap();
        in_workspace(&model, |s| {
            // the state of steady rolling at the equilibrium with `axial` [N], spins
            // balanced, and its skews
            let steady = |axial: f64| {
                let (solution, loaded) = loaded_equilibrium(&s, axial);
                let mut kin = s.kinematics(1.288, &s.steady_state(&solution));
                let (orbit, rolling) = s.rolling_speeds(solution.case.speed, 0.0);
                let spins = s.balanced_spins(&mut kin, orbit, rolling, None);
                let unskewed = kin.clone();
                let pressed = s.pressed_by_flanges(&s.evaluate_all(&kin));
                let zero = vec![0.0; spins.len()];
                let skews = s.balanced_skews(&mut kin, orbit, &spins, &zero, false, &pressed);
                (unskewed, kin, orbit, spins, skews, loaded)
            };
            let (unskewed, kin, orbit, spins, skews, loaded) = steady(1000.0);
            assert!(loaded.len() >= 5, "{loaded:?}");
            let moment_at = |i: usize, beta: f64| {
                let mut k = unskewed.clone();
                skew_roller(&mut k, &unskewed, i, beta, orbit, spins[i]);
                let radial = radial_direction(&k.rollers[i].center);
                s.skew_moment(&k, i, &s.skew_elements(i), &radial, true)
            };
            let at_zero = moment_at(0, 0.0);
            assert!(at_zero.net.abs() > 0.03, "{at_zero:?}");
            for &i in &loaded {
                let beta = skews[i];
                assert!((-2e-4..-5e-5).contains(&beta), "roller {i}: {beta}");
                let (_, measured) = crate::bearing::state::tilt_and_skew(
                    &kin.rollers[i].center,
                    &kin.rollers[i].axis,
                );
                assert!((measured - beta).abs() < 1e-12, "roller {i}: {measured}");
                let m = moment_at(i, beta);
                let slope = (moment_at(i, beta + 1e-9).net - m.net) / 1e-9;
                assert!(
                    m.net.abs() <= SKEW_BALANCE * m.gross
                        || (m.net / slope).abs() <= 2.0 * SKEW_TOLERANCE,
                    "roller {i}: {m:?}, slope {slope}"
                );
            }
            let skews = steady(0.0).4;
            assert!(skews.iter().all(|b| *b == 0.0), "{skews:?}");
        });
    }
}
