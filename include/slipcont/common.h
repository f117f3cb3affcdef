/**
 * @file common.h
 * @brief Status codes, message buffers, the accuracy object and
 *        convergence tests shared by every layer of slipcont.
 *
 * Nothing here allocates or keeps state; every function is thread safe.
 */
#ifndef SLIPCONT_COMMON_H
#define SLIPCONT_COMMON_H

#include <stddef.h>

/**
 * Marks a declaration as part of the public interface.  The libraries are
 * built with hidden visibility (-fvisibility=hidden), so only what carries
 * SC_API is exported from libslipcont.so and libslipcont_io.so; everything
 * else stays private to the library.
 */
#if !defined(SC_API)
#if defined(__GNUC__) || defined(__clang__)
#define SC_API __attribute__((visibility("default")))
#else
#define SC_API
#endif
#endif

#ifdef __cplusplus
extern "C" {
#endif

/**
 * The one list of status codes: name, value, text.  SC_OK is 0, errors
 * are negative, outcomes (reasons an iteration returned that are not
 * failures) are positive.
 */
#define SC_STATUS_LIST(X)                                                   \
  X(SC_OK, 0, "success")                                                    \
  X(SC_EINVAL, -1, "invalid argument")                                      \
  X(SC_ENOMEM, -2, "out of memory")                                         \
  X(SC_ENOCONV, -3, "iteration did not converge")                           \
  X(SC_EUNDEF, -4, "map undefined (no return to the map's section)")         \
  X(SC_EIO, -5, "input/output error")                                       \
  X(SC_ESING, -6, "singular linear system")                                 \
  X(SC_ENONFINITE, -7, "non-finite value")                                  \
  X(SC_ECALLBACK, -8, "user callback failed")                               \
  X(SC_ENEUTRAL, -9, "neutral orbit: the fixed point lies in a family")    \
  X(SC_EINTERNAL, -10, "internal error")                                    \
  X(SC_CONTINUE, 1, "continue")                                             \
  X(SC_SPECIAL, 2, "special point reached")                                 \
  X(SC_END, 3, "end of the computation reached")

/** Status codes; see SC_STATUS_LIST. */
typedef enum {
/** @cond */
#define SC_STATUS_ENUM_(name, value, text) name = value,
/** @endcond */
  SC_STATUS_LIST(SC_STATUS_ENUM_)
#undef SC_STATUS_ENUM_
} sc_status;

/**
 * @brief Text for a status code ("unknown status" for others).
 * @return a static string; never NULL.
 */
SC_API const char *sc_strerror(int status);

/** Length of a message buffer, terminating NUL included. */
#define SC_MSG_LEN 512

/**
 * A caller-owned message buffer.  Functions that can fail take an
 * `sc_msg *` (which may be NULL) and, on failure, write one line of the
 * form `function: what (value; valid range)` into it.
 */
typedef struct {
  char text[SC_MSG_LEN]; /**< the message, NUL-terminated */
} sc_msg;

/**
 * @brief Write a formatted message into @p msg (no-op if NULL).
 * @return @p status, so that `return sc_fail(msg, SC_EINVAL, ...)` reads.
 */
SC_API int sc_fail(sc_msg *msg, int status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/**
 * @brief The "what" of a message written as `function: what`: @p text
 * past its leading function names (`sc_shoot_solve: `, possibly several),
 * for a message embedded in another one or shown to a user, who is told
 * what and where, not which function.  A function name is `sc_` followed
 * by lower-case letters, digits and '_', then ": ".
 * @return a pointer into @p text (@p text itself when it starts with no
 *         function name).
 */
SC_API const char *sc_msg_what(const char *text);

/**
 * The accuracy object threaded through every computation.  Every field
 * can be set from a scene's `[accuracy]` section; see docs/guide.md.
 * Tolerances are absolute/relative pairs tested as
 * |err| <= atol + rtol |x|.
 */
typedef struct {
  double event_rtol;   /**< event times: relative tolerance (default 1e-14) */
  double event_atol;   /**< event times: absolute tolerance (default 1e-15) */
  double newton_atol;  /**< Newton corrector/shooting: absolute step tol */
  double newton_rtol;  /**< Newton corrector/shooting: relative step tol */
  double newton_ftol;  /**< Newton corrector/shooting: residual tol */
  int newton_maxiter;  /**< Newton iterations before SC_ENOCONV */
  double ode_atol;     /**< numerical flows: absolute tolerance */
  double ode_rtol;     /**< numerical flows: relative tolerance */
  double fd_step;      /**< finite-difference relative step (cross-checks) */
  double period_rtol;  /**< period detection: tolerance / attractor size */
  int max_events;      /**< slip phases per iterate before f is undefined */
  int precision;       /**< SC_PRECISION_DOUBLE (every preset), or
                            SC_PRECISION_QUAD: bk2's exact flows and event
                            location in __float128 (slow; the reference,
                            see docs/accuracy.md); scene key
                            `precision = double|quad` */
} sc_accuracy;

/** Values of sc_accuracy.precision. */
enum { SC_PRECISION_DOUBLE = 0, SC_PRECISION_QUAD = 1 };

/** Names accepted by sc_accuracy_preset(). */
#define SC_ACCURACY_PRESETS "fast, default, precise"

/**
 * @brief Fill @p acc with a named preset: "fast", "default", "precise".
 * @return SC_OK, or SC_EINVAL for an unknown name (message says which).
 */
SC_API int sc_accuracy_preset(sc_accuracy *acc, const char *name, sc_msg *msg);

/**
 * @brief Check every field: finite, positive tolerances, counts >= 1.
 * @return SC_OK or SC_EINVAL naming the first bad field.
 */
SC_API int sc_accuracy_check(const sc_accuracy *acc, sc_msg *msg);

/**
 * @brief Set one field by name (the names of the struct members with '_'
 * written as '-': "event-rtol", "newton-maxiter", ...), from text;
 * "precision" takes the words "double" or "quad".
 * @return SC_OK, or SC_EINVAL for an unknown name, a malformed number,
 *         NaN or an out-of-range value.
 */
SC_API int sc_accuracy_set(sc_accuracy *acc, const char *name, const char *value,
                           sc_msg *msg);

/** Number of settable fields; sc_accuracy_field_name(i) lists them. */
SC_API size_t sc_accuracy_nfields(void);
/** Name of field @p i (0 <= i < sc_accuracy_nfields()), or NULL. */
SC_API const char *sc_accuracy_field_name(size_t i);
/** Current value of field @p i as a double (counts converted). */
SC_API double sc_accuracy_field_value(const sc_accuracy *acc, size_t i);
/** One line saying what field @p i controls, or NULL. */
SC_API const char *sc_accuracy_field_doc(size_t i);
/**
 * @brief Valid range [lo, hi] of field @p i (closed; tolerances have
 * lo > 0).  @return 1 if the field is a count, 0 if a real, -1 if @p i is
 * out of range.
 */
SC_API int sc_accuracy_field_range(size_t i, double *lo, double *hi);

/**
 * @brief Convergence test |dx| <= epsabs + epsrel |x|.
 * @return SC_OK if converged, SC_CONTINUE if not, SC_EINVAL for NaN or
 *         negative tolerances, SC_ENONFINITE if dx or x is not finite.
 */
SC_API int sc_test_delta(double dx, double x, double epsabs, double epsrel);

/**
 * @brief Residual test |f| <= epsabs.
 * @return SC_OK, SC_CONTINUE, SC_EINVAL (bad tolerance) or SC_ENONFINITE.
 */
SC_API int sc_test_residual(double f, double epsabs);

/** How the points of a grid are spaced (sc_grid()). */
typedef enum {
  SC_GRID_LINEAR = 0, /**< equal differences (the default) */
  SC_GRID_LOG = 1,    /**< equal ratios: from and to of one sign, not 0 */
} sc_grid_scale;

/**
 * @brief Point @p i of the grid of @p steps points from @p from to @p to,
 * both ends included: the one grid formula of slipcont (sweeps, charts,
 * the fixed-point scan, map graphs).  With t = i / (steps - 1):
 * linear: from + (to - from) t, or from (1 - t) + to t when to - from
 * overflows (a grid from -1e308 to 1e308); log: from (to/from)^t, or
 * exp(ln|from| + t (ln|to| - ln|from|)) with from's sign when to/from
 * overflows.
 * Point 0 is exactly @p from and point steps - 1 exactly @p to; steps = 1
 * gives @p from only.
 * @return the point; NaN for i >= steps, steps = 0, non-finite ends, or a
 *         log grid whose ends are 0 or of different signs.
 */
SC_API double sc_grid(double from, double to, size_t steps, size_t i,
                      sc_grid_scale scale);

/**
 * @brief Check the ends of a grid: finite, and for SC_GRID_LOG non-zero
 * and of one sign.
 * @return SC_OK, or SC_EINVAL with "NAME: ..." in @p msg (NAME is the
 *         caller's name for the axis, e.g. "x").
 */
SC_API int sc_grid_check(const char *name, double from, double to,
                         sc_grid_scale scale, sc_msg *msg);

/* ------------------------------------------------------------------ */
/* Orbits: one equality rule, one minimal-period rule                   */

/**
 * Two points of orbits are the same point when they agree to this many
 * Newton step tolerances (newton_atol + newton_rtol |x|): far above the
 * accuracy of a polished point (a few tolerances), far below the spacing
 * of the points of distinct orbits.
 */
#define SC_ORBIT_SAME_TOLS 1e4

/** @brief The tolerance of sc_orbit_same() and sc_orbit_minimal_period()
 * at @p x: SC_ORBIT_SAME_TOLS (newton_atol + newton_rtol |x|). */
SC_API double sc_orbit_tol(const sc_accuracy *acc, double x);

/**
 * @brief The minimal period of the orbit @p pts[0..m-1] (the m iterates
 * of a fixed point of f^m, from pts[0]): the smallest divisor q of m with
 * |pts[q] - pts[0]| <= tol; m if none.
 */
SC_API int sc_orbit_minimal_period(const double *pts, int m, double tol);

/**
 * @brief Whether the orbits @p a and @p b of m points each are one orbit:
 * some rotation of b agrees with a point by point within @p tol.
 * @return 1 or 0.
 */
SC_API int sc_orbit_same(const double *a, const double *b, int m, double tol);

/**
 * @brief sc_orbit_minimal_period() for an orbit of points with @p n
 * components: @p pts[i n + c] is component c of point i.  Two points are
 * equal when every component agrees within @p tol (the max-norm).
 */
SC_API int sc_orbit_minimal_period_n(const double *pts, int m, size_t n,
                                     double tol);

/**
 * @brief sc_orbit_same() for orbits of points with @p n components (the
 * layout of sc_orbit_minimal_period_n()): some rotation of @p b agrees
 * with @p a point by point, every component within @p tol.
 * @return 1 or 0.
 */
SC_API int sc_orbit_same_n(const double *a, const double *b, int m, size_t n,
                           double tol);

/**
 * @brief The first field where two texts of @p sep-separated fields
 * differ (itineraries joined by '|', scene texts by '\n'): writes
 * "A -> B" into @p out (both fields, "" for a missing one).
 * @return the field's 1-based index, or 0 (and "" in @p out) if the texts
 *         are equal.
 */
SC_API int sc_first_change(const char *a, const char *b, char sep, char *out,
                           size_t len);

/** What sc_number_syntax() found. */
enum {
  SC_NUM_NONE = 0, /**< not a decimal number */
  SC_NUM_INT = 1,  /**< [sign] digits */
  SC_NUM_REAL = 2, /**< with a decimal point or an exponent */
};

/**
 * @brief The one rule for numbers read from text (scenes, options):
 * decimal only.  An integer is an optional sign and decimal digits
 * ("1000", "-3"); a real may also have a decimal point and an exponent
 * ("0.025", "1e-3", "2.5E+4").  Hexadecimal ("0x10", "0x1p3"), "nan" and
 * "inf" are not numbers.  Blanks around the number are allowed.
 * @return SC_NUM_NONE, SC_NUM_INT or SC_NUM_REAL.
 */
SC_API int sc_number_syntax(const char *text);

/**
 * @brief Parse a real number from the whole of @p text (sc_number_syntax():
 * an integer or a real).
 * @return SC_OK, or SC_EINVAL for empty text, trailing garbage, another
 *         syntax, or a value that overflows a double.
 */
SC_API int sc_parse_double(const char *text, double *out);

/**
 * @brief Parse an integer (sc_number_syntax() SC_NUM_INT: "1e3" is not
 * one) in [lo, hi] from the whole of @p text.
 * @return SC_OK or SC_EINVAL (also when the value overflows a long).
 */
SC_API int sc_parse_long(const char *text, long lo, long hi, long *out);

#ifdef __cplusplus
}
#endif
#endif
