"""The surface groups of a Gmsh mesh file (ASCII MSH 2.2 or 4.1) and which element of a results file
each holds, for the design run's resistance per surface group (docs/design-run.md).

The results file holds no group names, and etfe renumbers the nodes it reads (those no triangle
uses are dropped), so a results triangle is matched to the file's by its three nodes' coordinates,
which the results file holds as read.
"""
import numpy as np


class MeshGroupsError(Exception):
    pass


def _sections(path):
    with open(path, errors="replace") as f:
        lines = f.read().splitlines()
    out, k = {}, 0
    while k < len(lines):
        s = lines[k].strip()
        if s.startswith("$") and not s.startswith("$End"):
            name, j = s[1:], k + 1
            while j < len(lines) and lines[j].strip() != "$End" + name:
                j += 1
            out[name] = lines[k + 1:j]
            k = j
        k += 1
    return out


def read(path):
    """({surface group: [(x, y, z) x 3 per triangle]}) of an ASCII Gmsh file."""
    sec = _sections(path)
    if "MeshFormat" not in sec or not sec["MeshFormat"]:
        raise MeshGroupsError("%s is no ASCII Gmsh mesh ($MeshFormat missing): resistance per surface group reads "
                              "the groups from a .msh file (MSH 2.2 or 4.1, ASCII)" % path)
    version, binary = sec["MeshFormat"][0].split()[:2]
    if binary != "0":
        raise MeshGroupsError("%s is a binary Gmsh file: resistance per surface group reads ASCII .msh (gmsh -format "
                              "msh41 without -bin)" % path)
    names = {}
    for line in sec.get("PhysicalNames", [])[1:]:
        dim, tag, name = line.split(None, 2)
        if dim == "2":
            names[int(tag)] = name.strip().strip('"')
    nodes = {}
    tris = {}  # physical tag -> [node tags]
    if version.startswith("2"):
        for line in sec.get("Nodes", [])[1:]:
            t = line.split()
            nodes[int(t[0])] = (float(t[1]), float(t[2]), float(t[3]))
        for line in sec.get("Elements", [])[1:]:
            t = [int(x) for x in line.split()]
            if t[1] == 2 and t[2] >= 1:  # a 3-node triangle; first tag is the physical one
                tris.setdefault(t[3], []).append(t[3 + t[2]:6 + t[2]])
    elif version.startswith("4"):
        body = sec.get("Nodes", [])
        k = 1
        while k < len(body):
            _, _, _, n = (int(x) for x in body[k].split())
            tags = [int(body[k + 1 + i]) for i in range(n)]
            for i, tag in enumerate(tags):
                x = body[k + 1 + n + i].split()
                nodes[tag] = (float(x[0]), float(x[1]), float(x[2]))
            k += 1 + 2 * n
        surf_phys = {}
        ent = sec.get("Entities", [])
        if ent:
            npt, ncu, nsu = (int(x) for x in ent[0].split()[:3])
            for line in ent[1 + npt + ncu:1 + npt + ncu + nsu]:
                t = line.split()
                nphys = int(t[7])
                surf_phys[int(t[0])] = [int(x) for x in t[8:8 + nphys]]
        body = sec.get("Elements", [])
        k = 1
        while k < len(body):
            dim, etag, etype, n = (int(x) for x in body[k].split())
            if dim == 2 and etype == 2:
                for p in surf_phys.get(etag, []):
                    tris.setdefault(p, []).extend([int(x) for x in body[k + 1 + i].split()[1:4]]
                                                  for i in range(n))
            k += 1 + n
    else:
        raise MeshGroupsError("%s: Gmsh format %s, neither 2.2 nor 4.1" % (path, version))
    out = {}
    for tag, tl in tris.items():
        name = names.get(tag, str(tag))
        out.setdefault(name, []).extend(tuple(nodes[n] for n in t) for t in tl)
    return out


def element_groups(path, X, tri):
    """{surface group: bool array over the results triangles (X, tri: mesh/coordinates, mesh/triangles)}
    plus "all"; a group whose triangle is not in the results (another mesh) is refused."""
    key = {}
    for e, t in enumerate(tri):
        key[frozenset(tuple(X[n]) for n in t)] = e
    res = {"all": np.ones(len(tri), dtype=bool)}
    for name, tl in read(path).items():
        mask = np.zeros(len(tri), dtype=bool)
        for t in tl:
            e = key.get(frozenset(t))
            if e is None:
                raise MeshGroupsError("%s: a triangle of group %s at (%g, %g, %g) is not in the results' mesh: the "
                                      "resistance groups are read from another mesh than the run's"
                                      % (path, name, *np.mean(t, axis=0)))
            mask[e] = True
        res[name] = mask
    return res
