//! Every citation in `src/` resolves inside the repository: `thesis-ga §N` and `R…` to an anchor
//! of the book's design decisions for the thesis GA, `waypoint §N` and `W…` to those for the
//! waypoint planner, and nothing points to a document the repository does not hold (the design
//! notes and specification the project was started from, the folder of source papers).

use std::collections::BTreeSet;
use std::path::Path;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The design page each citation kind resolves into, by the citation's prefix.
const THESIS_PAGE: &str = "docs/src/concepts/thesis-ga-decisions.md";
const WAYPOINT_PAGE: &str = "docs/src/concepts/waypoint-decisions.md";

/// Words that cite a document outside the repository.
const OUTSIDE: [&str; 6] = ["spec §", "Spec §", "DESIGN.md", "DESIGN \"", "shared/", "design notes"];

/// The `<a id="…">` anchors of a page.
fn anchors(page: &str) -> BTreeSet<String> {
    let text = std::fs::read_to_string(root().join(page)).unwrap_or_else(|e| panic!("{page}: {e}"));
    text.split("<a id=\"").skip(1).filter_map(|rest| rest.split('"').next()).map(str::to_string).collect()
}

/// The section numbers cited after `prefix §` in `text`: `§3.3`, `§2–§7`, `§18–19`,
/// `§5–6, §12–13`, `§1.2 / §16.4` (each end of a range is an anchor of its own).
fn sections_cited(text: &str, prefix: &str) -> Vec<String> {
    let mut out = Vec::new();
    let needle = format!("{prefix} §");
    for (at, _) in text.match_indices(&needle) {
        // A longer prefix ending in this one (`xthesis-ga`) is not a citation of it.
        if text[..at].chars().next_back().is_some_and(|c| c.is_alphanumeric() || c == '-') {
            continue;
        }
        let mut rest = &text[at + needle.len()..];
        loop {
            let number: String = rest.chars().take_while(|c| c.is_ascii_digit() || *c == '.').collect();
            let number = number.trim_end_matches('.').to_string();
            if number.is_empty() {
                break;
            }
            rest = &rest[number.len()..];
            out.push(number);
            let next = ["–§", "–", ", §", " / §"].iter().find(|sep| rest.starts_with(**sep));
            match next {
                Some(sep) => rest = &rest[sep.len()..],
                None => break,
            }
        }
    }
    out
}

/// The resolution ids `R1`…, `W1`… in `text` (a capital letter and digits standing alone).
fn resolutions_cited(text: &str, letter: char) -> Vec<String> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    for (i, &c) in chars.iter().enumerate() {
        let alone_before = i == 0 || !(chars[i - 1].is_alphanumeric() || chars[i - 1] == '_');
        if c != letter || !alone_before {
            continue;
        }
        let digits: String = chars[i + 1..].iter().take_while(|d| d.is_ascii_digit()).collect();
        let after = chars.get(i + 1 + digits.len());
        if !digits.is_empty() && !after.is_some_and(|a| a.is_alphanumeric() || *a == '_') {
            out.push(format!("{letter}{digits}"));
        }
    }
    out
}

/// The problems of one source text: outside citations and citations without their anchor.
fn problems(name: &str, text: &str, thesis: &BTreeSet<String>, waypoint: &BTreeSet<String>) -> Vec<String> {
    let mut out = Vec::new();
    for word in OUTSIDE {
        if text.contains(word) {
            out.push(format!("{name}: cites `{word}`, a document outside the repository"));
        }
    }
    for (prefix, anchors, page) in [("thesis-ga", thesis, THESIS_PAGE), ("waypoint", waypoint, WAYPOINT_PAGE)] {
        for number in sections_cited(text, prefix) {
            let id = format!("s{}", number.replace('.', "-"));
            if !anchors.contains(&id) {
                out.push(format!("{name}: `{prefix} §{number}` has no anchor `{id}` in {page}"));
            }
        }
    }
    for (letter, anchors, page) in [('R', thesis, THESIS_PAGE), ('W', waypoint, WAYPOINT_PAGE)] {
        for id in resolutions_cited(text, letter) {
            if !anchors.contains(&id.to_lowercase()) {
                out.push(format!("{name}: `{id}` has no anchor `{}` in {page}", id.to_lowercase()));
            }
        }
    }
    out
}

#[test]
fn every_citation_in_src_resolves_to_an_anchor_of_the_book() {
    let (thesis, waypoint) = (anchors(THESIS_PAGE), anchors(WAYPOINT_PAGE));
    assert!(thesis.contains("r30") && waypoint.contains("w30"), "the pages hold every resolution");
    let files = crate::common::files_with_extension(&root().join("src"), "rs");
    let mut found = Vec::new();
    let mut cited = 0;
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        let name = file.strip_prefix(root()).unwrap().display().to_string();
        cited += sections_cited(&text, "thesis-ga").len() + sections_cited(&text, "waypoint").len();
        cited += resolutions_cited(&text, 'R').len() + resolutions_cited(&text, 'W').len();
        found.extend(problems(&name, &text, &thesis, &waypoint));
    }
    assert!(found.is_empty(), "{} problems:\n{}", found.len(), found.join("\n"));
    assert!(cited >= 200, "only {cited} citations found in src/: is the reader still right?");
}

/// The reader finds what it should, and the check fails where it should: the way the code cited
/// the specification before the book, a section the page lacks, a resolution beyond 30.
#[test]
fn the_citation_check_reads_every_form_and_fails_on_outside_documents() {
    let text = "(003 §3.3.4, thesis-ga §9.1, R17) waypoint §2–§7, §9 and waypoint §18–19, \
                thesis-ga §5–6, §12–13; waypoint §1.2 / §16.4. W18: x; R_a = 6; RW1; W3–W5";
    assert_eq!(sections_cited(text, "thesis-ga"), ["9.1", "5", "6", "12", "13"]);
    assert_eq!(sections_cited(text, "waypoint"), ["2", "7", "9", "18", "19", "1.2", "16.4"]);
    assert_eq!(resolutions_cited(text, 'R'), ["R17"]);
    assert_eq!(resolutions_cited(text, 'W'), ["W18", "W3", "W5"]);
    let (thesis, waypoint) = (anchors(THESIS_PAGE), anchors(WAYPOINT_PAGE));
    for bad in ["(003 §3.3, spec §3.3)", "see DESIGN.md", "thesis-ga §99", "waypoint §1.9", "R31", "W99"] {
        assert!(!problems("x.rs", bad, &thesis, &waypoint).is_empty(), "`{bad}` passed the check");
    }
    assert!(problems("x.rs", "thesis-ga §3.3, R4, waypoint §11.4, W18", &thesis, &waypoint).is_empty());
}
