"""Capstan check of the friction contact (docs/theory.md §5.6): a film strip over a fixed pipe.

* mu_eff = ln(T2/T1)/theta within 3 % of mu = 0.3 at theta = 180 deg and the documented density
  (options/capstan.opts, 64 cells along the wrap), and the error shrinks as the wrap is
  discretised more finely (16 -> 32 -> 64 -> 128 cells);
* other wrap angles and mu = 1.0 (the thesis's friction cases) within 5 %;
* the increments study over 40..320 increments: the implicit law's mu_eff barely changes; the
  lagged (thesis) law, chaotic, either completes in its rough range or stops with a message (which
  of the two is round-off's choice); the lagged law with -contact_lagged_repeat
  changes monotonically, by less each doubling, within 1.5 % of the implicit law;
* stiff penalties: k_n = k_t from 1e2 to 1e12 N/mm all converge (or would stop with a message).
"""
import math
import sys

from etfe_testlib import Checker, etfe_path, opts, run, scene_value, summary

etfe = etfe_path()
chk = Checker("contact_capstan")


def mu_eff(extra):
    rc, out = run(etfe, ["-options_file", opts("capstan"), "-output", "0", "-load_monitor", "0"] + extra,
                  expect_fail=None)
    if rc != 0:
        return None, out
    return float(out.split("mu_eff = ")[1].split()[0]), out


print("density study (theta = 180 deg, mu = 0.3, implicit law, 40 increments)")
print("%8s %12s %10s %8s" % ("cells", "mu_eff", "error", "wall s"))
errors = []
for nx in (16, 32, 64, 128):
    m, out = mu_eff(["-mesh_nx", str(nx)])
    chk.check(m is not None, "capstan nx=%d completes" % nx)
    if m is None:
        continue
    err = abs(m - 0.3) / 0.3
    errors.append(err)
    print("%8d %12.6f %10.3e %8.3f" % (nx, m, err, summary(out)["wall"]))
    if nx == 64:
        chk.check(err < 0.03, "mu_eff %.5f within 3%% of 0.3 at the documented density (64 cells)" % m)
chk.check(all(b < a for a, b in zip(errors, errors[1:])), "the error shrinks with the density: %s" % ["%.4f" % e for e in errors])

print("\nother cases (64 cells)")
# mu = 1 needs T2 = 23 T1: a longer pull to stretch the strip that far before gross slip.
for angle, mu, pull in ((90, 0.3, 0.1), (180, 1.0, 1.0)):
    m, out = mu_eff(["-capstan_angle", str(angle), "-contact_mu", str(mu), "-capstan_pull", str(pull)])
    chk.check(m is not None, "capstan angle %g mu %g completes" % (angle, mu))
    if m is not None:
        err = abs(m - mu) / mu
        print("theta %5.1f deg mu %.2f: mu_eff %.6f error %.3e" % (angle, mu, m, err))
        chk.check(err < 0.05, "angle %g mu %g: mu_eff %.5f within 5%%" % (angle, mu, m))

print("\nincrements study (64 cells)")
spread, series, outs = {}, {}, {}
laws = (("implicit", []), ("lagged", []), ("lagged-settled", ["-contact_lagged_repeat", "20"]))
for name, extra in laws:
    vals, outs[name] = [], []
    for n in (40, 80, 160, 320):
        m, out = mu_eff(["-contact_friction", name.split("-")[0], "-load_increments", str(n)] + extra)
        outs[name].append(out)
        s = summary(out) if "etfe: " in out else None
        print("%-15s %4d increments: mu_eff %s, Newton %s, wall %s s" %
              (name, n, "%.6f" % m if m is not None else "none (no gross slip)",
               s["newton"] if s else "-", "%.3f" % s["wall"] if s else "-"))
        vals.append(m)
    series[name] = vals
    done = [v for v in vals if v is not None]
    spread[name] = (max(done) - min(done)) if len(done) > 1 else float("inf")
print("spread over increments: " + ", ".join("%s %.4f" % (k, v) for k, v in spread.items()))
# (spread is infinite when fewer than two lagged runs reached gross slip: the comparison holds)
chk.check(spread["implicit"] < spread["lagged"],
          "the implicit law should depend less on the number of increments than the lagged one")
chk.check(all(v is not None for v in series["implicit"]) and spread["implicit"] < 0.01,
          "implicit mu_eff varies by %.4f over 40..320 increments" % spread["implicit"])
# The thesis's lagged law decides each increment's statuses at its start and takes a slipping
# pair's next direction from a step without tangential stiffness: its path is chaotic, so which
# increment counts reach gross slip is decided by round-off (another BLAS kernel, another CPU).
# Measured on one AMD EPYC at 40/80/160/320 increments: 0.586 / 0.456 / 0.369 / 0.363 with
# OpenBLAS's Prescott kernel, 0.586 / 0.456 / none / 0.545 with Sandybridge's, and with Haswell's
# 0.456 at 80 increments in one run and none in another (none: the run stops after its cut-backs,
# no gross slip). So only what holds on any machine is asserted: every run either
# completes in the law's rough range (its sticking pairs overshoot the cone for an increment, so
# it errs upward, and it does not fall far below mu) or stops with the load stepper's message
# (non-zero exit: an increment that did not converge, or one whose stabilization carried the
# load), never a crash or a result out of range.
plain = series["lagged"]
for n, v, out in zip((40, 80, 160, 320), plain, outs["lagged"]):
    if v is not None:
        chk.check(0.9 * 0.3 < v < 3.0 * 0.3, "plain lagged law at %d increments: 0.9 mu < mu_eff %.5f < 3 mu" % (n, v))
    else:
        chk.check(("did not converge after" in out and "Ways out" in out) or "not in equilibrium" in out,
                  "plain lagged law at %d increments stops with the load stepper's message: %s"
                  % (n, out.strip().splitlines()[-1][:200] if out.strip() else "(no output)"))
# -contact_lagged_repeat: statuses settled within each increment, directions kept while slipping.
# Measured 0.29079 / 0.29130 / 0.29254 / 0.29275 (implicit 0.2937): it rises steadily toward the
# implicit law, its change per doubling shrinking, within 1.5 % of it throughout.
settled, imp = series["lagged-settled"], series["implicit"][-1]
chk.check(all(v is not None for v in settled), "settled lagged law completes at 40..320 increments")
if all(v is not None for v in settled) and imp is not None:
    steps = [b - a for a, b in zip(settled, settled[1:])]
    chk.check(all(d > 0 for d in steps) or all(d < 0 for d in steps),
              "settled lagged mu_eff changes monotonically with the increments: %s" % ["%.5f" % v for v in settled])
    chk.check(abs(steps[-1]) < abs(steps[0]), "its change per doubling shrinks: %s" % ["%.1e" % d for d in steps])
    errs = [abs(v - imp) / imp for v in settled]
    chk.check(max(errs) < 0.015 and errs[-1] < errs[0],
              "settled lagged mu_eff within 1.5 %% of the implicit law's %.5f and closer at 320 than at 40: %s"
              % (imp, ["%.4f" % e for e in errs]))

print("\nlarge slide: frozen frame (thesis) vs following frame, pull 1 mm (64 cells)")
ends = {}
for normal in ("frozen", "follow"):
    rc, out = run(etfe, ["-options_file", opts("capstan"), "-output", "0", "-load_monitor", "0", "-capstan_pull", "1.0",
                         "-contact_normal", normal])
    t2_end = float(out.split("T2 at the end = ")[1].split()[0])
    ends[normal] = t2_end / (2.5 * math.exp(0.3 * math.pi)) - 1.0
    print("%-7s T2 at the end of the pull: %.4f N, %+.2f %% from T1 exp(mu theta)" % (normal, t2_end, 100 * ends[normal]))
chk.check(abs(ends["follow"]) < 0.01, "following frame: the gross-slip plateau stays within 1 %% of T1 exp(mu theta) (%+.2f %%)"
          % (100 * ends["follow"]))
chk.check(ends["frozen"] > 5 * abs(ends["follow"]), "the frozen frame drifts off the plateau as the slide grows (%+.2f %%)"
          % (100 * ends["frozen"]))

print("\nstiff penalties (k_n = k_t)")
for k in ("1e2", "1e4", "1e6", "1e8", "1e10", "1e12"):
    m, out = mu_eff(["-contact_kn", k, "-contact_kt", k])
    s = summary(out) if "etfe: " in out else None
    print("k %6s N/mm: %s" % (k, "mu_eff %.6f, Newton %d, cut-backs %d" % (m, s["newton"], s["cutbacks"])
                               if m is not None else "stopped: " + out.strip().splitlines()[-1][:200]))
    chk.check(m is not None and abs(m - 0.3) < 0.03, "penalty %s N/mm converges to mu_eff within 10%% of mu" % k)
chk.finish()
