"""Keyword arguments made from the CLI's own option tables.

Each binding asks the extension for a subcommand's options as the command line declares them
(hpcplan/cli/option_catalog.hpp: name, type, default, range, choices, help) and turns them into
a Python signature and docstring here. A call's keyword arguments become the command line's
``--name=value`` tokens and are parsed by the very options ``hpcplan <command>`` parses, so a
bad value is refused with the CLI's own message (``ValueError``) and a default is the CLI's.
"""
import inspect
import numbers
import operator
import os
from collections.abc import Sequence
from typing import Optional

import numpy as np

_TYPES = {"flag": bool, "int": int, "float": float, "text": str,
          "int_list": Sequence[int], "float_list": Sequence[float]}


def _default(option):
    text, kind = option["default"], option["kind"]
    if kind == "flag":
        return False
    if text == "" or option["required"]:
        return None
    try:
        if kind == "int":
            return int(text)
        if kind == "float":
            return float(text)
        if kind in ("int_list", "float_list"):
            items = text.strip("[]").replace(" ", "").split(",")
            cast = int if kind == "int_list" else float
            return [cast(x) for x in items if x]
    except ValueError:
        return None
    return text


def _is_bool(value):
    # NumPy's bool is not a bool, but operator.index() reads it as 0 or 1.
    return isinstance(value, (bool, np.bool_))


def _whole(name, value):
    if _is_bool(value):
        raise TypeError(f"{name} must be an integer, not bool")
    try:
        return operator.index(value)
    except TypeError:
        raise TypeError(f"{name} must be an integer, not {type(value).__name__}") from None


def _real(name, value):
    if _is_bool(value) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a real number, not {type(value).__name__}")
    # As the number would be typed: -1 as "-1", 0.1 as "0.1" (the shortest text that reads back
    # to the same double), so that a refusal quotes what was given.
    if isinstance(value, numbers.Integral):
        return str(int(value))
    return repr(float(value))


class Options:
    """One subcommand's options as keyword arguments.

    ``table``: the extension's description of the options; ``only``/``exclude``: the names a
    function takes; ``sequences``: text options that take coordinates (``start=(0, 0)``) and are
    written as the CLI's comma-separated text.
    """

    def __init__(self, table, only=None, exclude=(), sequences=()):
        self.options = [o for o in table
                        if (only is None or o["name"] in only) and o["name"] not in exclude]
        self.sequences = set(sequences)
        self.by_name = {o["name"]: o for o in self.options}

    def parameters(self):
        params = []
        for o in self.options:
            annotation = Sequence[int] if o["name"] in self.sequences else _TYPES[o["kind"]]
            default = inspect.Parameter.empty if o["required"] else _default(o)
            if default is None:  # left out: the CLI's own default, whatever it derives
                annotation = Optional[annotation]
            params.append(inspect.Parameter(o["name"], inspect.Parameter.KEYWORD_ONLY,
                                            default=default, annotation=annotation))
        return params

    def doc(self):
        lines = []
        for o in self.options:
            kind = "sequence of int" if o["name"] in self.sequences else {
                "flag": "bool", "int": "int", "float": "float", "text": "str",
                "int_list": "list of int", "float_list": "list of float"}[o["kind"]]
            facts = [kind]
            if o["required"]:
                facts.append("required")
            elif o["kind"] != "flag" and o["default"] != "":
                facts.append(f"default {o['default']}")
            if o["range"]:
                facts.append(f"in {o['range']}")
            if o["choices"]:
                facts.append("one of " + ", ".join(o["choices"]))
            lines.append(f"{o['name']} : {', '.join(facts)}  ({o['option']})")
            lines.append(f"    {o['help']}")
        return "\n".join(lines)

    def tokens(self, given):
        """The ``--name=value`` tokens of the keyword arguments actually given (a value of
        None means the default, as an option left out does)."""
        out = []
        for name, value in given.items():
            o = self.by_name[name]
            if value is None:
                continue
            kind, flag = o["kind"], o["option"]
            if kind == "flag":
                if isinstance(value, np.bool_):
                    value = bool(value)
                if not isinstance(value, bool):
                    raise TypeError(f"{name} must be a bool, not {type(value).__name__}")
                if value:
                    out.append(flag)
            elif kind == "int":
                out.append(f"{flag}={_whole(name, value)}")
            elif kind == "float":
                out.append(f"{flag}={_real(name, value)}")
            elif kind in ("int_list", "float_list") or name in self.sequences:
                # A set or a dict has no order: its numbers would go in whatever order it holds.
                if isinstance(value, (str, bytes, set, frozenset, dict)) or \
                        not hasattr(value, "__iter__"):
                    raise TypeError(f"{name} must be a sequence of numbers, not "
                                    f"{type(value).__name__}")
                def cast(v, name=name, kind=kind):
                    if kind == "float_list":
                        return str(_real(name, v))
                    try:
                        return str(_whole(name, v))
                    except (TypeError, ValueError):
                        # start= and goal= on a configuration space are real states; a grid
                        # refuses them with its own message.
                        if name in self.sequences:
                            return str(_real(name, v))
                        raise
                out.append(f"{flag}=" + ",".join(cast(v) for v in value))
            else:
                value = text(name, value)
                # "--name=" would be a missing value to CLI11; "--name" "" is the empty text the
                # command line passes (and which the CLI reads as not given, or refuses).
                out += [flag, ""] if value == "" else [f"{flag}={value}"]
        return out


def text(name, value):
    """A text option's or a file's value: a str, or a path (os.PathLike) as its str."""
    if isinstance(value, os.PathLike):
        value = os.fspath(value)
    if not isinstance(value, str):
        raise TypeError(f"{name} must be a str or a path, not {type(value).__name__}")
    return value


def whole(name, value):
    """A whole-number argument (an int or a NumPy integer, not a bool)."""
    return _whole(name, value)


STOP = inspect.Parameter("stop", inspect.Parameter.KEYWORD_ONLY, default=None)
STOP_DOC = ("stop : hpcplan.StopSource, optional\n"
            "    Ends the call early when another thread calls stop.request_stop().")


_SELF = inspect.Parameter("self", inspect.Parameter.POSITIONAL_ONLY)


def make(function, options, leading=(), trailing=(STOP,), summary="", extra_doc=STOP_DOC,
         returns=None, method=False):
    """Gives ``function`` (which takes ``**kwargs``, after ``self`` for a method, after the
    positional ``leading`` parameters otherwise) the signature and docstring of its options.
    Returns the signature its keyword arguments are bound with (``bind`` raises TypeError for an
    unknown or missing one, as Python does)."""
    signature = inspect.Signature(list(leading) + options.parameters() + list(trailing),
                                  return_annotation=returns or inspect.Signature.empty)
    shown = list(signature.parameters.values())
    function.__signature__ = signature.replace(parameters=[_SELF] + shown) if method else signature
    function.__doc__ = (inspect.cleandoc(summary) + "\n\nParameters\n----------\n" + options.doc()
                        + ("\n" + extra_doc if extra_doc else ""))
    return signature


class Binder:
    """Checks a call's keyword arguments against a signature of keyword-only parameters as
    Python does (TypeError naming the function, for an unknown or a missing one), without
    inspect's general binding (a tenth of a small query's time)."""

    def __init__(self, signature):
        self.names = frozenset(signature.parameters)
        self.required = tuple(n for n, p in signature.parameters.items()
                              if p.default is inspect.Parameter.empty)

    def __call__(self, name, kwargs):
        for key in kwargs:
            if key not in self.names:
                raise TypeError(f"{name}() got an unexpected keyword argument '{key}'")
        for key in self.required:
            if key not in kwargs:
                raise TypeError(f"{name}() missing a required argument: '{key}'")
        return dict(kwargs)


def bind(signature, name, kwargs):
    """The call's keyword arguments checked against ``signature`` (see Binder)."""
    binder = _BINDERS.get(id(signature))
    if binder is None or binder[0] is not signature:
        binder = _BINDERS[id(signature)] = (signature, Binder(signature))
    return binder[1](name, kwargs)


_BINDERS = {}
