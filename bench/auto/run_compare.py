"""slipcont and AUTO-07p side by side (docs/performance.md, "Beside
AUTO-07p"): the logistic cascade's flips r_1..r_6, the period-3 fold, and
the cubic map's fold curve with its cusp.  run_compare.sh builds what
this script runs.

    python3 run_compare.py WORK ROUNDS SLIPCONT ROOT

WORK holds AUTO's executables (cascade.exe, fold.exe, cusp.exe), their
constants (c.cascade, c.fold, c.cusp), and slipcont's cont_bench and
curve_bench; SLIPCONT is the program and ROOT the repository (for
examples/curve-cubic.ini).  Each task is timed ROUNDS times, the two
tools in turn (which goes first alternates), so that a shared machine's
load falls on both; the summary gives medians and the median of the
rounds' ratios, and each side's fastest run (a loaded machine only slows
a run down).

Timed the same way on both sides:

- whole: the processes, started and waited for from here (AUTO: one
  process a run, the constants on its standard input as its @r command
  gives them, fort.7/8/9 written; slipcont: one process, which prints its
  results and writes nothing, and for the curve also the `slipcont run`
  of the scene, which writes its files);
- inside: the computation inside its process, what it needs to start
  included (AUTO: its own "Total Time", summed over the runs; slipcont:
  from allocating the map to the last point, the attractor iterates that
  give the branches their first points included).

AUTO's values are read twice: as written in fort.7 (11 significant
digits) and through its PVLS hook, which stores each point's error
computed inside AUTO in double precision.
"""
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

REFS = ["3", "3.44948974278317809819728407471", "3.5440903595519228536159659866",
        "3.56440726609543259777355758653", "3.56875941954382643129821028003",
        "3.5696916098013967142882687063"]
REF = [float(x) for x in REFS]
RFOLDS = "3.82842712474619009760337744842"  # 1 + 2 sqrt 2
RFOLD = float(RFOLDS)
FEIGENBAUM = 4.669
POINT = re.compile(r"^\s*[1-9]\d*\s+-?\d+\s+-?\d+\s+\d+\s+[-+0-9.]")


def fail(what):
    sys.exit("run_compare.py: " + what)


def auto(work, exe, const, restart=False):
    """One AUTO run: (wall s, Total Time s, point rows of fort.7)."""
    t0 = time.perf_counter()
    if restart:
        shutil.copy(os.path.join(work, "fort.8"), os.path.join(work, "fort.3"))
    res = subprocess.run([os.path.join(work, exe)], input=const.encode(),
                         cwd=work, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE)
    wall = time.perf_counter() - t0
    if res.returncode != 0:
        fail("%s failed (%d): %s" % (exe, res.returncode,
                                     res.stderr.decode()[-400:]))
    m = re.search(rb"Total Time\s+(\S+)", res.stdout)
    if not m:
        fail("%s printed no Total Time" % exe)
    with open(os.path.join(work, "fort.7")) as f:
        rows = [line.split() for line in f if POINT.match(line)]
    return wall, float(m.group(1)), rows


def setc(text, **kw):
    """The constants text with the given keys replaced."""
    for key, value in kw.items():
        text, n = re.subn(r"(?<![\w])%s\s*=\s*(\{[^}]*\}|\[[^\]]*\]|[^,\n]*)"
                          % key, "%s=%s" % (key, value), text)
        if n == 0:
            text += "%s=%s\n" % (key, value)
    return text


def special(rows, ty):
    """The rows of one AUTO type code (7 PD, 2 LP; CP is reported as -22
    or 22 in fort.7 by this version)."""
    return [r for r in rows if abs(int(r[2])) in ty]


def auto_cascade(work):
    base = open(os.path.join(work, "c.cascade")).read()
    wall = total = 0.0
    points = 0
    found = []  # (written r, PVLS error)
    r = [None] * 7
    for k in range(1, 7):
        if k == 1:
            const = base
        else:
            w = 0.45 if k == 2 else (r[k - 1] - r[k - 2]) / FEIGENBAUM
            const = setc(base, IRS=lab, ISW=-1, DS=repr(w / 4),
                         DSMAX=repr(w / 4))
        wl, tt, rows = auto(work, "cascade.exe", const, restart=k > 1)
        wall, total, points = wall + wl, total + tt, points + len(rows)
        pd = special(rows, (7,))
        if not pd:
            fail("AUTO found no flip on branch %d" % k)
        row = pd[-1]
        lab = int(row[3])
        r[k] = float(row[4])
        # columns: BR PT TY LAB r L2-NORM PAR(2) .. PAR(7) (no room for x)
        found.append((r[k], abs(float(row[5 + k]))))
    return wall, total, points, found


def auto_fold(work):
    wall, total, rows = auto(work, "fold.exe",
                             open(os.path.join(work, "c.fold")).read())
    lp = special(rows, (2,))
    if not lp:
        fail("AUTO found no fold")
    return wall, total, len(rows), (float(lp[-1][4]), abs(float(lp[-1][7])))


def auto_curve(work):
    base = open(os.path.join(work, "c.cusp")).read()
    wall, total, rows = auto(work, "cusp.exe", base)
    lp = special(rows, (2,))
    if not lp:
        fail("AUTO found no fold of the fixed point")
    points = len(rows)
    lab = int(lp[-1][3])
    shutil.copy(os.path.join(work, "fort.8"), os.path.join(work, "s.fold"))
    worst = worst_written = first = 0.0
    cusp = []
    for ds in ("0.04", "-0.04"):
        shutil.copy(os.path.join(work, "s.fold"), os.path.join(work, "fort.8"))
        const = setc(base, IRS=lab, ISW=2, ICP="[1, 2, 3, 4]", DS=ds,
                     STOP="[]", UZSTOP="{2: [-0.5, 1.5]}")
        wl, tt, rows = auto(work, "cusp.exe", const, restart=True)
        wall, total, points = wall + wl, total + tt, points + len(rows)
        # columns: BR PT TY LAB mu1 L2-NORM x mu2 PAR(3) PAR(4)
        for i, row in enumerate(rows):
            m1, m2, v = float(row[4]), float(row[7]), abs(float(row[8]))
            if i == 0:
                first = max(first, v)  # the restart point, read back
                continue
            worst = max(worst, v)
            worst_written = max(worst_written, abs(27 * m1 * m1 - 4 * m2 ** 3)
                                / (1 + 27 * m1 * m1))
        cusp += [(max(abs(float(row[4])), abs(float(row[7])),
                      abs(float(row[6]))), float(row[9]))
                 for row in special(rows, (22,))]
    return wall, total, points, worst, worst_written, first, cusp


def run(cmd, cwd=None):
    t0 = time.perf_counter()
    res = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE)
    wall = time.perf_counter() - t0
    if res.returncode != 0:
        fail("%s failed (%d): %s" % (" ".join(cmd), res.returncode,
                                     res.stderr.decode()[-400:]))
    return wall, res.stdout.decode()


def num(text, key):
    m = re.search(r"\b%s (\S+)" % key, text)
    if not m:
        fail("no %s in: %s" % (key, text))
    return float(m.group(1))


def med(v):
    return statistics.median(v)


def ms(x):
    return "%.3g ms" % (1e3 * x)


def main():
    if len(sys.argv) != 5:
        sys.exit("usage: python3 run_compare.py WORK ROUNDS SLIPCONT ROOT")
    work, slipcont, root = sys.argv[1], sys.argv[3], sys.argv[4]
    rounds = int(sys.argv[2])
    if not 1 <= rounds <= 1000:
        fail("ROUNDS = %d (valid: 1..1000)" % rounds)
    cb, kb = os.path.join(work, "cont_bench"), os.path.join(work, "curve_bench")
    scene = os.path.join(root, "examples", "curve-cubic.ini")
    cli_out = os.path.join(work, "cli")
    t = {k: [] for k in ("cs_w", "cs_i", "cs_c", "ca_w", "ca_t",
                         "fs_w", "fs_i", "fs_c", "fa_w", "fa_t",
                         "ks_w", "ks_i", "kc_w", "ka_w", "ka_t",
                         "tr_w", "tr_t")}
    for i in range(rounds):
        order = (0, 1) if i % 2 == 0 else (1, 0)
        for side in order:
            if side == 0:
                w, out = run([cb, "once", "cascade"])
                t["cs_w"].append(w)
                t["cs_i"].append(num(out, "time_with_starts"))
                t["cs_c"].append(num(out, "time_continuation"))
                cs_out = out
                w, out = run([cb, "once", "fold"])
                t["fs_w"].append(w)
                t["fs_i"].append(num(out, "time_with_starts"))
                t["fs_c"].append(num(out, "time_continuation"))
                fs_out = out
                w, out = run([kb, "once"])
                t["ks_w"].append(w)
                t["ks_i"].append(num(out, "time"))
                ks_out = out
                w, _ = run([slipcont, "run", scene, "--quiet", "--out", cli_out,
                            "--set", "output.plot=no"])
                t["kc_w"].append(w)
            else:
                w, tt, ca_pts, ca_found = auto_cascade(work)
                t["ca_w"].append(w)
                t["ca_t"].append(tt)
                w, tt, fa_pts, fa_found = auto_fold(work)
                t["fa_w"].append(w)
                t["fa_t"].append(tt)
                w, tt, ka_pts, ka_worst, ka_written, ka_first, ka_cusp = \
                    auto_curve(work)
                t["ka_w"].append(w)
                t["ka_t"].append(tt)
                # an AUTO run that computes only its start (NMX = 1)
                w, tt, _ = auto(work, "cusp.exe",
                                setc(open(os.path.join(work, "c.cusp")).read(),
                                     NMX=1))
                t["tr_w"].append(w)
                t["tr_t"].append(tt)

    def ratio(a, b):
        return med([x / y for x, y in zip(t[a], t[b])])

    print("## slipcont and AUTO-07p, %d rounds in turn (medians)\n" % rounds)
    print("| task | timed | slipcont | AUTO-07p | AUTO / slipcont (median of the rounds' ratios) | fastest runs: slipcont, AUTO |")
    print("|---|---|---|---|---|---|")
    rows = [
        ("cascade, 6 flips", "whole process(es)", "cs_w", "ca_w", "1 process", "6 processes"),
        ("cascade, 6 flips", "inside, with the starts", "cs_i", "ca_t", "", "Total Time"),
        ("period-3 fold", "whole process(es)", "fs_w", "fa_w", "1 process", "1 process"),
        ("period-3 fold", "inside, with the starts", "fs_i", "fa_t", "", "Total Time"),
        ("cubic fold curve", "whole process(es)", "ks_w", "ka_w", "curve_bench", "3 processes"),
        ("cubic fold curve", "whole, `slipcont run` with its files", "kc_w", "ka_w", "", ""),
        ("cubic fold curve", "inside, with the start", "ks_i", "ka_t", "", "Total Time"),
    ]
    for task, how, s, a, _, _ in rows:
        print("| %s | %s | %s | %s | %.3g | %s, %s |"
              % (task, how, ms(med(t[s])), ms(med(t[a])), ratio(a, s),
                 ms(min(t[s])), ms(min(t[a]))))
    print("\nAn AUTO run that computes only its start (NMX = 1): whole %s, "
          "Total Time %s (fastest %s, %s)." % (ms(med(t["tr_w"])),
                                               ms(med(t["tr_t"])),
                                               ms(min(t["tr_w"])),
                                               ms(min(t["tr_t"]))))
    print("\nslipcont inside, continuation alone (without the attractor "
          "iterates): cascade %s, fold %s.\n"
          % (ms(med(t["cs_c"])), ms(med(t["fs_c"]))))
    print("Points: cascade slipcont %d, AUTO %d; fold slipcont %d, AUTO %d; "
          "curve slipcont %d, AUTO %d (with its run to the fold).\n"
          % (num(cs_out, "points"), ca_pts, num(fs_out, "points"), fa_pts,
             num(ks_out, "points"), ka_pts))
    print("| point | exact | slipcont | error | AUTO written | error | AUTO's own error (PVLS) |")
    print("|---|---|---|---|---|---|---|")
    for k in range(6):
        m = re.search(r"r_%d (\S+) err (\S+)" % (k + 1), cs_out)
        wr, pv = ca_found[k]
        print("| r_%d | %s | %s | %s | %.11g | %.2g | %.2g |"
              % (k + 1, REFS[k][:20], m.group(1), m.group(2), wr,
                 abs(wr - REF[k]), pv))
    m = re.search(r"fold (\S+) err (\S+)", fs_out)
    print("| fold | %s | %s | %s | %.11g | %.2g | %.2g |\n"
          % (RFOLDS[:20], m.group(1), m.group(2), fa_found[0],
             abs(fa_found[0] - RFOLD), fa_found[1]))
    print("Cubic fold curve, largest |27 mu1^2 - 4 mu2^3| / (1 + 27 mu1^2) "
          "over the computed points: slipcont %.2g; AUTO %.2g from its own "
          "values (PVLS), %.2g from the values it writes; AUTO's restart "
          "point, read back from its 11-digit file, %.2g.  The cusp's "
          "distance from the origin: slipcont %.2g; AUTO %s.\n"
          % (num(ks_out, "worst"), ka_worst, ka_written, ka_first,
             num(ks_out, "cusp"),
             ", ".join("%.2g written, %.2g (PVLS)" % c for c in ka_cusp)
             or "no CP"))
    raw = ["%s: %s" % (k, " ".join("%.4g" % x for x in v)) for k, v in t.items()]
    print("Every round (s):\n\n    " + "\n    ".join(raw))


if __name__ == "__main__":
    main()
