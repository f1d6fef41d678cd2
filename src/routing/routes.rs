//! Routed moves: the wall-free way a robot of a given width drives from one viewpoint of a
//! thesis genome to the next, the remedy 003 §5.3 names for moves that run into obstacles.
//!
//! A move `a → b` is driven straight, exactly as 003 sweeps it, when both viewpoints are places
//! the robot can stand ([`Router::position`]) and its body along the segment touches no
//! non-free cell (the executability rule of `map::body`, tested exactly:
//! [`Router::segment_clear`]). Otherwise the robot drives from where it stands near `a` to where
//! it stands near `b` (a viewpoint inside a wall or an unreachable pocket is replaced by the
//! nearest reachable cell centre the robot fits on) along a path of robot centres with
//! clearance ≥ width/2: it joins the grid of reachable centres at the nearest one its body
//! reaches along a clear leg (`Router::entry_centre`), follows weighted A* over that grid,
//! 8-connected without corner cutting (the moves of [`Clearance::steps`], as the cell-order
//! GA's transit matrix in [`super::transit`]), and is shortened by line of sight where the
//! body keeps clear. The heuristic is the larger of the octile distance and a landmark bound,
//! weighted by [`HEURISTIC_WEIGHT`]: a grid route at most that factor longer than the
//! shortest, found some five times faster on the office floor plan; the line-of-sight pass
//! then straightens it. Each move's route depends on its two viewpoints only, so a routed
//! path is the concatenation of its moves' routes and the incremental evaluator's
//! segment-by-segment bookkeeping holds unchanged; routes are cached per worker.
//!
//! A place where the body fits but no clear leg joins it to the grid (a lane at the clearance
//! limit in a corridor too narrow for any cell centre) counts as no place to stand, and the
//! robot stands at the nearest reachable centre instead: every route then passes the rule.
//!
//! On a map with no obstacle cells every viewpoint is a place to stand and every segment is
//! clear, so routed moves are the straight moves bit for bit.

use crate::coverage::bits::BitLayers;
use crate::geom::Point;
use crate::map::GridMap;
use crate::map::body;
use crate::map::clearance::Clearance;
use crate::map::reach::Reach;
use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap};
use std::hash::{BuildHasherDefault, Hasher};

/// Routes kept per worker before the cache starts again (about 24 bytes each plus points).
const CACHE_ROUTES: usize = 1 << 17;
/// Route points kept per worker before the cache starts again (16 bytes each).
const CACHE_POINTS: usize = 1 << 21;
/// Weight of the A* heuristic: routes at most this factor longer than the shortest grid path.
pub const HEURISTIC_WEIGHT: f64 = 1.5;
/// Extra slack of the standing test ([`Router::can_stand`]) over the planners' clearance
/// slack. The patterns put lane ends exactly at the clearance limit, and a pattern written
/// as a thesis genome decodes to viewpoints that the viewpoint lattice
/// (`thesis::genome::LATTICE_M`, 2⁻³⁶ m) and the chain of moves put up to about 7·10⁻¹⁰ m
/// (measured on a 1 305-point boustrophedon of the office floor plan) past that limit; without
/// a slack such a viewpoint counts as a place the robot cannot stand and is moved to a cell
/// centre centimetres away. 10⁻⁸ m is ten times that drift and a hundred times below the
/// planners' own slack: no point a random genome decodes to is practically ever that close.
pub const STAND_SLACK_M: f64 = 1e-8;
/// Landmarks of the A* heuristic (one cache line of `f32` distances per cell).
const LANDMARKS: usize = 16;
/// Line-of-sight answers between two cell centres kept per worker before starting again.
const CACHE_SIGHTS: usize = 1 << 20;

/// A hasher for the caches' integer keys (the multiply-rotate of rustc's `FxHasher`): the keys
/// are the bits of coordinates and cell indices, never chosen by an adversary, and the
/// standard library's SipHash costs more than the lookup it serves. Which hasher a map uses
/// changes no answer, only how fast it is found.
#[derive(Clone, Copy, Debug, Default)]
struct KeyHasher(u64);

impl Hasher for KeyHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(word));
        }
    }

    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }

    fn write_u32(&mut self, x: u32) {
        self.write_u64(u64::from(x));
    }

    fn write_usize(&mut self, x: usize) {
        self.write_u64(x as u64);
    }
}

/// A map keyed by integers, hashed by [`KeyHasher`].
type KeyMap<K, V> = HashMap<K, V, BuildHasherDefault<KeyHasher>>;

/// Where a robot of one width can stand and how it gets around on one map, from its stations.
#[derive(Clone, Debug)]
pub struct Router {
    clear: Clearance<'static>,
    /// Free cells some reachable pose of the robot sweeps (row-major).
    coverable: Vec<bool>,
    width: f64,
    /// For every cell, the reachable centre the robot fits on nearest to it (by 8-connected
    /// grid distance through all cells; `u32::MAX` when there is none).
    nearest: Vec<u32>,
    /// Grid distances (in cells) from each landmark to every reachable centre, `LANDMARKS` per
    /// cell; `f32::INFINITY` off the component.
    landmarks: Vec<f32>,
    /// The map's free cells as bit rows: a segment whose rectangle, a cell wider than the
    /// robot on either side, holds no other cell is clear without sampling it.
    bits: BitLayers,
}

/// A move's route: where it starts (where the robot stands at its first viewpoint) and the
/// points it drives through, the last one where the robot stands at its second viewpoint.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MoveRoute<'s> {
    /// The robot's position at the move's first viewpoint.
    pub start: Point,
    /// The points after `start`, ending at the robot's position at the second viewpoint.
    pub points: &'s [Point],
}

/// Reusable buffers of routing, one per worker: the A* arrays (reset by stamps, not cleared)
/// and the cache of routes already found.
#[derive(Debug, Default)]
pub struct RouteScratch {
    g: Vec<f64>,
    parent: Vec<u32>,
    stamp: Vec<u32>,
    closed: Vec<u32>,
    epoch: u32,
    heap: BinaryHeap<Reverse<(u64, u64, u32)>>,
    raw: Vec<Point>,
    /// Routes by the bits of their two viewpoints: start and the range of their points.
    cache: KeyMap<[u64; 4], (Point, u32, u32)>,
    points: Vec<Point>,
    /// Grid routes by their two cells: the range of their turning cells in `grid_cells`.
    grid_paths: KeyMap<(u32, u32), (u32, u32)>,
    grid_cells: Vec<u32>,
    /// [`Router::segment_clear`] between two cell centres, by the cells (first in the high
    /// half): the line-of-sight pass asks the same pairs again and again along grid routes
    /// it has straightened before.
    sights: KeyMap<u64, bool>,
    /// Routes searched so far (cache misses).
    searches: u64,
}

impl Clone for RouteScratch {
    /// A clone starts empty: a cache is a per-worker speed-up, never state.
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl RouteScratch {
    /// Routes computed so far (not found in the cache).
    pub fn searches(&self) -> u64 {
        self.searches
    }
}

impl Router {
    /// An upper estimate of a router's bytes on a map of `cells` cells used by `threads`
    /// worker threads: the landmark distances and tables, and each worker's search arrays and
    /// full route cache.
    pub fn memory_estimate(cells: usize, threads: usize) -> f64 {
        let shared = cells * (LANDMARKS * 4 + 4 + 8 + 1);
        let per_thread = cells * 20 + CACHE_ROUTES * (48 + 24) + CACHE_POINTS * (16 + 4);
        (shared + per_thread * threads.max(1)) as f64
    }

    /// The router of a robot `width` metres wide on `map`, whose plans start and end at
    /// `stations`: it stays in the stations' component.
    pub fn new(map: &GridMap, width: f64, stations: &[Point]) -> Self {
        let mut clear = Clearance::owned(map.clone(), width);
        let reach = Reach::new(&clear, stations);
        clear.restrict(reach.centres().to_vec());
        let landmarks = landmark_distances(&clear, stations);
        let nearest = nearest_centres(&clear);
        let bits = BitLayers::new(&crate::coverage::CoverageGrid::new(map));
        Self { clear, coverable: reach.coverable().to_vec(), width, nearest, landmarks, bits }
    }

    /// Whether the robot's body along `p → q`, both places it fits, keeps clear of every
    /// non-free cell and the map's edge: exactly the executability rule of `map::body`, so that
    /// a move driven straight is never one the scorer refuses. Accepted at once where the
    /// segment's rectangle widened by a cell on either side and lengthened by a cell at either
    /// end holds no non-free cell centre (a cell square nearer than a radius to the segment has
    /// its centre in that rectangle, or lies wholly beyond an end, where the end's own
    /// clearance keeps it off; the map's edge stays clear between two ends that keep clear of
    /// it); refused at once where the rectangle half a cell narrower than the robot holds one
    /// (its square then lies nearer than the radius less the rule's slack); else decided by
    /// [`body::segment_clear_of_cells`].
    pub fn segment_clear(&self, p: Point, q: Point) -> bool {
        let map = self.clear.map();
        let res = map.resolution();
        let along = q - p;
        let len = along.norm();
        if len == 0.0 {
            return true;
        }
        let step = along * (res / len);
        if self.bits.obstacle_cells(p - step, q + step, self.width + 2.0 * res) == 0 {
            return true;
        }
        if self.width > 2.0 * res && self.bits.obstacle_cells(p, q, self.width - res) > 0 {
            return false;
        }
        body::segment_clear_of_cells(map, p, q, self.width)
    }

    /// The reachable centre where a route from or to `p` joins the grid, if a clear leg
    /// ([`Router::segment_clear`]) joins them: the nearest one by grid distance
    /// ([`Router::nearest`]) when its leg is clear, else the fitting centre nearest to `p`
    /// within a robot's width whose leg is clear (ties to the lower index). `None` where there
    /// is none: `p` is then no place to stand ([`Router::position`]). Grid routes between
    /// centres need no test of their own: a step between two fitting centres, diagonal ones
    /// without cutting a corner, comes no nearer to any cell square than its ends do.
    fn entry_centre(&self, p: Point) -> Option<usize> {
        let map = self.clear.map();
        let centre = |i: usize| map.cell_centre(i / map.cols(), i % map.cols());
        let nearest = self.nearest_centre(p)?;
        if self.segment_clear(p, centre(nearest)) {
            return Some(nearest);
        }
        let i = self.cell_of(map.clamp(p))?;
        let (r0, c0, cols) = ((i / map.cols()) as isize, (i % map.cols()) as isize, map.cols() as isize);
        let reach = (self.width / map.resolution()).ceil() as isize;
        // The least (distance, index) among the clear legs; a leg is tested only when it would
        // be the best so far, the costly test last.
        let mut best: Option<(f64, usize)> = None;
        for r in (r0 - reach).max(0)..=(r0 + reach).min(map.rows() as isize - 1) {
            for c in (c0 - reach).max(0)..=(c0 + reach).min(cols - 1) {
                let j = (r * cols + c) as usize;
                let d = (centre(j) - p).norm();
                let better = best.is_none_or(|(bd, bj)| d.total_cmp(&bd).then(j.cmp(&bj)).is_lt());
                if better && self.clear.centre_fits(j) && self.segment_clear(p, centre(j)) {
                    best = Some((d, j));
                }
            }
        }
        best.map(|(_, j)| j)
    }

    /// The robot width the routes are planned for.
    pub fn width(&self) -> f64 {
        self.width
    }

    /// Whether the robot can stand at `p`: its cell is swept by some reachable pose and the disc
    /// centred at `p` keeps clear of every non-free cell (to [`STAND_SLACK_M`]).
    pub fn can_stand(&self, p: Point) -> bool {
        self.cell_of(p).is_some_and(|i| {
            self.coverable[i]
                && self.clear.inside_edges_within(p, STAND_SLACK_M)
                && self.clear.clear_of_cells_within(p, STAND_SLACK_M)
        })
    }

    /// The cell holding `p` (the map's upper edges belong to its last row and column, where
    /// decoded viewpoints are clamped), if `p` lies on the map.
    fn cell_of(&self, p: Point) -> Option<usize> {
        let map = self.clear.map();
        if !map.contains(p) {
            return None;
        }
        let cell = |v: f64, o: f64, n: usize| (((v - o) / map.resolution()).floor() as usize).min(n - 1);
        Some(map.index(cell(p.y, map.origin().y, map.rows()), cell(p.x, map.origin().x, map.cols())))
    }

    /// The reachable centre the robot fits on nearest to `p` (see [`Router::nearest`]).
    fn nearest_centre(&self, p: Point) -> Option<usize> {
        let map = self.clear.map();
        let i = self.cell_of(map.clamp(p))?;
        (self.nearest[i] != u32::MAX).then_some(self.nearest[i] as usize)
    }

    /// Where the robot stands when aimed at `p`: `p` itself where it can stand there and a
    /// clear leg joins it to the grid of reachable centres (`Router::entry_centre`), else the
    /// nearest reachable cell centre it fits on (`p` if there is none). A place where the body
    /// fits but no such leg exists (a lane at the clearance limit in a corridor too narrow for
    /// any cell centre) is no place to stand: every route from or to it would touch a wall.
    pub fn position(&self, p: Point) -> Point {
        if self.can_stand(p) && self.entry_centre(p).is_some() {
            return p;
        }
        let map = self.clear.map();
        self.nearest_centre(p).map_or(p, |i| map.cell_centre(i / map.cols(), i % map.cols()))
    }

    /// The route of the move `a → b` (cached in `scratch`). `layers` are the map's bit rows,
    /// which tell whether a segment's swept rectangle holds obstacle cells.
    pub fn route<'s>(&self, a: Point, b: Point, scratch: &'s mut RouteScratch) -> MoveRoute<'s> {
        let key = [a.x.to_bits(), a.y.to_bits(), b.x.to_bits(), b.y.to_bits()];
        let (start, from, len) = match scratch.cache.get(&key) {
            Some(&hit) => hit,
            None => {
                if scratch.cache.len() >= CACHE_ROUTES || scratch.points.len() >= CACHE_POINTS {
                    scratch.cache.clear();
                    scratch.points.clear();
                }
                scratch.searches += 1;
                let from = scratch.points.len();
                let start = self.search(a, b, scratch);
                let entry = (start, from as u32, (scratch.points.len() - from) as u32);
                scratch.cache.insert(key, entry);
                entry
            }
        };
        MoveRoute { start, points: &scratch.points[from as usize..(from + len) as usize] }
    }

    /// The driven path of the viewpoints `points`: the robot's position at the first, then each
    /// move's route, into `out` (cleared first).
    pub fn expand(&self, points: &[Point], scratch: &mut RouteScratch, out: &mut Vec<Point>) {
        out.clear();
        let Some(&first) = points.first() else { return };
        out.push(self.position(first));
        for w in points.windows(2) {
            out.extend_from_slice(self.route(w[0], w[1], scratch).points);
        }
    }

    /// Finds the route of `a → b`, appends its points to `scratch.points` and returns its start.
    fn search(&self, a: Point, b: Point, scratch: &mut RouteScratch) -> Point {
        let clear_segment = |p: Point, q: Point| self.segment_clear(p, q);
        let (pa, pb) = (self.position(a), self.position(b));
        // Where the robot stands at both viewpoints this is 003's straight move, if clear.
        if pa == pb || clear_segment(pa, pb) {
            scratch.points.push(pb);
            return pa;
        }
        let map = self.clear.map();
        let centre = |i: usize| map.cell_centre(i / map.cols(), i % map.cols());
        let ends = (self.entry_centre(pa), self.entry_centre(pb));
        let Some((from, len)) = (match ends {
            (Some(s), Some(t)) => self.turning_cells(s, t, scratch),
            _ => None,
        }) else {
            // No wall-free way (a station off the component): drive straight and let the
            // obstacle cells count.
            scratch.points.push(pb);
            return pa;
        };
        // The cells where the grid route turns, from `pa`'s to `pb`'s; the ends join them.
        let mut raw = std::mem::take(&mut scratch.raw);
        raw.clear();
        raw.push(pa);
        raw.extend(scratch.grid_cells[from..from + len].iter().map(|&i| centre(i as usize)));
        raw.push(pb);
        // Line of sight, forwards: from each anchor go on while the rectangle stays clear.
        // Between two of the route's cells (raw[1..=len]) the answer is the cells' own.
        if scratch.sights.len() >= CACHE_SIGHTS {
            scratch.sights.clear();
        }
        let RouteScratch { sights, grid_cells, points, .. } = scratch;
        let cells = &grid_cells[from..from + len];
        let mut sees = |i: usize, j: usize| {
            if i == 0 || j == raw.len() - 1 {
                return clear_segment(raw[i], raw[j]);
            }
            let key = (u64::from(cells[i - 1]) << 32) | u64::from(cells[j - 1]);
            *sights.entry(key).or_insert_with(|| clear_segment(raw[i], raw[j]))
        };
        let mut anchor = 0;
        while anchor + 1 < raw.len() {
            let mut next = anchor + 1;
            while next + 1 < raw.len() && sees(anchor, next + 1) {
                next += 1;
            }
            points.push(raw[next]);
            anchor = next;
        }
        raw.clear();
        scratch.raw = raw;
        pa
    }

    /// The cells where the grid route from cell `s` to cell `t` turns (its first and last
    /// included), as a range of `scratch.grid_cells`: only they can be anchors worth keeping,
    /// straight runs between them adding line-of-sight tests and nothing else. The route
    /// depends on the two cells alone, so it is searched once per worker and pair (`None`: no
    /// route).
    fn turning_cells(&self, s: usize, t: usize, scratch: &mut RouteScratch) -> Option<(usize, usize)> {
        let key = (s as u32, t as u32);
        if let Some(&(from, len)) = scratch.grid_paths.get(&key) {
            return Some((from as usize, len as usize));
        }
        if !self.astar(s, t, scratch) {
            return None;
        }
        if scratch.grid_paths.len() >= CACHE_ROUTES || scratch.grid_cells.len() >= CACHE_POINTS {
            scratch.grid_paths.clear();
            scratch.grid_cells.clear();
        }
        let cells: Vec<usize> = scratch.raw.iter().map(|p| p.x as usize).collect();
        let from = scratch.grid_cells.len();
        for (k, &i) in cells.iter().enumerate() {
            let turns = k == 0 || k + 1 == cells.len() || {
                let step = |x: usize, y: usize| y as isize - x as isize;
                step(cells[k - 1], i) != step(i, cells[k + 1])
            };
            if turns {
                scratch.grid_cells.push(i as u32);
            }
        }
        let len = scratch.grid_cells.len() - from;
        scratch.grid_paths.insert(key, (from as u32, len as u32));
        Some((from, len))
    }

    /// A* from cell `from` to cell `to` over the fitting reachable centres; on success the cells
    /// of the path, in order, are left in `scratch.raw` (cell index in `x`, to be replaced by
    /// the centre).
    fn astar(&self, from: usize, to: usize, scratch: &mut RouteScratch) -> bool {
        let map = self.clear.map();
        let (cols, n) = (map.cols(), map.rows() * map.cols());
        if scratch.g.len() != n {
            scratch.g = vec![f64::INFINITY; n];
            scratch.parent = vec![u32::MAX; n];
            scratch.stamp = vec![0; n];
            scratch.closed = vec![0; n];
            scratch.epoch = 0;
        }
        if scratch.epoch == u32::MAX {
            scratch.stamp.fill(0);
            scratch.closed.fill(0);
            scratch.epoch = 0;
        }
        scratch.epoch += 1;
        let epoch = scratch.epoch;
        let (tr, tc) = ((to / cols) as f64, (to % cols) as f64);
        let target = &self.landmarks[to * LANDMARKS..(to + 1) * LANDMARKS];
        // The larger of two lower bounds of the grid distance: the octile distance (exact on an
        // empty grid) and the landmarks' triangle inequality, which sees walls (ALT: Goldberg
        // and Harrelson 2005); weighted, so that far fewer cells are expanded.
        let h = |i: usize| {
            let (dr, dc) = (((i / cols) as f64 - tr).abs(), ((i % cols) as f64 - tc).abs());
            let octile = dr.max(dc) + (std::f64::consts::SQRT_2 - 1.0) * dr.min(dc);
            let here = &self.landmarks[i * LANDMARKS..(i + 1) * LANDMARKS];
            let alt = here.iter().zip(target).fold(0.0f32, |m, (a, b)| m.max((a - b).abs()));
            // f32 distances round: a thousandth of a cell below keeps the bound a bound.
            HEURISTIC_WEIGHT * octile.max(f64::from(alt) - 1e-3)
        };
        // Keys in 1e-6 cell units keep the order total and deterministic; among equal keys the
        // cell farthest from the start goes first, which spares the many ties of open floors.
        let key = |f: f64| (f * 1e6) as u64;
        let RouteScratch { g, parent, stamp, closed, heap, raw, .. } = scratch;
        heap.clear();
        stamp[from] = epoch;
        g[from] = 0.0;
        parent[from] = u32::MAX;
        heap.push(Reverse((key(h(from)), u64::MAX, from as u32)));
        while let Some(Reverse((_, _, i))) = heap.pop() {
            let i = i as usize;
            if closed[i] == epoch {
                continue; // a stale entry
            }
            closed[i] = epoch;
            if i == to {
                raw.clear();
                let mut k = to;
                while k != from {
                    raw.push(Point::new(k as f64, 0.0));
                    k = parent[k] as usize;
                }
                raw.push(Point::new(from as f64, 0.0));
                raw.reverse();
                return true;
            }
            for (j, step) in self.clear.steps(i) {
                let cand = g[i] + step;
                if closed[j] != epoch && (stamp[j] != epoch || cand < g[j] - 1e-12) {
                    stamp[j] = epoch;
                    g[j] = cand;
                    parent[j] = i as u32;
                    heap.push(Reverse((key(cand + h(j)), u64::MAX - key(cand), j as u32)));
                }
            }
        }
        false
    }
}

/// Grid distances from [`LANDMARKS`] landmarks spread over the stations' component, `LANDMARKS`
/// per cell (cell-major): the first is the centre farthest from the first station, each next
/// one the centre farthest from those chosen (ties to the lowest index), so that they sit in
/// the far corners and rooms where the triangle inequality bounds best.
fn landmark_distances(clear: &Clearance, stations: &[Point]) -> Vec<f32> {
    let map = clear.map();
    let n = map.rows() * map.cols();
    let mut out = vec![f32::INFINITY; n * LANDMARKS];
    let Some(first) = stations.first().and_then(|&p| clear.snap(p)) else { return out };
    let farthest =
        |d: &[f32]| (0..n).filter(|&i| d[i].is_finite()).fold(first, |best, i| if d[i] > d[best] { i } else { best });
    let mut nearest = dijkstra(clear, first);
    for l in 0..LANDMARKS {
        let landmark = farthest(&nearest);
        let d = dijkstra(clear, landmark);
        for (i, v) in d.iter().enumerate() {
            out[i * LANDMARKS + l] = *v;
            nearest[i] = if l == 0 { *v } else { nearest[i].min(*v) };
        }
    }
    out
}

/// For every cell, the fitting reachable centre nearest to it by 8-connected grid distance
/// through all cells (walls included: a viewpoint inside a wall goes to the nearer side), ties
/// to the lower index; `u32::MAX` everywhere when no centre fits. One multi-source Dijkstra.
fn nearest_centres(clear: &Clearance) -> Vec<u32> {
    let map = clear.map();
    let (rows, cols) = (map.rows() as isize, map.cols() as isize);
    let n = map.rows() * map.cols();
    let mut dist = vec![f64::INFINITY; n];
    let mut source = vec![u32::MAX; n];
    let mut heap = BinaryHeap::new();
    for i in (0..n).filter(|&i| clear.centre_fits(i)) {
        dist[i] = 0.0;
        source[i] = i as u32;
        heap.push(Reverse(((0.0f64).to_bits(), i as u32, i)));
    }
    while let Some(Reverse((d, src, i))) = heap.pop() {
        let d = f64::from_bits(d);
        if d > dist[i] || src != source[i] {
            continue;
        }
        let (r, c) = ((i as isize) / cols, (i as isize) % cols);
        for (dr, dc) in [(-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1)] {
            let (nr, nc) = (r + dr, c + dc);
            if nr < 0 || nc < 0 || nr >= rows || nc >= cols {
                continue;
            }
            let j = (nr * cols + nc) as usize;
            let nd = d + if dr != 0 && dc != 0 { std::f64::consts::SQRT_2 } else { 1.0 };
            if nd < dist[j] || (nd == dist[j] && src < source[j]) {
                dist[j] = nd;
                source[j] = src;
                heap.push(Reverse((nd.to_bits(), src, j)));
            }
        }
    }
    source
}

/// Grid distances in cells from cell `from` over the fitting centres ([`Clearance::steps`]).
fn dijkstra(clear: &Clearance, from: usize) -> Vec<f32> {
    let map = clear.map();
    let mut dist = vec![f64::INFINITY; map.rows() * map.cols()];
    let mut heap = BinaryHeap::new();
    dist[from] = 0.0;
    heap.push(Reverse(((0.0f64).to_bits(), from)));
    while let Some(Reverse((d, i))) = heap.pop() {
        let d = f64::from_bits(d);
        if d > dist[i] {
            continue;
        }
        for (j, step) in clear.steps(i) {
            if d + step < dist[j] {
                dist[j] = d + step;
                heap.push(Reverse(((d + step).to_bits(), j)));
            }
        }
    }
    dist.into_iter().map(|d| d as f32).collect()
}

#[cfg(test)]
#[path = "routes/tests.rs"]
mod tests;
