#!/usr/bin/env python3
"""Draws a world file (box map or sphere world) with one or more paths to a PNG.

  draw_paths.py MAP OUT.png [PATH.csv[:label] ...] [--plan ALGO[:label] ...] [--title T]

Box maps get four matplotlib 3D views (perspective, top, front, side); sphere worlds one 2D
plot. The world is read by the engine's own parser, through the Python package (hpcplan.map3d,
hpcplan.sphere2d), so the drawing shows what the planners see. Path files are what
`hpcplan map3d|sphere2d --path-out` and hpcplan_world_sweep --paths write (x,y[,z] per line,
optional header); --plan ALGO plans the map's own query in this process with that planner
(repeatable). Run with /usr/bin/python3 (Debian's matplotlib).
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

from hpcplan_package import import_hpcplan  # noqa: E402


def read_world(hpcplan, path):
    """The world as the engine parses it: a box map, else a sphere world (ValueError with the
    box map's message when it is neither)."""
    try:
        box = hpcplan.map3d.load(path)
        blocks = [list(b) + list(c) for b, c in zip(box.obstacles, box.colours)]
        lo, hi = box.bounds
        return box, {"blocks": blocks, "spheres": [], "boundary": list(lo) + list(hi),
                     "start": box.start, "goal": box.goal}
    except ValueError as as_box:
        try:
            world = hpcplan.sphere2d.load(path)
        except ValueError:
            raise as_box from None
        return world, {"blocks": [], "spheres": world.obstacles.tolist(),
                       "boundary": world.boundary.tolist(), "start": world.start,
                       "goal": world.goal}


def read_path(path):
    pts = []
    for line in open(path):
        line = line.strip()
        if not line or line[0].isalpha():
            continue
        pts.append([float(x) for x in line.split(",")])
    return pts


def box_faces(b):
    x0, y0, z0, x1, y1, z1 = b[:6]
    c = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    idx = [(0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (1, 2, 6, 5), (0, 3, 7, 4)]
    return [[c[i] for i in f] for f in idx]


def colour(b):
    rgb = b[6:9] if len(b) >= 9 else [0.5, 0.5, 0.5]
    if max(rgb) > 1:
        rgb = [v / 255 for v in rgb]
    return rgb


def draw_3d(world, paths, out, title):
    views = [("perspective", 25, -60), ("top", 90, -90), ("front", 0, -90), ("side", 0, 0)]
    fig = plt.figure(figsize=(14, 11))
    bnd = world["boundary"]
    for n, (name, elev, azim) in enumerate(views):
        ax = fig.add_subplot(2, 2, n + 1, projection="3d")
        faces, colours = [], []
        for b in world["blocks"]:
            for f in box_faces(b):
                faces.append(f)
                colours.append(colour(b))
        if faces:
            ax.add_collection3d(Poly3DCollection(faces, facecolors=colours, edgecolors=(0, 0, 0, 0.15),
                                                 linewidths=0.3, alpha=0.25))
        for pts, label in paths:
            xs, ys, zs = zip(*pts)
            ax.plot(xs, ys, zs, linewidth=2, label=label)
        for key, marker, col in (("start", "o", "green"), ("goal", "*", "red")):
            p = world[key]
            if p is None and paths:
                p = paths[0][0][0 if key == "start" else -1]
            if p is not None:
                ax.scatter(*p[:3], marker=marker, s=80, color=col, depthshade=False)
        if bnd:
            ax.set_xlim(bnd[0], bnd[3])
            ax.set_ylim(bnd[1], bnd[4])
            ax.set_zlim(bnd[2], bnd[5])
            ax.set_box_aspect((bnd[3] - bnd[0], bnd[4] - bnd[1], bnd[5] - bnd[2]))
        ax.view_init(elev=elev, azim=azim)
        ax.set_title(name)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_zlabel("z")
        if n == 0 and paths:
            ax.legend(loc="upper left", fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def draw_2d(world, paths, out, title):
    fig, ax = plt.subplots(figsize=(7, 7))
    cx, cy, r = world["boundary"]
    ax.add_patch(plt.Circle((cx, cy), r, fill=False, color="black"))
    for sx, sy, sr in world["spheres"]:
        ax.add_patch(plt.Circle((sx, sy), sr, color="grey", alpha=0.6))
    for pts, label in paths:
        xs, ys = zip(*[p[:2] for p in pts])
        ax.plot(xs, ys, linewidth=1.8, label=label)
    for key, marker, col in (("start", "o", "green"), ("goal", "*", "red")):
        if world[key] is not None:
            ax.plot(*world[key], marker=marker, color=col, markersize=10)
    ax.set_xlim(cx - r * 1.05, cx + r * 1.05)
    ax.set_ylim(cy - r * 1.05, cy + r * 1.05)
    ax.set_aspect("equal")
    if paths:
        ax.legend(fontsize=8, loc="lower left")
    ax.set_title(title)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    ap.add_argument("map")
    ap.add_argument("out")
    ap.add_argument("paths", nargs="*")
    ap.add_argument("--plan", action="append", default=[],
                    help="ALGO[:label]: plan the map's own query with this planner and draw it")
    ap.add_argument("--title", default=None)
    a = ap.parse_args()
    hpcplan = import_hpcplan("draw_paths", "reading the world")
    try:
        loaded, world = read_world(hpcplan, a.map)
        paths = []
        for spec in a.paths:
            file, _, label = spec.partition(":")
            paths.append((read_path(file), label or os.path.basename(file)))
        for spec in a.plan:
            algo, _, label = spec.partition(":")
            r = loaded.plan(algo=algo)
            if r.status != "solved":
                print(f"draw_paths: {algo} found no path ({r.status})", file=sys.stderr)
                continue
            paths.append((r.path.tolist(), label or f"{algo} ({r.length:.2f})"))
    except (OSError, ValueError, TypeError) as e:
        print(f"draw_paths: error: {e}", file=sys.stderr)
        return 2
    title = a.title or os.path.basename(a.map)
    tmp = a.out + ".tmp.png"
    (draw_2d if len(world["boundary"]) == 3 else draw_3d)(world, paths, tmp, title)
    os.replace(tmp, a.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
