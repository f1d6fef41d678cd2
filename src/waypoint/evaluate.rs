//! Objectives, constraints and penalties of the waypoint planner (000 §II-C, §III-A.4, §III-B;
//! waypoint §5–6, §12–13): union camera coverage (eq. 2), flight time with turning cost (eq. 3),
//! loop closures, the agents' loop-closure Laplacian, the coverage ramp and the scaled,
//! penalised objective vector.

use super::graph::Graph;
use super::precompute::{Traversals, Union};
use crate::coverage::camera::{blended_coverage, wrap};

/// Parameters of the objectives and constraints (Table I as reconciled in waypoint §18–19).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObjectiveParams {
    /// `α_cov`, weight of open-space coverage in eq. 2.
    pub alpha_cov: f64,
    /// `ρ`, turning cost factor (multiplier and exponent, eq. 3).
    pub rho: f64,
    /// Scaling of `−C` (−1.0).
    pub scale_coverage: f64,
    /// Scaling of flight time (0.0001).
    pub scale_time: f64,
    /// `C_start`.
    pub c_start: f64,
    /// `C_end`.
    pub c_end: f64,
    /// `G_age`.
    pub aging: u32,
    /// `T_sep` (waypoints).
    pub lc_separation: usize,
    /// Minimum self loop closures per agent.
    pub lc_min: usize,
    /// What counts as one loop closure.
    pub lc_rule: LoopClosureRule,
    /// `P_cov` = `P_time` (scaled units).
    pub penalty: f64,
}

/// `C_req(g) = C_start + (C_end − C_start)·min(1, g/G_age)` (waypoint §12.2, W22).
pub fn required_coverage(p: &ObjectiveParams, generation: u32) -> f64 {
    let t = if p.aging == 0 { 1.0 } else { (f64::from(generation) / f64::from(p.aging)).min(1.0) };
    p.c_start + (p.c_end - p.c_start) * t
}

/// Turning surcharge `ρ·|Δψ/(π/2)|^ρ` of one interior waypoint (000 eq. 3, W12).
pub fn turn_cost(rho: f64, delta_psi: f64) -> f64 {
    rho * (wrap(delta_psi).abs() / std::f64::consts::FRAC_PI_2).powf(rho)
}

/// Flight time of a path in px-equivalents: leg lengths plus turning surcharges (000 eq. 3).
pub fn flight_time(path: &[u32], graph: &Graph, tr: &Traversals, rho: f64) -> f64 {
    let mut total = 0.0;
    let mut prev: Option<f64> = None;
    for w in path.windows(2) {
        let t = tr.get(graph, w[0] as usize, w[1] as usize);
        total += t.dist;
        if let Some(h) = prev {
            total += turn_cost(rho, t.heading - h);
        }
        prev = Some(t.heading);
    }
    total
}

/// The turning surcharges of a graph's every pair of consecutive edges, computed once per run:
/// [`flight_time`] computes `|Δψ|^ρ` at each interior waypoint, which made `pow` a tenth of a
/// generation. Entries are [`turn_cost`] of the same arguments, so the sum is the same to the
/// bit.
#[derive(Clone, Debug, Default)]
pub struct TurnCosts {
    /// Id of the first edge leaving each waypoint (edge `i → adj[i][k]` is `first[i] + k`).
    first: Vec<usize>,
    /// Per edge `u → v`, where its costs start in `costs`; `adj[v].len()` of them follow.
    start: Vec<usize>,
    /// `turn_cost(ρ, ψ(v → adj[v][k]) − ψ(u → v))` for each edge `u → v` and each `k`.
    costs: Vec<f64>,
}

impl TurnCosts {
    /// The table of `graph` with the headings of `tr` and exponent `rho`.
    pub fn new(graph: &Graph, tr: &Traversals, rho: f64) -> Self {
        let mut table = Self::default();
        let mut edges = 0;
        for adj in &graph.adj {
            table.first.push(edges);
            edges += adj.len();
        }
        for (u, adj) in graph.adj.iter().enumerate() {
            for (k, &v) in adj.iter().enumerate() {
                let arrive = tr.edges[u][k].heading;
                table.start.push(table.costs.len());
                let leave = &tr.edges[v as usize];
                table.costs.extend(leave.iter().map(|t| turn_cost(rho, t.heading - arrive)));
            }
        }
        table
    }

    /// [`flight_time`] of `path` with the surcharges looked up (the same value to the bit).
    pub fn flight_time(&self, path: &[u32], graph: &Graph, tr: &Traversals) -> f64 {
        let mut total = 0.0;
        let mut arriving: Option<usize> = None;
        for w in path.windows(2) {
            let i = w[0] as usize;
            let k = graph.adj[i].binary_search(&w[1]).expect("consecutive waypoints are joined by an edge");
            total += tr.edges[i][k].dist;
            if let Some(e) = arriving {
                total += self.costs[self.start[e] + k];
            }
            arriving = Some(self.first[i] + k);
        }
        total
    }
}

/// ORs the views of a path into `u` (one pose per waypoint facing the next; the last facing
/// its arrival direction, W10).
pub fn add_views(path: &[u32], graph: &Graph, tr: &Traversals, u: &mut Union) {
    for w in path.windows(2) {
        u.add(&tr.get(graph, w[0] as usize, w[1] as usize).depart);
    }
    if let [.., a, b] = path {
        u.add(&tr.get(graph, *a as usize, *b as usize).arrive);
    }
}

/// What counts as one loop closure (000 §III-A.4: the same waypoints flown in the same
/// direction).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LoopClosureRule {
    /// A run of consecutive re-flown edges counts once (W23).
    #[default]
    Run,
    /// Every distinct re-flown directed edge counts once (the authors' driver).
    Edge,
}

impl LoopClosureRule {
    /// The rule's name as typed in `[waypoint]`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Run => "run",
            Self::Edge => "edge",
        }
    }
    /// Loop closures between `a` and `b` under this rule (see [`loop_closures`] and
    /// [`edge_loop_closures`]).
    pub fn count(self, a: &[u32], b: &[u32], same: bool, separation: usize) -> usize {
        match self {
            Self::Run => loop_closures(a, b, same, separation),
            Self::Edge => edge_loop_closures(a, b, same, separation),
        }
    }
}

/// Loop closures counted per distinct re-flown directed edge (the authors' driver): an edge of
/// `a` counts once if `b` flies it too — for a path with itself (`same`), at least
/// `separation` positions after the edge's first occurrence.
pub fn edge_loop_closures(a: &[u32], b: &[u32], same: bool, separation: usize) -> usize {
    EDGE_LISTS.with_borrow_mut(|(ka, kb)| {
        sorted_edges(a, ka);
        sorted_edges(b, kb);
        let mut count = 0;
        let mut rest: &[(u64, u32)] = kb;
        // Groups of one edge in `a`, first occurrence first; the last of its group in `b` is
        // its latest occurrence there.
        for (g, &(edge, first)) in ka.iter().enumerate() {
            if g > 0 && ka[g - 1].0 == edge {
                continue;
            }
            let from = if same { first as usize + separation.max(1) } else { 0 };
            rest = &rest[rest.partition_point(|&(e, _)| e < edge)..];
            let last_in_b = rest.iter().take_while(|&&(e, _)| e == edge).last();
            if last_in_b.is_some_and(|&(_, j)| j as usize >= from) {
                count += 1;
            }
        }
        count
    })
}

/// Loop closures between the directed edges of `a` and `b` (waypoint §12.3, W23): matches `(i, j)`
/// with the same directed edge and, for a path with itself (`same`), `j − i ≥ separation`;
/// a run of consecutive matches counts once.
///
/// Only pairs with the same edge can match, so `b`'s edges are sorted once and each edge of
/// `a` looks up its occurrences: O((|a| + |b|)·log |b|) instead of every pair of positions.
/// A match `(i, j)` continues a run when `(i − 1, j − 1)` matches too; with `a[i] = b[j]`
/// known and the separation the same for both, that is `a[i − 1] = b[j − 1]`.
pub fn loop_closures(a: &[u32], b: &[u32], same: bool, separation: usize) -> usize {
    EDGE_LISTS.with_borrow_mut(|(_, kb)| {
        sorted_edges(b, kb);
        let separation = separation.max(1);
        let mut count = 0;
        for i in 0..a.len().saturating_sub(1) {
            let edge = edge_key(a, i);
            let start = kb.partition_point(|&(e, _)| e < edge);
            for &(_, j) in kb[start..].iter().take_while(|&&(e, _)| e == edge) {
                let j = j as usize;
                let separated = !same || j >= i + separation;
                let continues_run = i > 0 && j > 0 && a[i - 1] == b[j - 1];
                count += usize::from(separated && !continues_run);
            }
        }
        count
    })
}

/// The directed edge `path[i] → path[i + 1]` as one sortable key.
#[inline]
fn edge_key(path: &[u32], i: usize) -> u64 {
    (u64::from(path[i]) << 32) | u64::from(path[i + 1])
}

/// `(edge, position)` of every edge of `path`, sorted by edge, then position.
fn sorted_edges(path: &[u32], out: &mut EdgeList) {
    out.clear();
    out.extend((0..path.len().saturating_sub(1)).map(|i| (edge_key(path, i), i as u32)));
    out.sort_unstable();
}

/// Directed edges as `(key, position)`, sorted (see [`sorted_edges`]).
type EdgeList = Vec<(u64, u32)>;

thread_local! {
    /// The sorted edge lists of [`loop_closures`] and [`edge_loop_closures`], kept per thread
    /// so that counting allocates nothing once they have grown.
    static EDGE_LISTS: std::cell::RefCell<(EdgeList, EdgeList)> = const {
        std::cell::RefCell::new((Vec::new(), Vec::new()))
    };
}

/// Number of connected components of the agents' loop-closure graph (= the number of zero
/// eigenvalues of its Laplacian), by union–find (W25).
pub fn components(adjacent: &[Vec<bool>]) -> usize {
    let n = adjacent.len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    for (i, row) in adjacent.iter().enumerate() {
        for (j, _) in row.iter().enumerate().skip(i + 1).filter(|(_, a)| **a) {
            let (a, b) = (find(&mut parent, i), find(&mut parent, j));
            parent[a] = b;
        }
    }
    (0..n).filter(|&i| find(&mut parent, i) == i).count()
}

/// The Laplacian `L = D − A` (000 eqs. 5–7) and its number of eigenvalues with `|λ| < tol`
/// (nalgebra's symmetric eigen-decomposition).
pub fn laplacian_zero_eigenvalues(adjacent: &[Vec<bool>], tol: f64) -> usize {
    let n = adjacent.len();
    let l = nalgebra::DMatrix::from_fn(n, n, |i, j| {
        if i == j {
            adjacent[i].iter().enumerate().filter(|&(k, &a)| a && k != i).count() as f64
        } else if adjacent[i][j] {
            -1.0
        } else {
            0.0
        }
    });
    l.symmetric_eigenvalues().iter().filter(|v| v.abs() < tol).count()
}

/// Everything measured of one organism (one path per agent).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Evaluation {
    /// `C_open`.
    pub open: f64,
    /// `C_walls`.
    pub walls: f64,
    /// `C` (eq. 2).
    pub coverage: f64,
    /// Total flight time (px-equivalents).
    pub flight_time: f64,
    /// Loop-closure matrix `C` (eq. 5): diagonal self closures, off-diagonal shared.
    pub closures: Vec<Vec<usize>>,
    /// Connected components of the agents' closure graph.
    pub components: usize,
}

impl Evaluation {
    /// Whether every agent has at least `lc_min` self loop closures.
    pub fn loops_ok(&self, lc_min: usize) -> bool {
        self.closures.iter().enumerate().all(|(i, row)| row[i] >= lc_min)
    }
    /// Whether the agents' closure graph is connected.
    pub fn connected(&self) -> bool {
        self.components == 1
    }
    /// Scaled, penalised objectives `(f1, f2)` at required coverage `c_req` (waypoint §12–13).
    pub fn objectives(&self, p: &ObjectiveParams, c_req: f64) -> [f64; 2] {
        let mut f1 = p.scale_coverage * self.coverage;
        let mut f2 = p.scale_time * self.flight_time;
        if !self.loops_ok(p.lc_min) || !self.connected() {
            f1 += p.penalty;
        }
        if self.coverage < c_req {
            f2 += p.penalty;
        }
        [f1, f2]
    }
    /// Number of violated constraint types at `c_req`.
    pub fn violations(&self, p: &ObjectiveParams, c_req: f64) -> usize {
        usize::from(!self.loops_ok(p.lc_min)) + usize::from(!self.connected()) + usize::from(self.coverage < c_req)
    }
}

/// The fixed parts of an evaluation.
pub struct Evaluator<'a> {
    /// The graph.
    pub graph: &'a Graph,
    /// Traversal data.
    pub traversals: &'a Traversals,
    /// Bitset of the wall band `B`.
    pub band: &'a [u64],
    /// `|F|`.
    pub free: u64,
    /// `|B|`.
    pub band_count: u64,
    /// Parameters.
    pub params: ObjectiveParams,
    /// The turning surcharges for `params.rho` ([`TurnCosts::new`]).
    pub turns: &'a TurnCosts,
}

impl Evaluator<'_> {
    /// Evaluates one organism (rows = agents' paths) using the scratch union.
    pub fn evaluate(&self, rows: &[Vec<u32>], scratch: &mut Union) -> Evaluation {
        scratch.clear();
        for r in rows {
            add_views(r, self.graph, self.traversals, scratch);
        }
        let (all, walls) = scratch.counts(self.band);
        let open = all as f64 / self.free.max(1) as f64;
        let walls = walls as f64 / self.band_count.max(1) as f64;
        let n = rows.len();
        let mut closures = vec![vec![0; n]; n];
        for i in 0..n {
            closures[i][i] = self.params.lc_rule.count(&rows[i], &rows[i], true, self.params.lc_separation);
            for j in i + 1..n {
                let c = self.params.lc_rule.count(&rows[i], &rows[j], false, 0);
                closures[i][j] = c;
                closures[j][i] = c;
            }
        }
        let adjacent: Vec<Vec<bool>> =
            (0..n).map(|i| (0..n).map(|j| i != j && closures[i][j] >= 1).collect()).collect();
        let comps = components(&adjacent);
        debug_assert_eq!(comps, laplacian_zero_eigenvalues(&adjacent, 1e-9));
        Evaluation {
            open,
            walls,
            coverage: blended_coverage(self.params.alpha_cov, open, walls),
            flight_time: rows.iter().map(|r| self.turns.flight_time(r, self.graph, self.traversals)).sum(),
            closures,
            components: comps,
        }
    }
}

#[cfg(test)]
mod tests;
