/* Status texts, accuracy presets and fields, convergence tests, number
 * parsing. */
#include <math.h>
#include <float.h>
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
  /* The one grid formula. */
  tu_close("grid: first", sc_grid(0.025, 0.015, 400, 0, SC_GRID_LINEAR), 0.025,
           0);
  tu_close("grid: last exactly to", sc_grid(0.025, 0.015, 400, 399,
                                            SC_GRID_LINEAR), 0.015, 0);
  tu_close("grid: from + (to - from) i/(n-1)",
           sc_grid(0.1, 0.7, 7, 3, SC_GRID_LINEAR), 0.1 + 0.6 * 0.5, 0);
  /* Ends near the largest double: to - from overflows, the points not. */
  tu_close("grid: -1e308..1e308 middle", sc_grid(-1e308, 1e308, 3, 1,
                                                 SC_GRID_LINEAR), 0, 0);
  tu_rel("grid: -1e308..1e308 quarter", sc_grid(-1e308, 1e308, 5, 1,
                                                SC_GRID_LINEAR), -5e307, 1e-15);
  for (size_t i = 0; i < 101; i++)
    if (!isfinite(sc_grid(-DBL_MAX, DBL_MAX, 101, i, SC_GRID_LINEAR)))
      tu_true(0, "grid: -DBL_MAX..DBL_MAX point %zu not finite", i);
  /* Log: equal ratios, ends exact, the sign of the ends kept. */
  /* exp and log each round: a few ulps (rtol 1e-15 is about 5 ulps). */
  tu_rel("log grid: 1..1000 point 1", sc_grid(1, 1000, 4, 1, SC_GRID_LOG), 10,
         1e-15);
  tu_rel("log grid: 1..1000 point 2", sc_grid(1, 1000, 4, 2, SC_GRID_LOG), 100,
         1e-15);
  tu_close("log grid: last exactly to", sc_grid(1e-3, 7, 9, 8, SC_GRID_LOG), 7,
           0);
  tu_rel("log grid: negative ends", sc_grid(-0.01, -1, 3, 1, SC_GRID_LOG), -0.1,
         1e-15);
  tu_true(isnan(sc_grid(-1, 1, 3, 1, SC_GRID_LOG)), "log grid across 0: NaN");
  tu_true(isnan(sc_grid(0, 1, 3, 1, SC_GRID_LOG)), "log grid from 0: NaN");
  tu_true(isnan(sc_grid(0, INFINITY, 3, 1, SC_GRID_LINEAR)),
          "grid to inf: NaN");
  tu_int("grid check: log across 0 refused",
         sc_grid_check("x", -1, 1, SC_GRID_LOG, &msg), SC_EINVAL);
  tu_true(strstr(msg.text, "x: a log scale needs both ends of one sign") !=
              NULL,
          "grid check message: %s", msg.text);
  tu_int("grid check: log 1e-3..7 ok",
         sc_grid_check("x", 1e-3, 7, SC_GRID_LOG, &msg), SC_OK);
  /* Orbits: one equality rule, one minimal-period rule. */
  sc_accuracy_preset(&acc, "default", &msg);
  tu_close("orbit tol at 0.5", sc_orbit_tol(&acc, 0.5),
           SC_ORBIT_SAME_TOLS * (acc.newton_atol + 0.5 * acc.newton_rtol), 0);
  double p2x2[] = {0.1, 0.7, 0.1 + 1e-12, 0.7};  /* period 2 seen as 4 */
  tu_int("minimal period of a doubled period-2 orbit",
         sc_orbit_minimal_period(p2x2, 4, 1e-9), 2);
  double p4[] = {0.1, 0.7, 0.2, 0.6};
  tu_int("minimal period 4", sc_orbit_minimal_period(p4, 4, 1e-9), 4);
  double p3[] = {0.1, 0.1 + 1e-6, 0.1};
  tu_int("3 does not divide by 2: period 3 kept",
         sc_orbit_minimal_period(p3, 3, 1e-9), 3);
  double a[] = {0.1, 0.5, 0.9}, rot[] = {0.9, 0.1, 0.5 + 1e-11},
         other[] = {0.1, 0.9, 0.5};
  tu_int("a rotation is the same orbit", sc_orbit_same(a, rot, 3, 1e-9), 1);
  tu_int("the reverse order is another orbit", sc_orbit_same(a, other, 3, 1e-9),
         0);
  tu_int("beyond tol: another orbit", sc_orbit_same(a, rot, 3, 1e-12), 0);
  char ch[64];
  tu_int("first change: field 2", sc_first_change("1-12|2|1", "1-12|12|1", '|',
                                                  ch, sizeof ch), 2);
  tu_true(strcmp(ch, "2 -> 12") == 0, "first change text: %s", ch);
  tu_int("first change: equal", sc_first_change("a\nb", "a\nb", '\n', ch,
                                                sizeof ch), 0);
  tu_int("first change: a missing field", sc_first_change("a\nb", "a", '\n',
                                                          ch, sizeof ch), 2);
  tu_true(strcmp(ch, "b -> ") == 0, "missing field text: '%s'", ch);
  tu_true(strcmp(sc_strerror(SC_EUNDEF),
                 "map undefined (no return to the map's section)") == 0,
          "strerror(SC_EUNDEF) = %s", sc_strerror(SC_EUNDEF));
  return tu_finish();
}
