#!/bin/sh
# What the state costs a frame loop, against another build: bench/state_io.c
# (public API only) linked to this build's libmsocl and to OTHER's, run
# alternately ROUNDS times at each size, with an LD_PRELOAD shim (written
# below) that counts the bytes of the OpenCL buffers a process holds.
#
#   bench/state_io.sh OTHER_BUILD_ROOT [SIZES] [ROUNDS]   (from the build root)
#
# e.g. git worktree add /tmp/old 0270594 && (cd /tmp/old && autoreconf -fi
# && ./configure -q && make -j2); bench/state_io.sh /tmp/old "256 1024" 3
set -eu
other=${1:?usage: $0 OTHER_BUILD_ROOT [SIZES] [ROUNDS]}
sizes=${2:-256 1024}
rounds=${3:-3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# clCreateBuffer less clReleaseMemObject, answered by clmem_now()
cat > "$tmp/clmem.c" <<'SHIM'
#define _GNU_SOURCE
#define CL_TARGET_OPENCL_VERSION 300
#include <CL/cl.h>
#include <dlfcn.h>
#include <stddef.h>
enum { MAX_LIVE = 1 << 16 };
static struct { cl_mem m; size_t bytes; } live[MAX_LIVE];
static int nlive;
static size_t held;
cl_mem clCreateBuffer(cl_context c, cl_mem_flags f, size_t size, void *host,
                      cl_int *err)
{
  cl_mem (*real)(cl_context, cl_mem_flags, size_t, void *, cl_int *);
  *(void **)&real = dlsym(RTLD_NEXT, "clCreateBuffer");
  cl_mem m = real(c, f, size, host, err);
  if (m && nlive < MAX_LIVE) {
    live[nlive].m = m;
    live[nlive++].bytes = size;
    held += size;
  }
  return m;
}
cl_int clReleaseMemObject(cl_mem m)
{
  cl_int (*real)(cl_mem);
  *(void **)&real = dlsym(RTLD_NEXT, "clReleaseMemObject");
  for (int q = 0; q < nlive; q++)
    if (live[q].m == m) {
      held -= live[q].bytes;
      live[q] = live[--nlive];
      break;
    }
  return real(m);
}
size_t clmem_now(void) { return held; }
SHIM
cc -O2 -shared -fPIC "$tmp/clmem.c" -o "$tmp/clmem.so" -ldl
src=$(cd "$(dirname "$0")" && pwd)/state_io.c
for b in this other; do
  root=$PWD
  [ $b = other ] && root=$(cd "$other" && pwd)
  cc -std=c99 -O2 -I"$root/lib" "$src" -L"$root/.libs" -lmsocl -ldl \
     -Wl,-rpath,"$root/.libs" -o "$tmp/state_io_$b"
done
r=1
while [ $r -le "$rounds" ]; do
  for b in other this; do
    for n in $sizes; do
      frames=$((300 * 256 * 256 / (n * n) + 10))
      printf '%s round %d: ' $b $r
      LD_PRELOAD="$tmp/clmem.so" POCL_CACHE_DIR="$tmp/cache_$b" \
        "$tmp/state_io_$b" "$n" "$frames" 100
    done
  done
  r=$((r + 1))
done
