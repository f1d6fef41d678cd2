//! The experiment file as TOML, both ways: its shared keys typed here, its planner sections
//! looked up in the registry ([`super::super::registry::planner_sections`]), each read and
//! written by its declaration. The file's keys come in one order, the one the written
//! `config.toml` has always had (and a run id hashes): the shared keys and sections, the planner
//! sections placed before `[budget]`, `[budget]`, those placed after it, then `[output]`,
//! `[[robots]]`, `[fleet]` and `[plugins]`. A key the file does not know is refused by name,
//! with every key it knows.

use super::ExperimentFile;
use crate::experiment::registry::planner_sections;
use crate::planner::section::{ItemSer, Placement, PlannerSections, SectionSpec};
use serde::de::{DeserializeSeed, Error as _, MapAccess, Visitor};
use serde::ser::{Error as _, SerializeStruct};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A key of the file: a shared one, or a planner section.
#[derive(Clone, Copy)]
enum Key {
    /// A key the file's own type reads.
    Shared(&'static str),
    /// A planner's section.
    Section(&'static dyn SectionSpec),
}

impl Key {
    fn name(self) -> &'static str {
        match self {
            Key::Shared(name) => name,
            Key::Section(s) => s.name(),
        }
    }
}

/// The shared keys before the planner sections.
const BEFORE_SECTIONS: [&str; 6] = ["seed", "planner", "map", "robot", "stations", "scorer"];
/// The shared keys after the planner sections placed after `[budget]`.
const AFTER_SECTIONS: [&str; 4] = ["output", "robots", "fleet", "plugins"];

/// Whether `name` is a key of the file's own.
pub(super) fn is_shared(name: &str) -> bool {
    BEFORE_SECTIONS.contains(&name) || name == "budget" || AFTER_SECTIONS.contains(&name)
}

/// Every key of a file with the planner sections `sections`, in the file's order.
fn keys(sections: &[&'static dyn SectionSpec]) -> Vec<Key> {
    let placed = |p: Placement| sections.iter().filter(move |s| s.placement() == p).map(|&s| Key::Section(s));
    BEFORE_SECTIONS
        .iter()
        .map(|&k| Key::Shared(k))
        .chain(placed(Placement::BeforeBudget))
        .chain(std::iter::once(Key::Shared("budget")))
        .chain(placed(Placement::AfterBudget))
        .chain(AFTER_SECTIONS.iter().map(|&k| Key::Shared(k)))
        .collect()
}

/// The planner sections a file holds when its text sets none of them: those every file holds,
/// at their defaults.
pub(super) fn default_sections() -> PlannerSections {
    let mut held = PlannerSections::default();
    for section in planner_sections().into_iter().filter(|s| s.always_held()) {
        held.insert_default(section);
    }
    held
}

impl Serialize for ExperimentFile {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let keys = keys(&planner_sections());
        let mut out = s.serialize_struct("ExperimentFile", keys.len())?;
        for key in keys {
            match key {
                Key::Section(section) => match self.sections.get(section.name()) {
                    Some(value) => {
                        let item = value.to_item().map_err(S::Error::custom)?;
                        out.serialize_field(section.name(), &ItemSer(&item))?;
                    }
                    None => out.skip_field(section.name())?,
                },
                Key::Shared(name) => self.serialize_shared(name, &mut out)?,
            }
        }
        out.end()
    }
}

impl ExperimentFile {
    /// Writes the shared key `name` (the optional ones only where set).
    fn serialize_shared<S: SerializeStruct>(&self, name: &'static str, out: &mut S) -> Result<(), S::Error> {
        match name {
            "seed" => out.serialize_field(name, &self.seed),
            "planner" => out.serialize_field(name, &self.planner),
            "map" => out.serialize_field(name, &self.map),
            "robot" => out.serialize_field(name, &self.robot),
            "stations" => out.serialize_field(name, &self.stations),
            "scorer" => out.serialize_field(name, &self.scorer),
            "budget" => out.serialize_field(name, &self.budget),
            "output" => out.serialize_field(name, &self.output),
            "robots" if !self.robots.is_empty() => out.serialize_field(name, &self.robots),
            "fleet" if self.fleet.is_some() => out.serialize_field(name, &self.fleet),
            "plugins" if !self.plugins.is_empty() => out.serialize_field(name, &self.plugins),
            _ => out.skip_field(name),
        }
    }
}

impl<'de> Deserialize<'de> for ExperimentFile {
    /// Every key optional (the defaults are the thesis's settings); an unknown key refused.
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_map(FileVisitor(keys(&planner_sections())))
    }
}

/// Reads a file's table, knowing its keys.
struct FileVisitor(Vec<Key>);

impl<'de> Visitor<'de> for FileVisitor {
    type Value = ExperimentFile;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("an experiment file's table")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<ExperimentFile, A::Error> {
        // The sections every file holds start at their defaults; the text's replace them.
        let mut file = ExperimentFile::default();
        while let Some(key) = map.next_key_seed(KeySeed(&self.0))? {
            match key {
                Key::Section(section) => {
                    let value = map.next_value_seed(SectionSeed(section))?;
                    file.sections.insert(section.name(), value);
                }
                Key::Shared(name) => file.read_shared(name, &mut map)?,
            }
        }
        Ok(file)
    }
}

impl ExperimentFile {
    /// Reads the value of the shared key `name`.
    fn read_shared<'de, A: MapAccess<'de>>(&mut self, name: &str, map: &mut A) -> Result<(), A::Error> {
        match name {
            "seed" => self.seed = map.next_value()?,
            "planner" => self.planner = map.next_value()?,
            "map" => self.map = map.next_value()?,
            "robot" => self.robot = map.next_value()?,
            "stations" => self.stations = map.next_value()?,
            "scorer" => self.scorer = map.next_value()?,
            "budget" => self.budget = map.next_value()?,
            "output" => self.output = map.next_value()?,
            "robots" => self.robots = map.next_value()?,
            "fleet" => self.fleet = map.next_value()?,
            "plugins" => self.plugins = map.next_value()?,
            other => return Err(A::Error::custom(format!("`{other}` is no key of an experiment file"))),
        }
        Ok(())
    }
}

/// Reads a key, refusing one the file does not know in serde's words, with every key it knows.
struct KeySeed<'a>(&'a [Key]);

impl<'de> DeserializeSeed<'de> for KeySeed<'_> {
    type Value = Key;

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Key, D::Error> {
        let name = String::deserialize(d)?;
        self.0.iter().copied().find(|k| k.name() == name).ok_or_else(|| {
            let known: Vec<String> = self.0.iter().map(|k| format!("`{}`", k.name())).collect();
            D::Error::custom(format!("unknown field `{name}`, expected one of {}", known.join(", ")))
        })
    }
}

/// Reads a planner section's table by its declaration.
struct SectionSeed(&'static dyn SectionSpec);

impl<'de> DeserializeSeed<'de> for SectionSeed {
    type Value = Box<dyn crate::planner::section::SectionValue>;

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Self::Value, D::Error> {
        let value = toml::Value::deserialize(d)?;
        self.0.read_value(value).map_err(D::Error::custom)
    }
}

/// The error `e` of reading `text` (whose table is `table`), placed at the key that caused it
/// where it lies in a planner section: a section is read from its table as a whole, so the
/// error of the whole read names the section's line; read alone from the text, the section
/// names the line of the bad value, and that error replaces the other when it says the same.
pub(super) fn in_place(text: &str, table: &toml::Table, e: toml::de::Error) -> toml::de::Error {
    planner_sections()
        .into_iter()
        .filter(|s| table.contains_key(s.name()))
        .find_map(|s| s.check_text(text).err().filter(|precise| precise.message() == e.message()))
        .unwrap_or(e)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::planner::entry::FileSections;

    /// The keys in the order the derived file type had them: the message of an unknown key
    /// and the written file's order are what they were.
    #[test]
    fn an_unknown_key_is_refused_with_every_key_in_the_files_order() {
        let e = ExperimentFile::parse("seed = 2\ncolour = 3\n", "t.toml").unwrap_err().to_string();
        assert!(
            e.contains(
                "t.toml:2: unknown field `colour`, expected one of `seed`, `planner`, `map`, `robot`, `stations`, \
                 `scorer`, `thesis`, `waypoint`, `pattern`, `cell_order`, `layouts`, `budget`, `retrain`, `output`, \
                 `robots`, `fleet`, `plugins`"
            ),
            "{e}"
        );
    }

    /// A planner section's own checks refuse its unknown keys and bad values, at the line of
    /// the value, as the typed section says.
    #[test]
    fn a_planner_sections_errors_name_its_line_and_its_types_words() {
        let bad_value = "seed = 2\n[thesis]\npop_min = 10\nc_len = \"long\"\n";
        let e = ExperimentFile::parse(bad_value, "t.toml").unwrap_err().to_string();
        assert!(e.starts_with("t.toml:4: invalid type: string \"long\", expected f64"), "{e}");
        let unknown = "[cell_order]\nsolver = \"ga\"\ncolour = 1\n";
        let e = ExperimentFile::parse(unknown, "t.toml").unwrap_err().to_string();
        assert!(e.starts_with("t.toml:3: unknown field `colour`, expected one of `solver`"), "{e}");
        // From a table (a study's run) the same words, without a line.
        let table: toml::Table = unknown.parse().unwrap();
        let e = toml::Value::Table(table).try_into::<ExperimentFile>().unwrap_err();
        assert!(e.message().starts_with("unknown field `colour`, expected one of `solver`"), "{e}");
    }

    /// The sections every file holds are held at their defaults, the others only where written,
    /// and a file reads back as it was written.
    #[test]
    fn sections_are_held_as_declared_and_read_back_as_written() {
        let file = ExperimentFile::parse("planner = \"spiral\"\n", "t.toml").unwrap();
        let held: Vec<&str> =
            planner_sections().into_iter().map(|s| s.name()).filter(|n| file.section(n).is_some()).collect();
        assert_eq!(held, ["thesis", "waypoint", "pattern"]);
        let text =
            "seed = 4\n[retrain]\nat_iteration = 7\n[cell_order]\nsolver = \"exact\"\n[pattern]\nangle_deg = 30.0\n";
        let file = ExperimentFile::parse(text, "t.toml").unwrap();
        let written = toml::to_string(&file).unwrap();
        let order: Vec<usize> =
            ["[thesis]", "[waypoint]", "[pattern]", "[cell_order]", "[budget]", "[retrain]", "[output]"]
                .iter()
                .map(|t| written.find(t).unwrap_or_else(|| panic!("{t} in {written}")))
                .collect();
        assert!(order.windows(2).all(|w| w[0] < w[1]), "{written}");
        assert!(written.contains("angle_deg = 30.0"), "{written}");
        assert_eq!(ExperimentFile::parse(&written, "t.toml").unwrap(), file);
        assert_ne!(ExperimentFile::parse("seed = 4\n", "t.toml").unwrap(), file);
    }
}
