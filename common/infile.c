/* infile.c: stat, open without blocking, fstat: input files are regular files or are refused (chapter 1). */
#include "infile.h"

#include <errno.h>
#include <fcntl.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Fails with "path: not a regular file (a ...)" unless `info` describes a regular file. */
static bool regular(const char *path, const struct stat *info, char *err, size_t err_size) {
    if (S_ISREG(info->st_mode))
        return true;
    const char *kind = S_ISDIR(info->st_mode) ? "a directory" : S_ISFIFO(info->st_mode) ? "a FIFO"
                     : S_ISCHR(info->st_mode) || S_ISBLK(info->st_mode) ? "a device"
                     : S_ISSOCK(info->st_mode) ? "a socket" : "not a file";
    snprintf(err, err_size, "%s: not a regular file (%s)", path, kind);
    return false;
}

FILE *infile_open(const char *path, char *err, size_t err_size) {
    struct stat info;
    if (stat(path, &info) != 0) {
        snprintf(err, err_size, "%s: cannot open: %s", path, strerror(errno));
        return NULL;
    }
    if (!regular(path, &info, err, err_size))
        return NULL;
    /* O_NONBLOCK: if a FIFO took the file's place since the stat, open returns at once instead of
     * waiting for a writer, and the fstat below refuses it. */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        snprintf(err, err_size, "%s: cannot open: %s", path, strerror(errno));
        return NULL;
    }
    FILE *file = NULL;
    if (fstat(fd, &info) != 0)
        snprintf(err, err_size, "%s: cannot open: %s", path, strerror(errno));
    else if (regular(path, &info, err, err_size)) {
        int flags = fcntl(fd, F_GETFL);
        if (flags >= 0)
            fcntl(fd, F_SETFL, flags & ~O_NONBLOCK); /* reads of a regular file never wait anyway */
        if ((file = fdopen(fd, "rb")) == NULL)
            snprintf(err, err_size, "%s: cannot open: %s", path, strerror(errno));
    }
    if (file == NULL)
        close(fd);
    return file;
}

unsigned char *infile_read_whole(const char *path, size_t max_bytes, size_t *size, char *err, size_t err_size) {
    FILE *file = infile_open(path, err, err_size);
    if (file == NULL)
        return NULL;
    long length = -1;
    if (fseek(file, 0, SEEK_END) == 0)
        length = ftell(file);
    rewind(file);
    unsigned char *bytes = NULL;
    if (length < 0)
        snprintf(err, err_size, "%s: cannot read", path);
    else if ((unsigned long)length > max_bytes)
        snprintf(err, err_size, "%s: larger than %zu bytes", path, max_bytes);
    else if ((bytes = malloc((size_t)length + 1)) == NULL)
        snprintf(err, err_size, "%s: out of memory", path);
    else if (fread(bytes, 1, (size_t)length, file) != (size_t)length) {
        snprintf(err, err_size, "%s: cannot read", path);
        free(bytes);
        bytes = NULL;
    }
    fclose(file);
    *size = bytes != NULL ? (size_t)length : 0;
    return bytes;
}
