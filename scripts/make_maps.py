#!/usr/bin/env python3
"""Writes hpcplan's example worlds to bench/maps/ (deterministic: rerunning gives the same files).

Box maps (seed 004 format, plus start/goal lines):
  single_box   one cube between start and goal
  maze         a 6x6 perfect maze of thin full-height walls
  thin_walls   corridors with 2 cm walls (far thinner than any grid cell) and offset doors
  tower        five floors; each floor's stairwell hole is at the opposite corner
  window       a room whose dividing wall has one small window
  forest       150 random pillars and floating blocks
Sphere worlds (seed 003 style): sphere_world (a few large discs), sphere_dense (many small).
"""
import math
import os
import random
import sys

OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "bench", "maps")


def write(name, header, lines):
    path = os.path.join(OUT, name)
    with open(path + ".tmp", "w") as f:
        f.write("".join("# " + h + "\n" for h in header))
        f.write("\n".join(lines) + "\n")
    os.replace(path + ".tmp", path)


def block(lo, hi, rgb=(0.6, 0.6, 0.6)):
    return "block " + " ".join(f"{v:g}" for v in (*lo, *hi, *rgb))


def boundary(lo, hi):
    return "boundary " + " ".join(f"{v:g}" for v in (*lo, *hi, 0, 0, 0))


def point(kind, p):
    return kind + " " + " ".join(f"{v:g}" for v in p)


def single_box():
    write("single_box.txt", ["One cube between start and goal."],
          [boundary((0, 0, 0), (10, 10, 10)), block((4, 4, 4), (6, 6, 6), (1, 0, 0)),
           point("start", (1, 5, 5)), point("goal", (9, 5, 5.2))])


def maze():
    rng = random.Random(4)
    n, cell, h, t = 6, 3.0, 3.0, 0.2
    # Depth-first carving of a perfect maze; walls between cells that stay closed become blocks.
    seen, stack, open_edges = {(0, 0)}, [(0, 0)], set()
    while stack:
        x, y = stack[-1]
        nbrs = [(x + dx, y + dy) for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1))
                if 0 <= x + dx < n and 0 <= y + dy < n and (x + dx, y + dy) not in seen]
        if not nbrs:
            stack.pop()
            continue
        nx, ny = rng.choice(nbrs)
        open_edges.add(frozenset(((x, y), (nx, ny))))
        seen.add((nx, ny))
        stack.append((nx, ny))
    lines = [boundary((0, 0, 0), (n * cell, n * cell, h))]
    for x in range(n):
        for y in range(n):
            if x + 1 < n and frozenset(((x, y), (x + 1, y))) not in open_edges:
                xs = (x + 1) * cell
                lines.append(block((xs - t / 2, y * cell, 0), (xs + t / 2, (y + 1) * cell, h)))
            if y + 1 < n and frozenset(((x, y), (x, y + 1))) not in open_edges:
                ys = (y + 1) * cell
                lines.append(block((x * cell, ys - t / 2, 0), ((x + 1) * cell, ys + t / 2, h)))
    lines += [point("start", (cell / 2, cell / 2, h / 2)),
              point("goal", (n * cell - cell / 2, n * cell - cell / 2, h / 2))]
    write("maze.txt", ["A 6x6 perfect maze of 0.2 m walls, 3 m high: no way over the top."], lines)


def thin_walls():
    t = 0.02
    lines = [boundary((0, 0, 0), (12, 4, 3))]
    # Five cross walls, 2 cm thick; each has a 0.6 m door, alternating sides.
    for i, x in enumerate((2, 4, 6, 8, 10)):
        door = (0.3, 0.9) if i % 2 == 0 else (3.1, 3.7)
        lines.append(block((x, 0, 0), (x + t, door[0], 3), (0, 0, 1)))
        lines.append(block((x, door[1], 0), (x + t, 4, 3), (0, 0, 1)))
        lines.append(block((x, door[0], 2.0), (x + t, door[1], 3), (0, 0, 1)))  # lintel
    lines += [point("start", (0.5, 2, 1)), point("goal", (11.5, 2, 1))]
    write("thin_walls.txt", ["Corridor cut by 2 cm walls with 0.6 m doors on alternating sides:",
                             "a grid that only checked cell centres would walk through them."], lines)


def tower():
    lines = [boundary((0, 0, 0), (6, 6, 15))]
    hole = 1.5
    for i, z in enumerate((3, 6, 9, 12)):
        # A 0.2 m floor with a square hole in one corner, alternating corners.
        hx = (0, hole) if i % 2 == 0 else (6 - hole, 6)
        hy = hx
        if hx[0] == 0:
            lines.append(block((hole, 0, z), (6, 6, z + 0.2), (0.8, 0.5, 0.2)))
            lines.append(block((0, hole, z), (hole, 6, z + 0.2), (0.8, 0.5, 0.2)))
        else:
            lines.append(block((0, 0, z), (6 - hole, 6, z + 0.2), (0.8, 0.5, 0.2)))
            lines.append(block((6 - hole, 0, z), (6, 6 - hole, z + 0.2), (0.8, 0.5, 0.2)))
        del hy
    lines.append(block((2.5, 2.5, 0), (3.5, 3.5, 15), (0.3, 0.3, 0.3)))  # central column
    lines += [point("start", (4.5, 4.5, 1)), point("goal", (1.0, 4.5, 14))]
    write("tower.txt", ["Four floors with stairwell holes in alternating corners around a column."],
          lines)


def window():
    lines = [boundary((0, 0, 0), (10, 8, 5))]
    # Dividing wall at x = 5 (0.3 m thick) with a 0.8 m x 0.8 m window at y 5.6..6.4, z 3..3.8.
    x0, x1 = 5.0, 5.3
    lines.append(block((x0, 0, 0), (x1, 5.6, 5), (0.5, 0.5, 0.8)))
    lines.append(block((x0, 6.4, 0), (x1, 8, 5), (0.5, 0.5, 0.8)))
    lines.append(block((x0, 5.6, 0), (x1, 6.4, 3.0), (0.5, 0.5, 0.8)))
    lines.append(block((x0, 5.6, 3.8), (x1, 6.4, 5), (0.5, 0.5, 0.8)))
    lines.append(block((2, 1, 0), (3, 6, 1.2), (0.4, 0.3, 0.2)))  # a table in the way
    lines += [point("start", (1, 1, 0.5)), point("goal", (9, 1, 0.5))]
    write("window.txt", ["Two rooms joined only by a small window high in the dividing wall."],
          lines)


def forest():
    rng = random.Random(7)
    lines = [boundary((0, 0, 0), (20, 20, 6))]
    start, goal = (0.5, 0.5, 1), (19.5, 19.5, 5)
    count = 0
    while count < 150:
        w, d = rng.uniform(0.3, 1.2), rng.uniform(0.3, 1.2)
        x, y = rng.uniform(0, 20 - w), rng.uniform(0, 20 - d)
        if rng.random() < 0.7:
            z0, z1 = 0, rng.uniform(3, 6)  # pillar
        else:
            z0 = rng.uniform(0, 4)
            z1 = z0 + rng.uniform(0.5, 2)
        lo, hi = (x, y, z0), (x + w, y + d, z1)
        if any(all(lo[k] - 0.3 <= p[k] <= hi[k] + 0.3 for k in range(3)) for p in (start, goal)):
            continue
        lines.append(block(lo, hi, (0.1, 0.6, 0.1)))
        count += 1
    lines += [point("start", start), point("goal", goal)]
    write("forest.txt", ["150 random pillars and floating blocks."], lines)


def spheres():
    write("sphere_world.txt", ["Seed 003 style sphere world: a few large discs in a disc."],
          ["boundary 0 0 10", "sphere -4 3 2.2", "sphere 3 4 2.5", "sphere 0 -1 2.0",
           "sphere -3 -5 1.8", "sphere 4.5 -3.5 2.0", "start -8 0", "goal 8 0.5"])
    rng = random.Random(3)
    lines, n = ["boundary 0 0 10"], 0
    while n < 40:
        r = rng.uniform(0.4, 1.1)
        a, rr = rng.uniform(0, 2 * math.pi), math.sqrt(rng.random()) * (9.5 - r)
        c = (rr * math.cos(a), rr * math.sin(a))
        if min(math.dist(c, (-8.5, 0)), math.dist(c, (8.5, 0))) < r + 0.5:
            continue
        lines.append(f"sphere {c[0]:.3f} {c[1]:.3f} {r:.3f}")
        n += 1
    lines += ["start -8.5 0", "goal 8.5 0"]
    write("sphere_dense.txt", ["40 random small discs in a disc."], lines)


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    for make in (single_box, maze, thin_walls, tower, window, forest, spheres):
        make()
