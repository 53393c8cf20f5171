// SPDX-License-Identifier: MIT
#include "fuzz.h"

#include <dirent.h>
#include <stdbool.h>
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

// The scratch files and directory this process made, removed when it exits
// (they used to be left in /dev/shm by every replay, issue 26).
static char gf_fuzz_made[16][256];
static int gf_fuzz_nmade;
static char gf_fuzz_made_dir[256];
static void gf_fuzz_empty(const char *dir, int depth);

static void gf_fuzz_cleanup(void)
{
    for (int k = 0; k < gf_fuzz_nmade; k++) {
        unlink(gf_fuzz_made[k]);
        char tmp[300]; // what an atomic write into it may have left
        if (snprintf(tmp, sizeof tmp, "%s.tmp", gf_fuzz_made[k]) < (int)sizeof tmp) unlink(tmp); // never a cut name
    }
    if (gf_fuzz_made_dir[0]) {
        gf_fuzz_empty(gf_fuzz_made_dir, 0);
        DIR *d = opendir(gf_fuzz_made_dir); // its subdirectories, emptied above
        for (struct dirent *e; d && (e = readdir(d)) != NULL;) {
            if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
            char path[600];
            snprintf(path, sizeof path, "%s/%s", gf_fuzz_made_dir, e->d_name);
            rmdir(path);
        }
        if (d) closedir(d);
        rmdir(gf_fuzz_made_dir);
    }
}

// Notes a path made (once each) and registers the cleanup at the first.
static void gf_fuzz_note(const char *path, bool dir)
{
    static bool registered;
    if (!registered) registered = atexit(gf_fuzz_cleanup) == 0;
    if (dir) {
        snprintf(gf_fuzz_made_dir, sizeof gf_fuzz_made_dir, "%s", path);
        return;
    }
    for (int k = 0; k < gf_fuzz_nmade; k++)
        if (!strcmp(gf_fuzz_made[k], path)) return;
    if (gf_fuzz_nmade < 16) snprintf(gf_fuzz_made[gf_fuzz_nmade++], sizeof gf_fuzz_made[0], "%s", path);
}

const char *gf_fuzz_file(const char *suffix, const uint8_t *data, size_t size)
{
    static char path[256];
    snprintf(path, sizeof path, "%s/gf-fuzz-%ld%s", gf_fuzz_tmp(), (long)getpid(), suffix);
    gf_fuzz_note(path, false);
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
    gf_fuzz_note(path, true);
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
