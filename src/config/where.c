// SPDX-License-Identifier: MIT
// Where each key of a gf_config got its value (config/where.h): recorded by
// gf_config_load and gf_config_set, quoted by gf_config_validate and callers.
#include "config/where.h"

#include <stdio.h>
#include <string.h>

#include "core/error.h"

// where_origin_ of a key whose origin did not fit the table.
#define GF_WHERE_LOST 255

_Static_assert(GF_CONFIG_MAX_ORIGINS < GF_WHERE_LOST, "origin indices fit a byte");

static size_t gf_where_index(const gf_key *k) { return (size_t)(k - gf_keys); }

void gf_config_mark(gf_config *cfg, const gf_key *k, const char *origin, int line)
{
    size_t i = gf_where_index(k);
    if (i >= GF_CONFIG_MAX_KEYS) return;
    uint8_t slot = GF_WHERE_LOST;
    for (int j = 0; j < GF_CONFIG_MAX_ORIGINS; j++) {
        char *name = cfg->where_names_[j];
        if (!name[0]) snprintf(name, GF_PATH_MAX, "%s", origin);
        if (strncmp(name, origin, GF_PATH_MAX - 1) == 0) {
            slot = (uint8_t)(j + 1);
            break;
        }
    }
    cfg->where_origin_[i] = slot;
    cfg->where_line_[i] = line;
}

void gf_config_where_of(const gf_config *cfg, const gf_key *k, char *buf, size_t n)
{
    size_t i = gf_where_index(k);
    uint8_t slot = i < GF_CONFIG_MAX_KEYS ? cfg->where_origin_[i] : 0;
    if (slot == 0) snprintf(buf, n, "default");
    else if (slot > GF_CONFIG_MAX_ORIGINS) snprintf(buf, n, "set");
    else if (cfg->where_line_[i] > 0) snprintf(buf, n, "%s:%d", cfg->where_names_[slot - 1], (int)cfg->where_line_[i]);
    else snprintf(buf, n, "%s", cfg->where_names_[slot - 1]);
}

gf_status gf_config_where(const gf_config *cfg, const char *key, char *buf, size_t size)
{
    if (!cfg || !buf || size == 0) return gf_error_set(GF_ERR_PARAM, "gf_config_where: NULL config or empty buffer");
    const gf_key *k = gf_keys_lookup(&gf_config_keys, key, "gf_config_where");
    if (!k) return GF_ERR_PARAM;
    gf_config_where_of(cfg, k, buf, size);
    return GF_OK;
}

const char *gf_config_where_lead(const gf_config *cfg, const char *key, char *buf, size_t size)
{
    if (!buf || size == 0) return buf;
    buf[0] = '\0';
    char where[GF_PATH_MAX + 32];
    if (gf_config_is_set(cfg, key) && gf_config_where(cfg, key, where, sizeof where) == GF_OK)
        snprintf(buf, size, "%s: ", where);
    return buf;
}

bool gf_config_is_set(const gf_config *cfg, const char *key)
{
    const char *dot = key ? strchr(key, '.') : NULL;
    if (!cfg || !dot) return false;
    char section[64];
    size_t len = (size_t)(dot - key);
    if (len >= sizeof section) return false;
    memcpy(section, key, len);
    section[len] = '\0';
    const gf_key *k = gf_keys_find(&gf_config_keys, section, dot + 1);
    size_t i = k ? gf_where_index(k) : GF_CONFIG_MAX_KEYS;
    return i < GF_CONFIG_MAX_KEYS && cfg->where_origin_[i] != 0;
}

// "section.name = value" of `key` into buf, with " (WHERE)" unless WHERE is `lead`.
static void gf_config_msg_key(const gf_config *cfg, const gf_key *k, const char *lead, char *buf, size_t n)
{
    char val[GF_PATH_MAX + 64], where[GF_PATH_MAX + 32];
    gf_keys_format(k, cfg, val, sizeof val);
    gf_config_where_of(cfg, k, where, sizeof where);
    int w = strcmp(where, lead) == 0 ? snprintf(buf, n, "%s.%s = %s", k->section, k->name, val)
                                     : snprintf(buf, n, "%s.%s = %s (%s)", k->section, k->name, val, where);
    if (w >= (int)n && n > 4) memcpy(buf + n - 4, "...", 4); // a path that long is cut, visibly
}

// The key named "section.name" (which must exist).
static const gf_key *gf_config_msg_find(const char *key)
{
    char section[64];
    const char *dot = strchr(key, '.');
    size_t len = (size_t)(dot - key);
    memcpy(section, key, len);
    section[len] = '\0';
    return gf_keys_find(&gf_config_keys, section, dot + 1);
}

bool gf_config_same_origin(const gf_config *cfg, const char *a, const char *b)
{
    size_t i = gf_where_index(gf_config_msg_find(a)), j = gf_where_index(gf_config_msg_find(b));
    uint8_t oa = cfg->where_origin_[i], ob = cfg->where_origin_[j];
    return oa != 0 && oa == ob && oa != GF_WHERE_LOST;
}

void gf_config_msg_make(gf_config_msg *m, const gf_config *cfg, const char *a, const char *b)
{
    const gf_key *k[2] = {gf_config_msg_find(a), b ? gf_config_msg_find(b) : NULL};
    char where[GF_PATH_MAX + 32] = "";
    for (int j = 0; j < 2 && !where[0]; j++) {
        if (!k[j]) continue;
        gf_config_where_of(cfg, k[j], where, sizeof where);
        if (strcmp(where, "default") == 0) where[0] = '\0';
    }
    if (where[0]) snprintf(m->lead, sizeof m->lead, "%s: ", where);
    else m->lead[0] = '\0';
    for (int j = 0; j < 2; j++) {
        m->key[j][0] = '\0';
        if (k[j]) gf_config_msg_key(cfg, k[j], where, m->key[j], sizeof m->key[j]);
    }
}
