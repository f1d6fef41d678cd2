//! The precomputed world of the waypoint planner (waypoint §2–§7): raster, waypoints, graph,
//! traversal views, wall band and start waypoints, built once per map and parameter set.

use super::graph::Graph;
use super::precompute::{Sensing, Traversals};
use super::{passages, waypoints};
use crate::coverage::camera::{Camera, ViewShape};
use crate::coverage::views::bitset;
use crate::coverage::work_map::WorkMap;
use crate::map::GridMap;

/// Which waypoints are used (waypoint §3.5).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WaypointSet {
    /// All waypoints.
    Full,
    /// Only waypoints at most the near-wall distance from a wall (plus what connectivity needs).
    NearWall,
}

/// Geometry parameters in metres and degrees.
#[derive(Clone, Debug, PartialEq)]
pub struct WorldParams {
    /// Pixel scale `s` (m/px).
    pub scale: f64,
    /// UAV width (m).
    pub uav_width: f64,
    /// Narrowest accessible hallway `h_min` (m).
    pub hallway: f64,
    /// Grid step, safety buffer, anti-crowding distance, wall band and near-wall distance (m).
    pub geometry: super::geometry::Geometry,
    /// Maximum traverse distance of a graph edge (m).
    pub max_traverse: f64,
    /// `d_min` (m).
    pub d_min: f64,
    /// `d_max` (m).
    pub d_max: f64,
    /// `θ_fov` (degrees).
    pub fov_deg: f64,
    /// `m` sections.
    pub sections: usize,
    /// How section depths become a view.
    pub view_shape: ViewShape,
    /// Waypoint set.
    pub set: WaypointSet,
    /// Entry positions (m), one shared or one per agent.
    pub starts: Vec<(f64, f64)>,
    /// What the planner optimises coverage of.
    pub objective: WaypointObjective,
}

/// What the waypoint planner's coverage objective measures (000 optimises the camera; the
/// footprint is an option for the ablation).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum ObjectiveKind {
    /// 000's camera views (eq. 2 on the camera's coverage).
    #[default]
    Camera,
    /// The ground robot's swept footprint along each edge (eq. 2 on the swept pixels).
    Footprint,
}

/// The objective with its parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WaypointObjective {
    /// Camera views.
    Camera,
    /// Swept footprint of this width in metres.
    Footprint {
        /// Width in metres.
        width: f64,
    },
}

/// Errors building the world.
#[derive(Debug, thiserror::Error)]
pub enum WorldError {
    /// No waypoint could be placed.
    #[error("no waypoint fits on the map with hallway width {0} m and the safety buffer")]
    NoWaypoints(f64),
    /// The start cannot reach most of the map.
    #[error(
        "the start at ({x:.2}, {y:.2}) m reaches only {reached} of {total} waypoints: check the map's doors, `hallway` and `max_traverse`"
    )]
    Unreachable {
        /// Start x.
        x: f64,
        /// Start y.
        y: f64,
        /// Waypoints reached.
        reached: usize,
        /// Waypoints placed.
        total: usize,
    },
    /// The wall clock ran out while the views of the graph's edges were computed.
    #[error(
        "the wall clock of {limit_s} s (`budget.wall_clock_s`) ran out while precomputing the views of {done} of {total} waypoints' edges, before any plan; raise it or coarsen `scorer.camera.scale`"
    )]
    OutOfTime {
        /// The wall-clock limit (s).
        limit_s: f64,
        /// Waypoints whose edges were done.
        done: usize,
        /// Waypoints of the graph.
        total: usize,
    },
    /// The wall clock ran out while the waypoints were placed.
    #[error(
        "the wall clock of {limit_s} s (`budget.wall_clock_s`) ran out while placing the waypoints, before any plan; raise it or coarsen `scorer.camera.scale`"
    )]
    PlacingOutOfTime {
        /// The wall-clock limit (s).
        limit_s: f64,
    },
    /// The run's interrupt was raised while the world was built (waypoints or views).
    #[error("interrupted while building the waypoint graph and its views")]
    Interrupted,
}

/// Everything precomputed.
pub struct World {
    /// The working raster.
    pub map: WorkMap,
    /// The graph (restricted to the starts' component).
    pub graph: Graph,
    /// Per-traversal data.
    pub traversals: Traversals,
    /// Wall band `B` as a bitset.
    pub band: Vec<u64>,
    /// `|F|`.
    pub free: u64,
    /// `|B|`.
    pub band_count: u64,
    /// Start waypoint per agent.
    pub starts: Vec<u32>,
    /// Safety buffer `b` (px).
    pub buffer: f64,
    /// Width of the wall band (px).
    pub band_px: f64,
    /// Waypoints of the full set dropped because the start could not reach them.
    pub dropped: usize,
    /// Waypoints added where nudging and merging had left space without one.
    pub gap_fills: usize,
    /// Waypoints added in narrow passages (doors) to connect space the graph missed.
    pub passage_fills: usize,
    /// Share of the wall band that some traversal of the graph sees: the most `C_walls` any
    /// plan can reach.
    pub reachable_walls: f64,
}

/// What the robot sees or sweeps along every edge of `graph` (the camera or the footprint of
/// `p`), given up at `cutoff`.
fn views_within(
    wm: &WorkMap,
    graph: &Graph,
    p: &WorldParams,
    cutoff: &crate::planner::executor::SetupCutoff,
) -> Result<Traversals, WorldError> {
    let camera = Camera {
        d_min: p.d_min / p.scale,
        d_max: p.d_max / p.scale,
        fov: p.fov_deg.to_radians(),
        sections: p.sections,
        shape: p.view_shape,
    };
    let sensing = match p.objective {
        WaypointObjective::Camera => Sensing::Camera(camera),
        WaypointObjective::Footprint { width } => Sensing::Footprint { width_px: width / p.scale },
    };
    let give_up = || cutoff.reached().is_some();
    Traversals::compute(wm, graph, &sensing, &give_up).map_err(|done| match cutoff.reached() {
        Some(crate::planner::StopReason::Interrupted) => WorldError::Interrupted,
        _ => WorldError::OutOfTime { limit_s: cutoff.limit_s(), done, total: graph.points.len() },
    })
}

impl World {
    /// Builds the world for `agents` agents.
    pub fn build(map: &GridMap, p: &WorldParams, agents: usize) -> Result<Self, WorldError> {
        Self::build_within(map, p, agents, &Default::default())
    }

    /// [`World::build`] that gives up at `cutoff`: with [`WorldError::OutOfTime`] once its wall
    /// clock has passed, [`WorldError::Interrupted`] once its interrupt is raised.
    pub fn build_within(
        map: &GridMap,
        p: &WorldParams,
        agents: usize,
        cutoff: &crate::planner::executor::SetupCutoff,
    ) -> Result<Self, WorldError> {
        let placing_stopped = || match cutoff.reached() {
            Some(crate::planner::StopReason::Interrupted) => WorldError::Interrupted,
            _ => WorldError::PlacingOutOfTime { limit_s: cutoff.limit_s() },
        };
        let wm = WorkMap::new_until(map, p.scale, &|| cutoff.reached().is_some()).ok_or_else(placing_stopped)?;
        if cutoff.reached().is_some() {
            return Err(placing_stopped());
        }
        let geo = &p.geometry;
        let spacing = waypoints::Spacing {
            step: geo.grid_step / p.scale,
            buffer: geo.buffer / p.scale,
            merge: geo.merge / p.scale,
            min_clearance: p.uav_width / (2.0 * p.scale),
        };
        let b = spacing.buffer;
        let give_up = || cutoff.reached().is_some();
        let (pts, gap_fills) = waypoints::place_until(&wm, &spacing, &give_up).ok_or_else(placing_stopped)?;
        if pts.is_empty() {
            return Err(WorldError::NoWaypoints(p.hallway));
        }
        let starts_px: Vec<(f64, f64)> = p.starts.iter().map(|&(x, y)| wm.to_px(x, y)).collect();
        let max_len = p.max_traverse / p.scale;
        let (full, passage_fills) =
            passages::connect(&wm, pts, starts_px[0], max_len, spacing.step, spacing.min_clearance);
        let placed = full.points.len();
        let comp = full.component(full.nearest(starts_px[0]));
        let reached = comp.iter().filter(|c| **c).count();
        if reached < 2 || reached * 2 < placed {
            let (x, y) = p.starts[0];
            return Err(WorldError::Unreachable { x, y, reached, total: placed });
        }
        let (mut graph, _) = full.restrict(&comp);
        if p.set == WaypointSet::NearWall {
            let near = geo.near_wall / p.scale;
            let start_ids: Vec<usize> = starts_px.iter().map(|&s| graph.nearest(s)).collect();
            let keep: Vec<bool> = (0..graph.points.len())
                .map(|i| wm.clearance(graph.points[i]) <= near || start_ids.contains(&i))
                .collect();
            let kept = connect_subset(&graph, keep, start_ids[0]);
            let pts = (0..kept.len()).filter(|&i| kept[i]).map(|i| graph.points[i]).collect();
            let near_graph = Graph::build(&wm, pts, max_len);
            let comp = near_graph.component(near_graph.nearest(starts_px[0]));
            graph = near_graph.restrict(&comp).0;
        }
        let starts: Vec<u32> =
            (0..agents).map(|a| graph.nearest(starts_px[a.min(starts_px.len() - 1)]) as u32).collect();
        let traversals = views_within(&wm, &graph, p, cutoff)?;
        let band_px = geo.wall_band / p.scale;
        let band_flags = wm.band(band_px);
        let band_count = band_flags.iter().filter(|x| **x).count() as u64;
        let band = bitset(&band_flags);
        let reachable_walls = reachable_fraction(&traversals, &band, band_count);
        Ok(Self {
            free: wm.free_count() as u64,
            band,
            band_count,
            band_px,
            gap_fills,
            passage_fills,
            reachable_walls,
            dropped: placed - reached,
            map: wm,
            graph,
            traversals,
            starts,
            buffer: b,
        })
    }
}

/// The share of the band (`band`, `band_count` pixels) seen by at least one view of any
/// traversal.
fn reachable_fraction(tr: &Traversals, band: &[u64], band_count: u64) -> f64 {
    tr.all_views().counts(band).1 as f64 / band_count.max(1) as f64
}

/// Adds back removed waypoints on shortest paths of the full graph until `keep` is connected
/// from `start` (W5).
fn connect_subset(full: &Graph, mut keep: Vec<bool>, start: usize) -> Vec<bool> {
    loop {
        let (sub, map) = full.restrict(&keep);
        let Some(s) = map[start] else { return keep };
        let comp = sub.component(s as usize);
        let in_comp: Vec<bool> = (0..keep.len()).map(|i| map[i].is_some_and(|k| comp[k as usize])).collect();
        let Some(target) = (0..keep.len()).find(|&i| keep[i] && !in_comp[i]) else { return keep };
        // BFS in the full graph from the start's component to the target.
        let mut prev = vec![usize::MAX; keep.len()];
        let mut queue: std::collections::VecDeque<usize> = (0..keep.len()).filter(|&i| in_comp[i]).collect();
        for &q in &queue {
            prev[q] = q;
        }
        while let Some(i) = queue.pop_front() {
            if i == target {
                break;
            }
            for &j in &full.adj[i] {
                if prev[j as usize] == usize::MAX {
                    prev[j as usize] = i;
                    queue.push_back(j as usize);
                }
            }
        }
        if prev[target] == usize::MAX {
            keep[target] = false; // unreachable even in the full graph
            continue;
        }
        let mut k = target;
        while prev[k] != k {
            keep[k] = true;
            k = prev[k];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::presets::preset;

    fn params(set: WaypointSet) -> WorldParams {
        WorldParams {
            scale: 0.15,
            uav_width: 0.5,
            hallway: 1.5,
            geometry: crate::waypoint::geometry::Geometry {
                grid_step: 0.75,
                buffer: 0.3,
                merge: 0.75,
                wall_band: 0.3,
                near_wall: 1.05,
            },
            max_traverse: 4.0,
            d_min: 0.2,
            d_max: 7.0,
            fov_deg: 69.4,
            sections: 15,
            view_shape: ViewShape::Sections,
            set,
            starts: vec![(2.0, 2.0)],
            objective: WaypointObjective::Camera,
        }
    }

    #[test]
    fn footprint_objective_sweeps_free_pixels_along_each_edge() {
        let map = preset("office").unwrap();
        let p = WorldParams { objective: WaypointObjective::Footprint { width: 0.6 }, ..params(WaypointSet::Full) };
        let w = World::build(&map, &p, 1).unwrap();
        let (i, k) = (0, 0);
        let t = &w.traversals.edges[i][k];
        assert!(t.arrive.words.is_empty(), "no arrival view with a footprint");
        let bits: Vec<usize> = t
            .depart
            .words
            .iter()
            .enumerate()
            .flat_map(|(n, word)| {
                (0..64).filter(move |b| word >> b & 1 == 1).map(move |b| (t.depart.first as usize + n) * 64 + b)
            })
            .collect();
        // A 0.6 m footprint (4 px) along an edge of at least one grid step sweeps at least
        // 4 px x the edge's length in pixels (less the half-open end), all of them free.
        assert!(bits.len() as f64 >= 3.0 * t.dist, "{} pixels for {} px", bits.len(), t.dist);
        assert!(bits.iter().all(|&b| !w.map.occluded[b]));
    }

    #[test]
    fn near_wall_set_is_smaller_and_stays_connected() {
        let map = preset("office").unwrap();
        let full = World::build(&map, &params(WaypointSet::Full), 1).unwrap();
        let near = World::build(&map, &params(WaypointSet::NearWall), 1).unwrap();
        assert!(near.graph.points.len() < full.graph.points.len());
        let comp = near.graph.component(near.starts[0] as usize);
        assert!(comp.iter().all(|c| *c), "every kept waypoint is reachable from the start");
        // Safety buffer 0.3 m at 0.15 m/px.
        assert!((full.buffer - 2.0).abs() < 1e-12);
    }

    #[test]
    fn an_isolated_start_is_a_clear_error() {
        // A start in the thesis map 2 corner with a hallway so wide that only a few waypoints fit.
        let map = preset("thesis-1").unwrap();
        let p = WorldParams { max_traverse: 0.1, scale: 0.2, starts: vec![(1.5, 1.5)], ..params(WaypointSet::Full) };
        let e = World::build(&map, &p, 1).err().expect("edges longer than 0.1 m are removed");
        assert!(e.to_string().contains("reaches only"), "{e}");
    }

    #[test]
    fn the_papers_values_reach_every_room_of_the_ring_office() {
        // 000's hallway of 2.5 m on the ring office. The 1.5 m doors are narrower than twice the
        // 1.25 m buffer; at the driver's 2.5 m grid no grid point falls in a door, so the rooms
        // stay in the graph only through passage waypoints.
        let map = preset("office-ring").unwrap();
        let section: crate::waypoint::config::WaypointSection = toml::from_str("hallway = 2.5\n").unwrap();
        for step in [crate::waypoint::geometry::GridStep::HalfHallway, crate::waypoint::geometry::GridStep::Hallway] {
            let w = crate::waypoint::config::WaypointSection { grid_step: step, ..section.clone() };
            let geometry = crate::waypoint::geometry::Geometry::resolve(&w, 0.15, "e.toml", &map).unwrap();
            let p = WorldParams { geometry, hallway: 2.5, starts: vec![(8.75, 8.75)], ..params(WaypointSet::Full) };
            let world = World::build(&map, &p, 1).unwrap();
            assert_eq!(world.dropped, 0, "{step:?}");
            assert!(world.reachable_walls > 0.99, "{step:?}: {}", world.reachable_walls);
            if step == crate::waypoint::geometry::GridStep::Hallway {
                assert!(world.passage_fills > 0, "{step:?}");
            }
        }
    }
}
