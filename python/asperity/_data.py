"""The data shipped with the package: the example case files of every command and the JSON
Schemas of every ``--json`` output (the source's ``examples/`` and ``docs/schema/``,
installed as ``asperity/data/examples`` and ``asperity/data/schema``; python/CMakeLists.txt)."""
from __future__ import annotations

import pathlib

from . import _core

_KINDS = ("examples", "schema")
_ROOT = pathlib.Path(__file__).resolve().parent / "data"


def data_path(kind: str | None = None) -> pathlib.Path:
    """The directory of the shipped data: ``data_path("examples")`` (the example case files,
    laid out as the source's ``examples/``: ``vibration/jenkins_sdof.toml``, ...),
    ``data_path("schema")`` (``<command>.schema.json`` for each command's ``--json``) or,
    without an argument, the directory holding both.

    >>> import asperity
    >>> case = asperity.data_path("examples") / "vibration" / "jenkins_sdof.toml"
    >>> schema = asperity.data_path("schema") / "vibration.schema.json"
    """
    if kind is not None and kind not in _KINDS:
        raise _core.InvalidInput(
            f"data_path({kind!r}): the shipped data are {', '.join(map(repr, _KINDS))} (or no "
            "argument: the directory holding both)")
    path = _ROOT if kind is None else _ROOT / kind
    if not path.is_dir():
        raise FileNotFoundError(
            f"{path}: the package's data are missing (a wheel and a CMake build with "
            "ASPERITY_BUILD_PYTHON=ON put them there; a copy of python/asperity alone has none)")
    return path
