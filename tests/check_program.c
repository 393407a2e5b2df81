/* Kernel sources: MSOCL_KERNEL_PATH loads them from a folder, and a build
 * failure returns MSOCL_ERR_BUILD carrying the compiler's log. */
#include "internal.h" /* the library's list of kernel files */
#include "scenes.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char dir[] = "/tmp/msocl-kernels-XXXXXX";

/* Copies kernels/<name> from the source tree into dir, appending `extra`. */
static void copy_kernel(const char *name, const char *extra)
{
  const char *src = getenv("srcdir");
  char from[4096], to[4096];
  snprintf(from, sizeof from, "%s/kernels/%s", src ? src : ".", name);
  snprintf(to, sizeof to, "%s/%s", dir, name);
  FILE *in = fopen(from, "rb"), *out = fopen(to, "wb");
  ck_assert_msg(in && out, "cannot copy %s", from);
  char buf[4096];
  size_t got;
  while ((got = fread(buf, 1, sizeof buf, in)) > 0)
    fwrite(buf, 1, got, out);
  fputs(extra, out);
  fclose(in);
  fclose(out);
}

static int make_sim(void)
{
  msocl_runtime *rt = NULL;
  ck_assert_int_eq(msocl_runtime_create(&rt, "cpu"), MSOCL_OK);
  msocl_model *m = scene_hanging(4);
  msocl_sim *s = NULL;
  int rc = msocl_sim_create(&s, rt, m, NULL);
  if (rc == MSOCL_OK)
    ck_assert_int_eq(msocl_sim_step(s, 3), MSOCL_OK);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
  msocl_runtime_destroy(rt);
  return rc;
}

/* Every kernel file the library embeds, in its order. */
#define NFILES ((size_t)msocl__kernel_source_count)
#define FILE_NAME(f) (msocl__kernel_sources[f].name)

/* All kernel files into dir, with `extra` after planes.cl. */
static void copy_all(const char *extra)
{
  for (size_t f = 0; f < NFILES; f++)
    copy_kernel(FILE_NAME(f), strcmp(FILE_NAME(f), "planes.cl") ? "\n" : extra);
}

START_TEST(kernel_path_loads_files)
{
  copy_all("\n");
  setenv("MSOCL_KERNEL_PATH", dir, 1);
  ck_assert_int_eq(make_sim(), MSOCL_OK);
  unsetenv("MSOCL_KERNEL_PATH");
}
END_TEST

START_TEST(build_error_carries_log)
{
  copy_all("\n__kernel void broken(void) { this_is_not_c; }\n");
  setenv("MSOCL_KERNEL_PATH", dir, 1);
  ck_assert_int_eq(make_sim(), MSOCL_ERR_BUILD);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "this_is_not_c"));
  unsetenv("MSOCL_KERNEL_PATH");
}
END_TEST

START_TEST(missing_kernel_file)
{
  setenv("MSOCL_KERNEL_PATH", "/nonexistent/msocl", 1);
  ck_assert_int_eq(make_sim(), MSOCL_ERR_KERNEL_SOURCE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "/nonexistent/msocl/"));
  unsetenv("MSOCL_KERNEL_PATH");
}
END_TEST

int main(void)
{
  scene_require_device("check_program");
  if (!mkdtemp(dir)) {
    perror("check_program: mkdtemp");
    return 99;
  }
  Suite *su = suite_create("program");
  TCase *tc = tcase_create("program");
  tcase_set_timeout(tc, 120);
  tcase_add_test(tc, kernel_path_loads_files);
  tcase_add_test(tc, build_error_carries_log);
  tcase_add_test(tc, missing_kernel_file);
  suite_add_tcase(su, tc);
  SRunner *sr = srunner_create(su);
  /* PoCL hangs in fork()ed children once the parent has used OpenCL. */
  srunner_set_fork_status(sr, CK_NOFORK);
  srunner_run_all(sr, CK_NORMAL);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  for (size_t f = 0; f < NFILES; f++) {
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, FILE_NAME(f));
    unlink(path);
  }
  rmdir(dir);
  return failed ? EXIT_FAILURE : EXIT_SUCCESS;
}
