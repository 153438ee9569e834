//! The mesh baseline (parry3d triangle meshes) of roller end–flange contact detection, at
//! a drawn resolution, on the cases of `contact_detection`. No panic; a found contact
//! (valid) has finite points, normal and penetration; a pairing with nothing within the
//! prediction distance is invalid with penetration −∞ (its documented answer). The mesh
//! gives no curvature, so its R_x, R_y are NaN by design; the border blending, which the
//! model applies to every detected contact, gives them the figures' curvature: the
//! blended deepest contact (default bands, and both bands 0: finding 6) must be defined.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rollerdyn_core::contact::border::{blend, BorderBands};
use rollerdyn_core::contact::deepest;
use rollerdyn_core::contact::mesh::{MeshDetector, MeshResolution};
use rollerdyn_fuzz::{case, require_defined, Reader};

fuzz_target!(|data: &[u8]| {
    let mut r = Reader::new(data);
    let Some(case) = case(&mut r) else {
        return;
    };
    if std::env::var_os("ROLLERDYN_FUZZ_PRINT").is_some() {
        eprintln!("{case:?}"); // to turn an artifact into a unit test
    }
    let resolution = MeshResolution {
        around: (r.byte() % 48) as usize,
        along: (r.byte() % 12) as usize,
    };
    let detector = MeshDetector::new(&case.end, &case.flange, resolution);
    let (start, end) = detector.window();
    assert!(
        start.is_finite() && end.is_finite(),
        "window {start} {end}\nfor {case:?}"
    );
    let found = detector.detect();
    if let Some(best) = deepest(&found) {
        let sharp = BorderBands {
            roller_angle: 0.0,
            flange_length: 0.0,
        };
        for b in [BorderBands::DEFAULT, sharp] {
            require_defined(
                "blended mesh",
                &blend(&best, &case.end, &case.flange, &b),
                &case,
            );
        }
    }
    for c in found {
        if c.valid {
            assert!(
                c.p1.iter()
                    .chain(c.p2.iter())
                    .chain(c.normal.iter())
                    .all(|x| x.is_finite())
                    && c.penetration.is_finite(),
                "mesh: undefined contact {c:?}\nfor {case:?}"
            );
        } else {
            assert_eq!(c.penetration, f64::NEG_INFINITY, "{c:?}\nfor {case:?}");
        }
    }
});
