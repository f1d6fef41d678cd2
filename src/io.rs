//! Small file helpers: atomic writes (write to a temporary sibling, fsync, rename), so a killed
//! process never leaves a half-written result file.

pub mod memory;
pub mod png;

use std::io::Write;
use std::path::Path;

/// Writes `bytes` to `path` atomically: a temporary file in the same folder is written, synced
/// and renamed over the target.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    write_atomic_with(path, bytes, None)
}

/// [`write_atomic`], the new file given `permissions` (those of the file it replaces, say)
/// before it takes the target's place.
pub fn write_atomic_with(path: &Path, bytes: &[u8], permissions: Option<std::fs::Permissions>) -> std::io::Result<()> {
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir)?;
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_else(|| "out".into());
    let tmp = dir.join(format!(".{name}.tmp{}", std::process::id()));
    {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        if let Some(p) = permissions {
            f.set_permissions(p)?;
        }
        f.sync_all()?;
    }
    std::fs::rename(&tmp, path)
}

/// An advisory lock on a results folder (the file `.covga.lock` in it), held while a covga
/// process writes there and released by the operating system when the process ends, however it
/// ends. Exclusive for a run or a whole study; shared for the shards of one study, which write
/// one folder side by side (a Slurm job array), so that a whole-study run and a shard never
/// write the same folder at once.
pub struct FolderLock {
    _file: std::fs::File,
}

impl FolderLock {
    /// Takes the folder's lock, `exclusive` or shared, or says which process holds it.
    pub fn take(dir: &Path, exclusive: bool) -> Result<Self, String> {
        let path = dir.join(".covga.lock");
        let mut file = std::fs::OpenOptions::new()
            .create(true)
            .truncate(false)
            .read(true)
            .write(true)
            .open(&path)
            .map_err(|e| format!("{}: cannot lock the folder: {e}", dir.display()))?;
        #[cfg(unix)]
        {
            use std::io::{Read, Seek};
            use std::os::fd::AsRawFd;
            let mode = if exclusive { libc::LOCK_EX } else { libc::LOCK_SH };
            // SAFETY: flock on a file descriptor this function owns; no memory is shared.
            let rc = unsafe { libc::flock(file.as_raw_fd(), mode | libc::LOCK_NB) };
            if rc != 0 {
                let mut holder = String::new();
                let _ = file.read_to_string(&mut holder);
                let by = holder.trim().parse::<u32>().map_or(String::new(), |pid| format!(" by process {pid}"));
                return Err(format!(
                    "{}: in use{by}: another covga process is writing this folder now; wait for it or choose another folder",
                    dir.display()
                ));
            }
            // The holder's process id, for the next one's message (a shard overwrites another's).
            let _ = file.set_len(0).and_then(|_| file.rewind()).and_then(|_| write!(file, "{}", std::process::id()));
        }
        Ok(Self { _file: file })
    }
}

use crate::geom::Point;
use std::path::PathBuf;

/// A bad path file: the file, the line (1-based, header = 1) and what is expected.
#[derive(Debug, thiserror::Error)]
#[error("{}{}: {message}", path.display(), if *line > 0 { format!(":{line}") } else { String::new() })]
pub struct PathFileError {
    /// The file.
    pub path: PathBuf,
    /// The line (0 when the file could not be read).
    pub line: u64,
    /// What is wrong and what is expected.
    pub message: String,
}

/// The largest experiment, grid, fleet or map YAML file read (bytes): far above any real one,
/// and a bound for a path that names a device (`/dev/zero`) or a runaway file.
pub const MAX_TEXT_FILE_BYTES: u64 = 16 << 20;
/// The largest map image read (bytes): a compressed floor plan is a few MiB.
pub const MAX_IMAGE_FILE_BYTES: u64 = 128 << 20;
/// The largest path file read (bytes): about four million points.
pub const MAX_PATH_FILE_BYTES: u64 = 128 << 20;

/// The bytes of `path`, refused when there are more than `limit`: never more than `limit + 1`
/// bytes are held, whatever the file is (an endless device included).
pub fn read_bounded(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let mut bytes = Vec::new();
    std::fs::File::open(path)?.take(limit + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("larger than {} MiB, the most this kind of file may hold", limit >> 20),
        ));
    }
    Ok(bytes)
}

/// [`read_bounded`] as UTF-8 text.
pub fn read_text_bounded(path: &Path, limit: u64) -> std::io::Result<String> {
    String::from_utf8(read_bounded(path, limit)?)
        .map_err(|_| std::io::Error::new(std::io::ErrorKind::InvalidData, "not UTF-8 text"))
}

/// Reads a path file: CSV with header `x_m,y_m` (metres, one point per row), optionally an
/// `agent` column (non-negative integer) that splits the rows into one path per agent, and an
/// `index` column that must number each agent's rows 0, 1, 2, … in the file's order. Returns the paths in ascending agent order.
pub fn read_path_csv(path: &Path) -> Result<Vec<Vec<Point>>, PathFileError> {
    read_path_file(path).map(|f| f.paths)
}

/// A path file's paths in ascending agent order, with each agent's `robot` name where the
/// file has that column (one name per agent).
#[derive(Clone, Debug, PartialEq)]
pub struct PathFile {
    /// One path per agent.
    pub paths: Vec<Vec<Point>>,
    /// Each agent's robot name (`None` without a `robot` column).
    pub robots: Vec<Option<String>>,
}

/// [`read_path_csv`] with each agent's `robot` name.
pub fn read_path_file(path: &Path) -> Result<PathFile, PathFileError> {
    // A FIFO or a device would block or never end: only regular files are read.
    if let Ok(meta) = std::fs::metadata(path)
        && !meta.is_file()
    {
        return Err(PathFileError {
            path: path.to_path_buf(),
            line: 0,
            message: "is not a regular file (a folder, FIFO or device); give a CSV file of points".into(),
        });
    }
    let text = read_text_bounded(path, MAX_PATH_FILE_BYTES).map_err(|e| PathFileError {
        path: path.to_path_buf(),
        line: 0,
        message: format!("cannot read path file: {e}"),
    })?;
    parse_path_file(&text, path)
}

/// Parses the text of a path file read from `path` (named in messages); see [`read_path_csv`].
pub fn parse_path_csv(text: &str, path: &Path) -> Result<Vec<Vec<Point>>, PathFileError> {
    parse_path_file(text, path).map(|f| f.paths)
}

/// [`parse_path_csv`] with each agent's `robot` name: every row of an agent must name the
/// same robot.
pub fn parse_path_file(text: &str, path: &Path) -> Result<PathFile, PathFileError> {
    let fail = |line: u64, message: String| PathFileError { path: path.to_path_buf(), line, message };
    let mut reader = csv::ReaderBuilder::new().trim(csv::Trim::All).from_reader(text.as_bytes());
    let headers = reader.headers().map_err(|e| fail(1, format!("bad CSV header: {e}")))?.clone();
    let col = |name: &str| headers.iter().position(|h| h == name);
    let (Some(xi), Some(yi)) = (col("x_m"), col("y_m")) else {
        return Err(fail(
            1,
            format!(
                "header is `{}`; expected columns x_m,y_m (and optionally agent, index)",
                headers.iter().collect::<Vec<_>>().join(",")
            ),
        ));
    };
    if let Some(bad) = headers.iter().find(|h| !["x_m", "y_m", "agent", "robot", "index"].contains(h)) {
        return Err(fail(1, format!("unknown column `{bad}`; allowed: x_m, y_m, agent, robot, index")));
    }
    let (ai, ii, ri) = (col("agent"), col("index"), col("robot"));
    let mut by_agent: std::collections::BTreeMap<u64, Vec<Point>> = Default::default();
    let mut names: std::collections::BTreeMap<u64, String> = Default::default();
    for (k, record) in reader.records().enumerate() {
        let line = k as u64 + 2;
        let record = record.map_err(|e| fail(line, format!("bad CSV row: {e}")))?;
        let num = |i: usize, name: &str| -> Result<f64, PathFileError> {
            let raw = record.get(i).unwrap_or("");
            match raw.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(fail(line, format!("`{name}` = `{raw}` is not a finite number of metres"))),
            }
        };
        let p = Point::new(num(xi, "x_m")?, num(yi, "y_m")?);
        let agent = match ai {
            None => 0,
            Some(i) => {
                let raw = record.get(i).unwrap_or("");
                raw.parse::<u64>()
                    .map_err(|_| fail(line, format!("`agent` = `{raw}` is not a non-negative integer")))?
            }
        };
        if let Some(i) = ri {
            let raw = record.get(i).unwrap_or("");
            let first = names.entry(agent).or_insert_with(|| raw.to_string());
            if first != raw {
                return Err(fail(
                    line,
                    format!("`robot` = `{raw}` where agent {agent}'s earlier rows name `{first}`: one robot per agent"),
                ));
            }
        }
        let points = by_agent.entry(agent).or_default();
        // The index, where given, numbers each agent's points in the file's order: a file
        // sorted otherwise would be read as another path.
        if let Some(i) = ii {
            let raw = record.get(i).unwrap_or("");
            if raw.parse::<usize>().ok() != Some(points.len()) {
                return Err(fail(
                    line,
                    format!(
                        "`index` = `{raw}` where {} was expected: each agent's rows must be in path order, numbered from 0",
                        points.len()
                    ),
                ));
            }
        }
        points.push(p);
    }
    let robots: Vec<Option<String>> = by_agent.keys().map(|a| names.get(a).cloned()).collect();
    let paths: Vec<Vec<Point>> = by_agent.into_values().collect();
    if paths.is_empty() {
        return Err(fail(2, "the file has no points; expected at least one row x_m,y_m".into()));
    }
    Ok(PathFile { paths, robots })
}

/// Writes paths as CSV `agent,index,x_m,y_m` (the format [`read_path_csv`] reads).
pub fn path_csv(paths: &[Vec<Point>]) -> Vec<u8> {
    fleet_path_csv(paths, &[])
}

/// A fleet's plan as CSV: `agent,robot,index,x_m,y_m`, the robot named by `names[agent]`
/// (the `robot` column is left out when `names` is empty; readers ignore it).
pub fn fleet_path_csv(paths: &[Vec<Point>], names: &[String]) -> Vec<u8> {
    if names.is_empty() {
        return plain_path_csv(paths);
    }
    let mut out = String::from("agent,robot,index,x_m,y_m\n");
    for (a, path) in paths.iter().enumerate() {
        for (i, p) in path.iter().enumerate() {
            out.push_str(&format!("{a},{},{i},{},{}\n", names[a], p.x, p.y));
        }
    }
    out.into_bytes()
}

fn plain_path_csv(paths: &[Vec<Point>]) -> Vec<u8> {
    let mut out = String::from("agent,index,x_m,y_m\n");
    for (a, path) in paths.iter().enumerate() {
        for (i, p) in path.iter().enumerate() {
            out.push_str(&format!("{a},{i},{},{}\n", p.x, p.y));
        }
    }
    out.into_bytes()
}

/// A number for messages: as typed when ordinary, in scientific notation when huge or tiny
/// (`1e300`, not three hundred digits).
pub fn short_number(v: f64) -> String {
    if v != 0.0 && v.is_finite() && !(1e-4..1e6).contains(&v.abs()) { format!("{v:e}") } else { format!("{v}") }
}

/// A byte count for messages (`10.6 GB`).
pub fn human_bytes(bytes: f64) -> String {
    match bytes {
        b if b >= 1e12 => format!("{:.3e} bytes", b),
        b if b >= 1e9 => format!("{:.1} GB", b / 1e9),
        b if b >= 1e6 => format!("{:.1} MB", b / 1e6),
        b if b >= 1e3 => format!("{:.0} kB", b / 1e3),
        // Below a kilobyte (a limit such as `--max-memory 1`): whole bytes, never "0 kB".
        b if b.round() == 1.0 => "1 byte".to_string(),
        b => format!("{:.0} bytes", b),
    }
}

/// Parses a byte count as users type it: `8G`, `512M`, `1.5GB`, `2GiB`, `4096` (decimal units
/// k, M, G, T = 10³…; binary units Ki, Mi, Gi, Ti = 2¹⁰…; an optional trailing `B`).
pub fn parse_bytes(text: &str) -> Result<u64, String> {
    let t = text.trim();
    let split = t.find(|c: char| !(c.is_ascii_digit() || c == '.')).unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let unit = unit.trim();
    let unit = unit.strip_suffix(['B', 'b']).unwrap_or(unit);
    let factor: f64 = match unit {
        "" => 1.0,
        "k" | "K" => 1e3,
        "M" | "m" => 1e6,
        "G" | "g" => 1e9,
        "T" | "t" => 1e12,
        "Ki" | "ki" => 1024.0,
        "Mi" | "mi" => 1024f64.powi(2),
        "Gi" | "gi" => 1024f64.powi(3),
        "Ti" | "ti" => 1024f64.powi(4),
        _ => return Err(format!("`{text}`: unknown unit `{unit}`; write e.g. 8G, 512M, 2GiB or a number of bytes")),
    };
    let v: f64 = number.parse().map_err(|_| format!("`{text}` is not a size; write e.g. 8G, 512M or 2GiB"))?;
    let bytes = v * factor;
    if !(1.0..1.8e19).contains(&bytes) {
        return Err(format!("`{text}` is out of range: at least 1 byte and below 1.8e19"));
    }
    Ok(bytes.round() as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_numbers_stay_short() {
        assert_eq!(short_number(60.0), "60");
        assert_eq!(short_number(0.6), "0.6");
        assert_eq!(short_number(1e300), "1e300");
        assert_eq!(short_number(-2.5e-7), "-2.5e-7");
        assert_eq!(short_number(0.0), "0");
    }

    #[test]
    fn byte_counts_read_as_people_write_them() {
        assert_eq!(human_bytes(10.6e9), "10.6 GB");
        assert_eq!(human_bytes(15.2e6), "15.2 MB");
        assert_eq!(human_bytes(6.4e13), "6.400e13 bytes");
        assert_eq!(human_bytes(2048.0), "2 kB");
        assert_eq!(human_bytes(1.0), "1 byte");
        assert_eq!(human_bytes(512.0), "512 bytes");
        assert!(memory::available_memory().is_none_or(|b| b > 0));
    }

    #[test]
    fn sizes_read_as_people_type_them() {
        for (text, bytes) in [
            ("4096", 4096),
            ("8G", 8_000_000_000),
            ("512M", 512_000_000),
            ("1.5GB", 1_500_000_000),
            ("2GiB", 2 * 1024 * 1024 * 1024),
            ("64 Ki", 65_536),
        ] {
            assert_eq!(parse_bytes(text), Ok(bytes), "{text}");
        }
        for bad in ["", "G", "8X", "-1G", "0", "1e30"] {
            assert!(parse_bytes(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn a_missing_path_file_has_no_line_number() {
        let e = read_path_csv(Path::new("/nonexistent/p.csv")).unwrap_err().to_string();
        assert!(e.starts_with("/nonexistent/p.csv: cannot read path file"), "{e}");
    }

    #[test]
    fn path_csv_round_trip_and_errors() {
        let dir = tempfile::tempdir().unwrap();
        let f = dir.path().join("p.csv");
        let paths = vec![vec![Point::new(1.0, 2.0), Point::new(3.5, 4.25)], vec![Point::new(0.1, 0.2)]];
        std::fs::write(&f, path_csv(&paths)).unwrap();
        assert_eq!(read_path_csv(&f).unwrap(), paths);
        for (text, needle) in [
            ("x,y\n1,2\n", "expected columns x_m,y_m"),
            ("x_m,y_m\n1,abc\n", ":2: `y_m` = `abc`"),
            ("x_m,y_m\n1,2\n1,inf\n", ":3: `y_m` = `inf`"),
            ("x_m,y_m\n", "no points"),
            ("x_m,y_m,z\n1,2,3\n", "unknown column `z`"),
        ] {
            std::fs::write(&f, text).unwrap();
            let e = read_path_csv(&f).unwrap_err().to_string();
            assert!(e.contains(needle), "{e}");
        }
    }
}
