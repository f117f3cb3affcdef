/* The two-block Burridge-Knopoff model (MODEL.md): stub table. */
#include "slipcont/models.h"
#include <math.h>

static const sc_param_info bk2_params[] = {
    {"alpha", 3, 0, 1e6, 1, 0, "coupling spring / driver spring, k_c/k"},
    {"beta", 1, 0, 1e6, 1, 0, "static friction of block 2 / block 1"},
    {"phi", 1.25, 1, 1e6, 1, 0, "static / kinetic friction ratio, 1/mu"},
    {"v", 0.025, 0, 1e3, 0, 0, "driver velocity (dimensionless)"},
};

static const sc_option_info bk2_options[] = {
    {"driver", {"moving", "frozen", NULL}, "the driver moves during slips, or stops"},
    {"friction", {"coulomb", "velocity-weakening", NULL}, "kinetic friction law"},
    {"flows", {"exact", "numerical", NULL}, "closed-form or integrated flows"},
};

double sc_bk2_dstar(double alpha, double beta) {
  return (beta - 1) / (1 + 2 * alpha);
}

static int bk2_eval(void *inst, double d, unsigned flags, sc_map_value *out,
                    sc_msg *msg) {
  (void)inst, (void)d, (void)flags, (void)out;
  return sc_fail(msg, SC_EINTERNAL, "bk2: not yet implemented");
}

const sc_model_type sc_model_bk2 = {
    .name = "bk2",
    .doc = "two-block Burridge-Knopoff stick-slip model",
    .state_name = "d",
    .nparam = 4,
    .params = bk2_params,
    .noption = 3,
    .options = bk2_options,
    .inst_size = 1,
    .eval = bk2_eval,
};
