"""Small Gmsh (MSH 2.2) meshes for the cable tests: a film whose edges carry 1-D groups.

strip(): a strip of film one element wide, x in [0, L], y in [0, W]; the row y = 0 is the 1-D
group "cable" (n segments), the row y = W the 1-D group "far", the first and last node of the
cable the point groups "anchor" and "end". square(): a flat film [0, L]^2 on an n x n grid, its
edges the 1-D groups "south" (y = 0), "north", "west" (x = 0) and "east". Node tags are the
node indices + 1; the film is the surface group "film". read_nodes41(): the nodes of a Gmsh 4.1
file etfe writes (a found form, -formfind_mesh_out). strip_model(): a cable strip model for the
design-run tests.
"""
import os

import etfe_testlib  # noqa: F401  (puts <repo>/scripts on sys.path)
from etfepy import msh22  # scripts/etfepy/msh22.py


def strip(path, L, W, n, points=None, lines=None, z=None):
    """points / lines: further point groups {name: [node, ...]} and 1-D groups {name: [(a, b), ...]};
    z: the height of each of the n + 1 columns (both rows; default flat)."""
    h = z or [0.0] * (n + 1)
    nodes = [(L * i / n, 0.0, h[i]) for i in range(n + 1)] + [(L * i / n, W, h[i]) for i in range(n + 1)]
    tris = []
    for i in range(n):
        a, b, c, d = i, i + 1, n + 2 + i, n + 1 + i
        tris += [(a, b, c), (a, c, d)]
    groups = {"cable": [(i, i + 1) for i in range(n)], "far": [(n + 1 + i, n + 2 + i) for i in range(n)]}
    groups.update(lines or {})
    pts = {"anchor": [0], "end": [n]}
    pts.update(points or {})
    msh22.write(path, nodes, points=pts, lines=groups, surfaces={"film": tris})
    return nodes


# A cable of EA 2e6 N prestressed to 500 N along a strip of film without stiffness (E = 0.001
# MPa), its ends and the far edge held: the model of the design-run tests (strip_model()).
STRIP_MODEL = """-scene structure
-mesh_file {mesh}
-material_type elastic
-material_young 1e-3
-material_poisson 0.3
-membrane_thickness 0.2
-bc_far_fix xyz
-bc_anchor_fix xyz
-bc_end_fix xyz
-cable_cable_EA 2e6
-cable_cable_prestress 500
-output_every 1
"""


def strip_model(tmp, name):
    """Writes tmp/strip.msh (strip(): 2000 x 200 mm, 10 segments) and the options file tmp/name of
    STRIP_MODEL on it; returns that file's path."""
    mesh = os.path.join(tmp, "strip.msh")
    strip(mesh, 2000.0, 200.0, 10)
    model = os.path.join(tmp, name)
    with open(model, "w") as f:
        f.write(STRIP_MODEL.format(mesh=mesh))
    return model


def square(path, L, n):
    idx = lambda i, j: j * (n + 1) + i  # noqa: E731
    nodes = [(L * i / n, L * j / n, 0.0) for j in range(n + 1) for i in range(n + 1)]
    tris = msh22.grid_triangles(n, n)
    lines = {"south": [(idx(i, 0), idx(i + 1, 0)) for i in range(n)],
             "north": [(idx(i, n), idx(i + 1, n)) for i in range(n)],
             "west": [(idx(0, j), idx(0, j + 1)) for j in range(n)],
             "east": [(idx(n, j), idx(n, j + 1)) for j in range(n)]}
    msh22.write(path, nodes, lines=lines, surfaces={"film": tris})
    return nodes


def read_nodes41(path):
    """Node tag -> (x, y, z) of a Gmsh 4.1 ASCII file."""
    lines = open(path).read().split("\n")
    i = lines.index("$Nodes")
    nb = int(lines[i + 1].split()[0])
    p, xyz = i + 2, {}
    for _ in range(nb):
        k = int(lines[p].split()[3])
        tags = [int(lines[p + 1 + j]) for j in range(k)]
        for j in range(k):
            xyz[tags[j]] = tuple(map(float, lines[p + 1 + k + j].split()))
        p += 1 + 2 * k
    return xyz
