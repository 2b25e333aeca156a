//! The ray-cast benchmark's workload (`harness::bench::queries`) is the
//! same in the three engines: run once, the rays that hit something agree
//! between this engine and Box2D (both skip a shape containing the ray's
//! origin) to within Box2D's f32 rounding on grazing rays, and rapier,
//! which also reports those shapes at distance 0, hits at least as many.
//! No time is judged here.

use harness::bench::queries::{RAYS, measure};

#[test]
fn the_three_engines_cast_the_same_rays() {
    let timings = measure(1).expect("the benchmark runs");
    assert_eq!(timings.len(), 3);
    for t in &timings {
        // Printed for a look only (one noisy repeat): nothing is judged.
        println!("{}: {:.0} ns per ray, {} hits", t.engine, t.ns_min, t.hits);
    }
    let (ours, rapier, box2d) = (timings[0].hits, timings[1].hits, timings[2].hits);
    assert!(ours > RAYS / 10, "too few hits to time anything: {ours}");
    // f32 positions of about 100 m carry ~1e-5 m of rounding: a grazing
    // ray can flip; at most 0.1 % of the rays.
    assert!(
        ours.abs_diff(box2d) <= RAYS / 1000,
        "ours {ours}, Box2D {box2d}"
    );
    assert!(rapier >= ours, "rapier {rapier}, ours {ours}");
}
