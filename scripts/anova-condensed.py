#!/usr/bin/env python3
"""The condensed analysis-of-variance tables of a study summary, from the full ones that
`covga report` writes: for each `### heading` of the report's "Analysis of variance" section,
the main effects, the three largest two-way interactions, the residual and its part between
replicates, in the report's own numbers.

Usage: python3 scripts/anova-condensed.py REPORT/summary.md "cov_final_free" "t_final" ...
(each argument a heading of the report, printed as `### heading` with its table).
"""
import sys


def tables(path):
    """{heading: [table lines]} of the report's `###` sections."""
    out, heading, rows = {}, None, []
    for line in open(path, encoding="utf-8"):
        line = line.rstrip("\n")
        if line.startswith("### "):
            if heading:
                out[heading] = rows
            heading, rows = line[4:], []
        elif line.startswith("## ") and heading:
            out[heading], heading = rows, None
        elif heading and line.startswith("|"):
            rows.append(line)
    if heading:
        out[heading] = rows
    return out


def condensed(rows):
    head, body = rows[:2], rows[2:]
    term = lambda r: r.split("|")[1].strip()
    tail = [r for r in body if term(r) == "residual" or term(r).startswith("of which")]
    main = [r for r in body if r not in tail and "×" not in term(r)]
    inter = [r for r in body if r not in tail and "×" in term(r)][:3]
    return head + main + inter + tail


def main(path, headings):
    found = tables(path)
    for h in headings:
        if h not in found:
            sys.exit(f"{path}: no analysis-of-variance table `### {h}`")
        print(f"### {h}\n")
        print("\n".join(condensed(found[h])))
        print()


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2:])
