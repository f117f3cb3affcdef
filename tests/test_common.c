/* Status texts, accuracy presets and fields, convergence tests, number
 * parsing. */
#include <math.h>
#include <limits.h>
#include <string.h>

#include "slipcont/common.h"
#include "test_util.h"

int main(void) {
  sc_msg msg;
  sc_accuracy acc;
  tu_int("default preset", sc_accuracy_preset(&acc, "default", &msg), SC_OK);
  tu_close("default event_rtol", acc.event_rtol, 1e-14, 0);
  tu_int("default preset passes check", sc_accuracy_check(&acc, &msg), SC_OK);
  sc_accuracy fast, precise;
  sc_accuracy_preset(&fast, "fast", &msg);
  sc_accuracy_preset(&precise, "precise", &msg);
  tu_true(fast.event_rtol > acc.event_rtol &&
              precise.event_rtol < acc.event_rtol,
          "presets are ordered fast > default > precise in event_rtol");
  tu_int("unknown preset", sc_accuracy_preset(&acc, "sloppy", &msg),
         SC_EINVAL);
  tu_true(strstr(msg.text, "sloppy") != NULL, "message names it: %s",
          msg.text);

  sc_accuracy_preset(&acc, NULL, &msg);
  tu_int("set event-rtol", sc_accuracy_set(&acc, "event-rtol", "2.5e-13", &msg),
         SC_OK);
  tu_close("event_rtol after set", acc.event_rtol, 2.5e-13, 0);
  tu_int("set newton-maxiter", sc_accuracy_set(&acc, "newton-maxiter", "17",
                                               &msg), SC_OK);
  tu_int("newton_maxiter", acc.newton_maxiter, 17);
  tu_int("NaN refused", sc_accuracy_set(&acc, "ode-rtol", "nan", &msg),
         SC_EINVAL);
  tu_int("negative refused", sc_accuracy_set(&acc, "ode-rtol", "-1e-8", &msg),
         SC_EINVAL);
  tu_true(strstr(msg.text, "ode-rtol") && strstr(msg.text, "valid"),
          "range message: %s", msg.text);
  tu_int("garbage refused", sc_accuracy_set(&acc, "fd-step", "1e-6x", &msg),
         SC_EINVAL);
  tu_int("unknown key", sc_accuracy_set(&acc, "tolerance", "1", &msg),
         SC_EINVAL);
  tu_true(strstr(msg.text, "event-rtol") != NULL, "lists valid keys: %s",
          msg.text);
  acc.ode_atol = NAN;
  tu_int("check catches NaN field", sc_accuracy_check(&acc, &msg), SC_EINVAL);

  tu_int("delta converged", sc_test_delta(1e-10, 2.385, 0, 1e-9), SC_OK);
  tu_int("delta not converged", sc_test_delta(1e-8, 2.385, 0, 1e-9),
         SC_CONTINUE);
  tu_int("delta NaN tol", sc_test_delta(1e-8, 2.385, NAN, 1e-9), SC_EINVAL);
  tu_int("delta negative tol", sc_test_delta(1e-8, 2.385, -1, 1e-9),
         SC_EINVAL);
  tu_int("delta non-finite", sc_test_delta(INFINITY, 2.385, 0, 1e-9),
         SC_ENONFINITE);
  tu_int("residual", sc_test_residual(-3e-14, 1e-13), SC_OK);

  double d;
  tu_int("parse 2.385", sc_parse_double(" 2.385 ", &d), SC_OK);
  tu_close("parsed", d, 2.385, 0);
  tu_int("parse inf refused", sc_parse_double("inf", &d), SC_EINVAL);
  tu_int("parse empty refused", sc_parse_double("  ", &d), SC_EINVAL);
  long l;
  tu_int("parse long out of range", sc_parse_long("0", 1, 10, &l), SC_EINVAL);
  /* The one number rule: decimal only; integers without point or
   * exponent. */
  static const struct {
    const char *text;
    int syntax;
  } rule[] = {{"1000", SC_NUM_INT},   {" -3 ", SC_NUM_INT},
              {"+7", SC_NUM_INT},     {"1e3", SC_NUM_REAL},
              {"2.5E+4", SC_NUM_REAL}, {".5", SC_NUM_REAL},
              {"3.", SC_NUM_REAL},    {"0x10", SC_NUM_NONE},
              {"0x1p3", SC_NUM_NONE}, {"nan", SC_NUM_NONE},
              {"inf", SC_NUM_NONE},   {"1e", SC_NUM_NONE},
              {".", SC_NUM_NONE},     {"1,5", SC_NUM_NONE},
              {"", SC_NUM_NONE},      {"1 2", SC_NUM_NONE}};
  for (size_t i = 0; i < sizeof rule / sizeof rule[0]; i++)
    tu_int(rule[i].text, sc_number_syntax(rule[i].text), rule[i].syntax);
  tu_int("1e3 is not a long", sc_parse_long("1e3", 0, 10000, &l), SC_EINVAL);
  tu_int("0x10 is not a long", sc_parse_long("0x10", 0, 100, &l), SC_EINVAL);
  tu_int("2^63 overflows a long", sc_parse_long("9223372036854775808", 0,
                                                 LONG_MAX, &l), SC_EINVAL);
  tu_int("1e3 is a double", sc_parse_double("1e3", &d), SC_OK);
  tu_close("1e3", d, 1000, 0);
  tu_int("hex float refused", sc_parse_double("0x1p3", &d), SC_EINVAL);
  tu_int("1e309 overflows", sc_parse_double("1e309", &d), SC_EINVAL);
  tu_true(strcmp(sc_strerror(SC_EUNDEF),
                 "map undefined (no return to a global stick phase)") == 0,
          "strerror(SC_EUNDEF) = %s", sc_strerror(SC_EUNDEF));
  return tu_finish();
}
