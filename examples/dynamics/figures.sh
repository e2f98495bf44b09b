#!/bin/sh
# Regenerates the thesis's Fig. 7.3-7.7 from the shipped cases: runs every case with
# `asperity dynamics` (into a temporary directory, removed afterwards) and overlays the
# outputs with gnuplot into fig_7_3.png ... fig_7_7.png.
#   examples/dynamics/figures.sh [path/to/asperity] [output dir]
# The output directory defaults to docs/figures of this repository (the committed
# figures of docs/dynamics.md). Assumptions are stated in each case file, in the figures'
# titles and in docs/dynamics.md: the physics-based (EPB) cases take A0 = 1 cm^2,
# A = 18 um and P = 9 N, which Table 7.2 does not give.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-asperity}
out=${2:-$here/../../docs/figures}
mkdir -p "$out"
out=$(cd "$out" && pwd)
runs=$(mktemp -d)
trap 'rm -rf "$runs"' EXIT
for f in "$here"/*.toml; do
  n=$(basename "$f" .toml)
  "$bin" dynamics "$f" --out "$runs/$n" --no-plots > /dev/null
done
cd "$runs"
# The largest power of each spectrum up to the plotted f_max = 5 (the normalisation).
peak() { awk -F, 'NR > 1 && $1 <= 5 && $2 > m { m = $2 } END { printf "%.10g", m }' "$1/spectrum.csv"; }
# A summary.json number (flat key).
num() { sed -n "s/^ *\"$2\": \([-0-9.eE+]*\),*$/\1/p" "$1/summary.json" | head -1; }
gnuplot <<GP
set encoding utf8
set terminal pngcairo size 1000,780 enhanced font 'DejaVu Sans,11'
set datafile separator ','
set datafile columnheaders
set grid
# Keys below the plots (transparent, outside the data): an opaque key inside hid peaks.
set key below left Left reverse noenhanced nobox
assumed = 'EPB (physics-based, rough flat): A0 = 1 cm^2, A = 18 µm, P = 9 N assumed (Table 7.2 gives no A0)'

set output '$out/fig_7_3.png'
set title "Fig. 7.3: power spectra of the impulse response, Coulomb and Dankowicz (Table 7.2)\n{/*0.8 each normalised by its own peak: the 200 A Coulomb pulse has about 10^6 times the raw power of the others}" enhanced
set xlabel 'non-dimensional frequency [cycles per unit tau]'
set ylabel 'power / peak power'
set logscale y; set format y '10^{%T}'; set yrange [1e-6:3]; set xrange [0:4]
plot 'impulse_none/spectrum.csv' using 1:(\$2/$(peak impulse_none)) with lines lw 1.5 title sprintf('no friction: peak %.4f, zeta %.4f', $(num impulse_none modal_frequency), $(num impulse_none modal_damping)), \
     'impulse_coulomb_large/spectrum.csv' using 1:(\$2/$(peak impulse_coulomb_large)) with lines lw 1.5 title sprintf('Coulomb, pulse 200 A: peak %.3f (undamped %.4f), zeta %.2f', $(num impulse_coulomb_large modal_frequency), $(num impulse_coulomb_large modal_frequency_undamped), $(num impulse_coulomb_large modal_damping)), \
     'impulse_coulomb/spectrum.csv' using 1:(\$2/$(peak impulse_coulomb)) with lines lw 1.5 dt 2 title 'Coulomb, unit pulse: overdamped creep, no peak', \
     'impulse_dankowicz/spectrum.csv' using 1:(\$2/$(peak impulse_dankowicz)) with lines lw 1.5 title sprintf('Dankowicz: peak %.3f, zeta %.4f', $(num impulse_dankowicz modal_frequency), $(num impulse_dankowicz modal_damping))

set output '$out/fig_7_4.png'
set title "Fig. 7.4: power spectra of the impulse response, physics-based (EPB) law, rough and smooth\n{/*0.8 each normalised by its own peak; ".assumed."}" enhanced
set xrange [0:5]
plot 'impulse_none/spectrum.csv' using 1:(\$2/$(peak impulse_none)) with lines lw 1.5 title sprintf('no friction: peak %.4f', $(num impulse_none modal_frequency)), \
     'impulse_physics_rough/spectrum.csv' using 1:(\$2/$(peak impulse_physics_rough)) with lines lw 1.5 title sprintf('EPB rough: peak %.3f, zeta %.4f', $(num impulse_physics_rough modal_frequency), $(num impulse_physics_rough modal_damping)), \
     'impulse_physics_smooth/spectrum.csv' using 1:(\$2/$(peak impulse_physics_smooth)) with lines lw 1.5 title sprintf('EPB smooth: peak %.3f, zeta %.4f', $(num impulse_physics_smooth modal_frequency), $(num impulse_physics_smooth modal_damping))
unset logscale y; set format y '%g'; set yrange [*:*]; set xrange [*:*]

set output '$out/fig_7_5.png'
set title "Fig. 7.5: ramp response (alpha = 1), soft (k = 1e4 N/m) and hard (k = 1e5 N/m) structure\n{/*0.8 ".assumed."; stick: |u'| < 5 % of the base velocity}" enhanced
# u from -1: a mass that sticks (u = 0) is drawn above the axis, not on it. One colour
# per law, solid for the soft and dashed for the hard structure.
set xlabel 'tau'; set ylabel 'u = x/A'; set xrange [0:30]; set yrange [-1:30]; set ytics 0, 5, 30
plot 'ramp_coulomb_soft/timeseries.csv' using 'tau':'y' with lines dt 2 lc 'black' title 'base y = tau', \
     '' using 'tau':'u' with lines lw 2 lc rgb '#009e73' title sprintf("Coulomb, k = 1e4: creeps from the start (|u'| past 5 %% at %.2f)", $(num ramp_coulomb_soft first_slip)), \
     'ramp_dankowicz_soft/timeseries.csv' using 'tau':'u' with lines lw 2 lc rgb '#0072b2' title sprintf('Dankowicz, k = 1e4: sticks until %.1f', $(num ramp_dankowicz_soft first_slip)), \
     'ramp_physics_rough_soft/timeseries.csv' using 'tau':'u' with lines lw 2 lc rgb '#d55e00' title sprintf('EPB rough, k = 1e4: sticks until %.1f', $(num ramp_physics_rough_soft first_slip)), \
     'ramp_dankowicz_hard/timeseries.csv' using 'tau':'u' with lines lw 2 dt 2 lc rgb '#0072b2' title sprintf('Dankowicz, k = 1e5: sticks until %.2f', $(num ramp_dankowicz_hard first_slip)), \
     'ramp_physics_rough_hard/timeseries.csv' using 'tau':'u' with lines lw 2 dt 2 lc rgb '#d55e00' title sprintf('EPB rough, k = 1e5: sticks until %.2f', $(num ramp_physics_rough_hard first_slip))
set xrange [*:*]; set yrange [*:*]; set ytics autofreq

# Steady part: the last 5 of 60 periods.
steady(t, x) = t >= 55 ? x : 1/0
set output '$out/fig_7_6.png'
set multiplot layout 2,2 title "Fig. 7.6: steady harmonic response (y = sin 2 pi tau), Coulomb (left) and Dankowicz (right)"
# u and u' scaled so that every tick label is a short plain number (one format in
# every panel); no rotated labels.
unset key; set format x '%g'; set format y '%g'; set xtics norotate
set xlabel 'u × 10^3'; set ylabel "u' × 10^2"
k3 = 1e3; k2 = 1e2
set title sprintf('(a) Coulomb: |u| <= %.2g %% of the base amplitude', 100*$(num harmonic_coulomb displacement_amplitude_over_base))
plot 'harmonic_coulomb/timeseries.csv' using (k3*steady(column('tau'), column('u'))):(k2*column('v')) with lines lw 2 lc rgb '#0072b2'
set title sprintf('(b) Dankowicz: |u| <= %.2g %%', 100*$(num harmonic_dankowicz displacement_amplitude_over_base))
plot 'harmonic_dankowicz/timeseries.csv' using (k3*steady(column('tau'), column('u'))):(k2*column('v')) with lines lw 2 lc rgb '#0072b2'
set ylabel 'F_s = f_s/(k A)'; set format y '%.1f'
set title sprintf('(c) Coulomb: no micro-slip, %.3g dissipated per cycle', $(num harmonic_coulomb energy_per_cycle))
plot 'harmonic_coulomb/timeseries.csv' using (k3*steady(column('tau'), column('u'))):'friction' with lines lw 2 lc rgb '#0072b2'
set title sprintf('(d) Dankowicz: micro-slip loop, %.3g per cycle', $(num harmonic_dankowicz energy_per_cycle))
plot 'harmonic_dankowicz/timeseries.csv' using (k3*steady(column('tau'), column('u'))):'friction' with lines lw 2 lc rgb '#0072b2'
unset multiplot

set output '$out/fig_7_7.png'
set multiplot layout 2,2 title "Fig. 7.7: steady harmonic response, EPB smooth (left) and rough (right)\n{/*0.8 ".assumed."}" enhanced
set ylabel "u' × 10^2"; set format y '%.1f'
set title sprintf('(a) EPB smooth: |u| <= %.2g %%', 100*$(num harmonic_physics_smooth displacement_amplitude_over_base))
plot 'harmonic_physics_smooth/timeseries.csv' using (k3*steady(column('tau'), column('u'))):(k2*column('v')) with lines lw 2 lc rgb '#0072b2'
set format y '%g'
set title sprintf('(b) EPB rough: |u| <= %.2g %%', 100*$(num harmonic_physics_rough displacement_amplitude_over_base))
plot 'harmonic_physics_rough/timeseries.csv' using (k3*steady(column('tau'), column('u'))):(k2*column('v')) with lines lw 2 lc rgb '#0072b2'
set ylabel 'F_s = f_s/(k A)'; set format y '%.1f'
set title sprintf('(c) EPB smooth: %.3g dissipated per cycle', $(num harmonic_physics_smooth energy_per_cycle))
plot 'harmonic_physics_smooth/timeseries.csv' using (k3*steady(column('tau'), column('u'))):'friction' with lines lw 2 lc rgb '#0072b2'
set title sprintf('(d) EPB rough: %.3g per cycle', $(num harmonic_physics_rough energy_per_cycle))
plot 'harmonic_physics_rough/timeseries.csv' using (k3*steady(column('tau'), column('u'))):'friction' with lines lw 2 lc rgb '#0072b2'
unset multiplot
GP
echo "wrote $out/fig_7_3.png ... fig_7_7.png"
