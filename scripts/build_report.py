#!/usr/bin/env python3
"""Where a test command's minutes went: the slowest steps of a build and the slowest tests.

  build_report.py steps BUILD_DIR [--top N]   the slowest build steps (ninja's own log)
  build_report.py tests BUILD_DIR [--top N]   the slowest tests of the last ctest run there

The build steps come from BUILD_DIR/.ninja_log (the newest entry of each output, so after a
warm rebuild the steps it did not redo keep their earlier times), with their share of the
log's whole step time. The
tests come from ctest's LastTest.log, which records each test's own wall time (ctest -j runs
two at once on a 2-core machine, so these are times under that load, as CI sees them).
Prints nothing but a note when the file is not there (a tree built by make, a stage that ran
no test), and exits 0 either way: a report is never what fails a stage.
"""
import argparse
import pathlib
import re
import sys


def ninja_steps(build: pathlib.Path):
    log = build / ".ninja_log"
    if not log.is_file():
        return None
    newest = {}
    for line in log.read_text(errors="replace").splitlines():
        if line.startswith("#"):
            continue
        parts = line.split("\t")
        if len(parts) < 4 or not parts[0].isdigit() or not parts[1].isdigit():
            continue
        start, end, output = int(parts[0]), int(parts[1]), parts[3]
        # A later entry for the same output is a rebuild; ninja appends, so the last one wins.
        newest[output] = (end - start) / 1000.0
    return newest


def short_name(output: str) -> str:
    # core/CMakeFiles/hpcplan_core.dir/src/memory.cpp.o -> core/src/memory.cpp
    name = re.sub(r"CMakeFiles/[^/]+\.dir/", "", output)
    return name[:-2] if name.endswith(".o") else name


TEST_TIME = re.compile(r"^Test time =\s*(?P<seconds>[0-9.]+) sec")
TEST_NAME = re.compile(r"^\d+/\d+ Test: (?P<name>.*)$")


def ctest_times(build: pathlib.Path):
    log = build / "Testing" / "Temporary" / "LastTest.log"
    if not log.is_file():
        return None
    times = {}
    name = None
    for line in log.read_text(errors="replace").splitlines():
        m = TEST_NAME.match(line)
        if m:
            name = m.group("name")
            continue
        m = TEST_TIME.match(line)
        if m and name is not None:
            times[name] = float(m.group("seconds"))
            name = None
    return times


def report(build: pathlib.Path, what: str, top: int) -> None:
    """Prints the `top` longest entries of the build's step or test times."""
    if what == "steps":
        times, source, noun, name = ninja_steps(build), ".ninja_log", "build steps", short_name
    else:
        times, source, noun = ctest_times(build), "Testing/Temporary/LastTest.log", "tests"
        name = str
    if not times:
        print(f"build_report: {build}/{source} not found or empty (no {noun} times)")
        return
    total = sum(times.values())
    print(f"{build}: {len(times)} {noun}, {total:.0f} s in all; the {top} slowest:")
    for key, seconds in sorted(times.items(), key=lambda kv: -kv[1])[:top]:
        print(f"  {seconds:7.1f} s  {100 * seconds / total:4.1f}%  {name(key)}")


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("what", choices=["steps", "tests"])
    p.add_argument("build", type=pathlib.Path)
    p.add_argument("--top", type=int, default=10)
    a = p.parse_args()
    try:
        report(a.build, a.what, a.top)
    except Exception as e:  # a report is never what fails a stage
        print(f"build_report: no report ({type(e).__name__}: {e})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
