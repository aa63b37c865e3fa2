"""Small surface meshes for the cutting-pattern tests, written as Gmsh 2.2 ASCII with
physical groups, so that the tests need no Gmsh. A mesh is (nodes, triangles, groups): nodes a
list of (x, y, z) in mm, triangles 0-based node triples, groups {name: (dim, [elements])} with
dim 2 (triangle ids: a strip) or 1 (node pairs: a named curve). cutpattern() and link_errors(): a
cutting-pattern run on such a mesh and the link errors it prints, per strip."""
import math
import os
import re

from etfe_testlib import run  # (and <repo>/scripts on sys.path)
from etfepy import msh22  # scripts/etfepy/msh22.py

NUM = r"([-+]?\d+\.?\d*(?:e[-+]?\d+)?)"


def grid(nx, ny, f):
    """The unit square in nx x ny cells (alternating diagonals) mapped through f(u, v) -> (x, y, z).
    Returns nodes, triangles and the sides as node-pair lists (left u=0, right u=1, bottom v=0,
    top v=1)."""
    nodes = [f(i / nx, j / ny) for j in range(ny + 1) for i in range(nx + 1)]
    idx = lambda i, j: j * (nx + 1) + i
    tris = []
    for j in range(ny):
        for i in range(nx):
            a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            if (i + j) % 2 == 0:
                tris += [(a, b, c), (a, c, d)]
            else:
                tris += [(a, b, d), (b, c, d)]
    sides = {"left": [(idx(0, j), idx(0, j + 1)) for j in range(ny)],
             "right": [(idx(nx, j), idx(nx, j + 1)) for j in range(ny)],
             "bottom": [(idx(i, 0), idx(i + 1, 0)) for i in range(nx)],
             "top": [(idx(i, ny), idx(i + 1, ny)) for i in range(nx)]}
    return nodes, tris, sides


def cylinder_strip(R=500.0, angle=1.2, length=1000.0, nx=12, ny=6):
    """A strip of a cylinder (radius R) across its axis: developable."""
    return grid(nx, ny, lambda u, v: (R * math.cos(angle * u), R * math.sin(angle * u), length * v))


def cone_strip(r0=300.0, r1=900.0, half_angle=0.5, angle=1.0, nx=10, ny=6):
    """A strip of a cone (apex at the origin, half opening angle half_angle) between the slant
    distances r0 and r1: developable."""
    s, c = math.sin(half_angle), math.cos(half_angle)
    def f(u, v):
        r = r0 + (r1 - r0) * v
        return (r * s * math.cos(angle * u), r * s * math.sin(angle * u), r * c)
    return grid(nx, ny, f)


def sphere_strip(R=1000.0, length=1000.0, width=400.0, nx=16, ny=8):
    """A strip of a sphere along a great circle: length along it, width across (both arc
    lengths): doubly curved."""
    def f(u, v):
        lon = (u - 0.5) * length / R
        lat = (v - 0.5) * width / R
        return (R * math.cos(lat) * math.cos(lon), R * math.cos(lat) * math.sin(lon), R * math.sin(lat))
    return grid(nx, ny, f)


def hypar(size=1000.0, rise=200.0, n=8):
    """A hyperbolic paraboloid z = rise * x y / (size/2)^2 over a square: doubly curved (negative)."""
    h = size / 2
    return grid(n, n, lambda u, v: ((u - 0.5) * size, (v - 0.5) * size,
                                    rise * (u - 0.5) * (v - 0.5) * 4))


def pyramid(a=500.0, h=300.0):
    """Four triangles over a square base of side 2a, apex h above its centre."""
    nodes = [(-a, -a, 0.0), (a, -a, 0.0), (a, a, 0.0), (-a, a, 0.0), (0.0, 0.0, h)]
    tris = [(0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)]
    return nodes, tris, {}


def write_msh(path, nodes, tris, groups):
    """Gmsh 2.2 ASCII; every triangle carries the physical tag of its (first) dim-2 group, 0 for
    none; each dim-1 group is written as line elements."""
    names = sorted(groups)
    tag = {n: k + 1 for k, n in enumerate(names)}
    phys = [0] * len(tris)
    for n in names:
        dim, items = groups[n]
        if dim == 2:
            for e in items:
                if phys[e] == 0:
                    phys[e] = tag[n]
    elems = []
    for n in names:
        dim, items = groups[n]
        if dim == 1:
            elems += [(1, tag[n], tag[n], ab) for ab in items]
    elems += [(2, p, max(p, 1), t) for t, p in zip(tris, phys)]
    # A triangle in two dim-2 groups (overlapping strips) is written twice, once per group.
    for n in names:
        dim, items = groups[n]
        if dim == 2:
            for e in items:
                if phys[e] != tag[n]:
                    elems.append((2, tag[n], tag[n], tris[e]))
    msh22.write_elements(path, nodes, [(groups[n][0], tag[n], n) for n in names], elems)


def read_msh41_nodes(path):
    """{tag: (x, y, z)} of an ASCII MSH 4.1 file (as etfe writes its patterns)."""
    with open(path) as f:
        lines = f.read().split("\n")
    k = lines.index("$Nodes") + 1
    nblocks, nn = int(lines[k].split()[0]), int(lines[k].split()[1])
    k += 1
    out = {}
    for _ in range(nblocks):
        cnt = int(lines[k].split()[3])
        tags = [int(t) for t in lines[k + 1:k + 1 + cnt]]
        for j, t in enumerate(tags):
            out[t] = tuple(float(x) for x in lines[k + 1 + cnt + j].split()[:3])
        k += 1 + 2 * cnt
    assert len(out) == nn
    return out


def tube(R=300.0, length=600.0, n=12, ny=3):
    """A closed ring of a cylinder (the grid's last column joined to its first): not a disc."""
    nodes, tris, _ = grid(n, ny, lambda u, v: (R * math.cos(2 * math.pi * u), R * math.sin(2 * math.pi * u),
                                              length * v))
    join = lambda k: k - n if (k % (n + 1)) == n else k
    tris = [tuple(join(k) for k in t) for t in tris]
    return nodes, tris, {}


def t_junction():
    """Three triangles on one edge (a fin on a flat pair): not a manifold surface."""
    nodes = [(0.0, 0.0, 0.0), (0.0, 100.0, 0.0), (100.0, 50.0, 0.0), (-100.0, 50.0, 0.0), (0.0, 50.0, 100.0)]
    return nodes, [(0, 2, 1), (0, 1, 3), (0, 1, 4)], {}


def bowtie():
    """Two triangles meeting at one node only."""
    nodes = [(0.0, 0.0, 0.0), (100.0, -50.0, 0.0), (100.0, 50.0, 0.0), (-100.0, 50.0, 0.0), (-100.0, -50.0, 0.0)]
    return nodes, [(0, 1, 2), (0, 3, 4)], {}


def msh41_point_groups(path):
    """{group name: [(x, y, z), ...]} of the node sets etfe writes as point groups (MSH 4.1)."""
    with open(path) as f:
        lines = f.read().split("\n")
    k = lines.index("$PhysicalNames") + 1
    names = {}
    for line in lines[k + 1:k + 1 + int(lines[k])]:
        dim, tag, name = line.split(None, 2)
        if dim == "0":
            names[int(tag)] = name.strip('"')
    k = lines.index("$Entities") + 1
    npoints = int(lines[k].split()[0])
    out = {n: [] for n in names.values()}
    for line in lines[k + 1:k + 1 + npoints]:
        f = line.split()
        xyz = tuple(float(x) for x in f[1:4])
        for t in f[5:5 + int(f[4])]:
            if int(t) in names:
                out[names[int(t)]].append(xyz)
    return out


def msh41_turn_half(path, out_path):
    """Writes the MSH 4.1 file turned by 180 degrees about the z axis through its bounding-box
    centre (points of $Entities and coordinates of $Nodes)."""
    with open(path) as f:
        lines = f.read().split("\n")
    pts = list(read_msh41_nodes(path).values())
    cx = 0.5 * (min(p[0] for p in pts) + max(p[0] for p in pts))
    cy = 0.5 * (min(p[1] for p in pts) + max(p[1] for p in pts))
    turn = lambda f: ["%.17g" % (2 * cx - float(f[0])), "%.17g" % (2 * cy - float(f[1]))] + f[2:]
    k = lines.index("$Entities") + 1
    for j in range(k + 1, k + 1 + int(lines[k].split()[0])):
        f = lines[j].split()
        lines[j] = " ".join(f[:1] + turn(f[1:]))
    k = lines.index("$Nodes") + 1
    nblocks = int(lines[k].split()[0])
    k += 1
    for _ in range(nblocks):
        cnt = int(lines[k].split()[3])
        for j in range(k + 1 + cnt, k + 1 + 2 * cnt):
            lines[j] = " ".join(turn(lines[j].split()))
        k += 1 + 2 * cnt
    with open(out_path, "w") as f:
        f.write("\n".join(lines))


def combine(parts):
    """One mesh of several strips: parts = [(name, (nodes, tris, sides), (dx, dy, dz))], each
    shifted by its offset (apart, so no two nodes meet). Returns nodes, triangles, groups."""
    nodes, tris, groups = [], [], {}
    for name, (n, t, _), off in parts:
        base, first = len(nodes), len(tris)
        nodes += [(p[0] + off[0], p[1] + off[1], p[2] + off[2]) for p in n]
        tris += [tuple(base + k for k in tri) for tri in t]
        groups[name] = (2, list(range(first, len(tris))))
    return nodes, tris, groups


def cutpattern(etfe, tmp, name, mesh_file, args, expect_fail=False):
    """etfe -analysis cutpattern on mesh_file (results tmp/name.h5): its printed output."""
    return run(etfe, ["-analysis", "cutpattern", "-mesh_file", mesh_file, "-output_file",
                      os.path.join(tmp, name + ".h5")] + list(args), expect_fail=expect_fail)[1]


def link_errors(out):
    """{strip: its largest link error} from a cutting-pattern run's output."""
    return {m.group(1): float(m.group(2)) for m in re.finditer(
        r"cutpattern: strip (\S+): \d+ nodes, \d+ links, .*?link error max %s" % NUM, out)}
