//! The cells a straight, axis-parallel move of the robot can sweep: a smaller denominator than
//! the reach's, for telling a planner's own shortfall from cells no move can sweep.
//!
//! The reach ([`covga::map::reach::Reach`]) counts every free cell within half a width of a
//! position the robot's centre can take, as if it could make a short move in any direction from
//! there. At the edge of the free positions it cannot: in a room's corner, the quarter disc
//! between the corner and the nearest position lies within half a width of that position, but
//! the swept line of a move (003 §3.1) reaches it only along a heading that leaves the free
//! positions. For a robot 1.2 m wide that is 0.28 m² per corner, a share that grows in small
//! rooms. Here the free positions are read on a lattice of a quarter cell (the robot fits
//! there, 8-connected to the start), and a cell counts where its centre lies in the band of a
//! horizontal or vertical run of those positions: what the robot sweeps driving the run.

use covga::geom::Point;
use covga::map::GridMap;
use covga::map::clearance::Clearance;

/// Lattice points per cell edge.
const PER_CELL: usize = 4;

/// How many free cells of `map` a robot `width` metres wide sweeps driving the horizontal and
/// vertical runs of the positions it can reach from `start`.
pub fn sweepable_cells(map: &GridMap, width: f64, start: Point) -> usize {
    let clear = Clearance::new(map, width);
    let h = map.resolution() / PER_CELL as f64;
    let (cols, rows) = (map.cols() * PER_CELL, map.rows() * PER_CELL);
    let o = map.origin();
    let point = |i: usize, j: usize| Point::new(o.x + (i as f64 + 0.5) * h, o.y + (j as f64 + 0.5) * h);
    let kept = reachable_points(&clear, (cols, rows), &point, start, h);
    let mut marks = Marks::new(map);
    let r = 0.5 * width;
    for j in 0..rows {
        for (a, b) in runs((0..cols).map(|i| kept[j * cols + i])) {
            let (pa, pb) = (point(a, j), point(b, j));
            marks.add(map, (pa.x, pb.x), (pa.y - r, pa.y + r));
        }
    }
    for i in 0..cols {
        for (a, b) in runs((0..rows).map(|j| kept[j * cols + i])) {
            let (pa, pb) = (point(i, a), point(i, b));
            marks.add(map, (pa.x - r, pa.x + r), (pa.y, pb.y));
        }
    }
    marks.count_free(map)
}

/// The lattice points where the robot fits, 8-connected to the one nearest `start`.
fn reachable_points(
    clear: &Clearance,
    (cols, rows): (usize, usize),
    point: &dyn Fn(usize, usize) -> Point,
    start: Point,
    h: f64,
) -> Vec<bool> {
    let o = clear.map().origin();
    let at = |v: f64, n: usize| ((v / h - 0.5).round().max(0.0) as usize).min(n - 1);
    let first = at(start.y - o.y, rows) * cols + at(start.x - o.x, cols);
    let mut state = vec![0u8; cols * rows]; // 0 unseen, 1 kept, 2 rejected
    let fits = |k: usize| clear.fits_geometry(point(k % cols, k / cols));
    if !fits(first) {
        return vec![false; cols * rows];
    }
    state[first] = 1;
    let mut stack = vec![first];
    while let Some(k) = stack.pop() {
        let (i, j) = ((k % cols) as isize, (k / cols) as isize);
        for (di, dj) in [(-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1)] {
            let (ni, nj) = (i + di, j + dj);
            if ni < 0 || nj < 0 || ni >= cols as isize || nj >= rows as isize {
                continue;
            }
            let n = nj as usize * cols + ni as usize;
            if state[n] == 0 {
                state[n] = if fits(n) { 1 } else { 2 };
                if state[n] == 1 {
                    stack.push(n);
                }
            }
        }
    }
    state.iter().map(|&s| s == 1).collect()
}

/// The maximal runs `(first, last)` of `true` in `flags`.
fn runs(flags: impl Iterator<Item = bool>) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut open: Option<usize> = None;
    let mut last = 0;
    for (k, f) in flags.enumerate() {
        match (f, open) {
            (true, None) => open = Some(k),
            (false, Some(a)) => {
                out.push((a, k - 1));
                open = None;
            }
            _ => {}
        }
        last = k;
    }
    if let Some(a) = open {
        out.push((a, last));
    }
    out
}

/// Cells marked by rectangles, through a two-dimensional difference array.
struct Marks {
    diff: Vec<i64>,
    cols: usize,
}

impl Marks {
    fn new(map: &GridMap) -> Self {
        Self { diff: vec![0; (map.cols() + 1) * (map.rows() + 1)], cols: map.cols() + 1 }
    }

    /// Marks the cells whose centres lie in `[x0, x1] × [y0, y1]`.
    fn add(&mut self, map: &GridMap, (x0, x1): (f64, f64), (y0, y1): (f64, f64)) {
        let (o, res) = (map.origin(), map.resolution());
        // Cell c's centre is o + (c + ½)·res: the first and one past the last with it inside.
        let first = |v: f64| ((v / res - 0.5).ceil().max(0.0)) as usize;
        let past = |v: f64, n: usize| (((v / res - 0.5).floor() + 1.0).max(0.0) as usize).min(n);
        let (c0, c1) = (first(x0 - o.x).min(map.cols()), past(x1 - o.x, map.cols()));
        let (r0, r1) = (first(y0 - o.y).min(map.rows()), past(y1 - o.y, map.rows()));
        if c0 >= c1 || r0 >= r1 {
            return;
        }
        let w = self.cols;
        self.diff[r0 * w + c0] += 1;
        self.diff[r0 * w + c1] -= 1;
        self.diff[r1 * w + c0] -= 1;
        self.diff[r1 * w + c1] += 1;
    }

    /// The free cells marked at least once.
    fn count_free(&self, map: &GridMap) -> usize {
        let w = self.cols;
        let mut sums = vec![0i64; self.diff.len()];
        let mut count = 0;
        for r in 0..map.rows() {
            for c in 0..map.cols() {
                let k = r * w + c;
                let up = if r > 0 { sums[k - w] } else { 0 };
                let left = if c > 0 { sums[k - 1] } else { 0 };
                let diag = if r > 0 && c > 0 { sums[k - w - 1] } else { 0 };
                sums[k] = self.diff[k] + up + left - diag;
                if sums[k] > 0 && map.is_free(r, c) {
                    count += 1;
                }
            }
        }
        count
    }
}
