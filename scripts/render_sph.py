#!/usr/bin/python3
"""Renders an `hpcplan sph --vtk DIR` or `hpcplan sim --vtk DIR` run (DIR/run_<n> for the
latter), headless: one PNG per written frame (particles coloured by speed, obstacle boxes as
wireframes; for a simulator run also the robot, the goal, the plan it follows and its trail)
and an animation, MP4 through ffmpeg when it is installed, else an animated GIF.

Usage: render_sph.py DIR [--out OUT_PREFIX] [--fps 10] [--max-points 200000] [--gif]
Reads DIR/fluid.pvd and the .vtu files it names with VTK's own reader (python3-vtk9).
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


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dir")
    ap.add_argument("--out", default=None, help="output prefix (default DIR/render)")
    ap.add_argument("--fps", type=int, default=10)
    ap.add_argument("--max-points", type=int, default=200000)
    ap.add_argument("--gif", action="store_true", help="write a GIF even when ffmpeg exists")
    a = ap.parse_args()
    pvd = os.path.join(a.dir, "fluid.pvd")
    if not os.path.exists(pvd):
        sys.exit(f"render_sph: error: {pvd} not found (run hpcplan sph --vtk {a.dir})")
    sets = ET.parse(pvd).getroot().find("Collection").findall("DataSet")
    frames = [(float(s.get("timestep")), s.get("file")) for s in sets if s.get("part") == "0"]
    boxes = {float(s.get("timestep")): s.get("file") for s in sets if s.get("part") == "1"}
    robots = {float(s.get("timestep")): s.get("file") for s in sets if s.get("part") == "2"}
    prefix = a.out or os.path.join(a.dir, "render")
    first = read(os.path.join(a.dir, frames[0][1]))
    lo, hi = np.array(first.GetBounds()[0::2]), np.array(first.GetBounds()[1::2])
    for _, name in frames:  # the axes hold every frame
        b = read(os.path.join(a.dir, name)).GetBounds()
        lo, hi = np.minimum(lo, b[0::2]), np.maximum(hi, b[1::2])
    pngs = []
    rng = np.random.default_rng(0)
    for k, (t, name) in enumerate(frames):
        g = read(os.path.join(a.dir, name))
        x = vtk_to_numpy(g.GetPoints().GetData())
        v = vtk_to_numpy(g.GetPointData().GetArray("velocity"))
        if len(x) > a.max_points:
            keep = rng.choice(len(x), a.max_points, replace=False)
            x, v = x[keep], v[keep]
        speed = np.linalg.norm(v, axis=1)
        fig = plt.figure(figsize=(6, 6))
        ax = fig.add_subplot(projection="3d")
        # With a robot on stage the fluid steps back (faint) so the robot, goal and plan show.
        sc = ax.scatter(x[:, 0], x[:, 1], x[:, 2], c=speed, s=1.5, cmap="viridis", vmin=0,
                        vmax=max(1e-9, np.percentile(speed, 99)), depthshade=False,
                        alpha=0.25 if t in robots else 1.0)
        if t in boxes:
            for p, q in box_edges(read(os.path.join(a.dir, boxes[t]))):
                ax.plot(*zip(p, q), color="tab:red", lw=1)
        if t in robots:
            draw_robot(ax, read(os.path.join(a.dir, robots[t])))
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
