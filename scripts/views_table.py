#!/usr/bin/env python3
"""The shadow-pass table of docs/views.md from the runs scripts/views_table.sh made.

Usage: scripts/views_table.py out/views

Reads <scene>/{none,<sun>-<casters>}/run-<n>/summary.json (VFC's configuration) and prints one
markdown table: per scene, sun (low, high) and caster culling (frustum, receivers) the casters
the shadow pass drew a frame, the casters whose shadow ground truth shows on a visible pixel
(what a perfect caster culler would draw) and the ratio of the two, the shadow pass's CPU time,
VFC's frame time with the sun and without it (means of the runs, with the spread: half the
range), the shadow error pixels and missed casters summed over the runs, and the load average
before and after each run. A busy run is flagged: such a table is not a result.

Then a second table from the <sun>-culler and <sun>-both runs: per scene, sun, culler and mode
(the culler in the light's view alone, or with the receiver mask), the casters it drew against
those light-frustum culling drew (the <sun>-frustum runs), the light view's queries a frame, the
shadow pass's CPU time and the
culler's frame time with each, the shadow error pixels and missed casters summed over the runs.
"""
import json
import os
import sys

from table_figures import fmt, load_text, mean_spread


def summaries(folder):
    runs = []
    if not os.path.isdir(folder):
        return runs
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name, "summary.json")
        if name.startswith("run-") and os.path.isfile(path):
            with open(path) as f:
                runs.append(json.load(f))
    return runs


def config(summary, name):
    return next(a for a in summary["algorithms"] if a["configuration"] == name)


def vfc(summary):
    return config(summary, "vfc")


def has_vfc(summary):
    return any(a["configuration"] == "vfc" for a in summary["algorithms"])


def loads(runs):
    return ", ".join(load_text(s) for s in runs)


def main(root):
    print("| scene | sun | casters | casters drawn / frame | casters seen / frame | drawn / seen | "
          "shadow pass CPU ms | frame ms with sun | frame ms without | shadow err px | "
          "missed casters | load (before→after) |")
    print("|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for scene in sorted(os.listdir(root)):
        none_runs = [s for s in summaries(os.path.join(root, scene, "none")) if has_vfc(s)]
        plain_ms = mean_spread([vfc(s)["frame_ms"]["mean"] for s in none_runs])
        for sun, casters in [(s, c) for s in ("low", "high") for c in ("frustum", "receivers")]:
            folder = os.path.join(root, scene, f"{sun}-{casters}")
            if not os.path.isdir(folder):
                continue
            runs = summaries(folder)
            if not all(has_vfc(s) for s in runs):
                continue  # a run of other cullers only (--algos without vfc): the second table
            shadows = [vfc(s)["shadow_pass"] for s in runs]
            if not runs or any(sh is None for sh in shadows):
                print(f"| {scene} | {sun} | {casters} | no shadow pass | | | | | | | | |")
                continue
            drawn = mean_spread([sh["casters_per_frame"] for sh in shadows])
            seen = mean_spread([sh["seen_casters_per_frame"] for sh in shadows])
            ratio = drawn[0] / seen[0] if seen[0] else None
            cpu = mean_spread([sh["cpu_ms_mean"] for sh in shadows])
            frame = mean_spread([vfc(s)["frame_ms"]["mean"] for s in runs])
            error = sum(sh["error_pixels_total"] for sh in shadows)
            missed = sum(sh["missed_casters_total"] for sh in shadows)
            print(f"| {scene} | {sun} | {casters} | {fmt(*drawn)} | {fmt(*seen)} | "
                  f"{fmt(ratio, None, 2) + '×' if ratio else '-'} | {fmt(*cpu, digits=2)} | "
                  f"{fmt(*frame, digits=2)} | {fmt(*plain_ms, digits=2)} | {error} | {missed} | "
                  f"{loads(runs + none_runs)} |")


def culler_table(root):
    print()
    print("| scene | sun | culler | light view | casters drawn / frame | light-frustum | "
          "light-frustum / this | light-view queries / frame | shadow pass CPU ms | "
          "light-frustum | frame ms | light-frustum | shadow err px | missed casters | "
          "load (before→after) |")
    print("|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for scene in sorted(os.listdir(root)):
        for sun, mode in [(s, m) for s in ("low", "high") for m in ("culler", "both")]:
            culled = summaries(os.path.join(root, scene, f"{sun}-{mode}"))
            frustum = summaries(os.path.join(root, scene, f"{sun}-frustum"))
            if not culled or not frustum:
                continue
            for a in culled[0]["algorithms"]:
                name = a["configuration"]
                if any(config(s, name)["shadow_pass"] is None for s in culled + frustum):
                    print(f"| {scene} | {sun} | {name} | {mode} | no shadow pass | | | | | | | | | | |")
                    continue
                c = [config(s, name)["shadow_pass"] for s in culled]
                f = [config(s, name)["shadow_pass"] for s in frustum]
                drawn = mean_spread([sh["casters_per_frame"] for sh in c])
                frustum_drawn = mean_spread([sh["casters_per_frame"] for sh in f])
                ratio = frustum_drawn[0] / drawn[0] if drawn[0] else None
                queries = mean_spread([sh.get("queries_per_frame", 0.0) for sh in c])
                cpu = mean_spread([sh["cpu_ms_mean"] for sh in c])
                frustum_cpu = mean_spread([sh["cpu_ms_mean"] for sh in f])
                frame = mean_spread([config(s, name)["frame_ms"]["mean"] for s in culled])
                frustum_frame = mean_spread([config(s, name)["frame_ms"]["mean"] for s in frustum])
                error = sum(sh["error_pixels_total"] for sh in c)
                missed = sum(sh["missed_casters_total"] for sh in c)
                label = "culler" if mode == "culler" else "culler + receivers"
                print(f"| {scene} | {sun} | {name} | {label} | {fmt(*drawn)} | {fmt(*frustum_drawn)} | "
                      f"{fmt(ratio, None, 2) + '×' if ratio else '-'} | {fmt(*queries)} | "
                      f"{fmt(*cpu, digits=2)} | "
                      f"{fmt(*frustum_cpu, digits=2)} | {fmt(*frame, digits=2)} | "
                      f"{fmt(*frustum_frame, digits=2)} | {error} | {missed} | "
                      f"{loads(culled)} |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: scripts/views_table.py out/views")
    main(sys.argv[1])
    culler_table(sys.argv[1])
