/* faultmesh CLI: an interrupted run (SIGINT, SIGTERM, SIGHUP) leaves no
 * temporary files. Outputs are renamed into place only when complete, so
 * no truncated file can appear under a real name anyway; the handler
 * removes the temporaries of writes in progress, then the signal ends the
 * process as it would have, so the parent sees which signal it was. */
#include <signal.h>
#include <stddef.h>

#include "cli.h"

static void on_signal(int sig)
{
    /* only async-signal-safe calls here: the writes go on in other threads */
    fm_remove_pending_files();
    /* SA_RESETHAND restored the default action; the signal, blocked while
     * this runs, is delivered again on return and ends the process */
    raise(sig);
}

void fm_cli_catch_signals(void)
{
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP};
    struct sigaction sa = {0};
    sa.sa_handler = on_signal;
    sa.sa_flags = SA_RESETHAND;
    sigemptyset(&sa.sa_mask);
    for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++)
        sigaddset(&sa.sa_mask, sigs[i]);
    for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++) {
        struct sigaction old;
        /* a signal ignored when we started (nohup, a background job of a
         * shell without job control) stays ignored */
        if (sigaction(sigs[i], NULL, &old) == 0 && old.sa_handler != SIG_IGN)
            sigaction(sigs[i], &sa, NULL);
    }
}
