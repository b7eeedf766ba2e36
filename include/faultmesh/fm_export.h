/** @file
 * faultmesh: FM_API marks the functions of the installed API.
 *
 * The library is built with hidden visibility (-fvisibility=hidden), so a
 * function is in libfaultmesh.so's dynamic symbol table only when its
 * declaration carries FM_API: every stage function the run calls stays
 * internal, and a consumer (C, or Python through ctypes) can only reach
 * what the public headers declare. The static libfaultmesh.a is made of
 * the same objects; the attribute changes nothing there. */
#ifndef FM_EXPORT_H
#define FM_EXPORT_H

#if defined(_WIN32)
#define FM_API /* faultmesh is built and tested on Linux only */
#elif defined(__GNUC__)
#define FM_API __attribute__((visibility("default")))
#else
#define FM_API
#endif

#endif
