#!/usr/bin/env python3
"""Lines of Rust per top-level module of crate/src at git revisions, as a Markdown table.

    python3 scripts/module-lines.py 23d8948 HEAD

Counts every line of every .rs file (tests, comments and blank lines included) under
crate/src/<module> or in crate/src/<module>.rs; the binary is `bin`, lib.rs is `lib`.
Tests kept in their own files (tests.rs, tests_*.rs) are counted apart, in `of which tests`.
"""
import subprocess
import sys
from collections import defaultdict


def count(rev):
    files = subprocess.run(
        ["git", "ls-tree", "-r", "--name-only", rev, "crate/src"],
        check=True, capture_output=True, text=True,
    ).stdout.split()
    lines, tests = defaultdict(int), defaultdict(int)
    for f in files:
        if not f.endswith(".rs"):
            continue
        text = subprocess.run(["git", "show", f"{rev}:{f}"], check=True,
                              capture_output=True, text=True).stdout
        module = f.split("/")[2].removesuffix(".rs")
        n = text.count("\n")
        lines[module] += n
        if f.rsplit("/", 1)[-1].startswith("tests"):
            tests[module] += n
    return lines, tests


def main(revs):
    counts = [count(r) for r in revs]
    modules = sorted(set().union(*(c[0].keys() for c in counts)))
    head = " | ".join(f"{r} lines (of which tests)" for r in revs)
    print(f"| module | {head} |")
    print("|---|" + "---:|" * len(revs))
    for m in modules:
        cells = " | ".join(
            f"{c[0][m]:,} ({c[1][m]:,})".replace(",", " ") if m in c[0] else "-" for c in counts)
        print(f"| {m} | {cells} |")
    total = " | ".join(f"{sum(c[0].values()):,}".replace(",", " ") for c in counts)
    print(f"| all | {total} |")


if __name__ == "__main__":
    main(sys.argv[1:] or ["HEAD"])
