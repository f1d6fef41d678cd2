//! Evaluated individuals, the scenario they are scored in, and the correction procedures that
//! follow every creation or change of a genome (003 §3.3.4, spec §9, order of R17).

use super::fitness::{Projection, ThesisScore, score};
use super::genome::{Action, Frame, decode, live, random_genome};
use crate::coverage::{CoverageGrid, Footprint, PathMetrics, SweepScratch};
use crate::geom::Point;
use crate::map::GridMap;
use rand::Rng;

/// Everything an evaluation reads: the map layers, the robot, the stations and the projection.
#[derive(Clone, Debug)]
pub struct Scenario {
    /// The map.
    pub map: GridMap,
    /// Obstacles and pre-marks as scored.
    pub grid: CoverageGrid,
    /// The robot.
    pub robot: Footprint,
    /// Stations and clamping rectangle.
    pub frame: Frame,
    /// `f1` or `f2`.
    pub projection: Projection,
}

impl Scenario {
    /// A scenario on `map` with stations `start` / `end` (already checked to be free).
    pub fn new(map: GridMap, robot: Footprint, start: Point, end: Point, projection: Projection) -> Self {
        let min = map.origin();
        let max = Point::new(min.x + map.width_m(), min.y + map.height_m());
        let grid = CoverageGrid::new(&map);
        Self { grid, robot, frame: Frame::new(start, end, min, max), projection, map }
    }
}

/// A decoded, evaluated genome with its visit-count map (the input of the diversity, §5).
#[derive(Clone, Debug, Default)]
pub struct Individual {
    /// The actions.
    pub genome: Vec<Action>,
    /// The viewpoints (`PA`), one per action.
    pub points: Vec<Point>,
    /// Footprint metrics of the path.
    pub metrics: PathMetrics,
    /// Thesis objectives and fitness.
    pub score: ThesisScore,
    /// `(cell, visits)` of every free cell the path swept.
    pub counts: Vec<(u32, u32)>,
}

impl Individual {
    /// `f_obstacle`.
    pub fn fitness(&self) -> f64 {
        self.score.fitness
    }
    /// `G_len`.
    pub fn len(&self) -> usize {
        self.genome.len()
    }
    /// Whether the genome is empty (never true for an evaluated individual).
    pub fn is_empty(&self) -> bool {
        self.genome.is_empty()
    }
}

/// How fresh genomes are drawn when a dead genome is replaced (spec §6).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InitParams {
    /// `Init_AC`.
    pub actions: usize,
    /// Upper bound of `AC_dist` in metres (R2).
    pub dist_max: f64,
}

/// Decodes with correction (written back) and evaluates, in place (spec §9 steps 1–2).
pub fn evaluate(ind: &mut Individual, scenario: &Scenario, scratch: &mut SweepScratch) {
    decode(&mut ind.genome, &scenario.frame, &mut ind.points);
    ind.metrics = scenario.robot.measure(&scenario.grid, scratch, &ind.points);
    ind.score = score(&ind.metrics, &scenario.robot, scenario.map.resolution(), scenario.projection);
    ind.counts.clear();
    ind.counts.extend(scratch.visit_counts());
}

/// Zero-action removal (003 §3.3.4, spec §9.2, R18): a free gene `1 ..= n − 3` that is a zero
/// action between two zero actions is deleted; all marks are taken on the current genome, then
/// deleted, so every run of zeros shrinks to at most two. The path does not change. Returns
/// the number of deleted genes.
pub fn remove_zero_actions(ind: &mut Individual) -> usize {
    let n = ind.genome.len();
    if n < 5 {
        return 0;
    }
    let g = &ind.genome;
    let marked: Vec<bool> =
        (0..n).map(|i| i >= 1 && i <= n - 3 && g[i - 1].is_zero() && g[i].is_zero() && g[i + 1].is_zero()).collect();
    let removed = marked.iter().filter(|&&m| m).count();
    if removed > 0 {
        let mut k = 0;
        ind.genome.retain(|_| {
            k += 1;
            !marked[k - 1]
        });
        let mut k = 0;
        ind.points.retain(|_| {
            k += 1;
            !marked[k - 1]
        });
    }
    removed
}

/// Dead genome (spec §9.3, R18): every live gene is a zero action.
pub fn is_dead(genome: &[Action]) -> bool {
    genome[live(genome.len())].iter().all(Action::is_zero)
}

/// The full correction sequence of R17 after a genome was created or changed: decode with
/// correction → evaluate → zero-action removal → dead check (re-initialise and start over).
/// Returns the number of evaluations spent.
pub fn correct_and_evaluate<R: Rng + ?Sized>(
    ind: &mut Individual,
    scenario: &Scenario,
    scratch: &mut SweepScratch,
    init: &InitParams,
    rng: &mut R,
) -> u64 {
    let mut evaluations = 0;
    loop {
        evaluate(ind, scenario, scratch);
        evaluations += 1;
        remove_zero_actions(ind);
        if !is_dead(&ind.genome) {
            return evaluations;
        }
        random_genome(rng, init.actions, init.dist_max, &mut ind.genome);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::presets::preset;

    fn a(dist_m: f64) -> Action {
        Action { alpha_deg: 90.0, dist_m }
    }

    #[test]
    fn zero_runs_shrink_to_two() {
        // Genes: S(1) 0 0 0 0 1 0 conn E → the middle two of the four zeros go.
        let mut ind = Individual {
            genome: vec![a(1.0), a(0.0), a(0.0), a(0.0), a(0.0), a(1.0), a(0.0), a(2.0), a(0.0)],
            ..Default::default()
        };
        ind.points = (0..9).map(|i| Point::new(i as f64, 0.0)).collect();
        assert_eq!(remove_zero_actions(&mut ind), 2);
        let d: Vec<f64> = ind.genome.iter().map(|x| x.dist_m).collect();
        assert_eq!(d, vec![1.0, 0.0, 0.0, 1.0, 0.0, 2.0, 0.0]);
        assert_eq!(ind.points.len(), 7);
        assert_eq!(ind.points[2], Point::new(4.0, 0.0));
    }

    #[test]
    fn dead_genomes_are_reinitialised() {
        let map = preset("thesis-1").unwrap();
        let s = Point::new(1.3, 1.3);
        let sc = Scenario::new(map, Footprint::default(), s, s, Projection::F1);
        let mut scratch = SweepScratch::new(&sc.grid);
        let mut ind = Individual { genome: vec![a(0.0), a(0.0), a(0.0), a(0.0)], ..Default::default() };
        assert!(is_dead(&ind.genome));
        let mut rng = crate::ga::rng::stream(9, crate::ga::rng::Purpose::Main, &[]);
        let evals =
            correct_and_evaluate(&mut ind, &sc, &mut scratch, &InitParams { actions: 10, dist_max: 5.0 }, &mut rng);
        assert_eq!(evals, 2);
        assert!(!is_dead(&ind.genome));
        assert!(ind.score.cov_final > 0.0);
        assert_eq!(ind.points.len(), ind.genome.len());
    }
}
