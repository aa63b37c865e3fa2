#!/usr/bin/python3
"""The streamed set-up (src/mesh/distribute.cpp): rank 0 alone builds or reads the scene and sends
each rank its share, so the share a rank receives shrinks with the ranks (the header's "set-up:"
line gives the bytes); the same answer on 1, 2 and 3 ranks; and what rank 0 alone decides about
the mesh (a missing group, a mesh that is not the scene's, contact nodes that do not form lines,
a broken file) is refused with the same message on every rank, not a hang."""
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402
import badmesh_cases  # noqa: E402

def shares(out):
    return T.lines.header(out).get("share_kb")


def main_test(etfe, chk):
    with T.scratch_dir("par-setup") as tmp:
        # 1. Shares and answers: Hencky with 36 rings (7 776 triangles) in one increment.
        res = {}
        for np_ in (1, 2, 3):
            rc, out = T.run(etfe, ["-options_file", T.opts("hencky"), "-mesh_rings", 36, "-load_increments", 1,
                                   "-output_file", os.path.join(tmp, "h%d.h5" % np_)], np=np_)
            res[np_] = out
            chk.check(shares(out) is not None, "np=%d: the header reports the set-up shares" % np_)
        s1, s2, s3 = (shares(res[n]) or (0, 0) for n in (1, 2, 3))
        print("shares (max, min) kB: 1 rank %s, 2 ranks %s, 3 ranks %s" % (s1, s2, s3))
        chk.check(s1[0] > 300, "1 rank: the whole mesh is one share of %d kB (> 300 kB for 7 776 triangles)" % s1[0])
        chk.less(s2[0], 0.6 * s1[0], "2 ranks: the largest share against the whole (%d of %d kB)" % (s2[0], s1[0]))
        chk.less(s3[0], 0.42 * s1[0], "3 ranks: the largest share against the whole (%d of %d kB)" % (s3[0], s1[0]))
        chk.check(s2[0] + s2[1] >= s1[0], "2 ranks: the shares together hold at least the whole mesh (ghosts twice)")
        first = {n: T.increments(res[n])[:1] for n in (1, 2, 3)}
        d = {n: (first[n][0]["newton"], first[n][0]["residual"]) if first[n] else None for n in first}
        print("increment 1 (Newton, |R|):", d)
        chk.check(d[1] and d[1][0] == d[2][0] == d[3][0], "increment 1 takes the same Newton iterations on 1, 2, 3 ranks")
        cd = {n: T.scene_values(res[n], "hencky", printed=True).get("centre_deflection", {}).get("centre_deflection")
              for n in (1, 2, 3)}
        chk.check(cd[1] and T.printed_agree(cd[1], cd[2]) and T.printed_agree(cd[1], cd[3]),
                  "hencky centre deflection after increment 1 on 1, 2, 3 ranks: %s" % cd)

        # 2. Refusals decided on rank 0, raised on every rank of 2.
        small = os.path.join(tmp, "square.msh")  # 500 mm: short of the saddle's arch line X = 1000
        badmesh_cases.write_msh(small, badmesh_cases.grid_nodes(500.0), badmesh_cases.grid_triangles())
        no_group = os.path.join(tmp, "no_left.msh")
        with open(small) as f:
            text = f.read()
        with open(no_group, "w") as f:  # the left edge's group under another name
            f.write(text.replace('"left"', '"west"'))
        crack = next(c for c in badmesh_cases.cases(tmp) if c[0].startswith("duplicate nodes"))
        cases = [
            ("patch mesh without the left edge's group", ["-options_file", badmesh_cases.PATCH_OPTS, "-mesh_file",
                                                           no_group], 'physical group named "left"'),
            ("saddle on a square that has no arch line", ["-options_file", T.opts("saddle/dd1511"), "-mesh_file", small],
             "no nodes on the arch line"),
            ("capstan with penalties per unit length (a contact area)",
             ["-options_file", T.opts("capstan"), "-contact_penalty_length", 10], "drop the option for a contact area"),
            ("a mesh file with a crack", crack[1], crack[2]),
        ]
        for name, argv, expect in cases:
            rc, out = T.run(etfe, argv + ["-output_file", os.path.join(tmp, "bad.h5"), "-load_monitor", 0], np=2,
                            expect_fail=None, timeout=120)
            msg = T.error_message(out)
            chk.check(rc != 0, "%s: refused on 2 ranks (exit %d)" % (name, rc))
            chk.check(expect in msg, "%s: the message says %r: %s" % (name, expect, msg.strip()[:200]))


if __name__ == "__main__":
    T.main(main_test)
