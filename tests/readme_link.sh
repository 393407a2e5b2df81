#!/bin/sh
# The README's "Using the library" program, built against the installed
# library the way the README says: pkg-config from PKG_CONFIG_PATH, and the
# run-time path from LD_LIBRARY_PATH. Run by `make installcheck` (and so by
# `make distcheck`).  Usage: readme_link.sh README.md PREFIX-LIBDIR BINDIR
set -eu
readme=$1 libdir=$2 bindir=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The first C block after the "## Using the library" heading.
sed -n '/^## Using the library/,$p' "$readme" |
  sed -n '/^```c$/,/^```$/p' | sed '1d;/^```$/,$d' > "$work/demo.c"
grep -q 'msocl_sim_step' "$work/demo.c" || {
  echo "readme_link: no C example found in $readme" >&2; exit 1; }

export PKG_CONFIG_PATH="$libdir/pkgconfig${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
# shellcheck disable=SC2046 # pkg-config's words are meant to split
${CC:-cc} -o "$work/demo" "$work/demo.c" $(pkg-config --cflags --libs libmsocl)
echo "readme_link: demo.c built with $(pkg-config --cflags --libs libmsocl)"

export LD_LIBRARY_PATH="$libdir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
# No OpenCL device: built and linked is all this machine can show.
if ! "$bindir/msocl-devices" >/dev/null 2>&1; then
  echo "readme_link: no OpenCL device; not running the demo"; exit 0
fi
out=$(MSOCL_DEVICE=${MSOCL_DEVICE:-cpu} "$work/demo")
echo "readme_link: $out"
case $out in "far corner at y = "*) ;; *) exit 1 ;; esac
