/* Sparse backend: SuiteSparse KLU.  The pattern is analysed once (BTF +
 * AMD ordering) at alloc; the first factorization pivots, later ones
 * refactor with the same pivot sequence (klu_refactor), and a refactor
 * that turns out singular or badly pivoted is redone with pivoting. */
#include <klu.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "linsolve_impl.h"

typedef struct {
  int n, nnz;
  klu_common common;
  klu_symbolic *sym;
  klu_numeric *num;       /* NULL until the first successful factor */
  double *val;            /* copy of the factored values (klu_condest) */
  unsigned char *mark;    /* n: permutation sign workspace */
} klu_state;

static void klu_state_release(void *state) {
  klu_state *k = state;
  if (k->num) klu_free_numeric(&k->num, &k->common);
  if (k->sym) klu_free_symbolic(&k->sym, &k->common);
  free(k->val);
  free(k->mark);
}

static int klu_init(void *state, const sc_pattern *p, sc_msg *msg) {
  klu_state *k = state;
  k->n = p->n;
  k->nnz = p->nnz;
  klu_defaults(&k->common);
  /* halt_if_singular (the default) makes klu_factor fail fast on a zero
   * pivot instead of dividing by it; we report SC_ESING. */
  k->common.halt_if_singular = 1;
  k->val = malloc(sizeof(double) * (size_t)(p->nnz > 0 ? p->nnz : 1));
  k->mark = malloc((size_t)p->n);
  if (!k->val || !k->mark) {
    klu_state_release(k);
    return sc_fail(msg, SC_ENOMEM, "sc_linsolve_alloc: klu: out of memory");
  }
  k->sym = klu_analyze(p->n, p->colptr, p->rowind, &k->common);
  if (!k->sym) {
    int st = k->common.status;
    klu_state_release(k);
    if (st == KLU_OUT_OF_MEMORY)
      return sc_fail(msg, SC_ENOMEM, "sc_linsolve_alloc: klu_analyze: out "
                                     "of memory");
    return sc_fail(msg, SC_EINVAL, "sc_linsolve_alloc: klu_analyze failed "
                                   "(KLU status %d)", st);
  }
  return SC_OK;
}

static double klu_pivot_ratio(const void *state) {
  const klu_state *k = state;
  const double *ud = k->num->Udiag;
  double lo = HUGE_VAL, hi = 0;
  for (int i = 0; i < k->n; i++) {
    lo = fmin(lo, fabs(ud[i]));
    hi = fmax(hi, fabs(ud[i]));
  }
  return hi > 0 ? lo / hi : 0;
}

/* A fresh factorization with pivoting; on failure k->num is NULL. */
static int klu_full(klu_state *k, const sc_pattern *p, sc_msg *msg) {
  if (k->num) klu_free_numeric(&k->num, &k->common);
  k->num = klu_factor(p->colptr, p->rowind, k->val, k->sym, &k->common);
  if (!k->num || k->common.status == KLU_SINGULAR) {
    int st = k->common.status;
    if (k->num) klu_free_numeric(&k->num, &k->common);
    if (st == KLU_SINGULAR)
      return sc_fail(msg, SC_ESING,
                     "sc_linsolve_factor: klu: zero pivot in column %d "
                     "(n = %d)",
                     k->common.singular_col, k->n);
    if (st == KLU_OUT_OF_MEMORY)
      return sc_fail(msg, SC_ENOMEM, "sc_linsolve_factor: klu: out of "
                                     "memory");
    return sc_fail(msg, SC_EINTERNAL, "sc_linsolve_factor: klu_factor "
                                      "failed (KLU status %d)", st);
  }
  return SC_OK;
}

static int klu_do_factor(void *state, const sc_pattern *p, const double *val,
                         int *refactored, sc_msg *msg) {
  klu_state *k = state;
  memcpy(k->val, val, sizeof(double) * (size_t)k->nnz);
  *refactored = 0;
  if (k->num) {
    /* Same pattern, new values: reuse the pivot order.  KLU does not pivot
     * here, so check the pivots and redo with pivoting if needed. */
    int ok = klu_refactor(p->colptr, p->rowind, k->val, k->sym, k->num,
                          &k->common);
    if (ok && klu_pivot_ratio(k) > SC_LINSOLVE_SING_RATIO) {
      *refactored = 1;
      return SC_OK;
    }
  }
  int st = klu_full(k, p, msg);
  if (st) return st;
  double ratio = klu_pivot_ratio(k);
  if (ratio <= SC_LINSOLVE_SING_RATIO) {
    klu_free_numeric(&k->num, &k->common);
    return sc_fail(msg, SC_ESING,
                   "sc_linsolve_factor: klu: numerically singular (pivot "
                   "ratio %.3g; valid: > %.3g)",
                   ratio, SC_LINSOLVE_SING_RATIO);
  }
  return SC_OK;
}

static int klu_do_solve(void *state, double *b, sc_msg *msg) {
  klu_state *k = state;
  if (!klu_solve(k->sym, k->num, k->n, 1, b, &k->common))
    return sc_fail(msg, SC_EINTERNAL, "sc_linsolve_solve: klu_solve failed "
                                      "(KLU status %d)", k->common.status);
  return SC_OK;
}

/* KLU factors (R \ A)(P, Q) = L U + F, with R = diag(Rs) (row scaling),
 * P = Pnum (the final row permutation, BTF and pivoting together),
 * Q = the symbolic column permutation, L unit lower triangular per block
 * and F strictly above the diagonal blocks.  So
 * det A = prod(Rs) sign(P) sign(Q) prod(Udiag). */
static void klu_det(const void *state, int *sign, double *logabs) {
  const klu_state *k = state;
  const double *ud = k->num->Udiag;
  unsigned char *mark = ((klu_state *)state)->mark; /* scratch only */
  int s = sc_perm_sign(k->n, k->num->Pnum, mark) *
          sc_perm_sign(k->n, k->sym->Q, mark);
  double l = 0;
  for (int i = 0; i < k->n; i++) {
    if (ud[i] < 0) s = -s;
    l += log(fabs(ud[i]));
    if (k->num->Rs) l += log(k->num->Rs[i]);
  }
  *sign = s;
  *logabs = l;
}

static int klu_do_rcond(void *state, const sc_pattern *p, double *rcond,
                        sc_msg *msg) {
  klu_state *k = state;
  if (!klu_condest(p->colptr, k->val, k->sym, k->num, &k->common))
    return sc_fail(msg, SC_EINTERNAL, "sc_linsolve_rcond: klu_condest "
                                      "failed (KLU status %d)",
                   k->common.status);
  *rcond = 1 / k->common.condest;
  return SC_OK;
}

const sc_linsolve_type sc_linsolve_klu_type = {
    .name = "klu",
    .state_size = sizeof(klu_state),
    .init = klu_init,
    .release = klu_state_release,
    .factor = klu_do_factor,
    .solve = klu_do_solve,
    .det = klu_det,
    .rcond = klu_do_rcond,
    .pivot_ratio = klu_pivot_ratio,
};
