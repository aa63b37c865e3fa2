"""The dense-mesh levers (the predictor shift and the round-off floor, the saddle cases'
default in options/saddle/stretch_base.opts, and the others tried) do not move the answer: DD1511
on the form-found 1:1 saddle at 10^4 triangles, first 3 of 200 increments, part A/B Mises and the
five slides of every step agree with the plain run (levers off) to 1e-6 of each quantity's largest
value; the default takes no more Newton iterations than the plain run."""

from etfe_testlib import dd1511_case, form_found_saddle, increments, largest_history_difference, main, scratch_dir

INCREMENTS = 3
PLAIN = ["-load_tangent_predictor_shift", "0", "-load_force_roundoff", "0"]
LEVERS = {
    "default": [],
    "all levers": ["-membrane_tangent_shift", "3e-5", "-snes_linesearch_etfe_max_update", "0",
                   "-snes_linesearch_etfe_max_strain_update", "0.05"],
}
COLUMNS = ["A_mises", "B_mises"] + ["slide%d_%s" % (i, c) for i in range(1, 6) for c in "XY"]


def test(etfe, chk):
    with scratch_dir() as tmp:
        msh = form_found_saddle(etfe, tmp, "ff_r15_s11.opts", ["-mesh_n", 50], name="ff_n50")

        def case(name, extra):
            out, history = dd1511_case(etfe, msh, tmp, name, ["-load_stop_after", INCREMENTS] + extra)
            its = [i["newton"] for i in increments(out)]
            print("%-10s Newton per increment %s" % (name, its))
            return its, history

        its0, h0 = case("plain", PLAIN)
        chk.check(len(h0) == INCREMENTS, "plain run: %d history rows" % len(h0))
        for name, extra in LEVERS.items():
            its, h = case(name.replace(" ", "_").replace(".", "_"), extra)
            chk.check(len(h) == len(h0), "%s: %d history rows" % (name, len(h)))
            worst, where = largest_history_difference(h0, h, COLUMNS)
            chk.less(worst, 1e-6, "%s: largest difference from the plain run (at step/column %s)" % (name, where))
            if name == "default":
                chk.check(sum(its) <= sum(its0), "default levers: %d Newton iterations <= plain %d" % (sum(its), sum(its0)))


main(test)
