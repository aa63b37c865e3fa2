#!/usr/bin/python3
"""The general scene's report names what it shows:
  * a probe node line gives the scene node (its row in the results' mesh/coordinates), its
    reference position in full precision (equal to that row) and its surface group: a two-layer
    cushion has two nodes at plan 0,0, one in each foil, and the line says which one it took;
    a probe element line gives the scene element;
  * a support group's reaction line says when some of its nodes are in another support group too
    (their reaction counts in both sums): on a sphere octant the three symmetry planes share its
    three corner nodes, 2 in each group; a lone support group (the cushion's rim) has no note.
"""
import math
import os
import re
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import balloon_mesh  # noqa: E402
import etfe_testlib as T  # noqa: E402

CUSHION = ["-scene", "structure", "-mesh_file", os.path.join(T.REPO, "meshes", "cushion_hexagon_2layer.msh"),
           "-membrane_thickness", 0.25, "-material_type", "elastic", "-material_young", 800, "-material_poisson", 0.43,
           "-structure_reference", "pattern", "-structure_pattern_strips", "top,bottom", "-bc_rim_fix", "xyz",
           "-structure_chambers", "air", "-chamber_air_groups", "top,bottom", "-chamber_air_pressure", 0.3,
           "-structure_probe_nodes", "0,0", "-structure_probe_elements", "0,0", "-load_increments", 4,
           "-load_tangent_predictor", "-membrane_tangent_shift", 1e-6, "-membrane_tangent_shift_adaptive"]
NODE = re.compile(r"structure: probe node 1 \(nearest plan 0, 0\): scene node (\d+) at \((\S+), (\S+), (\S+)\) mm "
                  r"in (\S+), u = \((\S+), (\S+), (\S+)\) mm")
ELEMENT = re.compile(r"structure: probe element 1 \(nearest plan 0, 0\): scene element (\d+), smin")


def cushion(etfe, chk, tmp):
    import h5py
    h5 = os.path.join(tmp, "cushion.h5")
    _, out = T.run(etfe, CUSHION + ["-output_file", h5])
    m = NODE.search(out)
    chk.check(m is not None, "cushion: the probe node line names the scene node, its position and its group: %s" % (
        [l for l in out.splitlines() if "probe node" in l][:1]))
    if not m:
        return
    node, X, group = int(m.group(1)), [float(m.group(i)) for i in (2, 3, 4)], m.group(5)
    with h5py.File(h5, "r") as f:
        coords = f["mesh/coordinates"][()]
        tris = f["mesh/triangles"][()]
        u = f["steps/%06d/displacement" % T.h5compare.written_steps(f)[-1]][node]
    at_centre = [n for n in range(len(coords)) if math.hypot(coords[n][0], coords[n][1]) < 1e-6]
    chk.check(len(at_centre) == 2 and node in at_centre,
              "cushion: 2 scene nodes at plan 0,0 (%s), the probe took node %d, the lower id" % (at_centre, node))
    chk.check(node == min(at_centre) and list(coords[node]) == X,
              "cushion: the printed position (%r, %r, %r) is row %d of mesh/coordinates to the last bit" % (
                  X[0], X[1], X[2], node))
    chk.check(group == "top" and X[2] > 0 and any(node in t for t in tris),
              "cushion: the node is on the top foil (z %.3f mm) and the line says so: %s" % (X[2], group))
    printed = [float(m.group(i)) for i in (6, 7, 8)]
    chk.check(all(abs(a - b) < 1e-4 for a, b in zip(printed, u)),
              "cushion: the printed displacement %s is that node's in the results %s" % (printed, list(u)))
    rim = [l for l in out.splitlines() if l.startswith("structure: support rim reaction")]
    chk.check(len(rim) == 1 and "another support group" not in rim[0],
              "cushion: one support group, no shared-node note: %s" % rim[:1])
    e = ELEMENT.search(out)
    chk.check(e is not None and 0 <= int(e.group(1)) < len(tris),
              "cushion: the probe element line names the scene element (%s)" % (e.group(1) if e else None))


def octant(etfe, chk, tmp):
    msh = os.path.join(tmp, "octant.msh")
    balloon_mesh.write(msh, 8, 1000.0)
    _, out = T.run(etfe, ["-scene", "structure", "-mesh_file", msh, "-material_type", "elastic", "-material_young", 800,
                          "-material_poisson", 0.3, "-membrane_thickness", 0.25, "-bc_sym_x_fix", "x",
                          "-bc_sym_y_fix", "y", "-bc_sym_z_fix", "z", "-film_skin_pressure", 2, "-load_increments", 2,
                          "-output", 0])
    lines = {g: [l for l in out.splitlines() if l.startswith("structure: support %s reaction" % g)]
             for g in ("sym_x", "sym_y", "sym_z")}
    ok = all(len(v) == 1 and "(2 of its nodes are in another support group too: nodes shared by two groups count "
             "in each)" in v[0] for v in lines.values())
    chk.check(ok, "octant: each symmetry plane's reaction line says 2 of its nodes are in another support group "
              "and count in each: %s" % (lines["sym_x"][:1]))


def main_test(etfe, chk):
    with T.scratch_dir("probe_report") as tmp:
        cushion(etfe, chk, tmp)
        octant(etfe, chk, tmp)


if __name__ == "__main__":
    T.main(main_test)
