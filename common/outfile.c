/* outfile.c: write to a temporary file, then rename it into place; write directly where a rename cannot
 * work (chapter 1). */
#include "outfile.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Permissions of finished files: mkstemp makes them private, but pictures are for everyone to read. */
#define OUTFILE_MODE 0644

/* Links followed before giving up on a chain of symbolic links: Linux's own limit (MAXSYMLINKS). */
#define OUTFILE_MAX_LINKS 40

/* Where "-" writes: standard output, or the copy of it that outfile_reserve_stdout set aside. */
static int stdout_fd = STDOUT_FILENO;

/* Returns a new string: `path` with every symbolic link at its end followed (a link to a link too), or
 * NULL when memory runs out. A link to a name that does not exist yet gives that name. */
static char *follow_links(const char *path) {
    char *current = strdup(path);
    for (int k = 0; current != NULL && k < OUTFILE_MAX_LINKS; k++) {
        struct stat info;
        if (lstat(current, &info) != 0 || !S_ISLNK(info.st_mode))
            return current;
        char link[PATH_MAX];
        ssize_t length = readlink(current, link, sizeof link - 1);
        if (length < 0)
            return current;
        link[length] = '\0';
        const char *slash = strrchr(current, '/');
        size_t folder = (link[0] == '/' || slash == NULL) ? 0 : (size_t)(slash - current) + 1;
        char *next = malloc(folder + (size_t)length + 1);
        if (next != NULL) {
            memcpy(next, current, folder);
            memcpy(next + folder, link, (size_t)length + 1);
        }
        free(current);
        current = next;
    }
    return current; /* a loop of links, or a chain longer than Linux follows: still a link (is_link) */
}

/* Whether `target`, a name follow_links gave, is still a symbolic link: then the links went round a loop,
 * and a rename over it would replace the link itself. */
static bool is_link(const char *target) {
    struct stat info;
    return lstat(target, &info) == 0 && S_ISLNK(info.st_mode);
}

/* Opens what "-" names, standard output, on a descriptor of its own. */
static FILE *open_stdout(void) {
    int fd = dup(stdout_fd);
    FILE *file = fd < 0 ? NULL : fdopen(fd, "wb");
    if (file == NULL && fd >= 0)
        close(fd);
    return file;
}

/* Opens an existing FIFO or device for writing as it is (no O_CREAT, no O_TRUNC). */
static FILE *open_direct(const char *target) {
    int fd = open(target, O_WRONLY | O_CLOEXEC);
    FILE *file = fd < 0 ? NULL : fdopen(fd, "wb");
    if (file == NULL && fd >= 0)
        close(fd);
    return file;
}

/* Creates the temporary file beside f->target; sets f->temp_path. */
static FILE *open_temporary(struct outfile *f) {
    size_t size = strlen(f->target) + sizeof OUTFILE_TEMP_SUFFIX;
    f->temp_path = malloc(size);
    if (f->temp_path == NULL) {
        errno = ENOMEM;
        return NULL;
    }
    snprintf(f->temp_path, size, "%s" OUTFILE_TEMP_SUFFIX, f->target);
    int fd = mkstemp(f->temp_path);
    FILE *file = NULL;
    if (fd >= 0) {
        fchmod(fd, OUTFILE_MODE);
        file = fdopen(fd, "wb");
        if (file == NULL) {
            int saved = errno;
            close(fd);
            remove(f->temp_path);
            errno = saved;
        }
    }
    if (file == NULL) {
        free(f->temp_path);
        f->temp_path = NULL;
    }
    return file;
}

bool outfile_open(struct outfile *f, const char *path, char *err, size_t err_size) {
    *f = (struct outfile){.path = path};
    if (strcmp(path, "-") == 0) {
        f->file = open_stdout();
    } else if ((f->target = follow_links(path)) == NULL) {
        errno = ENOMEM;
    } else if (is_link(f->target)) {
        errno = ELOOP;
    } else {
        struct stat info;
        bool special = stat(f->target, &info) == 0 && !S_ISREG(info.st_mode) && !S_ISDIR(info.st_mode);
        f->file = special ? open_direct(f->target) : open_temporary(f);
    }
    if (f->file == NULL) {
        snprintf(err, err_size, "%s: cannot create: %s", path, strerror(errno));
        free(f->target);
        f->target = NULL;
        return false;
    }
    return true;
}

bool outfile_write(struct outfile *f, const void *data, size_t size) {
    errno = 0;
    if (fwrite(data, 1, size, f->file) == size)
        return true;
    if (f->error == 0)
        f->error = errno != 0 ? errno : EIO;
    return false;
}

bool outfile_commit(struct outfile *f, char *err, size_t err_size) {
    bool ok = !ferror(f->file) && f->error == 0;
    /* A failure inside fprintf leaves no errno to report: say "Input/output error" then. */
    int saved = ok ? 0 : f->error != 0 ? f->error : EIO;
    if (fclose(f->file) != 0 && ok) {
        ok = false;
        saved = errno;
    }
    if (ok && f->temp_path != NULL && rename(f->temp_path, f->target) != 0) {
        ok = false;
        saved = errno;
    }
    if (!ok) {
        snprintf(err, err_size, "%s: cannot write: %s", f->path, strerror(saved != 0 ? saved : EIO));
        if (f->temp_path != NULL)
            remove(f->temp_path);
    }
    free(f->temp_path);
    free(f->target);
    *f = (struct outfile){0};
    return ok;
}

bool outfile_can_create(const char *path, char *err, size_t err_size) {
    if (strcmp(path, "-") == 0)
        return true;
    struct outfile f = {.path = path, .target = follow_links(path)};
    struct stat info;
    bool exists = f.target != NULL && stat(f.target, &info) == 0;
    if (exists && !S_ISREG(info.st_mode) && !S_ISDIR(info.st_mode)) { /* written directly */
        free(f.target);
        return true;
    }
    errno = f.target == NULL ? ENOMEM : is_link(f.target) ? ELOOP : exists && S_ISDIR(info.st_mode) ? EISDIR : 0;
    if (errno == 0 && (f.file = open_temporary(&f)) != NULL) {
        outfile_abandon(&f);
        return true;
    }
    snprintf(err, err_size, "%s: cannot create: %s", path, strerror(errno));
    free(f.target);
    return false;
}

void outfile_abandon(struct outfile *f) {
    fclose(f->file);
    if (f->temp_path != NULL)
        remove(f->temp_path);
    free(f->temp_path);
    free(f->target);
    *f = (struct outfile){0};
}

bool outfile_name_fits(const char *path) {
    const char *slash = strrchr(path, '/');
    size_t base = strlen(slash != NULL ? slash + 1 : path);
    size_t suffix = strlen(OUTFILE_TEMP_SUFFIX);
    return strcmp(path, "-") == 0 || (strlen(path) + suffix < PATH_MAX && base + suffix <= NAME_MAX);
}

/* Returns a new string naming `path` with its links followed and its folder made absolute (when the
 * folder exists), or NULL when memory runs out. */
static char *canonical_name(const char *path) {
    char *target = follow_links(path);
    if (target == NULL)
        return NULL;
    char *slash = strrchr(target, '/');
    const char *base = slash != NULL ? slash + 1 : target;
    if (slash != NULL)
        *slash = '\0';
    char folder[PATH_MAX];
    if (realpath(slash == NULL ? "." : slash == target ? "/" : target, folder) == NULL) {
        if (slash != NULL)
            *slash = '/';
        return target;
    }
    size_t size = strlen(folder) + strlen(base) + 2;
    char *joined = malloc(size);
    if (joined != NULL)
        snprintf(joined, size, "%s/%s", folder, base);
    free(target);
    return joined;
}

/* stat, with "-" meaning standard output. */
static int stat_name(const char *path, struct stat *info) {
    return strcmp(path, "-") == 0 ? fstat(stdout_fd, info) : stat(path, info);
}

bool outfile_same_file(const char *a, const char *b) {
    if (strcmp(a, b) == 0)
        return true;
    struct stat info_a, info_b;
    bool exists_a = stat_name(a, &info_a) == 0, exists_b = stat_name(b, &info_b) == 0;
    if (exists_a && exists_b)
        return info_a.st_dev == info_b.st_dev && info_a.st_ino == info_b.st_ino;
    if (exists_a || exists_b || strcmp(a, "-") == 0 || strcmp(b, "-") == 0)
        return false;
    char *name_a = canonical_name(a), *name_b = canonical_name(b);
    bool same = name_a != NULL && name_b != NULL && strcmp(name_a, name_b) == 0;
    free(name_a);
    free(name_b);
    return same;
}

/* A name of an outfile_index that exists: its file, and where the name is in the list given. */
struct outfile_index_file {
    dev_t device;
    ino_t inode;
    size_t position;
};

/* A name of an outfile_index as text, and where it is in the list given. */
struct outfile_index_name {
    const char *text; /* borrowed from the caller's list, or `owned` */
    char *owned;      /* a resolved name, which the index frees; NULL for the caller's */
    size_t position;
};

/* Orders files by device, inode, then position: the first of equal files is the first in the list. */
static int compare_index_files(const void *a, const void *b) {
    const struct outfile_index_file *x = a, *y = b;
    if (x->device != y->device)
        return x->device < y->device ? -1 : 1;
    if (x->inode != y->inode)
        return x->inode < y->inode ? -1 : 1;
    return x->position < y->position ? -1 : x->position > y->position;
}

/* Orders names by their text, then position: the first of equal names is the first in the list. */
static int compare_index_names(const void *a, const void *b) {
    const struct outfile_index_name *x = a, *y = b;
    int order = strcmp(x->text, y->text);
    if (order != 0)
        return order;
    return x->position < y->position ? -1 : x->position > y->position;
}

/* The position of the first of the `count` sorted names whose text is `text`, or OUTFILE_INDEX_NONE. */
static size_t find_index_name(const struct outfile_index_name *names, size_t count, const char *text) {
    size_t low = 0, high = count; /* the first whose text is not before `text` is in [low, high] */
    while (low < high) {
        size_t middle = low + (high - low) / 2;
        if (strcmp(names[middle].text, text) < 0)
            low = middle + 1;
        else
            high = middle;
    }
    return low < count && strcmp(names[low].text, text) == 0 ? names[low].position : OUTFILE_INDEX_NONE;
}

/* The position of the first of the `count` sorted files that is `info`'s, or OUTFILE_INDEX_NONE. */
static size_t find_index_file(const struct outfile_index_file *files, size_t count, const struct stat *info) {
    struct outfile_index_file key = {info->st_dev, info->st_ino, 0}; /* before every position of that file */
    size_t low = 0, high = count;
    while (low < high) {
        size_t middle = low + (high - low) / 2;
        if (compare_index_files(&files[middle], &key) < 0)
            low = middle + 1;
        else
            high = middle;
    }
    return low < count && files[low].device == key.device && files[low].inode == key.inode ? files[low].position
                                                                                           : OUTFILE_INDEX_NONE;
}

bool outfile_index_build(struct outfile_index *index, const char *const *names, size_t count) {
    *index = (struct outfile_index){0};
    size_t slots = count > 0 ? count : 1;
    index->files = malloc(slots * sizeof *index->files);
    index->names = malloc(slots * sizeof *index->names);
    index->absent = malloc(slots * sizeof *index->absent);
    bool enough = index->files != NULL && index->names != NULL && index->absent != NULL;
    for (size_t k = 0; enough && k < count; k++) {
        if (names[k] == NULL)
            continue;
        index->names[index->name_count++] = (struct outfile_index_name){names[k], NULL, k};
        struct stat info;
        if (stat_name(names[k], &info) == 0) {
            index->files[index->file_count++] = (struct outfile_index_file){info.st_dev, info.st_ino, k};
        } else if (strcmp(names[k], "-") != 0) {
            char *resolved = canonical_name(names[k]);
            enough = resolved != NULL;
            if (enough)
                index->absent[index->absent_count++] = (struct outfile_index_name){resolved, resolved, k};
        }
    }
    if (!enough) {
        outfile_index_free(index);
        return false;
    }
    qsort(index->files, index->file_count, sizeof *index->files, compare_index_files);
    qsort(index->names, index->name_count, sizeof *index->names, compare_index_names);
    qsort(index->absent, index->absent_count, sizeof *index->absent, compare_index_names);
    return true;
}

size_t outfile_index_find(const struct outfile_index *index, const char *path) {
    /* outfile_same_file's rules: the same name; else both exist and are one file; else neither exists,
     * neither is "-", and their names resolved are the same. */
    size_t found = find_index_name(index->names, index->name_count, path), other = OUTFILE_INDEX_NONE;
    struct stat info;
    if (stat_name(path, &info) == 0) {
        other = find_index_file(index->files, index->file_count, &info);
    } else if (index->absent_count > 0 && strcmp(path, "-") != 0) {
        char *resolved = canonical_name(path);
        if (resolved != NULL)
            other = find_index_name(index->absent, index->absent_count, resolved);
        free(resolved);
    }
    return other < found ? other : found; /* OUTFILE_INDEX_NONE is after every position */
}

void outfile_index_free(struct outfile_index *index) {
    for (size_t k = 0; index->absent != NULL && k < index->absent_count; k++)
        free(index->absent[k].owned);
    free(index->files);
    free(index->names);
    free(index->absent);
    *index = (struct outfile_index){0};
}

bool outfile_reserve_stdout(void) {
    fflush(stdout);
    int fd = fcntl(STDOUT_FILENO, F_DUPFD_CLOEXEC, 3);
    if (fd < 0)
        return false;
    if (dup2(STDERR_FILENO, STDOUT_FILENO) < 0) {
        close(fd);
        return false;
    }
    stdout_fd = fd;
    return true;
}
