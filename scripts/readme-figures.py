#!/usr/bin/env python3
"""Regenerates the README's "Figures" table (between the figures:begin and figures:end
markers) from runs of the release CLI on this machine: run it, paste nothing by hand.

    python3 scripts/readme-figures.py            # builds target/release/ridelab first

Each timing is the median wall time of 3 runs of the whole process; the machine, the date
and the load average are written with them. Counts (model runs) come from the commands'
own JSON. The wasm sizes are read from dist/ when a page build is there.
"""
import gzip
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CLI = ROOT / "target" / "release" / "ridelab"
CAR = "assets/examples/sedan-laden.json"
CASES = "assets/examples/cases-b-10-20-30.json"


def run(args, runs=3):
    """(median wall seconds, parsed JSON of the last run or None)."""
    times, out = [], None
    for _ in range(runs):
        t = time.perf_counter()
        p = subprocess.run([str(CLI), *args], cwd=ROOT, capture_output=True, text=True, check=True)
        times.append(time.perf_counter() - t)
        out = p.stdout
    try:
        data = json.loads(out)
    except ValueError:
        data = None
    return statistics.median(times), data


def runs(n):
    """A count with spaces between thousands, as the README writes them."""
    return f"{n:,}".replace(",", " ")


def machine():
    model = "unknown CPU"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    load = os.getloadavg()[0]
    return f"{os.cpu_count()} cores ({model}), {platform.system()}, load average {load:.1f} at the start"


def rows():
    out = []
    with tempfile.TemporaryDirectory() as d:
        t, rep = run(["report", "--out", d, "--json"])
        sections = ", ".join(f"{s['name']} {s['seconds']:.2f} s" for s in rep["sections"])
        out.append(("`ridelab report` (the default car), whole process", f"{t:.2f} s", f"sections: {sections}"))
    t, o = run(["optimize", "--evaluator", "full", "--method", "stm", "--json"])
    out.append(("`ridelab optimize --evaluator full --method stm` (STM 201, 3 levels)", f"{t:.2f} s", f"{runs(o['evaluations'])} HiFi runs"))
    t, o = run(["optimize", "--evaluator", "full", "--grid", "61", "--levels", "2", "--json"])
    out.append(("`ridelab optimize --evaluator full --grid 61 --levels 2` (the page's HiFi front)", f"{t:.2f} s", f"{runs(o['evaluations'])} HiFi runs"))
    t, o = run(["optimize", "--evaluator", "full", "--grid", "61", "--levels", "2", "--car", CAR, "--cases", CASES, "--json"])
    out.append(("the same on the laden sedan's 6 cases (class B at 10, 20, 30 m/s)", f"{t:.2f} s", f"{runs(o['evaluations'])} HiFi runs"))
    for tracks in ["correlated", "independent"]:
        t, _ = run(["map", "--model", "full", "--ks-range", "10000:40000:160", "--cs-range", "500:4000:120", "--compute", "cpu", "--tracks", tracks, "--json"])
        out.append((f"`ridelab map --model full` 160 x 120, {tracks} tracks", f"{t:.2f} s", ""))
    # A measured road (#31): describing the shipped profiles, and the HiFi map on one
    # against the same map on its ISO class (the bound: at most 2x).
    for road in ["concrete-slab-5m.csv", "class-c-waviness-2.5.csv"]:
        t, o = run(["road", f"assets/roads/{road}", "--json"])
        out.append((f"`ridelab road assets/roads/{road}`, whole process", f"{t:.2f} s", f"{runs(o['samples'])} samples, {o['tracks']} track{'s' if o['tracks'] == 2 else ''}, {o['length_m'] / 1000:g} km"))
    # Each measured map against the same map on class C with the same track setting:
    # one track seen by both wheels against correlated tracks, two measured tracks (both
    # halves of the car excited) against independent ones (both halves too) and against
    # correlated ones (one half). The maps are written as CSV, the same bytes for every
    # road: the JSON's feasible set is as large as the road makes it (14 423 points on the
    # slab road, none on class C), so its writing would be timed, not the models. The
    # four run in turn, 7 rounds; the ratios are the medians of each round's ratio.
    grid = ["--ks-range", "10000:40000:160", "--cs-range", "500:4000:120", "--csv"]
    cmds = {
        "correlated": ["--class", "C", "--compute", "cpu", "--tracks", "correlated"],
        "independent": ["--class", "C", "--compute", "cpu", "--tracks", "independent"],
        "slab": ["--road", "assets/roads/concrete-slab-5m.csv"],
        "profile": ["--road", "assets/roads/class-c-waviness-2.5.csv"],
    }
    rounds = [{k: run(["map", "--model", "full", *c, *grid], runs=1)[0] for k, c in cmds.items()} for _ in range(7)]
    med = lambda f: statistics.median(f(r) for r in rounds)
    t = {k: med(lambda r, k=k: r[k]) for k in cmds}
    out.append(("`ridelab map --model full --road assets/roads/concrete-slab-5m.csv` 160 x 120 (one track, both wheels; CSV)", f"{t['slab'] * 1000:.0f} ms", f"{med(lambda r: r['slab'] / r['correlated']):.2f}x the same map on class C, correlated tracks ({t['correlated'] * 1000:.0f} ms)"))
    out.append(("`ridelab map --model full --road assets/roads/class-c-waviness-2.5.csv` 160 x 120 (two measured tracks; CSV)", f"{t['profile'] * 1000:.0f} ms", f"{med(lambda r: r['profile'] / r['independent']):.2f}x the same map on class C with independent tracks ({t['independent'] * 1000:.0f} ms), {med(lambda r: r['profile'] / r['correlated']):.2f}x with correlated tracks"))
    names = {
        "ridelab-first_bg.wasm": "the page's first-screen wasm (dist/, fetched before the first map)",
        "ridelab_bg.wasm": "the page's on-demand wasm (dist/, the workers', fetched after the first map)",
    }
    for name, what in names.items():
        path = ROOT / "dist" / name
        if path.exists():
            raw = path.read_bytes()
            out.append((what, f"{len(raw):,} bytes".replace(",", " "), f"{len(gzip.compress(raw, 9)):,} gzipped (level 9)".replace(",", " ")))
    return out


def main():
    subprocess.run(["cargo", "build", "--release", "-p", "ridelab"], cwd=ROOT, check=True)
    head = f"Measured {time.strftime('%Y-%m-%d')} by `python3 scripts/readme-figures.py` on {machine()}; median of 3 wall times, release build."
    table = ["| what | time or size | notes |", "|---|---|---|"]
    table += [f"| {a} | {b} | {c} |" for a, b, c in rows()]
    block = "\n".join([head, "", *table])
    readme = (ROOT / "README.md").read_text()
    begin, end = "<!-- figures:begin -->", "<!-- figures:end -->"
    if begin not in readme or end not in readme:
        sys.exit("README.md lacks the figures markers")
    before, rest = readme.split(begin, 1)
    _, after = rest.split(end, 1)
    (ROOT / "README.md").write_text(f"{before}{begin}\n{block}\n{end}{after}")
    print(block)


if __name__ == "__main__":
    main()
