//! A planner's own section of an experiment file (`[thesis]`, `[cell_order]`, …), declared by
//! the planner's entry ([`super::entry::PlannerEntry::sections`]) as a [`Section`] of its
//! section type. The declaration is all the experiment file needs: it holds the sections of
//! every registered planner generically ([`PlannerSections`]), parses each from the file's
//! table with the section type's own checks (unknown keys refused), writes it into the written
//! `config.toml` where the declaration places it, and lists its keys for the warnings about
//! keys nothing reads.

use serde::Serialize;
use serde::de::DeserializeOwned;
use std::any::{Any, TypeId};
use std::collections::BTreeMap;
use std::fmt::Debug;
use std::marker::PhantomData;

/// Where the written `config.toml` places a planner section among the shared ones.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Placement {
    /// Before `[budget]`, after `[scorer]` (where a new section goes).
    BeforeBudget,
    /// After `[budget]`, before `[output]` (`[retrain]`, which files have written there since
    /// it was added: moving it would change the run ids of the committed studies).
    AfterBudget,
}

/// A section's value as an experiment file holds it: any typed section that clones, compares,
/// prints and serialises.
pub trait SectionValue: Any + Debug + Send + Sync {
    /// The value, to be read as its own type.
    fn as_any(&self) -> &dyn Any;
    /// The value, to be changed as its own type.
    fn as_any_mut(&mut self) -> &mut dyn Any;
    /// A copy.
    fn clone_box(&self) -> Box<dyn SectionValue>;
    /// Whether `other` is the same type and value.
    fn eq_dyn(&self, other: &dyn SectionValue) -> bool;
    /// The value as a TOML table in the order its type writes its keys, or why it cannot be.
    fn to_item(&self) -> Result<toml_edit::Item, String>;
}

impl<T: Any + Debug + Clone + PartialEq + Serialize + Send + Sync> SectionValue for T {
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
    fn clone_box(&self) -> Box<dyn SectionValue> {
        Box::new(self.clone())
    }
    fn eq_dyn(&self, other: &dyn SectionValue) -> bool {
        other.as_any().downcast_ref::<T>() == Some(self)
    }
    fn to_item(&self) -> Result<toml_edit::Item, String> {
        let doc = toml_edit::ser::to_document(self).map_err(|e| e.to_string())?;
        Ok(toml_edit::Item::Table(doc.as_table().clone()))
    }
}

/// A planner section as its entry declares it, whatever its type: what the experiment file
/// needs to read, hold, write and explain it.
pub trait SectionSpec: Send + Sync {
    /// The section's name (`thesis` for `[thesis]`).
    fn name(&self) -> &'static str;
    /// Who reads it, as the warnings say it ("only the thesis GA reads").
    fn readers(&self) -> &'static str;
    /// Where the written `config.toml` places it.
    fn placement(&self) -> Placement;
    /// Whether a file holds it (at its defaults) even where the text leaves it out, so that
    /// the written `config.toml` always shows it; false for a section a file holds only where
    /// it is written.
    fn always_held(&self) -> bool;
    /// The section type's name and the source that declares it, for the reference of the keys.
    fn source(&self) -> (&'static str, &'static str);
    /// The types of the section's own tables, declared in the same source.
    fn tables(&self) -> &'static [&'static str];
    /// The section type.
    fn type_id(&self) -> TypeId;
    /// The section at its defaults, if it has them (a section with a required key has none).
    fn default_value(&self) -> Option<Box<dyn SectionValue>>;
    /// The section from its TOML table, unknown keys refused; the message is the type's own.
    fn read_value(&self, value: toml::Value) -> Result<Box<dyn SectionValue>, String>;
    /// The section as the TOML `text` writes it, checked alone, with the error's place in the
    /// text (the file's other keys are not looked at).
    fn check_text(&self, text: &str) -> Result<(), toml::de::Error>;
}

/// The declaration of a planner section of type `T`: a `static` of the planner's module, which
/// its entry lists, and through which the planner reads its section of a file.
pub struct Section<T> {
    name: &'static str,
    readers: &'static str,
    placement: Placement,
    always_held: bool,
    type_name: &'static str,
    tables: &'static [&'static str],
    source: &'static str,
    default: Option<fn() -> T>,
}

/// What declares a [`Section`]: its name, its readers (as warnings say them), where it is
/// written, whether every file holds it, and its type's name with the source declaring it.
#[derive(Clone, Copy, Debug)]
pub struct SectionDecl {
    /// The section's name.
    pub name: &'static str,
    /// Who reads it, as the warnings say it.
    pub readers: &'static str,
    /// Where the written `config.toml` places it.
    pub placement: Placement,
    /// Whether every file holds it, at its defaults where the text leaves it out.
    pub always_held: bool,
    /// The section type's name as its source declares it.
    pub type_name: &'static str,
    /// The types of the section's own tables (`[thesis.control]`), declared in the same source.
    pub tables: &'static [&'static str],
    /// The source file declaring the type (`include_str!`).
    pub source: &'static str,
}

impl<T> Section<T> {
    /// The declaration `d` of a section of type `T`, with its defaults where a file may leave
    /// out all its keys (`None` for a section with a required key).
    pub const fn new(d: SectionDecl, default: Option<fn() -> T>) -> Self {
        Section {
            name: d.name,
            readers: d.readers,
            placement: d.placement,
            always_held: d.always_held,
            type_name: d.type_name,
            tables: d.tables,
            source: d.source,
            default,
        }
    }

    /// The section's name.
    pub fn name(&self) -> &'static str {
        self.name
    }
}

impl<T: Any> Section<T> {
    /// This section of `file`, or `None` where the file holds none.
    ///
    /// # Panics
    /// When the file holds the section as another type than `T`: a section has one type, so
    /// this is a mistake in covga's code, not in a file.
    pub fn get<'a>(&self, file: &'a dyn super::entry::FileSections) -> Option<&'a T> {
        super::entry::section::<T>(file, self.name)
    }
}

impl<T: Any + Clone + Default> Section<T> {
    /// This section of `file`, or its defaults where the file holds none.
    pub fn get_or_default(&self, file: &dyn super::entry::FileSections) -> T {
        self.get(file).cloned().unwrap_or_default()
    }
}

impl<T> SectionSpec for Section<T>
where
    T: SectionValue + Clone + DeserializeOwned,
{
    fn name(&self) -> &'static str {
        self.name
    }
    fn readers(&self) -> &'static str {
        self.readers
    }
    fn placement(&self) -> Placement {
        self.placement
    }
    fn always_held(&self) -> bool {
        self.always_held
    }
    fn source(&self) -> (&'static str, &'static str) {
        (self.type_name, self.source)
    }
    fn tables(&self) -> &'static [&'static str] {
        self.tables
    }
    fn type_id(&self) -> TypeId {
        TypeId::of::<T>()
    }
    fn default_value(&self) -> Option<Box<dyn SectionValue>> {
        self.default.map(|d| Box::new(d()) as Box<dyn SectionValue>)
    }
    fn read_value(&self, value: toml::Value) -> Result<Box<dyn SectionValue>, String> {
        T::deserialize(value).map(|s| Box::new(s) as Box<dyn SectionValue>).map_err(|e| e.message().to_string())
    }
    fn check_text(&self, text: &str) -> Result<(), toml::de::Error> {
        serde::de::DeserializeSeed::deserialize(
            OnlyKey::<T> { key: self.name, section: PhantomData },
            toml::de::Deserializer::new(text),
        )
    }
}

/// Reads the key `key` of a table as a `T` and passes over every other key.
struct OnlyKey<T> {
    key: &'static str,
    section: PhantomData<fn() -> T>,
}

impl<'de, T: DeserializeOwned> serde::de::DeserializeSeed<'de> for OnlyKey<T> {
    type Value = ();
    fn deserialize<D: serde::Deserializer<'de>>(self, d: D) -> Result<(), D::Error> {
        d.deserialize_map(self)
    }
}

impl<'de, T: DeserializeOwned> serde::de::Visitor<'de> for OnlyKey<T> {
    type Value = ();
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "a table with [{}]", self.key)
    }
    fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
        while let Some(key) = map.next_key::<String>()? {
            if key == self.key {
                map.next_value::<T>()?;
            } else {
                map.next_value::<serde::de::IgnoredAny>()?;
            }
        }
        Ok(())
    }
}

/// The planner sections a file holds, by name: each the typed value of its declaration.
#[derive(Debug, Default)]
pub struct PlannerSections(BTreeMap<&'static str, Box<dyn SectionValue>>);

impl Clone for PlannerSections {
    fn clone(&self) -> Self {
        PlannerSections(self.0.iter().map(|(k, v)| (*k, v.clone_box())).collect())
    }
}

impl PartialEq for PlannerSections {
    fn eq(&self, other: &Self) -> bool {
        self.0.len() == other.0.len()
            && self.0.iter().all(|(k, v)| other.0.get(k).is_some_and(|o| v.eq_dyn(o.as_ref())))
    }
}

impl PlannerSections {
    /// The section `[name]`, if held.
    pub fn get(&self, name: &str) -> Option<&dyn SectionValue> {
        self.0.get(name).map(|v| v.as_ref())
    }

    /// Holds `value` as the section `[name]` (replacing one held).
    pub fn insert(&mut self, name: &'static str, value: Box<dyn SectionValue>) {
        self.0.insert(name, value);
    }

    /// Holds the section of `spec` at its defaults, unless one is held or it has none.
    pub fn insert_default(&mut self, spec: &dyn SectionSpec) {
        if !self.0.contains_key(spec.name())
            && let Some(value) = spec.default_value()
        {
            self.0.insert(spec.name(), value);
        }
    }

    /// Drops the section `[name]`.
    pub fn remove(&mut self, name: &str) -> Option<Box<dyn SectionValue>> {
        self.0.remove(name)
    }

    /// The section of `section` as its type, held at its defaults first where it is not.
    ///
    /// # Panics
    /// When the section is held as another type than `T` (a mistake in covga's code).
    pub fn get_mut<T: SectionValue + Default>(&mut self, section: &Section<T>) -> &mut T {
        self.0
            .entry(section.name)
            .or_insert_with(|| Box::new(T::default()))
            .as_any_mut()
            .downcast_mut::<T>()
            .unwrap_or_else(|| panic!("[{}] is held as another type", section.name))
    }

    /// Holds `value` as the section of `section`.
    pub fn set<T: SectionValue>(&mut self, section: &Section<T>, value: T) {
        self.0.insert(section.name, Box::new(value));
    }
}

/// A TOML item written through any serializer, keys in the item's order.
pub struct ItemSer<'a>(pub &'a toml_edit::Item);

impl Serialize for ItemSer<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::{SerializeMap, SerializeSeq};
        match self.0 {
            toml_edit::Item::None => s.serialize_unit(),
            toml_edit::Item::Value(v) => ValueSer(v).serialize(s),
            toml_edit::Item::Table(t) => {
                let mut m = s.serialize_map(Some(t.len()))?;
                for (k, item) in t.iter() {
                    m.serialize_entry(k, &ItemSer(item))?;
                }
                m.end()
            }
            toml_edit::Item::ArrayOfTables(a) => {
                let mut q = s.serialize_seq(Some(a.len()))?;
                for t in a.iter() {
                    q.serialize_element(&ItemSer(&toml_edit::Item::Table(t.clone())))?;
                }
                q.end()
            }
        }
    }
}

/// A TOML value written through any serializer.
struct ValueSer<'a>(&'a toml_edit::Value);

impl Serialize for ValueSer<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::{Error, SerializeMap, SerializeSeq};
        match self.0 {
            toml_edit::Value::String(v) => s.serialize_str(v.value()),
            toml_edit::Value::Integer(v) => s.serialize_i64(*v.value()),
            toml_edit::Value::Float(v) => s.serialize_f64(*v.value()),
            toml_edit::Value::Boolean(v) => s.serialize_bool(*v.value()),
            toml_edit::Value::Datetime(_) => Err(S::Error::custom("a section holds no dates")),
            toml_edit::Value::Array(a) => {
                let mut q = s.serialize_seq(Some(a.len()))?;
                for v in a.iter() {
                    q.serialize_element(&ValueSer(v))?;
                }
                q.end()
            }
            toml_edit::Value::InlineTable(t) => {
                let mut m = s.serialize_map(Some(t.len()))?;
                for (k, v) in t.iter() {
                    m.serialize_entry(k, &ValueSer(v))?;
                }
                m.end()
            }
        }
    }
}
