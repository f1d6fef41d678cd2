//! `covga maps`: write the presets as ROS map files.

use super::CliError;
use crate::map::presets::{PRESET_NAMES, preset};
use std::path::PathBuf;

/// Arguments of `covga maps`.
#[derive(clap::Args, Debug)]
pub struct MapsArgs {
    /// Folder to write `<preset>.yaml` + `<preset>.pgm` into (required: the command overwrites
    /// files of those names, so it writes only where it is told).
    #[arg(long)]
    out: PathBuf,
}

pub fn run(a: MapsArgs) -> Result<(), CliError> {
    for name in PRESET_NAMES {
        let map = preset(name).expect("listed presets exist");
        // A folder that cannot be made or written is the user's environment (exit 2).
        crate::map::ros::write_ros(&map, &a.out, name)
            .map_err(|e| CliError::Input(format!("{}: cannot write the map files: {e}", a.out.display())))?;
        println!("wrote {}", a.out.join(format!("{name}.yaml")).display());
    }
    Ok(())
}
