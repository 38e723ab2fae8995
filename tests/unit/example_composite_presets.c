/* example_composite_presets.c — compiles and runs examples/c/composite_presets.c
 * (STYLE.md: examples are compiled and run in CI). The example checks its
 * own results (the L's exact volume, every body at rest on the floor) and
 * returns non-zero when one fails; the test is that exit status. */
#include "../../examples/c/composite_presets.c"
