/* File stems and short names from fault names (fm_names.h). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_names.h"

struct fm_namer {
    char **stem;
    size_t n, cap;
};

static int keep(unsigned char c)
{
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
           c == '.' || c == '-' || c == '_';
}

static int same_ignoring_case(const char *a, const char *b)
{
    for (; *a && *b; a++, b++) {
        char x = *a >= 'A' && *a <= 'Z' ? (char)(*a + 32) : *a;
        char y = *b >= 'A' && *b <= 'Z' ? (char)(*b + 32) : *b;
        if (x != y)
            return 0;
    }
    return *a == *b;
}

fm_namer *fm_namer_create(void)
{
    return calloc(1, sizeof(fm_namer));
}

void fm_namer_destroy(fm_namer *n)
{
    if (!n)
        return;
    for (size_t i = 0; i < n->n; i++)
        free(n->stem[i]);
    free(n->stem);
    free(n);
}

static int taken(const fm_namer *n, const char *s)
{
    for (size_t i = 0; i < n->n; i++)
        if (same_ignoring_case(n->stem[i], s))
            return 1;
    return 0;
}

const char *fm_namer_next(fm_namer *n, const char *name)
{
    char base[FM_STEM_MAX + 1];
    size_t k = 0;
    for (const char *c = name ? name : ""; *c && k < FM_STEM_MAX; c++) {
        if (keep((unsigned char)*c))
            base[k++] = *c;
        else if (c == name || keep((unsigned char)c[-1])) /* first of a run */
            base[k++] = '_';
    }
    base[k] = '\0';
    if (base[0] == '.')
        base[0] = '_';
    if (!k)
        snprintf(base, sizeof base, "fault");
    if (n->n == n->cap) {
        size_t cap = n->cap ? 2 * n->cap : 64;
        char **s = realloc(n->stem, cap * sizeof *s);
        if (!s)
            return NULL;
        n->stem = s;
        n->cap = cap;
    }
    /* base, "-" and a counter (at most 20 digits) */
    char *stem = malloc(FM_STEM_MAX + 24);
    if (!stem)
        return NULL;
    snprintf(stem, FM_STEM_MAX + 24, "%s", base);
    for (size_t i = 2; taken(n, stem); i++)
        snprintf(stem, FM_STEM_MAX + 24, "%s-%zu", base, i);
    n->stem[n->n++] = stem;
    return stem;
}

char *fm_section_name(const char *name)
{
    size_t n = strlen(name);
    char *s = malloc(n + 2);
    if (!s)
        return NULL;
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        if (keep((unsigned char)name[i]))
            s[k++] = name[i];
        else if (i == 0 || keep((unsigned char)name[i - 1])) /* first of a run */
            s[k++] = '_';
    }
    if (!k)
        s[k++] = '_';
    s[k] = 0;
    return s;
}

static uint32_t fnv1a(const char *s)
{
    uint32_t h = 2166136261u;
    for (; *s; s++)
        h = (h ^ (unsigned char)*s) * 16777619u;
    return h;
}

static int taken_exactly(char *const *names, size_t n, const char *s)
{
    for (size_t i = 0; i < n; i++)
        if (!strcmp(names[i], s))
            return 1;
    return 0;
}

void fm_short_names_free(char **s, size_t n)
{
    for (size_t i = 0; s && i < n; i++)
        free(s[i]);
    free(s);
}

char **fm_short_names(const char *const *names, size_t n, size_t max)
{
    if (max < 6)
        return NULL;
    char **out = calloc(n + 1, sizeof *out);
    for (size_t i = 0; out && i < n; i++) {
        char *t = fm_section_name(names[i] ? names[i] : "");
        if (!t) {
            fm_short_names_free(out, i);
            return NULL;
        }
        if (strlen(t) > max || taken_exactly(out, i, t)) {
            char *room = realloc(t, max + 1 > strlen(t) + 1 ? max + 1 : strlen(t) + 1);
            if (!room) {
                free(t);
                fm_short_names_free(out, i);
                return NULL;
            }
            t = room;
            const uint32_t span = 36u * 36u * 36u * 36u;
            uint32_t code = fnv1a(names[i] ? names[i] : "") % span;
            size_t cut = strlen(t) < max - 5 ? strlen(t) : max - 5;
            for (uint32_t k = 0; k < span; k++) {
                uint32_t c = (code + k) % span;
                char *p = t + cut;
                *p++ = '~';
                for (int d = 3; d >= 0; d--) {
                    uint32_t v = c;
                    for (int e = 0; e < d; e++)
                        v /= 36;
                    v %= 36;
                    *p++ = (char)(v < 10 ? '0' + v : 'a' + v - 10);
                }
                *p = 0;
                if (!taken_exactly(out, i, t))
                    break;
            }
        }
        out[i] = t;
    }
    return out;
}
