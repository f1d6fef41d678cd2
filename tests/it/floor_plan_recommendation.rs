//! The book's recommended settings for a real floor plan ("Plan your own floor plan"), read
//! from its table, against what follows them: each shipped floor-plan example and the file
//! `covga init` writes.

use std::path::Path;

/// The shipped examples that plan a real floor plan for a real robot.
const EXAMPLES: [&str; 2] = ["experiments/floor-plan-image.toml", "experiments/cell-order-basement.toml"];

/// The rows of the book's table of recommended settings: (dotted key, value as TOML).
fn recommended() -> Vec<(String, toml::Value)> {
    let page =
        std::fs::read_to_string(crate::common::repo().join("docs/src/getting-started/your-floor-plan.md")).unwrap();
    let table = page.split("| recommended key | value |").nth(1).expect("the table of recommended settings");
    let rows: Vec<(String, toml::Value)> = table
        .lines()
        .skip(2)
        .take_while(|l| l.starts_with('|'))
        .map(|l| {
            let cells: Vec<&str> = l.split('|').map(|c| c.trim().trim_matches('`')).collect();
            let value: toml::Table = format!("v = {}", cells[2]).parse().unwrap_or_else(|e| panic!("{l}: {e}"));
            (cells[1].to_string(), value["v"].clone())
        })
        .collect();
    assert!(rows.len() >= 5, "{rows:?}");
    rows
}

/// The value of dotted `key` in `table`.
fn value<'a>(table: &'a toml::Table, key: &str) -> Option<&'a toml::Value> {
    let (head, last) = key.rsplit_once('.').map_or((None, key), |(h, l)| (Some(h), l));
    let section = match head {
        Some(h) => table.get(h)?.as_table()?,
        None => table,
    };
    section.get(last)
}

/// Every key of the table set to its value in `text`, else the keys that are not.
fn follows(text: &str, what: &str) {
    let table: toml::Table = text.parse().unwrap();
    let off: Vec<String> = recommended()
        .into_iter()
        .filter(|(k, v)| value(&table, k) != Some(v))
        .map(|(k, v)| format!("{k} = {v} (it has {:?})", value(&table, &k)))
        .collect();
    assert!(off.is_empty(), "{what} departs from the book's recommended settings: {}", off.join("; "));
}

#[test]
fn the_shipped_floor_plan_examples_follow_the_books_recommendation() {
    for example in EXAMPLES {
        follows(&std::fs::read_to_string(crate::common::repo().join(example)).unwrap(), example);
    }
}

#[test]
fn covga_init_writes_the_books_recommendation() {
    let dir = tempfile::tempdir().unwrap();
    let o = crate::common::covga_in(dir.path(), &["init", "--map", "office", "--start", "1.3,1.3", "--out", "o.toml"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    follows(&std::fs::read_to_string(dir.path().join("o.toml")).unwrap(), "covga init's file");
}

/// The code's list and the book's table are the same rows in the same order.
#[test]
fn the_books_table_is_the_codes_list() {
    let code: Vec<(String, toml::Value)> = covga::experiment::recommended::FLOOR_PLAN
        .iter()
        .map(|r| (r.key.to_string(), format!("v = {}", r.value).parse::<toml::Table>().unwrap()["v"].clone()))
        .collect();
    assert_eq!(recommended(), code);
    assert!(Path::new(&crate::common::repo().join(EXAMPLES[0])).is_file());
}
