#!/usr/bin/env python3
"""Free-flow times of a scenario's groups: how long each unit would take alone, with no other
unit on the map. For every group it places the units as `rts run` does (row-major in the spawn
area, footprints not overlapping, earlier groups first), computes the shortest 8-connected path
of the unit's footprint (moves 1 and sqrt 2, no corner cutting, every footprint cell in the
type's capability) from its spawn anchor to the nearest anchor inside its goal area (arrival
is counted when the anchor enters the area), and divides by the speed on the terrain of each
move's destination cell; the time to accelerate to that speed (v / 2a) is added once.
Paths in the engine are smoothed, so the figures are slight overestimates.

Reads the flow-style group lines of the bundled scenarios (`- {name: .., team: .., type: ..,
count: N, spawn: {x: .., y: .., w: .., h: ..}, goal: {...}}`) and the catalogue's layout of
assets/units.yaml; `unit_types` overrides are not read. Standard library only.
Usage: tools/free_flow.py scenarios/X.yaml [...]"""
import heapq
import math
import os
import re
import sys

GLYPH = {".": "ground", "G": "ground", "S": "swamp", "T": "trees", "W": "water"}


def load_map(path):
    with open(path) as f:
        lines = f.read().split("\n")
    start = lines.index("map") + 1
    h = int(lines[1].split()[1])
    return [row for row in lines[start:start + h]]


def load_catalogue(path):
    types, name = {}, None
    for line in open(path):
        m = re.match(r"^  (\w+):\s*$", line)
        if m:
            name = m.group(1)
            types[name] = {}
            continue
        m = re.match(r"^    (size|capability|speed|acceleration):\s*(.+)$", line)
        if name and m:
            key, value = m.group(1), m.group(2).strip()
            if key == "size":
                types[name]["size"] = int(value)
            elif key == "acceleration":
                types[name]["acceleration"] = float(value)
            elif key == "capability":
                types[name]["capability"] = set(re.findall(r"\w+", value))
            elif value.startswith("{"):
                types[name]["speed"] = {k: float(v) for k, v in
                                        re.findall(r"(\w+):\s*([\d.]+)", value)}
            else:
                types[name]["speed"] = float(value)
    return types


def area(text, key):
    m = re.search(key + r":\s*\{x:\s*(\d+),\s*y:\s*(\d+),\s*w:\s*(\d+),\s*h:\s*(\d+)\}", text)
    return tuple(int(v) for v in m.groups()) if m else None


def load_scenario(path):
    text = open(path).read()
    here = os.path.dirname(os.path.abspath(path))
    grid = load_map(os.path.join(here, re.search(r"^map:\s*(\S+)", text, re.M).group(1)))
    types = load_catalogue(os.path.join(here, re.search(r"^catalogue:\s*(\S+)", text,
                                                          re.M).group(1)))
    section = text.split("\ngroups:", 1)[1]
    section = re.split(r"\n[a-z_]+:", section, maxsplit=1)[0]
    groups = []
    for entry in section.split("\n  - ")[1:]:
        groups.append({"name": re.search(r"name:\s*(\w+)", entry).group(1),
                       "type": re.search(r"type:\s*(\w+)", entry).group(1),
                       "count": int(re.search(r"count:\s*(\d+)", entry).group(1)),
                       "spawn": area(entry, "spawn"), "goal": area(entry, "goal")})
    return grid, types, groups


def stand(grid, unit, x, y):
    s = unit["size"]
    if x < 0 or y < 0 or y + s > len(grid) or x + s > len(grid[0]):
        return False
    return all(GLYPH.get(grid[y + dy][x + dx]) in unit["capability"]
               for dy in range(s) for dx in range(s))


def speed_at(grid, unit, x, y):
    v = unit["speed"]
    return v if isinstance(v, float) else v[GLYPH[grid[y][x]]]


def place(grid, unit, spawn, count, occupied):
    x0, y0, w, h = spawn
    s, anchors = unit["size"], []
    for y in range(y0, y0 + h):
        for x in range(x0, x0 + w):
            if len(anchors) >= count:
                return anchors
            cells = [(x + dx, y + dy) for dy in range(s) for dx in range(s)]
            if not stand(grid, unit, x, y) or any(c in occupied for c in cells):
                continue
            occupied.update(cells)
            anchors.append((x, y))
    return anchors


def times_to_goal(grid, unit, goal):
    """Seconds from every anchor to the goal area (Dijkstra from the area's anchors)."""
    x0, y0, w, h = goal
    best, queue = {}, []
    ok = [[stand(grid, unit, x, y) for x in range(len(grid[0]))] for y in range(len(grid))]

    def can(x, y):
        return 0 <= y < len(ok) and 0 <= x < len(ok[0]) and ok[y][x]

    for y in range(y0, y0 + h):
        for x in range(x0, x0 + w):
            if can(x, y):
                best[(x, y)] = 0.0
                queue.append((0.0, x, y))
    heapq.heapify(queue)
    while queue:
        t, x, y = heapq.heappop(queue)
        if t > best[(x, y)]:
            continue
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                if (dx, dy) == (0, 0) or not can(x + dx, y + dy):
                    continue
                if dx and dy and not (can(x + dx, y) and can(x, y + dy)):
                    continue
                # Reversed search: the move runs from (x+dx, y+dy) to (x, y) at (x, y)'s speed.
                n = t + math.hypot(dx, dy) / speed_at(grid, unit, x, y)
                if n < best.get((x + dx, y + dy), math.inf):
                    best[(x + dx, y + dy)] = n
                    heapq.heappush(queue, (n, x + dx, y + dy))
    return best


def main(paths):
    for path in paths:
        grid, types, groups = load_scenario(path)
        occupied = set()
        print(path)
        for g in groups:
            unit = types[g["type"]]
            anchors = place(grid, unit, g["spawn"], g["count"], occupied)
            best = times_to_goal(grid, unit, g["goal"])
            v = unit["speed"]
            top = v if isinstance(v, float) else max(v.values())
            accel = top / (2 * unit["acceleration"])
            t = sorted(best[a] + accel for a in anchors)
            print("  %-16s %-9s %4d units  free flow %6.1f s (nearest) %6.1f s (median) "
                  "%6.1f s (farthest)" % (g["name"], g["type"], len(anchors), t[0],
                                          t[len(t) // 2], t[-1]))


if __name__ == "__main__":
    main(sys.argv[1:])
