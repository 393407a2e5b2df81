#!/bin/sh
# The kernels as an NVIDIA GPU's compiler would take them: the files
# joined in the library's order (Makefile.am's KERNEL_FILES), compiled by
# clang for NVPTX with sets of -D options like those engine.c passes,
# must give no warning and no double (.f64) instruction; and each .cl file
# alone, with the headers it includes, must compile without a warning. A
# GPU is lent rarely and briefly; this catches the class of fault that
# would waste it. Each set also builds without a warning for x86-64 with
# AVX2 and no AVX-512 (PoCL's haswell target), where clang's ABI notes
# on float16 once printed hundreds of lines on a user's terminal. Skips
# (77) where no clang here targets NVPTX.
set -u
srcdir=${srcdir:-.}
cc=
for c in clang-15 clang-14 clang-16 clang-17 clang; do
  if command -v "$c" >/dev/null 2>&1 &&
     echo 'kernel void k(global float *a) { a[0] = 1.0f; }' |
       "$c" -x cl -cl-std=CL1.2 -target nvptx64-nvidia-nvcl \
         -Xclang -finclude-default-header -S -o /dev/null - 2>/dev/null; then
    cc=$c
    break
  fi
done
if [ -z "$cc" ]; then
  echo "ptx.sh: no clang with the nvptx64-nvidia-nvcl target (apt-get install clang): skipped"
  exit 77
fi
files=$(sed -n '/^KERNEL_FILES =/,/[^\\]$/p' "$srcdir/Makefile.am" |
  sed 's/^KERNEL_FILES =//; s/\\$//')
[ -n "$files" ] || { echo "ptx.sh: no KERNEL_FILES in Makefile.am" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for f in $files; do cat "$srcdir/$f"; done > "$tmp/all.cl"

# Each line a build: the layouts, every collider kind and force term,
# spill and classes, 2D and 3D grids, both math modes.
G='-DMSOCL_LAYOUT_GRID -DMSOCL_SLOTS=1 -DMSOCL_DEGREE=0'
B='-DMSOCL_LAYOUT_BUFFER -DMSOCL_SLOTS=12 -DMSOCL_DEGREE=0'
I='-DMSOCL_LAYOUT_IMAGE2D -DMSOCL_SLOTS=16 -DMSOCL_DEGREE=0'
P='-DMSOCL_PLANES -DMSOCL_GRID_KINDS=7'
EXACT=-cl-fp32-correctly-rounded-divide-sqrt
cat > "$tmp/sets" <<EOF
$B $P -DMSOCL_NCOL=0 $EXACT
$B $P -DMSOCL_NCOL=1 -DMSOCL_PLANE -DMSOCL_GATHER4 -DMSOCL_DENSE=10 -DMSOCL_DAMPING $EXACT
$I $P -DMSOCL_NCOL=1 -DMSOCL_PINS -DMSOCL_DAMPING -DMSOCL_TABLE $EXACT
$G $P -DMSOCL_NCOL=2 -DMSOCL_PINS -DMSOCL_DAMPING -DMSOCL_VISCOUS -DMSOCL_AIR -DMSOCL_SPHERE -DMSOCL_PLANE $EXACT
$G $P -DMSOCL_NCOL=1 -DMSOCL_PINS -DMSOCL_SPHERE -DMSOCL_DAMPING -DMSOCL_ROWS_RING_W=80 $EXACT
$G -DMSOCL_GRID_3D -DMSOCL_PLANES -DMSOCL_GRID_KINDS=15 -DMSOCL_NCOL=0 $EXACT
-DMSOCL_LAYOUT_BUFFER -DMSOCL_SLOTS=24 -DMSOCL_DEGREE=30 -DMSOCL_SPILL -DMSOCL_CLASSES -DMSOCL_GATHER4 -DMSOCL_DENSE=21 $P -DMSOCL_NCOL=5 -DMSOCL_PLANE -DMSOCL_SPHERE -DMSOCL_TABLE -DMSOCL_CAPSULE -DMSOCL_BOX -DMSOCL_PINS -DMSOCL_VISCOUS -DMSOCL_AIR $EXACT
$I $P -DMSOCL_NCOL=2 -DMSOCL_CAPSULE -DMSOCL_BOX -DMSOCL_DAMPING -DMSOCL_RELAXED -cl-fast-relaxed-math
EOF
status=0
n=0
while read -r set; do
  n=$((n + 1))
  # shellcheck disable=SC2086 # the set is a list of options
  if ! "$cc" -x cl -cl-std=CL1.2 -target nvptx64-nvidia-nvcl \
      -Xclang -finclude-default-header -Wall -O2 -I "$srcdir/kernels" $set \
      -S -o "$tmp/k$n.s" "$tmp/all.cl" 2> "$tmp/err$n"; then
    echo "FAIL: set $n does not compile: $set"
    cat "$tmp/err$n"
    status=1
    continue
  fi
  bad=0
  # shellcheck disable=SC2086
  if ! "$cc" -x cl -cl-std=CL1.2 -target x86_64-unknown-linux-gnu \
      -march=haswell -Xclang -finclude-default-header -Wall -O2 \
      -I "$srcdir/kernels" $set -S -o "$tmp/x$n.s" "$tmp/all.cl" \
      2> "$tmp/x86err$n" || [ -s "$tmp/x86err$n" ]; then
    echo "FAIL: set $n warns or fails for x86-64 haswell: $set"
    head -n 20 "$tmp/x86err$n"
    bad=1
  fi
  if [ -s "$tmp/err$n" ]; then
    echo "FAIL: set $n warns: $set"
    cat "$tmp/err$n"
    bad=1
  fi
  f64=$(grep -c '\.f64' "$tmp/k$n.s")
  if [ "$f64" -ne 0 ]; then
    echo "FAIL: set $n has $f64 double-precision lines: $set"
    grep -m 5 '\.f64' "$tmp/k$n.s"
    bad=1
  fi
  entries=$(grep -c '^\.entry' "$tmp/k$n.s")
  [ "$bad" -eq 0 ] &&
    echo "set $n: $entries kernels, no warning (NVPTX, haswell), no double: $set"
  [ "$bad" -eq 0 ] || status=1
  # each .cl file on its own (an include missing, a helper used before
  # the header that has it), front end only
  for f in $files; do
    case $f in *.cl) ;; *) continue ;; esac
    # shellcheck disable=SC2086
    if ! "$cc" -x cl -cl-std=CL1.2 -target nvptx64-nvidia-nvcl \
        -Xclang -finclude-default-header -Wall -I "$srcdir/kernels" $set \
        -fsyntax-only "$srcdir/$f" 2> "$tmp/alone$n"; then
      echo "FAIL: $f does not compile alone with set $n: $set"
      cat "$tmp/alone$n"
      status=1
    elif [ -s "$tmp/alone$n" ]; then
      echo "FAIL: $f warns alone with set $n: $set"
      cat "$tmp/alone$n"
      status=1
    fi
  done
done < "$tmp/sets"
[ "$status" -eq 0 ] && echo "ptx.sh: $n builds clean with $cc"
exit $status
