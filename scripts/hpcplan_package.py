"""What the scripts that call the engine in-process share: the Python package hpcplan (the
build tree's when no other is on the path) and option values written as text on their
command lines (KEY=VALUE lists)."""
import os
import sys


def import_hpcplan(tool, option):
    """The package, or exit naming the option that needs it."""
    sys.path.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build",
                                 "python"))
    try:
        import hpcplan
    except ImportError as e:
        sys.exit(f"{tool}: error: {option} needs the Python package hpcplan ({e}); build it "
                 "(scripts/build.sh) or set PYTHONPATH")
    return hpcplan


def value(text):
    """An option's value as its text reads: a whole number, a real number, or text."""
    for cast in (int, float):
        try:
            return cast(text)
        except ValueError:
            pass
    return text
