/* scene_from.c — a new scene starts from a checkpoint of another run
 * (issue 17; generator: csv with a .h5 file, io/scene_from.c).
 *
 * For each particle kind (spheres; convex boxes, cylinders, ellipsoids,
 * cones and an icosahedron; composites; the planar circles, ellipses and
 * polygons) a bed settles for a while and is checkpointed; a new scene
 * with the same templates and materials but other walls (a plane where
 * there was a box or servo walls) and a shift takes its particles from the
 * checkpoint. Every particle must come across exactly: position + shift,
 * velocity and spin bitwise, orientation to 1e-15 (normalised again), the
 * same template and material names, one for one in stable-id order; and
 * the new run must step on (finite, within the guards).
 */
#define _POSIX_C_SOURCE 200809L

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "test.h"

#include <shapedem/scene.h>

typedef struct from_case {
    const char *scene;  /* the bed's scene, sections simulation .. shapes reused */
    long settle;        /* steps before the checkpoint */
    const char *material;
    const char *walls;  /* the new scene's walls: section */
    double shift[3];    /* m */
} from_case;

static const from_case cases[] = {
    {"examples/settle-spheres.yaml", 5000, "glass",
     "walls:\n  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: glass}\n",
     {0.02, -0.01, 0.0002}},
    {"examples/mixed-shapes.yaml", 12000, "glass",
     "walls:\n  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: steel}\n"
     "  - {name: side, type: plane, point: [0.0, 0, 0], normal: [1, 0, 0], material: steel}\n",
     {0.005, 0.0, 0.0002}},
    {"tests/unit/scenes/restart-composites.yaml", 8000, "glass",
     "walls:\n  - {name: tray, type: box, min: [-0.03, -0.03, -0.001], max: [0.03, 0.03, 0.05], open: [zmax], "
     "material: glass}\n",
     {0.0, 0.0, 0.0}},
    {"examples/biaxial-2d.yaml", 15000, "grain",
     "walls:\n  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 1, 0], material: grain}\n",
     {0.1, 0.0002, 0.0}},
};

typedef struct saved_particle {
    sd_particle_state s;
    char shape[64], material[64];
} saved_particle;

static int by_id(const void *a, const void *b)
{
    const saved_particle *x = a, *y = b;
    return x->s.id < y->s.id ? -1 : x->s.id > y->s.id;
}

/* The world's particles with their template and material names, by id. */
static saved_particle *particles_by_id(const sd_world *w, size_t *n)
{
    *n = sd_world_particle_count(w);
    saved_particle *p = calloc(*n ? *n : 1, sizeof *p);
    sd_test_require(p != NULL, "memory", NULL);
    for (size_t k = 0; k < *n; ++k) {
        sd_world_get_particle(w, k, &p[k].s);
        sd_shape_info si;
        if (p[k].s.shape >= 0 && sd_world_get_shape(w, (size_t)p[k].s.shape, &si) == SD_OK)
            snprintf(p[k].shape, sizeof p[k].shape, "%s", si.name);
        const char *m = sd_world_material_name(w, (size_t)p[k].s.material);
        snprintf(p[k].material, sizeof p[k].material, "%s", m ? m : "?");
    }
    qsort(p, *n, sizeof *p, by_id);
    return p;
}

static char *read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    sd_test_require(f != NULL, path, NULL);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *t = malloc((size_t)n + 1);
    sd_test_require(t && fread(t, 1, (size_t)n, f) == (size_t)n, path, NULL);
    t[n] = '\0';
    fclose(f);
    return t;
}

static void run_case(const char *src, const char *dir, const from_case *c)
{
    char path[4096], ckpt[4096], scene[4096];
    snprintf(path, sizeof path, "%s/%s", src, c->scene);
    snprintf(ckpt, sizeof ckpt, "%s/bed.h5", dir);
    snprintf(scene, sizeof scene, "%s/from.yaml", dir);
    sd_error err;
    sd_scene *sa, *sb;
    sd_world *a, *b;
    sd_test_require(sd_scene_load(path, &sa, &err) == SD_OK, c->scene, &err);
    sd_test_require(sd_scene_build(sa, &a, &err) == SD_OK, c->scene, &err);
    sd_test_require(sd_world_step(a, c->settle, &err) == SD_OK, c->scene, &err);
    sd_test_require(sd_checkpoint_write(a, ckpt, &err) == SD_OK, "checkpoint", &err);

    /* the new scene: the bed's simulation, materials and shapes, then a
     * generator that reads the checkpoint and other walls */
    char *text = read_text(path);
    char *cut = strstr(text, "\nparticles:");
    sd_test_require(cut != NULL, "the bed's scene has a particles: section", NULL);
    cut[1] = '\0';
    FILE *f = fopen(scene, "w");
    sd_test_require(f != NULL, scene, NULL);
    fprintf(f, "%sparticles:\n  - generator: csv\n    material: %s\n    file: bed.h5\n"
               "    shift: [%.17g, %.17g, %.17g]\n%s",
            text, c->material, c->shift[0], c->shift[1], c->shift[2], c->walls);
    fclose(f);
    free(text);
    sd_status st = sd_scene_load(scene, &sb, &err);
    if (st != SD_OK) {
        char buf[1024];
        sd_error_format(&err, buf, sizeof buf);
        printf("FAIL %s: %s\n", c->scene, buf);
    }
    CHECK(st == SD_OK);
    if (st != SD_OK)
        return;
    sd_test_require(sd_scene_build(sb, &b, &err) == SD_OK, "the new scene builds", &err);

    size_t na, nb;
    saved_particle *pa = particles_by_id(a, &na), *pb = particles_by_id(b, &nb);
    long bad_x = 0, bad_v = 0, bad_name = 0;
    double dq = 0;
    for (size_t k = 0; k < na && k < nb; ++k) {
        const sd_particle_state *x = &pa[k].s, *y = &pb[k].s;
        double want[3] = {x->position.x + c->shift[0], x->position.y + c->shift[1], x->position.z + c->shift[2]};
        double got[3] = {y->position.x, y->position.y, y->position.z};
        if (memcmp(want, got, sizeof want))
            ++bad_x;
        double va[6] = {x->velocity.x, x->velocity.y, x->velocity.z, x->angular_velocity.x, x->angular_velocity.y,
                        x->angular_velocity.z};
        double vb[6] = {y->velocity.x, y->velocity.y, y->velocity.z, y->angular_velocity.x, y->angular_velocity.y,
                        y->angular_velocity.z};
        if (memcmp(va, vb, sizeof va))
            ++bad_v;
        if (x->shape >= 0)
            for (int j = 0; j < 4; ++j)
                dq = fmax(dq, fabs(x->quat[j] - y->quat[j]));
        if (strcmp(pa[k].shape, pb[k].shape) || strcmp(pa[k].material, pb[k].material) ||
            (x->shape < 0) != (y->shape < 0) || (x->shape < 0 && x->radius != y->radius))
            ++bad_name;
    }
    printf("  %-44s %5zu particles after %ld steps, %5zu in the new scene: %ld positions, %ld velocities or "
           "spins, %ld templates differ; orientations within %.2g\n",
           c->scene, na, c->settle, nb, bad_x, bad_v, bad_name, dq);
    CHECK(na == nb);
    CHECK(bad_x == 0);
    CHECK(bad_v == 0);
    CHECK(bad_name == 0);
    CHECK(dq <= 1e-15);
    /* the new scene runs on from the bed */
    st = sd_world_step(b, 300, &err);
    if (st != SD_OK) {
        char buf[1024];
        sd_error_format(&err, buf, sizeof buf);
        printf("FAIL %s: the new run: %s\n", c->scene, buf);
    }
    CHECK(st == SD_OK);
    sd_stats s;
    sd_world_stats(b, &s);
    printf("  %-44s the new run: 300 steps, %ld contacts (%ld with walls), kinetic energy %.3g J\n", "", s.contacts,
           s.wall_contacts, s.kinetic_translational + s.kinetic_rotational);
    CHECK(isfinite(s.kinetic_translational) && s.contacts + s.wall_contacts > 0);
    free(pa);
    free(pb);
    remove(ckpt);
    remove(scene);
    sd_world_destroy(a);
    sd_world_destroy(b);
    sd_scene_free(sa);
    sd_scene_free(sb);
}

int main(int argc, char **argv)
{
    const char *src = getenv("SD_SOURCE_DIR");
    sd_test_require(src != NULL, "SD_SOURCE_DIR is set (ctest sets it)", NULL);
    char dir[] = "/tmp/sd-scene-from-XXXXXX";
    sd_test_require(mkdtemp(dir) != NULL, "a temporary directory", NULL);
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c)
        if (argc < 2 || strstr(cases[c].scene, argv[1]))
            run_case(src, dir, &cases[c]);
    rmdir(dir);
    return sd_test_summary();
}
