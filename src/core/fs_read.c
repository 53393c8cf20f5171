// SPDX-License-Identifier: MIT
// Reading files that must be regular ones of bounded size (core/fs.h).
#include "core/fs.h"

#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/alloc.h"
#include "core/error.h"

static const char *gf_fs_kind(mode_t m)
{
    return S_ISFIFO(m)   ? "a FIFO"
           : S_ISCHR(m)  ? "a character device"
           : S_ISBLK(m)  ? "a block device"
           : S_ISDIR(m)  ? "a directory"
           : S_ISSOCK(m) ? "a socket"
                         : "not a file";
}

gf_status gf_fs_open_regular(const char *path, long long max_bytes, int *fd)
{
    *fd = -1;
    // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer.
    int f = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (f < 0) return gf_error_set(errno == ENOMEM ? GF_ERR_NOMEM : GF_ERR_IO, "cannot open %s: %s", path, strerror(errno));
    struct stat sb;
    if (fstat(f, &sb) != 0) {
        int e = errno;
        close(f);
        return gf_error_set(GF_ERR_IO, "cannot read %s: %s", path, strerror(e));
    }
    if (!S_ISREG(sb.st_mode)) {
        close(f);
        return gf_error_set(GF_ERR_IO, "%s: not a regular file (%s)", path, gf_fs_kind(sb.st_mode));
    }
    if (max_bytes > 0 && (long long)sb.st_size > max_bytes) {
        close(f);
        return gf_error_set(GF_ERR_FORMAT, "%s: %lld bytes, more than the %lld expected", path,
                            (long long)sb.st_size, max_bytes);
    }
    int flags = fcntl(f, F_GETFL);
    if (flags < 0 || fcntl(f, F_SETFL, flags & ~O_NONBLOCK) != 0) {
        int e = errno;
        close(f);
        return gf_error_set(GF_ERR_IO, "cannot read %s: %s", path, strerror(e));
    }
    *fd = f;
    return GF_OK;
}

gf_status gf_fs_read_all(const char *path, long long max_bytes, unsigned char **data, size_t *len, size_t *cap)
{
    *data = NULL;
    *len = *cap = 0;
    int fd;
    gf_status st = gf_fs_open_regular(path, max_bytes, &fd);
    if (st != GF_OK) return st;
    struct stat sb;
    if (fstat(fd, &sb) != 0 || sb.st_size < 0 || (unsigned long long)sb.st_size >= SIZE_MAX - 64) {
        close(fd);
        return gf_error_set(GF_ERR_IO, "cannot read %s: size unknown", path);
    }
    // One byte more than the size: reading it tells a file that grew since.
    size_t size = (size_t)sb.st_size + 1, n = 0;
    unsigned char *buf = gf_alloc(size + 1);
    if (!buf) {
        close(fd);
        return gf_error_set(GF_ERR_NOMEM, "%s: out of memory reading %zu bytes", path, size - 1);
    }
    while (n < size) {
        ssize_t got = read(fd, buf + n, size - n);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) {
            int e = errno;
            close(fd);
            gf_free(buf, size + 1);
            return gf_error_set(GF_ERR_IO, "%s: read error: %s", path, strerror(e));
        }
        if (got == 0) break;
        n += (size_t)got;
    }
    close(fd);
    if (n == size) {
        gf_free(buf, size + 1);
        return gf_error_set(GF_ERR_FORMAT, "%s: grew while it was read (another program writing it?)", path);
    }
    buf[n] = '\0';
    *data = buf;
    *len = n;
    *cap = size + 1;
    return GF_OK;
}
