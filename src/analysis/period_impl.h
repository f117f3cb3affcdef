/* What the one- and n-dimensional period detectors (period.c, periodn.c)
 * share. */
#ifndef SC_PERIOD_IMPL_H
#define SC_PERIOD_IMPL_H

#include "slipcont/common.h"

/* Check the settings of a period detector (max-period, confirm,
 * period-rtol against their ranges in period.h); SC_OK or SC_EINVAL with
 * "WHO: key = value (valid: ...)". */
int sc_period_check_args(const char *who, int max_period, int confirm,
                         double rtol, sc_msg *msg);

#endif
