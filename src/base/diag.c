#include "base/diag.h"

#include <stdarg.h>
#include <stdio.h>

#if defined(__GNUC__)
static __thread char create_error[TB_MESSAGE_SIZE];
#else
static char create_error[TB_MESSAGE_SIZE];
#endif

static const char* const level_names[] = { "debug", "info", "warning", "error" };

static void log_line(tb_diag* diag, tb_log_level level, const char* line)
{
    if (diag->log) {
        diag->log(diag->log_user, level, line);
    } else if (level >= TB_LOG_WARNING) {
        fprintf(stderr, "tumble %s: %s\n", level_names[level], line);
    }
}

tb_result tb_fail(tb_diag* diag, tb_result result, const char* fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    vsnprintf(diag->message, sizeof diag->message, fmt, args);
    va_end(args);
    log_line(diag, TB_LOG_INFO, diag->message);
    return result;
}

void tb_log(tb_diag* diag, tb_log_level level, const char* fmt, ...)
{
    char line[TB_MESSAGE_SIZE * 2];
    va_list args;
    va_start(args, fmt);
    vsnprintf(line, sizeof line, fmt, args);
    va_end(args);
    log_line(diag, level, line);
}

void tb_diag_set_create_error(const char* message)
{
    snprintf(create_error, sizeof create_error, "%s", message);
}

const char* tb_diag_create_error(void)
{
    return create_error;
}
