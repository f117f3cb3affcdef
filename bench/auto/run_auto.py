"""AUTO-07p on the logistic and cubic maps, the side of the comparison in
docs/accuracy.md ("Branches on smooth maps") that run_auto.sh
cannot do in sh: time each setting (median of REPEATS), read the special
points from fort.7, append rows to OUTDIR/smooth.csv and tables to
OUTDIR/smooth.md.

    python3 run_auto.py WORKDIR OUTDIR REPEATS

WORKDIR holds the executables built by run_auto.sh (logistic.exe,
logistic3.exe, cubic.exe) and the constants files c.*.  Each executable
is run as AUTO's own @r command runs it: the constants on its standard
input, fort.7 (b.), fort.8 (s.), fort.9 (d.) written in the working
directory, fort.3 / s.NAME read when restarting.
"""
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

# Settings: step (DS = DSMAX) and the Newton / location tolerances.
# "recommended" is what AUTO's manual recommends and its demos use (EPSS
# 100 to 1000 times EPSL); "1e-12" asks for all the digits.
TOLS = [
    ("loose", 1e-4, 1e-4, 1e-2),
    ("recommended", 1e-7, 1e-7, 1e-5),
    ("tight", 1e-10, 1e-10, 1e-8),
    ("1e-12", 1e-12, 1e-12, 1e-12),  # performance.md tightens EPSS to 1e-14
]
STEPS = [0.02, 0.01, 0.005]

# fort.7 type codes (AUTO-07p manual, "Output files").
TYPES = {1: "BP", 2: "LP", 3: "HB", 5: "LP", 6: "BP", 7: "PD", 8: "TR"}

# The exact points, each with the fort.7 column (0-based, after BR, PT,
# TY, LAB, PAR(1), L2-NORM, U(1)) where PVLS stored p - exact.
EXACT = {
    "logistic": [("PD", "PD m=1 r=3", 7), ("PD", "PD m=2 r=1+sqrt 6", 8),
                 ("PD", "PD m=4 r=3.5440903595519229", 9),
                 ("LP", "LP m=3 r=1+2 sqrt 2", 10)],
    "cubic": [("PD", "PD mu1=-sqrt(5/6)/3", 7),
              ("LP", "LP mu1=1/(3 sqrt 6)", 8),
              ("LP", "LP mu1=-1/(3 sqrt 6)", 9),
              ("PD", "PD mu1=sqrt(5/6)/3", 10)],
}

NUM = re.compile(r"^[-+]?\d")


def constants(path, ds_sign, ds, tol, extra=None):
    """The constants file at path with this setting (and extra lines)."""
    _, epsl, epsu, epss = tol
    text = open(path).read()
    text = re.sub(r"^EPSL=.*$", "EPSL=%g, EPSU=%g, EPSS=%g" % (epsl, epsu, epss),
                  text, flags=re.M)
    text = re.sub(r"^DS=.*$", "DS=%g, DSMIN=1e-08, DSMAX=%g, IADS=1"
                  % (ds_sign * ds, ds), text, flags=re.M)
    for key, value in (extra or {}).items():
        pattern = r"(?<!\w)%s\s*=[^,\n]*" % key
        if re.search(pattern, text):
            text = re.sub(pattern, "%s=%s" % (key, value), text)
        else:
            text = "%s=%s\n" % (key, value) + text
    return text.encode()


def auto(work, exe, cfile):
    """One run of an AUTO executable: (wall seconds, AUTO's Total Time,
    special points [(type, row)])."""
    t0 = time.perf_counter()
    res = subprocess.run([os.path.join(work, exe)], input=cfile, cwd=work,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    wall = time.perf_counter() - t0
    if res.returncode != 0:
        sys.exit("run_auto.py: %s failed (%d): %s" %
                 (exe, res.returncode, res.stderr.decode()[-400:]))
    m = re.search(rb"Total Time\s+(\S+)", res.stdout)
    if not m:
        sys.exit("run_auto.py: %s printed no Total Time:\n%s" %
                 (exe, res.stdout.decode()[-400:]))
    total = float(m.group(1))
    special = []
    with open(os.path.join(work, "fort.7")) as f:
        for line in f:
            w = line.split()
            if len(w) < 8 or not NUM.match(w[0]) or int(w[0]) == 0:
                continue
            ty = abs(int(w[2]))
            if ty in TYPES:
                special.append((TYPES[ty], [float(x) for x in w[4:]]))
    return wall, total, special


def chain(work, name, ds, tol):
    """One computation of a map's special points, as in
    bench_accuracy_branch: returns (wall, Total Time summed, specials,
    AUTO runs)."""
    wall = total = 0.0
    special = []
    runs = 0
    if name == "logistic":
        # Period 1 from r = 2.8, then the period-2 and period-4 branches
        # from the first flip of the previous run (ISW = -1).
        cfile = constants(os.path.join(work, "c.logistic"), 1, ds, tol)
        for k in range(3):
            w, t, sp = auto(work, "logistic.exe", cfile)
            wall, total, runs = wall + w, total + t, runs + 1
            special += [(ty, row) for ty, row in sp
                        if not (k > 0 and ty == "PD" and row[0] < prev_flip + 1e-9)]
            flips = [row[0] for ty, row in sp if ty == "PD"]
            flips = [p for p in flips if k == 0 or p > prev_flip + 1e-9]
            if k == 2 or not flips:
                break
            prev_flip = min(flips)
            t0 = time.perf_counter()
            shutil.copy(os.path.join(work, "fort.8"),
                        os.path.join(work, "s.run%d" % k))
            wall += time.perf_counter() - t0
            cfile = constants(os.path.join(work, "c.logistic"), 1, ds, tol,
                              {"IRS": "'PD1'", "ISW": "-1", "s": "'run%d'" % k})
        # The period-3 orbit from r = 3.84 down through its fold.
        cfile = constants(os.path.join(work, "c.logistic3"), -1, ds, tol)
        w, t, sp = auto(work, "logistic3.exe", cfile)
        wall, total, runs = wall + w, total + t, runs + 1
        special += sp
    else:
        cfile = constants(os.path.join(work, "c.cubic"), 1, ds, tol)
        wall, total, special = auto(work, "cubic.exe", cfile)
        runs = 1
    return wall, total, special, runs


def errors(name, special):
    """Largest |p - exact| over the exact points found within 1e-2 (as
    bench_accuracy_branch's SMOOTH_MATCH), and how many were not found."""
    worst, missing = 0.0, 0
    for label, _, col in EXACT[name]:
        d = [abs(row[col - 4]) for ty, row in special
             if ty == label and len(row) > col - 4]
        best = min(d) if d else float("inf")
        if best > 1e-2:
            missing += 1
        else:
            worst = max(worst, best)
    return worst, missing


def trivial(work, repeats):
    """Median wall time and Total Time of an AUTO run that computes
    nothing but its starting point (NMX=1): the process start, reading
    the constants and writing the files."""
    cfile = constants(os.path.join(work, "c.cubic"), 1, 0.01, TOLS[1],
                      {"NMX": "1"})
    walls, totals = [], []
    for _ in range(repeats):
        w, t, _ = auto(work, "cubic.exe", cfile)
        walls.append(w)
        totals.append(t)
    return statistics.median(walls), statistics.median(totals)


def main():
    if len(sys.argv) != 4:
        sys.exit("usage: python3 run_auto.py WORKDIR OUTDIR REPEATS")
    work, out, repeats = sys.argv[1], sys.argv[2], int(sys.argv[3])
    if repeats < 1:
        sys.exit("run_auto.py: REPEATS must be >= 1")
    rows, md = [], []
    triv_wall, triv_total = trivial(work, max(repeats, 11))
    for name in ("logistic", "cubic"):
        md.append("\nThe %s map with AUTO-07p (bench/auto/%s.f90, IPS = -1, "
                  "JAC = 1): median of %d runs of the whole computation; "
                  "\"wall\" includes %s AUTO process%s started, reading the "
                  "constants and writing fort.7/8/9, \"Total Time\" is what "
                  "AUTO prints (its own clock, summed over the runs).\n\n"
                  "| setting | EPSL = EPSU | EPSS | wall (s) | Total Time (s) "
                  "| max abs p - exact | missing (none within 1e-2) |\n"
                  "|---|---|---|---|---|---|---|"
                  % (name, name, repeats,
                     "four" if name == "logistic" else "one",
                     "es" if name == "logistic" else ""))
        for tol in TOLS:
            for ds in STEPS:
                walls, totals = [], []
                for _ in range(repeats):
                    w, t, special, runs = chain(work, name, ds, tol)
                    walls.append(w)
                    totals.append(t)
                err, missing = errors(name, special)
                wall = statistics.median(walls)
                total = statistics.median(totals)
                label = "%s DSMAX %g" % (tol[0], ds)
                md.append("| %s | %g | %g | %.3g | %.3g | %.3g | %d |"
                          % (label, tol[1], tol[3], wall, total, err, missing))
                # The plot needs a time > 0: Total Time is printed to 3
                # digits in units of 1e-5 s at best.
                rows.append("%s,auto,%s,%.6g,%.6g,%d,%.6g"
                            % (name, label, max(total, 1e-6), err, missing,
                               wall))
    md.append("\nAn AUTO run that computes only its starting point (cubic.exe, "
              "NMX = 1), median of %d: wall %.3g s, Total Time %.3g s.\n"
              % (max(repeats, 11), triv_wall, triv_total))
    with open(os.path.join(out, "smooth.csv"), "a") as f:
        f.write("\n".join(rows) + "\n")
    with open(os.path.join(out, "smooth.md"), "a") as f:
        f.write("\n".join(md) + "\n")


if __name__ == "__main__":
    main()
