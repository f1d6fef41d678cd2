//! A planner with a section of its own is its code and its entry, nothing else: a toy planner
//! ("stripe": out from the start station along x and back, `turns` times) declares its section
//! `[stripe]` in its entry, as covga's own planners declare theirs, and registers. The
//! experiment file then reads the section with the section type's own checks (an unknown key
//! refused at its line), writes it into `config.toml` where the declaration places it, hands
//! it to the planner, and the warnings name it as unread for another planner, with no edit of
//! covga. It takes everything it uses from `covga::prelude`.

use covga::prelude::{
    Budget, ConfigError, Context, ExperimentText, FileSections, Observer, Placement, Planner, PlannerEntry,
    PlannerError, PluginError, Point, RegisteredPlanner, RunOutcome, Scenario, Section, SectionDecl, SectionSpec,
    StopReason, check_range, prepare, register, run_in_folder,
};
use serde::{Deserialize, Serialize};
use std::sync::{Arc, Once};

/// `[stripe]`: how far the stripe reaches and how often it is driven.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct StripeSection {
    /// Length of the stripe in metres.
    pub length_m: f64,
    /// How often it is driven out and back.
    pub turns: u32,
}

impl Default for StripeSection {
    fn default() -> Self {
        Self { length_m: 1.0, turns: 2 }
    }
}

/// The section's declaration: the one thing the experiment file needs of it.
static STRIPE_SECTION: Section<StripeSection> = Section::new(
    SectionDecl {
        name: "stripe",
        readers: "only the stripe planner reads",
        placement: Placement::BeforeBudget,
        always_held: false,
        type_name: "StripeSection",
        tables: &[],
        source: include_str!("planner_section.rs"),
    },
    Some(StripeSection::default),
);

/// The planner, checked.
#[derive(Debug)]
struct Stripe(StripeSection);

impl Planner for Stripe {
    fn name(&self) -> &'static str {
        "stripe"
    }
    fn run(&self, s: &Scenario, _: u64, _: &Budget, _: &mut [&mut dyn Observer]) -> Result<RunOutcome, PlannerError> {
        let far = Point::new(s.start.x + self.0.length_m, s.start.y);
        let mut path = vec![s.start];
        for _ in 0..self.0.turns {
            path.extend([far, s.start]);
        }
        Ok(RunOutcome::new(vec![path], StopReason::Completed).with_effort(1, 0))
    }
}

impl RegisteredPlanner for Stripe {}

/// The entry: its name, its section, and the section's validation.
struct StripeEntry;

impl PlannerEntry for StripeEntry {
    fn name(&self) -> &'static str {
        "stripe"
    }
    fn is_deterministic(&self) -> bool {
        true
    }
    fn sections(&self) -> &'static [&'static dyn SectionSpec] {
        static SECTIONS: &[&dyn SectionSpec] = &[&STRIPE_SECTION];
        SECTIONS
    }
    fn why_unread(&self, _: &dyn FileSections, _: &str) -> Option<String> {
        None
    }
    fn validate(&self, file: &dyn FileSections, ctx: &Context) -> Result<Arc<dyn RegisteredPlanner>, ConfigError> {
        let section = STRIPE_SECTION.get_or_default(file);
        check_range(ctx.origin, "stripe.length_m", section.length_m, 0.1, 5.0, "[0.1, 5] metres")?;
        Ok(Arc::new(Stripe(section)))
    }
}

static STRIPE: StripeEntry = StripeEntry;

/// Registers the toy planner once for the whole test binary.
fn registered() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| register(&STRIPE).expect("a new name"));
}

/// A file of `planner` on a small map, with `sections` after its own.
fn experiment(planner: &str, sections: &str) -> ExperimentText {
    ExperimentText {
        text: format!(
            "planner = \"{planner}\"\n[map]\nsource = \"thesis-2\"\n[stations]\nstart = [1.3, 1.3]\n{sections}"
        ),
        origin: "stripe.toml".into(),
        stem: "stripe".into(),
    }
}

#[test]
fn a_planner_declaring_its_section_is_read_checked_written_and_warned_about() {
    registered();
    let tmp = tempfile::tempdir().unwrap();
    let prepared = prepare(&experiment("stripe", "[stripe]\nlength_m = 2.0\n"), None, None).unwrap();
    run_in_folder(&prepared, Some(tmp.path()), false, &mut []).unwrap();
    let config = std::fs::read_to_string(tmp.path().join("config.toml")).unwrap();
    let (stripe, budget) = (config.find("[stripe]\nlength_m = 2.0\nturns = 2\n"), config.find("[budget]"));
    assert!(stripe.is_some_and(|s| budget.is_some_and(|b| s < b)), "placed before [budget]: {config}");
    let path = std::fs::read_to_string(tmp.path().join("best_path.csv")).unwrap();
    assert!(path.contains("3.3"), "the planner read its section's length: {path}");
    // The section type's own checks, at the line of the key; then the entry's validation.
    let refused =
        |text: &str| prepare(&experiment("stripe", text), None, None).err().map(|e| e.to_string()).unwrap_or_default();
    let unknown = refused("[stripe]\ncolour = 3\n");
    assert!(unknown.contains("stripe.toml:7: unknown field `colour`, expected `length_m` or `turns`"), "{unknown}");
    assert!(refused("[stripe]\nlength_m = 9.0\n").contains("stripe.length_m"));
    // Another planner does not read it, in the words of its declaration.
    let warned = prepare(&experiment("spiral", "[stripe]\nturns = 3\n"), None, None).unwrap().warnings;
    assert!(warned.iter().any(|w| w.contains("only the stripe planner reads [stripe]")), "{warned:?}");
    // A file without it writes no [stripe].
    let spiral = prepare(&experiment("spiral", ""), None, None).unwrap();
    let dir = tmp.path().join("spiral");
    run_in_folder(&spiral, Some(&dir), false, &mut []).unwrap();
    assert!(!std::fs::read_to_string(dir.join("config.toml")).unwrap().contains("stripe"));
}

/// A section may not take a name the file has a key of, nor another section's name with
/// another type.
#[test]
fn a_section_named_as_a_key_of_the_file_is_refused() {
    registered();
    static BUDGET: Section<StripeSection> = Section::new(
        SectionDecl {
            name: "budget",
            readers: "",
            placement: Placement::BeforeBudget,
            always_held: false,
            type_name: "StripeSection",
            tables: &[],
            source: "",
        },
        None,
    );
    struct Clash;
    impl PlannerEntry for Clash {
        fn name(&self) -> &'static str {
            "clash"
        }
        fn sections(&self) -> &'static [&'static dyn SectionSpec] {
            static SECTIONS: &[&dyn SectionSpec] = &[&BUDGET];
            SECTIONS
        }
        fn why_unread(&self, _: &dyn FileSections, _: &str) -> Option<String> {
            None
        }
        fn validate(&self, file: &dyn FileSections, ctx: &Context) -> Result<Arc<dyn RegisteredPlanner>, ConfigError> {
            StripeEntry.validate(file, ctx)
        }
    }
    static CLASH: Clash = Clash;
    assert_eq!(register(&CLASH), Err(PluginError::SectionTaken("budget")));
}
