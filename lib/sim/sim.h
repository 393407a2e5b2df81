/* A simulation is one or more engines (engine.h) and, with several, the
 * plan for exchanging what their neighbours read. Shared by the files that
 * join engines into the public simulation (sim_create.c, sim_step.c,
 * sim_io.c, batch.c), exchange their halos (exchange*.c) and run them on
 * host threads (workers.c). */
#ifndef MSOCL_SIM_H
#define MSOCL_SIM_H

#include "engine.h"

/* The largest number of engines and of exchange buffers a step names. */
#define MSOCL__MAX_PARTS MSOCL__MAX_DEVICES
/* The most slices one buffer's halo is copied in (planes: x, y, z). */
#define MSOCL__X_SLICES 3
/* The most copies one engine queues for one exchange. */
#define MSOCL__X_COPIES (MSOCL__X_SLOTS * MSOCL__MAX_PARTS * MSOCL__X_SLICES)

/* A write an engine will receive into its halos: the buffer (bound when
 * the phase that filled the staging area ended) and the staging area. */
struct msocl__pending {
  cl_mem buf;
  const unsigned char *area;
};

/* What the exchange cost one engine. */
struct msocl__xstat {
  double bytes;        /* written into its halos */
  double copy_seconds; /* device time of its reads and writes */
  double host_seconds; /* host time queuing and reading them */
  double wait_seconds; /* host time waiting for the device */
  double compute_seconds; /* device time of its phases' kernels */
  double hidden_seconds;  /* boundary first: its copies' device time
                             while its interior still ran */
};

/* A job's markers around its phases, and the copies that may run beside
 * its interior, booked with them: its reads, and the next job's writes. */
struct msocl__mark {
  cl_event ev[2];
  cl_event copy[2 * MSOCL__X_COPIES];
  int ncopy;
};

/* Compute spans of a job's markers kept before their device time is read
 * (reading it waits for them). */
#define MSOCL__MARKS 8

/* The exchange plan and its staging (exchange_plan.c, exchange.c). */
struct msocl__exchange {
  /* where the slices of e's points that d reads (halo[d][e]) sit in an
   * area, one after another (exchange_slices.c), and an area's length,
   * in bytes */
  size_t base[MSOCL__MAX_PARTS][MSOCL__MAX_PARTS];
  size_t packed;
  unsigned char *area[2][MSOCL__X_SLOTS]; /* [parity][slot] */
  int parity;                    /* the set the next gather fills */
  void *host, *heap;             /* the areas' memory: pinned or heap */
  cl_mem pinned;
  cl_command_queue map_queue;
  struct msocl__pending pend[MSOCL__MAX_PARTS][MSOCL__X_SLOTS];
  int npend[MSOCL__MAX_PARTS];
  cl_event wev[MSOCL__MAX_PARTS][MSOCL__X_COPIES];
  int nwev[MSOCL__MAX_PARTS];    /* writes queued, not yet settled */
  struct msocl__xstat stat[MSOCL__MAX_PARTS];
  /* steps run split, rolled-back ones too: the stats' steps (a rollback
   * winds the simulation's count back, not what was exchanged) */
  long long steps_run;
  /* Boundary first (tuning.overlap): an engine's range as spans, those
   * other engines read (nbound) first, then the interior; the slices
   * leave through `send` and arrive through `recv` (buffers of `packed`
   * bytes, at the slices' area offsets), copied on a second queue `xq`
   * while the first runs the interior: OpenCL leaves two queues' commands
   * on one buffer object undefined, so they never share one. */
  int overlap;
  int span[MSOCL__MAX_PARTS][2 * MSOCL__MAX_PARTS][2];
  int nbound[MSOCL__MAX_PARTS], nspan[MSOCL__MAX_PARTS];
  cl_command_queue xq[MSOCL__MAX_PARTS];
  cl_mem send[MSOCL__MAX_PARTS][MSOCL__X_SLOTS];
  cl_mem recv[MSOCL__MAX_PARTS][MSOCL__X_SLOTS];
  cl_event rev[MSOCL__MAX_PARTS][MSOCL__X_COPIES];
  int nrev[MSOCL__MAX_PARTS];    /* reads in flight */
  struct msocl__mark mark[MSOCL__MAX_PARTS][MSOCL__MARKS];
  int nmark[MSOCL__MAX_PARTS];   /* compute spans not yet booked */
};

struct msocl__workers;

struct msocl_sim {
  msocl_sim_options o;
  int n, nparts;
  msocl__engine *part[MSOCL__MAX_PARTS];
  /* halo[d][e]: the half-open range of points of engine e that engine d's
   * springs reach (empty: first >= second) */
  int halo[MSOCL__MAX_PARTS][MSOCL__MAX_PARTS][2];
  struct msocl__exchange x;
  struct msocl__workers *workers; /* a host thread per engine */
  int *perm;              /* point k is the model's perm[k]; NULL: same */
  float *stage;           /* 3n floats for reads and writes */
  unsigned char *pinned;  /* writes keep pos.w */
  long long steps;
  int e0_valid;           /* baseline energy of the blow-up check */
  double e0, escale;
  /* The blow-up check counts steps across calls and writes: steps since
   * the state was last saved for it (0: none pending), and the step it was
   * saved at. Writes between two steps: `moved` once the first took the
   * energy of the state it replaced off e0 (the next step adds the written
   * state's and saves it; `wrote` from then on); `blown` when that state
   * was past the bound, at step blown_step with energy blown_total, for the
   * check to report. */
  int since_check;
  long long check_first;
  int moved, wrote, blown;
  long long blown_step;
  double blown_total;
  double total_mass, extent;
  double efloor;          /* the least energy scale, from the springs */
  struct msocl__live *live;     /* the model's count of its simulations */
  struct msocl__controls *ctl;  /* live controls (sim_controls.c), or NULL */
  struct msocl__moving *mov;    /* collider poses (sim_colliders.c), or NULL */
  int call_n, call_j;     /* a moving call's steps, and those done (motion.c) */
  struct msocl__soft *soft;     /* soft pins (sim_soft_pins.c), or NULL */
  int nmesh;              /* mesh colliders (sim_mesh.c) */
  struct msocl__mesh_dev **mesh;
  unsigned char *mesh_on;
};

/* Live controls (sim_controls.c): frees them; whether pins have targets
 * for the next call; the pins at their path's point fp, moving from f0 to
 * f1 in a step (capture: take their start from the state); their targets
 * reached. */
void msocl__controls_free(msocl_sim *s);
int msocl__pins_pending(const msocl_sim *s);
int msocl__pins_place(msocl_sim *s, float fp, float f0, float f1,
                      int capture);
void msocl__pins_done(msocl_sim *s);
/* Soft pins (sim_soft_pins.c): frees them; whether their anchors move
 * over the next call; the anchors at fraction f of that move (1: the end,
 * which ends it). */
void msocl__soft_pins_free(msocl_sim *s);
int msocl__soft_pins_moving(const msocl_sim *s);
void msocl__soft_pins_place(msocl_sim *s, float f);
/* Moving colliders (sim_colliders.c): frees them; whether any has a pose
 * for the next call; the collider table at their paths' point f0, moving
 * to f1 in a step; their poses reached (the table at rest there). */
void msocl__colliders_free(msocl_sim *s);
int msocl__colliders_pending(const msocl_sim *s);
int msocl__colliders_place(msocl_sim *s, float f0, float f1);
int msocl__colliders_done(msocl_sim *s);
/* Colliders added to the running simulation (sim_colliders_add.c): the
 * slot the next one takes (a removed one's, or the next id), after the
 * engine checks of `call`; collider c into that slot, at rest at the pose
 * it was given, enabled, from the next step. */
int msocl__colliders_slot(msocl_sim *s, const char *call, int *slot);
int msocl__colliders_insert(msocl_sim *s, int slot,
                            const struct msocl__collider *c);
/* Mesh colliders (sim_mesh.c): their device copies from the caller's
 * model (refused on a split);
 * freed; whether a call must run step by step for them; before a call of
 * n steps; after each step, from fraction f0 to f1 of the call; after the
 * call. */
int msocl__meshes_create(msocl_sim *s, const msocl_model *m);
void msocl__meshes_free(msocl_sim *s);
int msocl__meshes_active(const msocl_sim *s);
int msocl__meshes_begin(msocl_sim *s, int n);
int msocl__meshes_step(msocl_sim *s, float f0, float f1);
int msocl__meshes_end(msocl_sim *s);
/* A call that moves things over its steps (motion.c): begun before a
 * stepping call of n steps; whether it moves anything; `n` of its steps. */
void msocl__motion_call(msocl_sim *s, int n);
int msocl__motion_moving(const msocl_sim *s);
int msocl__motion_steps(msocl_sim *s, int n);
/* The simulation's number *k of the model's point i (in range). */
int msocl__sim_index(msocl_sim *s, int i, int *k);

/* Halo exchange. plan (exchange_plan.c): the slices, spans, staging and
 * buffers, once the halos are known. exchange.c: gather: the slices of
 * engine d's points that others read, of each buffer in `mask`, into the
 * current staging set (d's queue must be finished), and what d will
 * receive; send: the same queued behind d's work so far, without waiting
 * (boundary first); wait: waits for send's reads, then books them or,
 * given a job's mark, leaves them to it; scatter: queues the writes into
 * d's halos (boundary first, left to the last job's mark while its
 * interior may run); settle: waits for the writes and books their device
 * time; marks: books the compute spans of finished jobs, all but the last
 * `keep`, and how much of their copies ran beside them. */
int msocl__exchange_plan(msocl_sim *s);
void msocl__exchange_free(msocl_sim *s);
int msocl__exchange_gather(msocl_sim *s, int d, unsigned mask);
int msocl__exchange_send(msocl_sim *s, int d, unsigned mask);
int msocl__exchange_wait(msocl_sim *s, int d, struct msocl__mark *m);
int msocl__exchange_scatter(msocl_sim *s, int d);
void msocl__exchange_settle(msocl_sim *s, int d);
void msocl__exchange_marks(msocl_sim *s, int d, int keep);
/* Device seconds from the end of finished command a to that of b. */
double msocl__event_span(cl_event a, cl_event b);

/* Host threads (workers.c): run calls fn(ctx, i) for i < n, i on thread
 * i (0: the caller), and returns the first failure with its message. */
int msocl__workers_create(struct msocl__workers **out, int n);
int msocl__workers_run(struct msocl__workers *w, int (*fn)(void *ctx, int i),
                       void *ctx);
void msocl__workers_destroy(struct msocl__workers *w);

/* Energy of the whole simulation. */
int msocl__sim_energy(msocl_sim *s, msocl_energy *e);
/* Stepping pieces (sim_step.c) for batches of simulations. Checked, the
 * steps are counted across calls: room is how many may run before the
 * next check is due; begin saves the state where a checked stretch of
 * check_every steps starts, then queues `batch` (at most room) steps; end
 * checks the energy once the stretch is whole (restoring the saved state
 * past the bound). Unchecked, just queue; finish waits for the devices. */
int msocl__batch_room(const msocl_sim *s);
int msocl__batch_begin(msocl_sim *s, int batch);
int msocl__batch_end(msocl_sim *s);
/* The blow-up check's measures (check.c): the bound on the energy; the
 * baseline taken (or moved, after writes); the state saved (to_backup) or
 * restored; and, before a write replaces the state, the check's part. */
double msocl__check_bound(const msocl_sim *s);
int msocl__check_baseline(msocl_sim *s);
int msocl__check_backup(msocl_sim *s, int to_backup);
int msocl__check_write(msocl_sim *s);
int msocl__sim_steps(msocl_sim *s, int n);
int msocl__sim_finish(msocl_sim *s);
/* Ends a stepping call of n steps that returns rc: MSOCL_ERR_NO_CONVERGENCE
 * with its message if rc is MSOCL_OK and a step's CG missed the tolerance;
 * clears the record either way. */
int msocl__cg_report(msocl_sim *s, int rc, int n);

#endif
