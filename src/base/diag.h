/* Errors and log messages: every failure becomes one sentence and a tb_result. */
#ifndef TB_BASE_DIAG_H
#define TB_BASE_DIAG_H

#include <stdint.h>
#include "tumble.h"

#define TB_MESSAGE_SIZE 512

/// Where a world's errors and log lines go.
typedef struct tb_diag {
    char message[TB_MESSAGE_SIZE]; ///< the last error sentence ("" when none)
    tb_log_fn* log;                ///< NULL: warnings and errors to stderr
    void* log_user;
    uint64_t validation_messages;  ///< counted by the validation layer's messenger
} tb_diag;

#if defined(__GNUC__)
#define TB_PRINTF(fmt, args) __attribute__((format(printf, fmt, args)))
#else
#define TB_PRINTF(fmt, args)
#endif

/// Record `result` with a formatted sentence in diag->message, log it, and return `result`.
tb_result tb_fail(tb_diag* diag, tb_result result, const char* fmt, ...) TB_PRINTF(3, 4);

/// Send one log line to the diag's sink.
void tb_log(tb_diag* diag, tb_log_level level, const char* fmt, ...) TB_PRINTF(3, 4);

/// Remember the message of a world that failed to be created (per thread).
void tb_diag_set_create_error(const char* message);
const char* tb_diag_create_error(void);

#endif
