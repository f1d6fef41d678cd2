//! Grid studies: a grid file of axes over a base experiment expanded into runs with stable
//! ids ([`grid`]), the runner that executes them in parallel, resumably and by shards
//! ([`runner`]), their records in `runs.csv` ([`records`]), merging shard outputs ([`merge`]),
//! time estimates ([`estimate`]), the order runs start in ([`order`]), Slurm job arrays ([`slurm`])
//! and the reference of every file and column they write ([`outputs`]). Each run is an experiment
//! of `crate::experiment`; reading the records back into reports is `crate::report`'s.

pub mod estimate;
pub mod grid;
pub mod merge;
pub mod order;
pub mod outputs;
pub mod records;
pub mod runner;
pub mod shard_files;
pub mod slurm;
pub mod standalone;
