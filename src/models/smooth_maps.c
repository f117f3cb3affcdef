/* Small smooth maps with exact answers, used to validate shooting and
 * continuation: the logistic map and the cubic (cusp) normal form. */
#include <math.h>

#include "slipcont/models.h"

/* The logistic map x -> r x (1 - x).  Known answers: flip of the fixed
 * point at r = 3, of the period-2 orbit at r = 1 + sqrt 6, fold of the
 * period-3 orbit at r = 1 + 2 sqrt 2. */
typedef struct {
  double r;
} logistic_inst;

static const sc_param_info logistic_params[] = {
    {"r", 2.8, 0, 4, 0, 0, "growth rate", NULL},
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
  if (flags & SC_EVAL_DERIV) {
    out->dfdd = r * (1 - 2 * x);
    out->dfdp[0] = x * (1 - x);
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
typedef struct {
  double mu1, mu2;
} cubic_inst;

static const sc_param_info cubic_params[] = {
    {"mu1", 0, -1e6, 1e6, 0, 0, "constant term", NULL},
    {"mu2", 0.5, -1e6, 1e6, 0, 0, "linear term", NULL},
};

static int cubic_setup(void *inst, const double *p, const int *opt,
                       const sc_accuracy *acc, sc_msg *msg) {
  (void)opt, (void)acc, (void)msg;
  cubic_inst *c = inst;
  c->mu1 = p[0];
  c->mu2 = p[1];
  return SC_OK;
}

static int cubic_eval(void *inst, double x, unsigned flags, sc_map_value *out,
                      sc_msg *msg) {
  (void)msg;
  const cubic_inst *c = inst;
  out->f = x + c->mu1 + c->mu2 * x - x * x * x;
  if (flags & SC_EVAL_DERIV) {
    out->dfdd = 1 + c->mu2 - 3 * x * x;
    out->dfdp[0] = 1;
    out->dfdp[1] = x;
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
    .inst_size = sizeof(cubic_inst),
    .setup = cubic_setup,
    .eval = cubic_eval,
};
