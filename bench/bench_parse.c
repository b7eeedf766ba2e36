/* Parse throughput of the TSurf reader on a folder of .ts files.
 *
 *   bench_parse [-n REPEATS] [FOLDER]     (default FOLDER: the CFM 500 m set)
 *
 * Every file is read from disk and parsed REPEATS times (the first pass
 * warms the page cache and is not timed when REPEATS > 1). Prints the bytes
 * parsed, wall time on the monotonic clock, MB/s (10^6 bytes), files/s and
 * the time of one pass over the whole set. Any parse error aborts with the
 * reader's message and exit status 1. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "bench_common.h"
#include "fm_tsurf.h"

/* Parses every file once; returns bytes parsed or -1 on error. */
static long long pass(char **paths, size_t n, size_t *tris)
{
    long long bytes = 0;
    *tris = 0;
    for (size_t i = 0; i < n; i++) {
        fm_tsurf **objs;
        size_t nobj;
        fm_error err;
        if (fm_tsurf_read_file(paths[i], &objs, &nobj, &err) != FM_OK) {
            fprintf(stderr, "bench_parse: %s\n", err.message);
            return -1;
        }
        for (size_t k = 0; k < nobj; k++)
            *tris += fm_mesh_ntriangles(fm_tsurf_mesh(objs[k]));
        fm_tsurf_free_all(objs, nobj);
        struct stat sb;
        if (stat(paths[i], &sb) == 0)
            bytes += (long long)sb.st_size;
    }
    return bytes;
}

int main(int argc, char **argv)
{
    const char *dir = FM_CFM_DIR "/CFM5.3/500m";
    int repeats = 5;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-n") == 0 && i + 1 < argc)
            repeats = atoi(argv[++i]);
        else if (argv[i][0] == '-') {
            fprintf(stderr, "usage: bench_parse [-n REPEATS] [FOLDER]\n");
            return 2;
        } else
            dir = argv[i];
    }
    if (repeats < 1)
        repeats = 1;
    char **paths = NULL;
    size_t n = 0;
    if (bench_list_ts(dir, &paths, &n) != 0) {
        fprintf(stderr, "bench_parse: cannot read folder %s\n", dir);
        return 1;
    }
    if (n == 0) {
        fprintf(stderr, "bench_parse: no .ts file in %s\n", dir);
        return 1;
    }

    size_t tris = 0;
    if (repeats > 1 && pass(paths, n, &tris) < 0) /* warm-up */
        return 1;
    int timed = repeats > 1 ? repeats - 1 : 1;
    long long bytes = 0;
    double best = 1e300, t0 = fm_clock_seconds();
    for (int r = 0; r < timed; r++) {
        double t = fm_clock_seconds();
        long long b = pass(paths, n, &tris);
        if (b < 0)
            return 1;
        t = fm_clock_seconds() - t;
        if (t < best)
            best = t;
        bytes += b;
    }
    double secs = fm_clock_seconds() - t0;
    double mb = (double)bytes / 1e6;
    printf("folder      %s\n", dir);
    printf("files       %zu x %d passes (%zu triangles per pass)\n", n, timed, tris);
    printf("total       %.1f MB in %.3f s\n", mb, secs);
    printf("throughput  %.1f MB/s, %.0f files/s\n", mb / secs, (double)n * timed / secs);
    printf("whole set   %.3f s per pass (best %.3f s)\n", secs / timed, best);
    for (size_t i = 0; i < n; i++)
        free(paths[i]);
    free(paths);
    return 0;
}
