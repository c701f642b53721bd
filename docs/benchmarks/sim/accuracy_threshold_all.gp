# Redraw with: gnuplot accuracy_threshold_all.gp
set terminal pngcairo size 900,600 font 'DejaVu Sans,12' noenhanced
set output "accuracy_threshold_all.png"
set title "ADD-S accuracy-threshold curve, all datasets"
set xlabel "ADD-S threshold (cm)"
set ylabel "accuracy (%)"
set xrange [0:10]
set yrange [0:105]
set grid
set key outside right top box
plot "accuracy_threshold_all.dat" index 0 using 1:2 with lines lw 2 title "stocs (AUC 89.4%)", \
  '' index 1 using 1:2 with lines lw 2 title "stocs-hard (AUC 90.2%)", \
  '' index 2 using 1:2 with lines lw 2 title "fpcs (AUC 40.6%)", \
  '' index 3 using 1:2 with lines lw 2 title "kfpcs (AUC 37.8%)", \
  '' index 4 using 1:2 with lines lw 2 title "ppf (AUC 85.3%)"
