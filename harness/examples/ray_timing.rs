//! The ray-cast workload of `harness bench` ("World queries: ray casts",
//! `harness/src/bench/queries.rs`) run alone: 10 000 rays of 20 m against
//! 2 000 static shapes. With `all`, the three engines alternate `repeats`
//! times and the minimum and median ns per ray are printed with the rays
//! hitting; with `ours`, this engine's rays are cast `repeats` times, for
//! callgrind; with `dump FILE`, this engine's answers to every ray
//! (`World::cast_ray` and `World::cast_ray_all`: pieces, and distances,
//! points and normals as f64 bits) are written to FILE, to compare two
//! builds bit for bit:
//!
//! ```text
//! cargo run --release -p harness --example ray_timing -- [all|ours [repeats]|dump FILE]
//! valgrind --tool=callgrind --collect-atstart=no --toggle-collect='*cast_rays*' \
//!     target/release/examples/ray_timing ours 1
//! ```

use anyhow::Context;
use engine::prelude::*;
use harness::bench::queries::Workload;
use std::fmt::Write as _;
use std::time::Instant;

/// One hit as text, its floats as bits.
fn hit_line(h: &RayHit) -> String {
    let bits = [h.distance, h.point.x, h.point.y, h.normal.x, h.normal.y].map(f64::to_bits);
    format!("{} {} {:x?}", h.shape.body, h.shape.part, bits)
}

/// Writes every ray's closest hit and all its hits to `file`.
fn dump(workload: &Workload, file: &str) -> anyhow::Result<()> {
    let mut text = String::new();
    for (k, (o, d)) in workload.rays.iter().enumerate() {
        let length = harness::bench::queries::RAY_LENGTH;
        let closest = workload
            .ours
            .cast_ray(*o, *d, length, QueryFilter::DEFAULT)?;
        let _ = writeln!(text, "{k} closest {:?}", closest.as_ref().map(hit_line));
        for h in workload
            .ours
            .cast_ray_all(*o, *d, length, QueryFilter::DEFAULT)?
        {
            let _ = writeln!(text, "{k} all {}", hit_line(&h));
        }
    }
    std::fs::write(file, text)?;
    Ok(())
}

/// The timed casts (a separate function so that callgrind can count them
/// alone).
#[inline(never)]
fn cast_rays(workload: &Workload, engine: usize) -> anyhow::Result<usize> {
    workload.cast_all(engine)
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("dump") {
        let file = args.get(1).context("dump needs a file")?;
        return dump(&Workload::new()?, file);
    }
    let all = args.first().map(String::as_str) != Some("ours");
    let repeats: usize = args.get(1).map_or(Ok(10), |a| a.parse())?;
    let workload = Workload::new()?;
    let engines: &[(usize, &str)] = if all {
        &[(0, "ours"), (1, "rapier2d"), (2, "Box2D")]
    } else {
        &[(0, "ours")]
    };
    let mut times = vec![Vec::new(); engines.len()];
    let mut hits = vec![0; engines.len()];
    for _ in 0..repeats.max(1) {
        for (k, (e, _)) in engines.iter().enumerate() {
            let clock = Instant::now();
            hits[k] = cast_rays(&workload, *e)?;
            times[k].push(clock.elapsed().as_secs_f64() * 1e9 / workload.rays.len() as f64);
        }
    }
    for (k, (_, name)) in engines.iter().enumerate() {
        let t = &mut times[k];
        t.sort_by(f64::total_cmp);
        println!(
            "{name:<9} ns per ray: min {:.0}, median {:.0}; rays hitting {}",
            t[0],
            t[t.len() / 2],
            hits[k]
        );
    }
    Ok(())
}
