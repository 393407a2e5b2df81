/* libFuzzer harness for the OBJ reader: any bytes must give either a model
 * that validates or an error with a message, never a crash, leak or hang.
 * Built by `make fuzz-obj` (clang), not by `make check`. */
#include <stdint.h>
#include <stdlib.h>

#include "msocl.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  msocl_model *m = (msocl_model *)data; /* must be set to NULL on failure */
  msocl_obj_desc d;
  int rc;

  msocl_obj_desc_init(&d);
  /* Odd lengths also build bending springs, so both paths are fuzzed. */
  if (size % 2) d.k_bend = 10.0f;
  d.damping = size % 3 ? 0.0f : 0.5f;
  rc = msocl_model_from_obj_text(&m, (const char *)data, size, &d);
  if (rc == MSOCL_OK) {
    if (!m || msocl_model_validate(m) != MSOCL_OK) abort();
  } else if (m || !*msocl_last_error() || rc == MSOCL_ERR_NULL_HANDLE) {
    abort(); /* failures leave no model, always say why */
  }
  msocl_model_destroy(m);
  return 0;
}
