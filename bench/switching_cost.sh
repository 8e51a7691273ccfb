#!/bin/bash
# The cost of switching passing orders (issue 29, docs/execution.md "Cost"): SMART's 1000-robot
# warehouse plan run REPEATS times with each of --execution adg, switchable, switchable-opt and
# switchable-lookahead under `perf record`; for each run, the share of the monitor process's
# samples (all its threads) in the execution tracker's functions, and in the switching functions
# alone (the tries, the deadlock search, anticipation, expected durations, the lookahead: what
# plain ADG does not do). Comparing
# total CPU seconds cannot show a 5 % share (identical runs differ by ±0.7 s of 8.6 s); sampling
# inside one run can.
# With LIFELONG=1, the same for a lifelong run instead (LiveAdg's switching): 1000 robots on
# that map, random single-errand tasks, LoRR-style delays (p = 0.01, 1-4 s), 120 sim s, seed 1.
# With DENSE=1, LaCAM's 1000-robot plan of random-64-64-10 (random-1 scenario, planned here by
# `smart plan --algorithm lacam`) under LoRR-style delays (p = 0.01, 1-4 s, seed 0): the dense map
# where the deadlock search costs most (docs/execution.md, "On a dense random map under delays").
# Usage: bench/switching_cost.sh [REPEATS] [OUT_DIR] (SMART, SMART_BENCHMARKS, DOMAIN (92:
# outside the tests' ids), MODES (the executions, space separated) override; RUN_ARGS adds flags
# to every run, e.g. RUN_ARGS="--switch-lookahead-actions 64" with MODES=switchable-lookahead). Needs perf
# (Debian: linux-perf) and a kernel that lets this user sample (kernel.perf_event_paranoid <= 1,
# or root).
set -euo pipefail
repeats=${1:-3}
out=${2:-build/switching-bench}
smart=${SMART:-build/bin/smart}
bench=${SMART_BENCHMARKS:-../shared/benchmarks}
command -v perf > /dev/null || { echo "switching_cost.sh: perf not found; install linux-perf" >&2; exit 2; }
rm -rf "$out"
mkdir -p "$out"
# walk_cone, cone_saving and next_mark (the lookahead's cone, since 2026-11-29) were missing from
# this list until 2026-12-01: the lookahead's share was measured without its cone walk
# (docs/execution.md, "Cost"). needs_commit (whether a robot's next entry waits to be sent near
# it: plain ADG sends it) was missing until 2026-12-03 (docs/execution.md, "A chain's cone
# walked when it is compared"). RobotSet (the robots to try, robot_set.hpp) since 2026-12-06.
# collect_window and window_saving (the window search, --switch-window-pairs) since 2026-12-07.
switching='SwitchableTracker::(needs_commit|shares_next|try_switches|try_switch|blocking_stay|reaches|anticipate|expected_saving|queue_of|saving|lookahead_saving|collect_cone|walk_cone|cone_saving|collect_window|window_saving|cone_cost|next_mark|expect|next_in|prev_in|arrival|finish_estimate|observe|still_refused|forget_refusal|has_edge|decide|candidate|consider|take_first|swap_with_next|relink|settle|try_chain|chain_link|chain_cycle|chain_floor|each_chain_edge|undo_chain|redo_chain|chain_saves|init_look|path_holds|refuse|unsettle|unsettle_watchers|next_stamp|init_order|order_swapped|order_edge|order_walk|unordered)|RobotSet::|ActionDurations::|queue_saving'
tracker='(ExecutionTracker|SwitchableTracker|RobotSet|ActionDurations)::|queue_saving'
run_args=(--map "$bench/maps/warehouse-10-20-10-2-1.map"
  --scen "$bench/scens/warehouse-10-20-10-2-1-random-1.scen"
  --plan "$bench/smart-examples/scen_1_1000_paths.txt" --axis rowcol --agents 1000)
if [ "${DENSE:-0}" = 1 ]; then
  "$smart" plan --map "$bench/maps/random-64-64-10.map" \
    --scen "$bench/scens/random-64-64-10-random-1.scen" --agents 1000 --algorithm lacam \
    --out "$out/lacam-1000.txt" > "$out/plan.log"
  run_args=(--map "$bench/maps/random-64-64-10.map"
    --scen "$bench/scens/random-64-64-10-random-1.scen" --plan "$out/lacam-1000.txt" --axis xy
    --agents 1000 --delay-probability 0.01 --delay-min-s 1 --delay-max-s 4 --seed 0
    --state-rate-hz 0)
fi
if [ "${LIFELONG:-0}" = 1 ]; then
  # monitor/src/live_adg_switching.cpp, live_adg_chain.cpp, live_adg_anticipation.cpp and
  # live_adg_lookahead.cpp: all but the graph's growth and plain dispatch (advance, finish,
  # on_progress, append, commit_cut, truncate).
  switching='LiveAdg::(queue_of|pop_first|try_switches|try_switch|held|shared|due|reach|next_move|stays_before|comes_back|dirty_after_release|reaches|has_edge|still_refused|add_edge|remove_edge|swap_order|observe|finish_estimate|arrival|expected_saving|anticipate|decide|settle_due|clear_marks|margin|saving|lookahead_saving|cone_saving|collect_window|window_saving|exchange_edges|collect_cone|successors|expect|cone_cost|try_chain|chain_link|chain_swap|chain_cycle|undo_chain|chain_saves|switchable_pair)|ActionDurations::|queue_saving'
  tracker='(LiveAdg|ActionDurations)::|queue_saving'
  run_args=(--tasks random --map "$bench/maps/warehouse-10-20-10-2-1.map" --agents 1000
    --task-errands 1 --duration-s 120 --delay-probability 0.01 --delay-min-s 1 --delay-max-s 4
    --seed 1)
fi
# DATA: "tracker% switching% switching-of-user%" of the monitor (the lowest pid: smart run's own):
# the last of its user-space samples alone. The kernel's share of the monitor's samples (mostly
# wake-ups while it waits in lock-step) moved from 23 to 60 % between identical runs on this
# machine (2026-12-02), and the first two shares with it.
share() {
  local pid
  pid=$(perf script -i "$1" -F pid 2> /dev/null | sort -n | head -1 | tr -d ' ')
  perf report -i "$1" --pid "$pid" --sort sym --stdio --percentage relative 2> /dev/null |
    grep '%' | grep -v '^#' |
    awk -v sw="$switching" -v tr="$tracker" '{p = $1; sub("%", "", p)}
      $0 ~ tr {t += p}
      $0 ~ sw {s += p}
      $2 != "[k]" {u += p}
      END {printf "%.2f %.2f %.2f\n", t, s, (u > 0 ? 100 * s / u : 0)}'
}
modes=(adg switchable switchable-opt switchable-lookahead)
[ -z "${MODES:-}" ] || read -r -a modes <<< "$MODES"  # e.g. MODES="switchable-lookahead"
extra=()
[ -z "${RUN_ARGS:-}" ] || read -r -a extra <<< "$RUN_ARGS"
for mode in "${modes[@]}"; do
  for i in $(seq 1 "$repeats"); do
    dir="$out/$mode-$i"
    perf record -q -F 997 -o "$dir.data" -- "$smart" run "${run_args[@]}" \
      --execution "$mode" "${extra[@]}" --out "$dir" --no-progress --domain "${DOMAIN:-92}" \
      > "$dir.out" 2> "$dir.err"
    echo "$mode $i $(share "$dir.data")" | tee -a "$out/shares.txt"
  done
done
awk '{t[$1] += $3; tt[$1] += $3 * $3; s[$1] += $4; ss[$1] += $4 * $4; n[$1]++
    u[$1] += $5; uu[$1] += $5 * $5}
  END {
    for (m in n) {
      sdt = n[m] > 1 ? sqrt((tt[m] - t[m] * t[m] / n[m]) / (n[m] - 1)) : 0
      sds = n[m] > 1 ? sqrt((ss[m] - s[m] * s[m] / n[m]) / (n[m] - 1)) : 0
      sdu = n[m] > 1 ? sqrt((uu[m] - u[m] * u[m] / n[m]) / (n[m] - 1)) : 0
      printf "%-15s monitor CPU in the tracker %.1f ± %.1f %%, in switching %.1f ± %.1f %% (of user-space samples %.1f ± %.1f %%; %d runs)\n",
        m, t[m] / n[m], sdt, s[m] / n[m], sds, u[m] / n[m], sdu, n[m]
    }
  }' "$out/shares.txt" | sort
echo "machine: $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) cores, load $(cut -d' ' -f1 /proc/loadavg)"
