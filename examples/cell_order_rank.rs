//! How well the cell-order GA's tour cost ranks plans as the common scorer does, on the
//! cell-order study's maps and robots: for each map, robot and completion (the boundary pass,
//! the completion inside each cell, and the searched quota completion on lanes joined across
//! gaps of up to 2.4 m and offered split per cell, as the cell-order study runs it), 1 000
//! sampled plans
//! ([`covga::cell_order::rank::sample`]), Spearman's ρ of the cost the GA ranks by (with the
//! coverage goal) and of the whole tour's time (what it ranked by before) against the
//! scorer's time to the goal. Writes `rank.csv` (one row per plan) and `rank.png`/`.svg` (one
//! panel per map, robot and completion: each plan's rank by the GA's cost against its rank by
//! the scorer's time) into the folder given:
//!
//! `cargo run --release --example cell_order_rank -- out/cell-order-rank 0.9`

use covga::cell_order::config::{CellOrderSection, Completion};
use covga::cell_order::rank::sample;
use covga::cell_order::{Preparation, prepare};
use covga::experiment::file::ExperimentFile;
use covga::experiment::registry::PlannerKind;
use covga::plot::{Figure, err, save, text};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::Path;

/// One panel: its title and each plan's (cost rank, scorer rank), both as shares of the plans.
struct Panel {
    title: String,
    points: Vec<(f64, f64)>,
}

/// The panels in rows of four, in the order map, robot (rotation speed), completion.
struct RankFigure {
    panels: Vec<Panel>,
}

impl Figure for RankFigure {
    fn size(&self) -> (u32, u32) {
        (1600, 420 * self.panels.len().div_ceil(4) as u32)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let areas = root.split_evenly((self.panels.len().div_ceil(4), 4));
        for (panel, area) in self.panels.iter().zip(&areas) {
            let mut chart = ChartBuilder::on(area)
                .caption(&panel.title, text(15.0))
                .margin(12)
                .x_label_area_size(44)
                .y_label_area_size(56)
                .build_cartesian_2d(0.0..1.0, 0.0..1.0)
                .map_err(err)?;
            chart
                .configure_mesh()
                .x_desc("rank by the GA's cost (share of plans)")
                .y_desc("rank by the scorer's time")
                .label_style(text(12.0))
                .axis_desc_style(text(13.0))
                .x_labels(6)
                .y_labels(6)
                .draw()
                .map_err(err)?;
            chart.draw_series(panel.points.iter().map(|&p| Circle::new(p, 2, BLUE.mix(0.5).filled()))).map_err(err)?;
            chart.draw_series(LineSeries::new([(0.0, 0.0), (1.0, 1.0)], BLACK.mix(0.6))).map_err(err)?;
        }
        Ok(())
    }
}

/// Each value's mid-rank as a share of the sample, in (0, 1].
fn shares(values: &[f64]) -> Vec<f64> {
    let n = values.len() as f64;
    covga::stats::describe::ranks(values).0.into_iter().map(|r| r / n).collect()
}

/// The study's maps and start stations.
const MAPS: [(&str, [f64; 2]); 4] = [
    ("thesis-2", [1.3, 1.3]),
    ("office", [2.0, 2.0]),
    ("office-ring", [8.75, 8.75]),
    ("experiments/maps/basement.yaml", [0.0, 0.0]),
];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let (Some(out), Some(goal)) = (args.get(1), args.get(2)) else {
        return Err("usage: cell_order_rank <folder> <coverage goal in (0, 1]> [plans]".into());
    };
    let goal: f64 = goal.parse()?;
    let plans: usize = args.get(3).map_or(Ok(1000), |p| p.parse())?;
    std::fs::create_dir_all(out)?;
    let mut panels = Vec::new();
    let mut csv = String::from("map,rot_speed,completion,plan,surrogate_s,tour_time_s,scorer_s\n");
    println!("| map | rot_speed | completion | plans | ρ surrogate | ρ whole tour |");
    println!("|---|---|---|---|---|---|");
    for (source, start) in MAPS {
        for rot_speed in [0.0, 0.5] {
            for (name, completion, merge_gap_m, offer_split_lanes) in [
                ("boundary", Completion::Boundary, 0.0, false),
                ("cells", Completion::Cells, 0.0, false),
                ("quota_search-merged", Completion::QuotaSearch, 2.4, true),
            ] {
                let mut file = ExperimentFile {
                    planner: PlannerKind::named("cell_order").expect("a planner"),
                    ..ExperimentFile::default()
                };
                file.map.source = source.into();
                file.stations.start = start;
                (file.robot.width, file.robot.speed, file.robot.rot_speed) = (0.6, 0.2, rot_speed);
                let exp = file.validate("cell_order_rank", Path::new("."), "cell_order_rank")?;
                // The quota takes pieces up to the goal, so it needs the goal to plan with.
                let coverage_goal = (completion == Completion::QuotaSearch).then_some(goal);
                let section = CellOrderSection {
                    completion,
                    merge_gap_m,
                    offer_split_lanes,
                    coverage_goal,
                    ..CellOrderSection::default()
                };
                let prepared = prepare(&exp.scenario, Preparation::of(&section))?;
                let ranked = sample(&prepared, &exp.scenario, completion, goal, plans, 1);
                for (i, ((a, b), c)) in ranked.surrogate.iter().zip(&ranked.tour_time).zip(&ranked.scorer).enumerate() {
                    writeln!(csv, "{source},{rot_speed},{name},{i},{a},{b},{c}")?;
                }
                let show = |r: Option<f64>| r.map_or("–".into(), |r| format!("{r:.3}"));
                let short = Path::new(source).file_stem().map_or(source.into(), |f| f.to_string_lossy().into_owned());
                panels.push(Panel {
                    title: format!("{short}, {rot_speed} rad/s, {name}: ρ = {}", show(ranked.rho())),
                    points: shares(&ranked.surrogate).into_iter().zip(shares(&ranked.scorer)).collect(),
                });
                println!(
                    "| {source} | {rot_speed} | {name} | {plans} | {} | {} |",
                    show(ranked.rho()),
                    show(ranked.rho_tour_time())
                );
            }
        }
    }
    std::fs::write(Path::new(out).join("rank.csv"), csv)?;
    save(&RankFigure { panels }, &Path::new(out).join("rank"))?;
    Ok(())
}
