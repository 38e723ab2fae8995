/* spheres.c — one rank count's run of the MPI test (tests/mpi/ranks.sh):
 * 600 frictional spheres thrown about in a long box, split over the ranks
 * of mpirun (along x, or as --split asks), 500 steps with migrations and
 * contact history across rank boundaries. Every step the ranks' particle count and id sums
 * are checked against the whole set (none lost, none duplicated); at the
 * end rank 0 writes the gathered states, in stable-id order, to the file
 * given, which ranks.sh compares byte for byte across rank counts.
 *
 *   mpi_spheres OUT [--serial] [--periodic] [--fail-rank R] [--split SPEC] [--rebalance K]
 *     --serial: the plain world, no attach
 *     --periodic: periodic along x and y (a floor plane, no box): particles
 *                 cross the periodic faces and, as images, the rank cuts
 *     --split SPEC: the grid of boxes (tests/mpi/states.h: auto, x, y, z or
 *                 PxPyPz such as 2x2x1); x when not given
 *     --rebalance K: the split cut again every K steps (mpi/rebalance.c)
 */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/rng.h"
#include "mpi/mpi.h"
#include "mpi/states.h"

enum { N = 600, STEPS = 500 };

static sd_world *make_world(int periodic)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.threads = 1;
    d.dt = 1e-5;
    if (periodic) {
        d.periodic = SD_PERIODIC_X | SD_PERIODIC_Y;
        d.domain_lo = (sd_v3d){0, 0, 0};
        d.domain_hi = (sd_v3d){0.1, 0.0135, 0.2};
    }
    if (sd_world_create(&d, &w, &err) != SD_OK) {
        fprintf(stderr, "world: %s\n", err.msg);
        exit(1);
    }
    sd_material_def m = sd_material_def_default();
    m.youngs_modulus = 1e7;
    m.restitution = 0.5;
    m.friction = 0.5;
    int mat = sd_world_add_material(w, &m, &err);
    if (periodic)
        sd_world_add_plane(w, "floor", (sd_v3d){0, 0, 0}, (sd_v3d){0, 0, 1}, mat, &err);
    else
        sd_world_add_box(w, "box", (sd_v3d){0, 0, 0}, (sd_v3d){0.1, 0.0135, 0.2}, SD_BOX_ZMAX, mat, &err);
    sd_rng r = sd_rng_seed(5);
    static sd_sphere_def s[N];
    for (int k = 0; k < N; ++k) {
        int i = k % 40, j = (k / 40) % 6, l = k / 240;
        s[k] = (sd_sphere_def){0};
        s[k].position = (sd_v3d){0.0012 + 0.0021 * i, 0.0012 + 0.0021 * j, 0.0012 + 0.0021 * l};
        /* fast along x: particles cross the cuts within a few hundred steps */
        s[k].velocity = (sd_v3d){sd_rng_range(&r, -1.0, 1.0), sd_rng_range(&r, -0.2, 0.2), sd_rng_range(&r, -0.2, 0.2)};
        s[k].angular_velocity = (sd_v3d){0, sd_rng_range(&r, -50, 50), 0};
        s[k].radius = sd_rng_range(&r, 0.0009, 0.00104);
        s[k].material = mat;
    }
    if (sd_world_add_spheres(w, N, s, &err) != SD_OK) {
        fprintf(stderr, "spheres: %s\n", err.msg);
        exit(1);
    }
    return w;
}

int main(int argc, char **argv)
{
    MPI_Init(&argc, &argv);
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    if (argc < 2) {
        fprintf(stderr, "usage: mpi_spheres OUT [--serial] [--periodic] [--fail-rank R] [--split SPEC] [--rebalance K]\n");
        MPI_Abort(MPI_COMM_WORLD, 2);
    }
    int serial = 0, periodic = 0, fail_rank = -1;
    long rebalance = 0;
    sd_mpi_split_req split = {{-1, 1, 1}, 0}; /* along x */
    for (int a = 2; a < argc; ++a) {
        if (strcmp(argv[a], "--serial") == 0)
            serial = 1;
        else if (strcmp(argv[a], "--periodic") == 0)
            periodic = 1;
        else if (strcmp(argv[a], "--fail-rank") == 0 && a + 1 < argc)
            fail_rank = atoi(argv[++a]);
        else if (strcmp(argv[a], "--rebalance") == 0 && a + 1 < argc)
            rebalance = atol(argv[++a]);
        else if (strcmp(argv[a], "--split") == 0 && a + 1 < argc && mpi_test_split(argv[a + 1], &split) == 0)
            ++a;
        else {
            fprintf(stderr, "mpi_spheres: unknown option %s\n", argv[a]);
            MPI_Abort(MPI_COMM_WORLD, 2);
        }
    }
    /* --fail-rank R: rank R alone reads a bad material (as a scene read on
     * one rank only would be): the job must end with one message, the
     * other ranks waiting in the split are not left hanging */
    sd_error err;
    if (rank == fail_rank) {
        sd_material_def bad = sd_material_def_default();
        bad.density = -1;
        sd_world *wb;
        sd_world_def d = sd_world_def_default();
        sd_status sb = sd_world_create(&d, &wb, &err);
        if (sb == SD_OK && sd_world_add_material(wb, &bad, &err) < 0)
            sb = err.code;
        sd_mpi_fail(NULL, "scene", sb == SD_OK ? SD_ERR_INTERNAL : sb, &err);
    }
    sd_world *w = make_world(periodic);
    sd_mpi *m = NULL;
    sd_status st;
    if (!serial && (st = sd_mpi_attach(w, &split, &m, &err)) != SD_OK)
        sd_mpi_fail(m, "attach", st, &err);
    if (m)
        sd_mpi_set_rebalance(m, rebalance, 0);
    /* the whole set's id sums: 0 .. N-1 */
    unsigned long long want[3] = {N, 0, 0};
    for (unsigned long long id = 0; id < N; ++id) {
        want[1] += id;
        want[2] += id * id;
    }
    long bad_steps = 0;
    int reported = 0;
    for (int step = 0; step < STEPS; ++step) {
        if ((st = sd_world_step(w, 1, &err)) != SD_OK)
            sd_mpi_fail(m, "step", st, &err);
        bad_steps += mpi_test_check_ids(w, want, step, rank, &reported);
    }
    unsigned long long moved[3] = {m ? sd_mpi_migrated(m) : 0, m ? sd_mpi_carried(m) : 0, m ? sd_mpi_ghosts(m) : 0},
                       moved_all[3] = {0, 0, 0};
    MPI_Reduce(moved, moved_all, 3, MPI_UNSIGNED_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
    sd_stats stats;
    sd_world_stats(w, &stats);
    sd_particle_state *s = NULL;
    size_t n = 0;
    if (m) {
        if ((st = sd_mpi_gather(m, w, &s, &n, &err)) != SD_OK)
            sd_mpi_fail(m, "gather", st, &err);
    } else if (rank == 0) {
        n = sd_world_particle_count(w);
        s = sd_malloc(n * sizeof *s);
        for (uint64_t id = 0; id < n; ++id)
            sd_world_get_particle(w, sd_world_find_particle(w, id), &s[id]);
    }
    int fail = 0;
    const sd_mpi_grid *g = m ? sd_mpi_grid_of(m) : NULL;
    if (rank == 0) {
        size_t ids_in_order = 1;
        for (size_t k = 0; k < n; ++k)
            ids_in_order &= s[k].id == k;
        mpi_test_write_states(argv[1], s, n);
        printf("%d rank%s%s%s, split %d x %d x %d after %ld re-cuts: %zu particles gathered (ids 0..%d in order: "
               "%s), %llu migrations carrying %llu springs, %llu remote ghosts at the end, rank 0: %ld rebuilds, %ld contacts; steps with a wrong "
               "count or id set: %ld\n",
               size, size > 1 ? "s" : "", serial ? " (serial world)" : "", periodic ? " periodic x, y" : "",
               g ? g->n[0] : 1, g ? g->n[1] : 1, g ? g->n[2] : 1, m ? sd_mpi_rebalances(m) : 0L, n, N - 1,
               ids_in_order ? "yes" : "no", moved_all[0], moved_all[1], moved_all[2], stats.rebuilds, stats.contacts, bad_steps);
        /* on more than one rank, particles must cross, some in contact */
        fail = n != N || !ids_in_order || bad_steps != 0 || (size > 1 && (moved_all[0] == 0 || moved_all[1] == 0));
    }
    sd_free(s);
    sd_mpi_detach(w, m);
    sd_world_destroy(w);
    MPI_Finalize();
    return fail;
}
