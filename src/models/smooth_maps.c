/* Small smooth maps with exact answers, used to validate shooting and
 * continuation: the logistic map, the cubic (cusp) normal form and the
 * generalized-flip map gpd. */
#include <math.h>

#include "slipcont/models.h"

/* The logistic map x -> r x (1 - x).  Known answers: flip of the fixed
 * point at r = 3, of the period-2 orbit at r = 1 + sqrt 6, fold of the
 * period-3 orbit at r = 1 + 2 sqrt 2. */
typedef struct {
  double r;
} logistic_inst;

static const sc_param_info logistic_params[] = {
    {"r", 2.8, 0, 4, 0, 0, "growth rate", NULL, NULL},
};

static int logistic_setup(void *inst, const double *p, const int *opt,
                          const sc_accuracy *acc, sc_msg *msg) {
  (void)opt, (void)acc, (void)msg;
  ((logistic_inst *)inst)->r = p[0];
  return SC_OK;
}

static int logistic_eval(void *inst, double x, unsigned flags,
                         sc_map_value *out, sc_msg *msg) {
  (void)msg;
  double r = ((logistic_inst *)inst)->r;
  out->f = r * x * (1 - x);
  if (flags & (SC_EVAL_DERIV | SC_EVAL_DERIV2)) {
    out->dfdd = r * (1 - 2 * x);
    out->dfdp[0] = x * (1 - x);
  }
  if (flags & SC_EVAL_DERIV2) {
    out->d2fdd2 = -2 * r;
    out->d2fddp[0] = 1 - 2 * x;
    out->d3fdd3 = 0;
    out->d3fdd2p[0] = -2;
  }
  if (flags & SC_EVAL_ITINERARY) {
    /* The branch of the inverse: left or right of the critical point. */
    out->itinerary[0] = x < 0.5 ? 'L' : x > 0.5 ? 'R' : 'C';
    out->itinerary[1] = '\0';
  }
  return SC_OK;
}

const sc_model_type sc_model_logistic = {
    .name = "logistic",
    .doc = "logistic map x -> r x (1 - x)",
    .state_name = "x",
    .nparam = 1,
    .params = logistic_params,
    .inst_size = sizeof(logistic_inst),
    .setup = logistic_setup,
    .eval = logistic_eval,
};

/* The cubic map x -> x + mu1 + mu2 x - x^3: its fixed points solve
 * mu1 + mu2 x - x^3 = 0, with folds on mu1 = +-2 (mu2/3)^(3/2) meeting
 * in a cusp at the origin. */
/* The cubic and the gpd map are both two-parameter normal forms: one
 * instance type and one setup serve both. */
typedef struct {
  double mu1, mu2;
} mu_inst;

static int mu_setup(void *inst, const double *p, const int *opt,
                    const sc_accuracy *acc, sc_msg *msg) {
  (void)opt, (void)acc, (void)msg;
  mu_inst *c = inst;
  c->mu1 = p[0];
  c->mu2 = p[1];
  return SC_OK;
}

static const sc_param_info cubic_params[] = {
    {"mu1", 0, -1e6, 1e6, 0, 0, "constant term", NULL, NULL},
    {"mu2", 0.5, -1e6, 1e6, 0, 0, "linear term", NULL, NULL},
};

static int cubic_eval(void *inst, double x, unsigned flags, sc_map_value *out,
                      sc_msg *msg) {
  (void)msg;
  const mu_inst *c = inst;
  out->f = x + c->mu1 + c->mu2 * x - x * x * x;
  if (flags & (SC_EVAL_DERIV | SC_EVAL_DERIV2)) {
    out->dfdd = 1 + c->mu2 - 3 * x * x;
    out->dfdp[0] = 1;
    out->dfdp[1] = x;
  }
  if (flags & SC_EVAL_DERIV2) {
    out->d2fdd2 = -6 * x;
    out->d2fddp[0] = 0;
    out->d2fddp[1] = 1;
    out->d3fdd3 = -6;
    out->d3fdd2p[0] = out->d3fdd2p[1] = 0;
  }
  if (flags & SC_EVAL_ITINERARY) {
    out->itinerary[0] = 'S'; /* one smooth piece */
    out->itinerary[1] = '\0';
  }
  return SC_OK;
}

const sc_model_type sc_model_cubic = {
    .name = "cubic",
    .doc = "cubic map x -> x + mu1 + mu2 x - x^3 (cusp normal form)",
    .state_name = "x",
    .nparam = 2,
    .params = cubic_params,
    .inst_size = sizeof(mu_inst),
    .setup = mu_setup,
    .eval = cubic_eval,
};

/* The map x -> -(1 + mu1) x + mu2 x^3 - x^5: x = 0 is a fixed point with
 * multiplier -(1 + mu1), so it flips on mu1 = 0; there the period-2 map
 * is x -> x - 2 mu2 x^3 + O(x^5), so the flip's cubic normal-form
 * coefficient is c = mu2 (supercritical for mu2 > 0) and vanishes at the
 * origin: a generalized flip (degenerate period doubling), where the
 * quintic term -x^5 decides. */
static const sc_param_info gpd_params[] = {
    {"mu1", 0, -1e6, 1e6, 0, 0, "multiplier of x = 0 is -(1 + mu1)", NULL, NULL},
    {"mu2", 0.5, -1e6, 1e6, 0, 0, "cubic term", NULL, NULL},
};

static int gpd_eval(void *inst, double x, unsigned flags, sc_map_value *out,
                    sc_msg *msg) {
  (void)msg;
  const mu_inst *c = inst;
  double x2 = x * x;
  out->f = -(1 + c->mu1) * x + c->mu2 * x2 * x - x2 * x2 * x;
  if (flags & (SC_EVAL_DERIV | SC_EVAL_DERIV2)) {
    out->dfdd = -(1 + c->mu1) + 3 * c->mu2 * x2 - 5 * x2 * x2;
    out->dfdp[0] = -x;
    out->dfdp[1] = x2 * x;
  }
  if (flags & SC_EVAL_DERIV2) {
    out->d2fdd2 = 6 * c->mu2 * x - 20 * x2 * x;
    out->d2fddp[0] = -1;
    out->d2fddp[1] = 3 * x2;
    out->d3fdd3 = 6 * c->mu2 - 60 * x2;
    out->d3fdd2p[0] = 0;
    out->d3fdd2p[1] = 6 * x;
  }
  if (flags & SC_EVAL_ITINERARY) {
    out->itinerary[0] = 'S';
    out->itinerary[1] = '\0';
  }
  return SC_OK;
}

const sc_model_type sc_model_gpd = {
    .name = "gpd",
    .doc = "map x -> -(1 + mu1) x + mu2 x^3 - x^5 (generalized flip)",
    .state_name = "x",
    .nparam = 2,
    .params = gpd_params,
    .inst_size = sizeof(mu_inst),
    .setup = mu_setup,
    .eval = gpd_eval,
};
