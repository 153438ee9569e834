//! Roller end–flange contact detection in the bearing (paper sect. 2): the roller ends and
//! the flanges posed at the bodies' kinematics, and the composite contact of the six
//! pairings (fig. 1) by the configured detector ([`Detector`]):
//!
//! * semi-analytical (sect. 2.1), with the conservative pruning of sect. 5.3 if enabled;
//! * Koch's gradient method (sect. 2.2), warm-started from the last good solution of each
//!   roller end and flange (`WarmStarts`), retried from the cold start, and falling back
//!   to the semi-analytical solution of a pairing it cannot solve (counted in
//!   [`super::profile::Profile::gradient_fallbacks`]);
//! * the mesh baseline (parry3d).
//!
//! The detected contact's curvature is blended across patch borders ([`border::blend`]) so
//! that the force is continuous in the pose.

use super::params::{BearingParams, Detector, FlangeLaw};
use super::state::Kinematics;
use super::topology::{end_slot, flange_side};
use crate::bearing::workspace::BearingSystem;
use crate::contact::distributed::{self, Asperities, DistributedOverlap, SupportFrame};
use crate::contact::gradient::{self, Unknowns};
use crate::contact::mesh::{MeshDetector, MeshResolution};
use crate::contact::pruning;
use crate::contact::{border, deepest, semi_analytical, Contact};
use crate::geometry::end_flange::{Flange, FlangePlacement, RollerEnd};
use crate::tribology::foundation;
use std::sync::{Mutex, MutexGuard, PoisonError};

/// The gradient detector's warm starts: the last good unknowns of each of the six
/// pairings, one slot per roller end and flange ([`end_slot`]).
#[derive(Debug)]
pub(super) struct WarmStarts(Vec<Mutex<[Option<Unknowns>; 6]>>);

impl WarmStarts {
    /// No warm starts, for a bearing of `rollers` rollers.
    pub(super) fn new(rollers: usize) -> Self {
        Self((0..4 * rollers).map(|_| Mutex::new([None; 6])).collect())
    }

    /// The warm starts of roller i's end against flange k.
    fn slot(&self, roller: usize, flange: usize) -> MutexGuard<'_, [Option<Unknowns>; 6]> {
        self.0[end_slot(roller, flange)]
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
    }

    /// Forgets every warm start.
    pub(super) fn clear(&self) {
        for slot in &self.0 {
            *slot.lock().unwrap_or_else(PoisonError::into_inner) = [None; 6];
        }
    }
}

/// The distributed flange law's support frames ([`SupportFrame`]) that the evaluations of
/// a step start from, one slot per roller end and flange ([`end_slot`]): those the latest
/// evaluation of the step before found, taken when it was accepted
/// (`BearingSystem::take_support_frames`). Every evaluation within a step reads the same
/// frames, so a step's right-hand sides and Jacobian columns are one smooth function of
/// the state, whatever the threads; the frames follow the contacts from step to step.
#[derive(Debug)]
pub(super) struct SupportFrames(Vec<Mutex<Option<SupportFrame>>>);

impl SupportFrames {
    /// No frames, for a bearing of `rollers` rollers.
    pub(super) fn new(rollers: usize) -> Self {
        Self((0..4 * rollers).map(|_| Mutex::new(None)).collect())
    }

    fn lock(&self, slot: usize) -> MutexGuard<'_, Option<SupportFrame>> {
        self.0[slot].lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// The frame of roller i's end against flange k.
    fn get(&self, roller: usize, flange: usize) -> Option<SupportFrame> {
        *self.lock(end_slot(roller, flange))
    }

    /// Sets the frame of roller i's end against flange k.
    pub(super) fn set(&self, roller: usize, flange: usize, frame: Option<SupportFrame>) {
        *self.lock(end_slot(roller, flange)) = frame;
    }

    /// Forgets every frame.
    pub(super) fn clear(&self) {
        for slot in 0..self.0.len() {
            *self.lock(slot) = None;
        }
    }
}

/// The position-dependent part of a roller end–flange contact (`BearingSystem::end_geometry`).
#[derive(Debug, Clone, Copy)]
pub struct EndGeometry {
    /// The detected contact (None: no valid pairing).
    pub contact: Option<Contact>,
    /// The whole overlap (distributed flange law, overlapping contacts only).
    pub overlap: Option<DistributedOverlap>,
    /// The flange's Winkler modulus for the overlap [Pa/m].
    pub foundation_modulus: f64,
    /// The overlap's support frame, for the next step's evaluations to start from.
    pub support_frame: Option<SupportFrame>,
}

impl BearingSystem<'_> {
    /// The end of `roller` that faces flange k.
    pub(super) fn roller_end(&self, k: usize, roller: &Kinematics) -> RollerEnd {
        RollerEnd::new(
            &self.params.roller,
            roller.center,
            flange_side(k) * roller.axis,
        )
    }

    /// The flange k of a ring body at its current pose.
    pub(super) fn flange(&self, k: usize, ring: &Kinematics) -> Flange {
        flange_of(&self.params, k, ring)
    }

    /// The detected contact of roller i's `end` against flange k (`flange`) with its
    /// curvature blended across patch borders ([`border::blend`]), so that the force is
    /// continuous in the pose.
    pub(super) fn end_contact(
        &self,
        end: &RollerEnd,
        flange: &Flange,
        roller: usize,
        k: usize,
    ) -> Option<Contact> {
        if !self.params.flanges[k] {
            return None; // a ring without this flange (BearingParams::flanges)
        }
        self.detect(end, flange, roller, k)
            .map(|c| border::blend(&c, end, flange, &self.params.options.border_bands))
    }

    /// The position-dependent part of roller i's end against flange k: the detected contact
    /// ([`Self::end_contact`]) and, with the distributed flange law, its whole overlap
    /// ([`distributed::integrate_near`], from the step's support frame) when the detected
    /// contact overlaps.
    pub(super) fn end_geometry(
        &self,
        end: &RollerEnd,
        flange: &Flange,
        roller: usize,
        k: usize,
    ) -> EndGeometry {
        let contact = self.end_contact(end, flange, roller, k);
        let found = match (self.params.flange_law, &contact) {
            (FlangeLaw::Distributed, Some(c)) => {
                let start = self.workspace.profiler.stopwatch();
                let near = self.workspace.support_frames.get(roller, k);
                let found = self.overlap_near(end, flange, c, false, near.as_ref());
                self.workspace
                    .profiler
                    .spend_time(start, |pr, t| pr.detection += t);
                found
            }
            _ => None,
        };
        EndGeometry {
            contact,
            overlap: found.map(|(overlap, _)| overlap),
            foundation_modulus: self.foundation_modulus[usize::from(k >= 2)],
            support_frame: found.map(|(_, frame)| frame),
        }
    }

    /// The whole overlap of `end` on `flange` ([`distributed::integrate`], with the energy
    /// integral if `energy`) from the detected contact `c`, when `c` lies within the
    /// asperities' reach (None beyond it, or where nothing is carried): the one place the
    /// run, its energy check and the statics take the distributed law's overlap from.
    pub(crate) fn overlap(
        &self,
        end: &RollerEnd,
        flange: &Flange,
        c: &Contact,
        energy: bool,
    ) -> Option<DistributedOverlap> {
        self.overlap_near(end, flange, c, energy, None)
            .map(|(overlap, _)| overlap)
    }

    /// [`Self::overlap`] from the support frame `near` of a nearby pose
    /// ([`distributed::integrate_near`]), and the frame for the next.
    fn overlap_near(
        &self,
        end: &RollerEnd,
        flange: &Flange,
        c: &Contact,
        energy: bool,
        near: Option<&SupportFrame>,
    ) -> Option<(DistributedOverlap, SupportFrame)> {
        let asperities = self.asperities();
        // (a NaN penetration, no contact found, compares false: nothing carried)
        (c.penetration > -asperities.reach())
            .then(|| distributed::integrate_near(end, flange, &c.p1, asperities, energy, near))
            .flatten()
    }

    /// The roughness of the roller ends and flanges as the distributed law sees it.
    pub(super) fn asperities(&self) -> Asperities {
        Asperities {
            sigma: self.params.flange_surface.roughness,
        }
    }

    /// The elastic energy of roller i's end (`roller`) on flange k of `ring` under the
    /// distributed law ([`crate::tribology::foundation::foundation_energy`]) [J].
    pub(super) fn end_energy(
        &self,
        i: usize,
        k: usize,
        ring: &Kinematics,
        roller: &Kinematics,
    ) -> f64 {
        let (end, flange) = (self.roller_end(k, roller), self.flange(k, ring));
        self.end_contact(&end, &flange, i, k)
            .and_then(|c| self.overlap(&end, &flange, &c, true))
            .map_or(0.0, |o| {
                foundation::foundation_energy(
                    self.foundation_modulus[usize::from(k >= 2)],
                    o.energy,
                )
            })
    }

    /// The composite contact of roller i's end against flange k by the configured detector.
    fn detect(&self, end: &RollerEnd, flange: &Flange, roller: usize, k: usize) -> Option<Contact> {
        let start = self.workspace.profiler.stopwatch();
        let options = &self.params.options;
        let found = match options.detector {
            Detector::SemiAnalytical if options.pruning => pruning::composite_within_bounds(
                end,
                flange,
                &self.flange_bounds[k],
                self.params.squeeze_film.reach(),
            ),
            Detector::SemiAnalytical => semi_analytical::composite(end, flange),
            Detector::Gradient => self.detect_by_gradient(
                end,
                flange,
                &mut self.workspace.warm_starts.slot(roller, k),
            ),
            Detector::Mesh => {
                let (around, along) = options.mesh_resolution;
                let mesh = MeshDetector::new(end, flange, MeshResolution { around, along });
                deepest(&mesh.detect())
            }
        };
        self.workspace.profiler.count_detection(start);
        found
    }

    /// The composite contact by Koch's gradient method from the warm starts `memory` of
    /// the roller end and flange, which it updates.
    fn detect_by_gradient(
        &self,
        end: &RollerEnd,
        flange: &Flange,
        memory: &mut [Option<Unknowns>; 6],
    ) -> Option<Contact> {
        let mut outcomes = gradient::detect(end, flange, memory);
        // A pairing whose warm start failed is tried once more from the cold start.
        let failed: [Option<Unknowns>; 6] = std::array::from_fn(|k| {
            let o = &outcomes[k];
            (memory[k].is_some() && !(o.converged && o.opposite_normals))
                .then_some(None)
                .flatten()
        });
        if outcomes
            .iter()
            .zip(memory.iter())
            .any(|(o, m)| m.is_some() && !(o.converged && o.opposite_normals))
        {
            let cold = gradient::detect(end, flange, &failed);
            for k in 0..6 {
                let o = &outcomes[k];
                if memory[k].is_some() && !(o.converged && o.opposite_normals) {
                    outcomes[k] = cold[k];
                }
            }
        }
        let mut contacts = Vec::with_capacity(6);
        // Only converged solutions with opposite outward normals count and become the next
        // warm start; after a failure (no convergence, or a wrong stationary point, paper
        // fig. 2) the last good solution stays the warm start.
        // In runs, Newton also lands on stationary points off the patch where the true
        // contact is on it (torus–torus has several), and the lost contact lets the roller
        // pass through the flange. So a pairing that converged from neither start, or only
        // off its patch, takes the semi-analytical solution of that pairing when that one
        // counts; each is counted in `Profile::gradient_fallbacks` and reported with the run.
        let mut semi: Option<[Contact; 6]> = None;
        for (k, o) in outcomes.iter().enumerate() {
            let converged = o.converged && o.opposite_normals;
            if converged {
                memory[k] = Some(o.unknowns);
                if o.contact.valid {
                    contacts.push(o.contact);
                    continue;
                }
            }
            let all = semi.get_or_insert_with(|| semi_analytical::detect(end, flange));
            if all[k].valid {
                contacts.push(all[k]);
                self.workspace.profiler.spend(|p| p.gradient_fallbacks += 1);
            }
        }
        deepest(&contacts)
    }
}

/// The flange k (0, 1: inner ring at −x, +x; 2, 3: outer ring) of a ring body at its pose.
pub(super) fn flange_of(params: &BearingParams, k: usize, ring: &Kinematics) -> Flange {
    let inner = k < 2;
    let side = flange_side(k);
    let (shape, play, radius) = if inner {
        (
            &params.inner_flange,
            params.inner_axial_play,
            params.inner_raceway_radius,
        )
    } else {
        (
            &params.outer_flange,
            params.outer_axial_play,
            params.outer_raceway_radius,
        )
    };
    Flange::new(
        shape,
        &FlangePlacement {
            origin: ring.center,
            axis: ring.axis,
            raceway_radius: radius,
            rises: if inner { 1.0 } else { -1.0 },
            face_position: side * (0.5 * params.roller.length + play),
            facing: -side,
        },
    )
}
