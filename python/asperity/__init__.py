"""asperity: physics-based friction of bolted and clamped joints.

Python face of the C++ library (Eriten 2012, "Multiscale physics-based modeling of
friction"). Every function calls the same C++ code as the CLI; this package holds no
physics. Conventions:

* SI units in and out (m, N, Pa, J); dimensionless quantities end in ``_star`` and
  say what they are divided by.
* Functions of interference, load or displacement accept a float (and return a float)
  or anything array-like (and return a numpy array of the broadcast shape).
* Law and model names are strings: normal laws ``"hertz", "ceb", "ke", "bke"``;
  friction laws and models ``"cfc", "ceb", "ke", "bke"``.
* Const getters of C++ classes are read-only properties (``model.mu``, ``pair.critical``).
* Errors: :class:`InvalidInput` (a ``ValueError``) for bad input, naming the field;
  :class:`NumericalError` (a ``RuntimeError``) for a failed solve; both derive from
  :class:`Error`.

Layers: ``contact`` (one asperity, thesis ch. 2-3 and appendices A-B), ``surface``
(profiles and roughness, ch. 5-6; :class:`RoughFlat`, the rough flat of ch. 4),
``hysteresis`` (:class:`Hysteresis`, Masing's rules over any :class:`Backbone`) and
``dynamics`` (ch. 7: the friction models :class:`RegularizedCoulomb`, :class:`Dankowicz`,
:class:`HysteresisFriction`, ``make_jenkins``, ``make_segalman_iwan`` and the
physics-based ``make_physics_based``/``epb_backbone``; the base-excited oscillator of
Eq. 7.1 under :class:`ImpulseExcitation`, :class:`RampExcitation`,
:class:`HarmonicExcitation` or :class:`FreeVibration`; ``simulate``, returning a
:class:`Trajectory` of numpy arrays; ``Periodogram``, ``power_spectrum``,
``modal_estimate``, ``free_decay``, ``stick_slip_intervals``, ``steady_loop``) are bound
here. Dynamics works in the non-dimensional variables of section 7.2
(:class:`DimensionalScales` converts); :mod:`asperity.dynamics` runs the case files of
``asperity dynamics`` (``run_case``: summary and numpy arrays) and draws Fig. 7.3-7.7;
Cattaneo-Mindlin tilde functions live in :mod:`asperity.mindlin`; matplotlib helpers in
:mod:`asperity.plotting`; the thesis's experiments in :mod:`asperity.thesis`.
:mod:`asperity.vibration` holds the vibration layer (issue 10): structures from numpy
matrices or MatrixMarket files, joint elements (Jenkins, Iwan4, Coulomb,
ElasticDryFriction2d, RoughFlat), harmonic balance with its residual and Jacobian,
nonlinear modes (EPMC), frequency responses and the quasi-static modal estimate.
:mod:`asperity.fem` holds the finite-element layer (issue 19): stiffness and consistent
mass of tet10 / hex20 meshes as scipy.sparse matrices. ``data_path("examples")`` and
``data_path("schema")`` locate the example case files and the JSON Schemas shipped with
the package.
"""
from __future__ import annotations

import sys as _sys
import types as _types

from . import _core
from ._core import *  # noqa: F401,F403
from ._core import mindlin
from . import joints  # noqa: F401  (matplotlib helpers for predict / analyze_fretting)
from . import dynamics  # noqa: F401  (dynamics case files, Fig. 7.3-7.7 helpers)
from . import vibration  # noqa: F401  (harmonic balance, nonlinear modes, FRFs)
from . import fem  # noqa: F401  (finite elements: stiffness and mass of solid bodies)

# inspect.signature() on the compiled functions, methods and constructors (_signatures.py).
from . import _signatures  # noqa: E402

if not _signatures.RAW:
    _core._install_fast_history_methods()  # Hysteresis.forces/displacements (hysteresis.cpp)
for _name in dir(_core):
    _obj = getattr(_core, _name)
    if _name.startswith("_"):
        continue
    if _signatures.is_compiled_function(_obj):
        globals()[_name] = _signatures.with_signature(_obj)
    elif isinstance(_obj, type):
        _signatures.add_class_signature(_obj)
        _signatures.add_method_signatures(_obj)
# asperity.mindlin: the same functions as asperity._core.mindlin, with signatures.
mindlin = _types.ModuleType("asperity.mindlin", _core.mindlin.__doc__)
for _name in dir(_core.mindlin):
    _obj = getattr(_core.mindlin, _name)
    if not _name.startswith("_") and _signatures.is_compiled_function(_obj):
        setattr(mindlin, _name, _signatures.with_signature(_obj, "asperity.mindlin"))
_sys.modules[__name__ + ".mindlin"] = mindlin
del _name, _obj

__version__ = _core.version_info()["version"]

__all__ = [name for name in dir(_core) if not name.startswith("_")]


def thesis_normalization(model: "PartialSlipModel") -> dict:  # noqa: F405
    """Scales of the thesis's dimensionless tangential variables (section 3.3-3.4).

    Returns ``{"delta": 3 P_c/(16 G* a_c), "Q": P_c, "energy": P_c^2/(G* a_c)}`` so that
    ``delta* = delta/scales["delta"]``, ``Q* = Q/scales["Q"]`` and
    ``Delta W* = Delta W/scales["energy"]`` (Fig. 3.6-3.8).
    """
    return {
        "delta": model.delta_scale,
        "Q": model.critical.P_c,
        "energy": model.energy_scale,
    }


def loop_arrays(loop: "FrettingLoop"):  # noqa: F405
    """``(delta, Q, branch)`` of a :class:`FrettingLoop` as independent numpy copies."""
    import numpy as np

    return np.array(loop.delta), np.array(loop.Q), np.array(loop.branch)


from ._data import data_path  # noqa: E402  (the shipped examples and JSON Schemas)

__all__ += ["mindlin", "thesis_normalization", "loop_arrays", "data_path", "__version__"]
