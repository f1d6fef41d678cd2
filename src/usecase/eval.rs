//! Scoring a plan given from outside the planners: a pattern, a path file, or a fleet's area
//! division, on a map with optional extra obstacles (003 §3.2.2's test scenario), by the thesis
//! fitness (003 eqs. 3.13–3.15) and the common scorer; then its `metrics.json`, `path.csv` and
//! path figure. `covga eval` is this use case behind command-line flags, whose names its
//! messages use.

use super::UseCaseError;
use crate::coverage::bound::{TimeBound, area_time_s};
use crate::coverage::fitness::{Projection, ThesisScore, score};
use crate::coverage::score::{CameraSpec, Score, Scorer};
use crate::coverage::{CoverageGrid, Footprint, PathMetrics, SweepScratch};
use crate::fleet::Fleet;
use crate::geom::Point;
use crate::map::GridMap;
use crate::map::ros::{BareImage, load_map};
use crate::patterns::hand_made::{HandMade, hand_made};
use crate::patterns::{self, Pattern};
use crate::plot::path::PathFigure;
use std::path::{Path, PathBuf};

/// A pattern `eval` plans itself.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum EvalPattern {
    /// The boustrophedon with lanes at `angle_deg` from +x.
    Boustrophedon {
        /// Lane direction in degrees.
        angle_deg: f64,
    },
    /// The inward spiral.
    Spiral,
    /// The hand-made boustrophedon of 003 Table 3.1 (obstacles ignored, back to the start).
    ThesisBoustrophedon,
    /// The hand-made inward spiral of 003 Table 3.2.
    ThesisSpiral,
}

/// Where the scored plan comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum EvalPlan {
    /// A pattern planned from `start` to `end`, with the completion pass when `complete`.
    Pattern {
        /// Which pattern.
        pattern: EvalPattern,
        /// Visit the strips the pattern leaves uncovered afterwards.
        complete: bool,
        /// Start station in metres.
        start: Point,
        /// End station in metres.
        end: Point,
    },
    /// A path file (CSV `x_m,y_m`, optional `agent` and `robot` columns).
    PathFile(PathBuf),
    /// The fleet's area division (DARP style), each region swept by a boustrophedon at
    /// `angle_deg`; needs [`EvalRequest::fleet`].
    Divide {
        /// Lane direction in degrees.
        angle_deg: f64,
    },
}

/// What to score and how.
#[derive(Clone, Debug)]
pub struct EvalRequest {
    /// A preset name, a ROS map YAML or an image.
    pub map: String,
    /// How a bare image is read.
    pub image: BareImage,
    /// The robot of every path (a fleet's robots bring their own).
    pub robot: Footprint,
    /// Obstacles placed on the map: each as the user wrote it and its metre rectangle.
    pub obstacles: Vec<(String, [f64; 4])>,
    /// Keep the obstacles' cells in `A_pix` (R29, 003 Tables 3.1/3.2).
    pub obstacle_in_area: bool,
    /// Projection of the thesis fitness.
    pub projection: Projection,
    /// The plan.
    pub plan: EvalPlan,
    /// A fleet file: score the plan as this fleet's (one path per robot).
    pub fleet: Option<PathBuf>,
    /// The memory `eval` may use in bytes (default: the memory available, [`crate::io::memory`]);
    /// a map and width that would need more are refused before anything large is allocated.
    pub max_memory: Option<u64>,
}

/// Everything `eval` reports, as `metrics.json` holds it.
#[derive(Clone, Debug, serde::Serialize)]
pub struct EvalReport {
    /// The map's name.
    pub map: String,
    /// The plan's source in words (a pattern, a file, an area division).
    pub source: String,
    /// The robot.
    pub robot: Footprint,
    /// Projection of the thesis fitness.
    pub projection: Projection,
    /// Paths scored.
    pub agents: usize,
    /// The thesis metrics (003 §3.2.1).
    #[serde(flatten)]
    pub metrics: PathMetrics,
    /// The thesis score.
    #[serde(flatten)]
    pub score: ThesisScore,
    /// The thesis fitness with the obstacle term (eq. 3.13).
    pub f_obstacle: f64,
    /// The common scorer's metrics (both denominators, camera, time).
    pub common: Score,
    /// Free pockets a pattern could not reach (patterns only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pockets: Option<usize>,
    /// Their area in m².
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pocket_area_m2: Option<f64>,
    /// Fleet metrics (with a fleet).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fleet: Option<crate::fleet::metrics::FleetScore>,
    /// Times to 80, 90 and 95 % of the reachable cells and the area over the curve
    /// (`coverage_curve.csv` holds the curve), as `covga run` reports them.
    pub coverage_curve: crate::coverage::curve::CurveSummary,
    /// A lower bound on the time any plan needs to cover what this one covers of the reachable
    /// cells: the area bound (their area over the area the robots sweep per second driving
    /// straight, Σ width × speed; turning in place sweeps nothing new in the scorer's model)
    /// plus, for one robot that turns at a finite rate, the turning bound's time
    /// (`turning_bound_s`; [`crate::coverage::bound`]).
    pub time_lower_bound_s: f64,
    /// The turning bound's share of `time_lower_bound_s`: the least turning any path covering
    /// that area inside the map's free space needs, over `rot_speed` (0 for free turning and
    /// for fleets).
    pub turning_bound_s: f64,
}

/// A scored plan: the report and what its figure and files are made of.
pub struct Evaluation {
    /// The report.
    pub report: EvalReport,
    /// The map scored on, obstacles placed.
    pub map: GridMap,
    /// Its coverage grid (the figure draws the swept cells on it).
    pub grid: CoverageGrid,
    /// The paths, one per agent.
    pub paths: Vec<Vec<Point>>,
    /// The fleet's robots (name, width) in path order; empty without a fleet.
    pub robots: Vec<(String, f64)>,
    /// The plan's time-to-coverage curve over the reachable cells, each agent on its own clock.
    pub curve: crate::coverage::curve::CoverageCurve,
}

/// The map with the request's obstacles placed, the map before them and the cells they took.
/// The camera comes from the map as loaded (obstacles change neither its size nor its cells').
fn obstructed_map(req: &EvalRequest) -> Result<(GridMap, GridMap, usize, CameraSpec), UseCaseError> {
    let mut map = load_map(&req.map, &req.image).map_err(UseCaseError::input)?;
    let planned =
        matches!(req.plan, EvalPlan::Pattern { pattern: EvalPattern::Boustrophedon { .. } | EvalPattern::Spiral, .. });
    let camera = eval_camera(&map, &req.map)?;
    super::eval_memory::check(&map, req.robot.width, planned, req.max_memory)?;
    let unobstructed = map.clone();
    if req.obstacle_in_area && req.obstacles.is_empty() {
        return Err(UseCaseError::Input("--obstacle-in-area needs at least one --obstacle X0,Y0,X1,Y1".into()));
    }
    let mut placed = 0;
    for (text, rect) in &req.obstacles {
        let (with, n) = map.with_obstacle(*rect).map_err(|e| UseCaseError::Input(format!("--obstacle {text}: {e}")))?;
        if n == 0 && with.cells() == map.cells() {
            return Err(UseCaseError::Input(format!(
                "--obstacle {text}: holds no free cell centre of map `{}` ({} m cells: a cell is blocked when its \
                 centre lies inside), so it would change nothing",
                map.name(),
                map.resolution()
            )));
        }
        map = with;
        placed += n;
    }
    req.robot.check_fits(&map).map_err(|m| UseCaseError::Input(format!("--width {m}")))?;
    Ok((map, unobstructed, placed, camera))
}

/// Reads and validates the fleet file `file` against `map`.
fn read_fleet(file: &Path, map: &GridMap) -> Result<Fleet, UseCaseError> {
    let origin = file.display().to_string();
    let text = crate::io::read_text_bounded(file, crate::io::MAX_TEXT_FILE_BYTES)
        .map_err(|e| UseCaseError::Input(format!("{origin}: cannot read: {e}")))?;
    crate::fleet::config::FleetFile::parse(&text, &origin, map).map_err(UseCaseError::input)
}

/// The paths of path file `file`, checked: with a fleet, each `robot` column names the fleet's
/// robot of its agent; camera poses are well formed; every start and end is a station where
/// the robot's body fits.
fn read_paths(file: &Path, map: &GridMap, fleet: Option<(&str, &Fleet)>) -> Result<Vec<Vec<Point>>, UseCaseError> {
    let shown = file.display();
    let crate::io::PathFile { paths, robots: names } = crate::io::read_path_file(file).map_err(UseCaseError::input)?;
    if let Some((origin, f)) = fleet {
        for (k, name) in names.iter().enumerate() {
            let Some(name) = name else { continue };
            match f.robots().get(k) {
                Some(r) if &r.name == name => {}
                Some(r) => {
                    return Err(UseCaseError::Input(format!(
                        "{shown}: agent {k} names robot `{name}`, but robot {k} of {origin} is `{}` (agents follow \
                         the fleet's [[robots]] in order)",
                        r.name
                    )));
                }
                None => {
                    return Err(UseCaseError::Input(format!(
                        "{shown}: agent {k} names robot `{name}`, but {origin} has {} robots",
                        f.robots().len()
                    )));
                }
            }
        }
    }
    crate::coverage::score::check_camera_poses(&paths).map_err(|m| UseCaseError::Input(format!("{shown}: {m}")))?;
    for (k, p) in paths.iter().enumerate() {
        let what = |end: &str| format!("{shown}: agent {k} {end}");
        map.check_station(p[0], &what("start")).map_err(UseCaseError::Input)?;
        map.check_station(*p.last().expect("non-empty"), &what("end")).map_err(UseCaseError::Input)?;
    }
    Ok(paths)
}

/// A planned pattern's unreachable pockets: how many and their area in m² (`None` for plans
/// that are not planned patterns).
type Pockets = Option<(usize, f64)>;

/// A path planned as `pattern` from `start` to `end`, its name, and the pockets the pattern
/// could not reach (the planned patterns only). The hand-made thesis patterns are drawn over
/// `unobstructed`: the thesis puts the obstacle under the path afterwards (003 §3.2.2).
fn pattern_path(
    (map, unobstructed): (&GridMap, &GridMap),
    width: f64,
    (pattern, complete): (EvalPattern, bool),
    (start, end): (Point, Point),
) -> Result<(Vec<Point>, String, Pockets), UseCaseError> {
    patterns::check_plan_inputs(map, width, start, end, ["--start", "--end", "--width"])
        .map_err(UseCaseError::Input)?;
    let planned = |p: Pattern| patterns::plan(map, p, width, start, end, complete).map_err(UseCaseError::input);
    let hand = |kind: HandMade, name: &str| {
        if end != start {
            return Err(UseCaseError::Input(
                "--end: the hand-made thesis patterns start and end at the same station (003 §3.2.2); leave --end out"
                    .into(),
            ));
        }
        let path = hand_made(unobstructed, kind, width, start).map_err(UseCaseError::input)?;
        Ok((path, name.to_string(), None))
    };
    match pattern {
        EvalPattern::ThesisBoustrophedon => hand(HandMade::Boustrophedon, "thesis boustrophedon"),
        EvalPattern::ThesisSpiral => hand(HandMade::Spiral, "thesis spiral"),
        EvalPattern::Boustrophedon { angle_deg } => {
            let p = planned(Pattern::Boustrophedon { angle_deg })?;
            Ok((p.points, format!("boustrophedon {angle_deg}°"), Some((p.pockets, p.pocket_area_m2))))
        }
        EvalPattern::Spiral => {
            let p = planned(Pattern::Spiral)?;
            Ok((p.points, "spiral".into(), Some((p.pockets, p.pocket_area_m2))))
        }
    }
}

/// The paths of the request's plan, their source in words and a pattern's pockets.
type Planned = (Vec<Vec<Point>>, String, Pockets);

fn plan_paths(
    req: &EvalRequest,
    (map, unobstructed): (&GridMap, &GridMap),
    fleet: Option<(&str, &Fleet)>,
) -> Result<Planned, UseCaseError> {
    match &req.plan {
        EvalPlan::Divide { angle_deg } => {
            let (_, f) = fleet.ok_or_else(|| UseCaseError::Input("--divide needs --fleet".into()))?;
            let (paths, division) = crate::fleet::division::plan(map, f, *angle_deg).map_err(UseCaseError::input)?;
            let sizes: Vec<String> = division.sizes.iter().map(usize::to_string).collect();
            let detached = if division.detached > 0 {
                format!(", {} of them apart from their region", division.detached)
            } else {
                String::new()
            };
            Ok((
                paths,
                format!("area division ({} cells{detached}, boustrophedon {angle_deg}°)", sizes.join("/")),
                None,
            ))
        }
        EvalPlan::PathFile(file) => Ok((read_paths(file, map, fleet)?, file.display().to_string(), None)),
        EvalPlan::Pattern { .. } if fleet.is_some() => {
            Err(UseCaseError::Input("--fleet needs a plan: --path FILE (one path per robot) or --divide".into()))
        }
        &EvalPlan::Pattern { pattern, complete, start, end } => {
            let (path, name, pockets) =
                pattern_path((map, unobstructed), req.robot.width, (pattern, complete), (start, end))?;
            Ok((vec![path], name, pockets))
        }
    }
}

/// The camera of the common scorer's `cov_cam`: 000's default (`[scorer.camera]`'s defaults).
/// Its wall band is half 000's narrowest hallway, which bounds the map's cell size, and `eval`
/// has no camera settings, so a coarser map is blamed on its resolution. A map smaller than
/// that hallway is one hallway: the band is at most half the map's longer side, and at least
/// one pixel of the camera's working raster; a map smaller than one such pixel is refused for
/// its size (the user set no camera key, so no key is blamed).
fn eval_camera(map: &GridMap, source: &str) -> Result<CameraSpec, UseCaseError> {
    let mut camera = crate::planner::sections::CameraSection::default();
    let longest = map.width_m().max(map.height_m());
    if longest < camera.scale {
        return Err(UseCaseError::Input(format!(
            "map `{source}` is {} m across: the camera coverage eval reports (000's default camera) needs a map \
             at least one camera pixel, {} m, across; give a map of at least {} m",
            crate::io::short_number(longest),
            crate::io::short_number(camera.scale),
            crate::io::short_number(camera.scale)
        )));
    }
    let hallway = (2.0 * crate::planner::sections::DEFAULT_WALL_BAND_M).min(longest);
    if map.resolution() > hallway {
        return Err(UseCaseError::Input(format!(
            "map `{source}` has cells of {} m: the camera coverage eval reports (000's default camera, narrowest hallway {} m) needs cells of at most {} m; give a finer map (`--resolution` for a bare image, `resolution:` in a ROS map YAML)",
            crate::io::short_number(map.resolution()),
            crate::io::short_number(hallway),
            crate::io::short_number(hallway)
        )));
    }
    camera.wall_band = Some((hallway / 2.0).max(camera.scale));
    camera.spec("default camera", map).map_err(UseCaseError::input)
}

/// Plans (or reads) and scores the request's plan.
pub fn evaluate(req: &EvalRequest) -> Result<Evaluation, UseCaseError> {
    let (map, unobstructed, placed, camera) = obstructed_map(req)?;
    let fleet = match &req.fleet {
        Some(file) => Some((file.display().to_string(), read_fleet(file, &map)?)),
        None => None,
    };
    let fleet_ref = fleet.as_ref().map(|(o, f)| (o.as_str(), f));
    let (paths, source, pockets) = plan_paths(req, (&map, &unobstructed), fleet_ref)?;
    let fleet_score =
        match fleet_ref {
            Some((origin, f)) => Some(crate::fleet::metrics::FleetScorer::new(&map, f).score(&paths).map_err(|m| {
                UseCaseError::Input(format!("{origin}: {m} (one path per robot, by the `agent` column)"))
            })?),
            None => None,
        };
    // A fleet's robots sweep at their own widths and drive at their own speeds, in the headline
    // as in the fleet block; any other plan is the request's robot on every path.
    let robot = req.robot;
    let robots: Vec<Footprint> = match fleet_ref {
        Some((_, f)) => f.robots().iter().map(|r| r.footprint).collect(),
        None => vec![robot; paths.len()],
    };
    let widths: Vec<f64> = robots.iter().map(|r| r.width).collect();
    let grid = CoverageGrid::new(&map);
    let mut metrics = robot.measure_fleet(&grid, &mut SweepScratch::new(&grid), &paths, &widths);
    if req.obstacle_in_area {
        metrics.area_cells += placed as u64;
    }
    let sc = score(&metrics, &robot, map.resolution(), req.projection);
    let stations: Vec<Point> = paths.iter().filter_map(|p| p.first().copied()).collect();
    let scorer = Scorer::for_widths(&map, robot, &widths, req.projection, &camera, &stations);
    let common = scorer.score_agents(&paths, &robots);
    let curve = crate::coverage::curve::CoverageCurve::of_plan(scorer.grid(), scorer.reach(), &paths, &robots);
    let covered_m2 = common.unique_reach_cells as f64 * map.resolution().powi(2);
    let rates: Vec<(f64, f64)> = robots.iter().map(|r| (r.width, r.speed)).collect();
    // The turning bound is one path's: a fleet gets the length bound alone (its makespan).
    let turning_bound_s = match robots.as_slice() {
        [one] => {
            let diameter = crate::coverage::bound::free_diameter_m(&map);
            TimeBound::one_robot(covered_m2, (one.width, one.speed, one.rot_speed), map.resolution(), diameter)
                .turning_s
        }
        _ => 0.0,
    };
    let time_lower_bound_s = area_time_s(covered_m2, &rates, map.resolution()) + turning_bound_s;
    let report = EvalReport {
        map: map.name().to_string(),
        source,
        robot,
        projection: req.projection,
        agents: paths.len(),
        metrics,
        score: sc,
        f_obstacle: sc.fitness,
        common,
        pockets: pockets.map(|p| p.0),
        pocket_area_m2: pockets.map(|p| p.1),
        fleet: fleet_score,
        coverage_curve: curve.summary(),
        time_lower_bound_s,
        turning_bound_s,
    };
    let robots = fleet_ref
        .map(|(_, f)| f.robots().iter().map(|r| (r.name.clone(), r.footprint.width)).collect())
        .unwrap_or_default();
    Ok(Evaluation { report, map, grid, paths, robots, curve })
}

impl Evaluation {
    /// `metrics.json`'s text.
    pub fn json(&self) -> Result<String, UseCaseError> {
        serde_json::to_string_pretty(&self.report).map_err(UseCaseError::internal)
    }

    /// The path figure's title.
    pub fn title(&self) -> String {
        let r = &self.report;
        match &r.fleet {
            Some(f) => format!(
                "{} robots on {}: union {:.3} of reachable, makespan {:.0} s",
                f.robots.len(),
                r.map,
                f.union_reach,
                f.makespan_s
            ),
            None => format!(
                "{} on {}: cov_final {:.3}, t_final {:.3}",
                short(&r.source),
                r.map,
                r.score.cov_final,
                r.score.t_final
            ),
        }
    }

    /// Writes `metrics.json`, `path.csv`, `coverage_curve.csv`, `path.png` and `path.svg` into
    /// `out` (made if missing); each file appears whole or not at all.
    pub fn write(&self, out: &Path) -> Result<(), UseCaseError> {
        std::fs::create_dir_all(out)
            .map_err(|e| UseCaseError::Input(format!("{}: cannot create the output folder: {e}", out.display())))?;
        crate::io::write_atomic(&out.join("metrics.json"), self.json()?.as_bytes()).map_err(UseCaseError::internal)?;
        let names: Vec<String> = self.robots.iter().map(|(n, _)| n.clone()).collect();
        crate::io::write_atomic(&out.join("path.csv"), &crate::io::fleet_path_csv(&self.paths, &names))
            .map_err(UseCaseError::internal)?;
        crate::io::write_atomic(&out.join("coverage_curve.csv"), &self.curve.csv()).map_err(UseCaseError::internal)?;
        let figure = PathFigure {
            map: &self.map,
            grid: &self.grid,
            paths: self.paths.clone(),
            width: self.report.robot.width,
            robots: self.robots.clone(),
            title: self.title(),
        };
        crate::plot::save(&figure, &out.join("path")).map_err(UseCaseError::internal)
    }
}

/// A path file named by its last two components (its folder and name), so that a long path
/// does not run off the figure's title; a pattern's name as it is.
fn short(source: &str) -> String {
    let parts: Vec<&str> = source.split(['/', '\\']).filter(|p| !p.is_empty()).collect();
    match parts.len() {
        0..=2 => source.to_string(),
        n => format!(".../{}/{}", parts[n - 2], parts[n - 1]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn titles_name_a_path_by_its_folder_and_file() {
        let cases = [
            ("out/study/runs/6f13/best_path.csv", ".../6f13/best_path.csv"),
            ("runs/best_path.csv", "runs/best_path.csv"),
            ("boustrophedon 0°", "boustrophedon 0°"),
        ];
        for (source, shown) in cases {
            assert_eq!(short(source), shown);
        }
    }

    fn request(plan: EvalPlan) -> EvalRequest {
        EvalRequest {
            map: "thesis-1".into(),
            image: BareImage { resolution: None, free_threshold: None },
            robot: Footprint { width: 0.6, speed: 0.2, rot_speed: 0.0 },
            obstacles: Vec::new(),
            obstacle_in_area: false,
            projection: Projection::F1,
            plan,
            fleet: None,
            max_memory: None,
        }
    }

    #[test]
    fn a_boustrophedon_is_scored_and_a_bad_request_is_input() {
        let start = Point::new(1.3, 1.3);
        let plan = |pattern| EvalPlan::Pattern { pattern, complete: true, start, end: start };
        let e = evaluate(&request(plan(EvalPattern::Boustrophedon { angle_deg: 0.0 }))).unwrap();
        assert!(e.report.common.executable, "{:?}", e.report.common);
        assert!(e.report.common.cov_final_reach > 0.9, "{}", e.report.common.cov_final_reach);
        assert_eq!(e.report.pockets, Some(0));
        // A hand-made thesis pattern returns to its start: another end is refused.
        let away =
            EvalPlan::Pattern { pattern: EvalPattern::ThesisSpiral, complete: true, start, end: Point::new(2.0, 2.0) };
        assert!(matches!(evaluate(&request(away)), Err(UseCaseError::Input(m)) if m.contains("--end")));
        // An obstacle that holds no cell centre changes nothing and is refused.
        let mut tiny = request(plan(EvalPattern::Spiral));
        tiny.obstacles = vec![("1.01,1.01,1.02,1.02".into(), [1.01, 1.01, 1.02, 1.02])];
        assert!(matches!(evaluate(&tiny), Err(UseCaseError::Input(m)) if m.contains("change nothing")));
        // Dividing needs a fleet.
        let divide = request(EvalPlan::Divide { angle_deg: 0.0 });
        assert!(matches!(evaluate(&divide), Err(UseCaseError::Input(m)) if m.contains("--fleet")));
    }
}
