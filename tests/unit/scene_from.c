/* scene_from.c — a new scene starts from a checkpoint of another run
 * (issue 17; generator: csv with a .h5 file, io/scene_from.c).
 *
 * For each particle kind (spheres; convex boxes, cylinders, ellipsoids,
 * cones and an icosahedron; composites; the planar circles, ellipses,
 * polygons, polybeziers and Fourier outlines; the scaled copies of a box
 * and a composite, and of an ellipse and a polygon, that an insertion with
 * size laws makes) a small bed is
 * thrown onto the floor, steps a while and is checkpointed; a new scene
 * with the same templates and materials but other walls (a plane where
 * there was a box) and a shift takes its particles from the checkpoint.
 * Every particle must come across exactly: position + shift, velocity and
 * spin bitwise, orientation to 1e-15 (normalised again), the same
 * template and material names, the template's numbers (volume, bounding
 * and equivalent radius, principal moments and axes, centre of mass,
 * rounding, counts) and the particle's mass and radius bitwise, one for
 * one in stable-id order; and the new run must step on (finite, in
 * contact). The examples' templates, with beds of 25 to 150 particles.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "test.h"

#include <shapedem/scene.h>

typedef struct from_case {
    const char *scene;  /* its simulation, materials and shapes are both scenes' */
    const char *bed;    /* the bed's particles (or insert) and walls; NULL: the scene's own */
    const char *material;
    const char *walls;  /* the new scene's walls: section */
    double shift[3];    /* m */
    int scaled;         /* 1: every body is of an insertion's scaled copy */
} from_case;

/* Small beds thrown onto the floor, so that contacts start within the
 * settle steps: the new run must step on from a bed in contact. */
static const long settle = 800, run_on = 300;

static const from_case cases[] = {
    {"examples/settle-spheres.yaml",
     "particles:\n  - {generator: random, material: glass, radius: {min: 0.0010, max: 0.0015}, number: 150,\n"
     "     box: {min: [0, 0, 0], max: [0.0432, 0.0432, 0.008]}, velocity: [0, 0, -0.8], velocity_jitter: 0.05}\n"
     "walls:\n  - {name: container, type: box, min: [0, 0, 0], max: [0.0432, 0.0432, 0.1], open: [zmax], "
     "material: steel}\n",
     "glass", "walls:\n  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: glass}\n",
     {0.02, -0.01, 0.0002}, 0},
    {"examples/mixed-shapes.yaml", /* spheres, box, cylinder, ellipsoid, cone, icosahedron: a column each */
     "particles:\n"
     "  - {generator: random, material: glass, radius: 0.001, number: 8, box: {min: [0, 0, 0], max: [0.0065, "
     "0.039, 0.006]}, velocity: [0, 0, -0.8]}\n"
     "  - {generator: random, material: glass, shape: brick, number: 8, box: {min: [0.0065, 0, 0], max: [0.013, "
     "0.039, 0.006]}, velocity: [0, 0, -0.8]}\n"
     "  - {generator: random, material: glass, shape: rod, number: 8, box: {min: [0.013, 0, 0], max: [0.0195, "
     "0.039, 0.006]}, velocity: [0, 0, -0.8]}\n"
     "  - {generator: random, material: glass, shape: pebble, number: 8, box: {min: [0.0195, 0, 0], max: [0.026, "
     "0.039, 0.006]}, velocity: [0, 0, -0.8]}\n"
     "  - {generator: random, material: glass, shape: peak, number: 8, box: {min: [0.026, 0, 0], max: [0.0325, "
     "0.039, 0.006]}, velocity: [0, 0, -0.8]}\n"
     "  - {generator: random, material: glass, shape: d20, number: 8, box: {min: [0.0325, 0, 0], max: [0.039, "
     "0.039, 0.006]}, velocity: [0, 0, -0.8]}\n"
     "walls:\n  - {name: container, type: box, min: [0, 0, 0], max: [0.039, 0.039, 0.1], open: [zmax], "
     "material: steel}\n",
     "glass",
     "walls:\n  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: steel}\n"
     "  - {name: side, type: plane, point: [0.0, 0, 0], normal: [1, 0, 0], material: steel}\n",
     {0.005, 0.0, 0.0002}, 0},
    {"tests/unit/scenes/restart-composites.yaml", /* clumps of spheres, crosses of cylinders, spheres */
     "particles:\n"
     "  - {generator: random, material: glass, shape: clump, number: 8, box: {min: [-0.015, -0.015, 0], max: "
     "[-0.005, 0.015, 0.008]}, velocity: [0, 0, -0.8]}\n"
     "  - {generator: random, material: glass, shape: cross, number: 5, box: {min: [-0.005, -0.015, 0], max: "
     "[0.005, 0.015, 0.014]}, velocity: [0, 0, -0.8]}\n"
     "  - {generator: random, material: glass, radius: 0.0015, number: 10, box: {min: [0.005, -0.015, 0], max: "
     "[0.015, 0.015, 0.008]}, velocity: [0, 0, -0.8]}\n"
     "walls:\n  - {name: box, type: box, min: [-0.015, -0.015, 0], max: [0.015, 0.015, 0.05], open: [zmax], "
     "material: glass}\n",
     "glass",
     "walls:\n  - {name: tray, type: box, min: [-0.03, -0.03, -0.001], max: [0.03, 0.03, 0.05], open: [zmax], "
     "material: glass}\n",
     {0.0, 0.0, 0.0}, 0},
    {"examples/biaxial-2d.yaml", /* circles, ellipses, polygons, polybeziers, Fourier outlines */
     "particles:\n"
     "  - {generator: random, material: grain, shape: circle_45, number: 5, box: {min: [0, 0, -0.05], max: [0.2, "
     "0.3, 0.05]}, velocity: [0, -1, 0]}\n"
     "  - {generator: random, material: grain, shape: ellipse_55, number: 5, box: {min: [0.2, 0, -0.05], max: [0.4, "
     "0.3, 0.05]}, velocity: [0, -1, 0]}\n"
     "  - {generator: random, material: grain, shape: polygon_40, number: 5, box: {min: [0.4, 0, -0.05], max: [0.6, "
     "0.3, 0.05]}, velocity: [0, -1, 0]}\n"
     "  - {generator: random, material: grain, shape: polybezier_55, number: 5, box: {min: [0.6, 0, -0.05], max: "
     "[0.8, 0.3, 0.05]}, velocity: [0, -1, 0]}\n"
     "  - {generator: random, material: grain, shape: fourier_50, number: 5, box: {min: [0.8, 0, -0.05], max: "
     "[1.0, 0.3, 0.05]}, velocity: [0, -1, 0]}\n"
     "walls:\n  - {name: left, type: plane, material: grain, point: [0, 0, 0], normal: [1, 0, 0]}\n"
     "  - {name: right, type: plane, material: grain, point: [1, 0, 0], normal: [-1, 0, 0]}\n"
     "  - {name: bottom, type: plane, material: grain, point: [0, 0, 0], normal: [0, 1, 0]}\n",
     "grain", "walls:\n  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 1, 0], material: grain}\n",
     {0.1, 0.0002, 0.0}, 0},
    {"tests/unit/scenes/from-scaled.yaml", NULL, /* an insertion's scaled boxes and clumps */
     "glass",
     "walls:\n  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: glass}\n",
     {0.003, 0.001, 0.0001}, 1},
    {"tests/unit/scenes/from-scaled-2d.yaml", NULL, /* an insertion's scaled ellipses and hexagons */
     "grain", "walls:\n  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 1, 0], material: grain}\n",
     {0.001, 0.0001, 0.0}, 1},
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

/* The numbers of a template, as sd_shape_info gives them, in one array
 * (the bits compared). */
static size_t shape_numbers(const sd_world *w, int shape, double *out)
{
    sd_shape_info si;
    memset(&si, 0, sizeof si);
    if (shape < 0 || sd_world_get_shape(w, (size_t)shape, &si) != SD_OK)
        return 0;
    double v[] = {si.volume,         si.bounding_radius,     si.equivalent_radius, si.inertia.x,
                  si.inertia.y,      si.inertia.z,           si.center_of_mass.x,  si.center_of_mass.y,
                  si.center_of_mass.z, si.rounding,          (double)si.vertex_count, (double)si.face_count,
                  si.axes[0].x,      si.axes[0].y,           si.axes[0].z,         si.axes[1].x,
                  si.axes[1].y,      si.axes[1].z,           si.axes[2].x,         si.axes[2].y,
                  si.axes[2].z,      (double)si.element_count, (double)si.lattice, si.lattice_error};
    memcpy(out, v, sizeof v);
    return sizeof v / sizeof v[0];
}

/* The bed's scene (the file, or its head and the case's bed) and the new
 * scene's (the head, a generator that reads the checkpoint, other walls). */
static void write_scenes(const char *src, const char *dir, const from_case *c, char *bed, char *scene, size_t n)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", src, c->scene);
    snprintf(bed, n, "%s/bed.yaml", dir);
    snprintf(scene, n, "%s/from.yaml", dir);
    char *text = read_text(path);
    /* the head: simulation, materials and shapes, before particles or insert */
    char *cut = strstr(text, "\nparticles:"), *ins = strstr(text, "\ninsert:");
    if (!cut || (ins && ins < cut))
        cut = ins;
    sd_test_require(cut != NULL, "the bed's scene has a particles: or insert: section", NULL);
    FILE *f = fopen(bed, "w");
    sd_test_require(f != NULL, bed, NULL);
    if (c->bed) {
        cut[1] = '\0';
        fprintf(f, "%s%s", text, c->bed);
    } else {
        fputs(text, f);
        cut[1] = '\0';
    }
    fclose(f);
    f = fopen(scene, "w");
    sd_test_require(f != NULL, scene, NULL);
    fprintf(f, "%sparticles:\n  - generator: csv\n    material: %s\n    file: bed.h5\n"
               "    shift: [%.17g, %.17g, %.17g]\n%s",
            text, c->material, c->shift[0], c->shift[1], c->shift[2], c->walls);
    fclose(f);
    free(text);
}

static void run_case(const char *src, const char *dir, const from_case *c)
{
    char ckpt[4096], bed[4096], scene[4096];
    snprintf(ckpt, sizeof ckpt, "%s/bed.h5", dir);
    write_scenes(src, dir, c, bed, scene, sizeof bed);
    sd_error err;
    sd_scene *sa, *sb;
    sd_world *a, *b;
    sd_test_require(sd_scene_load(bed, &sa, &err) == SD_OK, c->scene, &err);
    sd_test_require(sd_scene_build(sa, &a, &err) == SD_OK, c->scene, &err);
    sd_test_require(sd_world_step(a, settle, &err) == SD_OK, c->scene, &err);
    sd_test_require(sd_checkpoint_write(a, ckpt, &err) == SD_OK, "checkpoint", &err);
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
    long bad_x = 0, bad_v = 0, bad_name = 0, bad_geom = 0, copies = 0, bodies = 0;
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
            (x->shape < 0) != (y->shape < 0))
            ++bad_name;
        /* the template's geometry, mass and inertia, and the particle's mass
         * and (bounding) radius: the same bits */
        double ga[32], gb[32];
        size_t la = shape_numbers(a, x->shape, ga), lb = shape_numbers(b, y->shape, gb);
        if (la != lb || memcmp(ga, gb, la * sizeof *ga) || memcmp(&x->mass, &y->mass, sizeof x->mass) ||
            memcmp(&x->radius, &y->radius, sizeof x->radius))
            ++bad_geom;
        bodies += x->shape >= 0;
        copies += strstr(pa[k].shape, "_i0e") != NULL;
    }
    printf("  %-42s %4zu particles after %ld steps, %4zu in the new scene (%ld of scaled copies): %ld positions, "
           "%ld velocities or spins, %ld names, %ld templates or masses differ; orientations within %.2g\n",
           c->scene, na, settle, nb, copies, bad_x, bad_v, bad_name, bad_geom, dq);
    CHECK(na == nb && na > 0);
    CHECK(bad_x == 0);
    CHECK(bad_v == 0);
    CHECK(bad_name == 0);
    CHECK(bad_geom == 0);
    CHECK(dq <= 1e-15);
    CHECK(c->scaled ? copies == bodies && bodies > 0 : copies == 0);
    /* the new scene runs on from the bed */
    st = sd_world_step(b, run_on, &err);
    if (st != SD_OK) {
        char buf[1024];
        sd_error_format(&err, buf, sizeof buf);
        printf("FAIL %s: the new run: %s\n", c->scene, buf);
    }
    CHECK(st == SD_OK);
    sd_stats s;
    sd_world_stats(b, &s);
    printf("  %-42s the new run: %ld steps, %ld contacts (%ld with walls), kinetic energy %.3g J\n", "", run_on,
           s.contacts, s.wall_contacts, s.kinetic_translational + s.kinetic_rotational);
    CHECK(isfinite(s.kinetic_translational) && s.contacts + s.wall_contacts > 0);
    free(pa);
    free(pb);
    remove(ckpt);
    remove(bed);
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
