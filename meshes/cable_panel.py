#!/usr/bin/env python3
"""Writes meshes/cable_panel.msh: a flat single-layer ETFE panel reinforced by a cable net
(docs/cables.md): a rectangle a x b in plan (corner at the origin, z = 0) in a frame, cables
cables_x along x and cables_y along y at equal spacing (bays), each bay n x n squares split into
triangles, so every cable runs along lines of the film's mesh through its nodes. Groups: the film
`film` (2-D), the frame `frame` (1-D, the whole boundary: hold it or draw it), the cables
`cable_x1`, `cable_x2`, ... (at y = b k / (cables_x + 1)) and `cable_y1`, ... (at x = a k /
(cables_y + 1)) as 1-D groups of line elements from frame to frame (a cable crosses the others at
film nodes; each stays one open chain), and the frame's corners `corner_1`..`corner_4`.
Usage: python3 meshes/cable_panel.py [n [a,b [cables_x,cables_y [path]]]]
(default 8 3000,3000 2,2 meshes/cable_panel.msh)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
from etfepy import msh22  # noqa: E402  (scripts/etfepy/msh22.py)

n = int(sys.argv[1]) if len(sys.argv) > 1 else 8
a, b = (float(v) for v in (sys.argv[2] if len(sys.argv) > 2 else "3000,3000").split(","))
kx, ky = (int(v) for v in (sys.argv[3] if len(sys.argv) > 3 else "2,2").split(","))
path = sys.argv[4] if len(sys.argv) > 4 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "cable_panel.msh")
nx, ny = n * (ky + 1), n * (kx + 1)  # squares along x (ky + 1 bays between the y cables) and along y
idx = lambda i, j: j * (nx + 1) + i  # noqa: E731
nodes = [(a * i / nx, b * j / ny, 0.0) for j in range(ny + 1) for i in range(nx + 1)]
tris = msh22.grid_triangles(nx, ny)
lines = {"frame": [(idx(i, 0), idx(i + 1, 0)) for i in range(nx)] + [(idx(nx, j), idx(nx, j + 1)) for j in range(ny)]
         + [(idx(i + 1, ny), idx(i, ny)) for i in range(nx)] + [(idx(0, j + 1), idx(0, j)) for j in range(ny)]}
for k in range(1, kx + 1):
    lines["cable_x%d" % k] = [(idx(i, k * n), idx(i + 1, k * n)) for i in range(nx)]
for k in range(1, ky + 1):
    lines["cable_y%d" % k] = [(idx(k * n, j), idx(k * n, j + 1)) for j in range(ny)]
corners = {"corner_1": idx(0, 0), "corner_2": idx(nx, 0), "corner_3": idx(nx, ny), "corner_4": idx(0, ny)}
msh22.write(path, nodes, points={k: [v] for k, v in corners.items()}, lines=lines, surfaces={"film": tris})
print(path)
