#!/bin/sh
# Smoke test of msocl-bench: tiny runs of each mode must exit 0 and
# write CSVs with the documented header. Asserts nothing about speed.
# Skips (77) when there is no OpenCL device.
./examples/msocl-devices >/dev/null 2>&1 || { echo "no OpenCL device: SKIP"; exit 77; }
tmp=$(mktemp -d) || exit 99
trap 'rm -rf "$tmp"' EXIT
header='device,layout,integrator,math,grid,dt,steps,seconds,steps_per_s,vertex_steps_per_s,bytes_per_vertex_step,effective_GBps,copy_GBps,fraction_of_copy,error,status,strain,sweeps'
fail() { echo "FAIL: $*"; exit 1; }

./examples/msocl-bench table1 --quick -g 8 -s 5 --csv "$tmp/t1.csv" ||
  fail "table1 exited $?"
[ "$(head -n 1 "$tmp/t1.csv")" = "$header" ] || fail "table1 CSV header"
# serial C + buffer + image2d on each device, all "ok"
rows=$(tail -n +2 "$tmp/t1.csv" | wc -l)
[ "$rows" -ge 3 ] || fail "table1 CSV has $rows rows"
if tail -n +2 "$tmp/t1.csv" | grep -v ',ok,,$'; then fail "table1 run not ok"; fi

# --fused adds a one-kernel row for each gather layout, bitwise the same
# final positions as serial C (error column 0)
./examples/msocl-bench table1 --quick -g 8 -s 5 -l buffer,grid --fused \
  --csv "$tmp/f.csv" >/dev/null || fail "table1 --fused exited $?"
for l in buffer+fused grid+fused; do
  grep -q ",$l,symplectic,precise,8,.*,0,ok,,\$" "$tmp/f.csv" ||
    fail "no $l row with error 0"
done

# --expert adds the expert C yardstick, whose final positions must be
# GRID's bit for bit
./examples/msocl-bench table1 --quick -g 8,13 -s 100 -l grid --expert \
  --csv "$tmp/e.csv" >"$tmp/e.txt" || fail "table1 --expert exited $?"
grep -q ",expert-planes,symplectic,precise,13,.*,0,ok,,\$" "$tmp/e.csv" ||
  fail "no expert C row with error 0"
[ "$(grep -c 'bitwise: yes, max |diff| 0;' "$tmp/e.txt")" -eq 2 ] ||
  fail "expert C not bitwise GRID: $(grep bitwise "$tmp/e.txt")"

# --sweep-steps reaches GRID's sweep, which says its count; 9 is refused
./examples/msocl-bench table1 --quick -g 20 -s 9 -l grid --sweep-steps 3 \
  >"$tmp/w.txt" || fail "table1 --sweep-steps exited $?"
grep -q "GRID's sweep: 3 steps a launch\$" "$tmp/w.txt" ||
  fail "no sweep count of 3: $(grep sweep "$tmp/w.txt")"
./examples/msocl-bench table1 --quick -g 20 --sweep-steps 9 >/dev/null 2>&1 &&
  fail "table1 --sweep-steps 9 accepted"

# --no-serial leaves serial C out: the device's row alone
./examples/msocl-bench table1 --quick -g 8 -s 5 -l grid --no-serial \
  --csv "$tmp/n.csv" >/dev/null || fail "table1 --no-serial exited $?"
[ "$(tail -n +2 "$tmp/n.csv" | wc -l)" -eq 1 ] &&
  grep -q ',grid,symplectic,precise,8,' "$tmp/n.csv" ||
  fail "table1 --no-serial rows: $(cat "$tmp/n.csv")"

# verify: every check within the tests' tolerance on this device; its
# saved positions read back bitwise; one point saved 1 m away is caught
./examples/msocl-bench verify --quick --save "$tmp/v.txt" --csv "$tmp/v.csv" \
  >"$tmp/v.out" || fail "verify exited $?: $(grep -v ' pass ' "$tmp/v.out")"
[ "$(head -n 1 "$tmp/v.csv")" = "$header" ] || fail "verify CSV header"
[ "$(grep -c ',pass,,$' "$tmp/v.csv")" -eq 16 ] || fail "verify: not 16 passes"
./examples/msocl-bench verify --quick --against "$tmp/v.txt" >"$tmp/a.out" ||
  fail "verify --against its own save exited $?"
[ "$(grep -c ' pass  *0 (bitwise)$' "$tmp/a.out")" -eq 16 ] ||
  fail "verify --against its own save: $(cat "$tmp/a.out")"
sed -E '/^tablecloth24-grid/ s/^([^ ]+ [0-9]+) [^ ]+/\1 0x1p+0/' "$tmp/v.txt" \
  >"$tmp/bad.txt"
./examples/msocl-bench verify --quick --against "$tmp/bad.txt" >"$tmp/b.out" &&
  fail "verify passed against a moved point"
grep -q '^tablecloth24-grid-.* pass .* FAIL$' "$tmp/b.out" ||
  fail "verify did not name the moved point's check: $(cat "$tmp/b.out")"
./examples/msocl-bench verify --quick --against "$tmp/none.txt" \
  >/dev/null 2>&1 && fail "verify accepted a missing --against file"

./examples/msocl-bench precision --quick -g 5 -i symplectic,implicit \
  -m precise --levels 2 --csv "$tmp/p.csv" || fail "precision exited $?"
[ "$(head -n 1 "$tmp/p.csv")" = "$header" ] || fail "precision CSV header"
# the reference row plus 2 integrators x 2 dt values
rows=$(tail -n +2 "$tmp/p.csv" | wc -l)
[ "$rows" -ge 5 ] || fail "precision CSV has $rows rows"
grep -q ',reference,,$' "$tmp/p.csv" || fail "no reference row"
# lattice: BUFFER and GRID, GRID bitwise BUFFER (error column 0)
./examples/msocl-bench lattice --quick --csv "$tmp/l.csv" >/dev/null ||
  fail "lattice exited $?"
[ "$(head -n 1 "$tmp/l.csv")" = "$header" ] || fail "lattice CSV header"
grep -q ",buffer,symplectic,precise,6,.*,ok,,\$" "$tmp/l.csv" || fail "no buffer row"
grep -q ",grid,symplectic,precise,6,.*,0,ok,,\$" "$tmp/l.csv" ||
  fail "no grid row with error 0"
# strain: unlimited plus each limit at each sweep count; every run ok with
# a strain in the error column and the limit in the last two
./examples/msocl-bench strain --quick --csv "$tmp/s.csv" >/dev/null ||
  fail "strain exited $?"
[ "$(head -n 1 "$tmp/s.csv")" = "$header" ] || fail "strain CSV header"
grep -q ",symplectic,precise,8,.*,[0-9.e-]*,ok,none,\$" "$tmp/s.csv" ||
  fail "no unlimited row"
for k in provot velocity; do
  for w in 1 3; do
    grep -q ",symplectic,precise,8,.*,[0-9.e-]*,ok,$k,$w\$" "$tmp/s.csv" ||
      fail "no $k row with $w sweeps"
  done
done
# colliders: each engine with each collider, at rest and moving, every
# run ok
./examples/msocl-bench colliders --quick --csv "$tmp/c.csv" >/dev/null ||
  fail "colliders exited $?"
[ "$(head -n 1 "$tmp/c.csv")" = "$header" ] || fail "colliders CSV header"
for e in grid buffer; do
  for c in none plane sphere table capsule box cap-mov box-mov; do
    grep -q ",$e+$c,symplectic,precise,8,.*,ok,,\$" "$tmp/c.csv" ||
      fail "no $e+$c row"
  done
done
# wind: the flag without and with wind, both ok
./examples/msocl-bench wind --quick --csv "$tmp/w.csv" >/dev/null ||
  fail "wind exited $?"
for w in none wind; do
  grep -q ",$w,symplectic,precise,16,.*,ok,,\$" "$tmp/w.csv" ||
    fail "no $w row"
done
# meshcollider: the cloth alone, with a static and a moving mesh, all ok
./examples/msocl-bench meshcollider --quick --csv "$tmp/m.csv" >/dev/null ||
  fail "meshcollider exited $?"
for w in none static moving; do
  grep -q ",$w,symplectic,precise,16,.*,ok,,\$" "$tmp/m.csv" ||
    fail "no mesh $w row"
done
echo "PASS"
