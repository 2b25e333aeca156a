//! One share of a run (`harness run --shard i/n --out DIR`) and the join
//! of the shares (`harness merge DIR...`), so that a run spreads over
//! machines (a CI matrix, a Slurm job array: docs/sharding.md) and still
//! writes the report a single run writes.
//!
//! A run is a fixed list of [`Unit`]s: each selected case, in the order
//! of the selection, then, on a full run, the studies, then, on a full run
//! that is not `--quick`, the many-body benchmark. [`assign`] gives each
//! unit to one shard by a fixed rule (longest estimated cost first, to the
//! least loaded shard, ties to the lower shard number), the same on every
//! machine. A shard runs its units, writes their files (the cases' charts,
//! the studies' pages and figures, the benchmark's report) into its folder
//! and, beside them, [`RECORD`]: what the report needs of them
//! ([`ShardRecord`]). `merge` checks that every shard of one run is there
//! once, copies their files into the report folder, draws the pictures and
//! replays of the cases' scenes (as a single run does after its cases) and
//! writes the report from the records.

use crate::cases::{CaseRecord, find};
use crate::study::StudySummary;
use anyhow::{Context, Result, bail};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The record's file name inside a shard's folder.
pub const RECORD: &str = "shard.cbor";

/// The version of [`ShardRecord`]'s layout; `merge` refuses another.
const FORMAT: u32 = 2;

/// Which share: shard `index` (from 1) of `count`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// From 1 to `count`.
    pub index: usize,
    /// How many shards the run is split into (≥ 1).
    pub count: usize,
}

impl std::str::FromStr for Shard {
    type Err = String;

    /// `i/n` with 1 ≤ i ≤ n.
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        let (i, n) = s
            .split_once('/')
            .ok_or_else(|| format!("'{s}': a shard is written i/n (e.g. 1/2)"))?;
        let parse = |t: &str, what: &str| {
            t.trim()
                .parse::<usize>()
                .map_err(|_| format!("'{s}': {what} '{t}' is not a whole number"))
        };
        let (index, count) = (parse(i, "the shard")?, parse(n, "the count")?);
        if count == 0 || index == 0 || index > count {
            return Err(format!(
                "'{s}': the shard must be from 1 to the count, and the count at least 1"
            ));
        }
        Ok(Self { index, count })
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// A piece of a run that one shard runs whole.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Unit {
    /// A case, by id.
    Case(&'static str),
    /// The studies (sweeps, orders, stability, figures): one unit, since
    /// their pages read every sweep (inside the shard, their jobs run on
    /// its pool, `harness::study::run`).
    Studies,
    /// The many-body benchmark at its short settings (timed).
    Bench,
}

/// Estimated wall time of `unit` on one core (s), measured on the
/// development machine (a release build, `RUST_LOG=info cargo run
/// --release -p harness` logs each job's wall and CPU time): only the
/// balance of the shards, and the order in which a run starts its jobs
/// (`harness::pool`), depend on it, never what they compute. A case not
/// listed costs [`DEFAULT_COST`].
pub fn cost(unit: &Unit) -> f64 {
    match unit {
        // The sum of the studies' jobs (`study::job_cost`) in the run of
        // the cases' numbers below, their sweeps at 3 timing runs.
        Unit::Studies => 50.0,
        Unit::Bench => BENCH_COST,
        Unit::Case(id) => crate::pool::estimated_cost(CASE_COSTS, id, DEFAULT_COST),
    }
}

/// The short benchmark of a full run (s): the sum of its jobs
/// (`bench::job_cost`) in the same run.
const BENCH_COST: f64 = 31.5;

/// The cost of a case without an estimate (s).
const DEFAULT_COST: f64 = 0.2;

/// Seconds of the slow cases (see [`cost`]): measured in one full run on
/// the 2-core development machine shared with other work (2026-12-02):
/// the larger of the case's thread CPU time and a quarter of its wall time
/// (the run had about a quarter of a core per worker, and rapier2d and
/// Box2D runs partly on threads of their own); every other case under
/// 0.3 s.
const CASE_COSTS: &[(&str, f64)] = &[
    ("pendulum", 32.8),
    ("container", 12.2),
    ("fuzz_scenes", 3.4),
    ("queries_parry", 1.8),
    ("collision_parry", 0.7),
    ("physical_pendulum", 0.6),
    ("pendulum_wall", 0.4),
    ("slider_crank", 0.4),
];

/// The units of a run of `cases`: each case in order, then the studies on
/// a `full` run, then the benchmark on a full run that is not `quick`.
pub fn units(cases: &[&'static str], full: bool, quick: bool) -> Vec<Unit> {
    let mut units: Vec<Unit> = cases.iter().map(|id| Unit::Case(id)).collect();
    if full {
        units.push(Unit::Studies);
        if !quick {
            units.push(Unit::Bench);
        }
    }
    units
}

/// The units of `units` that `shard` runs, in their order in `units`:
/// longest estimated cost first (ties in the order of `units`), each to the
/// shard with the least estimated load so far (ties to the lower number).
/// Every unit goes to exactly one shard; the rule depends on nothing but
/// the list and the count.
pub fn assign(units: &[Unit], shard: Shard) -> Vec<Unit> {
    let mut order: Vec<usize> = (0..units.len()).collect();
    // A stable sort: equal costs keep the order of `units`.
    order.sort_by(|&a, &b| cost(&units[b]).total_cmp(&cost(&units[a])));
    let mut load = vec![0.0_f64; shard.count];
    let mut owner = vec![0usize; units.len()];
    for u in order {
        let least = (0..shard.count)
            .min_by(|&a, &b| load[a].total_cmp(&load[b]).then(a.cmp(&b)))
            .unwrap_or(0);
        load[least] += cost(&units[u]);
        owner[u] = least;
    }
    units
        .iter()
        .zip(owner)
        .filter(|(_, o)| *o + 1 == shard.index)
        .map(|(u, _)| u.clone())
        .collect()
}

/// What identifies a run, the same in each of its shards.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Run {
    /// The case ids of the whole run, in its order.
    pub selection: Vec<String>,
    /// Whether the run is of every case (then with the studies).
    pub full: bool,
    /// Whether the run is `--quick`.
    pub quick: bool,
    /// The report's provenance paragraph (machine, commit, build).
    pub provenance: String,
}

/// What a shard writes beside its files, for `merge`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ShardRecord {
    /// [`FORMAT`].
    pub format: u32,
    /// Which shard.
    pub shard: Shard,
    /// The run this shard is a share of (the same in every shard).
    pub run: Run,
    /// The records of this shard's cases, in the run's order.
    pub cases: Vec<CaseRecord>,
    /// The studies, when this shard ran them.
    pub studies: Option<StudySummary>,
    /// Whether this shard ran the benchmark.
    pub bench: bool,
}

impl ShardRecord {
    /// A record of this version's layout.
    pub fn new(
        shard: Shard,
        run: Run,
        cases: Vec<CaseRecord>,
        studies: Option<StudySummary>,
        bench: bool,
    ) -> Self {
        Self {
            format: FORMAT,
            shard,
            run,
            cases,
            studies,
            bench,
        }
    }

    /// Writes it as `dir/shard.cbor` (CBOR keeps every f64's bits, NaN and
    /// infinities included, which JSON would not).
    pub fn write(&self, dir: &Path) -> Result<()> {
        let mut bytes = Vec::new();
        ciborium::into_writer(self, &mut bytes).context("encoding the shard's record")?;
        let path = dir.join(RECORD);
        std::fs::write(&path, bytes).with_context(|| format!("writing {}", path.display()))
    }

    /// Reads `dir/shard.cbor`.
    pub fn read(dir: &Path) -> Result<Self> {
        let path = dir.join(RECORD);
        let bytes = std::fs::read(&path).with_context(|| {
            format!(
                "reading {} (a folder written by `harness run --shard i/n --out DIR`)",
                path.display()
            )
        })?;
        let record: Self = ciborium::from_reader(bytes.as_slice())
            .with_context(|| format!("{}: not a shard record", path.display()))?;
        if record.format != FORMAT {
            bail!(
                "{}: a shard record of format {} (this harness reads {FORMAT}): run the shards again with this build",
                path.display(),
                record.format
            );
        }
        Ok(record)
    }
}

/// The shards of one run joined: every case's record in the run's order
/// and the studies.
#[derive(Debug, Clone)]
pub struct Joined {
    /// The run.
    pub run: Run,
    /// Every case's record, in the run's order.
    pub cases: Vec<CaseRecord>,
    /// The studies, on a full run.
    pub studies: Option<StudySummary>,
}

/// Joins the records of `dirs` (in any order): refuses a missing or
/// repeated shard, shards of different runs (selection, `--quick`,
/// commit or build) and a case or the studies found twice or missing.
pub fn join(records: Vec<(String, ShardRecord)>) -> Result<Joined> {
    let Some((first_dir, first)) = records.first() else {
        bail!("merge: no shard folder given");
    };
    let count = first.shard.count;
    let mut seen = vec![None::<&str>; count];
    for (dir, r) in &records {
        let same_run = r.shard.count == count && r.run == first.run;
        if !same_run {
            bail!(
                "merge: {dir} (shard {}) and {first_dir} (shard {}) are shards of different runs \
                 (count, cases, --quick, machine, commit or build differ)",
                r.shard,
                first.shard
            );
        }
        let slot = &mut seen[r.shard.index - 1];
        if let Some(other) = slot {
            bail!("merge: shard {} is given twice: {other} and {dir}", r.shard);
        }
        *slot = Some(dir);
    }
    let missing: Vec<String> = (1..=count)
        .filter(|i| seen[i - 1].is_none())
        .map(|i| format!("{i}/{count}"))
        .collect();
    if !missing.is_empty() {
        bail!("merge: shard(s) {} missing", missing.join(", "));
    }
    let mut cases = Vec::new();
    for id in &first.run.selection {
        let found: Vec<&CaseRecord> = records
            .iter()
            .flat_map(|(_, r)| &r.cases)
            .filter(|c| &c.id == id)
            .collect();
        match found.as_slice() {
            [one] => cases.push((*one).clone()),
            [] => bail!("merge: no shard holds case '{id}'"),
            _ => bail!("merge: case '{id}' is in more than one shard"),
        }
        if find(id).is_none() {
            bail!("merge: case '{id}' is not in this harness's registry");
        }
    }
    let studies: Vec<&StudySummary> = records
        .iter()
        .filter_map(|(_, r)| r.studies.as_ref())
        .collect();
    let studies = match (first.run.full, studies.as_slice()) {
        (false, []) => None,
        (true, [one]) => Some((*one).clone()),
        _ => bail!(
            "merge: {} shards hold the studies; a full run has them in exactly one, a partial run in none",
            studies.len()
        ),
    };
    let benches = records.iter().filter(|(_, r)| r.bench).count();
    let want = usize::from(first.run.full && !first.run.quick);
    if benches != want {
        bail!("merge: {benches} shards ran the benchmark; this run needs {want}");
    }
    Ok(Joined {
        run: first.run.clone(),
        cases,
        studies,
    })
}

/// Copies every file under `from` but [`RECORD`] into `to` (a staging
/// folder), keeping the folders; a file another shard already wrote there
/// must be identical.
pub fn copy_files(from: &Path, to: &Path) -> Result<()> {
    copy_under(from, from, to)
}

fn copy_under(root: &Path, from: &Path, to: &Path) -> Result<()> {
    let entries = std::fs::read_dir(from).with_context(|| format!("reading {}", from.display()))?;
    let mut entries: Vec<_> = entries.collect::<std::io::Result<_>>()?;
    entries.sort_by_key(|e| e.file_name());
    for entry in entries {
        let path = entry.path();
        let relative = path.strip_prefix(root).unwrap_or(&path);
        if relative == Path::new(RECORD) {
            continue;
        }
        let target = to.join(relative);
        if entry.file_type()?.is_dir() {
            std::fs::create_dir_all(&target)
                .with_context(|| format!("creating {}", target.display()))?;
            copy_under(root, &path, to)?;
        } else {
            let bytes =
                std::fs::read(&path).with_context(|| format!("reading {}", path.display()))?;
            if let Ok(there) = std::fs::read(&target) {
                if there != bytes {
                    bail!(
                        "merge: {} is written by two shards with different contents",
                        relative.display()
                    );
                }
                continue;
            }
            std::fs::write(&target, bytes)
                .with_context(|| format!("writing {}", target.display()))?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn case_units(n: usize) -> Vec<Unit> {
        let ids: Vec<&'static str> = crate::cases::CASES.iter().take(n).map(|c| c.id).collect();
        units(&ids, false, false)
    }

    #[test]
    fn every_unit_goes_to_exactly_one_shard() {
        let all = units(
            &crate::cases::CASES.iter().map(|c| c.id).collect::<Vec<_>>(),
            true,
            false,
        );
        for count in 1..=5 {
            let mut got: Vec<Unit> = Vec::new();
            for index in 1..=count {
                got.extend(assign(&all, Shard { index, count }));
            }
            assert_eq!(got.len(), all.len(), "count {count}");
            for u in &all {
                assert_eq!(
                    got.iter().filter(|g| *g == u).count(),
                    1,
                    "{u:?} of {count}"
                );
            }
        }
    }

    #[test]
    fn the_split_keeps_the_run_order_and_is_the_same_each_time() {
        let all = case_units(12);
        let one = assign(&all, Shard { index: 1, count: 3 });
        assert_eq!(one, assign(&all, Shard { index: 1, count: 3 }));
        let positions: Vec<usize> = one
            .iter()
            .map(|u| all.iter().position(|a| a == u).unwrap())
            .collect();
        assert!(positions.windows(2).all(|w| w[0] < w[1]), "{positions:?}");
    }

    #[test]
    fn shard_arguments_are_checked() {
        assert_eq!("2/3".parse::<Shard>(), Ok(Shard { index: 2, count: 3 }));
        for bad in ["0/2", "3/2", "1/0", "1", "a/2", "1/b"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
    }
}
