/* Private to the bk2 model: its rules, as data and in no number type, for
 * every path that follows the motion (the closed-form flows on doubles,
 * duals and jets, the numerical flows, and quad precision, bk2_quad.c):
 * the modes, the events that end a slip phase and the table of
 * docs/model.md ("Events") that says which mode each leads to, the onset
 * of a slip from a global stick phase (GSP), and the names of modes and
 * guards in itineraries and border names.
 *
 * A mode's value is the set of its slipping blocks (bit 0: block 1, bit
 * 1: block 2), so the blocks an event sticks and those that start to slip
 * are set differences of the two modes. */
#ifndef SC_MODELS_BK2_RULES_H
#define SC_MODELS_BK2_RULES_H

#include <string.h>

#include "slipcont/bk2.h"
#include "slipcont/models.h"

_Static_assert(SC_BK2_STICK == 0 && SC_BK2_SLIP1 == 1 && SC_BK2_SLIP2 == 2 &&
                   SC_BK2_SLIP12 == 3,
               "a bk2 mode is the set of its slipping blocks");

/* Event kinds, and the first byte of a phase in an itinerary code:
 * re-stick of block 1 or 2 (U_i reaches V_s), threshold of the stuck
 * block (S_j reaches T_j), both blocks re-stick at once at the root of
 * block 1's or block 2's guard.  BK2_EV_ATMAX on a re-stick: the phase
 * ends at the guard's (skip + 1)-th local maximum instead of a root (a
 * grazing's own defining system). */
enum {
  BK2_EV_RESTICK1 = 1,
  BK2_EV_RESTICK2,
  BK2_EV_THRESHOLD,
  BK2_EV_BOTH,
  BK2_EV_BOTH2,
  BK2_EV_ATMAX = 0x80
};
#define BK2_IS_BOTH(k) ((k) == BK2_EV_BOTH || (k) == BK2_EV_BOTH2)
/* The guard whose root an event is. */
#define BK2_GUARD_OF(k)                                                        \
  ((k) == BK2_EV_BOTH ? BK2_EV_RESTICK1 : (k) == BK2_EV_BOTH2 ? BK2_EV_RESTICK2 \
                                                               : (k))

/* The event table of docs/model.md: the mode a phase of `mode` enters
 * when the event `kind` ends it; -1 where that event cannot end it. */
static inline int bk2_next_mode(int mode, int kind) {
  static const signed char next[4][BK2_EV_BOTH2 + 1] = {
      [SC_BK2_STICK] = {-1, -1, -1, -1, -1, -1},
      [SC_BK2_SLIP1] = {-1, SC_BK2_STICK, -1, SC_BK2_SLIP12, -1, -1},
      [SC_BK2_SLIP2] = {-1, -1, SC_BK2_STICK, SC_BK2_SLIP12, -1, -1},
      [SC_BK2_SLIP12] = {-1, SC_BK2_SLIP2, SC_BK2_SLIP1, -1, SC_BK2_STICK,
                         SC_BK2_STICK},
  };
  return next[mode][kind];
}

/* The table read the other way: the single event (a re-stick or a
 * threshold) that takes `mode` to `next`; 0 if none does (the slip of
 * both blocks ended by both at once). */
static inline int bk2_event_between(int mode, int next) {
  for (int k = BK2_EV_RESTICK1; k <= BK2_EV_THRESHOLD; k++)
    if (bk2_next_mode(mode, k) == next) return k;
  return 0;
}

/* The blocks that start slipping when `mode` enters `next` (their U_i =
 * V_s at the start, so their re-stick guards start at zero), and those
 * that stick (their U_i becomes V_s). */
static inline int bk2_fresh_blocks(int mode, int next) { return next & ~mode; }
static inline int bk2_stuck_blocks(int mode, int next) { return mode & ~next; }

/* The events that can end a phase of `mode` (fresh: the blocks that
 * started slipping with it, bk2_fresh_blocks()), into kind in the order
 * the exact flows search them: a re-stick of each slipping block, the
 * threshold of a stuck one.  Later guards are searched only up to the
 * earliest root so far, so the likelier first event goes first: in
 * SLIP12, the block that has slipped longer (not fresh); there the two
 * are searched together and the order only breaks exact ties of the
 * roots' times (and orders guards that do not pair).  Returns their
 * number (at most 2). */
static inline int bk2_phase_kinds(int mode, int fresh, int kind[2]) {
  int ng = 0;
  int order[2] = {1, 2};
  if (mode == SC_BK2_SLIP12 && (fresh & 1) && !(fresh & 2))
    order[0] = 2, order[1] = 1;
  for (int k = 0; k < 2; k++)
    if (mode == order[k] || mode == SC_BK2_SLIP12) kind[ng++] = order[k];
  if (mode != SC_BK2_SLIP12) kind[ng++] = BK2_EV_THRESHOLD;
  return ng;
}

/* The mode of the slip that ends a GSP of displacement d (any number
 * type): block 1 is at its threshold first iff d < d* (docs/model.md,
 * "The event map"); at d* both are, and both start (the tie rule). */
#define BK2_ONSET_MODE(d, dstar)                                               \
  ((d) < (dstar) ? SC_BK2_SLIP1 : (d) > (dstar) ? SC_BK2_SLIP2 : SC_BK2_SLIP12)

/* The block whose threshold fixes the onset state of a slip of `mode`
 * from a GSP: the block that starts (block 2 when both do).  With d =
 * Y2 - Y1 and S_i = T_i, block 1: Y1 = 1 + alpha d, Y2 = Y1 + d; block 2:
 * Y2 = beta - alpha d, Y1 = Y2 - d. */
static inline int bk2_onset_block(int mode) {
  return mode == SC_BK2_SLIP1 ? 1 : 2;
}

/* A slip mode's name in itineraries and border names. */
static inline const char *bk2_mode_name(int mode) {
  return mode == SC_BK2_SLIP1 ? "1" : mode == SC_BK2_SLIP2 ? "2" : "12";
}

/* A guard's name in border names (by event kind). */
static inline const char *bk2_guard_text(int kind) {
  return kind == 1 ? "U1-Vs" : kind == 2 ? "U2-Vs" : "S-T of stuck block";
}

/* Append mode's name to the itinerary itin of length *len ("1-12-2");
 * "..." once it is full. */
static inline void bk2_itin_add(char *itin, size_t *len, int mode) {
  const char *tok = bk2_mode_name(mode);
  size_t need = strlen(tok) + (*len ? 1 : 0);
  if (*len + need + 4 >= SC_ITIN_LEN) {
    if (*len + 4 < SC_ITIN_LEN && strcmp(itin + *len - 3, "...") != 0) {
      strcpy(itin + *len, "...");
      *len += 3;
    }
    return;
  }
  if (*len) itin[(*len)++] = '-';
  strcpy(itin + *len, tok);
  *len += strlen(tok);
}

#endif
