/* The entry point libFuzzer calls, declared once for the fuzz targets and
 * the replay driver that feeds them a corpus without libFuzzer. */
#ifndef FM_FUZZ_H
#define FM_FUZZ_H

#include <stddef.h>
#include <stdint.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#endif
