/** @file
 * faultmesh: the installed API, one include.
 *
 * @code
 *   #include <faultmesh/faultmesh.h>
 * @endcode
 *
 * - fm_status.h: status codes and fm_error
 * - fm_version.h: the version of the headers and of the library
 * - fm_run.h: a whole remesh run: options (one at a time, in the command
 *   line's words, or from a settings file), inputs, callbacks, the result
 *   (per-fault status, the meshes) and its outputs
 * - fm_commands.h: `faultmesh info` and `faultmesh fit` as calls
 * - fm_synthetic.h: the synthetic fault system
 * - fm_process.h: once per process: temporaries on a signal, cleanup
 *
 * Link with -lfaultmesh (pkg-config faultmesh) or the CMake target
 * faultmesh::faultmesh (find_package(faultmesh)). docs/library.md is the
 * tutorial. */
#ifndef FAULTMESH_H
#define FAULTMESH_H

#include "fm_export.h"
#include "fm_status.h"
#include "fm_version.h"
#include "fm_run.h"
#include "fm_commands.h"
#include "fm_synthetic.h"
#include "fm_process.h"

#endif
