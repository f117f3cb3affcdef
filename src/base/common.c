/* Status texts, message buffers, accuracy presets and convergence tests. */
#include "slipcont/common.h"

#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *sc_strerror(int status) {
  switch (status) {
#define SC_STATUS_CASE_(name, value, text)                                  \
  case value:                                                               \
    return text;
    SC_STATUS_LIST(SC_STATUS_CASE_)
#undef SC_STATUS_CASE_
  default:
    return "unknown status";
  }
}

int sc_fail(sc_msg *msg, int status, const char *fmt, ...) {
  if (msg) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg->text, sizeof msg->text, fmt, ap);
    va_end(ap);
  }
  return status;
}

const char *sc_msg_what(const char *text) {
  for (;;) {
    if (strncmp(text, "sc_", 3) != 0) return text;
    size_t n = 3 + strspn(text + 3, "abcdefghijklmnopqrstuvwxyz0123456789_");
    if (n == 3 || text[n] != ':' || text[n + 1] != ' ') return text;
    text += n + 2;
  }
}

/* One row per settable field: its scene name, where it lives, whether it
 * is a count, and its valid range (closed; tolerances must be > 0, which
 * the lower bound DBL_MIN expresses). */
typedef struct {
  const char *name; /* scene name: the member name with '-' for '_' */
  size_t offset;
  int is_int;
  double lo, hi;
  const char *doc;
} field_info;

#define FIELD_(member, name, is_int, lo, hi, doc)                           \
  { name, offsetof(sc_accuracy, member), is_int, lo, hi, doc }

static const field_info fields[] = {
    FIELD_(event_rtol, "event-rtol", 0, 4 * DBL_EPSILON, 1e-2,
           "event times: relative tolerance of the located root"),
    FIELD_(event_atol, "event-atol", 0, DBL_MIN, 1e-2,
           "event times: absolute tolerance of the located root"),
    FIELD_(newton_atol, "newton-atol", 0, DBL_MIN, 1e-1,
           "Newton (shooting, continuation): absolute step tolerance"),
    FIELD_(newton_rtol, "newton-rtol", 0, DBL_MIN, 1e-1,
           "Newton: relative step tolerance"),
    FIELD_(newton_ftol, "newton-ftol", 0, DBL_MIN, 1e-1,
           "Newton: residual tolerance"),
    FIELD_(newton_maxiter, "newton-maxiter", 1, 1, 1000,
           "Newton iterations before giving up (a count)"),
    FIELD_(ode_atol, "ode-atol", 0, DBL_MIN, 1e-2,
           "numerical flows (flows = numerical): absolute tolerance"),
    FIELD_(ode_rtol, "ode-rtol", 0, 4 * DBL_EPSILON, 1e-2,
           "numerical flows: relative tolerance"),
    FIELD_(fd_step, "fd-step", 0, DBL_EPSILON, 1e-1,
           "relative step of finite-difference cross-checks"),
    FIELD_(period_rtol, "period-rtol", 0, DBL_EPSILON, 1e-1,
           "period detection: tolerance relative to the spread of the orbit"),
    /* no storage is sized by it: long chains' large slips take 10^4 to
     * 10^5 phases (docs/chain.md, "Event catalogue") */
    FIELD_(max_events, "max-events", 1, 2, 10000000,
           "slip phases in one iterate before the map is declared undefined (a count)"),
};
#define NFIELDS (sizeof fields / sizeof fields[0])

size_t sc_accuracy_nfields(void) { return NFIELDS; }

const char *sc_accuracy_field_name(size_t i) {
  return i < NFIELDS ? fields[i].name : NULL;
}

const char *sc_accuracy_field_doc(size_t i) {
  return i < NFIELDS ? fields[i].doc : NULL;
}

int sc_accuracy_field_range(size_t i, double *lo, double *hi) {
  if (i >= NFIELDS) return -1;
  *lo = fields[i].lo;
  *hi = fields[i].hi;
  return fields[i].is_int;
}

double sc_accuracy_field_value(const sc_accuracy *acc, size_t i) {
  if (i >= NFIELDS) return NAN;
  const char *base = (const char *)acc + fields[i].offset;
  return fields[i].is_int ? (double)*(const int *)base : *(const double *)base;
}

int sc_accuracy_preset(sc_accuracy *acc, const char *name, sc_msg *msg) {
  /* default: events to 1e-14 relative, Newton to ~1e2 eps; fast trades
   * event accuracy for fewer refinement steps; precise pushes every
   * tolerance to a few ulps. */
  sc_accuracy a = {
      .event_rtol = 1e-14,
      .event_atol = 1e-15,
      .newton_atol = 1e-13,
      .newton_rtol = 1e-13,
      .newton_ftol = 1e-13,
      .newton_maxiter = 30,
      .ode_atol = 1e-10,
      .ode_rtol = 1e-10,
      .fd_step = 1e-6,
      .period_rtol = 1e-6,
      .max_events = 256,
  };
  if (!name || strcmp(name, "default") == 0) {
    /* as above */
  } else if (strcmp(name, "fast") == 0) {
    a.event_rtol = 1e-9;
    a.event_atol = 1e-10;
    a.newton_atol = a.newton_rtol = a.newton_ftol = 1e-9;
    a.ode_atol = a.ode_rtol = 1e-7;
    a.period_rtol = 1e-5;
    a.max_events = 128;
  } else if (strcmp(name, "precise") == 0) {
    a.event_rtol = 4 * DBL_EPSILON;
    a.event_atol = 1e-16;
    a.newton_atol = a.newton_rtol = a.newton_ftol = 1e-15;
    a.newton_maxiter = 60;
    a.ode_atol = a.ode_rtol = 1e-13;
    a.period_rtol = 1e-8;
    a.max_events = 1024;
  } else {
    return sc_fail(msg, SC_EINVAL,
                   "sc_accuracy_preset: unknown preset '%s' (valid: %s)",
                   name, SC_ACCURACY_PRESETS);
  }
  *acc = a;
  return SC_OK;
}

static int check_field(const sc_accuracy *acc, size_t i, sc_msg *msg) {
  double v = sc_accuracy_field_value(acc, i);
  if (!(v >= fields[i].lo && v <= fields[i].hi))
    return sc_fail(msg, SC_EINVAL,
                   "sc_accuracy_check: %s = %.17g out of range (valid: "
                   "[%.17g, %.17g])",
                   sc_accuracy_field_name(i), v, fields[i].lo, fields[i].hi);
  return SC_OK;
}

int sc_accuracy_check(const sc_accuracy *acc, sc_msg *msg) {
  if (!acc) return sc_fail(msg, SC_EINVAL, "sc_accuracy_check: NULL");
  if (acc->precision != SC_PRECISION_DOUBLE &&
      acc->precision != SC_PRECISION_QUAD)
    return sc_fail(msg, SC_EINVAL,
                   "sc_accuracy_check: precision = %d out of range (valid: "
                   "SC_PRECISION_DOUBLE, SC_PRECISION_QUAD)",
                   acc->precision);
  for (size_t i = 0; i < NFIELDS; i++) {
    int st = check_field(acc, i, msg);
    if (st) return st;
  }
  return SC_OK;
}

int sc_accuracy_set(sc_accuracy *acc, const char *name, const char *value,
                    sc_msg *msg) {
  if (strcmp(name, "precision") == 0) {
    if (value && strcmp(value, "double") == 0)
      acc->precision = SC_PRECISION_DOUBLE;
    else if (value && strcmp(value, "quad") == 0)
      acc->precision = SC_PRECISION_QUAD;
    else
      return sc_fail(msg, SC_EINVAL,
                     "precision = '%s' is not valid (valid: double|quad)",
                     value ? value : "");
    return SC_OK;
  }
  for (size_t i = 0; i < NFIELDS; i++) {
    if (strcmp(fields[i].name, name) != 0) continue;
    char *base = (char *)acc + fields[i].offset;
    if (fields[i].is_int) {
      long l;
      if (sc_parse_long(value, (long)fields[i].lo, (long)fields[i].hi, &l))
        return sc_fail(msg, SC_EINVAL,
                       "%s = '%s' is not an integer in [%.0f, %.0f]", name,
                       value, fields[i].lo, fields[i].hi);
      *(int *)base = (int)l;
    } else {
      double d;
      if (sc_parse_double(value, &d))
        return sc_fail(msg, SC_EINVAL, "%s = '%s' is not a finite number",
                       name, value);
      if (!(d >= fields[i].lo && d <= fields[i].hi))
        return sc_fail(msg, SC_EINVAL,
                       "%s = %.17g out of range (valid: [%.3g, %.3g])", name,
                       d, fields[i].lo, fields[i].hi);
      *(double *)base = d;
    }
    return SC_OK;
  }
  char list[512] = "";
  for (size_t i = 0; i < NFIELDS; i++) {
    strncat(list, sc_accuracy_field_name(i), sizeof list - strlen(list) - 1);
    if (i + 1 < NFIELDS) strncat(list, ", ", sizeof list - strlen(list) - 1);
  }
  return sc_fail(msg, SC_EINVAL, "unknown accuracy key '%s' (valid: %s)",
                 name, list);
}

int sc_test_delta(double dx, double x, double epsabs, double epsrel) {
  if (!(epsabs >= 0) || !(epsrel >= 0)) return SC_EINVAL;
  if (!isfinite(dx) || !isfinite(x)) return SC_ENONFINITE;
  return fabs(dx) <= epsabs + epsrel * fabs(x) ? SC_OK : SC_CONTINUE;
}

int sc_test_residual(double f, double epsabs) {
  if (!(epsabs >= 0)) return SC_EINVAL;
  if (!isfinite(f)) return SC_ENONFINITE;
  return fabs(f) <= epsabs ? SC_OK : SC_CONTINUE;
}

static int only_blanks(const char *s) {
  while (*s && isspace((unsigned char)*s)) s++;
  return *s == '\0';
}

/* The one rule for numbers in scenes and options (docs/guide.md,
 * "Numbers"): decimal only.  A real is [sign] digits [. digits]
 * [e|E [sign] digits] (at least one digit before the exponent); an
 * integer is [sign] digits.  Hexadecimal, nan, inf and anything else are
 * refused.  Surrounding blanks are allowed.  Returns the length of the
 * number at @p p (0 if none), and whether it has a point or exponent. */
static size_t scan_decimal(const char *p, int *real) {
  size_t i = 0, digits = 0;
  *real = 0;
  if (p[i] == '+' || p[i] == '-') i++;
  while (isdigit((unsigned char)p[i])) i++, digits++;
  if (p[i] == '.') {
    *real = 1;
    i++;
    while (isdigit((unsigned char)p[i])) i++, digits++;
  }
  if (!digits) return 0;
  if (p[i] == 'e' || p[i] == 'E') {
    size_t j = i + 1, ed = 0;
    if (p[j] == '+' || p[j] == '-') j++;
    while (isdigit((unsigned char)p[j])) j++, ed++;
    if (!ed) return 0;
    *real = 1;
    i = j;
  }
  return i;
}

int sc_number_syntax(const char *text) {
  if (!text) return SC_NUM_NONE;
  while (isspace((unsigned char)*text)) text++;
  int real;
  size_t n = scan_decimal(text, &real);
  if (!n || !only_blanks(text + n)) return SC_NUM_NONE;
  return real ? SC_NUM_REAL : SC_NUM_INT;
}

int sc_parse_double(const char *text, double *out) {
  if (sc_number_syntax(text) == SC_NUM_NONE) return SC_EINVAL;
  char *end;
  errno = 0;
  double d = strtod(text, &end);
  if (errno == ERANGE && fabs(d) > 1) return SC_EINVAL;
  if (!only_blanks(end) || !isfinite(d)) return SC_EINVAL;
  *out = d;
  return SC_OK;
}

int sc_parse_long(const char *text, long lo, long hi, long *out) {
  if (sc_number_syntax(text) != SC_NUM_INT) return SC_EINVAL;
  char *end;
  errno = 0;
  long l = strtol(text, &end, 10);
  if (errno || !only_blanks(end) || l < lo || l > hi) return SC_EINVAL;
  *out = l;
  return SC_OK;
}

/* The one grid formula (common.h). */
double sc_grid(double from, double to, size_t steps, size_t i,
               sc_grid_scale scale) {
  if (steps == 0 || i >= steps || !isfinite(from) || !isfinite(to))
    return NAN;
  if (scale == SC_GRID_LOG && (from == 0 || to == 0 || (from < 0) != (to < 0)))
    return NAN;
  if (i == 0 || steps == 1) return from;
  if (i == steps - 1) return to;
  const double t = (double)i / (double)(steps - 1);
  if (scale == SC_GRID_LOG) {
    const double q = to / from; /* > 0: the ends have one sign */
    if (isfinite(q) && q > 0) {
      const double x = from * pow(q, t);
      if (isfinite(x) && x != 0) return x;
    }
    const double a = log(fabs(from)), b = log(fabs(to));
    const double x = exp(a + t * (b - a));
    return from < 0 ? -x : x;
  }
  const double span = to - from;
  if (isfinite(span)) return from + span * t;
  return from * (1 - t) + to * t;
}

int sc_grid_check(const char *name, double from, double to,
                  sc_grid_scale scale, sc_msg *msg) {
  if (!isfinite(from) || !isfinite(to))
    return sc_fail(msg, SC_EINVAL, "%s: grid ends must be finite (%g, %g)",
                   name, from, to);
  if (scale == SC_GRID_LOG && (from == 0 || to == 0 || (from < 0) != (to < 0)))
    return sc_fail(msg, SC_EINVAL,
                   "%s: a log scale needs both ends of one sign and not 0 "
                   "(from %.17g, to %.17g)",
                   name, from, to);
  if (scale != SC_GRID_LINEAR && scale != SC_GRID_LOG)
    return sc_fail(msg, SC_EINVAL, "%s: unknown grid scale %d", name,
                   (int)scale);
  return SC_OK;
}

/* Orbits (common.h). */
double sc_orbit_tol(const sc_accuracy *acc, double x) {
  return SC_ORBIT_SAME_TOLS * (acc->newton_atol + acc->newton_rtol * fabs(x));
}

/* Whether points a and b (n components each) agree within tol. */
static int same_point(const double *a, const double *b, size_t n,
                      double tol) {
  for (size_t c = 0; c < n; c++)
    if (!(fabs(a[c] - b[c]) <= tol)) return 0;
  return 1;
}

int sc_orbit_minimal_period_n(const double *pts, int m, size_t n,
                              double tol) {
  for (int q = 1; q < m; q++)
    if (m % q == 0 && same_point(pts + (size_t)q * n, pts, n, tol)) return q;
  return m;
}

int sc_orbit_same_n(const double *a, const double *b, int m, size_t n,
                    double tol) {
  for (int r = 0; r < m; r++) {
    int same = 1;
    for (int i = 0; i < m && same; i++)
      same = same_point(a + (size_t)i * n, b + (size_t)((r + i) % m) * n, n,
                        tol);
    if (same) return 1;
  }
  return 0;
}

/* The one-dimensional rules are the n-dimensional ones with n = 1. */
int sc_orbit_minimal_period(const double *pts, int m, double tol) {
  return sc_orbit_minimal_period_n(pts, m, 1, tol);
}

int sc_orbit_same(const double *a, const double *b, int m, double tol) {
  return sc_orbit_same_n(a, b, m, 1, tol);
}

int sc_first_change(const char *a, const char *b, char sep, char *out,
                    size_t len) {
  const char set[2] = {sep, '\0'};
  if (len) out[0] = '\0';
  for (int k = 1; *a || *b; k++) {
    size_t na = strcspn(a, set), nb = strcspn(b, set);
    if (na != nb || strncmp(a, b, na) != 0) {
      if (len)
        snprintf(out, len, "%.*s -> %.*s", (int)na, a, (int)nb, b);
      return k;
    }
    a += na + (a[na] == sep);
    b += nb + (b[nb] == sep);
  }
  return 0;
}
