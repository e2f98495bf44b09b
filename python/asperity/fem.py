"""Finite elements of elastic bodies: quadratic solids, stiffness and consistent mass.

The Python face of the C++ layer ``fem/`` (docs/structures.md); SI units throughout.

* :func:`assemble` - ``(K, M)`` as scipy.sparse matrices for one isotropic body meshed
  with 10-node tetrahedra or 20-node hexahedra (node order of
  ``include/asperity/fem/mesh.hpp``: tet10 corners 0-3 then mid-edges 0-1, 1-2, 2-0,
  0-3, 1-3, 2-3; hex20 as Abaqus C3D20). DOF ``3 * node + component``.
* :func:`run_structure` - a structure case file of ``asperity structure`` (the same C++
  run): the mesh, the reduced model, the linear modes (open, frictionless, stuck) and the
  prestress, as a dict of numpy arrays.
* :func:`structure_fretting` - the case's ``[fretting]`` apparatus (``asperity structure
  --fretting``, chapter 5's grips and drive around the finite-element joint): per total
  bolt preload the rough prestress and the quasi-static fretting cycles (loops, energy
  per cycle, tangential stiffness, energy-force exponents).
* :func:`read_reduced_model` - a reduced model (.mat: asperity's, or the published
  Brake-Reuss beam layout M, K, Fv, L, Qm, Tm) as a dict (with its rough record);
  :func:`rough_prestress` - the bolt preloads on the rough flat's normal law;
  :func:`read_mesh` - a gmsh
  ``.msh`` or Abaqus ``.inp`` mesh of quadratic solids; :func:`reduced_linear_modes` -
  the elastic modes of a reduced model file with a linear stiffness per interface element.
"""
from __future__ import annotations

import numpy as np

from . import _core

_f = _core._fem

__all__ = ["assemble", "run_structure", "structure_fretting", "read_reduced_model",
           "rough_prestress", "read_mesh", "reduced_linear_modes"]


def assemble(nodes, connectivity, E: float, nu: float, rho: float):
    """``(K [N/m], M [kg])``, scipy.sparse CSC matrices of size ``3 n``, for ``nodes``
    ``(n, 3)`` [m] and ``connectivity`` ``(m, 10)`` (tet10) or ``(m, 20)`` (hex20) of
    0-based node indices; Young's modulus ``E`` [Pa], Poisson's ratio ``nu`` in
    (-1, 0.5), density ``rho`` [kg/m^3]. Raises :class:`asperity.InvalidInput` for an
    index out of range, a node no element uses, an inverted or degenerate element (named
    by its row) or a material out of range."""
    nodes = np.ascontiguousarray(nodes, dtype=float)
    connectivity = np.ascontiguousarray(connectivity, dtype=np.int64)
    if nodes.ndim != 2 or connectivity.ndim != 2:
        raise _core.InvalidInput(
            f"nodes and connectivity must be 2-D arrays (got {nodes.ndim} and "
            f"{connectivity.ndim} dimensions)")
    return _f.assemble(nodes, connectivity, float(E), float(nu), float(rho))


def run_structure(path: str, gmsh: str = "gmsh") -> dict:
    """Runs a structure case file (docs/structures.md): mesh (gmsh, run as a separate
    program), assembly, bolts, interfaces, Craig-Bampton reduction, linear prestress and
    modes. Returns ``mesh`` (nodes, blocks, bodies), ``model`` (see
    :func:`read_reduced_model`), ``linear_modes`` (``open``, ``frictionless``, ``stuck``:
    ``frequency_hz``, reduced ``shapes``, ``rigid_body_modes``), ``prestress_pressure`` [Pa]
    per interface element, ``contact_area`` [m^2], ``bolt_load`` [N], ``mass`` [kg] and
    ``costs`` (step, seconds, peak memory MiB)."""
    return _core.fem_run_structure(str(path), gmsh)


def structure_fretting(path: str, gmsh: str = "gmsh") -> dict:
    """Runs a structure case file's ``[fretting]`` apparatus, the same C++ run as
    ``asperity structure CASE --fretting`` (docs/structures.md, "In the fretting
    apparatus"): the bodies condensed in the grips, then per total bolt preload the rough
    prestress and the steady cycle at each tip amplitude Delta_0 (harmonic balance at
    omega = 0). Returns ``mesh_nodes``, ``mesh_dofs``, ``interface_elements``,
    ``held_nodes``, ``driven_nodes``, ``drive_stiffness`` [N/m], ``mass`` [kg], ``costs``
    (step, seconds, peak memory MiB) and ``runs``, one dict per total preload:
    ``total_preload``, ``interface_load``, ``preload_through_grips`` [N] (the bolts are
    tightened in the grips), ``contact_area``, ``real_contact_area`` [m^2], ``pressure``
    [Pa] per interface element, ``elements_in_contact``, ``stiffness`` [N/m] (the stuck
    joint's dQ/d delta), ``exponents`` (d ln W / d ln Q_0 between successive cycles, NaN
    where undefined) and ``cycles``, one dict per tip amplitude: ``tip_amplitude`` [m],
    ``force_amplitude`` [N], ``displacement_amplitude`` [m], ``energy`` [J] (the loop's
    area), ``delta`` [m] and ``force`` [N] sampled at theta_i = 2 pi i / N_t (the loop),
    ``iterations``, ``residual`` (relative to k Delta_0). Raises
    :class:`asperity.InvalidInput` naming the key for a bad case (no ``[fretting]`` or
    ``[rough_contact]`` table among them)."""
    return _core.fem_structure_fretting(str(path), gmsh)


def read_reduced_model(path: str) -> dict:
    """A reduced model file as a dict: ``M``, ``K``, ``Q`` (element relative
    displacements, 3 per element: t1, t2, n), ``T`` (element tractions [Pa] to reduced
    forces [N]), ``element_area``, ``element_centroid``, ``element_frame`` (rows t1, t2, n),
    ``element_interface``, ``Fv`` (unit bolt tensions), ``bolt_elongation``,
    ``bolt_axial_stiffness``, ``bolt_preload``, ``bolt_names``, ``R`` (output-point
    recovery), ``output_names``, ``output_points``, ``source``, and ``rough``: ``None``, or
    for a model written with a ``[rough_contact]`` table (docs/rough_contact.md) a dict of the
    rough surface (``E_star``, ``G_star``, ``H`` [Pa], ``nu``, ``sigma``, ``R`` [m], ``eta``
    [1/m^2], ``summit_sigma``, ``summit_heights``: None or the measured summit-height density
    summed over, (n, 2) heights [m] from their mean and densities [1/m], ``model``), each
    element's prestress ``pressure`` [Pa] and
    ``in_contact`` (bool: at least one asperity expected in contact).
    :func:`asperity.vibration.rough_contact_on_interface` places rough-contact elements on it."""
    return _core.fem_read_reduced_model(str(path))


def rough_prestress(path: str, E_star: float, G_star: float, H: float, sigma: float | None,
                    R: float, eta: float, *, nu: float = 0.3, model: str = "bke",
                    summit_sigma: bool = False, gap=None, summit_heights=None) -> dict:
    """The bolt preloads of a reduced model file on an interface whose normal law is the
    thesis's rough flat (docs/rough_contact.md; ``asperity structure``'s ``[rough_contact]``
    step): the surfaces as combined values (SI), an optional initial ``gap`` [m] per
    interface element, an optional measured ``summit_heights`` density ((n, 2) heights [m] and
    densities, summed over instead of the Gaussian; sigma is then its standard deviation:
    give None or that value). Returns ``x`` (reduced displacement), per element ``pressure`` [Pa],
    ``separation_star``, ``real_area_ratio``, ``normal_stiffness`` and
    ``tangential_stiffness`` [Pa/m], ``in_contact``; ``interface_load`` and ``bolt_load``
    [N], ``contact_area`` and ``real_contact_area`` [m^2], ``iterations``, ``residual``.
    Tangentially frictionless while the bolts are tightened."""
    g = np.zeros(0) if gap is None else np.ascontiguousarray(gap, dtype=float).reshape(-1)
    table = None if summit_heights is None else np.ascontiguousarray(summit_heights, dtype=float)
    return _core.fem_rough_prestress(str(path), float(E_star), float(G_star), float(H),
                                     float(nu), None if sigma is None else float(sigma),
                                     float(R), float(eta), str(model), bool(summit_sigma), g,
                                     table)


def read_mesh(path: str) -> dict:
    """A gmsh ``.msh`` (4.1 or 2.2 ASCII) or Abaqus ``.inp`` mesh: ``nodes`` (n, 3) [m as in
    the file], ``blocks`` (``type``, ``connectivity``, ``body`` per element), ``bodies``."""
    return _core.fem_read_mesh(str(path))


def reduced_linear_modes(path: str, element_stiffness, count: int = 10) -> dict:
    """Elastic modes (``frequency_hz``, ``shapes``, ``rigid_body_modes``) of the reduced
    model file at ``path`` with a linear interface stiffness [Pa/m] per element direction
    (3 per element: t1, t2, n; 0 where open), multiplied by each element's area."""
    k = np.ascontiguousarray(element_stiffness, dtype=float).ravel()
    return _core.fem_reduced_linear_modes(str(path), k, int(count))
