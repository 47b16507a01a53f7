"""One `hpcplan grid --json` run, timed from outside, and two runs alternated round by round,
for the dense engine's bench scripts (dense_targets.py, dense_floor.py, dense_blocks.py)."""
import json
import os
import shutil
import statistics
import subprocess
import sys

MPIRUN = shutil.which("mpirun") or shutil.which("mpiexec")
# Open MPI as root, and more ranks than cores.
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")


def grid(binary, args, ranks=0, timeout=3600, who="bench"):
    """`binary grid --json ARGS` (under `mpirun -np RANKS --bind-to core` when ranks > 0, or
    `--bind-to none` for more ranks than cores): the JSON object, with its wall seconds and peak
    resident bytes as _wall_s and _rss_bytes. Exits naming the command and its error line if it
    fails."""
    cmd = ["/usr/bin/time", "-f", "%e %M"]
    if ranks:
        bind = "core" if ranks <= (os.cpu_count() or 1) else "none"
        cmd += [MPIRUN, "-np", str(ranks), "--bind-to", bind]
    cmd += [binary, "grid", "--json", *args]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=ENV)
    if p.returncode != 0:
        # time's own lines (its figures, last, and its "Command exited ..." note) left out: the
        # rest ends with the program's error (under mpirun, several lines before mpirun's own).
        lines = [l for l in p.stderr.strip().splitlines()[:-1]
                 if not l.startswith(("Command exited", "Command terminated"))]
        sys.exit(f"{who}: {' '.join(cmd[3:])} failed: {chr(10).join(lines)[-400:]}")
    wall, rss_kb = p.stderr.strip().splitlines()[-1].split()
    j = json.loads(p.stdout)
    j["_wall_s"], j["_rss_bytes"] = float(wall), int(rss_kb) * 1024
    return j


def alternated(a, b, rounds, who="bench"):
    """Runs a and b (each a (binary, args, ranks) triple) in turn, `rounds` times: the median
    times (a_ms, b_ms) and the median, least and largest per-round a/b time ratio (b's speed-up
    over a). Exits if a round's two answers differ."""
    ta, tb, ratios, last = [], [], [], None
    for _ in range(rounds):
        ra, rb = grid(*a, who=who), grid(*b, who=who)
        if ra["status"] != rb["status"] or abs((ra["cost"] or 0) - (rb["cost"] or 0)) > 1e-9:
            sys.exit(f"{who}: different answers for {a} and {b}")
        ta.append(ra["time_ms"])
        tb.append(rb["time_ms"])
        ratios.append(ra["time_ms"] / rb["time_ms"])
        last = (ra, rb)
    return {"a_ms": statistics.median(ta), "b_ms": statistics.median(tb),
            "ratio": statistics.median(ratios), "ratio_min": min(ratios),
            "ratio_max": max(ratios), "a": last[0], "b": last[1]}
