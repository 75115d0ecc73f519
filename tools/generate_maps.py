#!/usr/bin/env python3
"""Writes the scenario maps under assets/maps/ (MovingAI .map format). Deterministic: run it
again and the files come out byte for byte the same. Usage: tools/generate_maps.py

tools/generate_maps.py --large SIZE FILE writes a SIZE x SIZE map like stress512.map (the same
mix of lakes, forests, swamps and rocks per area, open lanes every 64 cells) to FILE, for the
scaling benchmarks of docs/benchmarks.md (2048 and 4096: too big to keep in the repository).

tools/generate_maps.py --maze SIZE CORRIDOR FILE writes a SIZE x SIZE maze like MovingAI's
maze512-CORRIDOR-0 (corridors CORRIDOR cells wide, walls one cell thick, one path between any
two places: a randomised depth-first maze, seeded by SIZE and CORRIDOR), where A* floods."""
import os
import random
import sys

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "assets", "maps")


def blank(w, h, fill="."):
    g = [[fill] * w for _ in range(h)]
    for x in range(w):
        g[0][x] = g[h - 1][x] = "@"
    for y in range(h):
        g[y][0] = g[y][w - 1] = "@"
    return g


def rect(g, x0, y0, x1, y1, c):
    """Fills [x0, x1) x [y0, y1), inside the border."""
    for y in range(max(y0, 1), min(y1, len(g) - 1)):
        for x in range(max(x0, 1), min(x1, len(g[0]) - 1)):
            g[y][x] = c


def blob(g, cx, cy, r, c, rng):
    for y in range(cy - r, cy + r + 1):
        for x in range(cx - r, cx + r + 1):
            if 0 < y < len(g) - 1 and 0 < x < len(g[0]) - 1:
                if (x - cx) ** 2 + (y - cy) ** 2 <= r * r + rng.randint(-r, r):
                    g[y][x] = c


def save_to(path, g):
    with open(path, "w") as f:
        f.write("type octile\nheight %d\nwidth %d\nmap\n" % (len(g), len(g[0])))
        for row in g:
            f.write("".join(row) + "\n")


def save(name, g):
    save_to(os.path.join(OUT, name), g)


def river():
    # A river 8 wide; a ground bridge (rows 8-12) and a swamp ford (rows 28-30).
    g = blank(64, 40)
    rect(g, 28, 0, 36, 40, "W")
    rect(g, 28, 8, 36, 13, ".")
    rect(g, 28, 28, 36, 31, "S")
    return g


def forest():
    # A forest block in the middle; open ground above and below it.
    g = blank(64, 48)
    rect(g, 20, 7, 44, 41, "T")
    return g


def narrow_pass():
    # A mountain ridge with one pass 4 cells wide: tanks (size 3) go through one at a time.
    g = blank(64, 40)
    rect(g, 30, 0, 34, 40, "@")
    rect(g, 30, 18, 34, 22, ".")
    return g


def swamp():
    # A swamp lake across the middle, ground corridors at the top and bottom.
    g = blank(64, 48)
    rect(g, 16, 6, 48, 42, "S")
    return g


def demo():
    # 96x64: a river with a bridge and a ford, a forest, a swamp and rocks.
    rng = random.Random(4)
    g = blank(96, 64)
    rect(g, 44, 0, 50, 64, "W")
    rect(g, 44, 28, 50, 34, ".")
    rect(g, 44, 50, 50, 53, "S")
    rect(g, 18, 6, 32, 22, "T")
    rect(g, 62, 42, 80, 58, "S")
    for cx, cy in [(24, 40), (70, 14), (84, 30), (12, 54)]:
        blob(g, cx, cy, 3, "@", rng)
    return g


def stress(size=512):
    # 512x512: lakes, forests, swamps and rocks scattered with a fixed seed; open lanes
    # along rows and columns every 64 cells keep every region connected for every unit. Larger
    # sizes scatter as many per area (seeded by the size).
    rng = random.Random(size)
    g = blank(size, size)
    scale = (size // 512) ** 2
    for kind, count, rmin, rmax in [("W", 40, 6, 14), ("T", 60, 5, 12), ("S", 40, 5, 12),
                                    ("@", 120, 2, 5)]:
        for _ in range(count * scale):
            blob(g, rng.randint(8, size - 9), rng.randint(8, size - 9), rng.randint(rmin, rmax),
                 kind, rng)
    for k in range(32, size, 64):
        rect(g, 1, k - 3, size - 1, k + 4, ".")
        rect(g, k - 3, 1, k + 4, size - 1, ".")
    return g


def maze(size, corridor):
    # Maze cells of corridor x corridor ground on a lattice of pitch corridor + 1; the walls
    # between lattice neighbours are knocked down along a randomised depth-first tree.
    rng = random.Random(size * 1000 + corridor)
    g = blank(size, size, "@")
    pitch = corridor + 1
    n = (size - 1) // pitch
    seen = [[False] * n for _ in range(n)]

    def open_cell(i, j):
        rect(g, 1 + i * pitch, 1 + j * pitch, 1 + i * pitch + corridor, 1 + j * pitch + corridor,
             ".")

    stack = [(0, 0)]
    seen[0][0] = True
    open_cell(0, 0)
    while stack:
        i, j = stack[-1]
        nexts = [(i + di, j + dj) for di, dj in ((1, 0), (-1, 0), (0, 1), (0, -1))
                 if 0 <= i + di < n and 0 <= j + dj < n and not seen[i + di][j + dj]]
        if not nexts:
            stack.pop()
            continue
        a, b = rng.choice(nexts)
        seen[a][b] = True
        open_cell(a, b)
        # The wall between: the corridor's width along the shared side.
        x0 = 1 + min(i, a) * pitch + (corridor if a != i else 0)
        y0 = 1 + min(j, b) * pitch + (corridor if b != j else 0)
        rect(g, x0, y0, x0 + (1 if a != i else corridor), y0 + (1 if b != j else corridor), ".")
        stack.append((a, b))
    return g


def ambush():
    # 96x48: a river (x 44-51) crossed by a bridge (rows 20-27); forests on the east bank on
    # both sides of the bridge road hide the ambushers; a swamp ford in the south (rows 40-42).
    rng = random.Random(6)
    g = blank(96, 48)
    rect(g, 44, 0, 52, 48, "W")
    rect(g, 44, 20, 52, 28, ".")
    rect(g, 44, 40, 52, 43, "S")
    rect(g, 54, 6, 68, 18, "T")
    rect(g, 54, 30, 68, 40, "T")
    for cx, cy in [(20, 10), (26, 38), (78, 12), (80, 36)]:
        blob(g, cx, cy, 3, "@", rng)
    return g


def forest_battle():
    # 80x64: a forest (x 16-63) cut by a road (rows 28-35) that opens into a clearing (x 34-45,
    # rows 22-41) in its middle; rocks scattered in the wood.
    rng = random.Random(7)
    g = blank(80, 64)
    rect(g, 16, 4, 64, 60, "T")
    rect(g, 1, 28, 79, 36, ".")
    rect(g, 34, 22, 46, 42, ".")
    for cx, cy in [(24, 14), (56, 50), (28, 48), (54, 12)]:
        blob(g, cx, cy, 2, "@", rng)
    return g


def landing():
    # 96x64: sea in the west (x < 40), a beach (x 40-51) with a strip of dunes (trees, x 52-55)
    # and swamp, then the hinterland with rocks. Only amphibious units cross the sea.
    rng = random.Random(8)
    g = blank(96, 64)
    rect(g, 1, 1, 40, 63, "W")
    rect(g, 40, 44, 46, 56, "S")
    rect(g, 52, 10, 56, 26, "T")
    rect(g, 52, 38, 56, 54, "T")
    for cx, cy in [(70, 16), (76, 44), (86, 30)]:
        blob(g, cx, cy, 3, "@", rng)
    return g


if __name__ == "__main__" and len(sys.argv) == 4 and sys.argv[1] == "--large":
    size = int(sys.argv[2])
    if size < 512 or size % 512 != 0:
        sys.exit("generate_maps: --large SIZE must be a multiple of 512")
    save_to(sys.argv[3], stress(size))
elif __name__ == "__main__" and len(sys.argv) == 5 and sys.argv[1] == "--maze":
    size, corridor = int(sys.argv[2]), int(sys.argv[3])
    if size < 16 or corridor < 1 or corridor > size // 4:
        sys.exit("generate_maps: --maze SIZE CORRIDOR needs SIZE >= 16 and 1 <= CORRIDOR <= SIZE/4")
    save_to(sys.argv[4], maze(size, corridor))
elif __name__ == "__main__":
    for name, make in [("river.map", river), ("forest.map", forest), ("pass.map", narrow_pass),
                       ("swamp.map", swamp), ("demo.map", demo), ("stress512.map", stress),
                       ("ambush.map", ambush), ("forest_battle.map", forest_battle),
                       ("landing.map", landing)]:
        save(name, make())
