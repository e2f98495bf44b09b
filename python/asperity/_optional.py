"""Optional dependencies: matplotlib (the `plot` extra) for the plotting helpers."""
from __future__ import annotations

PLOT_EXTRA_HINT = (
    "asperity's plotting helpers need matplotlib, which is not installed: install the "
    "package's `plot` extra (pip install 'asperity[plot]', or from a source tree "
    "pip install '.[plot]'), or pip install matplotlib")


def pyplot():
    """``matplotlib.pyplot``, or ModuleNotFoundError naming the `plot` extra."""
    try:
        import matplotlib.pyplot as plt
    except ModuleNotFoundError as e:
        if (e.name or "").split(".")[0] == "matplotlib":
            raise ModuleNotFoundError(PLOT_EXTRA_HINT, name="matplotlib") from e
        raise
    return plt
