"""etfepy: what the scripts and the tests share about running etfe and reading what it writes.

    runner     one way to launch build/etfe (alone or under mpirun), with logs and timeouts
    lines      one parser per kind of line etfe prints (summary, progress, header, scene report,
               PETSc errors)
    results    the HDF5 results file (h5py): steps, fields and the scene inputs of a run
    options    PETSc options files with etfe's include rule (-options_file, # requires:)
    msh22      the Gmsh 2.2 writer of the meshes made by script (meshes/*.py, cushion-mesh,
               surface2msh) and by the tests

Scripts import it as `import etfepy` (Python puts a script's own folder, scripts/, on the path);
the tests put <repo>/scripts on sys.path first (tests/regression/etfe_testlib.py).
"""
import os

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ETFE = os.path.join(REPO, "build", "etfe")
