"""-contact_penalty_length L0: contact penalties per unit length of the contact line.

A pair's kn, kt are the given ones times its tributary length along the line over L0, so refining
the mesh keeps the interface's stiffness (per-node penalties stiffen it as 1/h).

DD1511 at the thesis density (19 arch pairs, ~55 mm apart), 40 increments (the saddle cases' default
is L0 = 55.4; 0 gives per-node penalties):
* L0 = 55.4 mm (the interior pairs' tributary length) leaves the answer within 1e-4 (part A/B
  Mises) of the per-node run; the end pair (I, Y = 0) has half a tributary length, so half the
  tangential stiffness, and slides further than with per-node penalties;
* halving L0 doubles every pair's penalties: pair I's slide shrinks again;
* only kn/L0 and kt/L0 matter: (k, L0) and (2k, 2L0) give the same history;
* bad input: a negative length, and a contact area (the capstan's pipe, where pair nodes do not
  form lines), are refused with messages naming the option.
"""

from etfe_testlib import (dd1511_case, error_message, form_found_saddle, main, opts, run, saddle_report,
                          scene_values, scratch_dir)

L0 = 55.4


def test(etfe, chk):
    with scratch_dir() as tmp:
        msh = form_found_saddle(etfe, tmp)

        def case(name, extra):
            out, history = dd1511_case(etfe, msh, tmp, name, ["-load_increments", 40, "-load_monitor", 0] + extra)
            rep = saddle_report(out)
            res = {"A": rep["A_mises"], "B": rep["B_mises"], "slide1": scene_values(out, "saddle")["slide_1"]["X"],
                   "history": history}
            print("%-10s part A %.6f, part B %.6f MPa, slide I %.6f mm" % (name, res["A"], res["B"], res["slide1"]))
            return res

        node = case("per_node", ["-contact_penalty_length", 0])  # the saddle default is per length
        per_len = case("per_length", ["-contact_penalty_length", L0])
        half = case("half_L0", ["-contact_penalty_length", L0 / 2])
        for part in ("A", "B"):
            rel = abs(per_len[part] - node[part]) / node[part]
            chk.check(rel < 1e-4, "part %s Mises per length vs per node: %.2e relative (< 1e-4)" % (part, rel))
        chk.check(per_len["slide1"] > node["slide1"],
                  "pair I (half a tributary length: half the stiffness) slides further: %.6f > %.6f mm"
                  % (per_len["slide1"], node["slide1"]))
        chk.check(half["slide1"] < per_len["slide1"],
                  "L0 halved (penalties doubled): pair I slides less: %.6f < %.6f mm" % (half["slide1"], per_len["slide1"]))
        scaled = case("scaled", ["-contact_penalty_length", 2 * L0, "-contact_kn", 4e4, "-contact_kt", 4e4])
        chk.check(scaled["history"] == per_len["history"],
                  "(k, L0) and (2k, 2 L0) give the same history (%d rows)" % len(per_len["history"]))

    rc, out = run(etfe, ["-options_file", opts("capstan"), "-output", 0, "-contact_penalty_length", -1],
                  expect_fail=True)
    msg = error_message(out)
    chk.check("-contact_penalty_length" in msg and ">= 0" in msg, "a negative length is refused: %s" % msg[:120])
    rc, out = run(etfe, ["-options_file", opts("capstan"), "-output", 0, "-contact_penalty_length", 10],
                  expect_fail=True)
    msg = error_message(out)
    chk.check("-contact_penalty_length" in msg and "form lines" in msg,
              "a contact area (capstan pipe) is refused, naming the option: %s" % msg[:160])


main(test)
