"""Vibration of jointed structures: harmonic balance, nonlinear modes, frequency response.

The Python face of the C++ layer ``vibration/`` (docs/vibration.md); every number comes
from the same C++ code as ``asperity vibration``. SI units throughout.

* :class:`Structure` - mass, stiffness and damping matrices from numpy arrays (damping as
  a matrix or Rayleigh ``alpha M + beta K``) or MatrixMarket files.
* Joint elements, each placed by ``T`` (one row per element direction, one column per
  DOF; it acts on ``u = T x`` and returns ``T^T f``): :class:`Jenkins`, :class:`Iwan4`,
  :class:`Coulomb`, :class:`ElasticDryFriction2d`, :class:`PolynomialStiffness`,
  :class:`CubicDamping`, :class:`UnilateralSpring`, :class:`ElasticDryFriction3d`,
  :class:`RoughFlat` (any SI backbone under Masing's rules: from
  :func:`asperity.epb_backbone`, a joint case file or :func:`asperity.predict`) and
  :class:`RoughContact` (the rough flat as the 3-D contact law of a zero-thickness element,
  on a :class:`RoughContactSurface` shared by an interface's elements;
  :func:`rough_contact_on_interface` places one on every interface element of a reduced
  model in contact at its rough prestress).
* :func:`run_case` / :func:`run_case_text` - a case file of ``asperity vibration``
  (the same parser and run function as the command): the summary (summary.json as a
  dict) and each analysis's arrays; :meth:`HarmonicBalance.from_case` - a case file's
  system, for residuals and analyses of one's own.
* :class:`HarmonicBalance` - the AFT system (harmonics kept, ``N_t`` samples per
  period): residual and analytic Jacobian as numpy arrays, the force vector from cosine
  and sine parts, and the analyses :meth:`HarmonicBalance.nonlinear_mode` (EPMC, Krack
  2015), :meth:`HarmonicBalance.frequency_response`, :meth:`HarmonicBalance.force_response`
  (continuation in the force amplitude at one frequency),
  :meth:`HarmonicBalance.amplitude_control` and :meth:`HarmonicBalance.phase_resonance`
  (response-controlled harmonic balance), :meth:`HarmonicBalance.superharmonic_resonance`
  (an r:1 resonance followed in force) and
  :meth:`HarmonicBalance.quasi_static_mode` (also as module functions of the same names).

The unknowns ``U`` stack per DOF the coefficients ``[a_0, a_h1, b_h1, a_h2, b_h2, ...]``
of ``x(t) = a_0 + sum_h a_h cos(h omega t) + b_h sin(h omega t)``: ``U[dof * n_c + c]``;
:meth:`HarmonicBalance.index` finds one. Results are :class:`Result` objects (dicts whose
keys are also attributes) of numpy arrays; warnings of the solvers (a continuation that
stopped early, negative damping) are also issued as :class:`RuntimeWarning`.
:func:`plot_mode` and :func:`plot_response` draw them with matplotlib.
"""
from __future__ import annotations

import math
import os
import warnings
from typing import Iterable, Mapping, Sequence

import numpy as np

from . import _core

_v = _core._vibration

__all__ = [
    "Structure", "Element", "Jenkins", "Iwan4", "MasingTable", "Coulomb", "ElasticDryFriction2d",
    "PolynomialStiffness", "CubicDamping", "UnilateralSpring", "ElasticDryFriction3d", "RoughFlat",
    "OdfalkVingsbo", "UserElement", "RoughContactSurface", "RoughContact",
    "rough_contact_on_interface",
    "HarmonicBalance", "Result", "nonlinear_mode",
    "frequency_response", "force_response", "amplitude_control", "phase_resonance",
    "superharmonic_resonance", "quasi_static_mode", "linear_modes", "read_matrix_market",
    "rayleigh", "run_case",
    "run_case_text", "plot_mode", "plot_response", "force_label", "fit_loops",
]


class Result(dict):
    """A dict of named numpy arrays whose keys are also attributes (``r.omega``)."""

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError:
            raise AttributeError(name) from None

    def __dir__(self):
        return list(self.keys()) + list(super().__dir__())


def _issue(result: Mapping, source: str):
    for w in result.get("warnings", []):
        warnings.warn(f"{source}: {w}", RuntimeWarning, stacklevel=3)


def _matrix(a, name: str) -> np.ndarray:
    m = np.array(a, dtype=float, ndmin=2, copy=True)
    if m.ndim != 2:
        raise _core.InvalidInput(f"{name} must be a 2-D array (got {m.ndim} dimensions)")
    return np.ascontiguousarray(m)


def read_matrix_market(path: str | os.PathLike) -> np.ndarray:
    """A MatrixMarket file (coordinate or array; real or integer; general or symmetric)
    as a dense numpy array."""
    return np.asarray(_v.read_matrix_market(os.fspath(path)))


def rayleigh(M, K, alpha: float = 0.0, beta: float = 0.0) -> np.ndarray:
    """Rayleigh damping ``C = alpha M + beta K`` (alpha [1/s], beta [s], both >= 0)."""
    return np.asarray(_v.rayleigh(_matrix(M, "M"), _matrix(K, "K"), alpha, beta))


def linear_modes(K, M):
    """``(omega [rad/s] ascending, shapes)`` of (K, M): shapes are columns, mass-normalized
    (``phi^T M phi = 1``), each with its largest-magnitude entry positive."""
    w, s = _v.linear_modes(_matrix(K, "K"), _matrix(M, "M"))
    return np.asarray(w), np.asarray(s)


class Structure:
    """``M x'' + C x' + K x = f(t)`` with dense matrices of any size (SI).

    ``Structure(M, K, C=None, rayleigh=None)``: ``C`` a matrix, or ``rayleigh=(alpha, beta)``
    (or a dict with those keys) for ``C = alpha M + beta K``; neither means no damping.
    Raises :class:`asperity.InvalidInput` for sizes that differ, non-finite entries, M or K
    not symmetric, or M not positive definite.
    """

    def __init__(self, M, K, C=None, *, rayleigh=None):
        M = _matrix(M, "M")
        K = _matrix(K, "K")
        if C is not None and rayleigh is not None:
            raise _core.InvalidInput("give the damping as C or as rayleigh, not both")
        if rayleigh is not None:
            if isinstance(rayleigh, Mapping):
                alpha, beta = rayleigh.get("alpha", 0.0), rayleigh.get("beta", 0.0)
            else:
                alpha, beta = rayleigh
            if M.shape != K.shape:
                raise _core.InvalidInput(f"M is {M.shape} but K is {K.shape}: sizes differ")
            C = _v.rayleigh(M, K, float(alpha), float(beta))
        C = np.zeros((0, 0)) if C is None else _matrix(C, "C")
        self._core = _v.Structure(M, K, C)

    @classmethod
    def from_matrix_market(cls, mass, stiffness, damping=None, *, rayleigh=None) -> "Structure":
        """From MatrixMarket files (``damping`` a file too, or ``rayleigh=(alpha, beta)``)."""
        C = read_matrix_market(damping) if damping is not None else None
        return cls(read_matrix_market(mass), read_matrix_market(stiffness), C, rayleigh=rayleigh)

    @property
    def M(self) -> np.ndarray:
        return np.array(self._core.M)

    @property
    def K(self) -> np.ndarray:
        return np.array(self._core.K)

    @property
    def C(self) -> np.ndarray:
        return np.array(self._core.C)

    @property
    def dofs(self) -> int:
        return int(self._core.dofs)

    def linear_modes(self):
        """``(omega, shapes)`` of the structure without its elements (see
        :func:`linear_modes`)."""
        return linear_modes(self.K, self.M)

    def __repr__(self) -> str:
        return f"Structure(dofs={self.dofs})"


class Element:
    """A joint element placed in a structure by ``T`` (directions x DOFs; a 1-D array is
    one row). ``core`` is the C++ element: ``core.periodic_response(u, v)`` gives its
    steady response to sampled displacements, ``core.static_response(u)`` its monotone
    push, ``core.describe()`` its parameters."""

    def __init__(self, core, T, name: str | None = None):
        self.core = core
        self.T = _matrix(T, "T")
        if self.T.shape[0] != core.directions:
            raise _core.InvalidInput(
                f"T has {self.T.shape[0]} rows: a {core.type} element has {core.directions} "
                "direction(s), one row each")
        self.name = name

    @property
    def type(self) -> str:
        return self.core.type

    def describe(self) -> dict:
        return self.core.describe()

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.core.describe()}, T={self.T.tolist()})"


class Jenkins(Element):
    """Spring ``k_t`` [N/m] in series with a Coulomb slider of slip force ``F_s`` [N]."""

    def __init__(self, k_t: float, F_s: float, T=1.0, name: str | None = None):
        super().__init__(_v.jenkins(k_t, F_s), T, name)


class Iwan4(Element):
    """Segalman's four-parameter Iwan model (SI): ``F_S`` [N], ``K_T`` [N/m], ``chi`` in
    (-1, 0], ``beta`` >= 0; exactly Masing."""

    def __init__(self, F_S: float, K_T: float, chi: float, beta: float, T=1.0,
                 name: str | None = None):
        super().__init__(_v.iwan4(F_S, K_T, chi, beta), T, name)


class MasingTable(Element):
    """A backbone given as a table, force ``Q`` [N] against displacement ``x`` [m] (checked
    monotone and through the origin; monotone cubic interpolation, the force constant
    beyond the last point), under Masing's rules: the ``masing_table`` element of a case
    file. :meth:`from_csv` reads a table with units in its header, such as the
    ``backbones.csv`` of ``asperity predict --out``."""

    def __init__(self, x, Q, T=1.0, name: str | None = None, source: str = "table"):
        super().__init__(_v.masing_table(np.asarray(x, float), np.asarray(Q, float), source), T,
                         name)

    @classmethod
    def from_csv(cls, path: str | os.PathLike, preload: float | None = None, T=1.0,
                 name: str | None = None) -> "MasingTable":
        """From a CSV file with a displacement column (``delta``, ``x`` or
        ``displacement``, unit in the header, e.g. ``delta[um]``) and a force column (``Q``
        or ``force``, e.g. ``Q[N]``); a ``preload[N]`` column (predict's backbones.csv)
        needs ``preload`` [N] when it holds several (matched to 1e-9)."""
        import csv
        units = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "nm": 1e-9, "N": 1.0, "kN": 1e3}
        with open(path, newline="") as f:
            rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
        head = [h.strip() for h in rows[0]]
        names = [h.split("[")[0].strip() for h in head]
        scale = [units.get(h.split("[")[1].rstrip("]").strip(), None) if "[" in h else 1.0
                 for h in head]

        def col(*cands):
            for c in cands:
                if c in names:
                    i = names.index(c)
                    if scale[i] is None:
                        raise _core.InvalidInput(f"{path}: unit of {head[i]} not known (m, mm, um, nm, N, kN)")
                    return np.array([float(r[i]) for r in rows[1:]]) * scale[i]
            raise _core.InvalidInput(f"{path}: needs a column {' or '.join(cands)}")

        x, Q = col("delta", "x", "displacement"), col("Q", "force")
        if "preload" in names:
            P = col("preload")
            levels = sorted(set(P))
            if preload is None and len(levels) > 1:
                raise _core.InvalidInput(f"{path} holds the backbones of preloads {levels} N: "
                                         "choose one with preload=")
            chosen = levels[0] if preload is None else preload
            keep = np.abs(P - chosen) <= 1e-9 * abs(chosen)
            if not keep.any():
                raise _core.InvalidInput(f"preload = {chosen} N: {path} has {levels} N")
            x, Q = x[keep], Q[keep]
        return cls(x, Q, T, name, os.fspath(path))


def fit_loops(loops, model: str = "iwan4", T=1.0, name: str | None = None) -> Result:
    """Least-squares fit of measured or synthetic hysteresis loops by a Jenkins
    (``model="jenkins"``: ``k_t``, ``F_s``) or Segalman four-parameter Iwan element
    (``"iwan4"``: ``F_S``, ``K_T``, ``chi``, ``beta``), the same fit as
    ``asperity analyze --fit``.

    ``loops``: results of :func:`asperity.analyze_fretting` (their averaged loops
    ``loop_delta``, ``loop_Q``) or ``(delta, Q)`` pairs, each a closed loop whose first half
    is the unloading branch from the largest displacement. The parameters are shared, each
    loop has its own force offset. Returns a :class:`Result` with ``parameters``
    (``{name: {value, standard_error, unit}}``; an infinite standard error: not determined
    by the loops), ``residual_rms`` [N], ``relative_residual``, ``Q_model`` (the fitted
    loops), ``Q_offsets``, ``element_toml`` (the ``[[element]]`` table of a vibration case)
    and ``element``, a :class:`Jenkins` or :class:`Iwan4` placed by ``T``."""
    pairs = []
    for loop in loops:
        if isinstance(loop, Mapping):
            pairs.append((np.asarray(loop["loop_delta"], float), np.asarray(loop["loop_Q"], float)))
        else:
            delta, Q = loop
            pairs.append((np.asarray(delta, float), np.asarray(Q, float)))
    r = _v.fit_loops(pairs, model)
    p = {k: dict(v) for k, v in r["parameters"].items()}
    value = {k: v["value"] for k, v in p.items()}
    if r["model"] == "jenkins":
        element = Jenkins(value["k_t"], value["F_s"], T, name)
    else:
        element = Iwan4(value["F_S"], value["K_T"], value["chi"], value["beta"], T, name)
    return Result(model=r["model"], parameters=p, residual_rms=r["residual_rms"],
                  relative_residual=r["relative_residual"], points=r["points"],
                  Q_offsets=np.asarray(r["Q_offsets"]), Q_model=[np.asarray(q) for q in r["Q_model"]],
                  element_toml=r["element_toml"], element=element)


class Coulomb(Element):
    """Regularized Coulomb friction ``f = F_s tanh(k_tan v)`` (Eq. 7.3 in SI): ``F_s`` [N],
    ``k_tan`` [s/m]."""

    def __init__(self, F_s: float, k_tan: float, T=1.0, name: str | None = None):
        super().__init__(_v.coulomb(F_s, k_tan), T, name)


class ElasticDryFriction2d(Element):
    """Tangential Jenkins slider (row 0 of ``T``) that slips at ``mu f_n``, with a unilateral
    normal spring ``f_n = max(N0 + k_n u_n, 0)`` (row 1; ``u_n > 0`` presses): separation
    and normal-tangential coupling. The structure receives ``f_n - N0`` for a preload
    ``N0 > 0``; ``N0 < 0`` is a gap ``-N0 / k_n`` (the structure receives ``f_n``)."""

    def __init__(self, k_t: float, k_n: float, mu: float, T, N0: float = 0.0,
                 name: str | None = None):
        super().__init__(_v.elastic_dry_friction_2d(k_t, k_n, mu, N0), T, name)


class PolynomialStiffness(Element):
    """Polynomial stiffness ``f = k1 u + k2 u^2 + k3 u^3`` (Duffing: ``k3``): ``k1`` [N/m],
    ``k2`` [N/m^2], ``k3`` [N/m^3], not all zero."""

    def __init__(self, k1: float = 0.0, k2: float = 0.0, k3: float = 0.0, T=1.0,
                 name: str | None = None):
        super().__init__(_v.polynomial_stiffness(k1, k2, k3), T, name)


class CubicDamping(Element):
    """Cubic damping ``f = c3 v^3``: ``c3`` [N s^3/m^3]."""

    def __init__(self, c3: float, T=1.0, name: str | None = None):
        super().__init__(_v.cubic_damping(c3), T, name)


class ElasticDryFriction3d(Element):
    """Dry friction in two tangential directions (rows 0 and 1 of ``T``) and one normal (row
    2): a tangential spring ``k_t`` in series with an isotropic slider that slips at
    ``|f_t| = mu f_n`` along the trial force (radial return), and the normal spring
    ``f_n = max(N0 + k_n u_n, 0)`` of :class:`ElasticDryFriction2d` (``N0 > 0`` a preload,
    ``N0 < 0`` a gap ``-N0 / k_n``)."""

    def __init__(self, k_t: float, k_n: float, mu: float, T, N0: float = 0.0,
                 name: str | None = None):
        super().__init__(_v.elastic_dry_friction_3d(k_t, k_n, mu, N0), T, name)


class UnilateralSpring(Element):
    """Unilateral spring: contact force ``f_c = max(N0 + k (u - gap), 0)`` (``u > 0``
    closes): ``k`` [N/m], a ``gap`` [m] open at rest, or a preload ``N0`` [N] carried outside
    the model (the structure receives ``f_c - N0``, so ``u = 0`` is the rest state)."""

    def __init__(self, k: float, gap: float = 0.0, N0: float = 0.0, T=1.0,
                 name: str | None = None):
        super().__init__(_v.unilateral_spring(k, gap, N0), T, name)


class UserElement(Element):
    """An element whose force law is a Python function, usable in every harmonic-balance
    analysis (AFT samples it in time). The law is memoryless: ``force(u, v)`` maps the
    displacements and velocities ``u, v`` (arrays ``N x D``: ``N`` time samples, ``D`` the
    rows of ``T``) to the forces ``f`` (``N x D``; ``(N,)`` is accepted for ``D = 1``).

    ``jacobian(u, v)`` returns ``(df_du, df_dv)``, each ``N x D x D`` with
    ``[i, d, e] = d f_d / d x_e`` at sample ``i`` (``(N,)`` for ``D = 1``); unless
    ``velocity_dependent`` it may return ``df_du`` alone. Without it the Jacobian is taken by central
    differences, one call per direction and sign, with the step ``fd_step`` times the
    larger of the samples' magnitude in that direction and ``displacement_scale`` [m]
    (``velocity_scale`` [m/s] for velocities): accurate to about ``fd_step^2`` of the
    law's curvature, enough for Newton, slower than an exact Jacobian. The element's
    stiffness at rest (the linear modes) is its Jacobian at ``u = v = 0``."""

    def __init__(self, force, jacobian=None, T=1.0, velocity_dependent: bool = False,
                 name: str | None = None, *, fd_step: float = 1e-6,
                 displacement_scale: float = 1e-6, velocity_scale: float = 1e-3):
        if not callable(force):
            raise _core.InvalidInput("UserElement: force must be callable as force(u, v)")
        if jacobian is not None and not callable(jacobian):
            raise _core.InvalidInput("UserElement: jacobian must be None or callable(u, v)")
        for key, x in [("fd_step", fd_step), ("displacement_scale", displacement_scale),
                       ("velocity_scale", velocity_scale)]:
            if not (np.isfinite(x) and x > 0):
                raise _core.InvalidInput(f"UserElement.{key} = {x}: must be finite and > 0")
        T = _matrix(T, "T")
        D = T.shape[0]
        velocity_dependent = bool(velocity_dependent)

        def forces(u, v):
            f = np.asarray(force(u, v), dtype=float)
            if D == 1 and f.shape == (u.shape[0],):
                f = f.reshape(-1, 1)
            if f.shape != u.shape:
                raise _core.InvalidInput(
                    f"UserElement {name!r}: force(u, v) returned shape {f.shape}, expected "
                    f"{u.shape} (samples x directions)")
            return f

        def tensor(a, n, what):
            a = np.asarray(a, dtype=float)
            if D == 1 and a.shape == (n,):
                a = a.reshape(n, 1, 1)
            if a.shape != (n, D, D):
                raise _core.InvalidInput(
                    f"UserElement {name!r}: {what} has shape {a.shape}, expected {(n, D, D)}")
            return a

        def differences(x, scale, other, first):
            n = x.shape[0]
            out = np.empty((n, D, D))
            for e in range(D):
                h = fd_step * max(float(np.max(np.abs(x[:, e]))), scale)
                xp, xm = x.copy(), x.copy()
                xp[:, e] += h
                xm[:, e] -= h
                fp = forces(xp, other) if first else forces(other, xp)
                fm = forces(xm, other) if first else forces(other, xm)
                out[:, :, e] = (fp - fm) / (2.0 * h)
            return out

        def law(u, v, tangent):
            f = forces(u, v)
            empty = np.zeros((0, 0))
            if not tangent:
                return f, empty, empty
            n = u.shape[0]
            if jacobian is not None:
                j = jacobian(u, v)
                if velocity_dependent:
                    du, dv = j
                else:  # df_du alone, or (df_du, anything)
                    du, dv = (j[0] if isinstance(j, tuple) else j), None
                du = tensor(du, n, "df_du")
                dv = tensor(dv, n, "df_dv") if velocity_dependent else None
            else:
                du = differences(u, displacement_scale, v, True)
                dv = differences(v, velocity_scale, u, False) if velocity_dependent else None

            def flat(a):  # column d + D e holds d f_d / d x_e
                return np.ascontiguousarray(a.transpose(0, 2, 1).reshape(n, D * D))

            return f, flat(du), (flat(dv) if dv is not None else empty)

        label = name or getattr(force, "__name__", "user")
        super().__init__(_v.user_element(law, D, velocity_dependent, str(label)), T, name)
        self._law = law  # the C++ element holds it weakly (no cycle hidden from the GC)


class RoughFlat(Element):
    """The rough flat (or any SI backbone ``Q [N]`` against ``x [m]``) under Masing's rules.

    ``RoughFlat(backbone, T)`` takes a backbone object (:func:`asperity.epb_backbone`,
    ``asperity.predict(...)["loads"][i]["backbone"]``, a :class:`asperity.JenkinsBackbone`
    ...); :meth:`from_contact`, :meth:`from_normalized` and :meth:`from_joint_case` build
    one.
    """

    def __init__(self, backbone, T=1.0, name: str | None = None,
                 parameters: Mapping | None = None, type: str = "rough_flat"):
        super().__init__(_v.masing(backbone, type, dict(parameters or {})), T, name)
        self.backbone = backbone

    @classmethod
    def from_contact(cls, contact, T=1.0, name: str | None = None) -> "RoughFlat":
        """From an :class:`asperity.EpbContact` (Table 7.2's properties, A0 and P set)."""
        contact.validate()
        params = {"A0": contact.A0, "P": contact.P, "model": contact.model,
                  "sigma": contact.sigma, "E_star": contact.E_star}
        return cls(_core.epb_backbone(contact), T, name, params)

    @classmethod
    def from_normalized(cls, flat, P_star: float, sigma: float, force_scale: float, T=1.0,
                        name: str | None = None) -> "RoughFlat":
        """From a normalized :class:`asperity.RoughFlat` at the load ``P_star = P/(K H A0)``
        and its SI scales ``sigma`` [m] (lengths) and ``force_scale = K H A0`` [N]: the
        backbone at the separation of ``P_star`` (Eq. 4.4 inverted), as
        ``backbone = "normalized"`` of a case file."""
        for field, v in (("P_star", P_star), ("sigma", sigma), ("force_scale", force_scale)):
            if not (math.isfinite(v) and v > 0):
                raise _core.InvalidInput(f"{field} = {v}: must be finite and > 0")
        d_star = flat.separation_star(P_star)
        bb = _core.ScaledBackbone(flat.backbone(d_star), sigma, force_scale)
        params = {"backbone": "normalized", "beta": flat.beta, "psi": flat.psi,
                  "P_star": P_star, "d_star": d_star, "sigma_m": sigma,
                  "force_scale_N": force_scale}
        return cls(bb, T, name, params)

    @classmethod
    def from_joint_case(cls, path: str | os.PathLike, T=1.0, load: int = 0,
                        name: str | None = None) -> "RoughFlat":
        """From a joint case file (docs/joints.md) at its load case ``load`` (0-based)."""
        p = _core.predict(os.fspath(path))
        loads = p["loads"]
        if not 0 <= load < len(loads):
            raise _core.InvalidInput(
                f"load = {load}: the case has load cases 0 .. {len(loads) - 1}")
        L = loads[load]
        if L["odfalk_vingsbo"] is not None:
            ov = L["odfalk_vingsbo"]
            return OdfalkVingsbo(L["backbone"], ov["fretting_yield_point"],
                                 ov["hardening_coefficient"], T, name)
        params = {"case": os.fspath(path), "preload": L["preload"], "Q_max": L["Q_max"],
                  "stiffness": L["stiffness"]}
        return cls(L["backbone"], T, name, params)


class OdfalkVingsbo(Element):
    """The Odfalk-Vingsbo elastic-plastic tangential law (thesis Eq. 3.10) as an element:
    Masing's loop on ``backbone`` (the elastic part, ``Q [N]`` against ``x [m]``) with the
    parallelogram of plastic slip in series. ``fretting_yield_point`` Q_ty [N] and
    ``hardening_coefficient`` k_p [N/m] are measured on the joint (docs/joints.md: asperity
    never supplies them). Its steady response is where a period's plastic flows balance;
    below Q_ty it is the :class:`RoughFlat` element's. :meth:`RoughFlat.from_joint_case`
    returns one for a case with ``tangential = "odfalk_vingsbo"``.
    """

    def __init__(self, backbone, fretting_yield_point: float, hardening_coefficient: float,
                 T=1.0, name: str | None = None):
        super().__init__(_v.odfalk_vingsbo(backbone, fretting_yield_point,
                                           hardening_coefficient), T, name)
        self.backbone = backbone


def _sigma(sigma) -> float | None:
    # None: the length scale of a summit_heights table.
    return None if sigma is None else float(sigma)


def _heights(table):
    return None if table is None else np.ascontiguousarray(table, dtype=float)


class RoughContactSurface:
    """The two rough surfaces of an interface (combined values, SI: ``E_star``, ``G_star``,
    ``H`` [Pa], ``nu``, ``sigma`` [m], ``R`` [m], ``eta`` [1/m^2], the asperity ``model``
    ``"bke"``, ``"ke"``, ``"ceb"`` or ``"cfc"``, ``mu_cfc`` for CFC, ``summit_sigma``: sigma is
    the summit heights' standard deviation; ``summit_heights``: a measured summit-height
    density to sum over instead of the Gaussian, an (n, 2) array of heights [m] and densities,
    linear between rows, whose standard deviation is then sigma: give ``sigma=None`` or that
    value) as the rough flat per unit nominal area, with its
    tangential tables over the normal pressure from ``p_low`` to ``p_high`` [Pa]
    (docs/rough_contact.md). Build it once per interface and place elements with
    :meth:`element`: the tables are shared. Raises :class:`asperity.InvalidInput` naming the
    field."""

    def __init__(self, E_star: float, G_star: float, H: float, sigma: float | None, R: float,
                 eta: float, *, p_low: float, p_high: float, nu: float = 0.3,
                 model: str = "bke", mu_cfc: float | None = None, summit_sigma: bool = False,
                 summit_heights=None):
        self.parameters = {"E_star": float(E_star), "G_star": float(G_star), "H": float(H),
                           "nu": float(nu), "sigma": _sigma(sigma), "R": float(R),
                           "eta": float(eta), "model": str(model), "mu_cfc": mu_cfc,
                           "summit_sigma": bool(summit_sigma),
                           "summit_heights": _heights(summit_heights)}
        self.core = _v.rough_contact_surface(**self.parameters, p_low=float(p_low),
                                             p_high=float(p_high))
        self.parameters["sigma"] = float(self.core.sigma)
        self.parameters["summit_sigma"] = self.parameters["summit_sigma"] or (
            summit_heights is not None)

    @staticmethod
    def max_pressure_of(**parameters) -> float:
        """The largest nominal pressure [Pa] the rough flat of these surfaces represents (its
        load at ``d = -5 sigma_a``): the highest ``p_high`` allowed."""
        p = {"nu": 0.3, "model": "bke", "mu_cfc": None, "summit_sigma": False, **parameters}
        p["sigma"] = _sigma(p.get("sigma"))
        p["summit_heights"] = _heights(p.get("summit_heights"))
        return float(_v.rough_flat_max_pressure(**p))

    @property
    def p_low(self) -> float:
        return float(self.core.p_low)

    @property
    def p_high(self) -> float:
        return float(self.core.p_high)

    @property
    def pressure_scale(self) -> float:
        """``K H`` [Pa]: pressures over it are the rough flat's ``P*``."""
        return float(self.core.pressure_scale)

    def element(self, pressure: float, area: float, T=None, name: str | None = None
                ) -> "RoughContact":
        """A :class:`RoughContact` element of ``area`` [m^2] at the prestress ``pressure``
        [Pa] (in ``[p_low, p_high]``) placed by ``T`` (rows t1, t2, n: closure; default the
        first three DOFs)."""
        return RoughContact(surface=self, pressure=pressure, area=area, T=T, name=name)

    def __repr__(self) -> str:
        return (f"RoughContactSurface({self.parameters}, p_low={self.p_low}, "
                f"p_high={self.p_high})")


class RoughContact(Element):
    """The thesis's rough flat as the contact law of a zero-thickness interface element in
    three directions (rows of ``T``: t1, t2 tangential, n the closure, ``u_n > 0`` presses):
    the Greenwood-Williamson normal law unloading from the prestress's plastic set, Masing's
    rules with memory in each tangential direction at the current pressure, the traction
    limited to the rough flat's static friction (docs/rough_contact.md). ``u = 0`` is the
    prestressed state. At constant normal load and motion along t1 it is :class:`RoughFlat`
    at the same load.

    ``RoughContact(E_star=..., G_star=..., H=..., sigma=..., R=..., eta=..., pressure=,
    area=, T=)`` builds its own surface with tables from ``pressure/8`` to ``8 pressure``
    (as a case file's ``type = "rough_contact"`` element); ``RoughContact(surface=s,
    pressure=, area=, T=)`` (or ``s.element(...)``) shares the surface ``s``.
    """

    def __init__(self, *, pressure: float, area: float, T=None, surface=None,
                 name: str | None = None, **surface_parameters):
        if surface is None:
            # Checked before the surface's tables are built (a few tenths of a second).
            for field, v, unit in (("pressure", pressure, "Pa"), ("area", area, "m^2")):
                if not (math.isfinite(float(v)) and float(v) > 0):
                    raise _core.InvalidInput(f"{field} = {v} {unit}: must be finite and > 0")
            p = float(pressure)
            surface = RoughContactSurface(**surface_parameters, p_low=p / 8.0, p_high=8.0 * p)
        elif surface_parameters:
            raise _core.InvalidInput(
                f"give a surface or its parameters, not both (got {sorted(surface_parameters)})")
        if not isinstance(surface, RoughContactSurface):
            raise _core.InvalidInput(
                f"surface is a {type(surface).__name__}, not a RoughContactSurface")
        label = name or "rough_contact element"
        core = _v.rough_contact_element(surface.core, float(area), float(pressure), label)
        super().__init__(core, np.eye(3) if T is None else T, name)
        self.surface = surface
        self.pressure = float(pressure)
        self.area = float(area)


def rough_contact_on_interface(model, asperity_model: str | None = None,
                               mu_cfc: float | None = None,
                               name: str = "interface element") -> list:
    """:class:`RoughContact` elements on every interface element of a reduced model in contact
    at its rough prestress, as a case file's ``T = { interface_element = "all" }``
    (docs/rough_contact.md): ``model`` is :func:`asperity.fem.read_reduced_model`'s dict (or a
    path to the file) with its ``rough`` record; one shared surface with tables from
    ``p_min/8`` to ``8 p_max`` (at most 0.999 of the rough flat's largest load); each element
    placed by its rows of ``Q`` (t1, t2 and the closure, the negative opening).
    ``asperity_model`` and ``mu_cfc`` override the file's. Elements out of contact are left
    out with a :class:`RuntimeWarning`."""
    if isinstance(model, (str, os.PathLike)):
        model = _core.fem_read_reduced_model(os.fspath(model))
    r = model.get("rough")
    source = model.get("source", "the reduced model")
    if r is None:
        raise _core.InvalidInput(
            f"{source} has no rough record: write it with `asperity structure` and a "
            "[rough_contact] table (the rough surface and each element's prestress pressure)")
    pressure = np.asarray(r["pressure"], dtype=float)
    touching = [e for e in range(pressure.size) if bool(r["in_contact"][e]) and pressure[e] > 0]
    if not touching:
        raise _core.InvalidInput(
            f"no interface element of {source} is in contact at the rough prestress")
    if len(touching) < pressure.size:
        warnings.warn(f"{pressure.size - len(touching)} of the {pressure.size} interface "
                      "elements are out of contact at the rough prestress (less than one "
                      "asperity expected in contact) and are left out", RuntimeWarning,
                      stacklevel=2)
    params = {k: r[k] for k in ("E_star", "G_star", "H", "nu", "sigma", "R", "eta",
                                "summit_sigma")}
    params["summit_heights"] = r.get("summit_heights")
    params["model"] = asperity_model if asperity_model is not None else r["model"]
    params["mu_cfc"] = mu_cfc
    p_t = pressure[touching]
    p_max_flat = RoughContactSurface.max_pressure_of(**params)
    surface = RoughContactSurface(**params, p_low=float(p_t.min()) / 8.0,
                                  p_high=min(8.0 * float(p_t.max()), 0.999 * p_max_flat))
    Q = np.asarray(model["Q"], dtype=float)
    area = np.asarray(model["element_area"], dtype=float).reshape(-1)
    out = []
    for e in touching:
        T = np.vstack([Q[3 * e], Q[3 * e + 1], -Q[3 * e + 2]])
        out.append(surface.element(float(pressure[e]), float(area[e]), T, f"{name} {e}"))
    return out


class HarmonicBalance:
    """The harmonic-balance (AFT) system of a structure with joint elements.

    ``HarmonicBalance(structure, elements, harmonics=None, max_harmonic=None,
    time_points=256)``: ``harmonics`` a list of the harmonics kept (ascending, holding 1),
    or ``max_harmonic`` H for ``0..H`` (the default is 0..3).
    """

    def __init__(self, structure: Structure, elements: Sequence[Element] = (),
                 harmonics: Iterable[int] | None = None, max_harmonic: int | None = None,
                 time_points: int = 256):
        if harmonics is not None and max_harmonic is not None:
            raise _core.InvalidInput("give harmonics or max_harmonic, not both")
        if max_harmonic is not None:
            if int(max_harmonic) < 1:
                raise _core.InvalidInput(f"max_harmonic = {max_harmonic}: must be >= 1")
            harmonics = range(int(max_harmonic) + 1)
        harmonics = [0, 1, 2, 3] if harmonics is None else [int(h) for h in harmonics]
        if isinstance(elements, Element):
            elements = [elements]
        elements = list(elements)
        for k, e in enumerate(elements):
            if not isinstance(e, Element):
                raise _core.InvalidInput(f"elements[{k + 1}] is a {type(e).__name__}, not an Element")
        names = [e.name or f"element {k + 1}" for k, e in enumerate(elements)]
        self.structure = structure
        self.elements = elements
        self._core = _v.HarmonicBalance(structure._core, [e.core for e in elements],
                                        [e.T for e in elements], names, harmonics,
                                        int(time_points))

    @classmethod
    def from_case(cls, path: str | os.PathLike) -> "HarmonicBalance":
        """The structure, placed elements and harmonic-balance settings of a vibration case
        file (its analyses are not run; ``output_dofs`` of the case in ``.output_dofs``)."""
        d = _v.case_system(os.fspath(path))
        return cls._from_system(d)

    @classmethod
    def _from_system(cls, d) -> "HarmonicBalance":
        s = Structure.__new__(Structure)
        s._core = d["structure"]
        elements = []
        for core, T, name in d["elements"]:
            e = Element.__new__(Element)
            e.core, e.T, e.name = core, np.asarray(T), name
            elements.append(e)
        hb = cls(s, elements, harmonics=d["harmonics"], time_points=d["time_points"])
        hb.output_dofs = list(d["output_dofs"])
        return hb

    # -- layout ---------------------------------------------------------------------------
    @property
    def dofs(self) -> int:
        return int(self._core.dofs)

    @property
    def unknowns(self) -> int:
        return int(self._core.unknowns)

    @property
    def harmonics(self) -> list:
        return list(self._core.harmonics)

    @property
    def coefficients(self) -> int:
        """n_c, coefficients per DOF."""
        return int(self._core.coefficients)

    @property
    def time_points(self) -> int:
        return int(self._core.time_points)

    def index(self, dof: int, h: int, kind: int = 0) -> int:
        """Index in ``U`` of harmonic ``h`` of ``dof``: cosine (``kind`` 0) or sine (1)."""
        return int(self._core.index(dof, h, kind))

    def force(self, cos=None, sin=None) -> np.ndarray:
        """The excitation vector in the layout of ``U`` from its cosine and sine parts.

        Each of ``cos``/``sin`` is a dict ``{h: vector over DOFs}`` or an array with one row
        per harmonic in :attr:`harmonics` order and one column per DOF (as ``force_cos`` of
        a case file; the sine row of harmonic 0 must be zero)."""
        F = np.zeros(self.unknowns)
        for part, kind in ((cos, 0), (sin, 1)):
            if part is None:
                continue
            if isinstance(part, Mapping):
                items = part.items()
            else:
                rows = np.array(part, dtype=float, ndmin=2)
                if rows.shape != (len(self.harmonics), self.dofs):
                    raise _core.InvalidInput(
                        f"force_{'cos' if kind == 0 else 'sin'} is {rows.shape}: expected "
                        f"({len(self.harmonics)}, {self.dofs}) (harmonics x DOFs)")
                items = zip(self.harmonics, rows)
            for h, vec in items:
                vec = np.asarray(vec, dtype=float).reshape(-1)
                if vec.size != self.dofs:
                    raise _core.InvalidInput(
                        f"force of harmonic {h} has {vec.size} entries: expected {self.dofs}")
                if h == 0 and kind == 1:
                    if np.any(vec != 0.0):
                        raise _core.InvalidInput("harmonic 0 has no sine part")
                    continue
                for dof in range(self.dofs):
                    F[self.index(dof, int(h), kind)] += vec[dof]
        return F

    def coefficients_of(self, U, dof: int) -> np.ndarray:
        """The n_c coefficients of ``dof`` in ``U``."""
        U = np.asarray(U, dtype=float)
        n = self.coefficients
        return U[dof * n:(dof + 1) * n].copy()

    # -- evaluation -------------------------------------------------------------------------
    def residual(self, U, omega: float, F_ex=None, jacobian: bool = True):
        """``R = A(omega) U + F_nl(U, omega) - F_ex``; with ``jacobian`` returns
        ``(R, dR_dU, dR_domega)`` (analytic), else ``R``."""
        U = np.ascontiguousarray(U, dtype=float)
        F = np.zeros(0) if F_ex is None else np.ascontiguousarray(F_ex, dtype=float)
        d = self._core.residual(U, float(omega), F, bool(jacobian))
        if not jacobian:
            return np.asarray(d["R"])
        return np.asarray(d["R"]), np.asarray(d["dR_dU"]), np.asarray(d["dR_domega"])

    def nonlinear_force(self, U, omega: float) -> np.ndarray:
        """Coefficients of the elements' forces on the structure, ``sum_e T_e^T f_e``."""
        return np.asarray(self._core.nonlinear_force(np.ascontiguousarray(U, dtype=float),
                                                     float(omega)))

    def dynamic_stiffness(self, omega: float) -> np.ndarray:
        """``A(omega)`` (unknowns x unknowns) with the structure's damping."""
        return np.asarray(self._core.dynamic_stiffness(float(omega)))

    def stuck_stiffness(self) -> np.ndarray:
        """``K`` plus every element's initial stiffness (the joints stuck)."""
        return np.asarray(self._core.stuck_stiffness())

    def time_history(self, U, dof: int, samples: int = 0) -> np.ndarray:
        """``x_dof(t_i)`` over one period: ``N_t`` samples (or ``samples`` equally spaced),
        ``t_i = i T / N``."""
        return np.asarray(self._core.time_history(np.ascontiguousarray(U, dtype=float), dof,
                                                  int(samples)))

    def harmonic_amplitude(self, U, dof: int, h: int = 1) -> float:
        """``sqrt(a_h^2 + b_h^2)`` of ``dof`` (``|a_0|`` for h = 0)."""
        return float(self._core.harmonic_amplitude(np.ascontiguousarray(U, dtype=float), dof, h))

    @property
    def counters(self) -> dict:
        """Residual and Jacobian evaluations so far."""
        return dict(self._core.counters)

    # -- analyses ---------------------------------------------------------------------------
    def nonlinear_mode(self, mode: int = 1, log10_amplitude=(-6.0, -3.0),
                       output_dofs: Sequence[int] = (), **continuation) -> Result:
        """Nonlinear mode by EPMC (Krack 2015): unknowns ``[harmonics, omega, xi, log10 a]``,
        damping ``C - xi M``; ``a`` the modal amplitude of the mass-normalized first
        harmonic. Returns arrays ``log10_amplitude, amplitude, omega [rad/s],
        frequency_hz, xi [1/s], damping_ratio (xi / 2 omega), output_amplitude (points x
        outputs), harmonics (points x unknowns: U = a Psi)``, ``linear_omega``,
        ``linear_damping_ratio``, ``continuation`` and ``warnings``. Keyword options of the
        continuation: see :meth:`frequency_response`."""
        lo, hi = log10_amplitude
        r = Result(_v.nonlinear_mode(self._core, int(mode), float(lo), float(hi),
                                     [int(d) for d in output_dofs], dict(continuation)))
        _issue(r, "nonlinear_mode")
        return r

    def frequency_response(self, force, omega, force_scales: Sequence[float] = (1.0,),
                           output_dofs: Sequence[int] = (), *, force_per_omega=None,
                           force_per_omega2=None, stability: bool = False,
                           **continuation) -> list:
        """Forced response curves by continuation in ``omega = (from, to)`` [rad/s] for each
        force scale; ``force`` in the layout of ``U`` (see :meth:`force`). The excitation
        is ``force + omega force_per_omega + omega^2 force_per_omega2`` (the last two
        optional: base excitation, e.g. ``y = Y sin(w t)`` through k and c gives
        ``force = force(sin={1: k Y})`` and ``force_per_omega = force(cos={1: c Y})``).
        One :class:`Result` per scale: ``force_scale, omega, output_amplitude (points x
        outputs, first harmonic), harmonic_amplitude (per output: points x harmonics),
        max_displacement (points x outputs), harmonics (points x unknowns), continuation,
        warnings``; with ``stability=True`` also ``stability``: Hill's method per point
        (``stable`` bool array, ``max_real_exponent`` [1/s], ``max_multiplier_modulus``,
        ``instability`` ("" / "fold" / "period_doubling" / "neimark_sacker"),
        ``exponents``: points x reported Floquet exponents [1/s], complex, largest real part
        first; docs/vibration.md).

        Keyword options of the continuation (each optional; the analysis's own defaults
        otherwise, as in a case file's ``continuation`` table): step, min_step, max_step
        (arclength in scaled unknowns), max_points, target_iterations, max_angle [rad],
        max_iterations, step_tolerance, residual_tolerance (Newton), chord_unknowns (systems
        of at least this many unknowns use chord Newton; docs/vibration.md, "Solvers")."""
        w0, w1 = omega

        def vec(x):
            return np.zeros(0) if x is None else np.ascontiguousarray(x, dtype=float)

        curves = _v.frequency_response(self._core, vec(force), vec(force_per_omega),
                                       vec(force_per_omega2), [float(s) for s in force_scales],
                                       float(w0), float(w1), [int(d) for d in output_dofs],
                                       dict(continuation), bool(stability))
        out = []
        for c in curves:
            r = _curve_result(c)
            _issue(r, "frequency_response")
            out.append(r)
        return out

    def force_response(self, force, omega: float, force_scale=(0.0, 1.0),
                       output_dofs: Sequence[int] = (), *, force_per_omega=None,
                       force_per_omega2=None, **continuation) -> Result:
        """Forced response at the fixed frequency ``omega`` [rad/s] by continuation in the
        force scale ``lambda`` from ``force_scale[0]`` to ``force_scale[1]`` (both >= 0):
        ``A(omega) U + F_nl(U) = lambda F_ex`` with ``F_ex`` as in
        :meth:`frequency_response`. Returns ``omega, force_scale (lambda per point),
        output_amplitude, harmonic_amplitude, max_displacement, harmonics, folds`` (the
        turning points in ``lambda``, each ``force_scale, output_amplitude, harmonics``),
        ``continuation``, ``warnings``; keyword options of the continuation as in
        :meth:`frequency_response` (steps in units of the ``lambda`` range)."""
        s0, s1 = force_scale

        def vec(x):
            return np.zeros(0) if x is None else np.ascontiguousarray(x, dtype=float)

        r = Result(_v.force_response(self._core, vec(force), vec(force_per_omega),
                                     vec(force_per_omega2), float(omega), float(s0), float(s1),
                                     [int(d) for d in output_dofs], dict(continuation)))
        r["folds"] = [Result(f) for f in r["folds"]]
        _issue(r, "force_response")
        return r

    def mode_rom(self, mode: Mapping, force, output_dofs: Sequence[int] = (),
                 subdivisions: int = 16) -> Result:
        """Forced response near one nonlinear mode from its backbone (single nonlinear mode
        theory, Krack 2015): ``mode`` a result of :meth:`nonlinear_mode` of this system,
        ``force`` in the layout of ``U`` (its first harmonic is used). For each backbone
        point ``(omega^2 - W^2 + i W xi) a = psi^H F`` gives the excitation frequencies
        ``W`` below and above the backbone (``omega``, ``xi`` and ``Psi`` interpolated
        linearly in ``log a``, ``subdivisions`` points per backbone interval). Returns ``omega`` (``W``), ``amplitude``
        (modal), ``output_amplitude``, ``low_side_points`` (the first points, below the
        backbone, in increasing amplitude; then the high side in decreasing amplitude) and
        ``peak_amplitude``. Exact for one DOF on one harmonic with viscous damping;
        docs/vibration.md gives its error on a friction joint."""
        r = Result(_v.nonlinear_mode_rom(
            self._core, np.ascontiguousarray(mode["amplitude"], dtype=float),
            np.ascontiguousarray(mode["omega"], dtype=float),
            np.ascontiguousarray(mode["xi"], dtype=float),
            np.ascontiguousarray(np.atleast_2d(mode["harmonics"]), dtype=float),
            np.ascontiguousarray(force, dtype=float), [int(d) for d in output_dofs],
            int(subdivisions)))
        _issue(r, "mode_rom")
        return r

    def amplitude_control(self, force, dof: int, amplitude: float, omega,
                          output_dofs: Sequence[int] = (), **continuation) -> Result:
        """Amplitude-controlled harmonic balance (response-controlled testing): the first
        harmonic of ``dof`` held at ``amplitude`` [m] while ``omega = (from, to)`` [rad/s]
        is swept; the force scale ``lambda`` (``F_ex = lambda force``) is the unknown.
        Returns ``omega, force_scale, output_amplitude, harmonics, continuation,
        warnings``."""
        w0, w1 = omega
        r = Result(_v.amplitude_control(self._core, np.ascontiguousarray(force, dtype=float),
                                        int(dof), float(amplitude), float(w0), float(w1),
                                        [int(d) for d in output_dofs], dict(continuation)))
        _issue(r, "amplitude_control")
        return r

    def phase_resonance(self, force, dof: int, log10_amplitude=(-3.0, 0.0), mode: int = 1,
                        output_dofs: Sequence[int] = (), **continuation) -> Result:
        """Phase resonance (phase-controlled harmonic balance): the first harmonic of ``dof``
        lags the force at ``dof`` by 90 degrees; continuation in ``log10`` of its amplitude
        ``a`` [m] from the stuck structure's mode ``mode``. Returns ``amplitude, omega,
        force_scale`` (``lambda`` with ``F_ex = lambda force``), ``output_amplitude,
        harmonics, continuation, warnings``. For one nonlinear mode this traces the
        backbone."""
        lo, hi = log10_amplitude
        r = Result(_v.phase_resonance(self._core, np.ascontiguousarray(force, dtype=float),
                                      int(dof), int(mode), float(lo), float(hi),
                                      [int(d) for d in output_dofs], dict(continuation)))
        _issue(r, "phase_resonance")
        return r

    def superharmonic_resonance(self, force, harmonic: int = 3, log10_force=(-2.0, 0.0),
                                mode: int = 1, output_dofs: Sequence[int] = (),
                                **continuation) -> Result:
        """The ``harmonic``:1 superharmonic resonance followed as the force scale grows
        (variable-phase resonance nonlinear mode, VPRNM; Porter & Brake 2024): harmonic r of
        the response in quadrature with the elements' force at harmonic r from the lower
        harmonics; continuation in ``log10`` of the force scale ``lambda`` (``F_ex = lambda
        force``) from the stuck mode ``mode``'s frequency over r. Returns ``force_scale,
        omega`` (the excitation's), ``output_amplitude`` (harmonic 1),
        ``output_harmonic_amplitude`` (harmonic r), ``harmonics, continuation, warnings``."""
        lo, hi = log10_force
        r = Result(_v.superharmonic_resonance(
            self._core, np.ascontiguousarray(force, dtype=float), int(harmonic), int(mode),
            float(lo), float(hi), [int(d) for d in output_dofs], dict(continuation)))
        _issue(r, "superharmonic_resonance")
        return r

    def quasi_static_mode(self, mode: int = 1, amplitude=(1e-7, 1e-4), points: int = 60) -> Result:
        """Quasi-static modal estimate (static push along the stuck mode, Masing's rules):
        arrays ``amplitude (modal, log-spaced), omega, frequency_hz, damping_ratio,
        modal_force, dissipation [J]``, ``linear_omega``, ``newton_iterations``,
        ``warnings``."""
        a0, a1 = amplitude
        r = Result(_v.quasi_static_mode(self._core, int(mode), float(a0), float(a1),
                                        int(points)))
        _issue(r, "quasi_static_mode")
        return r

    def __repr__(self) -> str:
        return (f"HarmonicBalance(dofs={self.dofs}, elements={len(self.elements)}, "
                f"harmonics={self.harmonics}, time_points={self.time_points})")


def nonlinear_mode(hb: HarmonicBalance, mode: int = 1, log10_amplitude=(-6.0, -3.0),
                   output_dofs: Sequence[int] = (), **continuation) -> Result:
    """:meth:`HarmonicBalance.nonlinear_mode`."""
    return hb.nonlinear_mode(mode, log10_amplitude, output_dofs, **continuation)


def frequency_response(hb: HarmonicBalance, force, omega, force_scales=(1.0,),
                       output_dofs: Sequence[int] = (), **kwargs) -> list:
    """:meth:`HarmonicBalance.frequency_response`."""
    return hb.frequency_response(force, omega, force_scales, output_dofs, **kwargs)


def force_response(hb: HarmonicBalance, force, omega: float, force_scale=(0.0, 1.0),
                   output_dofs: Sequence[int] = (), **kwargs) -> Result:
    """:meth:`HarmonicBalance.force_response`."""
    return hb.force_response(force, omega, force_scale, output_dofs, **kwargs)


def amplitude_control(hb: HarmonicBalance, force, dof: int, amplitude: float, omega,
                      output_dofs: Sequence[int] = (), **continuation) -> Result:
    """:meth:`HarmonicBalance.amplitude_control`."""
    return hb.amplitude_control(force, dof, amplitude, omega, output_dofs, **continuation)


def phase_resonance(hb: HarmonicBalance, force, dof: int, log10_amplitude=(-3.0, 0.0),
                    mode: int = 1, output_dofs: Sequence[int] = (), **continuation) -> Result:
    """:meth:`HarmonicBalance.phase_resonance`."""
    return hb.phase_resonance(force, dof, log10_amplitude, mode, output_dofs, **continuation)


def superharmonic_resonance(hb: HarmonicBalance, force, harmonic: int = 3,
                            log10_force=(-2.0, 0.0), mode: int = 1,
                            output_dofs: Sequence[int] = (), **continuation) -> Result:
    """:meth:`HarmonicBalance.superharmonic_resonance`."""
    return hb.superharmonic_resonance(force, harmonic, log10_force, mode, output_dofs,
                                      **continuation)


def quasi_static_mode(hb: HarmonicBalance, mode: int = 1, amplitude=(1e-7, 1e-4),
                      points: int = 60) -> Result:
    """:meth:`HarmonicBalance.quasi_static_mode`."""
    return hb.quasi_static_mode(mode, amplitude, points)


def _curve_result(c: dict) -> Result:
    r = Result(c)
    if "stability" in c:
        s = dict(c["stability"])
        s["stable"] = np.asarray(s["stable"], dtype=bool)
        s["exponents"] = np.asarray(s.pop("exponents_real")) + 1j * np.asarray(
            s.pop("exponents_imag"))
        r["stability"] = Result(s)
    return r


def _case_result(d: dict, source: str) -> Result:
    out = Result(summary=d["summary"], complete=d["complete"], stop_reason=d["stop_reason"],
                 remedy=d["remedy"], failures=list(d["failures"]), warnings=list(d["warnings"]))
    out["nonlinear_mode"] = Result(d["nonlinear_mode"]) if d["nonlinear_mode"] is not None else None
    out["frequency_response"] = [_curve_result(c) for c in d["frequency_response"]]
    out["force_response"] = []
    for c in d["force_response"]:
        r = Result(c)
        r["folds"] = [Result(f) for f in r["folds"]]
        out["force_response"].append(r)
    out["amplitude_control"] = [Result(c) for c in d["amplitude_control"]]
    out["phase_resonance"] = [Result(c) for c in d["phase_resonance"]]
    out["superharmonic_resonance"] = [Result(c) for c in d["superharmonic_resonance"]]
    out["backbone_rom"] = [
        Result(table=c["table"], force_scale=c["force_scale"],
               omega=np.asarray(c["omega_rad_s"], dtype=float),
               amplitude=np.asarray(c["modal_amplitude"], dtype=float),
               output_amplitude=np.asarray(c["output_amplitude"], dtype=float),
               low_side_points=c["low_side_points"], peak_amplitude=c["peak_modal_amplitude"])
        for c in d["summary"].get("backbone_rom", [])]
    out["quasi_static_mode"] = (Result(d["quasi_static_mode"])
                                if d["quasi_static_mode"] is not None else None)
    out["system"] = HarmonicBalance._from_system(d["system"])
    _issue(out, source)
    return out


def run_case(path: str | os.PathLike, *, stability: bool = False) -> Result:
    """Runs a vibration case file (docs/vibration.md) through the same C++ code as
    ``asperity vibration``. Returns a :class:`Result` with ``summary`` (summary.json as a
    dict), ``nonlinear_mode`` and ``quasi_static_mode`` (:class:`Result` of arrays or None),
    ``frequency_response`` (one :class:`Result` per curve, ``table`` its
    ``[[frequency_response]]`` table, counted from 1 as in messages and file names,
    ``force_amplitude`` its forcing amplitude [N]: the norm of the table's force vector times
    the force scale), ``force_response``, ``amplitude_control``, ``phase_resonance`` and
    ``superharmonic_resonance`` (one per table of that name that ran, ``table`` its position,
    from 1),
    ``backbone_rom`` (one per ``[[backbone_rom]]`` table and force scale, with ``table``,
    ``force_scale`` and the arrays of :meth:`HarmonicBalance.mode_rom`),
    ``complete`` (every continuation reached its end),
    ``stop_reason``, ``remedy`` (what helps when it did not), ``failures`` (the curves that
    could not start, with their reasons), ``warnings`` (also issued as RuntimeWarning) and
    ``system`` (the case's :class:`HarmonicBalance`). ``stability=True`` adds Hill's
    stability to every forced-response curve (as ``stability = true`` in each table)."""
    r = _case_result(_v.run_case(os.fspath(path), bool(stability)), os.fspath(path))
    try:
        with open(path, "rb") as f:
            text = f.read().decode("utf-8")
    except (OSError, UnicodeDecodeError):
        return r
    return _with_force_amplitudes(r, text)


def run_case_text(text: str, base_dir: str | os.PathLike = ".", *,
                  stability: bool = False) -> Result:
    """:func:`run_case` for case-file text (``base_dir`` resolves .mtx files and a
    [joint]'s profiles)."""
    return _with_force_amplitudes(
        _case_result(_v.run_case_text(text, os.fspath(base_dir), bool(stability)), "<string>"),
        text)


# -- matplotlib helpers ----------------------------------------------------------------------
def _axes(ax, n=1):
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(n, 1, sharex=True, squeeze=False)
        return list(ax[:, 0])
    return list(ax) if n > 1 else [ax]


def plot_mode(mode: Mapping, axes=None, label: str | None = None, quasi_static: Mapping | None = None):
    """Frequency [Hz] and damping ratio against the modal amplitude (log axes) of a
    :meth:`HarmonicBalance.nonlinear_mode` result, with a quasi-static estimate dashed if
    given. ``axes``: two matplotlib axes (created when None). Returns the axes."""
    ax_f, ax_z = _axes(axes, 2)
    line, = ax_f.semilogx(mode["amplitude"], mode["frequency_hz"], label=label or "EPMC")
    ax_z.loglog(mode["amplitude"], mode["damping_ratio"], color=line.get_color())
    if quasi_static is not None:
        ax_f.semilogx(quasi_static["amplitude"], quasi_static["frequency_hz"], "--",
                      color=line.get_color(), label="quasi-static")
        ax_z.loglog(quasi_static["amplitude"], quasi_static["damping_ratio"], "--",
                    color=line.get_color())
    ax_f.set_ylabel("frequency [Hz]")
    ax_z.set_ylabel("damping ratio")
    ax_z.set_xlabel("modal amplitude [sqrt(kg) m]")
    ax_f.legend()
    return ax_f, ax_z


def force_label(curve: Mapping, force=None) -> str:
    """The legend of a forced-response curve: its forcing amplitude in N (the curve's
    ``force_amplitude``, from :func:`run_case`, or ``force_scale`` times the norm of
    ``force``, the excitation at scale 1), followed by ``at POINT`` for a force given at an
    output point of a reduced model; ``force x SCALE`` when neither is known."""
    amp = curve.get("force_amplitude") if hasattr(curve, "get") else None
    if amp is None and force is not None:
        norm = float(np.linalg.norm(np.asarray(force, dtype=float)))
        amp = float(curve["force_scale"]) * norm
    if amp is None or not np.isfinite(amp) or amp <= 0:
        return f"force x {float(curve['force_scale']):g}"
    point = curve.get("force_point") if hasattr(curve, "get") else None
    return f"F = {amp:.4g} N" + (f" at {point}" if point else "")


def plot_response(curves: Sequence[Mapping], output: int = 0, ax=None, *, force=None,
                  backbone: Mapping | None = None):
    """First-harmonic amplitude of output ``output`` [m] (log axis) against the excitation
    frequency [Hz] of :meth:`HarmonicBalance.frequency_response` curves (or
    :func:`run_case`'s), one line per force amplitude, labelled in N (:func:`force_label`;
    ``force``: the excitation vector at scale 1 for curves that do not carry it); with
    ``stability`` (Hill's method), the unstable stretches dashed red over them; with
    ``backbone`` (a :meth:`HarmonicBalance.nonlinear_mode` result computed with the same
    output DOFs), the backbone dashed black within the curves' range. The axes follow the
    CLI's ``frequency_response.png`` (docs/vibration.md, "Plots")."""
    (ax,) = _axes(ax)
    labelled = False
    f_lo, f_hi, a_hi = np.inf, 0.0, 0.0
    for c in curves:
        y = np.asarray(c["output_amplitude"])[:, output]
        f = np.asarray(c["omega"]) / (2.0 * np.pi)
        f_lo, f_hi = min(f_lo, f.min()), max(f_hi, f.max())
        a_hi = max(a_hi, float(np.nanmax(y)))
        ax.plot(f, y, label=force_label(c, force))
        if c.get("stability") is not None:
            yu = np.where(c["stability"]["stable"], np.nan, y)
            if np.isfinite(yu).any():
                ax.plot(f, yu, "--", color="#d62728", lw=2.5,
                        label=None if labelled else "unstable (Hill)")
                labelled = True
    if backbone is not None and np.asarray(backbone["output_amplitude"]).ndim == 2 and \
            np.asarray(backbone["output_amplitude"]).shape[1] > output:
        fb = np.asarray(backbone["frequency_hz"], dtype=float)
        yb = np.asarray(backbone["output_amplitude"], dtype=float)[:, output]
        # Within the curves' frequency range and up to twice their largest amplitude (the
        # mode goes on to amplitudes no curve reaches), as the CLI draws it.
        keep = (fb >= f_lo) & (fb <= f_hi) & (yb > 0) & (yb <= 2.0 * a_hi)
        if keep.sum() > 1:
            ax.plot(fb[keep], yb[keep], "--", color="k", label="backbone (nonlinear mode)")
    ax.set_yscale("log")
    ax.set_xlabel("excitation frequency [Hz]")
    ax.set_ylabel("amplitude [m]")
    ax.legend()
    return ax


def _table_force(t: Mapping) -> tuple[float, str | None]:
    """A ``[[frequency_response]]`` table's forcing amplitude at scale 1 [N]: the norm of
    its harmonic force vector (``force_cos`` and ``force_sin``, every harmonic and DOF; for
    one forced DOF and one harmonic, the force amplitude itself), NaN when it gives no force
    (base excitation); and the output point when the force is given at one
    (``{point, direction, force}``: the values given there, numbers [N] or quantity
    strings, as the CLI's legends), else None."""
    values = [x for key in ("force_cos", "force_sin")
              for row in (t[key].get("force", []) if isinstance(t.get(key), Mapping)
                          else t.get(key, []))
              for x in (row if isinstance(row, list) else [row])]
    try:
        values = [_core.parse_quantity(x).value if isinstance(x, str) else float(x)
                  for x in values]
        norm = float(np.sqrt(sum(x ** 2 for x in values))) if values else np.nan
    except (TypeError, ValueError, _core.InvalidInput):
        norm = np.nan
    points = {t[k].get("point") for k in ("force_cos", "force_sin")
              if isinstance(t.get(k), Mapping)}
    rows = any(k in t and not isinstance(t[k], Mapping) for k in ("force_cos", "force_sin"))
    return norm, (points.pop() if len(points) == 1 and not rows else None)


def _with_force_amplitudes(result: Result, text: str) -> Result:
    """Each curve's ``force_amplitude`` [N] (its table's, :func:`_table_force`, times the
    curve's force scale; NaN without a force) and, for a force at an output point,
    ``force_point``: what :func:`force_label` writes."""
    import tomllib

    try:
        case = tomllib.loads(text)
    except (tomllib.TOMLDecodeError, UnicodeDecodeError):
        return result
    tables = case.get("frequency_response", [])
    for c in result["frequency_response"]:
        t = c.get("table", 0)  # counted from 1
        t = tables[t - 1] if isinstance(t, int) and 1 <= t <= len(tables) else {}
        norm, point = _table_force(t)
        c["force_amplitude"] = norm * float(c["force_scale"]) if norm > 0 else np.nan
        if point is not None:
            c["force_point"] = point
    return result
