#!/bin/bash
# Recording cost (issue 30): SMART's 1000-robot warehouse plan run PAIRS times without and with
# `--mcap`, alternating (the machine's speed drifts: pairs compare runs made close together),
# then `smart export mcap` of the last results folder three times.
# Usage: bench/recording.sh [PAIRS] [OUT_DIR] (SMART, SMART_BENCHMARKS, DOMAIN (91: outside the
# tests' ids) override).
# Prints each run (whole command, run, the sim's and the monitor's CPU, the recording's CPU),
# the mean cost of --mcap as a share of the plain command's wall time (mean ± sd of the pairs),
# the recording's size per robot-minute, whether the live recording equals the export, and the
# machine.
set -euo pipefail
pairs=${1:-5}
out=${2:-build/recording-bench}
smart=${SMART:-build/bin/smart}
bench=${SMART_BENCHMARKS:-../shared/benchmarks}
rm -rf "$out"
mkdir -p "$out"
run() {  # MODE (plain|mcap) INDEX
  local dir="$out/$1-$2" extra=()
  [ "$1" = mcap ] && extra=(--mcap "$out/$1-$2.mcap")
  /usr/bin/time -f "%e %M" -o "$dir.time" "$smart" run \
    --map "$bench/maps/warehouse-10-20-10-2-1.map" \
    --scen "$bench/scens/warehouse-10-20-10-2-1-random-1.scen" \
    --plan "$bench/smart-examples/scen_1_1000_paths.txt" --axis rowcol --agents 1000 \
    --out "$dir" "${extra[@]}" --no-progress --domain "${DOMAIN:-91}" > "$dir.out" 2> "$dir.err"
}
for i in $(seq 1 "$pairs"); do
  run plain "$i"
  run mcap "$i"
done
for i in 1 2 3; do
  /usr/bin/time -f "%e %M" -o "$out/export-$i.time" "$smart" export mcap "$out/mcap-$pairs" \
    -o "$out/export.mcap" > /dev/null
done
cmp -s "$out/export.mcap" "$out/mcap-$pairs.mcap" && same=yes || same=no
python3 - "$out" "$pairs" "$same" <<'PY'
import json, os, platform, re, statistics, subprocess, sys
out, pairs, same = sys.argv[1], int(sys.argv[2]), sys.argv[3]
def run(mode, i):
    d = f"{out}/{mode}-{i}"
    total, rss = open(d + ".time").read().split()
    s = json.load(open(d + "/summary.json"))
    rec = re.search(r"recording: ([0-9.]+) s of CPU", open(d + ".err").read())
    return {"total": float(total), "rss_mb": int(rss) / 1024, "run": s["wall_time_s"],
            "sim_cpu": s["cpu_s"]["sim"], "monitor_cpu": s["cpu_s"]["monitor"],
            "rec_cpu": float(rec.group(1)) if rec else None, "sim_s": s["sim_time_s"]}
costs = []
for i in range(1, pairs + 1):
    p, m = run("plain", i), run("mcap", i)
    costs.append(m["total"] / p["total"] - 1)
    for mode, r in (("plain", p), ("mcap ", m)):
        print(f"{mode} {i}: command {r['total']:.2f} s, run {r['run']:.2f} s, sim CPU "
              f"{r['sim_cpu']:.1f} s, monitor CPU {r['monitor_cpu']:.1f} s, recording CPU "
              f"{r['rec_cpu'] if r['rec_cpu'] is not None else '-'} s, peak RSS {r['rss_mb']:.0f} MB")
size = os.path.getsize(f"{out}/mcap-{pairs}.mcap")
minutes = run("mcap", pairs)["sim_s"] / 60
exports = [float(open(f"{out}/export-{i}.time").read().split()[0]) for i in (1, 2, 3)]
sd = statistics.stdev(costs) if len(costs) > 1 else float("nan")
print(f"--mcap cost: {100 * statistics.mean(costs):+.1f} % ± {100 * sd:.1f} "
      f"of the plain command's wall time (mean ± sd of {pairs} pairs)")
print(f"recording: {size / 1e6:.1f} MB, {size / 1000 / (1000 * minutes):.1f} kB per robot-minute; "
      f"live recording == export: {same}; export alone: {min(exports):.2f}-{max(exports):.2f} s")
model = subprocess.run(["sh", "-c", "lscpu | sed -n 's/^Model name: *//p'"],
                       capture_output=True, text=True).stdout.strip()
print(f"machine: {model}, {os.cpu_count()} cores, Linux {platform.release()}")
PY
