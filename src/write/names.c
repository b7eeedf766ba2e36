/* File stems from fault names (fm_names.h). */
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
