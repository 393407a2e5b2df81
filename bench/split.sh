#!/bin/sh
# One model on one device and split over two, side by side in one run:
# the tablecloth at a few sizes, one device, then two boundary first (the
# default: copies beside the interior's kernels), then two with -O (all
# kernels, then all copies), back to back (this machine is noisy: read the
# ratio of neighbouring lines); the final meshes compared byte for byte.
#
#   bench/split.sh [SPEC] [SIZES] [REPEATS]   (run from the build root)
#
# SPEC names the two devices (default 0:0,0:1 - with
# POCL_DEVICES="pthread pthread", two PoCL CPU devices); on the GPU
# machine, e.g. "gpu,cpu" with -c calibration added through EXTRA.
set -eu
spec=${1:-0:0,0:1}
sizes=${2:-128 256 512}
repeats=${3:-2}
extra=${EXTRA:-}
prog=./examples/msocl-tablecloth
[ -x "$prog" ] || { echo "$0: build first ($prog missing)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "# MSOCL_DEVICE=$spec POCL_DEVICES=${POCL_DEVICES:-unset}" \
  "POCL_MAX_PTHREAD_COUNT=${POCL_MAX_PTHREAD_COUNT:-unset} EXTRA='$extra'"
for n in $sizes; do
  # about the same work at every size: 2e7 vertex-steps
  steps=$((20000000 / (n * n)))
  r=1
  while [ "$r" -le "$repeats" ]; do
    for run in "1" "2" "2 -O"; do
      set -- $run
      p=$1
      tag=$(echo "$run" | tr -d ' -')
      echo "== $prog -n $n -s $steps -p $run $extra"
      # shellcheck disable=SC2086
      MSOCL_DEVICE=$spec $prog -n "$n" -s "$steps" -p $run $extra \
        -o "$tmp/split_$tag.obj" | grep -v '^wrote\|^grid\|^device'
    done
    for tag in 2 2O; do
      if cmp -s "$tmp/split_1.obj" "$tmp/split_$tag.obj"; then
        echo "   final meshes 1 and $tag identical: bitwise the one-device run"
      else
        echo "   final meshes 1 and $tag DIFFER"
      fi
    done
    r=$((r + 1))
  done
done
