//! A fleet of a planner: an experiment file with `[[robots]]` plans them with the planner it
//! names, as `[fleet] mode` says. This composes the planners' entries with the fleet layer:
//! the named planner validates its settings (a waypoint team's section as the robots make it),
//! and the fleet takes the planners that can plan a team (the thesis GA's parameters, the
//! waypoint planner's team); any other refuses the fleet.

use super::file::ExperimentFile;
use crate::config::ConfigError;
use crate::fleet::config::{Team, waypoint_team, wrong_planner};
use crate::fleet::planner::FleetPlanner;
use crate::planner::Context;
use crate::planner::entry::FileSections;
use crate::thesis::config::{RETRAIN_SECTION, ThesisConfig};
use crate::thesis::objective::Objective;
use crate::waypoint::config::{WAYPOINT_SECTION, WaypointConfig, WaypointSection};
use std::any::Any;

/// The file as the planner of a fleet reads it: a waypoint team's section is the one the
/// robots make (one agent per robot), not the one written.
struct TeamSections<'a> {
    file: &'a ExperimentFile,
    waypoint: WaypointSection,
}

impl FileSections for TeamSections<'_> {
    fn section(&self, name: &str) -> Option<&dyn Any> {
        if name == WAYPOINT_SECTION.name() { Some(&self.waypoint) } else { self.file.section(name) }
    }
}

/// Validates the file's planner for its `[[robots]]` and the `[fleet]` section into the fleet.
pub fn validate(file: &ExperimentFile, ctx: &Context) -> Result<FleetPlanner, ConfigError> {
    let waypoint = waypoint_team(
        &WAYPOINT_SECTION.get_or_default(file),
        &file.robots,
        file.fleet.as_ref(),
        file.stations.start,
        ctx.origin,
    )?;
    let single = file.planner.entry().validate(&TeamSections { file, waypoint }, ctx)?;
    let single: &dyn Any = single.as_ref();
    let section = file.fleet.clone().unwrap_or_default();
    let team = if let Some(t) = single.downcast_ref::<ThesisConfig>() {
        Team::Thesis(thesis_team(t, ctx)?)
    } else if let Some(w) = single.downcast_ref::<WaypointConfig>() {
        Team::Waypoint(Box::new(w.clone()))
    } else {
        return Err(wrong_planner(ctx.origin, file.planner.name(), section.mode));
    };
    section.validate(&file.robots, file.stations.start, RETRAIN_SECTION.get(file).is_some(), team, ctx)
}

/// The thesis GA's parameters for a fleet's GAs, refusing what only the GA of one robot does.
fn thesis_team(t: &ThesisConfig, ctx: &Context) -> Result<crate::thesis::params::ThesisParams, ConfigError> {
    if !t.seeds.is_empty() {
        return Err(ctx.error(
            "thesis.seed_population",
            "seeds the GA of one robot; a fleet's GAs start from random genomes (leave it out)",
        ));
    }
    if !t.moves.is_straight() {
        return Err(ctx.error(
            "thesis.moves",
            "= \"routed\" is built for the GA of one robot; a fleet's GAs drive straight moves (leave it out)",
        ));
    }
    if t.objective.0 == Objective::Camera {
        return Err(ctx.error(
            "thesis.objective",
            "= \"camera\" is built for the GA of one robot; a fleet's GAs optimise the footprint (leave it out)",
        ));
    }
    Ok(t.params)
}
