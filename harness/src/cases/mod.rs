//! The validation cases and their registry.
//!
//! Each case is one file here, named after its id, that runs every method
//! (or the scene's own) against its reference and returns rows and traces,
//! and declares what it is in a `pub const CASE: Case` ([`Case`]): title,
//! scene files, snapshots, headline rows, sweep, stability axis, study
//! figures, bench. The registry below lists the cases in report order.
//!
//! To add a case:
//! 1. write `scenes/<id>.toml` if it reads a new scene;
//! 2. write `cases/<id>.rs` with `pub fn run() -> Result<CaseReport>` and
//!    `pub const CASE: Case = Case { ..Case::new("<id>", "title", run) }`,
//!    setting the fields it uses;
//! 3. add `<id>` to the `registry!` list below.
//!
//! `cargo test` then runs it (and snapshots it, as its `snapshots` field
//! says), the harness reports it, and the studies, headline table and
//! benches pick up what it declares. A snapshot test's first run writes
//! `harness/tests/snapshots/*.snap.new`: review and accept them
//! (`cargo insta review`).

mod case;
mod common;

pub mod collision_common;
mod collision_plots;
pub mod double_pendulum_exact;
pub mod joint_common;
mod newtons_cradle_engines;
mod pendulum_charts;
pub mod pendulum_exact;
pub mod pendulum_swing;
pub mod soft_step_common;

pub use case::{
    Case, CaseFigure, CaseRecord, CaseReport, FigureOutput, FigureRecord, FigureSection, Headline,
    MethodTrace, Snapshots, StudyFigure,
};
pub use common::{
    DP_TOLERANCE, all_methods, dp_global_bound, dp_reason, failing_rows, sample_at, thin,
};

/// Declares one module per case file and [`CASES`], the list of their
/// `CASE` declarations, in the order given.
macro_rules! registry {
    ($($id:ident),* $(,)?) => {
        $(pub mod $id;)*

        /// Every case, in report order (that of docs/cases.md).
        pub const CASES: &[Case] = &[$($id::CASE),*];
    };
}

registry! {
    spring,
    projectile,
    torque,
    projectile_drag,
    angular_drag,
    hoffman,
    shape_mass,
    collision_parry,
    shape_parry,
    queries_parry,
    collision_toi,
    collision_head_on,
    collision_off_centre,
    collision_bounce,
    collision_slide,
    collision_incline,
    collision_rest,
    rolling_disc,
    stack,
    pyramid,
    friction_ramp,
    overlap_recovery,
    mass_ratio,
    container,
    pendulum,
    physical_pendulum,
    double_pendulum,
    newtons_cradle,
    pendulum_wall,
    slider_crank,
    chain,
    slider,
    joint_motor_limit,
    wheel_suspension,
    motor_joint,
    fuzz_scenes,
    falling_hinges,
    snapshot_restore,
    contact_forces,
    sensor_gate,
    conveyor,
    rolling_resistance,
    filters,
    ghost_collisions,
    bowl,
    bullet_plate,
}

/// The case with this id.
pub fn find(id: &str) -> Option<&'static Case> {
    CASES.iter().find(|c| c.id == id)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_are_unique_and_name_their_files() {
        for (i, case) in CASES.iter().enumerate() {
            assert!(
                CASES[..i].iter().all(|c| c.id != case.id),
                "case id '{}' registered twice",
                case.id
            );
            let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("src/cases")
                .join(format!("{}.rs", case.id));
            assert!(
                file.is_file(),
                "no file {} for case '{}'",
                file.display(),
                case.id
            );
        }
    }

    #[test]
    fn every_declared_scene_file_exists() {
        for case in CASES {
            for scene in case.scenes {
                let path = crate::scenes::path_of(scene);
                assert!(path.is_file(), "case '{}': no {}", case.id, path.display());
            }
        }
    }
}
