/* outfile.c: write to a temporary file, then rename it into place (chapter 1). */
#include "outfile.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Permissions of finished files: mkstemp makes them private, but pictures are for everyone to read. */
#define OUTFILE_MODE 0644

bool outfile_open(struct outfile *f, const char *path, char *err, size_t err_size) {
    f->path = path;
    f->file = NULL;
    size_t size = strlen(path) + sizeof ".tmpXXXXXX";
    f->temp_path = malloc(size);
    if (f->temp_path == NULL) {
        snprintf(err, err_size, "%s: cannot create: out of memory", path);
        return false;
    }
    snprintf(f->temp_path, size, "%s.tmpXXXXXX", path);
    int fd = mkstemp(f->temp_path);
    if (fd >= 0) {
        fchmod(fd, OUTFILE_MODE);
        f->file = fdopen(fd, "wb");
    }
    if (f->file == NULL) {
        snprintf(err, err_size, "%s: cannot create: %s", path, strerror(errno));
        if (fd >= 0) {
            close(fd);
            remove(f->temp_path);
        }
        free(f->temp_path);
        f->temp_path = NULL;
        return false;
    }
    return true;
}

bool outfile_commit(struct outfile *f, char *err, size_t err_size) {
    errno = 0;
    bool ok = !ferror(f->file);
    ok = (fclose(f->file) == 0) && ok;
    ok = ok && rename(f->temp_path, f->path) == 0;
    if (!ok) {
        snprintf(err, err_size, "%s: cannot write: %s", f->path, errno ? strerror(errno) : "write error");
        remove(f->temp_path);
    }
    free(f->temp_path);
    f->temp_path = NULL;
    f->file = NULL;
    return ok;
}

void outfile_abandon(struct outfile *f) {
    fclose(f->file);
    remove(f->temp_path);
    free(f->temp_path);
    f->temp_path = NULL;
    f->file = NULL;
}
