//! `covga eval`: score a pattern or a path file with the footprint model and the thesis
//! fitness, print every metric and draw the path.

use super::{CliError, parse_point};
use crate::coverage::fitness::{Projection, ThesisScore, score};
use crate::coverage::score::{Score, Scorer};
use crate::coverage::{CoverageGrid, Footprint, PathMetrics, SweepScratch};
use crate::map::ros::load_map;
use crate::patterns::hand_made::{HandMade, hand_made};
use crate::patterns::{self, Pattern};
use crate::plot::path::PathFigure;
use std::path::PathBuf;

#[derive(clap::ValueEnum, Clone, Copy, Debug)]
enum PatternName {
    Boustrophedon,
    Spiral,
    /// The hand-made boustrophedon of 003 Table 3.1 (lanes one width apart over a rectangular
    /// free area, straight back to the start; obstacles ignored).
    ThesisBoustrophedon,
    /// The hand-made inward spiral of 003 Table 3.2.
    ThesisSpiral,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug)]
enum ProjectionName {
    F1,
    F2,
}

/// Arguments of `covga eval`.
#[derive(clap::Args, Debug)]
pub struct EvalArgs {
    /// Map: a preset (thesis-1, thesis-2, office, office-large, office-ring), a ROS map YAML, or
    /// a PGM/PNG image with --resolution.
    #[arg(long, default_value = "thesis-1")]
    map: String,
    /// Metres per pixel for a bare image map.
    #[arg(long)]
    resolution: Option<f64>,
    /// For a bare image map: grey values at or above this are free and darker ones occupied
    /// (the ipa room-segmentation benchmark uses 250). Without it, map_server's default
    /// thresholds apply: grey ≥ 206 free, ≤ 89 occupied, unknown between.
    #[arg(long, value_parser = clap::value_parser!(u8).range(1..))]
    free_threshold: Option<u8>,
    /// Plan this pattern (the default when no --path is given is boustrophedon).
    #[arg(long, conflicts_with = "path")]
    pattern: Option<PatternName>,
    /// Lane direction of the boustrophedon in degrees from +x.
    #[arg(long, default_value_t = 0.0)]
    angle: f64,
    /// Plan the pattern alone, without visiting the strips it leaves uncovered afterwards.
    #[arg(long)]
    no_complete: bool,
    /// Score this path file instead: CSV with header x_m,y_m (optional agent column).
    #[arg(long)]
    path: Option<PathBuf>,
    /// Score the path file as a fleet's plan: a TOML file of `[[robots]]` entries (name, width,
    /// speed, rot_speed, start, end; defaults from its `[robot]` and `[stations]`), one robot per
    /// path of the file, in order. Adds the fleet metrics (union, overlap, makespan, balance).
    #[arg(long)]
    fleet: Option<PathBuf>,
    /// Plan for the `--fleet` by area division (DARP style): one connected region per robot,
    /// sized by its width × speed around its start, swept by a boustrophedon at `--angle`.
    #[arg(long, requires = "fleet", conflicts_with_all = ["path", "pattern"])]
    divide: bool,
    /// Robot width R_width in metres.
    #[arg(long, default_value_t = 0.6)]
    width: f64,
    /// Robot speed R_speed in m/s.
    #[arg(long, default_value_t = 0.2)]
    speed: f64,
    /// Rotation speed R_rot in rad/s (0 = no rotation cost).
    #[arg(long = "rot-speed", default_value_t = 0.0)]
    rot_speed: f64,
    /// Start station X,Y in metres (patterns only); negative values as typed (`-17.4,-1.55`).
    #[arg(long, default_value = "1.3,1.3", allow_hyphen_values = true)]
    start: String,
    /// End station X,Y in metres (default: the start).
    #[arg(long, allow_hyphen_values = true)]
    end: Option<String>,
    /// Place an obstacle on the map: the cells whose centres lie in the metre rectangle
    /// `X0,Y0,X1,Y1` (half-open, `[X0, X1) × [Y0, Y1)`) become occupied, as in the test
    /// scenario of 003 §3.2.2. Repeatable.
    #[arg(long = "obstacle", allow_hyphen_values = true, value_name = "X0,Y0,X1,Y1")]
    obstacles: Vec<String>,
    /// Keep the cells of `--obstacle` in the area `A_pix` (spec R29, as 003 Tables 3.1/3.2 do):
    /// a path that crosses them then loses coverage as well as fitness. By default obstacles
    /// are known beforehand and left out of `A_pix`, as in the thesis's experiments.
    #[arg(long)]
    obstacle_in_area: bool,
    /// Projection f of the fitness (003 eqs. 3.14–3.15).
    #[arg(long, value_enum, default_value = "f1")]
    projection: ProjectionName,
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
    /// Folder for path.png, path.svg, path.csv and metrics.json.
    #[arg(long, default_value = "out/eval")]
    out: PathBuf,
}

/// Parses `X0,Y0,X1,Y1` (metres, `X0 < X1`, `Y0 < Y1`).
fn parse_rect(text: &str) -> Result<[f64; 4], String> {
    let v: Vec<f64> = text
        .split(',')
        .map(|t| t.trim().parse::<f64>().map_err(|_| format!("`{}` is not a number", t.trim())))
        .collect::<Result<_, _>>()?;
    match v[..] {
        [x0, y0, x1, y1] if v.iter().all(|x| x.is_finite()) && x0 < x1 && y0 < y1 => Ok([x0, y0, x1, y1]),
        [_, _, _, _] => Err("expected finite metres with X0 < X1 and Y0 < Y1".into()),
        _ => Err(format!("expected four numbers X0,Y0,X1,Y1, got {}", v.len())),
    }
}

fn check_robot(a: &EvalArgs) -> Result<Footprint, CliError> {
    let positive = |name: &str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(())
        } else {
            Err(CliError::Input(format!(
                "--{name} = {} is out of range: expected a finite number > 0",
                crate::io::short_number(v)
            )))
        }
    };
    positive("width", a.width)?;
    positive("speed", a.speed)?;
    if !(a.rot_speed.is_finite() && a.rot_speed >= 0.0) {
        return Err(CliError::Input(format!(
            "--rot-speed = {} is out of range: expected a finite number >= 0 (0 disables the rotation cost)",
            a.rot_speed
        )));
    }
    if !(a.angle.is_finite() && (-360.0..=360.0).contains(&a.angle)) {
        let angle = crate::io::short_number(a.angle);
        return Err(CliError::Input(format!("--angle = {angle} is out of range: allowed [-360, 360] degrees")));
    }
    Ok(Footprint { width: a.width, speed: a.speed, rot_speed: a.rot_speed })
}

/// Everything `eval` reports, as printed in JSON.
#[derive(serde::Serialize)]
struct Report<'a> {
    map: &'a str,
    source: String,
    robot: Footprint,
    projection: Projection,
    agents: usize,
    #[serde(flatten)]
    metrics: PathMetrics,
    #[serde(flatten)]
    score: ThesisScore,
    f_obstacle: f64,
    /// The common scorer's metrics (both denominators, camera, time).
    common: Score,
    /// Free pockets a pattern could not reach (patterns only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pockets: Option<usize>,
    /// Their area in m².
    #[serde(skip_serializing_if = "Option::is_none")]
    pocket_area_m2: Option<f64>,
    /// Fleet metrics (with `--fleet`).
    #[serde(skip_serializing_if = "Option::is_none")]
    fleet: Option<crate::fleet::metrics::FleetScore>,
}

/// Reads and validates `--fleet`.
fn read_fleet(file: &std::path::Path, map: &crate::map::GridMap) -> Result<crate::fleet::Fleet, CliError> {
    let origin = file.display().to_string();
    let text = crate::io::read_text_bounded(file, crate::io::MAX_TEXT_FILE_BYTES)
        .map_err(|e| CliError::Input(format!("{origin}: cannot read: {e}")))?;
    crate::fleet::config::FleetFile::parse(&text, &origin, map).map_err(CliError::input)
}

/// Runs `covga eval` with its parsed arguments.
pub fn run(a: EvalArgs) -> Result<(), CliError> {
    let robot = check_robot(&a)?;
    if let Some(r) = a.resolution
        && !(r.is_finite() && r > 0.0)
    {
        return Err(CliError::Input(format!("--resolution = {r} is out of range: expected metres per pixel > 0")));
    }
    let image = crate::map::ros::BareImage { resolution: a.resolution, free_threshold: a.free_threshold };
    let mut map = load_map(&a.map, &image).map_err(CliError::input)?;
    let camera = eval_camera(&map, &a.map)?;
    let unobstructed = map.clone();
    if a.obstacle_in_area && a.obstacles.is_empty() {
        return Err(CliError::Input("--obstacle-in-area needs at least one --obstacle X0,Y0,X1,Y1".into()));
    }
    let mut placed = 0;
    for text in &a.obstacles {
        let rect = parse_rect(text).map_err(|m| CliError::Input(format!("--obstacle {text}: {m}")))?;
        let (with, n) = map.with_obstacle(rect).map_err(|e| CliError::Input(format!("--obstacle {text}: {e}")))?;
        if n == 0 && with.cells() == map.cells() {
            return Err(CliError::Input(format!(
                "--obstacle {text}: holds no free cell centre of map `{}` ({} m cells: a cell is blocked when its \
                 centre lies inside), so it would change nothing",
                map.name(),
                map.resolution()
            )));
        }
        map = with;
        placed += n;
    }
    robot.check_fits(&map).map_err(|m| CliError::Input(format!("--width {m}")))?;
    let projection = match a.projection {
        ProjectionName::F1 => Projection::F1,
        ProjectionName::F2 => Projection::F2,
    };
    let mut pockets = None;
    let fleet = match &a.fleet {
        Some(file) => Some((file.display().to_string(), read_fleet(file, &map)?)),
        None => None,
    };
    if fleet.is_some() && a.path.is_none() && !a.divide {
        return Err(CliError::Input("--fleet needs a plan: --path FILE (one path per robot) or --divide".into()));
    }
    let (paths, source) = match &a.path {
        _ if a.divide => {
            let (_, f) = fleet.as_ref().expect("--divide requires --fleet");
            let (paths, division) = crate::fleet::division::plan(&map, f, a.angle).map_err(CliError::input)?;
            let sizes: Vec<String> = division.sizes.iter().map(usize::to_string).collect();
            let detached = if division.detached > 0 {
                format!(", {} of them apart from their region", division.detached)
            } else {
                String::new()
            };
            (paths, format!("area division ({} cells{detached}, boustrophedon {}°)", sizes.join("/"), a.angle))
        }
        Some(file) => {
            let crate::io::PathFile { paths, robots: names } =
                crate::io::read_path_file(file).map_err(CliError::input)?;
            // With a fleet, the `robot` column must name the fleet's robot of each agent.
            if let Some((origin, f)) = &fleet {
                for (k, name) in names.iter().enumerate() {
                    let Some(name) = name else { continue };
                    match f.robots().get(k) {
                        Some(r) if &r.name == name => {}
                        Some(r) => {
                            return Err(CliError::Input(format!(
                                "{}: agent {k} names robot `{name}`, but robot {k} of {origin} is `{}` (agents follow \
                                 the fleet's [[robots]] in order)",
                                file.display(),
                                r.name
                            )));
                        }
                        None => {
                            return Err(CliError::Input(format!(
                                "{}: agent {k} names robot `{name}`, but {origin} has {} robots",
                                file.display(),
                                f.robots().len()
                            )));
                        }
                    }
                }
            }
            crate::coverage::score::check_camera_poses(&paths)
                .map_err(|m| CliError::Input(format!("{}: {m}", file.display())))?;
            for (k, p) in paths.iter().enumerate() {
                let what = |end: &str| format!("{}: agent {k} {end}", file.display());
                map.check_station(p[0], &what("start")).map_err(CliError::Input)?;
                map.check_station(*p.last().expect("non-empty"), &what("end")).map_err(CliError::Input)?;
            }
            (paths, file.display().to_string())
        }
        None => {
            let start = parse_point(&a.start).map_err(|m| CliError::Input(format!("--start: {m}")))?;
            let end = match &a.end {
                Some(e) => parse_point(e).map_err(|m| CliError::Input(format!("--end: {m}")))?,
                None => start,
            };
            patterns::check_plan_inputs(&map, robot.width, start, end, ["--start", "--end", "--width"])
                .map_err(CliError::Input)?;
            let hand = match a.pattern {
                Some(PatternName::ThesisBoustrophedon) => Some((HandMade::Boustrophedon, "thesis boustrophedon")),
                Some(PatternName::ThesisSpiral) => Some((HandMade::Spiral, "thesis spiral")),
                Some(PatternName::Boustrophedon | PatternName::Spiral) | None => None,
            };
            if let Some((kind, name)) = hand {
                if end != start {
                    return Err(CliError::Input(
                        "--end: the hand-made thesis patterns start and end at the same station (003 §3.2.2); leave --end out".into(),
                    ));
                }
                // Drawn over the map as it was before `--obstacle`: the thesis puts the obstacle
                // under the path afterwards (003 §3.2.2).
                let path = hand_made(&unobstructed, kind, robot.width, start).map_err(CliError::input)?;
                (vec![path], name.to_string())
            } else {
                let pattern = match a.pattern {
                    Some(PatternName::Spiral) => Pattern::Spiral,
                    Some(PatternName::Boustrophedon | PatternName::ThesisBoustrophedon | PatternName::ThesisSpiral)
                    | None => Pattern::Boustrophedon { angle_deg: a.angle },
                };
                let planned =
                    patterns::plan(&map, pattern, robot.width, start, end, !a.no_complete).map_err(CliError::input)?;
                pockets = Some((planned.pockets, planned.pocket_area_m2));
                let name = match pattern {
                    Pattern::Boustrophedon { angle_deg } => format!("boustrophedon {angle_deg}°"),
                    Pattern::Spiral => "spiral".into(),
                };
                (vec![planned.points], name)
            }
        }
    };
    let fleet_score = match &fleet {
        Some((origin, f)) => Some(
            crate::fleet::metrics::FleetScorer::new(&map, f)
                .score(&paths)
                .map_err(|m| CliError::Input(format!("{origin}: {m} (one path per robot, by the `agent` column)")))?,
        ),
        None => None,
    };
    // A fleet's robots sweep at their own widths and drive at their own speeds, in the headline
    // as in the fleet block; any other plan is the command line's robot on every path.
    let robots: Vec<crate::coverage::Footprint> = match &fleet {
        Some((_, f)) => f.robots().iter().map(|r| r.footprint).collect(),
        None => vec![robot; paths.len()],
    };
    let widths: Vec<f64> = robots.iter().map(|r| r.width).collect();
    let grid = CoverageGrid::new(&map);
    let mut metrics = robot.measure_fleet(&grid, &mut SweepScratch::new(&grid), &paths, &widths);
    if a.obstacle_in_area {
        metrics.area_cells += placed as u64;
    }
    let sc = score(&metrics, &robot, map.resolution(), projection);
    let stations: Vec<crate::geom::Point> = paths.iter().filter_map(|p| p.first().copied()).collect();
    let common = Scorer::for_widths(&map, robot, &widths, projection, &camera, &stations).score_agents(&paths, &robots);
    let report = Report {
        map: map.name(),
        source,
        robot,
        projection,
        agents: paths.len(),
        metrics,
        score: sc,
        f_obstacle: sc.fitness,
        common,
        pockets: pockets.map(|p| p.0),
        pocket_area_m2: pockets.map(|p| p.1),
        fleet: fleet_score,
    };
    let json = serde_json::to_string_pretty(&report).map_err(CliError::internal)?;
    std::fs::create_dir_all(&a.out)
        .map_err(|e| CliError::Input(format!("{}: cannot create the output folder: {e}", a.out.display())))?;
    crate::io::write_atomic(&a.out.join("metrics.json"), json.as_bytes()).map_err(CliError::internal)?;
    let names: Vec<String> =
        fleet.as_ref().map(|(_, f)| f.robots().iter().map(|r| r.name.clone()).collect()).unwrap_or_default();
    crate::io::write_atomic(&a.out.join("path.csv"), &crate::io::fleet_path_csv(&paths, &names))
        .map_err(CliError::internal)?;
    let figure = PathFigure {
        map: &map,
        grid: &grid,
        paths: paths.clone(),
        width: robot.width,
        robots: fleet
            .as_ref()
            .map(|(_, f)| f.robots().iter().map(|r| (r.name.clone(), r.footprint.width)).collect())
            .unwrap_or_default(),
        title: match &report.fleet {
            Some(f) => format!(
                "{} robots on {}: union {:.3} of reachable, makespan {:.0} s",
                f.robots.len(),
                map.name(),
                f.union_reach,
                f.makespan_s
            ),
            None => {
                format!(
                    "{} on {}: cov_final {:.3}, t_final {:.3}",
                    short(&report.source),
                    map.name(),
                    sc.cov_final,
                    sc.t_final
                )
            }
        },
    };
    crate::plot::save(&figure, &a.out.join("path")).map_err(CliError::internal)?;
    if a.json {
        println!("{json}");
    } else {
        print_table(&report);
        println!("wrote {}/path.png, path.svg, path.csv, metrics.json", a.out.display());
    }
    Ok(())
}

/// Why the common scorer calls a plan not executable, in words.
pub fn not_executable_why(s: &crate::coverage::score::Score) -> String {
    if s.obstacle_cells > 0 {
        format!("the robot's body touches {} occupied or unknown cells", s.obstacle_cells)
    } else {
        "the robot's body reaches past the map's edge".to_string()
    }
}

fn print_table(r: &Report) {
    let m = &r.metrics;
    let c = &r.common;
    let executable = if c.executable { "yes".to_string() } else { format!("NO ({})", not_executable_why(c)) };
    let rows: [(&str, String); 23] = [
        ("map", r.map.to_string()),
        ("path", r.source.clone()),
        ("agents", r.agents.to_string()),
        ("executable", executable),
        ("cells swept (cov_pix)", m.cells_swept.to_string()),
        ("unique cells", m.unique_cells.to_string()),
        ("crossings (cross_pix)", m.crossings.to_string()),
        ("obstacle cells (obj_pix)", m.obstacle_cells.to_string()),
        ("area cells (A_pix)", m.area_cells.to_string()),
        ("length [m]", format!("{:.3}", m.length_m)),
        ("total turn [rad]", format!("{:.4}", m.total_turn_rad)),
        ("T_rot [s]", format!("{:.4}", m.t_rot_s)),
        ("cov_final", format!("{:.6}", r.score.cov_final)),
        ("t_final", format!("{:.6}", r.score.t_final)),
        ("f1", format!("{:.6}", r.score.f1)),
        ("f2", format!("{:.6}", r.score.f2)),
        ("f_obstacle", format!("{:.6} ({:?})", r.f_obstacle, r.projection)),
        ("reachable cells", format!("{} of {} free", c.reachable_cells, c.free_cells)),
        ("cov_final over reachable", format!("{:.6}", c.cov_final_reach)),
        ("camera walls / open", format!("{:.4} / {:.4}", c.cam_walls_free, c.cam_open_free)),
        ("time [s]", format!("{:.1}", c.time_s)),
        (
            "unreachable pockets",
            r.pockets.map_or("-".into(), |n| format!("{n} ({:.2} m²)", r.pocket_area_m2.unwrap_or(0.0))),
        ),
        ("turns", c.turns.to_string()),
    ];
    for (k, v) in rows {
        println!("{k:<26} {v}");
    }
    if let Some(f) = &r.fleet {
        println!("fleet ({} robots: {})", f.robots.len(), f.robots.join(", "));
        let rows = [
            (
                "union cells",
                format!("{} ({:.4} of free, {:.4} of reachable)", f.union_cells, f.union_free, f.union_reach),
            ),
            ("overlap cells", format!("{} ({:.4} of the union)", f.overlap_cells, f.overlap_fraction)),
            ("robot times [s]", f.robot_time_s.iter().map(|t| format!("{t:.1}")).collect::<Vec<_>>().join(", ")),
            ("makespan [s]", format!("{:.1}", f.makespan_s)),
            ("balance (max/min time)", f.balance.map_or("-".into(), |b| format!("{b:.3}"))),
            ("fleet cov_final / t_final", format!("{:.6} / {:.6}", f.cov_final, f.t_final)),
        ];
        for (k, v) in rows {
            println!("  {k:<26} {v}");
        }
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

/// The camera of the common scorer's `cov_cam`: 000's default. Its narrowest hallway bounds the
/// map's cell size, and `eval` has no camera flags, so a coarser map is blamed on its resolution.
fn eval_camera(map: &crate::map::GridMap, source: &str) -> Result<crate::coverage::score::CameraSpec, CliError> {
    let mut defaults = crate::waypoint::config::WaypointSection::default();
    // A map smaller than 000's narrowest hallway is one hallway: the camera's waypoint step
    // cannot exceed the map (maps under 1.5 m could not be scored at all).
    defaults.hallway = defaults.hallway.min(map.width_m().max(map.height_m()));
    let finest_needed = defaults.hallway;
    if map.resolution() > finest_needed {
        return Err(CliError::Input(format!(
            "map `{source}` has cells of {} m: the camera coverage eval reports (000's default camera, narrowest hallway {} m) needs cells of at most {} m; give a finer map (`--resolution` for a bare image, `resolution:` in a ROS map YAML)",
            crate::io::short_number(map.resolution()),
            crate::io::short_number(defaults.hallway),
            crate::io::short_number(finest_needed)
        )));
    }
    crate::waypoint::config::camera_spec(&defaults, "default camera", map).map_err(CliError::input)
}

#[cfg(test)]
mod tests {
    use super::short;

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
}
