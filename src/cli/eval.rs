//! `covga eval`: score a pattern or a path file with the footprint model and the thesis
//! fitness, print every metric and draw the path.

use super::{CliError, parse_point};
use crate::coverage::Footprint;
use crate::coverage::fitness::Projection;
use crate::usecase::eval::{EvalPattern, EvalPlan, EvalReport, EvalRequest, evaluate};
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
    /// Keep the cells of `--obstacle` in the area `A_pix` (R29, as 003 Tables 3.1/3.2 do):
    /// a path that crosses them then loses coverage as well as fitness. By default obstacles
    /// are known beforehand and left out of `A_pix`, as in the thesis's experiments.
    #[arg(long)]
    obstacle_in_area: bool,
    /// Projection f of the fitness (003 eqs. 3.14–3.15); f2 by default, as in experiment files.
    #[arg(long, value_enum, default_value = "f2")]
    projection: ProjectionName,
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
    /// Folder for path.png, path.svg, path.csv, coverage_curve.csv and metrics.json (default:
    /// out/eval-MAP, MAP the preset's name or the map file's stem, so that checking a second
    /// map keeps the first one's files).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Memory eval may use (8G, 512M, 2GiB; default: the memory available); a map and width
    /// that would need more are refused before anything large is allocated.
    #[arg(long, value_parser = crate::io::parse_bytes)]
    max_memory: Option<u64>,
}

/// The default results folder of `covga eval` for the map argument `map`: `out/eval-NAME`,
/// NAME the preset's name or the map file's stem, characters other than letters, digits, `-`,
/// `_` and `.` written as `_`.
fn default_out(map: &str) -> PathBuf {
    let stem = std::path::Path::new(map).file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let name: String =
        stem.chars().map(|c| if c.is_alphanumeric() || matches!(c, '-' | '_' | '.') { c } else { '_' }).collect();
    let name = if name.is_empty() || name.chars().all(|c| c == '.') { "map".to_string() } else { name };
    PathBuf::from("out").join(format!("eval-{name}"))
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
    let robot = Footprint { width: a.width, speed: a.speed, rot_speed: a.rot_speed };
    if let Some((name, v, allowed)) = robot.out_of_range() {
        let (flag, v) = (name.replace('_', "-"), crate::io::short_number(v));
        return Err(CliError::Input(format!("--{flag} = {v} is out of range: allowed {allowed}")));
    }
    if !(a.angle.is_finite() && (-360.0..=360.0).contains(&a.angle)) {
        let angle = crate::io::short_number(a.angle);
        return Err(CliError::Input(format!("--angle = {angle} is out of range: allowed [-360, 360] degrees")));
    }
    Ok(Footprint { width: a.width, speed: a.speed, rot_speed: a.rot_speed })
}

impl EvalArgs {
    /// The use case's request: the flags checked and parsed (the plan's stations only when a
    /// pattern is planned).
    fn request(&self) -> Result<EvalRequest, CliError> {
        let a = self;
        let robot = check_robot(a)?;
        if let Some(r) = a.resolution
            && !(r.is_finite() && r > 0.0)
        {
            return Err(CliError::Input(format!("--resolution = {r} is out of range: expected metres per pixel > 0")));
        }
        let obstacles = a
            .obstacles
            .iter()
            .map(|text| {
                let rect = parse_rect(text).map_err(|m| CliError::Input(format!("--obstacle {text}: {m}")))?;
                Ok((text.clone(), rect))
            })
            .collect::<Result<Vec<_>, CliError>>()?;
        let plan = match &a.path {
            _ if a.divide => EvalPlan::Divide { angle_deg: a.angle },
            Some(file) => EvalPlan::PathFile(file.clone()),
            None => {
                let start = parse_point(&a.start).map_err(|m| CliError::Input(format!("--start: {m}")))?;
                let end = match &a.end {
                    Some(e) => parse_point(e).map_err(|m| CliError::Input(format!("--end: {m}")))?,
                    None => start,
                };
                let pattern = match a.pattern {
                    Some(PatternName::Spiral) => EvalPattern::Spiral,
                    Some(PatternName::ThesisBoustrophedon) => EvalPattern::ThesisBoustrophedon,
                    Some(PatternName::ThesisSpiral) => EvalPattern::ThesisSpiral,
                    Some(PatternName::Boustrophedon) | None => EvalPattern::Boustrophedon { angle_deg: a.angle },
                };
                EvalPlan::Pattern { pattern, complete: !a.no_complete, start, end }
            }
        };
        Ok(EvalRequest {
            map: a.map.clone(),
            image: crate::map::ros::BareImage { resolution: a.resolution, free_threshold: a.free_threshold },
            robot,
            obstacles,
            obstacle_in_area: a.obstacle_in_area,
            projection: match a.projection {
                ProjectionName::F1 => Projection::F1,
                ProjectionName::F2 => Projection::F2,
            },
            plan,
            fleet: a.fleet.clone(),
            max_memory: a.max_memory,
        })
    }
}

/// Runs `covga eval` with its parsed arguments.
pub fn run(a: EvalArgs) -> Result<(), CliError> {
    let evaluation = evaluate(&a.request()?)?;
    let out = a.out.clone().unwrap_or_else(|| default_out(&a.map));
    evaluation.write(&out)?;
    if a.json {
        println!("{}", evaluation.json()?);
    } else {
        print_table(&evaluation.report);
        println!("wrote {}/path.png, path.svg, path.csv, coverage_curve.csv, metrics.json", out.display());
    }
    Ok(())
}

/// The plan's time as a multiple of its lower bound, with the bound; a plan that covers no
/// area (a single point) has a bound of 0 s and no multiple. A plan of several paths is timed
/// by its makespan (its slowest path's time): the length bound over the summed sweep rates is a
/// bound on the makespan, not on the sum of the paths' times.
fn times_the_bound(r: &EvalReport) -> String {
    let c = &r.common;
    let (time_s, what) = if r.agents > 1 { (c.makespan_s, "the makespan") } else { (c.time_s, "the time") };
    let bound = format!(
        "bound {:.1} s: the least driving that sweeps the covered cells, plus {:.1} s of turning",
        r.time_lower_bound_s - r.turning_bound_s,
        r.turning_bound_s
    );
    if r.time_lower_bound_s > 0.0 && time_s.is_finite() {
        format!("{:.2}, {what} {time_s:.1} s over its bound ({bound})", time_s / r.time_lower_bound_s)
    } else {
        format!("- ({bound}; the plan covers no area to bound)")
    }
}

/// The robot row: one robot's time model, or for a fleet word that each robot has its own.
fn robot_row(r: &EvalReport) -> String {
    match &r.fleet {
        Some(f) => format!("{} robots, each with its own time model (listed under fleet)", f.robots.len()),
        None => crate::coverage::motion::time_model(&r.robot),
    }
}

/// The time row: a plan of several paths sums their times, and says so beside its makespan.
fn time_row(r: &EvalReport) -> String {
    let c = &r.common;
    if r.agents > 1 {
        format!("{:.1} (summed over {} paths; makespan {:.1})", c.time_s, r.agents, c.makespan_s)
    } else {
        format!("{:.1}", c.time_s)
    }
}

fn print_table(r: &EvalReport) {
    let m = &r.metrics;
    let c = &r.common;
    let executable = if c.executable { "yes".to_string() } else { format!("NO ({})", c.not_executable_why()) };
    let rows: [(&str, String); 25] = [
        ("map", r.map.to_string()),
        ("path", r.source.clone()),
        ("robot", robot_row(r)),
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
        ("time [s]", time_row(r)),
        ("× the bound", times_the_bound(r)),
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
        for (name, model) in f.robots.iter().zip(&f.robot_time_model) {
            println!("  {:<26} {model}", format!("robot {name}"));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_folder_is_named_after_the_map() {
        assert_eq!(default_out("thesis-1"), PathBuf::from("out/eval-thesis-1"));
        assert_eq!(default_out("m/house-2.yaml"), PathBuf::from("out/eval-house-2"));
        assert_eq!(default_out("floor plan.png"), PathBuf::from("out/eval-floor_plan"));
        assert_eq!(default_out(""), PathBuf::from("out/eval-map"));
    }
}
