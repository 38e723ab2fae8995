/* alloc.c — counting allocator.
 *
 * Each block carries a 16-byte header with its size so sd_free and
 * sd_realloc keep the byte counter exact. Counters are atomics because
 * worlds may be built from several threads in user programs.
 */
#include "core/alloc.h"

#include <shapedem/shapedem.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#define SD_ALLOC_HEADER 16

static atomic_size_t sd_alloc_in_use;
static atomic_size_t sd_alloc_peak;
static atomic_long sd_alloc_countdown;

static int sd_alloc_should_fail(void)
{
    long n = atomic_load(&sd_alloc_countdown);
    if (n <= 0)
        return 0;
    if (atomic_fetch_sub(&sd_alloc_countdown, 1) == 1)
        return 1;
    return 0;
}

static void sd_alloc_account(size_t add, size_t sub)
{
    size_t now = atomic_fetch_add(&sd_alloc_in_use, add) + add;
    atomic_fetch_sub(&sd_alloc_in_use, sub);
    now -= sub;
    size_t peak = atomic_load(&sd_alloc_peak);
    while (now > peak && !atomic_compare_exchange_weak(&sd_alloc_peak, &peak, now)) {
    }
}

void *sd_malloc(size_t size)
{
    if (sd_alloc_should_fail())
        return NULL;
    unsigned char *p = malloc(size + SD_ALLOC_HEADER);
    if (!p)
        return NULL;
    memcpy(p, &size, sizeof size);
    sd_alloc_account(size, 0);
    return p + SD_ALLOC_HEADER;
}

void *sd_calloc(size_t count, size_t size)
{
    if (size && count > (size_t)-1 / size)
        return NULL;
    void *p = sd_malloc(count * size);
    if (p)
        memset(p, 0, count * size);
    return p;
}

void *sd_realloc(void *p, size_t size)
{
    if (!p)
        return sd_malloc(size);
    if (sd_alloc_should_fail())
        return NULL;
    unsigned char *base = (unsigned char *)p - SD_ALLOC_HEADER;
    size_t old;
    memcpy(&old, base, sizeof old);
    unsigned char *q = realloc(base, size + SD_ALLOC_HEADER);
    if (!q)
        return NULL;
    memcpy(q, &size, sizeof size);
    sd_alloc_account(size, old);
    return q + SD_ALLOC_HEADER;
}

void sd_free(void *p)
{
    if (!p)
        return;
    unsigned char *base = (unsigned char *)p - SD_ALLOC_HEADER;
    size_t old;
    memcpy(&old, base, sizeof old);
    atomic_fetch_sub(&sd_alloc_in_use, old);
    free(base);
}

void sd_alloc_fail_after(long n) { atomic_store(&sd_alloc_countdown, n); }

size_t sd_memory_in_use(void) { return atomic_load(&sd_alloc_in_use); }
size_t sd_memory_peak(void) { return atomic_load(&sd_alloc_peak); }
