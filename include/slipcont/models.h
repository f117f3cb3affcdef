/**
 * @file models.h
 * @brief The model interface and the built-in models.
 *
 * A model is a constant table: its parameters (name, default, valid range,
 * documentation), its string options, and callbacks that evaluate one
 * iterate of its one-dimensional map.  Scenes, the command line and error
 * messages are generated from these tables.
 */
#ifndef SLIPCONT_MODELS_H
#define SLIPCONT_MODELS_H

#include <stddef.h>

#include "slipcont/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Most parameters a model may declare. */
#define SC_MAXPARAM 8
/** Most string options a model may declare. */
#define SC_MAXOPTION 4

/** One parameter of a model. */
typedef struct {
  const char *name;  /**< as in MODEL.md: "alpha", "beta", "phi", "v" */
  double def;        /**< default value */
  double lo, hi;     /**< valid range */
  int lo_open;       /**< 1: lo itself is excluded */
  int hi_open;       /**< 1: hi itself is excluded (hi may be HUGE_VAL) */
  const char *doc;   /**< one line */
  const char *symbol; /**< plot label (gnuplot text), NULL: the name */
} sc_param_info;

/** Most values one string option may take. */
#define SC_MAXVALUES 6

/** One string option of a model. */
typedef struct {
  const char *name;                  /**< "driver" */
  const char *values[SC_MAXVALUES];  /**< allowed values, NULL-terminated;
                                          the first is the default */
  const char *doc;                   /**< one line */
} sc_option_info;

/**
 * @brief Check @p value against the range of @p pi.
 * @return SC_OK, or SC_EINVAL with `name = value out of range (valid:
 *         (lo, hi])` in @p msg (NaN and infinities are out of range).
 */
SC_API int sc_param_check(const sc_param_info *pi, double value, sc_msg *msg);

/**
 * @brief Write the valid values of @p oi joined by '|' into @p buf.
 * @return @p buf.
 */
SC_API char *sc_option_values_text(const sc_option_info *oi, char *buf, size_t len);

/** What to compute in sc_map_eval(); combine with |. */
enum {
  SC_EVAL_VALUE = 0,     /**< f only */
  SC_EVAL_DERIV = 1,     /**< also df/dd and df/dp for every parameter */
  SC_EVAL_ITINERARY = 2, /**< also the itinerary text */
};

/** Longest itinerary text, NUL included (longer ones are cut with "..."). */
#define SC_ITIN_LEN 256

/**
 * One evaluation of the map (one iterate, or n iterates).
 *
 * For bk2 the itinerary of one iterate is the sequence of slip modes
 * between two global stick phases, joined by '-': "1" (block 1 slips
 * alone and re-sticks), "1-12-2" (block 1 slips, triggers block 2, block 1
 * re-sticks first, block 2 re-sticks), "12" (both start together at d*).
 * The iterates of f^n are joined by '|'.
 */
typedef struct {
  double f;                   /**< f(d), or f^n(d) */
  double dfdd;                /**< df/dd (SC_EVAL_DERIV); NaN where f is not
                                   differentiable (an event with g' = 0,
                                   e.g. a start at d* with V_s = 0) */
  double dfdp[SC_MAXPARAM];   /**< df/dp_i, parameter order (SC_EVAL_DERIV) */
  int neutral;                /**< 1 if f' = 1 exactly: every iterate a
                                   single-block slip (MODEL.md) */
  int nphases;                /**< slip phases in the evaluation */
  double gsp_gap;             /**< bk2: smallest threshold gap T_i - S_i at
                                   the re-sticks (0 at crossing-sliding) */
  double graze_margin;        /**< bk2: smallest |guard| at a local extremum
                                   of a re-stick guard that did or did not
                                   reach zero (0 at grazing-sliding) */
  int graze_block;            /**< bk2: block (1, 2) of graze_margin; 0 none */
  int graze_mode;             /**< bk2: slip mode it ended (SC_BK2_SLIP1..) */
  int gap_block;              /**< bk2: block (1, 2) of gsp_gap */
  double dstar_dist;          /**< bk2: smallest |d - d*| over the starts */
  char itinerary[SC_ITIN_LEN];/**< SC_EVAL_ITINERARY */
} sc_map_value;

/**
 * The model interface.  `inst` is a model-owned block of `inst_size`
 * bytes (zeroed before init); `p` holds the parameter values in table
 * order and `opt` the option value indices.  Callbacks return SC_OK or a
 * negative status and fill @p msg.
 */
typedef struct sc_model_type {
  const char *name;       /**< "bk2" */
  const char *doc;        /**< one line */
  const char *state_name; /**< what the map acts on: "d" (bk2), "x" */
  const char *state_label; /**< plot label of the state, NULL: the name */
  size_t nparam;
  const sc_param_info *params;
  size_t noption;
  const sc_option_info *options;
  size_t inst_size;
  /** Prepare @p inst for the given values (derived constants, workspace);
   * called after every change.  May refuse option combinations. */
  int (*setup)(void *inst, const double *p, const int *opt,
               const sc_accuracy *acc, sc_msg *msg);
  /** Release what setup() took; may be NULL. */
  void (*release)(void *inst);
  /** One iterate: see sc_map_eval() in map.h. */
  int (*eval)(void *inst, double d, unsigned flags, sc_map_value *out,
              sc_msg *msg);
  /** Continuous motion (see sc_map_trajectory()); NULL if none. */
  int (*trajectory)(void *inst, double d, int iterations, double dtau,
                    int (*fn)(void *, double, const double *, int),
                    void *ctx, sc_msg *msg);
} sc_model_type;

/** The two-block Burridge-Knopoff model of MODEL.md. */
SC_API extern const sc_model_type sc_model_bk2;
/** The logistic map x -> r x (1 - x). */
SC_API extern const sc_model_type sc_model_logistic;
/** The cubic map x -> x + mu1 + mu2 x - x^3 (cusp normal form). */
SC_API extern const sc_model_type sc_model_cubic;

/** Number of built-in models; sc_model_get(i) lists them. */
SC_API size_t sc_model_count(void);
/** Built-in model @p i, or NULL. */
SC_API const sc_model_type *sc_model_get(size_t i);
/** Built-in model by name, or NULL. */
SC_API const sc_model_type *sc_model_find(const char *name);

/** bk2 modes (MODEL.md): the `mode` of trajectory samples. */
enum {
  SC_BK2_STICK = 0,  /**< both blocks stuck: global stick phase */
  SC_BK2_SLIP1 = 1,  /**< block 1 slips, block 2 stuck */
  SC_BK2_SLIP2 = 2,  /**< block 2 slips, block 1 stuck */
  SC_BK2_SLIP12 = 3, /**< both slip */
};

/** d* = (beta - 1)/(1 + 2 alpha): below it block 1 reaches its
 * threshold first (MODEL.md). */
SC_API double sc_bk2_dstar(double alpha, double beta);

#ifdef __cplusplus
}
#endif
#endif
