//! Where a disc-shaped robot of a given width fits, and collision-free connecting moves
//! (8-connected A* over cell centres, shortened by line of sight) for the pattern planners.
//! A clearance can be restricted to the part of the map reachable from the stations
//! ([`super::reach::Reach`]), so that planners never aim at pockets the robot cannot enter.

use crate::geom::Point;
use crate::map::GridMap;
use crate::map::wall_rows::WallRows;
use std::borrow::Cow;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Slack on the clearance test, so that lanes exactly half a width off a wall are drivable.
pub(crate) const CLEARANCE_EPS: f64 = 1e-6;

/// Clearance queries for a robot of radius `width / 2` on one map.
#[derive(Clone, Debug)]
pub struct Clearance<'m> {
    /// Borrowed by the planners that build one per run; owned by a [`Clearance::owned`] kept
    /// in a scenario.
    map: Cow<'m, GridMap>,
    radius: f64,
    window: isize,
    walls: WallRows,
    centre_ok: Vec<bool>,
    /// Per cell: every point of it keeps clear of the non-free cells with any slack: its
    /// centre keeps the radius plus half the cell's diagonal (and a margin far above rounding),
    /// and no point of the cell is farther from it than that. The window holds every cell
    /// that near: it reaches `radius + resolution` beyond the cell.
    roomy: Vec<bool>,
    /// Cell centres reachable from the stations, once restricted.
    reachable: Option<Vec<bool>>,
}

impl<'m> Clearance<'m> {
    /// Precomputes which cell centres the robot can occupy.
    pub fn new(map: &'m GridMap, width: f64) -> Self {
        Self::of(Cow::Borrowed(map), width)
    }

    /// [`Clearance::new`] on a map it keeps.
    pub fn owned(map: GridMap, width: f64) -> Clearance<'static> {
        Clearance::of(Cow::Owned(map), width)
    }

    fn of(map: Cow<'m, GridMap>, width: f64) -> Self {
        let radius = 0.5 * width;
        let window = (radius / map.resolution()).ceil() as isize + 1;
        let walls = WallRows::new(&map);
        let mut c = Self { map, radius, window, walls, centre_ok: Vec::new(), roomy: Vec::new(), reachable: None };
        let map = &*c.map;
        let half_diagonal = map.resolution() * std::f64::consts::FRAC_1_SQRT_2;
        let (lim, roomy_lim) = (radius - CLEARANCE_EPS, radius - CLEARANCE_EPS + half_diagonal + 1e-9);
        // Each cell's flags depend on the map alone.
        let flags = map.par_cells(|r, col| {
            let p = map.cell_centre(r, col);
            let d2 = c.nearest_cell_d2(p);
            // As `fits_geometry`, from the same squared distances.
            (c.inside_edges(p) && d2 >= lim * lim, d2 >= roomy_lim * roomy_lim)
        });
        let (centre_ok, roomy) = flags.into_iter().unzip();
        (c.centre_ok, c.roomy) = (centre_ok, roomy);
        c
    }

    /// Whether the robot disc centred at `p` stays on the map (the edges' test of
    /// [`Clearance::fits_geometry`]).
    fn inside_edges(&self, p: Point) -> bool {
        self.inside_edges_within(p, 0.0)
    }

    /// Whether the robot disc centred at `p` stays on the map, with `slack` metres more
    /// tolerance than the planners' own (see [`Clearance::clear_of_cells_within`]).
    pub fn inside_edges_within(&self, p: Point, slack: f64) -> bool {
        let m = &*self.map;
        let (ox, oy) = (m.origin().x, m.origin().y);
        let lim = self.radius - CLEARANCE_EPS - slack;
        !(p.x - ox < lim || p.y - oy < lim || ox + m.width_m() - p.x < lim || oy + m.height_m() - p.y < lim)
    }

    /// The distance from `p` to the nearest non-free cell square or the map's edge, capped at
    /// the window's reach (`radius + resolution`): what a station's refusal quotes.
    pub fn clearance_at(&self, p: Point) -> f64 {
        let m = &*self.map;
        let (o, cap) = (m.origin(), self.window as f64 * m.resolution());
        let edge = (p.x - o.x).min(p.y - o.y).min(o.x + m.width_m() - p.x).min(o.y + m.height_m() - p.y);
        self.nearest_cell_d2(p).sqrt().min(edge).min(cap)
    }

    /// The smallest squared distance from `p` to a non-free cell of the window about it
    /// (infinite when there is none).
    fn nearest_cell_d2(&self, p: Point) -> f64 {
        self.walls.least_near(&self.map, p, self.window, f64::INFINITY, |dx, dy| dx * dx + dy * dy, |dy| dy * dy)
    }

    /// Restricts every later query to the cell centres marked in `reachable` (one flag per
    /// cell, row-major): pieces and connections then stay in the stations' component.
    pub fn restrict(&mut self, reachable: Vec<bool>) {
        for (ok, r) in self.centre_ok.iter_mut().zip(&reachable) {
            *ok &= *r;
        }
        self.reachable = Some(reachable);
    }

    /// Whether [`Clearance::restrict`] narrowed the queries.
    pub fn is_restricted(&self) -> bool {
        self.reachable.is_some()
    }

    /// Whether the robot centred on cell `index` (row-major) fits (and is reachable, once
    /// restricted).
    pub fn centre_fits(&self, index: usize) -> bool {
        self.centre_ok[index]
    }

    /// The robot's radius in metres.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Whether the robot disc centred at `p` stays on the map and off every non-free cell and,
    /// once restricted, lies in or next to a reachable cell.
    pub fn fits(&self, p: Point) -> bool {
        self.fits_geometry(p) && self.near_reachable(p)
    }

    fn near_reachable(&self, p: Point) -> bool {
        let Some(reach) = &self.reachable else { return true };
        let m = &*self.map;
        let Some((r, c)) = m.cell_at(p) else { return false };
        let (r, c) = (r as isize, c as isize);
        (-1..=1).any(|dr| {
            (-1..=1).any(|dc| {
                let (nr, nc) = (r + dr, c + dc);
                nr >= 0
                    && nc >= 0
                    && (nr as usize) < m.rows()
                    && (nc as usize) < m.cols()
                    && reach[m.index(nr as usize, nc as usize)]
            })
        })
    }

    /// The map.
    pub fn map(&self) -> &GridMap {
        &self.map
    }

    /// Whether the robot disc centred at `p` stays on the map and off every non-free cell.
    pub fn fits_geometry(&self, p: Point) -> bool {
        self.inside_edges(p) && self.clear_of_cells(p)
    }

    /// Whether the robot disc centred at `p` keeps clear of every non-free cell of the map (the
    /// map's edge not counted: a disc may reach past it).
    pub fn clear_of_cells(&self, p: Point) -> bool {
        self.clear_of_cells_within(p, 0.0)
    }

    /// [`Clearance::clear_of_cells`] with `slack` metres more tolerance than the planners'
    /// own, for points that a planner put at the clearance limit and a later computation moved
    /// by a rounding error (see `routing::routes::STAND_SLACK_M`).
    pub fn clear_of_cells_within(&self, p: Point, slack: f64) -> bool {
        let m = &*self.map;
        if slack >= 0.0
            && let Some((r, c)) = m.cell_at(p)
            && self.roomy[m.index(r, c)]
        {
            return true;
        }
        let lim = self.radius - CLEARANCE_EPS - slack;
        // The same squared distances as a scan of the whole window (see WallRows).
        self.nearest_cell_d2(p) >= lim * lim
    }

    /// Whether every point of the segment fits (sampled every quarter cell).
    pub fn segment_fits(&self, a: Point, b: Point) -> bool {
        self.segment_fits_within(a, b, 0.0)
    }

    /// [`Clearance::segment_fits`] with `slack` metres more tolerance than the planners' own,
    /// for segments whose ends a planner put at the clearance limit (see
    /// [`Clearance::clear_of_cells_within`]).
    pub fn segment_fits_within(&self, a: Point, b: Point, slack: f64) -> bool {
        let steps = ((b - a).norm() / (0.25 * self.map.resolution())).ceil().max(1.0) as usize;
        (0..=steps).all(|i| {
            let p = a + (b - a) * (i as f64 / steps as f64);
            self.inside_edges_within(p, slack) && self.clear_of_cells_within(p, slack) && self.near_reachable(p)
        })
    }

    /// The free sub-intervals `[t0, t1]` (parameters in [0, 1]) of the segment `a → b` where the
    /// robot fits, ends refined by bisection; intervals shorter than `min_len` metres dropped.
    pub fn fitting_intervals(&self, a: Point, b: Point, min_len: f64) -> Vec<(f64, f64)> {
        let len = (b - a).norm();
        let steps = (len / (0.5 * self.map.resolution())).ceil().max(1.0) as usize;
        let at = |t: f64| self.fits(a + (b - a) * t);
        let refine = |mut inside: f64, mut outside: f64| {
            for _ in 0..40 {
                let mid = 0.5 * (inside + outside);
                if at(mid) { inside = mid } else { outside = mid }
            }
            inside
        };
        let mut out = Vec::new();
        let mut start: Option<f64> = None;
        let mut prev_t = 0.0;
        let mut prev_ok = false;
        for i in 0..=steps {
            let t = i as f64 / steps as f64;
            let ok = at(t);
            match (prev_ok, ok, i) {
                (_, true, 0) => start = Some(0.0),
                (false, true, _) => start = Some(refine(t, prev_t)),
                (true, false, _) => {
                    let end = refine(prev_t, t);
                    out.push((start.take().unwrap_or(0.0), end));
                }
                _ => {}
            }
            prev_ok = ok;
            prev_t = t;
        }
        if let Some(s) = start {
            out.push((s, 1.0));
        }
        out.retain(|&(t0, t1)| (t1 - t0) * len >= min_len);
        out
    }

    /// The fitting cell centre (row-major index) nearest to `p`, if any cell fits.
    pub fn snap(&self, p: Point) -> Option<usize> {
        let m = &*self.map;
        // The map's upper edges belong to its last row and column.
        let cell = |v: f64, o: f64, n: usize| (((v - o) / m.resolution()).floor().max(0.0) as usize).min(n - 1);
        let q = m.clamp(p);
        let (r0, c0) = (cell(q.y, m.origin().y, m.rows()), cell(q.x, m.origin().x, m.cols()));
        // Nearest fitting cell centre by growing square rings.
        let max_ring = m.rows().max(m.cols()) as isize;
        for ring in 0..max_ring {
            let mut best: Option<(f64, usize)> = None;
            for r in (r0 as isize - ring)..=(r0 as isize + ring) {
                for c in (c0 as isize - ring)..=(c0 as isize + ring) {
                    let on_ring = (r - r0 as isize).abs() == ring || (c - c0 as isize).abs() == ring;
                    if !on_ring || r < 0 || c < 0 || r >= m.rows() as isize || c >= m.cols() as isize {
                        continue;
                    }
                    let i = m.index(r as usize, c as usize);
                    if self.centre_ok[i] {
                        let d = (m.cell_centre(r as usize, c as usize) - p).norm();
                        if best.is_none_or(|(bd, _)| d < bd) {
                            best = Some((d, i));
                        }
                    }
                }
            }
            if let Some((_, i)) = best {
                return Some(i);
            }
        }
        None
    }

    /// A collision-free route from `a` to `b`: the points after `a`, ending with `b`. Straight
    /// when the segment fits, else A* over fitting cell centres shortened by line of sight.
    /// `None` when `b` cannot be reached.
    pub fn connect(&self, a: Point, b: Point) -> Option<Vec<Point>> {
        if self.segment_fits(a, b) {
            return Some(vec![b]);
        }
        let (from, to) = (self.snap(a)?, self.snap(b)?);
        let cells = self.astar(from, to)?;
        let mut raw: Vec<Point> = Vec::with_capacity(cells.len() + 2);
        raw.push(a);
        raw.extend(cells.iter().map(|&i| self.map.cell_centre(i / self.map.cols(), i % self.map.cols())));
        raw.push(b);
        // Line-of-sight shortening: from each anchor jump to the farthest visible point.
        let mut out = Vec::new();
        let mut anchor = 0;
        while anchor < raw.len() - 1 {
            let mut next = anchor + 1;
            for j in (anchor + 2..raw.len()).rev() {
                if self.segment_fits(raw[anchor], raw[j]) {
                    next = j;
                    break;
                }
            }
            out.push(raw[next]);
            anchor = next;
        }
        // From a point the body fits at, the first hop must pass the body rule too: a lane end
        // at the clearance limit between cell centres (a lane through a gap exactly one robot
        // wide) can see its nearest centre only past a wall's corner. Then the route starts at
        // the nearest centre it sees; where it sees none, the plan's check detours
        // ([`crate::planner::executable`]).
        if self.fits_geometry(a)
            && !crate::map::body::segment_clear_of_cells(&self.map, a, out[0], 2.0 * self.radius)
            && let Some(c) = self.visible_centre(a)
            && let Some(rest) = self.connect(c, b)
        {
            out = std::iter::once(c).chain(rest).collect();
        }
        // Every hop after the first must fit: the first may leave a start that the disc does
        // not fit (a station next to a wall), the others must not cut through obstacles.
        let mut prev = out[0];
        for &p in &out[1..] {
            if !self.segment_fits(prev, p) {
                return None;
            }
            prev = p;
        }
        Some(out)
    }

    /// The fitting cell centre nearest to `p` that a straight move from `p` reaches with the
    /// disc clear all along ([`Clearance::segment_fits`]), within the clearance window about
    /// `p`.
    fn visible_centre(&self, p: Point) -> Option<Point> {
        let m = &*self.map;
        let (r0, c0) = m.cell_at(m.clamp(p))?;
        let k = self.window;
        let mut best: Option<(f64, Point)> = None;
        for r in (r0 as isize - k).max(0)..=(r0 as isize + k).min(m.rows() as isize - 1) {
            for c in (c0 as isize - k).max(0)..=(c0 as isize + k).min(m.cols() as isize - 1) {
                let (r, c) = (r as usize, c as usize);
                let q = m.cell_centre(r, c);
                let d = (q - p).norm();
                if self.centre_ok[m.index(r, c)]
                    && best.is_none_or(|(bd, _)| d < bd)
                    && d > 1e-12
                    && self.segment_fits(p, q)
                {
                    best = Some((d, q));
                }
            }
        }
        best.map(|(_, q)| q)
    }

    /// The 8 neighbours of cell `i` that a robot centred on `i` can step to: fitting centres,
    /// and for diagonal steps both orthogonal neighbours fitting too (no corner cutting).
    pub fn steps(&self, i: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        let m = &*self.map;
        let cols = m.cols() as isize;
        let (r, c) = ((i / m.cols()) as isize, (i % m.cols()) as isize);
        [(-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1)].into_iter().filter_map(
            move |(dr, dc)| {
                let (nr, nc) = (r + dr, c + dc);
                if nr < 0 || nc < 0 || nr >= m.rows() as isize || nc >= cols {
                    return None;
                }
                let j = (nr * cols + nc) as usize;
                let diagonal = dr != 0 && dc != 0;
                if !self.centre_ok[j]
                    || (diagonal
                        && !(self.centre_ok[(r * cols + nc) as usize] && self.centre_ok[(nr * cols + c) as usize]))
                {
                    return None;
                }
                Some((j, if diagonal { std::f64::consts::SQRT_2 } else { 1.0 }))
            },
        )
    }

    fn astar(&self, from: usize, to: usize) -> Option<Vec<usize>> {
        ASTAR.with_borrow_mut(|scratch| {
            scratch.ready(self.centre_ok.len());
            let path = self.astar_in(from, to, scratch);
            scratch.reset();
            path
        })
    }

    fn astar_in(&self, from: usize, to: usize, scratch: &mut AstarScratch) -> Option<Vec<usize>> {
        let m = &*self.map;
        let h = |i: usize| {
            let (dr, dc) =
                ((i / m.cols()) as f64 - (to / m.cols()) as f64, (i % m.cols()) as f64 - (to % m.cols()) as f64);
            (dr * dr + dc * dc).sqrt()
        };
        let AstarScratch { g, parent, touched } = scratch;
        let mut heap = BinaryHeap::new();
        g[from] = 0.0;
        touched.push(from);
        // Keys in 1e-6 cell units keep the order total and deterministic.
        let key = |f: f64| (f * 1e6) as u64;
        heap.push(Reverse((key(h(from)), from)));
        while let Some(Reverse((_, i))) = heap.pop() {
            if i == to {
                let mut path = vec![to];
                let mut k = to;
                while k != from {
                    k = parent[k];
                    path.push(k);
                }
                path.reverse();
                return Some(path);
            }
            for (j, step) in self.steps(i) {
                let cand = g[i] + step;
                if cand < g[j] - 1e-12 {
                    if g[j] == f64::INFINITY {
                        touched.push(j);
                    }
                    g[j] = cand;
                    parent[j] = i;
                    heap.push(Reverse((key(cand + h(j)), j)));
                }
            }
        }
        None
    }
}

/// The search state of [`Clearance::connect`]'s A*, one per thread: cost so far and parent per
/// cell, and the cells written, so that a search resets only those (a fresh state per search
/// cleared megabytes on large maps for searches that touch a few thousand cells).
#[derive(Default)]
struct AstarScratch {
    g: Vec<f64>,
    parent: Vec<usize>,
    touched: Vec<usize>,
}

impl AstarScratch {
    fn ready(&mut self, n: usize) {
        if self.g.len() != n {
            self.g = vec![f64::INFINITY; n];
            self.parent = vec![usize::MAX; n];
        }
    }

    fn reset(&mut self) {
        for &i in &self.touched {
            self.g[i] = f64::INFINITY;
            self.parent[i] = usize::MAX;
        }
        self.touched.clear();
    }
}

thread_local! {
    static ASTAR: std::cell::RefCell<AstarScratch> = std::cell::RefCell::new(AstarScratch::default());
}

#[cfg(test)]
mod tests;
