"""Capstan check of the friction contact (SPEC §9, issue 4): a film strip over a fixed pipe.

* mu_eff = ln(T2/T1)/theta within 3 % of mu = 0.3 at theta = 180 deg and the documented density
  (options/capstan.opts, 64 cells along the wrap), and the error shrinks as the wrap is
  discretised more finely (16 -> 32 -> 64 -> 128 cells);
* other wrap angles and mu = 1.0 (the thesis's friction cases) within 5 %;
* the increments study: the implicit law's mu_eff changes less over 40..320 increments than the
  lagged (thesis) law's, and the lagged law's falls steadily toward mu;
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
spread, series = {}, {}
for law in ("implicit", "lagged"):
    vals = []
    for n in (40, 80, 160, 320):
        m, out = mu_eff(["-contact_friction", law, "-load_increments", str(n)])
        s = summary(out) if "etfe: " in out else None
        print("%-8s %4d increments: mu_eff %s, Newton %s, wall %s s" %
              (law, n, "%.6f" % m if m is not None else "none (no gross slip)",
               s["newton"] if s else "-", "%.3f" % s["wall"] if s else "-"))
        if m is not None:
            vals.append(m)
    spread[law] = (max(vals) - min(vals)) if len(vals) > 1 else float("inf")
    series[law] = vals
print("spread over increments: implicit %.4f, lagged %.4f" % (spread["implicit"], spread["lagged"]))
chk.check(spread["implicit"] < spread["lagged"],
          "the implicit law should depend less on the number of increments than the lagged one")
# The lagged law's error is its one-increment lag (k_t times the slide of an increment, far above
# a pair's Coulomb limit here), so it only approaches mu as the increments shrink; since its
# pairs stick again and turn (issue 16) it does so steadily, from above.
lag = series["lagged"]
chk.check(len(lag) == 4 and all(b < a for a, b in zip(lag, lag[1:])) and lag[-1] > 0.3 * 0.97,
          "lagged mu_eff approaches mu = 0.3 steadily from above over 40..320 increments: %s" % ["%.4f" % v for v in lag])
chk.check(spread["implicit"] < 0.01, "implicit mu_eff varies by %.4f over 40..320 increments" % spread["implicit"])

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
