/* Private to src/analysis/curve*.c: the orbit of f^m forced along an
 * itinerary code, as a curve system in (d, x, y) (curve_border.c). */
#ifndef SC_ANALYSIS_CURVE_IMPL_H
#define SC_ANALYSIS_CURVE_IMPL_H

#include "slipcont/curve.h"

/* The smallest residual tolerance of a curve's system: its residual
 * g_x -+ 1 is a product of m derivatives, each good to ~1e-13 relative
 * at event-rtol 1e-14 and amplified near d* and grazings, so 1e-13 (the
 * default preset's) is below its rounding floor on period-4 and -6
 * orbits of fig 5.8 (measured: 5e-13 .. 1.2e-12); 1e-11 is a factor 10
 * inside the 1e-10 the curves must meet (docs/curves.md). */
#define SC_CURVE_FTOL 1e-11

/* The largest residual floor met at a start that a curve accepts, and
 * the margin above it its tolerance is then set to: 4 x 2.5e-10 is the
 * fast preset's residual tolerance (1e-9), the loosest a curve keeps. */
#define SC_CURVE_FLOOR_MAX 2.5e-10
#define SC_CURVE_FLOOR_MARGIN 4

/* A corrected point meets its system when its residual's rounding floor
 * is within this many residual tolerances: a point polished to the
 * tolerance is within one or two; beyond ten, f'' is unbounded nearby
 * (next to d*, docs/derivations.md) and the points stop meeting their
 * system. */
#define SC_CURVE_FLOOR_FTOLS 10

/* A zero located from a sign change between two points a and b must lie
 * within this many times their distance of the interpolated point:
 * Newton from there converges to the zero the sign change brackets; one
 * farther away is another zero. */
#define SC_CURVE_BRACKET_REACH 2

/* Where a curve stopped, a watched border is near when its distance
 * estimate (|m| over its gradient) is within SC_CURVE_NEAR_HMAX largest
 * steps (the corrector gives up within a step or two of what stopped
 * it), and a location that converges farther than SC_CURVE_LOCATE_HMAX
 * largest steps away found another zero. */
#define SC_CURVE_NEAR_HMAX 4
#define SC_CURVE_LOCATE_HMAX 8

/* A curve is closed when, having gone farther than SC_CURVE_CLOSE_HMAX
 * largest steps from its start (so its first steps are not a return), it
 * comes back within SC_CURVE_CLOSE_STEPS of its current step of the start
 * (the next step would pass it). */
#define SC_CURVE_CLOSE_HMAX 4
#define SC_CURVE_CLOSE_STEPS 1.5

/* Bisections of a bracket at most: 2^-200 of any bracket is far below
 * the Newton tolerance, where a bisection stops. */
#define SC_CURVE_BISECTIONS 200

/* The accuracy a curve's Newton uses: at least SC_CURVE_FTOL, and 4 times
 * the residual floor met at the start where that is larger, never beyond
 * 1e-9 (the fast preset's). */
void sc_curve_ftol(sc_accuracy *acc, double floor);

/* The continuation settings of a curve from its own (steps, the box in
 * y, max points) in direction dir. */
void sc_curve_cont_settings(const sc_curve_settings *s, int dir,
                            sc_cont_settings *c);

/* sqrt(DBL_EPSILON): how small a located test function must be against
 * its values at the bracket's ends (what a difference-row Newton reaches
 * on a well-scaled zero) */
#define SC_SQRT_EPS 1.4901161193847656e-08

/* Border traces (curve_border.c), called by sc_curve_trace(). */
int sc_curve_trace_border(sc_map *m, const sc_curve_settings *set, double d0,
                          const sc_curve_output *out, sc_curve_stats *stats,
                          sc_msg *msg);

/* The systems of a forced orbit g = f^m along `codes` (sc_map_iterate_ex):
 *  - SC_CURVE_FOLD / SC_CURVE_FLIP: F = (g - d, g_d -+ 1); tests psi_j =
 *    the watched borders m_j (their zeros: the curve meets a border);
 *  - SC_CURVE_BORDER: F = (g - d, m_key); tests psi_0 = g_d - 1 (LP),
 *    psi_1 = g_d + 1 (PD), psi_{2+j} = m_j of the watched borders.
 * F's Jacobian is exact where it needs first derivatives only (g, m);
 * the fold/flip row g_d -+ 1 is differentiated by central differences of
 * the exact g_d (a forced evaluation has no second derivatives): it sets
 * Newton's rate, never the point, whose residual is exact. */
typedef struct {
  sc_map *m;
  int period, ix, iy;
  sc_curve_type type;
  sc_itin_code *codes; /* period entries (owned) */
  sc_border key;       /* SC_CURVE_BORDER: the border on which the orbit is */
  sc_border *watch;    /* the borders watched (owned) */
  size_t nwatch;
  const char **labels; /* tests' labels (owned array) */
  sc_border_list bl;   /* grown as needed (owned) */
  double fd_step;
  sc_msg emsg; /* of the last failed evaluation */
} sc_forced_sys;

/* Allocate codes (period entries) for s; zero the rest. */
int sc_forced_init(sc_forced_sys *s, sc_map *m, int period, int ix, int iy,
                   sc_curve_type type, double fd_step, sc_msg *msg);
void sc_forced_free(sc_forced_sys *s);
/* Set the watched borders (copied) and their labels. */
int sc_forced_watch(sc_forced_sys *s, const sc_border *w, size_t n,
                    sc_msg *msg);
/* g = f^m at u = (d, x, y) along s->codes (NULL codes: natural; `codes_out`
 * may receive the codes followed), borders into s->bl. */
int sc_forced_eval(sc_forced_sys *s, const double *u,
                   const sc_itin_code *force, sc_itin_code *codes_out,
                   sc_map_value *v);
/* The border of the list like `like` (same iterate, kind, name). */
const sc_border *sc_forced_find(const sc_border_list *l, const sc_border *like);
/* The watched border nearest to u (|m_j| over the size of its gradient
 * in (d, x, y)), or -1; that distance estimate in *dist. */
long sc_forced_nearest(sc_forced_sys *s, const double *u, double *dist);
/* Damped Newton at fixed u[fix] (1: x, 2: y) in d and the other
 * parameter on a two-equation system in (d, x, y): the orbits of f^m can sit close to d*, where f' ~
 * |d - d*|^(-1/2) (docs/derivations.md), and a full step from a guess overshoots;
 * the step is halved until the residual decreases.  Stops at
 * newton_ftol or at the residual's rounding floor (*floor_out: the last
 * residual).  SC_OK, or SC_ECALLBACK if F fails at u. */
int sc_curve_correct_fixed(const sc_cont_problem *pb, double *u, int fix,
                           const sc_accuracy *acc, double *floor_out);
/* sc_curve_correct_fixed() on a system of any size with a dense
 * Jacobian (pb->n equations in n + 1 unknowns, u[fix] held fixed, the
 * others free): multiple shooting's system.  SC_OK (the residual reached
 * in *floor_out), SC_ECALLBACK if F fails at u, SC_EINVAL for a sparse
 * pattern or fix out of range, SC_ENOMEM. */
int sc_curve_correct_fixed_n(const sc_cont_problem *pb, double *u, size_t fix,
                             const sc_accuracy *acc, double *floor_out);
/* A user point: whether the mark x = c is passed on the step from the
 * curve point a to b ((d, x, y) each; reached exactly at b, or at a when
 * `start`): -1 not passed; else the point located by damped Newton on
 * the two-equation system pb with x fixed at c, d and y free, down to
 * the residual's rounding floor, into u3 with its residual and a note
 * naming x (`xname`): 1 located, 0 not (u3 then interpolated, the note
 * says why). */
int sc_curve_mark(const sc_cont_problem *pb, const sc_accuracy *acc,
                  const char *xname, double c, const double *a,
                  const double *b, int start, double *u3, double *res,
                  char *note, size_t len);
/* Where test k of cs changes sign between the curve points a and b
 * (values pa, pb): bisection in the parameter that changes more, each
 * midpoint corrected onto cs at that value.  u receives the point with
 * the smallest |psi_k| met, m that value, width the final bracket in the
 * parameter.  SC_OK; SC_EUNDEF if psi_k jumps (its values do not go to
 * zero); SC_ENOCONV if a correction failed; SC_ENOMEM. */
int sc_curve_bisect(const sc_curve_system *cs, size_t k, const double *a,
                    const double *b, double pa, double pb,
                    const sc_accuracy *acc, double *u, double *m,
                    double *width);
/* Fill cs (n = 2, ntest = nwatch or 2 + nwatch) for s. */
void sc_forced_system(sc_forced_sys *s, sc_curve_system *cs);
/* The codes with the border's own code for its iterate substituted. */
void sc_forced_use_alt(sc_forced_sys *s, const sc_border *b);

#endif
