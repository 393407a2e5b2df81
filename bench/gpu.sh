#!/bin/sh
# Every GPU measurement the benchmarks still lack, in stages that each fit
# the GPU machine's 10-minute command limit. Run it in the build directory
# of a release tarball on the GPU machine (../shared/gpu/README.md), after
# `. .gpu/env.sh`:
#
#   bench/gpu.sh OUTDIR [STAGE ...]
#
# Stages (default: all, in this order):
#   devices    msocl-devices: what the machine offers
#   verify     the kernels on the GPU agree with themselves: the tablecloth
#              at 128^2 with BUFFER, GRID, IMAGE2D, the fused step of
#              BUFFER and of GRID, and BUFFER with spring classes (-C) and
#              values (-V) forced, final meshes compared bit for bit
#              with BUFFER's (as make check does on PoCL; the GPU
#              machine has no Check); then `msocl-bench verify`: every
#              layout, integrator, contact and relaxed math against the
#              double host reference with the tests' tolerances, and
#              against the same runs on PoCL saved on the build machine
#              in MSOCL_BENCH_AGAINST (default ../.gpu/verify_pocl.txt,
#              made there by `examples/msocl-bench verify -d cpu --save
#              .gpu/verify_pocl.txt`)                   (under a minute)
#   table1q    Table 1 trimmed for the first command: each layout at
#              MSOCL_BENCH_GRIDS (default 128,512,1024,2048), 200 steps
#              best of 3, the copy bandwidth, no serial C  (a minute or two)
#   table1     Table 1 on the GPU: 48..2048 per layout, with the one-kernel
#              step (--fused), BUFFER's classes and values rows
#              (--values), serial C beside it           (about 7 min)
#   precision  the work-precision data on the GPU, both math modes (1 min)
#   split      the tablecloth at 1024^2: GPU alone, PoCL's CPU alone, and
#              split over both with calibrated weights, boundary first
#              and with -O (kernels then copies)  (about 3 min)
#   lattice    the jello cube at 32^3..128^3: BUFFER and GRID (forced)
#              with symplectic Euler, Verlet, RK4 and implicit Euler, GRID
#              against BUFFER's speed and final positions (the error
#              column: 0 where bitwise)                    (minutes)
#   strain     strain limiting's cost against its result on the GPU: the
#              soft tablecloth at 64^2 and 256^2 draped for 1 s,
#              unlimited and each limit at 1..20 sweeps, symplectic
#              Euler, Verlet, RK4 and implicit Euler       (a few minutes)
#   wind       wind on a flag at 128..512^2 against the windless flag
#              (issue 16's 1.3x, missed on PoCL's CPU)      (under a minute)
#   live       live scenes' costs on the GPU: the 10 000-triangle mesh
#              collider at 128^2 and 512^2 (static, moving every 10
#              steps and every 60 Hz frame; the GPUs' device-built grid
#              and per-point search), the analytic colliders at rest and
#              moving                                       (a few minutes)
# Each stage writes STAGE.txt (and .csv) under OUTDIR with the command at
# the top; with MSOCL_BENCH_PACK=FILE, OUTDIR is then packed into the
# tarball FILE (the GPU machine returns a few files from $OUT: keep OUTDIR
# outside it). The first command, about 4 minutes on the GPU machine:
#   . .gpu/env.sh; tar xf libmsocl-0.1.0.tar.gz && cd libmsocl-0.1.0 &&
#   ./configure -q && make -j16 >/dev/null && MSOCL_BENCH_PACK=$OUT/first.tgz
#   bench/gpu.sh /tmp/gpu1 devices verify table1q wind
# the second, if time is left: `... bench/gpu.sh /tmp/gpu2 split
# precision` packed into $OUT/second.tgz. Back on the build machine:
# bench/plot.sh OUTDIR/precision.csv
# OUTDIR/precision.png and bench/plot_strain.sh OUTDIR/strain.csv
# OUTDIR/strain.png, then commit OUTDIR as bench/results/<gpu>/.
# MSOCL_BENCH_DEVICE=cpu runs the single-device stages on PoCL's CPU
# instead (a rehearsal; the split stage's specs stay gpu and cpu).
set -eu
[ $# -ge 1 ] || { awk 'NR > 1 && !/^#/ { exit } NR > 1' "$0"; exit 2; }
out=$1
shift
stages=${*:-devices verify table1 precision split wind lattice strain live}
dev=${MSOCL_BENCH_DEVICE:-gpu}
mkdir -p "$out"
bench=./examples/msocl-bench
[ -x "$bench" ] || { echo "$0: build first ($bench missing)" >&2; exit 1; }

# Largest coordinate difference between the vertices of two OBJ files.
maxdiff() {
  awk 'FNR == 1 { f++ }
    $1 == "v" { k = FNR; if (f == 1) { x[k] = $2; y[k] = $3; z[k] = $4 }
      else { d = $2 - x[k]; if (d < 0) d = -d; if (d > m) m = d
             d = $3 - y[k]; if (d < 0) d = -d; if (d > m) m = d
             d = $4 - z[k]; if (d < 0) d = -d; if (d > m) m = d } }
    END { printf "%.3g", m }' "$1" "$2"
}

# Runs a command, its output and the command itself into OUTDIR/NAME.txt.
record() {
  name=$1
  shift
  { echo "# $*"; echo "# $(date -u '+%F %T') UTC, $(uname -n)"; } > "$out/$name.txt"
  "$@" >> "$out/$name.txt" 2>&1 || echo "# exit status $?" >> "$out/$name.txt"
}

for stage in $stages; do
  echo "== $stage"
  case $stage in
  devices)
    record devices ./examples/msocl-devices
    ;;
  verify)
    : > "$out/verify.txt"
    for run in "buffer -l buffer" "grid -l grid" "image2d -l image2d" \
      "fused -l buffer -f" "classes -l buffer -C" "values -l buffer -V" \
      "gridfused -l grid -f"; do
      set -- $run
      tag=$1
      shift
      echo "# MSOCL_DEVICE=$dev ./examples/msocl-tablecloth -n 128 -s 500 $*" \
        >> "$out/verify.txt"
      MSOCL_DEVICE=$dev ./examples/msocl-tablecloth -n 128 -s 500 "$@" \
        -o "$out/verify_$tag.obj" >> "$out/verify.txt" 2>&1 ||
        echo "# exit status $?" >> "$out/verify.txt"
    done
    for tag in grid image2d fused classes values gridfused; do
      a=$out/verify_buffer.obj b=$out/verify_$tag.obj
      [ -f "$a" ] && [ -f "$b" ] || continue
      if cmp -s "$a" "$b"; then
        echo "# $tag: bitwise the BUFFER run" >> "$out/verify.txt"
      else
        echo "# $tag: DIFFERS from BUFFER by $(maxdiff "$a" "$b") m" \
          >> "$out/verify.txt"
      fi
    done
    rm -f "$out"/verify_*.obj
    against=${MSOCL_BENCH_AGAINST:-../.gpu/verify_pocl.txt}
    if [ -f "$against" ]; then
      record verify_reference env MSOCL_DEVICE=$dev $bench verify \
        --against "$against" --save "$out/verify_positions.txt" \
        --csv "$out/verify_reference.csv"
    else
      record verify_reference env MSOCL_DEVICE=$dev $bench verify \
        --save "$out/verify_positions.txt" --csv "$out/verify_reference.csv"
    fi
    ;;
  table1q)
    record table1q env MSOCL_DEVICE=$dev $bench table1 \
      -g "${MSOCL_BENCH_GRIDS:-128,512,1024,2048}" -s 1000 --big-steps 200 \
      --repeat 3 --no-serial --csv "$out/table1q.csv"
    ;;
  table1)
    record table1 env MSOCL_DEVICE=$dev $bench table1 --big-steps 200 \
      --repeat 3 --fused --values --csv "$out/table1.csv"
    ;;
  precision)
    record precision env MSOCL_DEVICE=$dev $bench precision \
      --csv "$out/precision.csv"
    ;;
  split)
    # one file, each run after the other: the ratios are same-run
    : > "$out/split.txt"
    # both: boundary first (the default); bothO: -O, kernels then copies
    for run in "gpu 1 gpu" "cpu 1 cpu" "gpu,cpu 2 both -c 20" \
      "gpu,cpu 2 bothO -c 20 -O" "gpu 1 gpu" "gpu,cpu 2 both -c 20" \
      "gpu,cpu 2 bothO -c 20 -O"; do
      set -- $run
      spec=$1 parts=$2 tag=$3
      shift 3
      echo "# MSOCL_DEVICE=$spec ./examples/msocl-tablecloth -n 1024 -s 500 -p $parts $*" \
        >> "$out/split.txt"
      MSOCL_DEVICE=$spec ./examples/msocl-tablecloth -n 1024 -s 500 -p "$parts" "$@" \
        -o "$out/split_$tag.obj" >> "$out/split.txt" 2>&1 ||
        echo "# exit status $?" >> "$out/split.txt"
    done
    # The GPU and the CPU round differently (NVIDIA's sqrt and division
    # are correctly rounded only when asked, fma, ...): the split is
    # compared with each device alone by the largest coordinate difference.
    for alone in gpu cpu; do
      a=$out/split_$alone.obj b=$out/split_both.obj
      [ -f "$a" ] && [ -f "$b" ] || continue
      echo "# split vs $alone alone after 500 steps: max |dx| $(maxdiff "$a" "$b") m" \
        >> "$out/split.txt"
    done
    # the two orders do the same arithmetic on each device: bitwise alike
    # when both runs calibrated to the same ranges (see their part lines)
    a=$out/split_both.obj b=$out/split_bothO.obj
    if [ -f "$a" ] && [ -f "$b" ]; then
      echo "# boundary first vs kernels then copies: max |dx| $(maxdiff "$a" "$b") m" \
        >> "$out/split.txt"
    fi
    rm -f "$out"/split_*.obj
    ;;
  lattice)
    record lattice env MSOCL_DEVICE=$dev $bench lattice -g 32,64,128 \
      -i symplectic,verlet,rk4,implicit -s 200 --repeat 3 \
      --csv "$out/lattice.csv"
    ;;
  strain)
    record strain env MSOCL_DEVICE=$dev $bench strain -g 64,256 -T 1 \
      -i symplectic,verlet,rk4,implicit --csv "$out/strain.csv"
    ;;
  wind)
    record wind env MSOCL_DEVICE=$dev $bench wind -s 1000 --repeat 3 \
      --csv "$out/wind.csv"
    ;;
  live)
    record meshcollider env MSOCL_DEVICE=$dev $bench meshcollider \
      -g 128,512 -s 1000 --repeat 3 --csv "$out/meshcollider.csv"
    record colliders env MSOCL_DEVICE=$dev $bench colliders -g 256,1024 \
      -s 500 --repeat 3 --csv "$out/colliders.csv"
    ;;
  *)
    echo "$0: unknown stage '$stage'" >&2
    exit 2
    ;;
  esac
done
if [ -n "${MSOCL_BENCH_PACK:-}" ]; then
  tar czf "$MSOCL_BENCH_PACK" -C "$(dirname "$out")" "$(basename "$out")"
  echo "packed $out into $MSOCL_BENCH_PACK"
fi
