#!/usr/bin/env python3
"""Prints every skip of a ctest run with its reason, from ctest's JUnit report (--output-junit).

ctest shows a skipped test as "***Skipped" and never its output, even with --output-on-failure,
so without this a skip's reason reaches no log. Listed: the tests ctest skipped (exit 77 under
SKIP_RETURN_CODE, GTEST_SKIP through gtest_discover_tests' SKIP_REGULAR_EXPRESSION), with the
lines that give the reason, and the skips inside tests that passed (pytest's summary lines
"SKIPPED [n] file:line: reason", which tests/python/conftest.py turns on).

Usage: ctest_skips.py JUNIT_XML
Exit 0 after printing (a skip is reported here, not judged: the tests themselves fail where a
skip is not allowed); exit 1 if the report is missing or unreadable.
"""
import re
import sys
import xml.etree.ElementTree as ET


def reason(output):
    """The lines of a skipped test's output that say why."""
    lines = [line.rstrip() for line in output.splitlines() if line.strip()]
    # hpcplan's own convention: "<test>: SKIPPED: <why>".
    said = [line for line in lines if "SKIPPED:" in line]
    if said:
        return said
    # GTEST_SKIP() << "why": "file:line: Skipped", the message, then "[  SKIPPED ] Test".
    for k, line in enumerate(lines):
        if line.endswith(": Skipped"):
            message = []
            for rest in lines[k + 1:]:
                if rest.startswith("[  SKIPPED ]"):
                    break
                message.append(rest)
            return message or [line + " (GTEST_SKIP gave no reason)"]
    return lines[-3:] or ["(the test printed nothing)"]


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    try:
        cases = ET.parse(sys.argv[1]).getroot().iter("testcase")
        cases = list(cases)
    except (OSError, ET.ParseError) as e:
        print(f"ctest_skips: cannot read {sys.argv[1]}: {e}", file=sys.stderr)
        return 1
    skipped, inner = [], []
    for case in cases:
        output = case.findtext("system-out") or ""
        mark = case.find("skipped")
        if mark is not None:
            skipped.append((case.get("name"), mark.get("message", ""), reason(output)))
            continue
        # (GoogleTest colours its lines where it thinks a terminal reads them, as under mpirun;
        # ctest's report writes each escape as "[NON-XML-CHAR-0x1B]".)
        lines = re.sub(r"(\x1b|\[NON-XML-CHAR-0x1B\])\[[0-9;]*m", "", output).splitlines()
        for k, line in enumerate(lines):
            if re.match(r"SKIPPED \[\d+\] ", line):
                inner.append((case.get("name"), line.rstrip()))
            # A GTEST_SKIP among the cases of a binary that ctest runs whole (the MPI suites,
            # the threaded tests): "file:line: Skipped", the message, "[  SKIPPED ] Case (N ms)".
            if line.rstrip().endswith(": Skipped"):
                message = []
                for rest in lines[k + 1:]:
                    m = re.match(r"\[  SKIPPED \] (\S+)", rest)
                    if m:
                        why = " ".join(x.strip() for x in message) or "(no reason given)"
                        inner.append((case.get("name"), f"{m.group(1)}: {why}"))
                        break
                    message.append(rest)
    print(f"skips: {len(skipped)} of {len(cases)} tests skipped"
          + (f", {len(inner)} skip lines inside passing tests" if inner else ""))
    for name, how, why in skipped:
        print(f"  {name} ({how}):")
        for line in why:
            print(f"      {line}")
    for name, line in inner:
        print(f"  {name} (passed): {line}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
