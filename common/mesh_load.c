/* mesh_load.c: loading a triangle mesh from a PLY or OBJ file (chapter 3).
 *
 * mesh_load reads the whole file into memory (mapped where it can be, else copied) with a NUL byte
 * after it, looks at its first line to choose the reader (mesh_ply.c or mesh_obj.c) and makes sure a
 * failed load leaves nothing behind.
 * What both readers share (messages, lines and words, numbers, growing arrays) is in mesh_read.c. */
#include "mesh_load.h"

#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "infile.h"
#include "mesh_obj.h"
#include "mesh_ply.h"
#include "mesh_read.h"

#define READ_CHUNK_BYTES ((size_t)1 << 16) /* first buffer size when the file's size is unknown */

/* Files smaller than this are read, not mapped: mapping costs system calls of its own, and a copy of a
 * small file costs less (a 100 KB model: 0.2 ms read, 0.5 ms mapped; a 6.6 MB one: 40 ms read in a
 * fresh process, 5 ms mapped). */
#define MAP_MIN_BYTES ((size_t)1 << 20)

/* The size to allocate first: the file's own size plus one byte, so that the first read already meets
 * the end of the file; a guess if its size cannot be known. *file_size is the file's size, or 0 when
 * it is not known. */
static bool initial_capacity(const struct mesh_input *in, FILE *file, size_t *capacity, size_t *file_size) {
    struct stat info;
    *capacity = READ_CHUNK_BYTES;
    *file_size = 0;
    if (fstat(fileno(file), &info) != 0 || !S_ISREG(info.st_mode))
        return true;
    if ((uintmax_t)info.st_size > MESH_MAX_FILE_BYTES)
        return mesh_fail_file(in, "file too large (%jd bytes; the limit is %zu)", (intmax_t)info.st_size,
                              MESH_MAX_FILE_BYTES);
    *file_size = (size_t)info.st_size;
    *capacity = *file_size + 1;
    return true;
}

/* Doubles the buffer, up to one byte more than MESH_MAX_FILE_BYTES (a file that fills that is too
 * long). Keeps room for a NUL after the last byte. */
static bool grow_buffer(const struct mesh_input *in, char **buffer, size_t *capacity) {
    if (*capacity > MESH_MAX_FILE_BYTES)
        return mesh_fail_file(in, "file too large (more than %zu bytes)", MESH_MAX_FILE_BYTES);
    size_t new_capacity = *capacity * 2;
    if (new_capacity > MESH_MAX_FILE_BYTES + 1)
        new_capacity = MESH_MAX_FILE_BYTES + 1;
    char *grown = realloc(*buffer, new_capacity + 1);
    if (grown == NULL)
        return mesh_fail_file(in, "out of memory reading the file");
    *buffer = grown;
    *capacity = new_capacity;
    return true;
}

/* A file in memory: read into a buffer of our own, or mapped (see map_file). */
struct file_in_memory {
    char *data;
    size_t size;
    bool mapped; /* data is a mapping of `size` bytes, given back with munmap; else a malloc'd buffer */
};

/* Maps the open regular file of `size` bytes into memory, read-only, its pages fetched at once
 * (MAP_POPULATE), instead of copying it into a new buffer: the pages are those the kernel already holds
 * in its file cache, so nothing is copied and no fresh memory is touched (a fresh page costs a page
 * fault; a 6.6 MB model read into a buffer of its own took 40 ms more than mapped, most of it faults).
 * Only when the file does not end exactly at the end of a page: the rest of its last page then reads as
 * zeros, which gives the NUL byte after the data that the readers rely on. Returns false (nothing to
 * undo) when the file cannot be mapped so; the caller then reads it. The one thing a mapping cannot
 * survive is the file being cut short by another program during the few milliseconds it is parsed
 * (its pages then vanish); a file already shorter than fstat said is refused here, and read instead. */
static bool map_file(FILE *file, size_t size, struct file_in_memory *f) {
    long page = sysconf(_SC_PAGESIZE);
    if (size < MAP_MIN_BYTES || page <= 0 || size % (size_t)page == 0)
        return false;
    int flags = MAP_PRIVATE;
#ifdef MAP_POPULATE
    flags |= MAP_POPULATE;
#endif
    void *p = mmap(NULL, size, PROT_READ, flags, fileno(file), 0);
    if (p == MAP_FAILED)
        return false;
    struct stat info; /* a file cut short since fstat: its missing pages would end the program (SIGBUS) */
    if (fstat(fileno(file), &info) != 0 || (uintmax_t)info.st_size < size) {
        munmap(p, size);
        return false;
    }
    *f = (struct file_in_memory){.data = p, .size = size, .mapped = true};
    return true;
}

/* Reads the whole file into memory with a NUL after its last byte: mapped where it can be (map_file),
 * else into a new buffer. Refuses anything but a regular file (infile.h), and more than
 * MESH_MAX_FILE_BYTES even if the file grows while it is read. */
static bool read_file(const char *path, struct file_in_memory *f, char *err, size_t err_size) {
    struct mesh_input in = {.path = path, .err = err, .err_size = err_size};
    *f = (struct file_in_memory){0};
    FILE *file = infile_open(path, err, err_size); /* a regular file, or refused without waiting */
    if (file == NULL)
        return false;
    size_t capacity, file_size, used = 0;
    char *buffer = NULL;
    bool ok = initial_capacity(&in, file, &capacity, &file_size);
    if (ok && map_file(file, file_size, f)) {
        fclose(file);
        return true;
    }
    if (ok && (buffer = malloc(capacity + 1)) == NULL) /* + 1 for the final NUL */
        ok = mesh_fail_file(&in, "out of memory reading the file");
    while (ok) {
        errno = 0;
        used += fread(buffer + used, 1, capacity - used, file);
        if (ferror(file))
            ok = mesh_fail_file(&in, "cannot read: %s", strerror(errno != 0 ? errno : EIO));
        else if (feof(file))
            break;
        else if (used == capacity)
            ok = grow_buffer(&in, &buffer, &capacity);
    }
    fclose(file);
    if (!ok) {
        free(buffer);
        return false;
    }
    buffer[used] = '\0';
    *f = (struct file_in_memory){.data = buffer, .size = used};
    return true;
}

/* Gives back what read_file took. */
static void release_file(struct file_in_memory *f) {
    if (f->mapped)
        munmap(f->data, f->size);
    else
        free(f->data);
    *f = (struct file_in_memory){0};
}

/* A PLY file's first line is exactly "ply" (LF or CRLF). */
static bool starts_as_ply(const char *data, size_t size) {
    return (size >= 4 && memcmp(data, "ply\n", 4) == 0) || (size >= 5 && memcmp(data, "ply\r\n", 5) == 0);
}

bool mesh_load(const char *path, struct mesh *m, char *err, size_t err_size) {
    return mesh_load_with_corners(path, m, NULL, err, err_size);
}

bool mesh_load_with_corners(const char *path, struct mesh *m, struct mesh_corners *corners, char *err,
                            size_t err_size) {
    *m = (struct mesh){0};
    if (corners != NULL)
        *corners = (struct mesh_corners){0};
    struct file_in_memory file;
    if (!read_file(path, &file, err, err_size))
        return false;
    struct mesh_input in = {.path = path, .data = file.data, .size = file.size, .err = err, .err_size = err_size,
                            .corners = corners};
    bool ok;
    if (file.size == 0)
        ok = mesh_fail_file(&in, "empty file");
    else if (starts_as_ply(file.data, file.size))
        ok = mesh_read_ply(&in, m);
    else if (file.size > 3 && memcmp(file.data, MESH_UTF8_BOM, 3) == 0 && starts_as_ply(file.data + 3, file.size - 3))
        ok = mesh_fail_line(&in, 1, "a byte-order mark before 'ply': a PLY file starts with the bytes 'ply' (save it "
                            "without the mark)");
    else
        ok = mesh_read_obj(&in, m);
    if (ok && m->face_count == 0)
        ok = mesh_fail_file(&in, "no faces");
    release_file(&file);
    if (!ok) {
        mesh_free(m);
        if (corners != NULL)
            mesh_corners_free(corners);
    }
    return ok;
}
