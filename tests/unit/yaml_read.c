/* yaml_read.c — the typed YAML reader (src/io/yaml_read.c) on its own,
 * without a scene: a file loaded, a list entry that is not a mapping
 * refused by the shared section prologue (sd_yaml_entry) with its line
 * and path, a mapping checked against the key table, and the table-driven
 * placement of number keys: given values and table defaults land at their
 * offsets, and a section key that is neither placed nor named as read by
 * its section is refused as a bug, never left at a silent default.
 */
#define _POSIX_C_SOURCE 200809L

#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/yaml_read.h"
#include "test.h"

typedef struct sd_probe {
    double density, friction, restitution;
} sd_probe;

int main(void)
{
    char dir[256], path[300];
    snprintf(dir, sizeof dir, "%s/sd_yaml_read_XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    sd_test_require(mkdtemp(dir) != NULL, "mkdtemp", NULL);
    snprintf(path, sizeof path, "%s/probe.yaml", dir);
    FILE *f = fopen(path, "w");
    sd_test_require(f != NULL, path, NULL);
    fputs("materials:\n"
          "  - {name: a, density: 2500, friction: 0.25}\n"
          "  - 7\n",
          f);
    fclose(f);

    sd_error err;
    memset(&err, 0, sizeof err);
    yaml_document_t doc;
    CHECK(sd_yaml_load(path, &doc, &err) == SD_OK);
    sd_yaml y = {&doc, path, &err};
    yaml_node_t *root = yaml_document_get_root_node(&doc);
    yaml_node_t *list = sd_yaml_map_get(&y, root, "materials");
    CHECK(sd_yaml_seq_len(list) == 2);
    CHECK(sd_yaml_key_line(&y, root, "materials") == 1);

    char ep[64];
    yaml_node_t *m = NULL;
    CHECK(sd_yaml_entry(&y, list, 0, "materials", "(name: ..., density: ...)", ep, sizeof ep, &m) == SD_OK);
    CHECK(!strcmp(ep, "materials[0]") && sd_yaml_line(m) == 2);
    CHECK(sd_yaml_check_map(&y, m, SD_SEC_MATERIAL, SD_KIND_ALL, "", ep, sd_yaml_line(m)) == SD_OK);

    /* placed: given values, and the table's default for restitution (0.5) */
    static const char *const rules_all[] = {"name", "youngs_modulus", "poisson_ratio", "rolling_friction",
                                            "stiffness", "tangential_stiffness_ratio", "damping",
                                            "volume_stiffness", "volume_face_omega_dt", NULL};
    const sd_yaml_place place[] = {{"density", offsetof(sd_probe, density)},
                                   {"friction", offsetof(sd_probe, friction)},
                                   {"restitution", offsetof(sd_probe, restitution)}};
    sd_probe pr = {-1, -1, -1};
    CHECK(sd_yaml_place_numbers(&y, m, SD_SEC_MATERIAL, ep, place, 3, rules_all, &pr) == SD_OK);
    CHECK_NEAR("placed density (given)", pr.density, 2500.0, 0.0);
    CHECK_NEAR("placed friction (given)", pr.friction, 0.25, 0.0);
    CHECK_NEAR("placed restitution (table default)", pr.restitution, 0.5, 0.0);

    /* a key neither placed nor read by name: a bug, named */
    static const char *const rules_short[] = {"name", "youngs_modulus", "poisson_ratio", "rolling_friction",
                                              "stiffness", "tangential_stiffness_ratio", "volume_stiffness",
                                              "volume_face_omega_dt", NULL};
    sd_status st = sd_yaml_place_numbers(&y, m, SD_SEC_MATERIAL, ep, place, 3, rules_short, &pr);
    printf("forgotten key: status %s, key '%s': %s\n", sd_status_name(st), err.key, err.msg);
    CHECK(st == SD_ERR_INTERNAL && !strcmp(err.key, "damping"));

    /* the prologue refuses an entry that is not a mapping, at its line */
    st = sd_yaml_entry(&y, list, 1, "materials", "(name: ..., density: ...)", ep, sizeof ep, &m);
    char buf[1024];
    sd_error_format(&err, buf, sizeof buf);
    printf("entry 2: %s\n", buf);
    CHECK(st == SD_ERR_INPUT && err.line == 3 && !strcmp(err.key, "materials[1]") &&
          strstr(err.msg, "expected a mapping (name: ..., density: ...), got 7"));

    yaml_document_delete(&doc);
    unlink(path);
    rmdir(dir);
    return sd_test_summary();
}
