#!/bin/sh
# Renders a scene's final mesh (an OBJ the examples write) to a PNG with
# gnuplot: the mesh's faces as lit polygons, with the scene's collider.
#
#   docs/render.sh tablecloth|jello|ball IN.obj OUT.png
#
# tablecloth: the round table (radius 0.35 m, top at y = 0) under the cloth;
# jello, ball: the ground, y = 0. Needs gnuplot 5.4 or later
# (apt-get install gnuplot-nox). The OBJ's y axis is up.
set -eu

usage() {
  echo "usage: $0 tablecloth|jello|ball IN.obj OUT.png" >&2
  exit 2
}
[ $# -eq 3 ] || usage
scene=$1 obj=$2 png=$3
case $scene in
tablecloth | jello | ball) ;;
*) usage ;;
esac
[ -r "$obj" ] || { echo "$0: cannot read $obj" >&2; exit 1; }
command -v gnuplot >/dev/null 2>&1 ||
  { echo "$0: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }

tmp=$(mktemp -d "${TMPDIR:-/tmp}/msocl-render.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM

# gnuplot's pm3d lights grid surfaces (its "with polygons" shades level
# faces wrongly in 5.4), so every face goes out as a 2 x 2 grid of its own:
# quad(p, q, r, s) prints the scans "p q" and "s r". A triangle a b c is
# the quadrangle a b m c, m the middle of b c: pm3d leaves a quadrangle
# with a repeated corner unlit, and takes its normal from three corners,
# which must not lie on a line. Larger faces are cut into a fan.
# OBJ (x, y, z) becomes gnuplot (x, -z, y), a rotation that puts y up.
# Faces may be "f a b c", "f a/t b/t c/t" or "f a//n b//n c//n"; negative
# indices count back from the last vertex.
quad='function quad(p, q, r, s) { printf "%s\n%s\n\n%s\n%s\n\n\n", p, q, s, r }'
awk "$quad"'
  function at(i) { return x[i] " " y[i] " " z[i] }
  function mid(i, j) {
    return (x[i] + x[j]) / 2 " " (y[i] + y[j]) / 2 " " (z[i] + z[j]) / 2
  }
  $1 == "v" { n++; x[n] = $2; y[n] = -$4; z[n] = $3; next }
  $1 == "f" {
    for (k = 2; k <= NF; k++) {
      split($k, part, "/")
      i = part[1] + 0
      if (i < 0) i = n + 1 + i
      if (i < 1 || i > n) { print "bad face: " $0 > "/dev/stderr"; exit 1 }
      c[k - 1] = i
    }
    for (k = 2; k < NF - 1; k++)
      quad(at(c[1]), at(c[k]), mid(c[k], c[k + 1]), at(c[k + 1]))
  }
' "$obj" >"$tmp/mesh.dat"
[ -s "$tmp/mesh.dat" ] || { echo "$0: no faces in $obj" >&2; exit 1; }

# The collider, in pieces about as small as the mesh's faces: pm3d sorts
# faces by the depth of their centres, right only for small ones.
if [ "$scene" = tablecloth ]; then
  # The round table: its side from the top down to -0.75 m, and its top in
  # rings; drawn 2 cm inside and 1 cm below the true surface, where the
  # cloth lies on it.
  awk "$quad"'
    function at(rad, a, h) { return rad * cos(a) " " rad * sin(a) " " h }
    BEGIN {
      pi = atan2(0, -1); r = 0.33; top = -0.01; bottom = -0.75
      m = 144; rows = 50; rings = 22
      for (k = 0; k < m; k++) {
        a0 = 2 * pi * k / m; a1 = 2 * pi * (k + 1) / m
        for (j = 0; j < rows; j++) {
          h0 = top + (bottom - top) * j / rows
          h1 = top + (bottom - top) * (j + 1) / rows
          quad(at(r, a0, h0), at(r, a1, h0), at(r, a1, h1), at(r, a0, h1))
        }
        for (j = 0; j < rings; j++)
          quad(at(r * j / rings, a0, top), at(r * (j + 1) / rings, a0, top),
               at(r * (j + 1) / rings, a1, top), at(r * j / rings, a1, top))
      }
    }' >"$tmp/collider.dat"
  view="62, 28, 1.35" mesh_colour="#b8323a" collider_colour="#8a6a4a"
else
  # The ground: a checkered square of 2 cm tiles, a file per colour.
  half=0.2
  [ "$scene" = ball ] && half=0.24
  awk -v h="$half" -v out="$tmp/collider" '
    function at(x, y) { return x " " y " 0" }
    BEGIN {
      s = 0.02; m = int(2 * h / s + 0.5)
      for (i = 0; i < m; i++)
        for (j = 0; j < m; j++) {
          x = -h + i * s; y = -h + j * s
          f = out ((i + j) % 2 ? "2.dat" : ".dat")
          printf "%s\n%s\n\n%s\n%s\n\n\n", at(x, y), at(x + s, y),
                 at(x, y + s), at(x + s, y + s) > f
        }
    }'

  view="60, 32, 1.6"
  if [ "$scene" = jello ]; then
    mesh_colour="#3fae49"
  else
    mesh_colour="#2f6fb5"
  fi
  collider_colour="#d8d8d8" collider_colour2="#b4b4b4"
fi

terminal=png
gnuplot -e "set terminal pngcairo" >/dev/null 2>&1 && terminal=pngcairo

# pm3d lights palette colours only (not "fc rgb"), so each part gets a
# band of a three-colour palette: ground tiles or table, tiles, mesh.
: "${collider_colour2:=$collider_colour}"
plots="'collider.dat' using 1:2:3:(0.5) with pm3d"
[ -s "$tmp/collider2.dat" ] &&
  plots="$plots, 'collider2.dat' using 1:2:3:(1.5) with pm3d"
plots="$plots, 'mesh.dat' using 1:2:3:(2.5) with pm3d"

(
  cd "$tmp"
  gnuplot <<EOF
set terminal $terminal size 800,600 background rgb "white"
set output "out.png"
unset border
unset tics
unset key
unset colorbox
set view $view
set view equal xyz
set palette defined (0 "$collider_colour", 1 "$collider_colour", \\
  1 "$collider_colour2", 2 "$collider_colour2", 2 "$mesh_colour", 3 "$mesh_colour")
set cbrange [0:3]
set pm3d depthorder
set pm3d lighting primary 0.5 specular 0.2
set style fill solid 1.0 noborder
splot $plots
EOF
)
cp "$tmp/out.png" "$png"
