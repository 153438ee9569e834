//! The bodies of the bearing and the contacts between them ("elements", paper sect. 3):
//! which contacts there are, which two bodies each one joins, and which contacts each body
//! takes part in (the sparsity the Jacobian uses: a roller couples only to its neighbours
//! and the rings).
//!
//! Every roller i has seven contacts, in this order: the inner race and the outer race
//! (line contacts by slices, eqs. 2, 3, 11), the neighbour i+1 (slices, eq. 11), and its two
//! ends against the two inner-ring and the two outer-ring flanges (roller end–flange
//! contacts, sect. 2; Hertz eqs. 5–8). A flange the rings do not have
//! ([`super::BearingParams::flanges`]) keeps its contacts here, which never touch.

/// A body of the bearing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Body {
    /// The inner ring (with its shaft).
    InnerRing,
    /// The outer ring (centred and aligned; fixed, or turning at its prescribed speed).
    OuterRing,
    /// Roller i.
    Roller(usize),
}

/// A contact of the bearing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Element {
    /// Roller i on the inner race.
    Inner(usize),
    /// Roller i on the outer race.
    Outer(usize),
    /// Roller i against roller i+1 (mod Z).
    Pair(usize),
    /// Roller i's end against a flange: 0 inner ring −x, 1 inner ring +x, 2 outer ring −x,
    /// 3 outer ring +x (the index of [`FLANGE_NAMES`]).
    End(usize, usize),
}

/// The kind of a line contact (a contact by slices along the roller).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LineContact {
    /// A roller on the inner race.
    InnerRace,
    /// A roller on the outer race.
    OuterRace,
    /// Two neighbouring rollers.
    RollerRoller,
}

impl LineContact {
    /// The index of this kind in the per-kind tables ordered inner race, outer race,
    /// roller–roller ([`crate::bearing::BearingParams::e_prime`],
    /// [`crate::bearing::BearingParams::line_laws`], the model's line-contact data).
    pub fn index(self) -> usize {
        match self {
            LineContact::InnerRace => 0,
            LineContact::OuterRace => 1,
            LineContact::RollerRoller => 2,
        }
    }
}

impl Element {
    /// The line-contact kind, None for a roller end–flange contact.
    pub fn line(&self) -> Option<LineContact> {
        match self {
            Element::Inner(_) => Some(LineContact::InnerRace),
            Element::Outer(_) => Some(LineContact::OuterRace),
            Element::Pair(_) => Some(LineContact::RollerRoller),
            Element::End(..) => None,
        }
    }

    /// Bodies (A, B) of the element in a bearing of `z` rollers: the ring (or roller i of a
    /// pair) is A, the roller (or roller i+1) is B.
    pub fn bodies(&self, z: usize) -> [Body; 2] {
        match *self {
            Element::Inner(i) => [Body::InnerRing, Body::Roller(i)],
            Element::Outer(i) => [Body::OuterRing, Body::Roller(i)],
            Element::Pair(i) => [Body::Roller(i), Body::Roller((i + 1) % z)],
            Element::End(i, k) if k < 2 => [Body::InnerRing, Body::Roller(i)],
            Element::End(i, _) => [Body::OuterRing, Body::Roller(i)],
        }
    }
}

/// Names of the four roller end / flange contacts of a roller.
pub const FLANGE_NAMES: [&str; 4] = ["inner-x", "inner+x", "outer-x", "outer+x"];

/// The side of flange k along the ring axis: −1 for the −x flanges (k = 0, 2), +1 else.
pub(super) fn flange_side(k: usize) -> f64 {
    if k % 2 == 1 {
        1.0
    } else {
        -1.0
    }
}

/// Slot of roller i's end against flange k among the 4·Z roller end–flange contacts
/// (the gradient detector's warm starts, [`super::detection::WarmStarts`]).
pub(super) fn end_slot(roller: usize, flange: usize) -> usize {
    4 * roller + flange
}

/// The contacts of a bearing and the contacts of each moving body.
#[derive(Debug, Clone)]
pub(super) struct Topology {
    /// All contacts: per roller Inner, Outer, Pair, then End for the four flanges.
    pub(super) elements: Vec<Element>,
    /// Indices (in `elements`) of the contacts of each roller.
    pub(super) roller_elements: Vec<Vec<usize>>,
    /// Indices of the contacts of the inner ring.
    pub(super) ring_elements: Vec<usize>,
}

impl Topology {
    /// The contacts of a bearing of `z` rollers.
    pub(super) fn new(z: usize) -> Self {
        let mut elements = Vec::with_capacity(7 * z);
        for i in 0..z {
            elements.extend([Element::Inner(i), Element::Outer(i), Element::Pair(i)]);
            elements.extend((0..4).map(|k| Element::End(i, k)));
        }
        let mut roller_elements = vec![Vec::new(); z];
        let mut ring_elements = Vec::new();
        for (e, element) in elements.iter().enumerate() {
            for body in element.bodies(z) {
                match body {
                    Body::Roller(i) => roller_elements[i].push(e),
                    Body::InnerRing => ring_elements.push(e),
                    Body::OuterRing => {}
                }
            }
        }
        Self {
            elements,
            roller_elements,
            ring_elements,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every roller end–flange contact has a slot of its own, numbered in the order of the
    /// elements, and every contact of a body is listed with it.
    #[test]
    fn slots_and_body_lists_follow_the_elements() {
        let z = 5;
        let topology = Topology::new(z);
        let slots: Vec<usize> = (topology.elements.iter())
            .filter_map(|e| match *e {
                Element::End(i, k) => Some(end_slot(i, k)),
                _ => None,
            })
            .collect();
        assert_eq!(slots, (0..4 * z).collect::<Vec<_>>());
        for (e, element) in topology.elements.iter().enumerate() {
            for body in element.bodies(z) {
                match body {
                    Body::Roller(i) => assert!(topology.roller_elements[i].contains(&e)),
                    Body::InnerRing => assert!(topology.ring_elements.contains(&e)),
                    Body::OuterRing => {}
                }
            }
        }
        assert_eq!(topology.ring_elements.len(), 3 * z);
    }
}
