"""Finite elements of elastic bodies: quadratic solids, stiffness and consistent mass.

The Python face of the C++ layer ``fem/`` (docs/structures.md); SI units throughout.

* :func:`assemble` - ``(K, M)`` as scipy.sparse matrices for one isotropic body meshed
  with 10-node tetrahedra or 20-node hexahedra (node order of
  ``include/asperity/fem/mesh.hpp``: tet10 corners 0-3 then mid-edges 0-1, 1-2, 2-0,
  0-3, 1-3, 2-3; hex20 as Abaqus C3D20). DOF ``3 * node + component``.
"""
from __future__ import annotations

import numpy as np

from . import _core

_f = _core._fem

__all__ = ["assemble"]


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
