/* A monotonic clock for the library's own timings: calibration, the
 * split's waits, the sweep's steps a launch. */
#include "config.h"
#include "internal.h"

#include <time.h>

double msocl__seconds(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}
