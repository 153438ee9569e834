//! The ring's axial position searched apart, for a case whose axial load is light: the
//! last path of the quasi-static solver ([`super::solver`]).
//!
//! Under a light axial load (none, or a few newtons) the ring's axial position is held by
//! millinewtons or not at all: a misaligned raceway pushes the rollers and the ring apart
//! along the axis by the misalignment times the race loads (B1 at 5 kN: 0.87 N at 0.01°),
//! and until the rollers' ends meet a flange nothing holds that push. The ring and its rollers then slide together across their axial plays (about
//! 43 µm on B1), which Newton's steps, limited by the stiffness floor given to an unheld
//! direction, do not cross; or, where the rollers rest on the ring's own flanges, the
//! ring's axial position is free within the plays and the equilibrium is not unique.
//!
//! Here the ring's axial position x is prescribed and every other unknown solved
//! ([`Problem::solve_at_axial_position`]); the ring's unbalanced axial force R(x) is then a
//! non-increasing function of x (moving the ring along +x presses its −x flange against
//! the rollers and them against the outer ring's +x flange, whose reaction on the ring
//! points along −x), and its root is found by bracketing and the Illinois variant of
//! regula falsi (Dowell & Jarratt, BIT 11 (1971) 168), bisecting where that does not
//! shrink the bracket. Where R(x) vanishes over an interval (the unit floats within its
//! plays) any point of it is an equilibrium and the first one met is taken.

use super::solver::Problem;
use crate::error::{Error, Result};
use nalgebra::DVector;

/// The share of the radial load and the ring's weight up to which an axial load counts as
/// light: below it a misalignment's axial push (about the misalignment times the race
/// loads: 1.7e-3 of them at 0.1°) can balance or exceed it, and the search is tried where
/// the coupled solver fails.
const LIGHT_AXIAL_SHARE: f64 = 0.05;
/// The first step of the ring's axial position away from its start [m]; doubled until
/// the unbalanced axial force changes sign.
const FIRST_STEP: f64 = 1e-6;
/// Solves at a prescribed axial position before the search gives up: the doubling steps
/// of a bracket across B1's plays (about 7) and the regula falsi's (10–20 where the
/// root lies on a flange contact's steep rise).
const MAX_SOLVES: usize = 60;
/// Retries of a solve between the bracket's ends that finds no equilibrium
/// ([`Problem::end_near`]). One: where a roller end lies on its face (B1 at 0.1° and
/// 100 N) no position finds one near the root, and three retries only took the refusal
/// from 1.9 to 4.6 s.
const RETRIES: usize = 1;
/// The narrowest bracket of the ring's axial position [m]: a picometre, below which the
/// two ends' forces differ by the flange contact's stiffness times it.
const NARROWEST: f64 = 1e-12;

/// One end of the bracket: the axial position, the ring's unbalanced axial force there
/// and the unknowns of its equilibrium.
struct End {
    x: f64,
    force: f64,
    u: Vec<f64>,
}

/// The solves at a prescribed axial position so far and their Newton iterations.
#[derive(Default)]
struct Tally {
    solves: usize,
    iterations: usize,
}

impl Problem<'_> {
    /// Whether the case's axial load is light ([`LIGHT_AXIAL_SHARE`]).
    pub(super) fn axial_load_is_light(&self) -> bool {
        let p = &self.model.params;
        let weight = p.inner_ring_mass * p.gravity.norm();
        self.case.axial_load.abs() <= LIGHT_AXIAL_SHARE * (self.case.radial_load.abs() + weight)
    }

    /// The equilibrium with the ring's axial position searched apart (module doc): the
    /// unknowns, their residual (the ring's axial row included) and the Newton iterations
    /// taken over every solve. Fails where a solve at the start fails or no position
    /// balances the ring within [`MAX_SOLVES`] solves. The ring's axial position is an
    /// unknown again afterwards, whatever the outcome.
    pub(super) fn axial_search(&mut self) -> Result<(Vec<f64>, DVector<f64>, usize)> {
        let found = self.search_axial_position();
        self.axial_position = None;
        found
    }

    /// [`Self::axial_search`] with the ring's axial position left held where it ends.
    fn search_axial_position(&mut self) -> Result<(Vec<f64>, DVector<f64>, usize)> {
        let tolerance = self.tolerance();
        // From the centre of the plays: the guess's position past both plays, where an
        // axial load pushes the ring, overlaps a misaligned ring's flanges with the rollers
        // (B1 at 0.1°: by micrometres).
        let start_x = 0.0;
        let mut tally = Tally::default();
        let first = self.end_at(&mut tally, start_x, None)?;
        if first.force.abs() < tolerance {
            return self.released(first.u, tally.iterations);
        }
        // Step along the unbalanced force, doubling, until it changes sign.
        let direction = first.force.signum();
        let travel =
            4.0 * (self.model.params.inner_axial_play + self.model.params.outer_axial_play) + 10e-6;
        let (mut a, mut b): (End, Option<End>) = (first, None);
        let mut step = FIRST_STEP;
        while b.is_none() {
            let x = a.x + direction * step;
            if (x - start_x).abs() > travel || tally.solves >= MAX_SOLVES {
                return Err(self.unbalanced_axially(&a, tolerance));
            }
            match self.end_at(&mut tally, x, Some(&a)) {
                Ok(end) if end.force.abs() < tolerance => {
                    return self.released(end.u, tally.iterations)
                }
                Ok(end) if end.force.signum() != direction => b = Some(end),
                Ok(end) => {
                    a = end;
                    step *= 2.0;
                }
                // No equilibrium at x (the rollers pressed too deep): bisect towards it.
                Err(_) => step *= 0.5,
            }
            if step < NARROWEST {
                return Err(self.unbalanced_axially(&a, tolerance));
            }
        }
        let mut b = b.expect("bracketed");
        // Illinois: where the same end is replaced twice in a row, the other one's force
        // is halved in the secant (again each time it stays).
        let (mut weight_a, mut weight_b) = (1.0, 1.0);
        let mut a_replaced_last: Option<bool> = None;
        while tally.solves < MAX_SOLVES && (b.x - a.x).abs() > NARROWEST {
            let (fa, fb) = (weight_a * a.force, weight_b * b.force);
            let secant = a.x - fa * (b.x - a.x) / (fb - fa);
            let inside = secant.is_finite() && (secant - a.x) * (secant - b.x) < 0.0;
            // Every third solve bisects: a flange contact's steep rise beside a plateau
            // of R makes regula falsi creep even so.
            let x = if inside && tally.solves % 3 != 0 {
                secant
            } else {
                0.5 * (a.x + b.x)
            };
            let from = if (x - a.x).abs() < (x - b.x).abs() {
                &a
            } else {
                &b
            };
            let end = self.end_near(&mut tally, x, from)?;
            if end.force.abs() < tolerance {
                return self.released(end.u, tally.iterations);
            }
            let replaces_a = end.force.signum() == a.force.signum();
            if replaces_a {
                a = end;
                weight_a = 1.0;
                if a_replaced_last == Some(true) {
                    weight_b *= 0.5;
                }
            } else {
                b = end;
                weight_b = 1.0;
                if a_replaced_last == Some(false) {
                    weight_a *= 0.5;
                }
            }
            a_replaced_last = Some(replaces_a);
        }
        let nearer = if a.force.abs() < b.force.abs() { a } else { b };
        Err(self.unbalanced_axially(&nearer, tolerance))
    }

    /// The bracket's end at `x` ([`Self::solve_at_axial_position`]), counted in `tally`.
    fn end_at(&mut self, tally: &mut Tally, x: f64, from: Option<&End>) -> Result<End> {
        tally.solves += 1;
        let (u, r, taken) = self.solve_at_axial_position(x, from.map(|e| e.u.as_slice()))?;
        tally.iterations += taken;
        Ok(End { x, force: r[0], u })
    }

    /// The bracket's end at `x` from the end `from`, or where that finds none, from the
    /// guess, or nearer to `from` ([`RETRIES`] times halving the way).
    fn end_near(&mut self, tally: &mut Tally, x: f64, from: &End) -> Result<End> {
        let mut x = x;
        let mut last = self.end_at(tally, x, Some(from));
        for _ in 0..RETRIES {
            if last.is_ok() {
                break;
            }
            last = self.end_at(tally, x, None);
            if last.is_ok() {
                break;
            }
            x = 0.5 * (x + from.x);
            last = self.end_at(tally, x, Some(from));
        }
        last
    }

    /// The equilibrium of every unknown but the ring's axial position, held at `x`: from
    /// `from` (another position's equilibrium) or from the guess. Each solve has the fast
    /// path's whole budget.
    fn solve_at_axial_position(
        &mut self,
        x: f64,
        from: Option<&[f64]>,
    ) -> Result<(Vec<f64>, DVector<f64>, usize)> {
        self.axial_position = Some(x);
        self.careful = false;
        self.evaluations = 0;
        self.roller_jacobians.iter_mut().for_each(|j| *j = None);
        let start = from.map(|u| {
            let mut u = u.to_vec();
            u[0] = x;
            u
        });
        self.solve_by_both_paths(start)
    }

    /// The equilibrium found with the ring's axial position released again: its residual
    /// over every unknown.
    fn released(
        &mut self,
        u: Vec<f64>,
        iterations: usize,
    ) -> Result<(Vec<f64>, DVector<f64>, usize)> {
        self.axial_position = None;
        let forces = self.evaluate(&u, false);
        let r = self.residual(&u, &forces);
        Ok((u, r, iterations))
    }

    /// The error of a search that found no axial position balancing the ring: the
    /// position nearest to it and the force left there.
    fn unbalanced_axially(&mut self, nearest: &End, tolerance: f64) -> Error {
        self.axial_position = None;
        Error::invalid(
            "load",
            self.case.describe(),
            format!(
                "no quasi-static equilibrium: with the inner ring's axial position searched \
                 apart, the nearest found leaves {:.3e} N along the axis at {:.2} um \
                 (tolerance {tolerance:.1e} N)",
                nearest.force,
                nearest.x * 1e6
            ),
        )
    }
}
