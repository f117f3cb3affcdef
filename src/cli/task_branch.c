/* Task `branch`: a periodic orbit continued in one parameter, with folds,
 * flips and discontinuity-induced bifurcations (sc_orbit_branch,
 * orbits.h), drawn over the brute-force diagram of the same range, and
 * the map f^m at a chosen special point (figs 5.8-5.12 with their
 * unstable orbits added). */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/progress.h"
#include "cli/task_branch_n.h"
#include "cli/tasks.h"
#include "slipcont/analysis.h"
#include "slipcont/orbits.h"

static const sc_key_info branch_keys[] = {
    {"parameter", SC_KEY_PARAM, 1, NULL, 0, 0, 0, 0, NULL,
     "the model parameter continued (bk2: alpha, beta, phi or v)"},
    {"from", SC_KEY_REAL, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "start value of the parameter (the starting orbit is found there)"},
    {"to", SC_KEY_REAL, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "other end of the parameter interval"},
    {"period", SC_KEY_INT, 0, "1", 1, 4096, 0, 0, NULL,
     "m: period of the starting orbit (fixed point of f^m)"},
    {"d0", SC_KEY_STATE, 0, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "guess of a point of the starting orbit, polished by multiple "
     "shooting at `at` (omit it to start from `starts` only)"},
    {"at", SC_KEY_REAL, 0, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "parameter value of the d0 start, inside [from, to] (default: from; "
     "inside, the branch is continued both ways)"},
    {"starts", SC_KEY_TEXT, 0, NULL, 0, 0, 0, 0, NULL,
     "more starting orbits, each continued both ways, separated by ';': "
     "'P D M' (parameter value, guess of an orbit point, period), "
     "'FILE:N' (row N of a points.csv written by a branch task), or "
     "'auto' (every orbit of period 1..auto-period at each auto-at value)"},
    {"auto-at", SC_KEY_TEXT, 0, NULL, 0, 0, 0, 0, NULL,
     "starts = auto: parameter values at which orbits are sought, "
     "separated by spaces (default: from)"},
    {"auto-period", SC_KEY_INT, 0, "8", 1, 4096, 0, 0, NULL,
     "starts = auto: the highest period sought (<= max-period)"},
    {"auto-d", SC_KEY_TEXT, 0, "-0.5 0.5", 0, 0, 0, 0, NULL,
     "starts = auto: the interval of d scanned, 'LO HI'"},
    {"switch", SC_KEY_BOOL, 0, "no", 0, 0, 0, 0, NULL,
     "yes: at each flip (PD) also continue the period-2m branch"},
    {"max-points", SC_KEY_INT, 0, "5000", 2, 10000000, 0, 0, NULL,
     "accepted points per branch segment"},
    {"max-branches", SC_KEY_INT, 0, "16", 1, 1000, 0, 0, NULL,
     "branch segments at most (period-doubled branches and continuations "
     "past discontinuity-induced bifurcations count)"},
    {"max-period", SC_KEY_INT, 0, "16", 1, 4096, 0, 0, NULL,
     "longest period resolved: no branch is followed beyond it (as a "
     "chart tells periods apart up to its max-period)"},
    {"h0", SC_KEY_REAL, 0, "0", 0, HUGE_VAL, 0, 1, NULL,
     "initial arclength step (0: hmax / 10)"},
    {"hmax", SC_KEY_REAL, 0, "0", 0, HUGE_VAL, 0, 1, NULL,
     "largest arclength step (0: |to - from| / 40)"},
    {"linsolve", SC_KEY_CHOICE, 0, "dense", 0, 0, 0, 0, "dense|klu",
     "linear solver of the bordered systems"},
    {"sweep", SC_KEY_BOOL, 0, "yes", 0, 0, 0, 0, NULL,
     "yes: draw the branch over a brute-force sweep of the same range"},
    {"sweep-steps", SC_KEY_INT, 0, "400", 2, 1000000, 0, 0, NULL,
     "parameter values of the brute-force sweep"},
    {"sweep-iterations", SC_KEY_INT, 0, "400", 1, 100000000, 0, 0, NULL,
     "sweep: iterates at each value, each starting from the previous one "
     "(the sweep task's iterations; its own name and default, those of "
     "the chapter's figs 5.8 and 5.12)"},
    {"sweep-keep", SC_KEY_INT, 0, "150", 1, 100000000, 0, 0, NULL,
     "sweep: last iterates drawn (<= sweep-iterations)"},
    {"marks", SC_KEY_TEXT, 0, NULL, 0, 0, 0, 0, NULL,
     "user points (UZ): values of the parameter, separated by spaces, at "
     "which every branch records its orbit (located by Newton with the "
     "parameter fixed; a row of points.csv, usable as a start)"},
    {"plot-at", SC_KEY_CHOICE, 0, "first", 0, 0, 0, 0,
     "first|LP|PD|GR|CS|SW|BR|TT|UZ",
     "special point at which f^m is drawn against d (figs 5.9-5.11): the "
     "first one with that label, or the first of any label but EP"},
    SC_CLI_SHOW_KEY,
};

/* What a start found by parse_starts() is given to. */
typedef int (*start_fn)(void *ctx, double p, double d, int period);

/* Read `starts`: triples, points.csv rows and `auto` (*is_auto set);
 * each start within [from, to] with a period in [1, max-period] is given
 * to fn (NULL: only check). */
static int parse_starts(const sc_scene *s, start_fn fn, void *ctx,
                        sc_msg *msg) {
  const char *starts = sc_scene_text(s, "starts");
  double from = sc_scene_real(s, "from"), to = sc_scene_real(s, "to");
  long maxp = sc_scene_int(s, "max-period");
  for (const char *q = starts; q && *q;) {
    while (*q == ' ' || *q == ';') q++;
    if (!*q) break;
    size_t len = strcspn(q, ";");
    char item[512];
    snprintf(item, sizeof item, "%.*s", (int)(len < 511 ? len : 511), q);
    for (size_t e = strlen(item); e && item[e - 1] == ' '; e--)
      item[e - 1] = '\0';
    double p = NAN, d = NAN;
    int per = 0;
    char why[1024] = "";
    const char *colon = strrchr(item, ':');
    const char *pname = sc_scene_text(s, "parameter");
    if (strcmp(item, "auto") == 0) {
      q += len;
      continue; /* handled by the run (needs the map) */
    } else if (colon && colon != item) {
      sc_cli_points_row row;
      if (sc_cli_points_row_read(item, &row, why, sizeof why) == SC_OK) {
        p = row.value, d = row.d, per = row.period;
        if (strcmp(row.param, pname) != 0)
          snprintf(why, sizeof why,
                   "'%.200s' is a point in %.40s (valid: a row of a branch "
                   "continued in %.40s)",
                   item, row.param, pname);
      }
    } else {
      /* strtod/strtol: sscanf's %d is undefined past INT_MAX */
      char *e1, *e2, *e3;
      p = strtod(item, &e1);
      d = strtod(e1, &e2);
      errno = 0;
      long lp = strtol(e2, &e3, 10);
      while (*e3 == ' ') e3++;
      if (e1 == item || e2 == e1 || e3 == e2 || *e3)
        snprintf(why, sizeof why,
                 "cannot read 'P D M' in '%.200s' (valid: 'P D M' with P "
                 "the parameter value, D a guess of an orbit point, M the "
                 "period; 'FILE:N', row N of a branch task's points.csv; or "
                 "'auto'; separated by ';')",
                 item);
      else if (errno == ERANGE || lp < 1 || lp > maxp)
        snprintf(why, sizeof why,
                 "'%.200s': period %s (valid: [1, max-period = %ld])", item,
                 e2 + strspn(e2, " "), maxp);
      else if (!isfinite(p) || !isfinite(d))
        snprintf(why, sizeof why,
                 "'%.200s': P = %g, D = %g (valid: finite numbers)", item, p,
                 d);
      else
        per = (int)lp;
    }
    if (!why[0] && !((from - p) * (to - p) <= 0))
      snprintf(why, sizeof why,
               "'%.200s': %s = %.17g (valid: inside [from, to] = [%.40s, "
               "%.40s])",
               item, pname, p, sc_scene_text(s, "from"),
               sc_scene_text(s, "to"));
    if (!why[0] && (per < 1 || per > maxp))
      snprintf(why, sizeof why, "'%.200s': period %d (valid: [1, max-period = "
                                "%ld])",
               item, per, maxp);
    if (why[0])
      return sc_scene_fail_key(s, "task", "starts", msg, "starts: %s", why);
    if (fn) {
      int st = fn(ctx, p, d, per);
      if (st) return st;
    }
    q += len;
  }
  return SC_OK;
}

static int has_auto(const sc_scene *s) {
  const char *q = sc_scene_text(s, "starts");
  while (q && *q) {
    while (*q == ' ' || *q == ';') q++;
    size_t len = strcspn(q, ";");
    size_t k = len;
    while (k && q[k - 1] == ' ') k--;
    if (k == 4 && strncmp(q, "auto", 4) == 0) return 1;
    q += len;
  }
  return 0;
}

/* auto-d: 'LO HI', two numbers with LO < HI. */
static int auto_d(const sc_scene *s, double *lo, double *hi, sc_msg *msg) {
  const char *q = sc_scene_text(s, "auto-d");
  char w[3][64];
  int n = 0;
  while (n < 3 && sc_cli_next_word(&q, w[n], sizeof w[n])) n++;
  if (n != 2 || sc_parse_double(w[0], lo) || sc_parse_double(w[1], hi) ||
      !(*lo < *hi))
    return sc_scene_fail_key(s, "task", "auto-d", msg,
                             "auto-d = %s (valid: 'LO HI', two numbers with "
                             "LO < HI)",
                             sc_scene_text(s, "auto-d"));
  return SC_OK;
}

/* auto-at: the next value of the list at *q (the list checked by
 * check_auto_at()), or `from` once when auto-at is not given; 0 at the
 * end. */
static int auto_at_next(const sc_scene *s, const char **q, double *p) {
  char w[64];
  if (!sc_scene_text(s, "auto-at")) {
    if (*q) return 0;
    *q = "";
    *p = sc_scene_real(s, "from");
    return 1;
  }
  if (!*q) *q = sc_scene_text(s, "auto-at");
  return sc_cli_next_word(q, w, sizeof w) && sc_parse_double(w, p) == SC_OK;
}

/* auto-at: numbers separated by blanks, each inside [from, to]. */
static int check_auto_at(const sc_scene *s, sc_msg *msg) {
  const char *q = sc_scene_text(s, "auto-at");
  double a = sc_scene_real(s, "from"), b = sc_scene_real(s, "to"), p;
  char w[64];
  for (int k = 1; q && sc_cli_next_word(&q, w, sizeof w); k++) {
    if (strlen(w) >= sizeof w - 1 || sc_parse_double(w, &p))
      return sc_scene_fail_key(s, "task", "auto-at", msg,
                               "auto-at: value %d, '%s', is not a number "
                               "(valid: numbers separated by spaces, inside "
                               "[from, to])",
                               k, w);
    if ((a - p) * (b - p) > 0)
      return sc_scene_fail_key(s, "task", "auto-at", msg,
                               "auto-at: value %d, %s, is outside [from, "
                               "to] = [%s, %s] (valid: inside it)",
                               k, w, sc_scene_text(s, "from"),
                               sc_scene_text(s, "to"));
  }
  return SC_OK;
}

static int branch_check(const sc_scene *s, sc_msg *msg) {
  int st = sc_cli_check_param_ends(s, msg);
  if (st) return st;
  if (sc_scene_real(s, "from") == sc_scene_real(s, "to"))
    return sc_scene_fail_key(s, "task", "to", msg,
                             "to = %s equals from (valid: to != from)",
                             sc_scene_text(s, "to"));
  const sc_map *m = sc_scene_map(s);
  if (sc_map_dim(m) > 1) {
    if (sc_scene_int(s, "max-period") < sc_scene_int(s, "period"))
      return sc_scene_fail_key(s, "task", "max-period", msg,
                               "max-period = %ld is below period = %ld "
                               "(valid: >= period)",
                               sc_scene_int(s, "max-period"),
                               sc_scene_int(s, "period"));
    return sc_brn_check(s, msg);
  }
  int show; /* read by the n-dimensional path; checked for every model */
  if ((st = sc_cli_show(s, &show, msg))) return st;
  if (sc_scene_int(s, "sweep-keep") > sc_scene_int(s, "sweep-iterations"))
    return sc_scene_fail_key(s, "task", "sweep-keep", msg,
                             "sweep-keep = %ld is more than sweep-iterations "
                             "= %ld (valid: [1, sweep-iterations])",
                             sc_scene_int(s, "sweep-keep"),
                             sc_scene_int(s, "sweep-iterations"));
  st = parse_starts(s, NULL, NULL, msg);
  if (st) return st;
  if (!sc_scene_text(s, "d0") && !sc_scene_text(s, "starts"))
    return sc_scene_fail_key(s, "task", "d0", msg,
                             "no start: give d0 (a guess of an orbit point at "
                             "`at`) or starts");
  if (sc_scene_text(s, "at")) {
    double at = sc_scene_real(s, "at");
    if ((sc_scene_real(s, "from") - at) * (sc_scene_real(s, "to") - at) > 0)
      return sc_scene_fail_key(s, "task", "at", msg,
                               "at = %s outside [from, to]",
                               sc_scene_text(s, "at"));
  }
  double lo, hi;
  if ((st = auto_d(s, &lo, &hi, msg)) || (st = check_auto_at(s, msg)))
    return st;
  if (has_auto(s) &&
      sc_scene_int(s, "auto-period") > sc_scene_int(s, "max-period"))
    return sc_scene_fail_key(s, "task", "auto-period", msg,
                             "auto-period = %ld is above max-period = %ld "
                             "(valid: [1, max-period])",
                             sc_scene_int(s, "auto-period"),
                             sc_scene_int(s, "max-period"));
  if (sc_scene_int(s, "max-period") < sc_scene_int(s, "period"))
    return sc_scene_fail_key(s, "task", "max-period", msg,
                             "max-period = %ld is below period = %ld "
                             "(valid: >= period)",
                             sc_scene_int(s, "max-period"),
                             sc_scene_int(s, "period"));
  double marks[SC_CLI_MAXMARKS];
  size_t nmarks;
  return sc_cli_marks(s, sc_scene_text(s, "parameter"),
                      sc_scene_real(s, "from"), sc_scene_real(s, "to"), marks,
                      &nmarks, msg);
}


/* The number of points is not known in advance: no bar, but a run
 * stops cleanly on SIGINT. */
static int on_progress(void *ctx, size_t n) {
  (void)ctx;
  (void)n;
  return sc_cli_interrupted();
}

/* The brute-force sweep stops on SIGINT too. */
static int on_sweep_progress(void *ctx, size_t done, size_t total) {
  (void)ctx;
  (void)done;
  (void)total;
  return sc_cli_interrupted();
}

/* The orbit points of the period-q orbit through d at parameter p. */
static int orbit_points(sc_map *m, size_t param, double p, double d, int q,
                        double *out) {
  if (sc_map_set_param(m, param, p, NULL)) return SC_EINVAL;
  sc_map_value v;
  out[0] = d;
  for (int i = 1; i < q; i++) {
    int st = sc_map_eval(m, out[i - 1], SC_EVAL_VALUE, &v, NULL);
    if (st) return st;
    out[i] = v.f;
  }
  return SC_OK;
}

/* A special point's note as written: "branch N: " before the note of a
 * point on branch N; a start that was not continued (branch -1) belongs
 * to no branch, and its note says what it is. */
static void branch_note(char *buf, size_t len, int branch, const char *note) {
  if (branch < 0) snprintf(buf, len, "%s", note);
  else snprintf(buf, len, "branch %d: %s", branch, note);
}

static int write_points(sc_cli_run *r, const sc_orbit_branch *ob,
                        const char *pname) {
  sc_file *csv = NULL;
  int st = sc_cli_open(r, "points.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  fputs("label,parameter,value,d,period,multiplier,residual,error,method,"
        "border,note\n",
        f);
  for (size_t i = 0; i < sc_orbit_branch_nspecial(ob); i++) {
    sc_orbit_special_info sp;
    sc_orbit_branch_special(ob, i, &sp);
    fprintf(f, "%s,%s,", sc_point_label_text(sp.label), pname);
    sc_csv_double(f, sp.p);
    fputc(',', f);
    sc_csv_double(f, sp.d);
    fprintf(f, ",%d,", sp.period);
    sc_csv_double(f, sp.multiplier);
    fputc(',', f);
    sc_csv_double(f, sp.residual);
    fputc(',', f);
    sc_csv_double(f, sp.error);
    char border[SC_BORDER_NAME];
    snprintf(border, sizeof border, "%s", sp.border ? sp.border : "");
    fprintf(f, ",%s,%s", sc_location_method_text(sp.method),
            sc_cli_csv_text(border));
    char note[1024];
    branch_note(note, sizeof note, sp.branch, sp.note);
    fprintf(f, ",%s\n", sc_cli_csv_text(note));
  }
  return sc_cli_commit(r, "points.csv", csv);
}

/* What the branch plot draws, gathered while its files are written: the
 * range of every d drawn, and a marker per orbit point of a special
 * point (its first point numbered as in the table), for sc_plot_place(). */
typedef struct {
  double ylo, yhi;
  sc_plot_spot *spot;
  size_t n, cap;
} plot_marks;

static void marks_range(plot_marks *pm, double d) {
  if (!isfinite(d)) return;
  pm->ylo = fmin(pm->ylo, d);
  pm->yhi = fmax(pm->yhi, d);
}

static int marks_add(plot_marks *pm, double p, double d, int num) {
  marks_range(pm, d);
  if (pm->n == pm->cap) {
    size_t cap = pm->cap ? 2 * pm->cap : 64;
    sc_plot_spot *t = realloc(pm->spot, cap * sizeof *t);
    if (!t) return SC_ENOMEM;
    pm->spot = t;
    pm->cap = cap;
  }
  sc_plot_spot *sp = &pm->spot[pm->n++];
  memset(sp, 0, sizeof *sp);
  sp->x = p;
  sp->y = d;
  if (num > 0) snprintf(sp->text, sizeof sp->text, "%d", num);
  return SC_OK;
}

/* Every orbit point of every special point but the ends, numbered as in
 * the plot's table: what the plot marks. */
static int write_point_orbits(sc_cli_run *r, const sc_orbit_branch *ob,
                              size_t param, double *buf, int maxq,
                              plot_marks *pm) {
  sc_file *csv = NULL;
  int st = sc_cli_open(r, "branch-points.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  fputs("number,label,parameter,d,first\n", f);
  int num = 0;
  for (size_t i = 0; i < sc_orbit_branch_nspecial(ob); i++) {
    sc_orbit_special_info sp;
    sc_orbit_branch_special(ob, i, &sp);
    if (sp.label == SC_PT_EP) continue;
    num++;
    int q = sp.period <= maxq ? sp.period : 1;
    if (orbit_points(r->map, param, sp.p, sp.d, q, buf)) q = 1, buf[0] = sp.d;
    for (int k = 0; k < q; k++) {
      fprintf(f, "%d,%s,", num, sc_point_label_text(sp.label));
      sc_csv_double(f, sp.p);
      fputc(',', f);
      sc_csv_double(f, buf[k]);
      fprintf(f, ",%d\n", k == 0);
      if (marks_add(pm, sp.p, buf[k], k == 0 ? num : 0))
        return sc_fail(r->msg, SC_ENOMEM, "branch: out of memory");
    }
  }
  return sc_cli_commit(r, "branch-points.csv", csv);
}

/* The kinds a branch plot may mark, in the key's order; markers and
 * colours are the figures' shared ones (sc_plot_point_style). */
static const char *const branch_kinds[] = {"LP", "PD", "GR", "CS", "SW",
                                           "BR", "TT", "IC", "UZ"};

static int write_branch(sc_cli_run *r, const sc_orbit_branch *ob,
                        const char *pname, size_t param, double *buf,
                        int maxq, plot_marks *pm) {
  sc_file *csv = NULL, *orb = NULL;
  int st = sc_cli_open(r, "branch.csv", &csv);
  if (!st) st = sc_cli_open(r, "branch-orbits.csv", &orb);
  if (st) return st; /* the driver aborts what is open */
  FILE *f = sc_file_stream(csv), *g = sc_file_stream(orb);
  fprintf(f, "%s,d,multiplier,stable,itinerary,period,branch\n", pname);
  fprintf(g, "# every orbit point along each branch: one block per branch "
             "and point index k\n%s,d_stable,d_unstable,k,branch\n",
          pname);
  size_t n = sc_orbit_branch_npoints(ob);
  sc_orbit_point_info pt;
  for (size_t i = 0; i < n; i++) {
    sc_orbit_branch_point(ob, i, &pt);
    sc_csv_double(f, pt.p);
    fputc(',', f);
    sc_csv_double(f, pt.d);
    fputc(',', f);
    sc_csv_double(f, pt.multiplier);
    char itin[SC_ITIN_LEN];
    snprintf(itin, sizeof itin, "%s", pt.itinerary);
    fprintf(f, ",%s,%s,%d,%d\n", pt.stable ? "yes" : "no",
            sc_cli_csv_text(itin), pt.period, pt.branch);
  }
  /* Blocks: for each branch and each k, the k-th orbit point. */
  int nb = sc_orbit_branch_nbranches(ob);
  for (int b = 0; b < nb; b++) {
    int q = 0;
    for (size_t i = 0; i < n && !q; i++) {
      sc_orbit_branch_point(ob, i, &pt);
      if (pt.branch == b) q = pt.period;
    }
    if (q < 1 || q > maxq) continue;
    for (int k = 0; k < q; k++) {
      for (size_t i = 0; i < n; i++) {
        sc_orbit_branch_point(ob, i, &pt);
        if (pt.branch != b) continue;
        if (orbit_points(r->map, param, pt.p, pt.d, q, buf)) continue;
        marks_range(pm, buf[k]);
        sc_csv_double(g, pt.p);
        fputc(',', g);
        sc_csv_double(g, pt.stable ? buf[k] : NAN);
        fputc(',', g);
        sc_csv_double(g, pt.stable ? NAN : buf[k]);
        fprintf(g, ",%d,%d\n", k, b);
      }
      fputs("\n\n", g);
    }
  }
  st = sc_cli_commit(r, "branch.csv", csv);
  return st ? st : sc_cli_commit(r, "branch-orbits.csv", orb);
}

/* The brute-force sweep of the same range drawn under the branch: each
 * value starts from the previous one's final state. */
static int run_sweep(sc_cli_run *r, size_t param, double from, double to,
                     double d0, sc_sweep **sw) {
  const sc_scene *s = r->scene;
  sc_sweep_spec sp = {0};
  sp.param = param;
  sp.from = from;
  sp.to = to;
  sp.steps = (size_t)sc_scene_int(s, "sweep-steps");
  sp.iterations = (int)sc_scene_int(s, "sweep-iterations");
  sp.keep = (int)sc_scene_int(s, "sweep-keep");
  sp.d0 = d0;
  sp.direction = to >= from ? SC_SWEEP_UP : SC_SWEEP_DOWN;
  sp.seed = SC_SEED_PREVIOUS;
  sp.progress = on_sweep_progress;
  int st = sc_sweep_alloc(r->map, &sp, sw, r->msg);
  if (!st) st = sc_sweep_run(*sw, r->msg);
  if (st == SC_ECALLBACK && sc_cli_interrupted()) st = sc_cli_stop(r);
  return st;
}

static int write_sweep(sc_cli_run *r, const sc_sweep *sw, plot_marks *pm) {
  sc_file *csv = NULL;
  int st = sc_cli_open(r, "branch-sweep.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  fputs("p,d\n", f);
  sc_sweep_point pt;
  for (size_t i = 0; i < sc_sweep_npoints(sw); i++) {
    sc_sweep_get_point(sw, i, &pt);
    for (int k = 0; k < pt.nd; k++) {
      sc_csv_double(f, pt.p);
      fputc(',', f);
      sc_csv_double(f, pt.d[k]);
      fputc('\n', f);
      marks_range(pm, pt.d[k]);
    }
  }
  return sc_cli_commit(r, "branch-sweep.csv", csv);
}

/* The branch plot's frame: the table of special points takes the right
 * fifth, the key two rows at the bottom under the x label. */
#define BRANCH_LEFT 0.08
#define BRANCH_RIGHT 0.80
#define BRANCH_BOTTOM 0.20
#define BRANCH_TOP 0.93
#define BRANCH_FONT 9   /* the numbers' font, points */
#define BRANCH_MARKER 6 /* half a marker at ps 1.4, pixels */

static int write_branch_plot(sc_cli_run *r, const sc_orbit_branch *ob,
                             const char *pname, double from, double to,
                             int with_sweep, plot_marks *pm) {
  sc_map *m = r->map;
  char title[512];
  sc_plot_title(m, pname, title, sizeof title);
  sc_file *gp = NULL;
  int st = sc_cli_plot_begin(r, "branch", title, sc_plot_label(m, pname),
                             sc_plot_label(m, sc_map_type(m)->state_name),
                             &gp);
  if (st) return st;
  FILE *f = sc_file_stream(gp);
  /* Numbered markers on every orbit point a special point concerns,
   * placed where no number covers another or a marker (points under one
   * marker share one label), a marker per kind present explained in the
   * key, and the numbers' table in the right margin. */
  double ylo = pm->ylo, yhi = pm->yhi;
  if (!(ylo <= yhi)) ylo = -1, yhi = 1;            /* nothing drawn */
  double pad = yhi > ylo ? 0.04 * (yhi - ylo)      /* room for labels */
                         : fmax(fabs(ylo), 1) * 0.01;
  sc_plot_frame fr = {.width = 1200, .height = 800,
                      .left = BRANCH_LEFT, .right = BRANCH_RIGHT,
                      .bottom = BRANCH_BOTTOM, .top = BRANCH_TOP,
                      .xmin = fmin(from, to), .xmax = fmax(from, to),
                      .ymin = ylo - pad, .ymax = yhi + pad,
                      .font = BRANCH_FONT, .marker = BRANCH_MARKER};
  sc_plot_frame_write(f, &fr);
  size_t left_out = sc_plot_place(&fr, pm->spot, pm->n);
  fputs("set key at screen 0.44, screen 0.015 center bottom horizontal "
        "maxrows 2 font 'Sans,10'\n",
        f);
  int num = 0, nrow = 0, shown[sizeof branch_kinds / sizeof *branch_kinds];
  memset(shown, 0, sizeof shown);
  for (size_t i = 0; i < sc_orbit_branch_nspecial(ob); i++) {
    sc_orbit_special_info sp;
    sc_orbit_branch_special(ob, i, &sp);
    if (sp.label == SC_PT_EP) continue;
    for (size_t k = 0; k < sizeof shown / sizeof *shown; k++)
      if (strcmp(branch_kinds[k], sc_point_label_text(sp.label)) == 0)
        shown[k] = 1;
    num++;
    if (nrow >= 40) continue; /* the table says how many are left out */
    nrow++;
    fprintf(f, "set label %d '%d  %s  %.10g  (%d)%s' at screen 0.81, "
               "screen %.4f font 'Sans,9' tc rgb '#000000' noenhanced\n",
            nrow, num, sc_point_label_text(sp.label), sp.p, sp.period,
            sp.method == SC_LOC_NEWTON ? "" : " *", 0.93 - 0.021 * nrow);
  }
  fprintf(f, "set label %d 'no.  label  %s  (period)' at screen 0.81, "
             "screen 0.93 font 'Sans,9' tc rgb '#000000' noenhanced\n",
          nrow + 1, pname);
  int row = nrow + 1;
  if (num > nrow)
    fprintf(f, "set label %d '... %d more in points.csv' at screen 0.81, "
               "screen %.4f font 'Sans,9'\n",
            nrow + 2, num - nrow, 0.93 - 0.021 * row++);
  fprintf(f, "set label %d '* not located by Newton (see points.csv)' at "
             "screen 0.81, screen %.4f font 'Sans,8'\n",
          nrow + 3, 0.93 - 0.021 * row++);
  if (left_out)
    fprintf(f, "set label %d '%zu numbers left out: no free place' at "
               "screen 0.81, screen %.4f font 'Sans,8'\n",
            nrow + 4, left_out, 0.93 - 0.021 * row++);
  sc_plot_labels_write(f, &fr, pm->spot, pm->n, "#000000");
  fputs("plot ", f);
  if (with_sweep)
    fputs("'branch-sweep.csv' skip 1 using 1:2 with points pt 7 ps 0.2 lc rgb '#aaaaaa' "
          "title 'brute force', \\\n     ",
          f);
  fputs("'branch-orbits.csv' skip 2 using 1:2 with lines lw 2 "
        "lc rgb '#1f4e9e' title 'stable', \\\n",
        f);
  fputs("     'branch-orbits.csv' skip 2 using 1:3 with lines lw 1.5 dt 2 "
        "lc rgb '#d62728' title 'unstable'",
        f);
  for (size_t k = 0; k < sizeof shown / sizeof *shown; k++) {
    if (!shown[k]) continue;
    int pt;
    const char *rgb, *what;
    sc_plot_point_style(branch_kinds[k], &pt, &rgb, &what);
    fprintf(f, ", \\\n     'branch-points.csv' skip 1 using 3:(strcol(2) eq "
               "'%s' ? $4 : NaN) with points pt %d ps 1.4 lc rgb '%s' "
               "title '%s %s'",
            branch_kinds[k], pt, rgb, branch_kinds[k], what);
  }
  fputc('\n', f);
  return sc_cli_plot_end(r, "branch", gp);
}

/* The special point at which f^m is drawn (plot-at): the first with
 * that label, or the first of any label but EP; its orbit in buf and the
 * d-range drawn.  0 when none qualifies (then nothing is drawn). */
static int pick_special(sc_cli_run *r, const sc_orbit_branch *ob,
                        size_t param, const char *which, double *buf,
                        int maxq, sc_orbit_special_info *sp, double *lo,
                        double *hi) {
  size_t ns = sc_orbit_branch_nspecial(ob);
  long idx = -1;
  int any = !which || strcmp(which, "first") == 0;
  for (size_t i = 0; idx < 0 && i < ns; i++) {
    sc_orbit_branch_special(ob, i, sp);
    if (sp->label == SC_PT_EP || (any && sp->label == SC_PT_UZ)) continue;
    if (any || strcmp(which, sc_point_label_text(sp->label)) == 0)
      idx = (long)i;
  }
  if (idx < 0) return 0;
  sc_orbit_branch_special(ob, (size_t)idx, sp);
  if (sp->period > maxq) return 0;
  if (orbit_points(r->map, param, sp->p, sp->d, sp->period, buf)) return 0;
  *lo = *hi = buf[0];
  for (int k = 1; k < sp->period; k++)
    *lo = fmin(*lo, buf[k]), *hi = fmax(*hi, buf[k]);
  double w = 0.3 * (*hi - *lo) + 0.01 * (1 + fabs(*hi));
  *lo -= w;
  *hi += w;
  return 1;
}

/* f^m against d at the special point, and its orbit on the diagonal. */
static int write_special_map(sc_cli_run *r, const sc_orbit_special_info *sp,
                             const double *buf, double lo, double hi) {
  int st = sc_cli_write_map_graph(r, "branch-map.csv", sp->period, lo, hi,
                                  4001);
  sc_file *csv = NULL;
  if (!st) st = sc_cli_open(r, "branch-map-orbit.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  fputs("d,d\n", f);
  for (int k = 0; k < sp->period; k++) {
    sc_csv_double(f, buf[k]);
    fputc(',', f);
    sc_csv_double(f, buf[k]);
    fputc('\n', f);
  }
  return sc_cli_commit(r, "branch-map-orbit.csv", csv);
}

/* The plot of f^m at the special point (figs 5.9-5.11). */
static int special_map_plot(sc_cli_run *r, const char *pname,
                            const sc_orbit_special_info *sp, double lo,
                            double hi) {
  sc_map *m = r->map;
  const char *state = sc_map_type(m)->state_name;
  char title[700], ylab[64];
  snprintf(title, sizeof title, "f^{%d} at the %s point %s = %.12g "
           "(multiplier %.6g)",
           sp->period, sc_point_label_text(sp->label), pname, sp->p,
           sp->multiplier);
  snprintf(ylab, sizeof ylab, "f^{%d}(%s)", sp->period, state);
  sc_file *gp = NULL;
  int st = sc_cli_plot_begin(r, "branch-map", title, sc_plot_label(m, state),
                             ylab, &gp);
  if (st) return st;
  FILE *f = sc_file_stream(gp);
  fprintf(f, "set xrange [%.17g:%.17g]\nset yrange [%.17g:%.17g]\n", lo, hi,
          lo, hi);
  fprintf(f, "plot 'branch-map.csv' skip 1 using 1:2 with lines lw 1.5 "
             "lc rgb '#1f4e9e' title 'f^{%d}', \\\n",
          sp->period);
  fputs("     x with lines dt 2 lc rgb '#777777' title 'diagonal', \\\n", f);
  fputs("     'branch-map-orbit.csv' skip 1 using 1:2 with points pt 6 ps 1.8 "
        "lw 2 lc rgb '#d62728' title 'orbit points'\n",
        f);
  return sc_cli_plot_end(r, "branch-map", gp);
}

static int add_start(void *ctx, double p, double d, int period) {
  return sc_orbit_branch_add_start(ctx, p, d, period, NULL);
}

/* starts = auto: every orbit of period 1..auto-period with a point in
 * auto-d, at each auto-at value (the fixed-point search, orbits.h), is a
 * start; orbits on one branch are joined by the run. */
static int auto_starts(sc_cli_run *r, sc_orbit_branch *ob, size_t param,
                       size_t *n, size_t *lost) {
  const sc_scene *s = r->scene;
  sc_map *m = r->map;
  double lo, hi, p;
  int st = auto_d(s, &lo, &hi, r->msg); /* checked by branch_check() */
  if (st) return st;
  int maxq = (int)sc_scene_int(s, "auto-period");
  double saved = sc_map_get_param(m, param);
  for (const char *q = NULL; auto_at_next(s, &q, &p);) {
    if ((st = sc_map_set_param(m, param, p, r->msg))) {
      sc_map_set_param(m, param, saved, NULL);
      return st;
    }
    for (int per = 1; per <= maxq; per++) {
      sc_fixed_points_spec fs = {.period = per, .from = lo, .to = hi,
                                 .steps = 2000};
      sc_orbit_set *set = NULL;
      st = sc_fixed_points_find(m, &fs, &set, r->msg);
      if (st) {
        sc_map_set_param(m, param, saved, NULL);
        return st;
      }
      int added = 0;
      for (size_t i = 0; i < sc_orbit_set_count(set); i++) {
        sc_orbit_info o;
        sc_orbit_set_get(set, i, &o);
        if (o.neutral) continue; /* a family: no isolated orbit to follow */
        if (sc_orbit_branch_add_start(ob, p, o.d[0], per, NULL) == SC_OK)
          (*n)++, added++;
        else
          (*lost)++;
      }
      sc_orbit_set_free(set);
      /* one search's orbits alike: an orbit and its mirror image are
       * continued both or neither */
      if (added > 0) sc_orbit_branch_group_starts(ob, added, NULL);
    }
  }
  sc_map_set_param(m, param, saved, NULL);
  return SC_OK;
}

/* One branch run: the spec, the branch, the brute-force sweep, the
 * special point drawn, and the parameter's value to restore. */
typedef struct {
  const char *pname;
  size_t param;
  double saved;          /* the parameter's value in the scene */
  double *buf;           /* max-period + 2 orbit points */
  sc_orbit_branch_spec sp;
  double at, d0;         /* the d0 start and where it lies */
  sc_orbit_branch *ob;
  sc_sweep *sw;          /* sweep = yes */
  size_t nauto, nauto_lost;
  double elapsed, tsweep;
  unsigned long nev;
  int have_special;      /* a special point is drawn: */
  sc_orbit_special_info special;
  double lo, hi;         /* d-range of its plot */
  plot_marks pm;         /* what branch.png draws */
  double marks[SC_CLI_MAXMARKS]; /* user points (UZ) */
  sc_brn_job nd;         /* n > 1: the n-dimensional branch */
} branch_job;

static int branch_prepare(sc_cli_run *r, void *job) {
  branch_job *j = job;
  const sc_scene *s = r->scene;
  if (sc_map_dim(r->map) > 1) return sc_brn_prepare(r, &j->nd);
  j->pname = sc_scene_text(s, "parameter");
  j->pm.ylo = INFINITY;
  j->pm.yhi = -INFINITY;
  j->param = (size_t)sc_map_param_index(r->map, j->pname);
  j->saved = sc_map_get_param(r->map, j->param);
  j->sp = (sc_orbit_branch_spec){
      .param = j->param,
      .from = sc_scene_real(s, "from"),
      .to = sc_scene_real(s, "to"),
      .period = (int)sc_scene_int(s, "period"),
      .d0 = sc_scene_text(s, "d0") ? sc_scene_real(s, "d0") : NAN,
      .switch_pd = sc_scene_flag(s, "switch"),
      .max_points = sc_scene_int(s, "max-points"),
      .max_branches = (int)sc_scene_int(s, "max-branches"),
      .max_period = (int)sc_scene_int(s, "max-period"),
      .h0 = sc_scene_real(s, "h0"),
      .hmax = sc_scene_real(s, "hmax"),
      .linsolve = sc_linsolve_type_find(sc_scene_text(s, "linsolve")),
      .progress = on_progress,
      .progress_ctx = r,
  };
  /* d0 at `at` inside the interval: a start continued both ways */
  j->at = sc_scene_text(s, "at") ? sc_scene_real(s, "at") : j->sp.from;
  j->d0 = j->sp.d0;
  if (j->at != j->sp.from) j->sp.d0 = NAN;
  int st = sc_cli_marks(s, j->pname, j->sp.from, j->sp.to, j->marks,
                        &j->sp.nmarks, r->msg);
  if (st) return st;
  j->sp.marks = j->marks;
  j->buf = malloc(((size_t)j->sp.max_period + 2) * sizeof *j->buf);
  if (!j->buf) return sc_fail(r->msg, SC_ENOMEM, "branch: out of memory");
  return sc_orbit_branch_alloc(r->map, &j->sp, &j->ob, r->msg);
}

/* Where the brute-force sweep starts its first orbit (any point serves:
 * its transient is dropped): d0 when the scene gives it, else the first
 * point of the branch (starts = ..., auto), else 0. */
static double sweep_seed(const branch_job *j) {
  if (isfinite(j->d0)) return j->d0;
  sc_orbit_point_info pt;
  if (sc_orbit_branch_npoints(j->ob) > 0 &&
      sc_orbit_branch_point(j->ob, 0, &pt) == SC_OK && isfinite(pt.d))
    return pt.d;
  return 0;
}

/* The message of a d0 start that is on no orbit: the key, the orbit
 * sought, why not, and how to find starts. */
static int start_not_found(sc_cli_run *r, const branch_job *j) {
  const sc_scene *s = r->scene;
  char why[SC_MSG_LEN], what[SC_MSG_LEN + 64];
  snprintf(why, sizeof why, "%s", r->msg->text);
  sc_cli_user_text(why);
  if (strncmp(why, "no period-", 10) == 0)
    snprintf(what, sizeof what, "%s", why);
  else
    snprintf(what, sizeof what, "no period-%d orbit found from it (%s)",
             j->sp.period, why);
  return sc_scene_fail_key(
      s, "task", "d0", r->msg,
      "d0 = %s at %s = %s: %s; to find starts, run the fixed-point task "
      "there (kind = fixed-point, period = 1..%d, [model] %s = %s) or give "
      "starts = auto",
      sc_scene_text(s, "d0"), j->pname, sc_scene_text(s, "from"), what,
      j->sp.period, j->pname, sc_scene_text(s, "from"));
}

/* The starts, the continuation, then the brute-force sweep. */
static int branch_compute(sc_cli_run *r, void *job) {
  branch_job *j = job;
  if (sc_map_dim(r->map) > 1) return sc_brn_compute(r, &j->nd);
  double t0 = sc_progress_now();
  unsigned long ev0 = sc_map_nevals(r->map);
  int st = SC_OK;
  if (j->at != j->sp.from && isfinite(j->d0))
    st = sc_orbit_branch_add_start(j->ob, j->at, j->d0, j->sp.period, r->msg);
  if (!st) st = parse_starts(r->scene, add_start, j->ob, r->msg);
  if (!st && has_auto(r->scene))
    st = auto_starts(r, j->ob, j->param, &j->nauto, &j->nauto_lost);
  if (!st) {
    st = sc_orbit_branch_run(j->ob, r->msg);
    /* The run fails only when its one start, d0 at from, is on no orbit
     * (errors of a segment are rows): say where, and what to do. */
    if (st && st != SC_ECALLBACK && st != SC_ENOMEM && isfinite(j->sp.d0) &&
        sc_orbit_branch_nbranches(j->ob) == 0)
      st = start_not_found(r, j);
  }
  j->elapsed = sc_progress_now() - t0;
  j->nev = sc_map_nevals(r->map) - ev0;
  if (st || !sc_scene_flag(r->scene, "sweep")) return st;
  t0 = sc_progress_now();
  sc_map_set_param(r->map, j->param, j->saved, NULL);
  st = run_sweep(r, j->param, j->sp.from, j->sp.to, sweep_seed(j), &j->sw);
  j->tsweep = sc_progress_now() - t0;
  return st;
}

static int branch_write(sc_cli_run *r, void *job) {
  branch_job *j = job;
  if (sc_map_dim(r->map) > 1) return sc_brn_write(r, &j->nd);
  int maxq = j->sp.max_period, st;
  if ((st = write_points(r, j->ob, j->pname)) ||
      (st = write_point_orbits(r, j->ob, j->param, j->buf, maxq, &j->pm)) ||
      (st = write_branch(r, j->ob, j->pname, j->param, j->buf, maxq,
                         &j->pm)) ||
      (j->sw && (st = write_sweep(r, j->sw, &j->pm))))
    return st;
  j->have_special = pick_special(r, j->ob, j->param,
                                 sc_scene_text(r->scene, "plot-at"), j->buf,
                                 maxq, &j->special, &j->lo, &j->hi);
  if (j->have_special)
    st = write_special_map(r, &j->special, j->buf, j->lo, j->hi);
  /* orbit_points() moved the parameter: the summary lists the scene's */
  sc_map_set_param(r->map, j->param, j->saved, NULL);
  return st;
}

/* Special points by label and by how they were located. */
typedef struct {
  int label[SC_PT_EP + 1];
  int nbis, nfail; /* by bisection (fallback); detected, not located */
  int ndeg;        /* solved on a degenerate system: no certificate */
} special_count;

static special_count count_specials(const sc_orbit_branch *ob) {
  special_count c = {{0}, 0, 0, 0};
  for (size_t i = 0; i < sc_orbit_branch_nspecial(ob); i++) {
    sc_orbit_special_info p;
    sc_orbit_branch_special(ob, i, &p);
    if ((unsigned)p.label <= SC_PT_EP) c.label[p.label]++;
    c.nbis += p.method == SC_LOC_BISECTION;
    c.nfail += p.method == SC_LOC_FAILED;
    c.ndeg += p.method == SC_LOC_DEGENERATE;
  }
  return c;
}

static int branch_summary(sc_cli_run *r, void *job, FILE *f) {
  const branch_job *j = job;
  if (sc_map_dim(r->map) > 1) return sc_brn_summary(r, &j->nd, f);
  const sc_orbit_branch *ob = j->ob;
  fprintf(f, "  branches: %d, points: %zu, special points: %zu\n",
          sc_orbit_branch_nbranches(ob), sc_orbit_branch_npoints(ob),
          sc_orbit_branch_nspecial(ob));
  special_count c = count_specials(ob);
  fputs("  by label:", f);
  for (int l = 0; l <= SC_PT_EP; l++)
    if (c.label[l]) fprintf(f, " %s %d", sc_point_label_text(l), c.label[l]);
  if (has_auto(r->scene)) {
    fprintf(f, "\n  starts = auto: %zu orbits found", j->nauto);
    if (j->nauto_lost)
      fprintf(f, ", %zu of them not added (out of memory)", j->nauto_lost);
  }
  /* the outcome of every added start, counted as its rows are written */
  size_t ok, notfound, noroom;
  sc_orbit_branch_start_counts(ob, &ok, &notfound, &noroom);
  if (ok + notfound + noroom)
    fprintf(f, "\n  added starts: %zu continued both ways, %zu not found by "
               "shooting, %zu not continued (max-branches)",
            ok, notfound, noroom);
  fprintf(f, "\n  met again by another segment (reported once): %zu\n",
          sc_orbit_branch_nduplicate(ob));
  fprintf(f, "  located by Newton with a residual certificate: %zu; by "
             "bisection (fallback): %d; detected but NOT located: %d",
          sc_orbit_branch_nspecial(ob) - (size_t)(c.nbis + c.nfail + c.ndeg) -
              (size_t)c.label[SC_PT_EP],
          c.nbis, c.nfail);
  if (c.ndeg)
    fprintf(f, "; by Newton on a DEGENERATE system (not certified, known to "
               "its error): %d",
            c.ndeg);
  fputc('\n', f);
  for (size_t i = 0; i < sc_orbit_branch_nspecial(ob); i++) {
    sc_orbit_special_info p;
    sc_orbit_branch_special(ob, i, &p);
    char note[1024];
    branch_note(note, sizeof note, p.branch, p.note);
    fprintf(f, "  %s  %s = %.17g  d = %.17g  period %d  multiplier %.17g\n"
               "      %s%s residual %.3g, error %.3g; %s\n",
            sc_point_label_text(p.label), j->pname, p.p, p.d, p.period,
            p.multiplier, sc_location_method_text(p.method),
            p.method == SC_LOC_NONE ? "" : ":", p.residual, p.error, note);
  }
  fprintf(f, "  continuation: %.3f s, %lu map evaluations\n", j->elapsed,
          j->nev);
  if (j->sw) fprintf(f, "  brute-force sweep: %.3f s\n", j->tsweep);
  if (j->have_special)
    fprintf(f, "  map drawn at: %s at %s = %.17g\n",
            sc_point_label_text(j->special.label), j->pname, j->special.p);
  else
    fputs("  map drawn at: none\n", f);
  return SC_OK;
}

static int branch_plots(sc_cli_run *r, void *job) {
  branch_job *j = job; /* the placement writes into the marks */
  if (sc_map_dim(r->map) > 1) return sc_brn_plots(r, &j->nd);
  int st = write_branch_plot(r, j->ob, j->pname, j->sp.from, j->sp.to,
                             j->sw != NULL, &j->pm);
  if (!st && j->have_special)
    st = special_map_plot(r, j->pname, &j->special, j->lo, j->hi);
  return st;
}

static int branch_report(sc_cli_run *r, void *job) {
  const branch_job *j = job;
  if (sc_map_dim(r->map) > 1) return sc_brn_report(r, &j->nd);
  sc_cli_note(r, "%d branches, %zu points, %zu special points in %.2f s",
              sc_orbit_branch_nbranches(j->ob), sc_orbit_branch_npoints(j->ob),
              sc_orbit_branch_nspecial(j->ob), j->elapsed);
  return SC_OK;
}

static void branch_release(sc_cli_run *r, void *job) {
  branch_job *j = job;
  sc_brn_release(&j->nd);
  if (j->pname) sc_map_set_param(r->map, j->param, j->saved, NULL);
  sc_orbit_branch_free(j->ob);
  sc_sweep_free(j->sw);
  free(j->buf);
  free(j->pm.spot);
}

const sc_cli_task sc_cli_task_branch = {
    .type = {.kind = "branch",
             .doc = "continuation of a periodic orbit in one parameter: "
                    "folds (LP), flips (PD), grazing (GR), crossing-sliding "
                    "(CS), switching (SW), both re-stick (BR), threshold "
                    "touched (TT); for maps of n > 1 dimensions folds, "
                    "flips, Neimark-Sacker (NS) and branch points (BP)",
             .keys = branch_keys,
             .nkeys = sizeof branch_keys / sizeof branch_keys[0],
             .check = branch_check},
    .outputs = "branch.csv (PARAMETER,d,multiplier,stable,itinerary,period,"
               "branch), points.csv (label,parameter,value,d,period,"
               "multiplier,residual,error,method,border,note), "
               "branch-points.csv (every orbit point of each special point), "
               "branch-orbits.csv, branch-sweep.csv, summary.txt, "
               "branch.gp/png, branch-map.gp/png; n > 1: branch.csv "
               "(PARAMETER,state,multiplier,multipliers,stable,period,"
               "branch), points.csv (label,parameter,value,state,period,"
               "multiplier,multipliers,coefficient,theta,residual,error,"
               "iterations,method,note), branch-points.csv, "
               "branch-orbits.csv, summary.txt, branch.gp/png",
    .job_size = sizeof(branch_job),
    .prepare = branch_prepare,
    .compute = branch_compute,
    .write = branch_write,
    .summary = branch_summary,
    .plots = branch_plots,
    .report = branch_report,
    .release = branch_release,
};
