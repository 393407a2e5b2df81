#!/bin/sh
# Draws the work-precision chart from `msocl-bench precision --csv` output:
# log-log, x = RMS position error at T relative to the cloth's size, y = wall
# seconds per simulated second, one series per integrator x math mode (x
# device), points joined in dt order. Runs that blew up are drawn as crosses
# in their series' colour in an "unstable" band at the right edge, at their
# time.
#
#   bench/plot.sh precision.csv chart.png [title]
#
# Needs gnuplot (Debian: apt-get install gnuplot-nox) and awk.
set -eu
if [ $# -lt 2 ]; then
  echo "usage: $0 PRECISION.csv OUT.png [TITLE]" >&2
  exit 2
fi
csv=$1 out=$2 title=${3:-}
command -v gnuplot >/dev/null || { echo "$0: gnuplot not found" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# One data file per series (x y status), and a gnuplot script. The bench
# writes no quoted fields, so splitting on commas is safe.
awk -F, -v dir="$tmp" -v out="$out" -v title="$title" '
NR == 1 {
  for (i = 1; i <= NF; i++) col[$i] = i
  split("device integrator math grid dt steps seconds error status", want, " ")
  for (w in want) if (!(want[w] in col)) {
    print "plot.sh: column " want[w] " missing" > "/dev/stderr"; exit 1
  }
  next
}
{
  st = $col["status"]
  if (st == "reference") { refdt = $col["dt"]; refconv = $col["error"]; next }
  if (st != "ok" && st != "unstable" && st != "nonfinite") next
  dev = $col["device"]; integ = $col["integrator"]; math = $col["math"]
  dt = $col["dt"] + 0; steps = $col["steps"] + 0; secs = $col["seconds"] + 0
  if (dt <= 0 || steps <= 0 || secs <= 0) next
  if (dt > dtmax) dtmax = dt
  if (dtmin == 0 || dt < dtmin) dtmin = dt
  grid = $col["grid"]
  if (!(dev in devs)) { devs[dev] = ++ndev; devname[ndev] = dev }
  key = dev SUBSEP integ SUBSEP math
  if (!(key in sid)) {
    sid[key] = ++ns; sdev[ns] = dev; sint[ns] = integ; smath[ns] = math
  }
  s = sid[key]
  y = secs / (steps * dt)
  if (st == "ok") {
    e = $col["error"] + 0
    if (e <= 0) next
    if (e > emax) emax = e
    if (emin == 0 || e < emin) emin = e
    ok[s] = ok[s] sprintf("%.9g %.9g\n", e, y)
    if (dt * steps > T) T = dt * steps
  } else {
    bad[s] = bad[s] sprintf("%.9g\n", y); nbad++
  }
  if (ymin == 0 || y < ymin) ymin = y
  if (y > ymax) ymax = y
}
END {
  if (ns == 0) { print "plot.sh: no runs in the CSV" > "/dev/stderr"; exit 1 }
  if (emax == 0) { emin = 1e-6; emax = 1 }
  # the unstable band: one decade right of the largest finite error
  d = int(log(emax) / log(10) + 1000.999) - 1000
  xband = 10 ^ (d + 0.5); xmax = 10 ^ (d + 1)
  xmin = 10 ^ (int(log(emin) / log(10) + 1000) - 1000)
  ylo = 10 ^ (int(log(ymin) / log(10) + 1000) - 1000)
  yhi = 10 ^ (int(log(ymax) / log(10) + 1000.999) - 1000)
  split("symplectic explicit verlet rk4 implicit", names, " ")
  split("#1f77b4 #d62728 #2ca02c #9467bd #ff7f0e", colours, " ")
  split("7 9 5 13 11", points, " ")
  for (i = 1; i <= 5; i++) { colour[names[i]] = colours[i]; pt[names[i]] = points[i] }
  g = dir "/plot.gp"
  print "set terminal pngcairo size 1200,800 font \"Sans,11\"" > g
  print "set output \"" out "\"" > g
  print "set datafile separator \" \"" > g
  print "set logscale xy" > g
  print "set format x \"10^{%L}\"; set format y \"10^{%L}\"" > g
  printf "set xrange [%g:%g]; set yrange [%g:%g]\n", xmin, xmax, ylo, yhi > g
  print "set xlabel \"RMS position error at T, relative to the cloth size (1 m)\"" > g
  print "set ylabel \"wall seconds per simulated second\"" > g
  print "set grid xtics ytics mxtics mytics lc rgb \"#dddddd\"" > g
  print "set key outside right top box opaque spacing 1.1" > g
  t = title
  if (t == "") {
    t = sprintf("Work-precision: %sx%s hanging cloth, T = %g s", grid, grid, T)
    for (i = 1; i <= ndev; i++) {
      dn = devname[i]; gsub("@", "at", dn)
      t = t "\\n" dn
    }
  }
  t = t sprintf("\\n{/*0.85 dt from %.3g s down to %.3g s by halves", dtmax, dtmin)
  if (refconv != "")
    t = t sprintf("; reference: double RK4, dt %.3g s, converged to %.1e", refdt, refconv)
  t = t "}"
  print "set title \"" t "\"" > g
  printf "set object 1 rect from %g,graph 0 to graph 1,graph 1 behind fc rgb \"#f4f4f4\" fs solid noborder\n", 10 ^ (d + 0.15) > g
  printf "set label 1 \"unstable\" at %g,graph 0.97 center tc rgb \"#555555\"\n", xband > g
  plot = "plot "
  for (s = 1; s <= ns; s++) {
    f = dir "/s" s ".dat"; fb = dir "/u" s ".dat"
    printf "%s", ok[s] > f; close(f)
    printf "%s", bad[s] > fb; close(fb)
    c = colour[sint[s]]; if (c == "") c = "#000000"
    p = pt[sint[s]] + 0; if (p == 0) p = 1
    relaxed = smath[s] == "relaxed"
    if (relaxed) p = p - 1          # the open variant of the point type
    name = sint[s] " " smath[s]
    if (ndev > 1) { split(sdev[s], dw, " "); name = name " (" dw[1] ")" }
    dash = relaxed ? 2 : 1
    # devices: each further device gets a thinner line
    lw = 2.0 / devs[sdev[s]]
    if (ok[s] != "")
      plot = plot sprintf("\"%s\" using 1:2 with linespoints lc rgb \"%s\" dt %d lw %g pt %d ps 1.3 title \"%s\", ", f, c, dash, lw, p, name)
    if (bad[s] != "")
      plot = plot sprintf("\"%s\" using (%g*(1+%g)):1 with points lc rgb \"%s\" pt 2 ps 2 lw 2 %s, ", fb, xband, (relaxed ? 0.25 : -0.2), c, ok[s] == "" ? "title \"" name " (unstable)\"" : "notitle")
  }
  if (nbad > 0)
    plot = plot "NaN with points lc rgb \"#555555\" pt 2 ps 2 lw 2 title \"blew up (at its time)\""
  else
    sub(/, $/, "", plot)
  print plot > g
}' "$csv"
gnuplot "$tmp/plot.gp"
echo "wrote $out"
