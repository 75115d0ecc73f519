#!/usr/bin/env python3
"""Writes the chokepoint maps of issue 12 under assets/maps/ (MovingAI .map format): corridors,
a door, bridges, a crossroads, a U-shaped trap and a gap, for the scenarios
scenarios/chokepoints/{corridor_tanks_4,corridor_tanks_5,door_30v30,bridge_two_way,crossroads,u_trap,
gap_200,bridge_2000,two_bridges}.yaml, and the shapes of scenarios/chokepoints/variations/ (other
widths, an L, a passing bay, a wider crossroads, a bridge 16 wide) and of
scenarios/chokepoints/scale/ (larger crowds on a bridge 16 wide). Deterministic (no randomness): run it again and the files come out
byte for byte the same. Standard library only. Usage: tools/generate_chokepoint_maps.py

Coordinates below are cells, x the column and y the row from the top-left; rect() fills
[x0, x1) x [y0, y1) inside the blocked border (tools/generate_maps.py)."""
from generate_maps import blank, rect, save


def corridor(width):
    # 64x24: open ground at both ends (columns 1-16 and 47-62) joined by a corridor 30 cells
    # long (columns 17-46) and `width` cells wide (rows 10 to 10 + width - 1); rock elsewhere.
    g = blank(64, 24)
    rect(g, 17, 0, 47, 24, "@")
    rect(g, 17, 10, 47, 10 + width, ".")
    return g


def door():
    # 49x33: a wall one cell thick (column 24) with a door of one cell (row 16). The map is
    # mirror-symmetric about column 24 and row 16.
    g = blank(49, 33)
    rect(g, 24, 0, 25, 33, "@")
    rect(g, 24, 16, 25, 17, ".")
    return g


def river_with_bridge(w, h, x0, x1, y0, y1):
    # w x h open ground cut by a river over columns [x0, x1), crossed by one bridge of ground over
    # rows [y0, y1).
    g = blank(w, h)
    rect(g, x0, 0, x1, h, "W")
    rect(g, x0, y0, x1, y1, ".")
    return g


def bridge():
    # 64x48: a river 8 cells wide (columns 28-35) with one bridge 6 cells wide (rows 21-26);
    # infantry, jeeps and tanks cannot enter water. Symmetric under a half turn about the centre.
    return river_with_bridge(64, 48, 28, 36, 21, 27)


def crossroads():
    # 64x64: two corridors 8 cells wide, rows 28-35 and columns 28-35, crossing in the middle;
    # rock elsewhere. Four arms of 27 cells from the border to the crossing.
    g = blank(64, 64, "@")
    rect(g, 1, 28, 63, 36, ".")
    rect(g, 28, 1, 36, 63, ".")
    return g


def u_trap():
    # 64x48: a U of rock open to the west: arms rows 12-13 and 34-35 from column 22 to 41, the
    # bottom of the U columns 40-41 (rows 12-35). Inside it is 18 cells deep and 20 high.
    g = blank(64, 48)
    rect(g, 22, 12, 42, 14, "@")
    rect(g, 22, 34, 42, 36, "@")
    rect(g, 40, 12, 42, 36, "@")
    return g


def gap():
    # 64x48: a wall two cells thick (columns 30-31) with a gap of three cells (rows 22-24).
    g = blank(64, 48)
    rect(g, 30, 0, 32, 48, "@")
    rect(g, 30, 22, 32, 25, ".")
    return g


def two_bridges():
    # 104x64: a river 8 cells wide (columns 52-59) with two bridges, a near one 2 cells wide
    # (rows 22-23) and a far one 3 cells wide (rows 38-40).
    g = blank(104, 64)
    rect(g, 52, 0, 60, 64, "W")
    rect(g, 52, 22, 60, 24, ".")
    rect(g, 52, 38, 60, 41, ".")
    return g


def bridge512():
    # 512x512 open ground cut by a river 16 cells wide (columns 248-263) with one bridge 16
    # cells wide (rows 248-263). Symmetric under a half turn about the centre.
    return river_with_bridge(512, 512, 248, 264, 248, 264)


def door2():
    # 49x33: the door map with a door of two cells (rows 15-16).
    g = door()
    rect(g, 24, 15, 25, 17, ".")
    return g


def l_corridor():
    # 56x56: a corridor 4 cells wide that turns once, from a room at the top left (1-14, 1-14)
    # along rows 5-8 to column 44, then down columns 41-44 to a room at the bottom right
    # (columns 35-54, rows 41-54).
    g = blank(56, 56, "@")
    rect(g, 1, 1, 15, 15, ".")
    rect(g, 15, 5, 45, 9, ".")
    rect(g, 41, 5, 45, 41, ".")
    rect(g, 35, 41, 55, 55, ".")
    return g


def long_corridor6():
    # 80x34: open ground at both ends (columns 1-20 and 59-78) joined by a corridor 38 cells
    # long and 6 wide (rows 14-19).
    g = blank(80, 34)
    rect(g, 21, 0, 59, 34, "@")
    rect(g, 21, 14, 59, 20, ".")
    return g


def bay():
    # 60x21: rooms at both ends (columns 1-12 and 47-58) joined by a corridor one cell wide (row
    # 10, columns 13-46) with a bay of 3x3 cells on its north side (columns 29-31, rows 7-9).
    g = blank(60, 21)
    rect(g, 13, 0, 47, 21, "@")
    rect(g, 13, 10, 47, 11, ".")
    rect(g, 29, 7, 32, 10, ".")
    return g


def crossroads6():
    # 64x64: two roads 6 cells wide, rows 29-34 and columns 29-34, crossing in the middle.
    g = blank(64, 64, "@")
    rect(g, 1, 29, 63, 35, ".")
    rect(g, 29, 1, 35, 63, ".")
    return g


def bridge16():
    # 128x96: a river 16 cells wide (columns 56-71) with one bridge 16 cells wide (rows 40-55).
    return river_with_bridge(128, 96, 56, 72, 40, 56)


def bridge192():
    # 192x128: a river 16 cells wide (columns 88-103) with one bridge 16 cells wide (rows 56-71),
    # for the crowds of scenarios/chokepoints/scale/.
    return river_with_bridge(192, 128, 88, 104, 56, 72)


if __name__ == "__main__":
    for name, make in [("corridor4.map", lambda: corridor(4)),
                       ("corridor5.map", lambda: corridor(5)), ("door.map", door),
                       ("bridge.map", bridge), ("crossroads.map", crossroads),
                       ("u_trap.map", u_trap), ("gap.map", gap), ("bridge512.map", bridge512),
                       ("two_bridges.map", two_bridges), ("corridor2.map", lambda: corridor(2)),
                       ("corridor3.map", lambda: corridor(3)), ("door2.map", door2),
                       ("l_corridor.map", l_corridor), ("corridor6_long.map", long_corridor6),
                       ("bay.map", bay), ("crossroads6.map", crossroads6),
                       ("bridge16.map", bridge16), ("bridge192.map", bridge192)]:
        save(name, make())
