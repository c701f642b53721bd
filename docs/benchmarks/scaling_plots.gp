# Time per object versus segment size and model size (docs/benchmarks/scaling_*.dat, written from
# `stocs_scaling_benchmarks --benchmark_format=json`). Run in this folder: gnuplot scaling_plots.gp
set terminal pngcairo size 800,500 font ",11"
set grid
set key top left

set output "scaling_segment.png"
set title "StoCS on the LM-O cat frame, 100 bases, 1 thread: CPU time vs segment size"
set xlabel "segment points"
set ylabel "CPU ms per object"
set fit quiet logfile "/dev/null"
lin(x) = a * x + b
fit lin(x) "scaling_segment.dat" using 1:2 via a, b
plot "scaling_segment.dat" using 1:2 with linespoints pt 7 title "measured", \
     lin(x) with lines dt 2 title sprintf("linear fit: %.2f ms per 1000 points", 1000 * a)

set output "scaling_model.png"
set title "StoCS on the LM-O cat frame, 100 bases, 1 thread: CPU time vs model samples"
set xlabel "model samples (Poisson-disc radius 8% to 2% of the diameter; default 4% = 519)"
plot "scaling_model.dat" using 1:2 with linespoints pt 7 title "measured"
