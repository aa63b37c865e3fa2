"""The HDF5 results file of a run (layout: include/etfe/io/output.h) and the scene inputs behind it.

    with Results.open("results/dd1511/dd1511.h5") as r:
        r.scene, r.status, r.X (reference coordinates), r.tri, r.steps, r.times, r.stages
        r.get("mises"), r.get("contact/node", i), r.deformed()
    inputs = SceneInputs.of("results/dd1511/dd1511.h5")       part boxes, stages, pressure cycle, ...
    read_history("results/dd1511/dd1511.h5", r, notes)       the probe history CSV beside it

A saddle run writes the inputs it used, defaults included, as root attributes (SCENE_ATTRIBUTES:
part boxes, arch line, number of drawing stages, pressure cycle); SceneInputs reads them first.
Older files fall back to the options the run recorded (root attribute `options`) and to
SADDLE_DEFAULTS, which mirror src/scenes/saddle_stretch.cpp and saddle_geometry.h.
"""
import glob
import os

import numpy as np

from . import REPO
from . import options as optionsfile

SADDLE_DEFAULTS = {"drawing_stages": 4, "part_A": (0.0, 0.0, 400.0, 400.0), "part_B": (1300.0, 0.0, 1700.0, 400.0),
                   "arch_x": 1000.0}
# Root attributes in which a results file holds the saddle's inputs (files written before they
# existed fall back to the recorded options and SADDLE_DEFAULTS).
SCENE_ATTRIBUTES = {"drawing_stages": "saddle_drawing_stages", "part_A": "saddle_part_A",
                    "part_B": "saddle_part_B", "arch_x": "saddle_arch_x",
                    "pressure_cycle": "saddle_pressure_cycle"}


def h5py():
    import h5py as mod  # imported on use: the runner and parsers work without it
    return mod


def text(v):
    """An HDF5 string attribute (bytes, str or 0-d array) as str."""
    if isinstance(v, bytes):
        return v.decode("utf-8", "replace")
    if isinstance(v, np.ndarray) and v.shape == ():
        return text(v[()])
    return str(v)


def datasets(group):
    """{path: dataset} of every dataset below an HDF5 group (scripts/h5compare.py's walk)."""
    import h5compare  # scripts/h5compare.py, beside this package
    return h5compare.datasets(group)


def status(path):
    """Status of a results file as a reader should believe it (etfepy.status; "" when missing)."""
    import h5compare
    return h5compare.file_status(path)


class Results:
    """One results file: mesh, step attributes and access to step datasets on demand."""

    def __init__(self, f, path):
        self.f = f
        self.path = os.path.abspath(path)
        self.dir = os.path.dirname(self.path)
        self.name = os.path.splitext(os.path.basename(path))[0]
        self.scene = text(f.attrs.get("scene", b""))
        self.status = text(f.attrs.get("status", b""))
        if self.status == "running":  # is its writer alive? (etfepy.status)
            from . import status as writer
            self.status = writer.seen_from_attrs(path, f.attrs)
        self.X = f["mesh/coordinates"][()]
        self.tri = f["mesh/triangles"][()].astype(np.int64)
        keys = sorted(f["steps"].keys(), key=int) if "steps" in f else []
        self.keys = keys
        attr = lambda k, name, default: f["steps"][k].attrs.get(name, default)
        self.steps = np.array([int(attr(k, "step", int(k))) for k in keys], dtype=int)
        self.times = np.array([float(attr(k, "time", np.nan)) for k in keys])
        self.stages = np.array([int(attr(k, "stage", -1)) for k in keys], dtype=int)
        self.load_factors = np.array([float(attr(k, "load_factor", np.nan)) for k in keys])

    @classmethod
    def open(cls, path):
        """A context manager: `with Results.open(path) as r:` closes the file afterwards."""
        return _Opened(cls, path)

    @property
    def last(self):
        return len(self.keys) - 1

    def has(self, name, i=None):
        i = self.last if i is None else i
        return i >= 0 and name in self.f["steps"][self.keys[i]]

    def get(self, name, i=None):
        """Dataset `name` of written step index i (default: last), or None."""
        i = self.last if i is None else i
        if i < 0:
            return None
        g = self.f["steps"][self.keys[i]]
        return g[name][()] if name in g else None

    def deformed(self, i=None):
        u = self.get("displacement", i)
        return self.X if u is None else self.X + u

    @property
    def has_contact(self):
        return self.last >= 0 and self.has("contact/node")


class _Opened:
    def __init__(self, cls, path):
        self.cls, self.path = cls, path

    def __enter__(self):
        self.f = h5py().File(self.path, "r")
        return self.cls(self.f, self.path)

    def __exit__(self, *exc):
        self.f.close()


def read_steps(path):
    """[(step, attrs, {dataset: array})] of a results file, in step order."""
    res = []
    with h5py().File(path, "r") as f:
        for k in sorted(f["steps"].keys(), key=int):
            g = f["steps"][k]
            res.append((int(k), {a: g.attrs[a] for a in g.attrs}, {n: d[()] for n, d in datasets(g).items()}))
    return res


def read_csv(path):
    """CSV with a header line as {column: float array}; None when missing or empty."""
    if not os.path.isfile(path):
        return None
    with open(path) as fh:
        header = fh.readline().strip().split(",")
        rows = [l.strip().split(",") for l in fh if l.strip()]
    if not rows or not header or header == [""]:
        return None
    n = len(header)
    good = [r for r in rows if len(r) == n]
    data = np.array([[float(x) for x in r] for r in good]) if good else np.zeros((0, n))
    return {h: data[:, j] for j, h in enumerate(header)}


def history_path(h5path):
    return os.path.splitext(os.path.abspath(h5path))[0] + "_history.csv"


def read_history(h5path, run=None, notes=None):
    """The scene's probe history beside the results (<case>_history.csv), checked against the
    results file: rows of the same increment must have the same load time (a CSV written by
    another run with the same -output_file, e.g. with -output 0, is reported and not used)."""
    path = history_path(h5path)
    h = read_csv(path)
    if h is None or "step" not in h or "time" not in h:
        return None
    if run is not None and len(run.steps):
        t_of = dict(zip(run.steps.tolist(), run.times.tolist()))
        common = [(s, t) for s, t in zip(h["step"].astype(int), h["time"]) if s in t_of]
        bad = [(s, t, t_of[s]) for s, t in common if abs(t - t_of[s]) > 1e-6 * max(1.0, abs(t))]
        if bad or not common:
            if notes is not None:
                why = ("increment %d has load time %g in the CSV but %g in the results" % bad[0] if bad
                       else "no increment of the CSV is a written step of the results")
                notes.append("%s does not belong to this results file (%s); not used"
                             % (os.path.relpath(path), why))
            return None
        if notes is not None and h["step"][-1] < run.steps[-1]:
            notes.append("%s ends at increment %d, the results at %d" % (os.path.relpath(path), h["step"][-1],
                                                                        run.steps[-1]))
    return h


def recorded_options(path):
    """{option: value or None} the run recorded in its results file (root attribute options), or {}."""
    try:
        with h5py().File(path, "r") as f:
            words = text(f.attrs.get("options", b"")).split()
    except OSError:
        return {}
    return dict(optionsfile.pairs(words))


def find_options(h5path, explicit=None):
    """(source, {option: value}): the options file `explicit`, else the options the run recorded in
    its results file, else the options file under options/ whose -output_file is this file, else
    (None, {})."""
    if explicit:
        return explicit, optionsfile.read_dict(explicit)
    recorded = recorded_options(h5path)
    if recorded:
        return h5path, recorded
    want = os.path.realpath(h5path)
    for p in sorted(glob.glob(os.path.join(REPO, "options", "**", "*.opts"), recursive=True)):
        try:
            d = optionsfile.read_dict(p)
        except optionsfile.OptionsFileError:
            continue
        out = d.get("-output_file")
        if out and os.path.realpath(out if os.path.isabs(out) else os.path.join(REPO, out)) == want:
            return p, d
    return None, {}


def root_attributes(h5path):
    try:
        with h5py().File(h5path, "r") as f:
            return {k: f.attrs[k] for k in f.attrs}
    except OSError:
        return {}


class SceneInputs:
    """Scene inputs of a run, with where they came from: drawing_stages, part_A, part_B (plan
    boxes x0, y0, x1, y1), arch_x (saddle); pressure_cycle (kPa); mu, friction; yield1 (first
    yield stress of a plastic material); t1 (capstan)."""

    def __init__(self, source, opts, attrs=None):
        self.source = ("options recorded in " + os.path.basename(source) if source and source.endswith(".h5")
                       else os.path.relpath(source, REPO) if source else None)
        o, a = opts, attrs or {}
        floats = optionsfile.floats

        def saddle(key, option_values):
            name = SCENE_ATTRIBUTES[key]
            if name in a:
                return np.atleast_1d(a[name]).tolist(), "results"
            if option_values:
                return option_values, "options"
            return SADDLE_DEFAULTS.get(key), "default"

        stages, _ = saddle("drawing_stages", len(floats(o.get("-saddle_draw_a"))))
        self.drawing_stages = int(stages[0] if isinstance(stages, list) else stages)
        part_a, how_a = saddle("part_A", tuple(floats(o.get("-saddle_part_A"))))
        part_b, how_b = saddle("part_B", tuple(floats(o.get("-saddle_part_B"))))
        self.part_A, self.part_B = tuple(map(float, part_a)), tuple(map(float, part_b))
        self.parts_default = how_a == "default" and how_b == "default"
        arch, self.arch_from = saddle("arch_x", None)
        self.arch_x = float(arch[0] if isinstance(arch, list) else arch)
        cycle, _ = saddle("pressure_cycle", floats(o.get("-saddle_pressure_cycle")))
        self.pressure_cycle = [float(x) for x in (cycle or [])]
        self.pressure_source = self.source if self.pressure_cycle else None
        self.mu = float(o["-contact_mu"]) if o.get("-contact_mu") else None
        if o.get("-contact_friction") in ("none",):
            self.mu = 0.0
        self.friction = o.get("-contact_friction")
        yields = floats(o.get("-material_yield"))
        self.yield1 = yields[0] if yields and o.get("-material_type") == "plastic" else None
        self.t1 = float(o["-capstan_t1"]) if o.get("-capstan_t1") else None

    @classmethod
    def of(cls, h5path, explicit_options=None):
        """The inputs of the run in h5path: its attributes and recorded options, or explicit_options
        (an options file) instead of the recorded ones."""
        source, opts = find_options(h5path, explicit_options)
        return cls(source, opts, root_attributes(h5path))

    def pressure(self, stage, load_factor):
        """Scene pressure [kPa] at a step (saddle_stretch.cpp: drawing stages at p = 0, then the
        cycle, linear within a stage from the previous stage's value), or None."""
        if not self.pressure_cycle:
            return None
        p = [0.0] * self.drawing_stages + list(self.pressure_cycle)
        s = min(max(int(stage), 0), len(p) - 1)
        start = p[s - 1] if s > 0 else 0.0
        return start + load_factor * (p[s] - start)
