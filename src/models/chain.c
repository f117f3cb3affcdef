/* The N-block chain (docs/chain.md): the Burridge-Knopoff chain of N
 * equal blocks, open or closed in a ring, with Coulomb friction (or velocity
 * weakening, whose phases chain_vw.c integrates), as an
 * (N - 1)-dimensional event map from one global stick phase (GSP) to the
 * next.  This file holds the model's table, its setup (the eigenbases of
 * the runs' coupling matrices, by LAPACK's dsyev), the onset of a slip
 * from a GSP and the event loop; one slip phase is chain_phase.c's. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chain_impl.h"

/* LAPACK: eigenvalues and eigenvectors of a symmetric matrix. */
extern void dsyev_(const char *jobz, const char *uplo, const int *n, double *a,
                   const int *lda, double *w, double *work, const int *lwork,
                   int *info);

/* Up to this many blocks the bases of every run shape are computed once
 * at setup (about 2 N^3 / 3 doubles: 1.4 MB at 64 blocks); longer chains
 * compute the bases of each phase's runs as the phase needs them, in
 * N^2 + N doubles, rather than hold ~90 MB at 256 blocks. */
#define CHAIN_EAGER_BLOCKS 64

/* Ranges as bk2's (docs/model.md). */
static const sc_param_info chain_params[CHAIN_NPARAM] = {
    {"alpha", 3, 0, 1e6, 1, 0, "coupling spring / driver spring", NULL, NULL},
    {"phi", 1.25, 1, 1e6, 1, 0,
     "static / kinetic friction ratio (kinetic friction T_i / phi)", NULL,
     "friction=coulomb"},
    {"v", 0.025, 0, 1e3, 0, 0, "driver velocity", "V", NULL},
    {"gamma", 1, 0, 1e6, 0, 0,
     "velocity weakening: K_i = T_i / (1 + gamma |U_i - W|) (friction = "
     "velocity-weakening only)",
     NULL, "friction=velocity-weakening"},
    {"beta2", 1, 0, 1e6, 1, 0, "static threshold of block 2 (block 1's is 1)",
     NULL, NULL},
    {"beta3", 1, 0, 1e6, 1, 0, "static threshold of block 3", NULL,
     "blocks>=3"},
    {"beta4", 1, 0, 1e6, 1, 0, "static threshold of block 4", NULL,
     "blocks>=4"},
    {"beta5", 1, 0, 1e6, 1, 0, "static threshold of block 5 (blocks past 5: betas or a draw)",
     NULL, "blocks>=5"},
};

static const sc_option_info chain_options[] = {
    {"blocks", {"3", NULL}, "number of blocks N (the map has N - 1 components)",
     2, CHAIN_MAXBLOCKS},
    {"topology", {"open", "ring", NULL},
     "free ends, or block N coupled to block 1 (N >= 3)", 0, 0},
    {"driver", {"moving", "frozen", NULL},
     "the driver keeps moving during slips, or stops", 0, 0},
    {"friction", {"coulomb", "velocity-weakening", NULL},
     "kinetic friction: T_i / phi (coulomb), or T_i / (1 + gamma |U_i - W|) "
     "(velocity-weakening, numerical flows)", 0, 0},
    {"flows", {"exact", "numerical", NULL},
     "closed-form flows, or GSL odeiv2 integration", 0, 0},
};

/* --- bases ------------------------------------------------------------ */

/* Fill the m x m coupling matrix of a run of @p shape (column-major). */
static void coupling_matrix(const chain_inst *c, int shape, int m, double *L) {
  memset(L, 0, (size_t)m * m * sizeof(double));
  for (int i = 0; i < m; i++) {
    L[i + (size_t)i * m] = 2;
    if (i + 1 < m) L[i + 1 + (size_t)i * m] = L[i + (size_t)(i + 1) * m] = -1;
  }
  if (shape == SHAPE_END) L[0] = 1;
  if (shape == SHAPE_WHOLE && !c->ring) {
    L[0] -= 1;
    L[(size_t)m * m - 1] -= 1;
  }
  if (shape == SHAPE_WHOLE && c->ring && m > 2) {
    L[m - 1] -= 1; /* blocks N and 1 are neighbours */
    L[(size_t)(m - 1) * m] -= 1;
  }
}

/* The eigenbasis of a run's coupling matrix into Q (m^2) and mu (m). */
static int compute_basis(chain_inst *c, int shape, int m, double *Q,
                         double *mu, sc_msg *msg) {
  coupling_matrix(c, shape, m, Q);
  int info = 0;
  dsyev_("V", "U", &m, Q, &m, mu, c->lwork, &c->nlwork, &info);
  if (info)
    return sc_fail(msg, SC_EINTERNAL,
                   "chain: dsyev failed on a run of %d blocks (info %d)", m,
                   info);
  return SC_OK;
}

int chain_basis_of(chain_inst *c, int shape, int m, size_t *used,
                   chain_basis *out, sc_msg *msg) {
  if (c->eager) {
    *out = c->eager[shape * (c->N + 1) + m];
    return SC_OK;
  }
  double *Q = c->scratch + *used, *mu = Q + (size_t)m * m;
  *used += (size_t)m * m + m;
  *out = (chain_basis){Q, mu};
  return compute_basis(c, shape, m, Q, mu, msg);
}

/* Every shape's basis, at setup: the inner and end paths of 1 .. N - 1
 * blocks and the whole chain. */
static int eager_bases(chain_inst *c, sc_msg *msg) {
  int N = c->N;
  size_t total = 0, used = 0;
  for (int m = 1; m <= N; m++) total += 2 * ((size_t)m * m + m);
  c->table = malloc(total * sizeof(double));
  c->eager = calloc((size_t)CHAIN_NSHAPES * (N + 1), sizeof *c->eager);
  if (!c->table || !c->eager)
    return sc_fail(msg, SC_ENOMEM, "chain: out of memory for %d blocks", N);
  for (int shape = 0; shape < CHAIN_NSHAPES; shape++)
    for (int m = 1; m <= N; m++) {
      if ((shape == SHAPE_WHOLE) != (m == N)) continue;
      double *Q = c->table + used, *mu = Q + (size_t)m * m;
      used += (size_t)m * m + m;
      int st = compute_basis(c, shape, m, Q, mu, msg);
      if (st) return st;
      c->eager[shape * (N + 1) + m] = (chain_basis){Q, mu};
    }
  return SC_OK;
}

/* --- instance --------------------------------------------------------- */

static void chain_release(void *inst) {
  chain_inst *c = inst;
  void **bufs[] = {(void **)&c->table, (void **)&c->eager, (void **)&c->scratch,
                   (void **)&c->lwork, (void **)&c->runs, (void **)&c->slip,
                   (void **)&c->Y, (void **)&c->TY, (void **)&c->gw};
  for (size_t i = 0; i < sizeof bufs / sizeof bufs[0]; i++) {
    free(*bufs[i]);
    *bufs[i] = NULL;
  }
  c->fresh = NULL; /* in slip's block */
  chain_log_free(c);
  c->alloc_N = 0;
  chain_num_release(c);
}

/* The buffers of a chain of c->N blocks (after release of any others). */
static int chain_alloc(chain_inst *c, sc_msg *msg) {
  int N = c->N, lw = -1, info = 0;
  double q = 0, dummy = 0;
  c->P = N - 1 + CHAIN_NPARAM;
  dsyev_("V", "U", &N, &dummy, &N, &dummy, &q, &lw, &info);
  c->nlwork = info == 0 && q >= 3 * N ? (int)q : 3 * N;
  c->lwork = malloc((size_t)c->nlwork * sizeof(double));
  c->scratch = malloc(((size_t)N * N + N) * sizeof(double));
  c->runs = malloc((size_t)N * sizeof *c->runs);
  c->slip = calloc(2 * (size_t)N, sizeof(int));
  /* Y U Y0 U0 lam om P0 P1 A B cs sn mz mzp NY NU Ad: 17 N */
  c->Y = malloc(17 * (size_t)N * sizeof(double));
  /* every guard of a phase at once (chain_phase.c, search_all): the
   * re-sticks of a run of m blocks have m^2 terms, the thresholds at most
   * 2N in all */
  size_t gcap = (size_t)N * N + 2 * (size_t)N;
  c->gw = malloc(3 * gcap * sizeof(double));
  c->TY = malloc(2 * (size_t)c->P * N * sizeof(double));
  if (!c->lwork || !c->scratch || !c->runs || !c->slip || !c->Y || !c->TY ||
      !c->gw)
    return sc_fail(msg, SC_ENOMEM, "chain: out of memory for %d blocks", N);
  c->fresh = c->slip + N;
  double **v[] = {&c->U,  &c->Y0, &c->U0, &c->lam, &c->om, &c->P0,
                  &c->P1, &c->A,  &c->B,  &c->cs,  &c->sn, &c->mz,
                  &c->mzp, &c->NY, &c->NU, &c->Ad};
  for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) *v[i] = c->Y + (i + 1) * N;
  c->ga = c->gw + gcap;
  c->gb = c->ga + gcap;
  c->TU = c->TY + (size_t)c->P * N;
  c->alloc_N = N;
  return N <= CHAIN_EAGER_BLOCKS ? eager_bases(c, msg) : SC_OK;
}

static int chain_setup(void *inst, const double *p, const int *opt,
                       const sc_accuracy *acc, sc_msg *msg) {
  chain_inst *c = inst;
  int N = opt[O_BLOCKS], ring = opt[O_TOPOLOGY] == 1;
  if (ring && N < 3)
    return sc_fail(msg, SC_EINVAL,
                   "chain: topology = ring needs blocks >= 3 (blocks = %d)", N);
  if (opt[O_FRICTION] == 1 && opt[O_DRIVER] == 1)
    return sc_fail(msg, SC_EINVAL,
                   "chain: friction = velocity-weakening with driver = frozen "
                   "is ill posed (a slip cannot start): use driver = moving");
  if ((opt[O_FLOWS] == 1 || opt[O_FRICTION] == 1) &&
      acc->precision == SC_PRECISION_QUAD)
    return sc_fail(msg, SC_EINVAL,
                   "chain: precision = quad needs flows = exact (the "
                   "numerical flows are double only)");
  int rebuild = N != c->alloc_N || ring != c->ring;
  c->ring = ring;
  c->N = N;
  c->frozen = opt[O_DRIVER] == 1;
  c->vw = opt[O_FRICTION] == 1;
  c->numerical = opt[O_FLOWS] == 1 || c->vw;
  c->alpha = p[P_ALPHA], c->phi = p[P_PHI], c->v = p[P_V];
  c->gamma = p[P_GAMMA];
  c->Vs = c->frozen ? 0 : c->v;
  c->acc = *acc;
  for (int i = 0; i < N; i++) {
    /* blocks past 5: the data's thresholds (betas or the draw), else 1 */
    c->T[i] = i == 0                    ? 1
              : i < CHAIN_PARAM_BLOCKS ? p[P_BETA2 + i - 1]
              : c->data.random || c->data.nbetas ? c->data.T[i]
                                                 : 1;
    c->K[i] = c->T[i] / c->phi;
  }
  int st = SC_OK;
  if (rebuild) {
    chain_release(c);
    st = chain_alloc(c, msg);
    if (st) chain_release(c);
  }
  if (!st && c->numerical) st = chain_num_setup(c, msg);
  if (!st && !c->numerical) chain_num_release(c);
  return st;
}

static double chain_precision(const void *inst) {
  const chain_inst *c = inst;
  return c->numerical ? chain_num_precision(c) : 0;
}

static size_t chain_dim_of(const void *inst) {
  const chain_inst *c = inst;
  return c->N > 1 ? (size_t)c->N - 1 : 1;
}

/* --- the onset of a slip from a GSP ----------------------------------- */

/* The state at the end of the GSP of differences d: every block at Vs,
 * the block with the smallest gap T_j - S_j at its threshold, and with
 * it every block whose gap equals it (docs/chain.md, "Events"); the
 * positions are placed from the last block of such a tie (bk2 places
 * them from block 2 at d*: f is not differentiable there, and its
 * derivatives are then the same one-sided ones as bk2's); with
 * deriv, the sensitivities of that state.  Positions relative to block
 * 1's during the GSP: D_i = d_1 + ... + d_(i-1), S_i = D_i + alpha c_i,
 * c_i = sum over neighbours n of (D_i - D_n) (block 1's own position
 * drops out of every gap difference). */
static void onset(chain_inst *c, const double *d, int deriv) {
  int N = c->N, j = 0;
  double *D = c->Y0, *cc = c->U0, al = c->alpha; /* scratch until a phase */
  D[0] = 0;
  for (int i = 1; i < N; i++) D[i] = D[i - 1] + d[i - 1];
  double gmin = HUGE_VAL;
  for (int i = 0; i < N; i++) {
    int nb[2], nn = chain_neighbours(c, i, nb);
    cc[i] = 0;
    for (int s = 0; s < nn; s++) cc[i] += D[i] - D[nb[s]];
    double gap = c->T[i] - (D[i] + al * cc[i]);
    if (gap <= gmin) gmin = gap, j = i; /* the last of a tie, as bk2 */
  }
  for (int i = 0; i < N; i++) {
    c->slip[i] = c->fresh[i] =
        c->T[i] - (D[i] + al * cc[i]) == gmin; /* ties start together */
    c->U[i] = c->Vs;
  }
  if (c->bx) { /* forced starters, codes, switching borders */
    double *gap = c->Y; /* scratch until placed below */
    for (int i = 0; i < N; i++) gap[i] = c->T[i] - (D[i] + al * cc[i]);
    j = chain_bx_onset(c, gap, j);
  }
  /* block j at its threshold: S_j = Y_j + alpha c_j = T_j */
  double yj = c->T[j] - al * cc[j];
  for (int i = 0; i < N; i++) c->Y[i] = yj + (D[i] - D[j]);
  c->onset_block = j;
  if (!deriv) return;
  for (int col = 0; col < c->P; col++) {
    double *ty = c->TY + (size_t)col * N, *tu = c->TU + (size_t)col * N;
    int q = col - (N - 1);
    /* dD_i: 1 for i > col along d_(col+1) */
    double dcj = 0, dyj;
    int nb[2], nn = chain_neighbours(c, j, nb);
    for (int s = 0; s < nn; s++)
      dcj += (q < 0) * ((j > col) - (nb[s] > col));
    dyj = (j >= 1 && j < CHAIN_PARAM_BLOCKS && q == P_BETA2 + j - 1) -
          (q == P_ALPHA) * cc[j] - al * dcj;
    for (int i = 0; i < N; i++) {
      ty[i] = dyj + (q < 0) * ((i > col) - (j > col));
      tu[i] = !c->frozen && q == P_V;
    }
  }
}

/* --- itineraries ------------------------------------------------------ */

/* Append the slipping set's name: its blocks' numbers, joined by '.' in
 * chains of 10 blocks or more ("1.2.10"); phases are joined by '-'. */
static void itin_add(const chain_inst *c, char *itin) {
  char name[4 * CHAIN_MAXBLOCKS + 2];
  size_t k = 0;
  if (itin[0]) name[k++] = '-';
  int first = 1;
  for (int i = 0; i < c->N; i++)
    if (c->slip[i]) {
      k += (size_t)snprintf(name + k, sizeof name - k, "%s%d",
                            c->N >= 10 && !first ? "." : "", i + 1);
      first = 0;
    }
  name[k] = '\0';
  size_t n = strlen(itin);
  if (n >= 3 && strcmp(itin + n - 3, "...") == 0) return; /* already cut */
  if (n + k + 4 <= SC_ITIN_LEN) memcpy(itin + n, name, k + 1);
  else strcpy(itin + n, "..."); /* room kept for it by the test above */
}

/* --- the map ---------------------------------------------------------- */

/* f and its derivatives from the state at a GSP. */
static void write_out(const chain_inst *c, unsigned flags, sc_mapn_value *out) {
  int N = c->N, n = N - 1;
  for (int i = 0; i < n; i++) out->f[i] = c->Y[i + 1] - c->Y[i];
  if (flags & SC_EVAL_DERIV)
    for (int col = 0; col < c->P; col++) {
      const double *ty = c->TY + (size_t)col * N;
      for (int i = 0; i < n; i++) {
        double v = ty[i + 1] - ty[i];
        if (col < n) out->J[i * n + col] = v;
        else out->fp[(size_t)(col - n) * n + i] = v;
      }
    }
}

int chain_eval_n(void *inst, const double *d, unsigned flags,
                 sc_mapn_value *out, sc_msg *msg) {
  chain_inst *c = inst;
  int N = c->N, deriv = (flags & (SC_EVAL_DERIV | SC_EVAL_DERIV2)) != 0;
  if (c->bx) deriv |= chain_bx_deriv(c);
  int jet = (flags & SC_EVAL_DERIV2) != 0; /* record the phases */
  chain_event ev[CHAIN_MAXBLOCKS];
  onset(c, d, deriv);
  if (jet) {
    int st = chain_log_start(c, msg);
    if (st) return st;
  }
  if (c->rec) chain_rec_begin(c);
  out->nphases = 0;
  out->itinerary[0] = '\0';
  for (int ph = 0; ph < c->acc.max_events; ph++) {
    if (flags & SC_EVAL_ITINERARY) itin_add(c, out->itinerary);
    int nev = 0, st = c->numerical ? chain_phase_num(c, deriv, ev, &nev, msg)
                                   : chain_phase(c, deriv, ev, &nev, msg);
    if (st) return st;
    if (jet) chain_log_phase(c, ev, nev);
    if (c->rec) chain_rec_phase(c, ev[0].t);
    out->nphases++;
    for (int i = 0; i < N; i++) c->fresh[i] = 0;
    /* re-sticks first, together */
    int left = 0;
    for (int e = 0; e < nev; e++)
      if (ev[e].kind == CHAIN_RESTICK) {
        int b = ev[e].block;
        c->slip[b] = 0;
        c->U[b] = c->Vs;
        if (deriv)
          for (int col = 0; col < c->P; col++)
            c->TU[(size_t)col * N + b] = !c->frozen && col - (N - 1) == P_V;
      }
    for (int i = 0; i < N; i++) left += c->slip[i];
    if (!left) {
      if (c->rec) chain_rec_end(c);
      write_out(c, flags, out);
      return jet ? chain_jet_fill(c, d, out, msg) : SC_OK;
    }
    /* then the thresholds reached at that instant, together */
    for (int e = 0; e < nev; e++)
      if (ev[e].kind == CHAIN_THRESHOLD)
        c->slip[ev[e].block] = c->fresh[ev[e].block] = 1;
  }
  return sc_fail(msg, SC_EUNDEF,
                 "chain: no global stick phase within max-events = %d slip "
                 "phases (a slip cycle?)",
                 c->acc.max_events);
}

const sc_model_type sc_model_chain = {
    .name = "chain",
    .doc = "chain of N Burridge-Knopoff blocks, open or ring (docs/chain.md)",
    .state_name = "d",
    .nparam = CHAIN_NPARAM,
    .params = chain_params,
    .noption = sizeof chain_options / sizeof chain_options[0],
    .options = chain_options,
    .inst_size = sizeof(chain_inst),
    .setup = chain_setup,
    .release = chain_release,
    .eval_n = chain_eval_n,
    .eval_n_ex = chain_eval_n_ex,
    .dim_of = chain_dim_of,
    .precision = chain_precision,
    .ndata = CHAIN_NDATA,
    .data = chain_data_info,
    .set_data = chain_set_data,
    .data_params = chain_data_params,
    .eval_event = chain_eval_event,
    .trajectory_n = chain_trajectory,
};
