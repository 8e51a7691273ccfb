#!/usr/bin/env python3
"""Fails when a project include goes up a layer.

The layers and what each may include are the table between the `layers:begin` and `layers:end`
markers of docs/architecture.md (one source: the page a newcomer reads is the rule the build
checks). Each row: layer | files (globs, comma separated; a file belongs to the row whose
matching glob is the most specific, i.e. the longest) | library | pure? | may include (layer
names, comma separated, or "—"; "everything" for the command line and the tests).

Every `#include "…"` of a tracked C++ file under a layer is resolved to the project file it names
(through the `include/` folders, the generated IDL headers belong to `wire`), and the include is
refused when the included file's layer is neither the includer's own nor one it may include.
Usage: scripts/check-layers.py [REPO]; exit 0 clean, 1 with findings, 2 on a broken table.
"""
import fnmatch
import pathlib
import re
import subprocess
import sys

GENERATED = {"smart.h": "wire", "ros2.h": "wire"}  # idlc's output for idl/*.idl


def read_table(doc):
    text = doc.read_text()
    m = re.search(r"<!-- layers:begin -->(.*?)<!-- layers:end -->", text, re.S)
    if not m:
        sys.exit(f"{doc}: no <!-- layers:begin --> ... <!-- layers:end --> table; restore it")
    rows = {}
    for line in m.group(1).splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) < 5 or cells[0] in ("layer", "") or set(cells[0]) <= set("-: "):
            continue
        name = cells[0]
        globs = [g.strip().strip("`") for g in cells[1].split(",") if g.strip()]
        allowed = cells[4]
        may = {"*"} if allowed == "everything" else {
            a.strip() for a in allowed.split(",") if a.strip() not in ("", "—", "-")}
        rows[name] = (globs, may)
    for name, (_, may) in rows.items():
        for a in may - {"*"}:
            if a not in rows:
                print(f"{doc}: layer '{name}' may include '{a}', which is no layer of the table",
                      file=sys.stderr)
                sys.exit(2)
    return rows


# Folders of tests and benchmarks: they may include every layer and belong to none.
UNLAYERED = ("tests/", "bench/")


def layer_of(path, rows):
    best, best_len = None, -1
    for name, (globs, _) in rows.items():
        for g in globs:
            if fnmatch.fnmatch(path, g) and len(g) > best_len:
                best, best_len = name, len(g)
    return best


def main():
    repo = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
    rows = read_table(repo / "docs/architecture.md")
    files = subprocess.run(["git", "-C", str(repo), "ls-files", "-co", "--exclude-standard", "*.cpp", "*.hpp", "*.h"],
                           capture_output=True, text=True, check=True).stdout.split()
    provided = {}  # "smart/x/y.hpp" -> repo path
    for f in files:
        parts = f.split("/include/", 1)
        if len(parts) == 2:
            provided[parts[1]] = f
    include = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
    findings, checked = [], 0
    for f in files:
        mine = layer_of(f, rows)
        if mine is None:
            if not f.startswith(UNLAYERED):
                findings.append(f"{f}: in no layer of the table; add its folder to a row (files)")
            continue
        allowed = rows[mine][1]
        for n, line in enumerate((repo / f).read_text().splitlines(), 1):
            m = include.match(line)
            if not m:
                continue
            target = m.group(1)
            if target in GENERATED:
                theirs = GENERATED[target]
            elif target in provided:
                theirs = layer_of(provided[target], rows)
            else:
                continue  # a file beside the includer, or a library's header
            checked += 1
            if theirs and theirs != mine and "*" not in allowed and theirs not in allowed:
                findings.append(f"{f}:{n}: layer '{mine}' includes \"{target}\" of layer "
                                f"'{theirs}'; it may include only: "
                                f"{', '.join(sorted(allowed)) or 'nothing of the project'}")
    for x in findings:
        print(x)
    if findings:
        print(f"layer check failed: {len(findings)} include(s) go up a layer (docs/architecture.md,"
              " \"Layers\"): move the type down, or the code up")
        return 1
    print(f"layer check: {checked} project includes in {len(files)} files, none goes up a layer")
    return 0


if __name__ == "__main__":
    sys.exit(main())
