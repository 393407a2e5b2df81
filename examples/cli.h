/* What the example programs' command lines share: help and error messages,
 * strict numbers and names, the output mesh checked before a run, and a
 * progress line on a terminal. A rejected command line exits CLI_USAGE
 * with one line on stderr naming the option, its value and why. */
#ifndef CLI_H
#define CLI_H

#include <msocl.h>

/* Exit status of a rejected command line. */
#define CLI_USAGE 2

/* In msocl_integrator and msocl_layout order. */
extern const char *const cli_integrators[5];
extern const char *const cli_layouts[5];

/* Seconds on a monotonic clock. */
double cli_now(void);

/* Digits of frame numbers 0..frames (at least 4), so that the names sort
 * in frame order however long the run. */
int cli_frame_digits(int frames);

/* What failed, the library's status and detailed message on stderr;
 * returns 1 (the exit status of a failed run). */
int cli_fail(const char *prog, const char *what, int rc);

/* The long options, which getopt does not know: --help sets *help (else
 * 0); any other "--word" is refused. optstring is getopt's, so that option
 * values are passed over. 0, or CLI_USAGE after the message. */
int cli_long_options(const char *prog, const char *optstring, int argc,
                     char **argv, int *help);

/* The -h answer: the usage text (a printf format) on stdout; returns 0. */
int cli_help(const char *fmt, ...);

/* "prog: message" and a pointer to -h on stderr; returns CLI_USAGE. */
int cli_bad(const char *prog, const char *fmt, ...);

/* getopt's answer c ('?' or, with optstring starting ':', ':') as a
 * message naming optopt; returns CLI_USAGE. */
int cli_bad_option(const char *prog, int c);

/* Arguments left after the options: refused (CLI_USAGE), else 0. */
int cli_no_operands(const char *prog, int optind_, int argc, char **argv);

/* The whole of arg a whole number in [lo, hi] (what: what -opt sets, for
 * the message). 0 and *out set, or CLI_USAGE after the message. */
int cli_int(const char *prog, int opt, const char *arg, const char *what,
            long lo, long hi, int *out);

/* The whole of arg a finite number in [lo, hi], or (lo, hi] when lo_open. */
int cli_double(const char *prog, int opt, const char *arg, const char *what,
               double lo, int lo_open, double hi, double *out);

/* arg one of names[0..n): its index in *out, or CLI_USAGE listing them. */
int cli_pick(const char *prog, int opt, const char *arg, const char *what,
             const char *const *names, int n, int *out);

/* -o: the mesh format by the name's extension (.obj or .ply, any case),
 * and the file opened for writing now, so a run never ends unable to
 * write it (a new file is removed again). 0 and *ply set, or CLI_USAGE. */
int cli_output(const char *prog, const char *path, int *ply);

/* msocl_write_obj or msocl_write_ply, as cli_output chose. */
int cli_write_mesh(const char *path, int ply, int n, const float *xyz,
                   const float *nrm, int ntri, const int *tri);

/* "\rstep DONE/TOTAL (P%)" on stderr when it is a terminal, once a run has
 * taken a few seconds, a few times a second; cleared by cli_progress_end.
 * Off a terminal it prints nothing and changes nothing. */
typedef struct {
  int tty;
  long long done, total, last_chunk;
  double start, shown;
  int width; /* of the line on screen, 0: none */
} cli_progress;

void cli_progress_start(cli_progress *p, long long total);
/* Steps for the next call, at most cap: cap off a terminal; on one, about
 * a quarter second's worth, so the line moves (the results are bitwise
 * those of one call). */
long long cli_progress_chunk(const cli_progress *p, long long cap);
/* Counts k more steps done and redraws when due. */
void cli_progress_add(cli_progress *p, long long k);
void cli_progress_end(cli_progress *p);

/* Steps n in calls of at most cap steps (0: as many as a call takes),
 * adding the calls' time to *secs and counting the steps in p. */
int cli_step(msocl_sim *s, cli_progress *p, long long n, int cap,
             double *secs);

/* The animation examples' command line (msocl-flag, msocl-character):
 * -n grid size in [4, n_max], -t seconds in (0, 600], -F frames a second
 * in [1, 240], -d device spec, -o folder (made if missing), -h the usage
 * text. *a holds the defaults on entry. 0 (with *done set after -h), or
 * CLI_USAGE after the message. */
struct cli_frames {
  int n, n_max, fps;
  double seconds;
  const char *spec, *dir;
};
int cli_frames_parse(const char *prog, const char *usage, int argc,
                     char **argv, struct cli_frames *a, int *done);
/* Their simulation of m on a->spec's device: symplectic Euler at half
 * msocl_safe_dt, shortened to a whole number of steps a frame (*per_frame,
 * *dt). 0, or 1 after cli_fail's message. */
int cli_frames_sim(const char *prog, const msocl_model *m,
                   const struct cli_frames *a, msocl_runtime **rt,
                   msocl_sim **s, int *per_frame, float *dt);

#endif /* CLI_H */
