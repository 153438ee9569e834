//! The roller train of a full-complement bearing in steady rolling (not in the paper): the
//! forces between neighbouring rollers, which the quasi-static equilibrium does not hold.
//!
//! The equilibrium ([`super::quasi_static`]) holds each roller at its azimuth and balances
//! its forces across the orbit and along the axis, never along it. Along the orbit a
//! roller is pushed by the field it stands in (gravity, a planet carrier's centrifugal
//! field) and the drag, and without a cage only its neighbours and its grip on the races
//! can take the push. A roller pinched between both races takes a push by slipping on
//! both, in the linear part of the traction curve in proportion to its load; when the
//! field stacks the rollers into one train that orbits at one speed, the races take the
//! pushes' sum in proportion to the rollers' loads, and the rest presses the rollers
//! against each other like beads on a ring: each roller is in equilibrium along its orbit,
//!
//! > P_{j−1} − P_j + F_j − g_j·ΣF = 0,  P_j ≥ 0,
//!
//! with P_j the compressive force between rollers j and j + 1, F_j the push on roller j
//! along increasing azimuth and g_j its share of the grip, and the train leaves its slack
//! (a full complement's rollers do not fill the pitch circle) where the pushes part:
//! P_j = S_j − min_k S_k with S_j the yielded pushes summed around the ring
//! ([`chain_forces`]), the least compressive forces that balance every roller, as for any
//! chain of rigid bodies with unilateral contacts.
//!
//! B1 in a planet carrier's field of 400 g stacks so in the dynamic model too, the loaded
//! rollers included (docs/statics.md, "The roller train"); under gravity alone it does
//! not, and the statics leave the train out there
//! ([`super::statics`]' `TRAIN_FIELD`).

use super::contacts::Geometry;
use super::state::{BearingKinematics, Kinematics};
use super::statics::SpinMoment;
use super::topology::{Element, LineContact};
use super::workspace::BearingSystem;
use crate::geometry::primitives::Vec3;
use std::f64::consts::TAU;

/// The compressive force [N] between roller i and roller i + 1 (mod z) of a roller train
/// (module doc): `push[i]` is the force on roller i along its orbit (increasing azimuth)
/// [N], `grip[i]` its grip on the races (any measure ≥ 0: the share of the pushes' sum
/// its races take is its share of the grip; evenly where no roller grips).
///
/// With the yielded pushes y_j = F_j − g_j·ΣF summed from roller 0, S_j = y_0 + … + y_j,
/// P_j = S_j − min_k S_k: every roller is in equilibrium along its orbit, every contact is
/// compressive, and the slack sits at the pair where S is least (P = 0).
pub fn chain_forces(push: &[f64], grip: &[f64]) -> Vec<f64> {
    let z = push.len();
    assert_eq!(grip.len(), z, "one grip per roller");
    if z < 2 {
        return vec![0.0; z];
    }
    let total: f64 = push.iter().sum();
    let gripped: f64 = grip.iter().sum();
    let mut sums = Vec::with_capacity(z);
    let mut s = 0.0;
    for (p, g) in push.iter().zip(grip) {
        let share = if gripped > 0.0 {
            g / gripped
        } else {
            1.0 / z as f64
        };
        s += p - share * total;
        sums.push(s);
    }
    let least = sums.iter().copied().fold(f64::INFINITY, f64::min);
    sums.iter().map(|s| s - least).collect()
}

/// One roller–roller contact of the train, where the train presses it
/// ([`BearingSystem::train_contacts`]).
pub struct TrainContact {
    /// The pair: roller `pair` and roller `pair` + 1 (mod z).
    pub pair: usize,
    /// The force the train puts on it [N] ([`chain_forces`]).
    pub force: f64,
    /// The turn of roller `pair` + 1 about the bearing axis [rad] at which the pair's
    /// normal force is `force`.
    pub turn: f64,
    /// The bearing with roller `pair` + 1 turned by [`Self::turn`]; the two rollers' angular
    /// velocities are set before each evaluation ([`Self::spin_as`], [`Self::spin_at`]).
    pub pressed: BearingKinematics,
    /// The pair's geometry at `pressed` (positions only).
    pub(super) geometry: Geometry,
}

impl TrainContact {
    /// The pair's two rollers, `pair` and `pair` + 1.
    fn rollers(&self) -> [usize; 2] {
        [self.pair, (self.pair + 1) % self.pressed.rollers.len()]
    }

    /// The two rollers spinning as in `kin` (roller `pair` + 1's angular velocity turned
    /// with it).
    pub fn spin_as(&mut self, kin: &BearingKinematics) {
        let [i, j] = self.rollers();
        self.pressed.rollers[i].omega = kin.rollers[i].omega;
        self.pressed.rollers[j].omega = turned(&kin.rollers[j], self.turn).omega;
    }

    /// Roller `body` of the pair orbiting at `orbit` [rad/s] about the bearing axis and
    /// spinning at `spin` [rad/s] about its own axis.
    pub fn spin_at(&mut self, body: usize, orbit: f64, spin: f64) {
        let k = &mut self.pressed.rollers[body];
        k.omega = Vec3::new(orbit, 0.0, 0.0) + spin * k.axis;
    }
}

/// The relative tolerance of a train contact's normal force ([`BearingSystem::train_contacts`]).
const TRAIN_FORCE_TOLERANCE: f64 = 1e-2;

impl BearingSystem<'_> {
    /// The pushes along the orbit [N] on each roller of `kin` that only its neighbours can
    /// take ([`chain_forces`]): the field `field` [m/s²] on its mass (gravity and a planet
    /// carrier's centrifugal field at the bearing's axis; the field's part across the axis at
    /// the roller, its orbit's centrifugal and Coriolis forces, is radial) and the drag of the
    /// oil–air mixture, each along t = x × e_r, the direction of increasing azimuth. The
    /// contacts' own tangential forces are each roller's races' to balance (its orbital
    /// slip, which the quasi-static model does not resolve).
    pub fn train_pushes(&self, kin: &BearingKinematics, field: &Vec3) -> Vec<f64> {
        let m = self.roller_mass.mass;
        kin.rollers
            .iter()
            .map(|k| {
                let tangential = Vec3::x().cross(&Vec3::new(0.0, k.center.y, k.center.z));
                let t = tangential / tangential.norm();
                (m * field + self.roller_drag(k).force).dot(&t)
            })
            .collect()
    }

    /// The roller train's forces ([`chain_forces`]) of the steady rolling at `kin` in the
    /// field `field` [m/s²]: the pushes of [`Self::train_pushes`], their sum taken by the
    /// races in proportion to each roller's lighter race load `race_loads` [N], its grip.
    pub fn train_forces(
        &self,
        kin: &BearingKinematics,
        field: &Vec3,
        race_loads: &[f64],
    ) -> Vec<f64> {
        chain_forces(&self.train_pushes(kin, field), race_loads)
    }

    /// Each pair of `forces` ([`Self::train_forces`]) that carries a force, evaluated by the
    /// roller–roller law with roller i + 1 turned about the bearing axis (its centre,
    /// axis, velocity and angular velocity alike, so that the pair neither approaches nor
    /// changes its races' or flanges' contacts) until the pair's normal force (the film's
    /// included) is the train's, to [`TRAIN_FORCE_TOLERANCE`]: the rest of the bearing
    /// stays at the equilibrium's positions, a few micrometres from where the train would
    /// put it.
    pub fn train_contacts(&self, kin: &BearingKinematics, forces: &[f64]) -> Vec<TrainContact> {
        let z = kin.rollers.len();
        (0..z)
            .filter(|&i| forces[i] > 0.0)
            .filter_map(|i| self.train_contact(kin, i, forces[i]))
            .collect()
    }

    /// [`Self::train_contacts`] of one pair (None where no turn of roller i + 1 within a
    /// roller radius gives the force).
    fn train_contact(&self, kin: &BearingKinematics, i: usize, force: f64) -> Option<TrainContact> {
        let mut press = Press::new(self, kin, i, force);
        let bracket = press.bracket()?;
        let turn = press.solve(bracket);
        let j = press.j;
        let mut pressed = press.local;
        pressed.rollers[j] = turned(&kin.rollers[j], turn);
        Some(TrainContact {
            pair: i,
            force,
            turn,
            geometry: self.geometry(&Element::Pair(i), &pressed),
            pressed,
        })
    }
}

/// The search of the turn of roller j = i + 1 about the bearing axis at which the pair
/// (i, j) carries `force` ([`BearingSystem::train_contact`]).
struct Press<'s, 'm> {
    system: &'s BearingSystem<'m>,
    kin: &'s BearingKinematics,
    i: usize,
    j: usize,
    force: f64,
    /// The bearing with roller j at the turn last tried.
    local: BearingKinematics,
    /// k₂ of the pair's eq. 11.
    k2: f64,
    /// Roller j's radius from the bearing axis [m].
    radius: f64,
}

/// (turn [rad], the normal force there to the power k₂ less the force's) of a bracket side.
type Side = (f64, f64);

impl<'s, 'm> Press<'s, 'm> {
    fn new(
        system: &'s BearingSystem<'m>,
        kin: &'s BearingKinematics,
        i: usize,
        force: f64,
    ) -> Self {
        let j = (i + 1) % kin.rollers.len();
        Self {
            system,
            kin,
            i,
            j,
            force,
            local: kin.clone(),
            k2: system.lines.kind(LineContact::RollerRoller).law.k2,
            radius: kin.rollers[j].center.y.hypot(kin.rollers[j].center.z),
        }
    }

    /// The pair's normal force with roller j turned by `turn`, to the power k₂ of eq. 11
    /// less the force's (nearly linear in the turn where the slices carry it, δ ∝ F^k₂),
    /// beside the normal force [N].
    fn miss(&mut self, turn: f64) -> (f64, f64) {
        self.local.rollers[self.j] = turned(&self.kin.rollers[self.j], turn);
        let normal = self
            .system
            .evaluate(&Element::Pair(self.i), &self.local)
            .normal;
        (
            normal.max(0.0).powf(self.k2) - self.force.powf(self.k2),
            normal,
        )
    }

    /// The turn at which the centres are a diameter apart, and twice the turn at which
    /// eq. 11 alone would carry the force on aligned straight rollers (δ over
    /// dd/dφ = r_i r_j sin φ / d): the search's start and first step.
    fn start(&self) -> (f64, f64) {
        let (a, b) = (
            &self.kin.rollers[self.i].center,
            &self.kin.rollers[self.j].center,
        );
        let ri = a.y.hypot(a.z);
        let rj = self.radius;
        let d = 2.0 * self.system.params.roller.radius;
        let spacing = (b.z.atan2(b.y) - a.z.atan2(a.y)).rem_euclid(TAU);
        let touching = ((ri * ri + rj * rj - d * d) / (2.0 * ri * rj))
            .clamp(-1.0, 1.0)
            .acos();
        let lines = &self.system.lines;
        let law = lines.kind(LineContact::RollerRoller).law;
        let deflection = law.deflection(self.force, lines.slices.len() as f64 * lines.slice_length);
        let guess = deflection * d / (ri * rj * touching.sin());
        let step = if guess.is_finite() && guess > 0.0 {
            2.0 * guess
        } else {
            1e-9 / ri
        };
        (touching - spacing, step)
    }

    /// Turns on either side of the force: (apart, pressed). From where the centres are a
    /// diameter apart, inwards (a negative turn, towards roller i) by doubling steps until
    /// the pair carries the force, or outwards on the film's scale (a tenth of a micrometre
    /// and more: across the gap Martin's load, ∝ 1/h, carries light forces) until it no
    /// longer does. None past a roller radius.
    fn bracket(&mut self) -> Option<(Side, Side)> {
        let (touching, mut step) = self.start();
        let limit = self.system.params.roller.radius / self.radius;
        let mut apart = (touching, self.miss(touching).0);
        if apart.1 <= 0.0 {
            let mut pressed = apart;
            while pressed.1 < 0.0 {
                apart = pressed;
                let turn = pressed.0 - step;
                pressed = (turn, self.miss(turn).0);
                step *= 2.0;
                if step > limit {
                    return None;
                }
            }
            return Some((apart, pressed));
        }
        let mut back = step.max(1e-7 / self.radius);
        let mut pressed = apart;
        while apart.1 > 0.0 {
            pressed = apart;
            let turn = apart.0 + back;
            apart = (turn, self.miss(turn).0);
            back *= 4.0;
            if back > limit {
                return None;
            }
        }
        Some((apart, pressed))
    }

    /// The turn at which the pair carries the force to [`TRAIN_FORCE_TOLERANCE`]: Illinois'
    /// regula falsi (Dowell & Jarratt 1971) on the bracket, every third step a bisection
    /// (where the film gives way to the slices within nanometres the force is a wall, and
    /// the regula falsi alone creeps along its foot).
    fn solve(&mut self, (mut apart, mut pressed): (Side, Side)) -> f64 {
        let mut turn = pressed.0;
        let mut side = 0;
        for n in 0..100 {
            if pressed.1 == apart.1 {
                break; // a side carries the force exactly
            }
            turn = if n % 3 == 2 {
                0.5 * (pressed.0 + apart.0)
            } else {
                pressed.0 - pressed.1 * (pressed.0 - apart.0) / (pressed.1 - apart.1)
            };
            let (miss, normal) = self.miss(turn);
            if (normal - self.force).abs() <= TRAIN_FORCE_TOLERANCE * self.force {
                break;
            }
            if miss < 0.0 {
                apart = (turn, miss);
                if side < 0 {
                    pressed.1 *= 0.5;
                }
                side = -1;
            } else {
                pressed = (turn, miss);
                if side > 0 {
                    apart.1 *= 0.5;
                }
                side = 1;
            }
        }
        turn
    }
}

impl BearingSystem<'_> {
    /// The power the roller train's contacts `train` take [W], their rollers spinning as in
    /// `kin`.
    pub fn train_power(&self, kin: &BearingKinematics, train: &mut [TrainContact]) -> f64 {
        let z = kin.rollers.len();
        train
            .iter_mut()
            .map(|c| {
                c.spin_as(kin);
                let element = Element::Pair(c.pair);
                let [a, b] = element.bodies(z);
                self.evaluate_at(&element, &c.pressed, &c.geometry)
                    .power_loss(c.pressed.of(a), c.pressed.of(b), &c.pressed.outer_ring)
            })
            .fold(0.0, |total, power| total + power) // 0 W, not −0 W, without a train
    }

    /// The moments about their axes [N m] that the roller train's contacts `train` put on
    /// the rollers marked `active` (the others' are 0), each pair's moment on a roller taken
    /// with that roller spinning at its spin in `spins` and its neighbour at its spin in
    /// `neighbours` [rad/s] about their axes, both orbiting at `orbit` [rad/s].
    pub(crate) fn train_moments(
        &self,
        train: &mut [TrainContact],
        orbit: f64,
        spins: &[f64],
        neighbours: &[f64],
        active: &[bool],
    ) -> Vec<SpinMoment> {
        let mut moments = vec![SpinMoment::default(); spins.len()];
        for c in train.iter_mut() {
            let [i, j] = c.rollers();
            for (roller, other) in [(i, j), (j, i)].into_iter().filter(|p| active[p.0]) {
                c.spin_at(roller, orbit, spins[roller]);
                c.spin_at(other, orbit, neighbours[other]);
                let r = self.evaluate_at(&Element::Pair(c.pair), &c.pressed, &c.geometry);
                let on = if roller == i { r.on_a } else { r.on_b };
                moments[roller].add(on.moment.dot(&c.pressed.rollers[roller].axis));
            }
        }
        moments
    }
}

/// `k` turned by `angle` [rad] about the bearing axis (x): its centre, axis, velocity and
/// angular velocity.
fn turned(k: &Kinematics, angle: f64) -> Kinematics {
    let (s, c) = angle.sin_cos();
    let turn = |v: &Vec3| Vec3::new(v.x, c * v.y - s * v.z, s * v.y + c * v.z);
    Kinematics {
        center: turn(&k.center),
        axis: turn(&k.axis),
        velocity: turn(&k.velocity),
        omega: turn(&k.omega),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The net force along its orbit on roller i: its push, its two neighbours' and its
    /// races' share of the pushes' sum.
    fn unbalanced(push: &[f64], grip: &[f64], pairs: &[f64], i: usize) -> f64 {
        let z = push.len();
        let total: f64 = push.iter().sum();
        let gripped: f64 = grip.iter().sum();
        let share = if gripped > 0.0 {
            grip[i] / gripped
        } else {
            1.0 / z as f64
        };
        pairs[(i + z - 1) % z] - pairs[i] + push[i] - share * total
    }

    #[test]
    fn a_stack_pushed_towards_one_gripping_roller_carries_the_sum_of_the_pushes() {
        // Roller 0 grips; rollers 1, 2, 3 are pushed back towards it (against the
        // azimuth) by 1, 2 and 3 N, which its races take: the pair (0, 1) carries all 6 N,
        // (1, 2) 5 N, (2, 3) 3 N, and the slack opens between roller 3 and roller 0.
        let pairs = chain_forces(&[0.0, -1.0, -2.0, -3.0], &[1.0, 0.0, 0.0, 0.0]);
        assert_eq!(pairs, vec![6.0, 5.0, 3.0, 0.0]);
    }

    #[test]
    fn a_field_across_the_ring_stacks_the_rollers_towards_the_bottom() {
        // Six rollers at 60° from the top (roller 0) in a field along −y: pushes
        // m·a·sin ψ, 0 at the top and the bottom; the sum is 0, so the races take nothing,
        // the slack opens at the top and the bottom pairs carry one side's pushes.
        let s = 3f64.sqrt() / 2.0;
        let push = [0.0, s, s, 0.0, -s, -s];
        let pairs = chain_forces(&push, &[1.0; 6]);
        let expected = [0.0, s, 2.0 * s, 2.0 * s, s, 0.0];
        for (p, e) in pairs.iter().zip(expected) {
            assert!((p - e).abs() < 1e-12, "{pairs:?}");
        }
    }

    /// B1 as a planet bearing (the outer ring at 500 rpm on a still pin, a carrier at
    /// 3000 rpm with the bearing 40 mm from its axis: a field of 3 948 m/s² along −y, with
    /// gravity's 9.81, 402 g): the field pushes roller k along its orbit by m·a·sin ψ_k,
    /// both halves of the ring towards the bottom, where the load zone is, and the sum is 0,
    /// so the pairs at the bottom carry one half's pushes, Σ m·a·|sin ψ_k| over the eight
    /// rollers between the bottom and the top (13.06 N). The drag and the free rollers'
    /// friction on their races add to it: within 0.5 % (measured 0.04 %). Each pair,
    /// pressed where it carries its force, carries it within the search's tolerance, and
    /// the train's friction power is that of the neighbours' sliding at the sum of their
    /// surface speeds, under the boundary friction's μ_B0 times their forces (the mixed
    /// friction stays below it).
    #[test]
    fn a_planet_carriers_field_stacks_the_rollers_with_one_halfs_pushes_at_the_bottom() {
        use crate::bearing::quasi_static::StaticCase;
        use crate::bearing::test_b1::{in_workspace, params, B1};
        use crate::bearing::{BearingModel, Carrier, History};
        let mut p = params(&B1);
        p.inner_ring_speed = History::constant(0.0);
        p.outer_ring_speed = History::constant(500.0 * std::f64::consts::PI / 30.0);
        let w = 3000.0 * std::f64::consts::PI / 30.0;
        p.carrier = Carrier {
            speed: History::constant(w),
            offset: Vec3::new(0.0, -0.04, 0.0),
        };
        let model = BearingModel::new(p).unwrap();
        in_workspace(&model, |s| {
            let case = StaticCase::at_time(&s.params, 1.0);
            let solution = s.statics(&case, None).expect("an equilibrium");
            let friction = s.steady_rolling_friction(&solution, None);
            let z = solution.rollers.len();
            let a = (case.roller_field(&s.params)).norm();
            let m = s.roller_mass.mass;
            let half: f64 = (1..=z / 2)
                .map(|k| m * a * solution.rollers[k].azimuth.sin().abs())
                .sum();
            assert!((12.9..13.2).contains(&half), "{half}");
            let largest = friction.pair_forces.iter().copied().fold(0.0, f64::max);
            assert!(
                (largest / half - 1.0).abs() < 5e-3,
                "{largest} N against {half} N"
            );
            for k in [0, z - 1] {
                let f = friction.pair_forces[k];
                assert!((f / half - 1.0).abs() < 5e-3, "pair {k}: {f} N");
            }
            // every pair pressed where it carries its force
            let y = s.steady_state(&solution);
            let kin = s.kinematics(1.0, &y);
            let train = s.train_contacts(&kin, &friction.pair_forces);
            assert_eq!(train.len(), z - 1, "all pairs but the slack's");
            for c in &train {
                let normal = s.evaluate(&Element::Pair(c.pair), &c.pressed).normal;
                assert!(
                    (normal / c.force - 1.0).abs() <= TRAIN_FORCE_TOLERANCE,
                    "{normal}"
                );
            }
            // the pairs' friction: positive, and at most μ_B0 times each pair's force at
            // the sum of the loaded rollers' surface speeds relative to the roller set
            let r = s.params.roller.radius;
            let (_, rolling) = s.rolling_speeds(case.speed, case.outer_speed);
            let bound: f64 = friction
                .pair_forces
                .iter()
                .map(|f| 0.1 * f * 2.0 * rolling.abs() * r * 1.05)
                .sum();
            assert!(
                friction.roller_pairs > 0.2 * bound && friction.roller_pairs < bound,
                "{} W against at most {bound} W",
                friction.roller_pairs
            );
        });
    }

    #[test]
    fn a_single_roller_carries_nothing() {
        assert_eq!(chain_forces(&[5.0], &[0.0]), vec![0.0]);
    }

    proptest! {
        /// Any pushes and grips: every contact is compressive, every roller is in
        /// equilibrium along its orbit with its races' share of the pushes' sum, and the
        /// train has its slack somewhere (a pair at 0 N): the least forces that balance it.
        #[test]
        fn every_roller_balances_with_compressive_contacts_and_slack(
            push in proptest::collection::vec(-10.0..10.0f64, 2..30),
            grip in proptest::collection::vec(prop_oneof![Just(0.0), 0.0..1000.0f64], 30),
        ) {
            let z = push.len();
            let grip = &grip[..z];
            let pairs = chain_forces(&push, grip);
            prop_assert!(pairs.iter().all(|p| *p >= 0.0));
            prop_assert!(pairs.contains(&0.0));
            for i in 0..z {
                prop_assert!(unbalanced(&push, grip, &pairs, i).abs() < 1e-9, "roller {i}");
            }
        }
    }
}
