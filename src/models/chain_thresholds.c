/* Thresholds per block of the chain (docs/chain.md, "Thresholds per
 * block"): the model's data keys `thresholds`, `betas`, `threshold-seed`
 * and `threshold-range`.  Block 1's threshold is 1 (the unit of force);
 * blocks 2..5's are the parameters beta2..beta5, which take the data's
 * values unless set explicitly (models.h, data_params); blocks 6..N's
 * come from the data alone. */
#define _POSIX_C_SOURCE 200809L /* strtok_r */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chain_impl.h"

/* Largest threshold, as the parameters beta2..beta5 (chain.c's table). */
#define CHAIN_T_MAX 1e6
/* Default draw: seed 1, uniform on [0.8, 1.2). */
#define CHAIN_SEED_DEFAULT 1ULL
#define CHAIN_RANGE_LO 0.8
#define CHAIN_RANGE_HI 1.2

const sc_data_info chain_data_info[CHAIN_NDATA] = {
    {"thresholds", "given",
     "given: block 1's is 1, blocks 2..5's beta2..beta5, the rest from betas "
     "(else 1); random: blocks 2..N drawn uniformly from threshold-range with "
     "threshold-seed (splitmix64)"},
    {"betas", "",
     "thresholds of blocks 2..N, N - 1 numbers > 0 (x*k repeats x k times); "
     "beta2..beta5 set explicitly override blocks 2..5"},
    {"threshold-seed", "",
     "thresholds = random: the draw's seed, an integer in [0, 2^53] "
     "(default 1)"},
    {"threshold-range", "",
     "thresholds = random: lo hi, 0 < lo <= hi (default 0.8 1.2)"},
};

/* splitmix64: a 64-bit generator with a fixed, platform-independent
 * sequence (Steele, Lea and Flood's SplittableRandom), enough for a
 * reproducible draw of at most 255 numbers. */
static unsigned long long splitmix64(unsigned long long *x) {
  unsigned long long z = (*x += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

/* The draw: block i + 1's threshold lo + (hi - lo) u_i, u_i in [0, 1)
 * the i-th number of the sequence from the seed (53 bits), for blocks 2
 * to CHAIN_MAXBLOCKS, so that block i's threshold does not depend on N. */
static void draw(chain_data *D) {
  unsigned long long x = D->seed;
  D->T[0] = 1;
  for (int i = 1; i < CHAIN_MAXBLOCKS; i++) {
    double u = (double)(splitmix64(&x) >> 11) * 0x1.0p-53;
    D->T[i] = D->lo + (D->hi - D->lo) * u;
  }
}

/* One threshold word: "x" or "x*k" (x repeated k times). */
static int threshold_word(const char *w, int pos, double *x, long *k,
                          sc_msg *msg) {
  char num[64];
  const char *star = strchr(w, '*');
  size_t n = star ? (size_t)(star - w) : strlen(w);
  *k = 1;
  if (n >= sizeof num) n = sizeof num - 1;
  memcpy(num, w, n);
  num[n] = '\0';
  if (star && sc_parse_long(star + 1, 1, CHAIN_MAXBLOCKS, k))
    return sc_fail(msg, SC_EINVAL,
                   "betas: '%s' (word %d): the count after '*' must be an "
                   "integer in [1, %d]",
                   w, pos, CHAIN_MAXBLOCKS);
  if (sc_parse_double(num, x) || !isfinite(*x))
    return sc_fail(msg, SC_EINVAL,
                   "betas: '%s' (word %d) is not a finite number", w, pos);
  if (!(*x > 0) || *x > CHAIN_T_MAX)
    return sc_fail(msg, SC_EINVAL,
                   "betas: %s (word %d) out of range (valid: (0, %g])", num,
                   pos, CHAIN_T_MAX);
  return SC_OK;
}

static int set_betas(chain_data *D, const char *value, sc_msg *msg) {
  char buf[SC_DATA_LEN];
  snprintf(buf, sizeof buf, "%s", value);
  int n = 0, pos = 0;
  for (char *save = NULL, *w = strtok_r(buf, " \t,", &save); w;
       w = strtok_r(NULL, " \t,", &save)) {
    double x;
    long k;
    int st = threshold_word(w, ++pos, &x, &k, msg);
    if (st) return st;
    if (n + k > CHAIN_MAXBLOCKS - 1)
      return sc_fail(msg, SC_EINVAL,
                     "betas: more than %d thresholds (blocks 2..%d at most)",
                     CHAIN_MAXBLOCKS - 1, CHAIN_MAXBLOCKS);
    for (long j = 0; j < k; j++)
      D->T[1 + n++] = x;
  }
  D->T[0] = 1;
  D->nbetas = n;
  return SC_OK;
}

static int set_range(chain_data *D, const char *value, sc_msg *msg) {
  double lo = CHAIN_RANGE_LO, hi = CHAIN_RANGE_HI;
  if (value[0]) {
    char a[64], b[64], extra[2];
    int n = sscanf(value, "%63s %63s %1s", a, b, extra);
    if (n != 2 || sc_parse_double(a, &lo) || sc_parse_double(b, &hi) ||
        !isfinite(lo) || !isfinite(hi))
      return sc_fail(msg, SC_EINVAL,
                     "threshold-range = '%s': two finite numbers lo hi "
                     "expected",
                     value);
    if (!(lo > 0) || !(lo <= hi) || hi > CHAIN_T_MAX)
      return sc_fail(msg, SC_EINVAL,
                     "threshold-range = '%s' (valid: 0 < lo <= hi <= %g)",
                     value, CHAIN_T_MAX);
  }
  D->lo = lo, D->hi = hi;
  D->range_given = value[0] != '\0';
  return SC_OK;
}

int chain_set_data(void *inst, size_t i, const char *value, sc_msg *msg) {
  chain_data *D = &((chain_inst *)inst)->data;
  int st = SC_OK;
  switch (i) {
  case D_THRESHOLDS:
    if (strcmp(value, "given") && strcmp(value, "random"))
      return sc_fail(msg, SC_EINVAL, "thresholds = '%s' (valid: given|random)",
                     value);
    D->random = strcmp(value, "random") == 0;
    break;
  case D_BETAS:
    st = set_betas(D, value, msg);
    break;
  case D_SEED: {
    long s = (long)CHAIN_SEED_DEFAULT;
    if (value[0] && sc_parse_long(value, 0, 1L << 53, &s))
      return sc_fail(msg, SC_EINVAL,
                     "threshold-seed = '%s' (valid: an integer in [0, "
                     "9007199254740992])",
                     value);
    D->seed = (unsigned long long)s;
    D->seed_given = value[0] != '\0';
    break;
  }
  case D_RANGE:
    st = set_range(D, value, msg);
    break;
  default:
    return sc_fail(msg, SC_EINVAL, "chain: no data key %zu", i);
  }
  if (!st && D->random) draw(D);
  return st;
}

/* Relations of the data keys with one another and with N. */
static int data_check(const chain_data *D, int N, sc_msg *msg) {
  if (D->random && D->nbetas)
    return sc_fail(msg, SC_EINVAL,
                   "betas and thresholds = random both give the thresholds "
                   "(give one of them)");
  if (!D->random && (D->seed_given || D->range_given))
    return sc_fail(msg, SC_EINVAL,
                   "%s acts only with thresholds = random (thresholds = "
                   "given)",
                   D->seed_given ? "threshold-seed" : "threshold-range");
  if (D->nbetas && D->nbetas != N - 1)
    return sc_fail(msg, SC_EINVAL,
                   "betas holds %d threshold%s; blocks = %d needs %d (blocks "
                   "2..%d; block 1's is 1)",
                   D->nbetas, D->nbetas == 1 ? "" : "s", N, N - 1, N);
  return SC_OK;
}

int chain_data_params(void *inst, const int *opt, double *p,
                      unsigned char *which, sc_msg *msg) {
  const chain_data *D = &((chain_inst *)inst)->data;
  int N = opt[O_BLOCKS];
  int st = data_check(D, N, msg);
  if (st || (!D->random && !D->nbetas)) return st;
  for (int b = 1; b < CHAIN_PARAM_BLOCKS && b < N; b++) {
    p[P_BETA2 + b - 1] = D->T[b];
    which[P_BETA2 + b - 1] = 1;
  }
  return SC_OK;
}
