#!/usr/bin/env python3
"""A lifelong planner for SMART-DDS in plain Python: reads the planning contract's requests on
stdin and writes a window per request on stdout (newline-delimited JSON, one object per line;
docs/planner-protocol.md). Run it as

    smart run --lifelong PROBLEM.json --planner-cmd "python3 examples/planners/greedy_planner.py"

It plans step by step, robots in a priority order that rotates every window: each robot takes the
neighbouring cell (or stays) that brings it closest to its next errand by breadth-first-search
distance, unless a robot planned before it holds that cell at the next step, a robot not yet
planned stands on it now, or the two would swap cells. Robots planned later can always stay, so
every window is free of vertex and swap conflicts. It is a starting point to replace with your
own planner, not a good one: robots can block each other for good.
"""
import json
import sys
from collections import deque

MOVES = ((1, 0), (-1, 0), (0, 1), (0, -1))


class Map:
    def __init__(self, spec):
        self.width = spec["width"]
        self.height = spec["height"]
        self.rows = spec["rows"]
        self._distances = {}

    def free(self, x, y):
        return 0 <= x < self.width and 0 <= y < self.height and self.rows[y][x] != "@"

    def distances(self, goal):
        """Steps from every free cell to `goal` (a dict), computed once per goal."""
        if goal not in self._distances:
            dist = {goal: 0}
            queue = deque([goal])
            while queue:
                x, y = queue.popleft()
                for dx, dy in MOVES:
                    n = (x + dx, y + dy)
                    if n not in dist and self.free(*n):
                        dist[n] = dist[(x, y)] + 1
                        queue.append(n)
            self._distances[goal] = dist
        return self._distances[goal]


def plan_window(grid, request):
    robots = request["robots"]
    steps = request["steps"]
    pos = [tuple(r["cell"]) for r in robots]
    goals = [tuple(r["errands"][0]) if r["errands"] else None for r in robots]
    paths = [[list(p)] for p in pos]
    shift = request["window"] % max(1, len(robots))
    order = list(range(shift, len(robots))) + list(range(shift))
    for _ in range(steps):
        standing = {p: r for r, p in enumerate(pos)}
        planned = {}  # robot -> its cell at the next step
        taken = set()  # cells held at the next step
        for r in order:
            here = pos[r]
            options = [here] + [(here[0] + dx, here[1] + dy) for dx, dy in MOVES]
            options = [c for c in options if grid.free(*c)]
            if goals[r] is not None:
                dist = grid.distances(goals[r])
                options.sort(key=lambda c: (dist.get(c, 1 << 30), c != here))
            else:
                options = [here]
            for c in options:
                if c == here:
                    break
                if c in taken:
                    continue
                other = standing.get(c)
                if other is not None and (other not in planned or planned[other] == here):
                    continue  # stands there now and may stay, or would swap with us
                break
            else:
                c = here
            if c == here and here in taken:
                raise RuntimeError("robot %d cannot stay" % r)  # never: see the docstring
            planned[r] = c
            taken.add(c)
        pos = [planned[r] for r in range(len(robots))]
        for r, p in enumerate(pos):
            paths[r].append(list(p))
    return paths


def main():
    grid = None
    for line in sys.stdin:
        message = json.loads(line)
        if message["type"] == "start":
            grid = Map(message["map"])
            print(json.dumps({"type": "ready", "name": "greedy_planner.py"}), flush=True)
            continue
        try:
            reply = {"window": message["window"], "paths": plan_window(grid, message)}
        except Exception as error:  # tell SMART-DDS why, rather than going silent
            reply = {"window": message["window"], "error": str(error)}
        sys.stdout.write(json.dumps(reply, separators=(",", ":")) + "\n")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
