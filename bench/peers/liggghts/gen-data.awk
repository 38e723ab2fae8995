# Writes a LIGGGHTS data file (atom_style granular) for the spheres-settle case:
# spheres of diameter 2 mm, density 2500 kg/m^3 on a simple cubic lattice of
# spacing 2.2 mm, side x side per layer (default 20 x 20), first centre at
# (1.1, 1.1, 1.1) mm, with each velocity component uniform in [-0.05, 0.05] m/s
# from a fixed seed; the box is side x 2.2 mm wide.
#
# Usage: awk -v n=8000 -v seed=42 -v zmax=0.5 [-v side=20] -f gen-data.awk > spheres.data
#
# The random numbers come from the Park-Miller "minimal standard" generator so
# that every awk (mawk, gawk, busybox) writes the same file; they are not the
# numbers shapedem draws, only the same distribution.
function uniform() {
    state = (state * 16807) % 2147483647   # exact in doubles: 16807 * 2^31 < 2^53
    return state / 2147483647
}
BEGIN {
    if (side == "") side = 20
    if (n == "" || n % (side * side) != 0) { print "gen-data.awk: n must be a multiple of side^2" > "/dev/stderr"; exit 1 }
    if (seed == "") seed = 42
    if (zmax == "") zmax = 0.5
    state = seed % 2147483647
    if (state <= 0) state = 1
    spacing = 0.0022; origin = 0.0011; per_side = side; jitter = 0.05
    layers = n / (per_side * per_side)
    printf "LIGGGHTS data file: shapedem spheres-settle, %d spheres, seed %d\n\n", n, seed
    printf "%d atoms\n1 atom types\n\n", n
    printf "0 %.6g xlo xhi\n0 %.6g ylo yhi\n0 %.6g zlo zhi\n\n", side * spacing, side * spacing, zmax
    printf "Atoms\n\n"
    id = 0
    for (k = 0; k < layers; k++)
        for (j = 0; j < per_side; j++)
            for (i = 0; i < per_side; i++) {
                id++
                printf "%d 1 0.002 2500 %.7f %.7f %.7f\n", id,
                    origin + i * spacing, origin + j * spacing, origin + k * spacing
            }
    printf "\nVelocities\n\n"
    for (id = 1; id <= n; id++) {
        vx = (2 * uniform() - 1) * jitter
        vy = (2 * uniform() - 1) * jitter
        vz = (2 * uniform() - 1) * jitter
        printf "%d %.6f %.6f %.6f 0 0 0\n", id, vx, vy, vz
    }
}
