//! The waypoint-graph maximin planner of 000 (Olson et al.), the ablation baseline: working
//! raster (`crate::coverage::work_map`, shared with the camera model), geometry ([`geometry`]), waypoints ([`waypoints`], [`passages`]), traversability graph ([`graph`]),
//! per-traversal camera views ([`precompute`]), objectives and constraints ([`evaluate`]),
//! path operators ([`operators`]), the maximin GA ([`run`]), the `[waypoint]` section
//! ([`config`]) and the planner's figures ([`figures`]).

pub mod config;
pub mod entry;
pub mod evaluate;
pub mod figures;
pub mod geometry;
pub mod graph;
pub mod operators;
pub mod passages;
pub mod planner;
pub mod precompute;
pub mod run;
pub mod waypoints;
pub mod world;
