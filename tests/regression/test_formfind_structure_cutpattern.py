#!/usr/bin/python3
"""A surface form-found by the general scene cuts into patterns as it is written: the hypar canopy
(options/structure/hypar_formfind.opts) form-found, then `-analysis cutpattern -mesh_file` on the
.msh it wrote.
  * the written mesh's surface groups are the strips (strip_1, strip_2), without the group "all"
    of every triangle that the scene adds to name the whole film (written, it overlapped both
    strips and the cutter refused the file);
  * the cutter flattens both strips and measures their cutting line, and the general scene reading
    the found surface back still knows "all" (-film_all_* in its -help);
  * -formfind_ratio holds where no group gives its own ratio: MD:TD 2 finds another surface than
    1, and the same, bit for bit, as -film_all_stress_ratio 2 (it was ignored: every element
    took 1).
"""
import os
import re
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402


def surface_groups(msh):
    """The names of the physical groups of dimension 2 of a Gmsh file."""
    with open(msh) as f:
        text = f.read()
    block = text.split("$PhysicalNames", 1)[1].split("$EndPhysicalNames", 1)[0].split("\n")[2:]
    return sorted(m.group(2) for m in (re.match(r'(\d+) \d+ "(.*)"', l) for l in block) if m and m.group(1) == "2")


def main_test(etfe, chk):
    with T.scratch_dir("ff_cut") as tmp:
        msh = os.path.join(tmp, "hypar_ff.msh")
        T.run(etfe, ["-options_file", os.path.join(T.OPTIONS, "structure", "hypar_formfind.opts"),
                     "-output_file", os.path.join(tmp, "hypar_ff.h5"), "-formfind_mesh_out", msh])
        groups = surface_groups(msh)
        chk.check(groups == ["strip_1", "strip_2"], "the found surface's surface groups are the strips: %s" % groups)
        rc, out = T.run(etfe, ["-analysis", "cutpattern", "-mesh_file", msh, "-output_file",
                               os.path.join(tmp, "cut.h5")], expect_fail=None)
        strips = re.findall(r"cutpattern: strip (\S+): \d+ nodes", out)
        chk.check(rc == 0 and strips == ["strip_1", "strip_2"],
                  "-analysis cutpattern flattens the found surface's strips %s (exit %d)%s" % (
                      strips, rc, "" if rc == 0 else ": " + T.tail(out, 3)))
        chk.check(rc == 0 and "line cut_strip_1_strip_2" in out, "and measures their cutting line cut_strip_1_strip_2")
        _, out = T.run(etfe, ["-scene", "structure", "-mesh_file", msh, "-help"])
        chk.check("-film_all_thickness" in out, "the general scene reading the found surface still names the whole "
                  "film \"all\" (-film_all_thickness in -help)")
        found = {}
        for name, extra in (("global", ["-formfind_ratio", 2]), ("group", ["-film_all_stress_ratio", 2])):
            path = os.path.join(tmp, "ratio_%s.msh" % name)
            T.run(etfe, ["-options_file", os.path.join(T.OPTIONS, "structure", "hypar_formfind.opts"),
                         "-output_file", os.path.join(tmp, "ratio_%s.h5" % name), "-formfind_mesh_out", path] + extra)
            with open(path, "rb") as f:
                found[name] = f.read()
        with open(msh, "rb") as f:
            isotropic = f.read()
        chk.check(found["global"] != isotropic, "-formfind_ratio 2 finds another surface than the isotropic one")
        chk.check(found["global"] == found["group"],
                  "-formfind_ratio 2 finds the surface -film_all_stress_ratio 2 finds, bit for bit")


if __name__ == "__main__":
    T.main(main_test)
