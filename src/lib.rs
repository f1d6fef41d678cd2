#![warn(missing_docs)]
//! covga: coverage path planning with genetic algorithms.
//!
//! The crate implements the action-encoded GA of 003 ([`thesis`]), the waypoint-graph maximin
//! planner of 000 ([`waypoint`]), pattern baselines ([`patterns`]), random search
//! ([`random_search`]) and fleets ([`fleet`]), all scored by one common scorer ([`coverage`])
//! on occupancy grid maps ([`map`]); experiments ([`experiment`]), grid studies ([`study`]),
//! reports ([`report`]), figures ([`plot`]) and the `covga` command line ([`cli`]).
//!
//! The user guide, the reference of every key and flag, and the design are the book in
//! `docs/` (`mdbook build docs`; its pages are Markdown in `docs/src/`). Citations in this
//! crate: `003 eq. 3.13` and `000 eq. 2` are equations, sections and tables of the two source
//! papers (Alberding's master's thesis and Olson et al.'s waypoint-graph planner); `thesis-ga §9.1`
//! and `R17` are sections and resolved ambiguities of the book's design decisions for the thesis
//! GA (`docs/src/concepts/thesis-ga-decisions.md`), `waypoint §11.4` and `W18` those for the
//! waypoint planner (`docs/src/concepts/waypoint-decisions.md`).
//!
//! The modules form layers, bottom to top; each imports only from its own layer and those
//! below (`tests/it/architecture.rs` holds the order):
//!
//! 1. [`geom`], [`stats`], [`io`], [`config`], [`ga`]: points and angles, the statistics
//!    every report and Python share, files and numbers, configuration errors and range
//!    checks, and what every GA shares (selection, control, RNG streams, observers: it needs no
//!    map, and the coverage layer hashes with its streams);
//! 2. [`map`]: grids, ROS files, presets, clearance and reachability;
//! 3. [`coverage`]: the swept footprint, the camera, the thesis fitness equations and the
//!    common scorer;
//! 4. [`routing`], [`lanes`]: wall-free routes and transit lengths for every planner that
//!    routes; the boustrophedon's lanes and cells, the route along them and coverage
//!    completion, which the sweeping planners share;
//! 5. [`plot`]: figure primitives (maps, paths, charts, legends);
//! 6. [`planner`]: the `Planner` interface, its scenario, budget and outcome;
//! 7. [`thesis`], [`waypoint`], [`patterns`], [`cell_order`], [`layouts`], then [`random_search`],
//!    [`seeded`] and [`fleet`]: the planners, peers that import none of each other, each
//!    validating its own section and drawing its own figures; then the compositions of them
//!    (random search draws the thesis genome at random, the thesis GA is seeded with other
//!    planners' plans, a fleet is planned by the others);
//! 8. [`experiment`]: the experiment file, the one registry of planners, one run's folder;
//! 9. [`study`]: grids, the runner, records, merge, estimates, Slurm;
//! 10. [`report`]: `covga report`, in rooms (figures, the study analysis, tables and
//!     comparisons, the replication of the papers, the summary's sections);
//! 11. [`usecase`]: run and eval as library functions, under the command line and Python;
//! 12. [`cli`] (and [`fuzz_entry`]), [`prelude`]: thin fronts over the library, and the one
//!     import a program or a planner from outside needs.

pub mod cell_order;
pub mod cli;
pub mod config;
pub mod coverage;
pub mod experiment;
pub mod fleet;
pub mod fuzz_entry;
pub mod ga;
pub mod geom;
pub mod io;
pub mod lanes;
pub mod layouts;
pub mod map;
pub mod patterns;
pub mod planner;
pub mod plot;
pub mod prelude;
pub mod random_search;
pub mod report;
pub mod routing;
pub mod seeded;
pub mod stats;
pub mod study;
pub mod thesis;
pub mod usecase;
pub mod waypoint;
