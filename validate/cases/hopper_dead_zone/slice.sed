# examples/hopper-grid.yaml cut to a slice (0.10 m x 0.0135 m, two rows of
# spheres, a 0.03 m slot, about 1,070 spheres poured to 0.15 m, dt 4e-5 s,
# 6 s): the short form shared by cli.grid_hopper_example and the quick form
# of validate: hopper_dead_zone (sed -f slice.sed)
s/dt: 5.0e-6 .*/dt: 4.0e-5/
s/duration: 14.0 .*/duration: 6.0/
s/max: \[0.20, 0.04, 0.40\]/max: [0.10, 0.0135, 0.25]/
s/fill_height: 0.36 .*/fill_height: 0.15/
s/height: 0.392 .*/height: 0.22/
s/min: \[0.08, 0.0\] .*/min: [0.035, 0.0]/
s/max: \[0.12, 0.04\]/max: [0.065, 0.0135]/
s/open_at: 6.5 .*/open_at: 3.2/
s/every: 100000 .*/every: 150000/
s/stats_every: 2000 .*/stats_every: 250/
