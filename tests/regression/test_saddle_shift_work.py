"""The adaptive tangent shift of the saddle cases read as a pseudo-transient (proximal-point) term:
the energy its viscous force would dissipate, sum over Newton iterations of
shift_k |x_{k+1} - x_k|^2, is reported per increment (progress line and the history CSV) next to
the work done on the film, and in total at the end; on DD1511 (thesis density, first 20
increments) it is small against the work, smallest once the film is taut, and it is absent
without a shift."""
import re

from etfe_testlib import NUMBER, dd1511_case, form_found_saddle, increments, main, scratch_dir

INCREMENTS = 20
TOTAL = re.compile(r"^etfe: work done on the film (%s) N mm; the tangent shift .* would dissipate (%s) N mm" %
                   (NUMBER, NUMBER), re.M)


def test(etfe, chk):
    with scratch_dir() as tmp:
        msh = form_found_saddle(etfe, tmp)

        def case(name, extra):
            return dd1511_case(etfe, msh, tmp, name, ["-load_stop_after", INCREMENTS] + extra)

        out, rows = case("shift", [])
        lines = {i["step"]: (i["work"], i["shift_work"]) for i in increments(out) if i["work"] is not None}
        chk.check(len(lines) == len(increments(out)) and len(lines) >= 2,
                  "%d progress lines carry work and shift work (of %d)" % (len(lines), len(increments(out))))
        chk.check(len(rows) == INCREMENTS and all("work" in r and "shift_work" in r for r in rows),
                  "history CSV: %d rows with work and shift_work" % len(rows))
        work = [float(r["work"]) for r in rows]
        shift = [float(r["shift_work"]) for r in rows]
        # The printed values are the CSV's, rounded.
        same = all(abs(lines[k][0] - work[k - 1]) <= 1e-3 * abs(work[k - 1]) and
                   abs(lines[k][1] - shift[k - 1]) <= 0.06 * shift[k - 1] for k in lines)
        chk.check(same, "printed work/shift work agree with the CSV at steps %s" % sorted(lines))
        chk.check(all(w > 0 for w in work), "drawing: positive work on the film in every increment (min %.3g N mm)" % min(work))
        chk.check(all(s >= 0 for s in shift) and shift[0] > 0,
                  "shift work >= 0, and > 0 in the slack first increment (%.3g N mm)" % shift[0])
        chk.less(sum(shift) / sum(work), 1e-4, "shift work / work over %d increments" % INCREMENTS)
        chk.less(shift[-1] / work[-1], 1e-6, "shift work / work in increment %d (film taut)" % INCREMENTS)
        m = TOTAL.search(out)
        chk.check(m is not None and abs(float(m.group(1)) - sum(work)) <= 1e-5 * sum(work) and
                  abs(float(m.group(2)) - sum(shift)) <= 2e-3 * sum(shift),
                  "the run's total (%s) is the sum of the increments (%.6e, %.3e)"
                  % (m.group(0) if m else "missing", sum(work), sum(shift)))

        # Without a tangent shift nothing is dissipated: the CSV says 0 and the line stays as before.
        out0, rows0 = case("noshift", ["-membrane_tangent_shift", 0, "-load_stop_after", 3])
        chk.check(len(rows0) == 3 and all(float(r["shift_work"]) == 0 for r in rows0) and not any(i["work"] is not None for i in increments(out0)),
                  "no shift: shift work 0 in the CSV, not printed")
        chk.check(all(abs(float(r0["work"]) - w) <= 1e-6 * abs(w) for r0, w in zip(rows0, work)),
                  "no shift: the same work per increment (the shift does not change the answer)")


main(test)
