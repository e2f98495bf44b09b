"""Stiffness and consistent mass of asperity.fem against scikit-fem (an independent FE code).

hex20 likewise against ``ElementVector(ElementHexS2())`` (the 20-node serendipity brick)
on a mesh of distorted (trilinear) hexahedra, both with 3 x 3 x 3 Gauss points
(scikit-fem's ``intorder=5``): the same rule on the same rational integrands, so again
agreement to round-off.

scikit-fem's ``ElementVector(ElementTetP2())`` (quadratic Lagrange tetrahedra, vector
valued) with its own linear-elasticity form (``skfem.models.elasticity``) and a mass form
``rho u . v``, integrated by its order-4 rule: exact for both on straight-sided
(affine) tetrahedra, as are asperity's (4-point rule of degree 2 for B^T D B, collapsed
Gauss of degree 5 for N^T N). The two must then agree to round-off: 1e-10 relative in
the Frobenius norm (sums of ~100 products per entry, condition of the element maps ~10:
~1e-14 expected; 1e-10 leaves room for summation order and still catches any wrong
shape function, node order, quadrature or DOF mapping, each an O(1) difference).

Node order (include/asperity/fem/mesh.hpp): tet10 corners 0-3, then mid-edges (0-1),
(1-2), (2-0), (0-3), (1-3), (2-3), DOF 3 node + component. scikit-fem numbers its DOFs
per mesh entity: ``basis.nodal_dofs[c, vertex]`` and ``basis.edge_dofs[c, edge]`` with the
edge's vertices in ``mesh.edges``; the test maps one numbering onto the other.
"""
from __future__ import annotations

import numpy as np
import pytest

import asperity
import asperity.fem

# scikit-fem is a test dependency (python/requirements.txt): imported, never skipped.
from skfem import (Basis, BilinearForm, ElementHexS2, ElementTetP2, ElementVector,  # noqa: E402
                   MeshHex, MeshTet, asm)
from skfem.helpers import dot  # noqa: E402
from skfem.models.elasticity import lame_parameters, linear_elasticity  # noqa: E402

E, NU, RHO = 200e9, 0.29, 7800.0
TET_EDGES = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]
# Abaqus C3D20: corners at these natural coordinates, then the mid-edges of these pairs.
HEX_CORNERS = [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
               (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)]
HEX_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
             (0, 4), (1, 5), (2, 6), (3, 7)]


def small_mesh(kind=MeshTet):
    """2 x 2 x 2 cells of uneven spacing [m] (48 tets or 8 hexahedra), the interior vertex
    moved: affine tetrahedra of several shapes and orientations, or trilinear bricks."""
    m = kind.init_tensor(np.array([0.0, 0.013, 0.03]), np.array([0.0, 0.008, 0.02]),
                         np.array([0.0, 0.011, 0.025]))
    p = m.p.copy()
    centre = np.argmin(np.linalg.norm(p - np.array([[0.013], [0.008], [0.011]]), axis=0))
    p[:, centre] += [0.0017, -0.0009, 0.0013]
    return kind(p, m.t)


def to_hex20(m: MeshHex):
    """asperity's (nodes, connectivity (m, 20)) of a serendipity mesh: each cell's corners
    put in C3D20 order by their direction from its centroid (bricks mildly distorted), the
    mid-edge nodes at edge midpoints, numbered after the vertices by scikit-fem's edges."""
    nv = m.p.shape[1]
    edge_index = {tuple(sorted(e)): k for k, e in enumerate(m.edges.T.tolist())}
    nodes = np.vstack([m.p.T, 0.5 * (m.p[:, m.edges[0]] + m.p[:, m.edges[1]]).T])
    connectivity = []
    for cell in m.t.T:
        x = m.p[:, cell]
        centre = x.mean(axis=1, keepdims=True)
        v = [int(cell[np.argmax(np.array(s) @ (x - centre))]) for s in HEX_CORNERS]
        assert len(set(v)) == 8
        connectivity.append(v + [nv + edge_index[tuple(sorted((v[a], v[b])))]
                                 for a, b in HEX_EDGES])
    return nodes, np.array(connectivity, dtype=np.int64)


def to_tet10(m: MeshTet):
    """asperity's (nodes (n, 3), connectivity (m, 10)) of the P2 mesh and, per asperity
    DOF, the scikit-fem DOF of the same node and component (for an assembled basis)."""
    nv = m.p.shape[1]
    edge_index = {tuple(sorted(e)): k for k, e in enumerate(m.edges.T.tolist())}
    nodes = np.vstack([m.p.T, 0.5 * (m.p[:, m.edges[0]] + m.p[:, m.edges[1]]).T])
    connectivity = []
    for tet in m.t.T:
        v = [int(i) for i in tet]
        x = m.p[:, v]
        if np.linalg.det(x[:, 1:] - x[:, [0]]) < 0:  # asperity wants positive orientation
            v[1], v[2] = v[2], v[1]
        mids = [nv + edge_index[tuple(sorted((v[a], v[b])))] for a, b in TET_EDGES]
        connectivity.append(v + mids)
    return nodes, np.array(connectivity, dtype=np.int64)


def dof_map(basis, nv: int, n_nodes: int) -> np.ndarray:
    out = np.empty(3 * n_nodes, dtype=np.int64)
    for node in range(n_nodes):
        for c in range(3):
            out[3 * node + c] = (basis.nodal_dofs[c, node] if node < nv
                                 else basis.edge_dofs[c, node - nv])
    return out


def skfem_matrices(m, element=None, intorder=4):
    basis = Basis(m, ElementVector(element or ElementTetP2()), intorder=intorder)
    K = asm(linear_elasticity(*lame_parameters(E, NU)), basis)

    @BilinearForm
    def mass(u, v, w):
        return RHO * dot(u, v)

    M = asm(mass, basis)
    return basis, K, M


def relative_frobenius(a, b) -> float:
    return float(np.linalg.norm((a - b).toarray()) / np.linalg.norm(b.toarray()))


def test_tet10_stiffness_and_mass_equal_scikit_fem():
    m = small_mesh()
    nodes, connectivity = to_tet10(m)
    K, M = asperity.fem.assemble(nodes, connectivity, E, NU, RHO)
    basis, K_ref, M_ref = skfem_matrices(m)
    P = dof_map(basis, m.p.shape[1], nodes.shape[0])
    assert sorted(P.tolist()) == list(range(basis.N))  # a permutation
    K_ref = K_ref.tocsr()[P][:, P]
    M_ref = M_ref.tocsr()[P][:, P]
    assert K.shape == K_ref.shape == (3 * nodes.shape[0],) * 2
    assert relative_frobenius(K, K_ref) < 1e-10
    assert relative_frobenius(M, M_ref) < 1e-10
    # The check can fail: E off by 1e-8 relative is 1e-8 in K, far above the tolerance.
    K_off, _ = asperity.fem.assemble(nodes, connectivity, E * (1 + 1e-8), NU, RHO)
    assert relative_frobenius(K_off, K_ref) > 5e-9


def test_hex20_stiffness_and_mass_equal_scikit_fem():
    m = small_mesh(MeshHex)
    nodes, connectivity = to_hex20(m)
    K, M = asperity.fem.assemble(nodes, connectivity, E, NU, RHO)
    basis, K_ref, M_ref = skfem_matrices(m, ElementHexS2(), intorder=5)
    P = dof_map(basis, m.p.shape[1], nodes.shape[0])
    assert sorted(P.tolist()) == list(range(basis.N))
    assert relative_frobenius(K, K_ref.tocsr()[P][:, P]) < 1e-10
    assert relative_frobenius(M, M_ref.tocsr()[P][:, P]) < 1e-10


def test_bad_input_is_named():
    m = small_mesh()
    nodes, connectivity = to_tet10(m)
    with pytest.raises(asperity.InvalidInput, match=r"connectivity\[0, 3\] = 999"):
        bad = connectivity.copy()
        bad[0, 3] = 999
        asperity.fem.assemble(nodes, bad, E, NU, RHO)
    with pytest.raises(asperity.InvalidInput, match=r"element 2 \(tet10, body \"body\"\) is inverted"):
        bad = connectivity.copy()
        bad[2, [1, 2]] = bad[2, [2, 1]]
        bad[2, [4, 6]] = bad[2, [6, 4]]
        bad[2, [8, 9]] = bad[2, [9, 8]]
        asperity.fem.assemble(nodes, bad, E, NU, RHO)
    with pytest.raises(asperity.InvalidInput, match="nu = 0.5"):
        asperity.fem.assemble(nodes, connectivity, E, 0.5, RHO)
    with pytest.raises(asperity.InvalidInput, match="10 \\(tet10\\) or 20 \\(hex20\\)"):
        asperity.fem.assemble(nodes, connectivity[:, :4], E, NU, RHO)
