/**
 * @file io.h
 * @brief Scenes (INI files naming a model, one task and its outputs),
 *        atomic output files, CSV numbers and gnuplot plots.
 *
 * A scene is parsed and validated completely by sc_scene_load() before
 * any work starts: unknown sections or keys, duplicate keys, malformed or
 * non-finite numbers, values outside their range (the ranges of model
 * parameters come from the model's table, models.h), missing required
 * keys and a missing file are refused with one line of the form
 *
 *     FILE:LINE: [section] key = value out of range (valid: (lo, hi])
 *
 * (or `--set section.key=value: ...` for an override).  The keys of the
 * `[task]` section are not fixed here: the caller passes one
 * sc_task_type per task kind, each with its table of keys, so the same
 * table drives validation, help texts and the documentation.
 *
 * Every function here is thread safe on distinct objects.  Nothing here
 * prints; plotting runs the external program `gnuplot` with its output
 * sent to a log file.
 */
#ifndef SLIPCONT_IO_H
#define SLIPCONT_IO_H

#include <stddef.h>
#include <stdio.h>

#include "slipcont/common.h"
#include "slipcont/map.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ */
/* Key tables                                                          */

/** The type of a scene key's value. */
typedef enum {
  SC_KEY_REAL,   /**< a finite number in [lo, hi] (open ends by flags) */
  SC_KEY_INT,    /**< a decimal integer in [lo, hi] */
  SC_KEY_CHOICE, /**< one of the '|'-separated words of `choices` */
  SC_KEY_BOOL,   /**< yes | no */
  SC_KEY_PARAM,  /**< the name of a parameter of the scene's model */
  SC_KEY_TEXT,   /**< any non-empty text (a folder, ...) */
  SC_KEY_STATE,  /**< a state of the model: n finite numbers in [lo, hi]
                      separated by spaces, n the model's dimension (one
                      number for a one-dimensional model, read as REAL) */
} sc_key_type;

/**
 * One key of a scene section.  A key is required when `required` is 1;
 * otherwise `def` is its default as text, or NULL when the default is
 * derived from other keys (the doc says how).
 */
typedef struct {
  const char *name;    /**< "from", "iterations", "seed" */
  sc_key_type type;    /**< how the value is parsed and checked */
  int required;        /**< 1: the scene must give it */
  const char *def;     /**< default as text, or NULL */
  double lo;           /**< lower end of REAL and INT keys */
  double hi;           /**< upper end (may be HUGE_VAL) */
  int lo_open;         /**< REAL: lo itself excluded */
  int hi_open;         /**< REAL: hi itself excluded */
  const char *choices; /**< CHOICE: "up|down|both" */
  const char *doc;     /**< one line */
} sc_key_info;

/**
 * @brief Write the valid values of @p k as text into @p buf: a range
 * "(0, inf)" / "[1, 1000000]", the choices "up|down|both", "yes|no",
 * "a parameter of the model" or "text".
 * @return @p buf.
 */
SC_API char *sc_key_range_text(const sc_key_info *k, char *buf, size_t len);

/**
 * @brief Check the text @p value against @p k (parse, finiteness, range,
 * choices; PARAM keys against @p m's parameter names, any name if @p m
 * is NULL).
 * @return SC_OK, or SC_EINVAL with `key = value ...(valid: ...)` in
 *         @p msg.
 */
SC_API int sc_key_check(const sc_key_info *k, const char *value, const sc_map *m,
                        sc_msg *msg);

/** A loaded, validated scene (opaque; sc_scene_load()). */
typedef struct sc_scene sc_scene;

/**
 * A task kind as far as scenes are concerned: its name (the value of
 * `[task] kind`), a doc line, its keys, and an optional check of the
 * relations between keys (e.g. `keep <= iterations`, `from` inside the
 * range of the swept parameter), called once every key has passed its
 * own check.  `check` reports with sc_scene_fail_key() and returns
 * SC_OK or SC_EINVAL.
 */
typedef struct sc_task_type {
  const char *kind;          /**< "sweep" */
  const char *doc;           /**< one line */
  const sc_key_info *keys;   /**< the [task] keys other than `kind` */
  size_t nkeys;              /**< entries in keys */
  int (*check)(const sc_scene *scene, sc_msg *msg); /**< or NULL */
} sc_task_type;

/* ------------------------------------------------------------------ */
/* Scenes                                                              */

/** How sc_scene_load() reads a scene; zero-initialise unused fields. */
typedef struct {
  /** Overrides "section.key=value", applied as if appended to the file
   * (a key given in the file is replaced, not duplicated). */
  const char *const *sets;
  size_t nsets;               /**< entries in sets */
  const char *out_dir;        /**< replaces [output] dir, or NULL */
  const sc_task_type *const *tasks; /**< the task kinds known */
  size_t ntasks;              /**< entries in tasks */
} sc_scene_options;

/** Longest scene file accepted, in bytes. */
#define SC_SCENE_MAXBYTES (1 << 20)

/** Largest other input file a scene may name (a branch task's
 * points.csv, a chart.csv, a curve.csv), in bytes: the tasks read its
 * head or a few rows, and this bounds the time a search for a row takes. */
#define SC_INPUT_MAXBYTES ((long long)1 << 30)

/**
 * @brief Open a file that a scene names, for reading: the scene itself,
 * a points.csv row, an overlay, a curve of `also`.  Every such file is
 * opened here: without blocking (a FIFO would wait for a writer
 * forever), and refused unless it is a regular file of at most
 * @p max_bytes bytes, so that no input can hang or flood a run.
 * @param what what the file is, for messages ("the scene file").
 * @param max_bytes the largest size accepted (SC_SCENE_MAXBYTES,
 *        SC_INPUT_MAXBYTES).
 * @param f the stream on success, owned by the caller (fclose()).
 * @return SC_OK; SC_EIO when it cannot be opened (the system's reason);
 *         SC_EINVAL for a folder, FIFO, device or socket, or a file
 *         larger than @p max_bytes; SC_ENOMEM.  The message is
 *         `PATH: cannot open WHAT (reason)`, `PATH: not a regular file
 *         (it is a pipe (FIFO); ...)` or `PATH: WHAT is too large (...)`.
 */
SC_API int sc_input_open(const char *path, const char *what,
                         long long max_bytes, FILE **f, sc_msg *msg);

/**
 * @brief Read, parse and validate the scene file @p path, and build the
 * model instance it describes.
 *
 * Sections: `[model]` (`name`, then the model's parameters and options),
 * `[task]` (`kind`, then the keys of that kind), `[accuracy]` (`preset`
 * first, then fields by their sc_accuracy_set() names) and `[output]`
 * (`dir`, `plot`).  The output folder is not touched here; see
 * sc_output_prepare().
 *
 * @param opts overrides and task kinds; may be NULL (no task kinds: every
 *        `[task]` key other than kind is refused).
 * @param out the scene, owned by the caller (sc_scene_free()).
 * @return SC_OK; SC_EINVAL with one line `FILE:LINE: [section] ...` in
 *         @p msg; SC_EIO if the file cannot be read; SC_ENOMEM.
 */
SC_API int sc_scene_load(const char *path, const sc_scene_options *opts,
                         sc_scene **out, sc_msg *msg);

/**
 * @brief As sc_scene_load() for a scene held in memory; @p name is used
 * in messages in place of a file name.
 */
SC_API int sc_scene_parse(const char *name, const char *text,
                          const sc_scene_options *opts, sc_scene **out,
                          sc_msg *msg);

/** @brief Release @p s and its model instance; NULL is accepted. */
SC_API void sc_scene_free(sc_scene *s);

/** The scene's file name (or the name given to sc_scene_parse()). */
SC_API const char *sc_scene_name(const sc_scene *s);
/** The scene's text as read (NUL-terminated). */
SC_API const char *sc_scene_source(const sc_scene *s);
/** The model instance, with every parameter, option and the accuracy of
 * the scene applied; owned by the scene. */
SC_API sc_map *sc_scene_map(const sc_scene *s);
/** The accuracy of the scene (preset, then fields). */
SC_API const sc_accuracy *sc_scene_accuracy(const sc_scene *s);
/** The task kind of the scene (one of the options' tasks). */
SC_API const sc_task_type *sc_scene_task(const sc_scene *s);
/** The output folder: [output] dir, --out, or "out/STEM" where STEM is
 * the scene file's name without folder and extension. */
SC_API const char *sc_scene_output_dir(const sc_scene *s);
/** [output] plot: 1 for yes (the default), 0 for no. */
SC_API int sc_scene_plot(const sc_scene *s);

/**
 * @brief The effective text of a key: the scene's value if given, else
 * the table default; NULL for a key that has neither or does not exist.
 * @param section "model", "task", "accuracy" or "output".
 */
SC_API const char *sc_scene_value(const sc_scene *s, const char *section,
                                  const char *key);

/** `[task]` key as a number (REAL or INT keys); NaN if absent. */
SC_API double sc_scene_real(const sc_scene *s, const char *key);
/** `[task]` key as an integer (INT keys); 0 if absent. */
SC_API long sc_scene_int(const sc_scene *s, const char *key);
/**
 * @brief The state held by [task] key @p key (an SC_KEY_STATE key, or a
 * REAL one): up to @p n numbers into @p x.
 * @return how many numbers the value holds (it was checked to be the
 *         model's dimension), 0 when the key has no value.
 */
SC_API size_t sc_scene_state(const sc_scene *s, const char *key, double *x,
                             size_t n);
/** `[task]` key as text (CHOICE, PARAM, TEXT); NULL if absent. */
SC_API const char *sc_scene_text(const sc_scene *s, const char *key);
/** `[task]` BOOL key: 1 for yes, 0 for no or absent. */
SC_API int sc_scene_flag(const sc_scene *s, const char *key);

/**
 * @brief Where a key was set: "FILE:LINE", "--set section.key=value",
 * "--out" or, for a key left at its default, the file name.
 * @return @p buf.
 */
SC_API char *sc_scene_origin(const sc_scene *s, const char *section,
                             const char *key, char *buf, size_t len);

/**
 * @brief Report a problem with a key, for sc_task_type.check: writes
 * `ORIGIN: [section] ` followed by the formatted text into @p msg.
 * @return SC_EINVAL.
 */
SC_API int sc_scene_fail_key(const sc_scene *s, const char *section,
                             const char *key, sc_msg *msg, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

/**
 * @brief The keys of the fixed sections "output" and "accuracy" (the
 * latter holds `preset` only; its fields are those of common.h).
 * @return the table, @p n set to its length; NULL for other sections.
 */
SC_API const sc_key_info *sc_scene_section_keys(const char *section, size_t *n);

/* ------------------------------------------------------------------ */
/* Output folders and atomic files                                      */

/**
 * @brief Make sure @p dir can receive the outputs.  With @p create 1,
 * create it and its parents (mkdir -p) and prove it writable by creating
 * and removing a probe file; with @p create 0 touch nothing and check
 * that the nearest existing ancestor is a writable folder.
 * @return SC_OK, or SC_EIO with `DIR: reason` in @p msg.
 */
SC_API int sc_output_prepare(const char *dir, int create, sc_msg *msg);

/** A file being written under a temporary name (see sc_file_open()). */
typedef struct sc_file sc_file;

/**
 * @brief Open `dir/name` for writing under a temporary name in the same
 * folder (".name.XXXXXX"); sc_file_commit() renames it into place, so
 * the final name never holds half a file.
 * @return SC_OK, SC_EIO (message names the file and the reason) or
 *         SC_ENOMEM.
 */
SC_API int sc_file_open(const char *dir, const char *name, sc_file **out,
                        sc_msg *msg);

/** The stream to write to. */
SC_API FILE *sc_file_stream(sc_file *f);

/** The temporary path being written ("dir/.name.XXXXXX"), owned by @p f:
 * a program that must end abruptly (a signal) may unlink() it. */
SC_API const char *sc_file_temp_path(const sc_file *f);

/**
 * @brief Flush, sync, close and rename into place; frees @p f in every
 * case (on failure the temporary file is removed).
 * @return SC_OK or SC_EIO naming the file and the reason.
 */
SC_API int sc_file_commit(sc_file *f, sc_msg *msg);

/** @brief Close and remove the temporary file, free @p f; NULL is
 * accepted. */
SC_API void sc_file_abort(sc_file *f);

/**
 * @brief Write @p x as CSV text: `%.17g`, or `nan`, `inf`, `-inf`.
 */
SC_API void sc_csv_double(FILE *f, double x);

/**
 * @brief The CSV column names of a state of @p m: its state name for a
 * one-dimensional model ("d"), the name with the component's index for
 * n > 1 ("d1,d2,..."), each preceded by @p prefix ("" or "start_").
 */
SC_API void sc_csv_state_header(FILE *f, const sc_map *m, const char *prefix);

/** @brief The @p n components of a state as CSV fields (sc_csv_double()
 * joined by commas): one field per column of sc_csv_state_header(). */
SC_API void sc_csv_state(FILE *f, const double *x, size_t n);

/**
 * @brief A list of @p npts states of @p n components as one CSV field:
 * points joined by ';', components of a point by a space ("0.1 0.2;0.3
 * 0.4"); a one-dimensional list is "0.1;0.3".
 */
SC_API void sc_csv_points(FILE *f, const double *pts, size_t npts, size_t n);

/**
 * @brief Multipliers as one CSV field: "a" for a real one, "a+bi" or
 * "a-bi" for a complex one, joined by spaces, in the order given
 * (callers give them by decreasing modulus).
 */
SC_API void sc_csv_multipliers(FILE *f, const double *re, const double *im,
                               size_t n);

/* ------------------------------------------------------------------ */
/* Plots                                                               */

/**
 * @brief Write the common head of a gnuplot script: the pngcairo
 * terminal (1200 x 800), an output file that the variable `outfile`
 * overrides (`gnuplot -e "outfile='x.png'" script.gp`), comma-separated
 * data, a title and axis labels (gnuplot enhanced text: `Y_2` is a
 * subscript).  Texts are quoted for gnuplot.
 */
SC_API void sc_plot_head(FILE *f, const char *png, const char *title,
                         const char *xlabel, const char *ylabel);

/** @brief Write @p text as a gnuplot single-quoted string. */
SC_API void sc_plot_quote(FILE *f, const char *text);

/**
 * @brief A plot title listing the model's parameter values and options,
 * e.g. "alpha = 2.9, beta = 1, phi = 1.25, driver moving" (the first
 * option always, the others when not at their default; the model's doc
 * line when nothing is left to list).
 * @param skip a parameter to leave out (the one on an axis), or NULL.
 * @return @p buf.
 */
SC_API char *sc_plot_title(const sc_map *m, const char *skip, char *buf,
                           size_t len);

/**
 * @brief sc_plot_title() leaving out two parameters (those on the axes
 * of a chart; either may be NULL).  Parameters that do not act with the
 * model's options (sc_param_info.only_with) are left out too.
 * @return @p buf.
 */
SC_API char *sc_plot_title_except(const sc_map *m, const char *skip1,
                                  const char *skip2, char *buf, size_t len);

/**
 * @brief The axis label of a model parameter or state variable: "V" for
 * bk2's v, "Y_2 - Y_1" for bk2's d, the name itself otherwise.
 */
SC_API const char *sc_plot_label(const sc_map *m, const char *name);

/**
 * @brief The colour of a period class in charts (0xRRGGBB): the same
 * table for the chart task and for a chart drawn under a curve, so that
 * the reader can relate one to the other.  @p period >= 1 cycles through
 * 16 colours; 0 (higher or chaos) is black, -1 (undefined) light grey,
 * -2 (not settled) white, -3 (invariant circle, n-dimensional maps) gold.
 */
SC_API unsigned sc_plot_period_rgb(int period);

/**
 * @brief The marker (gnuplot point type) and colour ("#rrggbb") of a
 * special-point label ("LP", "PD", "GR", ...), the same in every figure;
 * @p what (may be NULL) receives the kind's name ("fold", ...).
 * Unknown labels get a neutral grey cross.
 */
SC_API void sc_plot_point_style(const char *label, int *pt, const char **rgb,
                                const char **what);

/**
 * @brief The colour ("#rrggbb") of the k-th of several curves drawn in
 * one figure: 12 colours chosen so that consecutive ones differ in hue
 * and lightness; beyond 12 they repeat (the caller changes the dash).
 */
SC_API const char *sc_plot_curve_rgb(int k);

/**
 * @brief Write `set format AXIS '%.Ng'` when the range [lo, hi] is so
 * narrow for its magnitude that gnuplot's default six digits would print
 * equal tick labels; nothing otherwise.  @p axis is "x" or "y".
 */
SC_API void sc_plot_axis_format(FILE *f, const char *axis, double lo,
                                double hi);

/**
 * @brief The frame of a figure whose text labels slipcont places itself:
 * the picture's size, the plot area's fixed margins, the axes' ranges and
 * scales, and the labels' font.  With it every label's box is known in
 * pixels before gnuplot draws anything, so that no two labels overlap.
 */
typedef struct {
  int width;           /**< picture width, pixels (sc_plot_head: 1200) */
  int height;          /**< picture height, pixels (sc_plot_head: 800) */
  double left;         /**< plot area's left edge, fraction of the width */
  double right;        /**< plot area's right edge, fraction of the width */
  double bottom;       /**< plot area's bottom, fraction of the height */
  double top;          /**< plot area's top, fraction of the height */
  double xmin;         /**< x range's low end, data units (< xmax) */
  double xmax;         /**< x range's high end, data units */
  double ymin;         /**< y range's low end, data units (< ymax) */
  double ymax;         /**< y range's high end, data units */
  int xlog;            /**< 1: logarithmic x axis (its range > 0) */
  int ylog;            /**< 1: logarithmic y axis (its range > 0) */
  double font;         /**< labels' font size, points (Sans) */
  double marker;       /**< half the size of a point's marker, pixels */
} sc_plot_frame;

/** One text label for a point of a figure. */
typedef struct {
  double x;        /**< in: the point's x, data units */
  double y;        /**< in: the point's y, data units */
  char text[160];  /**< in: plain text, "" for a marker that only keeps
                        labels off; out: with merged labels' texts */
  int placed;      /**< out: 1 placed; 0 merged into label `into` (-1 for
                        a marker only); -1 no free place was found (not
                        drawn) */
  int into;        /**< out: the label that carries this one's text */
  int leader;      /**< out: 1 when set off from its point (draw a line) */
  double px;       /**< out: the point's x, pixels from the left */
  double py;       /**< out: the point's y, pixels from the bottom */
  double ax;       /**< out: the text anchor's x (the text's left end),
                        pixels from the left */
  double ay;       /**< out: the text anchor's y (the text's vertical
                        middle), pixels from the bottom */
  double box[4];   /**< out: the text's box x0, y0, x1, y1, pixels */
} sc_plot_spot;

/**
 * @brief The box (x0, y0, x1, y1, pixels, y up) of @p text drawn left
 * justified at the anchor (@p ax, @p ay) in Sans at @p font points on a
 * pngcairo picture: a per-character width estimate measured on that
 * font and rounded up (digits 0.84 em, capitals 1.0 em, `M`/`W`/`m`/`w`
 * 1.2 em, other lower case 0.8 em, `i`/`l`/`j`/`t`/`f`/`r` 0.45 em,
 * spaces and punctuation 0.45 em; height 1.4 em), padded by one pixel.
 */
SC_API void sc_plot_text_box(double font, const char *text, double ax,
                             double ay, double box[4]);

/** @brief 1 if the boxes @p a and @p b (x0, y0, x1, y1) overlap. */
SC_API int sc_plot_boxes_overlap(const double a[4], const double b[4]);

/**
 * @brief Place the labels of @p n points so that no two texts overlap,
 * no text covers a point's marker and every text lies inside the plot
 * area.  Points closer than a marker are given one label, their texts
 * joined ("exact fast, default, precise": a repeated first word is
 * written once; equal texts once).  Each label goes to the first free
 * place among eight directions around its point, at growing distances
 * (a leader line marks the farther ones); a label with no free place is
 * left out (placed = -1) rather than drawn over another.  Greedy in the
 * order given: put the labels that matter most first.
 * @return the number of labels left out.
 */
SC_API size_t sc_plot_place(const sc_plot_frame *fr, sc_plot_spot *spots,
                            size_t n);

/**
 * @brief Write the frame to a script: fixed margins, the ranges and log
 * scales (with sc_plot_axis_format() for narrow linear ranges).
 */
SC_API void sc_plot_frame_write(FILE *f, const sc_plot_frame *fr);

/**
 * @brief Write the placed labels of sc_plot_place() as gnuplot `set
 * label` lines at screen coordinates (each followed by a `# box` comment
 * with its pixel box, which the tests read) and leader lines as arrows;
 * text in @p rgb ("#rrggbb"), not enhanced.
 */
SC_API void sc_plot_labels_write(FILE *f, const sc_plot_frame *fr,
                                 const sc_plot_spot *spots, size_t n,
                                 const char *rgb);

/** @brief 1 if an executable `gnuplot` is on PATH, else 0. */
SC_API int sc_plot_available(void);

/**
 * @brief Run `gnuplot -e "outfile='.PNG.tmp'" SCRIPT` with @p dir as the
 * working folder, without a shell, its output sent to `SCRIPT.log`
 * (removed on success), and rename the picture to @p png when gnuplot
 * succeeded.
 * @return SC_OK; SC_EIO if gnuplot is missing, failed (the message
 *         quotes the last line of its log) or wrote no picture.
 */
SC_API int sc_plot_render(const char *dir, const char *script, const char *png,
                          sc_msg *msg);

#ifdef __cplusplus
}
#endif
#endif
