#!/bin/sh
# The README's "Using the library" and "A moving scene" programs, built
# against the installed library the way the README says: pkg-config from
# PKG_CONFIG_PATH, and the run-time path from LD_LIBRARY_PATH. Run by `make installcheck` (and so by
# `make distcheck`).  Usage: readme_link.sh README.md PREFIX-LIBDIR BINDIR
set -eu
readme=$1 libdir=$2 bindir=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The first C block after a heading: demo.c after "## Using the library",
# scene.c (the frame loop) after "### A moving scene".
block() {
  sed -n "/^$1/,\$p" "$readme" |
    sed -n '/^```c$/,/^```$/p' | sed '1d;/^```$/,$d' > "$work/$2"
  grep -q 'msocl_sim_step' "$work/$2" || {
    echo "readme_link: no C example after '$1' in $readme" >&2; exit 1; }
}
block '## Using the library' demo.c
block '### A moving scene' scene.c

export PKG_CONFIG_PATH="$libdir/pkgconfig${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
# shellcheck disable=SC2046 # pkg-config's words are meant to split
${CC:-cc} -o "$work/demo" "$work/demo.c" $(pkg-config --cflags --libs libmsocl)
# shellcheck disable=SC2046
${CC:-cc} -o "$work/scene" "$work/scene.c" \
  $(pkg-config --cflags --libs libmsocl) -lm
echo "readme_link: demo.c and scene.c built with $(pkg-config --cflags --libs libmsocl)"

export LD_LIBRARY_PATH="$libdir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
# No OpenCL device: built and linked is all this machine can show.
if ! "$bindir/msocl-devices" >/dev/null 2>&1; then
  echo "readme_link: no OpenCL device; not running the demo"; exit 0
fi
out=$(MSOCL_DEVICE=${MSOCL_DEVICE:-cpu} "$work/demo")
echo "readme_link: $out"
case $out in "far corner at y = "*) ;; *) exit 1 ;; esac

# The frame loop on a 16 x 16 cloth hanging in the x-y plane, 0.8 m a side.
awk 'BEGIN {
  n = 16
  for (j = 0; j < n; j++)
    for (i = 0; i < n; i++)
      printf "v %.4f %.4f 0\n", 0.8 * i / (n - 1), 1.0 - 0.8 * j / (n - 1)
  for (j = 0; j + 1 < n; j++)
    for (i = 0; i + 1 < n; i++) {
      p = j * n + i + 1
      printf "f %d %d %d\nf %d %d %d\n", p, p + 1, p + n + 1, p, p + n + 1, p + n
    }
}' > "$work/cloth.obj"
out=$(cd "$work" && MSOCL_DEVICE=${MSOCL_DEVICE:-cpu} ./scene cloth.obj)
echo "readme_link: $out"
case $out in "48 frames of "*"; lowest point at y = "*) ;; *) exit 1 ;; esac
[ -s "$work/frame-047.obj" ] || { echo "readme_link: no frames" >&2; exit 1; }
