#!/usr/bin/env python3
"""The stereo table of docs/views.md from the runs scripts/stereo_table.sh made.

Usage: scripts/stereo_table.py out/stereo

Reads <scene>/<mode>/run-<n>/{summary.json,frames.csv} for the modes mono (the camera alone),
enclosing and per_eye, and prints one markdown table: per scene, culler and mode the frame time
(mean of the runs' means, with the spread: half the range) and its ratio to the mono run's, the
objects drawn and the queries a frame (submissions: in `enclosing` one per object for both eyes,
in `per_eye` each eye's added), the error pixels summed over the runs (with each eye's part from
frames.csv) and the load average before and after each run. A busy run is flagged: such a table
is not a result.
"""
import csv
import json
import os
import sys

from table_figures import fmt, load_text, mean_spread

MODES = ("mono", "enclosing", "per_eye")


def runs_of(folder):
    runs = []
    if not os.path.isdir(folder):
        return runs
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        if name.startswith("run-") and os.path.isfile(os.path.join(path, "summary.json")):
            with open(os.path.join(path, "summary.json")) as f:
                summary = json.load(f)
            with open(os.path.join(path, "frames.csv")) as f:
                frames = list(csv.DictReader(f))
            runs.append((summary, frames))
    return runs


def config(summary, name):
    return next(a for a in summary["algorithms"] if a["configuration"] == name)


def loads(runs):
    return ", ".join(load_text(s) for s, _ in runs)


def eye_errors(runs, name):
    left = right = 0
    for _, frames in runs:
        for row in frames:
            if row["configuration"] != name:
                continue
            left += max(int(row["left_error_pixels"]), 0)
            right += max(int(row["right_error_pixels"]), 0)
    return left, right


def main(root):
    print("| scene | culler | eyes | frame ms | / mono | objects drawn / frame | queries / frame | "
          "error px (left, right) | missed objects | load (before→after) |")
    print("|---|---|---|---:|---:|---:|---:|---:|---:|---|")
    for scene in sorted(os.listdir(root)):
        by_mode = {m: runs_of(os.path.join(root, scene, m)) for m in MODES}
        first = next((r for r in by_mode.values() if r), None)
        if not first:
            continue
        for a in first[0][0]["algorithms"]:
            name = a["configuration"]
            mono_ms = mean_spread([config(s, name)["frame_ms"]["mean"] for s, _ in by_mode["mono"]])
            for mode in MODES:
                runs = by_mode[mode]
                if not runs:
                    continue
                frame = mean_spread([config(s, name)["frame_ms"]["mean"] for s, _ in runs])
                ratio = frame[0] / mono_ms[0] if mono_ms[0] else None
                drawn = mean_spread([config(s, name)["objects_per_frame"] for s, _ in runs])
                queries = mean_spread([config(s, name)["queries_per_frame"] for s, _ in runs])
                error = sum(config(s, name)["error"]["pixels_total"] for s, _ in runs)
                missed = sum(config(s, name)["error"]["missed_objects_total"] for s, _ in runs)
                eyes = f" ({eye_errors(runs, name)[0]}, {eye_errors(runs, name)[1]})" if mode != "mono" else ""
                label = {"mono": "one (camera)", "enclosing": "two, enclosing", "per_eye": "two, per eye"}[mode]
                print(f"| {scene} | {name} | {label} | {fmt(*frame, digits=2)} | "
                      f"{fmt(ratio, None, 2) + '×' if ratio else '-'} | {fmt(*drawn)} | "
                      f"{fmt(*queries)} | {error}{eyes} | {missed} | {loads(runs)} |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: scripts/stereo_table.py out/stereo")
    main(sys.argv[1])
