#!/usr/bin/python3
"""Option values checked before the run, by the option's name (docs/own-structure.md, "What the
general scene checks for you"):

* a value that is not a finite number (PETSc reads "nan" and "inf" as numbers) is refused where
  it is read, not met later as a NaN divergence or taken silently: the initial bulge, a probe,
  a rigid plane's centre, a control point, a chamber's kappa, extra volume and origin, the
  film temperature, the membrane's tangent shift;
* -film_<group>_thickness has -membrane_thickness's checks (a thickness in m refused, one in cm
  warned) and an explicit 0 is refused, not taken as the default; per-group values set up on 2 ranks;
* -bc_<group>_points: two equal consecutive points are refused, and so is a group whose nodes lie
  far from the polyline (four frame corners without the first repeated); the closed loop runs;
* units: the atmosphere in Pa, the density in g/cm^3, snow in Pa or negative, a temperature
  in K or past ETFE's melting point, negative stages, kappa below 1, an MD direction normal to
  the film;
* chamber messages say what is wrong: a group listed twice, an origin off the plane that closes
  the chamber.
Every refusal happens at set-up (about a second a run)."""
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

HYPAR = ["-scene", "structure", "-mesh_file", os.path.join(T.REPO, "meshes", "hypar_canopy.msh"),
         "-bc_boundary_fix", "xyz", "-output", "0", "-load_monitor", "0", "-load_increments", "1"]
SQUARE = ["-scene", "structure", "-mesh_file", os.path.join(T.REPO, "meshes", "square_groups.msh"),
          "-material_type", "elastic", "-output", "0", "-load_monitor", "0", "-load_increments", "1"] + \
    sum([["-bc_%s_fix" % g, "xyz"] for g in ("left", "right", "top", "bottom")], [])
CUSHION = ["-options_file", os.path.join(T.REPO, "options", "cushion", "hexagon_2layer.opts"), "-output", "0",
           "-load_monitor", "0", "-load_increments", "3"]
STRIP = ["-scene", "strip", "-options_file", os.path.join(T.REPO, "options", "material", "thesis_etfe.opts"),
         "-output", "0", "-load_monitor", "0", "-load_increments", "2"]
# The hypar's frame corners (meshes/hypar_canopy.msh: heights +-600 mm).
CORNERS = [(-1500, -1500, 600), (1500, -1500, -600), (1500, 1500, 600), (-1500, 1500, -600)]


def points(pts):
    return ",".join("%g" % c for p in pts for c in p)


def warned(out, text):
    return sum(1 for l in out.splitlines() if l.startswith("etfe: warning:") and text in l)


def with_scratch(args, tmp, name):
    """The run's files in tmp (the structure scene also writes a history CSV)."""
    out = ["-output_file", os.path.join(tmp, name + ".h5")]
    if "structure" in args or CUSHION[1] in args:
        out += ["-structure_history", os.path.join(tmp, name + ".csv")]
    return args + out


def refused(etfe, chk, tmp, base, args, texts, what):
    """A refusal before the run: non-zero exit with every text in the PETSc error message."""
    rc, out = T.run(etfe, with_scratch(base + args, tmp, "refused"), expect_fail=None)
    msg = T.error_message(out)
    ok = rc != 0 and all(t in msg for t in texts)
    chk.check(ok, "%s: refused with %s (%s)" % (what, " / ".join(repr(t) for t in texts),
                                                (msg.strip() or "exit %d, no error" % rc)[:240]))


def runs(etfe, chk, tmp, base, args, what, warning=None):
    """The run goes on (and warns once with `warning`, or not at all)."""
    rc, out = T.run(etfe, with_scratch(base + args, tmp, "runs"), expect_fail=None)
    if warning:
        chk.check(rc == 0 and warned(out, warning) == 1, "%s: warns once with %r and runs (exit %d)"
                  % (what, warning, rc))
    else:
        chk.check(rc == 0 and "etfe: warning: -" not in out and "etfe: warning: the" not in out,
                  "%s: runs without a warning on its values (exit %d; %s)"
                  % (what, rc, T.error_message(out).strip()[:200]))


def test_film_thickness(etfe, chk, tmp):
    refused(etfe, chk, tmp, HYPAR, ["-film_all_thickness", "0.00025"],
            ["-film_all_thickness 0.00025: the thickness is in mm", "Did you mean 0.25 (the value in m)?"],
            "-film_all_thickness 0.00025 (m)")
    refused(etfe, chk, tmp, HYPAR, ["-film_strip_1_thickness", "0"],
            ["-film_strip_1_thickness 0 must be positive (mm)", "leave the option out for -membrane_thickness"],
            "-film_strip_1_thickness 0")
    refused(etfe, chk, tmp, HYPAR, ["-film_all_thickness", "inf"],
            ["-film_all_thickness inf: not a finite number; give the value in mm"], "-film_all_thickness inf")
    refused(etfe, chk, tmp, HYPAR, ["-film_all_thickness", "100"],
            ["-film_all_thickness 100: the thickness is in mm", "above 10 mm no film has it"],
            "-film_all_thickness 100")
    runs(etfe, chk, tmp, HYPAR, ["-film_all_thickness", "0.02"], "-film_all_thickness 0.02",
         warning="-film_all_thickness 0.02: the thickness is in mm")
    runs(etfe, chk, tmp, HYPAR, ["-film_all_thickness", "0.25"], "-film_all_thickness 0.25")
    # Per-group values are set on rank 0, whose outcome every rank takes (the ranks once parted here).
    rc, out = T.run(etfe, with_scratch(HYPAR + ["-film_strip_1_thickness", "0.3", "-film_strip_2_md", "0,1,0"], tmp,
                                       "np2"), np=2, expect_fail=None)
    chk.check(rc == 0 and "etfe: completed" in out, "per-group thickness and MD on 2 ranks: the set-up runs (exit %d; %s)"
              % (rc, T.error_message(out).strip()[:160]))


def test_points(etfe, chk, tmp):
    held = ["-bc_boundary_fix", "yz"]  # x drawn by the points; y and z held: no rigid motion left free
    refused(etfe, chk, tmp, HYPAR, held + ["-bc_boundary_points", "-1500,-1500,nan,1500,-1500,-600",
                                           "-bc_boundary_ux", "1,2"],
            ['-bc_boundary_points: value 3 ("nan") is not a finite number'], "a control point of NaN")
    refused(etfe, chk, tmp, HYPAR, held + ["-bc_boundary_points", points(CORNERS[:1] + CORNERS[:2]),
                                           "-bc_boundary_ux", "1,1,2"],
            ["-bc_boundary_points: control points 1 and 2 are the same point (-1500, -1500, 600)"],
            "two equal consecutive control points")
    # Four corners of the frame without the first repeated: the fourth edge has no segment.
    refused(etfe, chk, tmp, HYPAR, held + ["-bc_boundary_points", points(CORNERS), "-bc_boundary_ux", "1,1,2,2"],
            ["-bc_boundary_points: node", "from the polyline through the 4 control points",
             "repeats its first point as its last"], "a closed frame given by its four corners")
    # (drawn outward in x on both sides, so the film is taut: a slack one would be refused as not in
    # equilibrium, its stabilizing force carrying the drawing)
    runs(etfe, chk, tmp, HYPAR, held + ["-bc_boundary_points", points(CORNERS + CORNERS[:1]),
                                        "-bc_boundary_ux", "-1,1,1,-1,-1"],
         "the closed frame with its first corner repeated")


def test_not_finite(etfe, chk, tmp):
    refused(etfe, chk, tmp, HYPAR, ["-structure_initial_bulge", "nan"],
            ["-structure_initial_bulge nan: not a finite number; give the value in mm"], "-structure_initial_bulge nan")
    refused(etfe, chk, tmp, HYPAR, ["-structure_probe_nodes", "nan,0"],
            ['-structure_probe_nodes: value 1 ("nan") is not a finite number'], "-structure_probe_nodes nan,0")
    refused(etfe, chk, tmp, HYPAR, ["-structure_rigid", "table", "-rigid_table_type", "plane", "-rigid_table_centre",
                                    "nan,0,0", "-rigid_table_axis", "0,0,1"],
            ['-rigid_table_centre: value 1 ("nan") is not a finite number'], "a rigid plane's centre of NaN")
    refused(etfe, chk, tmp, HYPAR, ["-film_all_md", "inf,0,0"],
            ['-film_all_md: "inf" is not a finite number'], "-film_all_md inf,0,0")
    refused(etfe, chk, tmp, HYPAR, ["-membrane_tangent_shift", "inf"],
            ["-membrane_tangent_shift inf", "must be a finite number"], "-membrane_tangent_shift inf")
    refused(etfe, chk, tmp, CUSHION, ["-chamber_air_kappa", "inf"],
            ["-chamber_air_kappa inf: not a finite number"], "-chamber_air_kappa inf")
    refused(etfe, chk, tmp, CUSHION, ["-chamber_air_extra_volume", "inf"],
            ["-chamber_air_extra_volume inf: not a finite number; give the value in m^3"],
            "-chamber_air_extra_volume inf")
    refused(etfe, chk, tmp, CUSHION, ["-chamber_air_origin", "nan,0,0"],
            ['-chamber_air_origin: value 1 ("nan") is not a finite number'], "-chamber_air_origin nan,0,0")
    refused(etfe, chk, tmp, STRIP, ["-material_temperature", "inf"],
            ["-material_temperature inf: not a finite number; give the temperature in deg C"],
            "-material_temperature inf")
    for v in ("nan", "-5"):
        refused(etfe, chk, tmp, SQUARE, ["-etfe_memory_node_gb", v], ["-etfe_memory_node_gb", "give a node's memory in GB"],
                "-etfe_memory_node_gb %s" % v)


def test_units(etfe, chk, tmp):
    refused(etfe, chk, tmp, HYPAR, ["-structure_atmosphere", "101325"],
            ["-structure_atmosphere 101325: the atmospheric pressure is in kPa", "Did you mean 101.325 (the value in Pa)?"],
            "-structure_atmosphere 101325 (Pa)")
    runs(etfe, chk, tmp, HYPAR, ["-structure_atmosphere", "30"], "-structure_atmosphere 30",
         warning="-structure_atmosphere 30: the atmospheric pressure is in kPa")
    refused(etfe, chk, tmp, HYPAR, ["-structure_density", "1.75", "-structure_self_weight", "1"],
            ["-structure_density 1.75: the density is in kg/m^3", "Did you mean 1750 (the value in g/cm^3)?"],
            "-structure_density 1.75 (g/cm^3)")
    refused(etfe, chk, tmp, HYPAR, ["-film_all_snow", "-0.5"],
            ["-film_all_snow -0.5: snow is a downward load", "cannot be negative"], "negative snow")
    refused(etfe, chk, tmp, HYPAR, ["-film_all_snow", "0,0,0,750"],
            ["-film_all_snow 750: snow is in kPa per plan area", "Did you mean 0.75 (the value in Pa)?"],
            "snow in Pa")
    refused(etfe, chk, tmp, HYPAR, ["-film_all_snow", "0.75", "-structure_stages", "-1"],
            ["-structure_stages -1: give the number of load stages"], "-structure_stages -1")
    refused(etfe, chk, tmp, CUSHION, ["-chamber_air_kappa", "0.5"],
            ["-chamber_air_kappa 0.5: the exponent of the sealed gas law", "1 (isothermal)"], "-chamber_air_kappa 0.5")
    refused(etfe, chk, tmp, SQUARE, ["-structure_md", "0,0,1"],
            ["the MD (roll) direction (0, 0, 1) of -structure_md is within 5.7 degrees of the normal of 42 of the "
             "film's 42 elements"], "an MD normal to a flat film")
    runs(etfe, chk, tmp, HYPAR, ["-film_all_md", "0,0,1"], "an MD normal to part of the hypar",
         warning="the MD (roll) direction (0, 0, 1) of -structure_md or -film_<group>_md is within 5.7 degrees")
    refused(etfe, chk, tmp, STRIP, ["-material_temperature", "1000"],
            ["-material_temperature 1000: the temperature is in deg C", "ETFE has melted"], "-material_temperature 1000")
    refused(etfe, chk, tmp, STRIP, ["-material_temperature", "293"],
            ["Did you mean 19.85 (the value in K)?"], "-material_temperature 293 (K)")
    runs(etfe, chk, tmp, STRIP, ["-material_temperature", "200"], "-material_temperature 200",
         warning="-material_temperature 200: the temperature is in deg C")
    runs(etfe, chk, tmp, STRIP, ["-material_temperature", "60"], "-material_temperature 60")


def test_chamber_messages(etfe, chk, tmp):
    refused(etfe, chk, tmp, CUSHION, ["-chamber_air_groups", "top,top"],
            ["-chamber_air_groups: group top is listed twice"], "a chamber group listed twice")
    refused(etfe, chk, tmp, CUSHION, ["-chamber_air_groups", "top", "-chamber_air_origin", "0,0,500"],
            ["-chamber_air_origin (0, 0, 500) lies 500 mm off the plane of its open rim",
             "Give a point of that plane as -chamber_air_origin"], "a chamber's origin off its closing plane")
    runs(etfe, chk, tmp, CUSHION, ["-chamber_air_groups", "top", "-load_increments", "1"],
         "the top foil closed by the rim's plane through the origin")


def main_test(etfe, chk):
    with T.scratch_dir("badinput_values") as tmp:
        test_film_thickness(etfe, chk, tmp)
        test_points(etfe, chk, tmp)
        test_not_finite(etfe, chk, tmp)
        test_units(etfe, chk, tmp)
        test_chamber_messages(etfe, chk, tmp)


if __name__ == "__main__":
    T.main(main_test)
