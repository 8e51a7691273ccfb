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
trap 'rm -f "$out"' EXIT
# Two at a time (the machine has two cores), at a lower priority than the tests that run beside
# it in `make test` (their processes wait for events, and a lint run should not starve them);
# each finding is printed with its file and line.
if ! printf '%s\n' $files | nice -n 10 xargs -P 2 -n 4 clang-tidy -p "$build" --quiet >"$out" 2>&1; then
  grep -E "(warning|error):" "$out" || cat "$out"
  echo "clang-tidy failed: fix the findings above (.clang-tidy says why each check is on)"
  exit 1
fi
echo "clang-tidy: $(printf '%s\n' $files | wc -l) files, no finding"
