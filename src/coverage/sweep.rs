//! Cell counting along a path: Listing 3.1 of 003 with the reading of R5.
//!
//! For every segment in order and every swept cell once: an obstacle cell adds to `obj_pix`;
//! a free cell adds to `cov_pix`, adds to `cross_pix` when it was already visited, and its
//! visit count `M_traveled` is incremented. So `cov_pix − cross_pix` is the number of
//! distinct free cells swept (`unique`).

use super::raster::{RasterGrid, for_each_swept_run};
use crate::geom::Point;
use crate::map::{CellState, GridMap};

/// The per-map, per-scenario layers the counting reads: which cells are obstacles and which
/// are pre-marked as already covered (the retrain region of 003 §3.5.3, R25).
#[derive(Clone, Debug)]
pub struct CoverageGrid {
    raster: RasterGrid,
    blocked: Vec<bool>,
    premark: Vec<u32>,
    area_cells: usize,
}

impl CoverageGrid {
    /// Layers of a map with nothing pre-marked; `A_pix` = free cells (R29).
    pub fn new(map: &GridMap) -> Self {
        let blocked: Vec<bool> = map.cells().iter().map(|&c| c != CellState::Free).collect();
        Self { raster: RasterGrid::of(map), premark: vec![0; blocked.len()], area_cells: map.free_count(), blocked }
    }

    /// Marks the free cells whose centre lies in `[x0, x1) × [y0, y1)` (metres) as already
    /// covered: their visit count starts at 1 and they leave `A_pix` (thesis-ga §13, R25).
    pub fn premark_rect(&mut self, x0: f64, y0: f64, x1: f64, y1: f64) {
        let g = self.raster;
        for r in 0..g.rows {
            let y = g.origin_y + (r as f64 + 0.5) * g.resolution;
            if y < y0 || y >= y1 {
                continue;
            }
            for c in 0..g.cols {
                let x = g.origin_x + (c as f64 + 0.5) * g.resolution;
                let i = r * g.cols + c;
                if x >= x0 && x < x1 && !self.blocked[i] && self.premark[i] == 0 {
                    self.premark[i] = 1;
                    self.area_cells -= 1;
                }
            }
        }
    }

    /// Replaces the pre-marks by the free cells flagged in `cells` (one flag per cell): the
    /// cells other robots' plans cover, in a fleet's negotiation. `A_pix` follows.
    pub fn set_premarks(&mut self, cells: &[bool]) {
        assert_eq!(cells.len(), self.blocked.len(), "one flag per cell");
        self.area_cells = 0;
        for ((p, &b), &mark) in self.premark.iter_mut().zip(&self.blocked).zip(cells) {
            *p = u32::from(mark && !b);
            self.area_cells += usize::from(!b && !mark);
        }
    }

    /// `A_pix`: free cells still to be covered.
    pub fn area_cells(&self) -> usize {
        self.area_cells
    }
    /// The raster geometry.
    pub fn raster(&self) -> &RasterGrid {
        &self.raster
    }
    /// Whether a cell is an obstacle (occupied or unknown).
    pub fn is_blocked(&self, index: usize) -> bool {
        self.blocked[index]
    }
    /// Whether a cell is pre-marked as covered.
    pub fn is_premarked(&self, index: usize) -> bool {
        self.premark[index] > 0
    }
    /// Number of cells.
    pub fn len(&self) -> usize {
        self.blocked.len()
    }
    /// Whether the grid has no cells.
    pub fn is_empty(&self) -> bool {
        self.blocked.is_empty()
    }
}

/// The raw counts of Listing 3.1.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SweepCounts {
    /// `cov_pix`: free-cell traversals (every sweep of a free cell counts).
    pub cov_pix: u64,
    /// `cross_pix`: traversals of free cells already visited.
    pub cross_pix: u64,
    /// `obj_pix`: traversals of obstacle cells.
    pub obj_pix: u64,
}

impl SweepCounts {
    /// Distinct free cells newly covered: `cov_pix − cross_pix`.
    pub fn unique(&self) -> u64 {
        self.cov_pix - self.cross_pix
    }
}

/// Running counts of one sweep.
#[derive(Default)]
struct RunTally {
    cov: u64,
    cross: u64,
    obj: u64,
    len: usize,
}

/// Listing 3.1 for one run of cells `first + k·stride`, `k < count`. Local counters stay in
/// registers; the bookkeeping is branch-free because random paths make its outcomes
/// unpredictable.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn tally_run(
    acc: &mut RunTally,
    first: usize,
    count: usize,
    stride: usize,
    blocked: &[bool],
    premark: &[u32],
    visits: &mut [u32],
    touched: &mut [u32],
) {
    let (mut c, mut x, mut o, mut l) = (0u64, 0u64, 0u64, acc.len);
    let mut i = first;
    for _ in 0..count {
        if blocked[i] {
            o += 1;
        } else {
            let v = visits[i];
            x += u64::from((v | premark[i]) != 0);
            touched[l] = i as u32;
            l += usize::from(v == 0);
            visits[i] = v + 1;
            c += 1;
        }
        i += stride;
    }
    acc.cov += c;
    acc.cross += x;
    acc.obj += o;
    acc.len = l;
}

/// Reusable visit-count grid (`M_traveled` without its pre-marks), reset in O(touched cells).
#[derive(Clone, Debug)]
pub struct SweepScratch {
    visits: Vec<u32>,
    /// Cells visited since the last reset, in first-visit order; only `touched_len` are valid.
    /// Sized to the grid so that recording a first visit needs no branch.
    touched: Vec<u32>,
    touched_len: usize,
}

impl SweepScratch {
    /// A scratch grid for `grid`.
    pub fn new(grid: &CoverageGrid) -> Self {
        Self { visits: vec![0; grid.len()], touched: vec![0; grid.len() + 1], touched_len: 0 }
    }

    fn reset(&mut self) {
        for &i in &self.touched[..self.touched_len] {
            self.visits[i as usize] = 0;
        }
        self.touched_len = 0;
    }

    /// Sweeps the polyline `points` with width `width` and counts per Listing 3.1. The visit
    /// counts stay in the scratch until the next call (see [`Self::visit_counts`]).
    pub fn sweep(&mut self, grid: &CoverageGrid, points: &[Point], width: f64) -> SweepCounts {
        self.reset();
        let mut counts = SweepCounts::default();
        self.add_path(grid, points, width, &mut counts);
        counts
    }

    /// Sweeps several paths (one per agent) into one shared visit grid, in order.
    pub fn sweep_all(&mut self, grid: &CoverageGrid, paths: &[Vec<Point>], width: f64) -> SweepCounts {
        self.reset();
        let mut counts = SweepCounts::default();
        for p in paths {
            self.add_path(grid, p, width, &mut counts);
        }
        counts
    }

    /// Sweeps one path per robot, each with its own width, into one shared visit grid, in
    /// order, and returns the fleet's counts; `per_path[k]` receives path `k`'s share (its
    /// crossings include the cells earlier paths swept). The cost is the sum of the robots'
    /// swept cells: there is no per-robot copy of the grid.
    pub fn sweep_fleet(
        &mut self,
        grid: &CoverageGrid,
        paths: &[Vec<Point>],
        widths: &[f64],
        per_path: &mut [SweepCounts],
    ) -> SweepCounts {
        assert!(paths.len() == widths.len() && paths.len() == per_path.len(), "one width and one count per path");
        self.reset();
        let mut total = SweepCounts::default();
        for ((p, &w), share) in paths.iter().zip(widths).zip(per_path.iter_mut()) {
            *share = SweepCounts::default();
            self.add_path(grid, p, w, share);
            total.cov_pix += share.cov_pix;
            total.cross_pix += share.cross_pix;
            total.obj_pix += share.obj_pix;
        }
        total
    }

    fn add_path(&mut self, grid: &CoverageGrid, points: &[Point], width: f64, counts: &mut SweepCounts) {
        // Plain slices, so the loop keeps their addresses in registers.
        let (visits, touched) = (&mut self.visits[..], &mut self.touched[..]);
        let (blocked, premark) = (&grid.blocked[..], &grid.premark[..]);
        let mut acc = RunTally { len: self.touched_len, ..RunTally::default() };
        for pair in points.windows(2) {
            for_each_swept_run(&grid.raster, pair[0], pair[1], width, |first, count, stride| {
                tally_run(&mut acc, first, count, stride, blocked, premark, visits, touched);
            });
        }
        self.touched_len = acc.len;
        counts.cov_pix += acc.cov;
        counts.cross_pix += acc.cross;
        counts.obj_pix += acc.obj;
    }

    /// The cells visited by the last sweep with the number of visits it added (pre-marks
    /// excluded), in first-visit order.
    pub fn visit_counts(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        self.touched[..self.touched_len].iter().map(move |&i| (i, self.visits[i as usize]))
    }

    /// Visits of one cell by the last sweep (pre-marks not included).
    pub fn visits(&self, index: usize) -> u32 {
        self.visits[index]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::presets::preset;

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    /// A fleet's pre-marks replace the earlier ones: flagged free cells are marked and leave
    /// `A_pix`, a flagged obstacle stays an obstacle and unmarked, unflagged cells stay open.
    #[test]
    fn set_premarks_replaces_the_marks_and_a_pix_by_hand() {
        use crate::map::CellState::{Free, Occupied};
        // 3 × 2 cells, the middle of the bottom row occupied: five free cells.
        let cells = vec![Free, Occupied, Free, Free, Free, Free];
        let map = GridMap::new("six", 3, 2, 0.5, Point::origin(), cells).unwrap();
        let mut g = CoverageGrid::new(&map);
        assert_eq!((g.len(), g.is_empty(), g.area_cells()), (6, false, 5));
        g.set_premarks(&[true, true, false, false, true, false]);
        let marked: Vec<bool> = (0..6).map(|i| g.is_premarked(i)).collect();
        assert_eq!(marked, [true, false, false, false, true, false]);
        assert_eq!(g.area_cells(), 3);
        assert!(g.is_blocked(1) && !g.is_blocked(0));
        g.set_premarks(&[false, true, true, false, false, false]);
        let marked: Vec<bool> = (0..6).map(|i| g.is_premarked(i)).collect();
        assert_eq!(marked, [false, false, true, false, false, false], "the earlier marks are gone");
        assert_eq!(g.area_cells(), 4);
    }

    /// A fleet's counts are the sum of its robots' shares, each robot with its width, on one
    /// shared visit grid; `visits` reads the grid cell by cell as `visit_counts` lists it.
    #[test]
    fn fleet_totals_are_the_shares_summed_and_visits_read_the_shared_grid() {
        use crate::map::CellState::{Free, Occupied};
        let mut cells = vec![Free; 100];
        cells[5 * 10 + 5] = Occupied;
        let map = GridMap::new("ten", 10, 10, 0.5, Point::origin(), cells).unwrap();
        let g = CoverageGrid::new(&map);
        let mut s = SweepScratch::new(&g);
        let paths = vec![vec![p(0.75, 2.75), p(4.25, 2.75)], vec![p(2.25, 0.5), p(2.25, 4.5), p(2.25, 0.5)]];
        let mut shares = [SweepCounts::default(); 2];
        let total = s.sweep_fleet(&g, &paths, &[0.4, 0.9], &mut shares);
        assert!(shares[0].obj_pix > 0 && shares[1].obj_pix == 0, "only the first robot crosses the obstacle");
        assert!(shares[1].cross_pix > 0, "the second robot re-sweeps the first one's cells and its own");
        let summed = SweepCounts {
            cov_pix: shares[0].cov_pix + shares[1].cov_pix,
            cross_pix: shares[0].cross_pix + shares[1].cross_pix,
            obj_pix: shares[0].obj_pix + shares[1].obj_pix,
        };
        assert_eq!(total, summed);
        let listed: Vec<(u32, u32)> = s.visit_counts().collect();
        assert_eq!(listed.iter().map(|&(_, n)| u64::from(n)).sum::<u64>(), total.cov_pix);
        assert!(listed.iter().any(|&(_, n)| n == 3), "the crossing cells are visited three times");
        for &(i, n) in &listed {
            assert_eq!(s.visits(i as usize), n);
        }
        assert_eq!(s.visits(99), 0, "a corner no robot reaches");
    }

    #[test]
    fn premark_of_the_retrain_corner_matches_spec() {
        // thesis-ga §16.4: the 5 m corner square leaves A_pix = 1400 (map 1) and 1225 (map 2).
        for (name, expected) in [("thesis-1", 1400), ("thesis-2", 1225)] {
            let mut g = CoverageGrid::new(&preset(name).unwrap());
            g.premark_rect(5.0, 5.0, 10.0, 10.0);
            assert_eq!(g.area_cells(), expected, "{name}");
        }
    }

    /// The pre-marked region takes the cells whose centres lie in `[x0, x1) × [y0, y1)`: a
    /// centre on the lower edge is in, one on the upper edge is out (map 1: centres at
    /// 0.1, 0.3, … m).
    #[test]
    fn premark_region_is_half_open_on_cell_centres() {
        for (rect, taken) in [
            ([1.0, 1.0, 1.4, 1.4], 4),       // centres 1.1, 1.3 in each axis
            ([1.1, 1.1, 1.5, 1.5], 4),       // 1.1 on the lower edge is in, 1.5 on the upper edge out
            ([1.1, 1.1, 1.1, 1.5], 0),       // empty in x
            ([1.0, 1.0, 1.5000001, 1.3], 3), // 1.1, 1.3, 1.5 in x; 1.1 in y
        ] {
            let mut g = CoverageGrid::new(&preset("thesis-1").unwrap());
            let before = g.area_cells();
            g.premark_rect(rect[0], rect[1], rect[2], rect[3]);
            assert_eq!(before - g.area_cells(), taken, "{rect:?}");
        }
    }

    /// A pre-marked cell swept twice counts two crossings (its pre-mark is a first visit,
    /// R26); an ordinary cell swept twice one.
    #[test]
    fn premarked_cells_swept_twice_cross_twice() {
        let mut g = CoverageGrid::new(&preset("thesis-1").unwrap());
        g.premark_rect(1.0, 1.0, 2.0, 2.0);
        let mut s = SweepScratch::new(&g);
        let there_and_back = [p(1.3, 1.3), p(4.3, 1.3), p(1.3, 1.3)];
        let c = s.sweep(&g, &there_and_back, 0.6);
        // Segments are half-open along their direction: out takes the centre columns
        // 1.3 … 4.1 m, back 1.5 … 4.3 m (15 columns × 3 rows each). Pre-marked (x, y < 2 m):
        // column 1.3 once → 1 crossing each (3), columns 1.5–1.9 twice → 2 each (18); the 33
        // other cells of columns 1.5–4.1 twice → 1 each (33); column 4.3 once → 0. Newly
        // covered: those 33 and column 4.3's 3.
        assert_eq!(c, SweepCounts { cov_pix: 90, cross_pix: 54, obj_pix: 0 });
        assert_eq!(c.unique(), 36);
        let layers = crate::coverage::bits::BitLayers::new(&g);
        let bits = layers.sweep(&mut crate::coverage::planes::VisitPlanes::default(), &there_and_back, 0.6).counts();
        assert_eq!(bits, c, "bit rows agree");
    }

    #[test]
    fn premarked_cells_count_as_crossings() {
        let mut g = CoverageGrid::new(&preset("thesis-1").unwrap());
        g.premark_rect(1.0, 1.0, 2.0, 2.0);
        let mut s = SweepScratch::new(&g);
        let c = s.sweep(&g, &[p(1.3, 1.3), p(4.3, 1.3)], 0.6);
        // Pre-marked cells of the lane: columns 1.3..1.9 (4) × rows 1.1..1.5 (3).
        assert_eq!(c, SweepCounts { cov_pix: 45, cross_pix: 12, obj_pix: 0 });
        // The scratch resets to the pre-marks.
        let c2 = s.sweep(&g, &[p(1.3, 1.3), p(4.3, 1.3)], 0.6);
        assert_eq!(c, c2);
        assert_eq!(s.visit_counts().map(|(_, n)| n as u64).sum::<u64>(), 45);
    }
}
