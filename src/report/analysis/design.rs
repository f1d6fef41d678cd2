//! How the swept parameters of a study relate: which one follows (is a function of) others,
//! so that a report names it as confounded with them instead of testing it on its own, and
//! which are crossed with each other; and the fitness projection a study may sweep, within
//! which a best or a mean of `f` is taken.

use crate::study::records::RunsTable;
use std::collections::BTreeMap;

/// Whether the column `c` is a function of the columns `of` over the rows.
pub(crate) fn follows(t: &RunsTable, c: usize, of: &[usize]) -> bool {
    let mut seen: BTreeMap<Vec<&str>, &str> = BTreeMap::new();
    t.rows.iter().all(|r| {
        let key: Vec<&str> = of.iter().map(|&i| r[i].as_str()).collect();
        *seen.entry(key).or_insert(r[c].as_str()) == r[c].as_str()
    })
}

/// The columns among `kept` that `c` follows: one alone where one suffices, else all of them;
/// `None` when `c` does not follow them.
pub(crate) fn followed_by(t: &RunsTable, c: usize, kept: &[usize]) -> Option<String> {
    let names = |cols: &[usize]| cols.iter().map(|&i| t.header[i].as_str()).collect::<Vec<_>>().join(", ");
    if kept.is_empty() || !follows(t, c, kept) {
        return None;
    }
    Some(kept.iter().find(|&&k| follows(t, c, &[k])).map_or_else(|| names(kept), |&k| names(&[k])))
}

/// The swept columns `candidates` (in order) that vary, split into the ones kept as factors
/// of their own and the ones that follow the kept ones before them (with the names of those
/// they follow). A column set to one value in every row is in neither.
pub(crate) fn split_followers(t: &RunsTable, candidates: &[usize]) -> (Vec<usize>, Vec<(usize, String)>) {
    let (mut kept, mut followers) = (Vec::new(), Vec::new());
    for &c in candidates {
        let values: std::collections::BTreeSet<&str> = t.rows.iter().map(|r| r[c].as_str()).collect();
        if values.len() < 2 {
            continue;
        }
        match followed_by(t, c, &kept) {
            Some(of) => followers.push((c, of)),
            None => kept.push(c),
        }
    }
    (kept, followers)
}

/// How a factor's values meet the other factors in the rows where it is set.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Crossing {
    /// Every combination of the other factors that occurs with one of its values occurs with
    /// each of them: a difference between its values is its own (the factors `nested`, set
    /// under some of its values only, are pooled within those).
    Crossed { nested: Vec<usize> },
    /// Its values were run with different settings of these factors: a difference between
    /// them is confounded with those.
    NotCrossed { with: Vec<usize> },
}

/// Whether factor `p` is crossed with the factors `others` over `rows` (the rows where `p` is
/// set). A factor set under some of `p`'s values and empty under the others (a tournament size
/// under tournament selection only) is nested in `p`, not crossed with it, and is left out of
/// the check.
pub(crate) fn crossing(t: &RunsTable, p: usize, rows: &[usize], others: &[usize]) -> Crossing {
    let value_of = |r: usize, c: usize| t.rows[r][c].as_str();
    let mut by_value: BTreeMap<&str, Vec<usize>> = BTreeMap::new();
    for &r in rows {
        by_value.entry(value_of(r, p)).or_default().push(r);
    }
    let (mut nested, mut checked) = (Vec::new(), Vec::new());
    for &q in others.iter().filter(|&&q| q != p) {
        let set_under: Vec<Option<bool>> = by_value
            .values()
            .map(|rs| {
                let set = rs.iter().filter(|&&r| !value_of(r, q).is_empty()).count();
                if set == rs.len() {
                    Some(true)
                } else if set == 0 {
                    Some(false)
                } else {
                    None
                }
            })
            .collect();
        let decided = set_under.iter().all(Option::is_some);
        if decided && set_under.contains(&Some(true)) && set_under.contains(&Some(false)) {
            nested.push(q);
        } else {
            checked.push(q);
        }
    }
    type Combos<'a> = std::collections::BTreeSet<Vec<&'a str>>;
    let combos = |cols: &[usize]| -> Vec<Combos> {
        by_value
            .values()
            .map(|rs| rs.iter().map(|&r| cols.iter().map(|&q| value_of(r, q)).collect()).collect())
            .collect()
    };
    let all = combos(&checked);
    if all.windows(2).all(|w| w[0] == w[1]) {
        return Crossing::Crossed { nested };
    }
    let with: Vec<usize> = checked
        .iter()
        .copied()
        .filter(|&q| {
            let one = combos(&[q]);
            !one.windows(2).all(|w| w[0] == w[1])
        })
        .collect();
    Crossing::NotCrossed { with: if with.is_empty() { checked } else { with } }
}

/// The swept key that picks the fitness function.
pub const PROJECTION: &str = "scorer.projection";

/// The projections of a study that sweeps them, when `metric` is an `f` (which then must be
/// compared within one projection only); `None` otherwise.
pub fn projection_levels(t: &RunsTable, metric: &str) -> Option<Vec<String>> {
    if !metric.starts_with("f_") {
        return None;
    }
    let c = t.col(PROJECTION)?;
    let levels: std::collections::BTreeSet<String> =
        t.rows.iter().map(|r| r[c].clone()).filter(|v| !v.is_empty()).collect();
    (levels.len() > 1).then(|| levels.into_iter().collect())
}

/// `rows` per projection where the study sweeps it (f1 and f2 are different functions, so a
/// best or a mean of f is taken within one), each with the suffix that names it; otherwise all
/// of `rows` with an empty suffix.
pub fn projection_scopes(t: &RunsTable, rows: &[usize]) -> Vec<(String, Vec<usize>)> {
    let (Some(levels), Some(c)) = (projection_levels(t, "f_free"), t.col(PROJECTION)) else {
        return vec![(String::new(), rows.to_vec())];
    };
    let scopes: Vec<(String, Vec<usize>)> = levels
        .into_iter()
        .filter_map(|l| {
            let scoped: Vec<usize> = rows.iter().copied().filter(|&r| t.rows[r][c] == l).collect();
            (!scoped.is_empty()).then(|| (format!(", {PROJECTION}={l}"), scoped))
        })
        .collect();
    // Rows of one projection (a group of `--by scorer.projection`) need no split.
    if scopes.len() > 1 { scopes } else { vec![(String::new(), rows.to_vec())] }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A table of columns `p,q,m` from `rows` ("a,1,x" each).
    fn table(rows: &[&str]) -> RunsTable {
        RunsTable::parse(&format!("p,q,m\n{}\n", rows.join("\n"))).unwrap()
    }

    #[test]
    fn crossing_of_a_factor_with_the_others() {
        let crossed = ["a,1,x", "a,2,x", "b,1,x", "b,2,x", "a,1,y", "a,2,y", "b,1,y", "b,2,y"];
        // q set under b only, m crossed: q is nested in p, p crossed with m.
        let nested = ["a,,x", "a,,y", "b,3,x", "b,7,x", "b,3,y", "b,7,y"];
        // a runs with q in {1, 2}, b with q in {2, 3}: not crossed with q (q does not follow p).
        let apart = ["a,1,x", "a,2,x", "b,2,x", "b,3,x"];
        let cases: [(&[&str], Crossing); 3] = [
            (&crossed, Crossing::Crossed { nested: vec![] }),
            (&nested, Crossing::Crossed { nested: vec![1] }),
            (&apart, Crossing::NotCrossed { with: vec![1] }),
        ];
        for (rows, expected) in cases {
            let t = table(rows);
            let all: Vec<usize> = (0..t.rows.len()).collect();
            assert_eq!(crossing(&t, 0, &all, &[0, 1, 2]), expected, "{rows:?}");
        }
    }

    #[test]
    fn a_column_that_follows_a_kept_one_is_named_with_it() {
        // q is a function of p (a budget per map); m varies on its own; a constant is neither.
        let t = RunsTable::parse("p,q,m,k\na,1,x,c\na,1,y,c\nb,2,x,c\nb,2,y,c\n").unwrap();
        let (kept, followers) = split_followers(&t, &[0, 1, 2, 3]);
        assert_eq!(kept, vec![0, 2]);
        assert_eq!(followers, vec![(1, "p".to_string())]);
    }
}
