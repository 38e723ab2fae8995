/* mpi_split.c — the static MPI split (mpi/decomp.c, in every build): slabs
 * and grids of boxes cut by count in (coordinate, stable id) order, ties
 * broken by id, every particle owned by exactly one rank and inside that
 * rank's box, empty ranks when there are more ranks than particles, the
 * grid's shape (auto: the least cut area; a product that is not the rank
 * count refused) and the even cut of an extent.
 */
#include <math.h>

#include "core/rng.h"
#include "test.h"

#include "mpi/mpi.h"

/* Every particle inside the box of the rank that owns it; the counts per
 * rank into count (ranks entries). Returns 1 when all are inside. */
static int owned_in_box(const sd_mpi_grid *g, size_t n, const double *x, const uint64_t *id, int *count)
{
    int ranks = g->n[0] * g->n[1] * g->n[2], inside = 1;
    for (int r = 0; r < ranks; ++r)
        count[r] = 0;
    for (size_t k = 0; k < n; ++k) {
        int r = sd_mpi_grid_rank(g, &x[3 * k], id[k]);
        if (r < 0 || r >= ranks)
            return 0;
        count[r]++;
        double lo[3], hi[3];
        sd_mpi_grid_box(g, r, lo, hi);
        for (int a = 0; a < 3; ++a)
            inside &= x[3 * k + (size_t)a] >= lo[a] && x[3 * k + (size_t)a] <= hi[a];
    }
    return inside;
}

int main(void)
{
    /* slabs along x: 10 particles, three of them at the same x (ids 7, 2,
     * 5 at x = 0.3) */
    double x1[10] = {0.9, 0.1, 0.3, 0.5, 0.7, 0.3, 0.2, 0.3, 0.8, 0.6};
    double x[3 * 1000];
    uint64_t id[1000];
    for (int k = 0; k < 10; ++k) {
        x[3 * k] = x1[k], x[3 * k + 1] = 0.5 - x1[k], x[3 * k + 2] = 0;
        id[k] = (uint64_t)k;
    }
    sd_mpi_grid g = {.n = {3, 1, 1}};
    CHECK(sd_mpi_grid_split(&g, 10, x, id) == SD_OK);
    /* order: (0.1,1) (0.2,6) (0.3,2) | (0.3,5) (0.3,7) (0.5,3) | (0.6,9) (0.7,4) (0.8,8) (0.9,0) */
    printf("     slab cuts (x, id): (%g, %llu) (%g, %llu), expected (0.3, 5) (0.6, 9)\n", g.cut[0][0].x,
           (unsigned long long)g.cut[0][0].id, g.cut[0][1].x, (unsigned long long)g.cut[0][1].id);
    CHECK(g.cut[0][0].x == 0.3 && g.cut[0][0].id == 5);
    CHECK(g.cut[0][1].x == 0.6 && g.cut[0][1].id == 9);
    int count[64];
    CHECK(owned_in_box(&g, 10, x, id, count));
    printf("     particles per rank: %d %d %d, expected 3 3 4\n", count[0], count[1], count[2]);
    CHECK(count[0] == 3 && count[1] == 3 && count[2] == 4);
    /* the tie at x = 0.3 splits by id: id 2 on rank 0, ids 5 and 7 on rank 1 */
    CHECK(sd_mpi_grid_rank(&g, (double[3]){0.3, 0, 0}, 2) == 0);
    CHECK(sd_mpi_grid_rank(&g, (double[3]){0.3, 0, 0}, 5) == 1);
    CHECK(sd_mpi_grid_rank(&g, (double[3]){0.3, 0, 0}, 7) == 1);
    double lo[3], hi[3];
    sd_mpi_grid_box(&g, 0, lo, hi);
    CHECK(isinf(lo[0]) && lo[0] < 0 && hi[0] == 0.3 && isinf(lo[1]) && isinf(hi[2]));
    sd_mpi_grid_box(&g, 2, lo, hi);
    CHECK(lo[0] == 0.6 && isinf(hi[0]) && hi[0] > 0);
    /* the same particles in slabs along y (y = 0.5 - x): the order reversed */
    g = (sd_mpi_grid){.n = {1, 3, 1}};
    CHECK(sd_mpi_grid_split(&g, 10, x, id) == SD_OK);
    CHECK(owned_in_box(&g, 10, x, id, count));
    printf("     slabs along y: %d %d %d, expected 3 3 4\n", count[0], count[1], count[2]);
    CHECK(count[0] == 3 && count[1] == 3 && count[2] == 4);
    CHECK(sd_mpi_grid_rank(&g, (double[3]){0, 0.5 - 0.9, 0}, 0) == 0);

    /* more ranks than particles: the ranks past them are empty, none lost */
    g = (sd_mpi_grid){.n = {5, 1, 1}};
    CHECK(sd_mpi_grid_split(&g, 2, x, id) == SD_OK);
    CHECK(owned_in_box(&g, 2, x, id, count));
    /* rank r takes sorted particles floor(r n / R) .. floor((r + 1) n / R) - 1 */
    printf("     2 particles on 5 ranks: %d %d %d %d %d, expected 0 0 1 0 1\n", count[0], count[1], count[2], count[3],
           count[4]);
    CHECK(count[0] == 0 && count[1] == 0 && count[2] == 1 && count[3] == 0 && count[4] == 1);

    /* a grid 2 x 3 x 2 over 1000 random particles, a quarter of them at one
     * point (ties at every level): nested runs of 500, then 166 or 167,
     * then 83 or 84; each inside its box */
    sd_rng rng = sd_rng_seed(3);
    for (int k = 0; k < 1000; ++k) {
        for (int a = 0; a < 3; ++a)
            x[3 * k + a] = k % 4 ? sd_rng_range(&rng, -1.0, 2.0) : 0.25;
        id[k] = (uint64_t)(1000 - k) * 7u;
    }
    g = (sd_mpi_grid){.n = {2, 3, 2}};
    CHECK(sd_mpi_grid_split(&g, 1000, x, id) == SD_OK);
    int inside = owned_in_box(&g, 1000, x, id, count), lo_n = 1000, hi_n = 0, sum = 0;
    for (int r = 0; r < 12; ++r) {
        lo_n = count[r] < lo_n ? count[r] : lo_n;
        hi_n = count[r] > hi_n ? count[r] : hi_n;
        sum += count[r];
    }
    printf("     2 x 3 x 2 grid, 1000 particles (250 at one point): %d to %d per rank (expected 83 to 84), %d in "
           "all, each in its box: %s\n",
           lo_n, hi_n, sum, inside ? "yes" : "no");
    CHECK(inside && lo_n == 83 && hi_n == 84 && sum == 1000);
    /* the boxes of one run along x share its x interval; rank 7 is (1, 0, 1) */
    double lo7[3], hi7[3], lo6[3], hi6[3];
    sd_mpi_grid_box(&g, 7, lo7, hi7);
    sd_mpi_grid_box(&g, 6, lo6, hi6);
    CHECK(lo7[0] == lo6[0] && hi7[0] == hi6[0] && isinf(hi7[0]) && lo7[1] == lo6[1] && hi6[2] == lo7[2]);

    /* the shape: auto takes the least cut area, ties to x then y */
    int out[3];
    CHECK(sd_mpi_grid_shape((int[3]){0, 0, 0}, 4, (double[3]){4, 1, 1}, 0, out) == 0);
    printf("     auto, 4 ranks, extent 4 x 1 x 1: %d x %d x %d (expected 4 x 1 x 1)\n", out[0], out[1], out[2]);
    CHECK(out[0] == 4 && out[1] == 1 && out[2] == 1);
    CHECK(sd_mpi_grid_shape((int[3]){0, 0, 0}, 4, (double[3]){1, 1, 1}, 0, out) == 0);
    printf("     auto, 4 ranks, extent 1 x 1 x 1: %d x %d x %d (expected 2 x 2 x 1)\n", out[0], out[1], out[2]);
    CHECK(out[0] == 2 && out[1] == 2 && out[2] == 1);
    CHECK(sd_mpi_grid_shape((int[3]){0, 0, 0}, 8, (double[3]){1, 1, 1}, 0, out) == 0);
    CHECK(out[0] == 2 && out[1] == 2 && out[2] == 2);
    CHECK(sd_mpi_grid_shape((int[3]){0, 0, 0}, 8, (double[3]){1, 1, 1}, 1, out) == 0); /* planar: pz = 1 */
    CHECK(out[2] == 1 && out[0] * out[1] == 8);
    CHECK(sd_mpi_grid_shape((int[3]){0, 0, 0}, 6, (double[3]){1, 3, 1}, 0, out) == 0);
    /* 2 x 3 x 1 and 1 x 3 x 2 both cut 5 m^2 (boxes 0.5 x 1 x 1): the tie to x */
    printf("     auto, 6 ranks, extent 1 x 3 x 1: %d x %d x %d (expected 2 x 3 x 1)\n", out[0], out[1], out[2]);
    CHECK(out[0] == 2 && out[1] == 3 && out[2] == 1);
    /* slabs, and [px, py, pz] against the rank count */
    CHECK(sd_mpi_grid_shape((int[3]){1, -1, 1}, 3, (double[3]){1, 1, 1}, 0, out) == 0);
    CHECK(out[0] == 1 && out[1] == 3 && out[2] == 1);
    CHECK(sd_mpi_grid_shape((int[3]){2, 2, 1}, 4, (double[3]){1, 1, 1}, 0, out) == 0);
    CHECK(sd_mpi_grid_shape((int[3]){2, 2, 1}, 3, (double[3]){1, 1, 1}, 0, out) == -1);
    CHECK(sd_mpi_grid_shape((int[3]){1, 1, -1}, 2, (double[3]){1, 1, 1}, 1, out) == -1); /* planar: no z cuts */

    /* even cuts over an extent: 2 x 2 x 1 over [0, 1]^2; a point on a cut
     * goes above it */
    g = (sd_mpi_grid){.n = {2, 2, 1}};
    sd_mpi_grid_even(&g, (double[3]){0, 0, 0}, (double[3]){1, 1, 1});
    CHECK(g.by_extent == 1);
    CHECK(sd_mpi_grid_rank(&g, (double[3]){0.25, 0.25, 0}, 9) == 0);
    CHECK(sd_mpi_grid_rank(&g, (double[3]){0.25, 0.75, 0}, 9) == 1);
    CHECK(sd_mpi_grid_rank(&g, (double[3]){0.75, 0.25, 0}, 9) == 2);
    CHECK(sd_mpi_grid_rank(&g, (double[3]){0.5, 0.5, 0}, 0) == 3);

    /* one rank: no cuts, everything on rank 0 */
    g = (sd_mpi_grid){.n = {1, 1, 1}};
    CHECK(sd_mpi_grid_split(&g, 10, x, id) == SD_OK);
    CHECK(sd_mpi_grid_rank(&g, (double[3]){0.5, 0, 0}, 3) == 0);
    return sd_test_summary();
}
