// SPDX-License-Identifier: MIT
// Running gnuplot on a script (core: used by analysis and dem alike).
#include "core/gnuplot.h"

#include <stdio.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

// gnuplot's own report of a failed script: its last line naming the script's
// line ("file" line N: what), else its last non-empty line.
static void gf_gnuplot_reason(const char *out, char *msg, size_t msgsize)
{
    const char *best = NULL, *last = NULL;
    size_t best_n = 0, last_n = 0;
    for (const char *p = out; *p;) {
        const char *e = strchr(p, '\n');
        size_t n = e ? (size_t)(e - p) : strlen(p);
        if (n > 0) {
            last = p, last_n = n;
            for (size_t i = 0; i + 6 <= n; i++)
                if (!memcmp(p + i, " line ", 6)) {
                    best = p, best_n = n;
                    break;
                }
        }
        p += n + (e != NULL);
    }
    if (!best) best = last, best_n = last_n;
    if (best) snprintf(msg, msgsize, "%.*s", (int)best_n, best);
}

int gf_gnuplot_run(const char *dir, const char *script, char *msg, size_t msgsize)
{
    if (msg && msgsize) msg[0] = '\0';
    int fd[2];
    if (pipe(fd) != 0) return -1;
    fflush(NULL); // the child must not repeat our buffered output
    pid_t pid = fork();
    if (pid < 0) {
        close(fd[0]);
        close(fd[1]);
        return -1;
    }
    if (pid == 0) {
        // gnuplot talks on stderr (warnings such as "empty y range" on a short
        // run): the library prints nothing, so the parent keeps it.
        close(fd[0]);
        dup2(fd[1], STDERR_FILENO);
        dup2(fd[1], STDOUT_FILENO);
        close(fd[1]);
        if (chdir(dir) != 0) _exit(126);
        execlp("gnuplot", "gnuplot", script, (char *)NULL);
        _exit(127);
    }
    close(fd[1]);
    char out[8192];
    size_t len = 0;
    for (;;) {
        char chunk[1024];
        ssize_t k = read(fd[0], chunk, sizeof chunk);
        if (k <= 0) break;
        // Keep the last sizeof out - 1 bytes: the failure is at the end.
        size_t n = (size_t)k;
        if (len + n >= sizeof out) {
            size_t drop = len + n - (sizeof out - 1);
            if (drop > len) drop = len;
            memmove(out, out + drop, len - drop);
            len -= drop;
            if (n > sizeof out - 1 - len) n = sizeof out - 1 - len;
        }
        memcpy(out + len, chunk, n);
        len += n;
    }
    out[len] = '\0';
    close(fd[0]);
    int status;
    if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status)) return -1;
    if (WEXITSTATUS(status) == 127) return 1;
    if (WEXITSTATUS(status) == 0) return 0;
    if (msg && msgsize) gf_gnuplot_reason(out, msg, msgsize);
    return -1;
}
