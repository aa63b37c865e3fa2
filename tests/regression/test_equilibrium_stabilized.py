"""A run that says "complete" is in equilibrium: the viscous stabilization must not carry the load
(docs/stabilization.md).

* A flat square film (1 m, 10 x 10 cells) with no support under 0.3 kPa of snow is refused before
  the run, the message naming the six free rigid motions; on rollers (-bc_boundary_fix z) it is
  refused naming the translations along x and y and the rotation about z. With the check off
  (-load_check_supports false) the unsupported film fails "not in equilibrium" (the stabilizing
  force carries all the snow).
* The hypar canopy of the worked example, form-found, laid on from its patterns and held at its
  four corners only (drawn 14 then 20 mm outward, heights held), then wind suction and snow:
  the film's free edges cannot carry the wind, the stabilization would (today it "completes"
  with the stabilizing force doing 11x the film's work and the corners taking 12 % of the snow).
  The increments where it would are cut back; once the cut-backs are spent the run ends non-zero,
  its results status "failed: not in equilibrium", naming the increment, the share and the node.
* The worked example itself (options/structure/hypar_canopy.opts), whose laying-on increment
  needs the stabilization, completes: the stabilizing force carried at most 1e-2 of the forces in
  play (measured 1.1e-3). With -load_stabilize_work_max below its work share it fails "not in
  equilibrium" over the run.
"""
import os
import re
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402
import pattern_meshes  # noqa: E402

MATERIAL = ["-membrane_thickness", 0.25, "-material_type", "plastic", "-material_young", 800, "-material_poisson", 0.43,
            "-material_yield", "13.28,23.04", "-material_hardening", "80.5,3.0",
            "-options_file", os.path.join(T.OPTIONS, "solvers", "mumps_lu.opts")]
CANOPY = os.path.join(T.OPTIONS, "structure", "hypar_canopy.opts")


def square(tmp):
    """A flat 1 m square (z = 0), surface group film, curve groups boundary, left, right, bottom, top."""
    nodes, tris, sides = pattern_meshes.grid(10, 10, lambda u, v: ((u - 0.5) * 1000.0, (v - 0.5) * 1000.0, 0.0))
    groups = {"film": (2, list(range(len(tris)))), "boundary": (1, sum(sides.values(), []))}
    groups.update({k: (1, v) for k, v in sides.items()})
    path = os.path.join(tmp, "square.msh")
    pattern_meshes.write_msh(path, nodes, tris, groups)
    return path


def canopy_options_without_supports():
    """hypar_canopy.opts as command-line arguments, without its frame supports, mesh and results."""
    args = []
    with open(CANOPY) as f:
        for line in f:
            line = line.split("#")[0].strip()
            if not line or line.startswith(("-bc_boundary", "-mesh_file", "-output_file")):
                continue
            key, _, value = line.partition(" ")
            if key == "-options_file":
                value = os.path.join(T.REPO, value)
            args += [key] + ([value] if value else [])
    return args


def status_of(etfe, h5):
    rc, out = T.run(etfe, ["-results_status", h5], expect_fail=None)
    return out.strip().split(": ", 1)[-1] if ": " in out else out.strip()


def test(etfe, chk):
    with T.scratch_dir("equilibrium") as tmp:
        msh = square(tmp)
        base = ["-scene", "structure", "-mesh_file", msh, "-film_film_snow", 0.3, "-load_increments", 5] + MATERIAL
        # 1. No support: refused before the first increment, the six motions named.
        rc, out = T.run(etfe, base + ["-output_file", os.path.join(tmp, "free.h5")], expect_fail=None)
        msg = T.error_message(out) or out
        chk.check(rc != 0 and "free to move as a rigid body" in msg and "step     1" not in out,
                  "unsupported film refused before the run: %s" % msg[:160])
        named = [m for m in ("translation along x", "translation along y", "translation along z", "rotation about x",
                             "rotation about y", "rotation about z") if m in msg]
        chk.check(len(named) == 6, "the six free motions named (%d: %s)" % (len(named), ", ".join(named)))
        chk.check("-bc_<group>_fix" in msg and "boundary" in msg, "the way out names -bc_<group>_fix and the groups")
        # 2. On rollers: the heights held, the plane motions free.
        rc, out = T.run(etfe, base + ["-bc_boundary_fix", "z", "-output_file", os.path.join(tmp, "rollers.h5")],
                        expect_fail=None)
        msg = T.error_message(out) or out
        chk.check(rc != 0 and all(m in msg for m in ("translation along x", "translation along y", "rotation about z"))
                  and "translation along z" not in msg and "rotation about x" not in msg,
                  "roller rim refused naming translation x, y and rotation about z: %s" % msg[:200])
        chk.check("-bc_" in msg and "_fix xyz" in msg, "the way out: add components to a -bc_<group>_fix")
        # ... and with the check off, the stabilization would carry the snow: not in equilibrium.
        h5 = os.path.join(tmp, "free_run.h5")
        rc, out = T.run(etfe, base + ["-load_check_supports", "false", "-output_file", h5], expect_fail=None)
        st = status_of(etfe, h5)
        chk.check(rc != 0 and st.startswith("failed: not in equilibrium: increment 1 "),
                  "unsupported film with the check off: status %r" % st[:120])

        # 3. The hypar canopy held at its corners only.
        ff = os.path.join(tmp, "hypar_ff.msh")
        T.run(etfe, ["-options_file", os.path.join(T.OPTIONS, "structure", "hypar_formfind.opts"), "-formfind_monitor",
                     0, "-formfind_mesh_out", ff, "-output_file", os.path.join(tmp, "hypar_ff.h5")])
        corners = []
        for k, (sx, sy) in enumerate([(-1, -1), (1, -1), (1, 1), (-1, 1)], start=1):
            ux = ",".join("%g" % (sx * d) for d in (10, 14.142, 14.142, 14.142))
            uy = ",".join("%g" % (sy * d) for d in (10, 14.142, 14.142, 14.142))
            corners += ["-bc_corner_%d_ux" % k, ux, "-bc_corner_%d_uy" % k, uy, "-bc_corner_%d_fix" % k, "z"]
        h5 = os.path.join(tmp, "corners.h5")
        rc, out = T.run(etfe, canopy_options_without_supports() + corners +
                        ["-mesh_file", ff, "-film_all_snow", "0,0,0,0.6", "-output_file", h5], expect_fail=None)
        st = status_of(etfe, h5)
        chk.check(rc != 0 and st.startswith("failed: not in equilibrium"), "corner-held canopy: status %r" % st[:100])
        m = re.search(r"increment (\d+) \(load time ([0-9.]+) -> ([0-9.]+)[^)]*\).*?carrying ([0-9.e+-]+) of the forces in "
                      r"play.*?at node (\d+), \(", st)
        chk.check(m is not None and float(m.group(4)) > 0.1,
                  "the status names the increment, the share (> 0.1) and the node: %s"
                  % str(m.groups() if m else st[:300]))
        chk.check("free edge" in st and "-load_stabilize_force_max" in st and "-load_increments" in st,
                  "the status names the likely cause and the ways out")

        # 4. The worked example: its stabilized laying-on is harmless and accepted.
        h5 = os.path.join(tmp, "canopy.h5")
        args = ["-options_file", CANOPY, "-mesh_file", ff, "-output_file", h5]
        rc, out = T.run(etfe, args, expect_fail=None)
        st = status_of(etfe, h5)
        chk.check(rc == 0 and st == "complete", "hypar canopy: status %r" % st)
        m = re.search(r"etfe: equilibrium: the stabilizing force did ([0-9.e+-]+) of the work .*? carried at most "
                      r"([0-9.e+-]+) of the forces in play", out)
        chk.check(m is not None and 0 < float(m.group(2)) < 1e-2 and float(m.group(1)) < 1e-2,
                  "hypar canopy: stabilized, its force's share of the forces in play and of the work below 1e-2 (%s)"
                  % str(m.groups() if m else "no equilibrium line"))
        # ... and judged by a work share below its own, the run fails at its end.
        h5 = os.path.join(tmp, "canopy_strict.h5")
        rc, out = T.run(etfe, args[:-1] + [h5, "-load_stabilize_work_max", 1e-6], expect_fail=None)
        st = status_of(etfe, h5)
        chk.check(rc != 0 and st.startswith("failed: not in equilibrium: over the run"),
                  "hypar canopy with -load_stabilize_work_max 1e-6: status %r" % st[:80])


T.main(test)
