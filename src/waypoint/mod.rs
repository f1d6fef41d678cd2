//! The waypoint-graph maximin planner of 000 (Olson et al.), the ablation baseline: working
//! raster ([`raster`]), waypoints ([`waypoints`]), traversability graph ([`graph`]),
//! per-traversal camera views ([`precompute`]), objectives and constraints ([`evaluate`]),
//! path operators ([`operators`]) and the maximin GA ([`run`]).

pub mod config;
pub mod evaluate;
pub mod graph;
pub mod operators;
pub mod planner;
pub mod precompute;
pub mod raster;
pub mod run;
pub mod waypoints;
pub mod world;
