/* name_index.c: a hash table from names to numbers, open addressing with linear probing (chapter 1). */
#include "name_index.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define NAME_INDEX_FIRST_CAPACITY 64 /* slots of a new table; a typical scene has a handful of names */

struct name_slot {
    char *name; /* owned; NULL for an empty slot */
    int value;
};

/* FNV-1a, 64 bits: simple, and spreads names that differ in one character well. */
static uint64_t hash_name(const char *name) {
    uint64_t hash = 14695981039346656037u; /* the FNV offset basis */
    for (const unsigned char *c = (const unsigned char *)name; *c != '\0'; c++)
        hash = (hash ^ *c) * 1099511628211u; /* the FNV prime */
    return hash;
}

/* Returns the slot holding `name`, or the empty slot where it would go. The table must have one. */
static struct name_slot *find_slot(struct name_slot *slots, size_t capacity, const char *name) {
    size_t k = (size_t)hash_name(name) & (capacity - 1);
    while (slots[k].name != NULL && strcmp(slots[k].name, name) != 0)
        k = (k + 1) & (capacity - 1);
    return &slots[k];
}

void name_index_init(struct name_index *ix) { *ix = (struct name_index){0}; }

/* Moves every name into a table of twice the size (or the first table). */
static bool grow(struct name_index *ix) {
    size_t capacity = ix->capacity == 0 ? NAME_INDEX_FIRST_CAPACITY : 2 * ix->capacity;
    struct name_slot *slots = calloc(capacity, sizeof *slots);
    if (slots == NULL)
        return false;
    for (size_t k = 0; k < ix->capacity; k++)
        if (ix->slots[k].name != NULL)
            *find_slot(slots, capacity, ix->slots[k].name) = ix->slots[k];
    free(ix->slots);
    ix->slots = slots;
    ix->capacity = capacity;
    return true;
}

bool name_index_add(struct name_index *ix, const char *name, int value) {
    if (2 * (ix->count + 1) > ix->capacity && !grow(ix)) /* keep it at most half full */
        return false;
    char *copy = strdup(name);
    if (copy == NULL)
        return false;
    *find_slot(ix->slots, ix->capacity, name) = (struct name_slot){copy, value};
    ix->count++;
    return true;
}

int name_index_find(const struct name_index *ix, const char *name) {
    if (ix->capacity == 0)
        return -1;
    const struct name_slot *slot = find_slot(ix->slots, ix->capacity, name);
    return slot->name != NULL ? slot->value : -1;
}

void name_index_free(struct name_index *ix) {
    for (size_t k = 0; k < ix->capacity; k++)
        free(ix->slots[k].name);
    free(ix->slots);
    *ix = (struct name_index){0};
}
