/* Model instances: parameters, options, accuracy, and the iterates of
 * their one-dimensional map with chain-rule derivatives. */
#include "slipcont/map.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <stddef.h>
#include <string.h>

#include "map_impl.h"

static const sc_model_type *const builtin[] = {
    &sc_model_bk2, &sc_model_logistic, &sc_model_cubic, &sc_model_gpd,
    &sc_model_henon, &sc_model_ghenon, &sc_model_chain, &sc_model_bcnf};

size_t sc_model_count(void) { return sizeof builtin / sizeof builtin[0]; }

const sc_model_type *sc_model_get(size_t i) {
  return i < sc_model_count() ? builtin[i] : NULL;
}

const sc_model_type *sc_model_find(const char *name) {
  for (size_t i = 0; name && i < sc_model_count(); i++)
    if (strcmp(builtin[i]->name, name) == 0) return builtin[i];
  return NULL;
}

/* The model's dimension after a setup: dim_of() where the options set it
 * (the n-dimensional workspace follows it), else the table's. */
static int refresh_dim(sc_map *m) {
  size_t n = m->type->dim_of ? m->type->dim_of(m->inst) : m->type->dim;
  if (n < 1) n = 1;
  if (n == m->dim && m->step) return SC_OK;
  sc_mapn_work_free(m);
  m->dim = n;
  return sc_mapn_work_alloc(m) ? SC_ENOMEM : SC_OK;
}

/* The parameters the model's data gives (models.h data_params), for
 * those not set explicitly. */
static int data_params(sc_map *m, sc_msg *msg) {
  double p[SC_MAXPARAM];
  unsigned char which[SC_MAXPARAM] = {0};
  memcpy(p, m->p, sizeof p);
  int st = m->type->data_params(m->inst, m->opt, p, which, msg);
  for (size_t i = 0; !st && i < m->type->nparam; i++)
    if (which[i] && !m->p_set[i]) m->p[i] = p[i];
  return st;
}

static int setup(sc_map *m, sc_msg *msg) {
  if (m->type->data_params) {
    int st = data_params(m, msg);
    if (st) return st;
  }
  int st = m->type->setup
               ? m->type->setup(m->inst, m->p, m->opt, &m->acc, msg)
               : SC_OK;
  if (st == SC_OK && refresh_dim(m))
    return sc_fail(msg, SC_ENOMEM, "%s: out of memory for dimension %zu",
                   m->type->name, m->dim);
  return st;
}

/* A whole-number option's value as its text (map.h's option getter). */
static void int_option_text(sc_map *m, size_t i) {
  snprintf(m->opt_text[i], sizeof m->opt_text[i], "%d", m->opt[i]);
}

int sc_map_alloc_type(const sc_model_type *type, const sc_accuracy *acc,
                      sc_map **out, sc_msg *msg) {
  *out = NULL;
  if (!type || type->nparam > SC_MAXPARAM || type->noption > SC_MAXOPTION ||
      type->ndata > SC_MAXDATA || (type->ndata && !type->set_data) ||
      type->dim > SC_MAXDIM ||
      (type->dim > 1 || type->dim_of ? !type->eval_n : !type->eval))
    return sc_fail(msg, SC_EINVAL, "sc_map_alloc: malformed model table");
  sc_map *m = calloc(1, sizeof *m);
  if (!m) goto fail;
  m->type = type;
  m->inst = calloc(1, type->inst_size ? type->inst_size : 1);
  if (!m->inst) goto fail;
  for (size_t i = 0; i < type->nparam; i++) m->p[i] = type->params[i].def;
  for (size_t i = 0; i < type->noption; i++)
    if (type->options[i].int_hi > 0) {
      m->opt[i] = atoi(type->options[i].values[0]);
      int_option_text(m, i);
    }
  for (size_t i = 0; i < type->ndata; i++) {
    snprintf(m->data[i], SC_DATA_LEN, "%s", type->data[i].def);
    if (type->set_data(m->inst, i, m->data[i], msg)) {
      sc_map_free(m);
      return sc_fail(msg, SC_EINVAL, "sc_map_alloc: malformed model table "
                                     "(data key %s's default)",
                     type->data[i].name);
    }
  }
  if (acc) {
    int st = sc_accuracy_check(acc, msg);
    if (st) {
      sc_map_free(m);
      return st;
    }
    m->acc = *acc;
  } else {
    sc_accuracy_preset(&m->acc, "default", NULL);
  }
  int st = setup(m, msg);
  if (st) {
    sc_map_free(m);
    return st;
  }
  *out = m;
  return SC_OK;
fail:
  sc_map_free(m);
  return sc_fail(msg, SC_ENOMEM, "sc_map_alloc: out of memory");
}

int sc_map_alloc(const char *model, const sc_accuracy *acc, sc_map **out,
                 sc_msg *msg) {
  const sc_model_type *t = sc_model_find(model);
  if (!t) {
    /* the valid names are the registry's */
    char valid[SC_MSG_LEN / 2] = "";
    size_t used = 0;
    for (size_t i = 0; i < sc_model_count(); i++) {
      int k = snprintf(valid + used, sizeof valid - used, "%s%s",
                       i ? ", " : "", sc_model_get(i)->name);
      if (k < 0 || (size_t)k >= sizeof valid - used) break;
      used += (size_t)k;
    }
    *out = NULL;
    return sc_fail(msg, SC_EINVAL,
                   "sc_map_alloc: unknown model '%s' (valid: %s)",
                   model ? model : "(null)", valid);
  }
  return sc_map_alloc_type(t, acc, out, msg);
}

int sc_map_clone(const sc_map *m, sc_map **out, sc_msg *msg) {
  int st = sc_map_alloc_type(m->type, &m->acc, out, msg);
  if (st) return st;
  memcpy((*out)->p, m->p, sizeof m->p);
  memcpy((*out)->opt, m->opt, sizeof m->opt);
  memcpy((*out)->opt_text, m->opt_text, sizeof m->opt_text);
  memcpy((*out)->p_set, m->p_set, sizeof m->p_set);
  for (size_t i = 0; i < m->type->ndata && !st; i++) {
    memcpy((*out)->data[i], m->data[i], SC_DATA_LEN);
    st = m->type->set_data((*out)->inst, i, m->data[i], msg);
  }
  if (!st) st = setup(*out, msg);
  if (st) {
    sc_map_free(*out);
    *out = NULL;
  }
  return st;
}

void sc_map_free(sc_map *m) {
  if (!m) return;
  if (m->inst && m->type->release) m->type->release(m->inst);
  sc_mapn_work_free(m);
  free(m->inst);
  free(m);
}

const sc_model_type *sc_map_type(const sc_map *m) { return m->type; }
size_t sc_map_nparam(const sc_map *m) { return m->type->nparam; }
const sc_accuracy *sc_map_accuracy(const sc_map *m) { return &m->acc; }
unsigned long sc_map_nevals(const sc_map *m) { return m->nevals; }

int sc_map_param_index(const sc_map *m, const char *name) {
  for (size_t i = 0; name && i < m->type->nparam; i++)
    if (strcmp(m->type->params[i].name, name) == 0) return (int)i;
  return -1;
}

double sc_map_get_param(const sc_map *m, size_t i) {
  return i < m->type->nparam ? m->p[i] : NAN;
}

int sc_param_check(const sc_param_info *pi, double value, sc_msg *msg) {
  int ok = isfinite(value) &&
           (pi->lo_open ? value > pi->lo : value >= pi->lo) &&
           (pi->hi_open ? value < pi->hi : value <= pi->hi);
  if (ok) return SC_OK;
  char hi[32];
  if (isinf(pi->hi)) snprintf(hi, sizeof hi, "inf");
  else snprintf(hi, sizeof hi, "%.17g", pi->hi);
  return sc_fail(msg, SC_EINVAL, "%s = %.17g out of range (valid: %c%.17g, %s%c)",
                 pi->name, value, pi->lo_open ? '(' : '[', pi->lo, hi,
                 pi->hi_open ? ')' : ']');
}

int sc_map_set_param(sc_map *m, size_t i, double value, sc_msg *msg) {
  if (i >= m->type->nparam)
    return sc_fail(msg, SC_EINVAL, "sc_map_set_param: index %zu (model %s has %zu)",
                   i, m->type->name, m->type->nparam);
  int st = sc_param_check(&m->type->params[i], value, msg);
  if (st) return st;
  double old = m->p[i];
  unsigned char was = m->p_set[i];
  m->p[i] = value;
  m->p_set[i] = 1;
  st = setup(m, msg);
  if (st) {
    m->p[i] = old;
    m->p_set[i] = was;
    setup(m, NULL);
  }
  return st;
}

int sc_map_param_is_set(const sc_map *m, size_t i) {
  return i < m->type->nparam && m->p_set[i];
}

static int data_index(const sc_map *m, const char *name) {
  for (size_t i = 0; name && i < m->type->ndata; i++)
    if (strcmp(m->type->data[i].name, name) == 0) return (int)i;
  return -1;
}

int sc_map_set_data(sc_map *m, const char *name, const char *value,
                    sc_msg *msg) {
  int i = data_index(m, name);
  if (i < 0)
    return sc_fail(msg, SC_EINVAL, "unknown data key '%s' for model %s",
                   name ? name : "(null)", m->type->name);
  if (!value || strlen(value) >= SC_DATA_LEN)
    return sc_fail(msg, SC_EINVAL, "%s: value too long (limit %d characters)",
                   name, SC_DATA_LEN - 1);
  char old[SC_DATA_LEN];
  memcpy(old, m->data[i], SC_DATA_LEN);
  int st = m->type->set_data(m->inst, (size_t)i, value, msg);
  if (!st) {
    snprintf(m->data[i], SC_DATA_LEN, "%s", value);
    st = setup(m, msg);
  }
  if (st) {
    memcpy(m->data[i], old, SC_DATA_LEN);
    m->type->set_data(m->inst, (size_t)i, old, NULL);
    setup(m, NULL);
  }
  return st;
}

const char *sc_map_get_data(const sc_map *m, const char *name) {
  int i = data_index(m, name);
  return i < 0 ? NULL : m->data[i];
}

int sc_map_set_param_by_name(sc_map *m, const char *name, double value,
                             sc_msg *msg) {
  int i = sc_map_param_index(m, name);
  if (i < 0) {
    char list[256] = "";
    for (size_t k = 0; k < m->type->nparam; k++) {
      if (k) strncat(list, ", ", sizeof list - strlen(list) - 1);
      strncat(list, m->type->params[k].name, sizeof list - strlen(list) - 1);
    }
    return sc_fail(msg, SC_EINVAL,
                   "unknown parameter '%s' for model %s (valid: %s)",
                   name ? name : "(null)", m->type->name, list);
  }
  return sc_map_set_param(m, (size_t)i, value, msg);
}

char *sc_option_values_text(const sc_option_info *oi, char *buf, size_t len) {
  buf[0] = '\0';
  if (oi->int_hi > 0) {
    snprintf(buf, len, "%d..%d", oi->int_lo, oi->int_hi);
    return buf;
  }
  for (int k = 0; k < SC_MAXVALUES && oi->values[k]; k++) {
    if (k) strncat(buf, "|", len - strlen(buf) - 1);
    strncat(buf, oi->values[k], len - strlen(buf) - 1);
  }
  return buf;
}

static int option_index(const sc_map *m, const char *name) {
  for (size_t i = 0; name && i < m->type->noption; i++)
    if (strcmp(m->type->options[i].name, name) == 0) return (int)i;
  return -1;
}

/* Set the whole-number option @p i from its text (a decimal integer in
 * the option's range); setup() may still refuse it. */
static int set_int_option(sc_map *m, int i, const char *value, sc_msg *msg) {
  const sc_option_info *oi = &m->type->options[i];
  char *end = NULL;
  long v = value ? strtol(value, &end, 10) : 0;
  if (!value || end == value || *end || v < oi->int_lo || v > oi->int_hi)
    return sc_fail(msg, SC_EINVAL,
                   "%s = '%s' is not valid (valid: a whole number in %d..%d)",
                   oi->name, value ? value : "(null)", oi->int_lo, oi->int_hi);
  int old = m->opt[i];
  m->opt[i] = (int)v;
  int st = setup(m, msg);
  if (st) {
    m->opt[i] = old;
    setup(m, NULL);
  }
  int_option_text(m, (size_t)i);
  return st;
}

int sc_map_set_option(sc_map *m, const char *name, const char *value,
                      sc_msg *msg) {
  int i = option_index(m, name);
  if (i < 0)
    return sc_fail(msg, SC_EINVAL, "unknown option '%s' for model %s",
                   name ? name : "(null)", m->type->name);
  const sc_option_info *oi = &m->type->options[i];
  if (oi->int_hi > 0) return set_int_option(m, i, value, msg);
  int v = -1;
  for (int k = 0; value && k < SC_MAXVALUES && oi->values[k]; k++)
    if (strcmp(oi->values[k], value) == 0) v = k;
  if (v < 0) {
    char list[128];
    return sc_fail(msg, SC_EINVAL, "%s = '%s' is not valid (valid: %s)", name,
                   value ? value : "(null)",
                   sc_option_values_text(oi, list, sizeof list));
  }
  int old = m->opt[i];
  m->opt[i] = v;
  int st = setup(m, msg);
  if (st) {
    m->opt[i] = old;
    setup(m, NULL);
  }
  return st;
}

const char *sc_map_get_option(const sc_map *m, const char *name) {
  int i = option_index(m, name);
  if (i < 0) return NULL;
  if (m->type->options[i].int_hi > 0) return m->opt_text[i];
  return m->type->options[i].values[m->opt[i]];
}

int sc_map_set_accuracy(sc_map *m, const sc_accuracy *acc, sc_msg *msg) {
  int st = sc_accuracy_check(acc, msg);
  if (st) return st;
  m->acc = *acc;
  return setup(m, msg);
}

const char *sc_border_label(sc_border_kind k) {
  static const char *t[SC_BORDER_NKINDS] = {"GR", "CS", "SW", "BR", "TT"};
  return (unsigned)k < SC_BORDER_NKINDS ? t[k] : "??";
}

int sc_map_has_borders(const sc_map *m) {
  return m->type->eval_ex || (m->type->eval_n_ex && m->dim == 1);
}

int sc_map_state_borders(sc_map *m, double d, sc_border_list *out,
                         sc_msg *msg) {
  out->n = 0;
  if (!sc_map_has_borders(m)) return SC_OK;
  sc_map_value v;
  int st = sc_map_eval_ex(m, d, SC_EVAL_VALUE, NULL, NULL, out, &v, msg);
  if (st) return st;
  if (out->n > out->cap)
    return sc_fail(msg, SC_ENOMEM,
                   "sc_map_state_borders: %zu borders, room for %zu", out->n,
                   out->cap);
  size_t k = 0;
  for (size_t i = 0; i < out->n; i++)
    if (out->b[i].on_state) out->b[k++] = out->b[i];
  out->n = k;
  return SC_OK;
}

double sc_map_precision(const sc_map *m) {
  return m->type->precision ? m->type->precision(m->inst) : 0;
}

void sc_map_solver_accuracy(const sc_map *m, sc_accuracy *acc) {
  *acc = *sc_map_accuracy(m);
  double prec = sc_map_precision(m);
  acc->newton_atol = fmax(acc->newton_atol, prec);
  acc->newton_ftol = fmax(acc->newton_ftol, prec);
}

/* Zero every field of @p v but the itinerary's bytes past its first (an
 * empty text): the map's inner loop clears a result per iterate, and the
 * 256-byte text is most of it.  Field by field, not by two memsets, which
 * GCC lays out as `rep stos`: their start-up cost was 6% of a chart's
 * time (docs/performance.md, "What was tried"). */
static void clear_value(sc_map_value *v) {
  /* every field is named below: a field added to sc_map_value changes its
   * size and stops the build here until it is cleared too */
  _Static_assert(sizeof(sc_map_value) ==
                     (4 + 3 * SC_MAXPARAM) * sizeof(double) + 2 * sizeof(int) +
                         SC_ITIN_LEN,
                 "clear_value() names every field of sc_map_value");
  v->f = v->dfdd = 0;
  v->neutral = v->nphases = 0;
  v->itinerary[0] = '\0';
  v->d2fdd2 = v->d3fdd3 = 0;
  for (int i = 0; i < SC_MAXPARAM; i++)
    v->dfdp[i] = v->d2fddp[i] = v->d3fdd2p[i] = 0;
}

/* One iterate of a model whose dimension is 1 at its current options but
 * which gives eval_n only (the chain of two blocks), as a one-dimensional
 * value, so every one-dimensional task runs on it. */
/* The borders of a one-component state evaluated through eval_n_ex
 * appended to @p out as sc_border: dm/dd = dm/dx_1, and a border in the
 * state m = s (d - d_on(p)) with d_on = d - m / m_d, d_on_p = -m_p / m_d. */
static void borders_from_n(const sc_bordern_list *l, double d,
                           sc_border_list *out) {
  for (size_t i = 0; i < l->n; i++, out->n++) {
    if (i >= l->cap || out->n >= out->cap) continue; /* counted only */
    const sc_bordern *b = &l->b[i];
    sc_border *o = &out->b[out->n];
    memset(o, 0, sizeof *o);
    o->kind = b->kind;
    o->iterate = b->iterate;
    o->value = b->value;
    o->dd = b->dx[0];
    /* a surface in the state with no normal gives no point d_on */
    o->on_state = b->on_state && b->dx[0] != 0;
    o->d_on = o->on_state ? d - b->value / b->dx[0] : 0;
    for (size_t q = 0; q < SC_MAXPARAM; q++) {
      o->dp[q] = b->dp[q];
      o->d_on_dp[q] = o->on_state ? -b->dp[q] / b->dx[0] : 0;
    }
    o->alt = b->alt;
    memcpy(o->name, b->name, sizeof o->name);
  }
}

/* One iterate of a model whose only map is n-dimensional, with one state
 * component: its value (and with force, code or borders, its code and
 * borders through eval_n_ex) as the one-dimensional interface's. */
static int eval_one_component(sc_map *m, double d, unsigned flags,
                              const sc_itin_code *force, sc_itin_code *code,
                              sc_border_list *borders, sc_map_value *out,
                              sc_msg *msg) {
  sc_mapn_value *v = m->step;
  v->nphases = 0;
  v->itinerary[0] = '\0';
  int st;
  if (m->type->eval_n_ex && (force || code || borders)) {
    sc_bordern_list *l = NULL;
    if (borders) {
      size_t cap = borders->cap ? borders->cap : 1;
      if (m->blist && m->blist->cap < cap) {
        sc_bordern_list_free(m->blist);
        m->blist = NULL;
      }
      if (!m->blist && (st = sc_bordern_list_alloc(m, cap, &m->blist, msg)))
        return st;
      l = m->blist;
      l->n = 0;
    }
    st = m->type->eval_n_ex(m->inst, &d, flags, force, code, l, v, msg);
    if (!st && l) borders_from_n(l, d, borders);
  } else {
    st = m->type->eval_n(m->inst, &d, flags, v, msg);
  }
  if (st) return st;
  out->f = v->f[0];
  out->nphases = v->nphases;
  if (flags & SC_EVAL_ITINERARY)
    memcpy(out->itinerary, v->itinerary, SC_ITIN_LEN);
  if (flags & SC_EVAL_DERIV) {
    out->dfdd = v->J[0];
    for (size_t q = 0; q < m->type->nparam; q++) out->dfdp[q] = v->fp[q];
  }
  if (flags & SC_EVAL_DERIV2) {
    out->d2fdd2 = v->H[0];
    out->d3fdd3 = v->T[0];
    for (size_t q = 0; q < m->type->nparam; q++) out->d2fddp[q] = v->Jp[q];
  }
  return SC_OK;
}

int sc_map_eval_ex(sc_map *m, double d, unsigned flags,
                   const sc_itin_code *force, sc_itin_code *code,
                   sc_border_list *borders, sc_map_value *out, sc_msg *msg) {
  if (!isfinite(d))
    return sc_fail(msg, SC_EINVAL, "sc_map_eval: %s = %g is not finite",
                   m->type->state_name, d);
  if (!m->type->eval && m->dim > 1)
    return sc_fail(msg, SC_EINVAL,
                   "model %s has %zu state components: its map is evaluated "
                   "with sc_map_eval_n()", m->type->name, m->dim);
  clear_value(out);
  if (code) code->n = 0;
  if (flags & SC_EVAL_DERIV2) flags |= SC_EVAL_DERIV;
  m->nevals++;
  int st;
  if (!m->type->eval)
    st = eval_one_component(m, d, flags, force, code, borders, out, msg);
  else if (m->type->eval_ex && (force || code || borders))
    st = m->type->eval_ex(m->inst, d, flags, force, code, borders, out, msg);
  else
    st = m->type->eval(m->inst, d, flags, out, msg);
  if (st) return st;
  if (!isfinite(out->f))
    return sc_fail(msg, SC_ENONFINITE, "sc_map_eval: f(%.17g) is not finite",
                   d);
  return SC_OK;
}

int sc_map_eval(sc_map *m, double d, unsigned flags, sc_map_value *out,
                sc_msg *msg) {
  return sc_map_eval_ex(m, d, flags, NULL, NULL, NULL, out, msg);
}

void sc_map_itin_append(char *dst, const char *s) {
  size_t n = strlen(dst), k = strlen(s);
  if (n + k + 1 <= SC_ITIN_LEN) {
    memcpy(dst + n, s, k + 1);
  } else if (n + 4 <= SC_ITIN_LEN && strcmp(dst + n - 3, "...") != 0) {
    strcpy(dst + SC_ITIN_LEN - 4, "...");
  }
}

/* Second and third derivatives of F_k = f(G, p), G = F_{k-1}(x, p), from
 * G's (in *G, not yet updated) and f's at G (in *f):
 *   H_xx  = f_xx G_x^2 + f_x G_xx,
 *   H_xp  = f_xx G_x G_p + f_xp G_x + f_x G_xp,
 *   H_xxx = f_xxx G_x^3 + 3 f_xx G_x G_xx + f_x G_xxx,
 *   H_xxp = (f_xxx G_p + f_xxp) G_x^2 + 2 f_xx G_x G_xp
 *           + (f_xx G_p + f_xp) G_xx + f_x G_xxp. */
static void chain2(sc_map_value *G, const sc_map_value *f, size_t np) {
  double gx = G->dfdd, gxx = G->d2fdd2;
  for (size_t i = 0; i < np; i++) {
    double gp = G->dfdp[i], gxp = G->d2fddp[i];
    G->d3fdd2p[i] = (f->d3fdd3 * gp + f->d3fdd2p[i]) * gx * gx +
                    2 * f->d2fdd2 * gx * gxp +
                    (f->d2fdd2 * gp + f->d2fddp[i]) * gxx +
                    f->dfdd * G->d3fdd2p[i];
    G->d2fddp[i] = f->d2fdd2 * gx * gp + f->d2fddp[i] * gx + f->dfdd * gxp;
  }
  G->d3fdd3 = f->d3fdd3 * gx * gx * gx + 3 * f->d2fdd2 * gx * gxx +
              f->dfdd * G->d3fdd3;
  G->d2fdd2 = f->d2fdd2 * gx * gx + f->dfdd * gxx;
}

/* f^n(d) = d + c(p) on a neutral orbit (docs/model.md): f' = 1 exactly, so the
 * higher derivatives in d vanish, and so do the mixed ones. */
static void neutral2(sc_map_value *out, size_t np) {
  out->d2fdd2 = out->d3fdd3 = 0;
  for (size_t i = 0; i < np; i++) out->d2fddp[i] = out->d3fdd2p[i] = 0;
}

int sc_map_iterate_ex(sc_map *m, double d, int n, unsigned flags,
                      const sc_itin_code *force, sc_itin_code *codes,
                      sc_border_list *borders, sc_map_value *out,
                      sc_msg *msg) {
  if (n < 1)
    return sc_fail(msg, SC_EINVAL, "sc_map_iterate: n = %d (valid: n >= 1)",
                   n);
  sc_map_value one;
  size_t np = m->type->nparam;
  double x = d;
  /* The borders need the derivatives of the iterates to be chained. */
  if (borders) flags |= SC_EVAL_DERIV;
  memset(out, 0, sizeof *out);
  out->dfdd = 1;
  out->neutral = 1;
  for (int k = 0; k < n; k++) {
    size_t b0 = borders ? borders->n : 0;
    int st = sc_map_eval_ex(m, x, flags, force ? &force[k] : NULL,
                            codes ? &codes[k] : NULL, borders, &one, msg);
    if (st) {
      if (n > 1 && msg) {
        char tail[SC_MSG_LEN];
        snprintf(tail, sizeof tail, "%s", msg->text);
        sc_fail(msg, st, "iterate %d of %d from %.17g: %s", k + 1, n, d, tail);
      }
      return st;
    }
    /* Borders of iterate k are functions of (x_k, p); x_k = F_{k-1}(d, p)
     * with derivatives out->dfdd, out->dfdp so far. */
    for (size_t i = b0; borders && i < borders->n && i < borders->cap; i++) {
      sc_border *bd = &borders->b[i];
      bd->iterate = k;
      double mx = bd->dd;
      for (size_t j = 0; j < np; j++) bd->dp[j] += mx * out->dfdp[j];
      bd->dd = mx * out->dfdd;
    }
    if (flags & SC_EVAL_DERIV2) chain2(out, &one, np);
    if (flags & (SC_EVAL_DERIV | SC_EVAL_DERIV2)) {
      /* Chain rule: F_k = f(F_{k-1}, p). */
      for (size_t i = 0; i < np; i++)
        out->dfdp[i] = one.dfdd * out->dfdp[i] + one.dfdp[i];
      out->dfdd *= one.dfdd;
    }
    if (flags & SC_EVAL_ITINERARY) {
      if (k) sc_map_itin_append(out->itinerary, "|");
      sc_map_itin_append(out->itinerary, one.itinerary);
    }
    out->neutral = out->neutral && one.neutral;
    out->nphases += one.nphases;
    x = one.f;
  }
  out->f = x;
  if (out->neutral && (flags & (SC_EVAL_DERIV | SC_EVAL_DERIV2))) {
    out->dfdd = 1;
    if (flags & SC_EVAL_DERIV2) neutral2(out, np);
  }
  return SC_OK;
}

int sc_map_iterate_points(sc_map *m, const double *x, int n,
                          unsigned flags, const sc_itin_code *force,
                          sc_itin_code *codes, size_t ip, sc_border_list *borders, double *each,
                          sc_map_value *out, sc_msg *msg) {
  if (n < 1 || ip >= m->type->nparam)
    return sc_fail(msg, SC_EINVAL,
                   "sc_map_iterate_points: n = %d, ip = %zu (valid: n >= 1, "
                   "ip < %zu)",
                   n, ip, m->type->nparam);
  sc_map_value one;
  size_t np = m->type->nparam;
  if (borders || each) flags |= SC_EVAL_DERIV;
  flags &= ~(unsigned)SC_EVAL_DERIV2; /* second derivatives: not chained */
  memset(out, 0, sizeof *out);
  out->dfdd = 1;
  out->neutral = 1;
  for (int k = 0; k < n; k++) {
    size_t b0 = borders ? borders->n : 0;
    int st = sc_map_eval_ex(m, x[k], flags, force ? &force[k] : NULL,
                            codes ? &codes[k] : NULL, borders, &one, msg);
    if (st) return st;
    for (size_t i = b0; borders && i < borders->n && i < borders->cap; i++)
      borders->b[i].iterate = k;
    if (each) {
      each[3 * k] = one.f;
      each[3 * k + 1] = one.dfdd;
      each[3 * k + 2] = one.dfdp[ip];
    }
    if (flags & SC_EVAL_DERIV) {
      for (size_t i = 0; i < np; i++)
        out->dfdp[i] = one.dfdd * out->dfdp[i] + one.dfdp[i];
      out->dfdd *= one.dfdd;
    }
    if (flags & SC_EVAL_ITINERARY) {
      if (k) sc_map_itin_append(out->itinerary, "|");
      sc_map_itin_append(out->itinerary, one.itinerary);
    }
    out->neutral = out->neutral && one.neutral;
    out->nphases += one.nphases;
  }
  out->f = one.f;
  if (out->neutral && (flags & SC_EVAL_DERIV)) out->dfdd = 1;
  return SC_OK;
}

int sc_map_iterate(sc_map *m, double d, int n, unsigned flags,
                   sc_map_value *out, sc_msg *msg) {
  return sc_map_iterate_ex(m, d, n, flags, NULL, NULL, NULL, out, msg);
}

int sc_map_trajectory(sc_map *m, double d, int iterations, double dtau,
                      sc_traj_fn fn, void *ctx, sc_msg *msg) {
  if (!m->type->trajectory)
    return sc_fail(msg, SC_EINVAL,
                   "sc_map_trajectory: model %s has no continuous motion",
                   m->type->name);
  if (!(dtau > 0) || !isfinite(dtau) || iterations < 1 || !isfinite(d))
    return sc_fail(msg, SC_EINVAL,
                   "sc_map_trajectory: dtau = %g, iterations = %d, d = %g "
                   "(valid: dtau > 0, iterations >= 1, d finite)",
                   dtau, iterations, d);
  return m->type->trajectory(m->inst, d, iterations, dtau, fn, ctx, msg);
}
