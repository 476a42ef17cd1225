/* Progress of a long run, for tumble-run and bench (header only, static functions).
 *
 * On a terminal: one bar line redrawn in place with a carriage return, and the detail lines
 * the caller prints (progress_line) appear above it. Anywhere else (a pipe, a file): no
 * bar and no carriage returns, only the detail lines, each flushed as it ends, so
 * `make run | cat` shows them one by one.
 */
#ifndef TUMBLE_PROGRESS_H
#define TUMBLE_PROGRESS_H

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#define PROGRESS_BAR_WIDTH 32

typedef struct progress {
    FILE* out;
    int bar;            /* out is a terminal: draw the bar */
    int drawn;          /* the bar is on screen (the cursor is at its end) */
    uint32_t total;
    uint32_t done;
    char label[64];     /* after the bar: e.g. "step 120/1000" */
} progress;

/* `total` units of work; `out` usually stdout. TUMBLE_PROGRESS=lines forces plain lines. */
static inline void progress_begin(progress* p, FILE* out, uint32_t total)
{
    const char* force = getenv("TUMBLE_PROGRESS");
    p->out = out;
    p->bar = isatty(fileno(out)) && !(force && force[0] == 'l');
    p->drawn = 0;
    p->total = total ? total : 1;
    p->done = 0;
    p->label[0] = '\0';
}

static inline void progress_erase(progress* p)
{
    if (p->drawn) fputs("\r\033[K", p->out);
    p->drawn = 0;
}

static inline void progress_draw(progress* p)
{
    if (!p->bar) return;
    uint32_t filled = (uint32_t)((uint64_t)p->done * PROGRESS_BAR_WIDTH / p->total);
    char cells[PROGRESS_BAR_WIDTH + 1];
    for (uint32_t i = 0; i < PROGRESS_BAR_WIDTH; i++) cells[i] = i < filled ? '#' : '.';
    cells[PROGRESS_BAR_WIDTH] = '\0';
    fprintf(p->out, "\r\033[K[%s] %3u%%  %s", cells,
            (unsigned)((uint64_t)p->done * 100 / p->total), p->label);
    fflush(p->out);
    p->drawn = 1;
}

/* `done` of the total units are finished; `fmt` (may be NULL) labels the bar. Draws only
 * on a terminal. */
static inline void progress_update(progress* p, uint32_t done, const char* fmt, ...)
{
    p->done = done < p->total ? done : p->total;
    if (fmt) {
        va_list args;
        va_start(args, fmt);
        vsnprintf(p->label, sizeof p->label, fmt, args);
        va_end(args);
    }
    progress_draw(p);
}

/* A detail line (fmt without its newline): above the bar on a terminal, else on its own,
 * flushed. */
static inline void progress_line(progress* p, const char* fmt, ...)
{
    progress_erase(p);
    va_list args;
    va_start(args, fmt);
    vfprintf(p->out, fmt, args);
    va_end(args);
    fputc('\n', p->out);
    fflush(p->out);
    progress_draw(p);
}

/* The run is over: the bar goes, so what follows starts on a clean line. */
static inline void progress_end(progress* p)
{
    progress_erase(p);
    fflush(p->out);
}

#endif
