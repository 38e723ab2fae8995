/* states.h — what the MPI test programs (tests/mpi/spheres.c, scene.c)
 * share: the id sums that check the particle set every step, the file of
 * gathered states that the scripts compare byte for byte, and the --split
 * option. */
#ifndef SD_TESTS_MPI_STATES_H
#define SD_TESTS_MPI_STATES_H

#include <mpi.h>
#include <stdio.h>
#include <string.h>

#include <shapedem/shapedem.h>

#include "mpi/mpi.h"

/* --split SPEC, as simulation.mpi_split reads it: auto, x, y, z or PxPyPz
 * ("2x2x1"). Returns 0, or -1 for a SPEC that is none of those. */
static inline int mpi_test_split(const char *spec, sd_mpi_split_req *out)
{
    *out = (sd_mpi_split_req){{0, 0, 0}, 0};
    if (!strcmp(spec, "auto"))
        return 0;
    if (spec[0] >= 'x' && spec[0] <= 'z' && !spec[1]) {
        for (int a = 0; a < 3; ++a)
            out->n[a] = a == spec[0] - 'x' ? -1 : 1;
        return 0;
    }
    char end;
    return sscanf(spec, "%dx%dx%d%c", &out->n[0], &out->n[1], &out->n[2], &end) == 3 ? 0 : -1;
}

/* This rank's count, id sum and id square sum (out[0..2]): summed over the
 * ranks they must equal the whole set's, or a particle was lost or doubled. */
static inline void mpi_test_id_sums(const sd_world *w, unsigned long long out[3])
{
    out[0] = out[1] = out[2] = 0;
    size_t n = sd_world_particle_count(w);
    for (size_t k = 0; k < n; ++k) {
        sd_particle_state p;
        sd_world_get_particle(w, k, &p);
        out[0]++;
        out[1] += p.id;
        out[2] += (unsigned long long)p.id * p.id;
    }
}

/* Summed over the ranks and compared with want; returns 1 when they
 * differ (and says so on rank 0, the first time: *reported). */
static inline int mpi_test_check_ids(const sd_world *w, const unsigned long long want[3], long step, int rank,
                                     int *reported)
{
    unsigned long long mine[3], all[3];
    mpi_test_id_sums(w, mine);
    MPI_Allreduce(mine, all, 3, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
    if (all[0] == want[0] && all[1] == want[1] && all[2] == want[2])
        return 0;
    if (rank == 0 && !*reported)
        fprintf(stderr, "step %ld: %llu particles (want %llu), id sums %llu %llu (want %llu %llu)\n", step, all[0],
                want[0], all[1], all[2], want[1], want[2]);
    *reported = 1;
    return 1;
}

/* Writes the n states (stable-id order) to path: per particle its id and
 * 13 doubles (position, velocity, spin, orientation), field by field so
 * the struct's padding stays out. Aborts the job when it cannot write. */
static inline void mpi_test_write_states(const char *path, const sd_particle_state *s, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "cannot write %s\n", path);
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    for (size_t k = 0; k < n; ++k) {
        const sd_particle_state *p = &s[k];
        double v[] = {p->position.x, p->position.y, p->position.z, p->velocity.x, p->velocity.y,
                      p->velocity.z, p->angular_velocity.x, p->angular_velocity.y, p->angular_velocity.z,
                      p->quat[0], p->quat[1], p->quat[2], p->quat[3]};
        fwrite(&p->id, sizeof p->id, 1, f);
        fwrite(v, sizeof v, 1, f);
    }
    if (fclose(f) != 0) {
        fprintf(stderr, "cannot write %s\n", path);
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
}

#endif
