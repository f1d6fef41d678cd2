//! Wall-free routes for every planner that routes: the robot's moves around walls on the
//! clearance raster ([`routes`], the thesis GA's routed moves), the transit lengths between
//! sweep ends that the cell-order planner orders ([`transit`]), and the bucket queue their
//! shortest-path searches share ([`bucket_queue`]). Below the planners, above the map and the
//! coverage raster.

pub mod bucket_queue;
pub mod routes;
pub mod transit;
