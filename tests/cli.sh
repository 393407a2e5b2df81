#!/bin/sh
# The example programs' command lines: -h and --help answer on stdout with
# the defaults, exit 0; a bad option or value exits 2 with a message on
# stderr that names it; -o is checked before any stepping; tiny runs write
# OBJ and PLY. The checks of the command line need no device; the runs
# skip (77) when there is no OpenCL device. Run from the build root.
tmp=$(mktemp -d) || exit 99
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

# A program that ignored a bad -o would run for minutes: stopped after 60 s.
limit=
if command -v timeout >/dev/null 2>&1; then limit="timeout 60"; fi

# run PROG ARGS...: exit status in $rc, output in $tmp/out and $tmp/err
run() {
  $limit "$@" >"$tmp/out" 2>"$tmp/err"
  rc=$?
}

# help PROG WORD...: -h and --help exit 0 with a usage on stdout that
# names each WORD (the defaults), nothing on stderr
help() {
  prog=$1
  shift
  for h in -h --help; do
    run "$prog" $h
    [ "$rc" = 0 ] || fail "$prog $h exited $rc"
    grep -q '^usage: ' "$tmp/out" || fail "$prog $h: no usage on stdout"
    [ ! -s "$tmp/err" ] || fail "$prog $h wrote to stderr"
    for w in "$@"; do
      grep -q -e "$w" "$tmp/out" || fail "$prog $h: usage lacks '$w'"
    done
  done
}

# refused PROG ARGS...: exit 2, stdout empty, stderr naming the last
# option and its value ("-n abc"), or the last argument
refused() {
  prog=$1
  shift
  run "$prog" "$@"
  [ "$rc" = 2 ] || fail "$prog $*: exited $rc, not 2"
  [ ! -s "$tmp/out" ] || fail "$prog $*: wrote to stdout"
  [ -s "$tmp/err" ] || fail "$prog $*: no message on stderr"
  eval "named=\${$#}"
  if [ $# -ge 2 ]; then
    eval "opt=\${$(($# - 1))}"
    case $opt in -*) named="$opt $named" ;; esac
  fi
  grep -q -e "$named" "$tmp/err" ||
    fail "$prog $*: message does not name '$named': $(cat "$tmp/err")"
}

# output PROG ARGS...: a bad -o is refused before the run, which ARGS make
# long (seconds at least): within 10 s and without a steps/s line
output() {
  prog=$1
  shift
  for o in /nonexistent/dir/x.obj "$tmp/out.txt" "$tmp/noext"; do
    t0=$(date +%s)
    refused "$prog" "$@" -o "$o"
    t1=$(date +%s)
    [ $((t1 - t0)) -lt 10 ] || fail "$prog -o $o: refused after $((t1 - t0)) s"
    ! grep -q 'steps/s' "$tmp/out" "$tmp/err" || fail "$prog -o $o: it ran"
  done
  [ ! -e "$tmp/out.txt" ] || fail "$prog -o out.txt: left the file behind"
}

e=$(pwd)/examples
t=$e/msocl-tablecloth j=$e/msocl-jello s=$e/msocl-solid
d=$e/msocl-devices b=$e/msocl-bench g=$e/msocl-flag c=$e/msocl-character
for p in $t $j $s $d $b $g $c; do
  [ -x "$p" ] || fail "$p not built"
done
# (in $tmp: a run that should have been refused writes its mesh there)
cd "$tmp" || exit 99

help $t 'default 64' 'default 2000' 'default symplectic' 'default 10' \
  'default tablecloth.obj'
help $j 'default 8' 'default 3' 'default 0.999' 'default jello.obj'
help $s 'default 2' 'default 3' 'default 0.998' 'default ball.obj'
help $d 'default: \$MSOCL_DEVICE'
help $b 'default 2000' 'default 256'
help $g 'default 32' 'default 4' 'default 12' 'default flag-frames'
help $c 'default 20' 'default 6' 'default 12' 'default' 'character-frames'

for p in $t $j $s; do
  refused $p -x
  refused $p --bogus
  refused $p -n
  refused $p -n abc
  refused $p -n 5x
  refused $p -n ''
  refused $p -n 99999999999999999999
  refused $p -n 1.5
  refused $p -i euler
  refused $p -l grids
  refused $p -d cpu extra
done
refused $t -s -5
refused $t -s 1e3
refused $t -k -1
refused $t -p 17
refused $t -I 0
refused $t -m fast
refused $t -S hooke
for p in $j $s; do
  refused $p -t -5
  refused $p -t 0
  refused $p -t inf
  refused $p -a 1.5
  refused $p -T 1
done
refused $t -n 0
refused $t -n 1
refused $t -n 13379
refused $j -n 0
refused $j -n 65
refused $s -n -1
refused $s -n 8
refused $d -x
refused $d cpu gpu
refused $b --bogus
for a in -x --bogus "-n 3" "-n 513" "-n abc" "-t 0" "-t inf" "-F 0" "-F 241" extra \
  "-o /nonexistent/dir/frames"; do
  # shellcheck disable=SC2086
  refused $g $a
done
touch "$tmp/afile"
refused $g -o "$tmp/afile"
refused $c -o "$tmp/afile"
refused $g -t 1e-320
refused $b table1 -s 0
refused $b table1 -s abc

output $t -n 256 -s 100000000
output $j -n 32 -t 10000
output $s -n 6 -t 10000

$d >/dev/null 2>&1 || { echo "no OpenCL device: SKIP the runs"; exit 77; }
for p in "$t -n 4 -s 10" "$j -n 2 -t 0.01" "$s -n 0 -t 0.01"; do
  for ext in obj ply; do
    f=$tmp/mesh.$ext
    rm -f "$f"
    run $p -o "$f"
    [ "$rc" = 0 ] || fail "$p -o $f exited $rc: $(cat "$tmp/err")"
    grep -q "^wrote $f\$" "$tmp/out" || fail "$p -o $f: no 'wrote' line"
    [ -s "$f" ] || fail "$p -o $f: no file"
    want='# libmsocl'
    [ "$ext" = obj ] || want=ply
    head -n 1 "$f" | grep -q "^$want" || fail "$p -o $f: not $ext: $(head -n 1 "$f")"
  done
done
# explicit Euler at its own stable step (it blew up at symplectic's)
run $t -n 8 -s 20 -i explicit -o "$tmp/explicit.obj"
[ "$rc" = 0 ] || fail "$t -i explicit exited $rc: $(cat "$tmp/err")"
# the flag: one OBJ a frame, each with the flag's points
run $g -n 4 -t 0.25 -F 8 -o "$tmp/frames"
[ "$rc" = 0 ] || fail "$g exited $rc: $(cat "$tmp/err")"
[ "$(ls "$tmp/frames" | wc -l)" = 3 ] || fail "$g: frames $(ls "$tmp/frames")"
[ "$(grep -c '^v ' "$tmp/frames/flag-0002.obj")" = 24 ] ||
  fail "$g: not 6 x 4 points in the last frame"
refused $c -n 3
refused $c -t 0
# the character: a cape and a body a frame, the cape's top edge on the
# shoulders, 1.44 m up, in every frame
run $c -n 4 -t 0.25 -F 8 -o "$tmp/walk"
[ "$rc" = 0 ] || fail "$c exited $rc: $(cat "$tmp/err")"
[ "$(ls "$tmp/walk" | wc -l)" = 6 ] || fail "$c: frames $(ls "$tmp/walk")"
[ "$(grep -c '^v ' "$tmp/walk/cape-0002.obj")" = 32 ] ||
  fail "$c: not 4 x 8 points in the last frame"
awk '$1 == "v" && ++k <= 4 && ($3 < 1.439 || $3 > 1.441) { bad = 1 }
  END { exit bad }' "$tmp/walk/cape-0002.obj" ||
  fail "$c: the cape's top edge left the shoulders"
grep -q '^f ' "$tmp/walk/body-0002.obj" || fail "$c: no body faces"
# no vertex twice (a pole ring on its pole, a sphere's equators on each
# other: faces without area, which msocl_model_from_obj refuses)
[ -z "$(grep '^v ' "$tmp/walk/body-0002.obj" | sort | uniq -d)" ] ||
  fail "$c: the body repeats a vertex"
echo "PASS"
