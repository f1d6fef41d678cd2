//! What a robot of a given width can reach and cover from its stations: the cell centres its
//! disc can occupy in the stations' connected component, the free cells its footprint can
//! sweep from there, and the free pockets it cannot (SLAM maps have many: gaps behind pillars,
//! specks of free space inside walls, rooms behind doors narrower than the robot).
//!
//! This is the fair denominator for coverage on real maps: a wall-free path cannot sweep a cell
//! that no reachable pose of the footprint touches. The robot centres are read at cell centres
//! (the pattern planners' moves); the coverable cells from the continuous positions with
//! clearance ≥ width/2 ([`super::coverable`]), so that lanes half a width off a wall, which
//! sit between cell centres, count.

use super::GridMap;
use super::clearance::Clearance;
use crate::geom::Point;
use std::sync::{Mutex, MutexGuard};

/// How many reaches [`Reach::new`] keeps: a plan's planner and the scorer that checks it ask
/// for the same one (on a 600 × 600 map it costs about a tenth of a second each time).
const RECENT_REACHES: usize = 4;

/// A reach and the inputs it was computed from (compared exactly: the same inputs give the
/// same reach, so a kept one is returned as a copy).
struct RecentReach {
    map: GridMap,
    radius: u64,
    stations: Vec<Point>,
    reach: Reach,
}

fn recent() -> MutexGuard<'static, Vec<RecentReach>> {
    static RECENT: Mutex<Vec<RecentReach>> = Mutex::new(Vec::new());
    // A panic while the lock was held leaves a list of whole entries: still usable.
    RECENT.lock().unwrap_or_else(|e| e.into_inner())
}

/// The reachable and coverable parts of a map for one robot width and a set of stations.
#[derive(Clone, Debug)]
pub struct Reach {
    centres: Vec<bool>,
    coverable: Vec<bool>,
    coverable_count: usize,
    pockets: Vec<usize>,
    cell_area_m2: f64,
}

/// The cell centres the robot's disc can occupy in the stations' component: flood-filled from
/// each station's nearest fitting centre (8-connected, no corner cutting, as the connecting
/// moves of the patterns). One flag per cell, row-major.
pub fn reachable_centres(clear: &Clearance, stations: &[Point]) -> Vec<bool> {
    let map = clear.map();
    let mut centres = vec![false; map.rows() * map.cols()];
    let mut stack: Vec<usize> = stations.iter().filter_map(|&p| clear.snap(p)).collect();
    for &s in &stack {
        centres[s] = true;
    }
    while let Some(i) = stack.pop() {
        for (j, _) in clear.steps(i) {
            if !centres[j] {
                centres[j] = true;
                stack.push(j);
            }
        }
    }
    centres
}

/// Why the robot's body does not fit at the station `p` (`what` names it), if it does not:
/// its centre must keep half the robot's width from every non-free cell and the map's edge
/// (the body of [`super::body`]); the message quotes the clearance there.
pub fn station_misfit(clear: &Clearance, p: Point, what: &str) -> Option<String> {
    if clear.fits_geometry(p) {
        return None;
    }
    Some(format!(
        "a {} m robot does not fit at {what} ({}, {}) m: its body would touch a wall, an unknown cell or the map's edge (clearance there {:.4} m, at least {} m needed: half the robot's width)",
        2.0 * clear.radius(),
        p.x,
        p.y,
        clear.clearance_at(p),
        clear.radius()
    ))
}

/// Why `end` is no place to end a plan that starts at `start` for a robot of the
/// clearance's width, if it is none: the disc does not fit there, or no path of its centre
/// from `start` keeps clear of every wall.
pub fn unreachable_end(clear: &Clearance, start: Point, end: Point) -> Option<String> {
    let width = 2.0 * clear.radius();
    if !clear.fits_geometry(end) {
        return Some(format!(
            "a {width} m robot does not fit at ({}, {}) m: its centre must keep {} m from every wall and the map's edge",
            end.x,
            end.y,
            clear.radius()
        ));
    }
    let centres = reachable_centres(clear, &[start]);
    match clear.snap(end) {
        Some(i) if centres[i] => None,
        _ => Some(format!(
            "({}, {}) m cannot be reached from the start ({}, {}) m by a {width} m robot: no path of its centre keeps {} m from every wall",
            end.x,
            end.y,
            start.x,
            start.y,
            clear.radius()
        )),
    }
}

/// Where the flood of the coverable positions starts: each station where the body fits, and
/// the reachable centres of the stations where it does not (a plan evaluated from such a
/// station is not executable; its denominator is the nearest fitting centre's component, as
/// the planners see it).
///
/// A fitting station seeds the flood itself, not its nearest fitting cell centre: in a
/// corridor barely wider than the robot the band where the body fits can hold no cell centre
/// (the centre raster is one cell apart), and the nearest fitting centre may lie beyond a wall.
/// From the station, the coverable cells are those of the positions the robot can really drive
/// to, the same positions the body rule accepts.
fn coverable_seeds(clear: &Clearance, stations: &[Point], centres: &[bool]) -> Vec<Point> {
    let map = clear.map();
    let mut seeds: Vec<Point> = stations.iter().copied().filter(|&p| clear.fits_geometry(p)).collect();
    if seeds.len() < stations.len() {
        let misfits: Vec<Point> = stations.iter().copied().filter(|&p| !clear.fits_geometry(p)).collect();
        let theirs = reachable_centres(clear, &misfits);
        seeds
            .extend((0..centres.len()).filter(|&i| theirs[i]).map(|i| map.cell_centre(i / map.cols(), i % map.cols())));
    }
    seeds
}

impl Reach {
    /// Flood-fills the fitting cell centres from each station (8-connected, no corner cutting,
    /// as the connecting moves of the patterns), then marks the coverable free cells and groups
    /// the free cells left over into pockets (8-connected).
    pub fn new(clear: &Clearance, stations: &[Point]) -> Self {
        if clear.is_restricted() {
            return Self::compute(clear, stations);
        }
        Self::recall(clear.map(), clear.radius(), stations).unwrap_or_else(|| Self::keep(clear, stations))
    }

    /// [`Reach::new`] for a robot `width` metres wide on `map`, without building the clearance
    /// when the same reach was computed a moment ago.
    pub fn for_width(map: &GridMap, width: f64, stations: &[Point]) -> Self {
        Self::recall(map, 0.5 * width, stations).unwrap_or_else(|| Self::keep(&Clearance::new(map, width), stations))
    }

    /// A kept reach for exactly these inputs.
    fn recall(map: &GridMap, radius: f64, stations: &[Point]) -> Option<Self> {
        let r = recent();
        r.iter()
            .find(|e| e.radius == radius.to_bits() && e.stations == stations && e.map == *map)
            .map(|e| e.reach.clone())
    }

    /// Computes the reach of an unrestricted clearance and keeps it.
    fn keep(clear: &Clearance, stations: &[Point]) -> Self {
        let reach = Self::compute(clear, stations);
        let mut r = recent();
        if r.len() == RECENT_REACHES {
            r.remove(0);
        }
        r.push(RecentReach {
            map: clear.map().clone(),
            radius: clear.radius().to_bits(),
            stations: stations.to_vec(),
            reach: reach.clone(),
        });
        reach
    }

    fn compute(clear: &Clearance, stations: &[Point]) -> Self {
        let map = clear.map();
        let n = map.rows() * map.cols();
        let centres = reachable_centres(clear, stations);
        let res = map.resolution();
        let (rows, cols) = (map.rows() as isize, map.cols() as isize);
        let seeds = coverable_seeds(clear, stations, &centres);
        let coverable = super::coverable::coverable_cells(map, clear.radius(), &seeds);
        let coverable_count = coverable.iter().filter(|c| **c).count();
        // Pockets: connected groups of free cells that are not coverable.
        let mut seen = coverable.clone();
        let mut pockets = Vec::new();
        for start in 0..n {
            if seen[start] || !map.state_at(start).eq(&super::CellState::Free) {
                continue;
            }
            seen[start] = true;
            let mut stack = vec![start];
            let mut size = 0;
            while let Some(i) = stack.pop() {
                size += 1;
                let (r, c) = ((i / map.cols()) as isize, (i % map.cols()) as isize);
                for dr in -1..=1 {
                    for dc in -1..=1 {
                        let (nr, nc) = (r + dr, c + dc);
                        if nr < 0 || nc < 0 || nr >= rows || nc >= cols {
                            continue;
                        }
                        let j = (nr * cols + nc) as usize;
                        if !seen[j] && map.is_free(nr as usize, nc as usize) {
                            seen[j] = true;
                            stack.push(j);
                        }
                    }
                }
            }
            pockets.push(size);
        }
        Self { centres, coverable, coverable_count, pockets, cell_area_m2: res * res }
    }

    /// Keeps only the coverable cells flagged in `keep` (a region of the map the robot is to
    /// sweep; it may still travel through the rest). Pockets stay those of the whole map.
    pub fn keep_only(&mut self, keep: &[bool]) {
        for (c, &k) in self.coverable.iter_mut().zip(keep) {
            *c &= k;
        }
        self.coverable_count = self.coverable.iter().filter(|c| **c).count();
    }

    /// Reachable robot centres, one flag per cell (row-major).
    pub fn centres(&self) -> &[bool] {
        &self.centres
    }
    /// Whether the footprint can sweep cell `index` from a reachable pose.
    pub fn is_coverable(&self, index: usize) -> bool {
        self.coverable[index]
    }
    /// Coverable free cells (the reachable `A_pix`).
    pub fn coverable_count(&self) -> usize {
        self.coverable_count
    }
    /// Coverable flags, one per cell (row-major).
    pub fn coverable(&self) -> &[bool] {
        &self.coverable
    }
    /// Number of free pockets the footprint cannot sweep.
    pub fn pocket_count(&self) -> usize {
        self.pockets.len()
    }
    /// Free cells in those pockets.
    pub fn pocket_cells(&self) -> usize {
        self.pockets.iter().sum()
    }
    /// Their area in m².
    pub fn pocket_area_m2(&self) -> f64 {
        self.pocket_cells() as f64 * self.cell_area_m2
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::{CellState, GridMap};

    /// 12 × 7 cells of 0.1 m: a room (columns 1–6) and, behind a wall with a 0.2 m slot, a
    /// 0.4 m wide pocket (columns 8–10); a 0.3 m robot fits in the room but not the slot.
    fn room_and_pocket() -> GridMap {
        let (cols, rows) = (12, 7);
        let mut cells = vec![CellState::Occupied; cols * rows];
        for r in 1..6 {
            for c in 1..7 {
                cells[r * cols + c] = CellState::Free;
            }
            for c in 8..11 {
                cells[r * cols + c] = CellState::Free;
            }
        }
        cells[3 * cols + 7] = CellState::Free;
        GridMap::new("pocket", cols, rows, 0.1, Point::origin(), cells).unwrap()
    }

    #[test]
    fn the_pocket_behind_a_narrow_slot_is_unreachable() {
        let map = room_and_pocket();
        let clear = Clearance::new(&map, 0.3);
        let reach = Reach::new(&clear, &[Point::new(0.35, 0.35)]);
        // The 0.15 m disc fits with its centre in columns 2–5, rows 2–4 of the room.
        let reachable: Vec<usize> = (0..reach.centres().len()).filter(|&i| reach.centres()[i]).collect();
        assert_eq!(reachable.len(), 12);
        assert!(reachable.iter().all(|&i| (2..=5).contains(&(i % 12)) && (2..=4).contains(&(i / 12))));
        // Every room cell is within 0.15 m of such a centre only along the orthogonal
        // neighbours: corners of the room (distance √2·0.1 > 0.15? no: 0.141 < 0.15) are in.
        assert_eq!(reach.coverable_count(), 30, "the whole 6 x 5 room");
        // The slot cell and the 3 x 5 pocket form one unreachable pocket of 16 cells.
        assert_eq!(reach.pocket_count(), 1);
        assert_eq!(reach.pocket_cells(), 16);
        assert!((reach.pocket_area_m2() - 0.16).abs() < 1e-12);
    }

    /// A station in a chamber two cells high, where a 0.19 m robot fits only between the
    /// cell centres, with a room behind a one-cell wall: the chamber is what the robot covers,
    /// not the room whose fitting centre lies nearest to the station.
    #[test]
    fn a_station_between_cell_centres_covers_its_own_chamber() {
        let (cols, rows) = (12, 10);
        let mut cells = vec![CellState::Occupied; cols * rows];
        for c in 1..11 {
            for r in (1..3).chain(4..9) {
                cells[r * cols + c] = CellState::Free;
            }
        }
        let map = GridMap::new("chamber", cols, rows, 0.1, Point::origin(), cells).unwrap();
        let clear = Clearance::new(&map, 0.19);
        let station = Point::new(0.55, 0.2);
        assert!(clear.fits_geometry(station));
        let reach = Reach::new(&clear, &[station]);
        let chamber: Vec<usize> =
            (0..rows * cols).filter(|&i| (1..3).contains(&(i / cols)) && map.is_free(i / cols, i % cols)).collect();
        assert!(chamber.iter().all(|&i| reach.is_coverable(i)), "the chamber the robot stands in");
        assert_eq!(reach.coverable_count(), chamber.len(), "nothing of the room behind the wall");
        assert_eq!((reach.pocket_count(), reach.pocket_cells()), (1, 50), "the room is a pocket");
    }

    #[test]
    fn an_end_must_fit_and_connect_to_the_start() {
        let map = room_and_pocket();
        let clear = Clearance::new(&map, 0.3);
        let start = Point::new(0.35, 0.35);
        let cases: [(Point, Option<&str>); 3] = [
            (Point::new(0.55, 0.45), None),
            (Point::new(0.95, 0.35), Some("cannot be reached from the start")),
            (Point::new(0.15, 0.35), Some("does not fit")),
        ];
        for (end, expected) in cases {
            let got = unreachable_end(&clear, start, end);
            match expected {
                None => assert_eq!(got, None, "{end:?}"),
                Some(words) => assert!(got.as_deref().is_some_and(|m| m.contains(words)), "{end:?}: {got:?}"),
            }
        }
        // A 0.2 m robot fits in the pocket, but the slot does not let it through.
        let narrow = Clearance::new(&map, 0.2);
        let got = unreachable_end(&narrow, start, Point::new(0.95, 0.35)).unwrap();
        assert!(got.contains("cannot be reached from the start"), "{got}");
    }

    #[test]
    fn restricted_clearance_stays_in_the_stations_component() {
        let map = room_and_pocket();
        let mut clear = Clearance::new(&map, 0.2);
        // A 0.2 m robot fits in the pocket (its 0.1 m radius) but not through the slot corner.
        assert!(clear.fits(Point::new(0.95, 0.35)));
        let reach = Reach::new(&clear, &[Point::new(0.35, 0.35)]);
        clear.restrict(reach.centres().to_vec());
        assert!(!clear.fits(Point::new(0.95, 0.35)));
        assert!(clear.connect(Point::new(0.35, 0.35), Point::new(0.95, 0.35)).is_none());
    }
}
