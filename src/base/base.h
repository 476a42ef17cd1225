/* src/base/: what every layer of the library may use, with no Vulkan and no world.
 *
 *   diag.h     errors and log lines: every failure becomes one sentence and a tb_result
 *   slots.h    slot tables and generations, the indices behind ids
 *   checks.h   argument checks: finite numbers, unit rotations
 *   file.h     reading a whole file
 *
 * It reads only its arguments (and the files it is named) and writes only the diag and
 * slot table it is handed.
 */
#ifndef TB_BASE_BASE_H
#define TB_BASE_BASE_H

#include "base/checks.h"
#include "base/diag.h"
#include "base/slots.h"

#endif
