/* The fit cache's folder (fm_model_cache.h): models by key, written
 * whole or not at all. */
#include "fm_model_cache.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fm_atomic.h"
#include "fm_sha256.h"
#include "model_store.h"

/* https://bford.info/cachedir/: backup tools skip a folder holding it. */
static const char TAG[] = "Signature: 8a477f597d28d172789f06886806bc55\n"
                          "# This file is a cache directory tag created by faultmesh.\n"
                          "# It holds fitted models only; it is safe to delete.\n";

fm_status fm_model_cache_open(const char *dir, fm_error *err)
{
    fm_status st = fm_mkdir_p(dir, err);
    if (st != FM_OK)
        return st;
    if (access(dir, W_OK | X_OK) != 0)
        return fm_error_set(err, FM_ERR_IO, dir, 0, "cannot write: %s", strerror(errno));
    size_t n = strlen(dir) + 16;
    char *tag = malloc(n);
    if (!tag)
        return fm_error_set(err, FM_ERR_NOMEM, dir, 0, "out of memory");
    snprintf(tag, n, "%s/CACHEDIR.TAG", dir);
    if (access(tag, F_OK) != 0) {
        fm_atomic_file *af = fm_atomic_open(tag, err);
        st = af ? FM_OK : err ? err->code : FM_ERR_IO;
        if (af && fputs(TAG, fm_atomic_stream(af)) < 0) {
            fm_atomic_abort(af);
            st = fm_error_set(err, FM_ERR_IO, tag, 0, "cannot write");
        } else if (af) {
            st = fm_atomic_commit(af, err);
        }
    }
    free(tag);
    return st;
}

char *fm_cache_key_path(const char *dir, const char *folder, const unsigned char key[32],
                        const char *ext)
{
    char hex[2 * FM_SHA256_BYTES + 1];
    fm_sha256_hex(key, hex);
    size_t n = strlen(dir) + strlen(folder) + strlen(ext) + sizeof hex + 8;
    char *p = malloc(n);
    if (p)
        snprintf(p, n, "%s/%s/%.2s/%s%s", dir, folder, hex, hex + 2, ext);
    return p;
}

fm_status fm_cache_key_folder(char *path, fm_error *err)
{
    char *slash = strrchr(path, '/');
    if (!slash)
        return FM_OK;
    *slash = '\0';
    fm_status st = fm_mkdir_p(path, err);
    *slash = '/';
    return st;
}

char *fm_model_cache_path(const char *dir, const unsigned char key[FM_MODEL_KEY_BYTES])
{
    return fm_cache_key_path(dir, "models", key, ".fmm");
}

fm_status fm_model_cache_get(const char *dir, const unsigned char key[FM_MODEL_KEY_BYTES],
                             fm_model **out, fm_error *err)
{
    *out = NULL;
    char *path = fm_model_cache_path(dir, key);
    if (!path)
        return fm_error_set(err, FM_ERR_NOMEM, dir, 0, "out of memory");
    fm_status st = FM_OK;
    if (access(path, F_OK) == 0)
        st = model_store_read(path, key, out, err);
    free(path);
    return st;
}

fm_status fm_model_cache_put(const char *dir, const unsigned char key[FM_MODEL_KEY_BYTES],
                             const fm_model *m, fm_error *err)
{
    char *path = fm_model_cache_path(dir, key);
    if (!path)
        return fm_error_set(err, FM_ERR_NOMEM, dir, 0, "out of memory");
    fm_status st = fm_cache_key_folder(path, err);
    if (st == FM_OK)
        st = model_store_write(m, key, path, err);
    free(path);
    return st;
}
