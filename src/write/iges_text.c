/* IGES free-format parameters packed into fixed 80-column lines. */
#include "iges_internal.h"
#include "fm_dtoa.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* v right-aligned in `width` columns, wider when it needs more: printf's
 * %*ld, without its cost on the millions of lines of a whole-set
 * model.igs. */
static size_t put_long(char *out, long v, int width)
{
    char d[24];
    int n = 0;
    unsigned long u = v < 0 ? 0UL - (unsigned long)v : (unsigned long)v;
    do {
        d[n++] = (char)('0' + u % 10);
        u /= 10;
    } while (u);
    if (v < 0)
        d[n++] = '-';
    size_t k = 0;
    for (int i = n; i < width; i++)
        out[k++] = ' ';
    while (n)
        out[k++] = d[--n];
    return k;
}

/* The first `len` characters of data left-aligned in `width` columns (as
 * %-*s when len is data's length), then the letter and the sequence
 * number in 7 columns, and the line's end. */
static void put_record(FILE *fp, const char *data, size_t len, size_t width, const long *de,
                       char letter, long seq)
{
    char line[128 + 64];
    size_t k = 0;
    if (len > 128)
        len = 128; /* not reached: lines hold at most 72 */
    memcpy(line, data, len);
    k = len;
    while (k < width)
        line[k++] = ' ';
    if (de)
        k += put_long(line + k, *de, 8);
    line[k++] = letter;
    k += put_long(line + k, seq, 7);
    line[k++] = '\n';
    fwrite(line, 1, k, fp);
}

void iges_put_line(FILE *fp, const char *data, char letter, long seq)
{
    size_t len = 0;
    while (len < 72 && data[len])
        len++;
    put_record(fp, data, len, 72, NULL, letter, seq);
}

void iges_lines_init(iges_lines *l, FILE *fp, char letter, long first_seq)
{
    memset(l, 0, sizeof *l);
    l->fp = fp;
    l->letter = letter;
    l->width = letter == 'P' ? 64 : 72;
    l->seq = first_seq - 1;
}

static void flush(iges_lines *l)
{
    l->seq++;
    if (l->fp) {
        l->buf[l->len] = '\0';
        if (l->letter == 'P')
            put_record(l->fp, l->buf, l->len, 64, &l->de, 'P', l->seq);
        else
            iges_put_line(l->fp, l->buf, l->letter, l->seq);
    }
    l->len = 0;
}

static void append(iges_lines *l, const char *s, size_t n)
{
    memcpy(l->buf + l->len, s, n);
    l->len += n;
}

/* Characters [from, from + n) of the token a || b. */
static void append_part(iges_lines *l, const char *a, size_t na, const char *b, size_t from,
                        size_t n)
{
    for (size_t i = from; i < from + n; i++)
        l->buf[l->len++] = i < na ? a[i] : b[i - na];
}

/* Places the token a || b. Every placement leaves one column free, so the
 * delimiter that follows a parameter always lands on the parameter's own
 * line: readers split records at line ends and a line starting with a
 * delimiter would read as an extra defaulted parameter. Numbers never
 * break across lines; a string longer than a line continues on the next
 * ones, as IGES allows. */
static void place(iges_lines *l, const char *a, size_t na, const char *b, size_t nb,
                  int splittable)
{
    size_t w = (size_t)l->width, n = na + nb, done = 0;
    if (l->need_delim)
        append(l, ",", 1);
    l->need_delim = 1;
    if (l->len + n + 1 > w && (!splittable || n + 1 <= w))
        flush(l);
    if (l->len + n + 1 <= w) {
        append_part(l, a, na, b, 0, n);
        return;
    }
    while (done < n) {
        size_t left = n - done, space = w - l->len, take = left < space ? left : space;
        if (take == left && take + 1 > space)
            take--;
        append_part(l, a, na, b, done, take);
        done += take;
        if (done < n)
            flush(l);
    }
}

void iges_int(iges_lines *l, long long v)
{
    char t[32];
    int n = snprintf(t, sizeof t, "%lld", v);
    place(l, t, (size_t)n, "", 0, 0);
}

void iges_real(iges_lines *l, double v)
{
    char t[32];
    if (l->digits > 0 && l->digits < 17)
        iges_format_real_digits(v, l->digits, t);
    else
        iges_format_real(v, t);
    place(l, t, strlen(t), "", 0, 0);
}

void iges_format_quantum(double x, int quantum_exp, char *buf)
{
    static const double p10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                 1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    int k = quantum_exp < 0 ? -quantum_exp : quantum_exp;
    if (k > 22 || !isfinite(x)) {
        iges_format_real(x, buf);
        return;
    }
    /* multiples of the quantum as an integer: the caller keeps |x| below
     * 1e15 quanta, far inside long long */
    double q = quantum_exp < 0 ? x * p10[k] : x / p10[k];
    long long n = llround(q);
    if (n == 0) {
        strcpy(buf, "0.");
        return;
    }
    char d[48];
    int nd = 0;
    unsigned long long u = n < 0 ? 0ULL - (unsigned long long)n : (unsigned long long)n;
    while (u) {
        d[nd++] = (char)('0' + u % 10);
        u /= 10;
    }
    /* d holds the digits least significant first */
    size_t o = 0;
    if (n < 0)
        buf[o++] = '-';
    if (quantum_exp >= 0) {
        for (int i = nd - 1; i >= 0; i--)
            buf[o++] = d[i];
        for (int i = 0; i < quantum_exp; i++)
            buf[o++] = '0';
        buf[o++] = '.';
        buf[o] = '\0';
        return;
    }
    while (nd <= k)
        d[nd++] = '0'; /* at least one digit before the point */
    for (int i = nd - 1; i >= k; i--)
        buf[o++] = d[i];
    buf[o++] = '.';
    int first = 0; /* fraction digits d[k - 1] .. d[first], zeros at the end dropped */
    while (first < k && d[first] == '0')
        first++;
    for (int i = k - 1; i >= first; i--)
        buf[o++] = d[i];
    buf[o] = '\0';
}

void iges_real_quantum(iges_lines *l, double v, int quantum_exp)
{
    char t[48];
    iges_format_quantum(v, quantum_exp, t);
    place(l, t, strlen(t), "", 0, 0);
}

void iges_str(iges_lines *l, const char *s)
{
    size_t n = s ? strlen(s) : 0;
    char h[32] = "";
    int k = 0;
    if (n > 0)
        k = snprintf(h, sizeof h, "%zuH", n);
    place(l, h, (size_t)k, s ? s : "", n, 1);
}

void iges_end(iges_lines *l)
{
    append(l, ";", 1);
    l->need_delim = 0;
    flush(l);
}

/* The C library writes the locale's decimal point; IGES wants '.', an E
 * exponent without '+' or leading zeros, and a point in every real. */
static void normalise(const char *raw, char *out)
{
    size_t k = 0;
    int in_exp = 0, exp_digits = 0, has_point = 0, in_point = 0;
    for (const char *p = raw; *p; p++) {
        char c = *p;
        if (c >= '0' && c <= '9') {
            in_point = 0;
            if (in_exp && exp_digits == 0 && c == '0' && p[1] != '\0')
                continue;
            if (in_exp)
                exp_digits++;
            out[k++] = c;
        } else if (c == '-') {
            out[k++] = c;
        } else if (c == '+') {
            continue;
        } else if (c == 'e' || c == 'E') {
            if (!has_point)
                out[k++] = '.';
            has_point = 1;
            in_exp = 1;
            out[k++] = 'E';
        } else if (!in_point) {
            out[k++] = '.';
            has_point = in_point = 1;
        }
    }
    if (!has_point)
        out[k++] = '.';
    out[k] = '\0';
}

void iges_format_real(double x, char *buf)
{
    if (x == 0) {
        strcpy(buf, "0.");
        return;
    }
    /* the shortest of %.15g, %.16g and %.17g that reads back as x, as
     * every text writer prints it, without printf + strtod's cost (a
     * whole-set model.igs holds some ten million reals) */
    char raw[40];
    fm_format_double(raw, x);
    normalise(raw, buf);
}

/* Digits d of |x| scaled to an integer of exactly `digits` digits, and
 * the decimal exponent e of its first one: |x| ~ 0.d * 10^(e + 1). */
static int scaled_digits(double a, int digits, unsigned long long *q)
{
    static const double p10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,
                                 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19,
                                 1e20, 1e21, 1e22};
    const unsigned long long top = (unsigned long long)p10[digits];
    int e = (int)floor(log10(a));
    for (int tries = 0; tries < 3; tries++) {
        int k = digits - 1 - e;
        if (k > 22 || k < -22)
            return INT_MIN;
        double scaled = k >= 0 ? a * p10[k] : a / p10[-k];
        *q = (unsigned long long)llround(scaled);
        /* log10's floor can be one off near a power of ten, and rounding
         * can carry into a new digit */
        if (*q >= top)
            e++;
        else if (*q < top / 10)
            e--;
        else
            return e;
    }
    return INT_MIN;
}

void iges_format_real_digits(double x, int digits, char *buf)
{
    if (x == 0 || !isfinite(x)) {
        iges_format_real(x, buf);
        return;
    }
    unsigned long long q;
    int e = scaled_digits(fabs(x), digits, &q);
    if (e == INT_MIN || e < -6 || e >= digits) {
        char raw[40];
        snprintf(raw, sizeof raw, "%.*E", digits - 1, x);
        normalise(raw, buf);
        return;
    }
    char d[24];
    for (int i = digits - 1; i >= 0; i--, q /= 10)
        d[i] = (char)('0' + q % 10);
    size_t k = 0;
    if (x < 0)
        buf[k++] = '-';
    if (e < 0) {
        buf[k++] = '0';
        buf[k++] = '.';
        for (int i = -1; i > e; i--)
            buf[k++] = '0';
        for (int i = 0; i < digits; i++)
            buf[k++] = d[i];
    } else {
        for (int i = 0; i <= e; i++)
            buf[k++] = d[i];
        buf[k++] = '.';
        for (int i = e + 1; i < digits; i++)
            buf[k++] = d[i];
    }
    while (buf[k - 1] == '0')
        k--;
    buf[k] = '\0';
}

int iges_printable(const char *s)
{
    for (; s && *s; s++)
        if ((unsigned char)*s < 0x20 || (unsigned char)*s > 0x7e)
            return 0;
    return 1;
}
