/* The example programs' shared command-line helpers (see cli.h). */
#include "cli.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

const char *const cli_integrators[5] = {"symplectic", "explicit", "verlet",
                                        "rk4", "implicit"};
const char *const cli_layouts[5] = {"auto", "image2d", "buffer", "edges",
                                    "grid"};

/* A run shorter than this shows no progress line. */
#define PROGRESS_AFTER 3.0
/* Seconds between redraws, and the step calls' length on a terminal. */
#define PROGRESS_EVERY 0.25

double cli_now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int cli_frame_digits(int frames)
{
  int w = 1;
  for (int f = frames; f >= 10; f /= 10)
    w++;
  return w > 4 ? w : 4;
}

int cli_fail(const char *prog, const char *what, int rc)
{
  fprintf(stderr, "%s: %s: %s (%s)\n%s\n", prog, what, msocl_strerror(rc),
          msocl_err_name(rc), msocl_last_error());
  return 1;
}

int cli_long_options(const char *prog, const char *optstring, int argc,
                     char **argv, int *help)
{
  *help = 0;
  for (int i = 1; i < argc && strcmp(argv[i], "--"); i++) {
    const char *a = argv[i];
    if (a[0] != '-' || !a[1])
      continue;
    if (a[1] == '-') {
      if (strcmp(a, "--help"))
        return cli_bad(prog, "%s: unknown option", a);
      *help = 1;
      continue;
    }
    /* A cluster of one-letter options: one taking a value ends it, and
     * takes the next argument when nothing of the cluster is left. */
    for (int k = 1; a[k]; k++) {
      const char *o = a[k] != ':' ? strchr(optstring, a[k]) : NULL;
      if (o && o[1] == ':') {
        i += !a[k + 1];
        break;
      }
    }
  }
  return 0;
}

int cli_help(const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  vprintf(fmt, ap);
  va_end(ap);
  return 0;
}

int cli_bad(const char *prog, const char *fmt, ...)
{
  va_list ap;
  fprintf(stderr, "%s: ", prog);
  va_start(ap, fmt);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
  fprintf(stderr, "\n(%s -h lists the options)\n", prog);
  return CLI_USAGE;
}

int cli_bad_option(const char *prog, int c)
{
  if (c == ':')
    return cli_bad(prog, "-%c: needs a value", optopt);
  if (isprint(optopt))
    return cli_bad(prog, "-%c: unknown option", optopt);
  return cli_bad(prog, "unknown option");
}

int cli_no_operands(const char *prog, int optind_, int argc, char **argv)
{
  if (optind_ < argc)
    return cli_bad(prog, "%s: unexpected argument (options only)",
                   argv[optind_]);
  return 0;
}

/* "must be >= lo", "must be from lo to hi", ... into buf. */
static void range(char *buf, size_t size, double lo, int lo_open, double hi,
                  int unbounded)
{
  if (unbounded)
    snprintf(buf, size, "must be %s %g", lo_open ? ">" : ">=", lo);
  else if (lo_open)
    snprintf(buf, size, "must be > %g and <= %g", lo, hi);
  else
    snprintf(buf, size, "must be from %g to %g", lo, hi);
}

int cli_int(const char *prog, int opt, const char *arg, const char *what,
            long lo, long hi, int *out)
{
  char *end, why[64];
  errno = 0;
  long v = strtol(arg, &end, 10);
  if (end == arg || *end || isspace((unsigned char)*arg))
    return cli_bad(prog, "-%c %s: %s must be a whole number", opt, arg,
                   what);
  if (errno == ERANGE || v < lo || v > hi || v < INT_MIN || v > INT_MAX) {
    range(why, sizeof why, (double)lo, 0, (double)hi, hi >= INT_MAX);
    return cli_bad(prog, "-%c %s: %s %s", opt, arg, what, why);
  }
  *out = (int)v;
  return 0;
}

int cli_double(const char *prog, int opt, const char *arg, const char *what,
               double lo, int lo_open, double hi, double *out)
{
  char *end, why[64];
  errno = 0;
  double v = strtod(arg, &end);
  if (end == arg || *end || isspace((unsigned char)*arg) || !isfinite(v) ||
      (errno && fabs(v) > 1.0))
    return cli_bad(prog, "-%c %s: %s must be a finite number", opt, arg,
                   what);
  if (errno) /* underflow: strtod's ERANGE for a subnormal or zero */
    return cli_bad(prog, "-%c %s: %s is too close to 0 for a double", opt,
                   arg, what);
  if ((lo_open ? !(v > lo) : !(v >= lo)) || v > hi) {
    range(why, sizeof why, lo, lo_open, hi, 0);
    return cli_bad(prog, "-%c %s: %s %s", opt, arg, what, why);
  }
  *out = v;
  return 0;
}

int cli_pick(const char *prog, int opt, const char *arg, const char *what,
             const char *const *names, int n, int *out)
{
  char list[256] = "";
  for (int i = 0; i < n; i++) {
    if (!strcmp(arg, names[i])) {
      *out = i;
      return 0;
    }
    size_t len = strlen(list);
    snprintf(list + len, sizeof list - len, "%s%s", i ? ", " : "", names[i]);
  }
  return cli_bad(prog, "-%c %s: %s must be one of %s", opt, arg, what, list);
}

int cli_output(const char *prog, const char *path, int *ply)
{
  const char *dot = strrchr(path, '.');
  const char *ext = dot && !strchr(dot, '/') ? dot + 1 : "";
  if (strcasecmp(ext, "obj") && strcasecmp(ext, "ply"))
    return cli_bad(prog, "-o %s: the name must end in .obj or .ply (the "
                   "format)", path);
  *ply = !strcasecmp(ext, "ply");
  /* "a" neither truncates an old file nor leaves a new one behind when
   * the run fails: the mesh is written only at the end. */
  int existed = access(path, F_OK) == 0;
  FILE *f = fopen(path, "a");
  if (!f)
    return cli_bad(prog, "-o %s: cannot write: %s", path, strerror(errno));
  fclose(f);
  if (!existed)
    remove(path);
  return 0;
}

int cli_write_mesh(const char *path, int ply, int n, const float *xyz,
                   const float *nrm, int ntri, const int *tri)
{
  return ply ? msocl_write_ply(path, n, xyz, nrm, ntri, tri)
             : msocl_write_obj(path, n, xyz, nrm, ntri, tri);
}

void cli_progress_start(cli_progress *p, long long total)
{
  memset(p, 0, sizeof *p);
  p->tty = isatty(STDERR_FILENO);
  p->total = total;
  p->start = cli_now();
}

long long cli_progress_chunk(const cli_progress *p, long long cap)
{
  if (!p->tty || cap <= 1)
    return cap < 1 ? 1 : cap;
  /* From one step, at most doubling: a first slow call cannot make the
   * next one long. */
  double secs = cli_now() - p->start;
  long long k = 2 * p->last_chunk;
  if (p->done > 0 && secs > 0) {
    double quarter = PROGRESS_EVERY * (double)p->done / secs;
    if (quarter < (double)k)
      k = (long long)quarter;
  }
  if (k < 1)
    k = 1;
  return k < cap ? k : cap;
}

void cli_progress_add(cli_progress *p, long long k)
{
  p->done += k;
  p->last_chunk = k;
  if (!p->tty || p->total <= 0)
    return;
  double t = cli_now();
  if (t - p->start < PROGRESS_AFTER || t - p->shown < PROGRESS_EVERY)
    return;
  p->shown = t;
  int w = fprintf(stderr, "\rstep %lld/%lld (%d%%)", p->done, p->total,
                  (int)(100.0 * (double)p->done / (double)p->total));
  if (w > p->width)
    p->width = w;
  fflush(stderr);
}

void cli_progress_end(cli_progress *p)
{
  if (p->width > 0) {
    fprintf(stderr, "\r%*s\r", p->width, "");
    fflush(stderr);
  }
  p->width = 0;
}

int cli_step(msocl_sim *s, cli_progress *p, long long n, int cap,
             double *secs)
{
  int rc = MSOCL_OK;
  long long most = cap > 0 ? cap : INT_MAX;
  while (rc == MSOCL_OK && n > 0) {
    long long k = cli_progress_chunk(p, n < most ? n : most);
    double t0 = cli_now();
    rc = msocl_sim_step(s, (int)k);
    *secs += cli_now() - t0;
    cli_progress_add(p, k);
    n -= k;
  }
  return rc;
}

int cli_frames_parse(const char *prog, const char *usage, int argc,
                     char **argv, struct cli_frames *a, int *done)
{
  static const char options[] = ":n:t:F:d:o:h";
  int rc, opt;
  if ((rc = cli_long_options(prog, options, argc, argv, done)))
    return rc;
  if (*done)
    return cli_help("%s", usage);
  while (!rc && (opt = getopt(argc, argv, options)) != -1) {
    switch (opt) {
    case 'n':
      rc = cli_int(prog, opt, optarg, "grid size", 4, a->n_max, &a->n);
      break;
    case 't':
      rc = cli_double(prog, opt, optarg, "seconds", 0.0, 1, 600.0,
                      &a->seconds);
      break;
    case 'F':
      rc = cli_int(prog, opt, optarg, "frames a second", 1, 240, &a->fps);
      break;
    case 'd': a->spec = optarg; break;
    case 'o': a->dir = optarg; break;
    case 'h': *done = 1; return cli_help("%s", usage);
    default: return cli_bad_option(prog, opt);
    }
  }
  if (!rc)
    rc = cli_no_operands(prog, optind, argc, argv);
  if (!rc && mkdir(a->dir, 0777) != 0 && errno != EEXIST)
    rc = cli_bad(prog, "-o %s: %s", a->dir, strerror(errno));
  struct stat st; /* there already: a folder, not a file */
  if (!rc && (stat(a->dir, &st) != 0 || !S_ISDIR(st.st_mode)))
    rc = cli_bad(prog, "-o %s: not a folder", a->dir);
  return rc;
}

int cli_frames_sim(const char *prog, const msocl_model *m,
                   const struct cli_frames *a, msocl_runtime **rt,
                   msocl_sim **s, int *per_frame, float *dt)
{
  int rc = msocl_safe_dt(m, MSOCL_SYMPLECTIC_EULER, dt);
  if (rc != MSOCL_OK)
    return cli_fail(prog, "stable step", rc);
  *dt *= 0.5f;
  *per_frame = (int)ceil(1.0 / (a->fps * (double)*dt));
  *dt = (float)(1.0 / (a->fps * (double)*per_frame));
  if ((rc = msocl_runtime_create(rt, a->spec)) != MSOCL_OK)
    return cli_fail(prog, "choosing a device", rc);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = *dt;
  if ((rc = msocl_sim_create(s, *rt, m, &o)) != MSOCL_OK)
    return cli_fail(prog, "creating the simulation", rc);
  return 0;
}
