//! The loaders as functions of raw bytes, for the fuzz targets in `fuzz/` and for the test that
//! replays their corpus (`tests/fuzz_corpus.rs`). Each function runs a loader the way the
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
    let _ = file.validate_with("fuzz.toml", Path::new("."), "fuzz", &presets_only);
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

/// A loader run on raw bytes.
pub type Entry = fn(&[u8]);

/// The targets by name, as the fuzz crate and the corpus replay know them.
pub const TARGETS: [(&str, Entry); 5] = [
    ("experiment_toml", experiment_toml),
    ("grid_toml", grid_toml),
    ("ros_yaml", ros_yaml),
    ("map_image", map_image),
    ("path_csv", path_csv),
];
