/* alloc.h — the one allocation hook (STYLE.md convention 8).
 *
 * Every byte shapedem allocates goes through here, so the library can report
 * its memory (bytes in use and the peak) and tests can make the n-th
 * allocation fail to prove the out-of-memory paths.
 */
#ifndef SD_CORE_ALLOC_H
#define SD_CORE_ALLOC_H

#include <stddef.h>

void *sd_malloc(size_t size);
void *sd_calloc(size_t count, size_t size);
void *sd_realloc(void *p, size_t size);
void sd_free(void *p);

/* Test hook: the n-th allocation from now fails (n >= 1); 0 disables. */
void sd_alloc_fail_after(long n);

#endif
