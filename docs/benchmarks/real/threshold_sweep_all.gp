# Redraw with: gnuplot threshold_sweep_all.gp
set terminal pngcairo size 900,600 font 'DejaVu Sans,12' noenhanced
set output "threshold_sweep_all.png"
set title "Success rate vs segmentation threshold, all datasets"
set xlabel "segmentation threshold (StoCS: epsilon; hard-segment methods: threshold)"
set ylabel "success: error < 2 cm and 10° (%)"
set xrange [0:1]
set yrange [0:105]
set grid
set key outside right top box
plot "threshold_sweep_all.dat" index 0 using 1:2 with linespoints pt 7 ps 0.8 lw 2 title "stocs", \
  '' index 1 using 1:2 with linespoints pt 7 ps 0.8 lw 2 title "stocs-hard", \
  '' index 2 using 1:2 with linespoints pt 7 ps 0.8 lw 2 title "fpcs", \
  '' index 3 using 1:2 with linespoints pt 7 ps 0.8 lw 2 title "kfpcs", \
  '' index 4 using 1:2 with linespoints pt 7 ps 0.8 lw 2 title "ppf"
