# Redraw with: gnuplot budget_sweep_all.gp
set terminal pngcairo size 900,600 font 'DejaVu Sans,12' noenhanced
set output "budget_sweep_all.png"
set title "Accuracy vs time budget (anytime), all datasets"
set xlabel "median time per object (s), one point per budget"
set ylabel "ADD-S AUC (%)"
set xrange [*:*]
set yrange [0:105]
set grid
set key outside right top box
set logscale x
plot "budget_sweep_all.dat" index 0 using 1:2 with linespoints pt 7 ps 0.8 lw 2 title "stocs", \
  '' index 1 using 1:2 with linespoints pt 7 ps 0.8 lw 2 title "stocs-hard", \
  '' index 2 using 1:2 with linespoints pt 7 ps 0.8 lw 2 title "fpcs", \
  '' index 3 using 1:2 with linespoints pt 7 ps 0.8 lw 2 title "kfpcs", \
  '' index 4 using 1:2 with linespoints pt 7 ps 0.8 lw 2 title "ppf"
