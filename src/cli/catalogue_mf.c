/* The magnitude-frequency distribution of an event catalogue (docs/chain.md,
 * "Event catalogue"): events counted in bins of log10 of their size (total
 * slip: the seismic moment in the model's units), written to mf.csv with
 * the number of events at least that large, drawn on log axes, and a
 * straight line fitted to log10 count against log10 size where the counts
 * make it meaningful.  Without MPI, the MPI side of the task is here too:
 * one rank. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli/catalogue.h"

/* Bins fitted hold at least this many events: a count's Poisson error is
 * then at most 1/sqrt(10) of it, 0.14 in log10. */
#define MF_FIT_MIN_COUNT 10
/* A slope needs this many such bins, over at least one decade. */
#define MF_FIT_MIN_BINS 4
/* and the line must explain this share of the log counts' variance: a
 * distribution with a bump of large events is not one power law. */
#define MF_FIT_MIN_R2 0.9

/* The least-squares line through the bins with enough events. */
static void mf_fit(sc_cli_mf *mf) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0, xlo = HUGE_VAL,
         xhi = -HUGE_VAL;
  long n = 0;
  for (long b = 0; b < mf->nbins; b++) {
    if (mf->count[b] < MF_FIT_MIN_COUNT) continue;
    double x = mf->lo10 + (b + 0.5) / mf->bpd, y = log10((double)mf->count[b]);
    sx += x, sy += y, sxx += x * x, sxy += x * y, syy += y * y, n++;
    xlo = fmin(xlo, x), xhi = fmax(xhi, x);
  }
  mf->fit_bins = n;
  if (n < MF_FIT_MIN_BINS || xhi - xlo < 1) {
    snprintf(mf->why, sizeof mf->why,
             "%ld bins hold %d events or more (a slope needs %d over a "
             "decade)",
             n, MF_FIT_MIN_COUNT, MF_FIT_MIN_BINS);
    return;
  }
  double vx = sxx - sx * sx / n, vy = syy - sy * sy / n,
         cxy = sxy - sx * sy / n;
  mf->slope = cxy / vx;
  mf->icpt = (sy - mf->slope * sx) / n;
  mf->r2 = vy > 0 ? cxy * cxy / (vx * vy) : 1;
  double rss = fmax(0, vy - mf->slope * cxy);
  mf->slope_se = n > 2 ? sqrt(rss / (n - 2) / vx) : NAN;
  mf->fit = mf->r2 >= MF_FIT_MIN_R2;
  if (!mf->fit)
    snprintf(mf->why, sizeof mf->why,
             "the line through the %ld bins explains %.2f of the variance of "
             "log10 counts (< %.2f): not one power law",
             n, mf->r2, MF_FIT_MIN_R2);
}

int sc_cli_mf_build(const sc_cli_cat_run *runs, long nruns, int bpd,
                    sc_cli_mf *mf, sc_msg *msg) {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  mf->bpd = bpd;
  for (long i = 0; i < nruns; i++)
    for (long k = 0; k < runs[i].n; k++)
      if (runs[i].size[k] > 0) {
        double x = log10(runs[i].size[k]);
        lo = fmin(lo, x), hi = fmax(hi, x);
      }
  if (lo > hi) {
    mf->nbins = 0;
    snprintf(mf->why, sizeof mf->why, "no event");
    return SC_OK;
  }
  mf->lo10 = floor(lo * bpd) / bpd;
  mf->nbins = (long)floor((hi - mf->lo10) * bpd) + 1;
  mf->count = calloc((size_t)mf->nbins, sizeof *mf->count);
  if (!mf->count) return sc_fail(msg, SC_ENOMEM, "catalogue: out of memory");
  for (long i = 0; i < nruns; i++)
    for (long k = 0; k < runs[i].n; k++)
      if (runs[i].size[k] > 0) {
        long b = (long)floor((log10(runs[i].size[k]) - mf->lo10) * bpd);
        if (b < 0) b = 0;
        if (b >= mf->nbins) b = mf->nbins - 1;
        mf->count[b]++;
        mf->total++;
      }
  mf_fit(mf);
  return SC_OK;
}

int sc_cli_mf_write(sc_cli_run *r, const sc_cli_mf *mf) {
  sc_file *csv = NULL;
  int st = sc_cli_open(r, "mf.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  fputs("lo,hi,center,count,cumulative\n", f);
  long above = mf->total;
  for (long b = 0; b < mf->nbins; b++) {
    double e0 = mf->lo10 + (double)b / mf->bpd;
    double v[3] = {pow(10, e0), pow(10, e0 + 1.0 / mf->bpd),
                   pow(10, e0 + 0.5 / mf->bpd)};
    for (int i = 0; i < 3; i++) {
      sc_csv_double(f, v[i]);
      fputc(',', f);
    }
    fprintf(f, "%ld,%ld\n", mf->count[b], above);
    above -= mf->count[b];
  }
  return sc_cli_commit(r, "mf.csv", csv);
}

void sc_cli_mf_summary(FILE *f, const sc_cli_mf *mf) {
  fprintf(f,
          "  magnitude-frequency: %ld events in %ld bins of 1/%d decade "
          "of total slip\n",
          mf->total, mf->nbins, mf->bpd);
  if (mf->fit)
    fprintf(f,
            "    log10 count = %.4f %+.4f log10 slip (standard error "
            "%.2g, R^2 %.3f, %ld bins of %d events or more)\n",
            mf->icpt, mf->slope, mf->slope_se, mf->r2, mf->fit_bins,
            MF_FIT_MIN_COUNT);
  else
    fprintf(f, "    no slope fitted: %s\n", mf->why);
}

int sc_cli_mf_plot(sc_cli_run *r, const sc_cli_mf *mf, const char *title) {
  sc_file *gp = NULL;
  int st =
      sc_cli_plot_begin(r, "mf", title, "total slip (moment)", "events", &gp);
  if (st) return st;
  FILE *f = sc_file_stream(gp);
  fputs("set datafile separator ','\nset logscale xy\nset key top right\n"
        "set format x '10^{%L}'\nset format y '10^{%L}'\n",
        f);
  fputs("plot 'mf.csv' skip 1 using 3:($4 > 0 ? $4 : NaN) with "
        "linespoints pt 7 lc rgb '#1f4e9e' title 'events per bin', \\\n"
        "     '' skip 1 using 1:5 with steps lc rgb '#888888' title 'events "
        "of this size or more'",
        f);
  if (mf->fit)
    fprintf(f,
            ", \\\n     10**(%.17g) * x**(%.17g) with lines dt 2 lw 2 lc "
            "rgb '#d62728' title 'slope %.2f'",
            mf->icpt, mf->slope, mf->slope);
  fputc('\n', f);
  return sc_cli_plot_end(r, "mf", gp);
}

void sc_cli_mf_free(sc_cli_mf *mf) {
  free(mf->count);
  mf->count = NULL;
}

#ifndef SLIPCONT_MPI
int sc_cli_catalogue_mpi_begin(sc_cli_run *r, int *rank, int *size) {
  (void)r;
  *rank = 0, *size = 1;
  return SC_OK;
}
int sc_cli_catalogue_mpi_gather(sc_cli_run *r, sc_cli_cat_run *runs, long nruns,
                                int rank, int size, int status) {
  (void)r, (void)runs, (void)nruns, (void)rank, (void)size;
  return status;
}
void sc_cli_catalogue_mpi_end(void) {}
#endif
