#!/bin/sh
# Regenerates the thesis's Fig. 7.3-7.7 from the shipped cases: runs every case with
# `asperity dynamics` and overlays the outputs with gnuplot.
#   examples/dynamics/figures.sh [path/to/asperity] [output dir]
# Assumptions are stated in each case file and in README.md (A0 = 1 cm^2, A = 18 um
# for the physics-based law; Table 7.2 gives neither).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-asperity}
out=${2:-dynamics-figures}
mkdir -p "$out"
for f in "$here"/*.toml; do
  n=$(basename "$f" .toml)
  "$bin" dynamics "$f" --out "$out/$n" --no-plots > /dev/null
done
cd "$out"
gnuplot <<'GP'
set terminal pngcairo size 1000,700 enhanced font 'DejaVu Sans,11'
set datafile separator ','
set grid
set key top right noenhanced

set output 'fig_7_3.png'
set title 'Fig. 7.3: power spectra of the impulse response (Coulomb, Dankowicz, no friction)'
set xlabel 'non-dimensional frequency'; set ylabel 'power'; set logscale y; set xrange [0:4]
plot 'impulse_none/spectrum.csv' every ::1 using 1:2 with lines lw 2 title 'no friction', \
     'impulse_coulomb_large/spectrum.csv' every ::1 using 1:2 with lines lw 2 title 'Coulomb (pulse 200 A)', \
     'impulse_dankowicz/spectrum.csv' every ::1 using 1:2 with lines lw 2 title 'Dankowicz'

set output 'fig_7_4.png'
set title 'Fig. 7.4: power spectra of the impulse response, physics-based law, rough and smooth'
plot 'impulse_none/spectrum.csv' every ::1 using 1:2 with lines lw 2 title 'no friction', \
     'impulse_physics_rough/spectrum.csv' every ::1 using 1:2 with lines lw 2 title 'EPB rough', \
     'impulse_physics_smooth/spectrum.csv' every ::1 using 1:2 with lines lw 2 title 'EPB smooth'
unset logscale y; set xrange [*:*]

set output 'fig_7_5.png'
set title 'Fig. 7.5: ramp response (alpha = 1)'
set xlabel 'tau'; set ylabel 'u'; set xrange [0:30]; set key top left
plot 'ramp_coulomb_soft/timeseries.csv' every ::1 using 1:4 with lines dt 2 lc 'black' title 'base', \
     'ramp_coulomb_soft/timeseries.csv' every ::1 using 1:2 with lines lw 2 title 'Coulomb, k = 1e4', \
     'ramp_dankowicz_soft/timeseries.csv' every ::1 using 1:2 with lines lw 2 title 'Dankowicz, k = 1e4', \
     'ramp_physics_rough_soft/timeseries.csv' every ::1 using 1:2 with lines lw 2 title 'EPB rough, k = 1e4', \
     'ramp_dankowicz_hard/timeseries.csv' every ::1 using 1:2 with lines lw 2 title 'Dankowicz, k = 1e5'
set xrange [*:*]; set key top right

set output 'fig_7_6.png'
set multiplot layout 2,2 title 'Fig. 7.6: steady harmonic response, Coulomb (left) and Dankowicz (right)'
unset title; set xtics rotate by 30 right
set xlabel 'u'; set ylabel "u'"; unset key
plot 'harmonic_coulomb/timeseries.csv' every ::1 using ($1 >= 55 ? $2 : 1/0):3 with lines lw 2
plot 'harmonic_dankowicz/timeseries.csv' every ::1 using ($1 >= 55 ? $2 : 1/0):3 with lines lw 2
set ylabel 'F_s'
plot 'harmonic_coulomb/timeseries.csv' every ::1 using ($1 >= 55 ? $2 : 1/0):5 with lines lw 2
plot 'harmonic_dankowicz/timeseries.csv' every ::1 using ($1 >= 55 ? $2 : 1/0):5 with lines lw 2
unset multiplot

set output 'fig_7_7.png'
set multiplot layout 2,2 title 'Fig. 7.7: steady harmonic response, EPB smooth (left) and rough (right)'
unset title; set xtics rotate by 30 right
set xlabel 'u'; set ylabel "u'"
plot 'harmonic_physics_smooth/timeseries.csv' every ::1 using ($1 >= 55 ? $2 : 1/0):3 with lines lw 2
plot 'harmonic_physics_rough/timeseries.csv' every ::1 using ($1 >= 55 ? $2 : 1/0):3 with lines lw 2
set ylabel 'F_s'
plot 'harmonic_physics_smooth/timeseries.csv' every ::1 using ($1 >= 55 ? $2 : 1/0):5 with lines lw 2
plot 'harmonic_physics_rough/timeseries.csv' every ::1 using ($1 >= 55 ? $2 : 1/0):5 with lines lw 2
unset multiplot
GP
echo "wrote $out/fig_7_3.png ... fig_7_7.png"
