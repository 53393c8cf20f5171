// SPDX-License-Identifier: MIT
// gf_config by name: a heap config and get/set of any key as text, so that
// bindings never depend on the layout of struct gf_config.
#include "granflow/config.h"

#include <stdio.h>
#include <string.h>

#include "config/keys.h"
#include "core/alloc.h"
#include "core/error.h"

gf_config *gf_config_create(void)
{
    gf_config *cfg = GF_NEW(gf_config, 1);
    if (!cfg) {
        gf_error_set(GF_ERR_NOMEM, "gf_config_create: out of memory");
        return NULL;
    }
    *cfg = gf_config_default();
    return cfg;
}

void gf_config_destroy(gf_config *cfg) { GF_DELETE(cfg, 1); }

gf_status gf_config_copy(gf_config *dst, const gf_config *src)
{
    if (!dst || !src) return gf_error_set(GF_ERR_PARAM, "gf_config_copy: NULL config");
    *dst = *src;
    return GF_OK;
}

gf_status gf_config_set_key(gf_config *cfg, const char *key, const char *value)
{
    if (!cfg) return gf_error_set(GF_ERR_PARAM, "gf_config_set_key: cfg is NULL");
    if (!value) return gf_error_set(GF_ERR_PARAM, "gf_config_set_key: value of '%s' is NULL", key ? key : "?");
    if (!gf_keys_lookup(&gf_config_keys, key, "gf_config_set_key")) return GF_ERR_PARAM;
    // One parser for every way a value arrives: the `section.key=value` path.
    size_t n = strlen(key) + strlen(value) + 2;
    char *assignment = gf_alloc(n);
    if (!assignment) return gf_error_set(GF_ERR_NOMEM, "gf_config_set_key: out of memory");
    snprintf(assignment, n, "%s=%s", key, value);
    gf_status st = gf_config_set(cfg, assignment, "gf_config_set_key");
    gf_free(assignment, n);
    return st;
}

gf_status gf_config_get_key(const gf_config *cfg, const char *key, char *buf, size_t size)
{
    return gf_keys_get(&gf_config_keys, cfg, key, buf, size, "gf_config_get_key");
}

size_t gf_config_key_count(void) { return gf_keys_count; }

gf_status gf_config_key_name(size_t i, char *buf, size_t size)
{
    return gf_keys_name(&gf_config_keys, i, buf, size, "gf_config_key_name");
}

const char *gf_config_key_doc(size_t i) { return i < gf_keys_count ? gf_keys[i].doc : NULL; }

const char *gf_config_key_default(size_t i) { return i < gf_keys_count ? gf_keys[i].def : NULL; }
