"""The general scene (-scene structure) against the built-in scenes, and its refusals.

* DD1511 as the saddle's form-found mesh plus options/structure/general_dd1511.opts gives the saddle
  scene's history CSV (parts A and B, elements I and II, the slides I-V, the pair counts, the
  work) in every printed digit; with the arch fitted to the mesh's arch curve (-rigid_arch_type
  curve) instead of written down, within 1e-6;
* Hencky through the general scene (the hencky scene's disc written with -scene_mesh_out): the
  same centre deflection; the capstan: the same T2 (the reaction on the pulled end) at every step;
* the worked example (options/structure/hypar_canopy.opts): 2 ranks agree with 1, a restart from
  a stage end equals the uninterrupted run bit for bit, the snow and the film's weight are carried
  by the frame;
* bad input is refused before the run with a message naming the option: a group the mesh does
  not have, a support group or rigid node group misspelt, two groups prescribing one DOF
  differently, a load in the wrong unit, wind without its coefficient, an empty report region, a
  curve that is no circular arc, no mesh file.
"""
import math
import os
import re

from etfe_testlib import (Checker, dd1511_case, etfe_path, form_found_saddle, largest_family_difference,
                          largest_history_difference, read_history, run, scratch_dir, stop_and_restart, REPO)

etfe = etfe_path()
chk = Checker("structure_scenes")
OPT = os.path.join(REPO, "options", "structure")


def structure(args, tmp, name, np=1, expect_fail=False):
    hist = os.path.join(tmp, name + ".csv")
    rc, out = run(etfe, list(args) + ["-load_monitor", 0, "-output_file", os.path.join(tmp, name + ".h5"),
                                      "-structure_history", hist], np=np, expect_fail=expect_fail)
    return out, (read_history(hist) if rc == 0 and os.path.exists(hist) else [])


with scratch_dir() as tmp:
    # --- DD1511: the saddle scene and the general scene on the same mesh
    msh = form_found_saddle(etfe, tmp)
    _, saddle = dd1511_case(etfe, msh, tmp, "saddle", [])
    dd = ["-options_file", os.path.join(OPT, "general_dd1511.opts"), "-mesh_file", msh, "-output", 0]
    out, general = structure(dd, tmp, "general")
    mapping = {"A_Exx": "part_A_Exx", "A_Eyy": "part_A_Eyy", "A_Exy": "part_A_Exy", "A_mises": "part_A_mises",
               "B_Exx": "part_B_Exx", "B_Eyy": "part_B_Eyy", "B_Exy": "part_B_Exy", "B_mises": "part_B_mises",
               "I_smin": "element1_smin", "I_emin": "element1_emin", "II_smin": "element2_smin",
               "II_emin": "element2_emin", "pairs_open": "pairs_open", "pairs_stick": "pairs_stick",
               "pairs_slip": "pairs_slip", "work": "work", "time": "time"}
    for k in range(1, 6):
        mapping["slide%d_X" % k] = "node%d_slide_X" % k
        mapping["slide%d_Y" % k] = "node%d_slide_Y" % k
    chk.check(len(general) == len(saddle) == 200, "DD1511: both histories have 200 increments (%d, %d)"
              % (len(saddle), len(general)))
    differ = [(rs["step"], a, rs[a], rg[b]) for rs, rg in zip(saddle, general) for a, b in mapping.items()
              if rs[a] != rg[b]]
    chk.check(not differ, "DD1511 through the general scene: every mapped history column equals the saddle scene's "
                          "in every printed digit (%d columns x %d increments)%s"
              % (len(mapping), len(saddle), "" if not differ else ": %d differ, first %s" % (len(differ), differ[0])))
    # The tangent shift's dissipation sums over the Newton iterates, whose round-off the two scenes
    # do not share (their constraint lists are built in another order): within a printed digit.
    shift = max(abs(float(rs["shift_work"]) - float(rg["shift_work"])) / max(abs(float(rs["shift_work"])), 1e-300)
                for rs, rg in zip(saddle, general))
    chk.less(shift, 1e-7, "DD1511: the shift_work diagnostic within its printed digits (largest relative difference)")
    # The arch fitted to the mesh's arch curve instead of written down.
    out, fitted = structure(dd + ["-rigid_arch_type", "curve", "-rigid_arch_curve", "arch"], tmp, "fitted")
    m = re.search(r"radius ([\d.]+) mm \(largest deviation ([\d.e+-]+) mm\)", out)
    chk.check(m and abs(float(m.group(1)) - 1816.6667) < 1e-3 and float(m.group(2)) < 1e-6,
              "the arch fitted to node group arch: radius %s mm (1816.6667), deviation %s mm"
              % (m.group(1) if m else "?", m.group(2) if m else "?"))
    worst, where = largest_history_difference(general, fitted, [c for c in mapping.values() if c != "time"])
    chk.less(worst, 1e-6, "DD1511 with the fitted arch: largest history difference against the written-down arch "
                          "(relative to each column's largest value, at %s)" % (where,))

    # --- Hencky: the hencky scene's disc through the general scene
    disc = os.path.join(tmp, "disc.msh")
    _, out_h = run(etfe, ["-options_file", os.path.join(REPO, "options", "hencky.opts"), "-scene_mesh_out", disc,
                          "-output", 0, "-load_monitor", 0])
    w_scene = float(re.search(r"centre_deflection = ([\d.e+-]+)", out_h).group(1))
    out, hist = structure(["-options_file", os.path.join(OPT, "general_hencky.opts"), "-mesh_file", disc, "-output", 0],
                          tmp, "hencky")
    w_general = float(hist[-1]["node1_uZ"])
    chk.less(abs(w_general - w_scene) / w_scene, 2e-6,
             "Hencky: centre deflection %.7g mm through the general scene vs %.7g mm (hencky scene), relative "
             "difference" % (w_general, w_scene))
    rz = float(hist[-1]["rim_RZ"])
    load = 0.2e-3 * math.pi * 500.0 ** 2
    chk.less(abs(abs(rz) - load) / load, 2e-3, "Hencky: the rim carries the pressure (%.2f N against p pi a^2 = "
                                                "%.2f N on the flat disc)" % (abs(rz), load))

    # --- Capstan: T2 at every step
    strip = os.path.join(tmp, "strip.msh")
    _, out_c = run(etfe, ["-options_file", os.path.join(REPO, "options", "capstan.opts"), "-scene_mesh_out", strip,
                          "-output", 0, "-load_monitor", 1])
    t2_scene = [float(x) for x in re.findall(r"capstan: T2 = ([\d.e+-]+) N", out_c)]
    out, hist = structure(["-options_file", os.path.join(OPT, "general_capstan.opts"), "-mesh_file", strip, "-output", 0],
                          tmp, "capstan")
    tb = (math.cos(math.pi / 2), 0.0, -math.sin(math.pi / 2))
    t2_general = [sum(float(r["right_R" + c]) * tb[i] for i, c in enumerate("XYZ")) for r in hist]
    worst = max((abs(a - b) / max(abs(a), 1e-300) for a, b in zip(t2_scene, t2_general)), default=1.0)
    chk.check(len(t2_scene) == len(t2_general) == 40 and worst < 2e-6,
              "capstan: T2 through the general scene equals the capstan scene's at all %d steps (largest "
              "relative difference %.1e, printed to 7 digits)" % (len(t2_general), worst))

    # --- A plane support: the patch scene's sheet pressed onto a table by 0.5 kPa and pulled by its
    # edge "right" until it slides: the pull equals mu times the normal force on the sliding pairs
    # (the pressure on the sheet less what the held edge takes itself, its reaction Z).
    sheet = os.path.join(tmp, "sheet.msh")
    run(etfe, ["-options_file", os.path.join(REPO, "options", "patch.opts"), "-scene_mesh_out", sheet, "-output", 0,
               "-load_monitor", 0])
    out, hist = structure(["-scene", "structure", "-mesh_file", sheet, "-material_type", "elastic", "-material_young",
                           800, "-material_poisson", 0.43, "-structure_rigid", "table", "-rigid_table_type", "plane",
                           "-rigid_table_centre", "0,0,0", "-rigid_table_axis", "0,0,1", "-contact_friction",
                           "implicit", "-contact_mu", 0.3, "-contact_frictionless_until", 1, "-film_all_pressure",
                           "-0.5,-0.5", "-bc_right_ux", "0,2", "-bc_right_fix", "yz", "-load_increments", 40,
                           "-output", 0], tmp, "table")
    pull, held = float(hist[-1]["right_RX"]), float(hist[-1]["right_RZ"])
    expect = 0.3 * (0.5e-3 * 1000.0 * 500.0 - held)
    chk.less(abs(pull - expect) / expect, 1e-3, "plane support: the sheet slides at T = %.3f N, mu (q A - R_z) = "
                                                 "%.3f N, relative difference" % (pull, expect))

    # --- The worked example: snow carried, 1 vs 2 ranks, restart from a stage end
    ff = os.path.join(tmp, "hypar_ff.msh")
    run(etfe, ["-options_file", os.path.join(OPT, "hypar_formfind.opts"), "-formfind_monitor", 0, "-output", 0,
               "-formfind_mesh_out", ff, "-output_file", os.path.join(tmp, "hypar_ff.h5")])
    canopy = ["-options_file", os.path.join(OPT, "hypar_canopy.opts"), "-mesh_file", ff]
    out1, h1 = structure(canopy, tmp, "canopy1")
    rz = float(h1[-1]["boundary_RZ"])
    snow = 0.75e-3 * 3000.0 ** 2
    weight = 1750 * 9.81 * 0.25e-9 * 3000.0 ** 2
    chk.check(snow < rz < snow + 3 * weight, "canopy: the frame carries the snow and the film's weight (%.1f N; "
                                             "snow on the plan %.1f N, weight above %.1f N)" % (rz, snow, weight))
    out2, h2 = structure(canopy, tmp, "canopy2", np=2)
    worst, where = largest_family_difference(h1, h2)
    chk.less(worst, 1e-8, "canopy: 2 ranks against 1, largest history difference relative to the largest value of "
                          "its quantity (displacements, strains, stresses, reactions; at %s)" % (where,))
    ck = os.path.join(tmp, "canopy_ck.h5")
    full, part = os.path.join(tmp, "canopy1.h5"), os.path.join(tmp, "canopy_part.h5")
    common = canopy + ["-load_monitor", 0, "-structure_history", os.path.join(tmp, "part.csv")]
    fails, _ = stop_and_restart(etfe, common, part, ck, 20, full)
    chk.check(not fails, "canopy: stopped at the end of stage 2 and restarted, the results equal the "
                         "uninterrupted run bit for bit%s" % ("" if not fails else ": " + "; ".join(map(str, fails[:3]))))
    hp = read_history(os.path.join(tmp, "part.csv"))
    differ = [(a["step"], k) for a, b in zip(h1, hp) for k in a if a[k] != b[k]]
    chk.check(len(hp) == len(h1) and not differ, "canopy: the restarted history CSV equals the uninterrupted one "
                                                 "(%d rows against %d%s)" % (len(hp), len(h1), "" if not differ else
                                                                             ", first difference %s" % (differ[0],)))

    # Per surface group: the film's own values given per group change nothing; a thicker strip
    # is less stressed than in the uniform film.
    _, hg = structure(canopy + ["-film_all_thickness", 0.25, "-film_all_md", "1,0,0"], tmp, "canopy_groups")
    chk.check(hg == h1, "canopy: -film_all_thickness 0.25 -film_all_md 1,0,0 (the defaults, given per group) "
                        "changes no history value")
    _, ht = structure(canopy + ["-film_strip_1_thickness", 0.3], tmp, "canopy_thick")
    s1, s0 = float(ht[-1]["strip_1_mises"]), float(h1[-1]["strip_1_mises"])
    chk.check(s1 < s0, "canopy: strip_1 at 0.3 mm carries the snow with less stress (mean Mises %.3f MPa) than at "
                       "0.25 mm (%.3f MPa)" % (s1, s0))

    # --- Refusals, on the canopy's own mesh (they stop before computing)
    hypar = os.path.join(REPO, "meshes", "hypar_canopy.msh")
    base = ["-scene", "structure", "-mesh_file", hypar, "-bc_boundary_fix", "xyz", "-output", 0]
    refusals = [
        (["-bc_boundry_fix", "z"], r"-bc_boundry_fix: no such group.*boundary"),
        (["-film_roof_pressure", "0.5"], r"-film_roof_pressure: no such group.*strip_1"),
        (["-structure_rigid", "arch", "-rigid_arch_type", "cylinder", "-rigid_arch_centre", "0,0,0",
          "-rigid_arch_axis", "1,0,0", "-rigid_arch_radius", "100", "-rigid_arch_nodes", "ridge"],
         r"no node group ridge"),
        (["-bc_edge_1_uz", "5"], r"boundary and edge_1, which prescribe its z displacement differently"),
        (["-film_all_pressure", "5000"], r"-film_all_pressure reaches 5000 kPa"),
        (["-structure_wind", "0.5"], r"-structure_wind given but no surface group has -film_<group>_wind_cp"),
        (["-structure_regions", "far", "-region_far_box", "5000,5000,6000,6000"], r"-region_far_box: no element"),
        (["-structure_rigid", "r", "-rigid_r_type", "curve", "-rigid_r_curve", "boundary"], r"no circular arc"),
        (["-structure_report", "roof"], r"-structure_report: roof is neither"),
        (["-film_all_md", "strip", "-film_strip_1_md", "0,1,0"], r"groups all and strip_1, which give it different MD"),
        (["-film_strip_2_thickness", "-0.1"], r"-film_strip_2_thickness -0.1 must be positive"),
    ]
    for args, pattern in refusals:
        _, out = run(etfe, base + args, expect_fail=True)
        chk.check(re.search(pattern, out, re.S), "refused: %s (%s)" % (" ".join(args), pattern))
    _, out = run(etfe, ["-scene", "structure", "-output", 0], expect_fail=True)
    chk.check("-scene structure needs -mesh_file" in out, "refused: the general scene without -mesh_file")
    _, out = run(etfe, base + ["-film_all_pressure", "50", "-structure_initial_bulge", "100", "-load_increments", 2],
                 expect_fail=None)
    chk.check(re.search(r"warning: -film_all_pressure reaches 50 kPa.*was it given in Pa", out),
              "warned: a pressure of 50 kPa (likely Pa) is stated before the run")

chk.finish()
