//! Evaluated individuals and the correction procedures that follow every creation or change
//! of a genome (003 §3.3.4, in the order [`correct_and_evaluate`] gives), scored in a
//! [`ThesisScenario`].

use super::genome::{Action, decode, decode_from, live, random_genome, same_bits};
use super::objective::with_coverage;
use super::scenario::ThesisScenario;
use super::segments::{Home, SegmentCache};
use crate::coverage::bits::{BitLayers, Tally};
use crate::coverage::fitness::{ThesisScore, score_counts};
use crate::coverage::planes::VisitPlanes;
use crate::coverage::views::SegmentViews;
use crate::coverage::{PathMetrics, SweepCounts, SweepScratch, motion};
use crate::geom::Point;
use crate::routing::routes::{RouteScratch, Router};
use rand::Rng;
use serde::{Deserialize, Serialize};

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

/// A decoded, evaluated genome with its visit-count map (the input of the diversity, §5),
/// held behind one pointer: a generation moves its members from list to list (children,
/// jobs, families, the next population) several times per evaluation, and a pointer moves
/// where the fields would be copied. The fields are read through it ([`IndividualFields`]).
#[derive(Debug, Default)]
pub struct Individual(Box<IndividualFields>);

// Moved as one pointer, whatever fields are added.
const _: () = assert!(std::mem::size_of::<Individual>() == std::mem::size_of::<usize>());

/// What an [`Individual`] holds.
#[derive(Debug, Default)]
pub struct IndividualFields {
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

impl std::ops::Deref for Individual {
    type Target = IndividualFields;
    #[inline(always)]
    fn deref(&self) -> &IndividualFields {
        &self.0
    }
}

impl std::ops::DerefMut for Individual {
    #[inline(always)]
    fn deref_mut(&mut self) -> &mut IndividualFields {
        &mut self.0
    }
}

impl From<IndividualFields> for Individual {
    fn from(fields: IndividualFields) -> Self {
        Individual(Box::new(fields))
    }
}

impl Clone for Individual {
    fn clone(&self) -> Self {
        let mut copy = Individual::default();
        copy.clone_from(self);
        copy
    }
    /// Field by field, into the buffers already held (a recycled member's).
    fn clone_from(&mut self, other: &Self) {
        self.0.clone_from(&other.0);
    }
}

impl Clone for IndividualFields {
    fn clone(&self) -> Self {
        let mut copy = IndividualFields::default();
        copy.clone_from(self);
        copy
    }
    /// Field by field, into the buffers already held.
    fn clone_from(&mut self, other: &Self) {
        // Destructured, so that a new field cannot be forgotten here.
        let IndividualFields { genome, points, sweep, t_rot_s, score, visits, stable_genes } = other;
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
    /// An unevaluated individual of `genome`.
    pub fn with_genome(genome: Vec<Action>) -> Self {
        IndividualFields { genome, ..Default::default() }.into()
    }
}

impl IndividualFields {
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
    pub fn path_metrics(&self, scenario: &ThesisScenario) -> PathMetrics {
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

/// How fresh genomes are drawn when a dead genome is replaced (thesis-ga §6).
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
    /// The segments' home slots in the cache, per edit.
    homes: Vec<Home>,
    /// Routes already found (routed moves).
    routes: RouteScratch,
    /// The driven path (routed moves).
    driven: Vec<Point>,
    /// Moves' camera views already computed (camera objective).
    views: SegmentViews,
}

/// Decodes with correction (written back) and evaluates, in place (thesis-ga §9 steps 1–2).
///
/// With [`EvaluationMode::Incremental`] and a base, only the segments the new path does not
/// share with the base's path are swept: the longest common prefix and suffix of viewpoints
/// (compared bit for bit) are kept, the base's segments between them are removed from its
/// visit map and the new ones added. Shared segments have identical endpoints and hence
/// identical cells, so the result equals a full evaluation exactly.
///
/// Returns how many leading genes are known to be the parent's, bit for bit, before and after
/// correction (0 without a parent base).
pub fn evaluate(
    ind: &mut Individual,
    scenario: &ThesisScenario,
    base: Base,
    mode: EvaluationMode,
    scratch: &mut EvalScratch,
) -> usize {
    let ind: &mut IndividualFields = ind;
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
    let EvalScratch { segments: cache, homes, routes, driven, .. } = scratch;
    let mut router = scenario.routes.as_deref().map(|r| (r, &mut *routes));
    let tally = match (mode, base) {
        (EvaluationMode::Full, _) => match &mut router {
            None => layers.sweep(&mut ind.visits, &points, width),
            Some((r, routes)) => {
                r.expand(&points, routes, driven);
                layers.sweep(&mut ind.visits, driven, width)
            }
        },
        (EvaluationMode::Incremental, Base::None) => {
            ind.visits.reset(layers.plane_words());
            edit(layers, cache, homes, router, &mut ind.visits, Tally::default(), &[], &points, 0, width)
        }
        (EvaluationMode::Incremental, Base::Own) => {
            let t = ind.tally();
            edit(layers, cache, homes, router, &mut ind.visits, t, &ind.points, &points, 0, width)
        }
        (EvaluationMode::Incremental, Base::Parent(p)) => {
            ind.visits.copy_from(&p.visits);
            edit(layers, cache, homes, router, &mut ind.visits, p.tally(), &p.points, &points, shared, width)
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
    score_path(ind, scenario, scratch);
    shared
}

/// Scores an individual whose path and sweep counts are current: its rotation time (over the
/// driven routes when moves are routed), 003 eq. 3.13's objectives, and the camera's coverage
/// in place of the footprint's when the scenario has a camera.
#[inline]
fn score_path(ind: &mut IndividualFields, scenario: &ThesisScenario, scratch: &mut EvalScratch) {
    let rot = scenario.robot.rot_speed;
    ind.t_rot_s = match (rot > 0.0, scenario.routes.as_deref()) {
        (false, _) => 0.0,
        (true, None) => motion::rotation_time(motion::turning(&ind.points).0, rot),
        (true, Some(r)) => {
            r.expand(&ind.points, &mut scratch.routes, &mut scratch.driven);
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
                r.expand(&ind.points, routes, driven);
                driven
            }
        };
        let coverage = camera.coverage(path, views);
        ind.score = with_coverage(ind.score, coverage, ind.sweep.obj_pix, scenario.projection);
    }
}

/// Adds (`ADD`) or removes the route of move `a → b`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn apply_route<const ADD: bool>(
    layers: &BitLayers,
    cache: &mut SegmentCache,
    (router, routes): (&Router, &mut RouteScratch),
    visits: &mut VisitPlanes,
    a: Point,
    b: Point,
    width: f64,
    tally: &mut Tally,
) {
    let route = router.route(a, b, routes);
    let mut from = route.start;
    for &p in route.points {
        cache.apply::<ADD>(layers, visits, from, p, width, tally);
        from = p;
    }
}

/// Turns the visit map of path `old` (with counts `tally`) into that of path `new`, whose first
/// `same + 1` viewpoints are known to be `old`'s. A routed move depends on its two viewpoints
/// only, so moves are shared exactly as straight segments are. `homes` is a scratch.
#[allow(clippy::too_many_arguments)]
fn edit(
    layers: &BitLayers,
    cache: &mut SegmentCache,
    homes: &mut Vec<Home>,
    router: Option<(&Router, &mut RouteScratch)>,
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
    let (removed, added) = (x..so - y, x..sn - y);
    match router {
        None => {
            // The cache's slots of all the segments are fetched at once, not one miss after
            // another; each segment's key is hashed once.
            homes.clear();
            homes.extend(removed.clone().map(|i| cache.prefetch(old[i], old[i + 1], width)));
            homes.extend(added.clone().map(|i| cache.prefetch(new[i], new[i + 1], width)));
            let (removed_homes, added_homes) = homes.split_at(removed.len());
            for (i, &home) in removed.zip(removed_homes) {
                cache.apply_from::<false>(layers, visits, old[i], old[i + 1], width, home, &mut tally);
            }
            for (i, &home) in added.zip(added_homes) {
                cache.apply_from::<true>(layers, visits, new[i], new[i + 1], width, home, &mut tally);
            }
        }
        Some((r, routes)) => {
            for i in removed {
                apply_route::<false>(layers, cache, (r, &mut *routes), visits, old[i], old[i + 1], width, &mut tally);
            }
            for i in added {
                apply_route::<true>(layers, cache, (r, &mut *routes), visits, new[i], new[i + 1], width, &mut tally);
            }
        }
    }
    tally
}

/// Zero-action removal (003 §3.3.4, thesis-ga §9.2, R18): a free gene `1 ..= n − 3` that is a zero
/// action between two zero actions is deleted; all marks are taken on the current genome, then
/// deleted, so every run of zeros shrinks to at most two. The path does not change. Returns
/// the number of deleted genes.
pub fn remove_zero_actions(ind: &mut Individual) -> usize {
    remove_zero_actions_after(ind, 0)
}

/// [`remove_zero_actions`] of a genome whose first `known` genes hold no three zeros in a row
/// ending before gene `known`: the search for the first run of three starts at gene
/// `known − 2`. (A child's genes it shares with a parent that went through this removal.)
fn remove_zero_actions_after(ind: &mut Individual, known: usize) -> usize {
    let n = ind.genome.len();
    if n < 5 {
        return 0;
    }
    // Most genomes have no run of three zeros: find the first marked gene without writing (the
    // middle of the first three zeros in a row ending at gene n − 2 or before).
    let from = known.saturating_sub(2).min(n - 1);
    let mut run = 0;
    let Some(end) = ind.genome[from..n - 1].iter().position(|g| {
        run = if g.is_zero() { run + 1 } else { 0 };
        run == 3
    }) else {
        return 0;
    };
    let first = from + end - 1;
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

/// Dead genome (thesis-ga §9.3, R18): every live gene is a zero action.
pub fn is_dead(genome: &[Action]) -> bool {
    genome[live(genome.len())].iter().all(Action::is_zero)
}

/// The full correction sequence of R17 after a genome was created or changed: decode with
/// correction → evaluate → zero-action removal → dead check (re-initialise and start over).
/// Returns the number of evaluations spent. `base` is what the genome was made from; a parent
/// base must have been through this correction itself (every member of a population has).
pub fn correct_and_evaluate<R: Rng + ?Sized>(
    ind: &mut Individual,
    scenario: &ThesisScenario,
    mut base: Base,
    mode: EvaluationMode,
    scratch: &mut EvalScratch,
    init: &InitParams,
    rng: &mut R,
) -> u64 {
    let mut evaluations = 0;
    loop {
        let parents_genes = evaluate(ind, scenario, base, mode, scratch);
        evaluations += 1;
        // Zero actions move nothing (see `decode_prefix`), so deleting them leaves the
        // segments, and hence the visit map, as they are. The parent's genes hold no run of
        // three zeros, so the search for one starts where the child's own genes do.
        remove_zero_actions_after(ind, parents_genes);
        if !is_dead(&ind.genome) {
            return evaluations;
        }
        random_genome(rng, init.actions, init.dist_max, &mut ind.genome);
        base = Base::None;
    }
}

#[cfg(test)]
mod tests;
