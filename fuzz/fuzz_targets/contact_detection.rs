//! Roller end–flange contact detection with every analytical method: the six
//! semi-analytical pairings, the semi-analytical composite, the pruned detection and
//! composite (pruning on/off), Koch's gradient method (cold and warm start) and the border
//! blending. No panic, and every number defined (rollerdyn_fuzz::defined), for any
//! shapes the validated constructors accept and any pose. On B1 near its flanges the cheap
//! composites must also return what all six pairings return.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rollerdyn_core::contact::border::{blend, BorderBands};
use rollerdyn_core::contact::{deepest, gradient, pruning, semi_analytical};
use rollerdyn_fuzz::{case, require_defined, Reader};

fuzz_target!(|data: &[u8]| {
    let mut r = Reader::new(data);
    let Some(case) = case(&mut r) else {
        return;
    };
    if std::env::var_os("ROLLERDYN_FUZZ_PRINT").is_some() {
        eprintln!("{case:?}"); // to turn an artifact into a unit test
    }
    let (end, flange) = (&case.end, &case.flange);

    let all = semi_analytical::detect(end, flange);
    for c in &all {
        require_defined("semi-analytical", c, &case);
    }
    let composite = semi_analytical::composite(end, flange);
    if let Some(c) = &composite {
        require_defined("composite", c, &case);
    }

    // Pruning on: the same numbers for the pairings it keeps.
    let (pruned, _) = pruning::detect(end, flange);
    for (p, c) in pruned.iter().zip(&all) {
        if let Some(p) = p {
            require_defined("pruned", p, &case);
            assert_eq!(p.penetration.to_bits(), c.penetration.to_bits(), "{case:?}");
        }
    }
    let pruned_composite = pruning::composite(end, flange);
    if let Some(c) = &pruned_composite {
        require_defined("pruned composite", c, &case);
        assert!(c.valid && c.penetration > 0.0, "{c:?}\nfor {case:?}");
    }

    // The border blending of the deepest contact, with the default and with drawn bands.
    let bands = [
        BorderBands::DEFAULT,
        BorderBands {
            roller_angle: r.range(0.0, 1.0),
            flange_length: r.log_range(1e-9, 1e-2),
        },
        BorderBands {
            roller_angle: 0.0,
            flange_length: 0.0,
        },
    ];
    let best = deepest(&all);
    if let Some(best) = &best {
        for b in &bands {
            require_defined("blended", &blend(best, end, flange, b), &case);
        }
    }

    // Koch's gradient method: cold start, then warm-started from its own solution (the
    // unknowns must stay finite to be reusable).
    let cold = gradient::detect(end, flange, &[None; 6]);
    for o in &cold {
        require_defined("gradient (cold)", &o.contact, &case);
        assert!(
            o.unknowns.iter().all(|x| x.is_finite()),
            "gradient unknowns {o:?}\nfor {case:?}"
        );
    }
    let warm = gradient::detect(
        end,
        flange,
        &std::array::from_fn(|k| Some(cold[k].unknowns)),
    );
    for o in &warm {
        require_defined("gradient (warm)", &o.contact, &case);
    }

    if case.b1 {
        // The composites' shortcuts are exact on B1's convex ends and flanges.
        match (&best, &composite) {
            (None, None) => {}
            (Some(a), Some(b)) => assert!(
                (a.penetration - b.penetration).abs() <= 1e-15,
                "composite {b:?} vs deepest {a:?}\nfor {case:?}"
            ),
            (a, b) => panic!("composite {b:?} vs deepest {a:?}\nfor {case:?}"),
        }
        let overlap = best.filter(|c| c.penetration > 0.0);
        if overlap.is_none_or(|c| c.penetration <= pruning::PENETRATION_BOUND) {
            match (&overlap, &pruned_composite) {
                (None, None) => {}
                (Some(a), Some(b)) => assert!(
                    (a.penetration - b.penetration).abs() <= 1e-15,
                    "pruned composite {b:?} vs deepest {a:?}\nfor {case:?}"
                ),
                (a, b) => panic!("pruned composite {b:?} vs deepest overlap {a:?}\nfor {case:?}"),
            }
        }
    }
});
