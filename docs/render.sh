#!/bin/sh
# Renders a scene's final mesh (an OBJ the examples write) to an 800 x 600
# PNG with gnuplot: the mesh's faces lit, with the scene's collider.
#
#   docs/render.sh tablecloth|jello|ball|flag|character IN.obj OUT.png
#
# tablecloth: the round table of examples/tablecloth.c (radius 0.35 m, top at
# y = 0) under the cloth; jello, ball: the ground y = 0, darkened under the
# body as if lit from above; flag: the pole of examples/flag.c (x = z = 0,
# 2.05 m tall), in a fixed frame so that frames make an animation;
# character: IN is examples/character.c's cape-NNNN.obj, and its body is the
# body-NNNN.obj beside it, in a fixed frame. The OBJ's y axis is up. Needs gnuplot 5.4
# (apt-get install gnuplot-nox); uses pngcairo when there is one.
set -eu

usage() {
  echo "usage: $0 tablecloth|jello|ball|flag|character IN.obj OUT.png" >&2
  exit 2
}
[ $# -eq 3 ] || usage
scene=$1 obj=$2 png=$3
case $scene in
tablecloth | jello | ball | flag | character) ;;
*) usage ;;
esac
[ -r "$obj" ] || { echo "$0: cannot read $obj" >&2; exit 1; }
command -v gnuplot >/dev/null 2>&1 ||
  { echo "$0: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }

tmp=$(mktemp -d "${TMPDIR:-/tmp}/msocl-render.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
trap 'exit 1' HUP INT TERM

# pm3d lights grid surfaces (its "with polygons" shades level faces wrongly
# in 5.4), so every face goes out as a 2 x 2 grid of its own, corners
# "x y z colour": quad(p, q, r, s) prints the scans "p q" and "s r". A
# triangle a b c is the quadrangle a b m c, m the middle of b c: pm3d
# leaves a quadrangle with a repeated corner unlit, and takes its normal
# from three corners, which must not lie on a line. Larger faces are cut
# into a fan. Colours are palette values (pm3d lights no "fc rgb"): 0 to 1
# the collider, 1 to 2 the ground's darker tiles, 2.5 the mesh.
quad='function quad(p, q, r, s) { printf "%s\n%s\n\n%s\n%s\n\n\n", p, q, s, r }'

# A mesh in palette value $1 from OBJ file $2. OBJ (x, y, z) becomes gnuplot (x, -z, y), a rotation
# that puts y up. Faces may be "f a b c", "f a/t b/t c/t" or "f a//n b//n
# c//n"; negative indices count back from the last vertex.
faces() {
awk -v colour="$1" "$quad"'
  function at(i) { return x[i] " " y[i] " " z[i] " " colour }
  function mid(i, j) {
    return (x[i] + x[j]) / 2 " " (y[i] + y[j]) / 2 " " (z[i] + z[j]) / 2 " " \
      colour
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
' "$2"
}
faces 2.5 "$obj" >"$tmp/mesh.dat"
[ -s "$tmp/mesh.dat" ] || { echo "$0: no faces in $obj" >&2; exit 1; }

# The collider, in pieces about as small as the mesh's faces: pm3d sorts
# faces by the depth of their centres, which is right only for small ones.
if [ "$scene" = tablecloth ]; then
  # The table: its side from the top down to -0.6 m, and its top in rings;
  # drawn 2 cm inside and 1 cm below the true surface, where the cloth
  # lies on it.
  awk "$quad"'
    function at(rad, a, h) { return rad * cos(a) " " rad * sin(a) " " h " 0.5" }
    BEGIN {
      pi = atan2(0, -1); r = 0.33; top = -0.01; bottom = -0.6
      m = 144; rows = 40; rings = 22
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
  view="64, 28, 1.5"
  palette='0 "#8a6a4a", 1 "#8a6a4a", 1 "#000000", 2 "#000000"'
  mesh_colour="#b8323a"
elif [ "$scene" = character ]; then
  body="$(dirname "$obj")/body-$(basename "$obj" | sed 's/^cape-//')"
  [ -r "$body" ] || { echo "$0: cannot read $body" >&2; exit 1; }
  faces 0.5 "$body" >"$tmp/collider.dat"
  # The ground along the walk: a ring from 0.9 to 1.4 m, in small pieces.
  awk "$quad"'
    function at(rad, a) { return rad * cos(a) " " rad * sin(a) " 0 1.5" }
    BEGIN {
      pi = atan2(0, -1); m = 96; rings = 8
      for (k = 0; k < m; k++)
        for (j = 0; j < rings; j++) {
          a0 = 2 * pi * k / m; a1 = 2 * pi * (k + 1) / m
          r0 = 0.9 + 0.5 * j / rings; r1 = 0.9 + 0.5 * (j + 1) / rings
          quad(at(r0, a0), at(r1, a0), at(r1, a1), at(r0, a1))
        }
    }' >>"$tmp/collider.dat"
  ranges="set xrange [-1.4:1.4]; set yrange [-1.4:1.4]; set zrange [0:1.8]"
  view="72, 28, 1.8"
  palette='0 "#5f7fa8", 1 "#5f7fa8", 1 "#cfcfcf", 2 "#cfcfcf"'
  mesh_colour="#b8323a"
elif [ "$scene" = flag ]; then
  # The pole: a cylinder of radius 2 cm from the ground to 2.05 m.
  awk "$quad"'
    function at(a, h) { return 0.02 * cos(a) " " 0.02 * sin(a) " " h " 0.5" }
    BEGIN {
      pi = atan2(0, -1); m = 12; rows = 60
      for (k = 0; k < m; k++)
        for (j = 0; j < rows; j++)
          quad(at(2 * pi * k / m, 2.05 * j / rows),
               at(2 * pi * (k + 1) / m, 2.05 * j / rows),
               at(2 * pi * (k + 1) / m, 2.05 * (j + 1) / rows),
               at(2 * pi * k / m, 2.05 * (j + 1) / rows))
    }' >"$tmp/collider.dat"
  ranges="set xrange [-0.1:1.7]; set yrange [-1.2:1.2]; set zrange [0.6:2.2]"
  view="72, 24, 2.1"
  palette='0 "#7a7a7a", 1 "#7a7a7a", 1 "#000000", 2 "#000000"'
  mesh_colour="#d9a21b"
else
  # The ground: a square checkered in 2 cm tiles, in 1 cm pieces, each
  # darker the nearer its centre lies to the body's points seen from above
  # (full shade within 1.5 cm of one, none beyond 6 cm).
  half=0.2
  [ "$scene" = ball ] && half=0.24
  awk -v half="$half" "$quad"'
    function at(x, y) { return x " " y " 0 " colour }
    $1 == "v" { n++; px[n] = $2; py[n] = -$4 }
    END {
      s = 0.01; m = int(2 * half / s + 0.5)
      for (i = 0; i < m; i++)
        for (j = 0; j < m; j++) {
          x = -half + i * s; y = -half + j * s; d = 1e9
          for (k = 1; k <= n; k++) {
            dx = px[k] - x - s / 2; dy = py[k] - y - s / 2
            if (dx * dx + dy * dy < d) d = dx * dx + dy * dy
          }
          d = sqrt(d); f = d < 0.015 ? 0 : d > 0.06 ? 1 : (d - 0.015) / 0.045
          colour = (int(i / 2) + int(j / 2)) % 2 + 0.02 + 0.97 * f
          quad(at(x, y), at(x + s, y), at(x + s, y + s), at(x, y + s))
        }
    }' "$obj" >"$tmp/collider.dat"
  # The ground never hides the body, so it is drawn first, and the mesh on
  # top in the same frame: no depth sorting between the two to go wrong.
  top=$(awk '$1 == "v" && $3 > t { t = $3 } END { print t + 0.001 }' "$obj")
  ranges="set xrange [-$half:$half]; set yrange [-$half:$half]; set zrange [0:$top]"
  view="66, 30, 1.7"
  palette='0 "#6e6e6e", 1 "#dadada", 1 "#5c5c5c", 2 "#b6b6b6"'
  if [ "$scene" = jello ]; then
    mesh_colour="#3fae49"
  else
    mesh_colour="#2f6fb5"
  fi
fi

if [ "$scene" = flag ] || [ "$scene" = character ]; then
  plots="$ranges
splot 'collider.dat' using 1:2:3:4 with pm3d, \\
    'mesh.dat' using 1:2:3:4 with pm3d"
elif [ "$scene" = tablecloth ]; then
  # The table hides part of the cloth and the cloth part of the table.
  plots="splot 'collider.dat' using 1:2:3:4 with pm3d, \\
    'mesh.dat' using 1:2:3:4 with pm3d"
else
  plots="$ranges
set multiplot
splot 'collider.dat' using 1:2:3:4 with pm3d
splot 'mesh.dat' using 1:2:3:4 with pm3d
unset multiplot"
fi

terminal=png
gnuplot -e "set terminal pngcairo" >/dev/null 2>&1 && terminal=pngcairo

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
set palette defined ($palette, 2 "$mesh_colour", 3 "$mesh_colour")
set cbrange [0:3]
set pm3d depthorder
set pm3d lighting primary 0.5 specular 0.2
set style fill solid 1.0 noborder
$plots
EOF
)
cp "$tmp/out.png" "$png"
