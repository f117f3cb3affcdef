/* Two-dimensional smooth maps with answers in closed form, used to
 * validate the n-dimensional layers (docs/maps.md): the Henon map and the
 * generalized Henon map. */
#include <string.h>

#include "slipcont/models.h"

static const char *const xy_names[] = {"x", "y"};

/* Zero the derivative arrays @p flags asks for (the maps below fill their
 * nonzero entries only). */
static void clear_derivs(sc_mapn_value *out, unsigned flags) {
  size_t n = out->n, np = out->np;
  if (flags & SC_EVAL_DERIV) {
    memset(out->J, 0, n * n * sizeof(double));
    memset(out->fp, 0, np * n * sizeof(double));
  }
  if (flags & SC_EVAL_DERIV2) {
    memset(out->H, 0, n * n * n * sizeof(double));
    memset(out->Jp, 0, np * n * n * sizeof(double));
    memset(out->T, 0, n * n * n * n * sizeof(double));
  }
}

/* Index helpers for n = 2. */
#define J2(i, j) ((i) * 2 + (j))
#define H2(i, j, k) (((i) * 2 + (j)) * 2 + (k))
#define FP2(q, i) ((q) * 2 + (i))

/* --- Henon: (x, y) -> (1 - a x^2 + y, b x) ------------------------- */

typedef struct {
  double p[3];
} p3_inst;

static int p3_setup(void *inst, const double *p, const int *opt,
                    const sc_accuracy *acc, sc_msg *msg) {
  (void)opt, (void)acc, (void)msg;
  p3_inst *c = inst;
  for (int i = 0; i < 3; i++) c->p[i] = p[i];
  return SC_OK;
}

static const sc_param_info henon_params[] = {
    {"a", 1.4, -1e6, 1e6, 0, 0, "quadratic term", NULL, NULL},
    {"b", 0.3, -1e6, 1e6, 0, 0, "contraction (the Jacobian's determinant is -b)",
     NULL, NULL},
};

static int henon_eval(void *inst, const double *s, unsigned flags,
                      sc_mapn_value *out, sc_msg *msg) {
  (void)msg;
  const p3_inst *c = inst;
  double a = c->p[0], b = c->p[1], x = s[0], y = s[1];
  out->f[0] = 1 - a * x * x + y;
  out->f[1] = b * x;
  clear_derivs(out, flags);
  if (flags & SC_EVAL_DERIV) {
    out->J[J2(0, 0)] = -2 * a * x;
    out->J[J2(0, 1)] = 1;
    out->J[J2(1, 0)] = b;
    out->fp[FP2(0, 0)] = -x * x; /* d/da */
    out->fp[FP2(1, 1)] = x;      /* d/db */
  }
  if (flags & SC_EVAL_DERIV2) {
    out->H[H2(0, 0, 0)] = -2 * a;
    out->Jp[0 * 4 + J2(0, 0)] = -2 * x; /* dJ/da */
    out->Jp[1 * 4 + J2(1, 0)] = 1;      /* dJ/db */
  }
  if (flags & SC_EVAL_ITINERARY) strcpy(out->itinerary, "S");
  return SC_OK;
}

const sc_model_type sc_model_henon = {
    .name = "henon",
    .doc = "Henon map (x, y) -> (1 - a x^2 + y, b x)",
    .state_name = "x",
    .dim = 2,
    .state_names = xy_names,
    .nparam = 2,
    .params = henon_params,
    .inst_size = sizeof(p3_inst),
    .setup = p3_setup,
    .eval_n = henon_eval,
};

/* --- generalized Henon: (x, y) -> (y, alpha - beta x - y^2 + R x y) - */

static const sc_param_info ghenon_params[] = {
    {"alpha", 0.1, -1e6, 1e6, 0, 0, "constant term", NULL, NULL},
    {"beta", 0.5, -1e6, 1e6, 0, 0, "linear term in x", NULL, NULL},
    {"R", 0.5, -1e6, 1e6, 0, 0, "coefficient of x y", NULL, NULL},
};

static int ghenon_eval(void *inst, const double *s, unsigned flags,
                       sc_mapn_value *out, sc_msg *msg) {
  (void)msg;
  const p3_inst *c = inst;
  double al = c->p[0], be = c->p[1], R = c->p[2], x = s[0], y = s[1];
  out->f[0] = y;
  out->f[1] = al - be * x - y * y + R * x * y;
  clear_derivs(out, flags);
  if (flags & SC_EVAL_DERIV) {
    out->J[J2(0, 1)] = 1;
    out->J[J2(1, 0)] = -be + R * y;
    out->J[J2(1, 1)] = -2 * y + R * x;
    out->fp[FP2(0, 1)] = 1;     /* d/dalpha */
    out->fp[FP2(1, 1)] = -x;    /* d/dbeta */
    out->fp[FP2(2, 1)] = x * y; /* d/dR */
  }
  if (flags & SC_EVAL_DERIV2) {
    out->H[H2(1, 0, 1)] = out->H[H2(1, 1, 0)] = R;
    out->H[H2(1, 1, 1)] = -2;
    out->Jp[1 * 4 + J2(1, 0)] = -1; /* dJ/dbeta */
    out->Jp[2 * 4 + J2(1, 0)] = y;  /* dJ/dR */
    out->Jp[2 * 4 + J2(1, 1)] = x;
  }
  if (flags & SC_EVAL_ITINERARY) strcpy(out->itinerary, "S");
  return SC_OK;
}

const sc_model_type sc_model_ghenon = {
    .name = "ghenon",
    .doc = "generalized Henon map (x, y) -> (y, alpha - beta x - y^2 + R x y)",
    .state_name = "x",
    .dim = 2,
    .state_names = xy_names,
    .nparam = 3,
    .params = ghenon_params,
    .inst_size = sizeof(p3_inst),
    .setup = p3_setup,
    .eval_n = ghenon_eval,
};
