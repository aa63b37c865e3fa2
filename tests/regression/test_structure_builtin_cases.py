"""The built-in scenes as cases of the general scene: each verification case written as options of
-scene structure only (options/structure/verify_*.opts, lab_strip_*.opts: a generated mesh,
supports, loads and -structure_check) gives the built-in scene's run (options/<scene>.opts) bit
for bit: every dataset of every step of the results, and the same check lines (hencky, patch,
annulus, capstan, catenoid, strip). Run on coarser meshes and fewer increments than the cases
(the same -mesh_* and -load_* options given to both). Also refused: a check whose case lacks what
it measures (-structure_check capstan without the capstan mesh; an annulus without a turned hub).
The saddle's stretch fabrication (DD1511 on its form-found surface, 40 increments) likewise:
options/structure/verify_dd1511_stretch.opts gives options/saddle/dd1511.opts's results, its report
lines and its history CSV bit for bit (the frame's drawing interpolated edge by edge,
-bc_frame_points_interpolation axis); refused: -structure_check saddle_stretch without the arch,
an axis interpolation whose segment runs along neither axis.
"""
import os
import re

from etfe_testlib import Checker, etfe_path, form_found_saddle, run, scratch_dir, REPO
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
    # The stretch cases start from a form-found surface: the thesis density's (1444 triangles), whose
    # frame corner lies at (2000 - 2e-13, 1000 - 1e-13): the nearest segment in 3D (the default
    # -bc_frame_points_interpolation projection) takes it to the edge Y = 1000 and the results
    # differ from the saddle scene's in the last bits (1e-16 relative at increment 10, measured);
    # a coarse surface (-mesh_n 8) has its corner on both edges and does not tell the two apart.
    msh = form_found_saddle(etfe, tmp, "ff_r15_s11_n19.opts")
    CASES.append(("saddle/dd1511.opts", "structure/verify_dd1511_stretch.opts",
                  ["-mesh_file", msh, "-load_increments", 40], r"^saddle: .*"))
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
        if "saddle" in builtin:
            csv = [open(h[:-3] + "_history.csv").read() for h in (h5["scene"], h5["structure"])]
            chk.check(csv[0] and csv[0] == csv[1], "%s: the saddle's history CSV (%d rows) equals %s's byte for byte"
                      % (general, csv[0].count("\n") - 1, builtin))

    # A check refuses a case that lacks what it measures, before the run.
    hencky = ["-options_file", os.path.join(OPT, "structure", "verify_hencky.opts"), "-output", 0]
    _, out = run(etfe, hencky + ["-structure_check", "capstan"], expect_fail=True)
    chk.check("-structure_check capstan: needs -structure_mesh_generator capstan" in out,
              "refused: -structure_check capstan on a disc")
    _, out = run(etfe, hencky + ["-structure_check", "annulus"], expect_fail=True)
    chk.check("-structure_check annulus: the node group hub needs" in out, "refused: -structure_check annulus on a disc")
    _, out = run(etfe, hencky + ["-structure_mesh_generator", "cone"], expect_fail=True)
    chk.check("Unknown option cone for -structure_mesh_generator" in out, "refused: an unknown mesh generator")
    _, out = run(etfe, hencky + ["-structure_check", "saddle_stretch"], expect_fail=True)
    chk.check("-structure_check saddle_stretch: the saddle's report needs its arch" in out,
              "refused: -structure_check saddle_stretch on a disc")
    twin = ["-options_file", os.path.join(OPT, "structure", "verify_dd1511_stretch.opts"), "-mesh_file", msh,
            "-output", 0]
    _, out = run(etfe, twin + ["-bc_frame_points", "0,1000,0,2000,0,0", "-bc_frame_ux", "0,10", "-bc_frame_uy",
                               "10,0"], expect_fail=True)
    chk.check("-bc_frame_points_interpolation axis: control points 1 (0, 1000) and 2 (2000, 0) make a segment "
              "parallel to neither" in out, "refused: -bc_frame_points_interpolation axis along a diagonal")

chk.finish()
