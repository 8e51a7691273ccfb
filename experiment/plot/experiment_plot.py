#!/usr/bin/env python3
"""Figures of a `smart experiment` (results.csv): PNG, SVG and PDF, with Debian's
python3-matplotlib, and figures.json, the data each figure shows.

Usage: experiment_plot.py RESULTS_DIR OUT_DIR

Every grid axis that varies is shown, never silently averaged (issue 26): plan (the planner),
robot model, QoS profile, uncertainty setting and clock are lines (the legend's title names
them), maps are panels, and scens are pooled, named in the title ("pooled over 3 scens"): a
scen is one sample of its map's instances. Each point is the mean of its n runs (n beside the
point, or in the caption when every point has the same n); error bars, only where n >= 2, are
one standard deviation, as the caption says. An axis is logarithmic only when its values span
a factor of 10 or more, with plain tick labels at the data; rates run from 0 to 1.

Figures (each when its data exist):
  aet_makespan     AET and makespan vs robots
  sim_speed        sim speed vs robots
  success          success rate vs robots
  memory           monitor and sim peak memory, CPU seconds per sim second, vs robots
  planner_runtime  planner wall seconds vs robots, a line per plan (when planners ran here)
  stalls           AET and success rate vs stall probability (when it varies)
  link             AET and success rate vs the link's delay to the hosts (when it varies)
  throughput       lifelong runs: throughput (tasks per minute) and mean task latency vs robots
  paired           switching runs (issue 29): each run's change against plain ADG's run of the
                   same cell and seed, in %: total waiting, and AET (plan runs) or tasks finished
                   (lifelong runs); a line per switching execution, zero marked
  paired_uncertainty  the same against the uncertainty setting, a tick per setting in the
                   grid's order (when a grid sweeps disturbances: a line per setting at one fleet
                   size hides the sweep in a legend); robots become a line when they vary
  throughput_time  lifelong runs: tasks finished and the last minute's throughput over sim time
                   (each cell's throughput.csv, at every replanning), a panel per team size,
                   the band one standard deviation over the repeats
  table.md         one row per cell of the grid (repeats folded): runs, success, AET, makespan,
                   sim speed, collisions, planner seconds, and throughput for lifelong runs;
                   with switching executions also waiting, switches and the paired changes
                   against plain ADG (waiting, and AET or, lifelong, tasks: mean +- sd in %)
  waiting_causes   the robots' total waiting split by what they waited for (summary.json
                   waiting_time_s.by_cause, when the run tells), a stacked bar per cell, and
                   waiting_causes.md: each cause's share of a run's waiting, mean +- sd
  figures.json     per figure: title, caption, and per panel its axes, scales, tick labels and
                   series of points {x, mean, sd, n} with the results.csv values they match
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
from matplotlib.ticker import FixedLocator, FuncFormatter, NullLocator  # noqa: E402

# The switching executions' knobs (`smart run --switch-*`), each an axis of its own.
SWITCH_KNOBS = ["switch_commit_actions", "switch_chain_locations", "switch_margin_s",
                "switch_horizon_actions", "switch_lookahead_actions", "switch_window_pairs"]
LINE_AXES = ["plan", "execution"] + SWITCH_KNOBS + ["robot", "qos", "uncertainty",
                                                    "replan_period_s", "lookahead", "clock"]
PANEL_AXES = ["map"]
POOLED_AXES = ["scen"]
AXIS_NAMES = {"plan": "plan", "robot": "robot", "qos": "QoS", "uncertainty": "uncertainty",
              "clock": "clock", "map": "map", "scen": "scen", "agents": "robots",
              "replan_period_s": "replan period (s)", "execution": "execution",
              "switch_commit_actions": "entries sent (actions ahead)",
              "switch_chain_locations": "chain (locations)",
              "switch_margin_s": "anticipation margin (s)",
              "switch_horizon_actions": "anticipation horizon (actions)",
              "switch_lookahead_actions": "lookahead reach (actions)",
              "switch_window_pairs": "window search (pairs)",
              "lookahead": "commit cut look-ahead (actions)"}
RATE_FIELDS = {"success_rate"}
FORMATS = ("png", "svg", "pdf")


def number(text):
    try:
        v = float(text)
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) else None


def read_rows(results_dir):
    with open(os.path.join(results_dir, "results.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        r["success_rate"] = "1" if r.get("success") == "true" else "0"
    return rows


def values_of(rows, key):
    return sorted({r.get(key, "") for r in rows}, key=natural)


def varying(rows, keys):
    return [k for k in keys if len(values_of(rows, k)) > 1]


def natural(text):
    """Sort key: numbers by value ("5" before "10")."""
    return [(0, float(p), "") if number(p) is not None else (1, 0.0, p)
            for p in str(text).split(" / ")]


def mean_sd(values):
    m = sum(values) / len(values)
    if len(values) < 2:
        return m, None
    return m, math.sqrt(sum((v - m) ** 2 for v in values) / (len(values) - 1))


def series(rows, field, x_field, line_keys):
    """[{label, match, points: [{x, mean, sd, n}]}], one per combination of line_keys."""
    groups = defaultdict(lambda: defaultdict(list))
    for r in rows:
        v, x = number(r.get(field)), number(r.get(x_field))
        if v is not None and x is not None:
            groups[tuple(r.get(k, "") for k in line_keys)][x].append(v)
    out = []
    for key in sorted(groups, key=lambda k: [natural(p) for p in k]):
        points = []
        for x in sorted(groups[key]):
            m, sd = mean_sd(groups[key][x])
            points.append({"x": x, "mean": m, "sd": sd, "n": len(groups[key][x])})
        # An axis a line does not have (plain ADG's commit distance) is left out of its label.
        out.append({"label": " / ".join(shown(k, v) for k, v in zip(line_keys, key) if v != "")
                    if key else "all runs",
                    "match": dict(zip(line_keys, key)), "points": points})
    return out


def shown(axis, value):
    """A value as a legend shows it: uncertainty settings as words, not JSON."""
    if axis != "uncertainty":
        return value
    try:
        settings = json.loads(value)
    except ValueError:
        return value
    if not settings:
        # No flags: a plan run has no delays then, but a LoRR problem keeps its own delayConfig.
        return "default"
    return ", ".join(f"{k.replace('_', ' ')} {plain(v) if isinstance(v, (int, float)) else v}"
                     for k, v in settings.items())


def disturbance(value):
    """An uncertainty setting as a tick: LoRR-style delays and stalls in the docs' words
    ("delays p 0.01, 1-4 s", "stalls p 0.05, 2 s"), any other setting as the legend shows it."""
    try:
        d = json.loads(value)
    except ValueError:
        return value
    delays = {"delay_probability", "delay_min_s", "delay_max_s"}
    if isinstance(d, dict) and set(d) == delays:
        return (f"delays p {plain(d['delay_probability'])}, "
                f"{plain(d['delay_min_s'])}-{plain(d['delay_max_s'])} s")
    if isinstance(d, dict) and set(d) == {"stall_probability", "stall_s"}:
        return f"stalls p {plain(d['stall_probability'])}, {plain(d['stall_s'])} s"
    return shown("uncertainty", value)


def plain(v):
    return f"{v:g}"


def scale_for(values):
    """Log only when positive values span a factor of 10 or more over 3+ distinct values."""
    vs = sorted({v for v in values if v is not None})
    if len(vs) >= 3 and vs[0] > 0 and vs[-1] / vs[0] >= 10:
        return "log"
    return "linear"


def set_x_axis(ax, xs):
    scale = scale_for(xs)
    ax.set_xscale(scale)
    distinct = sorted(set(xs))
    if len(distinct) <= 10:
        ax.xaxis.set_major_locator(FixedLocator(distinct))
    ax.xaxis.set_minor_locator(NullLocator())
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: plain(v)))
    return scale


def set_y_axis(ax, field, ys):
    if field in RATE_FIELDS:
        ax.set_ylim(-0.02, 1.05)
        return "linear"
    scale = scale_for(ys)
    ax.set_yscale(scale)
    if scale == "log":
        ax.yaxis.set_minor_locator(NullLocator())
        ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: plain(v)))
    elif ys and min(ys) == max(ys):  # a constant: from zero, not a 4 % window around it
        top = max(ys)
        ax.set_ylim(min(0.0, top) * 1.1, max(top * 1.1, 1e-9) if top >= 0 else 0.0)
    return scale


def dress_panel(ax, panel):
    """Labels, title, grid and legend: the same on every panel."""
    ax.set_xlabel(panel["xlabel"])
    ax.set_ylabel(panel["ylabel"])
    ax.set_title(panel["title"], fontsize=10)
    ax.grid(True, alpha=0.3)
    where = panel.get("legend", "inside")  # "right": beside the axes; "none": another panel's
    if panel["legend_title"] and where == "right":
        ax.legend(title=panel["legend_title"], fontsize=8, title_fontsize=8, loc="upper left",
                  bbox_to_anchor=(1.02, 1.0))
    elif panel["legend_title"] and where == "inside":
        ax.legend(title=panel["legend_title"], fontsize=8, title_fontsize=8)


def draw_time_panel(ax, panel):
    """A line per series over time, its band one standard deviation where n >= 2."""
    ys = []
    for s in panel["series"]:
        px = [p["x"] for p in s["points"]]
        py = [p["mean"] for p in s["points"]]
        line, = ax.plot(px, py, label=s["label"])
        if any(p["sd"] is not None for p in s["points"]):
            sd = [p["sd"] or 0.0 for p in s["points"]]
            ax.fill_between(px, [m - d for m, d in zip(py, sd)], [m + d for m, d in zip(py, sd)],
                            color=line.get_color(), alpha=0.2, linewidth=0)
        ys += py
    panel["xscale"] = "linear"
    panel["yscale"] = "linear"
    ax.set_ylim(0, max(ys + [1.0]) * 1.1)
    dress_panel(ax, panel)


def draw_panel(ax, panel, uniform_n):
    if panel.get("kind") == "time":
        return draw_time_panel(ax, panel)
    if panel.get("kind") == "paired":
        ax.axhline(0.0, color="0.5", linewidth=0.8)  # plain ADG
    xs, ys = [], []
    for s in panel["series"]:
        px = [p["x"] for p in s["points"]]
        py = [p["mean"] for p in s["points"]]
        err = [p["sd"] if p["sd"] is not None else 0.0 for p in s["points"]]
        has_err = any(p["sd"] is not None for p in s["points"])
        ax.errorbar(px, py, yerr=err if has_err else None, marker="o", capsize=3 if has_err else 0,
                    label=s["label"])
        if not uniform_n:
            for p in s["points"]:
                ax.annotate(f"n={p['n']}", (p["x"], p["mean"]), textcoords="offset points",
                            xytext=(4, 4), fontsize=7)
        xs += px
        ys += py
    if "categories" in panel:  # x is a category's index: its name as the tick
        panel["xscale"] = "linear"
        ax.set_xticks(range(len(panel["categories"])),
                      [c.replace(", ", ",\n") for c in panel["categories"]], fontsize=7)
        ax.set_xlim(-0.5, len(panel["categories"]) - 0.5)
    else:
        panel["xscale"] = set_x_axis(ax, xs)
    panel["yscale"] = set_y_axis(ax, panel["field"], ys)
    dress_panel(ax, panel)


def caption_of(panels):
    ns = [p["n"] for panel in panels for s in panel["series"] for p in s["points"]]
    uniform = len(set(ns)) == 1
    if all(panel.get("kind") == "time" for panel in panels):
        text = (f"Each line: the mean of n = {ns[0]} runs" if uniform
                else f"Each line: the mean of {min(ns)}-{max(ns)} runs") + ", at every replanning."
        text += (" Band: \u00b11 standard deviation over those runs." if any(n >= 2 for n in ns)
                 else " One run per line: no band.")
        return text, True
    text = (f"Each point: the mean of n = {ns[0]} runs." if uniform
            else "Each point: the mean of its n runs (n beside it).")
    if any(n >= 2 for n in ns):
        text += " Error bars: \u00b11 standard deviation over those runs."
    else:
        text += " One run per point: no error bars."
    return text, uniform


def figure(out_dir, name, title, panels, written, described):
    """panels: dicts of title, field, xlabel, ylabel, legend_title, series."""
    if not any(s["points"] for panel in panels for s in panel["series"]):
        return
    rows_n = len({panel["row"] for panel in panels})
    cols_n = len({panel["col"] for panel in panels})
    fig, axes = plt.subplots(rows_n, cols_n, figsize=(5.5 * cols_n, 3.8 * rows_n + 0.6),
                             squeeze=False, layout="constrained")
    caption, uniform = caption_of(panels)
    for panel in panels:
        draw_panel(axes[panel["row"]][panel["col"]], panel, uniform)
    fig.suptitle(title)
    fig.text(0.5, -0.01, caption, ha="center", va="top", fontsize=8, wrap=True)
    fig.canvas.draw()
    for panel in panels:
        ax = axes[panel["row"]][panel["col"]]
        panel["xticklabels"] = [t.get_text() for t in ax.get_xticklabels() if t.get_text()]
        panel["yticklabels"] = [t.get_text() for t in ax.get_yticklabels() if t.get_text()]
        panel["ylim"] = list(ax.get_ylim())
    for ext in FORMATS:
        path = os.path.join(out_dir, f"{name}.{ext}")
        fig.savefig(path, dpi=120, bbox_inches="tight")
        written.append(path)
    plt.close(fig)
    described[name] = {"title": title, "caption": caption, "panels": panels}


class Layout:
    """How the grid's varying axes appear: lines, panels, pooled (named in the title)."""

    def __init__(self, rows, x_field, exclude=()):
        self.lines = [k for k in varying(rows, LINE_AXES) if k not in exclude]
        self.panels = [k for k in varying(rows, PANEL_AXES) if k not in exclude]
        self.pooled = [k for k in varying(rows, POOLED_AXES) if k not in exclude]
        self.x_field = x_field
        self.panel_values = ([tuple(v.split("\x00")) for v in
                              sorted({"\x00".join(r.get(k, "") for k in self.panels)
                                      for r in rows}, key=natural)]
                             if self.panels else [()])

    def title(self, base, rows):
        """The pooled axes by name, counted within a panel (scens belong to their map)."""
        parts = []
        for k in self.pooled:
            counts = sorted({len(values_of([r for r in rows if all(
                r.get(pk) == v for pk, v in zip(self.panels, pv))], k))
                for pv in self.panel_values})
            each = f" per {' / '.join(AXIS_NAMES[p] for p in self.panels)}" if self.panels else ""
            parts.append("-".join(str(c) for c in (counts[0], counts[-1])[:len(set(counts))])
                         + f" {AXIS_NAMES[k]}s{each}")
        return base + (f" (pooled over {', '.join(parts)})" if parts else "")

    def panels_for(self, rows, metrics, xlabel):
        """metrics: [(field, ylabel)] as columns; one row of panels per panel value."""
        legend = " / ".join(AXIS_NAMES[k] for k in self.lines)
        out = []
        for i, pv in enumerate(self.panel_values):
            match = dict(zip(self.panels, pv))
            sub = [r for r in rows if all(r.get(k) == v for k, v in match.items())]
            where = ", ".join(f"{AXIS_NAMES[k]} {v}" for k, v in match.items())
            for j, (field, ylabel) in enumerate(metrics):
                out.append({"row": i, "col": j, "field": field, "x_field": self.x_field,
                            "match": match, "title": where, "xlabel": xlabel, "ylabel": ylabel,
                            "legend_title": legend,
                            "series": series(sub, field, self.x_field, self.lines)})
        return out


def robots_figures(rows, out_dir, written, described):
    lay = Layout(rows, "agents")
    for name, base, metrics in (
            ("aet_makespan", "AET and makespan",
             [("aet_s", "AET (s)"), ("makespan_s", "makespan (s)")]),
            ("sim_speed", "Sim speed", [("sim_speed", "sim speed (\u00d7 real time)")]),
            ("success", "Success rate", [("success_rate", "success rate")]),
            ("waiting", "Total waiting time",
             [("waiting_time_s.total", "total waiting (s)"),
              ("execution.switches", "passing orders switched")]),
            ("memory", "Memory and CPU",
             [("peak_rss_mb.monitor", "monitor peak RSS (MB)"),
              ("peak_rss_mb.sim", "sim peak RSS (MB)"),
              ("cpu_s_per_sim_s", "CPU s per sim s (monitor + sim)")])):
        figure(out_dir, name, lay.title(base, rows), lay.panels_for(rows, metrics, "robots"),
               written, described)


def planner_figure(rows, out_dir, written, described):
    """A planner's time is one per (map, scen, robots, plan): counted once, not per run."""
    seen, once = set(), []
    for r in rows:
        key = (r.get("map"), r.get("scen"), r.get("agents"), r.get("plan"))
        if number(r.get("planner_runtime_s")) is not None and key not in seen:
            seen.add(key)
            once.append(r)
    if not once:
        return
    lay = Layout(once, "agents", exclude=("robot", "qos", "uncertainty", "clock"))
    lay.lines = ["plan"]
    figure(out_dir, "planner_runtime", lay.title("Planner wall time", once),
           lay.panels_for(once, [("planner_runtime_s", "planner wall time (s)")], "robots"),
           written, described)


# (name, title, x field, the grid axis it replaces, x label): AET and success against a setting.
SWEEPS = (("stalls", "Stalls at action start", "uncertainty.stall_probability", "uncertainty",
           "stall probability"),
          ("link", "Link delay (monitor to hosts)", "link.to_host.delay_ms", "qos",
           "link delay (ms)"))


def sweep_figures(rows, out_dir, written, described):
    for name, title, x_field, replaced, xlabel in SWEEPS:
        if len(values_of(rows, x_field)) < 2:
            continue
        lay = Layout(rows, x_field, exclude=(replaced,))
        lay.lines = ["agents"] + lay.lines
        figure(out_dir, name, lay.title(title, rows),
               lay.panels_for(rows, [("aet_s", "AET (s)"), ("success_rate", "success rate")],
                              xlabel), written, described)


# What a switching run is paired with plain ADG's run by: everything of its cell but the
# execution (and the commit distance, which plain ADG has not), and the seed.
PAIR_KEYS = ["map", "scen", "agents", "plan", "robot", "qos", "uncertainty", "clock",
             "replan_period_s", "lookahead", "repeat"]
PAIRED_FIELDS = (("waiting_time_s.total", "paired.waiting_pct"), ("aet_s", "paired.aet_pct"),
                 ("lifelong.tasks_finished", "paired.tasks_pct"))


def paired_rows(rows):
    """Each switching run with its change in % against plain ADG's run on the same cell and
    seed (paired: the seed's own delays and tasks cancel out, which the spread of two means
    hides). Runs without a plain twin are left out."""
    plain = {tuple(r.get(k, "") for k in PAIR_KEYS): r for r in rows
             if r.get("execution") == "adg"}
    out = []
    for r in rows:
        base = plain.get(tuple(r.get(k, "") for k in PAIR_KEYS))
        if r.get("execution", "adg") in ("", "adg") or base is None:
            continue
        d = dict(r)
        for field, name in PAIRED_FIELDS:
            v, b = number(r.get(field)), number(base.get(field))
            d[name] = str(100.0 * (v / b - 1.0)) if v is not None and b else ""
        out.append(d)
    return out


def paired_metrics(prows):
    lifelong = any(number(r.get("paired.tasks_pct")) is not None for r in prows)
    return [("paired.waiting_pct", "total waiting against plain ADG (%)"),
            ("paired.tasks_pct", "tasks finished against plain ADG (%)") if lifelong
            else ("paired.aet_pct", "AET against plain ADG (%)")]


def paired_figure(rows, out_dir, written, described):
    prows = paired_rows(rows)
    if not prows:
        return
    metrics = paired_metrics(prows)
    lay = Layout(prows, "agents")
    if "execution" not in lay.lines:
        lay.lines.insert(0, "execution")
    panels = lay.panels_for(prows, metrics, "robots")
    for panel in panels:
        panel["kind"] = "paired"
    figure(out_dir, "paired", lay.title("Against plain ADG, paired by seed", prows), panels,
           written, described)


def paired_uncertainty_figure(rows, out_dir, written, described):
    """The paired changes against the uncertainty setting: x is the setting's place in the grid
    (results.csv's order, which is the spec's), its tick the setting in words."""
    prows = paired_rows(rows)
    settings = list(dict.fromkeys(r.get("uncertainty", "") for r in prows))
    if len(settings) < 2:
        return
    for r in prows:
        r["uncertainty_index"] = str(settings.index(r.get("uncertainty", "")))
    lay = Layout(prows, "uncertainty_index", exclude=("uncertainty",))
    if "execution" not in lay.lines:
        lay.lines.insert(0, "execution")
    if len(values_of(prows, "agents")) > 1:
        lay.lines.insert(0, "agents")
    panels = lay.panels_for(prows, paired_metrics(prows), "uncertainty")
    last = max(panel["col"] for panel in panels)
    for panel in panels:
        panel["kind"] = "paired"
        panel["categories"] = [disturbance(v) for v in settings]
        # One legend, beside the last column: inside, a sweep's lines leave it no room.
        panel["legend"] = "right" if panel["col"] == last else "none"
    figure(out_dir, "paired_uncertainty",
           lay.title("Against plain ADG by disturbance, paired by seed", prows), panels, written,
           described)


def lifelong_figures(results_dir, rows, out_dir, written, described):
    if not any(number(r.get("lifelong.throughput_per_min")) is not None for r in rows):
        return
    lay = Layout(rows, "agents")
    figure(out_dir, "throughput", lay.title("Lifelong throughput", rows),
           lay.panels_for(rows, [("lifelong.throughput_per_min", "throughput (tasks / min)"),
                                 ("lifelong.mean_latency_s", "mean task latency (s)")],
                          "robots"), written, described)
    time_figure(time_rows(results_dir, rows), out_dir, written, described)


def time_rows(results_dir, rows):
    """A row per results row and replanning: its parameters, t_s on the period's grid, and the
    tasks finished so far and in the last minute (the cell's throughput.csv)."""
    out = []
    for r in rows:
        path = os.path.join(results_dir, "cells", r.get("cell", ""), "throughput.csv")
        if not os.path.isfile(path):
            continue
        period = number(r.get("replan_period_s")) or 1.0
        with open(path, newline="") as f:
            for t in csv.DictReader(f):
                at = number(t.get("t_s"))
                if at is None:
                    continue
                out.append(dict(r, t_s=str(round(at / period) * period),
                                tasks_finished=t.get("tasks_finished"),
                                tasks_last_min=t.get("tasks_last_min")))
    return out


def time_figure(trows, out_dir, written, described):
    if not trows:
        return
    lay = Layout(trows, "t_s")
    lay.panels = ["agents"] + lay.panels
    lay.panel_values = [tuple(v.split("\x00")) for v in
                        sorted({"\x00".join(r.get(k, "") for k in lay.panels) for r in trows},
                               key=natural)]
    panels = lay.panels_for(trows, [("tasks_finished", "tasks finished"),
                                    ("tasks_last_min", "throughput (tasks in the last minute)")],
                            "sim time (s)")
    for panel in panels:
        panel["kind"] = "time"
    figure(out_dir, "throughput_time", lay.title("Lifelong throughput over time", trows),
           panels, written, described)


def table_keys(rows):
    """The columns that name a table's cell of the grid (repeats folded)."""
    keys = ["map", "scen", "agents", "plan", "robot", "qos", "uncertainty", "clock"]
    lifelong = any(number(r.get("lifelong.throughput_per_min")) is not None for r in rows)
    switching = len(values_of(rows, "execution")) > 1
    if switching:
        keys.insert(keys.index("plan") + 1, "execution")
    at = keys.index("plan") + 1 + switching
    for knob in SWITCH_KNOBS:
        if len(values_of(rows, knob)) > 1:
            keys.insert(at, knob)
            at += 1
    if lifelong:
        keys.insert(keys.index("uncertainty") + 1, "replan_period_s")
    if len(values_of(rows, "lookahead")) > 1:
        keys.insert(keys.index("uncertainty") + 1 + lifelong, "lookahead")
    return keys


def grouped(rows, keys):
    groups = defaultdict(list)
    for r in rows:
        groups[tuple(r.get(k, "") for k in keys)].append(r)
    return {k: groups[k] for k in sorted(groups, key=lambda k: [natural(str(x)) for x in k])}


def stat(rs, field, fmt="{:.1f}"):
    vs = [v for v in (number(r.get(field)) for r in rs) if v is not None]
    if not vs:
        return "-"
    m, sd = mean_sd(vs)
    sd_fmt = fmt.replace("+", "")  # a change is signed, its spread not
    return (fmt + " \u00b1 " + sd_fmt).format(m, sd) if sd is not None else fmt.format(m)


def write_table(rows, out_dir, written):
    """The paper-style table: repeats folded into mean +- sd (n = runs)."""
    keys = table_keys(rows)
    lifelong = any(number(r.get("lifelong.throughput_per_min")) is not None for r in rows)
    switching = "execution" in keys
    groups = grouped(rows, keys)
    # The changes against plain ADG paired by seed (the paired figure's numbers), which the
    # means of two columns hide: each seed's own delays and tasks cancel out.
    paired = defaultdict(list)
    for r in paired_rows(rows) if switching else []:
        paired[tuple(r.get(k, "") for k in keys)].append(r)
    paired_columns = ([("paired.waiting_pct", "waiting against plain ADG (%)"),
                       ("paired.tasks_pct", "tasks against plain ADG (%)") if lifelong
                       else ("paired.aet_pct", "AET against plain ADG (%)")] if paired else [])

    lines = ["| " + " | ".join(keys) + " | runs | success | AET (s) | makespan (s) | sim speed | "
             "collisions | planner (s) |" + (" throughput (tasks/min) |" if lifelong else "")
             + (" waiting (s) | switches |" if switching else "")
             + "".join(f" {title} |" for _, title in paired_columns),
             "|" + "---|" * (len(keys) + 7 + (1 if lifelong else 0) + (2 if switching else 0)
                             + len(paired_columns))]
    for key, rs in groups.items():
        ok = sum(1 for r in rs if r.get("success") == "true")
        cells = [disturbance(k) if name == "uncertainty" else str(k) for name, k in zip(keys, key)]
        lines.append("| " + " | ".join(cells) + f" | {len(rs)} | {ok}/{len(rs)} | "
                     + " | ".join([stat(rs, "aet_s"), stat(rs, "makespan_s"),
                                   stat(rs, "sim_speed"), stat(rs, "collisions", "{:.0f}"),
                                   stat(rs[:1], "planner_runtime_s", "{:.2f}")]
                                  + ([stat(rs, "lifelong.throughput_per_min")] if lifelong
                                     else [])
                                  + ([stat(rs, "waiting_time_s.total"),
                                      stat(rs, "execution.switches")] if switching else [])
                                  + [stat(paired.get(key, []), field, "{:+.1f}")
                                     for field, _ in paired_columns])
                     + " |")
    path = os.path.join(out_dir, "table.md")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    written.append(path)


# summary.json's waiting_time_s.by_cause (monitor/execution.hpp WaitCause): what the robots
# waited for, as the run supervisor sampled it each tick.
WAIT_CAUSES = [("at_location", "at the location, leaving"),
               ("at_location_turning", "at the location, turning"),
               ("at_location_waiting", "at the location, waiting itself"),
               ("entering", "entering"),
               ("on_its_way_near", "on its way, near"),
               ("on_its_way_far", "on its way, far"),
               ("on_its_way_waiting", "on its way, waiting itself"),
               ("held", "held back by switching"),
               ("no_action", "no action yet")]
CAUSE_FIELD = "waiting_time_s.by_cause."


def with_shares(rs):
    """Each run's cause as a share of its own waiting (%), in fields share.<cause>."""
    out = []
    for r in rs:
        total = number(r.get("waiting_time_s.total"))
        if not total:
            continue
        out.append(dict(r, **{"share." + c: str(100 * (number(r.get(CAUSE_FIELD + c)) or 0)
                                                / total) for c, _ in WAIT_CAUSES}))
    return out


def wait_causes(rows, out_dir, written, described):
    """waiting_causes.md: per cell, the share of waiting each cause took (mean +- sd over the
    runs' own shares); waiting_causes.png: their mean seconds, a stacked bar per cell."""
    if not any(number(r.get(CAUSE_FIELD + "at_location")) is not None for r in rows):
        return
    keys = [k for k in table_keys(rows) if len(values_of(rows, k)) > 1] or ["map"]
    groups = {k: with_shares([r for r in rs if number(r.get(CAUSE_FIELD + "at_location"))
                              is not None]) for k, rs in grouped(rows, keys).items()}
    groups = {k: rs for k, rs in groups.items() if rs}
    lines = ["| " + " | ".join(keys) + " | runs | waiting (s) | "
             + " | ".join(f"{title} (%)" for _, title in WAIT_CAUSES) + " |",
             "|" + "---|" * (len(keys) + 2 + len(WAIT_CAUSES))]
    bars = []
    for key, rs in groups.items():
        cells = [disturbance(k) if name == "uncertainty" else str(k) for name, k in zip(keys, key)]
        lines.append("| " + " | ".join(cells) + f" | {len(rs)} | "
                     + " | ".join([stat(rs, "waiting_time_s.total", "{:.0f}")]
                                  + [stat(rs, "share." + c) for c, _ in WAIT_CAUSES]) + " |")
        causes = {}
        for c, _ in WAIT_CAUSES:
            m, sd = mean_sd([number(r.get(CAUSE_FIELD + c)) or 0 for r in rs])
            causes[c] = {"mean": m, "sd": sd}
        bars.append({"label": ", ".join(cells), "match": dict(zip(keys, key)), "n": len(rs),
                     "causes": causes})
    path = os.path.join(out_dir, "waiting_causes.md")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    written.append(path)
    causes_figure(bars, out_dir, written, described)


def causes_figure(bars, out_dir, written, described):
    fig, ax = plt.subplots(figsize=(12, 0.5 * len(bars) + 2.2), layout="constrained")
    left = [0.0] * len(bars)
    ys = list(range(len(bars)))[::-1]
    for c, title in WAIT_CAUSES:
        widths = [b["causes"][c]["mean"] for b in bars]
        ax.barh(ys, widths, left=left, label=title)
        left = [a + w for a, w in zip(left, widths)]
    ax.set_yticks(ys, [f"{b['label']} (n = {b['n']})" for b in bars])
    ax.set_xlabel("total waiting (robot s), mean over the runs")
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1))  # beside, not over, bars
    title = "Where the waiting went"
    caption = ("Each bar: the robots' total waiting of a cell, split by what each waiting robot "
               "waited for at every tick: the robot it waits for at the location (leaving it, "
               "turning there or waiting itself), entering it, or on its way (near, far, or "
               "waiting itself); or no action to execute. Means over n runs.")
    fig.suptitle(title)
    fig.text(0.5, -0.01, caption, ha="center", va="top", fontsize=8, wrap=True)
    for ext in FORMATS:
        path = os.path.join(out_dir, f"waiting_causes.{ext}")
        fig.savefig(path, dpi=120, bbox_inches="tight")
        written.append(path)
    plt.close(fig)
    described["waiting_causes"] = {"title": title, "caption": caption, "bars": bars}


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    results_dir, out_dir = sys.argv[1], sys.argv[2]
    rows = read_rows(results_dir)
    if not rows:
        sys.exit(f"{results_dir}/results.csv has no runs")
    os.makedirs(out_dir, exist_ok=True)
    written, described = [], {}
    robots_figures(rows, out_dir, written, described)
    planner_figure(rows, out_dir, written, described)
    sweep_figures(rows, out_dir, written, described)
    paired_figure(rows, out_dir, written, described)
    paired_uncertainty_figure(rows, out_dir, written, described)
    wait_causes(rows, out_dir, written, described)
    lifelong_figures(results_dir, rows, out_dir, written, described)
    write_table(rows, out_dir, written)
    path = os.path.join(out_dir, "figures.json")
    with open(path, "w") as f:
        json.dump({"results": os.path.join(results_dir, "results.csv"), "figures": described},
                  f, indent=1)
    written.append(path)
    print(json.dumps({"figures": written, "runs": len(rows)}))


if __name__ == "__main__":
    main()
