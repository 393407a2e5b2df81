/* The host threads a split simulation runs its devices on (sim/workers.c):
 * every job index runs once a round, on a thread of its own, rounds never
 * overlap, and a job's failure reaches the caller with its message. No
 * OpenCL. */
#include "sim.h"

#include <check.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include "expect.h"

#define ROUNDS 2000

struct tally {
  int n;
  int runs[MSOCL__MAX_DEVICES]; /* each index's runs, written by its job */
  pthread_t who[MSOCL__MAX_DEVICES];
  int round;                    /* the caller's round, read by the jobs */
  int seen[MSOCL__MAX_DEVICES]; /* the round each job last saw */
  int fail_at;                  /* this index fails (-1: none) */
};

static int count(void *ctx, int i)
{
  struct tally *t = ctx;
  t->runs[i]++;
  t->who[i] = pthread_self();
  t->seen[i] = t->round;
  if (i == t->fail_at)
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "job %d says no", i);
  return MSOCL_OK;
}

START_TEST(every_index_once_a_round)
{
  for (int n = 1; n <= 4; n++) {
    struct msocl__workers *w = NULL;
    ck_assert_int_eq(msocl__workers_create(&w, n), MSOCL_OK);
    struct tally t;
    memset(&t, 0, sizeof t);
    t.n = n;
    t.fail_at = -1;
    for (int r = 1; r <= ROUNDS; r++) {
      t.round = r;
      ck_assert_int_eq(msocl__workers_run(w, count, &t), MSOCL_OK);
      /* the round is over for every job when run returns */
      for (int i = 0; i < n; i++) {
        ck_assert_int_eq(t.runs[i], r);
        ck_assert_int_eq(t.seen[i], r);
      }
    }
    /* job 0 on the caller, the others each on a thread of its own */
    ck_assert(pthread_equal(t.who[0], pthread_self()));
    for (int i = 1; i < n; i++) {
      ck_assert(!pthread_equal(t.who[i], pthread_self()));
      for (int k = 1; k < i; k++)
        ck_assert(!pthread_equal(t.who[i], t.who[k]));
    }
    msocl__workers_destroy(w);
  }
  printf("1 to 4 threads: %d rounds each, every job once a round\n",
         ROUNDS);
}
END_TEST

START_TEST(failure_reaches_the_caller)
{
  struct msocl__workers *w = NULL;
  ck_assert_int_eq(msocl__workers_create(&w, 3), MSOCL_OK);
  struct tally t;
  memset(&t, 0, sizeof t);
  t.fail_at = 2;
  ck_assert_int_eq(msocl__workers_run(w, count, &t), MSOCL_ERR_BAD_VALUE);
  /* the message was recorded on the failing thread; the caller gets it */
  SAYS("job 2 says no");
  SAYS("device part 2");
  /* the others still ran, and the next round works */
  ck_assert_int_eq(t.runs[0], 1);
  ck_assert_int_eq(t.runs[1], 1);
  t.fail_at = -1;
  ck_assert_int_eq(msocl__workers_run(w, count, &t), MSOCL_OK);
  ck_assert_int_eq(t.runs[2], 2);
  msocl__workers_destroy(w);
}
END_TEST

START_TEST(bad_counts)
{
  struct msocl__workers *w = (struct msocl__workers *)&w;
  ck_assert_int_eq(msocl__workers_create(&w, 0), MSOCL_ERR_BAD_COUNT);
  ck_assert_ptr_null(w);
  ck_assert_int_eq(msocl__workers_create(&w, MSOCL__MAX_DEVICES + 1),
                   MSOCL_ERR_BAD_COUNT);
  msocl__workers_destroy(NULL); /* harmless */
}
END_TEST

int main(void)
{
  Suite *su = suite_create("workers");
  TCase *tc = tcase_create("workers");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, every_index_once_a_round);
  tcase_add_test(tc, failure_reaches_the_caller);
  tcase_add_test(tc, bad_counts);
  suite_add_tcase(su, tc);
  return expect_run(su);
}
