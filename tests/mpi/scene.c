/* scene.c — one rank count's run of a scene for the MPI tests
 * (tests/mpi/kinds.sh): the scene (simulation.steps of it) built on every
 * rank, split over the ranks of mpirun (simulation.mpi_split, or --split),
 * stepped with migrations
 * and contact history across rank boundaries. Every step the ranks'
 * particle count and id sums are checked against the whole set (none
 * lost, none duplicated); at the end rank 0 writes the gathered states, in
 * stable-id order, to the file given, which kinds.sh compares byte for
 * byte across rank counts.
 *
 *   mpi_scene SCENE OUT [--serial] [--hints] [--walls] [--split SPEC] [--backend B] [--chunk N]
 *             [--fail-alloc RANK:N[:gather]]
 *     --serial: the plain world, no attach
 *     --backend: auto, cpu or cuda instead of the scene's (each rank's
 *               device slot is its node-local rank: sd_mpi_local_rank)
 *     --chunk:  N steps per sd_world_step call (default 1), the count and
 *               id set checked after each: on a device backend each call
 *               ends with a whole read back, which N > 1 leaves out
 *               between the steps of a call
 *     --hints:  on more than one rank, volume-law overlap hints (x0) must
 *               have travelled with migrating particles
 *     --walls:  on more than one rank, wall pairs' springs must have
 *               travelled with migrating particles
 *     --split SPEC: the grid of boxes instead of the scene's (auto, x, y,
 *               z or PxPyPz such as 2x2x1: tests/mpi/states.h)
 *     --spread: on more than one rank, every rank must own particles at
 *               the end (a world filled by insertion: not all on rank 0)
 *     --fail-alloc RANK:N[:gather]: on rank RANK only, the N-th
 *               allocation after attach (with :gather, from the final
 *               gather on) fails (core/alloc.h's hook): the run must end
 *               with that rank's one message (tests/mpi/oom.sh)
 *
 * On more than one rank particles must migrate and carry history entries
 * (the scenes are made so: fast particles in contact across the cuts).
 *
 * Built against the emulated CUDA backend (mpi_scene_cuda, SD_TEST_CUDA_EMULATED:
 * tests/mpi/kinds.sh --cuda), a run on backend cuda also checks that each
 * rank was given device (node-local rank mod SD_CUDA_EMULATE_DEVICES).
 */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <shapedem/process.h>
#include <shapedem/scene.h>

#include "core/alloc.h"
#include "io/scene.h"
#include "mpi/mpi.h"
#include "mpi/states.h"
#ifdef SD_TEST_CUDA_EMULATED
#include "backend/cuda/cuda.h"
#endif

static int cmp_u64(const void *a, const void *b)
{
    uint64_t p = *(const uint64_t *)a, q = *(const uint64_t *)b;
    return p < q ? -1 : (p > q ? 1 : 0);
}

/* With insertions and outlets the set changes: every id once over the
 * ranks (gathered on rank 0), as many as initial + inserted - removed,
 * and every rank holding the same accounts. Returns 1 when not. */
static int check_process(const sd_world *w, long step, int rank, int size, int *reported)
{
    sd_process_info pi;
    sd_world_get_process(w, &pi);
    unsigned long long acc[3] = {pi.initial, pi.inserted, pi.removed}, lo[3], hi[3];
    MPI_Allreduce(acc, lo, 3, MPI_UNSIGNED_LONG_LONG, MPI_MIN, MPI_COMM_WORLD);
    MPI_Allreduce(acc, hi, 3, MPI_UNSIGNED_LONG_LONG, MPI_MAX, MPI_COMM_WORLD);
    int n = (int)sd_world_particle_count(w);
    uint64_t *ids = sd_malloc((size_t)(n ? n : 1) * sizeof *ids);
    for (int k = 0; k < n; ++k) {
        sd_particle_state p;
        sd_world_get_particle(w, (size_t)k, &p);
        ids[k] = p.id;
    }
    int *cnt = sd_malloc((size_t)size * 2 * sizeof *cnt), total = 0;
    MPI_Gather(&n, 1, MPI_INT, cnt, 1, MPI_INT, 0, MPI_COMM_WORLD);
    for (int r = 0; rank == 0 && r < size; ++r) {
        cnt[size + r] = total;
        total += cnt[r];
    }
    uint64_t *all = rank == 0 ? sd_malloc((size_t)(total ? total : 1) * sizeof *all) : NULL;
    MPI_Gatherv(ids, n, MPI_UINT64_T, all, cnt, cnt + size, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    int bad = 0;
    if (rank == 0) {
        qsort(all, (size_t)total, sizeof *all, cmp_u64);
        size_t dup = 0;
        for (int k = 1; k < total; ++k)
            dup += all[k] == all[k - 1];
        unsigned long long want = pi.initial + pi.inserted - pi.removed;
        bad = dup != 0 || (unsigned long long)total != want || memcmp(lo, hi, sizeof lo) != 0;
        if (bad && !*reported)
            fprintf(stderr, "step %ld: %d particles over the ranks (want %llu = %zu initial + %zu inserted - %zu "
                            "removed), %zu ids twice, accounts %s over the ranks\n",
                    step, total, want, pi.initial, pi.inserted, pi.removed, dup,
                    memcmp(lo, hi, sizeof lo) ? "differ" : "agree");
        *reported |= bad;
    }
    sd_free(all);
    sd_free(cnt);
    sd_free(ids);
    MPI_Bcast(&bad, 1, MPI_INT, 0, MPI_COMM_WORLD);
    return bad;
}

#ifdef SD_TEST_CUDA_EMULATED
/* On backend cuda: every rank was given device (its node-local rank mod
 * the emulated devices), the device its backend set and its world's note
 * names; rank 0 prints each rank's. Returns 1 on rank 0 when not. */
static int check_devices(const sd_world *w, int local, int rank, int size)
{
    if (strcmp(sd_world_backend(w), "cuda") != 0)
        return 0;
    const char *env = getenv("SD_CUDA_EMULATE_DEVICES");
    int ndev = env && *env ? atoi(env) : 1;
    ndev = ndev > 0 ? ndev : 1;
    char named[48];
    snprintf(named, sizeof named, "device %d of %d:", local % ndev, ndev);
    int mine[3] = {local, sd_cuda_emulated_device(), strstr(sd_world_backend_note(w), named) != NULL};
    int *all = sd_malloc((size_t)size * sizeof mine);
    MPI_Gather(mine, 3, MPI_INT, all, 3, MPI_INT, 0, MPI_COMM_WORLD);
    int bad = 0;
    if (rank == 0) {
        printf("devices (%d emulated):", ndev);
        for (int r = 0; r < size; ++r) {
            int ok = all[3 * r + 1] == all[3 * r] % ndev && all[3 * r + 2];
            printf(" rank %d (local %d) device %d%s;", r, all[3 * r], all[3 * r + 1], ok ? "" : " WRONG");
            bad |= !ok;
        }
        printf("\n");
        if (bad)
            printf("  FAIL: a rank's device is not its local rank mod %d, or its backend note does not name it "
                   "(rank 0's: %s)\n", ndev, sd_world_backend_note(w));
    }
    sd_free(all);
    return bad;
}
#endif

int main(int argc, char **argv)
{
    MPI_Init(&argc, &argv);
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    if (argc < 3) {
        fprintf(stderr, "usage: mpi_scene SCENE OUT [--serial] [--hints] [--walls] [--split SPEC] [--spread] "
                        "[--backend B] [--chunk N] [--fail-alloc RANK:N[:gather]]\n");
        MPI_Abort(MPI_COMM_WORLD, 2);
    }
    int serial = 0, hints = 0, walls = 0, spread = 0;
    const char *split_arg = NULL;
    sd_backend_kind backend = SD_BACKEND_COUNT; /* the scene's */
    long chunk = 1;
    int fail_rank = -1;
    long fail_n = 0;
    char fail_at[8] = "";
    for (int a = 3; a < argc; ++a) {
        if (strcmp(argv[a], "--serial") == 0)
            serial = 1;
        else if (strcmp(argv[a], "--backend") == 0 && a + 1 < argc)
            backend = sd_backend_kind_from_name(argv[++a]);
        else if (strcmp(argv[a], "--chunk") == 0 && a + 1 < argc && atol(argv[a + 1]) > 0)
            chunk = atol(argv[++a]);
        else if (strcmp(argv[a], "--hints") == 0)
            hints = 1;
        else if (strcmp(argv[a], "--walls") == 0)
            walls = 1;
        else if (strcmp(argv[a], "--spread") == 0)
            spread = 1;
        else if (strcmp(argv[a], "--split") == 0 && a + 1 < argc)
            split_arg = argv[++a];
        else if (strcmp(argv[a], "--fail-alloc") == 0 && a + 1 < argc &&
                 sscanf(argv[a + 1], "%d:%ld:%7s", &fail_rank, &fail_n, fail_at) >= 2 && fail_n > 0 &&
                 (!*fail_at || strcmp(fail_at, "gather") == 0))
            ++a;
        else {
            fprintf(stderr, "mpi_scene: unknown option %s\n", argv[a]);
            MPI_Abort(MPI_COMM_WORLD, 2);
        }
    }
    sd_error err;
    sd_scene *sc = NULL;
    sd_world *w = NULL;
    sd_status st;
    if ((st = sd_scene_load(argv[1], &sc, &err)) != SD_OK)
        sd_mpi_fail(NULL, "scene", st, &err);
    sd_scene_set_threads(sc, 1);
    sd_scene_set_backend(sc, backend);
    int local = sd_mpi_local_rank();
    sd_scene_set_device(sc, local);
    if ((st = sd_scene_build(sc, &w, &err)) != SD_OK)
        sd_mpi_fail(NULL, "scene", st, &err);
    if (backend != SD_BACKEND_COUNT && backend != SD_BACKEND_AUTO &&
        strcmp(sd_world_backend(w), sd_backend_kind_name(backend)) != 0) {
        fprintf(stderr, "mpi_scene: asked for backend %s, runs on %s (%s)\n", sd_backend_kind_name(backend),
                sd_world_backend(w), sd_world_backend_note(w));
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    long steps = sd_scene_steps(sc);
    /* insertions or outlets: the set of ids changes (check_process) */
    int process = sd_world_insertion_count(w) + sd_world_outlet_count(w) > 0;
    unsigned long long want[3];
    mpi_test_id_sums(w, want);
    sd_mpi *m = NULL;
    /* the scene's simulation.mpi_split, or --split */
    sd_mpi_split_req split = {{sc->mpi_split[0], sc->mpi_split[1], sc->mpi_split[2]}, sc->mpi_split_line};
    if (split_arg && mpi_test_split(split_arg, &split) != 0) {
        fprintf(stderr, "mpi_scene: bad --split %s\n", split_arg);
        MPI_Abort(MPI_COMM_WORLD, 2);
    }
    if (!serial && (st = sd_mpi_attach_built(w, &split, &m, &err)) != SD_OK)
        sd_mpi_fail(m, "attach", st, &err);
    if (rank == fail_rank && !*fail_at)
        sd_alloc_fail_after(fail_n);
    long bad_steps = 0, contacts_max = 0, wall_contacts_max = 0;
    int reported = 0;
    for (long step = 0; step < steps; step += chunk) {
        if ((st = sd_world_step(w, chunk < steps - step ? chunk : steps - step, &err)) != SD_OK)
            sd_mpi_fail(m, "step", st, &err);
        bad_steps += process ? check_process(w, step, rank, size, &reported)
                             : mpi_test_check_ids(w, want, step, rank, &reported);
        sd_stats stats;
        sd_world_stats(w, &stats);
        long c[2] = {stats.contacts, stats.wall_contacts}, call[2] = {0, 0};
        MPI_Allreduce(c, call, 2, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
        contacts_max = call[0] > contacts_max ? call[0] : contacts_max;
        wall_contacts_max = call[1] > wall_contacts_max ? call[1] : wall_contacts_max;
    }
    unsigned long long moved[4] = {m ? sd_mpi_migrated(m) : 0, m ? sd_mpi_carried(m) : 0,
                                   m ? sd_mpi_carried_hints(m) : 0, m ? sd_mpi_carried_walls(m) : 0},
                       moved_all[4] = {0, 0, 0, 0};
    MPI_Reduce(moved, moved_all, 4, MPI_UNSIGNED_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
    /* the particles each rank owns at the end (at most 64 ranks) */
    unsigned long long own = sd_world_particle_count(w), owns[SD_MPI_MAX_RANKS] = {0}, fewest = own;
    MPI_Gather(&own, 1, MPI_UNSIGNED_LONG_LONG, owns, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
    for (int r = 0; rank == 0 && r < size; ++r)
        fewest = owns[r] < fewest ? owns[r] : fewest;
    sd_particle_state *s = NULL;
    size_t n = 0;
    if (rank == fail_rank && *fail_at)
        sd_alloc_fail_after(fail_n);
    if (m) {
        if ((st = sd_mpi_gather(m, w, &s, &n, &err)) != SD_OK)
            sd_mpi_fail(m, "gather", st, &err);
    } else if (rank == 0) {
        n = sd_world_particle_count(w);
        s = sd_malloc((n ? n : 1) * sizeof *s);
        for (size_t k = 0; k < n; ++k)
            sd_world_get_particle(w, k, &s[k]);
        /* in stable-id order, as the gather gives them */
        for (size_t a = 1; a < n; ++a)
            for (size_t b = a; b > 0 && s[b].id < s[b - 1].id; --b) {
                sd_particle_state t = s[b];
                s[b] = s[b - 1];
                s[b - 1] = t;
            }
    }
    int fail = 0;
    if (process) {
        /* the set the process leaves, and its accounts (every rank holds
         * them whole; kinds.sh compares this line across rank counts) */
        sd_process_info pi;
        sd_world_get_process(w, &pi);
        want[0] = pi.initial + pi.inserted - pi.removed;
        if (rank == 0)
            printf("accounts: %zu initial, %zu inserted (%.17g kg), %zu removed (%.17g kg)\n", pi.initial,
                   pi.inserted, pi.inserted_mass, pi.removed, pi.removed_mass);
        if (rank == 0 && (pi.inserted == 0 || pi.removed == 0)) {
            printf("  FAIL: the scene inserted or removed nothing\n");
            fail = 1;
        }
    }
    /* the walls where they ended (moving and servo walls: every rank
     * moves them alike; kinds.sh compares this line across rank counts) */
    if (rank == 0) {
        printf("walls:");
        for (size_t k = 0; k < sd_world_wall_count(w); ++k) {
            sd_wall_info wi;
            sd_world_get_wall(w, k, &wi);
            printf(" %s (%.17g %.17g %.17g)", wi.name, wi.point.x, wi.point.y, wi.point.z);
        }
        printf("\n");
    }
    if (rank == 0) {
        mpi_test_write_states(argv[2], s, n);
        const sd_mpi_grid *g = m ? sd_mpi_grid_of(m) : NULL;
        printf("%s: %d rank%s%s, split %d x %d x %d: %zu of %llu particles gathered, %ld steps, at most %ld particle "
               "and %ld "
               "wall contacts; %llu migrations carrying %llu history entries (%llu overlap hints, %llu wall pairs'); "
               "steps with a wrong count "
               "or id set: %ld\n",
               argv[1], size, size > 1 ? "s" : "", serial ? " (serial world)" : "", g ? g->n[0] : 1, g ? g->n[1] : 1,
               g ? g->n[2] : 1, n, want[0], steps, contacts_max, wall_contacts_max, moved_all[0], moved_all[1],
               moved_all[2], moved_all[3], bad_steps);
        fail |= n != want[0] || bad_steps != 0 || contacts_max == 0 || wall_contacts_max == 0;
        printf("  particles per rank at the end:");
        for (int r = 0; r < size; ++r)
            printf(" %llu", owns[r]);
        printf("\n");
        if (spread && size > 1 && !serial && fewest == 0) {
            printf("  FAIL: a rank owns no particle at the end\n");
            fail = 1;
        }
        /* on more than one rank, particles must cross, some in contact */
        if (size > 1 && !serial &&
            (moved_all[0] == 0 || moved_all[1] == 0 || (hints && moved_all[2] == 0) || (walls && moved_all[3] == 0))) {
            printf("  FAIL: no migration, or no history carried with one%s%s\n", hints ? " (or no overlap hint)" : "",
                   walls ? " (or no wall pair's spring)" : "");
            fail = 1;
        }
    }
#ifdef SD_TEST_CUDA_EMULATED
    fail |= check_devices(w, local, rank, size);
#endif
    sd_free(s);
    sd_mpi_detach(w, m);
    sd_world_destroy(w);
    sd_scene_free(sc);
    MPI_Finalize();
    return fail;
}
