/* broad.c — the cell-binning pair list against brute force.
 *
 * On random polydisperse sets (radius ratio up to 5, some clustered, one
 * particle far away) the list must hold exactly the pairs closer than
 * r_i + r_j + skin, each once; after particles move (rebuilds in between),
 * every touching pair must still be in the list, and the gather lists must
 * name each pair once from each side.
 */
#include "test.h"

#include "core/rng.h"
#include "world/world.h"

static sd_world *make(uint64_t seed, size_t n, double rmin, double rmax, double box)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.threads = 2;
    d.seed = seed;
    d.gravity = sd_test_v(0, 0, 0);
    d.dt = 1e-6;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.youngs_modulus = 1e7;
    int mat = sd_world_add_material(w, &m, &err);
    sd_rng r = sd_rng_seed(seed);
    sd_sphere_def *s = calloc(n, sizeof *s);
    for (size_t k = 0; k < n; ++k) {
        double scale = (k % 7 == 0) ? 0.2 : 1.0; /* a dense cluster */
        s[k].position = sd_test_v(sd_rng_range(&r, 0, box * scale), sd_rng_range(&r, 0, box * scale),
                                  sd_rng_range(&r, 0, box * scale));
        s[k].velocity = sd_test_v(sd_rng_range(&r, -1, 1), sd_rng_range(&r, -1, 1), sd_rng_range(&r, -1, 1));
        s[k].radius = sd_rng_range(&r, rmin, rmax);
        s[k].material = mat;
    }
    s[n - 1].position = sd_test_v(100 * box, -50 * box, 3 * box); /* far away */
    sd_test_require(sd_world_add_spheres(w, n, s, &err) == SD_OK, "spheres", &err);
    free(s);
    /* the positions are random, so the set (the cluster above all) starts
     * overlapped far beyond what a contact law describes: a test of the
     * pair list, not of the physics, so without the deep-overlap and speed
     * guards (world/guards.c) */
    w->guards_off = 1;
    return w;
}

/* Checks the list against brute force; strict: exact set within the skin;
 * otherwise only that every touching pair is present. */
static void compare(sd_world *w, int strict, const char *label)
{
    const sd_particles *p = &w->p;
    const sd_pair_list *l = &w->pairs;
    size_t n = p->n;
    unsigned char *mark = calloc(n * n, 1);
    int dup = 0, bad_order = 0;
    for (size_t e = 0; e < l->n; ++e) {
        size_t i = l->i[e], j = l->j[e];
        /* the canonical order (broad/canonical.c): i is the body of lower
         * stable id, whatever the storage order */
        if (i == j || p->id[i] >= p->id[j])
            bad_order++;
        size_t a = i < j ? i : j, b = i < j ? j : i;
        if (mark[a * n + b])
            dup++;
        mark[a * n + b] = 1;
    }
    long missing = 0, extra = 0, expected = 0;
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j) {
            double d = (double)sd_v3_norm(sd_v3_sub(p->x[i], p->x[j]));
            double reach = (double)(p->radius[i] + p->radius[j]) + (strict ? (double)w->skin : 0.0);
            int want = d < reach;
            expected += want;
            if (want && !mark[i * n + j])
                missing++;
            if (strict && !want && mark[i * n + j])
                extra++;
        }
    /* gather lists: each pair twice, once per side */
    long gather_bad = 0;
    for (size_t k = 0; k < n; ++k)
        for (uint32_t g = l->gstart[k]; g < l->gstart[k + 1]; ++g) {
            uint32_t e = l->gidx[g] >> 1, side = l->gidx[g] & 1u;
            if ((side ? l->j[e] : l->i[e]) != k)
                gather_bad++;
        }
    gather_bad += (long)l->gstart[n] != (long)(2 * l->n);
    printf("     %s: %zu pairs in list, %ld expected by brute force\n", label, l->n, expected);
    CHECK(missing == 0);
    CHECK(extra == 0);
    CHECK(dup == 0);
    CHECK(bad_order == 0);
    CHECK(gather_bad == 0);
    free(mark);
}

int main(void)
{
    sd_error err;
    for (uint64_t seed = 1; seed <= 3; ++seed) {
        sd_world *w = make(seed, 1000, 0.001, 0.005, 0.08);
        sd_test_require(sd_world_prepare(w, &err) == SD_OK, "prepare", &err);
        compare(w, 1, "fresh list");
        long r0 = w->rebuilds;
        for (int k = 0; k < 8; ++k) {
            sd_test_require(sd_world_step(w, 120, &err) == SD_OK, "step", &err);
            compare(w, 0, "after steps");
        }
        printf("     rebuilds during the run: %ld\n", w->rebuilds - r0);
        CHECK(w->rebuilds > r0);
        sd_world_destroy(w);
    }
    return sd_test_summary();
}
