#!/usr/bin/python3
"""The viscoelastic-plastic law in the lab scene (-scene strip) and its input checks:
  * standard linear solid (one Maxwell branch, tau 50 s, g 0.4, a yield of 100 MPa, far out of reach): a strain
    applied instantly (a stage of 0 s) then held 500 s; every increment of the hold carries
    S = E0 E (g_inf + g exp(-t/tau)) in every element (the closed form, to 1e-6 of E0 E; the
    recursion is exact for a held strain);
  * Comitti & Bosi's published MD compliance converted to a relaxation spectrum
    (options/material/comitti_bosi_2024_md.opts): a creep test at 0.5 MPa gives the effective
    modulus S/E = 1/D(t) of their compliance at 1, 1e2, 1e3, 1e4, 1e5 s within 0.5 % (the
    tolerance the interconversion is asked to meet; the creep stress in PK2 moves by ~strain,
    6e-4, under the dead nominal force), and in the model's own measures, nominal stress over
    engineering strain, within 1e-4 (the set runs the law in them: -material_strain_measure
    engineering; in Green-Lagrange/PK2 it was 6.4e-4 above); at 8 MPa (0.68-0.87 % strain) the
    same within 1e-4 (in Green-Lagrange/PK2: 1.0-1.3 % above);
  * the same load history cut into other stages at the same times gives the same answer: the
    thesis's ETFE drawn to 1 % in 10 s and held to 3 610 s as (ramp, log-spaced hold), (two half
    ramps, a plain stage of 1 800 s, a hold of 1 800 s) and (ramp, one plain stage of 3 600 s): the
    final stress agrees to 1e-8 (a held strain integrates exactly with any steps);
  * with no Maxwell branch the law prints the plastic law's figures digit for digit (patch,
    loading past both yields, unloading and reloading);
  * bad input is refused naming the option: a negative relaxation time or modulus, an unsorted
    spectrum, moduli summing to 1 or more, a temperature below absolute zero, a hold in a
    form-finding run, -load_hold_after without durations, the tension-field wrapper.
"""
import csv
import math
import os

import etfe_testlib as T

SLS = ["-material_type", "viscoelastic_plastic", "-material_young", 800, "-material_poisson", 0.43,
       "-material_prony_tau", 50, "-material_prony_g", 0.4, "-material_yield", 100, "-material_hardening", 0]


def rows(path):
    with open(path) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def compliance(path):
    D0, terms = None, []
    for line in open(path):
        if line.startswith("#") or not line.strip():
            continue
        d, tau = (float(x) for x in line.split(","))
        if D0 is None:
            D0 = d
        else:
            terms.append((d, tau))
    return lambda t: D0 + sum(d * (1 - math.exp(-t / tau)) for d, tau in terms)


def sls_relaxation(etfe, chk, tmp):
    csvp = os.path.join(tmp, "sls.csv")
    T.run(etfe, ["-scene", "strip", "-strip_test", "relaxation", "-strip_strain", 0.004] + SLS
          + ["-load_stage_duration", 0, "-load_hold_after", 1, "-load_hold_duration", 500, "-load_increments", 40,
             "-strip_history", csvp, "-output", 0, "-load_monitor", 0])
    worst, n = 0.0, 0
    for r in rows(csvp):
        if r["load_time"] <= 1.0:
            continue
        exact = 800.0 * r["strain_gl"] * (0.6 + 0.4 * math.exp(-r["seconds"] / 50.0))
        worst = max(worst, abs(r["stress_pk2"] - exact) / (800.0 * r["strain_gl"]))
        n += 1
    chk.check(n == 20, "SLS relaxation: %d increments in the hold" % n)
    chk.less(worst, 1e-6, "SLS relaxation on the strip: largest |S - E0 E (g_inf + g exp(-t/tau))| / (E0 E)")


def comitti_creep(etfe, chk, tmp, stress=0.5):
    csvp = os.path.join(tmp, "cb.csv")
    T.run(etfe, ["-scene", "strip", "-strip_test", "creep", "-strip_stress", stress,
                 "-options_file", "options/material/comitti_bosi_2024_md.opts",
                 "-load_stage_duration", 0, "-load_hold_after", 1, "-load_hold_duration", 1e5, "-load_hold_first", 1e-3,
                 "-load_increments", 160, "-strip_history", csvp, "-output", 0, "-load_monitor", 0])
    D = compliance("options/material/comitti_bosi_2024_md_compliance.csv")
    rs = rows(csvp)
    for target in (1.0, 1e2, 1e3, 1e4, 1e5):
        r = min(rs, key=lambda r: abs(math.log(max(r["seconds"], 1e-30) / target)))
        modulus = r["stress_pk2"] / r["strain_gl"]
        rel = modulus * D(r["seconds"]) - 1.0
        if stress < 1.0:  # in PK2/GL the measures differ by 1.5 x strain: small at 0.5 MPa only
            chk.less(abs(rel), 5e-3, "Comitti & Bosi MD creep at %.4g s: S/E = %.2f MPa against 1/D(t) = %.2f MPa, "
                     "relative difference" % (r["seconds"], modulus, 1 / D(r["seconds"])))
        # In the model's own measures (their tests': nominal stress, engineering strain), which the set's
        # -material_strain_measure engineering runs the law in: the interconversion's accuracy, not the
        # measures' 1.5 x strain (6e-4 here).
        nominal = r["stress_nominal"] / r["strain"]
        rel = nominal * D(r["seconds"]) - 1.0
        chk.less(abs(rel), 1e-4, "Comitti & Bosi MD creep at %g MPa, %.4g s (strain %.3g %%), nominal stress / "
                 "engineering strain %.3f MPa against 1/D(t) = %.3f MPa, relative difference"
                 % (stress, r["seconds"], 100 * r["strain"], nominal, 1 / D(r["seconds"])))


def same_history_other_stages(etfe, chk):
    base = ["-scene", "strip", "-options_file", "options/material/thesis_etfe.opts", "-output", 0, "-load_monitor", 0]
    cuts = {"ramp + hold": ["-strip_schedule", 1, "-load_stage_duration", 10, "-load_hold_after", 1,
                            "-load_hold_duration", 3600, "-load_increments", 40],
            "two half ramps + stage + hold": ["-strip_schedule", "0.5,1,1", "-load_stage_duration", "5,5,1800",
                                              "-load_hold_after", 3, "-load_hold_duration", 1800,
                                              "-load_increments", 80],
            "ramp + plain stage": ["-strip_schedule", "1,1", "-load_stage_duration", "10,3600",
                                   "-load_increments", 40]}
    stress = {}
    for name, args in cuts.items():
        _, out = T.run(etfe, base + args)
        line = [l for l in out.splitlines() if l.startswith("strip: relaxation at the end (3610 s)")]
        chk.check(len(line) == 1, "%s ends at 3610 s" % name)
        stress[name] = float(line[0].split("stress ")[1].split()[0]) if line else float("nan")
    ref = stress["ramp + hold"]
    for name, v in list(stress.items())[1:]:
        chk.less(abs(v / ref - 1.0), 1e-8, "stress at 3610 s, %s (%.9f MPa) against ramp + hold (%.9f): relative"
                 % (name, v, ref))


def no_branch_is_plastic(etfe, chk):
    base = ["-options_file", T.opts("patch"), "-patch_strain_x", 0.2, "-patch_schedule", "1,0.8,1.5",
            "-load_increments", 30, "-output", 0, "-load_monitor", 0]
    _, a = T.run(etfe, base + ["-material_type", "plastic"])
    _, b = T.run(etfe, base + ["-material_type", "viscoelastic_plastic", "-load_stage_duration", 10])
    pa = [l for l in a.splitlines() if l.startswith("patch:")]
    pb = [l for l in b.splitlines() if l.startswith("patch:")]
    chk.check(pa and pa == pb, "no Maxwell branch: the patch's figures equal the plastic law's digit for digit")


def bad_input(etfe, chk):
    strip = ["-scene", "strip", "-output", 0, "-load_monitor", 0]
    cases = [
        (SLS + ["-material_prony_tau", -5], "-material_prony_tau: relaxation time 1 is -5"),
        (SLS + ["-material_prony_tau", "10,5", "-material_prony_g", "0.1,0.2"], "-material_prony_tau: the spectrum is not sorted"),
        (SLS + ["-material_prony_g", -0.1], "-material_prony_g: modulus fraction 1 is -0.1"),
        (SLS + ["-material_prony_tau", "10,20", "-material_prony_g", "0.6,0.5"], "-material_prony_g sums to 1.1"),
        (SLS + ["-material_temperature", -300], "-material_temperature -300"),
        (SLS + ["-material_reference_temperature", -274], "-material_reference_temperature -274"),
        (SLS + ["-load_hold_after", 1], "-load_hold_after has 1 stages but -load_hold_duration 0"),
        (SLS + ["-load_hold_after", 1, "-load_hold_duration", -1], "-load_hold_duration: hold 1 lasts -1"),
        (SLS + ["-load_stage_duration", "1,2,3"], "-load_stage_duration has 3 values"),
        (SLS + ["-membrane_wrinkling", "tension_field"], "-membrane_wrinkling tension_field with -material_type "
                                                         "viscoelastic_plastic"),
    ]
    for args, words in cases:
        _, out = T.run(etfe, strip + args, expect_fail=True)
        chk.check(words in out, "refused naming the option: %s" % words)
    _, out = T.run(etfe, ["-options_file", "options/saddle/ff_r15_s11.opts", "-load_hold_after", 1,
                          "-load_hold_duration", 100, "-output", 0], expect_fail=True)
    chk.check("form finding (-analysis formfind)" in out and "-load_hold_after" in out,
              "a hold in a form-finding run is refused by name")


def main_test(etfe, chk):
    with T.scratch_dir("etfe-viscoelastic") as tmp:
        sls_relaxation(etfe, chk, tmp)
        comitti_creep(etfe, chk, tmp)
        comitti_creep(etfe, chk, tmp, 8.0)  # 0.68-0.87 % strain: 1.0-1.3 % apart in Green-Lagrange/PK2
    same_history_other_stages(etfe, chk)
    no_branch_is_plastic(etfe, chk)
    bad_input(etfe, chk)


if __name__ == "__main__":
    T.main(main_test)
