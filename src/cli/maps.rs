//! `covga maps`: write the presets as ROS map files, or generate floor plans
//! (`covga maps generate`).

use super::CliError;
use crate::map::generate::{PlanKind, PlanSpec, generate};
use crate::map::presets::{PRESET_NAMES, preset};
use std::path::PathBuf;

/// Arguments of `covga maps`.
#[derive(clap::Args, Debug)]
#[command(args_conflicts_with_subcommands = true)]
pub struct MapsArgs {
    /// Folder to write `<preset>.yaml` + `<preset>.pgm` into (required: the command overwrites
    /// files of those names, so it writes only where it is told).
    #[arg(long)]
    out: Option<PathBuf>,
    #[command(subcommand)]
    command: Option<MapsCommand>,
}

/// What `covga maps` does besides writing the presets.
#[derive(clap::Subcommand, Debug)]
enum MapsCommand {
    /// Generate a seeded floor plan (office, house, warehouse or hall), optionally with SLAM-like
    /// noise, as ROS map_server files; prints a start station where a 0.6 m robot fits
    Generate(GenerateArgs),
}

/// Arguments of `covga maps generate`.
#[derive(clap::Args, Debug)]
struct GenerateArgs {
    /// office (rooms on both sides of a corridor), house (rooms joined by doors), warehouse
    /// (racks, aisles and pillars) or hall (a lattice of pillars)
    #[arg(long)]
    kind: String,
    /// The seed of every random choice
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// The building's width in metres (6 to 200)
    #[arg(long, default_value_t = 24.0)]
    width: f64,
    /// The building's height in metres (6 to 200)
    #[arg(long, default_value_t = 16.0)]
    height: f64,
    /// Metres per cell (0.01 to 0.5)
    #[arg(long, default_value_t = 0.05)]
    resolution: f64,
    /// Ragged wall faces, specks in the open and unknown space outside the building
    #[arg(long)]
    noisy: bool,
    /// Folder to write `<kind>-<seed>[-noisy].yaml` + `.pgm` into
    #[arg(long)]
    out: PathBuf,
}

pub fn run(a: MapsArgs) -> Result<(), CliError> {
    match (a.command, a.out) {
        (Some(MapsCommand::Generate(g)), _) => run_generate(g),
        (None, Some(out)) => write_presets(&out),
        (None, None) => Err(CliError::Input("covga maps: --out FOLDER is required (or `covga maps generate`)".into())),
    }
}

fn write_presets(out: &std::path::Path) -> Result<(), CliError> {
    for name in PRESET_NAMES {
        let map = preset(name).expect("listed presets exist");
        // A folder that cannot be made or written is the user's environment (exit 2).
        crate::map::ros::write_ros(&map, out, name)
            .map_err(|e| CliError::Input(format!("{}: cannot write the map files: {e}", out.display())))?;
        println!("wrote {}", out.join(format!("{name}.yaml")).display());
    }
    Ok(())
}

fn run_generate(g: GenerateArgs) -> Result<(), CliError> {
    let kinds: Vec<&str> = PlanKind::ALL.iter().map(|(_, n)| *n).collect();
    let kind = PlanKind::parse(&g.kind)
        .ok_or_else(|| CliError::Input(format!("--kind {} is not one of {}", g.kind, kinds.join(", "))))?;
    let spec =
        PlanSpec { kind, width_m: g.width, height_m: g.height, resolution: g.resolution, noisy: g.noisy, seed: g.seed };
    let plan = generate(&spec).map_err(|e| CliError::Input(format!("covga maps generate: {e}")))?;
    let name = plan.map.name().to_string();
    crate::map::ros::write_ros(&plan.map, &g.out, &name)
        .map_err(|e| CliError::Input(format!("{}: cannot write the map files: {e}", g.out.display())))?;
    println!("wrote {}", g.out.join(format!("{name}.yaml")).display());
    println!("start = [{}, {}]", plan.start.x, plan.start.y);
    Ok(())
}
