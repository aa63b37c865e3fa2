"""The built-in scenes as cases of the general scene: each verification case written as options of
-scene structure only (options/structure/verify_*.opts, lab_strip_*.opts: a generated mesh,
supports, loads and -structure_check) gives the built-in scene's run (options/<scene>.opts) bit
for bit: every dataset of every step of the results, and the same check lines (hencky, patch,
annulus, capstan, catenoid, strip). Run on coarser meshes and fewer increments than the cases
(the same -mesh_* and -load_* options given to both). Also refused: a check whose case lacks what
it measures (-structure_check capstan without the capstan mesh; an annulus without a turned hub).
"""
import os
import re

from etfe_testlib import Checker, etfe_path, run, scratch_dir, REPO
import h5compare

etfe = etfe_path()
chk = Checker("structure_builtin_cases")
OPT = os.path.join(REPO, "options")

CASES = [  # built-in options file, options-only file, smaller run, the check lines' prefix
    ("hencky.opts", "structure/verify_hencky.opts", ["-mesh_rings", 8], r"^hencky: .*"),
    ("patch.opts", "structure/verify_patch.opts", [], r"^patch: .*"),
    ("annulus.opts", "structure/verify_annulus.opts", ["-mesh_rings", 8, "-mesh_sectors", 48], r"^annulus: .*"),
    ("capstan.opts", "structure/verify_capstan.opts", ["-mesh_nx", 32, "-load_increments", 20],
     r"^(capstan: .*|mu_eff = .*)"),
    ("catenoid.opts", "structure/verify_catenoid.opts", ["-mesh_ntheta", 24, "-mesh_nz", 8],
     r"^(neck_radius = .*|catenoid: .*)"),
    ("strip_relaxation.opts", "structure/lab_strip_relaxation.opts", ["-load_increments", 12], r"^strip: .*"),
    ("strip_creep.opts", "structure/lab_strip_creep.opts", ["-load_increments", 12], r"^strip: .*"),
]

with scratch_dir() as tmp:
    for builtin, general, small, lines in CASES:
        name = os.path.basename(general)[:-5]
        h5 = {}
        printed = {}
        for tag, opts in (("scene", builtin), ("structure", general)):
            h5[tag] = os.path.join(tmp, "%s_%s.h5" % (name, tag))
            extra = ["-formfind_mesh_out", os.path.join(tmp, "%s_%s.msh" % (name, tag))] if "catenoid" in name else []
            _, out = run(etfe, ["-options_file", os.path.join(OPT, opts), "-output_file", h5[tag], "-load_monitor", 1]
                         + small + extra)
            printed[tag] = [l for l in out.splitlines() if re.match(lines, l.strip())]
        fails = h5compare.compare(h5["structure"], h5["scene"], step="all", default_rtol=0.0, default_atol=0.0)
        chk.check(not fails, "%s: every results dataset of every step equals %s's bit for bit%s"
                  % (general, builtin, "" if not fails else ": " + "; ".join(map(str, fails[:3]))))
        chk.check(printed["scene"] and printed["scene"] == printed["structure"],
                  "%s: the same %d check lines as %s (first: %s)"
                  % (general, len(printed["scene"]), builtin, (printed["scene"] or ["none"])[0][:90]))

    # A check refuses a case that lacks what it measures, before the run.
    hencky = ["-options_file", os.path.join(OPT, "structure", "verify_hencky.opts"), "-output", 0]
    _, out = run(etfe, hencky + ["-structure_check", "capstan"], expect_fail=True)
    chk.check("-structure_check capstan: needs -structure_mesh_generator capstan" in out,
              "refused: -structure_check capstan on a disc")
    _, out = run(etfe, hencky + ["-structure_check", "annulus"], expect_fail=True)
    chk.check("-structure_check annulus: the node group hub needs" in out, "refused: -structure_check annulus on a disc")
    _, out = run(etfe, hencky + ["-structure_mesh_generator", "cone"], expect_fail=True)
    chk.check("Unknown option cone for -structure_mesh_generator" in out, "refused: an unknown mesh generator")

chk.finish()
