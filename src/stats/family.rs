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
            1 => format!("One test of {}: nothing to correct (Holm's p is its own).", self.name),
            n => format!("Holm–Bonferroni over the {n} tests of {}.", self.name),
        }
    }
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
    }
}
