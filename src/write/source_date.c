/* The date a file records (reproducible builds' SOURCE_DATE_EPOCH). */
#include <errno.h>
#include <stdlib.h>

#include "faultset_internal.h"

fm_status fs_source_date(const char *path, long long *t, fm_error *err)
{
    *t = 0;
    const char *env = getenv("SOURCE_DATE_EPOCH");
    if (!env || !*env)
        return FM_OK;
    char *endp;
    errno = 0;
    long long v = strtoll(env, &endp, 10);
    if (*endp || errno || v < 0)
        return fm_error_set(err, FM_ERR_INVALID, path, 0,
                            "SOURCE_DATE_EPOCH is not a number of seconds: %s", env);
    *t = v;
    return FM_OK;
}
