//! The mutation tooling names today's files: every core file of `scripts/mutants.sh` is there,
//! and every pinned exclusion of `.cargo/mutants.toml` (`file:line:column: mutant in function`)
//! names a file that is there, a function defined in it and, for an operator's mutant, that
//! operator at its line and column. A file moved or split leaves its pins matching nothing, and
//! the mutants they were judged equivalent for are tested (and reported missed) again.
//!
//! The full check of a pin against cargo-mutants' own list is `scripts/mutants.sh --check-pins`
//! (it needs cargo-mutants and a build); this one runs without either.

use std::path::Path;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The paths of `scripts/mutants.sh`'s `core=( … )` list.
fn core_files(script: &str) -> Vec<String> {
    let start = script.find("core=(").expect("scripts/mutants.sh has a core=( … ) list") + "core=(".len();
    let end = start + script[start..].find(')').expect("the core list ends");
    script[start..end].split_whitespace().map(str::to_string).collect()
}

/// The pins of `.cargo/mutants.toml`: its quoted patterns that begin with a path under `src/`.
fn pins(toml: &str) -> Vec<String> {
    toml.lines()
        .map(str::trim)
        .filter(|l| !l.starts_with('#'))
        .filter_map(|l| {
            l.strip_prefix("\"src/").map(|rest| format!("src/{}", rest.trim_end_matches(',').trim_end_matches('"')))
        })
        .collect()
}

/// The texts a pin's field matches: its alternatives `(a|b)` and character classes `[56]`
/// spelled out (the only regular expressions the pins use in their lines and columns).
fn alternatives(field: &str) -> Vec<String> {
    let mut out = vec![String::new()];
    let mut rest = field;
    while !rest.is_empty() {
        let (choices, tail): (Vec<String>, &str) = if let Some(r) = rest.strip_prefix('(') {
            let end = r.find(')').expect("a closed group");
            (r[..end].split('|').map(str::to_string).collect(), &r[end + 1..])
        } else if let Some(r) = rest.strip_prefix('[') {
            let end = r.find(']').expect("a closed class");
            (r[..end].chars().map(String::from).collect(), &r[end + 1..])
        } else {
            let end = rest.find(['(', '[']).unwrap_or(rest.len());
            (vec![rest[..end].to_string()], &rest[end..])
        };
        out = out.iter().flat_map(|o| choices.iter().map(move |c| format!("{o}{c}"))).collect();
        rest = tail;
    }
    out
}

/// What is wrong with one pin, if anything.
fn pin_problem(pin: &str) -> Option<String> {
    let mut fields = pin.splitn(4, ':');
    let (path, lines, columns, mutant) = (fields.next()?, fields.next()?, fields.next()?, fields.next()?.trim());
    let Ok(text) = std::fs::read_to_string(root().join(path)) else {
        return Some(format!("{pin}: no file {path}"));
    };
    let source: Vec<&str> = text.lines().collect();
    // `… in FUNCTION` names a function of the file (its last path segment: `Type::method`).
    if let Some((_, function)) = mutant.rsplit_once(" in ") {
        let name = function.rsplit("::").next().unwrap_or(function).replace('\\', "");
        if !text.contains(&format!("fn {name}")) {
            return Some(format!("{pin}: {path} defines no function `{name}`"));
        }
    }
    // An operator's mutant (`replace OP with …`, `replace (OP with X|OP2 with Y) …`,
    // `delete - in …`): the operator at line:column.
    let operators: Vec<String> = match (mutant.strip_prefix("replace "), mutant.strip_prefix("delete ")) {
        (Some(m), _) if m.starts_with('(') => {
            let group = &m[1..m.find(')')?];
            group.split('|').map(|alt| alt.split(" with").next().unwrap_or(alt).to_string()).collect()
        }
        (Some(m), _) => match m.split_once(" with") {
            Some((op, _)) if !op.contains(' ') => alternatives(op),
            _ => return None,
        },
        (_, Some(m)) => match m.split_once(" in ") {
            Some((op, _)) if !op.starts_with("match") => vec![op.to_string()],
            _ => return None,
        },
        _ => return None,
    };
    let operators: Vec<String> = operators.iter().map(|o| o.replace('\\', "")).collect();
    let found = alternatives(lines).iter().any(|line| {
        alternatives(columns).iter().any(|column| {
            let (Ok(l), Ok(c)) = (line.parse::<usize>(), column.parse::<usize>()) else { return false };
            let chars: Vec<char> = source.get(l.wrapping_sub(1)).map_or(Vec::new(), |s| s.chars().collect());
            let at: String = chars.iter().skip(c.saturating_sub(1)).collect();
            operators.iter().any(|o| at.starts_with(o.as_str()))
        })
    });
    (!found).then(|| format!("{pin}: no `{}` at {lines}:{columns} of {path}", operators.join("` or `")))
}

#[test]
fn the_mutation_tooling_names_files_functions_and_operators_that_are_there() {
    let script = std::fs::read_to_string(root().join("scripts/mutants.sh")).unwrap();
    let core = core_files(&script);
    assert!(core.len() > 20, "{core:?}");
    let mut problems: Vec<String> =
        core.iter().filter(|f| !root().join(f).is_file()).map(|f| format!("scripts/mutants.sh: no file {f}")).collect();
    let toml = std::fs::read_to_string(root().join(".cargo/mutants.toml")).unwrap();
    let pins = pins(&toml);
    assert!(pins.len() > 50, "{} pins", pins.len());
    problems.extend(pins.iter().filter_map(|p| pin_problem(p)));
    assert!(problems.is_empty(), "stale names in the mutation tooling:\n{}", problems.join("\n"));
}

#[test]
fn the_pin_check_finds_a_moved_file_a_missing_function_and_a_moved_operator() {
    assert_eq!(alternatives("(9|14)"), ["9", "14"]);
    assert_eq!(alternatives("8[56]"), ["85", "86"]);
    // src/stats/describe.rs's `ranks` scans ties with `let mut end = k + 1;` at line 30.
    assert_eq!(pin_problem("src/stats/describe.rs:30:25: replace \\\\+ with \\\\* in ranks"), None);
    assert!(pin_problem("src/report/stats.rs:43:25: replace \\\\+ with \\\\* in ranks").unwrap().contains("no file"));
    assert!(
        pin_problem("src/stats/describe.rs:30:25: replace \\\\+ with \\\\* in nowhere")
            .unwrap()
            .contains("no function")
    );
    assert!(pin_problem("src/stats/describe.rs:31:25: replace \\\\+ with \\\\* in ranks").unwrap().contains("no `+`"));
}
