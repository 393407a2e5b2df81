/* Runtimes on real OpenCL devices (PoCL's CPU device will do); skips (77)
 * where there is none. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L /* setenv */
#endif
#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h" /* to look at the queues a runtime made */

/* The devices as msocl_device_list sees them; fetched per test, since with
 * CK_NOFORK the tests share one process anyway. */
static msocl_device_info *devs;
static int ndevs;

static void list_setup(void) {
  ck_assert_int_eq(msocl_device_list(&devs, &ndevs), MSOCL_OK);
  ck_assert_int_gt(ndevs, 0);
}

static void list_teardown(void) {
  free(devs);
  devs = NULL;
  ndevs = 0;
}

static int find_type(msocl_device_type type) {
  int i;
  for (i = 0; i < ndevs; i++)
    if (devs[i].type == type) return i;
  return -1;
}

static int same_device(const msocl_device_info *a,
                       const msocl_device_info *b) {
  return a->platform_index == b->platform_index &&
         a->device_index == b->device_index && !strcmp(a->name, b->name);
}

/* Creates a runtime from spec and checks it holds exactly `want`. */
static void expect_runtime(const char *spec, const int *want, int nwant) {
  msocl_runtime *rt = NULL;
  msocl_device_info info;
  int n = -1, i;
  int rc = msocl_runtime_create(&rt, spec);
  ck_assert_msg(rc == MSOCL_OK, "spec '%s': %s: %s", spec ? spec : "(null)",
                msocl_err_name(rc), msocl_last_error());
  ck_assert_ptr_nonnull(rt);
  ck_assert_int_eq(msocl_runtime_device_count(rt, &n), MSOCL_OK);
  ck_assert_int_eq(n, nwant);
  for (i = 0; i < n; i++) {
    ck_assert_int_eq(msocl_runtime_device_info(rt, i, &info), MSOCL_OK);
    ck_assert_msg(same_device(&info, &devs[want[i]]),
                  "spec '%s': device %d is %d:%d, want %d:%d", spec, i,
                  info.platform_index, info.device_index,
                  devs[want[i]].platform_index, devs[want[i]].device_index);
  }
  msocl_runtime_destroy(rt);
}

static void expect_failure(const char *spec, int code) {
  msocl_runtime *rt = (msocl_runtime *)&rt; /* anything but NULL */
  int rc = msocl_runtime_create(&rt, spec);
  ck_assert_msg(rc == code, "spec '%s': got %s, want %s (%s)", spec,
                msocl_err_name(rc), msocl_err_name(code), msocl_last_error());
  ck_assert_ptr_null(rt);
}

START_TEST(test_cpu) {
  int cpu = find_type(MSOCL_DEVICE_CPU);
  if (cpu < 0) {
    printf("note: no CPU device, 'cpu' not tried\n");
    return;
  }
  expect_runtime("cpu", &cpu, 1);
  expect_runtime(" CPU ", &cpu, 1);
}
END_TEST

START_TEST(test_from_env) {
  char *saved = getenv("MSOCL_DEVICE") ? strdup(getenv("MSOCL_DEVICE")) : NULL;
  const int first = 0, last = ndevs - 1;
  char spec[32];

  ck_assert_int_eq(setenv("MSOCL_DEVICE", "0", 1), 0);
  expect_runtime(NULL, &first, 1);
  snprintf(spec, sizeof spec, "%d:%d", devs[last].platform_index,
           devs[last].device_index);
  ck_assert_int_eq(setenv("MSOCL_DEVICE", spec, 1), 0);
  expect_runtime(NULL, &last, 1);

  /* A spec nobody passed in code must be traced to the variable. */
  ck_assert_int_eq(setenv("MSOCL_DEVICE", "no-such-device-xyz", 1), 0);
  expect_failure(NULL, MSOCL_ERR_NO_DEVICE);
  ck_assert_msg(strstr(msocl_last_error(), "MSOCL_DEVICE='no-such-device-xyz'"),
                "message: %s", msocl_last_error());
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), devs[0].name));

  /* Unset: the default, one device. */
  ck_assert_int_eq(unsetenv("MSOCL_DEVICE"), 0);
  {
    msocl_runtime *rt = NULL;
    int n = 0;
    ck_assert_int_eq(msocl_runtime_create(&rt, NULL), MSOCL_OK);
    ck_assert_int_eq(msocl_runtime_device_count(rt, &n), MSOCL_OK);
    ck_assert_int_eq(n, 1);
    msocl_runtime_destroy(rt);
  }
  if (saved) setenv("MSOCL_DEVICE", saved, 1);
  free(saved);
}
END_TEST

START_TEST(test_all) {
  int want[MSOCL__MAX_DEVICES], i;
  if (ndevs > MSOCL__MAX_DEVICES) {
    expect_failure("all", MSOCL_ERR_TOO_MANY);
    return;
  }
  for (i = 0; i < ndevs; i++) want[i] = i;
  expect_runtime("all", want, ndevs);
}
END_TEST

START_TEST(test_info) {
  msocl_runtime *rt = NULL;
  msocl_device_info info;
  int i, n = 0;
  ck_assert_int_eq(msocl_runtime_create(&rt, "all"), MSOCL_OK);
  ck_assert_int_eq(msocl_runtime_device_count(rt, &n), MSOCL_OK);
  for (i = 0; i < n; i++) {
    ck_assert_int_eq(msocl_runtime_device_info(rt, i, &info), MSOCL_OK);
    ck_assert_str_ne(info.name, "");
    ck_assert_str_ne(info.platform_name, "");
    ck_assert_msg(!strncmp(info.version, "OpenCL ", 7), "version '%s'",
                  info.version);
    ck_assert_uint_gt(info.compute_units, 0);
    ck_assert_uint_gt(info.global_mem, 0);
    ck_assert(info.type == MSOCL_DEVICE_CPU || info.type == MSOCL_DEVICE_GPU ||
              info.type == MSOCL_DEVICE_ACCELERATOR ||
              info.type == MSOCL_DEVICE_OTHER);
    ck_assert(info.image_support == 0 || info.image_support == 1);
    ck_assert(info.fp64 == 0 || info.fp64 == 1);
    if (info.image_support) {
      /* OpenCL 1.2 asks for 8192 (2048 in the embedded profile). */
      ck_assert_uint_ge(info.image2d_max_width, 2048);
      ck_assert_uint_ge(info.image2d_max_height, 2048);
    }
    if (strstr(info.platform_name, "Portable Computing Language"))
      ck_assert_int_eq(info.type, MSOCL_DEVICE_CPU);
  }
  msocl_runtime_destroy(rt);
}
END_TEST

/* What the simulation relies on: a live context and an in-order queue with
 * profiling on the very device the info describes. */
START_TEST(test_queues) {
  msocl_runtime *rt = NULL;
  cl_command_queue_properties props = 0;
  cl_device_id dev = NULL;
  int i;
  ck_assert_int_eq(msocl_runtime_create(&rt, "all"), MSOCL_OK);
  for (i = 0; i < rt->ndev; i++) {
    ck_assert_ptr_nonnull(rt->dev[i].ctx);
    ck_assert_ptr_nonnull(rt->dev[i].queue);
    ck_assert_int_eq(clGetCommandQueueInfo(rt->dev[i].queue,
                                           CL_QUEUE_PROPERTIES, sizeof props,
                                           &props, NULL),
                     CL_SUCCESS);
    ck_assert(props & CL_QUEUE_PROFILING_ENABLE);
    ck_assert(!(props & CL_QUEUE_OUT_OF_ORDER_EXEC_MODE_ENABLE));
    ck_assert_int_eq(clGetCommandQueueInfo(rt->dev[i].queue,
                                           CL_QUEUE_DEVICE, sizeof dev, &dev,
                                           NULL),
                     CL_SUCCESS);
    ck_assert_ptr_eq(dev, rt->dev[i].id);
    ck_assert_int_eq(clFinish(rt->dev[i].queue), CL_SUCCESS);
  }
  msocl_runtime_destroy(rt);
}
END_TEST

START_TEST(test_no_device) {
  int i;
  char pd[32];
  expect_failure("no-such-device-xyz", MSOCL_ERR_NO_DEVICE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "'no-such-device-xyz'"));
  ck_assert_ptr_null(strstr(msocl_last_error(), "MSOCL_DEVICE="));
  for (i = 0; i < ndevs; i++) {
    snprintf(pd, sizeof pd, "%d:%d ", devs[i].platform_index,
             devs[i].device_index);
    ck_assert_ptr_nonnull(strstr(msocl_last_error(), pd));
    ck_assert_ptr_nonnull(strstr(msocl_last_error(), devs[i].name));
  }
  expect_failure("99:0", MSOCL_ERR_NO_DEVICE);
  if (find_type(MSOCL_DEVICE_GPU) < 0)
    expect_failure("gpu", MSOCL_ERR_NO_DEVICE);
}
END_TEST

START_TEST(test_bad_spec) {
  expect_failure("1:", MSOCL_ERR_BAD_SPEC);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "'1:'"));
  expect_failure("cpu,", MSOCL_ERR_BAD_SPEC);
  expect_failure("-1:0", MSOCL_ERR_BAD_SPEC);
  expect_failure("a:b", MSOCL_ERR_NO_DEVICE); /* a name: none holds it */
  expect_failure("0,0", MSOCL_ERR_DUP_DEVICE);
}
END_TEST

START_TEST(test_null_args) {
  msocl_runtime *rt = NULL;
  msocl_device_info info;
  int n;
  ck_assert_int_eq(msocl_runtime_create(NULL, "0"), MSOCL_ERR_NULL_HANDLE);
  ck_assert_str_ne(msocl_last_error(), "");
  msocl_runtime_destroy(NULL);
  ck_assert_int_eq(msocl_runtime_device_count(NULL, &n),
                   MSOCL_ERR_NULL_HANDLE);
  ck_assert_int_eq(msocl_runtime_device_info(NULL, 0, &info),
                   MSOCL_ERR_NULL_HANDLE);
  ck_assert_int_eq(msocl_device_list(NULL, &n), MSOCL_ERR_NULL_HANDLE);

  ck_assert_int_eq(msocl_runtime_create(&rt, "0"), MSOCL_OK);
  ck_assert_int_eq(msocl_runtime_device_count(rt, NULL),
                   MSOCL_ERR_NULL_HANDLE);
  ck_assert_int_eq(msocl_runtime_device_info(rt, 0, NULL),
                   MSOCL_ERR_NULL_HANDLE);
  msocl_runtime_destroy(rt);
}
END_TEST

START_TEST(test_bad_index) {
  msocl_runtime *rt = NULL;
  msocl_device_info info;
  int n = 0;
  ck_assert_int_eq(msocl_runtime_create(&rt, "0"), MSOCL_OK);
  ck_assert_int_eq(msocl_runtime_device_count(rt, &n), MSOCL_OK);
  ck_assert_int_eq(msocl_runtime_device_info(rt, -1, &info),
                   MSOCL_ERR_BAD_INDEX);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "-1"));
  ck_assert_int_eq(msocl_runtime_device_info(rt, n, &info),
                   MSOCL_ERR_BAD_INDEX);
  ck_assert_int_eq(msocl_runtime_device_info(rt, 1000, &info),
                   MSOCL_ERR_BAD_INDEX);
  ck_assert_int_eq(msocl_runtime_device_info(rt, n - 1, &info), MSOCL_OK);
  /* the success keeps the last failure's message, as errno */
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "1000"));
  msocl_runtime_destroy(rt);
}
END_TEST

/* Needs a platform with two devices: POCL_DEVICES="pthread pthread". */
START_TEST(test_two_devices) {
  int i, pair[2] = {-1, -1};
  char spec[64];
  for (i = 0; i + 1 < ndevs; i++)
    if (devs[i].platform_index == devs[i + 1].platform_index &&
        devs[i].device_index == 0) {
      pair[0] = i;
      pair[1] = i + 1;
      break;
    }
  if (pair[0] < 0) {
    printf("note: no platform with two devices; try "
           "POCL_DEVICES=\"pthread pthread\"\n");
    return;
  }
  snprintf(spec, sizeof spec, "%d:0,%d:1", devs[pair[0]].platform_index,
           devs[pair[0]].platform_index);
  expect_runtime(spec, pair, 2);
  snprintf(spec, sizeof spec, "%d:1, %d:0", devs[pair[0]].platform_index,
           devs[pair[0]].platform_index);
  {
    const int rev[2] = {pair[1], pair[0]};
    expect_runtime(spec, rev, 2);
  }
  snprintf(spec, sizeof spec, "%d:0,%d:0", devs[pair[0]].platform_index,
           devs[pair[0]].platform_index);
  expect_failure(spec, MSOCL_ERR_DUP_DEVICE);
}
END_TEST

/* Every option is checked at sim creation, fused and overlap too: AUTO, ON
 * or OFF. */
START_TEST(test_bad_switches) {
  static const float xyz[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0},
                     mass[4] = {1, 1, 1, 1};
  static const int ij[8] = {0, 1, 1, 2, 2, 3, 3, 0};
  static const float k[4] = {10, 10, 10, 10};
  static const struct {
    int fused, overlap;
    const char *says;
  } bad[] = {{7, MSOCL_ON, "fused is 7: MSOCL_AUTO, MSOCL_ON or"},
             {-1, MSOCL_ON, "fused is -1: MSOCL_AUTO, MSOCL_ON or"},
             {MSOCL_AUTO, 12345, "overlap is 12345: MSOCL_AUTO, MSOCL_ON"},
             {MSOCL_AUTO, -1, "overlap is -1: MSOCL_AUTO, MSOCL_ON or"}};
  msocl_runtime *rt = NULL;
  msocl_model *m = NULL;
  msocl_sim_options o;
  msocl_sim *s;
  size_t q;
  int rc;

  ck_assert_int_eq(msocl_runtime_create(&rt, "cpu"), MSOCL_OK);
  ck_assert_int_eq(msocl_model_create(&m), MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_points(m, 4, xyz, mass, NULL), MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_springs(m, 4, ij, k, NULL, NULL), MSOCL_OK);
  for (q = 0; q < sizeof bad / sizeof bad[0]; q++) {
    msocl_sim_options_init(&o);
    o.tuning.fused = (msocl_choice)bad[q].fused;
    o.tuning.overlap = (msocl_choice)bad[q].overlap;
    s = (msocl_sim *)&s;
    rc = msocl_sim_create(&s, rt, m, &o);
    ck_assert_msg(rc == MSOCL_ERR_BAD_VALUE, "%s: got %s (%s)", bad[q].says,
                  msocl_err_name(rc), msocl_last_error());
    ck_assert_ptr_null(s);
    ck_assert_msg(strstr(msocl_last_error(), bad[q].says), "message: %s",
                  msocl_last_error());
  }
  /* both forced values of each are still taken */
  msocl_sim_options_init(&o);
  o.tuning.fused = MSOCL_ON;
  o.tuning.overlap = MSOCL_OFF;
  rc = msocl_sim_create(&s, rt, m, &o);
  ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
  msocl_runtime_destroy(rt);
}
END_TEST

/* msocl_sim_options_init leaves the tuning all zero, which is every
 * field's "choose for me"; each switch takes AUTO, ON and OFF, and
 * nothing else; the public device limit is the library's own. */
START_TEST(test_tuning_zero_is_auto) {
  static const float xyz[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0},
                     mass[4] = {1, 1, 1, 1};
  static const int ij[8] = {0, 1, 1, 2, 2, 3, 3, 0};
  static const float k[4] = {10, 10, 10, 10};
  static const char *names[4] = {"fused", "renumber", "overlap", "classes"};
  const msocl_tuning zero = {0};
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  ck_assert(memcmp(&o.tuning, &zero, sizeof zero) == 0);
  ck_assert_int_eq(o.tuning.layout, MSOCL_LAYOUT_AUTO);
  ck_assert_int_eq(MSOCL_MAX_DEVICES, MSOCL__MAX_DEVICES);

  msocl_runtime *rt = NULL;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_runtime_create(&rt, "cpu"), MSOCL_OK);
  ck_assert_int_eq(msocl_model_create(&m), MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_points(m, 4, xyz, mass, NULL), MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_springs(m, 4, ij, k, NULL, NULL), MSOCL_OK);
  for (int f = 0; f < 4; f++) {
    static const int values[5] = {MSOCL_AUTO, MSOCL_ON, MSOCL_OFF, 3, -1};
    for (int q = 0; q < 5; q++) {
      msocl_sim_options_init(&o);
      msocl_choice *c[4] = {&o.tuning.fused, &o.tuning.renumber,
                            &o.tuning.overlap, &o.tuning.classes};
      *c[f] = (msocl_choice)values[q];
      msocl_sim *s = NULL;
      int rc = msocl_sim_create(&s, rt, m, &o);
      /* every choice applies to a ring of four points (BUFFER) */
      const int want = q > 2 ? MSOCL_ERR_BAD_VALUE : MSOCL_OK;
      ck_assert_msg(rc == want, "%s = %d: got %s (%s)", names[f], values[q],
                    msocl_err_name(rc), msocl_last_error());
      if (q > 2) {
        char says[64];
        snprintf(says, sizeof says, "tuning.%s is %d", names[f], values[q]);
        ck_assert_msg(strstr(msocl_last_error(), says), "message: %s",
                      msocl_last_error());
      }
      msocl_sim_destroy(s);
    }
  }
  msocl_model_destroy(m);
  msocl_runtime_destroy(rt);
}
END_TEST

static Suite *runtime_suite(void) {
  Suite *s = suite_create("runtime");
  TCase *tc = tcase_create("runtime");
  /* Contexts and program builds on a loaded CPU can be slow. */
  tcase_set_timeout(tc, 60);
  tcase_add_checked_fixture(tc, list_setup, list_teardown);
  tcase_add_test(tc, test_cpu);
  tcase_add_test(tc, test_from_env);
  tcase_add_test(tc, test_all);
  tcase_add_test(tc, test_info);
  tcase_add_test(tc, test_queues);
  tcase_add_test(tc, test_no_device);
  tcase_add_test(tc, test_bad_spec);
  tcase_add_test(tc, test_null_args);
  tcase_add_test(tc, test_bad_index);
  tcase_add_test(tc, test_two_devices);
  tcase_add_test(tc, test_bad_switches);
  tcase_add_test(tc, test_tuning_zero_is_auto);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) {
  SRunner *sr = srunner_create(runtime_suite());
  msocl_device_info *probe = NULL;
  int n = 0, failed;

  /* A fork()ed child hangs in OpenCL once the parent has called into PoCL,
   * so no forking, decided before the first OpenCL call below. */
  srunner_set_fork_status(sr, CK_NOFORK);
  if (msocl_device_list(&probe, &n) != MSOCL_OK) {
    printf("SKIP: no OpenCL device: %s\n", msocl_last_error());
    srunner_free(sr);
    return 77;
  }
  free(probe);
  srunner_run_all(sr, CK_NORMAL);
  failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  return failed ? EXIT_FAILURE : EXIT_SUCCESS;
}
