//! The mesh baseline (parry3d triangle meshes) of roller end–flange contact detection, at
//! a drawn resolution, on the cases of `contact_detection`. No panic; a found contact
//! (valid) has finite points, normal and penetration; a pairing with nothing within the
//! prediction distance is invalid with penetration −∞ (its documented answer). The mesh
//! gives no curvature, so R_x, R_y are NaN by design and not checked.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rollerdyn_core::contact::mesh::{MeshDetector, MeshResolution};
use rollerdyn_fuzz::{case, Reader};

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
    for c in detector.detect() {
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
