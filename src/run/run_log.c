/* The caller's callbacks of a run: log records and progress events, one
 * call at a time whatever thread they come from, and the cancel flag a
 * progress callback or fm_run_interrupt sets. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "run_internal.h"

run_ctl *run_ctl_create(void)
{
    run_ctl *c = calloc(1, sizeof *c);
    if (!c)
        return NULL;
    if (pthread_mutex_init(&c->lock, NULL)) {
        free(c);
        return NULL;
    }
    atomic_init(&c->cancelled, 0);
    c->log_max = FM_LOG_INFO;
    return c;
}

void run_ctl_destroy(run_ctl *c)
{
    if (!c)
        return;
    pthread_mutex_destroy(&c->lock);
    free(c);
}

int run_log_wants(const run_ctl *c, fm_log_level level)
{
    return c && c->log && level <= c->log_max;
}

void run_log(run_ctl *c, fm_log_level level, const char *fmt, ...)
{
    if (!run_log_wants(c, level))
        return;
    char buf[1024], *text = buf;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    /* a long record (a fault's line and its warnings, a long path) whole */
    if (n >= (int)sizeof buf && (text = malloc((size_t)n + 1)) != NULL) {
        va_start(ap, fmt);
        vsnprintf(text, (size_t)n + 1, fmt, ap);
        va_end(ap);
    }
    if (!text)
        text = buf;
    pthread_mutex_lock(&c->lock);
    c->log(c->log_user, level, text);
    pthread_mutex_unlock(&c->lock);
    if (text != buf)
        free(text);
}

static void tell(run_ctl *c, const fm_progress *p)
{
    if (!c || !c->progress)
        return;
    pthread_mutex_lock(&c->lock);
    int stop = c->progress(c->progress_user, p);
    pthread_mutex_unlock(&c->lock);
    if (stop)
        atomic_store(&c->cancelled, 1);
}

void run_progress_begin(run_ctl *c, const char *stage, size_t count, const char *unit,
                    double weight)
{
    fm_progress p = {FM_PROGRESS_BEGIN, stage, 0, count, unit, weight};
    tell(c, &p);
}

void run_progress_step(run_ctl *c, double weight)
{
    fm_progress p = {FM_PROGRESS_STEP, NULL, 0, 0, NULL, weight};
    tell(c, &p);
}

void run_progress_set(run_ctl *c, size_t done, size_t count, const char *unit)
{
    fm_progress p = {FM_PROGRESS_SET, NULL, done, count, unit, 0};
    tell(c, &p);
}

void run_progress_end(run_ctl *c)
{
    fm_progress p = {FM_PROGRESS_END, NULL, 0, 0, NULL, 0};
    tell(c, &p);
}

int run_cancelled(run_ctl *c)
{
    return c && atomic_load(&c->cancelled);
}
