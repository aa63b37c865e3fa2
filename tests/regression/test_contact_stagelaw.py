"""Friction law per stage: -contact_friction a,b gives each stage its law (the last one
for the stages after it), on the capstan (stage 1 tensions the strip, stage 2 pulls end B).

* a list that repeats one law is the single-law run, bit for bit;
* implicit,fixed: the strip slides while it is tensioned, then the pipe holds it: the probe
  pair's slide stops at the stage change (it keeps growing with implicit), and no gross slip
  is reached (the scene says so);
* fixed,implicit: the pairs leave the glued state by the return map and the pull reaches gross
  slip; a restart from a checkpoint inside stage 2 continues it bit for bit, and a restart that
  changes the list is refused naming -contact_friction;
* a list longer than the stages, an unknown law, and a lagged stage with the following frame
  are refused with a message.
"""
import csv
import os

from etfe_testlib import Checker, error_message, etfe_path, opts, run, scratch_dir
import h5compare

etfe = etfe_path()
chk = Checker("contact_stagelaw")
base = ["-options_file", opts("capstan"), "-load_monitor", "0"]


def probe(path):
    """[(step, time, slide_x0)] of a probe CSV."""
    with open(path) as f:
        return [(int(r["step"]), float(r["time"]), float(r["slide_x0"])) for r in csv.DictReader(f)]


def mu_eff(out):
    return [l for l in out.splitlines() if l.startswith("mu_eff")]


with scratch_dir() as tmp:
    path = lambda name: os.path.join(tmp, name + ".h5")
    rc, one = run(etfe, base + ["-contact_friction", "implicit", "-output_file", path("one")])
    rc, two = run(etfe, base + ["-contact_friction", "implicit,implicit", "-output_file", path("two")])
    fails = h5compare.compare(path("one"), path("two"), step="all", default_rtol=0.0, default_atol=0.0)
    chk.check(not fails and mu_eff(one) == mu_eff(two) and mu_eff(one),
              "implicit,implicit is the single-law run bit for bit (%s)" % (mu_eff(two) or fails[:2]))

    rc, held = run(etfe, base + ["-contact_friction", "implicit,fixed", "-output_file", path("held")], expect_fail=True)
    chk.check("no gross slip" in held, "implicit,fixed: the held strip never slips (%s)" % error_message(held)[:120])
    slides = {}
    for name in ("one", "held"):
        rows = probe(os.path.join(tmp, name + "_contact_node32.csv"))
        at1 = [s for step, t, s in rows if abs(t - 1.0) < 1e-9][0]
        slides[name] = max(abs(s - at1) for step, t, s in rows if t > 1.0)
    print("probe node 32, slide after the end of stage 1: implicit %.3e mm, implicit,fixed %.3e mm"
          % (slides["one"], slides["held"]))
    chk.check(slides["held"] < 1e-3 and slides["one"] > 1e-2,
              "the fixed stage holds the node where stage 1 left it (%.2e mm; the implicit law slides %.2e mm)"
              % (slides["held"], slides["one"]))

    free = base + ["-contact_friction", "fixed,implicit"]
    rc, full = run(etfe, free + ["-output_file", path("full")])
    chk.check(rc == 0 and mu_eff(full), "fixed,implicit reaches gross slip (%s)" % mu_eff(full))
    ck = path("ck")
    rc, out = run(etfe, free + ["-output_file", path("part"), "-load_stop_after", 25, "-checkpoint_file", ck])
    rc, out = run(etfe, free + ["-output_file", path("part"), "-restart", ck])
    fails = h5compare.compare(path("full"), path("part"), step="all", default_rtol=0.0, default_atol=0.0)
    chk.check(not fails and mu_eff(out) == mu_eff(full),
              "fixed,implicit restarted inside stage 2 continues bit for bit%s" % ("" if not fails else ": %s" % fails[:2]))
    rc, out = run(etfe, base + ["-contact_friction", "fixed,lagged", "-output_file", path("part2"), "-restart", ck],
                  expect_fail=True)
    words = "-contact_friction checkpoint: fixed,implicit this run: fixed,lagged"
    chk.check(words in " ".join(out.split()), "a restart with another list is refused naming it (%s)" % words)

for args, words in ((["-contact_friction", "implicit,fixed,none"], "lists 3 laws but the analysis has 2 stages"),
                    (["-contact_friction", "implicit,glued"], '"glued" (entry 2) is not a friction law'),
                    (["-contact_friction", "implicit,lagged", "-contact_normal", "follow"], "frozen frame")):
    rc, out = run(etfe, base + ["-output", "0"] + args, expect_fail=True)
    chk.check(words in error_message(out), "%s refused: %s" % (" ".join(args), error_message(out)[:140]))
chk.finish()
