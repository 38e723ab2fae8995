/* composite_cull.c — the separating-axis test that answers most element
 * pairs before GJK (sd_convex_apart_warm, geom/convex_contact.h; used by
 * backend/items.h for the element pairs of composites, seed 004 §2.5).
 *
 * Claims checked, on random poses of the cross3d preset's three cylinders
 * (two crosses at a random relative pose, all nine element pairs) and of
 * every convex kind, sharp and swept (sphere, box, cylinder, cone,
 * ellipsoid, polyhedron, with rounding and with a margin), each with several
 * start directions (none, random, GJK's own from a nearby pose, the exact
 * separating direction):
 *   1. conservative: a pair the test rejects is apart by GJK's distance of
 *      the cores, with no early stop: d > ra + rb. No touching pair (nor one
 *      within 1e-9 of the length scale of touching) is ever rejected;
 *   2. the same bits: for every rejected pair, sd_convex_collide_bodies (gap
 *      0, as the element pairs call it) with the same warm direction stops at
 *      GJK's first support point (apart, no iteration), and leaves the warm
 *      direction bitwise where the test leaves it;
 *   3. it does its job: it rejects every pair that GJK's first step rejects,
 *      up to its rounding allowance (at least 99.9 % of them here), and
 *      never on a pair that GJK's first step keeps (that would be a pair GJK
 *      iterates on, whose warm direction it would change).
 */
#include "test.h"

#include <string.h>

#include "core/quat.h"
#include "core/rng.h"
#include "random_pose.h"
#include "geom/convex_contact.h"
#include "world/world.h"

typedef struct tally {
    long pairs, touching, culled, rule0, culled_not_rule0, culled_touching, warm_differs, culled_near;
    double min_gap; /* smallest (d - ra - rb) / L over the culled pairs */
} tally;

/* One pair with one start direction: the test against GJK. Returns 1 when
 * the test rejected the pair. */
static int check_pair(const sd_convex *a, const sd_convex *b, sd_vec3 warm, tally *t)
{
    const sd_gjk_body A = sd_gjk_body_of(a), B = sd_gjk_body_of(b);
    double L = a->shape->bound + b->shape->bound, rr = a->shape->radius + b->shape->radius;
    sd_gjk_result full = sd_gjk_distance(a, b, sd_v3_zero()); /* no early stop */
    int cores_apart = full.status == SD_GJK_SEPARATED || full.status == SD_GJK_MAX_ITER;
    double gap = cores_apart ? full.distance - rr : -rr; /* m, <= 0 once the cores meet */
    int touching = !cores_apart || gap <= 0;
    sd_vec3 w_test = warm, w_gjk = warm;
    int culled = sd_convex_apart_warm(&A, &B, &w_test);
    sd_convex_contact c = sd_convex_collide_bodies(&A, &B, &w_gjk, 0);
    int rule0 = !c.touching && c.status == SD_GJK_SEPARATED && c.iterations == 0 && c.support_calls == 1;
    t->pairs++;
    t->touching += touching;
    t->rule0 += rule0;
    if (!culled) {
        if (memcmp(&w_test, &warm, sizeof warm))
            t->warm_differs++; /* a kept pair's warm direction is GJK's to write */
        return 0;
    }
    t->culled++;
    t->culled_not_rule0 += !rule0;
    t->culled_touching += touching;
    t->culled_near += gap <= 1e-9 * L;
    if (memcmp(&w_test, &w_gjk, sizeof w_gjk))
        t->warm_differs++;
    if (gap / L < t->min_gap)
        t->min_gap = gap / L;
    return 1;
}

/* Start directions: none (GJK then starts along xb - xa), random of random
 * length, GJK's own from the pair a little earlier (as a warm start is),
 * and the direction of the closest points (the best separating axis). */
static void check_pair_dirs(sd_rng *rng, const sd_convex *a, const sd_convex *b, tally *t)
{
    check_pair(a, b, sd_v3_zero(), t);
    check_pair(a, b, sd_v3_scale(rand_unit(rng), pow(10.0, sd_rng_range(rng, -6, 2))), t);
    sd_convex ea = *a, eb = *b;
    double L = a->shape->bound + b->shape->bound;
    ea.x = sd_v3_add(a->x, sd_v3_scale(rand_unit(rng), 0.02 * L));
    ea.q = sd_quat_normalize(sd_quat_mul(sd_quat_from_rotvec(sd_v3_scale(rand_unit(rng), 0.05)), a->q));
    sd_gjk_result g = sd_gjk_distance(&ea, &eb, sd_v3_zero());
    check_pair(a, b, g.dir, t);
    sd_gjk_result now = sd_gjk_distance(a, b, sd_v3_zero());
    check_pair(a, b, sd_v3_sub(now.pb, now.pa), t);
}

/* b placed along a random direction from a at a distance that puts the
 * pair near contact (a spread of gaps from overlap to well apart). */
static sd_vec3 near_contact(sd_rng *rng, const sd_convex *a, const sd_shape *sb)
{
    double reach = a->shape->bound + sb->bound;
    return sd_v3_add(a->x, sd_v3_scale(rand_unit(rng), reach * sd_rng_range(rng, 0.3, 1.05)));
}

static void report(const char *what, const tally *t)
{
    printf("%-28s %7ld pair tests, %6ld touching, %6ld rejected (GJK's first step: %6ld), smallest rejected gap "
           "%.3g L\n",
           what, t->pairs, t->touching, t->culled, t->rule0, t->culled ? t->min_gap : 0.0);
    CHECK(t->culled_touching == 0);
    CHECK(t->culled_near == 0);
    CHECK(t->culled_not_rule0 == 0);
    CHECK(t->warm_differs == 0);
    CHECK(t->culled > 0);
    CHECK(t->culled >= 0.999 * (double)t->rule0);
}

static int add_shape(sd_world *w, const char *name, const char *kind, sd_v3d size, double rounding, double margin)
{
    sd_shape_desc d = sd_shape_desc_default();
    d.kind = kind;
    d.size = size;
    d.rounding = rounding;
    d.margin = margin;
    sd_error err;
    int k = sd_world_add_shape(w, name, &d, &err);
    sd_test_require(k >= 0, name, &err);
    return k;
}

int main(void)
{
    sd_world_def wd = sd_world_def_default();
    sd_world *w = NULL;
    sd_error err;
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "sd_world_create", &err);
    const double r = 1e-3;

    /* seed 004's 3D cross as composites-settle has it */
    sd_composite_preset_def pd = sd_composite_preset_def_default();
    pd.preset = "cross3d";
    pd.diameter = 1.4 * r;
    pd.length = 4.2 * r;
    int cross = sd_world_add_composite_preset(w, "cross3d", &pd, &err);
    sd_test_require(cross >= 0, "cross3d", &err);

    /* every convex kind, sharp, rounded and with a margin */
    static const sd_v3d hull[] = {{1e-3, 0, 0},        {-0.7e-3, 0.6e-3, 0.1e-3}, {-0.5e-3, -0.8e-3, 0.2e-3},
                                  {0.1e-3, 0.2e-3, 1.1e-3}, {0.2e-3, -0.1e-3, -0.9e-3}, {0.6e-3, 0.7e-3, -0.3e-3},
                                  {-0.4e-3, 0.1e-3, 0.8e-3}, {0.3e-3, -0.9e-3, -0.2e-3}};
    int kinds[20], nk = 0;
    const char *names[] = {"sphere", "box", "cylinder", "cone", "ellipsoid"};
    const sd_v3d sizes[] = {{r, r, r}, {2 * r, 1.2 * r, 0.8 * r}, {1.4 * r, 0, 4.2 * r}, {1.6 * r, 0, 2 * r},
                            {r, 0.6 * r, 1.3 * r}};
    for (int k = 0; k < 5; ++k) {
        char nm[64];
        snprintf(nm, sizeof nm, "%s-sharp", names[k]);
        kinds[nk++] = add_shape(w, nm, names[k], sizes[k], 0, 0);
        if (k == 0)
            continue;
        snprintf(nm, sizeof nm, "%s-rounded", names[k]);
        kinds[nk++] = add_shape(w, nm, names[k], sizes[k], 0.1 * r, 0);
        snprintf(nm, sizeof nm, "%s-margin", names[k]);
        kinds[nk++] = add_shape(w, nm, names[k], sizes[k], 0, 0.1 * r);
    }
    {
        sd_shape_desc d = sd_shape_desc_default();
        d.kind = "polyhedron";
        d.vertices = hull;
        d.vertex_count = sizeof hull / sizeof hull[0];
        kinds[nk] = sd_world_add_shape(w, "hull-sharp", &d, &err);
        sd_test_require(kinds[nk] >= 0, "hull-sharp", &err);
        ++nk;
        d.rounding = 0.1 * r;
        kinds[nk] = sd_world_add_shape(w, "hull-rounded", &d, &err);
        sd_test_require(kinds[nk] >= 0, "hull-rounded", &err);
        ++nk;
    }
    const sd_shape *shapes = w->shapes; /* stable now that every shape is in */
    sd_rng rng = sd_rng_seed(20261203);

    /* two crosses: every element pair, elements posed as the step poses
     * them (seed 004 eqs. 5-6, backend/items.h sd_item_element_of) */
    tally tc = {0};
    tc.min_gap = 1e300;
    const sd_shape *cs = &shapes[cross];
    for (int trial = 0; trial < 4000; ++trial) {
        sd_vec3 xi = sd_v3(sd_rng_range(&rng, 0, 0.05), sd_rng_range(&rng, 0, 0.05), sd_rng_range(&rng, 0, 0.05));
        sd_quat qi = rand_quat(&rng), qj = rand_quat(&rng);
        sd_vec3 xj = sd_v3_add(xi, sd_v3_scale(rand_unit(&rng), 2 * cs->bound * sd_rng_range(&rng, 0.2, 1.0)));
        for (uint32_t ei = 0; ei < cs->ecount; ++ei)
            for (uint32_t ej = 0; ej < cs->ecount; ++ej) {
                const sd_element *a = &w->elements[cs->estart + ei], *b = &w->elements[cs->estart + ej];
                sd_convex ca, cb;
                ca.shape = &shapes[a->shape];
                cb.shape = &shapes[b->shape];
                ca.verts = cb.verts = w->verts;
                ca.planes = cb.planes = w->planes;
                ca.dtris = cb.dtris = w->dtris;
                ca.x = sd_v3_add(xi, sd_quat_rotate(qi, a->x));
                ca.q = sd_quat_mul(qi, a->q);
                cb.x = sd_v3_add(xj, sd_quat_rotate(qj, b->x));
                cb.q = sd_quat_mul(qj, b->q);
                check_pair_dirs(&rng, &ca, &cb, &tc);
            }
    }
    report("cross3d element pairs", &tc);

    /* every convex kind against every other */
    tally tk = {0};
    tk.min_gap = 1e300;
    for (int trial = 0; trial < 60; ++trial)
        for (int i = 0; i < nk; ++i)
            for (int j = 0; j < nk; ++j) {
                sd_convex ca, cb;
                ca.shape = &shapes[kinds[i]];
                cb.shape = &shapes[kinds[j]];
                ca.verts = cb.verts = w->verts;
                ca.planes = cb.planes = w->planes;
                ca.dtris = cb.dtris = w->dtris;
                ca.x = sd_v3(sd_rng_range(&rng, -1, 1), sd_rng_range(&rng, -1, 1), sd_rng_range(&rng, -1, 1));
                ca.q = rand_quat(&rng);
                cb.x = near_contact(&rng, &ca, cb.shape);
                cb.q = rand_quat(&rng);
                check_pair_dirs(&rng, &ca, &cb, &tk);
            }
    report("convex kinds, all pairs", &tk);

    /* face to face at tiny gaps (1e-11 to 1e-7 m, boxes of 2 mm within 1 cm
     * of the origin): the test's allowance is 1e-11 of the coordinates
     * (about 3e-13 m here), so every pair apart along the exact axis is
     * rejected and every pair that overlaps is kept */
    tally tg = {0};
    tg.min_gap = 1e300;
    int box = kinds[1];
    long wrong = 0;
    for (int trial = 0; trial < 400; ++trial) {
        double gap = (trial % 2 ? 1 : -1) * pow(10.0, sd_rng_range(&rng, -8, -4)) * r;
        sd_convex ca, cb;
        ca.shape = cb.shape = &shapes[box];
        ca.verts = cb.verts = w->verts;
        ca.planes = cb.planes = w->planes;
        ca.dtris = cb.dtris = w->dtris;
        ca.x = sd_v3(sd_rng_range(&rng, -0.01, 0.01), sd_rng_range(&rng, -0.01, 0.01), sd_rng_range(&rng, -0.01, 0.01));
        ca.q = cb.q = sd_quat_identity();
        cb.x = sd_v3_add(ca.x, sd_v3(2 * shapes[box].a.x + gap, 0.3 * r, 0));
        wrong += check_pair(&ca, &cb, sd_v3(1, 0, 0), &tg) != (gap > 0);
    }
    printf("boxes face to face: %ld of 400 answered otherwise than their gap's sign\n", wrong);
    CHECK(wrong == 0);
    report("boxes face to face, tiny gaps", &tg);

    sd_world_destroy(w);
    return sd_test_summary();
}
