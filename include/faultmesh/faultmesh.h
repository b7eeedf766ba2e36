/** @file
 * faultmesh: the installed API, one include.
 *
 * @code
 *   #include <faultmesh/faultmesh.h>
 * @endcode
 *
 * - fm_status.h: status codes and fm_error
 * - fm_version.h: the version of the headers and of the library
 * - fm_run.h: a whole remesh run: options, inputs, callbacks, the result
 *   (per-fault status, the meshes) and its outputs
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

#endif
