/* scene.c — the scene module: parsing with values and defaults, the
 * four generators, shape templates and bodies of shapes (every type, OBJ
 * and STL vertices, uniform random orientations), building a world, the
 * key table and its docs, and a
 * table of bad scenes that must each fail with SD_ERR_INPUT at the right
 * line and key.
 *
 * Scenes are written to a fresh directory under /tmp (mkdtemp), with a CSV
 * file beside them when a case needs one.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "core/alloc.h"
#include "io/scene.h"
#include "io/scene_keys.h"
#include "test.h"

static char dir[64];
static char scene_path[128];
static char csv_path[128];

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    sd_test_require(f != NULL, path, NULL);
    fputs(text, f);
    fclose(f);
}

/* Writes the scene (and csv, if any) and loads it. */
static sd_status load(const char *yaml, const char *csv, sd_scene **s, sd_error *err)
{
    write_file(scene_path, yaml);
    remove(csv_path);
    if (csv)
        write_file(csv_path, csv);
    return sd_scene_load(scene_path, s, err);
}

static void print_err(const char *what, const sd_error *err)
{
    char buf[1200];
    sd_error_format(err, buf, sizeof buf);
    printf("  %s: %s\n", what, buf);
}

static int near(double a, double b) { return fabs(a - b) <= 1e-12 * (fabs(a) + fabs(b) + 1e-300); }

/* ---- a good scene: values and defaults --------------------------------- */

static const char *good_scene =
    "simulation:\n"
    "  dt: 1.0e-6\n"
    "  duration: 0.00100005\n"
    "  seed: 42\n"
    "materials:\n"
    "  - name: glass\n"
    "    density: 2500\n"
    "    youngs_modulus: 1e7\n"
    "    restitution: 0.9\n"
    "  - name: steel\n"
    "    density: 7800\n"
    "    youngs_modulus: 2.0e8\n"
    "    poisson_ratio: 0.25\n"
    "    friction: 0.3\n"
    "    rolling_friction: 0.01\n"
    "    stiffness: 1000\n"
    "interactions:\n"
    "  - between: [glass, steel]\n"
    "    friction: 0.2\n"
    "    contact_law: hertz_mindlin\n"
    "particles:\n"
    "  - generator: lattice\n"
    "    material: glass\n"
    "    radius: 0.001\n"
    "    origin: [0.002, 0.003, 0.004]\n"
    "    spacing: [0.0025, 0.003, 0.0035]\n"
    "    count: [3, 4, 5]\n"
    "    velocity: [0.1, 0, 0]\n"
    "  - generator: list\n"
    "    material: steel\n"
    "    spheres:\n"
    "      - {position: [0.05, 0.05, 0.05], radius: 0.002}\n"
    "      - position: [0.06, 0.05, 0.05]\n"
    "        radius: 0.0015\n"
    "        velocity: [0, 0, -1]\n"
    "        angular_velocity: [0, 10, 0]\n"
    "        material: glass\n"
    "  - generator: csv\n"
    "    material: glass\n"
    "    file: spheres.csv\n"
    "    velocity: [0, 0.5, 0]\n"
    "  - generator: random\n"
    "    material: glass\n"
    "    radius: {min: 0.0005, max: 0.0008}\n"
    "    box: {min: [0.1, 0.1, 0.1], max: [0.12, 0.12, 0.12]}\n"
    "    number: 200\n"
    "    velocity_jitter: 0.01\n"
    "walls:\n"
    "  - type: plane\n"
    "    point: [0, 0, 0]\n"
    "    normal: [0, 0, 2]\n"
    "    material: steel\n"
    "  - name: bin\n"
    "    type: box\n"
    "    min: [-1, -1, -1]\n"
    "    max: [1, 1, 1]\n"
    "    open: [zmax, xmin]\n"
    "    material: steel\n"
    "output:\n"
    "  every: 7\n";

static const char *good_csv =
    "x, y, z, radius, vx\n"
    "0.08, 0.08, 0.08, 0.001, 1.5\n"
    "# a comment line\n"
    "\n"
    "0.083,0.08,0.08,0.001,0\n";

static void test_good_scene(void)
{
    printf("good scene: values and defaults\n");
    sd_scene *s;
    sd_error err;
    sd_status st = load(good_scene, good_csv, &s, &err);
    if (st != SD_OK)
        print_err("load", &err);
    sd_test_require(st == SD_OK, "load the good scene", &err);

    CHECK(s->world.dimension == 3);
    CHECK(near(s->world.dt, 1e-6));
    CHECK(s->steps == 1001); /* ceil(1000.05 - 1e-9) */
    CHECK(s->dt_line == 2);
    CHECK(s->simulation_line == 1);
    CHECK(s->world.gravity.x == 0.0 && s->world.gravity.y == 0.0 && near(s->world.gravity.z, -9.81));
    CHECK(s->world.seed == 42);
    CHECK(s->world.threads == 0);
    CHECK(s->world.law == SD_LAW_HERTZ_MINDLIN);
    CHECK(s->world.skin == 0.0);

    CHECK(s->material_count == 2);
    const sd_material_def *g = &s->materials[0].def, *m = &s->materials[1].def;
    CHECK(!strcmp(s->materials[0].name, "glass") && !strcmp(g->name, "glass"));
    CHECK(s->materials[0].line == 6 && s->materials[1].line == 10);
    CHECK(g->density == 2500.0 && g->youngs_modulus == 1e7 && g->restitution == 0.9);
    CHECK(near(g->poisson_ratio, 0.3) && near(g->friction, 0.5) && g->rolling_friction == 0.0);
    CHECK(g->stiffness == 0.0 && near(g->tangential_stiffness_ratio, 2.0 / 7.0));
    CHECK(m->density == 7800.0 && m->poisson_ratio == 0.25 && m->friction == 0.3);
    CHECK(m->rolling_friction == 0.01 && m->stiffness == 1000.0 && near(m->restitution, 0.5));

    CHECK(s->interaction_count == 1);
    const sd_scene_interaction *in = &s->interactions[0];
    CHECK(in->mat_a == 0 && in->mat_b == 1 && in->line == 18);
    CHECK(in->def.friction == 0.2 && in->def.restitution < 0.0 && in->def.stiffness < 0.0);
    CHECK(in->def.rolling_friction < 0.0 && in->def.law == SD_LAW_HERTZ_MINDLIN);

    CHECK(s->generator_count == 4);
    const sd_scene_generator *lat = &s->generators[0];
    CHECK(lat->kind == SD_GEN_LATTICE && lat->line == 22 && lat->material == 0);
    CHECK(lat->radius_min == 0.001 && lat->radius_max == 0.001);
    CHECK(lat->count[0] == 3 && lat->count[1] == 4 && lat->count[2] == 5);
    CHECK(lat->spacing.y == 0.003 && lat->origin.z == 0.004 && lat->velocity.x == 0.1);
    CHECK(lat->velocity_jitter == 0.0);
    const sd_scene_generator *lst = &s->generators[1];
    CHECK(lst->kind == SD_GEN_LIST && lst->list_count == 2);
    CHECK(lst->list[0].material == 1 && lst->list[1].material == 0);
    CHECK(lst->list_lines[0] == 32 && lst->list_lines[1] == 33);
    CHECK(lst->list[1].velocity.z == -1.0 && lst->list[1].angular_velocity.y == 10.0);
    CHECK(lst->list[0].radius == 0.002 && lst->list[1].radius == 0.0015);
    const sd_scene_generator *csv = &s->generators[2];
    CHECK(csv->kind == SD_GEN_CSV && csv->list_count == 2);
    CHECK(!strcmp(csv->file, csv_path));
    CHECK(csv->list_lines[0] == 2 && csv->list_lines[1] == 5);
    CHECK(csv->list[0].velocity.x == 1.5 && csv->list[0].velocity.y == 0.5);
    CHECK(csv->list[1].position.x == 0.083 && csv->list[1].radius == 0.001);
    const sd_scene_generator *rnd = &s->generators[3];
    CHECK(rnd->kind == SD_GEN_RANDOM && rnd->number == 200);
    CHECK(rnd->radius_min == 0.0005 && rnd->radius_max == 0.0008 && rnd->velocity_jitter == 0.01);
    CHECK(rnd->box_lo.x == 0.1 && rnd->box_hi.z == 0.12);

    CHECK(s->wall_count == 2);
    CHECK(!strcmp(s->walls[0].name, "wall0") && s->walls[0].kind == 0);
    CHECK(s->walls[0].normal.z == 1.0 && s->walls[0].normal.x == 0.0 && s->walls[0].material == 1);
    CHECK(!strcmp(s->walls[1].name, "bin") && s->walls[1].kind == 1);
    CHECK(s->walls[1].open_faces == (SD_BOX_ZMAX | SD_BOX_XMIN));
    CHECK(s->walls[1].lo.x == -1.0 && s->walls[1].hi.y == 1.0);

    CHECK(s->output.directory[0] == '\0');
    CHECK(s->output.every == 7 && s->output.stats_every == 1);
    CHECK(s->output.formats == (SD_OUT_VTK | SD_OUT_CSV));

    /* Generated spheres, in id order. */
    sd_scene_spheres sp;
    st = sd_scene_generate(s, NULL, &sp, &err);
    sd_test_require(st == SD_OK, "generate", &err);
    CHECK(sp.count == 60 + 2 + 2 + 200);
    int lattice_ok = 1;
    for (int k = 0; k < 60; ++k) {
        int ix = k % 3, iy = (k / 3) % 4, iz = k / 12;
        const sd_sphere_def *d = &sp.defs[k];
        lattice_ok &= near(d->position.x, 0.002 + ix * 0.0025) && near(d->position.y, 0.003 + iy * 0.003) &&
                      near(d->position.z, 0.004 + iz * 0.0035) && d->radius == 0.001 &&
                      d->velocity.x == 0.1 && d->material == 0 && sp.gen[k] == 0 && sp.line[k] == 22;
    }
    CHECK(lattice_ok);
    CHECK(sp.defs[60].position.x == 0.05 && sp.gen[60] == 1 && sp.entry[61] == 1 && sp.line[61] == 33);
    CHECK(sp.defs[62].position.x == 0.08 && sp.line[63] == 5 && sp.gen[63] == 2);
    int random_ok = 1;
    for (size_t k = 64; k < sp.count; ++k) {
        const sd_sphere_def *d = &sp.defs[k];
        random_ok &= d->radius >= 0.0005 && d->radius <= 0.0008;
        random_ok &= d->position.x - d->radius >= 0.1 && d->position.x + d->radius <= 0.12;
        random_ok &= d->position.y - d->radius >= 0.1 && d->position.y + d->radius <= 0.12;
        random_ok &= d->position.z - d->radius >= 0.1 && d->position.z + d->radius <= 0.12;
        random_ok &= fabs(d->velocity.x) <= 0.01 && fabs(d->velocity.z) <= 0.01;
        for (size_t q = 64; q < k; ++q) {
            double dx = d->position.x - sp.defs[q].position.x, dy = d->position.y - sp.defs[q].position.y,
                   dz = d->position.z - sp.defs[q].position.z;
            random_ok &= sqrt(dx * dx + dy * dy + dz * dz) >= d->radius + sp.defs[q].radius;
        }
    }
    CHECK(random_ok);

    /* The world gets the same spheres with ids in generation order. */
    sd_world *w;
    st = sd_scene_build(s, &w, &err);
    if (st != SD_OK)
        print_err("build", &err);
    CHECK(st == SD_OK);
    if (st == SD_OK) {
        CHECK(sd_world_particle_count(w) == sp.count);
        CHECK(sd_world_wall_count(w) == 2);
        CHECK(sd_world_find_material(w, "steel") == 1);
        int ids_ok = 1;
        for (size_t k = 0; k < sp.count; ++k) {
            sd_particle_state ps;
            size_t idx = sd_world_find_particle(w, (uint64_t)k);
            ids_ok &= idx != (size_t)-1 && sd_world_get_particle(w, idx, &ps) == SD_OK;
            ids_ok &= ps.position.x == sp.defs[k].position.x && ps.radius == sp.defs[k].radius &&
                      ps.material == sp.defs[k].material;
        }
        CHECK(ids_ok);
        sd_world_destroy(w);
    }
    sd_scene_spheres_free(&sp);
    sd_scene_free(s);
}

/* ---- the random generator: deterministic, seeded, fast ------------------ */

static const char *random_scene =
    "simulation: {dt: 1e-6, steps: 1, seed: %d}\n"
    "materials: [{name: a, density: 1000, youngs_modulus: 1e7}]\n"
    "particles:\n"
    "  - {generator: random, material: a, radius: {min: %g, max: %g}, number: %d,\n"
    "     box: {min: [0, 0, 0], max: [1, 1, 1]}}\n";

static void gen_random(int seed, double rmin, double rmax, int n, sd_scene_spheres *sp)
{
    char text[1024];
    sd_scene *s;
    sd_error err;
    snprintf(text, sizeof text, random_scene, seed, rmin, rmax, n);
    sd_test_require(load(text, NULL, &s, &err) == SD_OK, "load random scene", &err);
    sd_test_require(sd_scene_generate(s, NULL, sp, &err) == SD_OK, "generate random", &err);
    sd_scene_free(s);
}

static void test_random(void)
{
    printf("random generator\n");
    sd_scene_spheres a, b, c;
    gen_random(5, 0.01, 0.02, 3000, &a);
    gen_random(5, 0.01, 0.02, 3000, &b);
    gen_random(6, 0.01, 0.02, 3000, &c);
    CHECK(a.count == 3000 && b.count == 3000 && c.count == 3000);
    CHECK(memcmp(a.defs, b.defs, a.count * sizeof *a.defs) == 0);
    CHECK(memcmp(a.defs, c.defs, a.count * sizeof *a.defs) != 0);
    size_t i, j;
    CHECK(sd_scene_find_overlap(a.count, a.defs, 0.0, &i, &j) == 0);
    /* The grid search agrees with brute force on a pair made to overlap. */
    a.defs[2500].position = a.defs[1200].position;
    a.defs[2500].position.x += 0.5 * a.defs[1200].radius;
    CHECK(sd_scene_find_overlap(a.count, a.defs, 1e-6, &i, &j) == 1);
    size_t bi = 0, bj = 0;
    int found = 0;
    for (size_t q = 0; q < a.count && !found; ++q)
        for (size_t p = 0; p < q && !found; ++p) {
            double dx = a.defs[p].position.x - a.defs[q].position.x,
                   dy = a.defs[p].position.y - a.defs[q].position.y,
                   dz = a.defs[p].position.z - a.defs[q].position.z;
            if (a.defs[p].radius + a.defs[q].radius - sqrt(dx * dx + dy * dy + dz * dz) >
                1e-6 * fmin(a.defs[p].radius, a.defs[q].radius)) {
                bi = p;
                bj = q;
                found = 1;
            }
        }
    CHECK(found && i == bi && j == bj);
    sd_scene_spheres_free(&a);
    sd_scene_spheres_free(&b);
    sd_scene_spheres_free(&c);

    /* 1e5 spheres: the cell grid keeps this well under a second (printed,
     * not asserted: tests never check a time). */
    clock_t t0 = clock();
    gen_random(1, 0.003, 0.004, 100000, &a);
    double secs = (double)(clock() - t0) / CLOCKS_PER_SEC;
    printf("  100000 random spheres placed in %.3f s\n", secs);
    CHECK(a.count == 100000);
    CHECK(sd_scene_find_overlap(a.count, a.defs, 0.0, &i, &j) == 0);
    sd_scene_spheres_free(&a);
}

/* ---- shapes: every type, generators of bodies, orientations ------------ */

static const char *shape_scene =
    "simulation:\n"                                   /* 1 */
    "  dt: 1.0e-6\n"
    "  steps: 10\n"
    "  seed: 3\n"
    "materials:\n"                                    /* 5 */
    "  - name: glass\n"
    "    density: 2500\n"
    "    youngs_modulus: 1.0e7\n"
    "shapes:\n"                                       /* 9 */
    "  - name: ball\n"                                /* 10 */
    "    type: sphere\n"
    "    radius: 0.001\n"
    "  - name: brick\n"                               /* 13 */
    "    type: box\n"
    "    size: [0.002, 0.001, 0.0015]\n"
    "    rounding: 0.0001\n"
    "  - name: rod\n"                                 /* 17 */
    "    type: cylinder\n"
    "    diameter: 0.001\n"
    "    length: 0.003\n"
    "  - name: peak\n"                                /* 21 */
    "    type: cone\n"
    "    size: [0.002, 0.002, 0.002]\n"
    "    margin: 0.0001\n"
    "  - name: egg\n"                                 /* 25 */
    "    type: ellipsoid\n"
    "    semi_axes: [0.001, 0.0008, 0.0006]\n"
    "    scale: 2\n"
    "  - name: tetra\n"                               /* 29 */
    "    type: polyhedron\n"
    "    vertices: [[0, 0, 0], [0.002, 0, 0], [0, 0.002, 0], [0, 0, 0.002]]\n"
    "  - name: mesh\n"                                /* 32 */
    "    type: polyhedron\n"
    "    file: cube.obj\n"
    "    scale: 0.001\n"
    "particles:\n"                                    /* 36 */
    "  - generator: lattice\n"                        /* 37 */
    "    material: glass\n"
    "    shape: brick\n"
    "    origin: [0, 0, 0.01]\n"
    "    spacing: 0.005\n"
    "    count: [3, 3, 2]\n"
    "  - generator: random\n"                         /* 43 */
    "    material: glass\n"
    "    shape: egg\n"
    "    box: {min: [0.02, 0, 0.01], max: [0.05, 0.03, 0.04]}\n"
    "    number: 20\n"
    "    angular_velocity: [0, 0, 5]\n"
    "  - generator: list\n"                           /* 49 */
    "    material: glass\n"
    "    shape: rod\n"
    "    orientation: identity\n"
    "    spheres:\n"
    "      - {position: [0, 0.04, 0.01]}\n"          /* 54 */
    "      - {position: [0.006, 0.04, 0.01], shape: peak, orientation: [2, 0, 0, 0]}\n"
    "      - {position: [0.012, 0.04, 0.01], radius: 0.001}\n"
    "      - {position: [0.018, 0.04, 0.01], shape: tetra, orientation: random}\n"
    "      - {position: [0.024, 0.04, 0.01], shape: mesh}\n"
    "      - {position: [0.03, 0.04, 0.01], shape: ball, angular_velocity: [1, 0, 0]}\n"
    "  - generator: lattice\n"                        /* 60 */
    "    material: glass\n"
    "    radius: 0.001\n"
    "    origin: [0, 0.06, 0.01]\n"
    "    spacing: 0.0025\n"
    "    count: [2, 2, 2]\n"
    "walls:\n"
    "  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: glass}\n";

/* A cube of edge 2 (before scale), with the lines an exporter writes. */
static const char *cube_obj =
    "# cube\n"
    "o cube\n"
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
    "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
    "vn 0 0 1\nvt 0 0\n"
    "f 1 2 3 4\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

/* Bounding radii handed to sd_scene_generate without a world. */
static const double fake_bound[7] = {0.001, 0.0013, 0.0016, 0.0015, 0.002, 0.0017, 0.0018};

static void write_side_file(const char *name, const void *data, size_t n)
{
    char path[192];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    sd_test_require(f != NULL, path, NULL);
    fwrite(data, 1, n, f);
    fclose(f);
}

static void remove_side_file(const char *name)
{
    char path[192];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    remove(path);
}

static double quat_norm(const double q[4])
{
    return sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
}

static int is_identity(const double q[4])
{
    return q[0] == 1.0 && q[1] == 0.0 && q[2] == 0.0 && q[3] == 0.0;
}

static void test_shapes(void)
{
    printf("shapes: every type, bodies, orientations\n");
    write_side_file("cube.obj", cube_obj, strlen(cube_obj));
    sd_scene *s;
    sd_error err;
    sd_status st = load(shape_scene, NULL, &s, &err);
    if (st != SD_OK)
        print_err("load", &err);
    sd_test_require(st == SD_OK, "load the shape scene", &err);

    CHECK(s->shape_count == 7);
    const sd_scene_shape *sh = s->shapes;
    CHECK(!strcmp(sh[0].name, "ball") && sh[0].kind == 0 && sh[0].size.x == 0.001 && sh[0].line == 10);
    CHECK(sh[1].kind == 1 && sh[1].size.x == 0.002 && sh[1].size.y == 0.001 && sh[1].size.z == 0.0015);
    CHECK(sh[1].rounding == 0.0001 && sh[1].margin == 0.0 && sh[1].scale == 1.0);
    CHECK(sh[2].kind == 2 && sh[2].size.x == 0.001 && sh[2].size.y == 0.001 && sh[2].size.z == 0.003);
    CHECK(sh[3].kind == 3 && sh[3].size.z == 0.002 && sh[3].margin == 0.0001 && sh[3].rounding == 0.0);
    CHECK(sh[4].kind == 4 && sh[4].size.y == 0.0008 && sh[4].scale == 2.0);
    CHECK(sh[5].kind == 5 && sh[5].vertex_count == 4 && sh[5].vertices[1].x == 0.002);
    CHECK(sh[6].kind == 5 && sh[6].vertex_count == 8 && sh[6].scale == 0.001 && sh[6].file[0]);

    CHECK(s->generator_count == 4);
    const sd_scene_generator *lat = &s->generators[0], *rnd = &s->generators[1],
                             *lst = &s->generators[2], *sph = &s->generators[3];
    CHECK(lat->shape == 1 && lat->orient == SD_ORIENT_RANDOM && lat->spacing_line == 41);
    CHECK(rnd->shape == 4 && rnd->angular_velocity.z == 5.0 && rnd->box_line == 46);
    CHECK(lst->shape == 2 && lst->orient == SD_ORIENT_IDENTITY && lst->list_count == 6);
    CHECK(lst->list_shape[0] == 2 && lst->list_shape[1] == 3 && lst->list_shape[2] == -1);
    CHECK(lst->list_shape[3] == 5 && lst->list_shape[4] == 6 && lst->list_shape[5] == 0);
    CHECK(lst->list_orient[1] == SD_ORIENT_FIXED && lst->list_quat[1][0] == 1.0);
    CHECK(lst->list_orient[3] == SD_ORIENT_RANDOM && lst->list_orient[4] == SD_ORIENT_IDENTITY);
    CHECK(sph->shape == -1 && sph->radius_max == 0.001);

    /* Generation: bounding radii stand in for the radius, shapes and
     * orientations travel with each particle. */
    sd_scene_spheres a, b;
    st = sd_scene_generate(s, fake_bound, &a, &err);
    sd_test_require(st == SD_OK, "generate shapes", &err);
    CHECK(a.count == 18 + 20 + 6 + 8);
    int ok = 1;
    for (size_t k = 0; k < 18; ++k)
        ok &= a.shape[k] == 1 && a.defs[k].radius == fake_bound[1] &&
              fabs(quat_norm(a.quat[k]) - 1.0) < 1e-12 && !is_identity(a.quat[k]);
    for (size_t k = 18; k < 38; ++k)
        ok &= a.shape[k] == 4 && a.defs[k].radius == fake_bound[4] &&
              a.defs[k].angular_velocity.z == 5.0 && fabs(quat_norm(a.quat[k]) - 1.0) < 1e-12;
    CHECK(ok);
    static const int list_shapes[6] = {2, 3, -1, 5, 6, 0};
    ok = 1;
    for (size_t k = 0; k < 6; ++k) {
        size_t q = 38 + k;
        ok &= a.shape[q] == list_shapes[k] && a.entry[q] == (int)k && a.line[q] == 54 + (int)k;
        ok &= a.defs[q].radius == (list_shapes[k] >= 0 ? fake_bound[list_shapes[k]] : 0.001);
    }
    CHECK(ok);
    CHECK(is_identity(a.quat[38]) && is_identity(a.quat[39]) && is_identity(a.quat[40]));
    CHECK(!is_identity(a.quat[41]) && fabs(quat_norm(a.quat[41]) - 1.0) < 1e-12);
    CHECK(is_identity(a.quat[42]) && a.defs[43].angular_velocity.x == 1.0);
    ok = 1;
    for (size_t k = 44; k < a.count; ++k)
        ok &= a.shape[k] == -1 && a.defs[k].radius == 0.001 && is_identity(a.quat[k]);
    CHECK(ok);
    size_t oi, oj;
    CHECK(sd_scene_find_overlap(a.count, a.defs, 0.0, &oi, &oj) == 0);
    /* The same seed gives the same bodies and orientations. */
    st = sd_scene_generate(s, fake_bound, &b, &err);
    CHECK(st == SD_OK && b.count == a.count);
    CHECK(memcmp(a.defs, b.defs, a.count * sizeof *a.defs) == 0);
    CHECK(memcmp(a.quat, b.quat, a.count * sizeof *a.quat) == 0);
    CHECK(memcmp(a.shape, b.shape, a.count * sizeof *a.shape) == 0);
    sd_scene_spheres_free(&b);
    /* Shapes need their bounds. */
    CHECK(sd_scene_generate(s, NULL, &b, &err) == SD_ERR_INTERNAL);

    /* The world: shapes by index, mass = density x volume, the bounding
     * radius, the generated orientation. */
    sd_world *w;
    st = sd_scene_build(s, &w, &err);
    if (st != SD_OK)
        print_err("build", &err);
    CHECK(st == SD_OK);
    if (st == SD_OK) {
        CHECK(sd_world_shape_count(w) == 7 && sd_world_find_shape(w, "egg") == 4);
        CHECK(sd_world_particle_count(w) == a.count);
        int match = 1;
        for (size_t k = 0; k < a.count; ++k) {
            sd_particle_state ps;
            size_t idx = sd_world_find_particle(w, (uint64_t)k);
            match &= idx != (size_t)-1 && sd_world_get_particle(w, idx, &ps) == SD_OK;
            match &= ps.shape == a.shape[k] && ps.position.x == a.defs[k].position.x;
            if (a.shape[k] >= 0) {
                sd_shape_info info;
                match &= sd_world_get_shape(w, (size_t)a.shape[k], &info) == SD_OK;
                match &= fabs(ps.mass - 2500.0 * info.volume) <= 1e-12 * ps.mass;
                match &= fabs(ps.radius - info.bounding_radius) <= 1e-12 * ps.radius;
                for (int c = 0; c < 4; ++c)
                    match &= fabs(ps.quat[c] - a.quat[k][c]) < 1e-12;
            } else {
                match &= fabs(ps.mass - 2500.0 * 4.0 / 3.0 * 3.14159265358979323846 * 1e-9) <= 1e-12 * ps.mass;
            }
            if (!match) {
                printf("  particle %zu: shape %d (expected %d), mass %g\n", k, ps.shape, a.shape[k],
                       ps.mass);
                break;
            }
        }
        CHECK(match);
        sd_world_destroy(w);
    }
    sd_scene_spheres_free(&a);
    sd_scene_free(s);

    /* Out of memory anywhere in loading and building shapes: a clean
     * SD_ERR_MEMORY, nothing half-made (the sanitizer build checks leaks). */
    int oom_ok = 1, oom_seen = 0;
    for (long n = 1; n <= 2000; ++n) {
        sd_scene *t = NULL;
        sd_world *tw = NULL;
        sd_alloc_fail_after(n);
        st = sd_scene_load(scene_path, &t, &err);
        if (st == SD_OK) {
            st = sd_scene_build(t, &tw, &err);
            oom_ok &= (st == SD_OK) == (tw != NULL);
        } else {
            oom_ok &= t == NULL;
        }
        sd_alloc_fail_after(0);
        oom_ok &= st == SD_OK || st == SD_ERR_MEMORY;
        oom_seen += st == SD_ERR_MEMORY;
        sd_world_destroy(tw);
        sd_scene_free(t);
        if (st == SD_OK)
            break;
    }
    CHECK(oom_ok && oom_seen > 5);
    remove_side_file("cube.obj");
}

/* A tetrahedron as binary and ASCII STL: 4 triangles, 12 vertices, 4 distinct. */
static void test_stl(void)
{
    printf("shapes: polyhedra from STL files\n");
    static const float tv[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    static const int tri[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    unsigned char bin[84 + 4 * 50];
    memset(bin, 0, sizeof bin);
    bin[80] = 4; /* little-endian triangle count */
    char ascii[2048];
    size_t used = (size_t)snprintf(ascii, sizeof ascii, "solid tetra\n");
    for (int t = 0; t < 4; ++t) {
        used += (size_t)snprintf(ascii + used, sizeof ascii - used, " facet normal 0 0 0\n  outer loop\n");
        for (int c = 0; c < 3; ++c) {
            const float *p = tv[tri[t][c]];
            for (int a = 0; a < 3; ++a) {
                uint32_t u;
                memcpy(&u, &p[a], 4);
                unsigned char *q = bin + 84 + 50 * t + 12 + 12 * c + 4 * a;
                q[0] = (unsigned char)u;
                q[1] = (unsigned char)(u >> 8);
                q[2] = (unsigned char)(u >> 16);
                q[3] = (unsigned char)(u >> 24);
            }
            used += (size_t)snprintf(ascii + used, sizeof ascii - used, "   vertex %g %g %g\n",
                                     (double)p[0], (double)p[1], (double)p[2]);
        }
        used += (size_t)snprintf(ascii + used, sizeof ascii - used, "  endloop\n endfacet\n");
    }
    snprintf(ascii + used, sizeof ascii - used, "endsolid tetra\n");
    write_side_file("tb.stl", bin, sizeof bin);
    write_side_file("ta.stl", ascii, strlen(ascii));
    const char *text =
        "simulation: {dt: 1e-6, steps: 1}\n"
        "materials: [{name: a, density: 1000, youngs_modulus: 1e7}]\n"
        "shapes:\n"
        "  - {name: b, type: polyhedron, file: tb.stl, scale: 0.001}\n"
        "  - {name: t, type: polyhedron, file: ta.stl, scale: 0.001}\n"
        "particles:\n"
        "  - {generator: list, material: a, spheres: [{position: [0, 0, 0], radius: 0.001}]}\n";
    sd_scene *s;
    sd_error err;
    sd_status st = load(text, NULL, &s, &err);
    if (st != SD_OK)
        print_err("load", &err);
    CHECK(st == SD_OK);
    if (st == SD_OK) {
        CHECK(s->shapes[0].vertex_count == 4 && s->shapes[1].vertex_count == 4);
        int same = 1;
        for (size_t k = 0; k < 4; ++k)
            same &= !memcmp(&s->shapes[0].vertices[k], &s->shapes[1].vertices[k], sizeof(sd_v3d));
        CHECK(same);
        sd_scene_free(s);
    }
    remove_side_file("tb.stl");
    remove_side_file("ta.stl");
}

/* Random orientations are uniform over rotations: the mean rotation matrix
 * of N of them is 0 within a few / sqrt(3 N) per entry, and the mean of each
 * squared entry is 1/3. A different seed gives different orientations. */
static void test_random_orientation(void)
{
    printf("shapes: uniform random orientations\n");
    const char *fmt = "simulation: {dt: 1e-6, steps: 1, seed: %d}\n"
                      "materials: [{name: a, density: 1000, youngs_modulus: 1e7}]\n"
                      "shapes: [{name: c, type: box, size: 0.001}]\n"
                      "particles:\n"
                      "  - {generator: lattice, material: a, shape: c, origin: [0, 0, 0],\n"
                      "     spacing: 0.002, count: [20, 20, 10]}\n";
    char text[512];
    sd_scene *s;
    sd_error err;
    sd_scene_spheres a, b;
    const double bound[1] = {0.00087};
    snprintf(text, sizeof text, fmt, 9);
    sd_test_require(load(text, NULL, &s, &err) == SD_OK, "load orientation scene", &err);
    sd_test_require(sd_scene_generate(s, bound, &a, &err) == SD_OK, "generate", &err);
    sd_scene_free(s);
    snprintf(text, sizeof text, fmt, 10);
    sd_test_require(load(text, NULL, &s, &err) == SD_OK, "load orientation scene", &err);
    sd_test_require(sd_scene_generate(s, bound, &b, &err) == SD_OK, "generate", &err);
    sd_scene_free(s);
    CHECK(a.count == 4000 && b.count == 4000);
    CHECK(memcmp(a.quat, b.quat, a.count * sizeof *a.quat) != 0);
    double mean[3][3] = {{0}}, sq[3][3] = {{0}};
    for (size_t k = 0; k < a.count; ++k) {
        const double *q = a.quat[k];
        double w = q[0], x = q[1], y = q[2], z = q[3];
        double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                          {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                          {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                mean[i][j] += r[i][j] / (double)a.count;
                sq[i][j] += r[i][j] * r[i][j] / (double)a.count;
            }
    }
    /* sd of a mean entry: sqrt(1 / (3 N)) = 0.009; 5 sd. */
    double worst = 0.0, worst_sq = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            worst = fmax(worst, fabs(mean[i][j]));
            worst_sq = fmax(worst_sq, fabs(sq[i][j] - 1.0 / 3.0));
        }
    CHECK_NEAR("largest |mean rotation matrix entry|", worst, 0.0, 0.046);
    CHECK_NEAR("largest |mean squared entry - 1/3|", worst_sq, 0.0, 0.03);
    sd_scene_spheres_free(&a);
    sd_scene_spheres_free(&b);
}

/* ---- the example scene in the docs, and the docs themselves ------------- */

static void test_example_and_docs(void)
{
    printf("documented example and docs/scene-format.md\n");
    sd_scene *s;
    sd_error err;
    sd_world *w;
    sd_status st = load(sd_scene_example, NULL, &s, &err);
    if (st != SD_OK)
        print_err("example", &err);
    CHECK(st == SD_OK);
    if (st == SD_OK) {
        st = sd_scene_build(s, &w, &err);
        if (st != SD_OK)
            print_err("example build", &err);
        CHECK(st == SD_OK);
        if (st == SD_OK)
            sd_world_destroy(w);
        sd_scene_free(s);
    }

    /* Every key of the table appears in both help forms. */
    char *text = NULL, *md = NULL;
    size_t tn = 0, mn = 0;
    FILE *f = open_memstream(&text, &tn);
    sd_scene_print_keys(f, 0);
    fclose(f);
    f = open_memstream(&md, &mn);
    sd_scene_print_keys(f, 1);
    fclose(f);
    int all = 1;
    for (size_t k = 0; k < sd_scene_key_count; ++k) {
        char tick[80];
        snprintf(tick, sizeof tick, "`%s`", sd_scene_keys[k].key);
        all &= strstr(text, sd_scene_keys[k].key) != NULL && strstr(md, tick) != NULL;
    }
    CHECK(all);
    CHECK(strstr(md, sd_scene_example) != NULL);

    /* docs/scene-format.md is exactly what the table prints: regenerate it
     * with `shapedem help scene --markdown > docs/scene-format.md`. */
    const char *src = getenv("SD_SOURCE_DIR");
    if (src) {
        char path[512];
        snprintf(path, sizeof path, "%s/docs/scene-format.md", src);
        FILE *d = fopen(path, "rb");
        CHECK(d != NULL);
        if (d) {
            char *doc = malloc(mn + 2);
            size_t got = fread(doc, 1, mn + 1, d);
            fclose(d);
            int same = got == mn && memcmp(doc, md, mn) == 0;
            if (!same)
                printf("  docs/scene-format.md is stale: run `shapedem help scene --markdown > "
                       "docs/scene-format.md`\n");
            CHECK(same);
            free(doc);
        }
    }
    free(text);
    free(md);
}

/* ---- bad scenes --------------------------------------------------------- */

typedef struct bad_case {
    const char *name;
    const char *yaml;
    const char *csv;  /* written as spheres.csv beside the scene, or NULL */
    int line;
    const char *key;
    const char *msg;  /* a part of the message */
    int csv_file;     /* 1: the error names the CSV file */
} bad_case;

/* A small good scene, line by line, that the cases below vary. */
#define SIM "simulation:\n  dt: 1.0e-6\n  steps: 10\n"                           /* 1-3 */
#define MAT "materials:\n  - name: glass\n    density: 2500\n    youngs_modulus: 1.0e7\n" /* 4-7 */
#define PARTS                                                                                      \
    "particles:\n  - generator: list\n    material: glass\n    spheres:\n"                          \
    "      - {position: [0, 0, 0.01], radius: 0.001}\n"                                             \
    "      - {position: [0.003, 0, 0.01], radius: 0.001}\n" /* 8-13 */
/* the planar mode: two lines after SIM, and circles at z = 0 */
#define P2 "  dimension: 2\n  gravity: [0, -9.81, 0]\n" /* 4-5, MAT 6-9 */
#define PARTS2                                                                                     \
    "particles:\n  - generator: list\n    material: glass\n    spheres:\n"                          \
    "      - {position: [0, 0, 0], radius: 0.001}\n"                                                 \
    "      - {position: [0.003, 0, 0], radius: 0.001}\n" /* 10-15 (after shapes: 2 lines later each) */

/* One box shape, lines 8-9, for the shape cases. */
#define CUBE "shapes:\n  - {name: cube, type: box, size: 0.001}\n"

static const bad_case bad_cases[] = {
    {"good scene as a control", SIM MAT PARTS, NULL, 0, "", "", 0},
    {"unknown top-level key", "simulaton:\n  dt: 1\n", NULL, 1, "simulaton", "did you mean 'simulation'", 0},
    {"unknown material key", SIM "materials:\n  - name: glass\n    densty: 2500\n" PARTS, NULL, 6,
     "materials[0].densty", "unknown key", 0},
    {"string for a number", SIM "materials:\n  - name: glass\n    density: abc\n" PARTS, NULL, 6,
     "materials[0].density", "expected a number > 0, got abc", 0},
    {"quoted number", SIM "materials:\n  - name: glass\n    density: \"2500\"\n" PARTS, NULL, 6,
     "materials[0].density", "expected a number", 0},
    {"zero density", SIM "materials:\n  - name: glass\n    density: 0\n" PARTS, NULL, 6,
     "materials[0].density", "expected a number > 0, got 0", 0},
    {"restitution 0", SIM MAT "    restitution: 0\n" PARTS, NULL, 8, "materials[0].restitution",
     "in (0, 1]", 0},
    {"restitution 1.5", SIM MAT "    restitution: 1.5\n" PARTS, NULL, 8, "materials[0].restitution",
     "got 1.5", 0},
    {"poisson ratio 0.5", SIM MAT "    poisson_ratio: 0.5\n" PARTS, NULL, 8,
     "materials[0].poisson_ratio", "in (-1, 0.5)", 0},
    {"negative radius", SIM MAT "particles:\n  - generator: list\n    material: glass\n    spheres:\n"
                                "      - {position: [0, 0, 0.01], radius: -0.001}\n",
     NULL, 12, "particles[0].spheres[0].radius", "expected a number > 0, got -0.001", 0},
    {"missing dt", "simulation:\n  steps: 10\n" MAT PARTS, NULL, 1, "simulation.dt", "missing", 0},
    {"steps and duration", SIM "  duration: 0.1\n" MAT PARTS, NULL, 4, "simulation.duration",
     "not both", 0},
    {"no run length", "simulation:\n  dt: 1e-6\n" MAT PARTS, NULL, 1, "simulation.steps",
     "steps or duration", 0},
    {"steps not an integer", "simulation:\n  dt: 1e-6\n  steps: 2.5\n" MAT PARTS, NULL, 3,
     "simulation.steps", "expected an integer >= 0, got 2.5", 0},
    {"duplicate key", "simulation:\n  dt: 1e-6\n  dt: 2e-6\n  steps: 1\n" MAT PARTS, NULL, 3,
     "simulation.dt", "duplicate key", 0},
    {"planar mode, default gravity", SIM "  dimension: 2\n" MAT PARTS, NULL, 1, "simulation.gravity",
     "dimension 2 needs gravity in the x-y plane", 0},
    {"dimension 4", SIM "  dimension: 4\n" MAT PARTS, NULL, 4, "simulation.dimension", "expected 2 or 3, got 4", 0},
    {"local damping 1", SIM "  local_damping: 1\n" MAT PARTS, NULL, 4, "simulation.local_damping",
     "expected a coefficient in [0, 1)", 0},
    {"circle in 3D", SIM MAT "shapes:\n  - name: a\n    type: circle\n    radius: 0.001\n" PARTS, NULL, 10,
     "shapes[0].type", "is planar (2D), but simulation.dimension is 3", 0},
    {"planar scene", SIM P2 MAT
     "shapes:\n  - name: e\n    type: ellipse\n    axes: [0.0012, 0.0008]\n"
     "  - name: f\n    type: fourier\n    fourier_a: [0.002, 0, 0.0001]\n    fourier_b: [0, 0.00005]\n"
     "  - name: b\n    type: polybezier\n    rounding: 0.0001\n"
     "    points: [[0.001, 0], [0.001, 0.0005], [0.0005, 0.001], [0, 0.001], [-0.0005, 0.001], [-0.001, 0.0005],\n"
     "             [-0.001, 0], [-0.001, -0.0005], [-0.0005, -0.001], [0, -0.001], [0.0005, -0.001], [0.001, -0.0005]]\n"
     "particles:\n  - generator: list\n    material: glass\n    spheres:\n"
     "      - {position: [0, 0.002, 0], radius: 0.001}\n      - {position: [0.003, 0.002, 0], shape: e}\n"
     "      - {position: [0.006, 0.002, 0], shape: f}\n      - {position: [0.009, 0.002, 0], shape: b}\n"
     "walls:\n  - {type: plane, material: glass, point: [0, 0, 0], normal: [0, 1, 0]}\n"
     "  - {name: top, type: plane, material: glass, point: [0, 0.01, 0], normal: [0, -1, 0], servo_stress: 1000}\n"
     "  - {type: plane, material: glass, point: [-0.002, 0, 0], normal: [1, 0, 0], velocity: [0.1, 0, 0], "
     "move_start: 0.001, move_end: 0.002}\n"
     "  - {type: plane, material: glass, point: [0.011, 0, 0], normal: [-1, 0, 0]}\n",
     NULL, 0, "", "", 0},
    {"box shape in 2D", SIM P2 MAT "shapes:\n  - name: a\n    type: box\n    size: 0.001\n" PARTS2, NULL, 12,
     "shapes[0].type", "is 3D, but simulation.dimension is 2", 0},
    {"non-convex Fourier shape", SIM P2 MAT "shapes:\n  - name: f\n    type: fourier\n    fourier_a: [0.002, 0, 0.001]\n"
     PARTS2, NULL, 11, "shapes[0]", "conve", 0},
    {"polybezier of 4 points", SIM P2 MAT "shapes:\n  - name: b\n    type: polybezier\n"
     "    points: [[0, 0], [1, 0], [1, 1], [0, 1]]\n" PARTS2, NULL, 13, "shapes[0].points", "3m control points", 0},
    {"fourier_b too long", SIM P2 MAT "shapes:\n  - name: f\n    type: fourier\n    fourier_a: [0.002, 0]\n"
     "    fourier_b: [0, 0]\n" PARTS2, NULL, 14, "shapes[0].fourier_b", "one fewer than fourier_a", 0},
    {"ellipse axes of 3", SIM P2 MAT "shapes:\n  - name: e\n    type: ellipse\n    axes: [1, 1, 1]\n" PARTS2, NULL, 13,
     "shapes[0].axes", "expected a list of 2 numbers", 0},
    {"plane normal out of the plane", SIM P2 MAT PARTS2 "walls:\n  - type: plane\n    material: glass\n"
     "    point: [0, 0, 0]\n    normal: [0, 1, 1]\n", NULL, 17, "walls[0].normal", "normal needs z = 0", 0},
    {"servo ends before it starts", SIM P2 MAT PARTS2 "walls:\n  - type: plane\n    material: glass\n"
     "    point: [0, -0.01, 0]\n    normal: [0, 1, 0]\n    servo_stress: 1000\n    servo_start: 2\n"
     "    servo_end: 1\n", NULL, 23, "walls[0].servo_end", "expected servo_end > servo_start", 0},
    {"servo on a box", SIM P2 MAT PARTS2 "walls:\n  - type: box\n    material: glass\n"
     "    min: [-1, -1, -1]\n    max: [1, 1, 1]\n    servo_stress: 1000\n", NULL, 21, "walls[0].servo_stress",
     "does not apply to a box wall", 0},
    {"wall velocity out of the plane", SIM P2 MAT PARTS2 "walls:\n  - type: plane\n    material: glass\n"
     "    point: [0, -0.01, 0]\n    normal: [0, 1, 0]\n    velocity: [0, 0, 1]\n", NULL, 21, "walls[0].velocity",
     "velocity with z = 0", 0},
    {"3D sphere position in 2D", SIM P2 MAT PARTS, NULL, 14, "particles[0].spheres[0]", "plane z = 0", 0},
    {"gravity of length 2", SIM "  gravity: [0, -9.81]\n" MAT PARTS, NULL, 4, "simulation.gravity",
     "expected a list of 3 numbers", 0},
    {"unknown contact law", SIM "  contact_law: hooke\n" MAT PARTS, NULL, 4,
     "simulation.contact_law", "expected one of hertz_mindlin, linear", 0},
    {"duplicate material", SIM MAT "  - name: glass\n    density: 1000\n" PARTS, NULL, 8,
     "materials[1].name", "duplicate material name", 0},
    {"unknown material", SIM MAT "particles:\n  - generator: list\n    material: glas\n    spheres:\n"
                                 "      - {position: [0, 0, 0.01], radius: 0.001}\n",
     NULL, 10, "particles[0].material", "unknown material 'glas'", 0},
    {"unknown material in interaction", SIM MAT "interactions:\n  - between: [glass, wood]\n" PARTS,
     NULL, 9, "interactions[0].between", "unknown material 'wood'", 0},
    {"hertz without youngs modulus", SIM "materials:\n  - name: glass\n    density: 2500\n" PARTS, NULL,
     5, "materials[0].youngs_modulus", "hertz_mindlin", 0},
    {"linear without stiffness", SIM "  contact_law: linear\n" MAT PARTS, NULL, 6,
     "materials[0].stiffness", "linear", 0},
    {"YAML syntax error", "simulation:\n  dt: [1e-6\n  steps: 10\n" MAT, NULL, 3, "", "invalid YAML", 0},
    {"empty file", "", NULL, 1, "", "empty", 0},
    {"generator key of another kind", SIM MAT
     "particles:\n  - generator: random\n    material: glass\n    radius: 0.001\n"
     "    origin: [0, 0, 0]\n    box: {min: [0, 0, 0], max: [1, 1, 1]}\n    number: 5\n",
     NULL, 12, "particles[0].origin", "does not apply to a random generator", 0},
    {"unknown generator", SIM MAT "particles:\n  - generator: cloud\n    material: glass\n", NULL, 9,
     "particles[0].generator", "expected one of lattice, random, list, csv", 0},
    {"lattice spacing too small", SIM MAT
     "particles:\n  - generator: lattice\n    material: glass\n    radius: {min: 0.001, max: 0.002}\n"
     "    origin: [0, 0, 0]\n    spacing: 0.003\n    count: [2, 2, 2]\n",
     NULL, 13, "particles[0].spacing", "2 x the largest radius", 0},
    {"lattice count zero", SIM MAT
     "particles:\n  - generator: lattice\n    material: glass\n    radius: 0.001\n"
     "    origin: [0, 0, 0]\n    spacing: 0.003\n    count: [2, 0, 2]\n",
     NULL, 14, "particles[0].count", "expected an integer >= 1 for y, got 0", 0},
    {"radius min above max", SIM MAT
     "particles:\n  - generator: random\n    material: glass\n    radius:\n      min: 0.002\n"
     "      max: 0.001\n    box: {min: [0, 0, 0], max: [1, 1, 1]}\n    number: 5\n",
     NULL, 13, "particles[0].radius.max", "expected max >= min", 0},
    {"list entry without radius", SIM MAT
     "particles:\n  - generator: list\n    material: glass\n    spheres:\n"
     "      - {position: [0, 0, 0.01]}\n",
     NULL, 12, "particles[0].spheres[0].radius", "missing required key 'radius'", 0},
    {"wall normal zero", SIM MAT PARTS "walls:\n  - type: plane\n    point: [0, 0, 0]\n"
                                       "    normal: [0, 0, 0]\n    material: glass\n",
     NULL, 17, "walls[0].normal", "non-zero", 0},
    {"box max below min", SIM MAT PARTS "walls:\n  - type: box\n    min: [0, 0, 0]\n"
                                        "    max: [1, -1, 1]\n    material: glass\n",
     NULL, 17, "walls[0].max", "max > min", 0},
    {"unknown box face", SIM MAT PARTS "walls:\n  - type: box\n    min: [0, 0, 0]\n"
                                       "    max: [1, 1, 1]\n    open: [top]\n    material: glass\n",
     NULL, 18, "walls[0].open", "expected one of xmin", 0},
    {"unknown output format", SIM MAT PARTS "output:\n  formats: [vtk, pdf]\n", NULL, 15,
     "output.formats", "got pdf", 0},
    {"csv bad row", SIM MAT "particles:\n  - generator: csv\n    material: glass\n    file: spheres.csv\n",
     "x,y,z,radius\n0,0,0,0.001\n0.01,0,zero,0.001\n", 3, "particles[0].file",
     "column z: expected a number, got 'zero'", 1},
    {"csv missing column", SIM MAT "particles:\n  - generator: csv\n    material: glass\n    file: spheres.csv\n",
     "x,y,radius\n0,0,0.001\n", 1, "particles[0].file", "no 'z' column", 1},
    {"csv missing file", SIM MAT "particles:\n  - generator: csv\n    material: glass\n    file: nothere.csv\n",
     NULL, 11, "particles[0].file", "cannot open the CSV file", 0},
    {"random box too full", SIM MAT
     "particles:\n  - generator: random\n    material: glass\n    radius: 0.1\n"
     "    box: {min: [0, 0, 0], max: [1, 1, 1]}\n    number: 1000\n",
     NULL, 9, "particles[0].number", "placed only", 0},
    {"overlap at start", SIM MAT
     "particles:\n  - generator: list\n    material: glass\n    spheres:\n"
     "      - {position: [0, 0, 0.01], radius: 0.001}\n"
     "      - {position: [0.0015, 0, 0.01], radius: 0.001}\n",
     NULL, 13, "particles[0].spheres[1]", "overlap at the start", 0},
    {"overlap between generators", SIM MAT PARTS
     "  - generator: lattice\n    material: glass\n    radius: 0.001\n    origin: [0.003, 0.001, 0.01]\n"
     "    spacing: 0.002\n    count: [1, 1, 1]\n",
     NULL, 14, "particles[1]", "from particles[0].spheres[1] (line 13)", 0},
    {"particle below a plane", SIM MAT PARTS "walls:\n  - type: plane\n    point: [0, 0, 0.0105]\n"
                                             "    normal: [0, 0, 1]\n    material: glass\n",
     NULL, 12, "particles[0].spheres[0]", "behind plane 'wall0'", 0},
    {"particle through a box face", SIM MAT PARTS "walls:\n  - type: box\n    min: [-0.002, -0.002, 0]\n"
                                                  "    max: [0.0035, 0.002, 0.02]\n    material: glass\n",
     NULL, 13, "particles[0].spheres[1]", "closed xmax face", 0},
    {"unknown shape type", SIM MAT "shapes:\n  - name: a\n    type: torus\n" PARTS, NULL, 10,
     "shapes[0].type",
     "expected one of sphere, box, cylinder, cone, ellipsoid, polyhedron, composite, circle, ellipse, polygon, polybezier, "
     "fourier, got torus",
     0},
    {"shape without a size", SIM MAT "shapes:\n  - name: cube\n    type: box\n" PARTS, NULL, 9,
     "shapes[0].size", "missing required key 'size'", 0},
    {"cylinder with diameter only", SIM MAT "shapes:\n  - name: rod\n    type: cylinder\n"
                                            "    diameter: 0.001\n" PARTS,
     NULL, 9, "shapes[0].length", "missing required key 'length'", 0},
    {"polyhedron with 3 vertices", SIM MAT "shapes:\n  - name: tri\n    type: polyhedron\n"
                                           "    vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\n" PARTS,
     NULL, 11, "shapes[0].vertices", "at least 4 vertices", 0},
    {"polyhedron mesh file missing", SIM MAT "shapes:\n  - name: m\n    type: polyhedron\n"
                                             "    file: nothere.obj\n" PARTS,
     NULL, 11, "shapes[0].file", "cannot open the mesh file", 0},
    {"rounding and margin", SIM MAT "shapes:\n  - name: cube\n    type: box\n    size: 0.001\n"
                                    "    rounding: 0.0001\n    margin: 0.0001\n" PARTS,
     NULL, 13, "shapes[0].margin", "at most one of rounding and margin", 0},
    {"radius key on a box", SIM MAT "shapes:\n  - name: cube\n    type: box\n    radius: 0.001\n" PARTS,
     NULL, 11, "shapes[0].radius", "does not apply to a box shape", 0},
    {"duplicate shape name", SIM MAT CUBE "  - {name: cube, type: sphere, radius: 0.001}\n" PARTS, NULL,
     10, "shapes[1].name", "duplicate shape name 'cube'", 0},
    {"shape and radius together", SIM MAT CUBE
     "particles:\n  - generator: lattice\n    material: glass\n    radius: 0.001\n    shape: cube\n"
     "    origin: [0, 0, 0]\n    spacing: 0.003\n    count: [2, 2, 2]\n",
     NULL, 14, "particles[0].shape", "not both", 0},
    {"neither shape nor radius", SIM MAT CUBE
     "particles:\n  - generator: lattice\n    material: glass\n"
     "    origin: [0, 0, 0]\n    spacing: 0.003\n    count: [2, 2, 2]\n",
     NULL, 11, "particles[0].radius", "missing required key 'radius' (or shape", 0},
    {"unknown shape name", SIM MAT CUBE
     "particles:\n  - generator: random\n    material: glass\n    shape: cub\n"
     "    box: {min: [0, 0, 0], max: [1, 1, 1]}\n    number: 5\n",
     NULL, 13, "particles[0].shape", "unknown shape 'cub' (shapes: cube)", 0},
    {"shape in a list entry and radius", SIM MAT CUBE
     "particles:\n  - generator: list\n    material: glass\n    spheres:\n"
     "      - {position: [0, 0, 0.01], radius: 0.001, shape: cube}\n",
     NULL, 14, "particles[0].spheres[0].shape", "not both", 0},
    {"orientation of a sphere", SIM MAT CUBE
     "particles:\n  - generator: list\n    material: glass\n    spheres:\n"
     "      - {position: [0, 0, 0.01], radius: 0.001, orientation: identity}\n",
     NULL, 14, "particles[0].spheres[0].orientation", "bodies of a shape only", 0},
    {"zero quaternion", SIM MAT CUBE
     "particles:\n  - generator: list\n    material: glass\n    shape: cube\n    spheres:\n"
     "      - {position: [0, 0, 0.01], orientation: [0, 0, 0, 0]}\n",
     NULL, 15, "particles[0].spheres[0].orientation", "non-zero quaternion", 0},
    {"csv row with a radius and a shape", SIM MAT CUBE
     "particles:\n  - generator: csv\n    material: glass\n    shape: cube\n    file: spheres.csv\n",
     "x,y,z,radius,shape\n0,0,0,0.001,cube\n", 2, "particles[0].file", "not both", 1},
    {"lattice too tight for a shape", SIM MAT CUBE
     "particles:\n  - generator: lattice\n    material: glass\n    shape: cube\n"
     "    origin: [0, 0, 0.01]\n    spacing: 0.0015\n    count: [2, 2, 2]\n",
     NULL, 15, "particles[0].spacing", "bounding radius of shape 'cube'", 0},
    {"time step above the stability limit", "simulation:\n  dt: 1.0e-3\n  steps: 10\n" MAT PARTS, NULL,
     2, "simulation.dt", "time step above the stability limit", 0},
};

static void test_bad_scenes(void)
{
    printf("bad scenes\n");
    size_t n = sizeof bad_cases / sizeof bad_cases[0];
    for (size_t c = 0; c < n; ++c) {
        const bad_case *b = &bad_cases[c];
        sd_scene *s = NULL;
        sd_world *w = NULL;
        sd_error err;
        sd_status st = load(b->yaml, b->csv, &s, &err);
        if (st == SD_OK) {
            st = sd_scene_build(s, &w, &err);
            CHECK((st == SD_OK) == (w != NULL));
            sd_world_destroy(w);
            sd_scene_free(s);
        } else {
            CHECK(s == NULL);
        }
        char buf[1200];
        sd_error_format(&err, buf, sizeof buf);
        int ok;
        if (b->line == 0) {
            ok = st == SD_OK;
        } else {
            const char *want_file = b->csv_file ? csv_path : scene_path;
            ok = st == SD_ERR_INPUT && err.line == b->line && !strcmp(err.key, b->key) &&
                 !strcmp(err.file, want_file) && strstr(err.msg, b->msg) != NULL &&
                 !strchr(buf, '\n');
        }
        printf("  %s %-40s %s\n", ok ? "ok  " : "FAIL", b->name, st == SD_OK ? "(loaded and built)" : buf);
        if (!ok && b->line)
            printf("       expected line %d key '%s' message containing '%s'\n", b->line, b->key, b->msg);
        CHECK(ok);
    }
    /* A scene file that is not there. */
    sd_scene *s;
    sd_error err;
    CHECK(sd_scene_load("/nonexistent/scene.yaml", &s, &err) != SD_OK && s == NULL);
    CHECK(!strcmp(err.file, "/nonexistent/scene.yaml") && strstr(err.msg, "cannot open"));
}

/* Every allocation of load and build may fail: the result is then
 * SD_ERR_MEMORY (never a crash, never a half-made scene or world); the
 * sanitizer build also proves nothing leaks on these paths. */
static void test_out_of_memory(void)
{
    printf("out of memory at each allocation\n");
    write_file(scene_path, good_scene);
    int ok = 1, failures_seen = 0;
    for (long n = 1; n <= 400; ++n) {
        sd_scene *s = NULL;
        sd_world *w = NULL;
        sd_error err;
        write_file(csv_path, good_csv);
        sd_alloc_fail_after(n);
        sd_status st = sd_scene_load(scene_path, &s, &err);
        if (st == SD_OK) {
            st = sd_scene_build(s, &w, &err);
            ok &= (st == SD_OK) == (w != NULL);
        } else {
            ok &= s == NULL;
        }
        sd_alloc_fail_after(0);
        ok &= st == SD_OK || st == SD_ERR_MEMORY;
        failures_seen += st == SD_ERR_MEMORY;
        sd_world_destroy(w);
        sd_scene_free(s);
        if (st == SD_OK)
            break; /* n is past the last allocation */
    }
    CHECK(ok);
    CHECK(failures_seen > 5);
}

int main(void)
{
    snprintf(dir, sizeof dir, "/tmp/sd_test_scene_XXXXXX");
    sd_test_require(mkdtemp(dir) != NULL, "mkdtemp", NULL);
    snprintf(scene_path, sizeof scene_path, "%s/scene.yaml", dir);
    snprintf(csv_path, sizeof csv_path, "%s/spheres.csv", dir);

    test_good_scene();
    test_out_of_memory();
    test_random();
    test_shapes();
    test_stl();
    test_random_orientation();
    test_example_and_docs();
    test_bad_scenes();

    remove(scene_path);
    remove(csv_path);
    rmdir(dir);
    return sd_test_summary();
}
