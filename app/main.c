// SPDX-License-Identifier: MIT
// granflow CLI entry point (placeholder until the subcommands land).
#include <stdio.h>

#include "granflow/core.h"

int main(void)
{
    printf("granflow %s\n", gf_version());
    return 0;
}
