/* Assertions the host-side test programs share: a failed call reports the
 * code's name and the library's message, which is what a reader of a
 * failed run needs first. */
#ifndef MSOCL_TEST_EXPECT_H
#define MSOCL_TEST_EXPECT_H

#include <check.h>
#include <math.h>
#include <string.h>

#include "msocl.h"

#define EXPECT(call, code)                                                     \
  do {                                                                         \
    int rc_ = (call);                                                          \
    ck_assert_msg(rc_ == (code), "%s: got %s (%d), want %s; \"%s\"", #call,    \
                  msocl_err_name(rc_), rc_, #code, msocl_last_error());        \
  } while (0)

#define OK(call) EXPECT(call, MSOCL_OK)

#define SAYS(text)                                                             \
  ck_assert_msg(strstr(msocl_last_error(), (text)) != NULL,                    \
                "message \"%s\" does not contain \"%s\"", msocl_last_error(),  \
                (text))

#define NEAR(a, b, tol)                                                        \
  ck_assert_msg(fabs((double)(a) - (double)(b)) <= (tol),                      \
                "%s = %.9g, want %.9g", #a, (double)(a), (double)(b))

/* Runs a host-side suite (forking: no OpenCL in these programs); the exit
 * status for automake. */
static inline int expect_run(Suite *su)
{
  SRunner *sr = srunner_create(su);
  srunner_run_all(sr, CK_NORMAL);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  return failed ? 1 : 0;
}

#endif
