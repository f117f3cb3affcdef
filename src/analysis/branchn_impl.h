/* Branches of n-dimensional maps (branchn.h): what branchn.c (the run,
 * its segments and storage) and branchn_special.c (the special points
 * and the switching) share. */
#ifndef SC_BRANCHN_IMPL_H
#define SC_BRANCHN_IMPL_H

#include "slipcont/branchn.h"
#include "slipcont/continuation.h"
#include "slipcont/linalg.h"
#include "slipcont/mapn_system.h"
#include "slipcont/normal_form.h"

#define BN_MAXN SC_MAPN_MAXDIM
#define BN_NOTE 192

typedef struct {
  int branch, period, stable;
  double p, mult;
  double x[BN_MAXN], re[BN_MAXN], im[BN_MAXN];
} bn_point;

typedef struct {
  sc_branchn_label label;
  int branch, period, iterations;
  double p, coef, theta, kappa, residual, error;
  double x[BN_MAXN], re[BN_MAXN], im[BN_MAXN];
  sc_location_method method;
  char note[BN_NOTE];
  char border[SC_BORDER_NAME]; /* a border point's border, else "" */
} bn_special;

/* A segment to continue: from u (x, p) directly (dir: the sign of dp/ds),
 * or, with displaced set, from the point at distance h from u along dvec
 * (a switch), oriented away from u. */
typedef struct {
  int period, dir, displaced;
  int doubled; /* a flip's doubled branch: must not have period m / 2 */
  double u[BN_MAXN + 1], dvec[BN_MAXN + 1], h;
  char why[BN_NOTE]; /* where it comes from, for the EP notes */
  /* a hand-over at a border: 1 + the index in codes_pool of its period
   * codes; 0: the natural codes of the start (branchn_border.c) */
  size_t handover;
} bn_job;

/* g = f^m of the map, for the defining systems. */
typedef struct {
  sc_map *m;
  sc_mapn_value *v;
  int period;
  size_t np;
  const sc_itin_code *force; /* the segment's codes, NULL: smooth map */
} bn_jet_ctx;

struct sc_branchn {
  sc_map *m;
  sc_branchn_spec sp;
  size_t n, np, param;
  double x0[BN_MAXN], psave[SC_MAXPARAM];
  sc_accuracy acc;
  sc_cont_settings set;
  sc_mapn_value *v2, *v1;
  bn_jet_ctx jc;
  bn_point *pts;
  size_t npts, ptcap;
  bn_special *sps;
  size_t nsp, spcap;
  bn_job *jobs;
  size_t njobs, jobcap, jobnext;
  int nbranches;
  size_t ndup;
  /* the current segment's multipliers: m Jacobians along the orbit */
  double *Jk;
  const double **Aptr;
  sc_product_eigs_work *pw;
  int pw_period;
  /* borders of the n-dimensional map (branchn_border.c): the segment's
   * codes (max_period entries), the borders at the last point, at the
   * new one and in a Newton step, the hand-over codes of the jobs */
  int borders;
  sc_itin_code *codes, *codes2;
  sc_bordern_list *bl_prev, *bl_cur, *bl_tmp;
  sc_itin_code *codes_pool;
  size_t npool, poolcap;
};

int sc_bn_jet(const double *x, const double *p, int order, sc_mapn_jet *jet,
              void *user);
int sc_bn_multipliers(sc_branchn *b, int period, const double *x, double p,
                      double *re, double *im, sc_msg *msg);
int sc_bn_push_job(sc_branchn *b, const bn_job *j);
bn_special *sc_bn_new_special(sc_branchn *b);
int sc_bn_make_system(sc_branchn *b, sc_mapn_kind kind,
                      sc_mapn_system **out, sc_msg *msg);
int sc_bn_special(sc_branchn *b, int branch, int period, const double *u,
                  const double *t, int test, sc_msg *msg);
int sc_bn_displaced_start(sc_branchn *b, const bn_job *j, double *u,
                          int *dir, sc_msg *msg);
int sc_bn_gauss(size_t N, double *A, double *b);
int sc_bn_grow(void **arr, size_t *cap, size_t need, size_t size);
/* branchn_border.c */
int sc_bn_border_alloc(sc_branchn *b, sc_msg *msg);
void sc_bn_border_free(sc_branchn *b);
int sc_bn_segment_codes(sc_branchn *b, const bn_job *j, sc_msg *msg);
int sc_bn_border_start(sc_branchn *b, int period, const double *u,
                       sc_msg *msg);
int sc_bn_border_step(sc_branchn *b, int branch, int period,
                      const double *uprev, const double *u, int *crossed,
                      double *ub, sc_msg *msg);

#endif
