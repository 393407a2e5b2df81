/* One runtime shared by several threads: each creates, steps and destroys
 * simulations of its own at the same time as the others, and gets bitwise
 * the result of a run on a thread alone; the program cache holds one
 * program per set of build options however many threads asked for it. */
#include "internal.h"
#include "scenes.h"

#include <check.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#define N 12
#define STEPS 40
#define THREADS 4
#define ROUNDS 2

/* Layouts and options whose kernels build with different options, so the
 * threads build several programs at once as well as the same one. */
static const struct config {
  msocl_layout layout;
  msocl_choice fused;
} configs[] = {
    {MSOCL_LAYOUT_GRID, MSOCL_OFF},
    {MSOCL_LAYOUT_IMAGE2D, MSOCL_OFF},
    {MSOCL_LAYOUT_BUFFER, MSOCL_OFF},
    {MSOCL_LAYOUT_BUFFER, MSOCL_ON},
};
#define NCONFIGS (int)(sizeof configs / sizeof configs[0])

static float expected[NCONFIGS][3 * N * N];

/* Positions after STEPS steps of the tablecloth under configs[c]. */
static int run(msocl_runtime *rt, int c, float *xyz)
{
  msocl_model *m = scene_tablecloth(N);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = scene_tablecloth_dt(N);
  o.tuning.layout = configs[c].layout;
  o.tuning.fused = configs[c].fused;
  msocl_sim *s = NULL;
  int rc = m ? msocl_sim_create(&s, rt, m, &o) : MSOCL_ERR_NO_MEMORY;
  msocl_model_destroy(m);
  if (rc == MSOCL_OK)
    rc = msocl_sim_step(s, STEPS);
  if (rc == MSOCL_OK)
    rc = msocl_sim_read_positions(s, xyz);
  msocl_sim_destroy(s);
  return rc;
}

struct job {
  pthread_t th;
  int id;
  msocl_runtime *rt;
  int rc, mismatch;
  char msg[256];
};

/* Every config in a rotated order, ROUNDS times, on the shared runtime. */
static void *worker(void *arg)
{
  struct job *j = arg;
  static float got[THREADS][3 * N * N];
  for (int r = 0; r < ROUNDS; r++)
    for (int k = 0; k < NCONFIGS; k++) {
      int c = (j->id + k) % NCONFIGS;
      j->rc = run(j->rt, c, got[j->id]);
      if (j->rc != MSOCL_OK) {
        strncpy(j->msg, msocl_last_error(), sizeof j->msg - 1);
        return NULL;
      }
      if (memcmp(got[j->id], expected[c], sizeof expected[c]) != 0)
        j->mismatch++;
    }
  return NULL;
}

START_TEST(threads_share_a_runtime)
{
  msocl_runtime *rt = NULL;
  ck_assert_int_eq(msocl_runtime_create(&rt, "cpu"), MSOCL_OK);
  for (int c = 0; c < NCONFIGS; c++)
    ck_assert_int_eq(run(rt, c, expected[c]), MSOCL_OK);
  int alone = msocl__program_cache_size(&rt->dev[0]);
  msocl_runtime_destroy(rt);

  /* A fresh runtime, so the threads find its cache empty. */
  ck_assert_int_eq(msocl_runtime_create(&rt, "cpu"), MSOCL_OK);
  struct job jobs[THREADS];
  memset(jobs, 0, sizeof jobs);
  for (int t = 0; t < THREADS; t++) {
    jobs[t].id = t;
    jobs[t].rt = rt;
    ck_assert_int_eq(pthread_create(&jobs[t].th, NULL, worker, &jobs[t]), 0);
  }
  for (int t = 0; t < THREADS; t++)
    pthread_join(jobs[t].th, NULL);
  int programs = msocl__program_cache_size(&rt->dev[0]);
  msocl_runtime_destroy(rt);
  for (int t = 0; t < THREADS; t++) {
    ck_assert_msg(jobs[t].rc == MSOCL_OK, "thread %d: %s", t, jobs[t].msg);
    ck_assert_msg(jobs[t].mismatch == 0,
                  "thread %d: %d runs differ from the run alone", t,
                  jobs[t].mismatch);
  }
  ck_assert_int_eq(programs, alone);
}
END_TEST

int main(void)
{
  scene_require_device("check_threads");
  Suite *su = suite_create("threads");
  TCase *tc = tcase_create("threads");
  tcase_set_timeout(tc, 300);
  tcase_add_test(tc, threads_share_a_runtime);
  suite_add_tcase(su, tc);
  return scene_run(su);
}
