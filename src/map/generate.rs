//! Procedural floor plans, seeded: offices (rooms on both sides of a corridor), houses (rooms
//! of a binary space partition joined by doors) and warehouses (racks in rows, aisles between,
//! pillars), with optional SLAM-like noise (ragged wall faces, specks in the open, unknown
//! space outside the building). A study can then run over maps no one drew by hand, and tests
//! need no licensed data. The same spec and seed give the same map, cell for cell.
//!
//! Every plan is built from interior rectangles ("rooms") separated by walls: the building is
//! solid, rooms are carved out of it, and doors are carved through the walls between rooms
//! that share a long enough stretch of wall. Doors join every room to the others (a random
//! spanning tree of the rooms' adjacency, then a few more doors), and furniture stands against
//! walls away from doors, so that a robot that fits through a door reaches every room.

use super::{CellState, GridMap};
use crate::geom::Point;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The kinds of floor plan [`generate`] draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlanKind {
    /// Rooms of 3–6 m on both sides of a corridor of about 2 m, a desk or two in each.
    Office,
    /// Rooms of a binary space partition (none narrower than 2.6 m), joined by doors.
    House,
    /// One hall: rows of racks with aisles between them and a lattice of pillars.
    Warehouse,
    /// One hall full of pillars, 1.4–1.8 m apart (about 600 on 40 m × 40 m).
    Hall,
}

impl PlanKind {
    /// Every kind, by the name the command line gives it.
    pub const ALL: [(PlanKind, &'static str); 4] = [
        (PlanKind::Office, "office"),
        (PlanKind::House, "house"),
        (PlanKind::Warehouse, "warehouse"),
        (PlanKind::Hall, "hall"),
    ];

    /// The kind called `name`.
    pub fn parse(name: &str) -> Option<Self> {
        Self::ALL.iter().find(|(_, n)| *n == name).map(|(k, _)| *k)
    }

    /// The kind's name.
    pub fn name(self) -> &'static str {
        Self::ALL.iter().find(|(k, _)| *k == self).map(|(_, n)| *n).expect("every kind is listed")
    }
}

/// What a generated plan looks like.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanSpec {
    /// The kind of plan.
    pub kind: PlanKind,
    /// The building's outer size in metres (the map adds a margin of 1 m on every side).
    pub width_m: f64,
    /// See `width_m`.
    pub height_m: f64,
    /// Metres per cell.
    pub resolution: f64,
    /// SLAM-like noise: ragged wall faces, specks, unknown space outside the building.
    pub noisy: bool,
    /// The seed of every random choice.
    pub seed: u64,
}

/// The thickness of every wall, in metres.
pub const WALL_M: f64 = 0.15;
/// The width of a door, in metres (a 0.6 m robot passes with 0.15 m to spare on either side).
pub const DOOR_M: f64 = 0.9;
/// The margin around the building, in metres.
const MARGIN_M: f64 = 1.0;
/// A wall face cell turns occupied with this probability in a noisy plan (a ragged face).
const RAGGED: f64 = 0.25;
/// A free cell turns occupied with this probability in a noisy plan (a speck of noise).
const SPECKLE: f64 = 0.0003;

impl PlanSpec {
    /// Checks the sizes: a building of 6–200 m a side at 0.01–0.5 m per cell, at most 2²⁶ cells.
    pub fn check(&self) -> Result<(), String> {
        for (what, v) in [("width", self.width_m), ("height", self.height_m)] {
            if !(6.0..=200.0).contains(&v) {
                return Err(format!("{what} = {v} m is out of range [6, 200] metres"));
            }
        }
        if !(0.01..=0.5).contains(&self.resolution) {
            return Err(format!("resolution = {} is out of range [0.01, 0.5] metres per cell", self.resolution));
        }
        let cells =
            ((self.width_m + 2.0 * MARGIN_M) / self.resolution) * ((self.height_m + 2.0 * MARGIN_M) / self.resolution);
        if cells > (1u64 << 26) as f64 {
            return Err(format!("{cells:.3e} cells is more than 2^26: use a coarser resolution"));
        }
        Ok(())
    }
}

/// A generated plan: the map and a start station where a 0.6 m robot fits (in the first room
/// or the corridor, at least 0.5 m from every wall).
#[derive(Clone, Debug)]
pub struct Generated {
    /// The map, named `<kind>-<seed>` (with `-noisy` when noisy).
    pub map: GridMap,
    /// A start station.
    pub start: Point,
}

/// An axis-aligned rectangle in metres, `[x0, x1) × [y0, y1)`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Rect {
    x0: f64,
    y0: f64,
    x1: f64,
    y1: f64,
}

impl Rect {
    fn new(x0: f64, y0: f64, x1: f64, y1: f64) -> Self {
        Self { x0, y0, x1, y1 }
    }

    fn overlaps(&self, o: &Rect) -> bool {
        self.x0 < o.x1 && o.x0 < self.x1 && self.y0 < o.y1 && o.y0 < self.y1
    }

    fn centre(&self) -> Point {
        Point::new(0.5 * (self.x0 + self.x1), 0.5 * (self.y0 + self.y1))
    }
}

/// The raster being drawn: cell states, row 0 at the bottom (y up, as `GridMap`).
struct Canvas {
    cols: usize,
    rows: usize,
    res: f64,
    cells: Vec<CellState>,
}

impl Canvas {
    /// Sets every cell whose centre lies in `r` to `state`.
    fn fill(&mut self, r: Rect, state: CellState) {
        let to = |v: f64, n: usize| ((v / self.res - 0.5).ceil().max(0.0) as usize).min(n);
        let (c0, c1) = (to(r.x0, self.cols), to(r.x1, self.cols));
        let (r0, r1) = (to(r.y0, self.rows), to(r.y1, self.rows));
        for row in r0..r1 {
            self.cells[row * self.cols + c0..row * self.cols + c1].fill(state);
        }
    }
}

/// The clean twin of a generated map's source: the generator names a noisy plan
/// `<kind>-<seed>-noisy` and draws its walls and doors as those of `<kind>-<seed>`, so the two are
/// one floor plan. Any other source is its own.
pub fn clean_twin(source: &str) -> std::borrow::Cow<'_, str> {
    let (stem, extension) = match source.strip_suffix(".yaml") {
        Some(stem) => (stem, ".yaml"),
        None => (source, ""),
    };
    match stem.strip_suffix("-noisy") {
        Some(clean) => format!("{clean}{extension}").into(),
        None => source.into(),
    }
}

/// Draws the plan `spec` asks for; a spec out of range is refused with the reason.
pub fn generate(spec: &PlanSpec) -> Result<Generated, String> {
    spec.check()?;
    let mut rng = ChaCha8Rng::seed_from_u64(spec.seed);
    let res = spec.resolution;
    let (cols, rows) = (
        ((spec.width_m + 2.0 * MARGIN_M) / res).round() as usize,
        ((spec.height_m + 2.0 * MARGIN_M) / res).round() as usize,
    );
    // Outside the building: unknown space in a noisy plan (as a SLAM map has it), else solid.
    let outside = if spec.noisy { CellState::Unknown } else { CellState::Occupied };
    let mut canvas = Canvas { cols, rows, res, cells: vec![outside; cols * rows] };
    let building = Rect::new(MARGIN_M, MARGIN_M, MARGIN_M + spec.width_m, MARGIN_M + spec.height_m);
    canvas.fill(building, CellState::Occupied);
    let inside = Rect::new(building.x0 + WALL_M, building.y0 + WALL_M, building.x1 - WALL_M, building.y1 - WALL_M);
    let (rooms, links, furniture) = match spec.kind {
        PlanKind::Office => office(inside, &mut rng),
        PlanKind::House => house(inside, &mut rng),
        PlanKind::Warehouse => warehouse(inside, &mut rng),
        PlanKind::Hall => hall(inside, &mut rng),
    };
    for r in &rooms {
        canvas.fill(*r, CellState::Free);
    }
    // The doors are drawn before the noise (a clean and a noisy plan of one seed have the same
    // rooms, doors and furniture) and carved after it, their approaches cleared of it: a speck
    // in front of a door would close a room to a robot that fits the door with centimetres to
    // spare.
    let openings = doors(&rooms, &links, &mut rng);
    if spec.noisy {
        add_noise(&mut canvas, &mut rng);
    }
    for (door, approach) in &openings {
        canvas.fill(*approach, CellState::Free);
        canvas.fill(*door, CellState::Free);
    }
    // No furniture in a door's approach (a cupboard in a corner would close a door near it).
    for f in furniture.iter().filter(|f| openings.iter().all(|(_, a)| !f.overlaps(a))) {
        canvas.fill(*f, CellState::Occupied);
    }
    let name = format!("{}-{}{}", spec.kind.name(), spec.seed, if spec.noisy { "-noisy" } else { "" });
    let start = rooms[0].centre();
    let map = GridMap::new(name, cols, rows, res, Point::origin(), canvas.cells).map_err(|e| e.to_string())?;
    Ok(Generated { map, start })
}

/// Pairs of rooms to join by a door (indices into the rooms), and whether each pair must be
/// joined (`true`) or may be (`false`, joined by one of the extra doors).
type Links = Vec<(usize, usize, bool)>;

/// An office: a corridor along the middle (the first room), rooms of 3–6 m above and below it,
/// each with a door onto the corridor, and a desk or two against each room's far wall.
fn office(inside: Rect, rng: &mut ChaCha8Rng) -> (Vec<Rect>, Links, Vec<Rect>) {
    let corridor_w = rng.random_range(1.6..2.4);
    let mid = 0.5 * (inside.y0 + inside.y1) + rng.random_range(-0.15..0.15) * (inside.y1 - inside.y0);
    let corridor = Rect::new(inside.x0, mid - 0.5 * corridor_w, inside.x1, mid + 0.5 * corridor_w);
    let mut rooms = vec![corridor];
    let mut furniture = Vec::new();
    for (y0, y1, far_low) in [(inside.y0, corridor.y0 - WALL_M, true), (corridor.y1 + WALL_M, inside.y1, false)] {
        if y1 - y0 < 2.0 {
            continue;
        }
        let mut x = inside.x0;
        while inside.x1 - x > 2.5 {
            let w = rng.random_range(3.0..6.0f64).min(inside.x1 - x);
            let w = if inside.x1 - (x + w) < 3.0 { inside.x1 - x } else { w };
            let room = Rect::new(x, y0, x + w, y1);
            // Desks against the far wall, clear of the door (on the corridor's side).
            for _ in 0..rng.random_range(1..=2) {
                let (dw, dd) = (rng.random_range(0.8..1.6f64).min(w - 0.8), rng.random_range(0.6..0.8));
                let dx = rng.random_range(room.x0 + 0.2..room.x1 - dw - 0.2);
                let desk = if far_low {
                    Rect::new(dx, room.y0, dx + dw, room.y0 + dd)
                } else {
                    Rect::new(dx, room.y1 - dd, dx + dw, room.y1)
                };
                if (room.y1 - room.y0) - dd > 1.6 {
                    furniture.push(desk);
                }
            }
            rooms.push(room);
            x += w + WALL_M;
        }
    }
    let links = (1..rooms.len()).map(|i| (0, i, true)).collect();
    (rooms, links, furniture)
}

/// A house: the inside split in two, across its longer side, until no room can be split into
/// two of at least 2.6 m (or a coin says stop, for rooms up to 7 m); doors join the rooms
/// (every adjacent pair may have one: a spanning tree is drawn among them); a cupboard stands
/// in some corners.
fn house(inside: Rect, rng: &mut ChaCha8Rng) -> (Vec<Rect>, Links, Vec<Rect>) {
    const MIN_ROOM: f64 = 2.6;
    let mut todo = vec![inside];
    let mut rooms = Vec::new();
    while let Some(r) = todo.pop() {
        let (w, h) = (r.x1 - r.x0, r.y1 - r.y0);
        let long = w.max(h);
        if long < 2.0 * MIN_ROOM + WALL_M || (long < 7.0 && rng.random_bool(0.3)) {
            rooms.push(r);
            continue;
        }
        let at = rng.random_range(MIN_ROOM..long - MIN_ROOM - WALL_M);
        if w >= h {
            todo.push(Rect::new(r.x0, r.y0, r.x0 + at, r.y1));
            todo.push(Rect::new(r.x0 + at + WALL_M, r.y0, r.x1, r.y1));
        } else {
            todo.push(Rect::new(r.x0, r.y0, r.x1, r.y0 + at));
            todo.push(Rect::new(r.x0, r.y0 + at + WALL_M, r.x1, r.y1));
        }
    }
    // The largest room first: the start station stands there.
    rooms.sort_by(|a, b| ((b.x1 - b.x0) * (b.y1 - b.y0)).total_cmp(&((a.x1 - a.x0) * (a.y1 - a.y0))));
    let mut links = Vec::new();
    for i in 0..rooms.len() {
        for j in i + 1..rooms.len() {
            if shared_wall(&rooms[i], &rooms[j]).is_some() {
                links.push((i, j, false));
            }
        }
    }
    let mut furniture = Vec::new();
    for r in &rooms {
        if !rng.random_bool(0.5) {
            continue;
        }
        let (cw, cd) = (rng.random_range(0.6..1.2), 0.5);
        furniture.push(match rng.random_range(0..4) {
            0 => Rect::new(r.x0, r.y0, r.x0 + cw, r.y0 + cd),
            1 => Rect::new(r.x1 - cw, r.y0, r.x1, r.y0 + cd),
            2 => Rect::new(r.x0, r.y1 - cd, r.x0 + cw, r.y1),
            _ => Rect::new(r.x1 - cw, r.y1 - cd, r.x1, r.y1),
        });
    }
    (rooms, links, furniture)
}

/// A warehouse: one hall (the only room), rows of racks 1 m deep with aisles of 2–3 m, a cross
/// aisle at either end, and pillars of 0.4 m on a lattice of 3–5 m in the open space.
fn warehouse(inside: Rect, rng: &mut ChaCha8Rng) -> (Vec<Rect>, Links, Vec<Rect>) {
    let mut furniture = Vec::new();
    let (aisle, end_aisle) = (rng.random_range(2.0..3.0), 2.5);
    let (rx0, rx1) = (inside.x0 + end_aisle, inside.x1 - end_aisle);
    let racks_top = inside.y0 + 0.5 * (inside.y1 - inside.y0);
    let mut y = inside.y0 + aisle;
    while y + 1.0 + aisle <= racks_top {
        furniture.push(Rect::new(rx0, y, rx1, y + 1.0));
        y += 1.0 + aisle;
    }
    let spacing = rng.random_range(3.0..5.0);
    let mut py = racks_top + 0.5 * spacing;
    while py + 0.5 * spacing <= inside.y1 {
        let mut px = inside.x0 + 0.5 * spacing;
        while px + 0.5 * spacing <= inside.x1 {
            furniture.push(Rect::new(px - 0.2, py - 0.2, px + 0.2, py + 0.2));
            px += spacing;
        }
        py += spacing;
    }
    (vec![inside], Vec::new(), furniture)
}

/// A hall of pillars: 0.4 m squares on a square lattice 1.4–1.8 m apart, the hall's centre
/// (the start station) midway between four of them, none nearer the walls than 0.5 m.
fn hall(inside: Rect, rng: &mut ChaCha8Rng) -> (Vec<Rect>, Links, Vec<Rect>) {
    let spacing = rng.random_range(1.4..1.8);
    let c = inside.centre();
    let along = |lo: f64, hi: f64, mid: f64| {
        let k = ((mid - lo - 0.7) / spacing - 0.5).floor();
        (0..).map(move |i| mid - (k + 0.5) * spacing + i as f64 * spacing).take_while(move |&v| v + 0.7 <= hi)
    };
    let mut pillars = Vec::new();
    for y in along(inside.y0, inside.y1, c.y) {
        for x in along(inside.x0, inside.x1, c.x) {
            pillars.push(Rect::new(x - 0.2, y - 0.2, x + 0.2, y + 0.2));
        }
    }
    (vec![inside], Vec::new(), pillars)
}

/// The stretch of wall two rooms share, as `(vertical, at, from, to)`: the wall between them
/// runs along x = `at` (vertical) or y = `at`, from `from` to `to`; `None` unless it is long
/// enough for a door with 0.3 m on either side.
fn shared_wall(a: &Rect, b: &Rect) -> Option<(bool, f64, f64, f64)> {
    let near = |u: f64, v: f64| (u - v).abs() < 1e-6;
    let overlap = |a0: f64, a1: f64, b0: f64, b1: f64| (a0.max(b0), a1.min(b1));
    let wall = if near(a.x1 + WALL_M, b.x0) || near(b.x1 + WALL_M, a.x0) {
        let at = if near(a.x1 + WALL_M, b.x0) { a.x1 } else { b.x1 };
        let (from, to) = overlap(a.y0, a.y1, b.y0, b.y1);
        (true, at, from, to)
    } else if near(a.y1 + WALL_M, b.y0) || near(b.y1 + WALL_M, a.y0) {
        let at = if near(a.y1 + WALL_M, b.y0) { a.y1 } else { b.y1 };
        let (from, to) = overlap(a.x0, a.x1, b.x0, b.x1);
        (false, at, from, to)
    } else {
        return None;
    };
    (wall.3 - wall.2 >= DOOR_M + 0.6).then_some(wall)
}

/// The depth of a door's approach on either side, in metres: kept clear of noise.
const APPROACH_M: f64 = 0.6;

/// The door openings and their approaches (the door's width, [`APPROACH_M`] into either room):
/// every required link, then a random spanning tree of the optional ones (union–find over a
/// shuffled list) and one in five of the rest.
fn doors(rooms: &[Rect], links: &Links, rng: &mut ChaCha8Rng) -> Vec<(Rect, Rect)> {
    use rand::seq::SliceRandom;
    let mut parent: Vec<usize> = (0..rooms.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let mut order: Vec<&(usize, usize, bool)> = links.iter().collect();
    order.shuffle(rng);
    order.sort_by_key(|l| !l.2);
    let mut out = Vec::new();
    for &&(i, j, required) in &order {
        let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
        if !(required || ri != rj || rng.random_bool(0.2)) {
            continue;
        }
        parent[ri] = rj;
        let (vertical, at, from, to) = match shared_wall(&rooms[i], &rooms[j]) {
            Some(w) => w,
            // A required link between rooms that share no wall long enough: the corridor side
            // of an office room always does (they share the room's whole width).
            None => continue,
        };
        let d0 = rng.random_range(from + 0.3..to - 0.3 - DOOR_M);
        // Through the wall, a little into both rooms, so that no sliver of wall remains.
        let across = |depth: f64| (at - depth, at + WALL_M + depth);
        let rect = |(a0, a1): (f64, f64)| {
            if vertical { Rect::new(a0, d0, a1, d0 + DOOR_M) } else { Rect::new(d0, a0, d0 + DOOR_M, a1) }
        };
        out.push((rect(across(0.01)), rect(across(APPROACH_M))));
    }
    out
}

/// SLAM-like noise: wall faces made ragged (a face cell next to free space turns occupied with
/// probability [`RAGGED`]) and specks in the open ([`SPECKLE`]); the unknown outside is drawn
/// by [`generate`].
fn add_noise(canvas: &mut Canvas, rng: &mut ChaCha8Rng) {
    let (cols, rows) = (canvas.cols, canvas.rows);
    let before = canvas.cells.clone();
    for r in 1..rows - 1 {
        for c in 1..cols - 1 {
            let i = r * cols + c;
            if before[i] != CellState::Free {
                continue;
            }
            let by_wall = [i - 1, i + 1, i - cols, i + cols].iter().any(|&j| before[j] == CellState::Occupied);
            let p = if by_wall { RAGGED } else { SPECKLE };
            if rng.random_bool(p) {
                canvas.cells[i] = CellState::Occupied;
            }
        }
    }
}

#[cfg(test)]
#[path = "generate/tests.rs"]
mod tests;
