/* convex_epa_ref.h — the EPA of src/geom/epa.h as it was before issue 11
 * (commit 28aa3e8), kept verbatim with its names prefixed sd_eparef_ /
 * SD_EPAREF_, as the reference that tests/unit/convex_epa_reference.c
 * compares the engine's EPA with: a faster EPA must give the same contact
 * (depth and normal) on many random pairs. Not used by the engine.
 */
/* epa.h — EPA penetration depth of two overlapping convex cores.
 * Single source (SD_HD): C17 and CUDA C++, no allocation, no printing,
 * fixed arrays (SD_EPAREF_MAX_FACES faces, SD_EPAREF_MAX_VERTS vertices).
 *
 * What: the expanding polytope algorithm on K = A − B. The depth is the
 * distance from the origin (inside K) to K's boundary; the nearest face of a
 * polytope P ⊂ K gives a lower bound f.dist and the support of K along that
 * face's normal n an upper bound n·w; P grows by the support point until the
 * two meet (notes/algorithms.md §C, DESIGN.md note "GJK/EPA").
 *
 * Invariants: P is a closed, consistently wound (outward) triangle mesh whose
 * vertices are support points of K, so P ⊂ K and every face distance is a
 * lower bound of the depth; growing P deletes ALL faces visible from the new
 * point (a connected set, found by flood fill from the nearest face) and fans
 * the horizon, so P stays convex (the FCL #301/#305 bug was deleting only one
 * face). Nothing here divides by a quantity that can vanish unchecked: the
 * result is never NaN.
 *
 * Start: GJK's final simplex of 1, 2, 3 or 4 points. Smaller simplices (the
 * origin on a vertex, segment or triangle of K — e.g. aligned boxes, OpenRAL
 * #215) are blown up with supports along fixed directions (segment: three
 * directions at 120° about it; triangle: its normal ±; point: ±x, ±y, ±z),
 * a start tetrahedron is picked from those points and the rest are added as
 * ordinary expansions. Origin ON a start face (mujoco_warp #1526) is not a
 * reason to drop the contact: that face is then the nearest (distance ~0) and
 * the support along its normal decides — nothing beyond it means the cores
 * just touch (status TOUCHING, depth 0, that face's normal); a point beyond
 * it is a real overlap and the expansion proceeds.
 *
 * Termination: support·n − f.dist ≤ 1e-8·max(f.dist, 1e-6 L) → OK; a support
 * point already in P → OK (no progress possible); 64 iterations, a full face
 * or vertex array, or a zero-area new face → CAPPED (or DEGENERATE) with the
 * best face so far, whose distance is a lower bound of the depth. Curved
 * cores (ellipsoids, cylinder sides) rarely converge to 1e-8 within the caps:
 * there a capped run is finished by a few Newton steps on the direction
 * (sd_eparef_polish), accepted only if it converges and stays consistent with
 * the lower bound; it reports OK with the polished depth, else CAPPED.
 */
#ifndef SD_TEST_CONVEX_EPA_REF_H
#define SD_TEST_CONVEX_EPA_REF_H

#include "geom/gjk.h"

typedef enum {
    SD_EPAREF_OK,        /* converged */
    SD_EPAREF_TOUCHING,  /* origin on K's boundary (depth ≤ 1e-9 L): depth 0 */
    SD_EPAREF_CAPPED,    /* iteration/face cap: best face so far (a lower bound) */
    SD_EPAREF_DEGENERATE /* flat K, bad input or zero-area face: best estimate, maybe 0 */
} sd_eparef_status;

#define SD_EPAREF_MAX_ITERATIONS 64
#define SD_EPAREF_MAX_FACES 128
#define SD_EPAREF_MAX_VERTS (SD_EPAREF_MAX_ITERATIONS + 16)
#define SD_EPAREF_REL_TOL SD_R(1e-8)
#define SD_EPAREF_TOUCH_TOL SD_R(1e-9)

typedef struct sd_eparef_result {
    int status;      /* sd_eparef_status */
    sd_real depth;   /* m, penetration depth of the cores (≥ 0) */
    sd_vec3 normal;  /* unit, from b into a: moving a by depth*normal separates them */
    sd_vec3 pa, pb;  /* deepest points on each core (pa − pb = −depth·normal) */
    int iterations, support_calls;
} sd_eparef_result;

typedef struct sd_eparef_face {
    int i[3];     /* vertex indices, wound outward */
    sd_vec3 n;    /* unit outward normal */
    sd_real dist; /* n·v: signed distance of the plane from the origin */
} sd_eparef_face;

typedef struct sd_eparef_poly {
    sd_gjk_vertex v[SD_EPAREF_MAX_VERTS];
    sd_eparef_face f[SD_EPAREF_MAX_FACES];
    int nv, nf;
    sd_real L;
} sd_eparef_poly;

/* Fills face (i, j, k) wound outward; 0 for a zero-area triangle. */
SD_HD static SD_INLINE int sd_eparef_face_make(const sd_eparef_poly *P, sd_eparef_face *f, int i, int j, int k)
{
    sd_vec3 a = P->v[i].w, b = P->v[j].w, c = P->v[k].w;
    sd_vec3 n = sd_v3_cross(sd_v3_sub(b, a), sd_v3_sub(c, a));
    sd_real len = sd_v3_norm(n);
    /* area below (1e-15 L)^2: the normal would be rounding noise */
    if (!(len > sd_sq(SD_R(1e-15) * P->L)))
        return 0;
    n = sd_v3_scale(n, SD_R(1.0) / len);
    f->i[0] = i;
    f->i[1] = j;
    f->i[2] = k;
    f->n = n;
    /* mean of the three vertices: the least rounding-biased plane offset */
    f->dist = (sd_v3_dot(n, a) + sd_v3_dot(n, b) + sd_v3_dot(n, c)) / SD_R(3.0);
    return 1;
}

/* The face that holds directed edge (e0 → e1), or −1. */
SD_HD static SD_INLINE int sd_eparef_edge_owner(const sd_eparef_poly *P, int e0, int e1)
{
    for (int g = 0; g < P->nf; ++g)
        for (int m = 0; m < 3; ++m)
            if (P->f[g].i[m] == e0 && P->f[g].i[(m + 1) % 3] == e1)
                return g;
    return -1;
}

/* Adds vertex p (already stored at index pi) to P, starting the visible set
 * at face `seed` (−1: any visible face). Returns 1 if added, 0 if p is not
 * beyond any face (nothing changes), −1 on overflow or a zero-area face. */
SD_HD static SD_INLINE int sd_eparef_expand(sd_eparef_poly *P, int pi, int seed)
{
    sd_vec3 p = P->v[pi].w;
    unsigned char vis[SD_EPAREF_MAX_FACES];
    int stack[SD_EPAREF_MAX_FACES];
    int horizon[SD_EPAREF_MAX_FACES + 8][2];
    int nh = 0, ns = 0;
    for (int g = 0; g < P->nf; ++g)
        vis[g] = 0;
    if (seed < 0) {
        sd_real best = SD_R(0.0);
        for (int g = 0; g < P->nf; ++g) {
            sd_real h = sd_v3_dot(P->f[g].n, p) - P->f[g].dist;
            if (h > best) {
                best = h;
                seed = g;
            }
        }
        /* "beyond" by more than rounding of the plane offset */
        if (seed < 0 || !(best > SD_R(1e-13) * P->L))
            return 0;
    }
    vis[seed] = 1;
    stack[ns++] = seed;
    /* flood fill over edge-neighbours: a connected visible set, so the
     * horizon is one loop even when rounding blurs nearly coplanar faces */
    while (ns > 0) {
        int g = stack[--ns];
        for (int m = 0; m < 3; ++m) {
            int e0 = P->f[g].i[m], e1 = P->f[g].i[(m + 1) % 3];
            int h = sd_eparef_edge_owner(P, e1, e0);
            if (h >= 0 && vis[h])
                continue;
            /* a neighbour whose plane holds p (within rounding) goes too:
             * p then lies on the line of their shared edge (boxes: corners
             * in line with a face centre), and fanning that edge would make
             * a zero-area face; dropping the coplanar face keeps P convex */
            if (h >= 0 && sd_v3_dot(P->f[h].n, p) - P->f[h].dist > -SD_R(1e-13) * P->L) {
                vis[h] = 1;
                stack[ns++] = h;
                continue;
            }
            if (nh >= SD_EPAREF_MAX_FACES + 8)
                return -1;
            horizon[nh][0] = e0;
            horizon[nh][1] = e1;
            nh++;
        }
    }
    int nkeep = 0;
    for (int g = 0; g < P->nf; ++g)
        if (!vis[g])
            nkeep++;
    if (nkeep + nh > SD_EPAREF_MAX_FACES)
        return -1;
    sd_eparef_face nf[SD_EPAREF_MAX_FACES + 8];
    for (int e = 0; e < nh; ++e)
        if (!sd_eparef_face_make(P, &nf[e], horizon[e][0], horizon[e][1], pi))
            return -1;
    int k = 0;
    for (int g = 0; g < P->nf; ++g)
        if (!vis[g])
            P->f[k++] = P->f[g];
    for (int e = 0; e < nh; ++e)
        P->f[k++] = nf[e];
    P->nf = k;
    return 1;
}

/* Start tetrahedron from candidate points c[0..nc): the most spread four
 * (farthest pair, farthest from their line, farthest from that plane).
 * Returns 0 when all candidates are (nearly) coplanar, with *flat_n the
 * normal of their plane when there is one. */
SD_HD static SD_INLINE int sd_eparef_start(sd_eparef_poly *P, const sd_gjk_vertex *c, int nc, sd_vec3 *flat_n)
{
    const sd_real eps = SD_R(1e-10) * P->L;
    int i0 = 0, i1 = -1, i2 = -1, i3 = -1;
    sd_real best = SD_R(0.0);
    *flat_n = sd_v3_zero();
    for (int m = 0; m < nc; ++m) {
        sd_real d = sd_v3_norm2(sd_v3_sub(c[m].w, c[i0].w));
        if (d > best) {
            best = d;
            i1 = m;
        }
    }
    if (i1 < 0 || !(best > eps * eps))
        return 0;
    sd_vec3 e = sd_v3_sub(c[i1].w, c[i0].w);
    best = SD_R(0.0);
    for (int m = 0; m < nc; ++m) {
        sd_vec3 x = sd_v3_cross(e, sd_v3_sub(c[m].w, c[i0].w));
        sd_real d = sd_v3_norm2(x) / sd_v3_norm2(e);
        if (d > best) {
            best = d;
            i2 = m;
        }
    }
    if (i2 < 0 || !(best > eps * eps))
        return 0;
    sd_vec3 n = sd_v3_normalize(sd_v3_cross(e, sd_v3_sub(c[i2].w, c[i0].w)));
    *flat_n = n;
    best = SD_R(0.0);
    for (int m = 0; m < nc; ++m) {
        sd_real d = sd_fabs(sd_v3_dot(n, sd_v3_sub(c[m].w, c[i0].w)));
        if (d > best) {
            best = d;
            i3 = m;
        }
    }
    if (i3 < 0 || !(best > eps))
        return 0;
    /* wind the four faces outward: vertex 3 must lie below face (0, 1, 2) */
    if (sd_v3_dot(n, sd_v3_sub(c[i3].w, c[i0].w)) > SD_R(0.0)) {
        int t = i1;
        i1 = i2;
        i2 = t;
    }
    P->v[0] = c[i0];
    P->v[1] = c[i1];
    P->v[2] = c[i2];
    P->v[3] = c[i3];
    P->nv = 4;
    P->nf = 0;
    if (!sd_eparef_face_make(P, &P->f[0], 0, 1, 2) || !sd_eparef_face_make(P, &P->f[1], 0, 3, 1) ||
        !sd_eparef_face_make(P, &P->f[2], 1, 3, 2) || !sd_eparef_face_make(P, &P->f[3], 0, 2, 3))
        return 0;
    P->nf = 4;
    /* the rest of the candidates join as ordinary expansions */
    for (int m = 0; m < nc; ++m) {
        if (m == i0 || m == i1 || m == i2 || m == i3)
            continue;
        if (P->nv >= SD_EPAREF_MAX_VERTS)
            break;
        P->v[P->nv] = c[m];
        int added = sd_eparef_expand(P, P->nv, -1);
        if (added < 0)
            return 0;
        if (added > 0)
            P->nv++;
    }
    return 1;
}

/* Witnesses for the nearest face: the origin's projection (dist·n) in
 * barycentric coordinates of the face, clamped into it against rounding. */
SD_HD static SD_INLINE void sd_eparef_witness(const sd_eparef_poly *P, const sd_eparef_face *f, sd_vec3 *pa, sd_vec3 *pb)
{
    sd_vec3 a = P->v[f->i[0]].w, b = P->v[f->i[1]].w, c = P->v[f->i[2]].w;
    sd_vec3 p = sd_v3_scale(f->n, f->dist);
    sd_real l0 = sd_v3_dot(sd_v3_cross(sd_v3_sub(b, p), sd_v3_sub(c, p)), f->n);
    sd_real l1 = sd_v3_dot(sd_v3_cross(sd_v3_sub(c, p), sd_v3_sub(a, p)), f->n);
    sd_real l2 = sd_v3_dot(sd_v3_cross(sd_v3_sub(a, p), sd_v3_sub(b, p)), f->n);
    l0 = sd_max(l0, SD_R(0.0));
    l1 = sd_max(l1, SD_R(0.0));
    l2 = sd_max(l2, SD_R(0.0));
    sd_real s = l0 + l1 + l2;
    if (!(s > SD_R(0.0))) {
        l0 = l1 = l2 = SD_R(1.0);
        s = SD_R(3.0);
    }
    l0 /= s;
    l1 /= s;
    l2 /= s;
    const sd_gjk_vertex *A = &P->v[f->i[0]], *B = &P->v[f->i[1]], *C = &P->v[f->i[2]];
    *pa = sd_v3_add(sd_v3_add(sd_v3_scale(A->a, l0), sd_v3_scale(B->a, l1)), sd_v3_scale(C->a, l2));
    *pb = sd_v3_add(sd_v3_add(sd_v3_scale(A->b, l0), sd_v3_scale(B->b, l1)), sd_v3_scale(C->b, l2));
}

/* Newton polish of a capped EPA on curved cores. The depth is
 * min over unit u of h_K(u) (h_K = support function of K); EPA brackets it
 * by the nearest face (below) and h_K along faces' normals (above), but on
 * curved surfaces the bracket closes slowly (each expansion splits one face
 * into slivers) and 64 iterations can leave 1e-2 relative. Near the minimum
 * h_K is smooth for curved cores, so Newton's method on the sphere of
 * directions converges in a few steps: with u(x) = normalize(u + x1 t1 + x2 t2),
 * the gradient is g_i = s(u)·t_i (s = support point, the gradient of h_K)
 * and the Hessian H_ij = (∂s/∂x_j)·t_i − δ_ij h_K(u), with ∂s/∂x_j by a
 * forward difference (two more support calls). Steps along directions where
 * H is not positive (flat faces, kinks) are dropped, every step must lower
 * h_K (halving up to 4 times), so the answer only tightens the upper bound.
 * Returns 1 when the step has shrunk below 1e-7 rad (depth error ~1e-14 L). */
SD_HD static SD_INLINE int sd_eparef_polish(const sd_convex *a, const sd_convex *b, sd_vec3 *u, sd_gjk_vertex *w, int *calls)
{
    const sd_real hstep = SD_R(1e-6);
    sd_real f = sd_v3_dot(*u, w->w);
    for (int it = 0; it < 8; ++it) {
        sd_vec3 n = *u;
        sd_vec3 ax = sd_fabs(n.x) < SD_R(0.57735) ? sd_v3(SD_R(1.0), SD_R(0.0), SD_R(0.0))
                                                  : (sd_fabs(n.y) < SD_R(0.57735) ? sd_v3(SD_R(0.0), SD_R(1.0), SD_R(0.0))
                                                                                  : sd_v3(SD_R(0.0), SD_R(0.0), SD_R(1.0)));
        sd_vec3 t1 = sd_v3_normalize(sd_v3_cross(n, ax));
        sd_vec3 t2 = sd_v3_cross(n, t1);
        sd_vec3 s0 = w->w;
        sd_real g1 = sd_v3_dot(s0, t1), g2 = sd_v3_dot(s0, t2);
        sd_gjk_vertex w1 = sd_gjk_support(a, b, sd_v3_normalize(sd_v3_madd(n, hstep, t1)));
        sd_gjk_vertex w2 = sd_gjk_support(a, b, sd_v3_normalize(sd_v3_madd(n, hstep, t2)));
        *calls += 2;
        if (!sd_gjk_finite(w1.w) || !sd_gjk_finite(w2.w))
            return 0;
        sd_vec3 d1 = sd_v3_scale(sd_v3_sub(w1.w, s0), SD_R(1.0) / hstep);
        sd_vec3 d2 = sd_v3_scale(sd_v3_sub(w2.w, s0), SD_R(1.0) / hstep);
        sd_real h11 = sd_v3_dot(d1, t1) - f, h22 = sd_v3_dot(d2, t2) - f;
        sd_real h12 = SD_R(0.5) * (sd_v3_dot(d2, t1) + sd_v3_dot(d1, t2));
        /* eigen-decomposition of the symmetric 2x2 H: x = −Σ (e·g)/λ e over λ > 0 */
        sd_real tr = SD_R(0.5) * (h11 + h22), df = SD_R(0.5) * (h11 - h22);
        sd_real rad = sd_sqrt(df * df + h12 * h12);
        sd_real lam[2] = {tr + rad, tr - rad};
        sd_real x1 = SD_R(0.0), x2 = SD_R(0.0);
        for (int k = 0; k < 2; ++k) {
            /* eigenvector of λ: (h12, λ − h11) or (λ − h22, h12), the better conditioned */
            sd_real e1 = h12, e2 = lam[k] - h11;
            sd_real f1 = lam[k] - h22, f2 = h12;
            if (e1 * e1 + e2 * e2 < f1 * f1 + f2 * f2) {
                e1 = f1;
                e2 = f2;
            }
            sd_real en = sd_sqrt(e1 * e1 + e2 * e2);
            if (!(en > SD_R(0.0))) {
                e1 = k == 0 ? SD_R(1.0) : SD_R(0.0);
                e2 = k == 0 ? SD_R(0.0) : SD_R(1.0);
                en = SD_R(1.0);
            }
            e1 /= en;
            e2 /= en;
            /* λ must be clearly positive against the finite-difference noise */
            if (!(lam[k] > SD_R(1e-6) * sd_fabs(f) + SD_R(1e-300)))
                continue;
            sd_real c = -(e1 * g1 + e2 * g2) / lam[k];
            x1 += c * e1;
            x2 += c * e2;
        }
        sd_real xs = sd_sqrt(x1 * x1 + x2 * x2);
        if (!(xs > SD_R(0.0)))
            return 0; /* no positive curvature: leave it to EPA's bracket */
        if (xs > SD_R(0.5)) { /* stay in the basin EPA found */
            x1 *= SD_R(0.5) / xs;
            x2 *= SD_R(0.5) / xs;
        }
        int accepted = 0;
        for (int half = 0; half < 5 && !accepted; ++half) {
            sd_vec3 un = sd_v3_normalize(sd_v3_add(n, sd_v3_add(sd_v3_scale(t1, x1), sd_v3_scale(t2, x2))));
            sd_gjk_vertex wn = sd_gjk_support(a, b, un);
            *calls += 1;
            if (!sd_gjk_finite(wn.w))
                return 0;
            sd_real fn = sd_v3_dot(un, wn.w);
            if (fn <= f) {
                *u = un;
                *w = wn;
                f = fn;
                accepted = 1;
            } else {
                x1 *= SD_R(0.5);
                x2 *= SD_R(0.5);
            }
        }
        if (xs <= SD_R(1e-7))
            return 1;
        if (!accepted)
            return 0;
    }
    return 0;
}

/* Penetration depth of the cores of a and b, which GJK found touching or
 * overlapping (result g). */
SD_HD static SD_INLINE sd_eparef_result sd_eparef_penetration(const sd_convex *a, const sd_convex *b, const sd_gjk_result *g)
{
    sd_eparef_result r;
    sd_eparef_poly P;
    P.L = sd_gjk_length_scale(a, b);
    r.iterations = 0;
    r.support_calls = 0;
    r.status = SD_EPAREF_DEGENERATE;
    r.depth = SD_R(0.0);
    r.normal = sd_v3(SD_R(0.0), SD_R(0.0), SD_R(1.0));
    sd_gjk_witnesses(&g->simplex, &r.pa, &r.pb);

    /* candidate points: the simplex, then blow-up supports */
    sd_gjk_vertex c[4 + 12];
    int nc = 0;
    const sd_gjk_simplex *s = &g->simplex;
    for (int m = 0; m < s->n && m < 4; ++m)
        c[nc++] = s->v[m];
    if (s->n == 1) {
        /* the origin sits on a support point of K, i.e. on K's boundary,
         * when that point's search direction still supports K there */
        sd_vec3 d = sd_v3_normalize(g->dir);
        if (sd_v3_norm2(d) > SD_R(0.0)) {
            sd_gjk_vertex w = sd_gjk_support(a, b, d);
            r.support_calls++;
            if (sd_gjk_finite(w.w) && sd_v3_dot(d, w.w) <= SD_EPAREF_TOUCH_TOL * P.L) {
                r.status = SD_EPAREF_TOUCHING;
                r.normal = sd_v3_neg(d);
                return r;
            }
        }
    }
    if (s->n == 2) {
        sd_vec3 e = sd_v3_normalize(sd_v3_sub(s->v[1].w, s->v[0].w));
        /* the axis least aligned with e gives a well-conditioned perpendicular */
        sd_vec3 ax = sd_fabs(e.x) < sd_fabs(e.y) ? (sd_fabs(e.x) < sd_fabs(e.z) ? sd_v3(SD_R(1.0), SD_R(0.0), SD_R(0.0))
                                                                               : sd_v3(SD_R(0.0), SD_R(0.0), SD_R(1.0)))
                                                 : (sd_fabs(e.y) < sd_fabs(e.z) ? sd_v3(SD_R(0.0), SD_R(1.0), SD_R(0.0))
                                                                               : sd_v3(SD_R(0.0), SD_R(0.0), SD_R(1.0)));
        sd_vec3 u = sd_v3_normalize(sd_v3_cross(e, ax));
        sd_vec3 t = sd_v3_cross(e, u);
        const sd_real c120 = SD_R(-0.5), s120 = SD_R(0.86602540378443864676);
        c[nc++] = sd_gjk_support(a, b, u);
        c[nc++] = sd_gjk_support(a, b, sd_v3_add(sd_v3_scale(u, c120), sd_v3_scale(t, s120)));
        c[nc++] = sd_gjk_support(a, b, sd_v3_sub(sd_v3_scale(u, c120), sd_v3_scale(t, s120)));
        r.support_calls += 3;
    }
    if (s->n == 3) {
        sd_vec3 n = sd_v3_normalize(
            sd_v3_cross(sd_v3_sub(s->v[1].w, s->v[0].w), sd_v3_sub(s->v[2].w, s->v[0].w)));
        if (sd_v3_norm2(n) > SD_R(0.0)) {
            c[nc++] = sd_gjk_support(a, b, n);
            c[nc++] = sd_gjk_support(a, b, sd_v3_neg(n));
            r.support_calls += 2;
        }
    }
    for (int m = 0; m < nc; ++m)
        if (!sd_gjk_finite(c[m].w))
            return r;
    sd_vec3 flat_n;
    int ok = sd_eparef_start(&P, c, nc, &flat_n);
    if (!ok) {
        /* a point, or a simplex and blow-up that are flat: add the six axis supports */
        for (int ax = 0; ax < 6; ++ax) {
            sd_real sg = (ax & 1) ? SD_R(-1.0) : SD_R(1.0);
            sd_vec3 d = sd_v3(ax / 2 == 0 ? sg : SD_R(0.0), ax / 2 == 1 ? sg : SD_R(0.0), ax / 2 == 2 ? sg : SD_R(0.0));
            c[nc++] = sd_gjk_support(a, b, d);
            r.support_calls++;
            if (!sd_gjk_finite(c[nc - 1].w))
                return r;
        }
        ok = sd_eparef_start(&P, c, nc, &flat_n);
    }
    if (!ok) {
        /* K is flat (two flat cores in one plane): no depth across it */
        r.status = SD_EPAREF_DEGENERATE;
        if (sd_v3_norm2(flat_n) > SD_R(0.0))
            r.normal = flat_n;
        return r;
    }

    const sd_real floor_dist = SD_R(1e-6) * P.L;
    int best = 0;
    r.status = SD_EPAREF_CAPPED;
    /* the least h_K(n) seen: an upper bound of the depth, with its direction */
    sd_real ub = SD_R(1e300);
    sd_vec3 ub_n = P.f[0].n;
    sd_gjk_vertex ub_w = P.v[0];
    for (;;) {
        best = 0;
        for (int f = 1; f < P.nf; ++f)
            if (P.f[f].dist < P.f[best].dist)
                best = f;
        if (r.iterations >= SD_EPAREF_MAX_ITERATIONS)
            break;
        r.iterations++;
        sd_eparef_face fb = P.f[best];
        sd_gjk_vertex w = sd_gjk_support(a, b, fb.n);
        r.support_calls++;
        if (!sd_gjk_finite(w.w)) {
            r.status = SD_EPAREF_DEGENERATE;
            break;
        }
        if (sd_v3_dot(fb.n, w.w) < ub) {
            ub = sd_v3_dot(fb.n, w.w);
            ub_n = fb.n;
            ub_w = w;
        }
        sd_real gap = sd_v3_dot(fb.n, w.w) - fb.dist;
        if (gap <= SD_EPAREF_REL_TOL * sd_max(fb.dist, floor_dist)) {
            r.status = SD_EPAREF_OK;
            break;
        }
        int dup = 0;
        for (int m = 0; m < P.nv; ++m)
            if (sd_v3_norm2(sd_v3_sub(w.w, P.v[m].w)) <= sd_sq(SD_GJK_ABS_TOL * P.L))
                dup = 1;
        if (dup) { /* nothing new to add: the face is as good as it gets */
            r.status = SD_EPAREF_OK;
            break;
        }
        if (P.nv >= SD_EPAREF_MAX_VERTS)
            break;
        P.v[P.nv] = w;
        int added = sd_eparef_expand(&P, P.nv, best);
        if (added < 0) {
            break; /* full arrays or a sliver face: P is unchanged, keep its best face */
        }
        P.nv++;
    }
    sd_eparef_face fb = P.f[best];
    r.normal = sd_v3_neg(fb.n);
    r.depth = sd_max(fb.dist, SD_R(0.0));
    sd_eparef_witness(&P, &fb, &r.pa, &r.pb);
    if (r.status == SD_EPAREF_CAPPED && ub < SD_R(1e300)) {
        /* curved cores: polish the best direction by Newton's method */
        sd_vec3 u = ub_n;
        sd_gjk_vertex w = ub_w;
        if (sd_eparef_polish(a, b, &u, &w, &r.support_calls)) {
            sd_real dn = sd_v3_dot(u, w.w);
            if (dn >= fb.dist - SD_EPAREF_REL_TOL * sd_max(fb.dist, floor_dist)) {
                /* consistent with EPA's lower bound: a converged answer */
                r.status = SD_EPAREF_OK;
                r.depth = sd_max(dn, SD_R(0.0));
                r.normal = sd_v3_neg(u);
                r.pa = w.a;
                r.pb = w.b;
            }
        }
    }
    if (r.status == SD_EPAREF_OK && r.depth <= SD_EPAREF_TOUCH_TOL * P.L) {
        r.status = SD_EPAREF_TOUCHING;
        r.depth = SD_R(0.0);
    }
    return r;
}

#endif
