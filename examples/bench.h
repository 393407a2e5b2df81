/* What the parts of msocl-bench share: options, the tablecloth scene's
 * constants, one CSV row per run, timing and progress. */
#ifndef BENCH_H
#define BENCH_H

#include <msocl.h>

#include <stdio.h>

/* The paper's scene (examples/tablecloth.c): a 1 m square cloth of 0.5 kg,
 * 5 cm above a round table of radius 0.35 m, stretch / shear / bend springs
 * of 50 / 10 / 10 N/m, viscous damping 0.5 x the point mass. */
#define TC_MASS 0.5f
#define TC_HEIGHT 0.05f
#define TC_RADIUS 0.35f
#define TC_FRICTION 0.3f
#define TC_K_STRETCH 50.0f
#define TC_K_SHEAR 10.0f
#define TC_K_BEND 10.0f
#define TC_VISCOUS_PER_MASS 0.5f
#define TC_GRAVITY (-9.81f)

#define BENCH_MAX_LIST 32

struct bench_opts {
  const char *spec;               /* -d: device spec, NULL = MSOCL_DEVICE */
  int grids[BENCH_MAX_LIST], ngrids; /* -g */
  int steps;                      /* -s */
  int big_steps;                  /* --big-steps: grids above 128 */
  int repeat;                     /* --repeat: timed runs, best counts */
  int max_grid;                   /* --max-grid, 0 = none */
  int layouts[4], nlayouts;       /* -l (msocl_layout values) */
  int integrators[5], nintegrators; /* -i */
  int maths[2], nmaths;           /* -m */
  double sim_time;                /* -T: simulated seconds (precision) */
  int levels;                     /* --levels: dt values (precision) */
  double from;                    /* --from: largest dt / stable step */
  int copy_mib;                   /* --copy-mib: copy buffer size */
  int quick;                      /* --quick */
  int fused;                      /* --fused: also each gather layout's
                                     one-kernel step (table1) */
  int values;                     /* --values: also BUFFER with classes
                                     and with values forced (table1) */
  int expert;                     /* --expert: also expert C (table1) */
  int sweep_steps;                /* --sweep-steps: GRID's steps a launch
                                     (tuning.sweep_steps; 0 AUTO) */
  int sweeps[BENCH_MAX_LIST], nsweeps; /* --sweeps (strain) */
  const char *csv;                /* --csv */
  int no_serial;                  /* --no-serial: table1 without serial C */
  const char *save, *against;     /* --save, --against FILE (verify) */
};

/* One run: a CSV row. NaN numbers are written as empty fields. */
struct bench_row {
  char device[128];
  const char *layout, *integrator, *math;
  int grid;
  long long points; /* 0: grid x grid (a cloth) */
  double dt;
  long long steps;
  double seconds, steps_per_s, vertex_steps_per_s;
  double bytes_per_vertex_step, effective_gbps, copy_gbps, fraction;
  double error;
  const char *status;
  const char *strain; /* the strain limit (strain mode; "" elsewhere) */
  int sweeps;         /* its sweeps a step (0: none) */
};

extern const char *const bench_integrator_names[5];

/* Empty row: every number NaN, names "". */
void bench_row_init(struct bench_row *r);
/* Rates from grid, steps and seconds; GB/s and the fraction from the bytes
 * and copy bandwidth when both are known. */
void bench_row_rates(struct bench_row *r);
void bench_csv_header(FILE *f);
void bench_csv_row(FILE *f, const struct bench_row *r);
/* The device's name as a CSV field: commas and quotes replaced. */
void bench_device_label(char *out, size_t size, const msocl_device_info *d);

double bench_now(void);
/* The CPU time of the whole process (every thread, the device's workers on
 * a CPU device included): over a wall time, the cores kept busy. */
double bench_cpu_now(void);
/* "\r[i/n] text" on stderr when it is a terminal; nothing otherwise.
 * i = 0 clears the line. */
void bench_progress(int i, int n, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* The tablecloth's cloth: n x n points of TC_MASS in all, its springs,
 * placed at origin along u and v (1 m each); the rest as
 * msocl_cloth_desc_init leaves it. */
void bench_cloth(msocl_cloth_desc *d, int n, const float origin[3],
                 const float u[3], const float v[3]);
/* The two scenes the modes share, NULL after saying why: the tablecloth
 * (TC_*) with *dt half its symplectic stable step (table1), and a 1 m
 * square of n x n points (0.5 kg, the tablecloth's springs, dashpots)
 * flat in the x-z plane, held at the two corners of one edge
 * (precision, verify). */
msocl_model *bench_tablecloth(int n, float *dt);
msocl_model *bench_hanging_cloth(int n);
/* Prints the library's error and returns 1. */
int bench_fail(const char *what, int rc);
/* The runtime o->spec names, and its first device's info: 0, or 1 after
 * saying why. */
int bench_open(const struct bench_opts *o, msocl_runtime **rt,
               msocl_device_info *info);
/* r->device: the label of rt's first device. */
void bench_row_device(struct bench_row *r, msocl_runtime *rt);
/* The largest |a[i] - b[i]| over n floats (NaN where either is). */
double bench_max_diff(const float *a, const float *b, size_t n);
/* Times model m under options so on rt: a warm-up step, then the best of
 * o->repeat runs of o->steps into r->seconds; the final positions into pos
 * (3 r->points floats), their largest difference from ref (when not NULL)
 * into r->error. Returns the library's status. */
int bench_time_sim(const struct bench_opts *o, msocl_runtime *rt,
                   const msocl_model *m, const msocl_sim_options *so,
                   struct bench_row *r, float *pos, const float *ref);

int bench_table1(const struct bench_opts *o, FILE *csv);
int bench_precision(const struct bench_opts *o, FILE *csv);
int bench_lattice(const struct bench_opts *o, FILE *csv);
int bench_strain(const struct bench_opts *o, FILE *csv);
int bench_colliders(const struct bench_opts *o, FILE *csv);
int bench_meshes(const struct bench_opts *o, FILE *csv);
int bench_wind(const struct bench_opts *o, FILE *csv);
int bench_verify(const struct bench_opts *o, FILE *csv);
/* msocl-bench meshcollider (bench_mesh_collider.c). */
int bench_mesh_collider(const struct bench_opts *o, FILE *csv);

/* Device-to-device copy bandwidth (bytes read + written per second / 1e9)
 * of the device `info` names, through clEnqueueCopyBuffer on a context of
 * its own; buffers of at most max_bytes. */
int bench_copy_gbps(const msocl_device_info *info, size_t max_bytes,
                    double *gbps);

/* The paper's Algorithm 1 as plain serial C in single precision: the
 * tablecloth of n x n points, stepped with dt (bench_serial.c). */
typedef struct bench_serial bench_serial;
int bench_serial_create(bench_serial **s, int n, float dt);
void bench_serial_step(bench_serial *s, int steps);
/* 3 floats a point, the msocl model's point order. */
const float *bench_serial_positions(const bench_serial *s);
void bench_serial_destroy(bench_serial *s);

/* Rest lengths of the n x n tablecloth's stretch, shear and bend springs,
 * as lib/model/model_cloth.c rounds them (bench_serial.c). */
void bench_tc_rests(int n, float rest[3]);

/* The tablecloth as expert C: struct of arrays, padded rows, both passes
 * in one sweep, OpenMP over rows (bench_expert.c); bitwise GRID in PRECISE
 * math. xyz: the model's initial positions, 3 floats a point. */
typedef struct bench_expert bench_expert;
int bench_expert_create(bench_expert **e, int n, float dt, const float *xyz);
void bench_expert_step(bench_expert *e, int steps);
/* 3 floats a point, the msocl model's point order. */
const float *bench_expert_positions(const bench_expert *e);
void bench_expert_destroy(bench_expert *e);
/* The threads a step runs on (1 without OpenMP). */
int bench_expert_threads(void);

#endif /* BENCH_H */
