//! The correction of a family of tests for multiplicity.

/// Holm's step-down adjustment of p-values (family-wise error), in the input order.
pub fn holm(p: &[f64]) -> Vec<f64> {
    let m = p.len();
    let mut order: Vec<usize> = (0..m).collect();
    order.sort_by(|&x, &y| p[x].total_cmp(&p[y]));
    let mut adjusted = vec![0.0; m];
    let mut running: f64 = 0.0;
    for (k, &i) in order.iter().enumerate() {
        running = running.max(((m - k) as f64 * p[i]).min(1.0));
        adjusted[i] = running;
    }
    adjusted
}

/// A family of tests whose p-values are corrected together (Holm 1979): the family's name says
/// which question the tests share, so a reader knows what the correction covers.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Family {
    /// What the tests of the family compare, e.g. "each planner against the control, per map".
    pub name: String,
    /// Each test's label and raw p-value, in the order they were added.
    pub tests: Vec<(String, f64)>,
}

impl Family {
    /// An empty family named `name`.
    pub fn new(name: impl Into<String>) -> Self {
        Self { name: name.into(), tests: Vec::new() }
    }

    /// Adds a test.
    pub fn push(&mut self, label: impl Into<String>, p_value: f64) {
        self.tests.push((label.into(), p_value));
    }

    /// The Holm-adjusted p-values, in the order the tests were added.
    pub fn adjusted(&self) -> Vec<f64> {
        holm(&self.tests.iter().map(|t| t.1).collect::<Vec<_>>())
    }

    /// The sentence a report prints under the family's table.
    pub fn statement(&self) -> String {
        match self.tests.len() {
            0 => format!("No test of {}: nothing to correct.", self.name),
            1 => format!("One test of {}: nothing to correct (Holm's p is its own).", self.name),
            n => format!("Holm–Bonferroni over the {n} tests of {}.", self.name),
        }
    }
}

/// The smallest p a family can reach after its correction.
#[derive(Clone, Debug, PartialEq)]
pub struct Floor {
    /// The smallest Holm-adjusted p of the family.
    pub p: f64,
    /// Whether it is below the level: whether the family can show anything at all.
    pub reachable: bool,
    /// The sentence a report states it in.
    pub sentence: String,
}

impl Family {
    /// The family's floor when its most extreme possible data give the raw p `smallest_raw`
    /// (`best` says what that is, e.g. "its largest comparison, 8 strata, all pointing one
    /// way"): Holm multiplies the smallest raw p by the family's size. `None` without a test.
    pub fn floor(&self, smallest_raw: f64, alpha: f64, best: &str) -> Option<Floor> {
        floor(self.tests.len(), smallest_raw, alpha, best)
    }
}

/// [`Family::floor`] of a family of `tests` tests.
pub fn floor(tests: usize, smallest_raw: f64, alpha: f64, best: &str) -> Option<Floor> {
    if tests == 0 {
        return None;
    }
    let p = (smallest_raw * tests as f64).min(1.0);
    let text = |x: f64| match x {
        x if x < 1e-300 => "below 1e-300".to_string(),
        x if x < 1e-4 => format!("{x:.1e}"),
        x => format!("{x:.4}"),
    };
    let after = if tests == 1 { String::new() } else { format!(", {} after Holm over its {tests} tests", text(p)) };
    let sentence = if p < alpha {
        format!("The smallest p this family can reach is {}{after} ({best}).", text(smallest_raw))
    } else {
        format!(
            "**By design this family cannot show anything at the {alpha:.2} level**: at best ({best}) its p is {}{after}; \
             a test here that is not shown is no evidence either way.",
            text(smallest_raw)
        )
    };
    Some(Floor { p, reachable: p < alpha, sentence })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_family_adjusts_its_own_tests() {
        let mut f = Family::new("each setting against the control");
        f.push("a", 0.04);
        f.push("b", 0.01);
        f.push("c", 0.02);
        assert_eq!(f.adjusted(), holm(&[0.04, 0.01, 0.02]));
        assert_eq!(f.statement(), "Holm–Bonferroni over the 3 tests of each setting against the control.");
        let mut one = Family::new("one setting against the control");
        one.push("a", 0.04);
        assert_eq!(one.adjusted(), vec![0.04]);
        assert_eq!(
            one.statement(),
            "One test of one setting against the control: nothing to correct (Holm's p is its own)."
        );
        assert_eq!(Family::new("none").statement(), "No test of none: nothing to correct.");
    }

    #[test]
    fn a_family_states_the_smallest_p_it_can_reach() {
        let mut f = Family::new("x");
        assert_eq!(f.floor(0.01, 0.05, "b"), None);
        f.push("a", 0.3);
        let one = f.floor(0.0078125, 0.05, "8 units one way").unwrap();
        assert!(one.reachable && one.p == 0.0078125);
        assert_eq!(one.sentence, "The smallest p this family can reach is 0.0078 (8 units one way).");
        for _ in 0..9 {
            f.push("a", 0.3);
        }
        let ten = f.floor(0.0078125, 0.05, "8 units one way").unwrap();
        assert!(!ten.reachable && ten.p == 0.078125);
        assert!(ten.sentence.starts_with(
            "**By design this family cannot show anything at the 0.05 level**: at best (8 units one way) its p is 0.0078, 0.0781 after Holm over its 10 tests;"
        ), "{}", ten.sentence);
    }
}
