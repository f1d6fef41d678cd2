//! How long a recorded study would take on more cores, by the order its runs start in: a list
//! schedule ([`covga::study::order::list_schedule`], what `covga grid --jobs N` does) of the
//! `wall_s` each run took.
//!
//! ```sh
//! cargo run --release --example schedule_simulation -- results/ablation/runs.csv results/thesis-table-4-3/runs.csv.xz --cores 16,64
//! ```
//!
//! Orders:
//! - `seed by seed`: `--order seeds`, replicate by replicate, run id order within each;
//! - `longest first, budget`: `--order longest-first` with nothing recorded: by decreasing
//!   fitness evaluations (`budget.evaluations`, else `budget.iterations`, where the grid sweeps
//!   them) times the map's free cells, the patterns by free cells alone, ties seed by seed;
//! - `longest first, estimated`: `--order longest-first` with times recorded in the study
//!   folder: by decreasing mean `wall_s` of the other replicates of the run's configuration; a
//!   configuration run once gets its budget at the study's seconds per unit of budget;
//! - `longest first, exact`: by decreasing recorded `wall_s` (what no scheduler can know).
//!
//! Each makespan is divided by the lower bound max(total / cores, longest run): 1.000 is as good
//! as any order can be. The recorded times are those of the machine the study ran on, so the
//! figures speak of the order, not of a machine.

use covga::study::order::list_schedule;
use covga::study::records::RunsTable;
use std::collections::BTreeMap;
use std::process::ExitCode;

/// A runs.csv, or a runs.csv.xz decompressed.
fn read_runs(path: &str) -> Result<RunsTable, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{path}: {e}"))?;
    let text = if path.ends_with(".xz") {
        let mut out = Vec::new();
        lzma_rs::xz_decompress(&mut std::io::Cursor::new(bytes), &mut out).map_err(|e| format!("{path}: {e:?}"))?;
        String::from_utf8(out).map_err(|e| format!("{path}: {e}"))?
    } else {
        String::from_utf8(bytes).map_err(|e| format!("{path}: {e}"))?
    };
    RunsTable::parse(&text).map_err(|e| format!("{path}: {e}"))
}

/// One run as the orders read it.
struct Run {
    wall: f64,
    config: String,
    replicate: u64,
    id: String,
    budget: f64,
}

/// The runs of `t`; `Err` names a missing column.
fn runs(t: &RunsTable) -> Result<Vec<Run>, String> {
    let col = |n: &str| t.col(n).ok_or(format!("no column {n}"));
    let (wall, config, replicate, id) = (col("wall_s")?, col("config_id")?, col("replicate")?, col("run_id")?);
    // The metric `planner` column, not a swept `planner` key before it.
    let planner = t.header.iter().rposition(|h| h == "planner");
    let num = |r: &[String], n: &str| t.col(n).and_then(|c| r[c].parse::<f64>().ok());
    t.rows
        .iter()
        .map(|r| {
            let free = num(r, "free_cells").filter(|&f| f > 0.0).unwrap_or(1.0);
            let pattern = planner.is_some_and(|p| matches!(r[p].as_str(), "boustrophedon" | "spiral"));
            let units = ["budget.evaluations", "budget.iterations"].iter().find_map(|k| num(r, k).filter(|&v| v > 0.0));
            Ok(Run {
                wall: r[wall].parse().map_err(|_| format!("wall_s `{}` is not a number", r[wall]))?,
                config: r[config].clone(),
                replicate: r[replicate].parse().map_err(|_| format!("replicate `{}`", r[replicate]))?,
                id: r[id].clone(),
                budget: if pattern { free } else { units.map_or(free, |u| u * free) },
            })
        })
        .collect()
}

/// The four orders, each a list of indices into `runs`.
fn orders(runs: &[Run]) -> Vec<(&'static str, Vec<usize>)> {
    let mut by_config: BTreeMap<&str, (f64, usize)> = BTreeMap::new();
    for r in runs {
        let e = by_config.entry(&r.config).or_default();
        e.0 += r.wall;
        e.1 += 1;
    }
    let rate = runs.iter().map(|r| r.wall).sum::<f64>() / runs.iter().map(|r| r.budget).sum::<f64>();
    let estimate = |r: &Run| {
        let (sum, n) = by_config[r.config.as_str()];
        if n > 1 { (sum - r.wall) / (n - 1) as f64 } else { r.budget * rate }
    };
    let seeds = |a: &Run, b: &Run| a.replicate.cmp(&b.replicate).then_with(|| a.id.cmp(&b.id));
    let sorted = |key: &dyn Fn(&Run) -> f64| {
        let mut idx: Vec<usize> = (0..runs.len()).collect();
        idx.sort_by(|&a, &b| key(&runs[b]).total_cmp(&key(&runs[a])).then_with(|| seeds(&runs[a], &runs[b])));
        idx
    };
    let mut by_seed: Vec<usize> = (0..runs.len()).collect();
    by_seed.sort_by(|&a, &b| seeds(&runs[a], &runs[b]));
    vec![
        ("seed by seed", by_seed),
        ("longest first, budget", sorted(&|r| r.budget)),
        ("longest first, estimated", sorted(&estimate)),
        ("longest first, exact", sorted(&|r| r.wall)),
    ]
}

fn main() -> ExitCode {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let mut cores = vec![16usize, 64];
    if let Some(at) = args.iter().position(|a| a == "--cores") {
        let Some(list) = args.get(at + 1).map(|l| l.split(',').map(str::parse).collect::<Result<Vec<usize>, _>>())
        else {
            eprintln!("--cores: expected a list such as 16,64");
            return ExitCode::from(2);
        };
        match list {
            Ok(c) if c.iter().all(|&n| n >= 1) => cores = c,
            _ => {
                eprintln!("--cores: expected whole numbers of cores, at least 1, such as 16,64");
                return ExitCode::from(2);
            }
        }
        args.drain(at..at + 2);
    }
    if args.is_empty() {
        eprintln!("usage: schedule_simulation RUNS_CSV... [--cores 16,64]");
        return ExitCode::from(2);
    }
    let names: Vec<&str> = orders(&[]).iter().map(|(n, _)| *n).collect();
    println!("| study | runs | run time [h] | longest run [s] | cores | lower bound [s] | {} |", names.join(" | "));
    println!("|---|---|---|---|---|---|{}", "---|".repeat(names.len()));
    for path in &args {
        let table = match read_runs(path).and_then(|t| runs(&t).map_err(|e| format!("{path}: {e}"))) {
            Ok(r) => r,
            Err(e) => {
                eprintln!("{e}");
                return ExitCode::from(2);
            }
        };
        let study = std::path::Path::new(path)
            .canonicalize()
            .ok()
            .and_then(|p| p.parent()?.file_name().map(|n| n.to_string_lossy().into_owned()))
            .unwrap_or_else(|| path.clone());
        let total: f64 = table.iter().map(|r| r.wall).sum();
        let longest = table.iter().map(|r| r.wall).fold(0.0, f64::max);
        let orders = orders(&table);
        for &c in &cores {
            let bound = (total / c as f64).max(longest);
            let ratios: Vec<String> = orders
                .iter()
                .map(|(_, o)| {
                    let times: Vec<f64> = o.iter().map(|&i| table[i].wall).collect();
                    format!("{:.3}", list_schedule(&times, c) / bound)
                })
                .collect();
            println!(
                "| {study} | {} | {:.2} | {longest:.1} | {c} | {bound:.0} | {} |",
                table.len(),
                total / 3600.0,
                ratios.join(" | ")
            );
        }
    }
    ExitCode::SUCCESS
}
