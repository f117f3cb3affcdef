/**
 * @file models.h
 * @brief The model interface and the built-in models.
 *
 * A model is a constant table: its parameters (name, default, valid range,
 * documentation), its string options, its state dimension, and callbacks
 * that evaluate one iterate of its map: eval() for a one-dimensional
 * map, eval_n() for a map of n > 1 components.  Scenes, the command line and error
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
/** Most string options a model may declare (chain: blocks, topology,
 * driver, friction, flows). */
#define SC_MAXOPTION 5

/** One parameter of a model. */
typedef struct {
  const char *name;  /**< as in docs/model.md: "alpha", "beta", "phi", "v" */
  double def;        /**< default value */
  double lo;         /**< valid range: lower end */
  double hi;         /**< valid range: upper end */
  int lo_open;       /**< 1: lo itself is excluded */
  int hi_open;       /**< 1: hi itself is excluded (hi may be HUGE_VAL) */
  const char *doc;   /**< one line */
  const char *symbol; /**< plot label (gnuplot text), NULL: the name */
  /** NULL, or "option=value": the parameter acts only with that option
   * value (bk2: gamma with friction=velocity-weakening, phi with
   * friction=coulomb), or "option>=N" for a whole-number option (chain:
   * beta4 with blocks>=4); plot titles leave it out otherwise. */
  const char *only_with;
} sc_param_info;

/** Most data keys a model may declare (sc_model_type.data). */
#define SC_MAXDATA 4
/** Longest value of a data key, NUL included (a scene line is shorter). */
#define SC_DATA_LEN 256

/** One data key of a model: a value of its `[model]` section that is
 * neither a parameter (it is not continued) nor an option (not one word
 * of a list), read by the model as text: the chain's `betas`, a list of
 * thresholds.  The map keeps the text (sc_map_get_data()). */
typedef struct {
  const char *name; /**< "betas" */
  const char *def;  /**< its default as text ("" : not given) */
  const char *doc;  /**< one line: what it holds and its syntax */
} sc_data_info;

/** Most values one string option may take. */
#define SC_MAXVALUES 6

/** One string option of a model. */
typedef struct {
  const char *name;                  /**< "driver" */
  const char *values[SC_MAXVALUES];  /**< allowed values, NULL-terminated;
                                          the first is the default */
  const char *doc;                   /**< one line */
  /** int_hi > 0: a whole-number option ("blocks"), any value in
   * [int_lo, int_hi] written in decimal; values[0] is its default written
   * out and values[1] is NULL.  The model's setup() reads the number
   * itself in opt[] (not an index). */
  int int_lo;
  int int_hi;  /**< 0: the option takes one of values[] */
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
  SC_EVAL_DERIV2 = 4,    /**< also the second derivatives and the third
                              ones d3f/dd3, d3f/dd2 dp (implies DERIV) */
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
                                   single-block slip (docs/model.md) */
  int nphases;                /**< slip phases in the evaluation */
  char itinerary[SC_ITIN_LEN];/**< SC_EVAL_ITINERARY */
  double d2fdd2;              /**< d2f/dd2 (SC_EVAL_DERIV2); NaN where f is
                                   not twice differentiable */
  double d2fddp[SC_MAXPARAM]; /**< d2f/dd dp_i (SC_EVAL_DERIV2) */
  double d3fdd3;              /**< d3f/dd3 (SC_EVAL_DERIV2) */
  double d3fdd2p[SC_MAXPARAM];/**< d3f/dd2 dp_i (SC_EVAL_DERIV2) */
} sc_map_value;

/* ------------------------------------------------------------------ */
/* Maps in n dimensions                                                */

/** Most state components a model may declare (sc_model_type.dim). */
#define SC_MAXDIM 256
/** Largest dimension for which second and third derivative tensors are
 * kept (SC_EVAL_DERIV2 on sc_mapn_value): a third-derivative tensor has
 * n^4 entries, 65536 at n = 16.  Normal forms and the defining systems of
 * codimension-two points need them; a larger map still gives f, its
 * Jacobian and its parameter derivatives. */
#define SC_DIM_TENSOR 16

/**
 * One evaluation of an n-dimensional map (one iterate, or m iterates),
 * in storage owned by the caller (sc_mapn_value_alloc() in map.h sizes
 * it for a map).  Arrays are row-major; i indexes the component of f,
 * j, k, l the components of the state, q the parameters:
 *  - f[i];
 *  - J[i n + j] = d f_i / d x_j                 (SC_EVAL_DERIV);
 *  - fp[q n + i] = d f_i / d p_q                 (SC_EVAL_DERIV);
 *  - H[(i n + j) n + k] = d2 f_i / dx_j dx_k     (SC_EVAL_DERIV2);
 *  - Jp[(q n + i) n + j] = d2 f_i / dx_j dp_q    (SC_EVAL_DERIV2);
 *  - T[((i n + j) n + k) n + l] = d3 f_i / dx_j dx_k dx_l (SC_EVAL_DERIV2).
 * For n = 1 these are the scalars of sc_map_value (J = f', H = f'', ...).
 * An array the storage was not sized for is NULL.
 */
typedef struct {
  size_t n;    /**< state dimension */
  size_t np;   /**< number of parameters */
  double *f;   /**< n values */
  double *J;   /**< n x n Jacobian, or NULL */
  double *fp;  /**< np x n parameter derivatives, or NULL */
  double *H;   /**< n^3 second derivatives, or NULL */
  double *Jp;  /**< np n^2 mixed derivatives, or NULL */
  double *T;   /**< n^4 third derivatives, or NULL */
  int nphases; /**< slip phases in the evaluation (0 for smooth maps) */
  char itinerary[SC_ITIN_LEN]; /**< SC_EVAL_ITINERARY */
} sc_mapn_value;

/* ------------------------------------------------------------------ */
/* Borders: where the map's itinerary changes                          */

/**
 * Kinds of border.  A border is a smooth function m(d, p) of the state at
 * the start of an iterate and the parameters whose zero is a
 * discontinuity-induced bifurcation of an orbit through d (see
 * docs/branches.md for a picture of each).  The analysis layer knows
 * borders by kind and name only.
 */
typedef enum {
  SC_BORDER_GRAZING = 0, /**< GR: an event guard touches zero at a local
                              maximum (bk2: a re-stick velocity that only
                              just reaches V_s) */
  SC_BORDER_CROSSING,    /**< CS: an ending event and another part's
                              threshold at once (bk2: a global stick phase
                              of length zero) */
  SC_BORDER_SWITCHING,   /**< SW: the state on a switching surface of the
                              map (bk2: a global stick phase at d*) */
  SC_BORDER_BOTH,        /**< BR: two ending events at once (bk2: both
                              blocks re-stick together) */
  SC_BORDER_TOUCH,       /**< TT: a threshold guard touches zero without
                              crossing (bk2: the stuck block's spring force
                              just reaches its static threshold) */
} sc_border_kind;

/** Number of border kinds. */
#define SC_BORDER_NKINDS 5

/** Label of a border kind: "GR", "CS", "SW", "BR", "TT"; "??" otherwise. */
SC_API const char *sc_border_label(sc_border_kind k);

/** Longest itinerary code of one iterate. */
#define SC_CODE_LEN 64

/**
 * The itinerary of one iterate as the model encodes it, opaque to the
 * analysis layer: an evaluation reports the code it followed, and a
 * forced evaluation follows a given code, continuing every event past
 * the borders smoothly (the other events are watched, not taken).
 * n = 0: no code (a model without borders, or more phases than fit).
 */
typedef struct {
  int n;                        /**< bytes used; 0: no code */
  unsigned char c[SC_CODE_LEN]; /**< the code's bytes (model-defined) */
} sc_itin_code;

/** Longest border name, NUL included. */
#define SC_BORDER_NAME 64

/**
 * One border of an evaluation, with exact first derivatives.
 *
 * Sign: value > 0 on the side of the itinerary that was followed, 0 on
 * the border, < 0 beyond it (only a forced evaluation can get there: the
 * natural itinerary changes at the border).
 */
typedef struct {
  sc_border_kind kind; /**< grazing, crossing, switching, ... */
  int iterate;        /**< iterate of f^n it belongs to, from 0 */
  double value;       /**< m */
  double dd;          /**< dm/dd, d the argument of the evaluation */
  double dp[SC_MAXPARAM]; /**< dm/dp_i, parameter order */
  /** 1: the border is a surface in the state itself, m = +-(d_k - d_on(p))
   * with d_k the start of its iterate: d_on and d_on_dp give the point on
   * it.  The map may be singular there (bk2: f' grows like
   * |d - d*|^(-1/2) with the driver frozen), so a point on such a border
   * is located with the orbit started exactly on it. */
  int on_state;
  double d_on;                 /**< on_state: the point d_on(p) */
  double d_on_dp[SC_MAXPARAM]; /**< on_state: d d_on / dp_i */
  /** The code of this iterate to follow to stay on the border (n = 0:
   * the iterate's own code serves): e.g. a grazing met from the side
   * where the guard fires is followed with the event at the guard's
   * maximum instead of its root, so the defining system stays smooth. */
  sc_itin_code alt;
  char name[SC_BORDER_NAME]; /**< what it is, e.g. "U2 - Vs max, phase 3
                                  (slip 12)"; equal names on equal codes
                                  are the same border */
} sc_border;

/**
 * Where borders go: caller-owned storage of @p cap entries.  An evaluation
 * appends; @p n counts every border, also those beyond @p cap (then only
 * the first cap are stored: grow the storage and evaluate again).
 */
typedef struct {
  sc_border *b; /**< storage for cap borders */
  size_t cap;   /**< entries b holds */
  size_t n;     /**< borders of the evaluation (may exceed cap) */
} sc_border_list;


/**
 * One border of an evaluation of an n-dimensional map, with its exact
 * gradient: as sc_border, with dm/dx (n values) in place of dm/dd.
 *
 * on_state = 1: the border is a surface in the state itself, m = s(x_k,
 * p) with x_k the start of its iterate (bcnf: the switching line x = 0);
 * the gradient of one iterate's border, before any chaining, is then the
 * surface's normal at x_k.  A point on it is any state where m = 0: the
 * one-dimensional d_on has no counterpart.
 */
typedef struct {
  sc_border_kind kind; /**< grazing, crossing, switching, ... */
  int iterate;         /**< iterate of f^m it belongs to, from 0 */
  double value;        /**< m, > 0 on the side followed (as sc_border) */
  double *dx;          /**< n values, dm/dx (x the argument of the
                            evaluation): storage owned by the list */
  double dp[SC_MAXPARAM]; /**< dm/dp_i, parameter order */
  int on_state;           /**< 1: a surface in the state (above) */
  sc_itin_code alt;       /**< as sc_border.alt */
  char name[SC_BORDER_NAME]; /**< as sc_border.name */
} sc_bordern;

/**
 * Where the borders of an n-dimensional evaluation go: @p cap entries
 * whose gradients point into @p grad (cap x dim doubles), both owned by
 * the list (sc_bordern_list_alloc() in map.h).  An evaluation appends;
 * @p n counts every border, also those beyond @p cap.
 */
typedef struct {
  sc_bordern *b; /**< cap entries; b[i].dx = grad + i dim */
  double *grad;  /**< cap x dim doubles */
  size_t cap;    /**< entries b holds */
  size_t dim;    /**< state dimension n */
  size_t n;      /**< borders of the evaluation (may exceed cap) */
} sc_bordern_list;

/** Most blocks a slip event record describes (the chain's largest N). */
#define SC_EVENT_MAXBLOCKS 256

/**
 * What one iterate of a stick-slip map of many blocks did, block by block:
 * one slip event, from the end of one global stick phase to the start of
 * the next (sc_map_eval_event(); docs/chain.md, "Event catalogue").
 * Dimensionless as the model: lengths in block 1's threshold over the
 * driving spring's stiffness, energies in that length squared times it.
 */
typedef struct {
  int nblocks;     /**< blocks of the model (entries of bslip) */
  int first;       /**< the block that started the slip, from 1 (the
                        last of blocks that start together, as the map) */
  int nslipped;    /**< blocks that slipped during it */
  double duration; /**< the slip's length in time (its phases together) */
  double stick;    /**< the global stick phase after it: its length
                        (HUGE_VAL when the driver stands, V = 0) */
  double slip;     /**< total slip: the sum of bslip */
  double released; /**< elastic energy released: E(start) - E(end), E the
                        energy of every spring */
  double friction; /**< energy dissipated by friction, sum K_i bslip_i */
  double driver;   /**< work done by the driver during the slip; energy
                        balance: released = friction - driver */
  /** each block's slip, its displacement relative to the surface
   * (0 for a block that stayed stuck) */
  double bslip[SC_EVENT_MAXBLOCKS];
  /** 1 for each block that slipped (a block may slip by 0 in a phase of
   * zero length) */
  unsigned char slipped[SC_EVENT_MAXBLOCKS];
} sc_slip_event;

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
  /** the name of the point of its borders in the state (on_state), as
   * plots and summaries write it: "d*" (bk2); NULL: the border kind's
   * label ("SW") */
  const char *state_point_name;
  size_t nparam;                 /**< number of parameters */
  const sc_param_info *params;   /**< their table, in parameter order */
  size_t noption;                /**< number of options */
  const sc_option_info *options; /**< their table */
  size_t inst_size;              /**< bytes of a model instance */
  /** Prepare @p inst for the given values (derived constants, workspace);
   * called after every change.  May refuse option combinations. */
  int (*setup)(void *inst, const double *p, const int *opt,
               const sc_accuracy *acc, sc_msg *msg);
  /** Release what setup() took; may be NULL. */
  void (*release)(void *inst);
  /** One iterate: see sc_map_eval() in map.h. */
  int (*eval)(void *inst, double d, unsigned flags, sc_map_value *out,
              sc_msg *msg);
  /** One iterate following @p force (NULL: the natural itinerary),
   * reporting the code followed into @p code (may be NULL) and appending
   * the iterate's borders to @p borders (may be NULL; their derivatives
   * are filled whatever @p flags says).  NULL for a model without
   * borders (a smooth map).  See sc_map_eval_ex(). */
  int (*eval_ex)(void *inst, double d, unsigned flags,
                 const sc_itin_code *force, sc_itin_code *code,
                 sc_border_list *borders, sc_map_value *out, sc_msg *msg);
  /** The absolute accuracy to which eval() computes f (and, relative to
   * its size, f'): 0 for the rounding of closed forms; numerical flows
   * report their integration tolerance.  Newton's methods built on the
   * map ask for no more (sc_map_precision()).  May be NULL (0). */
  double (*precision)(const void *inst);
  /** State dimension n >= 1; 0 reads as 1 (the one-dimensional
   * models).  A model with n > 1 gives eval_n; eval is then NULL. */
  size_t dim;
  /** Names of the state components for n > 1 ("x", "y"), NULL: the
   * state name with its index ("d1", "d2", ...). */
  const char *const *state_names;
  /** One iterate of an n-dimensional map at @p x (n values): f, and by
   * @p flags its derivatives, into @p out (sized by the map layer for n
   * and the model's parameters).  NULL for a one-dimensional model: the
   * map layer reads eval() (sc_map_eval_n()). */
  int (*eval_n)(void *inst, const double *x, unsigned flags,
                sc_mapn_value *out, sc_msg *msg);
  /** The state dimension of a model whose dimension depends on its
   * options (the chain: blocks - 1), read after every setup(); NULL: dim
   * is the dimension.  Such a model gives eval_n (used for every n, 1
   * included) and no eval. */
  size_t (*dim_of)(const void *inst);
  /** One iterate of an n-dimensional map with borders, following
   * @p force (NULL: the natural itinerary), reporting the code followed
   * into @p code (may be NULL) and appending the iterate's borders to
   * @p borders (may be NULL; their gradients filled whatever @p flags
   * says): the contract of eval_ex for a state of n components.  NULL
   * for a smooth map.  See sc_map_eval_n_ex(). */
  int (*eval_n_ex)(void *inst, const double *x, unsigned flags,
                   const sc_itin_code *force, sc_itin_code *code,
                   sc_bordern_list *borders, sc_mapn_value *out, sc_msg *msg);
  size_t ndata;                /**< number of data keys (<= SC_MAXDATA) */
  const sc_data_info *data;    /**< their table, NULL when ndata = 0 */
  /** Read data key @p i's text @p value into @p inst: its syntax and the
   * range of each number, with a message naming the key and the bad word
   * (relations with the options and parameters are setup()'s).  The map
   * calls setup() after it.  NULL when ndata = 0. */
  int (*set_data)(void *inst, size_t i, const char *value, sc_msg *msg);
  /** The parameter values the data gives (the chain: its thresholds of
   * blocks 2..5 are parameters): for the options @p opt, set p[i] and
   * which[i] = 1 for each such parameter i (nparam entries each).  The
   * map applies them before each setup() to the parameters that were
   * never set by sc_map_set_param(), so that a parameter set explicitly
   * overrides the data.  May fail (SC_EINVAL: data that does not fit the
   * options, e.g. a list of the wrong length).  May be NULL. */
  int (*data_params)(void *inst, const int *opt, double *p,
                     unsigned char *which, sc_msg *msg);
  /** One iterate as eval_n() that also records what the slip did into
   * @p ev (sc_map_eval_event()); NULL for a model without slip events.
   * Recording costs only the calls that ask for it. */
  int (*eval_event)(void *inst, const double *x, unsigned flags,
                    sc_mapn_value *out, sc_slip_event *ev, sc_msg *msg);
  /** Continuous motion of a model of blocks whose state has n = N - 1
   * components (the chain), from the state @p x: as trajectory, each
   * sample passed to @p fn being the N positions then the N velocities
   * (2 N values) and the number of blocks slipping (0: a global stick
   * phase).  See sc_map_trajectory_n(); NULL if none. */
  int (*trajectory_n)(void *inst, const double *x, int iterations,
                      double dtau, int (*fn)(void *, double, const double *,
                                             int),
                      void *ctx, sc_msg *msg);
  /** Continuous motion (see sc_map_trajectory()); NULL if none. */
  int (*trajectory)(void *inst, double d, int iterations, double dtau,
                    int (*fn)(void *, double, const double *, int),
                    void *ctx, sc_msg *msg);
} sc_model_type;

/** The two-block Burridge-Knopoff model (docs/model.md). */
SC_API extern const sc_model_type sc_model_bk2;
/** The logistic map x -> r x (1 - x). */
SC_API extern const sc_model_type sc_model_logistic;
/** The cubic map x -> x + mu1 + mu2 x - x^3 (cusp normal form). */
SC_API extern const sc_model_type sc_model_cubic;
/** The map x -> -(1 + mu1) x + mu2 x^3 - x^5 (generalized flip). */
SC_API extern const sc_model_type sc_model_gpd;

/** The Henon map (x, y) -> (1 - a x^2 + y, b x). */
SC_API extern const sc_model_type sc_model_henon;
/** The generalized Henon map (x, y) -> (y, alpha - beta x - y^2 + R x y). */
SC_API extern const sc_model_type sc_model_ghenon;

/** The chain of N blocks, open or in a ring (docs/chain.md); its state
 * has N - 1 components. */
SC_API extern const sc_model_type sc_model_chain;
/** The border-collision normal form in two dimensions: (x, y) ->
 * (tau x + y + mu, -delta x), (tau, delta) = (tau_L, delta_L) for x <= 0
 * and (tau_R, delta_R) for x > 0; its border x = 0 is a switching line. */
SC_API extern const sc_model_type sc_model_bcnf;

/** Number of built-in models; sc_model_get(i) lists them. */
SC_API size_t sc_model_count(void);
/** Built-in model @p i, or NULL. */
SC_API const sc_model_type *sc_model_get(size_t i);
/** Built-in model by name, or NULL. */
SC_API const sc_model_type *sc_model_find(const char *name);

#ifdef __cplusplus
}
#endif
#endif
