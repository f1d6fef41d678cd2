//! ROS map_server files (YAML + PGM/PNG) and bare map images.
//!
//! The interpretation of pixel values follows map_server: with `negate: 0` the occupancy
//! probability of a pixel `x` is `p = (255 − x) / 255`; `p > occupied_thresh` is occupied,
//! `p < free_thresh` is free, anything else is unknown (`trinary`, and the intermediate
//! probabilities of `scale`); in `scale` mode a fully transparent pixel is unknown; `raw` reads
//! `x` as a percentage.

use super::presets::{PRESET_NAMES, preset};
use super::{CellState, GridMap, MapError};
use crate::geom::Point;
use serde::Deserialize;
use std::io::Write;
use std::path::{Path, PathBuf};

/// How map_server turns pixel values into occupancy (`mode` in the YAML).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PixelMode {
    /// Free / occupied / unknown by the two thresholds (the default).
    Trinary,
    /// Like trinary; intermediate values and transparent pixels are unknown.
    Scale,
    /// The pixel value is the occupancy in percent.
    Raw,
    /// Two classes, for bare images drawn without an unknown class (the ipa room-segmentation
    /// benchmark counts grey below 250 as obstacle): grey at or above `free_from` is free,
    /// anything darker occupied. Set by `map.free_threshold` / `--free-threshold`, never by a
    /// YAML.
    #[serde(skip)]
    Threshold {
        /// The darkest grey value that is free.
        free_from: u8,
    },
}

/// How a map given as a bare PGM/PNG image (no ROS YAML beside it) is read.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BareImage {
    /// Metres per pixel; required for a bare image.
    pub resolution: Option<f64>,
    /// With `Some(t)`: grey ≥ `t` is free and darker pixels are occupied ([`PixelMode::Threshold`]);
    /// `None`: map_server's default thresholds (occupancy 0.65 / 0.196, i.e. grey ≥ 206 free,
    /// ≤ 89 occupied, unknown between).
    pub free_threshold: Option<u8>,
}

impl BareImage {
    /// A bare image at `resolution` read with map_server's default thresholds.
    pub fn at(resolution: Option<f64>) -> Self {
        Self { resolution, free_threshold: None }
    }
}

/// Reads `negate` written either as `0`/`1` or as a boolean.
#[derive(Deserialize)]
#[serde(untagged)]
enum Flag {
    Int(i64),
    Bool(bool),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RosYaml {
    image: String,
    resolution: f64,
    origin: Vec<f64>,
    #[serde(default = "no_flag")]
    negate: Flag,
    occupied_thresh: f64,
    free_thresh: f64,
    #[serde(default = "trinary")]
    mode: PixelMode,
}

fn no_flag() -> Flag {
    Flag::Int(0)
}
fn trinary() -> PixelMode {
    PixelMode::Trinary
}

/// How to read pixels of an image.
#[derive(Clone, Copy, Debug)]
pub struct PixelRule {
    /// `negate` of the YAML.
    pub negate: bool,
    /// `occupied_thresh` in [0, 1].
    pub occupied_thresh: f64,
    /// `free_thresh` in [0, 1].
    pub free_thresh: f64,
    /// `mode` of the YAML.
    pub mode: PixelMode,
}

impl Default for PixelRule {
    /// map_server's usual values: 0.65 / 0.196, trinary, not negated.
    fn default() -> Self {
        Self { negate: false, occupied_thresh: 0.65, free_thresh: 0.196, mode: PixelMode::Trinary }
    }
}

impl PixelRule {
    /// Classifies one pixel (grey value and alpha).
    pub fn classify(&self, value: u8, alpha: u8) -> CellState {
        if let PixelMode::Threshold { free_from } = self.mode {
            return if value >= free_from { CellState::Free } else { CellState::Occupied };
        }
        if self.mode == PixelMode::Scale && alpha == 0 {
            return CellState::Unknown;
        }
        if self.mode == PixelMode::Raw {
            let pct = f64::from(value);
            return if pct <= self.free_thresh * 100.0 {
                CellState::Free
            } else if pct >= self.occupied_thresh * 100.0 && pct <= 100.0 {
                CellState::Occupied
            } else {
                CellState::Unknown
            };
        }
        let x = f64::from(value);
        let p = if self.negate { x / 255.0 } else { (255.0 - x) / 255.0 };
        if p > self.occupied_thresh {
            CellState::Occupied
        } else if p < self.free_thresh {
            CellState::Free
        } else {
            CellState::Unknown
        }
    }
}

fn yaml_error(path: &Path, message: impl Into<String>) -> MapError {
    MapError::Yaml { path: path.to_path_buf(), message: message.into() }
}

/// The metadata of a ROS map_server YAML file, checked.
#[derive(Clone, Debug)]
pub struct RosMeta {
    /// The image file, resolved against the YAML's folder.
    pub image: PathBuf,
    /// Metres per pixel.
    pub resolution: f64,
    /// Position of the lower-left pixel's corner in metres.
    pub origin: Point,
    /// How pixel values become occupancy.
    pub rule: PixelRule,
}

/// The largest map accepted, in cells (16 384 × 16 384): checked from the image header before
/// any pixel is decoded, so a small file declaring a huge image is refused without allocating.
pub const MAX_MAP_CELLS: u64 = 1 << 28;

/// Parses and checks the text of a ROS map_server YAML file read from `path` (which names it in
/// messages and resolves the image path).
pub fn parse_ros_yaml(text: &str, path: &Path) -> Result<RosMeta, MapError> {
    let y: RosYaml = serde_norway::from_str(text).map_err(|e| {
        let expected =
            "expected keys image, resolution, origin, negate, occupied_thresh, free_thresh, mode (trinary|scale|raw)";
        yaml_error(path, format!("malformed map YAML: {e} ({expected})"))
    })?;
    if !(y.resolution.is_finite() && y.resolution > 0.0) {
        return Err(yaml_error(
            path,
            format!("`resolution` = {} must be a number of metres per cell > 0", crate::io::short_number(y.resolution)),
        ));
    }
    if y.origin.len() != 3 || y.origin.iter().any(|v| !v.is_finite()) {
        return Err(yaml_error(path, format!("`origin` = {:?} must be [x, y, yaw] with finite numbers", y.origin)));
    }
    if y.origin[2].abs() > 1e-12 {
        return Err(yaml_error(
            path,
            format!("`origin` yaw = {} is not supported: only axis-aligned maps (yaw 0)", y.origin[2]),
        ));
    }
    for (field, v) in [("occupied_thresh", y.occupied_thresh), ("free_thresh", y.free_thresh)] {
        if !(0.0..=1.0).contains(&v) {
            return Err(yaml_error(path, format!("`{field}` = {v} must lie in [0, 1]")));
        }
    }
    if y.free_thresh > y.occupied_thresh {
        return Err(yaml_error(
            path,
            format!("`free_thresh` = {} must not exceed `occupied_thresh` = {}", y.free_thresh, y.occupied_thresh),
        ));
    }
    let negate = match y.negate {
        Flag::Int(0) | Flag::Bool(false) => false,
        Flag::Int(1) | Flag::Bool(true) => true,
        Flag::Int(v) => return Err(yaml_error(path, format!("`negate` = {v} must be 0 or 1"))),
    };
    if y.image.trim().is_empty() {
        return Err(yaml_error(path, "`image` is empty: it must name the map's PGM or PNG file"));
    }
    Ok(RosMeta {
        image: path.parent().unwrap_or(Path::new(".")).join(&y.image),
        resolution: y.resolution,
        origin: Point::new(y.origin[0], y.origin[1]),
        rule: PixelRule { negate, occupied_thresh: y.occupied_thresh, free_thresh: y.free_thresh, mode: y.mode },
    })
}

/// Loads a ROS map_server YAML file and the image it names (relative to the YAML's folder).
pub fn load_ros_yaml(path: &Path) -> Result<GridMap, MapError> {
    let text = crate::io::read_text_bounded(path, crate::io::MAX_TEXT_FILE_BYTES)
        .map_err(|source| MapError::Io { path: path.to_path_buf(), source })?;
    let meta = parse_ros_yaml(&text, path)?;
    let name = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let bytes = crate::io::read_bounded(&meta.image, crate::io::MAX_IMAGE_FILE_BYTES)
        .map_err(|source| MapError::Io { path: meta.image.clone(), source })?;
    decode_map_image(&bytes, &meta.image, &name, meta.resolution, meta.origin, meta.rule)
}

/// Loads a bare PGM/PNG image at `resolution` m per pixel, origin (0, 0): map_server's default
/// thresholds, or two classes split at `free_threshold` ([`BareImage`]).
pub fn load_image(path: &Path, resolution: f64, free_threshold: Option<u8>) -> Result<GridMap, MapError> {
    let name = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let bytes = crate::io::read_bounded(path, crate::io::MAX_IMAGE_FILE_BYTES)
        .map_err(|source| MapError::Io { path: path.to_path_buf(), source })?;
    let rule = match free_threshold {
        Some(free_from) => PixelRule { mode: PixelMode::Threshold { free_from }, ..PixelRule::default() },
        None => PixelRule::default(),
    };
    decode_map_image(&bytes, path, &name, resolution, Point::origin(), rule)
}

/// Decodes the bytes of a PGM or PNG image (read from `path`, named in messages) into a map.
/// The image's size is read from its header first and refused above [`MAX_MAP_CELLS`].
pub fn decode_map_image(
    bytes: &[u8],
    path: &Path,
    name: &str,
    resolution: f64,
    origin: Point,
    rule: PixelRule,
) -> Result<GridMap, MapError> {
    let image_error = |message: String| MapError::Image { path: path.to_path_buf(), message };
    let reader = || {
        image::io::Reader::new(std::io::Cursor::new(bytes))
            .with_guessed_format()
            .map_err(|e| image_error(e.to_string()))
    };
    let (w, h) = reader()?.into_dimensions().map_err(|e| image_error(e.to_string()))?;
    let cells_wanted = u64::from(w) * u64::from(h);
    if cells_wanted > MAX_MAP_CELLS || w == 0 || h == 0 {
        return Err(image_error(format!(
            "the image is {w} × {h} pixels; a map must have between 1 and {MAX_MAP_CELLS} cells"
        )));
    }
    let mut limited = reader()?;
    let mut limits = image::io::Limits::default();
    // The decoded image (up to 4 bytes per pixel in the decoder) and its grey-alpha copy.
    limits.max_alloc = Some(16 * MAX_MAP_CELLS);
    limited.limits(limits);
    let img = limited.decode().map_err(|e| image_error(e.to_string()))?;
    let la = img.to_luma_alpha8();
    drop(img);
    let (w, h) = (la.width() as usize, la.height() as usize);
    let mut cells = vec![CellState::Unknown; w * h];
    for (x, y, px) in la.enumerate_pixels() {
        let row = h - 1 - y as usize; // image row 0 is the top
        cells[row * w + x as usize] = rule.classify(px.0[0], px.0[1]);
    }
    GridMap::new(name, w, h, resolution, origin, cells).map_err(|e| match e {
        MapError::NoFreeCell { .. } => MapError::NoFreeCell { source_name: path.display().to_string() },
        other => other,
    })
}

/// Resolves `--map`: a preset name, a ROS YAML file, or a bare image read as `image` says.
/// A free threshold or a resolution is refused for anything but a bare image: a YAML and a
/// preset carry their own.
pub fn load_map(spec: &str, image: &BareImage) -> Result<GridMap, MapError> {
    let path = PathBuf::from(spec);
    let ext = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
    // Settings of a bare image only: a YAML and a preset bring their own.
    let bare = preset(spec).is_none() && matches!(ext.as_str(), "pgm" | "png");
    let only_bare = [
        (
            "free_threshold",
            image.free_threshold.map(|t| t.to_string()),
            "a free threshold applies to a bare PGM/PNG image only (a ROS map YAML sets free_thresh and occupied_thresh; presets are drawn in three classes)",
        ),
        (
            "resolution",
            image.resolution.map(|r| r.to_string()),
            "a resolution applies to a bare PGM/PNG image only (a ROS map YAML and a preset give their own); leave it out",
        ),
    ];
    if let Some((field, Some(value), allowed)) = only_bare.into_iter().find(|(_, v, _)| v.is_some() && !bare) {
        return Err(MapError::OutOfRange { source_name: spec.to_string(), field, value, allowed });
    }
    if let Some(m) = preset(spec) {
        return Ok(m);
    }
    match ext.as_str() {
        "yaml" | "yml" => load_ros_yaml(&path),
        "pgm" | "png" => match image.resolution {
            Some(r) => load_image(&path, r, image.free_threshold),
            None => Err(MapError::MissingResolution { source_name: spec.to_string() }),
        },
        _ => Err(MapError::UnknownMap { name: spec.to_string(), presets: PRESET_NAMES.join(", ") }),
    }
}

/// Writes `map` as `<dir>/<stem>.yaml` + `<dir>/<stem>.pgm` in map_server's trinary convention
/// (free 254, occupied 0, unknown 205).
pub fn write_ros(map: &GridMap, dir: &Path, stem: &str) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    let mut pgm = format!("P5\n{} {}\n255\n", map.cols(), map.rows()).into_bytes();
    for row in (0..map.rows()).rev() {
        for col in 0..map.cols() {
            pgm.push(match map.state(row, col) {
                CellState::Free => 254,
                CellState::Occupied => 0,
                CellState::Unknown => 205,
            });
        }
    }
    crate::io::write_atomic(&dir.join(format!("{stem}.pgm")), &pgm)?;
    let mut yaml = Vec::new();
    writeln!(yaml, "image: {stem}.pgm")?;
    writeln!(yaml, "mode: trinary")?;
    writeln!(yaml, "resolution: {}", map.resolution())?;
    writeln!(yaml, "origin: [{:?}, {:?}, 0.0]", map.origin().x, map.origin().y)?;
    writeln!(yaml, "negate: 0")?;
    writeln!(yaml, "occupied_thresh: 0.65")?;
    writeln!(yaml, "free_thresh: 0.196")?;
    crate::io::write_atomic(&dir.join(format!("{stem}.yaml")), &yaml)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trinary_thresholds_follow_map_server() {
        let rule = PixelRule::default();
        assert_eq!(rule.classify(254, 255), CellState::Free);
        assert_eq!(rule.classify(0, 255), CellState::Occupied);
        assert_eq!(rule.classify(205, 255), CellState::Unknown);
        let neg = PixelRule { negate: true, ..rule };
        assert_eq!(neg.classify(0, 255), CellState::Free);
        let scale = PixelRule { mode: PixelMode::Scale, ..rule };
        assert_eq!(scale.classify(254, 0), CellState::Unknown);
        let raw = PixelRule { mode: PixelMode::Raw, ..rule };
        assert_eq!(raw.classify(0, 255), CellState::Free);
        assert_eq!(raw.classify(100, 255), CellState::Occupied);
        assert_eq!(raw.classify(255, 255), CellState::Unknown);
    }

    /// map_server's defaults leave grey 90–205 unknown; a free threshold splits at its value
    /// into two classes, whatever the alpha.
    #[test]
    fn a_free_threshold_reads_two_classes() {
        use CellState::{Free as F, Occupied as O, Unknown as U};
        let ros = PixelRule::default();
        let ipa = PixelRule { mode: PixelMode::Threshold { free_from: 250 }, ..ros };
        for (grey, by_ros, by_ipa) in
            [(0, O, O), (89, O, O), (90, U, O), (205, U, O), (206, F, O), (249, F, O), (250, F, F), (255, F, F)]
        {
            assert_eq!((ros.classify(grey, 255), ipa.classify(grey, 0)), (by_ros, by_ipa), "grey {grey}");
        }
    }

    /// A free threshold is refused where no bare image is read.
    #[test]
    fn a_free_threshold_needs_a_bare_image() {
        let image = BareImage { resolution: None, free_threshold: Some(250) };
        for source in ["office", "map.yaml"] {
            let e = load_map(source, &image).unwrap_err().to_string();
            assert!(e.contains("`free_threshold` = 250 is out of range: a free threshold applies to a bare"), "{e}");
        }
    }

    #[test]
    fn round_trip_through_ros_files() {
        let dir = tempfile::tempdir().unwrap();
        for name in PRESET_NAMES {
            let m = preset(name).unwrap();
            write_ros(&m, dir.path(), name).unwrap();
            let back = load_ros_yaml(&dir.path().join(format!("{name}.yaml"))).unwrap();
            assert_eq!(back.cells(), m.cells(), "{name}");
            assert_eq!(back.resolution(), m.resolution());
            assert_eq!(back.origin(), m.origin());
        }
    }

    #[test]
    fn bad_yaml_names_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("bad.yaml");
        std::fs::write(
            &p,
            "image: x.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nfree_thresh: 0.2\noccupied_thresh: 0.6\nmode: fuzzy\n",
        )
        .unwrap();
        let e = load_ros_yaml(&p).unwrap_err().to_string();
        assert!(e.contains("bad.yaml") && e.contains("fuzzy"), "{e}");
        std::fs::write(
            &p,
            "image: x.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nfree_thresh: 0.2\noccupied_thresh: 0.6\n",
        )
        .unwrap();
        let e = load_ros_yaml(&p).unwrap_err().to_string();
        assert!(e.contains("x.pgm"), "{e}");
    }
}
