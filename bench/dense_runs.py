"""One `hpcplan grid --json` run, timed from outside, for the dense engine's bench scripts
(dense_targets.py, dense_floor.py)."""
import json
import os
import shutil
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
