#!/usr/bin/env python3
"""Writes the Abaqus test meshes of tests/fem/mesh_io_test.cpp, independently of asperity.

cube_c3d10.inp: a 10 mm cube split into five 10-node tetrahedra (four corner tetrahedra
of volume 1/6 and a central one of 1/3 of the cube), nodes labelled sparsely (corners
1-8, mid-edge nodes from 101) plus a node 999 used by no element; two bodies (ELSET=
STEEL, CORE on *ELEMENT), node and element sets, GENERATE, a set naming another set,
mixed-case keywords, a keyword and an element continued on the next line, comments.
block_c3d20r.inp: one 20-node hexahedron (C3D20R) of 10 x 20 x 30 mm in *PART "Block",
with one *INSTANCE translated by (100, 0, 0) mm and then rotated by 90 degrees about z.
Coordinates in m. Run: python3 tests/data/fem/make_inp.py (byte-for-byte reproducible).
"""
import itertools
import os

HERE = os.path.dirname(os.path.abspath(__file__))
L = 0.01
corner = {}  # label -> (x, y, z)
for label, (i, j, k) in enumerate(itertools.product((0, 1), repeat=3), start=1):
    corner[label] = (i * L, j * L, k * L)
by_pos = {v: k for k, v in corner.items()}


def c(i, j, k):
    return by_pos[(i * L, j * L, k * L)]


tets = [
    (c(0, 0, 0), c(1, 0, 0), c(0, 1, 0), c(0, 0, 1)),
    (c(1, 1, 0), c(1, 0, 0), c(0, 1, 0), c(1, 1, 1)),
    (c(1, 0, 1), c(1, 0, 0), c(0, 0, 1), c(1, 1, 1)),
    (c(0, 1, 1), c(0, 1, 0), c(0, 0, 1), c(1, 1, 1)),
    (c(1, 0, 0), c(0, 1, 0), c(0, 0, 1), c(1, 1, 1)),  # central
]


def det(t):
    p = [corner[n] for n in t]
    a = [p[1][m] - p[0][m] for m in range(3)]
    b = [p[2][m] - p[0][m] for m in range(3)]
    d = [p[3][m] - p[0][m] for m in range(3)]
    return (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0])
            + a[2] * (b[0] * d[1] - b[1] * d[0]))


# Abaqus C3D10: corners 1-2-3 anticlockwise seen from 4 (positive volume).
tets = [t if det(t) > 0 else (t[0], t[2], t[1], t[3]) for t in tets]
mid = {}  # frozenset(corner labels) -> label
nodes = dict(corner)
edges = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]  # C3D10 nodes 5-10
elements = []
for t in tets:
    conn = list(t)
    for a, b in edges:
        key = frozenset((t[a], t[b]))
        if key not in mid:
            mid[key] = 101 + len(mid)
            pa, pb = corner[t[a]], corner[t[b]]
            nodes[mid[key]] = tuple((pa[m] + pb[m]) / 2 for m in range(3))
        conn.append(mid[key])
    elements.append(conn)
nodes[999] = (1.0, 1.0, 1.0)  # used by no element

bottom = sorted(n for n, p in nodes.items() if p[2] == 0.0)
with open(os.path.join(HERE, "cube_c3d10.inp"), "w") as f:
    f.write("*Heading\n** A 10 mm cube of five C3D10 tetrahedra (make_inp.py)\n")
    f.write("*NODE, NSET=ALLNODES\n")
    for n in sorted(nodes):
        f.write("%d, %.17g, %.17g, %.17g\n" % ((n,) + nodes[n]))
    f.write("*Element, type=C3D10,\n    elset=Steel\n")
    for e, conn in enumerate(elements[:4], start=1):
        ints = [e] + conn
        if e == 2:  # continued over two lines
            f.write(", ".join(map(str, ints[:6])) + ",\n" + ", ".join(map(str, ints[6:])) + "\n")
        else:
            f.write(", ".join(map(str, ints)) + "\n")
    f.write("**\n** the central tetrahedron\n*ELEMENT, TYPE=C3D10, ELSET=CORE\n")
    f.write(", ".join(map(str, [5] + elements[4])) + "\n")
    f.write("*Nset, nset=Bottom\n")
    for i in range(0, len(bottom), 8):
        f.write(", ".join(map(str, bottom[i:i + 8])) + ",\n")
    f.write("*NSET, NSET=CORNERS, GENERATE\n1, 8, 1\n")
    f.write("*NSET, NSET=BOTTOM_AND_TOP_CORNER\nbottom, 8\n")
    f.write("*ELSET, ELSET=ALL, GENERATE\n1, 5\n")
    f.write("*Elset, elset=ODD\n1, 3, 5\n")
    f.write("*Solid Section, elset=ALL, material=Steel\n,\n")
    f.write("*Material, name=Steel\n*Elastic\n200e9, 0.29\n")

# One C3D20R brick 10 x 20 x 30 mm: corners in Abaqus order, then mid-edge nodes.
size = (0.01, 0.02, 0.03)
hc = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
hcorners = [tuple(s * q for s, q in zip(size, p)) for p in hc]
hedges = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
          (0, 4), (1, 5), (2, 6), (3, 7)]
hnodes = hcorners + [tuple((hcorners[a][m] + hcorners[b][m]) / 2 for m in range(3))
                     for a, b in hedges]
with open(os.path.join(HERE, "block_c3d20r.inp"), "w") as f:
    f.write("*HEADING\nOne C3D20R brick in a part, instanced once (make_inp.py)\n")
    f.write("*Part, name=Block\n*Node\n")
    for i, p in enumerate(hnodes, start=1):
        f.write("%d, %.17g, %.17g, %.17g\n" % ((i,) + p))
    f.write("*Element, type=C3D20R\n")
    ints = list(range(1, 21))
    f.write("1, " + ", ".join(map(str, ints[:15])) + ",\n" + ", ".join(map(str, ints[15:])) + "\n")
    f.write("*Nset, nset=Base\n1, 2, 3, 4, 9, 10, 11, 12\n*End Part\n")
    f.write("*Assembly, name=Assembly\n*Instance, name=Block-1, part=Block\n")
    f.write("0.1, 0., 0.\n0.1, 0., 0., 0.1, 0., 1., 90.\n*End Instance\n")
    f.write("*Node\n1, 0., 0., 0.\n*Nset, nset=RP\n1\n")
    f.write("*Nset, nset=Corner, instance=Block-1\n7\n*End Assembly\n")
