/* fm_atomic_open for writers that may run on several threads (private to
 * src/write).
 *
 * fm_atomic_open reads the process umask by setting it and setting it
 * back; two threads doing that at once can leave the umask at 0 for the
 * rest of the process. Every opening by this stage goes through one lock
 * instead (io's TSurf writer is reached through fm_tsurf_write_stream on a
 * file opened here). */
#ifndef FS_ATOMIC_H
#define FS_ATOMIC_H

#include "fm_atomic.h"

fm_atomic_file *fs_atomic_open(const char *path, fm_error *err);

#endif
