/* Device-spec grammar, status names and the last-error message: no OpenCL
 * device needed, the device lists here are made up. */
#include <check.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "msocl.h"
#include "expect.h"

/* Two CPUs on one platform, a GPU on another, an accelerator on a third:
 * the GPU is not first, so the default's preference shows. */
static const msocl_device_info devs[] = {
    {0, 0, "Portable Computing Language", "pthread-skylake-avx512",
     "OpenCL 3.0", MSOCL_DEVICE_CPU, 4, 1ULL << 33, 1, 8192, 8192, 1, 0},
    {0, 1, "Portable Computing Language", "pthread-zen2", "OpenCL 3.0",
     MSOCL_DEVICE_CPU, 4, 1ULL << 33, 1, 8192, 8192, 1, 0},
    {1, 0, "NVIDIA CUDA", "NVIDIA H100 80GB HBM3", "OpenCL 3.0 CUDA",
     MSOCL_DEVICE_GPU, 132, 1ULL << 36, 1, 32768, 32768, 1, 0},
    {2, 0, "Intel(R) FPGA Emulation Platform",
     "Intel(R) FPGA Emulation Device", "OpenCL 1.2",
     MSOCL_DEVICE_ACCELERATOR, 1, 1ULL << 30, 0, 0, 0, 0, 0},
};
#define NDEVS 4

static const char *show(const char *spec) { return spec ? spec : "(null)"; }

static void expect(const char *spec, const msocl_device_info *d, int nd,
                   const int *want, int nwant) {
  int chosen[8], n = -1, i;
  int rc = msocl_device_select(spec, d, nd, chosen, 8, &n);
  ck_assert_msg(rc == MSOCL_OK, "spec '%s': %s: %s", show(spec),
                msocl_err_name(rc), msocl_last_error());
  ck_assert_msg(n == nwant, "spec '%s': %d devices, want %d", show(spec), n,
                nwant);
  for (i = 0; i < n; i++)
    ck_assert_msg(chosen[i] == want[i], "spec '%s': choice %d is #%d, want #%d",
                  show(spec), i, chosen[i], want[i]);
}

#define CHOOSES(spec, ...)                                                    \
  do {                                                                        \
    const int w_[] = {__VA_ARGS__};                                           \
    expect(spec, devs, NDEVS, w_, (int)(sizeof w_ / sizeof w_[0]));           \
  } while (0)

/* Fails with `code`, leaves *nchosen 0, and the message contains `word`. */
static void expect_fail(const char *spec, const msocl_device_info *d, int nd,
                        int max, int code, const char *word) {
  int chosen[8], n = -1;
  int rc = msocl_device_select(spec, d, nd, chosen, max, &n);
  ck_assert_msg(rc == code, "spec '%s': got %s, want %s (%s)", show(spec),
                msocl_err_name(rc), msocl_err_name(code), msocl_last_error());
  ck_assert_int_eq(n, 0);
  ck_assert_msg(strstr(msocl_last_error(), word) != NULL,
                "spec '%s': message '%s' lacks '%s'", show(spec),
                msocl_last_error(), word);
}

#define FAIL(spec, code, word) expect_fail(spec, devs, NDEVS, 8, code, word)

/* ------------------------------------------------------------- grammar */

START_TEST(test_default) {
  const msocl_device_info no_gpu[] = {devs[3], devs[1], devs[0]};
  msocl_device_info neither[2];
  const int cpu = 1, first = 0;

  CHOOSES(NULL, 2);
  CHOOSES("", 2);
  CHOOSES("   ", 2);
  CHOOSES(" \t\n", 2);
  expect(NULL, no_gpu, 3, &cpu, 1); /* the first CPU, not the first device */
  expect("", no_gpu, 3, &cpu, 1);
  neither[0] = devs[3];
  neither[1] = devs[3];
  neither[1].type = MSOCL_DEVICE_OTHER;
  expect(NULL, neither, 2, &first, 1);
  expect(NULL, &devs[2], 1, &first, 1);
}
END_TEST

START_TEST(test_kinds) {
  CHOOSES("cpu", 0);
  CHOOSES("CPU", 0);
  CHOOSES("Cpu", 0);
  CHOOSES("gpu", 2);
  CHOOSES("GpU", 2);
  CHOOSES("acc", 3);
  CHOOSES("ACC", 3);
  CHOOSES("accelerator", 3);
  CHOOSES("Accelerator", 3);
  CHOOSES("all", 0, 1, 2, 3);
  CHOOSES("ALL", 0, 1, 2, 3);
  CHOOSES(" all ", 0, 1, 2, 3);
}
END_TEST

START_TEST(test_indices) {
  CHOOSES("0:0", 0);
  CHOOSES("0:1", 1);
  CHOOSES("1:0", 2);
  CHOOSES("2:0", 3);
  CHOOSES("00:01", 1);
  CHOOSES(" 1:0\t", 2);
  CHOOSES("0", 0);
  CHOOSES("1", 1);
  CHOOSES("3", 3);
  CHOOSES("03", 3);
}
END_TEST

START_TEST(test_names) {
  CHOOSES("h100", 2); /* device name */
  CHOOSES("ZEN2", 1);
  CHOOSES("pthread", 0); /* the first of two that match */
  CHOOSES("cuda", 2);    /* platform name */
  CHOOSES("portable", 0);
  CHOOSES("computing language", 0);      /* spaces inside a term stay */
  CHOOSES("FPGA Emulation Platform", 3); /* platform only */
  CHOOSES("Emulation Device", 3);        /* device only */
  CHOOSES("Intel(R)", 3);
  CHOOSES("80GB", 2); /* starts with digits, yet a name */
}
END_TEST

START_TEST(test_lists) {
  CHOOSES("gpu,cpu", 2, 0);
  CHOOSES(" gpu , cpu ", 2, 0);
  CHOOSES("\tgpu\t,\ncpu\n", 2, 0);
  CHOOSES("1:0, 0:1 ,3", 2, 1, 3);
  CHOOSES("zen2,GPU,acc", 1, 2, 3);
  CHOOSES("cpu,0:1", 0, 1);
  CHOOSES("3,2,1,0", 3, 2, 1, 0);
  CHOOSES("acc,portable,pthread-zen2,cuda", 3, 0, 1, 2);
}
END_TEST

/* A name may hold colons (ROCm's "gfx90a:sramecc+:xnack-"): a term
 * begun as no number begins is a name, colons and all. (Any term with a
 * colon used to be P:D: such a device could be chosen only by the part
 * before its first colon.) */
START_TEST(test_colon_names) {
  static const msocl_device_info rocm[] = {
      {0, 0, "AMD Accelerated Parallel Processing", "gfx90a:sramecc+:xnack-",
       "OpenCL 2.0", MSOCL_DEVICE_GPU, 104, 1ULL << 36, 1, 16384, 16384, 1,
       0},
      {0, 1, "AMD Accelerated Parallel Processing", "gfx90a:sramecc-:xnack-",
       "OpenCL 2.0", MSOCL_DEVICE_GPU, 104, 1ULL << 36, 1, 16384, 16384, 1,
       0},
  };
  const int second[] = {1}, both[] = {0, 1};
  expect("gfx90a:sramecc-", rocm, 2, second, 1);
  expect("gfx90a:sramecc-:xnack-", rocm, 2, second, 1);
  expect("0:0,sramecc-:xnack", rocm, 2, both, 2);
  expect_fail("gfx90a:xnack+", rocm, 2, 8, MSOCL_ERR_NO_DEVICE,
              "'gfx90a:xnack+'");
}
END_TEST

/* -------------------------------------------------------------- errors */

START_TEST(test_bad_spec) {
  FAIL(",", MSOCL_ERR_BAD_SPEC, "empty term");
  FAIL("gpu,", MSOCL_ERR_BAD_SPEC, "'gpu,'");
  FAIL(",gpu", MSOCL_ERR_BAD_SPEC, "empty term");
  FAIL(" , ", MSOCL_ERR_BAD_SPEC, "empty term");
  FAIL("gpu,,cpu", MSOCL_ERR_BAD_SPEC, "empty term");
  FAIL("gpu, ,cpu", MSOCL_ERR_BAD_SPEC, "empty term");
  FAIL("1:", MSOCL_ERR_BAD_SPEC, "'1:'");
  FAIL(":1", MSOCL_ERR_BAD_SPEC, "':1'");
  FAIL(":", MSOCL_ERR_BAD_SPEC, "':'");
  /* begun as no number begins: a name (README: "any other text") */
  FAIL("a:b", MSOCL_ERR_NO_DEVICE, "'a:b'");
  FAIL("-1:0", MSOCL_ERR_BAD_SPEC, "'-1:0'");
  FAIL("0:-1", MSOCL_ERR_BAD_SPEC, "'0:-1'");
  FAIL("1:2:3", MSOCL_ERR_BAD_SPEC, "'1:2:3'");
  FAIL("1 : 0", MSOCL_ERR_BAD_SPEC, "'1 : 0'");
  FAIL("0x1:0", MSOCL_ERR_BAD_SPEC, "'0x1:0'");
  FAIL("99999999999:0", MSOCL_ERR_BAD_SPEC, "'99999999999:0'");
  FAIL("0:2147483648", MSOCL_ERR_BAD_SPEC, "'0:2147483648'");
  FAIL("-1", MSOCL_ERR_BAD_SPEC, "'-1'");
  FAIL("+1", MSOCL_ERR_BAD_SPEC, "'+1'");
  FAIL("99999999999999999999", MSOCL_ERR_BAD_SPEC, "'99999999999999999999'");
  /* Syntax is checked before matching: the typo is what gets reported. */
  FAIL("no-such-device,1:", MSOCL_ERR_BAD_SPEC, "'1:'");
  FAIL("cpu,cpu,1:", MSOCL_ERR_BAD_SPEC, "'1:'");
}
END_TEST

/* The message names the term and lists every device, P:D and all. */
static void expect_no_device(const char *spec, const char *term,
                             const msocl_device_info *d, int nd) {
  int i;
  char pd[32];
  expect_fail(spec, d, nd, 8, MSOCL_ERR_NO_DEVICE, term);
  for (i = 0; i < nd; i++) {
    snprintf(pd, sizeof pd, "%d:%d ", d[i].platform_index, d[i].device_index);
    ck_assert_msg(strstr(msocl_last_error(), d[i].name) != NULL,
                  "'%s' not listed in: %s", d[i].name, msocl_last_error());
    ck_assert_msg(strstr(msocl_last_error(), d[i].platform_name) != NULL,
                  "'%s' not listed in: %s", d[i].platform_name,
                  msocl_last_error());
    ck_assert_msg(strstr(msocl_last_error(), pd) != NULL,
                  "'%s' not listed in: %s", pd, msocl_last_error());
  }
}

START_TEST(test_no_device) {
  const msocl_device_info cpus[] = {devs[0], devs[1]};
  expect_no_device("no-such-device", "'no-such-device'", devs, NDEVS);
  expect_no_device("cpus", "'cpus'", devs, NDEVS); /* not the keyword */
  expect_no_device("3:0", "'3:0'", devs, NDEVS);
  expect_no_device("1:1", "'1:1'", devs, NDEVS);
  expect_no_device("4", "'4'", devs, NDEVS);
  expect_no_device("2147483647", "'2147483647'", devs, NDEVS);
  expect_no_device("gpu, nvidia-a100", "'nvidia-a100'", devs, NDEVS);
  expect_no_device("gpu", "'gpu'", cpus, 2);
  expect_no_device("acc", "'acc'", cpus, 2);
  expect_no_device("accelerator", "'accelerator'", cpus, 2);
  expect_no_device("cuda", "'cuda'", cpus, 2);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "(CPU)"));
}
END_TEST

START_TEST(test_dup_device) {
  FAIL("cpu,0:0", MSOCL_ERR_DUP_DEVICE, "pthread-skylake-avx512");
  FAIL("all,cpu", MSOCL_ERR_DUP_DEVICE, "pthread-skylake-avx512");
  FAIL("cpu,all", MSOCL_ERR_DUP_DEVICE, "pthread-skylake-avx512");
  FAIL("gpu,gpu", MSOCL_ERR_DUP_DEVICE, "NVIDIA H100");
  FAIL("2,1:0", MSOCL_ERR_DUP_DEVICE, "1:0");
  FAIL("acc,emulation", MSOCL_ERR_DUP_DEVICE, "'emulation'");
  FAIL("all,all", MSOCL_ERR_DUP_DEVICE, "'all'");
}
END_TEST

START_TEST(test_too_many) {
  expect_fail("all", devs, NDEVS, 3, MSOCL_ERR_TOO_MANY, "3 devices");
  expect_fail("cpu,gpu", devs, NDEVS, 1, MSOCL_ERR_TOO_MANY, "'cpu,gpu'");
  {
    int chosen[4], n = 0;
    ck_assert_int_eq(msocl_device_select("all", devs, NDEVS, chosen, 4, &n),
                     MSOCL_OK);
    ck_assert_int_eq(n, 4);
  }
}
END_TEST

START_TEST(test_bad_args) {
  int chosen[8], n = -1;
  ck_assert_int_eq(msocl_device_select("cpu", devs, 0, chosen, 8, &n),
                   MSOCL_ERR_NO_PLATFORM);
  ck_assert_int_eq(n, 0);
  ck_assert_int_eq(msocl_device_select(NULL, NULL, 0, chosen, 8, &n),
                   MSOCL_ERR_NO_PLATFORM);
  ck_assert_int_eq(msocl_device_select("cpu", devs, -1, chosen, 8, &n),
                   MSOCL_ERR_BAD_COUNT);
  ck_assert_int_eq(msocl_device_select("cpu", NULL, NDEVS, chosen, 8, &n),
                   MSOCL_ERR_NULL_HANDLE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "devs"));
  ck_assert_int_eq(msocl_device_select("cpu", devs, NDEVS, NULL, 8, &n),
                   MSOCL_ERR_NULL_HANDLE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "chosen"));
  ck_assert_int_eq(msocl_device_select("cpu", devs, NDEVS, chosen, 8, NULL),
                   MSOCL_ERR_NULL_HANDLE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "nchosen"));
  ck_assert_int_eq(msocl_device_select("cpu", devs, NDEVS, chosen, 0, &n),
                   MSOCL_ERR_BAD_COUNT);
  ck_assert_int_eq(msocl_device_select(NULL, devs, NDEVS, chosen, -1, &n),
                   MSOCL_ERR_BAD_COUNT);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "-1"));
}
END_TEST

/* ------------------------------------------------------ status names */

START_TEST(test_err_names) {
#define CHECK_ROW(name, code, text)                                           \
  ck_assert_int_eq(MSOCL_ERR_##name, code);                                   \
  ck_assert_str_eq(msocl_err_name(code), "MSOCL_ERR_" #name);                 \
  ck_assert_str_eq(msocl_strerror(code), text);
  MSOCL_ERRNO_MAP(CHECK_ROW)
#undef CHECK_ROW
  ck_assert_str_eq(msocl_err_name(MSOCL_OK), "MSOCL_OK");
  ck_assert_str_eq(msocl_strerror(MSOCL_OK), "success");
}
END_TEST

START_TEST(test_cl_names) {
  ck_assert_str_eq(msocl_err_name(-5), "CL_OUT_OF_RESOURCES");
  ck_assert_str_eq(msocl_strerror(-5), "device out of resources");
  ck_assert_str_eq(msocl_err_name(-1), "CL_DEVICE_NOT_FOUND");
  ck_assert_str_eq(msocl_err_name(-11), "CL_BUILD_PROGRAM_FAILURE");
  ck_assert_str_eq(msocl_err_name(-30), "CL_INVALID_VALUE");
  ck_assert_str_eq(msocl_err_name(-54), "CL_INVALID_WORK_GROUP_SIZE");
  ck_assert_str_eq(msocl_err_name(-72), "CL_MAX_SIZE_RESTRICTION_EXCEEDED");
  ck_assert_str_eq(msocl_err_name(-1001), "CL_PLATFORM_NOT_FOUND_KHR");
}
END_TEST

START_TEST(test_unknown_codes) {
  static const int unknown[] = {1, 42, -20, -29, -73, -999, -1999, -2024,
                                -2999, INT_MIN, INT_MAX};
  size_t i;
  for (i = 0; i < sizeof unknown / sizeof unknown[0]; i++) {
    ck_assert_str_eq(msocl_err_name(unknown[i]), "MSOCL_ERR_UNKNOWN");
    ck_assert_str_eq(msocl_strerror(unknown[i]), "unknown error");
  }
}
END_TEST

/* --------------------------------------------------------- last error */

START_TEST(test_last_error) {
  int chosen[8], n;
  ck_assert_int_eq(msocl_device_select("1:x", devs, NDEVS, chosen, 8, &n),
                   MSOCL_ERR_BAD_SPEC);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "'1:x'"));
  /* A call that succeeds keeps the last failure's message (as errno). */
  ck_assert_int_eq(msocl_device_select("gpu", devs, NDEVS, chosen, 8, &n),
                   MSOCL_OK);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "'1:x'"));
}
END_TEST

START_TEST(test_truncated) {
  size_t len = 40000;
  char *spec = malloc(len + 1);
  int chosen[8], n;
  ck_assert_ptr_nonnull(spec);
  memset(spec, 'x', len);
  spec[len] = '\0';
  ck_assert_int_eq(msocl_device_select(spec, devs, NDEVS, chosen, 8, &n),
                   MSOCL_ERR_NO_DEVICE);
  ck_assert_uint_lt(strlen(msocl_last_error()), 16 * 1024);
  ck_assert_uint_gt(strlen(msocl_last_error()), 8 * 1024);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "truncated]"));
  free(spec);
}
END_TEST

static void *fail_in_thread(void *arg) {
  int chosen[8], n;
  (void)arg;
  msocl_device_select("gpu,", devs, NDEVS, chosen, 8, &n);
  return strstr(msocl_last_error(), "empty term") ? (void *)1 : NULL;
}

START_TEST(test_thread_local) {
  int chosen[8], n;
  pthread_t t;
  void *ok = NULL;
  msocl_device_select("no-such-device", devs, NDEVS, chosen, 8, &n);
  ck_assert_int_eq(pthread_create(&t, NULL, fail_in_thread, NULL), 0);
  ck_assert_int_eq(pthread_join(t, &ok), 0);
  ck_assert_ptr_nonnull(ok);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "'no-such-device'"));
}
END_TEST

START_TEST(test_version) {
  int major = -1, minor = -1, patch = -1;
  ck_assert_int_eq(sscanf(msocl_version_string(), "%d.%d.%d", &major,
                          &minor, &patch),
                   3);
  ck_assert_int_eq(msocl_version(), major * 10000 + minor * 100 + patch);
}
END_TEST

static Suite *select_suite(void) {
  Suite *s = suite_create("select");
  TCase *grammar = tcase_create("grammar");
  TCase *errors = tcase_create("errors");
  TCase *status = tcase_create("status");

  tcase_add_test(grammar, test_default);
  tcase_add_test(grammar, test_kinds);
  tcase_add_test(grammar, test_indices);
  tcase_add_test(grammar, test_names);
  tcase_add_test(grammar, test_lists);
  tcase_add_test(grammar, test_colon_names);
  suite_add_tcase(s, grammar);

  tcase_add_test(errors, test_bad_spec);
  tcase_add_test(errors, test_no_device);
  tcase_add_test(errors, test_dup_device);
  tcase_add_test(errors, test_too_many);
  tcase_add_test(errors, test_bad_args);
  suite_add_tcase(s, errors);

  tcase_add_test(status, test_err_names);
  tcase_add_test(status, test_cl_names);
  tcase_add_test(status, test_unknown_codes);
  tcase_add_test(status, test_last_error);
  tcase_add_test(status, test_truncated);
  tcase_add_test(status, test_thread_local);
  tcase_add_test(status, test_version);
  suite_add_tcase(s, status);
  return s;
}

int main(void) {
  return expect_run(select_suite());
}
