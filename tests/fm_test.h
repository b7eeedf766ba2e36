/* A plain test harness: CHECK macros that count failures and a runner that
 * prints one summary line ("N passed, N failed") for CTest logs. A test
 * binary exits 0 when all checks pass, 1 otherwise, 77 when it skips. */
#ifndef FM_TEST_H
#define FM_TEST_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int fm_test_failed_checks;

#define CHECK(cond)                                                                  \
    do {                                                                             \
        if (!(cond)) {                                                               \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
            fm_test_failed_checks++;                                                 \
        }                                                                            \
    } while (0)

#define CHECK_EQ(a, b)                                                                  \
    do {                                                                                \
        long long fm_a_ = (long long)(a), fm_b_ = (long long)(b);                       \
        if (fm_a_ != fm_b_) {                                                           \
            fprintf(stderr, "%s:%d: CHECK_EQ failed: %s == %s (%lld vs %lld)\n",        \
                    __FILE__, __LINE__, #a, #b, fm_a_, fm_b_);                          \
            fm_test_failed_checks++;                                                    \
        }                                                                               \
    } while (0)

#define CHECK_NEAR(a, b, tol)                                                          \
    do {                                                                               \
        double fm_a_ = (double)(a), fm_b_ = (double)(b);                               \
        if (!(fabs(fm_a_ - fm_b_) <= (tol))) {                                         \
            fprintf(stderr, "%s:%d: CHECK_NEAR failed: %s ~ %s (%.17g vs %.17g)\n",    \
                    __FILE__, __LINE__, #a, #b, fm_a_, fm_b_);                         \
            fm_test_failed_checks++;                                                   \
        }                                                                              \
    } while (0)

#define CHECK_STR(a, b)                                                                \
    do {                                                                               \
        const char *fm_a_ = (a), *fm_b_ = (b);                                         \
        if (!fm_a_ || !fm_b_ || strcmp(fm_a_, fm_b_) != 0) {                           \
            fprintf(stderr, "%s:%d: CHECK_STR failed: %s == %s (\"%s\" vs \"%s\")\n",  \
                    __FILE__, __LINE__, #a, #b, fm_a_ ? fm_a_ : "(null)",              \
                    fm_b_ ? fm_b_ : "(null)");                                         \
            fm_test_failed_checks++;                                                   \
        }                                                                              \
    } while (0)

typedef struct fm_test_case {
    const char *name;
    void (*fn)(void);
} fm_test_case;

/* The whole file, NUL-terminated (malloc'ed; NULL if it cannot be read);
 * *len (if not NULL) gets its size. */
static inline char *fm_test_read_file(const char *path, size_t *len)
{
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return NULL;
    char *buf = NULL;
    long n = -1;
    if (fseek(fp, 0, SEEK_END) == 0 && (n = ftell(fp)) >= 0 && fseek(fp, 0, SEEK_SET) == 0)
        buf = malloc((size_t)n + 1);
    if (buf && fread(buf, 1, (size_t)n, fp) != (size_t)n) {
        free(buf);
        buf = NULL;
    }
    fclose(fp);
    if (buf) {
        buf[n] = '\0';
        if (len)
            *len = (size_t)n;
    }
    return buf;
}

/* 1 when both files can be read and hold the same bytes. */
static inline int fm_test_same_file(const char *a, const char *b)
{
    size_t na = 0, nb = 0;
    char *x = fm_test_read_file(a, &na), *y = fm_test_read_file(b, &nb);
    int same = x && y && na == nb && memcmp(x, y, na) == 0;
    free(x);
    free(y);
    return same;
}

#define FM_TEST_SKIP 77

/* Runs the cases; returns the process exit status. */
static inline int fm_test_run(const fm_test_case *cases, size_t n)
{
    int passed = 0, failed = 0;
    for (size_t i = 0; i < n; i++) {
        int before = fm_test_failed_checks;
        cases[i].fn();
        if (fm_test_failed_checks == before) {
            passed++;
        } else {
            failed++;
            fprintf(stderr, "FAILED: %s\n", cases[i].name);
        }
    }
    printf("%d passed, %d failed\n", passed, failed);
    return failed ? 1 : 0;
}

#define FM_TEST_MAIN(...)                                                          \
    int main(void)                                                                 \
    {                                                                              \
        static const fm_test_case fm_cases_[] = {__VA_ARGS__};                     \
        return fm_test_run(fm_cases_, sizeof fm_cases_ / sizeof fm_cases_[0]);     \
    }
#define FM_CASE(fn) {#fn, fn}

#endif
