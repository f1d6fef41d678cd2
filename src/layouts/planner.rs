//! The idealised lane control behind the common [`Planner`] interface (issue 102, item 1):
//! every layout of [`LayoutsConfig`] (direction × spacing × offset) is laid and ordered and
//! given an estimate of its time to the goal; the best [`LayoutsConfig::finalists`] of them
//! are driven in full (lanes joined by wall-free routes, the shared greedy completion, the
//! return to the end station) and the common scorer's time to the goal chooses among them.
//! The plan is cut at the goal, checked with the body rule and scored on the map as given.

use super::config::LayoutsConfig;
use super::fill::Fill;
use super::lanes::{LanePiece, Layout, lay};
use super::order::{Leg, greedy};
use crate::coverage::CoverageGrid;
use crate::coverage::curve::CoverageCurve;
use crate::ga::observer::{GenerationRecord, Observer};
use crate::geom::Point;
use crate::lanes::GrowingRoute;
use crate::map::clearance::Clearance;
use crate::map::reach::Reach;
use crate::planner::memory::MemoryEstimate;
use crate::planner::{Budget, Planner, PlannerError, RunOutcome, Scenario, StopReason};
use rayon::prelude::*;
use std::time::Instant;

/// Without a coverage goal, plans whose reachable coverage lies this close to the best one's
/// count as covering as much, and the fastest of them is kept.
pub const COVERAGE_TIE: f64 = 0.005;

/// One laid and ordered layout with the estimate that ranks it.
#[derive(Clone, Debug)]
pub struct Ordered {
    /// The layout.
    pub layout: Layout,
    /// Its lane pieces.
    pub pieces: Vec<LanePiece>,
    /// Their greedy order.
    pub legs: Vec<Leg>,
    /// The share of the reachable coverable cells the lanes sweep.
    pub lane_share: f64,
    /// Estimated seconds to the goal (lanes, grid transit, half a turn each way per leg; the
    /// share the lanes miss at twice the lanes' seconds per cell).
    pub estimate_s: f64,
}

/// Lays and orders every layout of `config` on the reachable clearance `clear`.
pub fn laid_layouts(config: &LayoutsConfig, clear: &Clearance, reach: &Reach, s: &Scenario) -> Vec<Ordered> {
    let grid = CoverageGrid::new(clear.map());
    let layouts: Vec<Layout> = config
        .directions
        .iter()
        .flat_map(|&direction_deg| {
            config.spacings.iter().flat_map(move |&spacing_m| {
                (0..config.offsets).map(move |offset| Layout {
                    direction_deg,
                    spacing_m,
                    offset,
                    offsets: config.offsets,
                })
            })
        })
        .collect();
    let goal = config.coverage_goal.unwrap_or(1.0);
    layouts
        .into_par_iter()
        .map(|layout| {
            let laid = lay(clear, reach, &grid, s.robot.width, layout, config.min_lane_m);
            let lane_share = laid.share(reach);
            let legs = greedy(clear, &laid.pieces, s.start);
            let estimate_s = estimate(&laid.pieces, &legs, lane_share, goal, &s.robot);
            Ordered { layout, pieces: laid.pieces, legs, lane_share, estimate_s }
        })
        .collect()
}

/// The estimate of [`Ordered::estimate_s`].
fn estimate(pieces: &[LanePiece], legs: &[Leg], share: f64, goal: f64, robot: &crate::coverage::Footprint) -> f64 {
    let metres: f64 = legs.iter().map(|l| pieces[l.piece].length() + l.transit_m.min(1e6)).sum();
    let turns = if robot.rot_speed > 0.0 { legs.len() as f64 * std::f64::consts::PI / robot.rot_speed } else { 0.0 };
    let lanes_s = metres / robot.speed + turns;
    if share <= 0.0 {
        return f64::INFINITY;
    }
    if share >= goal { lanes_s * goal / share } else { lanes_s + 2.0 * lanes_s * (goal - share) / share }
}

/// `ordered` with the stretches of extra lanes of [`Fill`] up to `goal` (the lanes laid again
/// to mark what they sweep), ordered again with them.
fn filled(fill: &Fill, ordered: &mut Ordered, s: &Scenario, goal: f64) {
    let mut laid = lay(fill.clear, fill.reach, fill.grid, s.robot.width, ordered.layout, fill.min_lane_m);
    fill.fill(ordered.layout.direction_deg, &mut laid, goal);
    ordered.lane_share = laid.share(fill.reach);
    ordered.legs = greedy(fill.clear, &laid.pieces, s.start);
    ordered.pieces = laid.pieces;
}

/// `laid` driven from `start`: each piece from its entry, joined by wall-free routes, then the
/// shared greedy completion and the return to `end`; repaired by the body rule where it
/// touches. With the targets the route skipped.
pub fn drive(clear: &Clearance, reach: &Reach, s: &Scenario, laid: &Ordered) -> (Vec<Point>, usize) {
    let mut route = GrowingRoute::new(s.start);
    for leg in &laid.legs {
        let p = laid.pieces[leg.piece];
        let (entry, exit) = if leg.reversed { (p.b, p.a) } else { (p.a, p.b) };
        route.drive(clear, &[entry, exit]);
    }
    crate::lanes::complete::complete(clear, reach, s.robot.width, &mut route);
    route.finish(clear, s.end);
    let skipped = route.skipped();
    (crate::planner::executable::repaired(clear, s.robot.width, route.into_points()), skipped)
}

/// The plan of a run and how it was chosen.
struct Chosen {
    laid: Ordered,
    path: Vec<Point>,
    skipped: usize,
    /// Each finalist's time to the goal on the planning raster (or its whole time).
    times: Vec<f64>,
    scored: usize,
}

impl LayoutsConfig {
    /// The finalists driven and scored; the one the common scorer finds fastest to the goal
    /// (without a goal: fastest among those within [`COVERAGE_TIE`] of the best coverage).
    fn choose(&self, s: &Scenario) -> Result<Chosen, String> {
        let width = s.robot.width;
        let mut clear = Clearance::new(&s.map, width);
        let reach = Reach::new(&clear, &[s.start]);
        if reach.centres().iter().all(|c| !c) {
            return Err(format!("no free area reachable from the start fits a robot {width} m wide"));
        }
        clear.restrict(reach.centres().to_vec());
        let mut all = laid_layouts(self, &clear, &reach, s);
        all.retain(|l| !l.pieces.is_empty());
        if all.is_empty() {
            return Err(format!("no lane of a robot {width} m wide fits the area reachable from the start"));
        }
        // Stable: equal estimates keep the layouts' order.
        all.sort_by(|a, b| a.estimate_s.total_cmp(&b.estimate_s));
        all.truncate(self.finalists);
        let grid = CoverageGrid::new(&s.map);
        let goal = self.coverage_goal.unwrap_or(1.0);
        let fill = Fill { clear: &clear, reach: &reach, grid: &grid, robot: s.robot, min_lane_m: self.min_lane_m };
        all.par_iter_mut().for_each(|l| filled(&fill, l, s, goal));
        let driven: Vec<((Vec<Point>, usize), CoverageCurve)> = all
            .par_iter()
            .map(|l| {
                let plan = drive(&clear, &reach, s, l);
                let curve = CoverageCurve::of_plan(&grid, &reach, std::slice::from_ref(&plan.0), &[s.robot]);
                (plan, curve)
            })
            .collect();
        let last = |c: &CoverageCurve| c.points().last().copied().unwrap_or((0.0, 0.0));
        let (index, times) = match self.coverage_goal {
            Some(goal) => {
                let times: Vec<f64> = driven.iter().map(|(_, c)| c.time_to(goal).unwrap_or(f64::INFINITY)).collect();
                let index = (0..times.len()).fold(0, |b, i| if times[i] < times[b] { i } else { b });
                (index, times)
            }
            None => {
                let best = driven.iter().map(|(_, c)| last(c).1).fold(f64::NEG_INFINITY, f64::max);
                let times: Vec<f64> = driven.iter().map(|(_, c)| last(c).0).collect();
                let ok = |i: usize| last(&driven[i].1).1 >= best - COVERAGE_TIE;
                let index = (0..times.len()).filter(|&i| ok(i)).fold(None, |b: Option<usize>, i| match b {
                    Some(b) if times[b] <= times[i] => Some(b),
                    _ => Some(i),
                });
                (index.unwrap_or(0), times)
            }
        };
        let scored = driven.len();
        let ((path, skipped), _) = driven.into_iter().nth(index).expect("one finalist at least");
        let path = match self.coverage_goal {
            Some(goal) => crate::lanes::goal::end_at_goal(&clear, &reach, &grid, &s.robot, path, goal, s.end),
            None => path,
        };
        let path = crate::planner::executable::executable(&clear, width, path).map_err(|e| e.to_string())?;
        Ok(Chosen { laid: all.swap_remove(index), path, skipped, times, scored })
    }

    /// An upper estimate of a run's own memory on `map`: per layout laid at once, a flag per
    /// cell for the lanes' coverage and the order's search (a distance and an end per cell).
    pub fn memory_estimate(&self, map: &crate::map::GridMap, threads: usize) -> MemoryEstimate {
        let cells = (map.rows() * map.cols()) as f64;
        MemoryEstimate {
            bytes: cells * 16.0 * threads.max(1) as f64,
            key: "map.source",
            what: format!("the lane control on {cells} cells"),
        }
    }
}

impl Planner for LayoutsConfig {
    fn name(&self) -> &'static str {
        "layouts"
    }

    fn run(
        &self,
        scenario: &Scenario,
        _seed: u64,
        _budget: &Budget,
        observers: &mut [&mut dyn Observer],
    ) -> Result<RunOutcome, PlannerError> {
        let started = Instant::now();
        let planning = scenario.for_planning();
        let s = &*planning;
        let chosen =
            self.choose(s).map_err(|e| PlannerError::Input(format!("layouts on map `{}`: {e}", s.map.name())))?;
        let grid = CoverageGrid::new(&scenario.map);
        let mut scratch = crate::coverage::SweepScratch::new(&grid);
        let metrics = s.robot.measure(&grid, &mut scratch, &chosen.path);
        let sc = crate::coverage::fitness::score(&metrics, &s.robot, scenario.map.resolution(), s.projection);
        let reach_cov = crate::coverage::score::reach_coverage(&scenario.reach(), &scratch);
        let record = GenerationRecord {
            iteration: 0,
            evaluations: chosen.scored as u64,
            best_fitness: sc.fitness,
            mean_fitness: sc.fitness,
            best_coverage: sc.cov_final,
            best_coverage_reach: Some(reach_cov),
            feasible: Some(chosen.scored as u32),
            diversity: None,
            robots: Vec::new(),
            extras: Vec::new(),
        };
        for o in observers.iter_mut() {
            o.generation(&record)?;
        }
        let details = self.details(scenario, &chosen);
        Ok(RunOutcome::new(vec![chosen.path], StopReason::Completed)
            .with_objectives(vec![("cov_final", sc.cov_final), ("t_final", sc.t_final), ("fitness", sc.fitness)])
            .with_effort(chosen.scored as u64, 0)
            .with_wall_s(started.elapsed().as_secs_f64())
            .with_details(details)
            .with_history(crate::planner::History::Generations))
    }
}

impl LayoutsConfig {
    /// The planner's own fields of `summary.json`: the chosen layout, its lanes and the
    /// finalists' times; with a goal, the plan's time to it on the map as given.
    fn details(&self, scenario: &Scenario, chosen: &Chosen) -> serde_json::Map<String, serde_json::Value> {
        let l = &chosen.laid;
        let finite = |t: f64| t.is_finite().then_some(t);
        let mut details = crate::planner::details(serde_json::json!({
            "direction_deg": l.layout.direction_deg,
            "lane_spacing_m": l.layout.spacing_m,
            "lane_offset": l.layout.offset,
            "lanes": l.pieces.len(),
            "lane_share": l.lane_share,
            "estimate_s": l.estimate_s,
            "directions_deg": self.directions,
            "finalists_time_s": chosen.times.iter().map(|&t| finite(t)).collect::<Vec<_>>(),
            "skipped_targets": chosen.skipped,
        }));
        if let Some(goal) = self.coverage_goal {
            let grid = CoverageGrid::new(&scenario.map);
            let curve =
                CoverageCurve::of_plan(&grid, &scenario.reach(), std::slice::from_ref(&chosen.path), &[scenario.robot]);
            details.insert("coverage_goal".into(), goal.into());
            details.insert("time_to_goal_s".into(), curve.time_to(goal).into());
        }
        details
    }
}
