/* An integration of the chain of its own, for the chain's tests: the
 * equations of motion written again from docs/chain.md, integrated by
 * GSL's rk8pd at 1e-13 in steps of at most 0.01, events located by
 * bisection on re-integrations.  While block i slips, Y_i' = U_i and
 * U_i' = K_i - S_i with K_i = T_i / (phi (1 + gamma |U_i - W|)) (Coulomb
 * friction: gamma = 0; velocity weakening: phi = 1); while it sticks,
 * Y_i' = W, U_i' = 0. */
#ifndef SC_TESTS_CHAIN_REF_H
#define SC_TESTS_CHAIN_REF_H

/* Most blocks the reference takes. */
#define CHAIN_REF_MAXN 5

/* A slip of many phases is chaotic within itself (blocks trigger one
 * another back and forth): its end depends on the rounding of each event
 * and two correct computations part after a few dozen phases.  The
 * reference gives up on iterates longer than this, and the comparisons
 * leave them out. */
#define CHAIN_REF_MAX_PHASES 40

typedef struct {
  int N, ring;
  double alpha, phi, gamma;
  double W; /* the surface speed during slips and stick phases */
  double T[CHAIN_REF_MAXN];
  int slip[CHAIN_REF_MAXN]; /* working state */
} chain_ref;

/* f(d) by integration from the global stick phase with differences d,
 * and the itinerary as the chain writes it (N <= 9): 0, -1 (no event
 * within 1000 time units) or -2 (more than CHAIN_REF_MAX_PHASES
 * phases). */
int chain_ref_map(chain_ref *s, const double *d, double *f, char *itin);

/* The chain's tests' own set-up of the model: a chain of N blocks with the
 * given topology and driver (NULL, and a failed check, where refused);
 * a parameter set by name (a failed check where refused). */
struct sc_map;
struct sc_map *chain_ref_new(int N, const char *topology, const char *driver);
void chain_ref_set(struct sc_map *m, const char *name, double x);

#endif
