/* Maps in n dimensions: evaluation of one iterate at a state vector, and
 * the iterates f^k with their first, second and third derivatives by the
 * chain rule (docs/maps.md, "Derivatives of iterates"). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "map_impl.h"

size_t sc_map_dim(const sc_map *m) { return m->dim; }

const char *sc_map_state_component(const sc_map *m, size_t i, char *buf,
                                   size_t len) {
  size_t n = sc_map_dim(m);
  if (n == 1) snprintf(buf, len, "%s", m->type->state_name);
  else if (m->type->state_names) snprintf(buf, len, "%s", m->type->state_names[i]);
  else snprintf(buf, len, "%s%zu", m->type->state_name, i + 1);
  return buf;
}

/* Doubles of storage for n components, np parameters and @p flags. */
static size_t value_doubles(size_t n, size_t np, unsigned flags) {
  size_t k = n;
  if (flags & (SC_EVAL_DERIV | SC_EVAL_DERIV2)) k += n * n + np * n;
  if (flags & SC_EVAL_DERIV2) k += n * n * n + np * n * n + n * n * n * n;
  return k;
}

/* One block: the structure, then its arrays. */
static sc_mapn_value *value_new(size_t n, size_t np, unsigned flags) {
  size_t nd = value_doubles(n, np, flags);
  sc_mapn_value *v = calloc(1, sizeof *v + nd * sizeof(double));
  if (!v) return NULL;
  double *a = (double *)(v + 1);
  v->n = n;
  v->np = np;
  v->f = a;
  a += n;
  if (flags & (SC_EVAL_DERIV | SC_EVAL_DERIV2)) {
    v->J = a;
    a += n * n;
    v->fp = a;
    a += np * n;
  }
  if (flags & SC_EVAL_DERIV2) {
    v->H = a;
    a += n * n * n;
    v->Jp = a;
    a += np * n * n;
    v->T = a;
  }
  return v;
}

int sc_mapn_value_alloc(const sc_map *m, unsigned flags, sc_mapn_value **out,
                        sc_msg *msg) {
  size_t n = sc_map_dim(m);
  *out = NULL;
  if ((flags & SC_EVAL_DERIV2) && n > SC_DIM_TENSOR)
    return sc_fail(msg, SC_EINVAL,
                   "model %s: second and third derivatives are kept up to "
                   "dimension %d (it has %zu state components)",
                   m->type->name, SC_DIM_TENSOR, n);
  *out = value_new(n, m->type->nparam, flags);
  return *out ? SC_OK : sc_fail(msg, SC_ENOMEM, "out of memory");
}

void sc_mapn_value_free(sc_mapn_value *v) { free(v); }

/* Scratch of the chain rule: two n^4 arrays (third derivatives), one n^3
 * (second derivatives contracted with J) and a value for the result. */
int sc_mapn_work_alloc(sc_map *m) {
  size_t n = sc_map_dim(m), np = m->type->nparam;
  unsigned flags = n <= SC_DIM_TENSOR ? SC_EVAL_DERIV2 : SC_EVAL_DERIV;
  m->step = value_new(n, np, flags);
  size_t ns = n <= SC_DIM_TENSOR ? 2 * n * n * n * n + n * n * n : n * n;
  ns += value_doubles(n, np, flags);
  m->scratch = malloc(ns * sizeof(double));
  return m->step && m->scratch ? 0 : -1;
}

void sc_mapn_work_free(sc_map *m) {
  free(m->step);
  free(m->scratch);
  sc_bordern_list_free(m->blist);
  m->step = NULL;
  m->scratch = NULL;
  m->blist = NULL;
}

/* Storage check: the arrays @p flags needs are there, and the sizes are
 * @p m's. */
static int check_storage(const sc_map *m, unsigned flags,
                         const sc_mapn_value *v, sc_msg *msg) {
  int ok = v && v->n == sc_map_dim(m) && v->np == m->type->nparam && v->f;
  if (flags & (SC_EVAL_DERIV | SC_EVAL_DERIV2)) ok = ok && v->J && v->fp;
  if (flags & SC_EVAL_DERIV2) ok = ok && v->H && v->Jp && v->T;
  return ok ? SC_OK
            : sc_fail(msg, SC_EINVAL,
                      "sc_map_eval_n: storage not sized for model %s and the "
                      "derivatives asked for (use sc_mapn_value_alloc())",
                      m->type->name);
}

/* A one-dimensional model's iterate as a 1 x 1 map. */
static int eval_1d(sc_map *m, double x, unsigned flags, sc_mapn_value *out,
                   sc_msg *msg) {
  sc_map_value v;
  int st = sc_map_eval(m, x, flags, &v, msg);
  if (st) return st;
  size_t np = m->type->nparam;
  out->f[0] = v.f;
  if (flags & (SC_EVAL_DERIV | SC_EVAL_DERIV2)) {
    out->J[0] = v.dfdd;
    for (size_t q = 0; q < np; q++) out->fp[q] = v.dfdp[q];
  }
  if (flags & SC_EVAL_DERIV2) {
    out->H[0] = v.d2fdd2;
    out->T[0] = v.d3fdd3;
    for (size_t q = 0; q < np; q++) out->Jp[q] = v.d2fddp[q];
  }
  out->nphases = v.nphases;
  if (flags & SC_EVAL_ITINERARY)
    memcpy(out->itinerary, v.itinerary, SC_ITIN_LEN);
  return SC_OK;
}

int sc_map_has_borders_n(const sc_map *m) {
  return m->type->eval_n && m->type->eval_n_ex != NULL;
}

int sc_bordern_list_alloc(const sc_map *m, size_t cap, sc_bordern_list **out,
                          sc_msg *msg) {
  *out = NULL;
  if (cap == 0)
    return sc_fail(msg, SC_EINVAL, "sc_bordern_list_alloc: cap = 0 (valid: "
                                   ">= 1)");
  size_t n = sc_map_dim(m);
  sc_bordern_list *l = calloc(1, sizeof *l);
  if (l) {
    l->b = calloc(cap, sizeof *l->b);
    l->grad = calloc(cap * n, sizeof *l->grad);
  }
  if (!l || !l->b || !l->grad) {
    sc_bordern_list_free(l);
    return sc_fail(msg, SC_ENOMEM, "sc_bordern_list_alloc: out of memory");
  }
  l->cap = cap;
  l->dim = n;
  for (size_t i = 0; i < cap; i++) l->b[i].dx = l->grad + i * n;
  *out = l;
  return SC_OK;
}

void sc_bordern_list_free(sc_bordern_list *l) {
  if (!l) return;
  free(l->b);
  free(l->grad);
  free(l);
}

int sc_map_eval_n(sc_map *m, const double *x, unsigned flags,
                  sc_mapn_value *out, sc_msg *msg) {
  return sc_map_eval_n_ex(m, x, flags, NULL, NULL, NULL, out, msg);
}

int sc_map_eval_n_ex(sc_map *m, const double *x, unsigned flags,
                     const sc_itin_code *force, sc_itin_code *code,
                     sc_bordern_list *borders, sc_mapn_value *out,
                     sc_msg *msg) {
  int st = check_storage(m, flags, out, msg);
  if (st) return st;
  size_t n = out->n;
  char name[32];
  for (size_t i = 0; i < n; i++)
    if (!isfinite(x[i]))
      return sc_fail(msg, SC_EINVAL, "%s = %g is not finite",
                     sc_map_state_component(m, i, name, sizeof name), x[i]);
  if (flags & SC_EVAL_DERIV2) flags |= SC_EVAL_DERIV;
  out->nphases = 0;
  out->itinerary[0] = '\0';
  if (code) code->n = 0;
  if (!m->type->eval_n) {
    if (force || borders)
      return sc_fail(msg, SC_EINVAL,
                     "sc_map_eval_n_ex: model %s is one-dimensional: its "
                     "borders are sc_map_eval_ex()'s", m->type->name);
    return eval_1d(m, x[0], flags, out, msg);
  }
  if (borders && borders->dim != n)
    return sc_fail(msg, SC_EINVAL,
                   "sc_map_eval_n_ex: border list of dimension %zu for model "
                   "%s of %zu components", borders->dim, m->type->name, n);
  m->nevals++;
  if (m->type->eval_n_ex && (force || code || borders))
    st = m->type->eval_n_ex(m->inst, x, flags, force, code, borders, out,
                            msg);
  else
    st = m->type->eval_n(m->inst, x, flags, out, msg);
  if (st) return st;
  for (size_t i = 0; i < n; i++)
    if (!isfinite(out->f[i]))
      return sc_fail(msg, SC_ENONFINITE, "f is not finite at the state given");
  return SC_OK;
}

/* Copy the arrays of @p src that @p flags names into @p dst (same n). */
static void copy_value(sc_mapn_value *dst, const sc_mapn_value *src,
                       unsigned flags) {
  size_t n = src->n, np = src->np;
  memcpy(dst->f, src->f, n * sizeof(double));
  if (flags & SC_EVAL_DERIV) {
    memcpy(dst->J, src->J, n * n * sizeof(double));
    memcpy(dst->fp, src->fp, np * n * sizeof(double));
  }
  if (flags & SC_EVAL_DERIV2) {
    memcpy(dst->H, src->H, n * n * n * sizeof(double));
    memcpy(dst->Jp, src->Jp, np * n * n * sizeof(double));
    memcpy(dst->T, src->T, n * n * n * n * sizeof(double));
  }
}

/* First derivatives of F o G into @p R, with A = F.J at G's value and
 * B = G.J:  J = A B,  fp_q = A G.fp_q + F.fp_q. */
static void chain1(sc_mapn_value *R, const sc_mapn_value *F,
                   const sc_mapn_value *G) {
  size_t n = F->n, np = F->np;
  const double *A = F->J, *B = G->J;
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++) {
      double s = 0;
      for (size_t a = 0; a < n; a++) s += A[i * n + a] * B[a * n + j];
      R->J[i * n + j] = s;
    }
  for (size_t q = 0; q < np; q++)
    for (size_t i = 0; i < n; i++) {
      double s = F->fp[q * n + i];
      for (size_t a = 0; a < n; a++) s += A[i * n + a] * G->fp[q * n + a];
      R->fp[q * n + i] = s;
    }
}

/* Second derivatives of F o G (M[i][a][l] = sum_b F.H[i][a][b] B[b][l],
 * precomputed in @p M):
 *   H[i][j][k]  = sum_a A[i][a] G.H[a][j][k] + sum_a M[i][a][k] B[a][j],
 *   Jp[q][i][j] = sum_a A[i][a] G.Jp[q][a][j]
 *               + sum_a,b F.H[i][a][b] B[a][j] G.fp[q][b]
 *               + sum_a F.Jp[q][i][a] B[a][j]. */
static void chain2(sc_mapn_value *R, const sc_mapn_value *F,
                   const sc_mapn_value *G, const double *M) {
  size_t n = F->n, np = F->np;
  const double *A = F->J, *B = G->J;
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++)
      for (size_t k = 0; k < n; k++) {
        double s = 0;
        for (size_t a = 0; a < n; a++)
          s += A[i * n + a] * G->H[(a * n + j) * n + k] +
               M[(i * n + a) * n + k] * B[a * n + j];
        R->H[(i * n + j) * n + k] = s;
      }
  for (size_t q = 0; q < np; q++)
    for (size_t i = 0; i < n; i++)
      for (size_t j = 0; j < n; j++) {
        double s = 0;
        for (size_t a = 0; a < n; a++) {
          double hb = 0; /* sum_b F.H[i][a][b] G.fp[q][b] */
          for (size_t b = 0; b < n; b++)
            hb += F->H[(i * n + a) * n + b] * G->fp[q * n + b];
          s += A[i * n + a] * G->Jp[(q * n + a) * n + j] +
               (hb + F->Jp[(q * n + i) * n + a]) * B[a * n + j];
        }
        R->Jp[(q * n + i) * n + j] = s;
      }
}

/* Third derivatives of F o G:
 *   T[i][j][k][l] = sum_a A[i][a] G.T[a][j][k][l]
 *     + sum_a (M[i][a][l] G.H[a][j][k] + M[i][a][k] G.H[a][j][l]
 *              + M[i][a][j] G.H[a][k][l])
 *     + sum_a,b,c F.T[i][a][b][c] B[a][j] B[b][k] B[c][l],
 * the last contracted one index at a time through W1, W2 (n^5 each). */
static void chain3(sc_mapn_value *R, const sc_mapn_value *F,
                   const sc_mapn_value *G, const double *M, double *W1,
                   double *W2) {
  size_t n = F->n, n2 = n * n, n3 = n2 * n;
  const double *A = F->J, *B = G->J;
  /* W1[i][a][b][l] = sum_c F.T[i][a][b][c] B[c][l] */
  for (size_t iab = 0; iab < n3; iab++)
    for (size_t l = 0; l < n; l++) {
      double s = 0;
      for (size_t c = 0; c < n; c++) s += F->T[iab * n + c] * B[c * n + l];
      W1[iab * n + l] = s;
    }
  /* W2[i][a][k][l] = sum_b W1[i][a][b][l] B[b][k] */
  for (size_t ia = 0; ia < n2; ia++)
    for (size_t k = 0; k < n; k++)
      for (size_t l = 0; l < n; l++) {
        double s = 0;
        for (size_t b = 0; b < n; b++)
          s += W1[(ia * n + b) * n + l] * B[b * n + k];
        W2[(ia * n + k) * n + l] = s;
      }
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++)
      for (size_t k = 0; k < n; k++)
        for (size_t l = 0; l < n; l++) {
          double s = 0;
          for (size_t a = 0; a < n; a++) {
            size_t ia = i * n + a;
            s += A[ia] * G->T[((a * n + j) * n + k) * n + l] +
                 M[ia * n + l] * G->H[(a * n + j) * n + k] +
                 M[ia * n + k] * G->H[(a * n + j) * n + l] +
                 M[ia * n + j] * G->H[(a * n + k) * n + l] +
                 W2[(ia * n + k) * n + l] * B[a * n + j];
          }
          R->T[((i * n + j) * n + k) * n + l] = s;
        }
}

/* Compose: @p G (the iterates so far) becomes F o G, F the step's value
 * at G's end point; @p R is storage of G's size. */
static void compose(sc_map *m, sc_mapn_value *G, const sc_mapn_value *F,
                    sc_mapn_value *R, unsigned flags) {
  size_t n = F->n;
  if (flags & SC_EVAL_DERIV) chain1(R, F, G);
  if (flags & SC_EVAL_DERIV2) {
    double *M = m->scratch, *W1 = M + n * n * n, *W2 = W1 + n * n * n * n;
    for (size_t ia = 0; ia < n * n; ia++)
      for (size_t l = 0; l < n; l++) {
        double s = 0;
        for (size_t b = 0; b < n; b++) s += F->H[ia * n + b] * G->J[b * n + l];
        M[ia * n + l] = s;
      }
    chain2(R, F, G, M);
    chain3(R, F, G, M, W1, W2);
  }
  memcpy(R->f, F->f, n * sizeof(double));
  copy_value(G, R, flags);
}

/* The value in the scratch after the chain rule's arrays, sized as the
 * step (R of compose()). */
static sc_mapn_value result_view(sc_map *m, unsigned flags) {
  size_t n = sc_map_dim(m), np = m->type->nparam;
  sc_mapn_value r = {.n = n, .np = np};
  double *a = m->scratch + (n <= SC_DIM_TENSOR ? 2 * n * n * n * n + n * n * n
                                               : n * n);
  r.f = a;
  a += n;
  if (flags & SC_EVAL_DERIV) {
    r.J = a;
    a += n * n;
    r.fp = a;
    a += np * n;
  }
  if (flags & SC_EVAL_DERIV2) {
    r.H = a;
    a += n * n * n;
    r.Jp = a;
    a += np * n * n;
    r.T = a;
  }
  return r;
}

/* The borders of iterate @p it appended from @p b0, functions of x_it =
 * G(x_0, p) (G in @p out: f^it with its J and f_p), chained to x_0:
 * dm/dx_0 = m_x G.J, dm/dp += m_x G.fp.  @p w: n doubles of scratch. */
static void chain_borders(sc_bordern_list *bl, size_t b0, int it,
                          const sc_mapn_value *G, double *w) {
  size_t n = G->n, np = G->np;
  for (size_t i = b0; i < bl->n && i < bl->cap; i++) {
    sc_bordern *bd = &bl->b[i];
    bd->iterate = it;
    if (it == 0) continue;
    for (size_t q = 0; q < np; q++) {
      double s = 0;
      for (size_t a = 0; a < n; a++) s += bd->dx[a] * G->fp[q * n + a];
      bd->dp[q] += s;
    }
    for (size_t j = 0; j < n; j++) {
      double s = 0;
      for (size_t a = 0; a < n; a++) s += bd->dx[a] * G->J[a * n + j];
      w[j] = s;
    }
    memcpy(bd->dx, w, n * sizeof *w);
  }
}

int sc_map_iterate_n(sc_map *m, const double *x, int k, unsigned flags,
                     sc_mapn_value *out, sc_msg *msg) {
  return sc_map_iterate_n_ex(m, x, k, flags, NULL, NULL, NULL, out, msg);
}

int sc_map_iterate_n_ex(sc_map *m, const double *x, int k, unsigned flags,
                        const sc_itin_code *force, sc_itin_code *codes,
                        sc_bordern_list *borders, sc_mapn_value *out,
                        sc_msg *msg) {
  if (k < 1)
    return sc_fail(msg, SC_EINVAL, "sc_map_iterate_n: k = %d (valid: k >= 1)",
                   k);
  if (flags & SC_EVAL_DERIV2) flags |= SC_EVAL_DERIV;
  if (borders) flags |= SC_EVAL_DERIV;
  size_t b0 = borders ? borders->n : 0;
  int st = sc_map_eval_n_ex(m, x, flags, force, codes, borders, out, msg);
  if (st) return st;
  if (borders) chain_borders(borders, b0, 0, out, m->scratch);
  sc_mapn_value *F = m->step;
  sc_mapn_value R = result_view(m, flags);
  int nph = out->nphases;
  for (int it = 1; it < k; it++) {
    b0 = borders ? borders->n : 0;
    st = sc_map_eval_n_ex(m, out->f, flags, force ? &force[it] : NULL,
                          codes ? &codes[it] : NULL, borders, F, msg);
    if (st) {
      if (msg) {
        char tail[SC_MSG_LEN];
        snprintf(tail, sizeof tail, "%s", msg->text);
        sc_fail(msg, st, "iterate %d of %d: %s", it + 1, k, tail);
      }
      return st;
    }
    /* the scratch is free between compositions */
    if (borders) chain_borders(borders, b0, it, out, m->scratch);
    compose(m, out, F, &R, flags);
    nph += F->nphases;
    if (flags & SC_EVAL_ITINERARY) {
      sc_map_itin_append(out->itinerary, "|");
      sc_map_itin_append(out->itinerary, F->itinerary);
    }
  }
  out->nphases = nph;
  return SC_OK;
}
