/* faultmesh CLI: progress of a long run on stderr (progress.h). */
#include "progress.h"

#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* The wall clock, monotonic: a stage's time and its ETA. */
static double clock_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#define BAR_WIDTH 28
/* Redrawing more often only costs a terminal time. */
#define REDRAW_S 0.1

struct progress {
    FILE *fp;
    progress_level level;
    int tty;
    pthread_mutex_t mu;
    char stage[40];
    const char *unit;
    size_t count, done;
    double weight, done_weight;
    double t0;      /* the ETA runs from here: when the count became known */
    double t_begin; /* the stage's start: "done in" is the whole stage, as the summary's times */
    double last_draw;
    int quarter; /* plain mode: the last quarter logged */
    /* tty: a thread that keeps the clock of a stage without steps moving */
    pthread_t ticker;
    pthread_cond_t wake;
    int ticking, stop;
};

progress *progress_create(FILE *fp, progress_level level, int force_plain)
{
    progress *p = calloc(1, sizeof *p);
    if (!p)
        return NULL;
    p->fp = fp;
    p->level = level;
    p->tty = !force_plain && isatty(fileno(fp));
    pthread_mutex_init(&p->mu, NULL);
    pthread_cond_init(&p->wake, NULL);
    return p;
}

void progress_destroy(progress *p)
{
    if (!p)
        return;
    pthread_cond_destroy(&p->wake);
    pthread_mutex_destroy(&p->mu);
    free(p);
}

static void clock_text(double s, char *buf, size_t n)
{
    long t = (long)(s + 0.5);
    if (t >= 3600)
        snprintf(buf, n, "%ld:%02ld:%02ld", t / 3600, t / 60 % 60, t % 60);
    else
        snprintf(buf, n, "%ld:%02ld", t / 60, t % 60);
}

/* The share done: by weight when there is one, else by count. */
static double share(const progress *p)
{
    if (p->weight > 0)
        return p->done_weight / p->weight < 1 ? p->done_weight / p->weight : 1;
    return p->count ? (double)p->done / (double)p->count : 0;
}

/* Caller holds the lock. */
static void draw(progress *p, double now)
{
    double f = share(p), el = now - p->t0;
    char eta[32] = "--:--", elapsed[32];
    clock_text(now - p->t_begin, elapsed, sizeof elapsed);
    /* the first few percent say little about the rest */
    if (f >= 0.03 && f < 1)
        clock_text(el * (1 - f) / f, eta, sizeof eta);
    if (p->count == 0) {
        fprintf(p->fp, "\r%-16s %s\033[K", p->stage, elapsed);
    } else {
        char bar[BAR_WIDTH + 1];
        int full = (int)(f * BAR_WIDTH + 0.5);
        for (int i = 0; i < BAR_WIDTH; i++)
            bar[i] = i < full ? '#' : '.';
        bar[BAR_WIDTH] = 0;
        fprintf(p->fp, "\r%-16s [%s] %zu/%zu %s %3.0f%%  %s  ETA %s\033[K", p->stage, bar,
                p->done, p->count, p->unit, 100 * f, elapsed, f < 1 ? eta : "0:00");
    }
    fflush(p->fp);
    p->last_draw = now;
}

/* Plain mode (a log, not a terminal): a line at each quarter, with its
 * ETA, once a stage has run a second (short stages need no interim
 * lines). Caller holds the lock. */
static void log_quarter(progress *p, double now)
{
    int q = (int)(4 * share(p));
    if (q > p->quarter && q < 4 && now - p->t_begin >= 1.0) {
        p->quarter = q;
        double f = share(p), el = now - p->t0;
        char eta[32];
        clock_text(el * (1 - f) / f, eta, sizeof eta);
        fprintf(p->fp, "faultmesh: %s: %zu/%zu %s, %.0f%%, ETA %s\n", p->stage, p->done,
                p->count, p->unit, 100 * f, eta);
    }
}

static void *tick(void *arg)
{
    progress *p = arg;
    pthread_mutex_lock(&p->mu);
    while (!p->stop) {
        struct timespec ts;
        clock_gettime(CLOCK_REALTIME, &ts);
        ts.tv_nsec += 500000000L;
        if (ts.tv_nsec >= 1000000000L) {
            ts.tv_sec++;
            ts.tv_nsec -= 1000000000L;
        }
        pthread_cond_timedwait(&p->wake, &p->mu, &ts);
        /* stages with a count redraw as they step */
        if (!p->stop && p->count == 0)
            draw(p, clock_seconds());
    }
    pthread_mutex_unlock(&p->mu);
    return NULL;
}

void progress_begin(progress *p, const char *stage, size_t count, const char *unit,
                    double weight)
{
    if (!p)
        return;
    pthread_mutex_lock(&p->mu);
    snprintf(p->stage, sizeof p->stage, "%s", stage);
    p->unit = unit ? unit : "";
    p->count = count;
    p->done = 0;
    p->weight = weight;
    p->done_weight = 0;
    p->quarter = 0;
    p->t0 = p->t_begin = clock_seconds();
    if (p->level != PROGRESS_QUIET) {
        if (p->tty)
            draw(p, p->t0);
        else if (count)
            fprintf(p->fp, "faultmesh: %s: %zu %s\n", p->stage, count, p->unit);
    }
    p->stop = 0;
    int start = p->tty && p->level != PROGRESS_QUIET && !p->ticking;
    pthread_mutex_unlock(&p->mu);
    if (start && pthread_create(&p->ticker, NULL, tick, p) == 0)
        p->ticking = 1;
}

void progress_step(progress *p, double weight)
{
    if (!p)
        return;
    pthread_mutex_lock(&p->mu);
    p->done++;
    p->done_weight += weight;
    if (p->level != PROGRESS_QUIET) {
        double now = clock_seconds();
        if (p->tty) {
            if (now - p->last_draw >= REDRAW_S || p->done == p->count)
                draw(p, now);
        } else if (p->count) {
            log_quarter(p, now);
        }
    }
    pthread_mutex_unlock(&p->mu);
}

void progress_set(progress *p, size_t done, size_t count, const char *unit)
{
    if (!p)
        return;
    pthread_mutex_lock(&p->mu);
    double now = clock_seconds();
    int known = p->count == 0 && count > 0;
    if (known) {
        /* the ETA runs from when the count is known */
        p->t0 = now;
        p->unit = unit ? unit : "";
        p->weight = 0;
    }
    p->count = count;
    p->done = done;
    if (p->level != PROGRESS_QUIET && p->tty && (now - p->last_draw >= REDRAW_S || done == count))
        draw(p, now);
    else if (p->level != PROGRESS_QUIET && !p->tty && known)
        fprintf(p->fp, "faultmesh: %s: %zu %s\n", p->stage, count, p->unit);
    else if (p->level != PROGRESS_QUIET && !p->tty)
        log_quarter(p, now);
    pthread_mutex_unlock(&p->mu);
}

double progress_end(progress *p)
{
    if (!p)
        return 0;
    if (p->ticking) {
        pthread_mutex_lock(&p->mu);
        p->stop = 1;
        pthread_cond_signal(&p->wake);
        pthread_mutex_unlock(&p->mu);
        pthread_join(p->ticker, NULL);
        p->ticking = 0;
    }
    pthread_mutex_lock(&p->mu);
    double now = clock_seconds(), el = now - p->t_begin;
    if (p->level != PROGRESS_QUIET) {
        if (p->tty) {
            fprintf(p->fp, "\r%-16s done in %.1f s", p->stage, el);
            if (p->count)
                fprintf(p->fp, " (%zu %s)", p->done, p->unit);
            fputs("\033[K\n", p->fp);
        } else {
            fprintf(p->fp, "faultmesh: %s: done in %.1f s", p->stage, el);
            if (p->count)
                fprintf(p->fp, " (%zu %s)", p->done, p->unit);
            fputc('\n', p->fp);
        }
        fflush(p->fp);
    }
    pthread_mutex_unlock(&p->mu);
    return el;
}
