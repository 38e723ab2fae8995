/* convex_epa_reference.c — the engine's EPA (geom/epa.h) gives the same
 * contact as the reference EPA kept in convex_epa_ref.h (the EPA before
 * issue 11's work on sharp curved shapes), on many random pairs whose cores
 * overlap: every pair of box, cylinder, cone, ellipsoid and polyhedron cores,
 * deep (centres 0.3–1.0 of the summed bounding radii apart) and shallow
 * (sharp cylinders and cubes of the packing, placed at a penetration
 * depth of 0–2 % of their size, the contacts a packing has).
 *
 * Checked: status, depth and normal agree. The worst depth difference
 * (relative to the pair's length scale L) and the worst normal angle are
 * printed; tolerances 1e-12 L and 1e-9 rad (round-off; the face-adjacency
 * EPA builds the same polytopes, so today both are 0).
 */
#include <string.h>

#include "test.h"

#include "core/rng.h"
#include "random_pose.h"
#include "geom/convex_contact.h"

#include "convex_epa_ref.h"

#define POOL 64
static sd_vec3 pool[POOL];
static uint32_t pool_n;

/* A random sharp core of a kind (sizes 0.18–0.5). */
static sd_shape make_shape(sd_rng *r, int kind)
{
    sd_shape s;
    memset(&s, 0, sizeof s);
    s.kind = kind;
    double z = sd_rng_range(r, 0.3, 0.5);
    s.a = sd_v3(z * sd_rng_range(r, 0.6, 1), z * sd_rng_range(r, 0.6, 1), z * sd_rng_range(r, 0.6, 1));
    switch (kind) {
    case SD_SHAPE_BOX:
        s.bound = sd_v3_norm(s.a);
        break;
    case SD_SHAPE_CYLINDER:
        s.a.y = s.a.x;
        s.bound = sqrt(s.a.x * s.a.x + s.a.z * s.a.z);
        break;
    case SD_SHAPE_CONE:
        s.a.y = s.a.x;
        s.a.z *= 2;
        s.offset = sd_v3(0, 0, -0.25 * s.a.z);
        s.bound = sd_max(0.75 * s.a.z, sqrt(s.a.x * s.a.x + 0.0625 * s.a.z * s.a.z));
        break;
    case SD_SHAPE_ELLIPSOID:
        s.bound = sd_max(s.a.x, sd_max(s.a.y, s.a.z));
        break;
    default: {
        /* 20 points on a squashed sphere */
        s.vstart = pool_n;
        s.vcount = 20;
        double b = 0;
        for (int i = 0; i < 20; ++i) {
            sd_vec3 p = sd_v3_mul(rand_unit(r), s.a);
            pool[pool_n++] = p;
            b = sd_max(b, sd_v3_norm(p));
        }
        s.bound = b;
    }
    }
    return s;
}

typedef struct worst {
    long pairs, status_differ;
    double depth, angle; /* worst |depth difference| / L, worst normal angle (rad) */
} worst;

static void compare(const sd_convex *a, const sd_convex *b, worst *w)
{
    sd_gjk_result g = sd_gjk_distance(a, b, sd_v3_zero());
    if (!(g.status == SD_GJK_TOUCHING || g.status == SD_GJK_OVERLAP))
        return;
    sd_epa_result e = sd_epa_penetration(a, b, &g);
    sd_eparef_result f = sd_eparef_penetration(a, b, &g);
    double L = (double)sd_gjk_length_scale(a, b);
    w->pairs++;
    w->status_differ += e.status != f.status;
    w->depth = fmax(w->depth, fabs((double)(e.depth - f.depth)) / L);
    double c = fmin(1.0, fmax(-1.0, (double)sd_v3_dot(e.normal, f.normal)));
    /* the angle from the cross product: accurate for tiny angles */
    double s = (double)sd_v3_norm(sd_v3_cross(e.normal, f.normal));
    w->angle = fmax(w->angle, atan2(s, c));
}

/* b placed along u where its penetration depth (the reference EPA's) is target. */
static void place_shallow(sd_convex *a, sd_convex *b, sd_vec3 u, double target)
{
    double lo = 0, hi = a->shape->bound + b->shape->bound;
    for (int k = 0; k < 60; ++k) { /* the touching distance along u */
        double mid = 0.5 * (lo + hi);
        b->x = sd_v3_scale(u, mid);
        sd_gjk_result g = sd_gjk_distance(a, b, sd_v3_zero());
        if (g.status == SD_GJK_SEPARATED && g.distance > 0)
            hi = mid;
        else
            lo = mid;
    }
    double t0 = hi;
    lo = t0 - 0.3 * a->shape->bound;
    for (int k = 0; k < 50; ++k) {
        double mid = 0.5 * (lo + hi);
        b->x = sd_v3_scale(u, mid);
        sd_gjk_result g = sd_gjk_distance(a, b, sd_v3_zero());
        double d = 0;
        if (g.status == SD_GJK_TOUCHING || g.status == SD_GJK_OVERLAP)
            d = sd_eparef_penetration(a, b, &g).depth;
        if (d > target)
            lo = mid;
        else
            hi = mid;
    }
    b->x = sd_v3_scale(u, hi);
}

int main(void)
{
    const int kinds[5] = {SD_SHAPE_BOX, SD_SHAPE_CYLINDER, SD_SHAPE_CONE, SD_SHAPE_ELLIPSOID, SD_SHAPE_POLYHEDRON};
    const char *names[5] = {"box", "cylinder", "cone", "ellipsoid", "polyhedron"};
    sd_rng r = sd_rng_seed(9);
    worst all = {0, 0, 0, 0};
    printf("deep pairs (centres 0.3-1.0 of the summed bounding radii apart)\n");
    for (int ka = 0; ka < 5; ++ka)
        for (int kb = ka; kb < 5; ++kb) {
            worst w = {0, 0, 0, 0};
            for (int i = 0; i < 400; ++i) {
                pool_n = 0;
                sd_shape sa = make_shape(&r, kinds[ka]), sb = make_shape(&r, kinds[kb]);
                sd_convex a, b;
                memset(&a, 0, sizeof a);
                memset(&b, 0, sizeof b);
                a.shape = &sa;
                b.shape = &sb;
                a.verts = b.verts = pool;
                a.q = rand_quat(&r);
                b.q = rand_quat(&r);
                b.x = sd_v3_scale(rand_unit(&r), sd_rng_range(&r, 0.3, 1.0) * (sa.bound + sb.bound));
                compare(&a, &b, &w);
            }
            printf("  %-10s %-10s %4ld pairs, status differs %ld, worst depth %.3g L, normal %.3g rad\n", names[ka],
                   names[kb], w.pairs, w.status_differ, w.depth, w.angle);
            all.pairs += w.pairs;
            all.status_differ += w.status_differ;
            all.depth = fmax(all.depth, w.depth);
            all.angle = fmax(all.angle, w.angle);
        }
    printf("shallow pairs of the issue's packing (depth 0-2 %% of the size)\n");
    for (int k = 0; k < 2; ++k) {
        sd_shape s;
        memset(&s, 0, sizeof s);
        s.kind = k == 0 ? SD_SHAPE_CYLINDER : SD_SHAPE_BOX;
        /* L = D = 2.62 mm cylinders; cubes of the same volume */
        s.a = k == 0 ? sd_v3(1.31e-3, 1.31e-3, 1.31e-3) : sd_v3(1.209e-3, 1.209e-3, 1.209e-3);
        s.bound = sd_v3_norm(k == 0 ? sd_v3(1.31e-3, 0, 1.31e-3) : s.a);
        worst w = {0, 0, 0, 0};
        for (int i = 0; i < 300; ++i) {
            sd_convex a, b;
            memset(&a, 0, sizeof a);
            memset(&b, 0, sizeof b);
            a.shape = b.shape = &s;
            a.q = rand_quat(&r);
            b.q = rand_quat(&r);
            place_shallow(&a, &b, rand_unit(&r), sd_rng_range(&r, 0, 0.02) * 2.62e-3);
            compare(&a, &b, &w);
        }
        printf("  %-21s %4ld pairs, status differs %ld, worst depth %.3g L, normal %.3g rad\n",
               k == 0 ? "cylinder-cylinder" : "cube-cube", w.pairs, w.status_differ, w.depth, w.angle);
        all.pairs += w.pairs;
        all.status_differ += w.status_differ;
        all.depth = fmax(all.depth, w.depth);
        all.angle = fmax(all.angle, w.angle);
    }
    printf("%ld pairs with overlapping cores in all\n", all.pairs);
    CHECK(all.pairs > 3000);
    CHECK_NEAR("pairs whose EPA status differs", (double)all.status_differ, 0, 0);
    CHECK_NEAR("worst depth difference / L", all.depth, 0, 1e-12);
    CHECK_NEAR("worst normal angle (rad)", all.angle, 0, 1e-9);
    return sd_test_summary();
}
