#!/usr/bin/python3
"""Inputs off by a unit or a scale are stated before the run (include/etfe/kernels/plausibility.h): a mesh
in m, a thickness in m, Young's modulus or yield stresses in Pa, a compensation given in percent,
a pressure in Pa. A warning names the option and the likely intent and the run goes on; where no
film can have the value, the run stops with the message. Also: a CAD surface (meshes/cad_vault.step) as -mesh_file,
meshed by Gmsh on rank 0 (the same lines on 1 and 2 ranks), or refused by a build without the
Gmsh API with a message naming the file and libgmsh-dev."""
import os
import shutil
import subprocess
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402
import badmesh_cases  # noqa: E402

PATCH = ["-options_file", T.opts("patch"), "-output", "0", "-load_monitor", "0"]
HYPAR = os.path.join(T.REPO, "meshes", "hypar_two_strips.msh")
VAULT = os.path.join(T.REPO, "meshes", "cad_vault.step")


def warned(out, text):
    return sum(1 for l in out.splitlines() if l.startswith("etfe: warning:") and text in l)


def refused(etfe, chk, args, text, what):
    rc, out = T.run(etfe, args, expect_fail=True)
    msg = T.error_message(out)
    chk.check(text in msg, "%s: refused with %r (%s)" % (what, text, msg.strip()[:200]))


def test_options(etfe, chk):
    rc, out = T.run(etfe, PATCH)
    chk.check("warning" not in out, "the patch case as shipped: no warning")
    refused(etfe, chk, PATCH + ["-membrane_thickness", "0.00025"], "Did you mean 0.25 (the value in m)?",
            "-membrane_thickness 0.00025")
    rc, out = T.run(etfe, PATCH + ["-membrane_thickness", "0.02"])
    chk.check(warned(out, "-membrane_thickness 0.02: the thickness is in mm") == 1,
              "-membrane_thickness 0.02 warns once and runs")
    refused(etfe, chk, PATCH + ["-material_young", "8e8"], "Did you mean 800 (the value in Pa)?",
            "-material_young 8e8")
    rc, out = T.run(etfe, PATCH + ["-material_young", "8e5"])
    chk.check(warned(out, "Did you mean 800 (the value in kPa)?") == 1, "-material_young 8e5 warns and runs")
    refused(etfe, chk, PATCH + ["-material_type", "plastic", "-material_yield", "1.328e7,2.304e7"],
            "-material_yield 1.328e+07 (value 1)", "-material_yield in Pa")
    refused(etfe, chk, ["-options_file", T.opts("hencky"), "-output", "0", "-hencky_pressure", "2000"],
            "scene hencky: the pressure (-hencky_* options) reaches 2000 MPa", "-hencky_pressure 2000 (Pa for MPa)")


def test_mesh_extent(etfe, chk, tmp):
    small = os.path.join(tmp, "square_in_m.msh")
    badmesh_cases.write_msh(small, badmesh_cases.grid_nodes(3.0), badmesh_cases.grid_triangles())
    rc, out = T.run(etfe, PATCH + ["-mesh_file", small])
    chk.check(warned(out, "mesh %s spans 4.24264 mm" % small) == 1 and "was the file in m" in out,
              "a 3 x 3 mm mesh warns once that it may be in m")
    rc, out = T.run(etfe, PATCH + ["-mesh_file", small], np=2)
    chk.check(warned(out, "spans 4.24264 mm") == 1, "on 2 ranks the warning is printed once")


def test_compensation(etfe, chk, tmp):
    cut = ["-analysis", "cutpattern", "-mesh_file", HYPAR, "-output_file", os.path.join(tmp, "hypar.h5"),
           "-cutpattern_compensation", "uniform"]
    refused(etfe, chk, cut + ["-cutpattern_compensation_md", "1"],
            "this is 100 % and cuts the strips at 1/2 of the design", "-cutpattern_compensation_md 1")
    rc, out = T.run(etfe, cut + ["-cutpattern_compensation_td", "0.08"])
    chk.check(warned(out, "-cutpattern_compensation_td 0.08: the compensation is a fraction (0.01 = 1 %)") == 1
              and "cutpattern: strip" in out, "-cutpattern_compensation_td 0.08 warns and patterns")
    rc, out = T.run(etfe, cut + ["-cutpattern_compensation_md", "0.01"])
    chk.check("warning" not in out, "-cutpattern_compensation_md 0.01: no warning")


def test_cad(etfe, chk, tmp):
    cut = ["-analysis", "cutpattern", "-mesh_file", VAULT, "-output_file", os.path.join(tmp, "vault.h5"),
           "-mesh_cad_size", "100"]
    # The build has the Gmsh API when CMake made the module beside etfe (CMakeLists.txt).
    if not os.path.exists(os.path.join(os.path.dirname(etfe), "libetfe_cad.so")):
        refused(etfe, chk, cut, "this build has no Gmsh API to mesh it: install libgmsh-dev", "no Gmsh API")
        chk.check(VAULT in T.error_message(T.run(etfe, cut, expect_fail=True)[1]), "the refusal names the file")
        return
    rc, one = T.run(etfe, cut)
    chk.check("meshed by Gmsh at the target element size 100 mm" in one, "the CAD file is meshed at -mesh_cad_size")
    chk.check("faces named in the file: apron, vault" in one and "strip vault" in one and "strip apron" in one,
              "the STEP product names are the strips")
    rc, two = T.run(etfe, cut, np=2)
    mine = [l for l in one.splitlines() if l.startswith(("mesh ", "cutpattern:"))]
    chk.check(mine and mine == [l for l in two.splitlines() if l.startswith(("mesh ", "cutpattern:"))],
              "2 ranks print the same mesh and pattern lines as 1 (Gmsh runs on rank 0 only)")
    # A scene reads it through SceneReadMesh (rank 0) too: the patch scene meshes it, then asks for
    # its edge groups, which a CAD file names by tag.
    rc, out = T.run(etfe, PATCH + ["-mesh_file", VAULT, "-mesh_cad_size", "200"], np=2, expect_fail=True)
    chk.check("meshed by Gmsh at the target element size 200 mm" in out
              and 'needs a physical group named "left"' in T.error_message(out),
              "a scene on 2 ranks reads the CAD file and checks its groups")
    if shutil.which("gmsh"):  # scripts/surface2msh meshes it with the gmsh command line
        msh = os.path.join(tmp, "vault.msh")
        res = subprocess.run([sys.executable, os.path.join(T.REPO, "scripts", "surface2msh"), VAULT, msh, "--size",
                              "100"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
        chk.check(res.returncode == 0 and "element size 100 mm" in res.stdout, "surface2msh meshes the STEP file")
        rc, out = T.run(etfe, cut[:2] + ["-mesh_file", msh] + cut[4:6])
        chk.check("strip surface_1" in out and "strip surface_2" in out,
                  "its .msh has the faces as physical surfaces surface_<tag>")


def main_test(etfe, chk):
    test_options(etfe, chk)
    with T.scratch_dir("plausibility") as tmp:
        test_mesh_extent(etfe, chk, tmp)
        test_compensation(etfe, chk, tmp)
        test_cad(etfe, chk, tmp)


if __name__ == "__main__":
    T.main(main_test)
