"""Load cases, combinations, resistance and checks of a design file (docs/design-run.md), and the
etfe options of the base run and of each combination's branch run.

A combination is no superposition: each is its own nonlinear run from the base state (the
film prestressed or inflated, solved once and checkpointed), its loads applied together in one
stage after the base's stages. Per load option X (a per-stage array of the general scene:
-structure_self_weight, -structure_wind, -film_<g>_snow, -film_<g>_pressure, -chamber_<c>_pressure)
the combination's stage holds

    X_comb = X_base_end + sum over the combination's cases i of (f_i - [i in the base]) * v_i(X)

where v_i(X) is case i's characteristic value and f_i its factor (gamma * psi): a permanent case
already in the base (the film's weight) keeps its base value at f = 1 and adds (f - 1) v at f != 1;
prestress is the base state itself and is never factored.
"""
import json
import os
import re

from . import REPO
from . import options as optionsfile
from .resistance import Resistance, ResistanceError

# EN 1990 (2002) Annex A1 recommended values (Tables A1.1 and A1.2(B)); a National Annex may set
# others, and the design file's "factors" replace any of them.
DEFAULT_FACTORS = {
    "gamma_G_sup": 1.35,  # permanent action, unfavourable
    "gamma_G_inf": 1.0,   # permanent action, favourable (wind suction lifting the film)
    "gamma_Q": 1.5,       # variable action
    "psi0_snow": 0.5,     # snow, sites at altitude H <= 1000 m (CEN members except Finland, Iceland, Norway, Sweden)
    "psi0_wind": 0.6,
    "psi0_imposed": 0.7,  # internal pressure changes treated as an imposed action (an assumption: state yours)
    "psi2_snow": 0.0,
    "psi2_wind": 0.0,
    "psi2_imposed": 0.3,
}

LOAD_OPTION = re.compile(r"^(structure_self_weight|structure_wind|film_\w+_(snow|pressure)|chamber_\w+_pressure"
                         r"|cable_\w+_weight)$")

# A cable's design resistance is its breaking load over this factor unless the check gives its own:
# EN 1993-1-11 (6.2) F_Rd = F_uk / (1.5 gamma_R) with gamma_R = 1.0 (our reading; state yours).
DEFAULT_CABLE_FACTOR = 1.5


def load_unit(option):
    """The unit of a load option's value: kPa, N/m (a cable's weight), or a factor of the film's weight."""
    if option == "structure_self_weight":
        return "x weight"
    return "N/m" if option.startswith("cable_") else "kPa"


class DesignError(Exception):
    pass


def factor_value(expr, factors, where):
    """A factor: a number, or names of `factors` multiplied ("gamma_Q*psi0_wind")."""
    if isinstance(expr, (int, float)):
        return float(expr)
    value = 1.0
    for name in str(expr).split("*"):
        name = name.strip()
        try:
            value *= float(name)
        except ValueError:
            if name not in factors:
                raise DesignError("%s: factor %r is neither a number nor one of %s" % (where, name, sorted(factors)))
            value *= float(factors[name])
    return value


class Design:
    def __init__(self, data, path="design"):
        self.path = path
        self.title = data.get("title", os.path.basename(path))
        self.model = data["model"]
        self.options = dict(data.get("options", {}))
        base = data.get("base", {})
        self.base_loads = {k: [float(x) for x in v] for k, v in base.get("loads", {}).items()}
        self.base_stages = int(base.get("stages", max([len(v) for v in self.base_loads.values()] or [1])))
        self.base_note = base.get("note", "")
        self.per_stage = int(data.get("increments_per_stage", 10))
        self.factors = dict(DEFAULT_FACTORS)
        self.factors.update(data.get("factors", {}))
        self.cases = data.get("load_cases", {})
        try:
            self.resistance = Resistance(data.get("resistance"))
        except ResistanceError as e:
            raise DesignError(str(e))
        self.checks = data.get("checks", [])
        self.combinations = []
        for k, c in enumerate(list(data.get("combinations", [])) + self.generated(data.get("generate", []))):
            where = "combination %d (%s)" % (k + 1, c.get("name", "?"))
            f = {}
            for case, expr in c.get("factors", {}).items():
                if case not in self.cases:
                    raise DesignError("%s: load case %r is not in load_cases (%s)" % (where, case, sorted(self.cases)))
                f[case] = factor_value(expr, self.factors, where)
            self.combinations.append(dict(name=c["name"], situation=c.get("situation", "ULS"), factors=f,
                                          expressions=dict(c.get("factors", {})),
                                          duration=c.get("duration"), temperature=c.get("temperature"),
                                          options=dict(c.get("options", {}))))
        self.validate()

    def generated(self, which):
        """EN 1990 6.4.3.2 (6.10) and 6.5.3 (6.14b) combinations, each variable case leading in turn:
        ULS  gamma_G,sup G (gamma_G,inf where the leading case says "G_favourable") + gamma_Q Q1
             + sum gamma_Q psi0,i Qi;   SLS (characteristic)  G + Q1 + sum psi0,i Qi.
        Permanent cases: kind "permanent"; accidental ones are never generated; cases of one
        "group" (wind directions) never meet in a combination."""
        out = []
        for sit in which:
            if sit not in ("ULS", "SLS"):
                raise DesignError("generate: %r is neither ULS nor SLS" % sit)
        variable = [n for n, c in self.cases.items() if c.get("kind", "variable") not in ("permanent", "accidental")]
        permanent = [n for n, c in self.cases.items() if c.get("kind") == "permanent"]
        for sit in which:
            for lead in variable:
                lc = self.cases[lead]
                f = {}
                for g in permanent:
                    f[g] = 1 if sit == "SLS" else ("gamma_G_inf" if lc.get("G_favourable") else "gamma_G_sup")
                f[lead] = 1 if sit == "SLS" else "gamma_Q"
                for other in variable:
                    oc = self.cases[other]
                    if other == lead or (oc.get("group") and oc.get("group") == lc.get("group")):
                        continue
                    psi = "psi0_" + oc.get("kind", "variable")
                    f[other] = psi if sit == "SLS" else "gamma_Q*" + psi
                out.append(dict(name="%s-%s" % (sit, lead), situation=sit, factors=f))
        return out

    @staticmethod
    def load(path):
        with open(path) as f:
            return Design(json.load(f), path)

    def validate(self):
        names = [c["name"] for c in self.combinations]
        if len(set(names)) != len(names):
            raise DesignError("combination names repeat: %s" % names)
        for c in names:
            if not re.match(r"^[A-Za-z0-9_.+-]+$", c):
                raise DesignError("combination name %r: use letters, digits and _ . + - (it names files)" % c)
        for name, case in self.cases.items():
            for opt in case.get("loads", {}):
                if not LOAD_OPTION.match(opt):
                    raise DesignError("load case %s: %s is no per-stage load option of the general scene (%s)"
                                      % (name, opt, LOAD_OPTION.pattern))
        model = self.model if os.path.isabs(self.model) else os.path.join(REPO, self.model)
        try:
            given = [k.lstrip("-") for k, _ in optionsfile.read(model)]
        except optionsfile.OptionsFileError as e:
            raise DesignError("model: %s" % e)
        loads = sorted(set(k for k in given if LOAD_OPTION.match(k) or k == "structure_stages"))
        if loads:
            raise DesignError("model %s sets %s: load options belong in the design file (base loads, load cases), "
                              "which gives them per stage" % (self.model, ", ".join("-" + k for k in loads)))
        for comb in self.combinations:
            # The scene has one velocity pressure (-structure_wind) per run: two wind cases would add
            # their q and share every zone's cp. Per-zone wind pressures that add up are
            # film_<zone>_pressure loads (kPa along the normal, = -cp q): docs/design-run.md.
            winds = [c for c in comb["factors"] if "structure_wind" in self.cases[c].get("loads", {})]
            if len(winds) > 1:
                raise DesignError("combination %s: load cases %s both give structure_wind, but a run has one velocity "
                                  "pressure; give wind cases that meet as per-zone pressures, film_<zone>_pressure "
                                  "= -cp q (kPa), which add up" % (comb["name"], " and ".join(winds)))
        for chk in self.checks:
            if chk.get("kind") == "cable_force" and not isinstance(chk.get("breaking_load"), dict):
                raise DesignError("check %s: a cable_force check needs breaking_load {cable group: N}"
                                  % chk.get("name", "cable_force"))
        self.validate_resistance()
        for opt, v in self.base_loads.items():
            if len(v) != self.base_stages:
                raise DesignError("base load %s has %d values for %d base stages" % (opt, len(v), self.base_stages))

    def validate_resistance(self):
        """Every combination a utilisation check applies to has a duration class and a strength for it
        (and its temperature) in every material the design names; refused by name otherwise."""
        r = self.resistance
        mats = sorted(set(r.groups.values()) | ({r.default} if r.default else set()))
        checked = set()
        for chk in self.checks:
            if chk.get("kind") == "utilisation":
                checked |= set(chk.get("situations", ["ULS", "SLS"]))
        for comb in self.combinations:
            try:
                dur, temp, _ = r.combination_class(comb, self.cases)
                if comb["situation"] in checked or comb.get("duration") is not None:
                    for m in mats:
                        r.design_strength(m, dur, temp, "combination %s" % comb["name"])
            except ResistanceError as e:
                raise DesignError(str(e))

    def mesh_file(self):
        """The run's mesh file (the design's options over the model's -mesh_file), as etfe finds it."""
        path = self.options.get("mesh_file")
        if path is None:
            model = self.model if os.path.isabs(self.model) else os.path.join(REPO, self.model)
            path = dict((k.lstrip("-"), v) for k, v in optionsfile.read(model)).get("mesh_file")
        if path is None:
            raise DesignError("resistance groups: the model gives no -mesh_file to read the surface groups from")
        return path if os.path.isabs(str(path)) else os.path.join(REPO, str(path))

    def strength_class(self, comb):
        """(duration class or None, temperature C, where they came from) of a combination."""
        return self.resistance.combination_class(comb, self.cases)

    def in_base(self, case):
        return bool(self.cases[case].get("in_base", False))

    def base_end(self, opt):
        v = self.base_loads.get(opt)
        return v[-1] if v else 0.0

    def combination_loads(self, comb):
        """{option: value in the combination's stage}."""
        opts = set(self.base_loads)
        for case in comb["factors"]:
            opts |= set(self.cases[case].get("loads", {}))
        res = {}
        for opt in sorted(opts):
            x = self.base_end(opt)
            for case, f in comb["factors"].items():
                v = self.cases[case].get("loads", {}).get(opt)
                if v is not None:
                    x += (f - (1.0 if self.in_base(case) else 0.0)) * float(v)
            res[opt] = x
        return res

    def fixed_options(self, comb):
        """Non-array options the combination's cases set (a wind case's pressure coefficients)."""
        res = {}
        for case in comb["factors"]:
            for k, v in self.cases[case].get("options", {}).items():
                if k in res and str(res[k]) != str(v):
                    raise DesignError("combination %s: load cases give %s both %s and %s" % (comb["name"], k, res[k], v))
                res[k] = v
        res.update(comb["options"])
        return res

    def common_args(self):
        args = ["-options_file", self.model]
        for k, v in self.options.items():
            args += ["-" + k, fmt(v)]
        return args + ["-load_monitor", "0"]

    def base_args(self, out_dir):
        args = self.common_args()
        for opt, v in sorted(self.base_loads.items()):
            args += ["-" + opt, ",".join(fmt(x) for x in v)]
        return args + ["-structure_stages", str(self.base_stages), "-load_increments",
                       str(self.per_stage * self.base_stages), "-output_file", os.path.join(out_dir, "base.h5"),
                       "-checkpoint_final"]

    def combination_args(self, comb, out_dir, branch=True):
        """The branch run's options (branch=False: the same history run directly from the start)."""
        n = self.base_stages
        args = self.common_args()
        for opt, x in self.combination_loads(comb).items():
            base = self.base_loads.get(opt, [0.0] * n)
            args += ["-" + opt, ",".join(fmt(v) for v in list(base) + [x])]
        for k, v in self.fixed_options(comb).items():
            args += ["-" + k, fmt(v)]
        args += ["-structure_stages", str(n + 1), "-load_increments", str(self.per_stage * (n + 1)),
                 "-output_file", os.path.join(out_dir, comb["name"] + ".h5")]
        if branch:
            args += ["-restart_branch", os.path.join(out_dir, "base.checkpoint.h5")]
        return args


def fmt(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return repr(v)
    return str(v)
