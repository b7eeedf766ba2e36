/* Bad-input corpus: every tests/data/bad/NAME.ts must fail to read with
 * exactly the message in NAME.expected (the text after "PATH:"), without
 * crashing or leaking (the sanitizer build checks the latter). */
#include <dirent.h>
#include <sys/stat.h>

#include "fm_atomic.h"
#include "fm_test.h"
#include "fm_tsurf.h"

#define BAD_DIR FM_TEST_DATA "/bad"

static int ncases;

static int read_text(const char *path, char *buf, size_t n)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    size_t k = fread(buf, 1, n - 1, f);
    fclose(f);
    buf[k] = '\0';
    while (k && (buf[k - 1] == '\n' || buf[k - 1] == '\r'))
        buf[--k] = '\0';
    return 0;
}

/* Reads path, which must fail with "path:" + expected. */
static void expect_failure(const char *path, const char *expected)
{
    fm_tsurf **objs = NULL;
    size_t n = 0;
    fm_error err;
    fm_error_clear(&err);
    fm_status s = fm_tsurf_read_file(path, &objs, &n, &err);
    CHECK(s != FM_OK);
    CHECK(objs == NULL && n == 0);
    fm_tsurf_free_all(objs, n);
    size_t plen = strlen(path);
    int prefixed = strncmp(err.message, path, plen) == 0 && err.message[plen] == ':';
    if (!prefixed || strcmp(err.message + plen + 1, expected) != 0) {
        fprintf(stderr, "%s:\n  expected: %s\n  got:      %s\n", path, expected, err.message);
        CHECK(0);
    }
    ncases++;
}

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static void test_corpus(void)
{
    DIR *d = opendir(BAD_DIR);
    CHECK(d != NULL);
    if (!d)
        return;
    char *names[512];
    size_t n = 0;
    struct dirent *de;
    while ((de = readdir(d)) != NULL && n < 512) {
        size_t len = strlen(de->d_name);
        if (len > 3 && strcmp(de->d_name + len - 3, ".ts") == 0) {
            names[n] = malloc(len + 1);
            if (names[n])
                memcpy(names[n++], de->d_name, len + 1);
        }
    }
    closedir(d);
    qsort(names, n, sizeof *names, by_name);
    for (size_t i = 0; i < n; i++) {
        char path[1024], exp_path[1024], expected[1024];
        snprintf(path, sizeof path, "%s/%s", BAD_DIR, names[i]);
        snprintf(exp_path, sizeof exp_path, "%s/%.*s.expected", BAD_DIR,
                 (int)(strlen(names[i]) - 3), names[i]);
        if (read_text(exp_path, expected, sizeof expected) != 0) {
            fprintf(stderr, "%s has no .expected file\n", path);
            CHECK(0);
        } else {
            expect_failure(path, expected);
        }
        free(names[i]);
    }
    /* Guard against an empty or lost corpus passing vacuously. */
    CHECK(ncases >= 30);
}

/* A line over 1 MiB, generated rather than committed. */
static void test_enormous_line(void)
{
    fm_error err;
    CHECK_EQ(fm_mkdir_p(FM_TMP_DIR, &err), FM_OK);
    const char *path = FM_TMP_DIR "/enormous_line.ts";
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL);
    if (!f)
        return;
    fputs("GOCAD TSurf 1\nHEADER {\nname:", f);
    for (int i = 0; i < (1 << 20) + 10; i++)
        fputc('a', f);
    fputs("\n}\nTFACE\nVRTX 1 0 0 0\nEND\n", f);
    fclose(f);
    expect_failure(path, "3: line longer than 1048576 bytes");
    /* Exactly at the limit is fine (and then fails later for another reason). */
    f = fopen(path, "wb");
    if (!f)
        return;
    fputs("GOCAD TSurf 1\n#", f);
    for (int i = 0; i < (1 << 20) - 1; i++)
        fputc('#', f);
    fputs("\nTFACE\nVRTX 1 0 0 0\nEND\n", f);
    fclose(f);
    expect_failure(path, "5: object #1 has no triangles");
}

static void test_missing_file(void)
{
    fm_tsurf **objs = NULL;
    size_t n = 0;
    fm_error err;
    CHECK_EQ(fm_tsurf_read_file(BAD_DIR "/does_not_exist.ts", &objs, &n, &err), FM_ERR_IO);
    CHECK(strstr(err.message, "does_not_exist.ts: cannot open") != NULL);
    CHECK_EQ(fm_tsurf_read_file(BAD_DIR, &objs, &n, &err), FM_ERR_IO);
}

/* Every prefix of a good file is either a clean error or (at full length)
 * a success: truncation anywhere must not crash. */
static void test_truncations(void)
{
    const char *text = "GOCAD TSurf 1\r\nHEADER {\r\nname:t\r\n}\r\nPROPERTIES a\r\nTFACE\r\n"
                       "PVRTX 1 0 0 0 1\r\nPVRTX 2 1 0 0 2\r\nATOM 3 2\r\nPVRTX 4 0 1 0 3\r\n"
                       "TRGL 1 3 4\r\nBSTONE 1\r\nBORDER 5 1 3\r\nEND\r\n";
    size_t len = strlen(text);
    int ok = 0;
    for (size_t k = 0; k <= len; k++) {
        char *copy = malloc(k ? k : 1); /* exact size: ASan sees over-reads */
        if (!copy)
            return;
        memcpy(copy, text, k);
        fm_tsurf **objs = NULL;
        size_t n = 0;
        fm_error err;
        fm_status s = fm_tsurf_read_buffer("t", copy, k, &objs, &n, &err);
        if (s == FM_OK)
            ok++;
        else
            CHECK(strncmp(err.message, "t:", 2) == 0);
        fm_tsurf_free_all(objs, n);
        free(copy);
    }
    /* Only the full text and the one missing its final line break (or
     * CR/LF) read successfully. */
    CHECK_EQ(ok, 3);
}

FM_TEST_MAIN(FM_CASE(test_corpus), FM_CASE(test_enormous_line), FM_CASE(test_missing_file),
             FM_CASE(test_truncations))
