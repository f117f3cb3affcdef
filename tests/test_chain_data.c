/* Thresholds per block of the chain (docs/chain.md, "Thresholds per
 * block"): `betas` against the parameters it replaces, a block past 5
 * read from it (the onset from d = 0 starts at the smallest threshold; a
 * mirrored list gives the mirror symmetry), the seeded draw against the
 * stated generator written again here, its reproducibility, explicit
 * parameters overriding the data in either order, clones, and every
 * refusal with its message. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/map.h"
#include "test_util.h"

static sc_map *chain_new(int N, const char *driver) {
  sc_map *m = NULL;
  sc_msg msg;
  char nb[24];
  snprintf(nb, sizeof nb, "%d", N);
  if (sc_map_alloc("chain", NULL, &m, &msg) ||
      sc_map_set_option(m, "blocks", nb, &msg) ||
      sc_map_set_option(m, "driver", driver, &msg)) {
    tu_true(0, "chain_new(%d): %s", N, msg.text);
    sc_map_free(m);
    return NULL;
  }
  return m;
}

static int data(sc_map *m, const char *key, const char *value) {
  sc_msg msg;
  int st = sc_map_set_data(m, key, value, &msg);
  tu_true(st == SC_OK, "set %s = '%s': %s", key, value, st ? msg.text : "");
  return st;
}

static double param(const sc_map *m, const char *name) {
  return sc_map_get_param(m, (size_t)sc_map_param_index(m, name));
}

/* f(x) of m into f (n values) with the itinerary into itin; status. */
static int eval(sc_map *m, const double *x, double *f, char *itin) {
  sc_mapn_value *v = NULL;
  sc_msg msg;
  int st = sc_mapn_value_alloc(m, SC_EVAL_VALUE, &v, &msg);
  if (!st) st = sc_map_eval_n(m, x, SC_EVAL_ITINERARY, v, &msg);
  if (!st) {
    memcpy(f, v->f, v->n * sizeof *f);
    if (itin) snprintf(itin, SC_ITIN_LEN, "%s", v->itinerary);
  } else {
    tu_true(0, "eval: %s", msg.text);
  }
  sc_mapn_value_free(v);
  return st;
}

/* A refusal: status SC_EINVAL and a message holding @p want; the key
 * keeps its previous text. */
static void refused(sc_map *m, const char *key, const char *value,
                    const char *want) {
  sc_msg msg = {0};
  char before[SC_DATA_LEN];
  snprintf(before, sizeof before, "%s", sc_map_get_data(m, key));
  int st = sc_map_set_data(m, key, value, &msg);
  tu_true(st == SC_EINVAL && strstr(msg.text, want),
          "%s = '%s' refused with '%s' (got %d: '%s')", key, value, want, st,
          msg.text);
  tu_true(strcmp(sc_map_get_data(m, key), before) == 0,
          "%s keeps '%s' after a refusal (has '%s')", key, before,
          sc_map_get_data(m, key));
}

/* betas for five blocks is the four parameters: f bit for bit. */
static void betas_are_params(void) {
  sc_map *a = chain_new(5, "moving"), *b = chain_new(5, "moving");
  if (!a || !b) goto done;
  data(a, "betas", "1.5 2 0.7 1.3");
  const char *names[] = {"beta2", "beta3", "beta4", "beta5"};
  const double vals[] = {1.5, 2, 0.7, 1.3};
  sc_msg msg;
  for (int i = 0; i < 4; i++) {
    tu_close(names[i], param(a, names[i]), vals[i], 0);
    sc_map_set_param_by_name(b, names[i], vals[i], &msg);
  }
  double x[4] = {0.013, -0.021, 0.007, 0.017}, fa[4], fb[4];
  char ia[SC_ITIN_LEN], ib[SC_ITIN_LEN];
  if (!eval(a, x, fa, ia) && !eval(b, x, fb, ib)) {
    for (int i = 0; i < 4; i++)
      tu_close("betas: f = f(beta2..5)", fa[i], fb[i], 0);
    tu_true(strcmp(ia, ib) == 0, "the same itinerary (%s, %s)", ia, ib);
  }
done:
  sc_map_free(a);
  sc_map_free(b);
}

/* A block past 5 has the list's threshold: from d = 0 every spring
 * force is equal, so the block of smallest threshold starts (block 7 at
 * 0.5); a mirrored list gives f(mirror d) = mirror f(d) (docs/chain.md,
 * "Checks"). */
static void blocks_past_five(void) {
  sc_map *m = chain_new(8, "frozen");
  if (!m) return;
  data(m, "betas", "1.2 0.9 1.1 1.1 0.9 0.5*1 1.2");
  double x[7] = {0}, f[7], g[7];
  char it[SC_ITIN_LEN];
  if (!eval(m, x, f, it))
    tu_true(strncmp(it, "7", 1) == 0 && (it[1] == '-' || !it[1]),
            "d = 0: block 7 (threshold 0.5) starts (itinerary %.40s)", it);
  data(m, "betas", "1.3 0.8 1.1 1.1 0.8 1.3 1");
  double y[7] = {0.011, -0.004, 0.019, 0.002, -0.013, 0.008, -0.006};
  double ym[7];
  for (int i = 0; i < 7; i++)
    ym[i] = -y[6 - i];
  if (!eval(m, y, f, NULL) && !eval(m, ym, g, NULL))
    for (int i = 0; i < 7; i++)
      tu_close("mirrored thresholds: f(mirror d) = mirror f(d)", g[i],
               -f[6 - i], 1e-12);
  sc_map_free(m);
}

/* The stated generator, written again: splitmix64 from the seed, 53 bits
 * of each number scaled to [0, 1). */
static double draw_ref(unsigned long long seed, int block, double lo,
                       double hi) {
  unsigned long long x = seed, z = 0;
  for (int i = 2; i <= block; i++) {
    x += 0x9E3779B97F4A7C15ULL;
    z = x;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
  }
  return lo + (hi - lo) * (double)(z >> 11) / 9007199254740992.0;
}

static void random_draw(void) {
  sc_map *a = chain_new(5, "moving"), *b = chain_new(12, "moving");
  sc_map *c = chain_new(12, "moving");
  if (!a || !b || !c) goto done;
  data(a, "thresholds", "random");
  data(a, "threshold-seed", "12345");
  data(a, "threshold-range", "0.5 1.5");
  const char *names[] = {"beta2", "beta3", "beta4", "beta5"};
  for (int i = 0; i < 4; i++)
    tu_close("drawn beta = splitmix64's", param(a, names[i]),
             draw_ref(12345, i + 2, 0.5, 1.5), 0);
  /* block i's threshold does not depend on N */
  data(b, "thresholds", "random");
  data(b, "threshold-range", "0.5 1.5");
  data(b, "threshold-seed", "12345");
  for (int i = 0; i < 4; i++)
    tu_close("the same draw for 5 and 12 blocks", param(b, names[i]),
             param(a, names[i]), 0);
  /* reproducible: the same seed, the same map; another, another map */
  data(c, "thresholds", "random");
  data(c, "threshold-range", "0.5 1.5");
  data(c, "threshold-seed", "12345");
  double x[11], fb[11], fc[11];
  for (int i = 0; i < 11; i++)
    x[i] = 0.01 * sin(1.7 * i);
  if (!eval(b, x, fb, NULL) && !eval(c, x, fc, NULL))
    for (int i = 0; i < 11; i++)
      tu_close("same seed: same f", fc[i], fb[i], 0);
  data(c, "threshold-seed", "12346");
  int differ = 0;
  if (!eval(c, x, fc, NULL))
    for (int i = 0; i < 11; i++)
      differ |= fc[i] != fb[i];
  tu_true(differ, "another seed gives another map");
  /* a clone keeps the data */
  sc_map *k = NULL;
  sc_msg msg;
  if (!sc_map_clone(b, &k, &msg)) {
    if (!eval(k, x, fc, NULL))
      for (int i = 0; i < 11; i++)
        tu_close("clone: same f", fc[i], fb[i], 0);
    sc_map_free(k);
  } else {
    tu_true(0, "clone: %s", msg.text);
  }
done:
  sc_map_free(a);
  sc_map_free(b);
  sc_map_free(c);
}

/* An explicit parameter overrides the data, set before or after it. */
static void explicit_wins(void) {
  sc_map *m = chain_new(6, "moving");
  sc_msg msg;
  if (!m) return;
  sc_map_set_param_by_name(m, "beta3", 2.5, &msg);
  data(m, "betas", "1.1 1.2 1.3 1.4 1.5");
  tu_close("beta3 set before betas stays", param(m, "beta3"), 2.5, 0);
  tu_close("beta2 from betas", param(m, "beta2"), 1.1, 0);
  tu_int("beta3 is set",
         sc_map_param_is_set(m, (size_t)sc_map_param_index(m, "beta3")), 1);
  tu_int("beta2 is not",
         sc_map_param_is_set(m, (size_t)sc_map_param_index(m, "beta2")), 0);
  sc_map_set_param_by_name(m, "beta4", 0.75, &msg);
  data(m, "betas", "2.1 2.2 2.3 2.4 2.5");
  tu_close("beta4 set after betas stays", param(m, "beta4"), 0.75, 0);
  tu_close("beta5 follows the new betas", param(m, "beta5"), 2.4, 0);
  sc_map_free(m);
}

static void refusals(void) {
  sc_map *m = chain_new(5, "moving");
  if (!m) return;
  refused(m, "betas", "1 2 3", "betas holds 3 thresholds; blocks = 5 needs 4");
  refused(m, "betas", "1 nan 2 3", "'nan' (word 2) is not a finite number");
  refused(m, "betas", "1 2 0 3", "0 (word 3) out of range (valid: (0,");
  refused(m, "betas", "1 2 -1.5 3", "-1.5 (word 3) out of range");
  refused(m, "betas", "1 2*x 3", "count after '*'");
  refused(m, "thresholds", "uniform", "valid: given|random");
  refused(m, "threshold-seed", "3", "acts only with thresholds = random");
  data(m, "thresholds", "random");
  refused(m, "betas", "1 2 3 4", "give one of them");
  refused(m, "threshold-range", "1.2 0.8", "valid: 0 < lo <= hi");
  refused(m, "threshold-range", "0 1", "valid: 0 < lo <= hi");
  refused(m, "threshold-range", "0.5", "two finite numbers");
  refused(m, "threshold-seed", "-1", "valid: an integer");
  data(m, "thresholds", "given");
  data(m, "betas", "1 2 3 4");
  sc_msg msg = {0};
  int st = sc_map_set_option(m, "blocks", "6", &msg);
  tu_true(st == SC_EINVAL && strstr(msg.text, "betas holds 4 thresholds"),
          "blocks = 6 with four betas refused (%s)", msg.text);
  tu_true(strcmp(sc_map_get_option(m, "blocks"), "5") == 0,
          "blocks stays 5 (%s)", sc_map_get_option(m, "blocks"));
  sc_map_free(m);
}

int main(void) {
  betas_are_params();
  blocks_past_five();
  random_draw();
  explicit_wins();
  refusals();
  return tu_finish();
}
