#!/usr/bin/env python3
"""The tables of docs/results.md from the runs scripts/results.sh made.

Usage: scripts/results_table.py [--one-run] out/results/<set> [more sets...]

Reads <set>/<scene>/run-<n>/summary.json (two or more runs per scene) and prints, per set, one
markdown table: per scene and algorithm the speedup over VFC as the mean of the runs with their
spread (half the range), VFC's frame time, the ratio of statistical+ to Ideal, the fastest
conservative culler (bold; every culler within the spread of the fastest is marked too), the
error (pixels and missed objects, summed over the runs) and the load average before and after each
run. A run whose summary says busy is flagged: such a table is not a result. --one-run takes
scenes of one run (scripts/results.sh --quick): no spread, and said to be no result. A second table per set
gives each culler's own CPU time per frame (`cull ms`: deciding, queries' bookkeeping, the software
buffer of masked; draws and waits excluded) and the objects it drew per frame, means of the runs.
"""
import json
import os
import sys

ORDER = ["vfc", "stop-and-wait", "statistical", "statistical+", "chc", "chc++", "async", "conditional",
         "hzb", "raster", "masked", "ideal-box", "ideal"]
NOT_CONSERVATIVE = {"async", "ideal", "ideal-box"}  # async may miss; the oracles are not cullers
# ideal-box is not timed against the cullers (it queries every box it cannot rule out): the tables
# give its triangles per frame beside those of the query cullers and Ideal instead of a speedup.
NOT_TIMED = {"ideal-box"}
TRIANGLE_COLUMNS = ["statistical+", "chc", "chc++", "ideal-box", "ideal"]
MIN_RUNS = 2  # 1 with --one-run


def runs_of(scene_dir):
    """Each run's summary; a run's cullers measured in a process of their own (a subfolder with
    its own summary.json, e.g. run-1/conditional/, beside its own VFC) join it, each with the
    speedup over the VFC of its own process."""
    runs = []
    for name in sorted(os.listdir(scene_dir)):
        run_dir = os.path.join(scene_dir, name)
        path = os.path.join(run_dir, "summary.json")
        if not (name.startswith("run-") and os.path.isfile(path)):
            continue
        with open(path) as f:
            summary = json.load(f)
        have = {a["configuration"] for a in summary["algorithms"]}
        for sub in sorted(os.listdir(run_dir)):
            sub_path = os.path.join(run_dir, sub, "summary.json")
            if os.path.isfile(sub_path):
                with open(sub_path) as f:
                    apart = json.load(f)
                summary["algorithms"] += [a for a in apart["algorithms"]
                                          if a["configuration"] not in have]
        runs.append(summary)
    return runs


def scenes_with_runs(set_dir, warn=False):
    """(scene, runs) for every scene folder of the set with MIN_RUNS or more runs."""
    for scene in sorted(os.listdir(set_dir)):
        scene_dir = os.path.join(set_dir, scene)
        if not os.path.isdir(scene_dir):
            continue
        runs = runs_of(scene_dir)
        if len(runs) < MIN_RUNS:
            if warn:
                print(f"results_table: {scene_dir}: {len(runs)} run(s); the tables need "
                      f"{MIN_RUNS}", file=sys.stderr)
            continue
        yield scene, runs


def configurations(tables):
    """The configurations every run has: the built-ins in ORDER, then the others as run."""
    configs = [c for c in ORDER if all(c in t for t in tables)]
    return configs + [c for c in tables[0] if c not in configs and all(c in t for t in tables)]


def by_configuration(summary):
    return {a["configuration"]: a for a in summary["algorithms"]}


def fmt_load(machine):
    before = machine.get("load_average_before") or [float("nan")]
    after = machine.get("load_average_after") or [float("nan")]
    return f"{before[0]:.2f}/{after[0]:.2f}"


def scene_row(scene, runs):
    tables = [by_configuration(r) for r in runs]
    configs = configurations(tables)
    speed = {}
    for c in configs:
        if c in NOT_TIMED:
            continue
        values = [t[c].get("speedup_over_vfc") for t in tables]  # absent: no timed frame
        if any(v is None for v in values):
            continue
        speed[c] = (sum(values) / len(values), (max(values) - min(values)) / 2)
    conservative = [c for c in speed if c not in NOT_CONSERVATIVE]
    fastest = max(conservative, key=lambda c: speed[c][0]) if conservative else None
    best_mean, best_spread = speed[fastest] if fastest else (0.0, 0.0)
    cells = {}
    for c in configs:
        if c in NOT_TIMED:
            continue
        if c not in speed:
            cells[c] = "n/a"
            continue
        mean, spread = speed[c]
        text = f"{mean:.2f}× ±{spread:.2f}" if len(runs) > 1 else f"{mean:.2f}×"
        if c == fastest:
            text = f"**{text}**"
        elif len(runs) > 1 and c in conservative and mean + spread >= best_mean - best_spread:
            text = f"_{text}_"  # within the spread of the fastest
        cells[c] = text
    vfc_ms = [t["vfc"]["frame_ms"]["mean"] for t in tables if "vfc" in t]
    error_px = sum(t[c].get("error", {}).get("pixels_total", 0) for t in tables for c in configs
                   if c not in NOT_CONSERVATIVE)
    missed = sum(t[c].get("error", {}).get("missed_objects_total", 0) for t in tables for c in configs
                 if c not in NOT_CONSERVATIVE)
    ideal_ratio = ""
    if "statistical+" in configs and all(t["statistical+"].get("ratio_to_ideal") for t in tables):
        ratios = [t["statistical+"]["ratio_to_ideal"] for t in tables]
        ideal_ratio = f"{sum(ratios) / len(ratios):.2f}"
    loads = ", ".join(fmt_load(r["machine"]) + (" BUSY" if r["machine"].get("busy") else "")
                      for r in runs)
    vfc = f"{sum(vfc_ms) / len(vfc_ms):.1f}" if vfc_ms else "n/a"
    triangles = []
    for c in TRIANGLE_COLUMNS:
        values = [t[c]["triangles_per_frame"] for t in tables if c in t]
        triangles.append(f"{sum(values) / len(values) / 1000:.1f}" if len(values) == len(tables)
                         else "–")
    return (cells, [scene, vfc], [" / ".join(triangles), ideal_ratio, f"{error_px} / {missed}",
                                  loads], fastest)


def table(set_dir):
    rows, columns, leads, scenes = [], [], 0, 0
    for scene, runs in scenes_with_runs(set_dir, warn=True):
        cells, head, tail, fastest = scene_row(scene, runs)
        # Scenes may have run different configurations (a sweep over other values): one column
        # per configuration any scene has, a dash where a scene lacks it.
        columns += [c for c in cells if c not in columns]
        rows.append((cells, head, tail))
        scenes += 1
        leads += fastest == "statistical+"
    if not rows:
        return f"(no scene of {set_dir} has {MIN_RUNS} runs)\n"
    header = ["scene", "VFC ms"] + columns + ["K triangles/frame: " + " / ".join(TRIANGLE_COLUMNS),
                                              "statistical+ / Ideal",
                                              "error px / missed (conservative)",
                                              "load before/after per run"]
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for cells, head, tail in rows:
        out.append("| " + " | ".join(head + [cells.get(c, "–") for c in columns] + tail) + " |")
    out.append("")
    if MIN_RUNS == 1:
        out.append(f"statistical+ fastest conservative culler on {leads} of {scenes} scenes "
                   f"(bold: fastest). One run a scene (--quick): no spread; not a result.")
    else:
        out.append(f"statistical+ fastest conservative culler on {leads} of {scenes} scenes "
                   f"(bold: fastest; italic: within the spread of the fastest).")
    return "\n".join(out) + "\n"


def cost_table(set_dir):
    """Per scene and culler: cull CPU ms per frame (mean of the runs ± half their range) and
    objects drawn per frame (mean of the runs)."""
    rows, columns = [], []
    for scene, runs in scenes_with_runs(set_dir):
        tables = [by_configuration(r) for r in runs]
        configs = configurations(tables)
        cells = {}
        for c in configs:
            cull = [t[c]["cull_cpu_ms_mean"] for t in tables]
            objects = [t[c]["objects_per_frame"] for t in tables]
            spread = f" ±{(max(cull) - min(cull)) / 2:.2f}" if len(runs) > 1 else ""
            cells[c] = (f"{sum(cull) / len(cull):.2f}{spread}"
                        f" / {sum(objects) / len(objects):.0f}")
        columns += [c for c in cells if c not in columns]
        rows.append((scene, cells))
    if not rows:
        return ""
    header = ["scene"] + columns
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for scene, cells in rows:
        out.append("| " + " | ".join([scene] + [cells.get(c, "–") for c in columns]) + " |")
    out.append("")
    if MIN_RUNS == 1:
        out.append("Each cell: the culler's CPU ms per frame (one run) / objects drawn per frame.")
    else:
        out.append("Each cell: the culler's CPU ms per frame ± half the range of the runs / "
                   "objects drawn per frame.")
    return "\n".join(out) + "\n"


def main(argv):
    global MIN_RUNS
    if len(argv) > 1 and argv[1] == "--one-run":
        MIN_RUNS = 1
        argv = argv[:1] + argv[2:]
    if len(argv) < 2:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    for set_dir in argv[1:]:
        if not os.path.isdir(set_dir):
            print(f"results_table: {set_dir}: no such folder (run scripts/results.sh first)",
                  file=sys.stderr)
            return 2
        print(f"### {os.path.basename(os.path.normpath(set_dir))}\n")
        print(table(set_dir))
        costs = cost_table(set_dir)
        if costs:
            print(f"#### {os.path.basename(os.path.normpath(set_dir))}: cull ms / objects per frame\n")
            print(costs)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
