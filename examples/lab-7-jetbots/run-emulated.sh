#!/bin/sh
# The lab experiment with 7 emulated JetBots (README.md): TRIALS mixed real-time runs of the
# lab plan, each robot a `smart agent --i2c emulated --emulate-realistic` process at 40 Hz, and
# the same plan in the Simbody sim (lock-step, jetbot-lab model). Writes OUT/trials.csv and
# OUT/table.md. Usage: ./run-emulated.sh [TRIALS=10] [OUT=lab-results] [DOMAIN=40]
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
SMART=${SMART:-$HERE/../../build/bin/smart}
TRIALS=${1:-10}
OUT=${2:-lab-results}
DOMAIN=${3:-40}
CELL=0.3
mkdir -p "$OUT"
# One key for every process of the lab's runs (README, "Running safely"): only they hear each
# other. SMART_RUN_KEY is --run-key for every command below.
[ -f "$OUT/run.key" ] || (umask 077 && python3 -c 'import secrets; print(secrets.token_hex(32))' > "$OUT/run.key")
export SMART_RUN_KEY="$OUT/run.key"
"$SMART" plan --map "$HERE/lab.map" --scen "$HERE/lab.scen" --out "$OUT/lab.plan" > /dev/null
echo "trial,aet_s,makespan_s,success,finished_actions,total_actions,pose_contacts,pose_min_separation_m" > "$OUT/trials.csv"
summary() {  # FILE -> the csv fields of a run summary
  python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print(",".join(str(d[k]) for k in ("aet_s","makespan_s","success","finished_actions","total_actions","pose_contacts","pose_min_separation_m")))' "$1"
}
trial=1
while [ "$trial" -le "$TRIALS" ]; do
  # One agent per robot, at its start cell (scenario columns 5 and 6), facing east.
  tail -n +2 "$HERE/lab.scen" | awk -v c=$CELL '{ printf "%d %.4f %.4f\n", NR-1, $5*c, (4-1-$6)*c }' |
  while read -r id x y; do
    "$SMART" --log-level warn agent --robot-id "$id" --config "$HERE/jetbot-lab.yaml" --i2c emulated \
      --emulate-pose "$x,$y,0" --emulate-realistic --emulate-seed "$trial$id" --period-s 0.025 \
      --domain "$DOMAIN" > "$OUT/agent-$trial-$id.json" &
  done
  "$SMART" --log-level warn monitor --map "$HERE/lab.map" --scen "$HERE/lab.scen" \
    --plan "$OUT/lab.plan" --clock realtime --robot "$HERE/jetbot-lab.yaml" --cell-m $CELL \
    --domain "$DOMAIN" --no-progress --timeout-s 30 --out "$OUT/trial-$trial" \
    > "$OUT/trial-$trial.json" || true
  wait
  echo "$trial,$(summary "$OUT/trial-$trial.json")" >> "$OUT/trials.csv"
  trial=$((trial + 1))
done
"$SMART" --log-level warn run --map "$HERE/lab.map" --scen "$HERE/lab.scen" --plan "$OUT/lab.plan" \
  --robot "$HERE/jetbot-lab.yaml" --cell-m $CELL --domain "$DOMAIN" --no-progress > "$OUT/sim.json"
python3 - "$OUT" <<'PY'
import csv, json, statistics, sys
out = sys.argv[1]
rows = list(csv.DictReader(open(f"{out}/trials.csv")))
aet = [float(r["aet_s"]) for r in rows]
mk = [float(r["makespan_s"]) for r in rows]
sim = json.load(open(f"{out}/sim.json"))
ok = sum(r["success"] == "True" for r in rows)
contacts = sum(int(r["pose_contacts"]) for r in rows)
closest = min(float(r["pose_min_separation_m"]) for r in rows)
sd = lambda v: statistics.stdev(v) if len(v) > 1 else 0.0
with open(f"{out}/table.md", "w") as f:
    f.write("| execution | runs | AET (mean ± sd) | max execution time (mean ± sd) | contacts | closest approach |\n|---|---:|---:|---:|---:|---:|\n")
    f.write(f"| 7 emulated JetBots, real time | {len(rows)} ({ok} succeeded) | {statistics.mean(aet):.2f} ± {sd(aet):.2f} s | {statistics.mean(mk):.2f} ± {sd(mk):.2f} s | {contacts} (poses) | {closest * 100:.1f} cm |\n")
    f.write(f"| Simbody sim, lock-step | 1 | {sim['aet_s']:.2f} s | {sim['makespan_s']:.2f} s | {sim['collisions']} (physics) | {sim['min_separation_m'] * 100:.1f} cm |\n")
print(open(f"{out}/table.md").read())
PY
