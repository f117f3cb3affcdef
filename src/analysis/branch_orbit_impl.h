/* Private to src/analysis/branch_*.c: the orbit-branch object, its
 * records and the steps shared by its files.
 *
 * A branch is run as jobs, each a segment continued along one itinerary
 * code (branch_segment.c): sc_orbit_branch_run() (branch_orbit.c) runs
 * the jobs; a segment watches the model's borders and locates the one
 * crossed (branch_border.c), then hands over to the orbit on the other
 * side, or falls back to a bisection, or switches at a flip to the
 * doubled period (branch_switch.c); each hand-over or switch queues a new
 * job.  The object, its records and the small orbit helpers are in
 * branch_orbit.c.  See orbits.h and docs/branches.md. */
#ifndef SC_ANALYSIS_BRANCH_ORBIT_IMPL_H
#define SC_ANALYSIS_BRANCH_ORBIT_IMPL_H

#include "analysis/border_list.h"
#include "slipcont/orbits.h"
#include "slipcont/continuation.h"
#include "slipcont/shooting.h"

/* Notes longer than this are cut. */
#define NOTE_LEN 640

/* How far (relative to 1 + |p|) a border located by Newton from the far
 * side may lie from a bisection bracket and still be the border that
 * bracket found: well below the distance between distinct special
 * points of a branch (1e-4 and more on the chapter's examples). */
#define BISECTION_REACH 1e-6

typedef struct {
  int branch, period, stable;
  double p, d, multiplier;
  double dmin; /* smallest orbit point: the same for every cyclic shift */
  char itin[SC_ITIN_LEN];
} point_rec;

typedef struct {
  sc_point_label label;
  int branch, period;
  double p, d, multiplier, degeneracy, residual, error;
  sc_location_method method;
  int iterations;
  char border[SC_BORDER_NAME];
  char note[NOTE_LEN];
} special_rec;

typedef struct {
  int period, direction;
  double p, d;
  double offset; /* > 0: started this far beyond a located point, which
                    may be moved further if the start fails */
  char origin[96];
  int group;     /* an added start: its group (continued all or none) */
  int found;     /* an added start: found by shooting, at d_found */
  double d_found;
} job;

/* What the callbacks of the continuation layer read. */
typedef struct {
  sc_map *m;
  size_t param;
  int period;
  const sc_itin_code *force; /* the segment's codes (a model with borders) */
  char itin[SC_ITIN_LEN];    /* the piece being continued */
  int lock;                  /* 1: stay on that piece (a piecewise-smooth
                                model whose codes could not be forced);
                                0: a smooth map, or forced codes */
} g_ctx;

struct sc_orbit_branch {
  sc_map *m;
  sc_orbit_branch_spec sp;
  size_t npts, cap_pts, nsp, cap_sp;
  point_rec *pts;
  special_rec *sps;
  int nomem;   /* a point or special point could not be stored */
  size_t nduplicate; /* special points met again by another segment */
  job *jobs;
  int njobs, nbranches;
  job *starts; /* added starts (direction unused) */
  int nstarts;
  size_t cap_starts;
  /* how the added starts fared: continued both ways, not found by
   * shooting, no room for their two segments (max_branches); one row
   * each for the last two */
  size_t nstart_ok, nstart_notfound, nstart_noroom;
  double *orbit; /* scratch: orbit points, up to max_period + 1 */
  double *seed;
  double *orb_a; /* scratch: the orbit on the known side of a DIB */
  double *orb_c; /* scratch: the orbit at the current point */
  double *orb_f; /* the orbit at the first point of the segment */
  sc_itin_code *codes;  /* the segment's codes (max_period + 2) */
  sc_itin_code *codes2; /* scratch codes */
  sc_itin_code *codes3; /* scratch codes */
  sc_itin_code *codes4; /* a border's defining codes (its own code in) */
  sc_border_list bl_prev, bl_cur, bl_tmp; /* borders (grow as needed) */
  sc_accuracy acc; /* the map's, its Newton tolerances no tighter than the
                      map's precision (sc_map_precision()) */
  sc_shoot **shooters; /* multiple shooting by period, made on first use
                          (max_period + 2 entries) */
  g_ctx ctx;
};

/* What sc_ob_locate_border() found. */
typedef struct {
  int ok;
  double p, d0;   /* the parameter and the orbit's first point */
  double dk;      /* the orbit point where the border is met */
  double m, F;    /* border and orbit residual at the solution */
  double step;    /* last Newton step in p (the error estimate) */
  double mult;    /* (f^m)' there */
  int iterations;
  int degenerate; /* the reduced system G(p) is degenerate there */
  double slope;   /* G'(p) at the solution */
  double noise;   /* the rounding level of G there */
  char why[200];
  double *orb;    /* multiple shooting: the located orbit (m points), in
                     the segment's scratch; NULL for single shooting */
} border_fix;

/* One segment being continued (branch_segment.c). */
typedef struct {
  const job *jb;
  int branch, period;
  sc_branch *br;
  sc_cont_settings set;
  double last_p, last_d, last_t, last_td, last_mult;
  double p_first, dmin_first, prev_p;
  int moved;
  unsigned long nrej; /* rejected LP/PD locations seen so far */
  /* Multiple shooting (branch_ms.c): the continued point is u = (x_0,
   * ..., x_{m-1}, p) instead of (d, p).  ms = 0: single shooting. */
  int ms;
  struct sc_orbit_branch *ob; /* the branch (the callbacks' context) */
  double u2[2];    /* (x_0, p) of the current point: what the rest reads */
  double t2[2];    /* (dx_0/ds, dp/ds) of the current tangent */
  double *ms_last; /* m + 1: the last accepted point */
  double *ms_tan;  /* m + 1: its tangent */
  double *ms_try;  /* m + 1: a border's Newton point */
  double *ms_best; /* m + 1: the nearest border's located point */
  double *ms_start; /* m + 1: a border's Newton start */
  double *ms_rhs, *ms_mat; /* m + 1, (m + 1)^2: its Newton system */
  double *ms_val;  /* scratch for the evaluation: f, f', f_p per iterate */
  sc_linsolve *ms_ls; /* dense (m + 1)^2 for the borders' Newton */
} segment;

/* branch_orbit.c: records, jobs and orbits ------------------------- */

/* Set parameter i of m to p unless it has that value already. */
int sc_ob_set_p(sc_map *m, size_t i, double p);
/* Store an accepted point (sets b->nomem when it cannot). */
void sc_ob_add_point(sc_orbit_branch *b, int branch, int period, double p,
                     double d, const sc_map_value *v, double dmin);
/* Store a special point; NULL when it is a duplicate (counted) or memory
 * is short. */
special_rec *sc_ob_add_special(sc_orbit_branch *b, sc_point_label l,
                               int branch, int period, double p, double d,
                               double mult, double deg);
/* Store an end point whose note is fmt with a and c (NULL: ""). */
void sc_ob_add_end(sc_orbit_branch *b, int branch, int period, double p,
                   double d, double mult, const char *fmt, const char *a,
                   const char *c);
/* Queue a job; 0 when max_branches are queued already. */
int sc_ob_push_job(sc_orbit_branch *b, int period, double p, double d,
                   int direction, double offset, const char *origin);
/* Shoot a period-q orbit at p from seed[0..q-1]; the orbit into
 * b->orbit. */
int sc_ob_shoot_at(sc_orbit_branch *b, int q, double p, const double *seed,
                   sc_shoot_result *res);
/* The q orbit points of d into out, along codes (NULL: natural). */
int sc_ob_iterate_orbit_forced(sc_orbit_branch *b, double d, int q,
                               const sc_itin_code *codes, double *out);
int sc_ob_iterate_orbit(sc_orbit_branch *b, double d, int q, double *out);
/* The minimal period of the orbit orb[0..m-1] by the one rule of
 * common.h: sc_orbit_minimal_period() at sc_orbit_tol(&b->acc, orb[0]);
 * with the orbit's codes (NULL: not known) a period q whose codes are
 * not q-periodic is not taken (m is returned). */
int sc_ob_minimal_period(const sc_orbit_branch *b, const double *orb, int m,
                         const sc_itin_code *codes);
/* Whether a[0..m-1] and c[0..m-1] are one orbit by the one rule of
 * common.h: sc_orbit_same() at sc_orbit_tol() of their largest point. */
int sc_ob_same_orbit(const sc_orbit_branch *b, const double *a,
                     const double *c, int m);
/* Every point of orbit a (na) within tol of a point of orbit c (nc). */
int sc_ob_close_orbits(const double *a, int na, const double *c, int nc,
                       double tol);
/* Codes of q iterates equal (a aligned with c shifted by k). */
int sc_ob_same_codes(const sc_itin_code *a, const sc_itin_code *c, int q,
                     int k);
/* f^m at (d, p) with every border, along force (NULL: natural), the
 * codes into codes. */
int sc_ob_orbit_borders(sc_orbit_branch *b, double d, int period,
                        const sc_itin_code *force, sc_itin_code *codes,
                        sc_border_list *bl, sc_map_value *v, sc_msg *msg);

/* branch_segment.c ------------------------------------------------- */
/* The corrector's largest arclength step: the spec's hmax, or the
 * interval over HMAX_AUTO_STEPS. */
double sc_ob_hmax(const sc_orbit_branch *b);

/* Continue the job jb as branch number `branch`. */
int sc_ob_run_segment(sc_orbit_branch *b, const job *jb, int branch,
                      sc_msg *msg);

/* branch_ms.c: segments by multiple shooting ---------------------- */

/* Whether a segment of a model with borders whose period-`period` orbit
 * through d has multiplier `mult` is continued by multiple shooting (the
 * switch criterion, see branch_ms.c). */
int sc_ob_ms_wanted(const sc_orbit_branch *b, int period, double d,
                    double mult);
/* The continuation problem of the multiple-shooting system on b->ctx's
 * codes and the segment's scratch; SC_OK or SC_ENOMEM. */
int sc_ob_ms_problem(sc_orbit_branch *b, segment *S, sc_cont_problem *pb,
                     sc_msg *msg);
void sc_ob_ms_free(segment *S);
/* The orbit at u (m + 1 entries) along the segment's codes, each
 * iterate from its own point: v as f^m chained (f of the last iterate,
 * multiplier the product, itinerary), the borders into bl when not NULL
 * (each border's dd is then with respect to its own iterate's point);
 * each: f, f', f_p per iterate (3 m), or NULL; out: the codes followed
 * (codes NULL: the natural ones), or NULL. */
int sc_ob_ms_eval(sc_orbit_branch *b, const sc_itin_code *codes, int period,
                  const double *u, sc_border_list *bl, sc_map_value *v,
                  double *each, sc_itin_code *out);
/* Newton on {x_{k+1} - f(x_k) = 0, border `like` = 0} in (x, p) from ua
 * (m + 1 entries), the orbit into S->ms_try; fx as
 * sc_ob_locate_border's but for the bracket checks. */
void sc_ob_ms_locate(sc_orbit_branch *b, segment *S, const sc_itin_code *codes,
                     const sc_border *like, const double *ua, border_fix *fx);

/* branch_marks.c: user points ------------------------------------- */

/* The marks passed on the step from the segment's last point to u
 * (d, p): each located at its value and recorded as a UZ point. */
void sc_ob_marks(sc_orbit_branch *b, const segment *S, const double *u);

/* branch_border.c: locating a border ------------------------------- */

/* Newton iterations on a border's defining system: from the linear
 * interpolation between two accepted points it converges quadratically
 * in a handful; more means it is not converging. */
#define BORDER_NEWTON_MAX 40

/* A Newton step dx on a border's system (single or multiple shooting)
 * that is within tolerance at x, or at the rounding floor. */
int sc_ob_border_step_done(double dx, double x, const sc_accuracy *acc);

/* Newton on the defining system of border `like` between (pa, da, ma)
 * and (pb, db, mb); the result, or why not, in fx. */
void sc_ob_locate_border(sc_orbit_branch *b, int period,
                         const sc_itin_code *codes, const sc_border *like,
                         double pa, double da, double ma, double pb,
                         double db, double mb, border_fix *fx);
/* Record a located (or not located) border point. */
special_rec *sc_ob_record_border(sc_orbit_branch *b, int branch, int period,
                                 const sc_border *bd, const border_fix *fx,
                                 double p_est, double d_est, double width);
/* A border changed sign since the last accepted point: 1 located and
 * handed over, 2 none located (fall back), 0 none changed sign. */
int sc_ob_border_crossed(sc_orbit_branch *b, segment *S, const double *u);
/* The point d_on(p) on a border in the state (like) and its derivative
 * in the parameter; SC_OK or SC_EUNDEF. */
int sc_ob_d_on(sc_orbit_branch *b, const sc_border *like, double p,
               double *don, double *don_p);
/* Where the corrector stopped: the nearest border ahead located and
 * handed over (1), or 0. */
int sc_ob_locate_ahead(sc_orbit_branch *b, segment *S, int dir);

/* branch_switch.c: hand-overs, the bisection fallback, flips -------- */

/* After a located point: the orbit on the other side, queued. */
int sc_ob_hand_over(sc_orbit_branch *b, special_rec *r, int m,
                    const sc_itin_code *cod, const char *itin, double p,
                    double *orb, int dir);
/* The fallback from the segment's last point: bisection on a change of
 * itinerary code, then the border there located from the far side. */
void sc_ob_fall_back(sc_orbit_branch *b, segment *S, const job *jb,
                     sc_msg *msg);
/* At a located flip: the period-doubled orbit queued (1), or 0. */
int sc_ob_switch_flip(sc_orbit_branch *b, int m, double p, double d);

#endif
