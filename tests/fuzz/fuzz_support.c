// SPDX-License-Identifier: MIT
#include "fuzz.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

// TMPDIR (scripts/fuzz.sh points it at memory), else /dev/shm, else /tmp.
static const char *gf_fuzz_tmp(void)
{
    const char *dir = getenv("TMPDIR");
    if (!dir || !*dir) dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    return dir;
}

const char *gf_fuzz_file(const char *suffix, const uint8_t *data, size_t size)
{
    static char path[256];
    snprintf(path, sizeof path, "%s/gf-fuzz-%ld%s", gf_fuzz_tmp(), (long)getpid(), suffix);
    FILE *f = fopen(path, "wb");
    if (!f) return NULL;
    size_t w = size ? fwrite(data, 1, size, f) : 0;
    if (fclose(f) != 0 || w != size) return NULL;
    return path;
}

char *gf_fuzz_string(const uint8_t *data, size_t size)
{
    char *s = malloc(size + 1);
    if (!s) abort();
    if (size) memcpy(s, data, size);
    s[size] = '\0';
    return s;
}

// Removes the files of `dir` and, one level down, of its subdirectories
// (which stay: the next input may use them again).
static void gf_fuzz_empty(const char *dir, int depth)
{
    DIR *d = opendir(dir);
    if (!d) return;
    for (struct dirent *e; (e = readdir(d)) != NULL;) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        char path[512];
        struct stat sb;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        if (lstat(path, &sb) != 0) continue;
        if (S_ISDIR(sb.st_mode)) {
            if (depth == 0) gf_fuzz_empty(path, 1);
        } else {
            unlink(path);
        }
    }
    closedir(d);
}

const char *gf_fuzz_dir(void)
{
    static char path[256];
    snprintf(path, sizeof path, "%s/gf-fuzz-%ld.d", gf_fuzz_tmp(), (long)getpid());
    if (mkdir(path, 0700) != 0) gf_fuzz_empty(path, 0);
    struct stat sb;
    return stat(path, &sb) == 0 && S_ISDIR(sb.st_mode) ? path : NULL;
}

int gf_fuzz_dir_file(const char *dir, const char *name, const uint8_t *data, size_t size)
{
    char path[512];
    const char *slash = strchr(name, '/');
    if (slash) {
        snprintf(path, sizeof path, "%s/%.*s", dir, (int)(slash - name), name);
        mkdir(path, 0700);
    }
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (!f) return -1;
    size_t w = size ? fwrite(data, 1, size, f) : 0;
    return fclose(f) != 0 || w != size ? -1 : 0;
}
