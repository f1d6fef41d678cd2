//! The loaders as functions of raw bytes, for the fuzz targets in `fuzz/` and for the test that
//! replays their corpus (`tests/replays/fuzz_corpus.rs`). Each function runs a loader the way the
//! command line does and discards the result: a fuzz input may make a loader return an error,
//! never panic, hang or allocate without bound.

use crate::experiment::file::ExperimentFile;
use crate::geom::Point;
use crate::map::ros::{PixelRule, decode_map_image, parse_ros_yaml};
use crate::study::grid::Study;
use std::path::Path;

/// An experiment TOML file, parsed and validated (maps: the presets only, no file access).
pub fn experiment_toml(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let Ok(file) = ExperimentFile::parse(text, "fuzz.toml") else { return };
    let presets_only = |source: &str, _image: &crate::map::ros::BareImage| {
        crate::map::presets::preset(source)
            .ok_or_else(|| crate::map::MapError::UnknownMap { name: source.to_string(), presets: String::new() })
    };
    let _ = file.validate_with("fuzz.toml", Path::new("."), "fuzz", &presets_only, crate::planner::Checks::Full);
}

/// A grid TOML file, parsed and expanded (counted before it is enumerated).
pub fn grid_toml(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else { return };
    if let Ok(study) = Study::parse(text, Path::new("fuzz/grid.toml")) {
        let _ = study.branches();
    }
}

/// A ROS map_server YAML file (the metadata; the image is not read).
pub fn ros_yaml(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let _ = parse_ros_yaml(text, Path::new("fuzz/map.yaml"));
}

/// A PGM or PNG map image at 0.05 m per pixel with map_server's default thresholds.
pub fn map_image(data: &[u8]) {
    let _ = decode_map_image(data, Path::new("fuzz.pgm"), "fuzz", 0.05, Point::origin(), PixelRule::default());
}

/// A path CSV file (`x_m,y_m[,agent][,index]`).
pub fn path_csv(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let _ = crate::io::parse_path_csv(text, Path::new("fuzz.csv"));
}

/// `covga eval` alone, for [`eval_args`].
#[derive(clap::Parser)]
struct EvalCommand {
    #[command(flatten)]
    args: crate::cli::eval::EvalArgs,
}

/// `covga eval`'s arguments: NUL-separated words (at most 32), parsed as the command line
/// parses them and run. So that an input neither reads nor writes the user's files, `--path`,
/// `--fleet` and `--out` are dropped with their values, a `--map` that is not a preset becomes
/// `thesis-1`, and results go to a folder of this process under the system's temporary folder.
pub fn eval_args(data: &[u8]) {
    use clap::Parser;
    let Ok(text) = std::str::from_utf8(data) else { return };
    let mut argv = vec!["eval".to_string()];
    let mut words = text.split('\0').take(32).peekable();
    while let Some(word) = words.next() {
        let (flag, inline) = match word.split_once('=') {
            Some((f, v)) if f.starts_with("--") => (f, Some(v)),
            _ => (word, None),
        };
        match flag {
            "--path" | "--fleet" | "--out" => {
                if inline.is_none() {
                    words.next();
                }
            }
            "--map" => {
                let value = inline.map(str::to_string).or_else(|| words.next().map(str::to_string));
                let value = value.filter(|v| crate::map::presets::preset(v).is_some());
                argv.extend(["--map".to_string(), value.unwrap_or_else(|| "thesis-1".into())]);
            }
            _ => argv.push(word.to_string()),
        }
    }
    let out = std::env::temp_dir().join(format!("covga-fuzz-eval-{}", std::process::id()));
    argv.extend(["--out".to_string(), out.display().to_string()]);
    if let Ok(command) = EvalCommand::try_parse_from(argv) {
        let _ = crate::cli::eval::run(command.args);
    }
    let _ = std::fs::remove_dir_all(&out);
}

/// A loader run on raw bytes.
pub type Entry = fn(&[u8]);

/// The targets by name, as the fuzz crate and the corpus replay know them.
pub const TARGETS: [(&str, Entry); 6] = [
    ("experiment_toml", experiment_toml),
    ("grid_toml", grid_toml),
    ("ros_yaml", ros_yaml),
    ("map_image", map_image),
    ("path_csv", path_csv),
    ("eval_args", eval_args),
];
