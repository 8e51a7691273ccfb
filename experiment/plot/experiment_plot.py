#!/usr/bin/env python3
"""Figures of a `smart experiment` (results.csv): PNG and SVG, with Debian's python3-matplotlib.

Usage: experiment_plot.py RESULTS_DIR OUT_DIR

Figures (each only when the results vary along its axis):
  sim_speed.{png,svg}      sim speed vs robots, a line per map / robot model / QoS profile
  aet_makespan.{png,svg}   AET and makespan vs robots, mean +- sd over repeats (replicability)
  memory.{png,svg}         peak memory of monitor and sim, and CPU seconds per sim second, vs
                           robots
  success.{png,svg}        success rate vs robots, per robot model / QoS profile
  stalls.{png,svg}         AET and success rate vs stall probability (when it varies), a line
                           per fleet size / robot model
  link.{png,svg}           AET and success rate vs the link's delay to the hosts (when it
                           varies: QoS profiles with different link sections)
  table.md                 one row per cell of the grid (every parameter but the repeat): runs,
                           success rate, AET and makespan mean +- sd, sim speed, collisions
Prints one JSON line naming the files written.
"""
import csv
import json
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")  # no display: files only
import matplotlib.pyplot as plt  # noqa: E402


def number(text):
    try:
        v = float(text)
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) else None


def read_rows(results_dir):
    with open(os.path.join(results_dir, "results.csv"), newline="") as f:
        return list(csv.DictReader(f))


def series_key(row, keys):
    return " / ".join(row[k] for k in keys if row.get(k))


def varying(rows, keys):
    """The grouping columns that take more than one value (they name the lines)."""
    return [k for k in keys if len({r.get(k) for r in rows}) > 1]


def grouped(rows, field, line_keys, x_field="agents"):
    """line -> x (robots by default) -> [values of field] (None skipped)."""
    out = defaultdict(lambda: defaultdict(list))
    for r in rows:
        v = number(r.get(field))
        x = number(r.get(x_field))
        if v is not None and x is not None:
            out[series_key(r, line_keys) or "all"][x].append(v)
    return out


def mean_sd(values):
    m = sum(values) / len(values)
    sd = math.sqrt(sum((v - m) ** 2 for v in values) / (len(values) - 1)) if len(values) > 1 else 0.0
    return m, sd


def natural(text):
    """Sort key: numbers by value ("5 / a" before "10 / a")."""
    return [(0, float(p), "") if number(p) is not None else (1, 0.0, p)
            for p in text.split(" / ")]


def draw(ax, series, label_suffix=""):
    for line, by_n in sorted(series.items(), key=lambda kv: natural(kv[0])):
        ns = sorted(by_n)
        stats = [mean_sd(by_n[n]) for n in ns]
        label = line
        ax.errorbar(ns, [m for m, _ in stats], yerr=[s for _, s in stats], marker="o", capsize=3,
                    label=line + label_suffix)


def save(fig, out_dir, name, written):
    for ext in ("png", "svg"):
        path = os.path.join(out_dir, f"{name}.{ext}")
        fig.savefig(path, dpi=120, bbox_inches="tight")
        written.append(path)
    plt.close(fig)


def figure(out_dir, name, title, ylabel, panels, written, logx=True, xlabel="robots"):
    fig, axes = plt.subplots(1, len(panels), figsize=(6 * len(panels), 4), squeeze=False)
    for ax, (series, sub, suffix) in zip(axes[0], panels):
        draw(ax, series, suffix)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel if not sub else sub)
        if logx:
            ax.set_xscale("log")
        ax.grid(True, alpha=0.3)
        if series:
            ax.legend(fontsize=8)
    fig.suptitle(title)
    save(fig, out_dir, name, written)


def write_table(rows, out_dir, written):
    """The paper-style table: repeats folded into mean +- sd."""
    keys = ["map", "scen", "agents", "robot", "qos", "uncertainty", "plan", "clock"]
    groups = defaultdict(list)
    for r in rows:
        groups[tuple(r.get(k, "") for k in keys)].append(r)

    def stat(rs, field, fmt="{:.1f}"):
        vs = [number(r.get(field)) for r in rs]
        vs = [v for v in vs if v is not None]
        if not vs:
            return "-"
        m, sd = mean_sd(vs)
        return (fmt + " \u00b1 " + fmt).format(m, sd) if len(vs) > 1 else fmt.format(m)

    lines = ["| " + " | ".join(keys) + " | runs | success | AET (s) | makespan (s) | sim speed | "
             "collisions |", "|" + "---|" * (len(keys) + 6)]
    for key in sorted(groups, key=lambda k: [natural(str(x)) for x in k]):
        rs = groups[key]
        ok = sum(1 for r in rs if r.get("success") == "true")
        lines.append("| " + " | ".join(str(k) for k in key) + f" | {len(rs)} | {ok}/{len(rs)} | "
                     + " | ".join([stat(rs, "aet_s"), stat(rs, "makespan_s"),
                                   stat(rs, "sim_speed"), stat(rs, "collisions", "{:.0f}")])
                     + " |")
    path = os.path.join(out_dir, "table.md")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    written.append(path)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    results_dir, out_dir = sys.argv[1], sys.argv[2]
    rows = read_rows(results_dir)
    if not rows:
        sys.exit(f"{results_dir}/results.csv has no runs")
    os.makedirs(out_dir, exist_ok=True)
    lines = varying(rows, ["map", "robot", "qos", "clock"])
    logx = len({r["agents"] for r in rows}) > 2
    written = []
    figure(out_dir, "sim_speed", "Sim speed (sim s per wall s)", "sim speed (x real time)",
           [(grouped(rows, "sim_speed", lines), None, "")], written, logx)
    figure(out_dir, "aet_makespan", "AET and makespan, mean \u00b1 sd over repeats", "s",
           [(grouped(rows, "aet_s", lines), "AET (s)", ""),
            (grouped(rows, "makespan_s", lines), "makespan (s)", "")], written, logx)
    figure(out_dir, "memory", "Memory and CPU", "MB",
           [(grouped(rows, "peak_rss_mb.monitor", lines), "monitor peak RSS (MB)", ""),
            (grouped(rows, "peak_rss_mb.sim", lines), "sim peak RSS (MB)", ""),
            (grouped(rows, "cpu_s_per_sim_s", lines), "CPU s per sim s (monitor + sim)", "")],
           written, logx)
    success = [dict(r, success_rate="1" if r.get("success") == "true" else "0") for r in rows]
    figure(out_dir, "success", "Success rate", "success rate",
           [(grouped(success, "success_rate", lines), None, "")], written, logx)
    stall = "uncertainty.stall_probability"
    if len({r.get(stall) for r in rows}) > 1:
        by = ["agents"] + varying(rows, ["map", "robot", "qos"])
        figure(out_dir, "stalls", "Execution uncertainty: stalls at action start", "",
               [(grouped(rows, "aet_s", by, stall), "AET (s)", ""),
                (grouped(success, "success_rate", by, stall), "success rate", "")],
               written, False, "stall probability")
    delay = "link.to_host.delay_ms"
    if len({r.get(delay) for r in rows}) > 1:
        by = ["agents"] + varying(rows, ["map", "robot"])
        figure(out_dir, "link", "Link delay (monitor to hosts)", "",
               [(grouped(rows, "aet_s", by, delay), "AET (s)", ""),
                (grouped(success, "success_rate", by, delay), "success rate", "")],
               written, False, "link delay (ms)")
    write_table(rows, out_dir, written)
    print(json.dumps({"figures": written, "runs": len(rows)}))


if __name__ == "__main__":
    main()
