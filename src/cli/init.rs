//! `covga init`: write the recommended experiment file for a floor plan.

use super::{CliError, parse_point};
use crate::usecase::init::{InitRequest, experiment_text};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Arguments of `covga init`.
#[derive(clap::Args, Debug)]
pub struct InitArgs {
    /// The floor plan: a preset (thesis-1, office, …), a ROS map YAML, or a PGM/PNG image with
    /// --resolution. The file records the path as given, read from the folder covga runs in.
    #[arg(long)]
    map: String,
    /// Start (and end) station X,Y in metres, in the map's frame; negative values as typed.
    #[arg(long, allow_hyphen_values = true)]
    start: String,
    /// Metres per pixel of a bare image map.
    #[arg(long, allow_hyphen_values = true)]
    resolution: Option<f64>,
    /// For a bare image map: grey values at or above this are free, darker ones occupied.
    #[arg(long, value_parser = clap::value_parser!(u8).range(1..))]
    free_threshold: Option<u8>,
    /// `robot.width` in metres: the swept width, and the body that must fit between walls.
    #[arg(long, default_value_t = 0.6, allow_hyphen_values = true)]
    width: f64,
    /// `robot.speed` in m/s.
    #[arg(long, default_value_t = 0.3, allow_hyphen_values = true)]
    speed: f64,
    /// `robot.rot_speed` in rad/s (0 makes turning free; measure your robot's).
    #[arg(long = "rot-speed", default_value_t = 0.52, allow_hyphen_values = true)]
    rot_speed: f64,
    /// The experiment file to write (default: MAP.toml in the current folder, MAP the preset's
    /// name or the map file's stem); an existing file is never overwritten.
    #[arg(long)]
    out: Option<PathBuf>,
}

/// The default file: `<map stem>.toml` in the current folder.
fn default_out(map: &str) -> PathBuf {
    let stem = Path::new(map).file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    PathBuf::from(format!("{}.toml", if stem.is_empty() { "experiment" } else { &stem }))
}

/// Runs `covga init`: the text is made and validated, then written to a file that did not
/// exist (made exclusively, so that a file made meanwhile is not overwritten either).
pub fn run(a: InitArgs) -> Result<(), CliError> {
    let out = a.out.clone().unwrap_or_else(|| default_out(&a.map));
    if out.exists() || out.is_symlink() {
        return Err(CliError::Input(format!(
            "--out {}: the file exists; covga init writes a new file and never overwrites one (give another --out, \
             or remove it)",
            out.display()
        )));
    }
    let start = parse_point(&a.start).map_err(|m| CliError::Input(format!("--start: {m}")))?;
    let request = InitRequest {
        map: a.map.clone(),
        image: crate::map::ros::BareImage { resolution: a.resolution, free_threshold: a.free_threshold },
        start,
        width: a.width,
        speed: a.speed,
        rot_speed: a.rot_speed,
    };
    let text = experiment_text(&request, &out.display().to_string())?;
    write_new(&out, text.as_bytes())?;
    println!("wrote {} (run it with `covga run {}`)", out.display(), out.display());
    Ok(())
}

/// Writes `bytes` to the new file `path`; a file that cannot be written whole is removed.
fn write_new(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    let mut file = std::fs::OpenOptions::new().write(true).create_new(true).open(path).map_err(|e| {
        let kind = if e.kind() == std::io::ErrorKind::AlreadyExists { "the file exists" } else { "cannot create it" };
        CliError::Input(format!("--out {}: {kind}: {e}", path.display()))
    })?;
    file.write_all(bytes).and_then(|()| file.sync_all()).map_err(|e| {
        let _ = std::fs::remove_file(path);
        CliError::Internal(format!("cannot write {}: {e}", path.display()))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_file_is_named_after_the_map() {
        assert_eq!(default_out("thesis-1"), PathBuf::from("thesis-1.toml"));
        assert_eq!(default_out("plans/floor.png"), PathBuf::from("floor.toml"));
        assert_eq!(default_out(""), PathBuf::from("experiment.toml"));
    }
}
