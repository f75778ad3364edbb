//! The exact reference against Monte Carlo on random scenes
//! (`arbitrary::scene::visibility_case`: every light kind, occluders
//! straddling the receiver's side and the light's plane, strips and fans
//! whose shared edges cross the light, coincident copies, corners at the
//! receiver, edge-on triangles).
//!
//! Each case is one check: `|mc − exact| ≤ q · stderr`, where `q` is the
//! two-sided Student-t quantile with `K − 1` degrees of freedom (the
//! standard error is estimated from `K` replicates) at the Šidák-corrected
//! level that keeps the false-failure rate of the whole test at `ALPHA`;
//! when every replicate agrees (`stderr = 0`), one replicate's resolution
//! (see `stats::agreement_tolerance`). More cases with
//! `SOFTSHADOW_EXHAUSTIVE=1`.
#![cfg(all(feature = "reference", feature = "arbitrary"))]

mod support;

use softshadow::arbitrary::scene::visibility_case;
use softshadow::arbitrary::Rng;
use softshadow::bvh::{Bvh, Occluders};
use softshadow::reference::exact;
use softshadow::reference::monte_carlo::{self, Options, REPLICATES};
use softshadow::reference::stats::{agreement_tolerance, sidak, student_t_two_sided_quantile};

const ALPHA: f64 = 1e-3;
const SAMPLES: u32 = 4096;

#[test]
fn exact_agrees_with_monte_carlo_on_random_scenes() {
    let cases = support::samples(300);
    let q = student_t_two_sided_quantile(sidak(ALPHA, cases), REPLICATES - 1);
    let mut rng = Rng::new(0x5eed_a9ee);
    let mut penumbra = 0;
    for case_index in 0..cases {
        let case = visibility_case(&mut rng, 12);
        let bvh = Bvh::new(Occluders::from_triangles(case.triangles.clone()));
        let Ok(e) = exact::visibility(&bvh, &case.light, case.receiver) else {
            // A receiver the light cannot be seen from: both must say so.
            assert!(
                monte_carlo::visibility(&bvh, &case.light, case.receiver, &Options::new(SAMPLES))
                    .is_err(),
                "case {case_index}: {case:?}"
            );
            continue;
        };
        let m = monte_carlo::visibility(
            &bvh,
            &case.light,
            case.receiver,
            &Options::new(SAMPLES).with_seed(case_index as u64),
        )
        .expect("the exact reference accepted this receiver");
        penumbra += usize::from(e > 0.0 && e < 1.0);
        let allowed = agreement_tolerance(&m, SAMPLES, q);
        assert!(
            (m.visibility - e).abs() <= allowed,
            "case {case_index}: exact {e}, mc {m:?}, allowed {allowed}\n{case:?}"
        );
        assert!((0.0..=1.0).contains(&e));
    }
    // The generator must actually produce penumbrae, or the test is idle.
    assert!(
        penumbra * 3 >= cases,
        "only {penumbra} of {cases} in a penumbra"
    );
}
