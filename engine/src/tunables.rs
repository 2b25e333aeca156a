//! Every tunable number of the engine, in one place, each with its unit,
//! its value and where the value comes from (a Box2D or rapier value, a
//! derivation, or a measurement). The code reads them from here; the
//! settings structs' `Default`s ([`crate::ContactSettings`],
//! [`crate::SoftStepSettings`]) are built from the `*_DEFAULT` ones.
//!
//! Not here: sizes of data structures that change no result (inline
//! capacities, SIMD lane counts, colour counts of the constraint graph,
//! sentinels, hash constants), which stay beside the structure they size.
//!
//! Changing a value changes traces: the snapshot tests of `engine/tests`
//! and `harness/tests` pin them.

// ---------------------------------------------------------------------
// The world's step
// ---------------------------------------------------------------------

/// How many ulps of the current time separate a force-window edge from a
/// step end before the step is split there (ulps; 16). Derivation: a few
/// ulps above the round-off of summing step lengths, so an edge that is
/// the step end up to round-off does not make a sliver step.
pub(crate) const EDGE_RESOLUTION_ULPS: f64 = 16.0;

// ---------------------------------------------------------------------
// Integrators
// ---------------------------------------------------------------------

/// Exponent β of the previous error in the adaptive method's PI step
/// controller (dimensionless; 0.04). Source: Hairer, Nørsett & Wanner,
/// *Solving ODEs I*, §II.4 (the DOPRI5 code's value).
pub(crate) const STEP_CONTROLLER_BETA: f64 = 0.04;
/// Exponent α of the current error, for an order-5 pair (dimensionless;
/// 0.17). Derivation: α = 1/5 − 0.75 β (Hairer et al., §II.4).
pub(crate) const STEP_CONTROLLER_ALPHA: f64 = 0.2 - STEP_CONTROLLER_BETA * 0.75;
/// Safety factor applied to the optimal step (dimensionless; 0.9).
/// Source: DOPRI5's `safe`.
pub(crate) const STEP_CONTROLLER_SAFETY: f64 = 0.9;
/// Smallest shrink factor of a step (dimensionless; 0.2). Source: DOPRI5's
/// `fac1` = 0.2.
pub(crate) const STEP_CONTROLLER_MIN_FACTOR: f64 = 0.2;
/// Largest growth factor of a step (dimensionless; 10). Source: DOPRI5's
/// `fac2` = 10.
pub(crate) const STEP_CONTROLLER_MAX_FACTOR: f64 = 10.0;

/// Newton iterations allowed per implicit-Euler step (count; 25).
/// Measurement: the stiff test converges in a handful; 25 leaves room
/// before `NewtonDiverged` is reported.
pub const IMPLICIT_EULER_MAX_ITERATIONS: usize = 25;
/// Relative size of the Newton correction at which the implicit-Euler
/// iteration stops (relative; 1e-12). Derivation: a few hundred ulps,
/// above round-off of the residual and far below the method's own O(h²)
/// local error for any step the harness uses.
pub(crate) const NEWTON_TOLERANCE: f64 = 1e-12;

// ---------------------------------------------------------------------
// The exact model (engine/src/exact/)
// ---------------------------------------------------------------------

/// Relative width (of the step) to which event times are located (relative
/// to max(h, |t|); 1e-15). Derivation: a few ulps of the time, far below
/// any tolerance the harness applies.
pub(crate) const EVENT_TIME_TOLERANCE: f64 = 1e-15;

/// Relative time tolerance of the stick-time root finding (relative;
/// 1e-15). Derivation: the same as the world's event location.
pub(crate) const STICK_TIME_TOLERANCE: f64 = 1e-15;

/// Samples of the rest of the step when the swept search's conservative
/// advancement creeps (count; 32). Measurement: enough to find the thin
/// wall of the `collision_toi` cases at their fastest speed.
pub(crate) const SWEEP_SAMPLES: usize = 32;

/// Overlap beyond which a pair is projected apart at a settle (units of
/// the contact tolerance ε; 4). Derivation: above the 2ε a located
/// impact can leave, so a pair found by the time-of-impact search is never
/// moved.
pub const PROJECTION_SLOP: f64 = 4.0;

/// Most projection passes at one settle (count; 16). Each is linearised,
/// so a deep overlap (bodies created inside each other) may need a few;
/// measurement: the `overlap_recovery` cases need at most a few.
pub(crate) const PROJECTION_PASSES: usize = 16;

/// Largest contact problem the exact model solves (rows; 512). Derivation:
/// its matrix has n² entries (2 MiB at 512 rows) and the polish
/// eliminates up to n unknowns (n³/3 ≈ 4.5e7 operations), once per
/// right-hand-side evaluation; a larger problem is refused with a typed
/// error rather than left to run for minutes.
pub(crate) const MAX_CONTACT_ROWS: usize = 512;

/// Most projected Gauss–Seidel sweeps (count; 500). The polish, not the
/// sweeps, gives the final precision; measurement: the validation cases
/// converge in far fewer.
pub(crate) const PGS_MAX_SWEEPS: usize = 500;

/// PGS stops when no λ moves by more than this times the scale of `b`
/// (relative; 1e-15). Derivation: a few ulps.
pub(crate) const PGS_TOLERANCE: f64 = 1e-15;

/// Relative size under which a λ counts as zero when reading the active
/// set (relative; 1e-10). Derivation: well above the PGS's round-off,
/// well below any contact force the cases meet.
pub(crate) const ACTIVE_THRESHOLD: f64 = 1e-10;

/// Relative violation the polished solution may show and still be taken
/// (relative; 1e-12). Derivation: round-off of a dense elimination of up
/// to [`MAX_CONTACT_ROWS`] rows.
pub(crate) const POLISH_TOLERANCE: f64 = 1e-12;

/// Most Newton iterations of the exact model's joint position projection
/// (count; 8). Measurement: the joint cases converge in 2–3.
pub const JOINT_MAX_PROJECTIONS: usize = 8;

/// Relative size of a Cholesky pivot below which a joint row is redundant
/// (relative; 1e-12). Derivation: round-off of the factorization.
pub(crate) const REDUNDANT_PIVOT: f64 = 1e-12;

/// [`crate::ContactSettings::restitution`] default (dimensionless; 1).
/// Source: the design's rule that defaults are ideal: elastic.
pub(crate) const EXACT_RESTITUTION_DEFAULT: f64 = 1.0;
/// [`crate::ContactSettings::friction`] default (dimensionless; 0).
/// Source: the same rule: frictionless.
pub(crate) const EXACT_FRICTION_DEFAULT: f64 = 0.0;
/// [`crate::ContactSettings::tolerance`] default, the contact distance ε
/// (m; 1e-10). Derivation: far below any length of the cases, far above
/// round-off of positions of order 1 m.
pub(crate) const EXACT_TOLERANCE_DEFAULT: f64 = 1e-10;
/// [`crate::ContactSettings::resting_speed`] default (m/s; 1e-3).
/// Measurement: below every bounce the validation cases resolve.
pub(crate) const EXACT_RESTING_SPEED_DEFAULT: f64 = 1e-3;
/// [`crate::ContactSettings::sliding_speed`] default (m/s; 1e-9).
/// Derivation: round-off of velocities of order 1 m/s after many steps.
pub(crate) const EXACT_SLIDING_SPEED_DEFAULT: f64 = 1e-9;
/// [`crate::ContactSettings::max_toi_iterations`] default (count; 200).
/// Derivation: bisection halves the step each time, so 200 is far more
/// than the ~60 to reach ε from any step the harness uses.
pub(crate) const EXACT_MAX_TOI_ITERATIONS_DEFAULT: usize = 200;
/// [`crate::ContactSettings::max_events_per_step`] default (count;
/// 10 000). A guard against an endless sequence of impacts, not a value
/// any case comes near.
pub(crate) const EXACT_MAX_EVENTS_PER_STEP_DEFAULT: usize = 10_000;

// ---------------------------------------------------------------------
// The soft step (engine/src/soft_step/)
// ---------------------------------------------------------------------

/// Linear slop: the round-off scale of contact geometry (m; 0.005).
/// Source: Box2D v3.2's `B2_LINEAR_SLOP`.
pub(crate) const LINEAR_SLOP: f64 = 0.005;

/// The largest broad-phase margin of a collider as a fraction of its
/// extent (dimensionless; 1/8). Source: Box2D v3.2's
/// `B2_AABB_MARGIN_FRACTION`.
pub(crate) const MARGIN_FRACTION: f64 = 0.125;

/// Cosine of the largest turn (about 11.5°) of either body for which a
/// manifold may be recycled (dimensionless; 0.98). Source: Box2D v3.2's
/// `B2_CONTACT_RECYCLE_COS_ANGLE`.
pub(crate) const RECYCLE_COS_ANGLE: f64 = 0.98;

/// Fraction of its smallest extent a body must move in a step to be swept
/// by continuous collision (dimensionless; 0.5). Source: Box2D v3.2's
/// safety factor in `b2FinalizeBodies`.
pub(crate) const FAST_FRACTION: f64 = 0.5;

/// Most distance evaluations of one continuous sweep (count; 50); a sweep
/// that needs more is abandoned (the speculative contacts still act).
/// Source: Box2D v3.2's `B2_MAX_TOI_ITERATIONS`-like bound of 50.
pub(crate) const SWEEP_MAX_ITERATIONS: usize = 50;

/// Largest |Δθ| (rad; 1/4) for which the rotation since the step began
/// uses Taylor polynomials instead of `sin_cos`. Derivation: within
/// 0.6 ulp there (`soft_step/bodies.rs`).
pub(crate) const SMALL_ANGLE: f64 = 0.25;

/// Default stiffness of the joints' rigid rows (Hz; 60). Source: Box2D
/// v3.2's `jointHertz`.
pub const DEFAULT_CONSTRAINT_HERTZ: f64 = 60.0;
/// Default damping ratio of the joints' rigid rows (dimensionless; 2).
/// Source: Box2D v3.2's `jointDampingRatio`.
pub const DEFAULT_CONSTRAINT_DAMPING_RATIO: f64 = 2.0;

/// [`crate::SoftStepSettings::substeps`] default (count; 4). Source:
/// Box2D v3.2's `subStepCount`.
pub(crate) const SOFT_SUBSTEPS_DEFAULT: usize = 4;
/// [`crate::SoftStepSettings::contact_hertz`] default (Hz; 30). Source:
/// Box2D v3.2's `contactHertz`.
pub(crate) const SOFT_CONTACT_HERTZ_DEFAULT: f64 = 30.0;
/// [`crate::SoftStepSettings::contact_damping_ratio`] default
/// (dimensionless; 10). Source: Box2D v3.2's `contactDampingRatio`.
pub(crate) const SOFT_CONTACT_DAMPING_RATIO_DEFAULT: f64 = 10.0;
/// [`crate::SoftStepSettings::push_out_speed`] default (m/s; 3). Source:
/// Box2D v3.2's `maxContactPushSpeed`.
pub(crate) const SOFT_PUSH_OUT_SPEED_DEFAULT: f64 = 3.0;
/// [`crate::SoftStepSettings::restitution_threshold`] default (m/s; 1).
/// Source: Box2D v3.2's `restitutionThreshold`.
pub(crate) const SOFT_RESTITUTION_THRESHOLD_DEFAULT: f64 = 1.0;
/// [`crate::SoftStepSettings::speculative_distance`] default (m; 0.02).
/// Source: Box2D v3.2's `B2_SPECULATIVE_DISTANCE` = 4 × linear slop.
pub(crate) const SOFT_SPECULATIVE_DISTANCE_DEFAULT: f64 = 0.02;
/// [`crate::SoftStepSettings::aabb_margin`] default, the cap of a fat
/// box's margin (m; 0.1). Source: Box2D v3.2's `B2_AABB_MARGIN`.
pub(crate) const SOFT_AABB_MARGIN_DEFAULT: f64 = 0.1;
/// [`crate::SoftStepSettings::friction`] default (dimensionless; 0.6).
/// Source: Box2D v3.2's `b2DefaultShapeDef` friction.
pub(crate) const SOFT_FRICTION_DEFAULT: f64 = 0.6;
/// [`crate::SoftStepSettings::restitution`] default (dimensionless; 0).
/// Source: Box2D v3.2's `b2DefaultShapeDef` restitution.
pub(crate) const SOFT_RESTITUTION_DEFAULT: f64 = 0.0;
/// [`crate::SoftStepSettings::recycle_distance`] default (m; 0.05).
/// Derivation: 10 × Box2D's linear slop (docs/soft_step.md).
pub(crate) const SOFT_RECYCLE_DISTANCE_DEFAULT: f64 = 0.05;
/// [`crate::SoftStepSettings::sleep_threshold`] default (m/s; 0.05).
/// Source: Box2D v3.2's body `sleepThreshold`.
pub(crate) const SOFT_SLEEP_THRESHOLD_DEFAULT: f64 = 0.05;
/// [`crate::SoftStepSettings::time_to_sleep`] default (s; 0.5). Source:
/// Box2D v3.2's `B2_TIME_TO_SLEEP`.
pub(crate) const SOFT_TIME_TO_SLEEP_DEFAULT: f64 = 0.5;
/// [`crate::SoftStepSettings::rolling_resistance`] default (dimensionless; 0).
/// Source: Box2D v3.2's `b2DefaultShapeDef` rolling resistance.
pub(crate) const SOFT_ROLLING_RESISTANCE_DEFAULT: f64 = 0.0;
/// [`crate::SoftStepSettings::hit_event_threshold`] default (m/s; 1).
/// Source: Box2D v3.2's `hitEventThreshold`.
pub(crate) const SOFT_HIT_EVENT_THRESHOLD_DEFAULT: f64 = 1.0;

// ---------------------------------------------------------------------
// Chains (engine/src/shape/chain.rs, engine/src/collision/chain_segment.rs)
// ---------------------------------------------------------------------

/// Sine of the smallest turn (about 0.57°) at which a chain's join counts
/// as convex, so that its neighbour's normal widens the normals a segment
/// admits (dimensionless; 0.01). A join that turns less is treated as flat:
/// only the segment's own normal is admitted there. Source: Box2D v3.2's
/// `convexTol` in `b2CollideChainSegmentAndPolygon`.
pub(crate) const CHAIN_CONVEX_SIN: f64 = 0.01;

/// Sine of the angle (about 0.57°) by which a contact normal may pass a
/// convex neighbour's normal and still be admitted by a chain segment
/// (dimensionless; 0.01). Source: Box2D v3.2's `sinTol` in
/// `b2ClassifyNormal`.
pub(crate) const CHAIN_ADMIT_SIN: f64 = 0.01;
