"""-load_max_it: the Newton limit of every increment but the history's first.

DD1511 at the thesis density, first 12 of 200 increments:
* with -load_max_it 3 the first increment still converges with more than 3 iterations (the slack
  start keeps -snes_max_it), a later increment fails after exactly 3 with a message naming
  -load_max_it and is cut back, every converged later increment takes at most 3, and the run goes on;
* the saddle default (60) is never reached at this density: the Newton iterations and the history
  equal those of -load_max_it 0 (the limit off) exactly.
"""
import re

from etfe_testlib import dd1511_case, form_found_saddle, increments, main, scratch_dir

INCREMENTS = 12


def test(etfe, chk):
    with scratch_dir() as tmp:
        msh = form_found_saddle(etfe, tmp)

        def case(name, extra):
            out, history = dd1511_case(etfe, msh, tmp, name, ["-load_stop_after", INCREMENTS, "-checkpoint_every", 0] + extra)
            its = [i["newton"] for i in increments(out)]
            print("%-8s Newton per increment %s" % (name, its))
            return out, its, history

        out, its, _ = case("limit3", ["-load_max_it", 3, "-load_stabilize_when", "never"])
        chk.check(len(its) == INCREMENTS, "-load_max_it 3: %d of %d increments converged" % (len(its), INCREMENTS))
        chk.check(its and its[0] > 3, "the first increment keeps -snes_max_it: %s iterations" % (its[:1],))
        chk.check(all(n <= 3 for n in its[1:]), "later increments take at most 3 iterations: %s" % its[1:])
        fails = re.findall(r"failed: DIVERGED_MAX_IT after (\d+) Newton iterations.*?-load_max_it", out)
        chk.check(fails and all(f == "3" for f in fails),
                  "a later increment fails after 3 iterations naming -load_max_it (%d such lines)" % len(fails))
        chk.check(re.search(r"\b%d cut-backs" % len(fails), out) is not None, "every such failure is one cut-back")

        _, its_default, h_default = case("default", [])
        _, its_off, h_off = case("off", ["-load_max_it", 0])
        chk.check(its_default == its_off, "default limit vs off: Newton %s vs %s" % (its_default, its_off))
        chk.check(h_default == h_off, "default limit vs off: identical history (%d rows)" % len(h_off))
        chk.check(max(its_default[1:]) < 60, "the default limit (60) is not reached: largest later increment %d"
                  % max(its_default[1:]))


main(test)
