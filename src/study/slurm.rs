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

/// The batch script for `grid` (absolute paths) writing into `out`, run by `exe`.
pub fn sbatch_script(exe: &Path, grid: &Path, out: &Path, name: &str, o: &SlurmOptions) -> String {
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
        let s = sbatch_script(Path::new("/bin/covga"), Path::new("/g/smoke.toml"), Path::new("/o/s"), "smoke", &o);
        assert!(s.contains("#SBATCH --array=0-3"));
        assert!(s.contains("--shard \"$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT\""));
        assert!(s.contains("#SBATCH --cpus-per-task=2"));
        assert!(s.contains("#SBATCH --mem=1536M"));
        assert!(s.contains("--max-memory 1610612736\n"));
    }
}
