#!/bin/sh
# Draws strain limiting's cost against its result from `msocl-bench strain
# --csv` output: x = the largest strain at the end (%), y = wall seconds per
# simulated second (log), one series per grid x integrator x limit joined in
# sweep order and each point labelled with its sweeps; the unlimited run of
# each grid and integrator a black square. Runs that blew up are listed in
# the title (there were none when this was written).
#
#   bench/plot_strain.sh strain.csv chart.png [title]
#
# Needs gnuplot (Debian: apt-get install gnuplot-nox) and awk.
set -eu
if [ $# -lt 2 ]; then
  echo "usage: $0 STRAIN.csv OUT.png [TITLE]" >&2
  exit 2
fi
csv=$1 out=$2 title=${3:-}
command -v gnuplot >/dev/null || { echo "$0: gnuplot not found" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

awk -F, -v dir="$tmp" -v out="$out" -v title="$title" '
NR == 1 {
  for (i = 1; i <= NF; i++) col[$i] = i
  split("device integrator grid dt steps seconds error status strain sweeps", want, " ")
  for (w in want) if (!(want[w] in col)) {
    print "plot_strain.sh: column " want[w] " missing" > "/dev/stderr"; exit 1
  }
  next
}
{
  st = $col["status"]; kind = $col["strain"]
  if (kind == "") next
  grid = $col["grid"]; integ = $col["integrator"]
  dt = $col["dt"] + 0; steps = $col["steps"] + 0; secs = $col["seconds"] + 0
  if (st != "ok") { bad = bad sprintf(" %s^2 %s %s %s;", grid, integ, kind, $col["sweeps"]); next }
  if (dt <= 0 || steps <= 0 || secs <= 0) next
  x = 100 * $col["error"]; y = secs / (steps * dt)
  if (dev == "") { dev = $col["device"]; T = dt * steps }
  if (ymin == 0 || y < ymin) ymin = y
  if (y > ymax) ymax = y
  if (x > xmax) xmax = x
  if (kind == "none") { none = none sprintf("%.6g %.6g %s^2/%s\n", x, y, grid, integ); next }
  key = grid SUBSEP integ SUBSEP kind
  if (!(key in sid)) { sid[key] = ++ns; sname[ns] = grid "^2 " integ " " kind; skind[ns] = kind; sgrid[ns] = grid }
  s = sid[key]
  data[s] = data[s] sprintf("%.6g %.6g %s\n", x, y, $col["sweeps"])
  if (!(grid in gi)) gi[grid] = ++ng
}
END {
  if (ns == 0) { print "plot_strain.sh: no strain-limited runs in the CSV" > "/dev/stderr"; exit 1 }
  g = dir "/plot.gp"
  print "set terminal pngcairo size 1200,800 font \"Sans,11\"" > g
  print "set output \"" out "\"" > g
  print "set logscale y" > g
  ylo = 10 ^ (int(log(ymin) / log(10) + 1000) - 1000)
  yhi = 10 ^ (int(log(ymax) / log(10) + 1000.999) - 1000)
  printf "set xrange [0:%g]; set yrange [%g:%g]\n", (int(xmax / 5) + 2) * 5, ylo, yhi > g
  print "set xlabel \"largest strain at the end, % (limit 10%)\"" > g
  print "set ylabel \"wall seconds per simulated second\"" > g
  print "set grid xtics ytics mytics lc rgb \"#dddddd\"" > g
  print "set key outside right top box opaque spacing 1.1" > g
  print "set arrow 1 from 10,graph 0 to 10,graph 1 nohead dt 2 lc rgb \"#888888\"" > g
  t = title
  if (t == "") {
    t = sprintf("Strain limiting: soft tablecloth draped for %.3g s at half the stable step", T)
    dn = dev; gsub("@", "at", dn); t = t "\\n" dn
    t = t "\\n{/*0.85 each point: the sweeps a step"
    t = t (bad == "" ? "; no run blew up}" : "; blew up:" bad "}")
  }
  print "set title \"" t "\"" > g
  split("#1f77b4 #d62728 #2ca02c #9467bd #ff7f0e #8c564b", colours, " ")
  plot = "plot "
  for (s = 1; s <= ns; s++) {
    f = dir "/s" s ".dat"
    printf "%s", data[s] > f; close(f)
    c = colours[(s - 1) % 6 + 1]
    dash = skind[s] == "velocity" ? 2 : 1
    pt = gi[sgrid[s]] == 1 ? 7 : 5
    plot = plot sprintf("\"%s\" using 1:2 with linespoints lc rgb \"%s\" dt %d lw 2 pt %d ps 1.2 title \"%s\", ", f, c, dash, pt, sname[s])
    plot = plot sprintf("\"%s\" using 1:2:3 with labels offset 0.9,0.6 tc rgb \"%s\" font \",9\" notitle, ", f, c)
  }
  if (none != "") {
    f = dir "/none.dat"; printf "%s", none > f; close(f)
    plot = plot sprintf("\"%s\" using 1:2 with points lc rgb \"#000000\" pt 4 ps 1.6 lw 2 title \"unlimited\", ", f)
    plot = plot sprintf("\"%s\" using 1:2:3 with labels offset 0,-1 font \",9\" notitle, ", f)
  }
  sub(/, $/, "", plot)
  print plot > g
}' "$csv"
gnuplot "$tmp/plot.gp"
echo "wrote $out"
