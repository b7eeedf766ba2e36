/* Pieces shared by the benchmarks: the clock (fm_clock.h) and the list of .ts files of a
 * folder, in name order so that runs are comparable. */
#ifndef FM_BENCH_COMMON_H
#define FM_BENCH_COMMON_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include "fm_clock.h"

/* CPU seconds of this process, all threads, user + system: on a shared
 * machine wall time also counts other processes' turns. */
static inline double bench_cpu_seconds(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
           (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
}

/* CPU seconds of the calling thread: what a single-threaded stage costs,
 * whatever else the machine runs meanwhile. */
static inline double bench_thread_cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int bench_by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The .ts files directly in dir, sorted; -1 if the folder cannot be read
 * or memory runs out. */
static inline int bench_list_ts(const char *dir, char ***out, size_t *count)
{
    DIR *d = opendir(dir);
    if (!d)
        return -1;
    char **paths = NULL;
    size_t n = 0, cap = 0;
    int rc = 0;
    struct dirent *de;
    while (rc == 0 && (de = readdir(d)) != NULL) {
        size_t len = strlen(de->d_name);
        if (len < 4 || strcmp(de->d_name + len - 3, ".ts") != 0)
            continue;
        if (n == cap) {
            cap = cap ? 2 * cap : 512;
            char **np = realloc(paths, cap * sizeof *np);
            if (!np) {
                rc = -1;
                break;
            }
            paths = np;
        }
        size_t m = strlen(dir) + len + 2;
        paths[n] = malloc(m);
        if (!paths[n]) {
            rc = -1;
            break;
        }
        snprintf(paths[n++], m, "%s/%s", dir, de->d_name);
    }
    closedir(d);
    if (n > 1)
        qsort(paths, n, sizeof *paths, bench_by_name);
    *out = paths;
    *count = n;
    return rc;
}

#endif
