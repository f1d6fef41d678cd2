//! Writing the recommended experiment file for a floor plan (`covga init`): the map, the
//! robot and the start as given, the planner settings the book recommends for a real floor
//! plan ([`crate::experiment::recommended::FLOOR_PLAN`]), each key commented. The text is
//! validated as `covga run` validates it (the map read, the start checked against the robot's
//! body, the memory estimated) before anything is written, and a bad value is blamed on the
//! flag that gave it.

use super::UseCaseError;
use crate::config::ConfigError;
use crate::experiment::file::ExperimentFile;
use crate::experiment::recommended::FLOOR_PLAN;
use crate::geom::Point;
use crate::map::ros::BareImage;
use std::fmt::Write;
use std::path::Path;

/// The evaluation budget the file sets: the shipped floor-plan example's, a few seconds of
/// search on an office floor.
pub const EVALUATIONS: u64 = 20_000;

/// What `covga init` is asked for.
#[derive(Clone, Debug)]
pub struct InitRequest {
    /// The map: a preset, a ROS map YAML or a bare image (read from the working directory).
    pub map: String,
    /// A bare image's scale and thresholds.
    pub image: BareImage,
    /// The start (and end) station in metres.
    pub start: Point,
    /// `robot.width` in metres.
    pub width: f64,
    /// `robot.speed` in m/s.
    pub speed: f64,
    /// `robot.rot_speed` in rad/s.
    pub rot_speed: f64,
}

/// The flag of `covga init` that sets a dotted key, with its value as given.
fn flag_of(req: &InitRequest, key: &str) -> Option<String> {
    let (x, y) = (req.start.x, req.start.y);
    Some(match key {
        "robot.width" => format!("--width {}", req.width),
        "robot.speed" => format!("--speed {}", req.speed),
        "robot.rot_speed" => format!("--rot-speed {}", req.rot_speed),
        "stations.start" | "stations.end" | "stations" => format!("--start {x},{y}"),
        "map.resolution" => match req.image.resolution {
            Some(r) => format!("--resolution {r}"),
            None => "--resolution".to_string(),
        },
        "map.free_threshold" => format!("--free-threshold {}", req.image.free_threshold.unwrap_or(0)),
        k if k.is_empty() || k.starts_with("map") => format!("--map {}", req.map),
        _ => return None,
    })
}

/// The error of a value the file would hold, blamed on the flag that gave it.
fn blamed(req: &InitRequest, e: &ConfigError) -> UseCaseError {
    match flag_of(req, &e.key) {
        Some(flag) if e.key.is_empty() => UseCaseError::Input(format!("{flag}: {}: {}", e.file, e.message)),
        Some(flag) => UseCaseError::Input(format!("{flag}: `{}` {}", e.key, e.message)),
        None => UseCaseError::Input(format!("covga init: {e}")),
    }
}

/// Refuses a value that is not a finite number before it is written as TOML.
fn finite(flag: &str, v: f64) -> Result<(), UseCaseError> {
    if v.is_finite() { Ok(()) } else { Err(UseCaseError::Input(format!("{flag} {v} is not a finite number"))) }
}

/// The commented experiment text for `req`, named `file` in its comments (where it is
/// written), checked to load and validate as `covga run` would.
pub fn experiment_text(req: &InitRequest, file: &str) -> Result<String, UseCaseError> {
    for (flag, v) in [("--width", req.width), ("--speed", req.speed), ("--rot-speed", req.rot_speed)] {
        finite(flag, v)?;
    }
    finite("--start", req.start.x)?;
    finite("--start", req.start.y)?;
    if let Some(r) = req.image.resolution {
        finite("--resolution", r)?;
    }
    let text = text(req, file);
    let origin = "covga init";
    let parsed = ExperimentFile::parse(&text, origin).map_err(|e| UseCaseError::Internal(e.to_string()))?;
    let experiment = parsed.validate(origin, Path::new("."), "init").map_err(|e| blamed(req, &e))?;
    let limit = crate::experiment::memory::memory_limit(None);
    experiment.check_memory(origin, limit.as_ref(), 1, rayon::current_num_threads()).map_err(|e| blamed(req, &e))?;
    Ok(text)
}

/// `key = value`, its comment aligned with the others' after it.
fn keyed(t: &mut String, key_value: &str, why: &str) {
    let _ = writeln!(t, "{key_value:<31}# {why}");
}

/// The file's text: header, map, robot, station, the recommended planner settings, budget.
fn text(req: &InitRequest, file: &str) -> String {
    let mut t = String::new();
    let _ = writeln!(
        t,
        "# An experiment for the floor plan {}, written by `covga init` with the settings the book's\n\
         # \"Plan your own floor plan\" recommends for the fastest executable plan to a coverage goal\n\
         # on a real floor plan. Relative paths are read from the folder covga runs in. Run it with:\n\
         #   covga run {file}\nseed = 1",
        req.map
    );
    keyed(&mut t, &format!("planner = {}", FLOOR_PLAN[0].value), FLOOR_PLAN[0].why);
    t.push_str("\n[map]\n");
    keyed(
        &mut t,
        &format!("source = {}", toml::Value::String(req.map.clone())),
        "a preset, a ROS map YAML or an image",
    );
    if let Some(r) = req.image.resolution {
        keyed(&mut t, &format!("resolution = {r:?}"), "metres per pixel of the image");
    }
    if let Some(g) = req.image.free_threshold {
        keyed(&mut t, &format!("free_threshold = {g}"), &format!("grey >= {g} free, darker occupied"));
    }
    t.push_str("\n[robot]\n");
    keyed(&mut t, &format!("width = {:?}", req.width), "m: the swept width, and the body that must fit between walls");
    keyed(&mut t, &format!("speed = {:?}", req.speed), "m/s");
    keyed(&mut t, &format!("rot_speed = {:?}", req.rot_speed), "rad/s: turning in place costs time (0: it is free)");
    t.push_str("\n[stations]\n");
    let start = format!("start = [{:?}, {:?}]", req.start.x, req.start.y);
    keyed(&mut t, &start, "m, in the map's frame: the plan starts and ends here");
    t.push_str("\n[cell_order]\n");
    for r in &FLOOR_PLAN[1..] {
        let key = r.key.strip_prefix("cell_order.").expect("a cell_order key");
        keyed(&mut t, &format!("{key} = {}", r.value), r.why);
    }
    if req.rot_speed == 0.0 {
        t.push_str(
            "# With free turning (rot_speed = 0) the quota completion was not measured against the\n\
             # boundary pass: try completion = \"boundary\" too.\n",
        );
    }
    t.push_str("\n[budget]\n");
    keyed(&mut t, "iterations = 1000000", "the evaluation budget stops the search");
    keyed(
        &mut t,
        &format!("evaluations = {EVALUATIONS}"),
        "tours the search evaluates: a larger budget searches longer",
    );
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    fn request() -> InitRequest {
        InitRequest {
            map: "thesis-1".into(),
            image: BareImage::default(),
            start: Point::new(1.3, 1.3),
            width: 0.6,
            speed: 0.3,
            rot_speed: 0.52,
        }
    }

    #[test]
    fn the_text_sets_every_recommended_key_and_validates() {
        let text = experiment_text(&request(), "e.toml").unwrap();
        let table: toml::Table = text.parse().unwrap();
        assert_eq!(crate::experiment::recommended::departures(&table), vec![]);
        assert!(text.contains("covga run e.toml"), "{text}");
        assert!(!text.contains("boundary"), "a turning robot gets no note on free turning: {text}");
    }

    #[test]
    fn a_bad_value_is_blamed_on_its_flag() {
        let e = experiment_text(&InitRequest { width: 0.0, ..request() }, "e.toml").unwrap_err().to_string();
        assert!(e.starts_with("--width 0: `robot.width`"), "{e}");
        let e = experiment_text(&InitRequest { start: Point::new(50.0, 1.0), ..request() }, "e.toml")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("--start 50,1: "), "{e}");
        let e = experiment_text(&InitRequest { speed: f64::NAN, ..request() }, "e.toml").unwrap_err().to_string();
        assert_eq!(e, "--speed NaN is not a finite number");
    }
}
