//! Records the git commit the binary was built from (saved in every study folder), with
//! `-dirty` when the sources it is built from differ from that commit: a study run with such a
//! binary names the commit it was made on top of, not code that ran.

fn main() {
    let git = |args: &[&str]| std::process::Command::new("git").args(args).output().ok().filter(|o| o.status.success());
    let commit = git(&["rev-parse", "HEAD"])
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_else(|| "unknown".into());
    // What the binary is built from: its sources, manifest, lock file and this script.
    let sources = ["src", "Cargo.toml", "Cargo.lock", "build.rs"];
    let changed = git(&[&["diff", "--quiet", "HEAD", "--"][..], &sources[..]].concat()).is_none();
    let dirty = if commit != "unknown" && changed { "-dirty" } else { "" };
    println!("cargo:rustc-env=COVGA_GIT_COMMIT={commit}{dirty}");
    println!("cargo:rerun-if-changed=.git/HEAD");
    println!("cargo:rerun-if-changed=.git/refs");
    println!("cargo:rerun-if-changed=.git/index");
    for s in sources {
        println!("cargo:rerun-if-changed={s}");
    }
}
