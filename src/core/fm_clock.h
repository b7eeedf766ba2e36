/* faultmesh core: the wall clock that stage statistics and reports use.
 *
 * Monotonic, in seconds from an arbitrary origin: stages run single
 * threaded or in worker threads, and what a report wants is elapsed time,
 * not the CPU time of a process doing other work. */
#ifndef FM_CLOCK_H
#define FM_CLOCK_H

#ifdef __cplusplus
extern "C" {
#endif

double fm_clock_seconds(void);

#ifdef __cplusplus
}
#endif
#endif
