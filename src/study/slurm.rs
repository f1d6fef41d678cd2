//! Slurm job arrays: a batch script whose array tasks are the shards of a study; each task is
//! resumable because it is an ordinary `covga grid --shard` invocation.

use std::path::Path;

/// Settings of the array job.
#[derive(Clone, Debug)]
pub struct SlurmOptions {
    /// Array tasks (= shards).
    pub array_size: usize,
    /// Time limit per task, `HH:MM:SS`.
    pub time: String,
    /// CPUs per task (= `--jobs` of each shard).
    pub cpus_per_task: usize,
    /// Memory per task in bytes: requested from Slurm (`--mem`, in MiB rounded up) and passed
    /// to each shard as `--max-memory`, so a shard checks its runs against its allocation, not
    /// against the node's memory.
    pub mem_bytes: u64,
}

/// Checks `HH:MM:SS` (hours may exceed 24, as Slurm allows).
pub fn check_time(t: &str) -> Result<(), String> {
    let parts: Vec<&str> = t.split(':').collect();
    let ok = parts.len() == 3
        && parts.iter().all(|p| !p.is_empty() && p.chars().all(|c| c.is_ascii_digit()))
        && parts[1].parse::<u32>().is_ok_and(|m| m < 60)
        && parts[2].parse::<u32>().is_ok_and(|s| s < 60);
    if ok { Ok(()) } else { Err(format!("--time `{t}` is not HH:MM:SS (minutes and seconds below 60)")) }
}

fn quote(p: &Path) -> String {
    format!("'{}'", p.display().to_string().replace('\'', "'\\''"))
}

/// Where a task runs and what it runs: the binary, the grid file and the study folder (all
/// absolute), and the folder the grid was written from (`covga grid --slurm`'s working
/// directory), which a task changes to so that the grid's relative map paths resolve as they
/// did there, wherever `sbatch` is called.
#[derive(Clone, Copy, Debug)]
pub struct TaskPaths<'a> {
    /// The covga binary.
    pub exe: &'a Path,
    /// The grid file.
    pub grid: &'a Path,
    /// The study folder.
    pub out: &'a Path,
    /// The working directory of the tasks.
    pub dir: &'a Path,
}

/// The batch script of the study `name` at `paths`.
pub fn sbatch_script(paths: TaskPaths, name: &str, o: &SlurmOptions) -> String {
    let TaskPaths { exe, grid, out, dir } = paths;
    format!(
        "#!/bin/bash\n\
         # covga study as a Slurm job array: one task per shard; rerunning a task resumes it.\n\
         # Submit with: sbatch {script}\n\
         # When every task has finished: covga merge {outq}\n\
         #SBATCH --job-name=covga-{name}\n\
         #SBATCH --array=0-{last}\n\
         #SBATCH --time={time}\n\
         #SBATCH --cpus-per-task={cpus}\n\
         #SBATCH --mem={mem_mib}M\n\
         #SBATCH --ntasks=1\n\
         #SBATCH --output={log}/%A_%a.out\n\
         set -euo pipefail\n\
         # Relative map paths in the grid are read from the folder it was written from.\n\
         cd {dirq}\n\
         exec {exe} grid {grid} --out {outq} --jobs \"${{SLURM_CPUS_PER_TASK:-{cpus}}}\" --shard \"$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT\" --max-memory {mem_bytes}\n",
        script = quote(&out.join("study.sbatch")),
        outq = quote(out),
        name = name,
        last = o.array_size.saturating_sub(1),
        time = o.time,
        cpus = o.cpus_per_task,
        mem_mib = o.mem_bytes.div_ceil(1024 * 1024),
        mem_bytes = o.mem_bytes,
        log = out.join("slurm").display(),
        exe = quote(exe),
        grid = quote(grid),
        dirq = quote(dir),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_format() {
        assert!(check_time("01:30:00").is_ok());
        assert!(check_time("100:00:00").is_ok());
        assert!(check_time("1:60:00").is_err());
        assert!(check_time("90").is_err());
    }

    #[test]
    fn script_has_array_and_shard() {
        let o = SlurmOptions { array_size: 4, time: "00:10:00".into(), cpus_per_task: 2, mem_bytes: 3 << 29 };
        let paths = TaskPaths {
            exe: Path::new("/bin/covga"),
            grid: Path::new("/g/smoke.toml"),
            out: Path::new("/o/s"),
            dir: Path::new("/home/it's"),
        };
        let s = sbatch_script(paths, "smoke", &o);
        assert!(s.contains("\ncd '/home/it'\\''s'\nexec '/bin/covga' grid"), "{s}");
        assert!(s.contains("#SBATCH --array=0-3"));
        assert!(s.contains("--shard \"$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT\""));
        assert!(s.contains("#SBATCH --cpus-per-task=2"));
        assert!(s.contains("#SBATCH --mem=1536M"));
        assert!(s.contains("--max-memory 1610612736\n"));
    }
}
