/* Augmented systems for fixed points, folds and flips of a 1-D map
 * iterate g = f^m(x, p), as continuation problems (continuation.h):
 *
 *   fixed point  u = (x, p_a):       F = g - x
 *   fold curve   u = (x, p_a, p_b):  F = (g - x, g_x - 1)
 *   flip curve   u = (x, p_a, p_b):  F = (g - x, g_x + 1)
 *
 * with Jacobians from g's first (fixed point) or second (curves)
 * derivatives.  The callbacks only read the system: thread safe. */
#include <string.h>

#include "slipcont/continuation.h"

/* Evaluate g at u with the free parameters taken from u. */
static int jet_at(const sc_map1d_system *s, const double *u, int order,
                  sc_map1d_jet *jet) {
  double p[SC_MAP1D_MAXPARAM];
  memcpy(p, s->p, sizeof p);
  p[s->ifree[0]] = u[1];
  if (s->kind != SC_MAP1D_FIXED) p[s->ifree[1]] = u[2];
  memset(jet, 0, sizeof *jet);
  return s->fn(u[0], p, order, jet, s->user);
}

static int map1d_f(const double *u, double *F, void *user) {
  const sc_map1d_system *s = user;
  sc_map1d_jet j;
  int rc = jet_at(s, u, s->kind == SC_MAP1D_FIXED ? 0 : 1, &j);
  if (rc) return rc;
  F[0] = j.g - u[0];
  if (s->kind == SC_MAP1D_FOLD) F[1] = j.gx - 1;
  if (s->kind == SC_MAP1D_FLIP) F[1] = j.gx + 1;
  return 0;
}

static int map1d_jac(const double *u, double *J, void *user) {
  const sc_map1d_system *s = user;
  sc_map1d_jet j;
  int a = s->ifree[0], b = s->ifree[1];
  if (s->kind == SC_MAP1D_FIXED) {
    int rc = jet_at(s, u, 1, &j);
    if (rc) return rc;
    J[0] = j.gx - 1;
    J[1] = j.gp[a];
    return 0;
  }
  int rc = jet_at(s, u, 2, &j);
  if (rc) return rc;
  /* Row-major 2 x 3: d(g - x)/d(x, p_a, p_b), d(g_x -+ 1)/d(x, p_a, p_b). */
  J[0] = j.gx - 1;
  J[1] = j.gp[a];
  J[2] = j.gp[b];
  J[3] = j.gxx;
  J[4] = j.gxp[a];
  J[5] = j.gxp[b];
  return 0;
}

static int map1d_test(const double *u, const double *t, double *psi,
                      void *user) {
  const sc_map1d_system *s = user;
  sc_map1d_jet j;
  (void)t;
  if (s->kind == SC_MAP1D_FIXED) {
    int rc = jet_at(s, u, 1, &j);
    if (rc) return rc;
    psi[0] = j.gx - 1; /* multiplier +1: fold */
    psi[1] = j.gx + 1; /* multiplier -1: flip */
    return 0;
  }
  int rc = jet_at(s, u, 2, &j);
  if (rc) return rc;
  psi[0] = j.gxx; /* the fold's quadratic coefficient: cusp */
  return 0;
}

static const char *const fixed_names[] = {"fold", "flip"};
static const char *const fold_names[] = {"cusp"};

int sc_map1d_problem(const sc_map1d_system *sys, sc_cont_problem *pb,
                     sc_msg *msg) {
  if (!sys || !sys->fn || sys->np < 1 || sys->np > SC_MAP1D_MAXPARAM)
    return sc_fail(msg, SC_EINVAL,
                   "sc_map1d_problem: NULL map or np = %zu (valid: [1, %d])",
                   sys ? sys->np : 0, SC_MAP1D_MAXPARAM);
  int two = sys->kind != SC_MAP1D_FIXED;
  if (sys->kind != SC_MAP1D_FIXED && sys->kind != SC_MAP1D_FOLD &&
      sys->kind != SC_MAP1D_FLIP)
    return sc_fail(msg, SC_EINVAL, "sc_map1d_problem: unknown kind %d",
                   (int)sys->kind);
  for (int i = 0; i <= two; i++)
    if (sys->ifree[i] < 0 || (size_t)sys->ifree[i] >= sys->np)
      return sc_fail(msg, SC_EINVAL,
                     "sc_map1d_problem: free parameter index %d (valid: [0, "
                     "%zu))",
                     sys->ifree[i], sys->np);
  if (two && sys->ifree[0] == sys->ifree[1])
    return sc_fail(msg, SC_EINVAL,
                   "sc_map1d_problem: both free parameters are index %d",
                   sys->ifree[0]);
  memset(pb, 0, sizeof *pb);
  pb->n = two ? 2 : 1;
  pb->f = map1d_f;
  pb->jac = map1d_jac;
  pb->user = (void *)sys; /* only read by the callbacks */
  switch (sys->kind) {
  case SC_MAP1D_FIXED:
    pb->ntest = 2;
    pb->test = map1d_test;
    pb->test_names = fixed_names;
    break;
  case SC_MAP1D_FOLD:
    pb->ntest = 1;
    pb->test = map1d_test;
    pb->test_names = fold_names;
    break;
  case SC_MAP1D_FLIP:
    pb->ntest = 0;
    break;
  }
  return SC_OK;
}
