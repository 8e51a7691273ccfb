#!/usr/bin/env bash
# Fails when clang-tidy finds anything in the project's own code, with the checks of .clang-tidy
# (bugprone, performance and modernize subsets, and the house limit on a function's length:
# readability-function-size, 80 lines; README, "Conventions"), over every .cpp of the layers and
# the headers they include. Usage: scripts/clang-tidy.sh BUILD_DIR (with compile_commands.json)
# [FILE...] (default: every tracked .cpp of the layers).
set -euo pipefail
build=${1:?usage: $0 BUILD_DIR [FILE...]}
shift
cd "$(dirname "$0")/.."
command -v clang-tidy >/dev/null || { echo "clang-tidy not found; run scripts/install-deps.sh" >&2; exit 2; }
[[ -f $build/compile_commands.json ]] || { echo "$build/compile_commands.json missing; configure first" >&2; exit 2; }
if (($#)); then
  files=$*
else
  files=$(git ls-files 'common/*.cpp' 'idl/*.cpp' 'grid/*.cpp' 'planning/*.cpp' 'agent/*.cpp' \
    'convert/*.cpp' 'monitor/*.cpp' 'lifelong/*.cpp' 'record/*.cpp' 'bridge/*.cpp' 'sim/*.cpp' \
    'hw/*.cpp' 'security/*.cpp' 'commissioning/*.cpp' 'experiment/*.cpp' 'serve/*.cpp' \
    'tools/*.cpp')
fi
out=$(mktemp)
jobs=$(mktemp)
db=$(mktemp -d)
trap 'rm -rf "$out" "$jobs" "$db"' EXIT
# Unity builds list batch files, not sources: scripts/tidy_units.py says what to lint (whole
# batches where they hold only files to lint, the rest one by one) and writes a per-source
# database for the latter.
python3 scripts/tidy_units.py "$build" "$db" $files >"$jobs"
# A batch #includes its sources, which bugprone-suspicious-include would flag: off for batches.
lint() {
  if [[ $3 == 1 ]]; then
    clang-tidy -p "$build" --config-file="$1" --checks=-bugprone-suspicious-include --quiet "$2"
  else
    clang-tidy -p "$db" --config-file="$1" --quiet "$2"
  fi
}
export -f lint
export build db
# Two at a time (the machine has two cores), at a lower priority than the tests that run beside
# it in `make test` (their processes wait for events, and a lint run should not starve them);
# each finding is printed with its file and line.
if ! nice -n 10 xargs -P 2 -L 1 bash -c 'lint "$@"' _ <"$jobs" >"$out" 2>&1; then
  grep -E "(warning|error):" "$out" || cat "$out"
  echo "clang-tidy failed: fix the findings above (.clang-tidy says why each check is on)"
  exit 1
fi
echo "clang-tidy: $(printf '%s\n' $files | wc -l) files in $(wc -l <"$jobs") runs, no finding"
