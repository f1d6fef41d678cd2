//! Built-in maps: the two experiment maps of 003 (Fig. 4.1, geometry of thesis-ga §1.2 / §16.4) and a
//! synthetic office floor for the waypoint planner (000 §II-B uses real floor plans).

use super::{CellState, GridMap, MapError};
use crate::geom::Point;

/// Names of the presets accepted by [`preset`].
pub const PRESET_NAMES: [&str; 5] = ["thesis-1", "thesis-2", "office", "office-large", "office-ring"];

/// Builds a preset by name.
pub fn preset(name: &str) -> Option<GridMap> {
    let map = match name {
        "thesis-1" => thesis_map(false),
        "thesis-2" => thesis_map(true),
        "office" => office(),
        "office-large" => office_large(),
        "office-ring" => office_ring(),
        _ => return None,
    };
    Some(map.expect("presets always have free cells"))
}

/// 003 map 1 (and map 2 with `disc`): 11 m × 11 m at 0.2 m, a 1 m wall frame, free area
/// `[1, 10)² m` = 2025 cells. Map 2 adds the disc of cells whose centre is strictly within 2 m
/// of (5.5, 5.5) m, tested in integer cell units (`dr² + dc² < 10²`: in floating metres 12
/// lattice points lie on the circle and rounding puts some inside), leaving 1720 free cells
/// (thesis-ga §16.4).
fn thesis_map(disc: bool) -> Result<GridMap, MapError> {
    const N: usize = 55;
    const WALL: usize = 5;
    let mut cells = vec![CellState::Free; N * N];
    for r in 0..N {
        for c in 0..N {
            let wall = r < WALL || c < WALL || r >= N - WALL || c >= N - WALL;
            let (dr, dc) = (r as i64 - 27, c as i64 - 27);
            let in_disc = disc && dr * dr + dc * dc < 100;
            if wall || in_disc {
                cells[r * N + c] = CellState::Occupied;
            }
        }
    }
    let name = if disc { "thesis-2" } else { "thesis-1" };
    GridMap::new(name, N, N, 0.2, Point::origin(), cells)
}

/// Fills the half-open metre rectangle `[x0, x1) × [y0, y1)` (cell centres inside) with `state`.
fn fill(cells: &mut [CellState], cols: usize, res: f64, rect: [f64; 4], state: CellState) {
    let [x0, y0, x1, y1] = rect;
    let rows = cells.len() / cols;
    for r in 0..rows {
        let y = (r as f64 + 0.5) * res;
        if y < y0 || y >= y1 {
            continue;
        }
        for c in 0..cols {
            let x = (c as f64 + 0.5) * res;
            if x >= x0 && x < x1 {
                cells[r * cols + c] = state;
            }
        }
    }
}

/// A synthetic office floor, 30 m × 20 m at 0.1 m: 0.2 m walls, a 2.4 m corridor across the
/// middle, three rooms below and four above with 1 m doors, a door between two lower rooms, a
/// pillar in the corridor and a table block in one room.
fn office() -> Result<GridMap, MapError> {
    const COLS: usize = 300;
    const ROWS: usize = 200;
    const RES: f64 = 0.1;
    use CellState::{Free, Occupied};
    let mut cells = vec![Occupied; COLS * ROWS];
    let f = |cells: &mut Vec<CellState>, rect: [f64; 4], s: CellState| fill(cells, COLS, RES, rect, s);
    // Interior.
    f(&mut cells, [0.2, 0.2, 29.8, 19.8], Free);
    // Corridor walls (below y 8.6 and above y 11.0).
    f(&mut cells, [0.2, 8.4, 29.8, 8.6], Occupied);
    f(&mut cells, [0.2, 11.0, 29.8, 11.2], Occupied);
    // Lower rooms: walls at x = 10 and 20.
    for x in [10.0, 20.0] {
        f(&mut cells, [x, 0.2, x + 0.2, 8.4], Occupied);
    }
    // Upper rooms: walls at x = 7.5, 15, 22.5.
    for x in [7.5, 15.0, 22.5] {
        f(&mut cells, [x, 11.2, x + 0.2, 19.8], Occupied);
    }
    // Doors from the corridor, 1 m wide.
    for x in [4.5, 14.5, 24.5] {
        f(&mut cells, [x, 8.4, x + 1.0, 8.6], Free);
    }
    for x in [3.3, 10.8, 18.3, 25.8] {
        f(&mut cells, [x, 11.0, x + 1.0, 11.2], Free);
    }
    // Door between the first two lower rooms.
    f(&mut cells, [10.0, 2.0, 10.2, 3.0], Free);
    // Pillar in the corridor and a table block in the lower-right room.
    f(&mut cells, [14.8, 9.5, 15.2, 9.9], Occupied);
    f(&mut cells, [24.0, 3.5, 26.0, 4.5], Occupied);
    GridMap::new("office", COLS, ROWS, RES, Point::origin(), cells)
}

/// A larger synthetic floor for multi-agent runs, 45 m × 30 m at 0.1 m: two corridors across
/// joined by a cross corridor, three rows of rooms with 1 m doors, a few obstacles.
fn office_large() -> Result<GridMap, MapError> {
    const COLS: usize = 450;
    const ROWS: usize = 300;
    const RES: f64 = 0.1;
    use CellState::{Free, Occupied};
    let mut cells = vec![Occupied; COLS * ROWS];
    let f = |cells: &mut Vec<CellState>, rect: [f64; 4], s: CellState| fill(cells, COLS, RES, rect, s);
    f(&mut cells, [0.2, 0.2, 44.8, 29.8], Free);
    // Corridor walls: corridor A at y 9.0–11.4, corridor B at y 19.0–21.4.
    for y in [8.8, 11.4, 18.8, 21.4] {
        f(&mut cells, [0.2, y, 44.8, y + 0.2], Occupied);
    }
    // Room walls: bottom row every 9 m, middle row every 7.5 m, top row every 9 m.
    for k in 1..5 {
        let x = 9.0 * k as f64;
        f(&mut cells, [x, 0.2, x + 0.2, 8.8], Occupied);
        f(&mut cells, [x, 21.6, x + 0.2, 29.8], Occupied);
    }
    for k in 1..6 {
        let x = 7.5 * k as f64;
        f(&mut cells, [x, 11.6, x + 0.2, 18.8], Occupied);
    }
    // Cross corridor between A and B at x 21.0–23.4 (replaces the middle room walls there).
    f(&mut cells, [21.0, 11.4, 23.4, 19.0], Free);
    f(&mut cells, [20.8, 11.6, 21.0, 18.8], Occupied);
    f(&mut cells, [23.4, 11.6, 23.6, 18.8], Occupied);
    // Doors (1 m) from every room to its corridor.
    for k in 0..5 {
        let x = 9.0 * k as f64 + 4.0;
        f(&mut cells, [x, 8.8, x + 1.0, 9.0], Free);
        f(&mut cells, [x, 21.4, x + 1.0, 21.6], Free);
    }
    for k in 0..6 {
        let x = 7.5 * k as f64 + 3.0;
        if (20.8..23.6).contains(&x) {
            continue;
        }
        f(&mut cells, [x, 11.4, x + 1.0, 11.6], Free);
        f(&mut cells, [x, 18.8, x + 1.0, 19.0], Free);
    }
    // Obstacles: pillars in the corridors, tables in two rooms.
    for x in [10.0, 30.0] {
        f(&mut cells, [x, 9.9, x + 0.4, 10.3], Occupied);
        f(&mut cells, [x + 5.0, 19.9, x + 5.4, 20.3], Occupied);
    }
    f(&mut cells, [2.5, 3.5, 5.5, 4.5], Occupied);
    f(&mut cells, [38.0, 24.0, 40.0, 26.0], Occupied);
    GridMap::new("office-large", COLS, ROWS, RES, Point::origin(), cells)
}

/// A floor plan of the kind 000 plans on (a university building floor), 60 m × 40 m at
/// 0.15 m/px: a 2.5 m ring corridor around a central block, rooms on both sides of the corridor
/// (three outside along each long side, two inside, 1.5 m doors), 0.3 m walls. As in 000
/// §II-B.1, space that is not to be mapped (stairwells and services at the short ends, the
/// block's core) is segmented as occluded, which leaves about 1 400 m² of explorable floor.
/// Nobody's data: drawn here from these rules.
fn office_ring() -> Result<GridMap, MapError> {
    const COLS: usize = 400;
    const ROWS: usize = 267;
    const RES: f64 = 0.15;
    const TOP: f64 = 39.75; // inner face of the top outer wall
    use CellState::{Free, Occupied};
    let mut cells = vec![Occupied; COLS * ROWS];
    let f = |cells: &mut Vec<CellState>, rect: [f64; 4], s: CellState| fill(cells, COLS, RES, rect, s);
    // Outer rooms: the long sides' strips [7.5, 52.5] × [0.3, 7.2] and [7.5, 52.5] × [32.8, TOP].
    f(&mut cells, [7.5, 0.3, 52.5, 7.2], Free);
    f(&mut cells, [7.5, 32.8, 52.5, TOP], Free);
    // The ring corridor [7.5, 52.5] × [7.5, 32.5] less [10, 50] × [10, 30].
    f(&mut cells, [7.5, 7.5, 52.5, 32.5], Free);
    f(&mut cells, [10.0, 10.0, 50.0, 30.0], Occupied);
    // Inner rooms along the block's long sides; its core and short ends stay occluded.
    f(&mut cells, [10.3, 10.3, 49.7, 16.0], Free);
    f(&mut cells, [10.3, 24.0, 49.7, 29.7], Free);
    for x in [22.35, 37.35] {
        f(&mut cells, [x, 0.3, x + 0.3, 7.2], Occupied);
        f(&mut cells, [x, 32.8, x + 0.3, TOP], Occupied);
    }
    f(&mut cells, [29.85, 10.3, 30.15, 16.0], Occupied);
    f(&mut cells, [29.85, 24.0, 30.15, 29.7], Occupied);
    // Doors, 1.5 m, centred on each room's corridor wall.
    let door = |cells: &mut Vec<CellState>, centre: f64, wall: f64| {
        f(cells, [centre - 0.75, wall, centre + 0.75, wall + 0.3], Free);
    };
    for x in [15.0, 30.0, 45.0] {
        door(&mut cells, x, 7.2);
        door(&mut cells, x, 32.5);
    }
    for x in [20.0, 40.0] {
        door(&mut cells, x, 10.0);
        door(&mut cells, x, 29.7);
    }
    GridMap::new("office-ring", COLS, ROWS, RES, Point::origin(), cells)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thesis_free_cell_counts_match_spec() {
        // thesis-ga §16.4: A_pix = 2025 on map 1 and 1720 on map 2 (disc of 305 cells).
        assert_eq!(preset("thesis-1").unwrap().free_count(), 2025);
        assert_eq!(preset("thesis-2").unwrap().free_count(), 1720);
    }

    #[test]
    fn thesis_free_area_is_one_to_ten_metres() {
        let m = preset("thesis-1").unwrap();
        assert!(m.is_free_point(Point::new(1.01, 1.01)));
        assert!(!m.is_free_point(Point::new(0.99, 5.0)));
        assert!(m.is_free_point(Point::new(9.99, 9.99)));
        assert!(!m.is_free_point(Point::new(10.0, 5.0)));
    }

    #[test]
    fn office_has_rooms_and_doors() {
        let m = preset("office").unwrap();
        assert_eq!((m.cols(), m.rows()), (300, 200));
        assert!(m.is_free_point(Point::new(5.0, 8.5)), "door of the first lower room");
        assert!(!m.is_free_point(Point::new(3.0, 8.5)), "corridor wall");
        assert!(m.is_free_point(Point::new(15.5, 9.7)), "corridor beside the pillar");
        assert!(!m.is_free_point(Point::new(15.0, 9.7)), "pillar");
        assert!(m.free_count() > 40_000);
    }

    #[test]
    fn office_ring_has_a_ring_corridor_and_doors() {
        let m = preset("office-ring").unwrap();
        assert_eq!((m.cols(), m.rows()), (400, 267));
        for (x, y) in [(8.75, 20.0), (30.0, 8.75), (30.0, 31.25), (51.25, 20.0)] {
            assert!(m.is_free_point(Point::new(x, y)), "corridor at ({x}, {y})");
        }
        assert!(!m.is_free_point(Point::new(30.0, 20.0)), "central block");
        assert!(!m.is_free_point(Point::new(4.0, 20.0)), "services at the short end");
        assert!(m.is_free_point(Point::new(15.0, 7.35)), "door of the first outer room");
        assert!(!m.is_free_point(Point::new(13.0, 7.35)), "corridor wall beside it");
        assert!(m.is_free_point(Point::new(20.0, 10.15)), "door of the first inner room");
        assert!(m.is_free_point(Point::new(15.0, 3.0)), "inside the first outer room");
        // About 1 400 m² of explorable floor (62 500 px of 0.0225 m²).
        assert!((60_000..65_000).contains(&m.free_count()), "{}", m.free_count());
    }

    #[test]
    fn unknown_preset_is_none() {
        assert!(preset("thesis-3").is_none());
    }
}
