//! The waypoint-graph maximin planner of 000 (Olson et al.), the ablation baseline: working
//! raster ([`raster`]), geometry ([`geometry`]), waypoints ([`waypoints`], [`passages`]), traversability graph ([`graph`]),
//! per-traversal camera views ([`precompute`]), objectives and constraints ([`evaluate`]),
//! path operators ([`operators`]) and the maximin GA ([`run`]).

pub mod config;
pub mod evaluate;
pub mod geometry;
pub mod graph;
pub mod operators;
pub mod passages;
pub mod planner;
pub mod precompute;
pub mod raster;
pub mod run;
pub mod waypoints;
pub mod world;
