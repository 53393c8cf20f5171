// SPDX-License-Identifier: MIT
// The file-system chores shared by every tool that writes a directory.
#include "core/fs.h"

#include <dirent.h>
#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "core/error.h"

#define GF_FS_PATH 4096  // longest path handled (PATH_MAX on Linux)
#define GF_FS_DEPTH 16   // deepest tree gf_fs_remove_tree descends into

static gf_status gf_fs_mkdir(const char *path)
{
    if (mkdir(path, 0777) == 0 || errno == EEXIST) {
        struct stat sb;
        if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode)) return GF_OK;
        return gf_error_set(GF_ERR_IO, "%s: exists and is not a directory", path);
    }
    return gf_error_set(GF_ERR_IO, "%s: cannot create directory: %s", path, strerror(errno));
}

gf_status gf_fs_mkdirs(const char *path)
{
    char buf[GF_FS_PATH];
    if (!path || !*path) return gf_error_set(GF_ERR_PARAM, "empty directory name");
    if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf)
        return gf_error_set(GF_ERR_PARAM, "path too long: %s", path);
    for (char *s = buf + 1; *s; s++) {
        if (*s != '/') continue;
        *s = '\0';
        gf_status st = gf_fs_mkdir(buf);
        *s = '/';
        if (st != GF_OK) return st;
    }
    return gf_fs_mkdir(buf);
}

gf_status gf_fs_remove(const char *path)
{
    if (remove(path) == 0 || errno == ENOENT) return GF_OK;
    return gf_error_set(GF_ERR_IO, "%s: cannot remove: %s", path, strerror(errno));
}

static gf_status gf_fs_remove_below(const char *path, int depth)
{
    struct stat sb;
    if (lstat(path, &sb) != 0) return errno == ENOENT ? GF_OK : gf_error_set(GF_ERR_IO, "%s: %s", path, strerror(errno));
    if (!S_ISDIR(sb.st_mode) || depth > GF_FS_DEPTH) return gf_fs_remove(path);
    DIR *d = opendir(path);
    if (!d) return gf_error_set(GF_ERR_IO, "%s: cannot open directory: %s", path, strerror(errno));
    gf_status st = GF_OK;
    for (struct dirent *e; st == GF_OK && (e = readdir(d)) != NULL;) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        char sub[GF_FS_PATH + 300];
        if (snprintf(sub, sizeof sub, "%s/%s", path, e->d_name) >= (int)sizeof sub)
            st = gf_error_set(GF_ERR_IO, "%s/%s: path too long to remove", path, e->d_name);
        else
            st = gf_fs_remove_below(sub, depth + 1);
    }
    closedir(d);
    return st == GF_OK ? gf_fs_remove(path) : st;
}

gf_status gf_fs_remove_tree(const char *path)
{
    return gf_fs_remove_below(path, 0);
}

gf_status gf_fs_clear(const char *dir, const char *prefix, const char *const *suffixes, size_t nsuffix)
{
    DIR *d = opendir(dir);
    if (!d) return GF_OK;
    size_t np = strlen(prefix);
    gf_status st = GF_OK;
    for (struct dirent *e; (e = readdir(d)) != NULL;) {
        size_t n = strlen(e->d_name);
        if (strncmp(e->d_name, prefix, np) != 0) continue;
        bool match = false;
        for (size_t i = 0; !match && i < nsuffix; i++) {
            size_t ns = strlen(suffixes[i]);
            match = n >= np + ns && strcmp(e->d_name + n - ns, suffixes[i]) == 0;
        }
        if (!match) continue;
        char path[GF_FS_PATH + 300];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        gf_status s = gf_fs_remove(path);
        if (st == GF_OK) st = s;
    }
    closedir(d);
    return st;
}
