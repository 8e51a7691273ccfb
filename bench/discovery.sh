#!/bin/sh
# Discovery and start-up at fleet scale: N `smart agent` processes (emulated JetBots, one process
# per robot as on a lab floor) and one `smart monitor` (real time) started together on this
# machine, loopback DDS. Measures, per N, the time from the launch to each robot's first
# finished action (the monitor's actions.csv, on its clock that starts at launch), which
# includes discovery (each process finding every other), the first window, and the first
# action's own duration (the N = 1 row is that floor). Prints one JSON line per N and the machine.
# Usage: bench/discovery.sh [N...] (default 1 10 50 100); SMART=path/to/smart, DOMAIN=id.
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
SMART=${SMART:-$HERE/../build/bin/smart}
DOMAIN=${DOMAIN:-50}
CELL=0.4
PERIOD=${PERIOD:-0.1}  # the agents' control period
SIZES=${*:-1 10 50 100}
WORK=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$WORK"' EXIT

for n in $SIZES; do
  # An empty square map with about one robot per four cells; starts and goals at random.
  side=$(python3 -c "import math; print(max(4, math.ceil(math.sqrt(4 * $n))))")
  "$SMART" gen-map empty --width "$side" --height "$side" --out "$WORK/m.map" > /dev/null
  "$SMART" gen-scen --map "$WORK/m.map" --agents "$n" --seed 1 --out "$WORK/m.scen" > /dev/null
  "$SMART" plan --map "$WORK/m.map" --scen "$WORK/m.scen" --out "$WORK/m.plan" > /dev/null
  rm -rf "$WORK/out"
  start=$(date +%s.%N)
  "$SMART" --log-level warn monitor --map "$WORK/m.map" --scen "$WORK/m.scen" --plan "$WORK/m.plan" \
    --axis xy --clock realtime --robot jetbot --cell-m $CELL --domain "$DOMAIN" --no-progress \
    --timeout-s 60 --out "$WORK/out" > "$WORK/summary.json" &
  monitor=$!
  tail -n +2 "$WORK/m.scen" | awk -v c=$CELL -v h="$side" \
    '{ printf "%d %.4f %.4f\n", NR-1, $5*c, (h-1-$6)*c }' |
  while read -r id x y; do
    "$SMART" --log-level error agent --robot-id "$id" --config jetbot --i2c emulated \
      --emulate-pose "$x,$y,0" --period-s "$PERIOD" --domain "$DOMAIN" > /dev/null &
  done
  wait "$monitor" || true
  wait
  python3 - "$WORK" "$n" "$start" <<'PY'
import csv, json, statistics, sys, time
work, n, start = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
s = json.load(open(f"{work}/summary.json"))
first, heard = {}, {}
for row in csv.DictReader(open(f"{work}/out/actions.csv")):
    if row["action"] == "0" and row["finish_time_s"]:
        first[int(row["robot"])] = float(row["finish_time_s"])
for row in csv.reader(open(f"{work}/out/states.csv")):
    if row[0] != "t_s":
        heard.setdefault(int(row[1]), float(row[0]))
def spread(d):
    t = sorted(d.values())
    return {"robots": len(t), "first": round(t[0], 3), "median": round(statistics.median(t), 3),
            "last": round(t[-1], 3)}
print(json.dumps({"agents": n, "success": s["success"], "heard_s": spread(heard),
                  "first_action_s": spread(first), "wall_time_s": s["wall_time_s"],
                  "machine": s.get("machine", "")}))
PY
done
