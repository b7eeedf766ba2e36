/* fm_process.h: core's process-wide helpers under installed names (core's
 * own header stays as it is: the fit cache's key digests core's sources). */
#include "fm_atomic.h"
#include "fm_process.h"

void fm_remove_pending_files(void)
{
    fm_atomic_remove_pending(); /* async-signal-safe, as it is */
}

fm_status fm_make_dirs(const char *path, fm_error *err)
{
    return fm_mkdir_p(path, err);
}
