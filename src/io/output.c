/* Output folders and atomic files: every result is written under a
 * temporary name in its final folder and renamed into place once
 * complete, so a reader never sees half a file under a result's name. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "slipcont/io.h"

/* Create @p path and its parents (mkdir -p); errno on failure. */
static int mkdir_p(const char *path) {
  size_t n = strlen(path);
  char *buf = malloc(n + 1);
  if (!buf) return ENOMEM;
  memcpy(buf, path, n + 1);
  int err = 0;
  for (size_t i = 1; i <= n && !err; i++) {
    if (buf[i] != '/' && buf[i] != '\0') continue;
    if (buf[i - 1] == '/') continue; /* "a//b" */
    char c = buf[i];
    buf[i] = '\0';
    if (mkdir(buf, 0777) != 0) {
      struct stat sb;
      if (errno != EEXIST) err = errno;
      else if (stat(buf, &sb) != 0) err = errno;
      else if (!S_ISDIR(sb.st_mode)) err = ENOTDIR;
    }
    buf[i] = c;
  }
  free(buf);
  return err;
}

/* The nearest existing ancestor of @p path (or path itself) must be a
 * writable folder; nothing is created. */
static int check_ancestor(const char *path, sc_msg *msg) {
  size_t n = strlen(path);
  char *buf = malloc(n + 2);
  if (!buf) return sc_fail(msg, SC_ENOMEM, "%s: out of memory", path);
  memcpy(buf, path, n + 1);
  int st = SC_OK;
  for (;;) {
    struct stat sb;
    if (stat(buf, &sb) == 0) {
      if (!S_ISDIR(sb.st_mode))
        st = sc_fail(msg, SC_EIO,
                     "%s: cannot create the output folder: %s is not a "
                     "folder",
                     path, buf);
      else if (access(buf, W_OK | X_OK) != 0)
        st = sc_fail(msg, SC_EIO,
                     "%s: cannot create the output folder: %s is not "
                     "writable (%s)",
                     path, buf, strerror(errno));
      break;
    }
    if (errno == ENOTDIR) {
      st = sc_fail(msg, SC_EIO,
                   "%s: cannot create the output folder: a part of the "
                   "path is not a folder",
                   path);
      break;
    }
    if (errno != ENOENT) {
      st = sc_fail(msg, SC_EIO, "%s: cannot create the output folder: %s (%s)",
                   path, buf, strerror(errno));
      break;
    }
    char *slash = strrchr(buf, '/');
    while (slash && slash > buf && slash[1] == '\0') {
      *slash = '\0';
      slash = strrchr(buf, '/');
    }
    if (!slash) {
      memcpy(buf, ".", 2);
    } else if (slash == buf) {
      buf[1] = '\0';
    } else {
      *slash = '\0';
    }
  }
  free(buf);
  return st;
}

/* Room a result file needs inside the folder: its temporary name
 * "/.chart.checkpoint.XXXXXX" and a little more. */
#define SC_OUT_NAME_ROOM 64

/* Refuse, before anything is created, a path the system cannot hold:
 * the whole path with a result file in it, or one part longer than a
 * name may be.  The message says which and the limits. */
static int check_path_length(const char *dir, sc_msg *msg) {
  size_t n = strlen(dir);
  if (n + SC_OUT_NAME_ROOM >= PATH_MAX)
    return sc_fail(msg, SC_EIO,
                   "output folder: path too long (%zu characters; at most "
                   "%d)",
                   n, PATH_MAX - SC_OUT_NAME_ROOM - 1);
  for (const char *p = dir; *p;) {
    size_t k = strcspn(p, "/");
    if (k + SC_OUT_NAME_ROOM > NAME_MAX)
      return sc_fail(msg, SC_EIO,
                     "output folder: a part of the path is too long (%zu "
                     "characters; at most %d)",
                     k, NAME_MAX - SC_OUT_NAME_ROOM);
    p += k + (p[k] == '/');
  }
  return SC_OK;
}

int sc_output_prepare(const char *dir, int create, sc_msg *msg) {
  if (!dir || !dir[0])
    return sc_fail(msg, SC_EIO, "output folder: empty name");
  int lst = check_path_length(dir, msg);
  if (lst) return lst;
  if (!create) return check_ancestor(dir, msg);
  int err = mkdir_p(dir);
  if (err)
    return sc_fail(msg, SC_EIO, "%s: cannot create the output folder (%s)", dir,
                   strerror(err));
  /* Prove it writable: permissions alone do not tell (root, read-only
   * mounts). */
  size_t n = strlen(dir);
  char *probe = malloc(n + 32);
  if (!probe) return sc_fail(msg, SC_ENOMEM, "%s: out of memory", dir);
  snprintf(probe, n + 32, "%s/.slipcont-probe.XXXXXX", dir);
  int fd = mkstemp(probe);
  if (fd < 0) {
    int e = errno;
    free(probe);
    return sc_fail(msg, SC_EIO, "%s: output folder not writable (%s)", dir,
                   strerror(e));
  }
  close(fd);
  unlink(probe);
  free(probe);
  return SC_OK;
}

struct sc_file {
  FILE *f;
  char *tmp;   /* dir/.name.XXXXXX */
  char *final; /* dir/name */
};

int sc_file_open(const char *dir, const char *name, sc_file **out,
                 sc_msg *msg) {
  *out = NULL;
  sc_file *w = calloc(1, sizeof *w);
  size_t n = strlen(dir) + strlen(name) + 16;
  if (!w || !(w->tmp = malloc(n)) || !(w->final = malloc(n))) goto nomem;
  snprintf(w->final, n, "%s/%s", dir, name);
  snprintf(w->tmp, n, "%s/.%s.XXXXXX", dir, name);
  int fd = mkstemp(w->tmp);
  if (fd < 0) {
    int e = errno;
    free(w->tmp);
    free(w->final);
    free(w);
    return sc_fail(msg, SC_EIO, "%s/%s: cannot create (%s)", dir, name,
                   strerror(e));
  }
  /* mkstemp makes the file private; results are ordinary files. */
  fchmod(fd, 0644);
  w->f = fdopen(fd, "w");
  if (!w->f) {
    close(fd);
    unlink(w->tmp);
    goto nomem;
  }
  *out = w;
  return SC_OK;
nomem:
  if (w) {
    free(w->tmp);
    free(w->final);
  }
  free(w);
  return sc_fail(msg, SC_ENOMEM, "%s/%s: out of memory", dir, name);
}

FILE *sc_file_stream(sc_file *f) { return f->f; }

const char *sc_file_temp_path(const sc_file *f) { return f->tmp; }

int sc_file_commit(sc_file *w, sc_msg *msg) {
  int err = 0;
  if (fflush(w->f) != 0 || ferror(w->f)) err = errno ? errno : EIO;
  if (!err && fsync(fileno(w->f)) != 0) err = errno;
  if (fclose(w->f) != 0 && !err) err = errno ? errno : EIO;
  w->f = NULL;
  if (!err && rename(w->tmp, w->final) != 0) err = errno;
  int st = SC_OK;
  if (err) {
    unlink(w->tmp);
    st = sc_fail(msg, SC_EIO, "%s: write failed (%s)", w->final, strerror(err));
  }
  free(w->tmp);
  free(w->final);
  free(w);
  return st;
}

void sc_file_abort(sc_file *w) {
  if (!w) return;
  if (w->f) fclose(w->f);
  unlink(w->tmp);
  free(w->tmp);
  free(w->final);
  free(w);
}

void sc_csv_double(FILE *f, double x) {
  if (isnan(x)) fputs("nan", f);
  else if (isinf(x)) fputs(x > 0 ? "inf" : "-inf", f);
  else fprintf(f, "%.17g", x);
}

void sc_csv_state_header(FILE *f, const sc_map *m, const char *prefix) {
  size_t n = sc_map_dim(m);
  const char *name = sc_map_type(m)->state_name;
  if (n == 1) {
    fprintf(f, "%s%s", prefix, name);
    return;
  }
  for (size_t i = 0; i < n; i++)
    fprintf(f, "%s%s%s%zu", i ? "," : "", prefix, name, i + 1);
}

void sc_csv_state(FILE *f, const double *x, size_t n) {
  for (size_t i = 0; i < n; i++) {
    if (i) fputc(',', f);
    sc_csv_double(f, x[i]);
  }
}

void sc_csv_points(FILE *f, const double *pts, size_t npts, size_t n) {
  for (size_t k = 0; k < npts; k++)
    for (size_t i = 0; i < n; i++) {
      if (k || i) fputc(i ? ' ' : ';', f);
      sc_csv_double(f, pts[k * n + i]);
    }
}

void sc_csv_multipliers(FILE *f, const double *re, const double *im,
                        size_t n) {
  for (size_t i = 0; i < n; i++) {
    if (i) fputc(' ', f);
    sc_csv_double(f, re[i]);
    if (im && im[i] != 0) {
      fputc(im[i] > 0 ? '+' : '-', f);
      sc_csv_double(f, fabs(im[i]));
      fputc('i', f);
    }
  }
}
