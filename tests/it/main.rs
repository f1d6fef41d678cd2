//! covga's integration tests, one binary (one link, shared helpers in `tests/common`): a
//! module per command (`*_cli`, `report_*`), per planner property (`cell_order`, `thesis_*`,
//! `planner_contract`, `parent_schemes`, `reachable`), per contract of the repository
//! (`architecture`, `citations`, `readme`, `reference`, `run_ids`, `generated_maps`, `stats_reference`,
//! `mutation_tooling`) and the reliability suite of bad inputs and interrupts. The heavy replays of committed data (studies
//! re-run, reports re-made, the fuzzing corpus, every key variation) are the other binary,
//! `tests/replays`. `cargo test --release --test it MODULE::` runs one module.

#[path = "../common/mod.rs"]
mod common;

mod architecture;
mod cell_order;
mod cell_order_controls;
mod citations;
mod equal_coverage;
mod eval_cli;
mod floor_plan_recommendation;
mod generated_maps;
mod grid_cli;
mod init_cli;
mod layouts;
mod mutation_tooling;
mod parent_schemes;
mod planner_contract;
mod planner_section;
mod plugins;
mod reachable;
mod readme;
mod reference;
mod reliability;
mod report_compare;
mod report_numbers;
mod report_plans;
mod run_cli;
mod run_ids;
mod stats_reference;
mod study_stop;
mod tables_3_1_3_2;
mod thesis_camera;
mod thesis_nsga2;
mod thesis_routed;
mod thesis_seeding;
mod waypoint_cli;
