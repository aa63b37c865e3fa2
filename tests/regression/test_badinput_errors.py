#!/usr/bin/python3
"""Bad input and failed runs: every case must exit non-zero with an error message that names the
offending thing and the way out, without the source location (only -etfe_traceback shows it), and
must not leave a results file whose status is "complete". A run that
diverges with its cut-backs exhausted must name the increment and the SNES reason, and leave a
results file with status "failed: ..." holding the last converged step (serial and 2 ranks)."""
import os
import re
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402


def write_msh(path, extra_triangles=()):
    """A 1000 x 1000 mm square, Gmsh MSH 4.1, physical groups left/right/bottom/top (lines) and
    film (surface): 5 nodes (node 5 mid-bottom), 3 valid triangles plus extra_triangles."""
    pts = {1: (0, 0), 2: (1000, 0), 3: (1000, 1000), 4: (0, 1000)}
    tris = [(1, 5, 4), (5, 3, 4), (5, 2, 3)] + list(extra_triangles)
    lines = [(1, [(1, 5), (5, 2)]), (2, [(2, 3)]), (3, [(3, 4)]), (4, [(4, 1)])]
    s = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat",
         "$PhysicalNames", "5", '1 1 "bottom"', '1 2 "right"', '1 3 "top"', '1 4 "left"', '2 5 "film"',
         "$EndPhysicalNames",
         "$Entities", "4 4 1 0",
         "1 0 0 0 0", "2 1000 0 0 0", "3 1000 1000 0 0", "4 0 1000 0 0",
         "1 0 0 0 1000 0 0 1 1 2 1 -2",
         "2 1000 0 0 1000 1000 0 1 2 2 2 -3",
         "3 0 1000 0 1000 1000 0 1 3 2 3 -4",
         "4 0 0 0 0 1000 0 1 4 2 4 -1",
         "1 0 0 0 1000 1000 0 1 5 4 1 2 3 4",
         "$EndEntities",
         "$Nodes", "5 5 1 5"]
    for k in range(1, 5):
        s += ["0 %d 0 1" % k, str(k), "%g %g 0" % pts[k]]
    s += ["1 1 0 1", "5", "500 0 0", "$EndNodes"]
    nel = sum(len(l) for _, l in lines) + len(tris)
    s += ["$Elements", "%d %d 1 %d" % (len(lines) + 1, nel, nel)]
    tag = 1
    for curve, els in lines:
        s.append("1 %d 1 %d" % (curve, len(els)))
        for e in els:
            s.append("%d %d %d" % ((tag,) + e))
            tag += 1
    s.append("2 1 2 %d" % len(tris))
    for e in tris:
        s.append("%d %d %d %d" % ((tag,) + e))
        tag += 1
    s.append("$EndElements")
    with open(path, "w") as f:
        f.write("\n".join(s) + "\n")


def main_test(etfe, chk):
    with T.scratch_dir("badinput") as tmp:
        good, zero, badid = (os.path.join(tmp, n + ".msh") for n in ("good", "zero_area", "bad_node"))
        write_msh(good)
        write_msh(zero, [(1, 5, 2)])      # three collinear nodes on the bottom edge
        write_msh(badid, [(1, 2, 99)])    # node 99 does not exist
        # A surface in OBJ given as the mesh, and a case whose "# requires:" surface is missing.
        obj, missing = os.path.join(tmp, "surface.obj"), os.path.join(tmp, "not_made_yet.msh")
        with open(obj, "w") as f:
            f.write("v 0 0 0\nv 1000 0 0\nv 0 1000 0\nf 1 2 3\n")
        needs = os.path.join(tmp, "needs_surface.opts")
        with open(needs, "w") as f:
            f.write("# requires: %s from options/saddle/ff_r15_s11_n19.opts\n-options_file %s\n-mesh_file %s\n"
                    % (missing, os.path.abspath(T.opts("patch")), missing))
        # The mesh writer itself is right: the valid mesh runs and passes the patch test.
        rc, out = T.run(etfe, ["-options_file", T.opts("patch"), "-mesh_file", good,
                               "-output_file", os.path.join(tmp, "good.h5"), "-load_monitor", "0"])
        chk.less(T.scene_value(out, "patch", "closed_form", "relative_error"), 1e-9,
                 "control: the valid hand-written MSH 4.1 mesh runs (closed-form error)")

        patch = ["-options_file", T.opts("patch")]
        cases = [
            ("missing mesh file", patch + ["-mesh_file", "/nonexistent.msh"], [r"/nonexistent\.msh", r"cannot open"]),
            ("zero-area triangle", patch + ["-mesh_file", zero], [re.escape(zero), r"element 3\b", r"degenerate|area"]),
            ("triangle with a missing node", patch + ["-mesh_file", badid], [re.escape(badid), r"node 99\b"]),
            ("unknown scene", patch + ["-scene", "nosuch"], [r"-scene nosuch", r"not a registered scene"]),
            ("unknown option", patch + ["-patch_bogus", "1"], [r"-patch_bogus"]),
            ("negative thickness", patch + ["-membrane_thickness", "-1"], [r"-membrane_thickness", r"positive"]),
            ("empty schedule", patch + ["-patch_schedule", ""], [r"patch_schedule"]),
            ("non-numeric schedule", patch + ["-patch_schedule", "1,abc"], [r"\babc\b"]),
            ("non-finite schedule", patch + ["-patch_schedule", "nan"], [r"schedule"]),
            ("unknown material type", patch + ["-material_type", "nosuch"], [r"-material_type nosuch"]),
            ("Poisson's ratio 0.7", patch + ["-material_poisson", "0.7"], [r"-material_poisson 0\.7", r"Poisson"]),
            ("OBJ surface as the mesh", patch + ["-mesh_file", obj], [re.escape(obj), r"scripts/surface2msh"]),
            ("missing required surface", ["-options_file", needs],
             [re.escape(missing), r"cannot open", re.escape(needs) + r" requires it",
              r"etfe -options_file options/saddle/ff_r15_s11_n19\.opts"]),
        ]
        for k, (what, args, patterns) in enumerate(cases):
            h5 = os.path.join(tmp, "case%02d.h5" % k)
            rc, out = T.run(etfe, args + ["-output_file", h5], expect_fail=None, timeout=120)
            msg = T.error_message(out)
            if not chk.check(rc != 0, "%s: exit code %d (non-zero)" % (what, rc)):
                print("    output tail:\n" + T.tail(out, 6))
                continue
            missing = [p for p in patterns if not re.search(p, msg)]
            chk.check(not missing, "%s: message names it: %s%s" % (
                what, " | ".join(l for l in msg.splitlines()[:3]),
                "" if not missing else "  (missing %s)" % missing))
            st = T.status(h5) if os.path.exists(h5) else None
            chk.check(st != "complete", "%s: no results file with status 'complete' (%s)" % (
                what, "no file" if st is None else "status %r" % st))
            chk.check(not re.search(r"\.(cpp|c|h):\d+", out) and out.count("-etfe_traceback") <= 1,
                      "%s: no source location, at most one -etfe_traceback hint" % what)

        # -etfe_traceback gives where the error was raised (PETSc's full report).
        rc, out = T.run(etfe, patch + ["-membrane_thickness", "-1", "-output", "0", "-etfe_traceback"],
                        expect_fail=True, timeout=120)
        chk.check(re.search(r"#1 \w+\(\) at \S+\.cpp:\d+", out) is not None,
                  "-etfe_traceback: the report names the function and source line")

        diverging(etfe, chk, tmp, 1)
        diverging(etfe, chk, tmp, 2)


def diverging(etfe, chk, tmp, np_):
    """Compressing the patch to 10% of its length collapses elements: the first half increment
    converges (load time 0.5), the second cannot, and with -load_max_cutbacks 1 the run stops."""
    h5 = os.path.join(tmp, "diverging_np%d.h5" % np_)
    args = ["-options_file", T.opts("patch"), "-patch_strain_x", "-0.9", "-load_increments", "1",
            "-load_max_cutbacks", "1", "-output_file", h5]
    rc, out = T.run(etfe, args, np=np_, expect_fail=True, timeout=120)
    msg = T.error_message(out)
    what = "diverging increment (np=%d)" % np_
    m = re.search(r"increment (\d+) \(load time (%s) -> (%s)\) did not converge after (\d+) cut-backs: (DIVERGED_\w+)"
                  % (T.NUMBER, T.NUMBER), msg)
    chk.check(m is not None, "%s: message names the increment and the SNES reason: %s" % (what, msg.splitlines()[0] if msg else "<none>"))
    if not m:
        return
    inc, t_from, reason = int(m.group(1)), float(m.group(2)), m.group(5)
    print("    %s: increment %d from load time %g, cut-backs %s, reason %s" % (what, inc, t_from, m.group(4), reason))
    chk.check(inc == 2 and abs(t_from - 0.5) < 1e-12, "%s: it is increment 2 from load time 0.5 (got %d from %g)" % (what, inc, t_from))
    chk.check(os.path.exists(h5), "%s: results file exists" % what)
    if not os.path.exists(h5):
        return
    st = T.status(h5)
    chk.check(st.startswith("failed") and reason in st and "increment %d" % inc in st,
              "%s: status %r starts with 'failed' and repeats the reason" % (what, st[:90] + "..."))
    steps = T.read_steps(h5)
    last = steps[-1]
    chk.check(len(steps) >= 2 and abs(float(last[1]["time"]) - t_from) < 1e-12,
              "%s: the file holds the last converged step (step %d, time %g; %d steps written)"
              % (what, last[0], float(last[1]["time"]), len(steps)))
    import numpy as np
    u = last[2]["displacement"]
    chk.check(np.isfinite(u).all() and abs(u[:, 0].min() + 0.9 * 1000 * 0.5) < 1e-9,
              "%s: last converged displacement is finite, right edge at -450 mm (min ux = %.6f)" % (what, u[:, 0].min()))


if __name__ == "__main__":
    T.main(main_test)
