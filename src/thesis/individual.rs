//! Evaluated individuals, the scenario they are scored in, and the correction procedures that
//! follow every creation or change of a genome (003 §3.3.4, spec §9, order of R17).

use super::genome::{Action, Frame, decode, decode_from, live, random_genome, same_bits};
use super::objective::{CameraObjective, with_coverage};
use crate::coverage::bits::{BitLayers, Tally};
use crate::coverage::fitness::{Projection, ThesisScore, score_counts};
use crate::coverage::planes::VisitPlanes;
use crate::coverage::routes::{RouteScratch, Router};
use crate::coverage::segments::SegmentCache;
use crate::coverage::views::SegmentViews;
use crate::coverage::{CoverageGrid, Footprint, PathMetrics, SweepCounts, SweepScratch, motion};
use crate::geom::Point;
use crate::map::GridMap;
use rand::Rng;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// Everything an evaluation reads: the map layers, the robot, the stations and the projection.
#[derive(Clone, Debug)]
pub struct Scenario {
    /// The map.
    pub map: GridMap,
    /// Obstacles and pre-marks as scored.
    pub grid: CoverageGrid,
    /// The same layers as bit rows, for the evaluator.
    pub layers: BitLayers,
    /// The robot.
    pub robot: Footprint,
    /// Stations and clamping rectangle.
    pub frame: Frame,
    /// `f1` or `f2`.
    pub projection: Projection,
    /// With routed moves, how the robot drives from one viewpoint to the next (`None`: straight,
    /// as 003).
    pub routes: Option<Arc<Router>>,
    /// With `thesis.objective = "camera"`, what `cov_final` measures instead of the footprint
    /// (`None`: 003's footprint).
    pub camera: Option<Arc<CameraObjective>>,
}

impl Scenario {
    /// The thesis scenario (visit grid, clamping frame) of the common scenario every planner
    /// plans for.
    pub fn from_common(s: &crate::planner::Scenario) -> Self {
        Self::new(s.map.clone(), s.robot, s.start, s.end, s.projection)
    }

    /// A scenario on `map` with stations `start` / `end` (already checked to be free).
    pub fn new(map: GridMap, robot: Footprint, start: Point, end: Point, projection: Projection) -> Self {
        let min = map.origin();
        let max = Point::new(min.x + map.width_m(), min.y + map.height_m());
        let grid = CoverageGrid::new(&map);
        let layers = BitLayers::new(&grid);
        Self {
            grid,
            layers,
            robot,
            frame: Frame::new(start, end, min, max),
            projection,
            map,
            routes: None,
            camera: None,
        }
    }

    /// The same scenario with `cov_final` measured by `camera` (see [`super::objective`]).
    pub fn with_camera(mut self, camera: Option<CameraObjective>) -> Self {
        self.camera = camera.map(Arc::new);
        self
    }

    /// The same scenario with moves driven as `moves` says.
    pub fn with_moves(mut self, moves: Moves) -> Self {
        self.routes = match moves {
            Moves::Straight => None,
            Moves::Routed => {
                let stations = [self.frame.start, self.frame.end];
                Some(Arc::new(Router::new(&self.map, self.robot.width, &stations)))
            }
        };
        self
    }

    /// The path the robot drives through `points` (a genome's viewpoints): the viewpoints
    /// themselves with straight moves, else the routes between them.
    pub fn driven(&self, points: &[Point]) -> Vec<Point> {
        match &self.routes {
            None => points.to_vec(),
            Some(router) => {
                let mut out = Vec::new();
                router.expand(&self.layers, points, &mut RouteScratch::default(), &mut out);
                out
            }
        }
    }

    /// Replaces the pre-marks by the flagged free cells (see
    /// [`CoverageGrid::set_premarks`]). Individuals must be re-evaluated in full afterwards.
    pub fn set_premarks(&mut self, cells: &[bool]) {
        self.grid.set_premarks(cells);
        self.layers = BitLayers::new(&self.grid);
    }

    /// Marks the free cells whose centre lies in `[x0, x1) × [y0, y1)` as already covered
    /// (the retrain region, spec R25). Individuals must be re-evaluated in full afterwards.
    pub fn premark_rect(&mut self, x0: f64, y0: f64, x1: f64, y1: f64) {
        self.grid.premark_rect(x0, y0, x1, y1);
        self.layers = BitLayers::new(&self.grid);
    }
}

/// How the robot drives from one viewpoint to the next (`thesis.moves`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Moves {
    /// Straight segments, as 003: a move into a wall sweeps it and is penalised (eq. 3.16).
    #[default]
    Straight,
    /// Around obstacles (003 §5.3's future work): see [`crate::coverage::routes`].
    Routed,
}

impl Moves {
    /// Whether these are 003's straight moves.
    pub fn is_straight(&self) -> bool {
        matches!(self, Moves::Straight)
    }
}

/// How a changed genome is evaluated. Both give identical results; `Full` exists to prove it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum EvaluationMode {
    /// A child is its parent's visit map minus the parent's segments it does not share plus
    /// its own new segments (the counts of Listing 3.1 depend only on the final map).
    #[default]
    Incremental,
    /// Every evaluation sweeps the whole path.
    Full,
}

/// A decoded, evaluated genome with its visit-count map (the input of the diversity, §5).
#[derive(Debug, Default)]
pub struct Individual {
    /// The actions.
    pub genome: Vec<Action>,
    /// The viewpoints (`PA`), one per action.
    pub points: Vec<Point>,
    /// The counts of Listing 3.1 of the path.
    pub sweep: SweepCounts,
    /// `T_rot` in seconds (0 when `R_rot` = 0).
    pub t_rot_s: f64,
    /// Thesis objectives and fitness.
    pub score: ThesisScore,
    /// `M_traveled`: visits of every free cell the path swept (pre-marks not included).
    pub visits: VisitPlanes,
    /// Leading genes whose moves, decoded again, give the same first viewpoints (see
    /// [`decode`]); a child that shares them is decoded from its first changed gene. 0 is
    /// always safe.
    pub stable_genes: usize,
}

impl Clone for Individual {
    fn clone(&self) -> Self {
        let mut copy = Individual::default();
        copy.clone_from(self);
        copy
    }
    /// Field by field, into the buffers already held (a recycled member's).
    fn clone_from(&mut self, other: &Self) {
        // Destructured, so that a new field cannot be forgotten here.
        let Individual { genome, points, sweep, t_rot_s, score, visits, stable_genes } = other;
        self.genome.clone_from(genome);
        self.points.clone_from(points);
        self.sweep = *sweep;
        self.t_rot_s = *t_rot_s;
        self.score = *score;
        self.visits.copy_from(visits);
        self.stable_genes = *stable_genes;
    }
}

impl Individual {
    /// `best_genome.csv`: one row per action with its role, move and viewpoint.
    pub fn genome_csv(&self) -> Vec<u8> {
        let n = self.genome.len();
        let mut s = String::from("index,role,alpha_deg,dist_m,x_m,y_m\n");
        for (i, (a, p)) in self.genome.iter().zip(&self.points).enumerate() {
            let role = match i {
                0 => "start",
                _ if i == n - 1 => "end",
                _ if i == n - 2 => "connector",
                _ => "action",
            };
            s.push_str(&format!("{i},{role},{},{},{},{}\n", a.alpha_deg(), a.dist_m(), p.x, p.y));
        }
        s.into_bytes()
    }

    /// The complete footprint metrics of the path (length and turning included), measured
    /// anew; the evaluation itself keeps only what the fitness reads.
    pub fn path_metrics(&self, scenario: &Scenario) -> PathMetrics {
        let grid = &scenario.grid;
        let metrics = scenario.robot.measure(grid, &mut SweepScratch::new(grid), &scenario.driven(&self.points));
        debug_assert_eq!(metrics.counts(), self.sweep, "the evaluator and the cell sweep agree");
        metrics
    }

    fn tally(&self) -> Tally {
        Tally { cov_pix: self.sweep.cov_pix, obj_pix: self.sweep.obj_pix, unique: self.sweep.unique() }
    }

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

/// What a changed genome is evaluated against.
#[derive(Clone, Copy, Debug)]
pub enum Base<'a> {
    /// Nothing: sweep the whole path.
    None,
    /// The individual's own path and visit map before its genome changed.
    Own,
    /// The parent it was made from (the receiving parent of a crossover).
    Parent(&'a Individual),
}

/// Reusable buffers of an evaluation, one per worker thread.
#[derive(Clone, Debug, Default)]
pub struct EvalScratch {
    points: Vec<Point>,
    /// Segments already swept, replayed by incremental evaluations.
    segments: SegmentCache,
    /// Routes already found (routed moves).
    routes: RouteScratch,
    /// The driven path (routed moves).
    driven: Vec<Point>,
    /// Moves' camera views already computed (camera objective).
    views: SegmentViews,
}

/// Decodes with correction (written back) and evaluates, in place (spec §9 steps 1–2).
///
/// With [`EvaluationMode::Incremental`] and a base, only the segments the new path does not
/// share with the base's path are swept: the longest common prefix and suffix of viewpoints
/// (compared bit for bit) are kept, the base's segments between them are removed from its
/// visit map and the new ones added. Shared segments have identical endpoints and hence
/// identical cells, so the result equals a full evaluation exactly.
pub fn evaluate(
    ind: &mut Individual,
    scenario: &Scenario,
    base: Base,
    mode: EvaluationMode,
    scratch: &mut EvalScratch,
) {
    // The new path is decoded into the individual's own buffer, unless its old path is the
    // base the visit map is edited from; then into the scratch, copied over at the end.
    let keep_old = matches!((mode, base), (EvaluationMode::Incremental, Base::Own));
    let mut points = std::mem::take(if keep_old { &mut scratch.points } else { &mut ind.points });
    // A child shares its receiving parent's first genes up to the first changed one; those
    // of the parent's stable prefix decode to the parent's viewpoints, so decoding starts there.
    let (shared, stable) = match (mode, base) {
        (EvaluationMode::Incremental, Base::Parent(p)) => {
            let bound = p.stable_genes.min(ind.genome.len() - 2);
            let shared = (0..bound).find(|&i| !same_bits(&ind.genome[i], &p.genome[i])).unwrap_or(bound);
            points.clear();
            points.extend_from_slice(&p.points[..=shared]);
            let last = p.genome.len() - 2;
            let connector = Some((p.points[last], p.genome[last]));
            (shared, decode_from(&mut ind.genome, &scenario.frame, &mut points, connector))
        }
        _ => (0, decode(&mut ind.genome, &scenario.frame, &mut points)),
    };
    ind.stable_genes = stable;
    let (layers, width) = (&scenario.layers, scenario.robot.width);
    let EvalScratch { segments: cache, routes, driven, .. } = scratch;
    let mut router = scenario.routes.as_deref().map(|r| (r, &mut *routes));
    let tally = match (mode, base) {
        (EvaluationMode::Full, _) => match &mut router {
            None => layers.sweep(&mut ind.visits, &points, width),
            Some((r, routes)) => {
                r.expand(layers, &points, routes, driven);
                layers.sweep(&mut ind.visits, driven, width)
            }
        },
        (EvaluationMode::Incremental, Base::None) => {
            ind.visits.reset(layers.plane_words());
            edit(layers, cache, router, &mut ind.visits, Tally::default(), &[], &points, 0, width)
        }
        (EvaluationMode::Incremental, Base::Own) => {
            let t = ind.tally();
            edit(layers, cache, router, &mut ind.visits, t, &ind.points, &points, 0, width)
        }
        (EvaluationMode::Incremental, Base::Parent(p)) => {
            ind.visits.copy_from(&p.visits);
            edit(layers, cache, router, &mut ind.visits, p.tally(), &p.points, &points, shared, width)
        }
    };
    if keep_old {
        // Copied, not swapped: a swap would hand the scratch the individual's old vector,
        // perhaps a short one, to be grown again by the next decode.
        ind.points.clear();
        ind.points.extend_from_slice(&points);
        scratch.points = points;
    } else {
        ind.points = points;
    }
    ind.sweep = tally.counts();
    let rot = scenario.robot.rot_speed;
    ind.t_rot_s = match (rot > 0.0, scenario.routes.as_deref()) {
        (false, _) => 0.0,
        (true, None) => motion::rotation_time(motion::turning(&ind.points).0, rot),
        (true, Some(r)) => {
            r.expand(&scenario.layers, &ind.points, &mut scratch.routes, &mut scratch.driven);
            motion::rotation_time(motion::turning(&scratch.driven).0, rot)
        }
    };
    let res = scenario.map.resolution();
    ind.score = score_counts(
        &ind.sweep,
        scenario.grid.area_cells() as u64,
        ind.t_rot_s,
        &scenario.robot,
        res,
        scenario.projection,
    );
    if let Some(camera) = scenario.camera.as_deref() {
        let EvalScratch { routes, driven, views, .. } = scratch;
        let path: &[Point] = match scenario.routes.as_deref() {
            None => &ind.points,
            Some(r) => {
                r.expand(&scenario.layers, &ind.points, routes, driven);
                driven
            }
        };
        let coverage = camera.coverage(path, views);
        ind.score = with_coverage(ind.score, coverage, ind.sweep.obj_pix, scenario.projection);
    }
}

/// Adds (`ADD`) or removes move `a → b`: its straight segment, or with a router its route.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn apply_move<const ADD: bool>(
    layers: &BitLayers,
    cache: &mut SegmentCache,
    router: &mut Option<(&Router, &mut RouteScratch)>,
    visits: &mut VisitPlanes,
    a: Point,
    b: Point,
    width: f64,
    tally: &mut Tally,
) {
    match router {
        None => cache.apply::<ADD>(layers, visits, a, b, width, tally),
        Some((r, routes)) => {
            let route = r.route(layers, a, b, routes);
            let mut from = route.start;
            for &p in route.points {
                cache.apply::<ADD>(layers, visits, from, p, width, tally);
                from = p;
            }
        }
    }
}

/// Turns the visit map of path `old` (with counts `tally`) into that of path `new`, whose first
/// `same + 1` viewpoints are known to be `old`'s. A routed move depends on its two viewpoints
/// only, so moves are shared exactly as straight segments are.
#[allow(clippy::too_many_arguments)]
fn edit(
    layers: &BitLayers,
    cache: &mut SegmentCache,
    mut router: Option<(&Router, &mut RouteScratch)>,
    visits: &mut VisitPlanes,
    mut tally: Tally,
    old: &[Point],
    new: &[Point],
    same: usize,
    width: f64,
) -> Tally {
    let (so, sn) = (old.len().saturating_sub(1), new.len().saturating_sub(1));
    let shared = so.min(sn);
    // Segment `x` of both paths is the same while both its ends are. Each end is compared once:
    // segment `x`'s start is segment `x − 1`'s end, and viewpoint `same.min(shared)` is shared.
    let mut x = same.min(shared);
    while x < shared && old[x + 1] == new[x + 1] {
        x += 1;
    }
    let mut y = 0;
    if x < shared && old[so] == new[sn] {
        while x + y < shared && old[so - y - 1] == new[sn - y - 1] {
            y += 1;
        }
    }
    if router.is_none() {
        // The cache's slots of all the segments are fetched at once, not one miss after another.
        for i in x..so - y {
            cache.prefetch(old[i], old[i + 1], width);
        }
        for i in x..sn - y {
            cache.prefetch(new[i], new[i + 1], width);
        }
    }
    for i in x..so - y {
        apply_move::<false>(layers, cache, &mut router, visits, old[i], old[i + 1], width, &mut tally);
    }
    for i in x..sn - y {
        apply_move::<true>(layers, cache, &mut router, visits, new[i], new[i + 1], width, &mut tally);
    }
    tally
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
    // Most genomes have no run of three zeros: find the first marked gene without writing (the
    // middle of the first three zeros in a row ending at gene n − 2 or before).
    let mut run = 0;
    let Some(first) = ind.genome[..n - 1].iter().position(|g| {
        run = if g.is_zero() { run + 1 } else { 0 };
        run == 3
    }) else {
        return 0;
    };
    let first = first - 1;
    // From there, one pass in place, no marks buffer: a gene's mark reads its neighbours as
    // they were, and the write position never passes the read position, so the genes ahead
    // are still unchanged; the zero flag of the gene behind is carried over from the previous
    // step.
    let mut write = first;
    let mut behind_zero = true;
    let mut deleted_in_stable = 0;
    for i in first..n {
        let here_zero = ind.genome[i].is_zero();
        let ahead_zero = i + 1 < n && ind.genome[i + 1].is_zero();
        let marked = i >= 1 && i <= n - 3 && behind_zero && here_zero && ahead_zero;
        behind_zero = here_zero;
        if marked && i < ind.stable_genes {
            deleted_in_stable += 1;
        }
        if !marked {
            ind.genome[write] = ind.genome[i];
            if i < ind.points.len() {
                ind.points[write] = ind.points[i];
            }
            write += 1;
        }
    }
    let removed = n - write;
    // The deleted genes are zero actions, which move nothing when decoded again: the stable
    // prefix stays stable, shorter by the genes deleted from it.
    ind.stable_genes -= deleted_in_stable;
    ind.genome.truncate(write);
    ind.points.truncate(write);
    removed
}

/// Dead genome (spec §9.3, R18): every live gene is a zero action.
pub fn is_dead(genome: &[Action]) -> bool {
    genome[live(genome.len())].iter().all(Action::is_zero)
}

/// The full correction sequence of R17 after a genome was created or changed: decode with
/// correction → evaluate → zero-action removal → dead check (re-initialise and start over).
/// Returns the number of evaluations spent. `base` is what the genome was made from.
pub fn correct_and_evaluate<R: Rng + ?Sized>(
    ind: &mut Individual,
    scenario: &Scenario,
    mut base: Base,
    mode: EvaluationMode,
    scratch: &mut EvalScratch,
    init: &InitParams,
    rng: &mut R,
) -> u64 {
    let mut evaluations = 0;
    loop {
        evaluate(ind, scenario, base, mode, scratch);
        evaluations += 1;
        // Zero actions move nothing (see `decode_prefix`), so deleting them leaves the
        // segments, and hence the visit map, as they are.
        remove_zero_actions(ind);
        if !is_dead(&ind.genome) {
            return evaluations;
        }
        random_genome(rng, init.actions, init.dist_max, &mut ind.genome);
        base = Base::None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::presets::preset;

    fn a(dist_m: f64) -> Action {
        Action::new(90.0, dist_m)
    }

    /// Thesis map 1 with this robot, S and E, projection f2.
    fn thesis1(robot: Footprint, s: Point, e: Point) -> Scenario {
        Scenario::new(preset("thesis-1").unwrap(), robot, s, e, Projection::F2)
    }

    /// One move 3 m east, then two zero genes (the connector's slot and E's).
    fn three_metres_east() -> Individual {
        Individual {
            genome: vec![Action::new(0.0, 3.0), Action::new(0.0, 0.0), Action::new(0.0, 0.0)],
            ..Default::default()
        }
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
        let d: Vec<f64> = ind.genome.iter().map(|x| x.dist_m()).collect();
        assert_eq!(d, vec![1.0, 0.0, 0.0, 1.0, 0.0, 2.0, 0.0]);
        assert_eq!(ind.points.len(), 7);
        assert_eq!(ind.points[2], Point::new(4.0, 0.0));
    }

    #[test]
    fn a_premarked_rectangle_makes_its_cells_revisits_in_both_evaluations() {
        // The 3 m lane east from (1.3, 1.3) on thesis map 1 sweeps 45 cells; with the 1 m square
        // at (1, 1) pre-marked, its 12 lane cells are revisits (as the sweep's own case says).
        let (s, e) = (Point::new(1.3, 1.3), Point::new(4.3, 1.3));
        let mut scenario = thesis1(Footprint::default(), s, e);
        let eval = |scenario: &Scenario, mode| {
            let mut ind = three_metres_east();
            evaluate(&mut ind, scenario, Base::None, mode, &mut EvalScratch::default());
            ind
        };
        for mode in [EvaluationMode::Full, EvaluationMode::Incremental] {
            assert_eq!(eval(&scenario, mode).sweep, SweepCounts { cov_pix: 45, cross_pix: 0, obj_pix: 0 });
        }
        scenario.premark_rect(1.0, 1.0, 2.0, 2.0);
        for mode in [EvaluationMode::Full, EvaluationMode::Incremental] {
            let ind = eval(&scenario, mode);
            assert_eq!(ind.sweep, SweepCounts { cov_pix: 45, cross_pix: 12, obj_pix: 0 }, "{mode:?}");
            // The accessors read the member.
            assert_eq!(ind.fitness(), ind.score.fitness);
            assert!(ind.fitness() > 0.0 && ind.fitness() != 1.0, "{}", ind.fitness());
            assert_eq!((ind.len(), ind.is_empty()), (3, false));
        }
        assert!(Individual::default().is_empty());
    }

    #[test]
    fn turning_costs_r_rot_and_nothing_without_it() {
        // East 3 m, then the connector north 3 m to E: a quarter turn, T_rot = (π/2) / R_rot.
        let (s, e) = (Point::new(1.3, 1.3), Point::new(4.3, 4.3));
        for (rot_speed, t_rot) in [(0.5, std::f64::consts::PI), (0.0, 0.0)] {
            let robot = Footprint { rot_speed, ..Footprint::default() };
            let scenario = thesis1(robot, s, e);
            let mut ind = three_metres_east();
            evaluate(&mut ind, &scenario, Base::None, EvaluationMode::Incremental, &mut EvalScratch::default());
            assert!((ind.t_rot_s - t_rot).abs() < 1e-12, "R_rot {rot_speed}: {}", ind.t_rot_s);
        }
    }

    #[test]
    fn a_child_equal_to_its_parent_up_to_its_connector_evaluates_as_in_full() {
        // Parent: five equal moves of 0.5 m east, the connector, E. Child: the same five genes,
        // the fifth now in its connector's slot, and E. All the child's genes before E are the
        // parent's bit for bit, one more than the child's stable prefix can hold.
        let (s, e) = (Point::new(1.3, 1.3), Point::new(1.3, 3.3));
        let scenario = thesis1(Footprint::default(), s, e);
        let (g, zero) = (Action::new(0.0, 0.5), Action::new(0.0, 0.0));
        let mut scratch = EvalScratch::default();
        let mut parent = Individual { genome: vec![g, g, g, g, g, zero, zero], ..Default::default() };
        evaluate(&mut parent, &scenario, Base::None, EvaluationMode::Incremental, &mut scratch);
        assert_eq!(parent.stable_genes, 5);
        let mut child = Individual { genome: vec![g, g, g, g, g, zero], ..Default::default() };
        let mut full = Individual { genome: child.genome.clone(), ..Default::default() };
        evaluate(&mut child, &scenario, Base::Parent(&parent), EvaluationMode::Incremental, &mut scratch);
        evaluate(&mut full, &scenario, Base::None, EvaluationMode::Full, &mut scratch);
        assert_eq!((&child.genome, &child.points, child.sweep), (&full.genome, &full.points, full.sweep));
        assert_eq!((child.stable_genes, child.score), (full.stable_genes, full.score));
        assert_eq!(child.visits, full.visits);
        assert!((child.points[4] - Point::new(3.3, 1.3)).norm() < 1e-9, "four moves east, then the connector to E");
    }

    #[test]
    fn an_edit_skips_only_the_segments_both_paths_share() {
        // A path's visit map edited into another's equals the other's fresh sweep, however
        // many viewpoints the two share at either end (`same`: leading viewpoints known shared).
        let s = Point::new(1.3, 1.3);
        let scenario = thesis1(Footprint::default(), s, s);
        let (layers, width) = (&scenario.layers, scenario.robot.width);
        let p = Point::new;
        let old = [s, p(4.3, 1.3), p(4.3, 4.3), p(2.3, 6.3), p(6.3, 6.3), p(6.3, 2.3), s];
        let cases: [(Vec<Point>, usize); 9] = [
            // The third viewpoint from the end differs; the last two are shared.
            (vec![s, p(4.3, 1.3), p(4.3, 4.3), p(2.3, 6.3), p(8.3, 8.3), p(6.3, 2.3), s], 3),
            // The second differs; all after it are shared.
            (vec![s, p(4.3, 1.3), p(5.3, 4.3), p(2.3, 6.3), p(6.3, 6.3), p(6.3, 2.3), s], 1),
            // The same, with nothing known shared beyond S.
            (vec![s, p(4.3, 1.3), p(5.3, 4.3), p(2.3, 6.3), p(6.3, 6.3), p(6.3, 2.3), s], 0),
            // A viewpoint inserted, one removed.
            (vec![s, p(4.3, 1.3), p(4.3, 4.3), p(3.3, 3.3), p(2.3, 6.3), p(6.3, 6.3), p(6.3, 2.3), s], 2),
            (vec![s, p(4.3, 1.3), p(2.3, 6.3), p(6.3, 6.3), p(6.3, 2.3), s], 1),
            // S again where the other path has a viewpoint, and S twice at the end: a shared
            // tail is two equal segments, not one equal viewpoint matched with a neighbour.
            (vec![s, p(4.3, 1.3), p(4.3, 4.3), p(2.3, 6.3), s, p(6.3, 2.3), s], 1),
            (vec![s, p(4.3, 1.3), p(4.3, 4.3), p(2.3, 6.3), p(6.3, 6.3), s, s], 1),
            // Nothing shared but S and E; and the same path.
            (vec![s, p(9.3, 9.3), s], 0),
            (old.to_vec(), 6),
        ];
        let counts = |v: &VisitPlanes| {
            let mut c = Vec::new();
            v.for_each_count(|cell, k| c.push((cell, k)));
            c
        };
        // Each pair both ways: from `old` to the case's path and back.
        for (i, (path, same)) in cases.iter().enumerate() {
            for (from, to) in [(&old[..], &path[..]), (&path[..], &old[..])] {
                let mut visits = VisitPlanes::default();
                let tally = layers.sweep(&mut visits, from, width);
                let edited =
                    edit(layers, &mut SegmentCache::default(), None, &mut visits, tally, from, to, *same, width);
                let mut fresh = VisitPlanes::default();
                assert_eq!(edited, layers.sweep(&mut fresh, to, width), "case {i}");
                assert_eq!(counts(&visits), counts(&fresh), "case {i}");
            }
        }
    }

    /// Zero-action removal by its definition: marks on the unchanged genome, then deletion;
    /// the indices of the genes kept.
    fn kept_by_marks(genome: &[Action]) -> Vec<usize> {
        let n = genome.len();
        let z = |i: usize| genome[i].is_zero();
        (0..n).filter(|&i| !(n >= 5 && i >= 1 && i <= n - 3 && z(i - 1) && z(i) && z(i + 1))).collect()
    }

    proptest::proptest! {
        /// The in-place pass deletes exactly the marked genes and their viewpoints (with one
        /// viewpoint per gene, or one fewer), and the stable prefix loses the genes deleted
        /// from it.
        #[test]
        fn zero_action_removal_follows_its_marks(zeros in proptest::collection::vec(proptest::prelude::any::<bool>(), 0..40), stable in 0usize..41, short in proptest::bool::ANY) {
            let genome: Vec<Action> = zeros.iter().enumerate().map(|(i, &z)| a(if z { 0.0 } else { 1.0 + i as f64 })).collect();
            let n_points = if short { genome.len().saturating_sub(1) } else { genome.len() };
            let points: Vec<Point> = (0..n_points).map(|i| Point::new(i as f64, 0.0)).collect();
            let stable = stable.min(genome.len());
            let kept = kept_by_marks(&genome);
            let mut ind = Individual { genome: genome.clone(), points: points.clone(), stable_genes: stable, ..Default::default() };
            proptest::prop_assert_eq!(remove_zero_actions(&mut ind), genome.len() - kept.len());
            proptest::prop_assert_eq!(ind.genome, kept.iter().map(|&i| genome[i]).collect::<Vec<_>>());
            let kept_points: Vec<Point> = kept.iter().filter(|&&i| i < n_points).map(|&i| points[i]).collect();
            proptest::prop_assert_eq!(&ind.points[..kept_points.len().min(ind.points.len())], &kept_points[..]);
            proptest::prop_assert_eq!(ind.stable_genes, kept.iter().filter(|&&i| i < stable).count());
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200))]
        /// A crossover child, a mutated copy and a mutated child evaluated against their base
        /// equal their full evaluation in every field, visit map included.
        #[test]
        fn incremental_evaluation_equals_full(seed in 0u64..1_000_000, na in 3usize..70, nb in 3usize..70, c_len in 0.0..0.6f64, mode in 0u8..3, map in 0usize..2, dist in 0.5..12.0f64, camera in proptest::bool::ANY) {
            use crate::thesis::crossover::{ChildMode, Parent, ShortGenomes, crossover};
            use crate::thesis::mutation::mutate_action;
            let m = preset(["thesis-1", "thesis-2"][map]).unwrap();
            let s = Point::new(1.3, 1.3);
            let spec = crate::coverage::score::CameraSpec { scale: 0.15, d_min: 0.2, d_max: 7.0, fov_deg: 69.4, sections: 15, band_m: 0.45 };
            let objective = camera.then(|| CameraObjective::new(&m, &spec, 0.1, &[s]));
            let sc = Scenario::new(m, Footprint { rot_speed: 0.7, ..Footprint::default() }, s, Point::new(9.7, 1.3), Projection::F2)
                .with_camera(objective);
            let mut rng = crate::ga::rng::stream(seed, crate::ga::rng::Purpose::Main, &[]);
            let mut scratch = EvalScratch::default();
            let mut parents = Vec::new();
            for n in [na, nb] {
                let mut ind = Individual::default();
                random_genome(&mut rng, n - 2, dist, &mut ind.genome);
                evaluate(&mut ind, &sc, Base::None, EvaluationMode::Full, &mut scratch);
                remove_zero_actions(&mut ind);
                parents.push(ind);
            }
            let both = |ind: &Individual, base: Base, scratch: &mut EvalScratch| {
                let (mut inc, mut full) = (ind.clone(), ind.clone());
                evaluate(&mut inc, &sc, base, EvaluationMode::Incremental, scratch);
                evaluate(&mut full, &sc, Base::None, EvaluationMode::Full, scratch);
                (inc, full)
            };
            let same = |a: &Individual, b: &Individual| {
                a.genome == b.genome && a.points == b.points && a.sweep == b.sweep && a.score == b.score
                    && a.stable_genes == b.stable_genes && {
                    let (mut x, mut y) = (Vec::new(), Vec::new());
                    a.visits.for_each_count(|c, k| x.push((c, k)));
                    b.visits.for_each_count(|c, k| y.push((c, k)));
                    x == y
                }
            };
            let pa = Parent { genome: &parents[0].genome, points: &parents[0].points, stable: parents[0].stable_genes };
            let pb = Parent { genome: &parents[1].genome, points: &parents[1].points, stable: parents[1].stable_genes };
            let kids = crossover(pa, pb, c_len, ShortGenomes::Clamp, ChildMode::from_index(mode).unwrap(), 300, &sc.frame, &mut rng);
            for (k, genome) in kids.into_iter().flatten().enumerate() {
                let receiver = &parents[k % 2];
                let mut child = Individual { genome, ..Default::default() };
                if rng.random_bool(0.3) {
                    mutate_action(&mut child.genome, &mut rng);
                }
                let (inc, full) = both(&child, Base::Parent(receiver), &mut scratch);
                proptest::prop_assert!(same(&inc, &full), "child {k}");
            }
            // A copy whose genome was mutated, against its own former self.
            let mut copy = parents[0].clone();
            mutate_action(&mut copy.genome, &mut rng);
            let (inc, full) = both(&copy, Base::Own, &mut scratch);
            proptest::prop_assert!(same(&inc, &full), "mutated copy");
        }
    }

    #[test]
    fn dead_genomes_are_reinitialised() {
        let map = preset("thesis-1").unwrap();
        let s = Point::new(1.3, 1.3);
        let sc = Scenario::new(map, Footprint::default(), s, s, Projection::F1);
        let mut scratch = EvalScratch::default();
        let mut ind = Individual { genome: vec![a(0.0), a(0.0), a(0.0), a(0.0)], ..Default::default() };
        assert!(is_dead(&ind.genome));
        let mut rng = crate::ga::rng::stream(9, crate::ga::rng::Purpose::Main, &[]);
        let init = InitParams { actions: 10, dist_max: 5.0 };
        let evals =
            correct_and_evaluate(&mut ind, &sc, Base::None, EvaluationMode::Incremental, &mut scratch, &init, &mut rng);
        assert_eq!(evals, 2);
        assert!(!is_dead(&ind.genome));
        assert!(ind.score.cov_final > 0.0);
        assert_eq!(ind.points.len(), ind.genome.len());
    }
}
