/* mesh_cap.c — a particle near more facets of one mesh than the bins'
 * stack workspace holds (SD_BINS_MESH_MAXT = 2048, broad/bins.c): a
 * sphere of 3 mm with a 2 mm skin resting on a 10 mm square split into
 * 80,000 triangles has about 28,000 triangles within its reach. Checked:
 *  - the wall pair's near-triangle list (tcount) holds every triangle
 *    within reach, counted here by brute force (the cap used to cut the
 *    list at 2,048 without a word);
 *  - the sphere rests on the mesh as on the analytic plane: the same
 *    height (to 1e-12 m) and the wall force is its weight.
 */
#include "test.h"

#include <stdlib.h>
#include <string.h>

#include "geom/clip.h"
#include "world/world.h"

#define PI 3.14159265358979323846

enum { N = 200 }; /* cells per side, two triangles each */

static sd_world *sd_cap_world(int mesh, double r, double z0, int *mat_out)
{
    sd_error err;
    sd_world *w;
    sd_world_def wd = sd_world_def_default();
    wd.law = SD_LAW_LINEAR;
    wd.dt = 1e-5;
    wd.gravity = sd_test_v(0, 0, -9.81);
    wd.threads = 1;
    wd.skin = 0.002;
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "steel";
    m.density = 7800;
    m.stiffness = 1e5;
    m.restitution = 0.3;
    m.friction = 0.5;
    int mat = sd_world_add_material(w, &m, &err);
    sd_test_require(mat >= 0, "material", &err);
    if (mesh) {
        const double L = 0.005, h = 2 * L / N;
        sd_v3d *v = malloc((size_t)(N + 1) * (N + 1) * sizeof *v);
        uint32_t(*t)[3] = malloc((size_t)2 * N * N * sizeof *t);
        sd_test_require(v && t, "memory", NULL);
        for (int j = 0; j <= N; ++j)
            for (int i = 0; i <= N; ++i)
                v[j * (N + 1) + i] = sd_test_v(-L + i * h, -L + j * h, 0);
        size_t nt = 0;
        for (int j = 0; j < N; ++j)
            for (int i = 0; i < N; ++i) {
                uint32_t a = (uint32_t)(j * (N + 1) + i), b = a + 1, c = a + N + 1, d = c + 1;
                uint32_t tt[2][3] = {{a, b, d}, {a, d, c}};
                memcpy(t[nt++], tt[0], sizeof tt[0]);
                memcpy(t[nt++], tt[1], sizeof tt[1]);
            }
        sd_mesh_def md = sd_mesh_def_default();
        md.vertices = v;
        md.vertex_count = (size_t)(N + 1) * (N + 1);
        md.triangles = (const uint32_t(*)[3])t;
        md.triangle_count = nt;
        md.material = mat;
        sd_test_require(sd_world_add_mesh(w, "floor", &md, &err) >= 0, "mesh", &err);
        free(v);
        free(t);
    } else {
        sd_test_require(sd_world_add_plane(w, "floor", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), mat, &err) >= 0,
                        "plane", &err);
    }
    sd_sphere_def s = {0};
    s.position = sd_test_v(0.0003, -0.0002, z0);
    s.radius = r;
    s.material = mat;
    sd_test_require(sd_world_add_spheres(w, 1, &s, &err) == SD_OK, "sphere", &err);
    *mat_out = mat;
    return w;
}

int main(void)
{
    const double r = 0.003, skin = 0.002, g = 9.81;
    const double mass = 7800 * 4.0 / 3.0 * PI * r * r * r, delta = mass * g / 1e5;
    const double z0 = r - delta;
    sd_error err;
    int mat;
    double zend[2], fz[2];
    long near = 0, listed = -1;
    for (int mesh = 0; mesh < 2; ++mesh) {
        sd_world *w = sd_cap_world(mesh, r, z0, &mat);
        sd_test_require(sd_world_step(w, 2000, &err) == SD_OK, "step", &err);
        sd_particle_state p = {0};
        sd_world_get_particle(w, 0, &p);
        zend[mesh] = p.position.z;
        sd_wall_info wi;
        CHECK(sd_world_get_wall(w, 0, &wi) == SD_OK);
        fz[mesh] = -wi.force.z;
        if (mesh) {
            /* every triangle within reach (radius + skin) of the centre at
             * the last rebuild: the sphere has not moved since (it rests) */
            const sd_wall_pair_list *l = &w->wpairs;
            CHECK(l->n == 1); /* one plane group: one pair */
            if (l->n >= 1)
                listed = (long)l->tcount[0];
            sd_mesh_info mi;
            CHECK(sd_world_get_mesh(w, 0, &mi) == SD_OK);
            sd_vec3 x = sd_v3((sd_real)p.position.x, (sd_real)p.position.y, (sd_real)p.position.z);
            sd_real reach = (sd_real)(r + skin);
            for (size_t k = 0; k < mi.triangle_count; ++k) {
                sd_vec3 c[3];
                for (int q = 0; q < 3; ++q) {
                    const double *vv = mi.vertices + 3 * mi.triangles[k][q];
                    c[q] = sd_v3((sd_real)vv[0], (sd_real)vv[1], (sd_real)vv[2]);
                }
                int f;
                sd_vec3 cp = sd_clip_closest(x, c[0], c[1], c[2], &f);
                near += sd_v3_norm2(sd_v3_sub(x, cp)) < reach * reach;
            }
            printf("mesh of %zu triangles: %ld within reach of the sphere, %ld in its wall pair's list\n",
                   mi.triangle_count, near, listed);
        }
        sd_world_destroy(w);
    }
    CHECK(near > 2048);
    CHECK_NEAR("near triangles listed vs brute force (no cap)", (double)listed, (double)near, 0.0);
    CHECK_NEAR("rest height on the mesh vs the plane (m)", zend[1], zend[0], 1e-12);
    CHECK_REL("wall force on the mesh vs m g (N)", fz[1], mass * g, 1e-3);
    return sd_test_summary();
}
