// SPDX-License-Identifier: MIT
// Fuzz target: the readers of `granflow report` (src/report/html.c): the
// input as a flat JSON file (summary.json's table), as a CSV file (the
// comparison tables) and as a text file (config.ini in <pre>), each written
// out as HTML (keys in words, numbers to 4 digits), which must have no
// unescaped '<' of the input.
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz.h"
#include "report/html.h"

// The HTML written, in memory.
static char *gf_fuzz_html(int which, const char *path, size_t *len)
{
    char *buf = NULL;
    FILE *out = open_memstream(&buf, len);
    if (!out) abort();
    bool found;
    if (which == 0) gf_html_json_table(out, path, &found);
    else if (which == 1) gf_html_csv_table(out, path, 100, &found);
    else gf_html_pre_file(out, path, &found);
    fclose(out);
    return buf;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = gf_fuzz_file(".txt", data, size);
    if (!path) return 0;
    for (int which = 0; which < 3; which++) {
        size_t len = 0;
        char *html = gf_fuzz_html(which, path, &len);
        // Every '<' written opens one of the writer's own tags.
        static const char *const tags[] = {"<table", "</table", "<tr>",   "</tr>",  "<th>",  "</th>",
                                           "<td>",   "<td class=\"num\">", "</td>", "<code>", "</code>",
                                           "<sup>",  "</sup>",  "<pre>",  "</pre>"};
        for (const char *lt = html; (lt = memchr(lt, '<', len - (size_t)(lt - html))) != NULL; lt++) {
            int known = 0;
            for (size_t t = 0; t < sizeof tags / sizeof tags[0] && !known; t++)
                known = strncmp(lt, tags[t], strlen(tags[t])) == 0;
            if (!known) abort();
        }
        free(html);
    }
    return 0;
}
