#include "fs_atomic.h"

#include <pthread.h>

static pthread_mutex_t open_lock = PTHREAD_MUTEX_INITIALIZER;

fm_atomic_file *fs_atomic_open(const char *path, fm_error *err)
{
    pthread_mutex_lock(&open_lock);
    fm_atomic_file *f = fm_atomic_open(path, err);
    pthread_mutex_unlock(&open_lock);
    return f;
}
