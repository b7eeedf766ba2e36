/* fm_atomic (src/core/atomic_file.c): a file appears under its name only
 * when committed, its temporary is hidden and named after it, and
 * fm_atomic_remove_pending removes the temporaries of writes in progress,
 * from a signal handler too, after which new writes fail and leave
 * nothing. The cases that call it run last (it cannot be undone) or in a
 * child process. */
#include <dirent.h>
#include <pthread.h>
#include <stdint.h>
#include <time.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "fm_atomic.h"
#include "fm_test.h"

static char dir[512];

static void path_of(char *buf, size_t n, const char *name)
{
    snprintf(buf, n, "%s/%s", dir, name);
}

/* Entries of dir (but . and ..) whose name contains part; total in *all. */
static int count_entries(const char *part, int *all)
{
    int n = 0, total = 0;
    DIR *d = opendir(dir);
    struct dirent *e;
    while (d && (e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        total++;
        n += strstr(e->d_name, part) != NULL;
    }
    if (d)
        closedir(d);
    if (all)
        *all = total;
    return n;
}

static void clear_dir(void)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    char p[1024];
    while (d && (e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        unlink(p);
    }
    if (d)
        closedir(d);
}

static void test_commit(void)
{
    clear_dir();
    char p[1024];
    path_of(p, sizeof p, "out.txt");
    fm_error err;
    fm_error_clear(&err);
    fm_atomic_file *f = fm_atomic_open(p, &err);
    CHECK(f != NULL);
    if (!f)
        return;
    fputs("hello\n", fm_atomic_stream(f));
    /* while written: only the hidden temporary, named after the output */
    int all;
    CHECK_EQ(count_entries(".out.txt.tmp.", &all), 1);
    CHECK_EQ(all, 1);
    CHECK(access(p, F_OK) != 0);
    CHECK_EQ(fm_atomic_commit(f, &err), FM_OK);
    size_t n = 0;
    char *text = fm_test_read_file(p, &n);
    CHECK_STR(text, "hello\n");
    free(text);
    CHECK_EQ(count_entries(".tmp.", &all), 0);
    CHECK_EQ(all, 1);
    /* an ordinary file for the user: the umask applies, not 0600 */
    mode_t um = umask(0);
    umask(um);
    struct stat sb;
    CHECK(stat(p, &sb) == 0 && (sb.st_mode & 0777) == (0666 & ~um));
}

static void test_replace_and_abort(void)
{
    clear_dir();
    char p[1024];
    path_of(p, sizeof p, "keep.txt");
    FILE *fp = fopen(p, "w");
    CHECK(fp != NULL);
    if (!fp)
        return;
    fputs("old\n", fp);
    fclose(fp);
    fm_error err;
    fm_error_clear(&err);
    fm_atomic_file *f = fm_atomic_open(p, &err);
    CHECK(f != NULL);
    if (!f)
        return;
    fputs("new, not finished", fm_atomic_stream(f));
    fflush(fm_atomic_stream(f));
    char *text = fm_test_read_file(p, NULL);
    CHECK_STR(text, "old\n");
    free(text);
    fm_atomic_abort(f);
    text = fm_test_read_file(p, NULL);
    CHECK_STR(text, "old\n");
    free(text);
    int all;
    CHECK_EQ(count_entries(".tmp.", &all), 0);
    CHECK_EQ(all, 1);
}

/* more writes at once than the registry has slots: all still atomic */
static void test_many_open(void)
{
    clear_dir();
    enum { N = 300 };
    static fm_atomic_file *f[N];
    fm_error err;
    fm_error_clear(&err);
    char p[1024];
    int opened = 0;
    for (int i = 0; i < N; i++) {
        char name[32];
        snprintf(name, sizeof name, "many%03d", i);
        path_of(p, sizeof p, name);
        f[i] = fm_atomic_open(p, &err);
        opened += f[i] != NULL;
        if (f[i])
            fprintf(fm_atomic_stream(f[i]), "%d\n", i);
    }
    CHECK_EQ(opened, N);
    CHECK_EQ(count_entries(".tmp.", NULL), N);
    for (int i = 0; i < N; i++)
        if (f[i])
            CHECK_EQ(fm_atomic_commit(f[i], &err), FM_OK);
    int all;
    CHECK_EQ(count_entries(".tmp.", &all), 0);
    CHECK_EQ(all, N);
}

static void test_name(void)
{
    clear_dir();
    char p[1024];
    path_of(p, sizeof p, "lib.bin");
    fm_error err;
    fm_error_clear(&err);
    fm_atomic_name *n = fm_atomic_name_create(p, &err);
    CHECK(n != NULL);
    if (!n)
        return;
    CHECK(strstr(fm_atomic_name_tmp(n), "/.lib.bin.tmp.") != NULL);
    CHECK(access(fm_atomic_name_tmp(n), F_OK) != 0); /* nothing under it yet */
    FILE *fp = fopen(fm_atomic_name_tmp(n), "w");
    CHECK(fp != NULL);
    if (fp) {
        fputs("data", fp);
        fclose(fp);
    }
    CHECK_EQ(fm_atomic_name_commit(n, 0, &err), FM_OK);
    char *text = fm_test_read_file(p, NULL);
    CHECK_STR(text, "data");
    free(text);
    /* aborted: whatever the library wrote is removed */
    n = fm_atomic_name_create(p, &err);
    CHECK(n != NULL);
    if (!n)
        return;
    fp = fopen(fm_atomic_name_tmp(n), "w");
    if (fp)
        fclose(fp);
    fm_atomic_name_abort(n);
    int all;
    CHECK_EQ(count_entries(".tmp.", &all), 0);
    CHECK_EQ(all, 1);
    /* a commit that fails (nothing was written) reports it and leaves nothing */
    n = fm_atomic_name_create(p, &err);
    CHECK(n != NULL);
    if (n)
        CHECK_EQ(fm_atomic_name_commit(n, 0, &err), FM_ERR_IO);
    CHECK_EQ(count_entries(".tmp.", &all), 0);
}

static void on_term(int sig)
{
    fm_atomic_remove_pending();
    signal(sig, SIG_DFL);
    raise(sig);
}

/* A child process in a clean folder that removes its temporaries on
 * SIGTERM (0 in the child, as fork). */
static pid_t child_catching_term(void)
{
    clear_dir();
    fflush(NULL);
    pid_t pid = fork();
    CHECK(pid >= 0);
    if (pid == 0)
        signal(SIGTERM, on_term);
    return pid;
}

/* The child ended by SIGTERM. */
static void reap_term(pid_t pid)
{
    int status = 0;
    CHECK(waitpid(pid, &status, 0) == pid);
    CHECK(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM);
}

/* A child writing three files (one still unflushed, one through a name)
 * gets SIGTERM: it ends by the signal and leaves no temporary; the file it
 * committed before stays. */
static void test_signal_in_child(void)
{
    pid_t pid = child_catching_term();
    if (pid == 0) {
        fm_error err;
        fm_error_clear(&err);
        char p[1024];
        path_of(p, sizeof p, "done.txt");
        fm_atomic_file *d = fm_atomic_open(p, &err);
        if (!d)
            _exit(3);
        fputs("done\n", fm_atomic_stream(d));
        if (fm_atomic_commit(d, &err) != FM_OK)
            _exit(3);
        fm_atomic_file *f[2];
        for (int i = 0; i < 2; i++) {
            path_of(p, sizeof p, i ? "b.txt" : "a.txt");
            if (!(f[i] = fm_atomic_open(p, &err)))
                _exit(3);
            fputs("partial", fm_atomic_stream(f[i]));
        }
        fflush(fm_atomic_stream(f[0]));
        path_of(p, sizeof p, "c.exo");
        fm_atomic_name *n = fm_atomic_name_create(p, &err);
        FILE *fp = n ? fopen(fm_atomic_name_tmp(n), "w") : NULL;
        if (!fp)
            _exit(3);
        fclose(fp);
        kill(getpid(), SIGTERM);
        _exit(4); /* not reached */
    }
    reap_term(pid);
    int all;
    CHECK_EQ(count_entries(".tmp.", &all), 0);
    CHECK_EQ(all, 1);
    char p[1024];
    path_of(p, sizeof p, "done.txt");
    char *text = fm_test_read_file(p, NULL);
    CHECK_STR(text, "done\n");
    free(text);
}

static void *churn(void *arg)
{
    int k = (int)(intptr_t)arg;
    fm_error err;
    fm_error_clear(&err);
    char p[1024], name[64];
    for (unsigned i = 0;; i++) {
        snprintf(name, sizeof name, "t%d_%u.txt", k, i % 8);
        path_of(p, sizeof p, name);
        fm_atomic_file *f = fm_atomic_open(p, &err);
        if (!f)
            return NULL; /* interrupted */
        fputs(name, fm_atomic_stream(f));
        fm_atomic_commit(f, &err);
    }
}

/* Threads create, write and commit files without pause while the process
 * is killed by a caught signal at moments spread over a few milliseconds:
 * no temporary may outlive it, including one a thread on another core
 * creates while the handler runs or after it returned. */
static void test_signal_while_creating(void)
{
    int rounds = 150, left = 0;
    for (int r = 0; r < rounds; r++) {
        pid_t pid = child_catching_term();
        if (pid == 0) {
            pthread_t t[4];
            for (int k = 0; k < 4; k++)
                pthread_create(&t[k], NULL, churn, (void *)(intptr_t)k);
            for (;;)
                pause();
        }
        struct timespec ts = {0, 200000L + (long)(r % 30) * 100000L};
        nanosleep(&ts, NULL);
        kill(pid, SIGTERM);
        reap_term(pid);
        left += count_entries(".tmp.", NULL) > 0;
    }
    CHECK_EQ(left, 0);
}

/* Last: in this process, writes in progress lose their temporaries and
 * new ones fail. */
static void test_remove_pending(void)
{
    clear_dir();
    fm_error err;
    fm_error_clear(&err);
    char p[1024];
    path_of(p, sizeof p, "x.txt");
    fm_atomic_file *f = fm_atomic_open(p, &err);
    CHECK(f != NULL);
    if (!f)
        return;
    fputs("x", fm_atomic_stream(f));
    CHECK(!fm_atomic_interrupted());
    CHECK_EQ(count_entries(".x.txt.tmp.", NULL), 1);
    fm_atomic_remove_pending();
    CHECK(fm_atomic_interrupted());
    CHECK_EQ(count_entries(".tmp.", NULL), 0);
    /* its commit finds the temporary gone and puts nothing in place */
    CHECK_EQ(fm_atomic_commit(f, &err), FM_ERR_IO);
    CHECK(access(p, F_OK) != 0);
    path_of(p, sizeof p, "y.txt");
    fm_error_clear(&err);
    CHECK(fm_atomic_open(p, &err) == NULL);
    CHECK(strstr(err.message, "interrupted") != NULL);
    int all;
    CHECK_EQ(count_entries("", &all), 0);
    CHECK_EQ(all, 0);
}

int main(void)
{
    snprintf(dir, sizeof dir, "%s/atomic", FM_TMP_DIR);
    fm_error err;
    fm_error_clear(&err);
    if (fm_mkdir_p(dir, &err) != FM_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    static const fm_test_case cases[] = {
        FM_CASE(test_commit),      FM_CASE(test_replace_and_abort), FM_CASE(test_many_open),
        FM_CASE(test_name),        FM_CASE(test_signal_in_child),   FM_CASE(test_signal_while_creating),
        FM_CASE(test_remove_pending),
    };
    return fm_test_run(cases, sizeof cases / sizeof cases[0]);
}
