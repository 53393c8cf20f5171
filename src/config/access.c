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

// Splits "section.name" and finds its key; NULL (error set) when unknown.
static const gf_key *gf_config_key_lookup(const char *key, const char *fn)
{
    if (!key) {
        gf_error_set(GF_ERR_PARAM, "%s: key is NULL", fn);
        return NULL;
    }
    const char *dot = strchr(key, '.');
    char section[64];
    size_t len = dot ? (size_t)(dot - key) : 0;
    const gf_key *k = NULL;
    if (dot && len < sizeof section) {
        memcpy(section, key, len);
        section[len] = '\0';
        k = gf_keys_find(section, dot + 1);
    }
    if (!k) {
        char list[2048];
        if (dot && len < sizeof section && gf_keys_section_known(section)) {
            gf_keys_list(section, list, sizeof list);
            gf_error_set(GF_ERR_PARAM, "%s: unknown key '%s' (keys of [%s]: %s)", fn, key, section, list);
        } else {
            gf_keys_list(NULL, list, sizeof list);
            gf_error_set(GF_ERR_PARAM, "%s: unknown key '%s' (expected section.key; sections: %s)", fn,
                         key, list);
        }
    }
    return k;
}

gf_status gf_config_set_key(gf_config *cfg, const char *key, const char *value)
{
    if (!cfg) return gf_error_set(GF_ERR_PARAM, "gf_config_set_key: cfg is NULL");
    if (!value) return gf_error_set(GF_ERR_PARAM, "gf_config_set_key: value of '%s' is NULL", key ? key : "?");
    if (!gf_config_key_lookup(key, "gf_config_set_key")) return GF_ERR_PARAM;
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
    if (!cfg || !buf || size == 0)
        return gf_error_set(GF_ERR_PARAM, "gf_config_get_key: NULL config or empty buffer");
    const gf_key *k = gf_config_key_lookup(key, "gf_config_get_key");
    if (!k) return GF_ERR_PARAM;
    char text[GF_PATH_MAX + 64];
    gf_keys_format(k, cfg, text, sizeof text);
    if (strlen(text) >= size)
        return gf_error_set(GF_ERR_PARAM, "gf_config_get_key: '%s' needs %zu bytes, buffer has %zu", key,
                            strlen(text) + 1, size);
    memcpy(buf, text, strlen(text) + 1);
    return GF_OK;
}

size_t gf_config_key_count(void) { return gf_keys_count; }

gf_status gf_config_key_name(size_t i, char *buf, size_t size)
{
    if (i >= gf_keys_count) return gf_error_set(GF_ERR_PARAM, "gf_config_key_name: index %zu >= %zu", i, gf_keys_count);
    if (!buf || size == 0) return gf_error_set(GF_ERR_PARAM, "gf_config_key_name: empty buffer");
    int w = snprintf(buf, size, "%s.%s", gf_keys[i].section, gf_keys[i].name);
    if (w < 0 || (size_t)w >= size) return gf_error_set(GF_ERR_PARAM, "gf_config_key_name: buffer too small");
    return GF_OK;
}

const char *gf_config_key_doc(size_t i) { return i < gf_keys_count ? gf_keys[i].doc : NULL; }

const char *gf_config_key_default(size_t i) { return i < gf_keys_count ? gf_keys[i].def : NULL; }
