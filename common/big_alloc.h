/* big_alloc.h: memory for big arrays, backed by 2 MB pages (chapter 3: a model's arrays; chapter 9's
 * gathered triangles; chapter 11's build). */
#ifndef WHITTED_BIG_ALLOC_H
#define WHITTED_BIG_ALLOC_H

#include <stdbool.h>
#include <stddef.h>

/* Returns `bytes` bytes aligned to 64 (a cache line), or NULL when memory runs out; release with free().
 * With huge_pages, an array of 1 MB or more is aligned to 2 MB instead and the kernel is asked to back it
 * with 2 MB pages (big_alloc.c says why and which part; where the kernel cannot or will not, nothing else
 * changes). */
void *big_alloc(size_t bytes, bool huge_pages);

#endif
