"""slipcont and AUTO-07p side by side on the generalized Henon map
(docs/performance.md, "Beside AUTO-07p: ghenon"): the branch of fixed
points through its fold (LP), Neimark-Sacker point (AUTO's TR) and flip
(PD), then the fold, flip and NS curves in (alpha, beta) with the points
of codimension two that each tool reports on them.  run_ghenon.sh builds
what this script runs.

    python3 run_ghenon.py WORK ROUNDS [GHENON_BENCH]

WORK holds AUTO's executable ghenon.exe and its constants c.ghenon;
GHENON_BENCH, when given, is slipcont's side (bench/auto/ghenon_bench.c,
built by run_ghenon.sh).  Each task is timed ROUNDS times, the tools in
turn (which goes first alternates), so that a shared machine's load falls
on both; the summary gives medians, the median of the rounds' ratios and
each side's fastest run.

Timed the same way on both sides:

- whole: the processes, started and waited for from here (AUTO: one
  process a run, the constants on its standard input as its @r command
  gives them, fort.7/8/9 written, the restart file copied; slipcont: one
  process that prints its results);
- inside: the computation inside its process (AUTO: its own "Total
  Time", summed over the runs; slipcont: from allocating the map to the
  last point).

AUTO's values are read twice: as written in fort.7 (11 significant
digits; fort.8, which its Python interface reads, holds the same 11) and
through its PVLS hook (ghenon.f90), which stores each point's error
against the closed forms computed inside AUTO in double precision.
"""
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

# The window of the curves (docs/maps.md, "The ghenon atlas") and the
# step of every AUTO run (DS = DSMAX), in the units of its arclength.
ALO, AHI, BLO, BHI = -3.0, 5.0, -1.5, 2.0
STEP = 0.08
R = 0.5
BETA0 = 1.2  # the branch's beta

POINT = re.compile(r"^\s*[1-9]\d*\s+-?\d+\s+-?\d+\s+\d+\s+[-+0-9.]")
LABEL = re.compile(r"^\s*(\d+)\s+(-?\d+)\s+([A-Z][A-Z0-9]*)\s+(\d+)\s+[-+0-9.]")


def fail(what):
    sys.exit("run_ghenon.py: " + what)


# The closed forms (ghenon.f90's header; docs/maps.md, "The ghenon atlas").
def alpha_of(s, beta, r=R):
    return (1 - r) * s * s + (1 + beta) * s


def alpha_fold(beta, r=R):
    return (1 + beta) ** 2 / (4 * (r - 1))


def alpha_flip(beta, r=R):
    return (3 - r) * (1 + beta) ** 2 / 4


def alpha_ns(beta, r=R):
    return alpha_of((beta - 1) / r, beta, r)


def codim2(r=R):
    """(name, alpha, beta) of R1, R2, R3, R4 and LPPD at this R."""
    out = []
    for name, s in (("R1", 2 / (r - 2)), ("R2", -2 / (r - 2)),
                    ("R3", -1 / (r - 2)), ("R4", 0.0)):
        b = 1 + r * s
        out.append((name, alpha_of(s, b, r), b))
    out.append(("LPPD", 0.0, -1.0))
    return out


CODIM2 = codim2()
# PVLS's columns of the distance from each (ghenon.f90).
CODIM2_PAR = {"R1": "PAR(13)", "R2": "PAR(14)", "R3": "PAR(15)",
              "R4": "PAR(16)", "LPPD": "PAR(17)"}
# The branch's special points: AUTO's label, exact alpha, PVLS column.
BRANCH = [("LP", alpha_fold(BETA0), "PAR(4)"),
          ("TR", alpha_ns(BETA0), "PAR(6)"),
          ("PD", alpha_flip(BETA0), "PAR(5)")]
CURVES = [("fold", "LP", "PAR(4)", alpha_fold),
          ("flip", "PD", "PAR(5)", alpha_flip),
          ("NS", "TR", "PAR(6)", alpha_ns)]


def setc(text, **kw):
    """The constants text with the given keys replaced."""
    for key, value in kw.items():
        text, n = re.subn(r"(?<![\w])%s\s*=\s*(\{[^}]*\}|\[[^\]]*\]|[^,\n]*)"
                          % key, "%s=%s" % (key, value), text)
        if n == 0:
            text += "%s=%s\n" % (key, value)
    return text


def auto(work, const, restart=None):
    """One AUTO run, restarted from the file restart (copied to fort.3)
    if given: (wall s, Total Time s, rows as dicts by fort.7's column
    names, special rows as (AUTO's label, row))."""
    t0 = time.perf_counter()
    if restart:
        shutil.copy(os.path.join(work, restart), os.path.join(work, "fort.3"))
    res = subprocess.run([os.path.join(work, "ghenon.exe")],
                         input=const.encode(), cwd=work,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    wall = time.perf_counter() - t0
    if res.returncode != 0:
        fail("ghenon.exe failed (%d): %s" % (res.returncode,
                                            res.stderr.decode()[-400:]))
    out = res.stdout.decode()
    m = re.search(r"Total Time\s+(\S+)", out)
    if not m:
        fail("ghenon.exe printed no Total Time")
    names, rows = None, []
    with open(os.path.join(work, "fort.7")) as f:
        for line in f:
            w = line.split()
            if len(w) > 4 and w[0] == "0" and w[1] == "PT":
                names = w[4:]
            elif POINT.match(line):
                if names is None:
                    fail("fort.7 has points before its header")
                row = {k: float(v) for k, v in zip(names, w[4:])}
                row["LAB"] = int(w[3])
                rows.append(row)
    bylab = {r["LAB"]: r for r in rows if r["LAB"] > 0}
    special = []
    for line in out.splitlines():
        lm = LABEL.match(line)
        if lm and int(lm.group(4)) in bylab:
            special.append((lm.group(3), bylab[int(lm.group(4))]))
    return wall, float(m.group(1)), rows, special


class AutoResult:
    """Everything one AUTO computation gives."""

    def __init__(self):
        self.wall = self.total = 0.0
        self.points = self.runs = 0
        self.branch = {}    # label -> (written alpha, PVLS error)
        self.curve = {}     # name -> [worst PVLS, worst written, first, points]
        self.special = []   # (curve, direction, AUTO's label, row)


def auto_all(work, step=STEP):
    """The branch, then each curve both ways from its point on it."""
    res = AutoResult()
    base = open(os.path.join(work, "c.ghenon")).read()
    wall, tt, rows, special = auto(work, base)
    res.wall, res.total, res.points, res.runs = wall, tt, len(rows), 1
    res.branch_points = len(rows)
    labs = {}
    for label, row in special:
        labs.setdefault(label, row)
    for label, exact, col in BRANCH:
        if label not in labs:
            fail("AUTO found no %s on the branch" % label)
        row = labs[label]
        res.branch[label] = (row["alpha"], abs(row[col]))
    t0 = time.perf_counter()
    shutil.copy(os.path.join(work, "fort.8"), os.path.join(work, "s.br"))
    res.wall += time.perf_counter() - t0
    for name, label, col, closed in CURVES:
        worst = written = first = 0.0
        npts = 0
        for sign in (1, -1):
            const = setc(base, IRS=int(labs[label]["LAB"]), ISW=2,
                         ICP="[2, 1, 4, 5, 6, 7, 13, 14, 15, 16, 17]",
                         DS=repr(sign * step), DSMAX=repr(step),
                         UZSTOP="{1: [%r, %r], 2: [%r, %r]}"
                         % (ALO, AHI, BLO, BHI))
            if name == "NS":
                # Beyond R2 (theta = pi) and R1 (theta = 0) AUTO's NS
                # system retraces the curve (theta changes sign, cos theta
                # does not): it reports the turn at R2 as LP; stop there
                # and at R1.
                const = setc(const, STOP="['LP1', 'R11']")
            wall, tt, rows, sp = auto(work, const, restart="s.br")
            res.wall, res.total = res.wall + wall, res.total + tt
            res.points += len(rows)
            npts += len(rows)
            res.runs += 1
            for i, row in enumerate(rows):
                if i == 0:  # the restart point, read back from fort.8
                    first = max(first, abs(row[col]))
                    continue
                worst = max(worst, abs(row[col]))
                written = max(written, abs(row["alpha"] - closed(row["beta"])))
            res.special += [(name, sign, lab, row) for lab, row in sp
                            if lab not in ("UZ", "EP")]
        res.curve[name] = [worst, written, first, npts]
    return res


def nearest(row):
    """The codimension-two point nearest to an AUTO row: (name, PVLS
    distance, distance from the written values)."""
    best = min(CODIM2, key=lambda c: row[CODIM2_PAR[c[0]]])
    name, a, b = best
    return (name, row[CODIM2_PAR[name]],
            max(abs(row["alpha"] - a), abs(row["beta"] - b)))


def run(cmd):
    t0 = time.perf_counter()
    res = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    wall = time.perf_counter() - t0
    if res.returncode != 0:
        fail("%s failed (%d): %s" % (" ".join(cmd), res.returncode,
                                     res.stderr.decode()[-400:]))
    return wall, res.stdout.decode()


def num(text, key):
    m = re.search(r"(?m)^%s (\S+)" % re.escape(key), text)
    if not m:
        fail("no %s in: %s" % (key, text))
    return float(m.group(1))


def med(v):
    return statistics.median(v)


def ms(x):
    return "%.3g ms" % (1e3 * x)


def slipcont_parse(out):
    """slipcont's results from ghenon_bench's lines: branch {label:
    (alpha, error, residual, coefficient)}, curves {name: (points,
    worst)}, specials [(curve, label, alpha, beta, residual)]."""
    branch, curves, special = {}, {}, []
    for line in out.splitlines():
        w = line.split()
        if w[:1] == ["branch"]:
            branch[w[1]] = (float(w[2]), float(w[4]), float(w[6]), float(w[8]))
        elif w[:1] == ["curve"]:
            curves[w[1]] = (int(w[3]), float(w[5]))
        elif w[:1] == ["special"]:
            special.append((w[1], w[2], float(w[3]), float(w[4]), float(w[6])))
    return branch, curves, special


def nearest_ab(alpha, beta):
    """The codimension-two point nearest to (alpha, beta) and the
    distance max(|alpha - alpha*|, |beta - beta*|)."""
    name, a, b = min(CODIM2, key=lambda c: max(abs(alpha - c[1]),
                                                 abs(beta - c[2])))
    return name, max(abs(alpha - a), abs(beta - b))


def report_both(a, s_out):
    branch, curves, special = slipcont_parse(s_out)
    print("| branch point | exact alpha | slipcont | error | residual | AUTO written | error | AUTO's own error (PVLS) |")
    print("|---|---|---|---|---|---|---|---|")
    for (label, exact, _), sl in zip(BRANCH, ("LP", "NS", "PD")):
        w, e = a.branch[label]
        p, err, res, _ = branch[sl]
        print("| %s | %.17g | %.17g | %.2g | %.2g | %.11g | %.2g | %.2g |"
              % (sl, exact, p, err, res, w, abs(w - exact), e))
    print("\n| curve | slipcont points | largest alpha - closed form | "
          "AUTO points | AUTO (PVLS) | AUTO written |")
    print("|---|---|---|---|---|---|")
    for name, _, _, _ in CURVES:
        worst, written, _, npts = a.curve[name]
        sp, sw = curves[name]
        print("| %s | %d | %.2g | %d | %.2g | %.2g |"
              % (name, sp, sw, npts, worst, written))
    print("\nslipcont's points of codimension two (the distance from the "
          "nearest of the table's, max(|alpha - alpha*|, |beta - beta*|)):\n")
    print("| curve | label | alpha | beta | residual | nearest | distance |")
    print("|---|---|---|---|---|---|---|")
    for name, label, al, be, res in special:
        c, d = nearest_ab(al, be)
        print("| %s | %s | %.17g | %.17g | %.2g | %s | %.2g |"
              % (name, label, al, be, res, c, d))
    print()


def report_auto(a, t, rounds):
    print("AUTO-07p: %d runs (the branch, then each curve both ways), %d "
          "points (%d on the branch).\n" % (a.runs, a.points, a.branch_points))
    print("| point | exact alpha | AUTO written | error | AUTO's own error (PVLS) |")
    print("|---|---|---|---|---|")
    for label, exact, _ in BRANCH:
        w, e = a.branch[label]
        print("| %s (beta = %g) | %.17g | %.11g | %.2g | %.2g |"
              % (label, BETA0, exact, w, abs(w - exact), e))
    print("\n| curve | AUTO points | largest alpha - closed form (PVLS) "
          "| from the written values | its restart point, read back |")
    print("|---|---|---|---|---|")
    for name, _, _, _ in CURVES:
        worst, written, first, npts = a.curve[name]
        print("| %s | %d | %.2g | %.2g | %.2g |"
              % (name, npts, worst, written, first))
    print("\nWhat AUTO reports on the curves (ICP = [beta, alpha], both "
          "ways from the branch's point; the distance is "
          "max(|alpha - alpha*|, |beta - beta*|) from the nearest point of "
          "codimension two):\n")
    print("| curve | way | AUTO's label | alpha | beta | nearest | distance (PVLS) | from the written values |")
    print("|---|---|---|---|---|---|---|---|")
    for name, sign, lab, row in a.special:
        c, d, dw = nearest(row)
        print("| %s | %s | %s | %.11g | %.11g | %s | %.2g | %.2g |"
              % (name, "+" if sign > 0 else "-", lab, row["alpha"],
                 row["beta"], c, d, dw))
    print("\nAn AUTO run that computes only its start (NMX = 1): whole %s, "
          "Total Time %s (fastest %s, %s).\n"
          % (ms(med(t["tr_w"])), ms(med(t["tr_t"])), ms(min(t["tr_w"])),
             ms(min(t["tr_t"]))))


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit("usage: python3 run_ghenon.py WORK ROUNDS [GHENON_BENCH]")
    work = sys.argv[1]
    rounds = int(sys.argv[2])
    if not 1 <= rounds <= 1000:
        fail("ROUNDS = %d (valid: 1..1000)" % rounds)
    bench = sys.argv[3] if len(sys.argv) == 4 else None
    t = {k: [] for k in ("s_w", "s_i", "a_w", "a_t", "tr_w", "tr_t")}
    a = s_out = None
    for i in range(rounds):
        order = (0, 1) if i % 2 == 0 else (1, 0)
        for side in order:
            if side == 0 and bench:
                w, s_out = run([bench, "once"])
                t["s_w"].append(w)
                t["s_i"].append(num(s_out, "time"))
            elif side == 1:
                a = auto_all(work)
                t["a_w"].append(a.wall)
                t["a_t"].append(a.total)
                w, tt, _, _ = auto(work, setc(
                    open(os.path.join(work, "c.ghenon")).read(), NMX=1))
                t["tr_w"].append(w)
                t["tr_t"].append(tt)
    print("## ghenon: slipcont and AUTO-07p, %d rounds in turn (medians)\n"
          % rounds)
    print("| timed | slipcont | AUTO-07p | AUTO / slipcont (median of the rounds' ratios) | fastest runs: slipcont, AUTO |")
    print("|---|---|---|---|---|")
    for how, s, x in (("whole process(es)", "s_w", "a_w"),
                      ("inside", "s_i", "a_t")):
        if bench:
            ratio = med([p / q for p, q in zip(t[x], t[s])])
            print("| %s | %s | %s | %.3g | %s, %s |"
                  % (how, ms(med(t[s])), ms(med(t[x])), ratio,
                     ms(min(t[s])), ms(min(t[x]))))
        else:
            print("| %s | (not built) | %s | | -, %s |"
                  % (how, ms(med(t[x])), ms(min(t[x]))))
    print()
    if bench:
        report_both(a, s_out)
    report_auto(a, t, rounds)
    if bench:
        print("slipcont (%s once), its last round:\n" % os.path.basename(bench))
        print("    " + "\n    ".join(s_out.strip().splitlines()))
    raw = ["%s: %s" % (k, " ".join("%.4g" % x for x in v))
           for k, v in t.items() if v]
    print("\nEvery round (s):\n\n    " + "\n    ".join(raw))


if __name__ == "__main__":
    main()
