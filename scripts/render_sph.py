#!/usr/bin/python3
"""Renders an `hpcplan sph --vtk DIR` or `hpcplan sim --vtk DIR` run (DIR/run_<n> for the
latter), headless: one PNG per written frame (particles coloured by speed, obstacle boxes as
wireframes; for a simulator run also the robot, the goal, the plan it follows and its trail)
and an animation, MP4 through ffmpeg when it is installed, else an animated GIF.

Usage: render_sph.py DIR [--out OUT_PREFIX] [--fps 10] [--max-points 200000] [--gif]
       render_sph.py --fluid KEY=VALUE,... [--frames 100] [--every 5] --out OUT_PREFIX ...
Reads DIR/fluid.pvd and the .vtu files it names with VTK's own reader (python3-vtk9). With
--fluid it runs the fluid itself through the Python package (hpcplan.sph.Fluid, the options of
hpcplan sph's problem: preset=water,scenario=dambreak,particles=4000,...) and draws each K-th
frame straight from the engine's particle arrays (zero-copy NumPy views), with no file between.
"""
import argparse
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import vtk  # noqa: E402
from vtk.util.numpy_support import vtk_to_numpy  # noqa: E402

from hpcplan_package import import_hpcplan, value  # noqa: E402


def read(path):
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    return r.GetOutput()


def box_edges(g):
    """The 12 edges of every hexahedron of a boxes_*.vtu grid."""
    pts = vtk_to_numpy(g.GetPoints().GetData()) if g.GetNumberOfPoints() else np.zeros((0, 3))
    pairs = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
             (0, 4), (1, 5), (2, 6), (3, 7)]
    for c in range(g.GetNumberOfCells()):
        ids = [g.GetCell(c).GetPointId(k) for k in range(8)]
        for a, b in pairs:
            yield pts[ids[a]], pts[ids[b]]


def draw_robot(ax, g):
    """robot_*.vtu: cells with role 0 robot, 1 goal (vertices), 2 plan, 3 trail (polylines)."""
    pts = vtk_to_numpy(g.GetPoints().GetData())
    roles = vtk_to_numpy(g.GetCellData().GetArray("role"))
    style = {0: dict(color="lime", marker="o", s=160, edgecolors="black", label="robot"),
             1: dict(color="red", marker="*", s=260, edgecolors="black", label="goal"),
             2: dict(color="darkorange", lw=3, label="plan"),
             3: dict(color="black", lw=1.5, ls="--", label="trail")}
    for c in range(g.GetNumberOfCells()):
        cell = g.GetCell(c)
        xyz = pts[[cell.GetPointId(k) for k in range(cell.GetNumberOfPoints())]]
        st = style[int(roles[c])]
        if roles[c] <= 1:
            ax.scatter(*xyz.T, depthshade=False, zorder=5, **st)
        else:
            ax.plot(*xyz.T, zorder=4, **st)
    ax.legend(loc="upper left", fontsize=7)


def vtk_frames(a):
    """(time, positions, velocities, box edges, robot grid or None) of each written frame of an
    hpcplan sph/sim --vtk directory, and the bounds holding every frame."""
    pvd = os.path.join(a.dir, "fluid.pvd")
    if not os.path.exists(pvd):
        sys.exit(f"render_sph: error: {pvd} not found (run hpcplan sph --vtk {a.dir})")
    sets = ET.parse(pvd).getroot().find("Collection").findall("DataSet")
    frames = [(float(s.get("timestep")), s.get("file")) for s in sets if s.get("part") == "0"]
    boxes = {float(s.get("timestep")): s.get("file") for s in sets if s.get("part") == "1"}
    robots = {float(s.get("timestep")): s.get("file") for s in sets if s.get("part") == "2"}
    first = read(os.path.join(a.dir, frames[0][1]))
    lo, hi = np.array(first.GetBounds()[0::2]), np.array(first.GetBounds()[1::2])
    for _, name in frames:  # the axes hold every frame
        b = read(os.path.join(a.dir, name)).GetBounds()
        lo, hi = np.minimum(lo, b[0::2]), np.maximum(hi, b[1::2])

    def each():
        for t, name in frames:
            g = read(os.path.join(a.dir, name))
            x = vtk_to_numpy(g.GetPoints().GetData())
            v = vtk_to_numpy(g.GetPointData().GetArray("velocity"))
            edges = list(box_edges(read(os.path.join(a.dir, boxes[t])))) if t in boxes else []
            robot = read(os.path.join(a.dir, robots[t])) if t in robots else None
            yield t, x, v, edges, robot
    return each(), lo, hi


def live_frames(a):
    """The same, from a fluid run in this process: every --every-th frame's fluid particles,
    read from the engine's own arrays."""
    hpcplan = import_hpcplan("render_sph", "--fluid")
    options = {}
    for item in a.fluid.split(","):
        key, _, text = (x.strip() for x in item.partition("="))
        options[key] = value(text)
    try:
        fluid = hpcplan.sph.Fluid(**options)
    except (TypeError, ValueError) as e:
        sys.exit(f"render_sph: error: --fluid: {e}")
    x = fluid.positions  # walls included: the tank frames the axes
    lo, hi = x.min(axis=0), x.max(axis=0)

    def each():
        for frame in range(0, a.frames + 1, a.every):
            if frame > 0:
                report = fluid.step(frames=a.every)
                if not report["stable"]:
                    sys.exit(f"render_sph: error: the fluid became unsound: {report['problem']}")
            keep = fluid.wall == 0  # a copy of the fluid's rows; the views are valid until here
            edges = []
            for b in fluid.boxes:
                corners = [np.array([b[0 + 3 * i], b[1 + 3 * j], b[2 + 3 * k]])
                           for i in (0, 1) for j in (0, 1) for k in (0, 1)]
                edges += [(corners[p], corners[q]) for p, q in
                          [(0, 1), (2, 3), (4, 5), (6, 7), (0, 2), (1, 3), (4, 6), (5, 7),
                           (0, 4), (1, 5), (2, 6), (3, 7)]]
            yield fluid.time, fluid.positions[keep], fluid.velocities[keep], edges, None
    return each(), lo, hi


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dir", nargs="?")
    ap.add_argument("--out", default=None, help="output prefix (default DIR/render)")
    ap.add_argument("--fps", type=int, default=10)
    ap.add_argument("--max-points", type=int, default=200000)
    ap.add_argument("--gif", action="store_true", help="write a GIF even when ffmpeg exists")
    ap.add_argument("--fluid", help="run this fluid here (hpcplan.sph.Fluid's options, "
                                    "key=value,...) instead of reading DIR")
    ap.add_argument("--frames", type=int, default=100, help="with --fluid: frames to run")
    ap.add_argument("--every", type=int, default=5, help="with --fluid: draw every K-th frame")
    a = ap.parse_args()
    if (a.dir is None) == (a.fluid is None):
        sys.exit("render_sph: error: give a VTK directory or --fluid, not both or neither")
    if a.fluid is not None and (a.out is None or a.frames < 1 or a.every < 1):
        sys.exit("render_sph: error: --fluid needs --out, and positive --frames and --every")
    frames, lo, hi = live_frames(a) if a.fluid else vtk_frames(a)
    prefix = a.out or os.path.join(a.dir, "render")
    pngs = []
    rng = np.random.default_rng(0)
    for k, (t, x, v, edges, robot) in enumerate(frames):
        if len(x) > a.max_points:
            keep = rng.choice(len(x), a.max_points, replace=False)
            x, v = x[keep], v[keep]
        speed = np.linalg.norm(v, axis=1)
        fig = plt.figure(figsize=(6, 6))
        ax = fig.add_subplot(projection="3d")
        # With a robot on stage the fluid steps back (faint) so the robot, goal and plan show.
        sc = ax.scatter(x[:, 0], x[:, 1], x[:, 2], c=speed, s=1.5, cmap="viridis", vmin=0,
                        vmax=max(1e-9, np.percentile(speed, 99)), depthshade=False,
                        alpha=0.25 if robot is not None else 1.0)
        for p, q in edges:
            ax.plot(*zip(p, q), color="tab:red", lw=1)
        if robot is not None:
            draw_robot(ax, robot)
        ax.set_xlim(lo[0], hi[0]); ax.set_ylim(lo[1], hi[1]); ax.set_zlim(lo[2], hi[2])
        ax.set_box_aspect(hi - lo)
        ax.set_title(f"t = {t:.2f} s, {len(x)} particles")
        fig.colorbar(sc, ax=ax, shrink=0.6, label="speed (m/s)")
        png = f"{prefix}_{k:05d}.png"
        fig.savefig(png, dpi=90)
        plt.close(fig)
        pngs.append(png)
    if shutil.which("ffmpeg") and not a.gif:
        out = prefix + ".mp4"
        subprocess.run(["ffmpeg", "-y", "-loglevel", "error", "-framerate", str(a.fps), "-i",
                        f"{prefix}_%05d.png", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                        "-pix_fmt", "yuv420p", out], check=True)
    else:
        from PIL import Image
        out = prefix + ".gif"
        images = [Image.open(p) for p in pngs]
        images[0].save(out, save_all=True, append_images=images[1:], duration=1000 // a.fps, loop=0)
    print(f"render_sph: {len(pngs)} frames -> {out}")


if __name__ == "__main__":
    main()
