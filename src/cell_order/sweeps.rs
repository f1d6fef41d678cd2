//! The candidate sweeps of the cell-order planner: the boustrophedon cells of the reachable
//! free space and, for each cell, one sweep per lane direction and entry corner.
//!
//! The cells come from one decomposition, at the direction of `directions` that gives the
//! fewest cells (the coarsest split, so that the order has the fewest items to arrange). Each
//! cell is then swept at every direction inside its own region: the region is the set of map
//! cells nearest to the cell's lanes, and a sweep at another direction keeps the parts of that
//! direction's lanes whose centres lie in the region. Where those parts form several pieces
//! per lane (a region that is not monotone at that direction), they are re-decomposed into
//! sub-cells and mowed one after another. This keeps the cells the same for every direction,
//! which is what a genome of one order plus one choice per cell needs (the generalised
//! travelling-salesman view of Bähnemann et al. 2019, where each cell is a cluster of sweeps).

use super::merged_lanes::LaneLayout;
use crate::geom::{Point, Vector};
use crate::lanes::boustrophedon::{Piece, decompose, lane_pieces, sweep_cells_with};
use crate::map::clearance::Clearance;

/// One way to sweep one cell: its polyline (first point the entry, last the exit), length,
/// total turning inside it and the headings at both ends.
#[derive(Clone, Debug, PartialEq)]
pub struct Sweep {
    /// Lane direction in degrees.
    pub direction_deg: f64,
    /// Entry corner: 0–3 (first or last lane, low or high end).
    pub entry: u8,
    /// The polyline, collision-free.
    pub points: Vec<Point>,
    /// Its length in metres.
    pub length_m: f64,
    /// Its total absolute turning in radians (003 eq. 3.2 inside the sweep).
    pub turn_rad: f64,
    /// Unit heading of the first non-degenerate segment (zero when there is none).
    pub start_heading: Vector,
    /// Unit heading of the last non-degenerate segment (zero when there is none).
    pub end_heading: Vector,
    /// Coverable cells of the cell's region that this sweep leaves unswept (set by
    /// [`CellSweeps::new`]).
    pub missed_cells: usize,
    /// Whether its lanes end at every obstacle where the map's lanes are otherwise joined
    /// across small ones ([`super::merged_lanes::LaneLayout::split_too`]).
    pub split: bool,
}

impl Sweep {
    pub(super) fn new(direction_deg: f64, entry: u8, points: Vec<Point>) -> Self {
        let (turn_rad, _) = crate::coverage::motion::turning(&points);
        let heading = |w: &[Point]| {
            let v = w[1] - w[0];
            (v.norm() > crate::geom::ZERO_LENGTH).then(|| v / v.norm())
        };
        let zero = Vector::zeros();
        Self {
            direction_deg,
            entry,
            length_m: crate::coverage::motion::path_length(&points),
            turn_rad,
            start_heading: points.windows(2).find_map(heading).unwrap_or(zero),
            end_heading: points.windows(2).rev().find_map(heading).unwrap_or(zero),
            points,
            missed_cells: 0,
            split: false,
        }
    }

    /// The entry point.
    pub fn start(&self) -> Point {
        self.points[0]
    }

    /// The exit point.
    pub fn end(&self) -> Point {
        *self.points.last().expect("a sweep has points")
    }
}

/// The cells of a map and their candidate sweeps.
#[derive(Clone, Debug)]
pub struct CellSweeps {
    /// The direction the cells were decomposed at, in degrees.
    pub base_direction_deg: f64,
    /// Per cell, its candidate sweeps (at least one).
    pub cells: Vec<Vec<Sweep>>,
    /// Which cell each map cell's region belongs to (`u32::MAX`: none).
    pub labels: Vec<u32>,
    /// Per cell, the coverable map cells of its region.
    pub region_cells: Vec<usize>,
}

impl CellSweeps {
    /// Decomposes the free space `clear` allows (restricted to the reachable part) and builds
    /// every cell's sweeps at `directions` (degrees) for a robot `width` wide; each sweep
    /// counts the cells of `coverable` (one flag per map cell) in its region it leaves. Where
    /// `layout.merge_gap_m` > 0 the lanes first continue across small obstacles
    /// ([`super::merged_lanes`]), so that the cells are fewer and their lanes longer; with
    /// `layout.split_too` each cell is also offered, at every direction where they differ, the
    /// sweeps of its region with lanes split at every obstacle.
    pub fn new(clear: &Clearance, width: f64, directions: &[f64], coverable: &[bool], layout: LaneLayout) -> Self {
        let joined = layout.merge_gap_m > 0.0;
        let join = super::merged_lanes::LaneJoin::new(clear, layout.merge_gap_m, width);
        let split_lanes: Vec<Vec<Vec<Piece>>> = directions.iter().map(|&d| lane_pieces(clear, width, d)).collect();
        let by_direction: Vec<Vec<Vec<Piece>>> = split_lanes.iter().map(|lanes| join.joined(lanes.clone())).collect();
        let decompositions: Vec<Vec<Vec<Piece>>> = by_direction.iter().map(|lanes| decompose(lanes)).collect();
        // The coarsest decomposition; the first direction among equals.
        let base = (0..directions.len())
            .filter(|&k| !decompositions[k].is_empty())
            .min_by_key(|&k| decompositions[k].len())
            .unwrap_or(0);
        let base_cells = &decompositions[base];
        if base_cells.is_empty() {
            return Self {
                base_direction_deg: directions[base],
                cells: Vec::new(),
                labels: Vec::new(),
                region_cells: Vec::new(),
            };
        }
        let labels = region_labels(clear, width, directions[base], base_cells);
        let mut cells: Vec<Vec<Sweep>> = (0..base_cells.len())
            .map(|k| {
                let mut out = Vec::new();
                for (d, &dir) in directions.iter().enumerate() {
                    let pieces: Vec<Vec<Piece>> = if d == base {
                        vec![base_cells[k].clone()]
                    } else {
                        let lanes = lanes_in_region(clear, &by_direction[d], (&labels, k), dir, joined);
                        decompose(&lanes)
                    };
                    if pieces.is_empty() {
                        continue;
                    }
                    push_sweeps(clear, (dir, &pieces), joined, &mut out);
                    if layout.offers_split() {
                        let split = decompose(&lanes_in_region(clear, &split_lanes[d], (&labels, k), dir, false));
                        if !split.is_empty() && split != pieces {
                            let first = out.len();
                            push_sweeps(clear, (dir, &split), false, &mut out);
                            out[first..].iter_mut().for_each(|w| w.split = true);
                        }
                    }
                }
                out
            })
            .collect();
        let region_cells = count_missed(clear.map(), width, &labels, coverable, &mut cells);
        Self { base_direction_deg: directions[base], cells, labels, region_cells }
    }

    /// Ends every candidate sweep with the completion of its own region
    /// ([`super::cell_completion`]) and counts what each then leaves.
    pub fn complete_in_cells(&mut self, clear: &Clearance, width: f64, coverable: &[bool], speed: f64) {
        super::cell_completion::extend(clear, width, &self.labels, coverable, speed, &mut self.cells);
        count_missed(clear.map(), width, &self.labels, coverable, &mut self.cells);
    }

    /// The number of cells.
    pub fn len(&self) -> usize {
        self.cells.len()
    }

    /// Whether there is no cell.
    pub fn is_empty(&self) -> bool {
        self.cells.is_empty()
    }
}

/// The sweeps of a cell's (sub-)`pieces` at lane direction `dir`, one per entry corner, their
/// lanes driven around the obstacles they cross where they are `joined`.
fn push_sweeps(clear: &Clearance, (dir, pieces): (f64, &[Vec<Piece>]), joined: bool, out: &mut Vec<Sweep>) {
    for (entry, corner) in corners(pieces).into_iter().enumerate() {
        let route = sweep_cells_with(clear, pieces, corner, joined);
        out.push(Sweep::new(dir, entry as u8, route.into_points()));
    }
}

/// Sets every sweep's `missed_cells`: its region's coverable cells minus those it sweeps;
/// returns the coverable cells of each region.
fn count_missed(
    map: &crate::map::GridMap,
    width: f64,
    labels: &[u32],
    coverable: &[bool],
    cells: &mut [Vec<Sweep>],
) -> Vec<usize> {
    let grid = crate::coverage::CoverageGrid::new(map);
    let raster = *grid.raster();
    let mut in_region = vec![0usize; cells.len()];
    for (i, &l) in labels.iter().enumerate() {
        if l != u32::MAX && coverable[i] {
            in_region[l as usize] += 1;
        }
    }
    // Stamps instead of clearing a flag per map cell for every sweep.
    let mut stamp = vec![0u32; labels.len()];
    let mut now = 0u32;
    for (k, cell) in cells.iter_mut().enumerate() {
        for sweep in cell {
            now += 1;
            let mut swept = 0usize;
            for w in sweep.points.windows(2) {
                crate::coverage::raster::for_each_swept_cell(&raster, w[0], w[1], width, |i| {
                    if stamp[i] != now && labels[i] == k as u32 && coverable[i] {
                        stamp[i] = now;
                        swept += 1;
                    }
                });
            }
            sweep.missed_cells = in_region[k] - swept;
        }
    }
    in_region
}

/// The four entry corners of a cell's (sub-)cells: both ends of the first lane's first piece
/// and of the last lane's last piece.
fn corners(pieces: &[Vec<Piece>]) -> [Point; 4] {
    let (head, tail) = (pieces[0][0], *pieces[pieces.len() - 1].last().expect("cells are never empty"));
    [head.a, head.b, tail.a, tail.b]
}

/// Which base cell each map cell belongs to (`u32::MAX`: none): the cells under each lane
/// piece's strip (one width across, the piece's extent plus a radius along), then every other
/// free cell from its nearest labelled neighbour (8-connected flood in index order).
fn region_labels(clear: &Clearance, width: f64, angle_deg: f64, cells: &[Vec<Piece>]) -> Vec<u32> {
    let map = clear.map();
    let (rows, cols) = (map.rows(), map.cols());
    let u = Vector::new(angle_deg.to_radians().cos(), angle_deg.to_radians().sin());
    let n = Vector::new(-u.y, u.x);
    let r = 0.5 * width;
    let res = map.resolution();
    let mut label = vec![u32::MAX; rows * cols];
    for (k, cell) in cells.iter().enumerate() {
        for piece in cell {
            let o = piece.a.coords.dot(&n);
            let corners =
                [piece.a - u * r - n * r, piece.a - u * r + n * r, piece.b + u * r - n * r, piece.b + u * r + n * r];
            let (x0, x1) = corners.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| (lo.min(p.x), hi.max(p.x)));
            let (y0, y1) = corners.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| (lo.min(p.y), hi.max(p.y)));
            let col = |x: f64| (((x - map.origin().x) / res).floor().max(0.0) as usize).min(cols - 1);
            let row = |y: f64| (((y - map.origin().y) / res).floor().max(0.0) as usize).min(rows - 1);
            for rr in row(y0)..=row(y1) {
                for cc in col(x0)..=col(x1) {
                    let i = rr * cols + cc;
                    if label[i] != u32::MAX || !map.is_free(rr, cc) {
                        continue;
                    }
                    let p = map.cell_centre(rr, cc).coords;
                    let along = p.dot(&u);
                    if (p.dot(&n) - o).abs() <= r && along >= piece.lo - r && along <= piece.hi + r {
                        label[i] = k as u32;
                    }
                }
            }
        }
    }
    // Flood the rest of the free cells from their labelled neighbours, breadth first.
    let mut queue: std::collections::VecDeque<usize> = (0..label.len()).filter(|&i| label[i] != u32::MAX).collect();
    while let Some(i) = queue.pop_front() {
        let (r0, c0) = ((i / cols) as isize, (i % cols) as isize);
        for (dr, dc) in [(-1, 0), (1, 0), (0, -1), (0, 1), (-1, -1), (-1, 1), (1, -1), (1, 1)] {
            let (nr, nc) = (r0 + dr, c0 + dc);
            if nr < 0 || nc < 0 || nr >= rows as isize || nc >= cols as isize {
                continue;
            }
            let j = nr as usize * cols + nc as usize;
            if label[j] == u32::MAX && map.is_free(nr as usize, nc as usize) {
                label[j] = label[i];
                queue.push_back(j);
            }
        }
    }
    label
}

/// The parts of `lanes` (the whole map's lane pieces at `angle_deg`) whose points lie in
/// region `k`, lane by lane; parts shorter than one map cell are dropped. Where the lanes are
/// `joined` across obstacles, a part goes on over the obstacle's cells (which belong to no
/// region) and starts and ends at points of the region where the robot fits.
fn lanes_in_region(
    clear: &Clearance,
    lanes: &[Vec<Piece>],
    (label, k): (&[u32], usize),
    angle_deg: f64,
    joined: bool,
) -> Vec<Vec<Piece>> {
    let map = clear.map();
    let u = Vector::new(angle_deg.to_radians().cos(), angle_deg.to_radians().sin());
    let res = map.resolution();
    let inside = |p: Point| map.cell_at(p).is_some_and(|(r, c)| label[map.index(r, c)] == k as u32);
    lanes
        .iter()
        .map(|lane| {
            let mut out = Vec::new();
            for piece in lane {
                let len = (piece.b - piece.a).norm();
                let steps = (len / (0.25 * res)).ceil().max(1.0) as usize;
                let at = |i: usize| piece.a + (piece.b - piece.a) * (i as f64 / steps as f64);
                let mut run: Option<usize> = None;
                // A joined piece crosses the obstacle it goes around: cells of no region carry
                // the run on, and it ends at its last point in the region.
                let mut last_in = 0;
                for i in 0..=steps + 1 {
                    let here = (i <= steps).then(|| at(i));
                    // A part starts and ends where the robot fits (beside the obstacle a joined
                    // piece passes it does not); in between it goes on over the obstacle.
                    let own = here.is_some_and(|p| inside(p) && (!joined || clear.fits(p)));
                    let across =
                        |p: Point| map.cell_at(p).is_some_and(|(r, c)| label[map.index(r, c)] == u32::MAX) || inside(p);
                    let ok = own || (joined && run.is_some() && here.is_some_and(across));
                    if own {
                        last_in = i;
                    }
                    match (run, ok) {
                        (None, true) => run = Some(i),
                        (Some(s), false) => {
                            let (a, b) = (at(s), at(last_in.max(s)));
                            if (b - a).norm() >= res {
                                out.push(Piece { a, b, lo: a.coords.dot(&u), hi: b.coords.dot(&u) });
                            }
                            run = None;
                        }
                        _ => {}
                    }
                }
            }
            out
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::presets::preset;
    use crate::map::reach::reachable_centres;

    #[test]
    fn every_cell_has_a_sweep_per_direction_and_entry_on_an_open_map() {
        let m = preset("thesis-1").unwrap();
        let mut clear = Clearance::new(&m, 0.6);
        clear.restrict(reachable_centres(&clear, &[Point::new(1.3, 1.3)]));
        let all = vec![true; m.rows() * m.cols()];
        let s = CellSweeps::new(&clear, 0.6, &[0.0, 45.0, 90.0, 135.0], &all, LaneLayout::SPLIT);
        assert_eq!(s.len(), 1, "an empty square is one cell");
        assert_eq!(s.cells[0].len(), 16);
        for sweep in &s.cells[0] {
            let mut prev = sweep.start();
            for &p in &sweep.points[1..] {
                assert!(clear.segment_fits(prev, p), "{} {}: {prev:?} {p:?}", sweep.direction_deg, sweep.entry);
                prev = p;
            }
            assert!(sweep.length_m > 50.0, "{} {}", sweep.direction_deg, sweep.length_m);
        }
        // Lanes along x half a width inside the 1 m walls: the first lane's low end is the
        // entry of corner 0.
        let first = &s.cells[0][0];
        assert_eq!(first.direction_deg, 0.0);
        assert!((first.start() - Point::new(1.3, 1.3)).norm() < 1e-3, "{:?}", first.start());
    }

    #[test]
    fn the_disc_map_splits_into_cells_swept_at_every_direction() {
        let m = preset("thesis-2").unwrap();
        let mut clear = Clearance::new(&m, 0.6);
        clear.restrict(reachable_centres(&clear, &[Point::new(1.3, 1.3)]));
        let all = vec![true; m.rows() * m.cols()];
        let s = CellSweeps::new(&clear, 0.6, &[0.0, 45.0, 90.0, 135.0], &all, LaneLayout::SPLIT);
        assert_eq!(s.len(), 4);
        for cell in &s.cells {
            let dirs: std::collections::BTreeSet<i64> = cell.iter().map(|w| w.direction_deg as i64).collect();
            assert_eq!(dirs.len(), 4, "{dirs:?}");
        }
    }

    /// A 10 × 6 m room at 0.1 m with a 0.4 m pillar in the middle.
    fn pillar_room() -> crate::map::GridMap {
        use crate::map::CellState;
        let (cols, rows) = (100, 60);
        let cells = (0..rows * cols)
            .map(|i| {
                let (r, c) = (i / cols, i % cols);
                let border = r == 0 || c == 0 || r == rows - 1 || c == cols - 1;
                let pillar = (48..52).contains(&c) && (28..32).contains(&r);
                if border || pillar { CellState::Occupied } else { CellState::Free }
            })
            .collect();
        crate::map::GridMap::new("room", cols, rows, 0.1, Point::origin(), cells).unwrap()
    }

    #[test]
    fn split_sweeps_are_offered_beside_joined_ones_only_where_they_differ() {
        let m = pillar_room();
        let mut clear = Clearance::new(&m, 0.6);
        clear.restrict(reachable_centres(&clear, &[Point::new(1.0, 1.0)]));
        let all = vec![true; m.rows() * m.cols()];
        let dirs = [0.0, 45.0, 90.0, 135.0];
        let build = |merge_gap_m: f64, split_too: bool| {
            CellSweeps::new(&clear, 0.6, &dirs, &all, LaneLayout { merge_gap_m, split_too })
        };
        let joined = build(2.0, false);
        assert_eq!(joined.len(), 1, "the pillar's lanes are joined: one cell");
        assert!(joined.cells[0].iter().all(|w| !w.split));
        let both = build(2.0, true);
        assert_eq!(both.len(), 1);
        assert_eq!(both.cells[0].iter().filter(|w| !w.split).cloned().collect::<Vec<_>>(), joined.cells[0]);
        let split: Vec<&Sweep> = both.cells[0].iter().filter(|w| w.split).collect();
        for d in [0.0, 90.0] {
            assert_eq!(split.iter().filter(|w| w.direction_deg == d).count(), 4, "the pillar splits lanes at {d}°");
        }
        for w in &split {
            for s in w.points.windows(2) {
                assert!(clear.segment_fits(s[0], s[1]), "{} {}: {s:?}", w.direction_deg, w.entry);
            }
            // Split lanes end at the pillar instead of driving round it: another sweep.
            let twin = joined.cells[0].iter().find(|j| j.direction_deg == w.direction_deg && j.entry == w.entry);
            assert_ne!(w.points, twin.unwrap().points, "{} {}", w.direction_deg, w.entry);
        }
        // With lanes split everywhere there is nothing else to offer.
        assert_eq!(build(0.0, true).cells, build(0.0, false).cells);
    }
}
