#!/usr/bin/env python3
"""docs/tuning.md's results table from the sessions scripts/tune_table.sh ran.

Usage: scripts/tune_table.py out/tuning/<set> [more sets...]

Reads <set>/<scene>/run-<n>/tune/confirmation.json (occtune), <set>/<scene>/run-<n>/peers/summary.json
(occsim bench with the tuned file) and load.txt, and prints per set one markdown table, a row per
scene: the tuned values of each run (the defaults in the header), the verdict, the tuned/defaults
mean frame-time ratio on the fitted and on the held-out frames (the median over occtune's
repetitions, the two runs' mean and half their range), tuned statistical+ against the fastest
other conservative culler of the same bench run, statistical+ over Ideal, and the loads.
"""
import json
import os
import sys

# Not candidates for "the fastest conservative peer": async may miss; ideal is the oracle; vfc is
# the reference every speedup is over (still a peer, it stays).
NOT_CONSERVATIVE = {"async", "ideal"}
TUNED = "statistical+"


def load(path):
    with open(path) as f:
        return json.load(f)


def runs_of(scene_dir):
    runs = []
    for name in sorted(os.listdir(scene_dir)):
        run = os.path.join(scene_dir, name)
        conf = os.path.join(run, "tune", "confirmation.json")
        if not name.startswith("run-") or not os.path.isfile(conf):
            continue
        peers = os.path.join(run, "peers", "summary.json")
        loads = os.path.join(run, "load.txt")
        written = [os.path.join(run, "tune", f) for f in ("tuned.json", "tuned.rejected.json")]
        written = [load(f) for f in written if os.path.isfile(f)]
        runs.append({
            "confirmation": load(conf),
            "written": written[0] if written else None,
            "peers": load(peers) if os.path.isfile(peers) else None,
            "loads": open(loads).read().split("\n") if os.path.isfile(loads) else [],
        })
    return runs


def mean_spread(values):
    values = [v for v in values if v is not None]
    if not values:
        return "n/a"
    mean = sum(values) / len(values)
    return f"{mean:.3f} ±{(max(values) - min(values)) / 2:.3f}"


def variant_ratio(conf, kind):
    for v in conf["variants"]:
        if v["variant"].startswith(kind):
            return v["mean_ratio"]["median"]
    return None


def peers_cell(peers):
    """Tuned statistical+ over the fastest other conservative culler (mean frame ms), and which."""
    if not peers:
        return None, "", None
    algos = {a["configuration"]: a for a in peers["algorithms"]}
    tuned = algos.get(TUNED)
    others = {c: a for c, a in algos.items()
              if c != TUNED and a["algorithm"] not in NOT_CONSERVATIVE and c not in NOT_CONSERVATIVE}
    if not tuned or not others:
        return None, "", None
    best = min(others, key=lambda c: others[c]["frame_ms"]["mean"])
    ideal = algos.get("ideal")
    ideal_ratio = (tuned["frame_ms"]["mean"] / ideal["frame_ms"]["mean"]) if ideal else None
    return tuned["frame_ms"]["mean"] / others[best]["frame_ms"]["mean"], best, ideal_ratio


def load_cell(lines):
    firsts = [line.split(": ")[1].split()[0] for line in lines if ": " in line]
    return "/".join(firsts)


def is_integer_option(run, name):
    """Whether the culler's option is an integer: tuned.json (or tuned.rejected.json) writes it as
    one, and the confirmation ran the tuned value rounded (confirmation.json before 2026-12-03
    kept the unrounded optimum)."""
    conf, written = run["confirmation"], run["written"]
    if not written:
        return False
    value = written.get("culling", {}).get(conf["culler"], {}).get(name)
    return isinstance(value, int) and not isinstance(value, bool)


def scene_row(scene, runs):
    confs = [r["confirmation"] for r in runs]
    values = []
    for run, conf in zip(runs, confs):
        parts = []
        for p in conf["parameters"]:
            mark = "" if not p["kept_at_reference"] else " (kept)"
            bound = f" [{p['bound_hit']} bound]" if p["bound_hit"] else ""
            tuned = round(p["tuned"]) if is_integer_option(run, p["name"]) else p["tuned"]
            parts.append(f"{p['name']}={tuned:.4g}{mark}{bound}")
        values.append(", ".join(parts))
    peer = [peers_cell(r["peers"]) for r in runs]
    best = sorted({b for _, b, _ in peer if b})
    error = sum(v["tuned_error_pixels"] for c in confs for v in c["variants"])
    missed = sum(v["tuned_missed_objects"] for c in confs for v in c["variants"])
    return [
        scene,
        "<br>".join(f"run {i + 1}: {v}" for i, v in enumerate(values)),
        ", ".join(c["verdict"] for c in confs),
        mean_spread([variant_ratio(c, "fitted") for c in confs]),
        mean_spread([variant_ratio(c, "held") for c in confs]),
        mean_spread([p for p, _, _ in peer]) + (f" ({', '.join(best)})" if best else ""),
        mean_spread([i for _, _, i in peer]),
        f"{error} / {missed}",
        "; ".join(load_cell(r["loads"]) for r in runs),
    ]


def table(set_dir):
    header = ["scene", "tuned values (per run)", "verdict", "tuned/defaults, fitted",
              "tuned/defaults, held out", "tuned/fastest other conservative", "tuned/Ideal",
              "error px / missed (tuned)", "load 1-min (tune before/after/peers before/after)"]
    rows, notes = [], []
    defaults = None
    for scene in sorted(os.listdir(set_dir)):
        scene_dir = os.path.join(set_dir, scene)
        if not os.path.isdir(scene_dir):
            continue
        runs = runs_of(scene_dir)
        failed = sorted(name for name in os.listdir(scene_dir)
                        if os.path.isfile(os.path.join(scene_dir, name, "failed.txt")))
        if failed:  # occtune ended without a confirmation, or the peers bench failed
            notes.append(f"{scene}: {', '.join(failed)}: " + "; ".join(
                open(os.path.join(scene_dir, name, "failed.txt")).read().strip()
                for name in failed))
        if not runs:
            continue
        defaults = defaults or ", ".join(f"{p['name']}={p['reference']:.4g}"
                                         for p in runs[0]["confirmation"]["parameters"])
        rows.append(scene_row(scene, runs))
    out = [f"### {os.path.basename(os.path.normpath(set_dir))}", ""]
    if defaults:
        out.append(f"Defaults of {TUNED}: {defaults}. Ratios below 1: tuned is faster.")
        out.append("")
    out.append("| " + " | ".join(header) + " |")
    out.append("|" + "---|" * len(header))
    out += ["| " + " | ".join(r) + " |" for r in rows]
    if notes:
        out += [""] + [f"- {n}" for n in notes]
    return "\n".join(out)


def main(argv):
    if len(argv) < 2:
        print("usage: tune_table.py out/tuning/<set> [more sets...]", file=sys.stderr)
        return 2
    for d in argv[1:]:
        if not os.path.isdir(d):
            print(f"tune_table.py: {d}: not a folder (run scripts/tune_table.sh first)",
                  file=sys.stderr)
            return 2
        print(table(d))
        print()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
