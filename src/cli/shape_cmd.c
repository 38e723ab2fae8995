/* shape_cmd.c — `shapedem shape info`: a shape's volume, centre of mass,
 * principal moments of inertia and bounding radius, from the command line
 * or for every shape of a scene file. */
#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <shapedem/shapedem.h>

#include "cli/commands.h"
#include "core/alloc.h"
#include "io/scene.h"
#include "shape/polylib.h"
#include "shape/shape.h"

static void sd_print_shape(const sd_world *w, size_t k, double density)
{
    sd_shape_info si;
    sd_world_get_shape(w, k, &si);
    double m = density * si.volume;
    printf("shape              %s (%s)\n", si.name, si.kind);
    printf("volume             %.10g m^3\n", si.volume);
    printf("equivalent radius  %.10g m (sphere of the same volume)\n", si.equivalent_radius);
    printf("bounding radius    %.10g m (about the centre of mass)\n", si.bounding_radius);
    printf("centre of mass     (%.10g, %.10g, %.10g) m in the frame the shape was given in\n",
           si.center_of_mass.x, si.center_of_mass.y, si.center_of_mass.z);
    printf("principal moments  (%.10g, %.10g, %.10g) m^5 per unit density\n", si.inertia.x, si.inertia.y,
           si.inertia.z);
    printf("  at %g kg/m^3     mass %.10g kg, moments (%.10g, %.10g, %.10g) kg m^2\n", density, m,
           density * si.inertia.x, density * si.inertia.y, density * si.inertia.z);
    printf("principal axes     (%.6g, %.6g, %.6g), (%.6g, %.6g, %.6g), (%.6g, %.6g, %.6g) in the given frame\n",
           si.axes[0].x, si.axes[0].y, si.axes[0].z, si.axes[1].x, si.axes[1].y, si.axes[1].z, si.axes[2].x,
           si.axes[2].y, si.axes[2].z);
    if (!strcmp(si.kind, "composite")) {
        printf("elements           %zu convex (seed 004 glued convex)\n", si.element_count);
        if (si.lattice)
            printf("mass properties    exact sums minus the overlaps integrated on a voxel lattice of %d points "
                   "per direction, estimated relative error %.2g\n",
                   si.lattice, si.lattice_error);
        else
            printf("mass properties    exact (no two elements overlap: parallel-axis sums)\n");
    }
    if (si.rounding > 0)
        printf("rounding           %.10g m swept over the core\n", si.rounding);
    if (si.vertex_count)
        printf("hull vertices      %zu\n", si.vertex_count);
    if (si.face_count)
        printf("welded faces       %zu (exact overlap volume: %s)\n", si.face_count,
               si.face_count <= si.overlap_face_limit ? "yes" : "no, more than the workspace's faces");
}

static int sd_parse_v3(const char *s, sd_v3d *out);

/* A built-in polyhedron from the command line (shape/polylib.h):
 * --size D (circumscribed diameter; prism, cylinder: D,-,L), --edge A,
 * --sides N, --faces N, --vertex-count N, --seed S. Returns 0, or 2 after
 * printing why. */
static int sd_preset_desc(int preset, int argc, char **argv, sd_shape_desc *d, sd_v3d *buf, size_t cap,
                          double *density)
{
    sd_poly_def pd;
    memset(&pd, 0, sizeof pd);
    pd.preset = preset;
    pd.seed = 1;
    for (int k = 4; k < argc; k += 2) {
        const char *a = argv[k], *v = k + 1 < argc ? argv[k + 1] : NULL;
        sd_v3d x;
        if (!v || sd_parse_v3(v, &x)) {
            fprintf(stderr, "shapedem: bad option or value '%s %s' (see 'shapedem shape info')\n", a, v ? v : "");
            return 2;
        }
        if (!strcmp(a, "--size")) {
            pd.diameter = x.x;
            pd.length = x.z;
        } else if (!strcmp(a, "--edge"))
            pd.diameter = sd_polylib_edge_to_diameter(preset, x.x);
        else if (!strcmp(a, "--sides"))
            pd.sides = (int)x.x;
        else if (!strcmp(a, "--faces"))
            pd.faces = (int)x.x;
        else if (!strcmp(a, "--vertex-count"))
            pd.points = (int)x.x;
        else if (!strcmp(a, "--seed"))
            pd.seed = (uint64_t)x.x;
        else if (!strcmp(a, "--density"))
            *density = x.x;
        else if (!strcmp(a, "--scale"))
            d->scale = x.x;
        else {
            fprintf(stderr, "shapedem: bad option '%s' for a %s (--size, --edge, --sides, --faces, --vertex-count, "
                            "--seed, --scale, --density)\n", a, sd_polylib_name(preset));
            return 2;
        }
    }
    size_t n = 0;
    sd_error err;
    if (sd_polylib_vertices(&pd, buf, cap, &n, &err) != SD_OK) {
        fprintf(stderr, "shapedem: %s: --%s: %s\n", sd_polylib_name(preset), err.key, err.msg);
        return 2;
    }
    d->kind = "polyhedron";
    d->vertices = buf;
    d->vertex_count = n;
    return 0;
}

static int sd_parse_v3(const char *s, sd_v3d *out)
{
    double v[3];
    int n = 0;
    char *end;
    const char *c = s;
    while (n < 3) {
        v[n++] = strtod(c, &end);
        if (end == c)
            return -1;
        if (*end == '\0')
            break;
        if (*end != ',')
            return -1;
        c = end + 1;
    }
    if (*end != '\0')
        return -1;
    out->x = v[0];
    out->y = n > 1 ? v[1] : v[0];
    out->z = n > 2 ? v[2] : (n > 1 ? v[1] : v[0]);
    return 0;
}

static int sd_ends_with(const char *s, const char *tail)
{
    size_t n = strlen(s), k = strlen(tail);
    if (n <= k)
        return 0;
    for (size_t i = 0; i < k; ++i)
        if ((s[n - k + i] | 0x20) != (tail[i] | 0x20)) /* ASCII, any case */
            return 0;
    return 1;
}

/* `shape info mesh.obj|mesh.stl`: a polyhedron from a mesh file, read and
 * checked as a scene's `file:` is, with the options of such a shape
 * (--scale, --rounding, --margin, --nonconvex reject|hull) and --density. */
static int sd_shape_mesh_info(const char *path, int argc, char **argv)
{
    sd_shape_desc d = sd_shape_desc_default();
    d.kind = "polyhedron";
    double density = 1000.0;
    int take_hull = 0;
    for (int k = 4; k < argc; k += 2) {
        const char *a = argv[k], *v = k + 1 < argc ? argv[k + 1] : NULL;
        sd_v3d x = {0, 0, 0}; /* set when num; gcc -O3 cannot see that */
        int num = v && !sd_parse_v3(v, &x);
        if (!v) {
            fprintf(stderr, "shapedem: %s needs a value\n", a);
            return 2;
        }
        if (!strcmp(a, "--nonconvex") && (!strcmp(v, "hull") || !strcmp(v, "reject")))
            take_hull = !strcmp(v, "hull");
        else if (!strcmp(a, "--scale") && num)
            d.scale = x.x;
        else if (!strcmp(a, "--rounding") && num)
            d.rounding = x.x;
        else if (!strcmp(a, "--margin") && num)
            d.margin = x.x;
        else if (!strcmp(a, "--density") && num)
            density = x.x;
        else {
            fprintf(stderr, "shapedem: bad option or value '%s %s' for a mesh file (--scale S, --rounding R, "
                            "--margin M, --nonconvex reject|hull, --density RHO)\n", a, v);
            return 2;
        }
    }
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_v3d *verts = NULL;
    size_t n = 0;
    char warning[400];
    if (sd_scene_read_mesh(path, take_hull, &verts, &n, warning, sizeof warning, &err) != SD_OK) {
        /* the scene key's advice, in this command's words */
        char *at = strstr(err.msg, "set nonconvex: hull");
        if (at && strlen(err.msg) + 8 < sizeof err.msg) {
            char tail[sizeof err.msg];
            snprintf(tail, sizeof tail, "%s", at + strlen("set nonconvex: hull"));
            snprintf(at, sizeof err.msg - (size_t)(at - err.msg), "add --nonconvex hull%s", tail);
        }
        return sd_cli_fail_input(&err);
    }
    d.vertices = verts;
    d.vertex_count = n;
    sd_world_def wd = sd_world_def_default();
    sd_world *w;
    int rc = 0;
    if (sd_world_create(&wd, &w, &err) != SD_OK) {
        sd_free(verts);
        return sd_cli_fail_input(&err);
    }
    const char *base = strrchr(path, '/');
    if (sd_world_add_shape(w, base ? base + 1 : path, &d, &err) < 0) {
        if (!err.file[0])
            snprintf(err.file, sizeof err.file, "%s", path);
        rc = sd_cli_fail_input(&err);
    } else {
        sd_print_shape(w, 0, density);
        if (warning[0])
            printf("warning            %s\n", warning);
    }
    sd_world_destroy(w);
    sd_free(verts);
    return rc;
}

int sd_cmd_shape(int argc, char **argv)
{
    if (argc >= 3 && !strcmp(argv[2], "fit-fourier"))
        return sd_cmd_fit_fourier(argc, argv);
    int help = 0; /* shape --help, shape info --help: the usage on stdout, exit 0 */
    for (int k = 2; k < argc; ++k)
        help |= !strcmp(argv[k], "--help") || !strcmp(argv[k], "-h");
    if (help || argc < 4 || strcmp(argv[2], "info") != 0) {
        fprintf(help ? stdout : stderr, "usage: shapedem shape info KIND --size X[,Y,Z] [--rounding R] [--margin M] [--scale S] "
                        "[--density RHO]\n       shapedem shape info PRESET --size D|--edge A [--sides N] "
                        "[--faces N|--vertex-count N] [--seed S]\n         (PRESET: tetrahedron, cube, octahedron, "
                        "dodecahedron, icosahedron, prism, polycylinder, random)\n"
                        "       shapedem shape info MESH.obj|MESH.stl [--scale S] [--rounding R|--margin M]\n"
                        "         [--nonconvex reject|hull] [--density RHO]\n"
                        "       shapedem shape info SCENE.yaml\n"
                        "       shapedem shape fit-fourier OUTLINE.csv [--order N] [--directions M] [--beta B]\n");
        return help ? 0 : 2;
    }
    const char *what = argv[3];
    size_t len = strlen(what);
    sd_error err;
    memset(&err, 0, sizeof err);
    if ((len > 5 && !strcmp(what + len - 5, ".yaml")) || (len > 4 && !strcmp(what + len - 4, ".yml"))) {
        sd_scene *scene;
        sd_world *w;
        if (sd_scene_load(what, &scene, &err) != SD_OK)
            return sd_cli_fail_input(&err);
        if (sd_scene_build(scene, &w, &err) != SD_OK) {
            sd_scene_free(scene); /* the loaded scene is ours to free on every path */
            return sd_cli_fail_input(&err);
        }
        size_t n = sd_world_shape_count(w);
        if (n == 0)
            printf("%s defines no shapes (its particles are plain spheres)\n", what);
        for (size_t k = 0; k < n; ++k) {
            if (k)
                printf("\n");
            double rho = scene->material_count ? scene->materials[0].def.density : 1000.0;
            sd_print_shape(w, k, rho);
            if (k < scene->shape_count && scene->shapes[k].warning[0])
                printf("warning            %s\n", scene->shapes[k].warning);
        }
        sd_world_destroy(w);
        sd_scene_free(scene);
        return 0;
    }
    if (sd_ends_with(what, ".obj") || sd_ends_with(what, ".stl"))
        return sd_shape_mesh_info(what, argc, argv);
    sd_shape_desc d = sd_shape_desc_default();
    d.kind = what;
    double density = 1000.0;
    static sd_v3d preset_vertices[SD_SHAPE_MAX_VERTICES];
    int preset = sd_polylib_from_name(what);
    if (preset >= 0 && strcmp(what, "cylinder") == 0)
        preset = -1; /* "cylinder" is the smooth kind; the polyhedral one is "polycylinder" */
    if (strcmp(what, "polycylinder") == 0)
        preset = SD_POLY_CYLINDER;
    if (preset >= 0) {
        int rc = sd_preset_desc(preset, argc, argv, &d, preset_vertices, SD_SHAPE_MAX_VERTICES, &density);
        if (rc)
            return rc;
    }
    for (int k = 4; k < argc && preset < 0; ++k) {
        const char *a = argv[k], *v = k + 1 < argc ? argv[k + 1] : NULL;
        sd_v3d x;
        if (!v) {
            fprintf(stderr, "shapedem: %s needs a value\n", a);
            return 2;
        }
        ++k;
        if (!strcmp(a, "--size") && !sd_parse_v3(v, &x))
            d.size = x;
        else if (!strcmp(a, "--rounding") && !sd_parse_v3(v, &x))
            d.rounding = x.x;
        else if (!strcmp(a, "--margin") && !sd_parse_v3(v, &x))
            d.margin = x.x;
        else if (!strcmp(a, "--scale") && !sd_parse_v3(v, &x))
            d.scale = x.x;
        else if (!strcmp(a, "--density") && !sd_parse_v3(v, &x))
            density = x.x;
        else {
            fprintf(stderr, "shapedem: bad option or value '%s %s' (see 'shapedem shape info')\n", a, v);
            return 2;
        }
    }
    sd_world_def wd = sd_world_def_default();
    sd_world *w;
    if (sd_world_create(&wd, &w, &err) != SD_OK)
        return sd_cli_fail_input(&err);
    if (sd_world_add_shape(w, what, &d, &err) < 0) {
        sd_world_destroy(w);
        return sd_cli_fail_input(&err);
    }
    sd_print_shape(w, 0, density);
    sd_world_destroy(w);
    return 0;
}
