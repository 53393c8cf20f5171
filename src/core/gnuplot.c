// SPDX-License-Identifier: MIT
// Running gnuplot on a script (core: used by analysis and dem alike).
#include "core/gnuplot.h"

#include <stdio.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

int gf_gnuplot_run(const char *dir, const char *script)
{
    fflush(NULL); // the child must not repeat our buffered output
    pid_t pid = fork();
    if (pid < 0) return -1;
    if (pid == 0) {
        if (chdir(dir) != 0) _exit(126);
        execlp("gnuplot", "gnuplot", script, (char *)NULL);
        _exit(127);
    }
    int status;
    if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status)) return -1;
    return WEXITSTATUS(status) == 127 ? 1 : WEXITSTATUS(status) == 0 ? 0 : -1;
}
