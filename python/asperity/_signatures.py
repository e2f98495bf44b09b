"""``inspect.signature`` for the compiled functions and classes.

nanobind's functions carry their signatures only as text (``__nb_signature__``, what the
stub file ``_core.pyi`` is generated from); ``inspect.signature`` cannot read it. This
module turns that text into :class:`inspect.Signature` objects. Every public function of
:mod:`asperity._core` and every public method of its classes is wrapped in a C-level
forwarder (``_core._signed``, python/src/signatures.cpp) that carries ``__signature__``,
the name and the docstring, and passes each call on unchanged (vectorcall; a method
wrapper binds as nanobind's own methods do); every class with a constructor gets
``__signature__`` on the class. Functions with several overloads have no single
signature and stay as they are. With the environment variable ``ASPERITY_RAW_BINDINGS=1``
nothing is wrapped: the build sets it for nanobind's stub generator, which reads the
compiled callables themselves.
"""
from __future__ import annotations

import ast
import inspect
import os
import re
from typing import Any, Callable, Optional

_DEFAULT = re.compile(r"\\(\d+)")
RAW = os.environ.get("ASPERITY_RAW_BINDINGS") == "1"


def _split_top_level(text: str, sep: str) -> list:
    """``text`` split at each ``sep`` outside brackets and quotes."""
    parts, depth, quote, current = [], 0, None, ""
    i = 0
    while i < len(text):
        c = text[i]
        if quote:
            quote = None if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        elif depth == 0 and text.startswith(sep, i):
            parts.append(current)
            current = ""
            i += len(sep)
            continue
        current += c
        i += 1
    parts.append(current)
    return parts


def signature_of(fn: Any, drop_first: bool = False) -> Optional[inspect.Signature]:
    """The signature of a nanobind function or method from its ``__nb_signature__``;
    ``None`` when it has several overloads (no single signature exists). ``drop_first``
    leaves out ``self`` (for a constructor seen as the class's signature). Annotations
    are kept as nanobind's text (as in the stub file)."""
    overloads = getattr(fn, "__nb_signature__", None)
    if not overloads or len(overloads) != 1:
        return None
    text, _doc, defaults = (tuple(overloads[0]) + (None, None, None))[:3]
    # "def name(a: T, b: U = \\0, *, c: V = \\1) -> R"
    open_paren = text.index("(")
    depth, close_paren = 0, len(text)
    for i in range(open_paren, len(text)):
        depth += {"(": 1, "[": 1, "{": 1, ")": -1, "]": -1, "}": -1}.get(text[i], 0)
        if depth == 0:
            close_paren = i
            break
    head, rest = text[open_paren + 1:close_paren], text[close_paren + 1:]
    returns = rest.split("->", 1)[1].strip() if "->" in rest else inspect.Signature.empty
    params = []
    kind = inspect.Parameter.POSITIONAL_OR_KEYWORD
    for part in (p.strip() for p in _split_top_level(head, ",")):
        if not part:
            continue
        if part == "/":
            params = [p.replace(kind=inspect.Parameter.POSITIONAL_ONLY) for p in params]
            continue
        if part == "*":
            kind = inspect.Parameter.KEYWORD_ONLY
            continue
        name_ann, *dflt = _split_top_level(part, " = ")
        name, *ann = _split_top_level(name_ann, ":")
        name = name.strip()
        annotation = ann[0].strip() if ann else inspect.Parameter.empty
        default = inspect.Parameter.empty
        if dflt:
            d = dflt[0].strip()
            m = _DEFAULT.fullmatch(d)
            default = defaults[int(m.group(1))] if m else ast.literal_eval(d)
        if name.startswith("**"):
            params.append(inspect.Parameter(name[2:], inspect.Parameter.VAR_KEYWORD,
                                            annotation=annotation))
        elif name.startswith("*"):
            params.append(inspect.Parameter(name[1:], inspect.Parameter.VAR_POSITIONAL,
                                            annotation=annotation))
            kind = inspect.Parameter.KEYWORD_ONLY
        else:
            params.append(inspect.Parameter(name, kind, default=default, annotation=annotation))
    if drop_first and params:
        params = params[1:]
    try:
        return inspect.Signature(params, return_annotation=returns)
    except ValueError:
        # A required parameter after one with a default (`bolt_preload(torque, nut_factor=0.2,
        # diameter)`): valid for nanobind (pass it by keyword), not in Python's own syntax.
        return inspect.Signature(params, return_annotation=returns,
                                 __validate_parameters__=False)


def _signed(fn: Any, method: bool, module: str, qualname: str) -> Any:
    from . import _core

    sig = None if RAW else signature_of(fn)
    if sig is None:
        return fn
    wrapper = _core._signed(fn, method)
    wrapper.__signature__ = sig
    wrapper.__name__ = fn.__name__
    wrapper.__qualname__ = qualname
    wrapper.__module__ = module
    wrapper.__doc__ = fn.__doc__
    return wrapper


def with_signature(fn: Callable, module: str = "asperity") -> Callable:
    """``fn`` as a function of ``module`` with its signature readable by ``inspect``."""
    return _signed(fn, False, module, fn.__name__)


def add_method_signatures(cls: type, module: str = "asperity") -> None:
    """Wraps the public methods (and static methods) defined by ``cls`` itself."""
    for name, value in list(vars(cls).items()):
        if name.startswith("_"):
            continue
        kind = type(value).__name__
        if kind not in ("nb_method", "nb_func"):
            continue
        wrapper = _signed(value, kind == "nb_method", module, f"{cls.__name__}.{name}")
        if kind == "nb_func" and wrapper is not value:
            wrapper = staticmethod(wrapper)  # what it is (help() lists it so)
        setattr(cls, name, wrapper)


def add_class_signature(cls: type, module: str = "asperity") -> None:
    """Sets ``cls.__signature__`` from its constructor (when it has exactly one), and
    replaces ``cls.__init__`` (a nanobind method, which ``inspect`` cannot read) by a
    forwarder carrying the same signature with ``self``. Constructing an instance does not
    go through that attribute (nanobind's type calls the constructor it was made with), so
    it costs the same; ``super().__init__(...)`` of a Python subclass goes through it."""
    init = cls.__dict__.get("__init__")
    sig = signature_of(init, drop_first=True) if init is not None else None
    if sig is not None:
        cls.__signature__ = sig.replace(return_annotation=inspect.Signature.empty)
        cls.__init__ = _signed(init, True, module, f"{cls.__name__}.__init__")


def is_compiled_function(obj: Any) -> bool:
    return type(obj).__name__ == "nb_func"
