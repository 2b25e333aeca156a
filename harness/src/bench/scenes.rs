//! The benchmark scenes (Box2D's benchmark suite and Solver2D's stack,
//! `docs/soft_step.md#benchmark-scenes`): their scene files, and which
//! body the quality figures watch. The jointed scenes (`joint_grid`,
//! `ragdoll_rain`) also get the joint figures (`measure`), from the
//! scene's joints.

/// A benchmark scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BenchScene {
    /// Id in the report.
    pub id: &'static str,
    /// Its scene file, relative to the scenes folder.
    pub file: &'static str,
    /// The full-size file for `bench --full`, when it differs.
    pub full: Option<&'static str>,
    /// The body whose sink (below its starting height) and sideways drift
    /// the quality figures report: the top box of a pyramid or stack.
    pub top: Option<&'static str>,
    /// Whether it belongs to the pyramid series of the scaling chart.
    pub scaling: bool,
    /// Timed steps per run in the fair protocol (`harness bench`): the
    /// scene's step count in Box2D's `benchmark/main.c` (`totalStepCount`:
    /// joint_grid 500, large_pyramid 500, many_pyramids 200, rain 1000,
    /// smash 300, tumbler 750), or, for the scenes Box2D's benchmark does
    /// not have, [`OTHER_STEPS`].
    pub box2d_steps: usize,
}

/// Timed steps of the scenes that are not in Box2D's benchmark (the smaller
/// pyramids, the stack, the shape rain): 500, Box2D's count for its
/// pyramid (`large_pyramid`), the series they belong to.
pub const OTHER_STEPS: usize = 500;

const fn pyramid(id: &'static str, file: &'static str, top: &'static str) -> BenchScene {
    BenchScene {
        id,
        file,
        full: None,
        top: Some(top),
        scaling: true,
        box2d_steps: OTHER_STEPS,
    }
}

/// Every benchmark scene, in report order: the pyramid series (base 10,
/// 20, 40, 70 and 100 = `large_pyramid`), the stack, then Box2D's other
/// benchmarks, a rain of mixed shapes into a container (`shape_rain`),
/// the same rain of capsules, rounded boxes and concave pieces
/// (`capsule_rain`), and the two of joints.
pub const SCENES: &[BenchScene] = &[
    pyramid("pyramid_10", "bench/pyramid_10", "pyramid_54"),
    pyramid("pyramid_20", "pyramid_20", "pyramid_209"),
    pyramid("pyramid_40", "bench/pyramid_40", "pyramid_819"),
    pyramid("pyramid_70", "bench/pyramid_70", "pyramid_2484"),
    BenchScene {
        box2d_steps: 500,
        ..pyramid("large_pyramid", "bench/large_pyramid", "pyramid_5049")
    },
    BenchScene {
        id: "stack",
        file: "stack",
        full: None,
        top: Some("stack_14"),
        scaling: false,
        box2d_steps: OTHER_STEPS,
    },
    BenchScene {
        id: "many_pyramids",
        file: "bench/many_pyramids",
        full: Some("bench/full/many_pyramids"),
        top: None,
        scaling: false,
        box2d_steps: 200,
    },
    BenchScene {
        id: "tumbler",
        file: "bench/tumbler",
        full: None,
        top: None,
        scaling: false,
        box2d_steps: 750,
    },
    BenchScene {
        id: "smash",
        file: "bench/smash",
        full: Some("bench/full/smash"),
        top: None,
        scaling: false,
        box2d_steps: 300,
    },
    BenchScene {
        id: "shape_rain",
        file: "bench/shape_rain",
        full: None,
        top: None,
        scaling: false,
        box2d_steps: OTHER_STEPS,
    },
    BenchScene {
        id: "capsule_rain",
        file: "bench/capsule_rain",
        full: None,
        top: None,
        scaling: false,
        box2d_steps: OTHER_STEPS,
    },
    BenchScene {
        id: "joint_grid",
        file: "bench/joint_grid",
        full: Some("bench/full/joint_grid"),
        top: None,
        scaling: false,
        box2d_steps: 500,
    },
    BenchScene {
        id: "ragdoll_rain",
        file: "bench/ragdoll_rain",
        full: Some("bench/full/ragdoll_rain"),
        top: None,
        scaling: false,
        box2d_steps: 1000,
    },
];
