/* Private to the bk2 model: its event loop, from the global stick phase
 * (GSP) of displacement d through the slip phases a flow computes to the
 * next GSP, written once for two instances: the general loop on duals
 * (sc_bk2_iterate_ex(), bk2_map.c: every flow, forced codes, the code
 * followed, borders, derivatives, a phase callback) and the value-only
 * loop of the exact flows on plain doubles (bk2.c).
 *
 * A body included once per instance, after defining:
 *   BK2_LOOP_NAME   the function's name
 *   BK2_LOOP_FULL   1 for the general loop's extras, 0 without them (then
 *                   force, code, borders and fn must be NULL)
 *   BK2_LOOP_NUM, BK2_LOOP_PAR, BK2_LOOP_STATE  the number, parameter
 *                   and state types (bk2_flow.h's instance)
 *   BK2_LOOP_VAL(a)           the value of a number
 *   BK2_LOOP_ONSET(P, d, mode, x)   the onset state (bk2_flow.h)
 *   BK2_LOOP_PHASE  one slip phase: the next mode, or a negative status
 *                   (in scope: b, P, mode, fresh, x, msg, the onset's
 *                   threshold gap `gap`; with BK2_LOOP_FULL ev and dur)
 * The general loop also needs, from bk2_map.c: loop_force_start(),
 * switch_border(), gap_border(), code_add(), loop_derivatives() and
 * border_codes().  The body undefines its parameters at its end. */

static int BK2_LOOP_NAME(const bk2_inst *b, const BK2_LOOP_PAR *P,
                         BK2_LOOP_NUM d, unsigned flags,
                         const sc_itin_code *force, sc_itin_code *code,
                         sc_border_list *borders, BK2_LOOP_STATE *x,
                         sc_map_value *out, bk2_phase_fn fn, void *ctx,
                         sc_msg *msg) {
  double dv = BK2_LOOP_VAL(d);
  /* the mode of the onset state, and the mode of the first phase (they
   * differ only at the tie rule of a forced code, loop_force_start()) */
  int onset = BK2_ONSET_MODE(dv, b->dstar), mode = onset;
#if BK2_LOOP_FULL
  const unsigned char *fc = force && force->n > 0 ? force->c : NULL;
  int fpos = 1;
  if (fc && loop_force_start(b, dv, force, &onset, &mode, &fpos, msg))
    return SC_EINVAL;
  sc_itin_code own; /* borders need the code for their own codes */
  if (borders && !code) code = &own;
  bk2_events ev = {0};
  ev.want_code = code != NULL;
  ev.borders = borders;
  if (code) code->n = 1, code->c[0] = (unsigned char)mode;
  size_t border0 = borders ? borders->n : 0;
  if (borders) switch_border(b, P, d, mode, borders);
#else
  (void)force, (void)code, (void)borders, (void)fn, (void)ctx;
#endif
  BK2_LOOP_ONSET(P, d, onset, x);
  int fresh = bk2_fresh_blocks(SC_BK2_STICK, mode), first_mode = mode;
  size_t ilen = 0;
  out->itinerary[0] = '\0';
  for (int n = 0; n < b->acc.max_events; n++) {
    if (flags & SC_EVAL_ITINERARY) bk2_itin_add(out->itinerary, &ilen, mode);
    /* S_j - T_j of the stuck block j at the onset, exactly */
    int at_onset = n == 0 && mode != SC_BK2_SLIP12;
    double gap = at_onset ? (1 + 2 * b->alpha) * (mode == SC_BK2_SLIP1
                                                      ? dv - b->dstar
                                                      : b->dstar - dv)
                          : NAN;
#if BK2_LOOP_FULL
    BK2_LOOP_STATE x0 = *x;
    double dur;
    if (fc) {
      if (fpos + 1 >= force->n)
        return sc_fail(msg, SC_EINVAL,
                       "bk2: the forced itinerary code ends before a global "
                       "stick phase");
      ev.force = fc + fpos;
      fpos += 2;
    }
    ev.phase = n + 1;
    ev.onset = at_onset;
    ev.onset_gap = gap;
#endif
    int next = BK2_LOOP_PHASE;
    if (next < 0) return next;
    out->nphases++;
#if BK2_LOOP_FULL
    if (code && code->n > 0) code_add(code, ev.rec);
    if (borders && mode != SC_BK2_SLIP12 && next == SC_BK2_STICK)
      gap_border(P, mode, x, n + 1, borders);
    if (fn) {
      int st = fn(ctx, mode, &x0, dur);
      if (st) return st;
    }
#endif
    if (next == SC_BK2_STICK) {
      out->f = BK2_LOOP_VAL(x->y2) - BK2_LOOP_VAL(x->y1);
      /* One block slipping alone from a GSP: f(d) = d + c (docs/model.md) */
      out->neutral = out->nphases == 1 && first_mode != SC_BK2_SLIP12;
#if BK2_LOOP_FULL
      loop_derivatives(P, x, out);
      if (borders && code && code->n > 0)
        border_codes(code, border0, &ev, borders);
#endif
      return SC_OK;
    }
    fresh = bk2_fresh_blocks(mode, next);
    mode = next;
  }
  return sc_bk2_slip_cycle(b, msg);
}

#undef BK2_LOOP_NAME
#undef BK2_LOOP_FULL
#undef BK2_LOOP_NUM
#undef BK2_LOOP_PAR
#undef BK2_LOOP_STATE
#undef BK2_LOOP_VAL
#undef BK2_LOOP_ONSET
#undef BK2_LOOP_PHASE
