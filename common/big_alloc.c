/* big_alloc.c: aligned arrays, with 2 MB pages for the big ones when asked (chapter 3).
 *
 * Memory comes from the kernel in 4 KB pages, each costing a page fault the first time it is touched and
 * an entry in the processor's small cache of page addresses (the TLB) whenever it is used. Linux can
 * back an array with 2 MB pages instead (madvise MADV_HUGEPAGE, when the array is aligned to 2 MB): one
 * fault per 2 MB instead of one per 4 KB, and 512 times fewer TLB entries. On the virtual machine this
 * was measured on, first-touch page faults cost 70 ms per 25 MB, most of a big build's time, and the
 * 350,000-triangle teapot's arrays took 50 ms to read in 4 KB pages and 18 ms in 2 MB ones. The advice
 * is only a hint: elsewhere, or when the kernel refuses it, the array is an ordinary one. */
#include "big_alloc.h"

#include <stdint.h>
#include <stdlib.h>
#include <sys/mman.h>

/* The size of a big page, and the smallest array worth one. */
#define BIG_ALLOC_HUGE_PAGE ((size_t)1 << 21)

/* Every array starts on a cache line, so that a 64-byte node never straddles two. */
#define BIG_ALLOC_ALIGNMENT 64

void *big_alloc(size_t bytes, bool huge_pages) {
    if (bytes > SIZE_MAX / 2)
        return NULL; /* no machine has that much; and the roundings below would wrap around */
    if (bytes < BIG_ALLOC_HUGE_PAGE / 2 || !huge_pages) /* aligned_alloc wants a multiple of the alignment */
        return aligned_alloc(BIG_ALLOC_ALIGNMENT, (bytes / BIG_ALLOC_ALIGNMENT + 1) * BIG_ALLOC_ALIGNMENT);
    size_t rounded = (bytes + BIG_ALLOC_HUGE_PAGE - 1) / BIG_ALLOC_HUGE_PAGE * BIG_ALLOC_HUGE_PAGE;
    void *p = aligned_alloc(BIG_ALLOC_HUGE_PAGE, rounded);
#if defined(MADV_HUGEPAGE)
    /* The whole big pages the array fills, and its last part too when that fills at least half a big
     * page: touching the end of the array then makes the rest of that big page resident (less than
     * 1 MB an array), where in small pages it would cost 256 faults or more. A shorter last part stays
     * in small pages. */
    size_t whole = bytes / BIG_ALLOC_HUGE_PAGE * BIG_ALLOC_HUGE_PAGE;
    size_t advised = bytes - whole >= BIG_ALLOC_HUGE_PAGE / 2 ? rounded : whole;
    if (p != NULL)
        madvise(p, advised, MADV_HUGEPAGE); /* only a hint */
#endif
    return p;
}
