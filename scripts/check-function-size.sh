#!/usr/bin/env bash
# Fails when a function in the project's own code is longer than the house limit (README,
# "Conventions"): clang-tidy's readability-function-size, LineThreshold 80, over every .cpp of the
# layers. Usage: scripts/check-function-size.sh BUILD_DIR (with compile_commands.json).
set -euo pipefail
build=${1:?usage: $0 BUILD_DIR}
cd "$(dirname "$0")/.."
command -v clang-tidy >/dev/null || { echo "clang-tidy not found; run scripts/install-deps.sh" >&2; exit 2; }
[[ -f $build/compile_commands.json ]] || { echo "$build/compile_commands.json missing; configure first" >&2; exit 2; }
files=$(git ls-files 'idl/*.cpp' 'grid/*.cpp' 'planning/*.cpp' 'monitor/*.cpp' 'agent/*.cpp' 'convert/*.cpp' \
  'sim/*.cpp' 'hw/*.cpp' 'tools/*.cpp' 'common/*.cpp' 'serve/*.cpp')
config='{Checks: "-*,readability-function-size", WarningsAsErrors: "readability-function-size",
  CheckOptions: [{key: readability-function-size.LineThreshold, value: 80}]}'
out=$(mktemp)
trap 'rm -f "$out"' EXIT
# Two at a time (the machine has two cores); each file's findings are printed with its name.
if ! printf '%s\n' $files | xargs -P 2 -n 4 clang-tidy -p "$build" --quiet --config="$config" \
    >"$out" 2>&1; then
  grep -E "exceeds|lines including" "$out" || cat "$out"
  echo "function size check failed: split the functions above into named steps (limit 80 lines)"
  exit 1
fi
echo "function size check: $(printf '%s\n' $files | wc -l) files, no function over 80 lines"
