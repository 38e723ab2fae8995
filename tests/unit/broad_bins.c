/* broad_bins.c — the broad phase as a service (broad/bins.h) on plain
 * arrays, against brute force, and the walls module (dynamics/walls.h)
 * against the box-face formulas the engine used before it.
 *
 * On a random polydisperse set of spheres, 3D shapes and sharp polyhedra
 * (two materials, one pair of them under a volume law) with periodic
 * images as ghosts: every pair closer than r_i + r_j + skin is in the list
 * exactly once, in the segment of its kind; no pair of two ghosts, none
 * with one's own image, an image contact only from the lower stable id;
 * the gather lists give a ghost's side to its owner. Ids that agree in
 * their low 32 bits and wall features (sub-indices) carry their history
 * across a rebuild in a new storage order.
 */
#include <string.h>

#include "test.h"

#include "broad/bins.h"
#include "core/rng.h"

enum { NO = 400, NMAX = 1200 };

typedef struct scene {
    size_t no, nt;
    sd_vec3 x[NMAX];
    sd_real r[NMAX];
    uint64_t id[NMAX];
    int32_t shape[NMAX], mat[NMAX];
    uint32_t owner[NMAX];
} scene;

static const uint8_t shape_class[2] = {SD_CLASS_SHAPE, SD_CLASS_SHARP_POLY};
static const uint8_t volume_law[4] = {0, 0, 0, 1};

/* Images across x = 0 and x = 1 (period 1) of the particles within 0.15 of
 * a face, after the owned ones. */
static void make_ghosts(scene *s)
{
    s->nt = s->no;
    for (size_t k = 0; k < s->no; ++k)
        for (int side = -1; side <= 1; side += 2) {
            int near = side < 0 ? s->x[k].x > 0.85 : s->x[k].x < 0.15;
            if (!near)
                continue;
            size_t g = s->nt++;
            s->x[g] = sd_v3(s->x[k].x + (sd_real)side, s->x[k].y, s->x[k].z);
            s->r[g] = s->r[k];
            s->id[g] = s->id[k];
            s->shape[g] = s->shape[k];
            s->mat[g] = s->mat[k];
            s->owner[g - s->no] = (uint32_t)k;
        }
}

static sd_bins_input input_of(const scene *s, const sd_wall_geom *walls, const int32_t *wmat, size_t nw)
{
    sd_bins_input in;
    memset(&in, 0, sizeof in);
    in.n_owned = s->no;
    in.n_total = s->nt;
    in.x = s->x;
    in.radius = s->r;
    in.id = s->id;
    in.shape = s->shape;
    in.shape_class = shape_class;
    in.material = s->mat;
    in.ghost_owner = s->owner;
    in.material_count = 2;
    in.volume_law = volume_law;
    in.wall_count = nw;
    in.walls = walls;
    in.wall_material = wmat;
    in.skin = SD_R(0.01);
    in.threads = 2;
    in.parallel = 1;
    return in;
}

static size_t owner_of(const scene *s, size_t k)
{
    return k < s->no ? k : s->owner[k - s->no];
}

static int class_of(const scene *s, size_t k)
{
    return s->shape[k] < 0 ? SD_CLASS_SPHERE : shape_class[s->shape[k]];
}

/* Applies new[k] = old[perm[k]] to the owned particles (the world's job). */
static void permute(scene *s, const uint32_t *perm)
{
    static scene t;
    t = *s;
    for (size_t k = 0; k < s->no; ++k) {
        s->x[k] = t.x[perm[k]];
        s->r[k] = t.r[perm[k]];
        s->id[k] = t.id[perm[k]];
        s->shape[k] = t.shape[perm[k]];
        s->mat[k] = t.mat[perm[k]];
    }
}

static void check_pairs(const scene *s, const sd_pair_list *l, sd_real skin)
{
    size_t n = s->nt;
    static signed char want[NMAX][NMAX];
    memset(want, -1, sizeof want);
    long expected = 0, ghost_pairs = 0;
    for (size_t a = 0; a < n; ++a)
        for (size_t b = a + 1; b < n; ++b) {
            sd_real rs = s->r[a] + s->r[b] + skin;
            if (!(sd_v3_norm2(sd_v3_sub(s->x[a], s->x[b])) < rs * rs))
                continue;
            if (a >= s->no && b >= s->no)
                continue;
            if (b >= s->no) {
                size_t k = owner_of(s, b);
                if (k == a || !(s->id[a] < s->id[k]))
                    continue;
                ghost_pairs++;
            }
            want[a][b] = (signed char)sd_bins_pair_kind(class_of(s, a), class_of(s, b),
                                                        volume_law[s->mat[a] * 2 + s->mat[b]]);
            expected++;
        }
    long wrong_kind = 0, extra = 0, two_ghosts = 0, dup = 0;
    for (int k = 0; k < SD_PAIR_KIND_COUNT; ++k)
        for (size_t e = l->kind_start[k]; e < l->kind_start[k + 1]; ++e) {
            size_t i = l->i[e], j = l->j[e];
            if (i >= s->no && j >= s->no)
                two_ghosts++;
            if (!(i < j) || want[i][j] == -1) {
                extra++;
                continue;
            }
            if (want[i][j] == -2)
                dup++;
            else if (want[i][j] != k)
                wrong_kind++;
            want[i][j] = -2;
        }
    long missing = 0;
    for (size_t a = 0; a < n; ++a)
        for (size_t b = a + 1; b < n; ++b)
            missing += want[a][b] >= 0;
    printf("pairs: %zu in the list, %ld expected (%ld through images)\n", l->n, expected, ghost_pairs);
    CHECK(ghost_pairs > 0);
    CHECK_NEAR("pairs in the list", (double)l->n, (double)expected, 0);
    CHECK_NEAR("pairs missing", (double)missing, 0, 0);
    CHECK_NEAR("pairs not expected", (double)extra, 0, 0);
    CHECK_NEAR("pairs twice", (double)dup, 0, 0);
    CHECK_NEAR("pairs in the wrong kind segment", (double)wrong_kind, 0, 0);
    CHECK_NEAR("pairs of two ghosts", (double)two_ghosts, 0, 0);
    int kinds_seen = 0;
    for (int k = 0; k < SD_PAIR_KIND_COUNT; ++k)
        kinds_seen += l->kind_start[k + 1] > l->kind_start[k];
    CHECK_NEAR("kinds with pairs (spheres, convex, poly volume)", kinds_seen, 3, 0);

    /* gather lists: owned particles only; the ghost's side to its owner */
    long bad = 0, to_owner = 0;
    for (size_t k = 0; k < s->no; ++k)
        for (uint32_t g = l->gstart[k]; g < l->gstart[k + 1]; ++g) {
            uint32_t e = l->gidx[g] >> 1, side = l->gidx[g] & 1u;
            size_t who = side ? l->j[e] : l->i[e];
            if (owner_of(s, who) != k)
                bad++;
            to_owner += side && who >= s->no;
        }
    CHECK_NEAR("gather entries in the wrong list", (double)bad, 0, 0);
    CHECK_NEAR("gather entries, two per pair", (double)l->gstart[s->no], 2.0 * (double)l->n, 0);
    CHECK_NEAR("ghost sides gathered by their owners", (double)to_owner, (double)ghost_pairs, 0);
}

static void test_pairs_and_history(void)
{
    static scene s;
    memset(&s, 0, sizeof s);
    sd_rng rng = sd_rng_seed(12);
    s.no = NO;
    for (size_t k = 0; k < NO; ++k) {
        s.x[k] = sd_v3((sd_real)sd_rng_range(&rng, 0, 1), (sd_real)sd_rng_range(&rng, 0, 0.5),
                       (sd_real)sd_rng_range(&rng, 0, 0.5));
        s.r[k] = (sd_real)sd_rng_range(&rng, 0.015, 0.05);
        /* ids that agree in their low 32 bits: a 32-bit key half would alias them */
        s.id[k] = ((uint64_t)(k * 7919 % NO + 1) << 32) | 5u;
        s.shape[k] = (int32_t)(k % 3) - 1; /* sphere, shape, sharp polyhedron */
        s.mat[k] = (int32_t)(k % 5 == 0 ? 0 : 1);
    }
    make_ghosts(&s);
    sd_wall_geom walls[2];
    memset(walls, 0, sizeof walls);
    walls[0].kind = SD_WALL_BOX;
    walls[0].lo = sd_v3(-1, 0, 0);
    walls[0].hi = sd_v3(2, SD_R(0.5), SD_R(0.5));
    walls[0].open_faces = SD_BOX_XMIN | SD_BOX_XMAX;
    walls[1].kind = SD_WALL_PLANE;
    walls[1].normal = sd_v3(0, 0, 1);
    int32_t wmat[2] = {1, 0};

    sd_bins b;
    sd_pair_list l;
    sd_wall_pair_list wl;
    memset(&b, 0, sizeof b);
    memset(&l, 0, sizeof l);
    memset(&wl, 0, sizeof wl);
    sd_bins_input in = input_of(&s, walls, wmat, 2);
    const uint32_t *perm;
    void *scratch;
    CHECK(sd_bins_sort(&b, &in, &perm, &scratch) == SD_OK);
    permute(&s, perm);
    make_ghosts(&s);
    in = input_of(&s, walls, wmat, 2);
    CHECK(sd_bins_build(&b, &in, &l, &wl) == SD_OK);
    check_pairs(&s, &l, in.skin);

    /* history: each pair's spring names its key, each wall pair's its
     * particle, wall and feature */
    for (size_t e = 0; e < l.n; ++e)
        l.ds[e] = sd_v3((sd_real)(l.key[e].id_lo >> 32), (sd_real)(l.key[e].id_hi >> 32), 1);
    for (size_t e = 0; e < wl.n; ++e)
        wl.ds[e] = sd_v3((sd_real)(wl.key[e].id >> 32), (sd_real)wl.key[e].wall, (sd_real)wl.key[e].sub + 1);
    long features = 0;
    for (size_t e = 0; e < wl.n; ++e)
        features += wl.sub[e] != 0;
    CHECK(features > 0);

    /* a new storage order (reversed), then a rebuild */
    uint32_t rev[NO];
    for (size_t k = 0; k < NO; ++k)
        rev[k] = (uint32_t)(NO - 1 - k);
    permute(&s, rev);
    make_ghosts(&s);
    in = input_of(&s, walls, wmat, 2);
    CHECK(sd_bins_build(&b, &in, &l, &wl) == SD_OK);
    check_pairs(&s, &l, in.skin);
    long bad_key = 0, bad_spring = 0;
    for (size_t e = 0; e < l.n; ++e) {
        uint64_t a = s.id[l.i[e]], c = s.id[l.j[e]];
        if (l.key[e].id_lo != (a < c ? a : c) || l.key[e].id_hi != (a < c ? c : a) || l.flip[e] != (a > c))
            bad_key++;
        sd_vec3 want = sd_v3((sd_real)(l.key[e].id_lo >> 32), (sd_real)(l.key[e].id_hi >> 32), 1);
        if (memcmp(&want, &l.ds[e], sizeof want) != 0)
            bad_spring++;
    }
    CHECK_NEAR("pair keys not (lower id, higher id)", (double)bad_key, 0, 0);
    CHECK_NEAR("pair springs not carried to their key", (double)bad_spring, 0, 0);
    long bad_wall = 0, wall_kind = 0;
    for (int k = 0; k < SD_WALL_PAIR_KIND_COUNT; ++k)
        for (size_t e = wl.kind_start[k]; e < wl.kind_start[k + 1]; ++e) {
            size_t i = wl.i[e];
            sd_vec3 want = sd_v3((sd_real)(s.id[i] >> 32), (sd_real)wl.wall[e], (sd_real)wl.sub[e] + 1);
            if (memcmp(&want, &wl.ds[e], sizeof want) != 0)
                bad_wall++;
            int kk = sd_bins_wall_pair_kind(class_of(&s, i), volume_law[s.mat[i] * 2 + wmat[wl.wall[e]]]);
            wall_kind += kk != k || i >= s.no;
        }
    CHECK_NEAR("wall springs not carried to (id, wall, feature)", (double)bad_wall, 0, 0);
    CHECK_NEAR("wall pairs of the wrong kind or of ghosts", (double)wall_kind, 0, 0);
    /* wall gather lists: each owned particle's wall pairs once, in wall order */
    long wbad = 0;
    for (size_t k = 0; k < s.no; ++k)
        for (uint32_t g = wl.gstart[k]; g < wl.gstart[k + 1]; ++g) {
            uint32_t e = wl.gidx[g];
            wbad += wl.i[e] != k;
            if (g > wl.gstart[k]) {
                uint32_t p = wl.gidx[g - 1];
                wbad += wl.wall[p] * 8 + wl.sub[p] >= wl.wall[e] * 8 + wl.sub[e];
            }
        }
    CHECK_NEAR("wall gather entries wrong or out of wall order", (double)wbad, 0, 0);
    CHECK_NEAR("wall gather entries, one per pair", (double)wl.gstart[s.no], (double)wl.n, 0);
    sd_pairs_free(&l, &wl);
    sd_bins_free(&b);
}

/* ---- the walls module against the formulas it replaced ------------------- */

static int old_near(const sd_wall_geom *w, int face, sd_vec3 x, sd_real reach)
{
    if (w->kind == SD_WALL_PLANE)
        return sd_v3_dot(sd_v3_sub(x, w->point), w->normal) < reach;
    const sd_real c[3] = {x.x, x.y, x.z}, lo[3] = {w->lo.x, w->lo.y, w->lo.z}, hi[3] = {w->hi.x, w->hi.y, w->hi.z};
    int axis = face / 2;
    sd_real s = (face & 1) ? hi[axis] - c[axis] : c[axis] - lo[axis];
    return s < reach && s > -reach;
}

static int old_plane(const sd_wall_geom *w, int face, sd_vec3 x, sd_vec3 *p0, sd_vec3 *n)
{
    if (w->kind == SD_WALL_PLANE) {
        *p0 = w->point;
        *n = w->normal;
        return 1;
    }
    int axis = face / 2;
    sd_real lo[3] = {w->lo.x, w->lo.y, w->lo.z}, hi[3] = {w->hi.x, w->hi.y, w->hi.z}, c[3] = {x.x, x.y, x.z};
    for (int k = 0; k < 3; ++k)
        if (k != axis && (c[k] < lo[k] || c[k] > hi[k]))
            return 0;
    sd_real nn[3] = {0, 0, 0}, pp[3] = {c[0], c[1], c[2]};
    nn[axis] = (face & 1) ? -1 : 1;
    pp[axis] = (face & 1) ? hi[axis] : lo[axis];
    *p0 = sd_v3(pp[0], pp[1], pp[2]);
    *n = sd_v3(nn[0], nn[1], nn[2]);
    return 1;
}

static void test_walls(void)
{
    sd_rng rng = sd_rng_seed(3);
    long near_bad = 0, plane_bad = 0, face_bad = 0, line_bad = 0, features = 0;
    for (int t = 0; t < 20000; ++t) {
        sd_wall_geom w;
        memset(&w, 0, sizeof w);
        w.kind = t % 4 == 0 ? SD_WALL_PLANE : SD_WALL_BOX;
        w.point = sd_v3((sd_real)sd_rng_range(&rng, -1, 1), (sd_real)sd_rng_range(&rng, -1, 1), 0);
        w.normal = sd_v3_normalize(sd_v3((sd_real)sd_rng_range(&rng, -1, 1), (sd_real)sd_rng_range(&rng, -1, 1),
                                         (sd_real)sd_rng_range(&rng, -1, 1)));
        w.lo = sd_v3((sd_real)sd_rng_range(&rng, -1, 0), (sd_real)sd_rng_range(&rng, -1, 0),
                     (sd_real)sd_rng_range(&rng, -1, 0));
        w.hi = sd_v3((sd_real)sd_rng_range(&rng, 0, 1), (sd_real)sd_rng_range(&rng, 0, 1),
                     (sd_real)sd_rng_range(&rng, 0, 1));
        w.open_faces = (unsigned)(sd_rng_next(&rng) & 63u);
        sd_vec3 x = sd_v3((sd_real)sd_rng_range(&rng, -1.2, 1.2), (sd_real)sd_rng_range(&rng, -1.2, 1.2),
                          (sd_real)sd_rng_range(&rng, -1.2, 1.2));
        sd_real reach = (sd_real)sd_rng_range(&rng, 0, 0.5);
        int nf = sd_wall_feature_count(&w);
        for (int f = 0; f < nf; ++f) {
            int exists = w.kind == SD_WALL_PLANE ? 1 : !(w.open_faces & (1u << f));
            if (exists != sd_wall_feature_exists(&w, f))
                face_bad++;
            if (!exists)
                continue;
            features++;
            near_bad += old_near(&w, f, x, reach) != sd_wall_feature_near(&w, f, x, reach);
            sd_vec3 p0a = sd_v3_zero(), na = sd_v3_zero(), p0b = sd_v3_zero(), nb = sd_v3_zero();
            int a = old_plane(&w, f, x, &p0a, &na), b = sd_wall_feature_plane(&w, f, x, &p0b, &nb);
            plane_bad += a != b || (a && (memcmp(&p0a, &p0b, sizeof p0a) || memcmp(&na, &nb, sizeof na)));
            if (w.kind == SD_WALL_BOX) {
                sd_wall_face d = sd_wall_box_face_of(w.lo, w.hi, f);
                face_bad += !(d.axis == f / 2 && d.value == (a ? sd_wall_comp(p0a, d.axis) : d.value) &&
                              d.dir == ((f & 1) ? -1 : 1));
            }
            /* the 2D line is the 3D plane cut by z = 0 (x and y faces) */
            sd_vec2 lp, ln;
            int c = sd_wall_feature_line(&w, f, x, &lp, &ln);
            if (w.kind == SD_WALL_BOX && f < 4) {
                int inside = (f / 2 == 0) ? !(x.y < w.lo.y || x.y > w.hi.y) : !(x.x < w.lo.x || x.x > w.hi.x);
                line_bad += c != inside || (c && (ln.x != sd_wall_box_face_of(w.lo, w.hi, f).dir * (f / 2 == 0) ||
                                                  ln.y != sd_wall_box_face_of(w.lo, w.hi, f).dir * (f / 2 == 1)));
            } else if (w.kind == SD_WALL_BOX) {
                line_bad += c != 0;
            } else {
                line_bad += !c || lp.x != w.point.x || ln.y != w.normal.y;
            }
        }
    }
    printf("walls: %ld features checked\n", features);
    CHECK_NEAR("feature_near differs from the old face loop", (double)near_bad, 0, 0);
    CHECK_NEAR("feature_plane differs from the old one", (double)plane_bad, 0, 0);
    CHECK_NEAR("box face data or existence wrong", (double)face_bad, 0, 0);
    CHECK_NEAR("feature_line wrong", (double)line_bad, 0, 0);
    /* walls across periodic axes */
    sd_wall_geom pl;
    memset(&pl, 0, sizeof pl);
    pl.kind = SD_WALL_PLANE;
    pl.normal = sd_v3(0, 0, 1);
    CHECK(!sd_wall_crosses_axis(&pl, 0) && sd_wall_crosses_axis(&pl, 2));
    pl.kind = SD_WALL_BOX;
    pl.open_faces = SD_BOX_XMIN | SD_BOX_XMAX;
    CHECK(!sd_wall_crosses_axis(&pl, 0) && sd_wall_crosses_axis(&pl, 1));
}

int main(void)
{
    test_pairs_and_history();
    test_walls();
    return sd_test_summary();
}
