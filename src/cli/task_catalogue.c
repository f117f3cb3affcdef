/* Task `catalogue`: the event catalogue of a chain of blocks (docs/chain.md,
 * "Event catalogue"): the map iterated from d0 for a number of slip
 * events (or a simulated time), every event written with its start time,
 * first block, the blocks that slipped, total slip, energy released,
 * duration and itinerary; the magnitude-frequency distribution of the
 * events' sizes on log axes with its fitted slope.  Several threshold
 * seeds run independently, in parallel (OpenMP; with MPI, dealt to the
 * ranks); the files are the same whatever the threads or ranks. */
#define _POSIX_C_SOURCE 200809L
#include <float.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/catalogue.h"
#include "cli/progress.h"
#include "cli/tasks.h"

static const sc_key_info catalogue_keys[] = {
    {"d0", SC_KEY_STATE, 0, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "initial state (the N - 1 differences d_i = Y_(i+1) - Y_i of the "
     "first global stick phase); default: every d_i = 0"},
    {"events", SC_KEY_INT, 0, "1000", 1, 100000000, 0, 0, NULL,
     "slip events catalogued per seed, after the skipped ones"},
    {"time", SC_KEY_REAL, 0, "0", 0, HUGE_VAL, 0, 1, NULL,
     "stop before the first event that starts after this simulated time "
     "(0: no limit; time 0 is the start of the first event, skipped or not)"},
    {"skip", SC_KEY_INT, 0, "0", 0, 100000000, 0, 0, NULL,
     "events skipped first (the transient from d0)"},
    {"seeds", SC_KEY_TEXT, 0, NULL, 0, 0, 0, 0, NULL,
     "threshold seeds, one independent run each (integers separated by "
     "blanks, with [model] thresholds = random; default: threshold-seed)"},
    {"itineraries", SC_KEY_BOOL, 0, "yes", 0, 0, 0, 0, NULL,
     "write each event's itinerary (no: faster for long chains)"},
    {"bins-per-decade", SC_KEY_INT, 0, "5", 1, 100, 0, 0, NULL,
     "bins of the magnitude-frequency histogram per decade of moment"},
};

/* Most seeds one run takes. */
#define CAT_MAX_SEEDS 4096
/* Events between two checks of the interrupt flag and progress. */
#define CAT_POLL 256

/* The seeds of `seeds` into out (at most CAT_MAX_SEEDS); their number,
 * or -1 with a message naming the bad word. */
static long read_seeds(const char *text, long *out, char *bad, size_t len) {
  long n = 0;
  char w[64];
  const char *q = text;
  size_t k;
  while ((k = sc_cli_next_word(&q, w, sizeof w)) > 0) {
    long s;
    if (k >= sizeof w || sc_parse_long(w, 0, 1L << 53, &s)) {
      snprintf(bad, len, "'%s' is not an integer in [0, 2^53]", w);
      return -1;
    }
    if (n == CAT_MAX_SEEDS) {
      snprintf(bad, len, "more than %d seeds", CAT_MAX_SEEDS);
      return -1;
    }
    out[n++] = s;
  }
  if (n == 0) snprintf(bad, len, "no seed");
  return n ? n : -1;
}

static int catalogue_check(const sc_scene *s, sc_msg *msg) {
  const sc_map *m = sc_scene_map(s);
  if (!sc_map_has_events(m))
    return sc_scene_fail_key(s, "task", "kind", msg,
                             "kind = catalogue: model %s records no slip "
                             "events (valid: chain)",
                             sc_map_type(m)->name);
  int iv = sc_map_param_index(m, "v");
  if (iv >= 0 && !(sc_map_get_param(m, (size_t)iv) > 0))
    return sc_scene_fail_key(s, "model", "v", msg,
                             "kind = catalogue needs v > 0: with the driver "
                             "standing no event follows a global stick "
                             "phase");
  const char *seeds = sc_scene_text(s, "seeds");
  if (seeds) {
    long buf[CAT_MAX_SEEDS];
    char bad[128];
    if (read_seeds(seeds, buf, bad, sizeof bad) < 0)
      return sc_scene_fail_key(s, "task", "seeds", msg, "seeds = '%s': %s",
                               seeds, bad);
    const char *thr = sc_map_get_data(m, "thresholds");
    if (!thr || strcmp(thr, "random") != 0)
      return sc_scene_fail_key(s, "task", "seeds", msg,
                               "seeds draw the thresholds: set [model] "
                               "thresholds = random (with thresholds = %s "
                               "every seed is the same chain)",
                               thr ? thr : "given");
  }
  return SC_OK;
}

typedef sc_cli_cat_run cat_run;

typedef struct {
  long nseeds;
  long *seeds;
  cat_run *runs;
  size_t dim;
  double x0[SC_MAXDIM];
  long events, skip;
  double tmax;
  int itin, bpd;
  int rank, size; /* MPI (1 rank without it) */
  sc_cli_mf mf;   /* the magnitude-frequency distribution */
  long done;      /* events done, all seeds (progress) */
  sc_progress bar;
} cat_job;

static int catalogue_prepare(sc_cli_run *r, void *job) {
  cat_job *j = job;
  const sc_scene *s = r->scene;
  const char *seeds = sc_scene_text(s, "seeds");
  j->seeds = malloc(CAT_MAX_SEEDS * sizeof *j->seeds);
  if (!j->seeds) return sc_fail(r->msg, SC_ENOMEM, "catalogue: out of memory");
  if (seeds) {
    char bad[128];
    j->nseeds = read_seeds(seeds, j->seeds, bad, sizeof bad);
  } else {
    const char *thr = sc_map_get_data(r->map, "thresholds");
    const char *sd = sc_map_get_data(r->map, "threshold-seed");
    long sv = 1;
    if (sd && sd[0]) sc_parse_long(sd, 0, 1L << 53, &sv);
    j->nseeds = 1;
    j->seeds[0] = thr && strcmp(thr, "random") == 0 ? sv : -1;
  }
  j->runs = calloc((size_t)j->nseeds, sizeof *j->runs);
  if (!j->runs) return sc_fail(r->msg, SC_ENOMEM, "catalogue: out of memory");
  for (long i = 0; i < j->nseeds; i++)
    j->runs[i].seed = j->seeds[i];
  j->dim = sc_map_dim(r->map);
  if (sc_scene_state(s, "d0", j->x0, SC_MAXDIM) < j->dim)
    memset(j->x0, 0, sizeof j->x0);
  j->events = sc_scene_int(s, "events");
  j->skip = sc_scene_int(s, "skip");
  j->tmax = sc_scene_real(s, "time");
  j->itin = sc_scene_flag(s, "itineraries");
  j->bpd = (int)sc_scene_int(s, "bins-per-decade");
  j->size = 1;
  return sc_cli_catalogue_mpi_begin(r, &j->rank, &j->size);
}

/* Blocks that slipped as ranges, "3..7 12", into f. */
static void put_blocks(FILE *f, const sc_slip_event *ev) {
  const char *sep = "";
  for (int i = 0; i < ev->nblocks;) {
    if (!ev->slipped[i]) {
      i++;
      continue;
    }
    int k = i;
    while (k + 1 < ev->nblocks && ev->slipped[k + 1])
      k++;
    if (k > i)
      fprintf(f, "%s%d..%d", sep, i + 1, k + 1);
    else
      fprintf(f, "%s%d", sep, i + 1);
    sep = " ";
    i = k + 1;
  }
}

/* The lowest and highest block that slipped. */
static void block_range(const sc_slip_event *ev, int *lo, int *hi) {
  *lo = ev->nblocks, *hi = 1;
  for (int i = 0; i < ev->nblocks; i++)
    if (ev->slipped[i]) {
      if (i + 1 < *lo) *lo = i + 1;
      if (i + 1 > *hi) *hi = i + 1;
    }
}

static void put_row(FILE *f, const cat_run *c, long k, double t,
                    const sc_slip_event *ev, const char *itin) {
  int lo, hi;
  block_range(ev, &lo, &hi);
  if (c->seed >= 0) fprintf(f, "%ld", c->seed);
  fprintf(f, ",%ld,", k);
  sc_csv_double(f, t);
  fprintf(f, ",%d,%d,%d,%d,", ev->first, ev->nslipped, lo, hi);
  put_blocks(f, ev);
  const double v[] = {ev->slip, ev->released, ev->friction, ev->driver,
                      ev->duration};
  for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) {
    fputc(',', f);
    sc_csv_double(f, v[i]);
  }
  fprintf(f, ",%s\n", itin);
}

/* Interrupted, or a progress step: the master thread draws the bar. */
static int poll(cat_job *j, long add) {
  long done;
#pragma omp atomic capture
  done = j->done += add;
  if (omp_get_thread_num() == 0) sc_progress_update(&j->bar, done);
  return sc_cli_interrupted();
}

/* One seed: the map iterated from x0, the events past skip written into
 * c->rows.  Returns a status only for what stops the whole task (out of
 * memory, an interrupt); a map failure ends the seed's run (c->fail). */
static int run_seed(sc_cli_run *r, cat_job *j, cat_run *c, sc_map *m) {
  sc_mapn_value *v = NULL;
  sc_slip_event *ev = malloc(sizeof *ev);
  double *x = malloc(j->dim * sizeof *x);
  FILE *f = open_memstream(&c->rows, &c->nbytes);
  c->size = malloc((size_t)j->events * sizeof *c->size);
  int st = ev && x && f && c->size
               ? sc_mapn_value_alloc(m, SC_EVAL_VALUE, &v, r->msg)
               : sc_fail(r->msg, SC_ENOMEM, "catalogue: out of memory");
  if (!st) memcpy(x, j->x0, j->dim * sizeof *x);
  unsigned flags = j->itin ? SC_EVAL_ITINERARY : SC_EVAL_VALUE;
  double t = 0;
  for (long k = 0; !st && c->n < j->events; k++) {
    if (k % CAT_POLL == CAT_POLL - 1 && poll(j, CAT_POLL))
      st = sc_fail(r->msg, SC_ECALLBACK, "interrupted");
    if (st || (j->tmax > 0 && t > j->tmax)) break;
    c->fail = sc_map_eval_event(m, x, flags, v, ev, &c->em);
    if (c->fail) {
      c->fail_at = k;
      break;
    }
    if (k >= j->skip) {
      put_row(f, c, c->n, t, ev, j->itin ? sc_cli_csv_text(v->itinerary) : "");
      c->size[c->n++] = ev->slip;
      c->t_end = t;
      double res = fabs(ev->released - (ev->friction - ev->driver));
      c->balance = fmax(c->balance, res);
      c->scale = fmax(c->scale, fabs(ev->released) + fabs(ev->friction) +
                                    fabs(ev->driver));
      if (ev->slip > c->top) c->top = ev->slip, c->top_n = ev->nslipped;
    }
    t += ev->duration + ev->stick;
    memcpy(x, v->f, j->dim * sizeof *x);
  }
  if (f && fclose(f) && !st)
    st = sc_fail(r->msg, SC_ENOMEM, "catalogue: out of memory for the rows");
  sc_mapn_value_free(v);
  free(ev);
  free(x);
  return st;
}

/* The seeds of this rank (seed i on rank i mod size), in parallel; each
 * thread with a map of its own, the seed's thresholds drawn in it. */
static int catalogue_compute(sc_cli_run *r, void *job) {
  cat_job *j = job;
  int st = SC_OK;
  sc_progress_start(&j->bar, "events",
                    (j->events + j->skip) * j->nseeds / j->size, 0,
                    j->rank == 0 && sc_progress_wanted(r->quiet));
#pragma omp parallel
  {
    sc_map *m = NULL;
    sc_msg em;
    int mine = sc_map_clone(r->map, &m, &em);
#pragma omp for schedule(dynamic, 1)
    for (long i = j->rank; i < j->nseeds; i += j->size) {
      cat_run *c = &j->runs[i];
      int s = mine;
      if (!s && c->seed >= 0) {
        char w[32];
        snprintf(w, sizeof w, "%ld", c->seed);
        s = sc_map_set_data(m, "threshold-seed", w, &em);
      }
      sc_msg rm;
      sc_cli_run rr = *r;
      rr.msg = &rm;
      if (!s)
        s = run_seed(&rr, j, c, m);
      else
        rm = em;
      if (s) {
#pragma omp critical(catalogue_status)
        if (!st) {
          st = s;
          *r->msg = rm;
        }
      }
    }
    sc_map_free(m);
  }
  sc_progress_finish(&j->bar);
  return sc_cli_catalogue_mpi_gather(r, j->runs, j->nseeds, j->rank, j->size,
                                     st);
}

static int catalogue_write(sc_cli_run *r, void *job) {
  cat_job *j = job;
  sc_file *csv = NULL;
  int st = sc_cli_open(r, "catalogue.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  fputs("seed,event,start,first,count,lo,hi,blocks,slip,released,friction,"
        "driver,duration,itinerary\n",
        f);
  for (long i = 0; i < j->nseeds; i++)
    if (j->runs[i].nbytes) fwrite(j->runs[i].rows, 1, j->runs[i].nbytes, f);
  if ((st = sc_cli_commit(r, "catalogue.csv", csv))) return st;
  st = sc_cli_mf_build(j->runs, j->nseeds, j->bpd, &j->mf, r->msg);
  if (st) return st;
  return sc_cli_mf_write(r, &j->mf);
}

static int catalogue_summary(sc_cli_run *r, void *job, FILE *f) {
  const cat_job *j = job;
  (void)r;
  for (long i = 0; i < j->nseeds; i++) {
    const cat_run *c = &j->runs[i];
    if (c->seed >= 0)
      fprintf(f, "  seed %ld: ", c->seed);
    else
      fputs("  ", f);
    fprintf(f,
            "%ld events up to time %.6g; the largest slips %.6g over %ld "
            "block%s\n",
            c->n, c->t_end, c->top, c->top_n, c->top_n == 1 ? "" : "s");
    fprintf(f,
            "    energy balance: |released - (friction - driver)| <= "
            "%.3g (%.3g of the energies' size)\n",
            c->balance, c->scale > 0 ? c->balance / c->scale : 0);
    if (c->fail)
      fprintf(f, "    stopped: the map is undefined at iterate %ld: %s\n",
              c->fail_at, c->em.text);
  }
  sc_cli_mf_summary(f, &j->mf);
  return SC_OK;
}

static int catalogue_plots(sc_cli_run *r, void *job) {
  const cat_job *j = job;
  char title[512];
  sc_plot_title(r->map, NULL, title, sizeof title);
  int st = sc_cli_mf_plot(r, &j->mf, title);
  if (st) return st;
  sc_file *gp = NULL;
  if ((st =
           sc_cli_plot_begin(r, "catalogue", title, "time (start of the event)",
                             "blocks that slipped", &gp)))
    return st;
  FILE *f = sc_file_stream(gp);
  fputs("# each event a bar over the blocks that slipped (lo to hi), at "
        "its start time,\n# coloured by log10 of its total slip\n"
        "set datafile separator ','\nset cblabel 'log10 total slip'\n"
        "set palette rgbformulae 33,13,10\n",
        f);
  fprintf(f, "set yrange [0.5:%zu.5]\n", sc_map_dim(r->map) + 1);
  fputs("plot 'catalogue.csv' skip 1 using 3:($6 - 0.5):(0):($7 - $6 + 1):"
        "(log10($9)) with vectors nohead lw 1.5 lc palette notitle\n",
        f);
  return sc_cli_plot_end(r, "catalogue", gp);
}

/* A seed whose map failed fails the run, its files written. */
static int catalogue_report(sc_cli_run *r, void *job) {
  const cat_job *j = job;
  for (long i = 0; i < j->nseeds; i++)
    if (j->runs[i].fail)
      return sc_fail(r->msg, j->runs[i].fail,
                     "catalogue: the map is undefined at iterate %ld%s: %s",
                     j->runs[i].fail_at,
                     j->runs[i].seed >= 0 ? " of a seed's run" : "",
                     j->runs[i].em.text);
  return SC_OK;
}

static void catalogue_release(sc_cli_run *r, void *job) {
  cat_job *j = job;
  (void)r;
  for (long i = 0; j->runs && i < j->nseeds; i++) {
    free(j->runs[i].rows);
    free(j->runs[i].size);
  }
  free(j->runs);
  free(j->seeds);
  sc_cli_mf_free(&j->mf);
  sc_cli_catalogue_mpi_end();
}

const sc_cli_task sc_cli_task_catalogue = {
    .type = {.kind = "catalogue",
             .doc = "the slip events of a chain of blocks, one row each, and "
                    "their magnitude-frequency distribution",
             .keys = catalogue_keys,
             .nkeys = sizeof catalogue_keys / sizeof catalogue_keys[0],
             .check = catalogue_check},
    .outputs = "catalogue.csv (seed,event,start,first,count,lo,hi,blocks,"
               "slip,released,friction,driver,duration,itinerary), mf.csv "
               "(lo,hi,count,cumulative), summary.txt, mf.gp/png, "
               "catalogue.gp/png",
    .job_size = sizeof(cat_job),
    .prepare = catalogue_prepare,
    .compute = catalogue_compute,
    .write = catalogue_write,
    .summary = catalogue_summary,
    .plots = catalogue_plots,
    .report = catalogue_report,
    .release = catalogue_release,
};
