//! `box2d_child <scene> <timed steps>`: one benchmark run of a Box2D build
//! other than the harness's (see `harness::bench::child`).

use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match harness::bench::child::child_main(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("box2d_child: {e:#}");
            ExitCode::from(2)
        }
    }
}
