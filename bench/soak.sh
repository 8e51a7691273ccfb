#!/bin/bash
# Lifelong soak (issue 27): a 1000-robot lifelong run on warehouse-10-20-10-2-1 for HOURS of sim
# time, with a lossy link model (sim-lossy-wifi) and LoRR-style delay events, sampling the
# monitor's and the sim's resident memory every SAMPLE_S wall seconds into soak-memory.csv.
# Usage: bench/soak.sh HOURS [OUT_DIR] (ROBOTS, SAMPLE_S, DOMAIN (90: outside the tests' ids),
# SMART and SMART_BENCHMARKS override).
# Prints the run's summary line and whether memory stayed flat after the first sixth of the run
# (the last sample within 10 % of the one at a sixth: a 1-hour run's first 10 minutes).
set -euo pipefail
hours=${1:?usage: bench/soak.sh HOURS [OUT_DIR]}
out=${2:-build/soak}
robots=${ROBOTS:-1000}
sample_s=${SAMPLE_S:-5}
smart=${SMART:-build/bin/smart}
bench=${SMART_BENCHMARKS:-../shared/benchmarks}
duration=$(python3 -c "print(float('$hours') * 3600)")
rm -rf "$out"
mkdir -p "$out"
"$smart" run --tasks random --map "$bench/maps/warehouse-10-20-10-2-1.map" --agents "$robots" \
  --seed 1 --duration-s "$duration" --qos sim-lossy-wifi --delay-probability 0.002 \
  --delay-min-s 0.5 --delay-max-s 4 --state-rate-hz 0.2 --no-progress \
  --timeout-s 120 --domain "${DOMAIN:-90}" --out "$out/run" > "$out/summary.json" 2> "$out/stderr.log" &
run=$!
echo "wall_s,monitor_rss_kb,sim_rss_kb" > "$out/soak-memory.csv"
start=$(date +%s)
while kill -0 "$run" 2> /dev/null; do
  sim=$(pgrep -P "$run" -f " sim " | head -1 || true)
  m=$(awk '/VmRSS/ {print $2}' "/proc/$run/status" 2> /dev/null || echo "")
  s=$([ -n "$sim" ] && awk '/VmRSS/ {print $2}' "/proc/$sim/status" 2> /dev/null || echo "")
  [ -n "$m" ] && echo "$(($(date +%s) - start)),$m,${s:-}" >> "$out/soak-memory.csv"
  sleep "$sample_s"
done
wait "$run" || true
python3 - "$out" << 'PY'
import csv, json, sys
out = sys.argv[1]
text = open(out + "/summary.json").read()
j = json.loads(text[text.index("{"):])
rows = [r for r in csv.DictReader(open(out + "/soak-memory.csv")) if r["monitor_rss_kb"]]
l = j.get("lifelong", {})
print(f"outcome {j['outcome']}, collisions {j['collisions']}, sim {j['sim_time_s']:.0f} s in "
      f"{j['wall_time_s']:.0f} s wall, tasks {l.get('tasks_finished')}, "
      f"windows refused {l.get('windows_refused')}")
if len(rows) >= 6:
    for key in ("monitor_rss_kb", "sim_rss_kb"):
        vals = [int(r[key]) for r in rows if r[key]]
        if len(vals) < 6:
            continue
        at, last = vals[len(vals) // 6], vals[-1]
        flat = last <= 1.1 * at
        print(f"{key}: {at} kB at a sixth of the run, {last} kB at the end: "
              f"{'flat' if flat else 'GROWING'}")
PY
