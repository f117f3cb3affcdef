/* The generic linear solver object: pattern checks, counters and the
 * dispatch to a backend table (linsolve_dense.c, linsolve_klu.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "linsolve_impl.h"

const sc_linsolve_type *const sc_linsolve_dense = &sc_linsolve_dense_type;
const sc_linsolve_type *const sc_linsolve_klu = &sc_linsolve_klu_type;

struct sc_linsolve {
  const sc_linsolve_type *type;
  sc_pattern pat;
  void *state;            /* type->state_size bytes */
  int factored;           /* 1 while a valid factorization is held */
  unsigned long nfactor, nrefactor, nsolve;
};

const sc_linsolve_type *sc_linsolve_type_find(const char *name) {
  if (!name) return NULL;
  if (strcmp(name, sc_linsolve_dense->name) == 0) return sc_linsolve_dense;
  if (strcmp(name, sc_linsolve_klu->name) == 0) return sc_linsolve_klu;
  return NULL;
}

const char *sc_linsolve_type_name(const sc_linsolve_type *type) {
  return type ? type->name : "(null)";
}

int sc_perm_sign(int n, const int *perm, unsigned char *mark) {
  memset(mark, 0, (size_t)n);
  int cycles = 0;
  for (int i = 0; i < n; i++) {
    if (mark[i]) continue;
    cycles++;
    for (int j = i; !mark[j]; j = perm[j]) mark[j] = 1;
  }
  return (n - cycles) % 2 ? -1 : 1;
}

static int check_pattern(int n, const int *colptr, const int *rowind,
                         sc_msg *msg) {
  if (n < 1 || !colptr || !rowind)
    return sc_fail(msg, SC_EINVAL,
                   "sc_linsolve_alloc: n = %d or NULL pattern (valid: n >= "
                   "1, colptr and rowind given)",
                   n);
  if (colptr[0] != 0)
    return sc_fail(msg, SC_EINVAL, "sc_linsolve_alloc: colptr[0] = %d "
                                   "(valid: 0)", colptr[0]);
  for (int j = 0; j < n; j++) {
    if (colptr[j + 1] < colptr[j])
      return sc_fail(msg, SC_EINVAL,
                     "sc_linsolve_alloc: colptr decreases at column %d", j);
    for (int k = colptr[j]; k < colptr[j + 1]; k++) {
      if (rowind[k] < 0 || rowind[k] >= n)
        return sc_fail(msg, SC_EINVAL,
                       "sc_linsolve_alloc: row index %d in column %d "
                       "(valid: [0, %d))",
                       rowind[k], j, n);
      if (k > colptr[j] && rowind[k] <= rowind[k - 1])
        return sc_fail(msg, SC_EINVAL,
                       "sc_linsolve_alloc: rows of column %d not strictly "
                       "increasing (%d after %d)",
                       j, rowind[k], rowind[k - 1]);
    }
  }
  return SC_OK;
}

int sc_linsolve_alloc(const sc_linsolve_type *type, int n, const int *colptr,
                      const int *rowind, sc_linsolve **out, sc_msg *msg) {
  *out = NULL;
  if (!type)
    return sc_fail(msg, SC_EINVAL, "sc_linsolve_alloc: NULL backend "
                                   "(valid: dense, klu)");
  int st = check_pattern(n, colptr, rowind, msg);
  if (st) return st;
  int nnz = colptr[n];
  sc_linsolve *s = calloc(1, sizeof *s);
  if (!s) goto fail;
  s->type = type;
  s->pat.n = n;
  s->pat.nnz = nnz;
  s->pat.colptr = malloc(sizeof(int) * (size_t)(n + 1));
  s->pat.rowind = malloc(sizeof(int) * (size_t)(nnz > 0 ? nnz : 1));
  s->state = calloc(1, type->state_size);
  if (!s->pat.colptr || !s->pat.rowind || !s->state) goto fail;
  memcpy(s->pat.colptr, colptr, sizeof(int) * (size_t)(n + 1));
  memcpy(s->pat.rowind, rowind, sizeof(int) * (size_t)nnz);
  st = type->init(s->state, &s->pat, msg);
  if (st) {
    free(s->pat.colptr);
    free(s->pat.rowind);
    free(s->state);
    free(s);
    return st;
  }
  *out = s;
  return SC_OK;
fail:
  if (s) {
    free(s->pat.colptr);
    free(s->pat.rowind);
    free(s->state);
    free(s);
  }
  return sc_fail(msg, SC_ENOMEM, "sc_linsolve_alloc: out of memory (n = %d, "
                                 "nnz = %d)", n, nnz);
}

int sc_linsolve_alloc_full(const sc_linsolve_type *type, int n,
                           sc_linsolve **out, sc_msg *msg) {
  *out = NULL;
  if (n < 1 || n > 46340) /* n^2 must fit in an int */
    return sc_fail(msg, SC_EINVAL,
                   "sc_linsolve_alloc_full: n = %d (valid: [1, 46340])", n);
  int *cp = malloc(sizeof(int) * (size_t)(n + 1));
  int *ri = malloc(sizeof(int) * (size_t)n * (size_t)n);
  if (!cp || !ri) {
    free(cp);
    free(ri);
    return sc_fail(msg, SC_ENOMEM, "sc_linsolve_alloc_full: out of memory "
                                   "(n = %d)", n);
  }
  for (int j = 0; j <= n; j++) cp[j] = j * n;
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) ri[j * n + i] = i;
  int st = sc_linsolve_alloc(type, n, cp, ri, out, msg);
  free(cp);
  free(ri);
  return st;
}

void sc_linsolve_free(sc_linsolve *s) {
  if (!s) return;
  s->type->release(s->state);
  free(s->state);
  free(s->pat.colptr);
  free(s->pat.rowind);
  free(s);
}

int sc_linsolve_factor(sc_linsolve *s, const double *val, sc_msg *msg) {
  s->factored = 0;
  for (int k = 0; k < s->pat.nnz; k++)
    if (!isfinite(val[k]))
      return sc_fail(msg, SC_ENONFINITE,
                     "sc_linsolve_factor: value %d of the matrix is %g", k,
                     val[k]);
  int refactored = 0;
  int st = s->type->factor(s->state, &s->pat, val, &refactored, msg);
  if (st) return st;
  if (refactored) s->nrefactor++;
  else s->nfactor++;
  s->factored = 1;
  return SC_OK;
}

int sc_linsolve_solve(sc_linsolve *s, double *b, sc_msg *msg) {
  if (!s->factored)
    return sc_fail(msg, SC_EINVAL,
                   "sc_linsolve_solve: no valid factorization (factor first)");
  int st = s->type->solve(s->state, b, msg);
  if (st) return st;
  s->nsolve++;
  for (int i = 0; i < s->pat.n; i++)
    if (!isfinite(b[i]))
      return sc_fail(msg, SC_ENONFINITE,
                     "sc_linsolve_solve: solution entry %d is %g", i, b[i]);
  return SC_OK;
}

int sc_linsolve_det(const sc_linsolve *s, int *sign, double *logabs) {
  if (!s->factored) return SC_EINVAL;
  s->type->det(s->state, sign, logabs);
  return SC_OK;
}

int sc_linsolve_rcond(sc_linsolve *s, double *rcond, sc_msg *msg) {
  if (!s->factored)
    return sc_fail(msg, SC_EINVAL,
                   "sc_linsolve_rcond: no valid factorization (factor first)");
  return s->type->rcond(s->state, &s->pat, rcond, msg);
}

int sc_linsolve_pivot_ratio(const sc_linsolve *s, double *ratio) {
  if (!s->factored) return SC_EINVAL;
  *ratio = s->type->pivot_ratio(s->state);
  return SC_OK;
}

const sc_linsolve_type *sc_linsolve_get_type(const sc_linsolve *s) {
  return s->type;
}
int sc_linsolve_n(const sc_linsolve *s) { return s->pat.n; }
int sc_linsolve_nnz(const sc_linsolve *s) { return s->pat.nnz; }
unsigned long sc_linsolve_nfactor(const sc_linsolve *s) { return s->nfactor; }
unsigned long sc_linsolve_nrefactor(const sc_linsolve *s) {
  return s->nrefactor;
}
unsigned long sc_linsolve_nsolve(const sc_linsolve *s) { return s->nsolve; }

int sc_csc_from_triplets(int n, int nt, const int *ti, const int *tj,
                         int *colptr, int *rowind, int *map, int *nnz,
                         sc_msg *msg) {
  if (n < 1 || nt < 0)
    return sc_fail(msg, SC_EINVAL,
                   "sc_csc_from_triplets: n = %d, nt = %d (valid: n >= 1, "
                   "nt >= 0)",
                   n, nt);
  for (int k = 0; k < nt; k++)
    if (ti[k] < 0 || ti[k] >= n || tj[k] < 0 || tj[k] >= n)
      return sc_fail(msg, SC_EINVAL,
                     "sc_csc_from_triplets: triplet %d at (%d, %d) (valid: "
                     "[0, %d))",
                     k, ti[k], tj[k], n);
  int *next = malloc(sizeof(int) * (size_t)(n + 1));
  if (!next)
    return sc_fail(msg, SC_ENOMEM, "sc_csc_from_triplets: out of memory");
  /* Counting sort by column (duplicates kept), then an insertion sort of
   * each column (columns are short) and a merge of duplicate rows; the
   * columns only move towards the front, so this works in place.  Each
   * triplet's slot is then found by bisection in its merged column. */
  for (int j = 0; j <= n; j++) colptr[j] = 0;
  for (int k = 0; k < nt; k++) colptr[tj[k] + 1]++;
  for (int j = 0; j < n; j++) colptr[j + 1] += colptr[j];
  for (int j = 0; j <= n; j++) next[j] = colptr[j];
  for (int k = 0; k < nt; k++) rowind[next[tj[k]]++] = ti[k];
  free(next);
  int out = 0;
  for (int j = 0; j < n; j++) {
    int lo = colptr[j], hi = colptr[j + 1]; /* old bounds, not yet moved */
    for (int a = lo + 1; a < hi; a++) {
      int r = rowind[a], b = a - 1;
      while (b >= lo && rowind[b] > r) {
        rowind[b + 1] = rowind[b];
        b--;
      }
      rowind[b + 1] = r;
    }
    colptr[j] = out;
    for (int a = lo; a < hi; a++)
      if (a == lo || rowind[a] != rowind[a - 1]) rowind[out++] = rowind[a];
  }
  colptr[n] = out;
  for (int k = 0; k < nt; k++) {
    int a = colptr[tj[k]], b = colptr[tj[k] + 1] - 1;
    while (a < b) {
      int mid = a + (b - a) / 2;
      if (rowind[mid] < ti[k]) a = mid + 1;
      else b = mid;
    }
    map[k] = a;
  }
  *nnz = out;
  return SC_OK;
}

void sc_csc_scatter(int nt, const int *map, const double *tval, int nnz,
                    double *val) {
  for (int k = 0; k < nnz; k++) val[k] = 0;
  for (int k = 0; k < nt; k++) val[map[k]] += tval[k];
}
