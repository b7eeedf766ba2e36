/* faultmesh io: the lexical layer of the TSurf reader and writer: lines,
 * tokens, integers and correctly rounded decimals, and the shortest
 * round-tripping decimal form of a double.
 *
 * Everything works on [p, end) ranges of the file buffer, which is not
 * NUL-terminated; a token ends at a space, a tab or the end of its line. */
#ifndef FM_TSURF_LEX_H
#define FM_TSURF_LEX_H

#include <stddef.h>
#include <stdint.h>

/* Longest accepted line, in bytes (without its terminator). */
#define FM_TSURF_MAX_LINE 1048576

/* Splits a buffer into lines ended by LF, CRLF or a lone CR (any mixture:
 * real files contain a stray CRLF among LF lines). */
typedef struct fm_lines {
    const char *p, *end;
    const char *nl, *cr; /* next '\n' / '\r' at or after p, or end */
    long line;           /* number of the line last returned */
} fm_lines;

void fm_lines_init(fm_lines *L, const char *buf, size_t len);
/* The next '\n' or '\r' at or after p, or end. */
const char *fm_lines_find(const char *p, const char *end, int c);

/* Returns 1 with the next line in [*s, *e), 0 at the end of the buffer,
 * -1 when the line is longer than FM_TSURF_MAX_LINE (L->line is its number).
 * Inline: it runs once per line of every file. */
static inline int fm_lines_next(fm_lines *L, const char **s, const char **e)
{
    if (L->p >= L->end)
        return 0;
    /* The next LF and the next CR are cached and only searched again once
     * passed: a file without CR pays one memchr per line, no byte loop. */
    if (L->nl < L->p)
        L->nl = fm_lines_find(L->p, L->end, '\n');
    if (L->cr < L->p)
        L->cr = fm_lines_find(L->p, L->end, '\r');
    const char *stop = L->nl < L->cr ? L->nl : L->cr;
    *s = L->p;
    *e = stop;
    L->line++;
    if (stop == L->end)
        L->p = L->end;
    else if (*stop == '\r' && stop + 1 < L->end && stop[1] == '\n')
        L->p = stop + 2;
    else
        L->p = stop + 1;
    return stop - *s > FM_TSURF_MAX_LINE ? -1 : 1;
}

static inline const char *fm_lex_skip_ws(const char *p, const char *end)
{
    while (p < end && (*p == ' ' || *p == '\t'))
        p++;
    return p;
}

static inline const char *fm_lex_token_end(const char *p, const char *end)
{
    while (p < end && *p != ' ' && *p != '\t')
        p++;
    return p;
}

/* Strips spaces and tabs at the end of [s, *e). */
static inline void fm_lex_rtrim(const char *s, const char **e)
{
    while (*e > s && ((*e)[-1] == ' ' || (*e)[-1] == '\t'))
        (*e)--;
}

static inline int fm_lex_is_digit(char c) { return (unsigned)(c - '0') < 10u; }

/* The general case of fm_lex_double: checks the syntax of the token at p
 * and converts it with strtod. */
const char *fm_lex_double_slow(const char *p, const char *end, double *out);

/* A decimal number at p: [sign] digits [. digits] [e|E [sign] digits],
 * ending at a space, tab or end. Returns the end of the token, or NULL when
 * the token is not such a number (this includes "nan" and "inf"). The value
 * is correctly rounded; it is infinite when the literal overflows.
 *
 * Inline fast path (Clinger): at most 19 digits, so the digits fit in a
 * uint64 without any check per digit; if they also fit in 53 bits and the
 * decimal exponent is within +-22, the digits and the power of ten are
 * both exact doubles and one multiplication or division rounds correctly.
 * Everything else (rare in real files) goes to fm_lex_double_slow. */
static inline const char *fm_lex_double(const char *p, const char *end, double *out)
{
    static const double pow10[23] = {
        1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
        1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
    };
    const char *q = p;
    int neg = 0;
    if (q < end && (*q == '-' || *q == '+'))
        neg = *q++ == '-';
    uint64_t m = 0; /* wraps harmlessly past 19 digits; then unused */
    const char *d0 = q;
    while (q < end && fm_lex_is_digit(*q))
        m = m * 10 + (uint64_t)(*q++ - '0');
    long ndig = q - d0, nfrac = 0;
    if (q < end && *q == '.') {
        const char *f0 = ++q;
        while (q < end && fm_lex_is_digit(*q))
            m = m * 10 + (uint64_t)(*q++ - '0');
        nfrac = q - f0;
        ndig += nfrac;
    }
    if (ndig == 0 || ndig > 19 || (q < end && *q != ' ' && *q != '\t') ||
        m > 9007199254740992ULL || nfrac > 22)
        return fm_lex_double_slow(p, end, out); /* exponent, long, or bad */
    double v = (double)m / pow10[nfrac];
    *out = neg ? -v : v;
    return q;
}

/* A non-negative decimal integer that fits in int64 at p, ending at a
 * space, tab or end. Returns the end of the token or NULL. */
static inline const char *fm_lex_int64(const char *p, const char *end, int64_t *out)
{
    const char *q = p;
    uint64_t v = 0;
    while (q < end && fm_lex_is_digit(*q))
        v = v * 10 + (uint64_t)(*q++ - '0');
    long n = q - p;
    if (n == 0 || (q < end && *q != ' ' && *q != '\t'))
        return NULL;
    if (n > 18) { /* may not fit: redo with checks */
        v = 0;
        for (q = p; q < end && fm_lex_is_digit(*q); q++) {
            unsigned d = (unsigned)(*q - '0');
            if (v > ((uint64_t)INT64_MAX - d) / 10)
                return NULL;
            v = v * 10 + d;
        }
    }
    *out = (int64_t)v;
    return q;
}

/* Writes the shortest decimal text that reads back as exactly x (finite)
 * into buf (at least 32 bytes), NUL-terminated; returns its length.
 * Values with few decimals come out in plain notation (521258.67969). */
size_t fm_format_double(char *buf, double x);

#endif
