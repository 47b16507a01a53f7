#!/usr/bin/python3
"""Draws a 2D occupancy map with a path and, optionally, a distance field to a PNG.

  draw_map.py MAP OUT.png [--path FILE|-] [--field FIELD.npy] [--slice Z] [--px N]

MAP is a MovingAI .map ('.', 'G', 'S' free; 'W' water, drawn blue; anything else blocked), a
.3dmap voxel map (one z slice, --slice, default 0) or a 2D .npy array (bool or integer,
nonzero = blocked, shape (H, W): row y, column x). The file is read here, not by the engine.

--path: the JSON that `hpcplan grid --map MAP --path --json` prints (or writes with --output);
FILE, or '-' for stdin. Its "path" is a list of [x, y] (or [x, y, z]: drawn projected onto the
slice) cell coordinates, x the column; the start and goal are marked.

--field: a distance field as a .npy of shape (H, W), float32 (cost) or int32 (hops), -1 where
unreachable: reachable cells coloured by distance (viridis, a colour bar inset), unreachable
free cells grey, blocked cells black.

The PNG is the map alone, N pixels per cell (--px; default the largest N with N * max(H, W)
<= 1024, at least 1), so its size is W*N x H*N; written atomically (a temporary file beside it,
then renamed). Bad input: one line "draw_map: error: ..." on stderr, exit 2. Run with
/usr/bin/python3 (Debian's matplotlib and NumPy).
"""
import argparse
import json
import os
import sys
import tempfile

import numpy as np


class InputError(Exception):
    pass


def read_movingai(path):
    """(blocked, water) boolean (H, W) arrays of a .map."""
    with open(path, "r", newline=None) as f:
        lines = f.read().splitlines()
    height = width = None
    k = 0
    while k < len(lines):
        words = lines[k].split()
        k += 1
        if not words:
            continue
        key = words[0].lower()
        if key == "map":
            break
        if key in ("height", "width") and len(words) == 2 and words[1].isdigit():
            if key == "height":
                height = int(words[1])
            else:
                width = int(words[1])
        elif key != "type":
            raise InputError(f"{path}:{k}: unexpected header line '{lines[k - 1]}'")
    else:
        raise InputError(f"{path}: no 'map' line")
    if not height or not width:
        raise InputError(f"{path}: the header gives no height and width")
    rows = lines[k:k + height]
    if len(rows) < height:
        raise InputError(f"{path}: {len(rows)} map rows, the header says {height}")
    grid = np.array([list(r[:width].ljust(width, "@")) for r in rows])
    for y, r in enumerate(rows):
        if len(r.rstrip()) < width:
            raise InputError(f"{path}:{k + y + 1}: a row of {len(r.rstrip())} cells, not {width}")
    free = np.isin(grid, [".", "G", "S"])
    water = grid == "W"
    return ~(free | water), water


def read_voxel(path, z):
    """The blocked cells of slice z of a .3dmap, (H, W) = (y, x)."""
    with open(path) as f:
        header = f.readline().split()
        if len(header) != 4 or header[0].lower() != "voxel":
            raise InputError(f"{path}:1: not a .3dmap header ('voxel W H D')")
        try:
            w, h, d = (int(v) for v in header[1:])
        except ValueError:
            raise InputError(f"{path}:1: not a .3dmap header ('voxel W H D')") from None
        if z < 0 or z >= d:
            raise InputError(f"--slice {z} is outside the map's depth 0..{d - 1}")
        blocked = np.zeros((h, w), dtype=bool)
        for n, line in enumerate(f, start=2):
            words = line.split()
            if not words:
                continue
            try:
                x, y, zz = (int(v) for v in words)
            except ValueError:
                raise InputError(f"{path}:{n}: not a voxel 'x y z'") from None
            if not (0 <= x < w and 0 <= y < h and 0 <= zz < d):
                raise InputError(f"{path}:{n}: voxel outside the {w} x {h} x {d} box")
            if zz == z:
                blocked[y, x] = True
    return blocked, np.zeros_like(blocked)


def read_npy_map(path):
    try:
        a = np.load(path, allow_pickle=False)
    except (ValueError, OSError, EOFError) as e:
        raise InputError(f"{path}: not a NumPy .npy file ({e})") from None
    if a.ndim != 2 or a.dtype.kind not in "biu":
        raise InputError(f"{path}: a map .npy must be 2D bool or integer, not {a.ndim}D "
                         f"{a.dtype}")
    blocked = a != 0
    return blocked, np.zeros_like(blocked)


def read_map(path, z):
    ext = os.path.splitext(path)[1].lower()
    if ext == ".map":
        return read_movingai(path)
    if ext == ".3dmap":
        return read_voxel(path, z)
    if ext == ".npy":
        return read_npy_map(path)
    raise InputError(f"{path}: unknown map format (.map, .3dmap or .npy)")


def read_path(source):
    """The [x, y(, z)] points of a `hpcplan grid --path --json` result."""
    name = "stdin" if source == "-" else source
    text = sys.stdin.read() if source == "-" else open(source).read()
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as e:
        raise InputError(f"{name}: not JSON ({e.msg} at line {e.lineno})") from None
    path = doc.get("path") if isinstance(doc, dict) else None
    if path is None and isinstance(doc, dict) and isinstance(doc.get("result"), dict):
        path = doc["result"].get("path")
    if path is None:
        status = doc.get("status") if isinstance(doc, dict) else None
        raise InputError(f"{name}: no \"path\" (run hpcplan grid with --path"
                         + (f"; status {status}" if status else "") + ")")
    try:
        pts = np.array(path, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name}: \"path\" is not a list of points") from None
    if pts.ndim != 2 or pts.shape[1] < 2 or len(pts) == 0:
        raise InputError(f"{name}: \"path\" is not a list of [x, y] points")
    return pts


def read_field(path, shape):
    try:
        f = np.load(path, allow_pickle=False)
    except (ValueError, OSError, EOFError) as e:
        raise InputError(f"{path}: not a NumPy .npy file ({e})") from None
    if f.dtype.kind not in "fi":
        raise InputError(f"{path}: a field is float32 (cost) or int32 (hops), not {f.dtype}")
    if f.shape != shape:
        raise InputError(f"{path}: the field's shape {f.shape} is not the map's {shape}")
    return f


def draw(args):
    blocked, water = read_map(args.map, args.slice)
    h, w = blocked.shape
    if h == 0 or w == 0:
        raise InputError(f"{args.map}: an empty map")
    pts = read_path(args.path) if args.path is not None else None
    field = read_field(args.field, blocked.shape) if args.field is not None else None
    if pts is not None:
        bad = (pts[:, 0] < 0) | (pts[:, 0] >= w) | (pts[:, 1] < 0) | (pts[:, 1] >= h)
        if bad.any():
            x, y = pts[np.argmax(bad), :2]
            raise InputError(f"path point ({x:g}, {y:g}) is outside the {w} x {h} map")
    px = args.px or max(1, 1024 // max(h, w))
    if px * max(h, w) > 32768:
        raise InputError(f"--px {px}: an image of {w * px} x {h * px} pixels is too large")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    dpi = 100
    fig = plt.figure(figsize=(w * px / dpi, h * px / dpi), dpi=dpi)
    ax = fig.add_axes([0, 0, 1, 1])
    ax.set_axis_off()
    rgb = np.ones((h, w, 3))
    rgb[blocked] = 0.0
    rgb[water] = (0.55, 0.7, 0.95)
    ax.imshow(rgb, interpolation="nearest", origin="upper")
    if field is not None:
        reach = (field >= 0) & ~blocked
        masked = np.ma.masked_where(~reach, field.astype(float))
        cmap = matplotlib.colormaps["viridis"].copy()
        cmap.set_bad(alpha=0.0)
        img = ax.imshow(masked, cmap=cmap, interpolation="nearest", origin="upper")
        grey = np.zeros((h, w, 4))
        grey[(field < 0) & ~blocked] = (0.6, 0.6, 0.6, 1.0)
        ax.imshow(grey, interpolation="nearest", origin="upper")
        from matplotlib.patches import Rectangle
        ax.add_patch(Rectangle((0.84, 0.02), 0.15, 0.36, transform=ax.transAxes,
                               facecolor="white", alpha=0.85, zorder=3))
        cax = ax.inset_axes([0.86, 0.05, 0.025, 0.3])
        bar = fig.colorbar(img, cax=cax)
        bar.ax.tick_params(labelsize=max(5, min(9, w * px // 120)))
    if pts is not None:
        lw = max(1.0, px * 0.6)
        ax.plot(pts[:, 0], pts[:, 1], color="red", linewidth=lw, solid_capstyle="round")
        ms = max(4.0, px * 2.5)
        ax.plot(pts[0, 0], pts[0, 1], "o", color="lime", markersize=ms, markeredgecolor="black")
        ax.plot(pts[-1, 0], pts[-1, 1], "*", color="orange", markersize=ms * 1.4,
                markeredgecolor="black")
    ax.set_xlim(-0.5, w - 0.5)
    ax.set_ylim(h - 0.5, -0.5)

    out_dir = os.path.dirname(os.path.abspath(args.out))
    fd, tmp = tempfile.mkstemp(prefix=".draw_map.", suffix=".png.tmp", dir=out_dir)
    try:
        with os.fdopen(fd, "wb") as f:
            fig.savefig(f, format="png", dpi=dpi)
        os.replace(tmp, args.out)
    except BaseException:
        os.unlink(tmp)
        raise
    finally:
        plt.close(fig)
    return w * px, h * px


def main():
    p = argparse.ArgumentParser(prog="draw_map", description=__doc__.split("\n\n")[0])
    p.add_argument("map", help=".map, .3dmap or 2D .npy")
    p.add_argument("out", help="the PNG to write")
    p.add_argument("--path", help="hpcplan grid --path --json output (FILE or - for stdin)")
    p.add_argument("--field", help="distance field .npy, (H, W) float32/int32, -1 unreachable")
    p.add_argument("--slice", type=int, default=0, help="z slice of a .3dmap (default 0)")
    p.add_argument("--px", type=int, default=0, help="pixels per cell (default: fit 1024)")
    args = p.parse_args()
    if args.px < 0:
        p.exit(2, "draw_map: error: --px must be >= 0\n")
    try:
        out_dir = os.path.dirname(os.path.abspath(args.out))
        if not os.path.isdir(out_dir):
            raise InputError(f"{args.out}: the folder {out_dir} does not exist")
        width, height = draw(args)
    except InputError as e:
        p.exit(2, f"draw_map: error: {e}\n")
    except (OSError, UnicodeDecodeError) as e:
        p.exit(2, f"draw_map: error: {e}\n")
    print(f"{args.out}: {width} x {height}")


if __name__ == "__main__":
    main()
