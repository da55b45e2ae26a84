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
    return current; /* a loop of links: opening it reports "Too many levels of symbolic links" */
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
    errno = f.target == NULL ? ENOMEM : exists && S_ISDIR(info.st_mode) ? EISDIR : 0;
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
