/* mpi_split.c — the static MPI split along x (mpi/decomp.c, in every
 * build): runs of equal particle count in (x, stable id) order, ties in x
 * broken by id, every particle owned by exactly one rank, empty ranks when
 * there are more ranks than particles, and the slabs' ends.
 */
#include <math.h>

#include "test.h"

#include "mpi/mpi.h"

int main(void)
{
    /* 10 particles, three of them at the same x (ids 7, 2, 5 at x = 0.3) */
    double x[10] = {0.9, 0.1, 0.3, 0.5, 0.7, 0.3, 0.2, 0.3, 0.8, 0.6};
    uint64_t id[10] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
    sd_mpi_cut cut[3];
    CHECK(sd_mpi_split(10, x, id, 3, cut) == SD_OK);
    /* order: (0.1,1) (0.2,6) (0.3,2) | (0.3,5) (0.3,7) (0.5,3) | (0.6,9) (0.7,4) (0.8,8) (0.9,0) */
    printf("     cuts (x, id): (%g, %llu) (%g, %llu), expected (0.3, 5) (0.6, 9)\n", cut[0].x,
           (unsigned long long)cut[0].id, cut[1].x, (unsigned long long)cut[1].id);
    CHECK(cut[0].x == 0.3 && cut[0].id == 5);
    CHECK(cut[1].x == 0.6 && cut[1].id == 9);
    int count[3] = {0, 0, 0};
    for (int k = 0; k < 10; ++k) {
        int r = sd_mpi_rank_of(cut, 3, x[k], id[k]);
        CHECK(r >= 0 && r < 3);
        count[r]++;
    }
    printf("     particles per rank: %d %d %d, expected 3 3 4\n", count[0], count[1], count[2]);
    CHECK(count[0] == 3 && count[1] == 3 && count[2] == 4);
    /* the tie at x = 0.3 splits by id: id 2 on rank 0, ids 5 and 7 on rank 1 */
    CHECK(sd_mpi_rank_of(cut, 3, 0.3, 2) == 0);
    CHECK(sd_mpi_rank_of(cut, 3, 0.3, 5) == 1);
    CHECK(sd_mpi_rank_of(cut, 3, 0.3, 7) == 1);
    /* slabs: the ends open, the inner ones between the cuts */
    double lo, hi;
    sd_mpi_slab(cut, 3, 0, &lo, &hi);
    CHECK(isinf(lo) && lo < 0 && hi == 0.3);
    sd_mpi_slab(cut, 3, 1, &lo, &hi);
    CHECK(lo == 0.3 && hi == 0.6);
    sd_mpi_slab(cut, 3, 2, &lo, &hi);
    CHECK(lo == 0.6 && isinf(hi) && hi > 0);
    /* more ranks than particles: the last ranks are empty, none lost */
    sd_mpi_cut c5[4];
    CHECK(sd_mpi_split(2, x, id, 5, c5) == SD_OK);
    int c5n[5] = {0};
    for (int k = 0; k < 2; ++k)
        c5n[sd_mpi_rank_of(c5, 5, x[k], id[k])]++;
    /* rank r takes sorted particles floor(r n / R) .. floor((r + 1) n / R) - 1 */
    printf("     2 particles on 5 ranks: %d %d %d %d %d, expected 0 0 1 0 1\n", c5n[0], c5n[1], c5n[2], c5n[3],
           c5n[4]);
    CHECK(c5n[0] == 0 && c5n[1] == 0 && c5n[2] == 1 && c5n[3] == 0 && c5n[4] == 1);
    /* one rank: no cuts, everything on rank 0 */
    CHECK(sd_mpi_split(10, x, id, 1, NULL) == SD_OK);
    CHECK(sd_mpi_rank_of(NULL, 1, 0.5, 3) == 0);
    return sd_test_summary();
}
