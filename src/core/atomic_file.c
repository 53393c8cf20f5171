// SPDX-License-Identifier: MIT
#include "core/atomic_file.h"

#include <errno.h>
#include <string.h>

#include "core/error.h"

gf_status gf_atomic_open(const char *path, char *tmp, size_t n, FILE **out)
{
    *out = NULL;
    if (snprintf(tmp, n, "%s.tmp", path) >= (int)n)
        return gf_error_set(GF_ERR_PARAM, "cannot write %s: path too long", path);
    *out = fopen(tmp, "wb");
    if (!*out)
        return gf_error_set(GF_ERR_IO, "cannot write %s: cannot create '%s': %s", path, tmp, strerror(errno));
    return GF_OK;
}

gf_status gf_atomic_commit(FILE *f, const char *tmp, const char *path)
{
    int err = 0;
    if (ferror(f) || fflush(f) != 0) err = errno ? errno : EIO;
    if (fclose(f) != 0 && !err) err = errno ? errno : EIO;
    if (err) {
        remove(tmp);
        return gf_error_set(GF_ERR_IO, "cannot write '%s': %s", tmp, strerror(err));
    }
    if (rename(tmp, path) != 0) {
        err = errno;
        remove(tmp);
        return gf_error_set(GF_ERR_IO, "cannot rename '%s' to '%s': %s", tmp, path, strerror(err));
    }
    return GF_OK;
}

void gf_atomic_abort(FILE *f, const char *tmp)
{
    fclose(f);
    remove(tmp);
}
