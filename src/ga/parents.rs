//! How a GA draws its parents: each selection scheme is a component of its own file, listed
//! once in [`SCHEMES`], and every GA that draws parents one at a time (the thesis GA's
//! architecture (a), the cell-order GA) offers all of them from its TOML section. A scheme
//! states the parameters it reads ([`Param`]); each GA maps those to its own keys, so that its
//! validation and its "key is ignored" warnings follow from the registry, not from lists kept
//! by hand. Adding a scheme is its file plus its line in [`SCHEMES`].
//!
//! The operators themselves (tournament, wheels, low-variance sampling) are the pure functions
//! of [`super::selection`]; a scheme prepares them once per generation over the fitness.

pub mod best;
pub mod prws;
pub mod rrws;
pub mod sus;
pub mod tournament;

use rand::RngCore;

/// Every parent-selection scheme, by the name experiment files give it. The registration
/// point: a new scheme's file adds its line here.
pub const SCHEMES: &[&dyn ParentScheme] = &[&tournament::Tournament, &prws::Prws, &rrws::Rrws, &best::Best, &sus::Sus];

/// A parameter a scheme may read; each GA section spells it as its own key.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Param {
    /// The tournament size `TS` (003 §2.2.1.1), in `[1, population]`.
    TournamentSize,
    /// The selection pressure `SP` of a rank wheel (003 §2.2.1.3), in `[1, 2]`.
    Pressure,
    /// How many of the best may be parents, in `[1, population]`.
    BestParents,
}

impl Param {
    /// Every parameter, in the order messages list them.
    pub const ALL: [Param; 3] = [Param::TournamentSize, Param::Pressure, Param::BestParents];
}

/// The values of the parameters a draw reads (the others are ignored).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DrawParams {
    /// `TS`.
    pub tournament_size: usize,
    /// `SP`.
    pub pressure: f64,
    /// How many of the best may be parents.
    pub best_parents: usize,
}

impl DrawParams {
    /// The value of `param`, as a number.
    pub fn get(&self, param: Param) -> f64 {
        match param {
            Param::TournamentSize => self.tournament_size as f64,
            Param::Pressure => self.pressure,
            Param::BestParents => self.best_parents as f64,
        }
    }
}

/// A parent-selection scheme.
pub trait ParentScheme: Sync {
    /// The name experiment files give it.
    fn name(&self) -> &'static str;
    /// The parameters it reads.
    fn reads(&self) -> &'static [Param];
    /// The parameter a linear ramp (003 eq. 3.25) drives from generation to generation, if
    /// the scheme has one.
    fn ramped(&self) -> Option<Param> {
        None
    }
    /// The draws of one generation over `fitness` (higher is better, one value per member).
    fn prepare<'f>(&self, fitness: &'f [f64], params: &DrawParams) -> Box<dyn Draw + 'f>;
}

/// One generation's draws, prepared.
pub trait Draw {
    /// The index of the next parent.
    fn pick(&mut self, rng: &mut dyn RngCore) -> usize;
}

/// The scheme called `name`, if one is registered.
pub fn scheme(name: &str) -> Option<&'static dyn ParentScheme> {
    SCHEMES.iter().copied().find(|s| s.name() == name)
}

/// Old scheme name → its registered name; the old name is read for one more release (the
/// experiment file's warnings say so and `covga migrate` rewrites it). `"elite"` meant the
/// thesis GA's families in `[thesis]` and the draw from the best in `[cell_order]`.
pub const RENAMED_SCHEMES: [(&str, &str); 1] = [("elite", "best")];

/// Whether `key` sets a selection parameter that the registered scheme `name` does not read,
/// with `param_key` spelling a GA's key of each parameter (a GA's warnings about unread keys
/// follow from each scheme's [`ParentScheme::reads`]).
pub fn unread_by_scheme(name: &str, key: &str, param_key: impl Fn(Param) -> Option<&'static str>) -> bool {
    scheme(name).is_some_and(|s| Param::ALL.iter().any(|&p| param_key(p) == Some(key) && !s.reads().contains(&p)))
}

/// The name of a registered scheme, as a GA's section holds it: parsed against [`SCHEMES`]
/// (an unknown name is refused where the file is read), written back as the name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SchemeName(&'static str);

impl SchemeName {
    /// The registered scheme called `name`.
    pub fn parse(name: &str) -> Option<Self> {
        let name = RENAMED_SCHEMES.iter().find(|(old, _)| *old == name).map_or(name, |(_, new)| new);
        scheme(name).map(|s| SchemeName(s.name()))
    }

    /// The scheme.
    pub fn scheme(self) -> &'static dyn ParentScheme {
        scheme(self.0).expect("a parsed name is registered")
    }

    /// The name.
    pub fn as_str(self) -> &'static str {
        self.0
    }
}

impl serde::Serialize for SchemeName {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.0)
    }
}

impl<'de> serde::Deserialize<'de> for SchemeName {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let name = String::deserialize(d)?;
        Self::parse(&name).ok_or_else(|| unknown_scheme(&name, &[]))
    }
}

/// serde's error for a scheme name that is neither one of `own` (a GA's names of its own) nor
/// registered, listing both as serde lists an enum's variants.
pub fn unknown_scheme<E: serde::de::Error>(name: &str, own: &[&str]) -> E {
    let registered = SCHEMES.iter().map(|s| s.name()).filter(|n| !own.contains(n));
    let all: Vec<String> = own.iter().copied().chain(registered).map(|n| format!("`{n}`")).collect();
    E::custom(format!("unknown variant `{name}`, expected one of {}", all.join(", ")))
}

/// A scheme with the values of its parameters: what a GA's validated parameters hold.
#[derive(Clone, Copy)]
pub struct ParentDraw {
    /// The scheme.
    pub scheme: &'static dyn ParentScheme,
    /// Its parameters' values.
    pub params: DrawParams,
}

impl ParentDraw {
    /// The scheme called `name` with `params`, if registered.
    pub fn named(name: &str, params: DrawParams) -> Option<Self> {
        scheme(name).map(|scheme| Self { scheme, params })
    }

    /// The draws of one generation over `fitness`.
    pub fn prepare<'f>(&self, fitness: &'f [f64]) -> Box<dyn Draw + 'f> {
        self.scheme.prepare(fitness, &self.params)
    }
}

impl std::fmt::Debug for ParentDraw {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ParentDraw").field("scheme", &self.scheme.name()).field("params", &self.params).finish()
    }
}

impl PartialEq for ParentDraw {
    /// Equal when the schemes are and the parameters they read are.
    fn eq(&self, other: &Self) -> bool {
        self.scheme.name() == other.scheme.name()
            && self.scheme.reads().iter().all(|&p| self.params.get(p) == other.params.get(p))
    }
}

#[cfg(test)]
#[path = "parents/tests.rs"]
mod tests;
