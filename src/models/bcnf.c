/* The border-collision normal form in two dimensions (docs/maps.md,
 * "Borders in n dimensions"): a piecewise-linear map, continuous across
 * its switching line x = 0, whose fixed points and period-2 orbits are
 * known in closed form on each side. */
#include <stdio.h>
#include <string.h>

#include "slipcont/models.h"

static const char *const xy_names[] = {"x", "y"};

enum { P_MU, P_TAU_L, P_DELTA_L, P_TAU_R, P_DELTA_R, NP };

typedef struct {
  double p[NP];
} bcnf_inst;

static int bcnf_setup(void *inst, const double *p, const int *opt,
                      const sc_accuracy *acc, sc_msg *msg) {
  (void)opt, (void)acc, (void)msg;
  bcnf_inst *c = inst;
  for (int i = 0; i < NP; i++) c->p[i] = p[i];
  return SC_OK;
}

static const sc_param_info bcnf_params[] = {
    {"mu", -0.2, -1e6, 1e6, 0, 0, "the border-collision parameter", NULL,
     NULL},
    {"tau_L", 0.5, -1e6, 1e6, 0, 0, "trace of the Jacobian for x <= 0", NULL,
     NULL},
    {"delta_L", 0.3, -1e6, 1e6, 0, 0,
     "determinant of the Jacobian for x <= 0", NULL, NULL},
    {"tau_R", -1.5, -1e6, 1e6, 0, 0, "trace of the Jacobian for x > 0", NULL,
     NULL},
    {"delta_R", 0.3, -1e6, 1e6, 0, 0,
     "determinant of the Jacobian for x > 0", NULL, NULL},
};

/* The code of one iterate: the side of the switching line, 'L' (x <= 0)
 * or 'R' (x > 0). */
static int side_of(const double *s, const sc_itin_code *force, int *right,
                   sc_msg *msg) {
  if (!force) {
    *right = s[0] > 0;
    return SC_OK;
  }
  if (force->n != 1 || (force->c[0] != 'L' && force->c[0] != 'R'))
    return sc_fail(msg, SC_EINVAL,
                   "bcnf: itinerary code of %d bytes (valid: one, L or R)",
                   force->n);
  *right = force->c[0] == 'R';
  return SC_OK;
}

/* The switching line as the border of the side followed: m = x on the
 * right, -x on the left (> 0 inside the side, as models.h asks). */
static void add_border(sc_bordern_list *bl, const double *s, int right) {
  size_t i = bl->n++;
  if (i >= bl->cap) return;
  sc_bordern *b = &bl->b[i];
  double sg = right ? 1 : -1;
  double *dx = b->dx;
  memset(b, 0, sizeof *b);
  b->dx = dx;
  b->kind = SC_BORDER_SWITCHING;
  b->value = sg * s[0];
  dx[0] = sg;
  dx[1] = 0;
  b->on_state = 1;
  snprintf(b->name, sizeof b->name, "x = 0");
}

static int bcnf_eval_ex(void *inst, const double *s, unsigned flags,
                        const sc_itin_code *force, sc_itin_code *code,
                        sc_bordern_list *borders, sc_mapn_value *out,
                        sc_msg *msg) {
  const bcnf_inst *c = inst;
  int right = 0, st = side_of(s, force, &right, msg);
  if (st) return st;
  int qt = right ? P_TAU_R : P_TAU_L, qd = right ? P_DELTA_R : P_DELTA_L;
  double tau = c->p[qt], delta = c->p[qd], x = s[0], y = s[1];
  out->f[0] = tau * x + y + c->p[P_MU];
  out->f[1] = -delta * x;
  if (flags & SC_EVAL_DERIV) {
    memset(out->fp, 0, NP * 2 * sizeof(double));
    out->J[0] = tau, out->J[1] = 1;
    out->J[2] = -delta, out->J[3] = 0;
    out->fp[P_MU * 2 + 0] = 1;
    out->fp[qt * 2 + 0] = x;
    out->fp[qd * 2 + 1] = -x;
  }
  if (flags & SC_EVAL_DERIV2) {
    memset(out->H, 0, 8 * sizeof(double));
    memset(out->T, 0, 16 * sizeof(double));
    memset(out->Jp, 0, NP * 4 * sizeof(double));
    out->Jp[qt * 4 + 0] = 1;  /* d2 f_x / dx dtau */
    out->Jp[qd * 4 + 2] = -1; /* d2 f_y / dx ddelta */
  }
  if (flags & SC_EVAL_ITINERARY) strcpy(out->itinerary, right ? "R" : "L");
  if (code) code->n = 1, code->c[0] = right ? 'R' : 'L';
  if (borders) add_border(borders, s, right);
  return SC_OK;
}

static int bcnf_eval(void *inst, const double *s, unsigned flags,
                     sc_mapn_value *out, sc_msg *msg) {
  return bcnf_eval_ex(inst, s, flags, NULL, NULL, NULL, out, msg);
}

const sc_model_type sc_model_bcnf = {
    .name = "bcnf",
    .doc = "border-collision normal form (x, y) -> (tau x + y + mu, "
           "-delta x), tau, delta = tau_L, delta_L for x <= 0, tau_R, "
           "delta_R for x > 0",
    .state_name = "x",
    .state_point_name = "x = 0",
    .dim = 2,
    .state_names = xy_names,
    .nparam = NP,
    .params = bcnf_params,
    .inst_size = sizeof(bcnf_inst),
    .setup = bcnf_setup,
    .eval_n = bcnf_eval,
    .eval_n_ex = bcnf_eval_ex,
};
