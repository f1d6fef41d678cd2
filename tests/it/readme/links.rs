//! Links of Markdown pages: which targets a page links to, and whether a target resolves to a
//! file of the repository and an anchor of it.

use std::path::{Component, Path, PathBuf};

/// The text of `markdown` outside fenced code blocks and inline code spans.
fn prose(markdown: &str) -> String {
    let mut out = String::new();
    let mut fenced = false;
    for line in markdown.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        // Inline code: drop what lies between pairs of backticks.
        for (k, part) in line.split('`').enumerate() {
            if k % 2 == 0 {
                out.push_str(part);
            }
        }
        out.push('\n');
    }
    out
}

/// The targets of the links and images of `markdown` (`[text](target)`), web addresses left out.
pub fn links(markdown: &str) -> Vec<String> {
    let text = prose(markdown);
    let mut out = Vec::new();
    for (at, _) in text.match_indices("](") {
        let rest = &text[at + 2..];
        let Some(end) = rest.find(')') else { continue };
        let target = rest[..end].split_whitespace().next().unwrap_or("");
        if target.is_empty()
            || target.starts_with("http://")
            || target.starts_with("https://")
            || target.starts_with("mailto:")
        {
            continue;
        }
        out.push(target.to_string());
    }
    out
}

/// The id mdBook and GitHub give a heading: lower case, spaces as `-`, punctuation dropped.
pub fn slug(heading: &str) -> String {
    heading
        .replace('`', "")
        .chars()
        .filter_map(|c| {
            if c.is_alphanumeric() || c == '_' || c == '-' {
                Some(c.to_ascii_lowercase())
            } else if c.is_whitespace() {
                Some('-')
            } else {
                None
            }
        })
        .collect()
}

/// The anchors of a page: its headings' ids and its `<a id="…">`s.
pub fn anchors(markdown: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut fenced = false;
    for line in markdown.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        } else if !fenced && line.starts_with('#') {
            out.push(slug(line.trim_start_matches('#').trim()));
        }
    }
    out.extend(markdown.split("<a id=\"").skip(1).filter_map(|r| r.split('"').next()).map(str::to_string));
    out
}

/// `path` with `.` and `..` resolved lexically.
fn normalise(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            Component::ParentDir => {
                out.pop();
            }
            Component::CurDir => {}
            other => out.push(other),
        }
    }
    out
}

/// Whether `link` on `page` (a path from `root`) resolves: its file exists inside the
/// repository and its anchor, if any, is one of that page's.
pub fn resolve(root: &Path, page: &Path, link: &str) -> Result<(), String> {
    let (file, anchor) = match link.split_once('#') {
        Some((f, a)) => (f, Some(a)),
        None => (link, None),
    };
    let target = if file.is_empty() { page.to_path_buf() } else { normalise(&page.parent().unwrap().join(file)) };
    if target.starts_with("..") || !root.join(&target).exists() {
        return Err(format!("no file {} in the repository", target.display()));
    }
    if let Some(anchor) = anchor {
        let text = std::fs::read_to_string(root.join(&target)).map_err(|e| e.to_string())?;
        if !anchors(&text).iter().any(|a| a == anchor) {
            return Err(format!("no anchor #{anchor} in {}", target.display()));
        }
    }
    Ok(())
}

#[test]
fn links_and_anchors_are_read_as_mdbook_writes_them() {
    let page = "# The thesis GA: `covga run`\n\nSee [a](x.md#b), ![f](p.png \"t\") and [w](https://e.org).\n\
                `[not](code.md)`\n```sh\n[no](fence.md)\n```\n<a id=\"r12\"></a>\n";
    assert_eq!(links(page), ["x.md#b", "p.png"]);
    assert_eq!(anchors(page), ["the-thesis-ga-covga-run", "r12"]);
    assert_eq!(slug("§3.3 The swept rectangle"), "33-the-swept-rectangle");
    assert_eq!(normalise(Path::new("docs/src/guide/../../../results/x")), PathBuf::from("results/x"));
}
