#!/usr/bin/env python3
"""Writes meshes/sail_4point.msh: a four-point sail, 6 m x 6 m in plan, corners c1 (0,0) and c3
(6,6) at z = 0, c2 (6,0) and c4 (0,6) raised 1.5 m, on the hyperbolic paraboloid through the four
corners (a start for form finding), n x n squares split into triangles. Groups: the film as strips strip_1, strip_2, ... of `rows` rows
of squares each along x (the cloth widths its cutting patterns are flattened from: one pattern for
the whole doubly curved sail misfits its links by 1 %, a 1 m strip by 0.08 %), its four free edges edge_1 (c1-c2), edge_2 (c2-c3), edge_3 (c3-c4), edge_4 (c4-c1) as 1-D groups
(line elements: the cables run along them), the corners c1..c4 as point groups (the masts).
Usage: python3 meshes/sail_4point.py [n [rows [path]]] (default 12 2 meshes/sail_4point.msh)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
from etfepy import msh22  # noqa: E402  (scripts/etfepy/msh22.py)

n = int(sys.argv[1]) if len(sys.argv) > 1 else 12
rows = int(sys.argv[2]) if len(sys.argv) > 2 else 2
L, H = 6000.0, 1500.0
idx = lambda i, j: j * (n + 1) + i  # noqa: E731
nodes = []
for j in range(n + 1):
    for i in range(n + 1):
        x, y = L * i / n, L * j / n
        nodes.append((x, y, H * (x / L + y / L - 2 * x * y / (L * L))))
tris = msh22.grid_triangles(n, n)
edges = {"edge_1": [(idx(i, 0), idx(i + 1, 0)) for i in range(n)],
         "edge_2": [(idx(n, j), idx(n, j + 1)) for j in range(n)],
         "edge_3": [(idx(n - i, n), idx(n - i - 1, n)) for i in range(n)],
         "edge_4": [(idx(0, n - j), idx(0, n - j - 1)) for j in range(n)]}
corners = {"c1": idx(0, 0), "c2": idx(n, 0), "c3": idx(n, n), "c4": idx(0, n)}
strips = ["strip_%d" % (k + 1) for k in range((n + rows - 1) // rows)]
path = sys.argv[3] if len(sys.argv) > 3 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "sail_4point.msh")
# Row of squares r holds triangles 2 n r .. 2 n (r + 1) - 1, so each strip's triangles are one run.
surfaces = {s: tris[2 * n * rows * k:2 * n * rows * (k + 1)] for k, s in enumerate(strips)}
msh22.write(path, nodes, points={k: [v] for k, v in corners.items()}, lines=edges, surfaces=surfaces)
print(path)
