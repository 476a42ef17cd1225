/* inotify over the directories of watched files. Editors replace files in several ways
 * (write in place, write a new file and rename it over the old one): a file closed after
 * writing and a file moved in both count as written. */
#define _GNU_SOURCE
#include "gpu/watch.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/inotify.h>
#include <unistd.h>

#define WATCH_EVENTS (IN_CLOSE_WRITE | IN_MOVED_TO)

int tb_watch_open(tb_watch* watch)
{
    memset(watch, 0, sizeof *watch);
    watch->fd = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
    return watch->fd >= 0;
}

void tb_watch_close(tb_watch* watch)
{
    if (watch->fd >= 0) close(watch->fd);
    for (uint32_t i = 0; i < watch->dir_count; i++) free(watch->dirs[i].path);
    free(watch->dirs);
    memset(watch, 0, sizeof *watch);
    watch->fd = -1;
}

static const tb_watched_dir* dir_of_wd(const tb_watch* watch, int wd)
{
    for (uint32_t i = 0; i < watch->dir_count; i++)
        if (watch->dirs[i].wd == wd) return &watch->dirs[i];
    return NULL;
}

int tb_watch_add_file(tb_watch* watch, const char* file)
{
    const char* slash = strrchr(file, '/');
    if (watch->fd < 0 || !slash) return 0;
    size_t length = slash == file ? 1 : (size_t)(slash - file);
    for (uint32_t i = 0; i < watch->dir_count; i++)
        if (strlen(watch->dirs[i].path) == length && !strncmp(watch->dirs[i].path, file, length))
            return 1;
    tb_watched_dir* dirs = realloc(watch->dirs, (watch->dir_count + 1) * sizeof *dirs);
    if (!dirs) return 0;
    watch->dirs = dirs;
    char* path = strndup(file, length);
    int wd = path ? inotify_add_watch(watch->fd, path, WATCH_EVENTS) : -1;
    if (wd < 0) {
        free(path);
        return 0;
    }
    dirs[watch->dir_count++] = (tb_watched_dir){ wd, path };
    return 1;
}

/* One event: a file of a watched directory was written (or events were lost). */
static uint32_t report(const tb_watch* watch, const struct inotify_event* e, tb_watch_fn* fn,
                       void* user)
{
    if (e->mask & IN_Q_OVERFLOW) {
        fn(user, NULL);
        return 1;
    }
    const tb_watched_dir* dir = dir_of_wd(watch, e->wd);
    if (!dir || !e->len || !(e->mask & WATCH_EVENTS)) return 0;
    char path[PATH_MAX];
    int n = snprintf(path, sizeof path, "%s/%s", strcmp(dir->path, "/") ? dir->path : "", e->name);
    if (n <= 0 || (size_t)n >= sizeof path) return 0;
    fn(user, path);
    return 1;
}

uint32_t tb_watch_poll(tb_watch* watch, tb_watch_fn* fn, void* user)
{
    if (watch->fd < 0) return 0;
    char buffer[8192] __attribute__((aligned(__alignof__(struct inotify_event))));
    uint32_t reports = 0;
    for (;;) {
        ssize_t n = read(watch->fd, buffer, sizeof buffer);
        if (n <= 0) break;   /* EAGAIN: nothing more */
        for (char* at = buffer; at < buffer + n;) {
            const struct inotify_event* e = (const struct inotify_event*)at;
            reports += report(watch, e, fn, user);
            at += sizeof *e + e->len;
        }
    }
    return reports;
}
