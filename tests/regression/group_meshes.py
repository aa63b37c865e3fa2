"""Flat meshes (MSH 2.2) for the tests of per-group film properties and per-support friction.

halves(path, L, W, nx, ny, split): the rectangle [0, L] x [0, W] on an nx x ny grid of squares,
each cut into two triangles; split "x" makes the surface groups "left" (x < L/2) and "right",
split "y" the groups "bottom" (y < W/2) and "top" (nx, ny even). Node groups: "x0" (x = 0),
"x1" (x = L) and "all" (every node). Node tags are the node indices + 1.
"""
import etfe_testlib  # noqa: F401  (puts <repo>/scripts on sys.path)
from etfepy import msh22  # scripts/etfepy/msh22.py


def halves(path, L, W, nx, ny, split):
    idx = lambda i, j: j * (nx + 1) + i  # noqa: E731
    nodes = [(L * i / nx, W * j / ny, 0.0) for j in range(ny + 1) for i in range(nx + 1)]
    groups = ("left", "right") if split == "x" else ("bottom", "top")
    tris = {g: [] for g in groups}
    for j in range(ny):
        for i in range(nx):
            a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            first = (i < nx // 2) if split == "x" else (j < ny // 2)
            tris[groups[0] if first else groups[1]] += [(a, b, c), (a, c, d)]
    points = {"x0": [idx(0, j) for j in range(ny + 1)], "x1": [idx(nx, j) for j in range(ny + 1)],
              "all": list(range(len(nodes)))}
    msh22.write(path, nodes, points=points, surfaces=tris)


def two_sheets(path, L, W, nx, ny, gap):
    """Two flat sheets L x W side by side in one mesh, a gap apart in x: surface groups "sheet_a"
    ([0, L] x [0, W]) and "sheet_b" (from x = L + gap); node groups "a_nodes", "b_nodes" (each
    sheet's nodes) and "a_right", "b_right" (each sheet's edge at its largest x)."""
    nodes, tris, groups = [], {"sheet_a": [], "sheet_b": []}, {}
    for s, x0 in (("a", 0.0), ("b", L + gap)):
        base = len(nodes)
        idx = lambda i, j: base + j * (nx + 1) + i  # noqa: E731
        nodes += [(x0 + L * i / nx, W * j / ny, 0.0) for j in range(ny + 1) for i in range(nx + 1)]
        for j in range(ny):
            for i in range(nx):
                a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
                tris["sheet_" + s] += [(a, b, c), (a, c, d)]
        groups[s + "_nodes"] = list(range(base, len(nodes)))
        groups[s + "_right"] = [idx(nx, j) for j in range(ny + 1)]
    msh22.write(path, nodes, points=groups, surfaces=tris)
