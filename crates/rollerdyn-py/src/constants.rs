//! Names the core defines, exported as module constants of `rollerdyn._core` so that
//! Python need not mirror the core's tables: `PAIRINGS` (the roller end / flange pairings
//! of paper fig. 1, in the order of `flange_pairing` in the results), `FLANGES` (the four
//! roller end / flange contacts of a roller) and `DETECTORS` (`solver.detector`).

use pyo3::prelude::*;
use pyo3::types::PyTuple;
use rollerdyn_core::bearing::topology::FLANGE_NAMES;
use rollerdyn_core::bearing::Detector;
use rollerdyn_core::contact::Pairing;

/// The pairings' labels in the order of [`Pairing::ALL`] (the index a result records).
fn pairings() -> [&'static str; 6] {
    Pairing::ALL.map(|p| p.label())
}

/// The detectors' names in the order of [`Detector::ALL`].
fn detectors() -> [&'static str; 3] {
    Detector::ALL.map(|d| d.name())
}

/// Adds the constants to `m`, each a tuple of strings.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("PAIRINGS", PyTuple::new(py, pairings())?)?;
    m.add("FLANGES", PyTuple::new(py, FLANGE_NAMES)?)?;
    m.add("DETECTORS", PyTuple::new(py, detectors())?)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The names are part of the results' format and of the configuration: the exported
    /// tuples are the core's tables, and those are the names Python has always used.
    #[test]
    fn constants_are_the_core_tables_and_the_known_names() {
        assert_eq!(
            pairings(),
            [
                "TO-CO",
                "TO-TO(root)",
                "TO-TO(rim)",
                "SP-CO",
                "SP-TO(root)",
                "SP-TO(rim)"
            ]
        );
        for (k, pairing) in Pairing::ALL.iter().enumerate() {
            assert_eq!(pairings()[k], pairing.label());
        }
        assert_eq!(FLANGE_NAMES, ["inner-x", "inner+x", "outer-x", "outer+x"]);
        assert_eq!(detectors(), ["semi-analytical", "gradient", "mesh"]);
        for (k, detector) in Detector::ALL.iter().enumerate() {
            assert_eq!(detectors()[k], detector.name());
        }
    }
}
