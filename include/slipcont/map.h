/**
 * @file map.h
 * @brief Event maps: a model instance (parameters, options, accuracy),
 *        one-dimensional map evaluation f(d) with exact derivatives and
 *        itineraries, iterates f^n, and continuous trajectories.
 *
 * A `sc_map` is an instance of a model (see models.h): the two-block
 * stick-slip model `bk2`, or a small map with known answers (`logistic`,
 * `cubic`).  It owns its workspace, so one instance must not be used by
 * two threads at once; give each thread its own (sc_map_clone()).  All
 * memory is taken by sc_map_alloc(): evaluation never allocates.
 */
#ifndef SLIPCONT_MAP_H
#define SLIPCONT_MAP_H

#include "slipcont/common.h"
#include "slipcont/models.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A model instance: a model type with its parameter values, options and
 * accuracy (sc_map_new()); opaque. */
typedef struct sc_map sc_map;

/**
 * @brief Create an instance of the model named @p model ("bk2",
 * "logistic", "cubic"), every parameter and option at its default.
 * @param acc accuracy to use (copied); NULL for the "default" preset.
 * @return SC_OK; SC_EINVAL for an unknown model or a bad accuracy;
 *         SC_ENOMEM.
 */
SC_API int sc_map_alloc(const char *model, const sc_accuracy *acc, sc_map **out,
                 sc_msg *msg);

/** @brief As sc_map_alloc() for a model table of the caller's own. */
SC_API int sc_map_alloc_type(const sc_model_type *type, const sc_accuracy *acc,
                      sc_map **out, sc_msg *msg);

/** @brief A new instance with the same model, parameters, options and
 * accuracy, and a workspace of its own (for another thread). */
SC_API int sc_map_clone(const sc_map *m, sc_map **out, sc_msg *msg);

/** @brief Release @p m; NULL is accepted. */
SC_API void sc_map_free(sc_map *m);

/** The model table of @p m. */
SC_API const sc_model_type *sc_map_type(const sc_map *m);

/** Number of parameters; their order is the model table's. */
SC_API size_t sc_map_nparam(const sc_map *m);
/** Index of parameter @p name, or -1. */
SC_API int sc_map_param_index(const sc_map *m, const char *name);
/** Current value of parameter @p i. */
SC_API double sc_map_get_param(const sc_map *m, size_t i);

/**
 * @brief Set parameter @p i, checking its valid range (models.h).
 * @return SC_OK, or SC_EINVAL with `name = value out of range (valid: ...)`
 *         for NaN, infinity or a value outside the range.
 */
SC_API int sc_map_set_param(sc_map *m, size_t i, double value, sc_msg *msg);

/** @brief As sc_map_set_param() by name; unknown names are SC_EINVAL. */
SC_API int sc_map_set_param_by_name(sc_map *m, const char *name, double value,
                             sc_msg *msg);

/**
 * @brief Set a string option ("driver", "friction", "flows" for bk2).
 * @return SC_OK, or SC_EINVAL for an unknown option or value, or a
 *         combination the model refuses (velocity weakening with the
 *         driver frozen).
 */
SC_API int sc_map_set_option(sc_map *m, const char *name, const char *value,
                      sc_msg *msg);
/** Current value of option @p name, or NULL for an unknown option. */
SC_API const char *sc_map_get_option(const sc_map *m, const char *name);

/**
 * @brief Set a data key of the model (sc_data_info: the chain's `betas`,
 * `thresholds`, ...) from its text.  Parameters the data gives (the
 * chain's beta2..beta5) take its values unless sc_map_set_param() set
 * them (before or after).
 * @return SC_OK, or SC_EINVAL for an unknown key, a bad value or data
 *         that does not fit the options (the key is then back to its
 *         previous value); SC_ENOMEM.
 */
SC_API int sc_map_set_data(sc_map *m, const char *name, const char *value,
                           sc_msg *msg);
/** Current text of data key @p name (its default when never set), or
 * NULL for an unknown key. */
SC_API const char *sc_map_get_data(const sc_map *m, const char *name);
/** 1 if parameter @p i was set by sc_map_set_param() (it then overrides
 * what the data gives it), else 0. */
SC_API int sc_map_param_is_set(const sc_map *m, size_t i);

/** @brief Replace the accuracy (checked with sc_accuracy_check()). */
SC_API int sc_map_set_accuracy(sc_map *m, const sc_accuracy *acc, sc_msg *msg);
/** The accuracy in use. */
SC_API const sc_accuracy *sc_map_accuracy(const sc_map *m);


/**
 * @brief Evaluate one iterate f(d).
 * @param flags SC_EVAL_* bits.
 * @return SC_OK; SC_EUNDEF if the map is undefined at @p d (the message
 *         says why, e.g. no return to a global stick phase within
 *         max-events slip phases); SC_EINVAL for non-finite @p d;
 *         SC_ENOCONV if a numerical flow failed.
 */
SC_API int sc_map_eval(sc_map *m, double d, unsigned flags, sc_map_value *out,
                sc_msg *msg);

/**
 * @brief Evaluate f^n(d), n >= 1, with the chain rule for derivatives
 * (df^n/dd is the product of f' along the orbit).
 * @return as sc_map_eval(); the message names the iterate that failed.
 */
SC_API int sc_map_iterate(sc_map *m, double d, int n, unsigned flags,
                   sc_map_value *out, sc_msg *msg);

/** The absolute accuracy of f as computed by @p m's model (0: rounding;
 * numerical flows: about their integration tolerance).  Newton's methods
 * on the map (branches, borders) use it as a floor under their
 * tolerances: asking for more would chase noise. */
SC_API double sc_map_precision(const sc_map *m);

/**
 * @brief The accuracy every Newton method on the map uses: @p m's
 * (sc_map_accuracy()) with newton_atol and newton_ftol raised to its
 * precision (sc_map_precision()), so that shooting, the fixed-point
 * search, the starts and the corrector of a branch all stop at the same
 * noise floor (numerical flows: residuals of ~1e-12 are their rounding,
 * not a failure to converge).
 * @param m    the map
 * @param acc  out: the accuracy (a copy; owned by the caller)
 * Thread safety: reads @p m only.
 */
SC_API void sc_map_solver_accuracy(const sc_map *m, sc_accuracy *acc);

/** 1 if the model of @p m declares borders and forced evaluation
 * (sc_map_eval_ex() does more than sc_map_eval()); 0 for a smooth map. */
SC_API int sc_map_has_borders(const sc_map *m);

/**
 * @brief The model's borders that are surfaces in the state itself
 * (sc_border.on_state: m = +-(d - d_on(p))) at the current parameters,
 * as one iterate from @p d reports them: where the state is a switching
 * point of the map (bk2: d*).  A caller draws or reports them without
 * knowing the model.
 * @param out caller's storage; on return out->n of its entries are the
 *        state borders (none for a smooth map).
 * @return SC_OK; the evaluation's status if the iterate from @p d fails
 *         (try another d); SC_ENOMEM if the iterate has more borders than
 *         out->cap (out->n is then their number).
 */
SC_API int sc_map_state_borders(sc_map *m, double d, sc_border_list *out,
                                sc_msg *msg);

/**
 * @brief One iterate with its itinerary code and borders, optionally
 * forced along a given itinerary.
 *
 * With @p force NULL this is sc_map_eval() that also reports the code of
 * the itinerary followed and the iterate's borders (see models.h).  With
 * a code from an earlier evaluation, the model follows that itinerary
 * whatever the events say: each event of the code is continued past the
 * border where it would stop being the first (the value of f is then that
 * of the smooth extension of the piece, and the borders passed are
 * negative).  A model without borders ignores @p force and reports none.
 * @param code receives the code followed; may be NULL.
 * @param borders receives the borders (appended, see sc_border_list);
 *        may be NULL.  Borders carry exact first derivatives.
 * @return as sc_map_eval(); SC_EINVAL for a code the model cannot follow
 *         (its message says why); SC_EUNDEF where a forced event does not
 *         occur at all (a grazing passed from the side where it fires).
 */
SC_API int sc_map_eval_ex(sc_map *m, double d, unsigned flags,
                   const sc_itin_code *force, sc_itin_code *code,
                   sc_border_list *borders, sc_map_value *out, sc_msg *msg);

/**
 * @brief f^n(d) as sc_map_iterate(), with the codes of the n iterates
 * (@p codes: n entries, or NULL), forced along @p force (n codes, or
 * NULL), and the borders of every iterate (sc_border.iterate says which),
 * their derivatives taken with respect to the d and parameters of f^n by
 * the chain rule.
 */
SC_API int sc_map_iterate_ex(sc_map *m, double d, int n, unsigned flags,
                      const sc_itin_code *force, sc_itin_code *codes,
                      sc_border_list *borders, sc_map_value *out,
                      sc_msg *msg);

/**
 * @brief The iterates of an orbit taken each from its own point (multiple
 * shooting): iterate k of f evaluated at @p x[k] (n points), along
 * @p force[k] (n codes, or NULL), its code into @p codes[k] (or NULL).  @p out is chained as
 * sc_map_iterate_ex()'s (f of the last iterate, the product of the f',
 * f_p by the chain rule, the itinerary), so that at an orbit it holds
 * f^n's values without iterating f^n from x[0]; @p each (3 n entries, or
 * NULL) receives f, f' and df/dp_ip of every iterate; the borders of
 * iterate k (appended) carry derivatives with respect to x[k] and the
 * parameters, not chained.  flags as sc_map_iterate_ex() (SC_EVAL_DERIV
 * with borders or @p each; SC_EVAL_DERIV2 is ignored).
 * @return as sc_map_eval_ex(); SC_EINVAL for n < 1 or ip out of range.
 */
SC_API int sc_map_iterate_points(sc_map *m, const double *x, int n,
                                 unsigned flags, const sc_itin_code *force,
                                 sc_itin_code *codes, size_t ip, sc_border_list *borders,
                                 double *each, sc_map_value *out,
                                 sc_msg *msg);

/* ------------------------------------------------------------------ */
/* Maps in n dimensions                                                */

/** State dimension n >= 1 of @p m's model (1 for bk2, logistic, cubic,
 * gpd; 2 for henon, ghenon). */
SC_API size_t sc_map_dim(const sc_map *m);

/** Name of state component @p i of @p m (i < n): the model's name for it
 * ("x", "y"), "d1", "d2", ... by default, the state name when n = 1. */
SC_API const char *sc_map_state_component(const sc_map *m, size_t i,
                                          char *buf, size_t len);

/**
 * @brief Storage for n-dimensional evaluations of @p m: f always, J and
 * f_p when @p flags has SC_EVAL_DERIV, the tensors H, Jp, T too with
 * SC_EVAL_DERIV2 (one block; release with sc_mapn_value_free()).
 * @return SC_OK; SC_EINVAL for SC_EVAL_DERIV2 when n > SC_DIM_TENSOR;
 *         SC_ENOMEM.
 */
SC_API int sc_mapn_value_alloc(const sc_map *m, unsigned flags,
                               sc_mapn_value **out, sc_msg *msg);
/** @brief Release @p v; NULL is accepted. */
SC_API void sc_mapn_value_free(sc_mapn_value *v);

/**
 * @brief One iterate of @p m at the state @p x (n values), with the
 * derivatives @p flags asks for (SC_EVAL_DERIV: J, f_p; SC_EVAL_DERIV2:
 * also H, Jp, T; SC_EVAL_ITINERARY).  Every model can be evaluated so: a
 * one-dimensional one through its eval() (then J = f', H = f'', ...).
 * @param out sized by sc_mapn_value_alloc() for at least @p flags.
 * @return SC_OK; SC_EINVAL for a non-finite state or storage not sized
 *         for @p flags; SC_ENONFINITE if f is not finite; the model's
 *         status (SC_EUNDEF, ...) otherwise.
 */
SC_API int sc_map_eval_n(sc_map *m, const double *x, unsigned flags,
                         sc_mapn_value *out, sc_msg *msg);

/**
 * @brief The iterate g = f^k at @p x, k >= 1, with the derivatives of g
 * by the chain rule: J_g = J(x_{k-1}) ... J(x_0), and the second and
 * third derivatives of the composition (exact: no differences).  The
 * itineraries of the iterates are joined by '|'.
 * @return as sc_map_eval_n(); the message names the iterate that failed.
 */
SC_API int sc_map_iterate_n(sc_map *m, const double *x, int k, unsigned flags,
                            sc_mapn_value *out, sc_msg *msg);

/** 1 if the model of @p m records slip events (sc_map_eval_event():
 * the chain), else 0. */
SC_API int sc_map_has_events(const sc_map *m);

/**
 * @brief One iterate at @p x as sc_map_eval_n(), with what its slip did
 * block by block (start block, blocks that slipped, each one's slip, the
 * energy released, the work of friction and of the driver, the slip's
 * duration and the global stick phase after it) into @p ev.
 * @param flags SC_EVAL_VALUE or SC_EVAL_ITINERARY (no derivatives).
 * @return as sc_map_eval_n(); SC_EINVAL for a model without slip events
 *         (sc_map_has_events()), for derivatives in @p flags, or storage
 *         of another dimension.  @p ev is filled only on SC_OK.
 * Thread safety: as sc_map_eval_n() (one map per thread).
 */
SC_API int sc_map_eval_event(sc_map *m, const double *x, unsigned flags,
                             sc_mapn_value *out, sc_slip_event *ev,
                             sc_msg *msg);

/* ------------------------------------------------------------------ */
/* Borders of n-dimensional maps                                       */

/** 1 if the model of @p m declares borders of its n-dimensional map
 * (eval_n_ex: sc_map_eval_n_ex() does more than sc_map_eval_n()); 0 for
 * a smooth map and for the one-dimensional models, whose borders are
 * sc_map_has_borders()'s. */
SC_API int sc_map_has_borders_n(const sc_map *m);

/**
 * @brief Storage for @p cap borders of @p m's n-dimensional map: the
 * entries and their gradients (cap x n doubles), one block per array.
 * Memory is cap (sizeof(sc_bordern) + 8 n) bytes: bounded for every n up
 * to SC_MAXDIM.
 * @return SC_OK; SC_EINVAL for cap = 0; SC_ENOMEM.
 */
SC_API int sc_bordern_list_alloc(const sc_map *m, size_t cap,
                                 sc_bordern_list **out, sc_msg *msg);
/** @brief Release @p l; NULL is accepted. */
SC_API void sc_bordern_list_free(sc_bordern_list *l);

/**
 * @brief One iterate of an n-dimensional map with its itinerary code and
 * borders, optionally forced along @p force: the contract of
 * sc_map_eval_ex() for a state of n components.  With @p force, @p code
 * and @p borders all NULL, or for a smooth model, this is
 * sc_map_eval_n().  Borders are appended to @p borders (iterate 0), each
 * with its exact gradient in @p x and the parameters.
 * @return as sc_map_eval_n(); SC_EINVAL for a list of another dimension,
 *         a code the model cannot follow, or a one-dimensional model with
 *         @p force or @p borders (its borders are sc_map_eval_ex()'s).
 */
SC_API int sc_map_eval_n_ex(sc_map *m, const double *x, unsigned flags,
                            const sc_itin_code *force, sc_itin_code *code,
                            sc_bordern_list *borders, sc_mapn_value *out,
                            sc_msg *msg);

/**
 * @brief g = f^k at @p x as sc_map_iterate_n(), with the codes of the k
 * iterates (@p codes: k entries, or NULL), forced along @p force (k
 * codes, or NULL), and the borders of every iterate (sc_bordern.iterate
 * says which), their gradients taken with respect to the x and
 * parameters of f^k by the chain rule: a border m(x_i, p) of iterate i
 * has dm/dx = m_x J(x_{i-1}) ... J(x_0) and dm/dp = m_p + m_x dx_i/dp.
 * Asking for borders implies SC_EVAL_DERIV.
 * @return as sc_map_eval_n_ex(); the message names the iterate that
 *         failed.
 */
SC_API int sc_map_iterate_n_ex(sc_map *m, const double *x, int k,
                               unsigned flags, const sc_itin_code *force,
                               sc_itin_code *codes, sc_bordern_list *borders,
                               sc_mapn_value *out, sc_msg *msg);

/**
 * A continuous trajectory sample: time tau (dimensionless), the model's
 * state (bk2: Y1, Y2, U1, U2) and its mode (the model's own numbering; bk2: 0 stick, 1, 2 one block slips, 3 both).
 * Return non-zero to stop.
 */
typedef int (*sc_traj_fn)(void *ctx, double tau, const double *state,
                          int mode);

/**
 * @brief Follow the continuous motion for @p iterations iterates of the
 * map from the global stick phase with relative displacement @p d,
 * calling @p fn every @p dtau of time and at every event.  Global stick
 * phases last (threshold gap)/V; with V = 0 they are passed at once.
 * @return SC_OK; SC_EINVAL if the model has no continuous motion
 *         (logistic, cubic) or dtau <= 0; SC_EUNDEF as sc_map_eval();
 *         SC_ECALLBACK if @p fn stopped.
 */
SC_API int sc_map_trajectory(sc_map *m, double d, int iterations, double dtau,
                      sc_traj_fn fn, void *ctx, sc_msg *msg);

/**
 * @brief The continuous motion of a model of N blocks whose map has n =
 * N - 1 components (the chain): @p iterations iterates from the state
 * @p x, sampled every @p dtau of each slip phase and of each global stick
 * phase and at each phase's end, tau = 0 at the start of the first slip
 * (as sc_map_trajectory() for bk2).  @p fn gets tau, the state (the N
 * positions relative to the driver, then the N velocities: 2 N values)
 * and the number of blocks slipping (0 in a global stick phase); a
 * non-zero return stops the run with SC_ECALLBACK.
 * @return SC_OK; SC_EINVAL for a model without it, dtau <= 0,
 *         iterations < 1 or a state not finite; the map's status.
 */
SC_API int sc_map_trajectory_n(sc_map *m, const double *x, int iterations,
                               double dtau, sc_traj_fn fn, void *ctx,
                               sc_msg *msg);


/** Map evaluations made by @p m since its creation (a counter). */
SC_API unsigned long sc_map_nevals(const sc_map *m);

#ifdef __cplusplus
}
#endif
#endif
